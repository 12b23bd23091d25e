"""The paper's protocol as a recording plan (:class:`~ebantenna.device.plan.Plan`)."""

from __future__ import annotations

from ..._validate import check_int
from ...device.plan import Plan
from ...paper.data import design
from ...paper.protocol import DATASET
from ...simulate import dataset_plan

__all__ = ["protocol_plan"]


def protocol_plan(*, quick: bool = False, scene=None, seed: int = 0) -> Plan:
    """The touches of the paper's data set design (:data:`~ebantenna.paper.data.PAPER_DESIGN`,
    or :data:`~ebantenna.paper.data.QUICK_DESIGN` with ``quick``) as a recording plan.

    Parameters
    ----------
    quick : bool
        The quick design: every 5 cm from 2.5 cm, 3 repetitions.
    scene : ebantenna.simulate.Scene, optional
        For a simulated rig: every touch then carries the design's row in this scene (realised
        contact, sweep speed, tilt ratio, seed; :func:`~ebantenna.simulate.dataset_plan`), so that
        the recordings are the simulated data set's rows passed through the rig. Its probe
        length is the plan's; without it, the paper's 40 cm.
    seed : int
        Seed of the design's variation (with ``scene``).

    Examples
    --------
    >>> plan = protocol_plan(quick=True)
    >>> len(plan), plan.contacts[:2], plan.repetitions
    (120, (0.025, 0.075), 3)
    >>> len(protocol_plan())  # the paper's: 5 materials x 79 distances x 25 repetitions
    9875
    """
    from ...simulate import Scene

    chosen = design(quick)
    seed = check_int("seed", seed, minimum=0)
    if scene is not None and not isinstance(scene, Scene):
        raise TypeError(f"scene must be a Scene (or None), got {type(scene).__name__}")
    length = DATASET.probe_length if scene is None else scene.probe.length
    simulation = ()
    if scene is not None:
        rows = dataset_plan(scene, chosen, seed)
        simulation = tuple(
            {"contact_true": float(rows["contact_true"][i]),
             "sweep_speed": float(rows["sweep_speed"][i]),
             "tilt_ratio": float(rows["tilt_ratio"][i]), "seed": int(rows["seed_row"][i])}
            for i in range(rows["contact"].size))
    return Plan(chosen.name, chosen.materials, tuple(chosen.contacts(length).tolist()),
                chosen.repetitions, length, {}, simulation)
