"""How far rounding moves an eigenvalue of the inverted solve, and the floor at zero it allows.

Shared by the dense and sparse solves of :mod:`~ebantenna.fem.modal` and the batched dense
sweep of :mod:`~ebantenna.fem.sweeps`, so that a rigid or nearly rigid mode that rounding
leaves a hair below zero is floored by one bound everywhere, and a truly negative eigenvalue
(a stiffness that is not semi-definite) is refused everywhere.
"""

from __future__ import annotations

import numpy as np

__all__ = ["floored", "rounding"]


def floored(lam: np.ndarray, rounding) -> np.ndarray:
    """``lam`` (1/s^2) floored at zero; raise where it lies below ``-rounding`` (per mode)."""
    if np.any(lam < -rounding):
        raise np.linalg.LinAlgError(
            f"negative eigenvalue {lam.min():g} 1/s^2, below what rounding reaches "
            f"({-np.max(rounding):.2g}): K is not semi-definite"
        )
    return np.maximum(lam, 0.0)


def rounding(A, shift: float, lam: np.ndarray, phi: np.ndarray) -> np.ndarray:
    """How far rounding can move each eigenvalue of the inverted solve, 1/s^2, from ``A = K + s M``.

    The factorisation ``A = L L^T`` and the two solves with ``L`` are each exact for ``A``
    perturbed by at most ``gamma_{w+2} |L| |L^T|`` entry by entry (Higham, *Accuracy and
    Stability of Numerical Algorithms*, Thms 8.5 and 10.3), ``w`` the half-bandwidth of ``A`` (the
    longest inner product). With ``A`` positive definite, ``(|L| |L^T|)_ij <= sqrt(a_ii a_jj)``,
    zero for ``|i - j| > w``; to first order a perturbation ``dA`` moves ``lam`` by ``phi^T dA phi``
    (``phi`` mass-normalised), so by at most ``3 gamma_{w+2} (2w + 1) sum_i a_ii phi_i^2``, for a
    rigid-body mode of the order of ``eps * omega_max^2``. The eigen-solve of ``L^-1 M L^-T`` adds
    ``n eps mu_max`` to ``mu = 1 / (lam + s)``: ``n eps (|lam| + s)^2 / s`` to ``lam``. The sparse
    path factorises the same ``A`` (SuperLU) and is held to the same bound.
    """
    rows, cols = A.nonzero()
    w = int(np.max(np.abs(rows - cols), initial=0))
    eps = np.finfo(float).eps
    gamma = (w + 2) * eps / (1 - (w + 2) * eps)
    energy = np.einsum("i,ik,ik->k", A.diagonal(), phi, phi)
    return 3 * gamma * (2 * w + 1) * energy + A.shape[0] * eps * (np.abs(lam) + shift) ** 2 / shift
