"""The band-pass filters of the paper's Tables 1 and 2: second-order sections, zero phase.

Table 1 (Chebyshev, used before the decay fit of section 4.1.2) and Table 2 (elliptic, used before
the full-range distance network of section 4.2) give a full specification at ``fs = 1000 Hz``:

============  ============  ============  ==========  ===========
filter        pass band Hz  stop band Hz  ripple dB   stop dB
============  ============  ============  ==========  ===========
Chebyshev I   60 - 160      55 - 165      1           30
elliptic      52 - 325      48 - 330      1           45
============  ============  ============  ==========  ===========

**A contradiction in the paper.** Its text calls both filters "second order", yet their 5 Hz and 4
Hz transition bands need far more: the order-selection routines (:func:`scipy.signal.cheb1ord`,
:func:`scipy.signal.ellipord`) give 13 for the Chebyshev and 8 for the elliptic specification (a
band-pass of prototype order ``N`` has ``2N`` poles). A second-order design leaves only about
1.3-2.7 dB of attenuation at the stop-band edges instead of 30 or 45 dB, so the Table 1 band does
not isolate the 100-200 Hz region the paper chose it for; the high-order design meets the table but
rings for a long time (its slowest pole has a time constant of about 0.42 s for Table 1 and 0.52 s
for Table 2, against 0.01 s for the second-order designs). :func:`paper_filter` builds both:
``order=None`` for the order the table needs, ``order="stated"`` for the order the text states.

**Why second-order sections.** As one transfer function ``b(z)/a(z)`` of degree 26, the Table 1
filter has coefficients that round-off cannot represent: the roots of the rounded denominator leave
the unit circle and the filter is unstable, and its computed response misses the pass band by tens
of dB. Cascaded second-order sections keep each pole pair exact to rounding error.

**Zero phase.** :func:`apply_filter` runs the filter forward and backward
(:func:`scipy.signal.sosfiltfilt`): no phase shift and no delay of the decay envelope, but the
magnitude response is squared, so the applied pass-band ripple is ``2 Rp`` and the stop-band
attenuation ``2 Rs``.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np
from scipy import signal as sps

from .._budget import check_allocation
from .._validate import check_array, check_choice, check_int, check_positive
from ._checks import check_band, check_fs

__all__ = [
    "FilterSpec",
    "SpecReport",
    "PAPER_FILTERS",
    "STATED_ORDER",
    "filter_order",
    "design_bandpass",
    "paper_filter",
    "apply_filter",
    "check_specification",
    "filter_time_constant",
    "freqz_sos",
]

#: ``scipy.signal.freqz_sos``, the frequency response of second-order sections. SciPy 1.15
#: introduced that name for the older ``sosfreqz``, which later releases deprecate; on an older
#: SciPy this is ``sosfreqz`` itself (same arguments, same result).
freqz_sos = getattr(sps, "freqz_sos", None) or sps.sosfreqz

#: The order the paper's text gives for both filters ("second order").
STATED_ORDER = 2


@dataclass(frozen=True)
class FilterSpec:
    """A band-pass specification.

    Parameters
    ----------
    kind : {"chebyshev", "elliptic"}
        Chebyshev type I or elliptic (Cauer) design.
    fs : float
        Sampling frequency, Hz.
    passband : tuple of float
        Pass-band edges ``(low, high)``, Hz.
    stopband : tuple of float
        Stop-band edges ``(low, high)``, Hz; they enclose the pass band.
    ripple : float
        Largest pass-band loss ``Rp``, dB.
    attenuation : float
        Smallest stop-band attenuation ``Rs``, dB.
    source : str
        Where the numbers come from.

    Examples
    --------
    >>> from ebantenna.signal import PAPER_FILTERS
    >>> PAPER_FILTERS["chebyshev"].passband
    (60.0, 160.0)
    """

    kind: str
    fs: float
    passband: tuple
    stopband: tuple
    ripple: float
    attenuation: float
    source: str = ""

    def __post_init__(self):
        check_choice("kind", self.kind, ("chebyshev", "elliptic"))
        fs = check_fs(self.fs)
        object.__setattr__(self, "fs", fs)
        pb = check_band("passband", self.passband, fs)
        sb = check_band("stopband", self.stopband, fs)
        if not (sb[0] < pb[0] and pb[1] < sb[1]):
            raise ValueError(
                f"stopband {sb} must enclose passband {pb}: "
                "stop_low < pass_low < pass_high < stop_high"
            )
        object.__setattr__(self, "passband", pb)
        object.__setattr__(self, "stopband", sb)
        object.__setattr__(self, "ripple", check_positive("ripple", self.ripple))
        attenuation = check_positive("attenuation", self.attenuation)
        if not attenuation > self.ripple:
            raise ValueError(
                f"attenuation must exceed ripple ({self.ripple} dB), got {attenuation}"
            )
        object.__setattr__(self, "attenuation", attenuation)

    def at(self, fs) -> FilterSpec:
        """The same band edges and ripples at another sampling frequency ``fs`` (Hz)."""
        return FilterSpec(self.kind, fs, self.passband, self.stopband, self.ripple,
                          self.attenuation, self.source)


#: Table 1 (Chebyshev) and Table 2 (elliptic) of the paper.
PAPER_FILTERS = {
    "chebyshev": FilterSpec("chebyshev", 1000.0, (60.0, 160.0), (55.0, 165.0), 1.0, 30.0,
                            "Table 1 (section 4.1.2, before the decay fit)"),
    "elliptic": FilterSpec("elliptic", 1000.0, (52.0, 325.0), (48.0, 330.0), 1.0, 45.0,
                           "Table 2 (section 4.2, before the full-range distance network)"),
}


def filter_order(spec: FilterSpec) -> int:
    """Smallest prototype order whose design meets ``spec``.

    Found by the order-selection routines :func:`scipy.signal.cheb1ord` and
    :func:`scipy.signal.ellipord`.

    Examples
    --------
    >>> from ebantenna.signal import PAPER_FILTERS, filter_order
    >>> filter_order(PAPER_FILTERS["chebyshev"]), filter_order(PAPER_FILTERS["elliptic"])
    (13, 8) """
    if not isinstance(spec, FilterSpec):
        raise TypeError(f"spec must be a FilterSpec, got {type(spec).__name__}")
    ordfunc = sps.cheb1ord if spec.kind == "chebyshev" else sps.ellipord
    try:
        with np.errstate(all="ignore"):  # edges far below fs make SciPy's estimate NaN
            order, _ = ordfunc(spec.passband, spec.stopband, spec.ripple, spec.attenuation,
                               fs=spec.fs)
    except ValueError:  # SciPy's "cannot convert float NaN to integer"
        order = np.nan
    if not np.isfinite(order):
        raise ValueError(f"fs = {spec.fs:g} Hz puts the band edges ({spec.passband[0]:g} Hz...) "
                         "too far below the sampling frequency for a filter to be designed in "
                         "float64; filter at a lower sampling frequency")
    return int(order)


def design_bandpass(spec: FilterSpec, order=None, *, output: str = "sos"):
    """Design the band-pass filter of ``spec``.

    Parameters
    ----------
    spec : FilterSpec
        Band edges (Hz), ripple and attenuation (dB).
    order : int or None or "stated"
        Prototype order (the band-pass has twice as many poles). ``None``: the smallest order that
        meets the specification (:func:`filter_order`); ``"stated"``: the paper's "second order".
    output : {"sos", "ba"}
        ``"sos"``: second-order sections, shape ``(n_sections, 6)``; ``"ba"``: one transfer function
        ``(b, a)``, for demonstration only (it is numerically unusable at the orders the tables
        need).

    Returns
    -------
    ndarray or tuple of ndarray
        The filter, with the pass-band edges of ``spec`` as its design frequencies.

    Examples
    --------
    >>> from ebantenna.signal import PAPER_FILTERS, design_bandpass
    >>> design_bandpass(PAPER_FILTERS["elliptic"]).shape
    (8, 6)
    """
    if not isinstance(spec, FilterSpec):
        raise TypeError(f"spec must be a FilterSpec, got {type(spec).__name__}")
    check_choice("output", output, ("sos", "ba"))
    if order is None:
        order = filter_order(spec)
    elif isinstance(order, str):
        check_choice("order", order, ("stated",))
        order = STATED_ORDER
    else:
        order = check_int("order", order, minimum=1, maximum=40)
    if spec.kind == "chebyshev":
        return sps.cheby1(order, spec.ripple, spec.passband, btype="bandpass", output=output,
                          fs=spec.fs)
    return sps.ellip(order, spec.ripple, spec.attenuation, spec.passband, btype="bandpass",
                     output=output, fs=spec.fs)


def paper_filter(kind: str, order=None, *, fs=None) -> np.ndarray:
    """The band-pass filter of Table 1 (``"chebyshev"``) or Table 2 (``"elliptic"``) as SOS.

    Parameters
    ----------
    kind : {"chebyshev", "elliptic"}
        Which table.
    order : int or None or "stated"
        ``None`` (default): the smallest order that meets the table at ``fs``
        (:func:`filter_order`): 13 and 8 at the tables' 1000 Hz, 13 and 9 at 2 kHz, 14 and 9 at
        10 kHz; ``"stated"``: the "second order" of the paper's text, which does not meet the
        table (see the module notes).
    fs : float, optional
        Sampling frequency, Hz; default the tables' 1000 Hz. The band edges in Hz stay the same, and
        must lie below ``fs / 2``: ``fs`` above 330 Hz for Table 1 and above 660 Hz for Table 2,
        twice their highest stop-band edges.

    Returns
    -------
    ndarray of shape (n_sections, 6)
        Second-order sections for :func:`apply_filter` or :func:`scipy.signal.sosfiltfilt`.

    Examples
    --------
    >>> from ebantenna.signal import paper_filter, check_specification, PAPER_FILTERS
    >>> sos = paper_filter("chebyshev")
    >>> sos.shape
    (13, 6)
    >>> check_specification(sos, PAPER_FILTERS["chebyshev"]).meets
    True
    >>> check_specification(paper_filter("chebyshev", "stated"), PAPER_FILTERS["chebyshev"]).meets
    False """
    check_choice("kind", kind, tuple(PAPER_FILTERS))
    spec = PAPER_FILTERS[kind] if fs is None else PAPER_FILTERS[kind].at(_table_rate(kind, fs))
    with np.errstate(all="ignore"):  # a design too far below fs is refused just below
        sos = _designed(spec, order)
        fails = fs is not None and order is None and not (np.all(np.isfinite(sos))
                                                          and _meets(spec))
    if fails:
        raise ValueError(
            f"fs = {spec.fs:g} Hz: the filter of the table's order designed in float64 at this "
            "sampling frequency does not meet the table (its band edges are too small a fraction "
            "of fs); filter at a lower sampling frequency")
    return sos.copy()


def _table_rate(kind: str, fs) -> float:
    """``fs`` (Hz) checked for the table of ``kind``: all its band edges below ``fs / 2``.

    The caller gave ``fs`` alone, so the error names ``fs``, not the table's stop band.
    """
    fs = check_fs(fs)
    edge = PAPER_FILTERS[kind].stopband[1]
    if not edge < fs / 2.0:
        raise ValueError(f"fs must exceed {2 * edge:g} Hz, twice the highest band edge of the "
                         f"{kind} table ({edge:g} Hz, which must lie below fs/2 = {fs / 2:g} Hz); "
                         f"got {fs:g} Hz")
    return fs


@functools.lru_cache(maxsize=32)
def _meets(spec: FilterSpec) -> bool:
    """Whether the design of the table's order at ``spec.fs`` meets ``spec`` (checked once)."""
    return check_specification(_designed(spec, None), spec).meets


