"""The simulated rig for a recording session: one :class:`SimulatedRig` per touch.

Each touch plays what the scene simulator computes for it: the touch's material at its contact
distance, or, when the plan carries them (a plan made from a simulated data set's design, see
:class:`~ebantenna.device.plan.Touch`), the row's realised contact, sweep speed, tilt ratio and
seed, so that the recording is that row of the data set passed through the rig. The bus faults are
drawn from a seed of their own for every attempt, so that a touch made again meets other faults.
"""

from __future__ import annotations

import math

import numpy as np

from ..._validate import check_int
from ..recording_session import Connection
from .faults import Faults
from .rig import SimulatedRig

__all__ = ["simulated_connect"]


def simulated_connect(scene, simulate, *, faults: Faults | None = None, seed: int = 0):
    """``connect(touch, attempt)`` on simulated rigs of ``scene``, for
    :class:`~ebantenna.device.recording_session.RecordingSession`.

    Parameters
    ----------
    scene : ebantenna.simulate.Scene
        The scene every touch is simulated in (its probe must be the plan's).
    simulate : callable
        The scene simulator, :func:`ebantenna.simulate.simulate`: ``simulate(scene, seed=...)``
        returns a :class:`~ebantenna.recording.Recording`. Passed in, so that the device package
        imports the simulator in one place only (:mod:`~ebantenna.device.simulated.rig`).
    faults : Faults, optional
        Faults injected on every touch's bus.
    seed : int
        Seed of the touches that carry none of their own, and of every attempt's faults.

    Examples
    --------
    >>> from ebantenna.simulate import builtin_scene, simulate
    >>> from ebantenna.device.plan import Plan
    >>> connect = simulated_connect(builtin_scene("paper"), simulate)
    >>> conn = connect(Plan("demo", ("brass",), (0.2,), 1)[0], 1)
    >>> round(conn.simulated.clock.monotonic(), 6)
    0.0
    """
    if not callable(simulate):
        raise TypeError(f"simulate must be callable, got {type(simulate).__name__}")
    if not (faults is None or isinstance(faults, Faults)):
        raise TypeError(f"faults must be Faults or None, got {type(faults).__name__}")
    seed = check_int("seed", seed, minimum=0)
    if not (callable(getattr(scene, "with_", None)) and hasattr(scene, "fs")):
        raise TypeError(f"scene must be a Scene (ebantenna.simulate), got "
                        f"{type(scene).__name__}")

    def connect(touch, attempt: int) -> Connection:
        sim = touch.simulation
        changes = {"contact": float(sim.get("contact_true", touch.contact)),
                   "material": touch.material}
        for name in ("sweep_speed", "tilt_ratio"):
            if name in sim:
                changes[name] = float(sim[name])
        run = scene.with_(**changes)
        signal_seed = int(sim.get("seed", _derived(seed, touch.index, 0)))

        def vibration(fs: float):
            return simulate(run if math.isclose(run.fs, fs) else run.with_(fs=fs),
                            seed=signal_seed)

        rig = SimulatedRig(vibration, faults=faults, seed=_derived(seed, touch.index, attempt + 1))
        return Connection(rig.bus, rig.clock, None, rig)

    return connect


def _derived(seed: int, index: int, attempt: int) -> int:
    """A seed of its own for each (touch, attempt), from the session's."""
    # shifted as a Python int: NumPy 1.24 refuses uint64 >> int (it casts the int to int64)
    return int(np.random.SeedSequence([seed, index, attempt]).generate_state(1, np.uint64)[0]) >> 1
