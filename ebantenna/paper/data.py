"""The paper's data set: five materials, contacts every 5 mm along the probe, 25 repetitions.

The paper (sections 2.1 and 4.2) records, for each of five touched materials, the probe's vibration
after a contact at every 5 mm along the probe, 25 times each (:data:`~.protocol.DATASET`). Here the
recordings come from the ``paper`` scene. How one repetition differs from the next is not in the
paper; these are the rig's assumed scatter, named once here:

- the servo's speed at the contact varies by 10 % (log-normal): the sweep is an ellipse and the
  object is met at slightly different points of it;
- the rate across the sweep plane varies by 20 % (log-normal);
- the probe does not hit exactly the nominal point: the error is normal with a standard deviation of
  1 mm, rounded to a 0.5 mm grid.

The material enters the signals only through the scene's contact effects.
"""

from __future__ import annotations

from dataclasses import replace

from .._validate import check_bool
from ..simulate import Dataset, DatasetDesign, Scene, build_dataset, builtin_scene, dataset_plan
from .protocol import DATASET

__all__ = ["PAPER_DESIGN", "QUICK_DESIGN", "design", "build_paper_dataset", "paper_dataset_plan"]

#: The paper's data set: every 5 mm, 25 repetitions, with the rig's assumed scatter.
PAPER_DESIGN = DatasetDesign(
    name="dataset",
    materials=DATASET.materials,
    first_contact=DATASET.contact_step,
    contact_step=DATASET.contact_step,
    repetitions=DATASET.repetitions,
    position_error=1e-3,
    position_grid=5e-4,
    speed_spread=0.10,
    tilt_spread=0.20,
)

#: A small version for tests, examples and ``--quick``: every 5 cm from 2.5 cm, 3 repetitions.
QUICK_DESIGN = replace(
    PAPER_DESIGN, name="dataset-quick", first_contact=0.025, contact_step=0.05, repetitions=3
)


def design(quick: bool = False) -> DatasetDesign:
    """The paper's data-set design, or its small version.

    Examples
    --------
    >>> design().repetitions, design(quick=True).contact_step
    (25, 0.05)
    """
    return QUICK_DESIGN if check_bool("quick", quick) else PAPER_DESIGN


def paper_dataset_plan(seed: int = 0, quick: bool = False, *, scene: Scene | None = None) -> dict:
    """The rows of the paper's data set before simulation (see
    :func:`ebantenna.simulate.dataset_plan`).

    Examples
    --------
    >>> import numpy as np
    >>> plan = paper_dataset_plan(seed=0)
    >>> plan["contact"].size, np.unique(plan["contact"])[[0, -1]]
    (9875, array([0.005, 0.395]))
    """
    scene = builtin_scene("paper") if scene is None else scene
    return dataset_plan(scene, design(quick), seed)


def build_paper_dataset(
    out_dir,
    seed: int = 0,
    quick: bool = False,
    *,
    scene: Scene | None = None,
    n_jobs: int = 1,
    show_progress=None,
) -> Dataset:
    """Build (or reuse) the paper's data set in ``out_dir``.

    Parameters
    ----------
    out_dir : path
        Directory for the ``.npz`` file (created if needed).
    seed : int
        Seed of everything random in the data set.
    quick : bool
        The small version (:data:`QUICK_DESIGN`).
    scene : Scene, optional
        The scene to record; default the built-in ``paper`` scene.
    n_jobs : int
        Worker processes (each task a range of contact positions of one material); the
        result does not depend on it.
    show_progress : bool, optional
        Force the progress bar on or off (default: on a terminal).

    Returns
    -------
    Dataset
        Also saved as ``paper-dataset-seed<seed>.npz`` (``paper-dataset-quick-seed<seed>.npz``);
        see :func:`ebantenna.simulate.build_dataset`.

    Examples
    --------
    >>> import tempfile
    >>> with tempfile.TemporaryDirectory() as tmp:
    ...     data = build_paper_dataset(tmp, seed=1, quick=True)
    >>> data.ax.shape, sorted({str(m) for m in data.material})[:2]
    ((120, 1000), ['aluminium', 'brass'])
    """
    scene = builtin_scene("paper") if scene is None else scene
    return build_dataset(
        out_dir, scene, design(quick), seed, n_jobs=n_jobs, show_progress=show_progress
    )