@functools.lru_cache(maxsize=32)
def _designed(spec: FilterSpec, order) -> np.ndarray:
    # Designing a 13th-order filter costs milliseconds, far more than applying it to a one-second
    # record: a data set of ten thousand records asks for the same few designs again and again.
    return design_bandpass(spec, order)


def _check_sos(sos) -> np.ndarray:
    try:
        sos = np.asarray(sos, dtype=float)
    except (TypeError, ValueError):
        raise TypeError(f"sos must be an array of second-order sections, got {sos!r:.40}") from None
    if sos.ndim != 2 or sos.shape[1] != 6 or sos.shape[0] < 1:
        raise ValueError(f"sos must have shape (n_sections, 6), got {sos.shape}")
    if not np.all(np.isfinite(sos)):
        raise ValueError("sos must contain only finite values")
    a0 = sos[:, 3]
    if np.any(a0 != 1.0):
        i = int(np.argmax(a0 != 1.0))
        why = ("a section with a0 = 0 has no output" if a0[i] == 0 else
               "divide each section by its a0 first")
        raise ValueError(f"sos[:, 3] (each section's a0) must be 1, got {a0[i]:g} in section "
                         f"{i} ({why})")
    return sos


def apply_filter(sos, x) -> np.ndarray:
    """Filter ``x`` with zero phase (forward and backward, :func:`scipy.signal.sosfiltfilt`).

    Parameters
    ----------
    sos : array of shape (n_sections, 6)
        Second-order sections.
    x : array of shape (n,) or (n_signals, n)
        Signal, or one signal per row; longer than the edge padding, ``3 (2 n_sections + 1)``
        samples.

    Returns
    -------
    ndarray of the shape of ``x``
        Filtered signal (magnitude response squared, no phase shift), each row on its own.

    Examples
    --------
    >>> import numpy as np
    >>> from ebantenna.signal import apply_filter, paper_filter
    >>> t = np.arange(1000) / 1000.0
    >>> x = np.sin(2 * np.pi * 100 * t) + np.sin(2 * np.pi * 20 * t)
    >>> y = apply_filter(paper_filter("chebyshev"), x)
    >>> round(float(np.std(y[300:700]) * np.sqrt(2)), 2)  # the 100 Hz tone passes, 20 Hz is gone
    1.0 """
    sos = _check_sos(sos)
    padlen = 3 * (2 * sos.shape[0] + 1)
    x = check_array("x", x, ndim=(1, 2), min_length=padlen + 1)
    return sps.sosfiltfilt(sos, x, axis=-1, padlen=padlen)


