"""Sections 4 and 5: the dominant frequency along the probe (Figs. 9, 10) and the gain and time
constant of the band-passed decay per material (Fig. 11)."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..chips.mpu6050 import STANDARD_GRAVITY
from ..paper import printed
from ..paper.protocol import DECAY_REGION
from ..signal import filter_time_constant, paper_filter
from ._common import check_render, check_step, per_contact, probe_length

__all__ = ["FrequencyResult", "DecayResult", "compute_frequency", "render_frequency",
           "compute_decay", "render_decay"]


@dataclass(frozen=True, eq=False)
class FrequencyResult:
    """Dominant frequency against the contact distance.

    Attributes
    ----------
    length : float
        Probe length, m.
    per_material : tuple of (str, ndarray, ndarray)
        Material, contact grid (m) and median dominant frequency (Hz) at each contact.
    grid, spread : ndarray
        Contact grid (m) and standard deviation (Hz) of the dominant frequency over all
        recordings at each contact.
    peaks : dict of str to float
        Per material, the contact where its median dominant frequency is highest, m. A median
        over all materials at once would be that of a mixture: where the materials' curves jump
        at different contacts, it falls between their branches.
    spread_rises_at : float
        First contact whose spread exceeds three times the median spread of the first half, m.
    z_static : float or None
        The static acceleration the Z axis reads, m/s^2: the median over the recordings of
        each recording's mean ``az`` (gravity, where Z points up); None when not measured.
    steps : dict or None
        The largest rise between neighbouring contacts, where a curve leaves its trend at once,
        as ``(from_m, to_m, from_hz, to_hz)``: ``"median"``, a dict of each material's median
        dominant frequency's; ``"spread"``, the spread's. None when not measured.
    """

    length: float
    per_material: tuple
    grid: np.ndarray
    spread: np.ndarray
    peaks: dict
    spread_rises_at: float
    z_static: float | None = None
    steps: dict | None = None

    def to_dict(self) -> dict:
        """The summary numbers, in cm."""
        rises = (self.steps or {}).get("median") or {}
        return {
            "dominant_frequency_peaks_cm": {m: 100 * p for m, p in self.peaks.items()},
            "first_material_peak_cm": 100 * min(self.peaks.values()),
            "median_largest_rise": {
                m: dict(zip(("from_cm", "to_cm", "from_hz", "to_hz"),
                            (100 * step[0], 100 * step[1], step[2], step[3]), strict=True))
                for m, step in rises.items() if step is not None
            },
            "spread_rises_at_cm": 100 * self.spread_rises_at,
            "z_axis_static_m_s2": self.z_static,
        }


def compute_frequency(ds, feats, materials) -> FrequencyResult:
    """Median dominant frequency per material and contact (its peak and largest rise, per
    material), and its spread over all recordings."""
    check_step(ds=ds, feats=feats, materials=materials)
    per_material, peaks, rises = [], {}, {}
    for m in materials:
        sel = ds.material == m
        grid, med, _ = per_contact(feats.dominant[sel], ds.contact[sel])
        per_material.append((m, grid, med))
        peaks[m] = float(grid[np.nanargmax(med)])
        rises[m] = _largest_step(grid, med)
    grid, _, spread = per_contact(feats.dominant, ds.contact)
    first = int(np.argmax(spread > 3 * np.nanmedian(spread[: max(3, grid.size // 2)])))
    z_static = float(np.median(np.mean(ds.az, axis=1)))
    return FrequencyResult(probe_length(ds), tuple(per_material), grid, spread, peaks,
                           float(grid[first]), z_static,
                           {"median": rises, "spread": _largest_step(grid, spread)})


def _largest_step(grid, values) -> tuple | None:
    """The largest rise of ``values`` between neighbouring points of ``grid``:
    ``(from, to, value_from, value_to)``, or None with fewer than two finite neighbours.

    Examples
    --------
    >>> _largest_step(np.array([0.1, 0.2, 0.3, 0.4]), np.array([50.0, 52.0, 80.0, 81.0]))
    (0.2, 0.3, 52.0, 80.0)
    """
    rise = np.diff(np.asarray(values, dtype=float))
    if not np.any(np.isfinite(rise)):
        return None
    i = int(np.nanargmax(rise))
    return (float(grid[i]), float(grid[i + 1]), float(values[i]), float(values[i + 1]))


def render_frequency(result: FrequencyResult, report, figures) -> None:
    """Figs. 9 and 10 and the comparison with the paper."""
    check_render(result, FrequencyResult, report, figures)
    import matplotlib.pyplot as plt

    L = result.length
    fig, (a9, a10) = plt.subplots(1, 2, figsize=(12, 4))
    for m, grid, med in result.per_material:
        a9.semilogy(100 * grid, med, ".-", label=m, ms=3)
    a9.set_xlabel("contact distance (cm)")
    a9.set_ylabel("dominant frequency (Hz, log scale)")
    a9.set_title("cf. Fig. 9")
    a9.legend(fontsize="small")
    a10.plot(100 * result.grid, result.spread, ".-")
    a10.set_xlabel("contact distance (cm)")
    a10.set_ylabel("std of the dominant frequency (Hz)")
    a10.set_title("cf. Fig. 10 (a)")
    name = figures.save(fig, "fig09_10_dominant_frequency")
    rises = result.spread_rises_at
    report.heading("Dominant frequency against contact distance (Figs. 9, 10)")
    report.paragraph(
        "Dominant frequency of the sweep-plane (X) acceleration of every recording, median over "
        "repetitions per material, and its standard deviation over all recordings at a contact. "
        + _resultant_text(result.z_static)
    )
    report.table(
        ["quantity", "paper", "this reproduction"],
        [
            [
                "deviation from the linear trend",
                f"{printed.DEVIATION_CM.value} cm ({printed.PROBE_LENGTH_CM.value:g} cm probe)",
                _peaks_words(result) + _rises_words(result),
            ],
            [
                "spread grows near",
                f"{100 * printed.SPREAD_RATIO.value:g} % of L ("
                f"{printed.SPREAD_RATIO.value * printed.PROBE_LENGTH_CM.value:g} cm)",
                f"above three times its first half's from {100 * rises:.1f} cm "
                f"({rises / L:.2f} L)" + _step_words(result, "spread", "the spread"),
            ],
        ],
    )
    report.figure(name, "Dominant frequency per material (log scale) and its spread")


def _peaks_words(result: FrequencyResult) -> str:
    """Where each material's median dominant frequency is highest, from
    :attr:`FrequencyResult.peaks`.

    Examples
    --------
    >>> from types import SimpleNamespace as S
    >>> grid = np.array([0.1, 0.2, 0.3])
    >>> _peaks_words(S(length=0.4, grid=grid, peaks={"brass": 0.3, "pvc": 0.3})).split(", ")[1]
    '30.0 cm (0.75 L): no peak inside the range'
    >>> _peaks_words(S(length=0.4, grid=grid, peaks={"brass": 0.3, "pvc": 0.2})).split(": ")[1]
    'brass 30.0 cm (0.75 L), pvc 20.0 cm (0.50 L)'
    """
    L, last = result.length, float(np.max(result.grid))
    if all(p >= last for p in result.peaks.values()):
        return ("each material's median dominant frequency is highest at the last position "
                f"measured, {100 * last:.1f} cm ({last / L:.2f} L): no peak inside the range")
    return "the median dominant frequency is highest at: " + ", ".join(
        f"{m} {100 * p:.1f} cm ({p / L:.2f} L)" for m, p in result.peaks.items())


def _rises_words(result: FrequencyResult) -> str:
    """``; the largest rise ...`` of each material's median between neighbouring contacts,
    largest first, or ''."""
    rises = {m: s for m, s in ((result.steps or {}).get("median") or {}).items() if s is not None}
    if not rises:
        return ""
    L = result.length
    order = sorted(rises, key=lambda m: rises[m][3] - rises[m][2], reverse=True)
    return ("; the largest rise of each material's median between neighbouring contacts: "
            + ", ".join(f"{m} {rises[m][2]:.1f} to {rises[m][3]:.1f} Hz at {100 * rises[m][0]:.1f}"
                        f" to {100 * rises[m][1]:.1f} cm ({rises[m][1] / L:.2f} L)"
                        for m in order))


def _step_words(result: FrequencyResult, key: str, what: str) -> str:
    """``; its largest rise between neighbouring contacts ...`` of one curve, or ''."""
    step = (result.steps or {}).get(key)
    if step is None:
        return ""
    a, b, va, vb = step
    return (f"; {what}'s largest rise between neighbouring contacts: {va:.1f} to {vb:.1f} Hz, "
            f"{100 * a:.1f} to {100 * b:.1f} cm ({b / result.length:.2f} L)")


def _resultant_text(z_static: float | None) -> str:
    """Why the resultant of eq. 1 is not used, from the static acceleration the data's Z axis
    reads (``z_static``, m/s^2; :attr:`FrequencyResult.z_static`): gravity where Z points up, as
    the simulator's ``gravity`` effect puts it and as the rig's mounting is meant to.

    Examples
    --------
    >>> _resultant_text(9.79).split(";")[0]
    'The resultant of eq. 1 is not used here: the Z axis carries a static 9.79 m/s^2 (1.00 g'
    >>> "no static acceleration of the order of gravity" in _resultant_text(0.02)
    True
    """
    if z_static is None:
        return ("The resultant of eq. 1 is not used here: it mixes the axes, and its spectrum "
                "carries the vibration squared (at sums and differences of its frequencies), not "
                "the sweep-plane vibration itself.")
    g = abs(z_static)
    if g > STANDARD_GRAVITY / 2:
        return (f"The resultant of eq. 1 is not used here: the Z axis carries a static "
                f"{z_static:.2f} m/s^2 ({g / STANDARD_GRAVITY:.2f} g; the median over the "
                "recordings of each one's mean), gravity, as the probe is mounted, and for a "
                "vibration small against it the resultant is about "
                "g + a_z + a_x^2 / (2 g), so its spectrum carries the Z axis's "
                "vibration and the sweep-plane vibration squared (at sums and differences of "
                "its frequencies), not the sweep-plane vibration itself.")
    return (f"The resultant of eq. 1 is not used here. The Z axis carries no static acceleration "
            f"of the order of gravity in these recordings ({z_static:.2f} m/s^2; the median "
            "over the recordings of each one's mean), so the resultant, sqrt(a_x^2 + a_z^2), is "
            "the vibration's own magnitude: its spectrum carries the vibration squared (at sums "
            "and differences of its frequencies), not the sweep-plane vibration itself.")


@dataclass(frozen=True, eq=False)
class DecayResult:
    """Gain and time constant of the band-passed decay, on the paper's region of the probe.

    Attributes
    ----------
    per_material : tuple of dict
        Per material: ``material``, ``grid`` (m), ``gain`` (m/s^2) and ``tau`` (s) medians per
        contact over the usable fits, and the medians ``median_gain``, ``median_tau`` (NaN
        without a usable fit), the share ``ok`` of usable fits (``status == "ok"``) and their
        number ``n_ok`` of ``n`` fits.
    ok_fraction : float
        Share of all recordings in the region whose fit is usable.
    filter_tau : float or None
        Time constant of the Table 1 filter's slowest pole at the data set's sampling
        frequency, s (:func:`~ebantenna.signal.filter_time_constant`); None when not computed.
    statuses : dict
        How many fits of the region ended with each ``status``, most first.
    """

    per_material: tuple
    ok_fraction: float
    filter_tau: float | None = None
    statuses: dict | None = None

    def to_dict(self) -> dict:
        """The summary numbers."""
        return {"decay_fit_ok_fraction": self.ok_fraction,
                "decay_fit_statuses": dict(self.statuses or {})}


def compute_decay(ds, feats, materials) -> DecayResult:
    """Median gain and time constant per material along the first 80 % of the probe."""
    check_step(ds=ds, feats=feats, materials=materials)
    region = ds.contact <= DECAY_REGION * probe_length(ds)
    per_material = []
    for m in materials:
        sel = (ds.material == m) & region
        ok = feats.decay_ok[sel]
        enough = ok.sum() >= MIN_USABLE
        grid, gain, _ = per_contact(feats.gain[sel], ds.contact[sel], ok)
        _, tau, _ = per_contact(feats.tau[sel], ds.contact[sel], ok)
        per_material.append({
            "material": m, "grid": grid, "gain": gain, "tau": tau,
            "median_gain": _median(feats.gain[sel][ok]) if enough else math.nan,
            "median_tau": _median(feats.tau[sel][ok]) if enough else math.nan,
            "ok": float(ok.mean()), "n_ok": int(ok.sum()), "n": int(ok.size),
        })
    tau_filter = filter_time_constant(paper_filter("chebyshev", fs=ds.fs), ds.fs)
    names, counts = np.unique(feats.decay_status[region], return_counts=True)
    statuses = {str(names[i]): int(counts[i]) for i in np.argsort(-counts, kind="stable")}
    return DecayResult(tuple(per_material), float(feats.decay_ok[region].mean()), tau_filter,
                       statuses)


def _median(values: np.ndarray) -> float:
    """The median of the finite ``values``; NaN when there are none (no usable fit)."""
    values = values[np.isfinite(values)]
    return float(np.median(values)) if values.size else math.nan


def render_decay(result: DecayResult, report, figures) -> None:
    """Fig. 11 and the table of medians."""
    check_render(result, DecayResult, report, figures)
    import matplotlib.pyplot as plt

    fig, (ag, at) = plt.subplots(1, 2, figsize=(12, 4))
    for row in result.per_material:
        ag.plot(100 * row["grid"], row["gain"], ".-", ms=3, label=row["material"])
        at.plot(100 * row["grid"], 1000 * row["tau"], ".-", ms=3, label=row["material"])
    for axis, label in ((ag, "gain a (m/s^2)"), (at, "time constant tau (ms)")):
        axis.set_xlabel("contact distance (cm)")
        axis.set_ylabel(label)
        axis.legend(fontsize="small")
    ag.set_title("cf. Fig. 11 (a)")
    at.set_title("cf. Fig. 11 (b)")
    name = figures.save(fig, "fig11_gain_time_constant")
    report.heading("Gain and time constant by material (Fig. 11)")
    report.paragraph(
        "Resultant acceleration band-passed by the Table 1 Chebyshev filter at the order its "
        "specification needs (zero phase), then a*exp(b t) fitted to the envelope (tau = -1/b), on "
        "the first 80 % of the probe; only usable fits (status 'ok') enter the medians. "
        + status_sentence(result.statuses)
        + ringing_sentence(result.filter_tau, [r["median_tau"] for r in result.per_material])
    )
    report.table(
        ["material", "median gain (m/s^2)", "median tau (ms)", "usable fits"],
        [
            [r["material"], _shown(r["median_gain"], "{:.3g}"),
             _shown(1000 * r["median_tau"], "{:.1f}"), f"{r['n_ok']} of {r['n']}"]
            for r in result.per_material
        ],
    )
    report.figure(name, "Gain and time constant along the probe per material")


#: What each status of :class:`~ebantenna.signal.DecayFit` says of a fit, for the report.
STATUS_WORDS = {
    "noise_limited": "no single decay the rate can be read from to 3 %: noise, or other modes "
                     "beating in the envelope, scatter it about the line",
    "not_decaying": "no decay stands out",
    "too_few_points": "the decay is over too soon to be measured",
    "inconsistent": "the envelope disagrees with the damped sinusoid",
}


#: Fewest usable fits for a median of the table (a median of fewer is one or two recordings'
#: own value), and for the section to say it reproduces Fig. 11.
MIN_USABLE = 3


def status_sentence(statuses: dict | None) -> str:
    """How many fits are usable and why the others are not, from the counts of their statuses.

    Examples
    --------
    >>> status_sentence({"ok": 3, "not_decaying": 1})
    'Of the 4 fits, 3 are usable; not_decaying: 1 (no decay stands out). '
    >>> status_sentence({"noise_limited": 2})[:52]
    'Of the 2 fits, none is usable, so the gains and time'
    """
    if not statuses:
        return ""
    total, usable = sum(statuses.values()), statuses.get("ok", 0)
    others = "; ".join(f"{k}: {v} ({STATUS_WORDS.get(k, 'see DecayFit')})"
                       for k, v in statuses.items() if k != "ok")
    if usable < MIN_USABLE:
        count = "none is" if usable == 0 else f"only {usable} {'is' if usable == 1 else 'are'}"
        return (f"Of the {total} fits, {count} usable, so the gains and time constants of Fig. 11 "
                f"are not reproduced here; {others}. ")
    return (f"Of the {total} fits, {usable} {'is' if usable == 1 else 'are'} usable"
            + (f"; {others}. " if others else ". "))


def _shown(value: float, spec: str) -> str:
    """``value`` in ``spec``, or 'n/a' where it is NaN (no usable fit)."""
    return spec.format(value) if math.isfinite(value) else "n/a"


def ringing_sentence(filter_tau, taus) -> str:
    """The filter's own ringing against the fitted time constants, from their values.

    A decay fitted over a record whose tail is the filter's ringing is pulled towards the
    filter's time constant (:mod:`ebantenna.signal.decay`, "Filters ring too"): upwards for a
    decay shorter than the filter's, downwards for a longer one.

    Parameters
    ----------
    filter_tau : float or None
        The filter's slowest time constant, s (None: not computed, nothing said).
    taus : sequence of float
        The medians of the fitted time constants, s (NaN where no fit found a decay).

    Examples
    --------
    >>> ringing_sentence(0.42, [0.13, 0.18])[:60]
    "The filter's own slowest pole decays with a time constant of"
    >>> "every median here is shorter" in ringing_sentence(0.42, [0.13, 0.18])
    True
    >>> "every median here is longer" in ringing_sentence(0.05, [0.13, 0.18])
    True
    """
    if filter_tau is None:
        return ""
    taus = np.asarray(taus, dtype=float)
    taus = taus[np.isfinite(taus)]
    head = (f"The filter's own slowest pole decays with a time constant of "
            f"{1000 * filter_tau:.0f} ms (ebantenna.signal.filter_time_constant)")
    if taus.size == 0:
        return head + "."
    shorter = int(np.sum(taus < filter_tau))
    if shorter == taus.size:
        where = ("every median here is shorter, so a fit that reaches into the filter's "
                 "ringing is pulled upwards, towards it")
    elif shorter == 0:
        where = ("every median here is longer, so a fit that reaches into the filter's "
                 "ringing is pulled downwards, towards it")
    else:
        where = (f"{shorter} of the {taus.size} medians here are shorter (a fit reaching into "
                 "the ringing is pulled up towards it) and the others longer (pulled down)")
    return head + f": {where}; how far depends on how much of the tail the fit uses."
