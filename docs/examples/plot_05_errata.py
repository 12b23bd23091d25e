r"""
The paper's printed matrices against the derivation
===================================================

:func:`ebantenna.fem.symbolic.paper_errata` lists the printed entries of the element matrices
``K``, ``M`` and the two-element matrices ``K1``, ``M1`` that differ from the sympy derivation.
Here we print that list and ask what the differences do to the frequencies: we solve the
two-element model once with the derived matrices and once with the printed ones.

The printed :math:`K_1` and :math:`M_1` carry one factor :math:`EI/l^3` and
:math:`\rho A l/420` with an :math:`l` the paper does not define. With equal elements (contact at
half the length) the obvious reading :math:`l = l_1 = l_2` is unambiguous, and only the typos
remain.
"""

import matplotlib.pyplot as plt
import numpy as np
import scipy.linalg as sla

from ebantenna import Probe
from ebantenna.fem.symbolic import (
    EI,
    l,
    l1,
    l2,
    paper_errata,
    paper_matrices,
    rhoA,
    two_element_matrices,
)

for e in paper_errata():
    print(f"{e.matrix:>2} ({e.row},{e.col})  printed {e.printed:<28} "
          f"derived {e.derived:<40} {e.reason}")

# %%
# Frequencies of the model with three free DOFs :math:`(\theta_2, v_3, \theta_3)`
# -------------------------------------------------------------------------------
probe = Probe()
free = [3, 4, 5]
printed = paper_matrices()
K_derived, M_derived = two_element_matrices()


def frequencies(K, M, values):
    """Natural frequencies (Hz) of symbolic K, M with the free DOFs kept; complex -> NaN."""
    Kn = np.array(K.subs(values).extract(free, free), dtype=float)
    Mn = np.array(M.subs(values).extract(free, free), dtype=float)
    lam = sla.eigvals(Kn, Mn)
    lam = np.sort_complex(lam)
    ok = (np.abs(lam.imag) < 1e-9 * np.abs(lam)) & (lam.real > 0)
    return np.where(ok, np.sqrt(np.abs(lam.real)) / (2 * np.pi), np.nan)


half = probe.length / 2
values = {EI: probe.flexural_rigidity, rhoA: probe.mass_per_length, l: half, l1: half, l2: half}
f_derived = frequencies(K_derived, M_derived, values)
f_printed = frequencies(printed["K1"], printed["M1"], values)
print("contact at L/2, derived matrices:", np.round(f_derived, 2), "Hz")
print("contact at L/2, printed matrices:", np.round(f_printed, 2), "Hz")
print("printed K1 symmetric?", printed["K1"] == printed["K1"].T)

# %%
# Where the printed matrices differ: a map of the 6 × 6 entries of :math:`K_1` and :math:`M_1`,
# one mark for each record of :func:`~ebantenna.fem.symbolic.paper_errata` (rows and columns
# 1-based, as printed), coloured by its reason.
from matplotlib.colors import ListedColormap  # noqa: E402
from matplotlib.patches import Patch  # noqa: E402

codes = {"common factor": 1, "typo": 2}
colours = {"common factor": "tab:orange", "typo": "tab:red"}
for name in ("K1", "M1"):  # one figure each
    fig, ax = plt.subplots(figsize=(6.2, 4.4))
    grid = np.zeros((6, 6))
    for e in paper_errata():
        if e.matrix == name:
            grid[e.row - 1, e.col - 1] = codes[e.reason]
    ax.imshow(grid, cmap=ListedColormap(["white", "tab:orange", "tab:red"]), vmin=0, vmax=2)
    ax.set_xticks(range(6), [f"{k + 1}" for k in range(6)])
    ax.set_yticks(range(6), [f"{k + 1}" for k in range(6)])
    ax.set_xlabel("column")
    ax.set_ylabel("row")
    n = int(np.count_nonzero(grid))
    ax.set_title(f"${name[0]}_{name[1]}$: {n} printed entries differ")  # K1 -> $K_1$
    ax.legend(handles=[Patch(color=c, label=reason) for reason, c in colours.items()],
              loc="upper left", bbox_to_anchor=(1.02, 1), fontsize="small")
    fig.tight_layout()
print("errata in K1 and M1:", sum(e.matrix in ("K1", "M1") for e in paper_errata()),
      "of", len(paper_errata()))
plt.show()