@dataclass(frozen=True)
class SpecReport:
    """How a filter's single-pass magnitude response compares with a :class:`FilterSpec`.

    Attributes
    ----------
    passband_loss : float
        Largest loss in the pass band, dB (must be <= ``spec.ripple``).
    stopband_attenuation : float
        Smallest attenuation in the two stop bands, dB (must be >= ``spec.attenuation``).
    meets : bool
        Both requirements hold (to 1e-6 dB).
    """

    passband_loss: float
    stopband_attenuation: float
    meets: bool


def check_specification(sos, spec: FilterSpec, *, n_points: int = 8192) -> SpecReport:
    """Measure ``sos`` against ``spec`` on a dense grid of the pass and stop bands.

    Examples
    --------
    >>> from ebantenna.signal import PAPER_FILTERS, check_specification, paper_filter
    >>> r = check_specification(paper_filter("elliptic"), PAPER_FILTERS["elliptic"])
    >>> r.meets, round(r.passband_loss, 3), r.stopband_attenuation > 45
    (True, 1.0, True)
    """
    sos = _check_sos(sos)
    if not isinstance(spec, FilterSpec):
        raise TypeError(f"spec must be a FilterSpec, got {type(spec).__name__}")
    n_points = check_int("n_points", n_points, minimum=16)
    # three grids, and per grid the complex response, its magnitude and its decibels
    check_allocation(3 * n_points * (8 + 16 + 8 + 8) * (1 + sos.shape[0]), parameter="n_points",
                     what=f"the frequency response on {3 * n_points} points")
    nyq = spec.fs / 2.0
    f_pass = np.linspace(spec.passband[0], spec.passband[1], n_points)
    f_stop = np.concatenate([np.linspace(0.0, spec.stopband[0], n_points),
                             np.linspace(spec.stopband[1], nyq, n_points)])

    def gain_db(f):
        _, h = freqz_sos(sos, worN=f, fs=spec.fs)
        return 20.0 * np.log10(np.maximum(np.abs(h), 1e-300))

    loss = float(-gain_db(f_pass).min())
    atten = float(-gain_db(f_stop).max())
    meets = loss <= spec.ripple + 1e-6 and atten >= spec.attenuation - 1e-6
    return SpecReport(loss, atten, bool(meets))


def filter_time_constant(sos, fs) -> float:
    """Time constant of the slowest-decaying pole of ``sos``, s: ``-1 / (fs ln max|p|)``.

    The filter's own ringing decays like ``exp(-t / tau_filter)``. When it is longer than the decay
    being measured, the tail of a filtered vibration is the filter's ringing, not the probe's.

    Examples
    --------
    >>> from ebantenna.signal import filter_time_constant, paper_filter
    >>> round(filter_time_constant(paper_filter("chebyshev"), 1000.0), 2)
    0.42
    """
    sos = _check_sos(sos)
    fs = check_fs(fs)
    poles = np.concatenate([np.roots(section[3:]) for section in sos])
    radius = float(np.max(np.abs(poles))) if poles.size else 0.0
    if radius == 0.0:
        return 0.0
    if radius >= 1.0:
        return math.inf
    return -1.0 / (fs * math.log(radius))
