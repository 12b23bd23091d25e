"""Scene-based simulator of the tip accelerometer, and data sets of simulated recordings.

- :mod:`~ebantenna.simulate.scene`: :class:`Scene`, the built-in ``ideal`` and ``paper`` scenes,
  TOML/JSON files;
- :mod:`~ebantenna.simulate.effects`: every effect a scene may list, with its physics and sources;
- :mod:`~ebantenna.simulate.modes`: the modal response after the object arrests the swept probe;
- :mod:`~ebantenna.simulate.touched_object`: the touched object's physics models (pinned,
  coupled, unilateral, friction);
- :mod:`~ebantenna.simulate.simulator`: :func:`simulate` and :func:`simulate_batch`, the effects
  applied as one ordered chain of steps;
- :mod:`~ebantenna.simulate.dataset`: data sets of recordings (materials x contacts x
  repetitions); the paper's own is :mod:`ebantenna.paper.data`.

Examples
--------
>>> from ebantenna.simulate import Scene, builtin_scene, simulate
>>> scene = builtin_scene("paper").with_(contact=0.25, material="brass")
>>> rec = simulate(scene, seed=3)
>>> rec.ax.shape, rec.fs
((1000,), 1000.0)
"""

# the engines register themselves beside their references: the contact laws' march "blocks"
# (unilateral.MARCHES) and the modal sum's "grid" (modes.EXPONENTIAL_ENGINES)
from . import _block_march, _exponential_grid  # noqa: F401
from .dataset import (
    Dataset,
    DatasetDesign,
    build_dataset,
    build_datasets,
    dataset_plan,
    load_dataset,
)
from .effects import effect_names
from .scene import Scene, builtin_scene, load_scene, make_effect, scene_names
from .simulator import ModalTerms, modal_terms, simulate, simulate_batch

__all__ = [
    "Scene",
    "builtin_scene",
    "scene_names",
    "load_scene",
    "simulate",
    "simulate_batch",
    "modal_terms",
    "ModalTerms",
    "effect_names",
    "make_effect",
    "Dataset",
    "DatasetDesign",
    "build_dataset",
    "build_datasets",
    "dataset_plan",
    "load_dataset",
]
