"""The input contract of the steps the spectral reference is made of, and of the fits' models.

The bins of a search band, the peak picked in it and the interpolation about it, the window and
the method by name, a decay fit's model at given times and a time-frequency plot: each refuses
a band outside the spectrum or reversed, a peak bin without the neighbours its interpolation
reads, an unknown window or method, NaN times and a non-bool ``db``, naming the parameter;
good inputs are checked by hand.

Found by these rows and fixed: NumPy's "argmax of an empty sequence" for a reversed band,
``IndexError`` from an interpolation at the spectrum's edge, an unknown window or method read as
the rectangular window or the Jacobsen estimate, a band reaching beyond the spectrum accepted,
NaN times evaluated, ``db="no"`` taken as true and ``AttributeError`` for an ``ax`` that is not
matplotlib's.
"""

from __future__ import annotations

import math
import os
import sys

import numpy as np
import pytest

sys.path.insert(0, os.path.dirname(__file__))
from contract_files_cases import Row, check_row  # noqa: E402

from ebantenna import signal  # noqa: E402
from ebantenna.signal import spectral as sp  # noqa: E402

NAN = math.nan
MAG = np.array([9.0, 1.0, 4.0, 2.0, 5.0, 3.0])
T = np.arange(1000) / 1000.0
FIT = signal.fit_decay(np.exp(-T / 0.1) * np.sin(2 * np.pi * 50 * T), 1000.0)
TF = signal.spectrogram(np.sin(2 * np.pi * 50 * T), 1000.0)
#: a parabola in the log of the magnitude, vertex a quarter bin right of bin 2
PARABOLA = np.exp(-((np.arange(5) - 2.25) ** 2))

#: ``surface -> [(id, call, names or None, same)]``
S = "ebantenna.signal.spectral."
ROWS = {
    S + "strongest_bin": [
        ("lo-above-hi", lambda: sp.strongest_bin(MAG, 4, 2), ("hi",), None),
        ("hi-beyond", lambda: sp.strongest_bin(MAG, 0, 20), ("hi",), None),
        ("lo-negative", lambda: sp.strongest_bin(MAG, -1, 3), ("lo",), None),
        ("magnitude-2-D", lambda: sp.strongest_bin(np.ones((2, 2)), 0, 1), ("magnitude",), None),
        ("band-leaves-out-bin-0", lambda: sp.strongest_bin(MAG, 1, 5), None, lambda k: k == 4),
    ],
    S + "local_maxima": [
        ("lo-above-hi", lambda: sp.local_maxima(MAG, 4, 2), ("hi",), None),
        ("hi-beyond", lambda: sp.local_maxima(MAG, 0, 9), ("hi",), None),
        ("strongest-first", lambda: sp.local_maxima(MAG, 0, 5), None,
         lambda r: r.tolist() == [4, 2]),
    ],
    S + "parabolic_offset": [
        ("k-at-the-edge", lambda: sp.parabolic_offset(MAG, 0), ("k",), None),
        ("k-beyond", lambda: sp.parabolic_offset(MAG, 20), ("k",), None),
        ("k-float", lambda: sp.parabolic_offset(MAG, 1.5), ("k",), None),
        # exact for a Gaussian peak: its log is a parabola
        ("gaussian-exact", lambda: sp.parabolic_offset(PARABOLA, 2), None,
         lambda d: abs(d - 0.25) < 1e-12),
    ],
    S + "jacobsen_offset": [
        ("window-unknown", lambda: sp.jacobsen_offset(MAG + 0j, 3, 1, "x"), ("window",), None),
        ("k-at-the-edge", lambda: sp.jacobsen_offset(MAG + 0j, 0, 1, "hann"), ("k",), None),
        ("step-0", lambda: sp.jacobsen_offset(MAG + 0j, 3, 0, "hann"), ("step",), None),
        # a tone on a bin: its neighbours cancel, no offset
        ("tone-on-a-bin", lambda: sp.jacobsen_offset(
            np.fft.rfft(np.cos(2 * np.pi * 8 * np.arange(64) / 64)), 8, 1, "rectangular"),
         None, lambda d: abs(d) < 1e-12),
    ],
    S + "interpolated_frequency": [
        ("method-unknown", lambda: sp.interpolated_frequency(MAG + 0j, 3, 1000.0, 10, "x",
                                                             "hann", 1), ("method",), None),
        ("window-unknown", lambda: sp.interpolated_frequency(MAG + 0j, 3, 1000.0, 10, "bin",
                                                             "x", 1), ("window",), None),
        ("bin-by-hand", lambda: sp.interpolated_frequency(MAG + 0j, 3, 1000.0, 10, "bin",
                                                          "hann", 2), None, lambda f: f == 150.0),
    ],
    "ebantenna.signal.decay.DecayFit.model": [
        ("t-nan", lambda: FIT.model([NAN]), ("t",), None),
        ("t-str", lambda: FIT.model("x"), ("t",), None),
        ("t-complex", lambda: FIT.model([1j]), ("t",), None),
        ("a-exp-bt", lambda: FIT.model([0.0, 0.1]), None,
         lambda r: r[0] == FIT.a and math.isclose(r[1], FIT.a * math.exp(FIT.b * 0.1),
                                                   rel_tol=1e-15)),
    ],
    "ebantenna.signal.timefreq.TimeFrequency.plot": [
        ("ax-int", lambda: TF.plot(5), ("ax",), None),
        ("db-str", lambda: TF.plot(db="no"), ("db",), None),
        ("dynamic_range-negative", lambda: TF.plot(dynamic_range=-1.0), ("dynamic_range",),
         None),
        ("a-figure", lambda: _closed(TF.plot()), None, lambda ok: ok),
    ],
}
CASES = [(surface, *row) for surface, rows in ROWS.items() for row in rows]


def _closed(fig) -> bool:
    import matplotlib.pyplot as plt

    ok = len(fig.axes) >= 1
    plt.close(fig)
    return ok


@pytest.mark.parametrize(("surface", "id_", "call", "names", "same"), CASES,
                         ids=[f"{s.rsplit('.', 1)[-1]}:{i}" for s, i, *_ in CASES])
def test_every_row_ends_in_a_clear_error_or_the_right_answer(surface, id_, call, names, same):
    import matplotlib

    matplotlib.use("Agg")
    check_row(Row(surface, id_, call, names or (), same), id_)


def contract_rows() -> dict[str, list[str]]:
    """The surfaces these rows cover (read by the inventory test)."""
    return {surface: [row[0] for row in rows] for surface, rows in ROWS.items()}
