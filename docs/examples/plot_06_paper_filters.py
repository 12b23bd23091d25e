"""
The paper's band-pass filters against their tables
==================================================

The paper gives two band-pass specifications: Table 1 (Chebyshev, 60-160 Hz, before the decay fit)
and Table 2 (elliptic, 52-325 Hz, before the distance network), and calls both filters "second
order". :func:`ebantenna.signal.paper_filter <ebantenna.signal.filters.paper_filter>` designs the
lowest order that meets each table; :func:`ebantenna.signal.check_specification
<ebantenna.signal.filters.check_specification>` measures a design against its table. The stated
"second order" does not meet either table.
"""

import matplotlib.pyplot as plt
import numpy as np

from ebantenna.signal import PAPER_FILTERS, check_specification, paper_filter
from ebantenna.signal.filters import freqz_sos

for kind in ("chebyshev", "elliptic"):  # one figure each
    fig, ax = plt.subplots(figsize=(7, 4))
    spec = PAPER_FILTERS[kind]
    for order, style in ((None, "-"), ("stated", "--")):
        sos = paper_filter(kind, order)
        report = check_specification(sos, spec)
        f, h = freqz_sos(sos, worN=4096, fs=spec.fs)
        which = "order the table needs" if order is None else "the text's \"second order\""
        verdict = "meets the table" if report.meets else "fails the table"
        label = f"{which} ({len(sos)} sections): {verdict}"
        ax.plot(f, 20 * np.log10(np.maximum(np.abs(h), 1e-12)), style, label=label)
        print(f"{kind:9s} {label}; pass-band loss {report.passband_loss:.2f} dB, "
              f"stop-band attenuation {report.stopband_attenuation:.1f} dB")
    # the table as forbidden regions
    ax.fill_between(spec.passband, -spec.ripple, -200, color="tab:red", alpha=0.15, lw=0,
                    label="forbidden by the table")
    ax.fill_between([0, spec.stopband[0]], -spec.attenuation, 10, color="tab:red", alpha=0.15, lw=0)
    ax.fill_between([spec.stopband[1], spec.fs / 2], -spec.attenuation, 10, color="tab:red",
                    alpha=0.15, lw=0)
    ax.set_ylim(-100, 5)
    ax.set_xlim(0, spec.fs / 2)
    ax.set_xlabel("frequency (Hz)")
    ax.set_ylabel("gain (dB)")
    ax.set_title(f"{kind}: {spec.source}", fontsize="small")
    ax.legend(fontsize="small", loc="lower center")
    fig.tight_layout()
plt.show()
