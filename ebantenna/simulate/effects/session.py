"""Effects that change from strike to strike and from session to session.

:class:`PreloadScatter` (how hard the stopped servo presses the probe on the object) and
:class:`SensorDrift` (the accelerometer's offset and sensitivity). The sweep speed's scatter is a
property of the data set's design (:class:`ebantenna.simulate.DatasetDesign`), not an effect.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar

import numpy as np

from ..._validate import check_nonnegative
from ...chips.mpu6050 import STANDARD_GRAVITY
from ._base import Effect, check_rng


@dataclass(frozen=True)
class PreloadScatter(Effect):
    """The contact's preload varies from strike to strike.

    The servo stops where the search sweep met the object, and how far it drove on before it
    stopped sets how hard the probe presses; so the preload that :class:`~.objects.ObjectModes`
    linearises the contact at scatters. Each strike's preload is the effect's preload times a
    log-normal factor of standard deviation ``spread`` (in log units), and with it the Hertz
    stiffness (as ``preload^(1/3)``) and the coupled modes. Requires :class:`~.objects.ObjectModes`.
    Each strike then needs its own coupled eigenproblem (about 1.5 ms each).

    Parameters
    ----------
    spread : float
        Standard deviation of the log of the preload (dimensionless). Default 0.2: an assumption,
        as for the data set's sweep speed (the paper does not measure the rig's scatter).

    Examples
    --------
    >>> import numpy as np
    >>> f = PreloadScatter().factor(np.random.default_rng(0))
    >>> 0.3 < f < 3
    True
    """

    name: ClassVar[str] = "preload_scatter"
    stream: ClassVar[int] = 4
    spread: float = 0.2

    def __post_init__(self):
        check_nonnegative("spread", self.spread)

    def factor(self, rng: np.random.Generator) -> float:
        """One strike's preload relative to the nominal one (dimensionless, > 0)."""
        return float(np.exp(check_rng(rng).normal(0.0, self.spread)))


#: MPU6050 zero-g level change over 0-70 degC, X and Y axes, g (PS rev. 3.4, table 6.2).
ZERO_G_DRIFT_XY = 35e-3
#: The same for the Z axis, g (PS rev. 3.4, table 6.2).
ZERO_G_DRIFT_Z = 60e-3
#: Span of temperature those drifts are specified over, degC (PS rev. 3.4, table 6.2).
DRIFT_SPAN = 70.0
#: MPU6050 sensitivity change with temperature, per degC (+-0.02 %/degC, PS rev. 3.4, table 6.2).
SENSITIVITY_DRIFT = 2e-4


@dataclass(frozen=True)
class SensorDrift(Effect):
    """The accelerometer's offset and gain differ between recording sessions.

    The MPU6050's zero-g level moves by up to 35 mg (X) and 60 mg (Z) over 0-70 degC and its
    sensitivity by 0.02 %/degC (product specification rev. 3.4, table 6.2). Taking the drifts
    as linear in temperature, a session at a room temperature ``delta`` away from another reads
    ``(1 + s_g delta) a + (o / 70 degC) delta`` instead of ``a``, per axis, with the datasheet's
    ``o`` and ``s_g``. Assumptions: the room's temperature varies between sessions with a standard
    deviation of ``temperature_std``; the paper does not say how the recordings were grouped in
    time, so each recording is taken as its own session (the drift is drawn per recording and
    axis, independent of the material, so it can never label one). Applied after the sensor's
    filter, before clipping.

    Parameters
    ----------
    temperature_std : float
        Standard deviation of the room's temperature between sessions, degC. Default 3 degC.

    Examples
    --------
    >>> import numpy as np
    >>> gain, offset = SensorDrift().draw(np.random.default_rng(0))
    >>> gain.shape, offset.shape
    ((2,), (2,))
    """

    name: ClassVar[str] = "sensor_drift"
    stream: ClassVar[int] = 5
    temperature_std: float = 3.0

    def __post_init__(self):
        check_nonnegative("temperature_std", self.temperature_std)

    def draw(self, rng: np.random.Generator) -> tuple[np.ndarray, np.ndarray]:
        """One session's gain factors and offsets (m/s^2) for X and Z."""
        delta = check_rng(rng).normal(0.0, self.temperature_std, 2)
        gain = 1.0 + SENSITIVITY_DRIFT * delta
        offset = np.array([ZERO_G_DRIFT_XY, ZERO_G_DRIFT_Z]) / DRIFT_SPAN * delta
        return gain, offset * STANDARD_GRAVITY

    def offset_std(self) -> np.ndarray:
        """Standard deviation of the offsets of X and Z, m/s^2."""
        scale = self.temperature_std / DRIFT_SPAN * STANDARD_GRAVITY
        return np.array([ZERO_G_DRIFT_XY, ZERO_G_DRIFT_Z]) * scale

    def gain_std(self) -> float:
        """Standard deviation of the gain factor (dimensionless)."""
        return SENSITIVITY_DRIFT * self.temperature_std
