"""Scene-based simulator of the tip accelerometer, and the paper's data set.

- :mod:`~ebantenna.simulate.scene`: :class:`Scene`, the built-in ``ideal`` and ``paper`` scenes,
  TOML/JSON files;
- :mod:`~ebantenna.simulate.effects`: every effect a scene may list, with its physics and sources;
- :mod:`~ebantenna.simulate.modes`: the modal response after the object arrests the swept probe;
- :mod:`~ebantenna.simulate.simulator`: :func:`simulate` and :func:`simulate_batch`;
- :mod:`~ebantenna.simulate.dataset`: the paper's data set (materials x contacts x repetitions).

Examples
--------
>>> from ebantenna.simulate import Scene, builtin_scene, simulate
>>> scene = builtin_scene("paper").with_(contact=0.25, material="brass")
>>> rec = simulate(scene, seed=3)
>>> rec.ax.shape, rec.fs
((1000,), 1000.0)
"""

from .dataset import Dataset, build_dataset, load_dataset
from .effects import effect_names, make_effect
from .scene import Scene, builtin_scene, load_scene, scene_names
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
    "build_dataset",
    "load_dataset",
]
