"""Which SMO engine runs, and the compiled one (numba) when it is installed and works (private).

:func:`ebantenna.ml.smo.solve_smo` runs :func:`run_if_chosen` (which this module adds to
:data:`ebantenna.ml.smo.SMO_ENGINES` as ``"compiled"`` when the package is imported) for every
problem; it asks :func:`choose_engine`:

* ``'numpy'``: the NumPy engines, :mod:`ebantenna.ml._smo_whole` and
  :mod:`ebantenna.ml._smo_state`, the reference path of the package and the one that needs
  nothing beyond NumPy;
* ``'compiled'``: :func:`ebantenna.ml._smo_numba.smo_loop`, the same loop compiled by numba
  (``pip install ebantenna[fast]``), which returns the same numbers to the last bit (alpha, rho,
  the number of updates, the violation) with no NumPy call per update. It needs the whole
  kernel stored (:meth:`~ebantenna.ml.kernels.KernelRows.stored_entries`); rows computed on
  demand stay on the NumPy engines.

The choice is ``'auto'`` unless the environment variable :data:`ENGINE_VARIABLE`
(``EBANTENNA_ENGINE=numpy|compiled|auto``) or the ``engine`` argument of ``solve_smo`` says
otherwise: the compiled engine when numba imports and compiles the loop, the NumPy engines
otherwise. The first time it is needed, :func:`engine_status` imports numba and compiles the
loop (or loads it from numba's cache) once per process, and says once why it falls back: a
logged INFO when numba is not installed, a :class:`RuntimeWarning` when it is installed but
fails (for instance a numba release that does not support the installed NumPy). Asking for
``'compiled'`` when it is not available raises :class:`RuntimeError` with that reason.
"""

from __future__ import annotations

import functools

import numpy as np

from .._engines import (
    ENGINE_VARIABLE,
    ENGINES,
    EngineStatus,
    interrupts_pass_through,
    load_compiled,
    use_compiled,
)
from .smo import SMO_ENGINES
from .smo_policy import SMOPolicy

__all__ = ["ENGINES", "ENGINE_VARIABLE", "EngineStatus", "engine_status", "choose_engine",
           "run_compiled", "run_if_chosen"]

@functools.cache
def engine_status() -> EngineStatus:
    """Import numba and compile the loop, once per process; say once why not, if it fails.

    Examples
    --------
    >>> status = engine_status()
    >>> status.available or "NumPy engines" in status.reason
    True
    """
    return load_compiled(
        "compiled SMO engine",
        "SMO runs on the NumPy engines (the same numbers, slower on small problems)",
        "_smo_numba",
        _smoke_test,
    )


def _smoke_test(module) -> None:
    """Compile (or load) the loop for float64 and float32 kernels on a two-point problem,
    whose solution is known: :math:`\\alpha = 2/|x_1 - x_2|^2 = 0.5` for the points 0 and 2."""
    for dtype in (np.float64, np.float32):
        K = np.array([[0.0, 0.0], [0.0, 4.0]], dtype=dtype)
        F, up, low, g, perm = _initial_state(np.array([-1.0, 1.0]), np.array([0.0, 4.0]),
                                             np.full(2, 10.0), np.arange(2))
        n_iter, converged, _ = module.smo_loop(K, g, F, up, low, perm, 1e-3, 100.0,
                                               (True, False, False, False), False, 0.0)
        if not (converged and n_iter == 1 and np.array_equal(F[3], [0.5, 0.5])):
            raise RuntimeError(f"the compiled loop solved a two-point problem wrongly: {F[3]}")


def choose_engine(engine: str | None = None) -> str:
    """The engine that runs: ``'numpy'`` or ``'compiled'``.

    Parameters
    ----------
    engine : {'auto', 'numpy', 'compiled'} or None
        None reads :data:`ENGINE_VARIABLE` (default ``'auto'``): the compiled engine when it
        works, else the NumPy engines.

    Raises
    ------
    ValueError
        For another value.
    RuntimeError
        For ``'compiled'`` when numba is missing or fails (the reason in the message).

    Examples
    --------
    >>> choose_engine("numpy")
    'numpy'
    """
    if use_compiled(engine, engine_status, "compiled SMO engine"):
        return "compiled"
    return "numpy"


def _initial_state(y, QD, C, index):
    """The loop's state at :math:`\\alpha = 0`: ``(F, up, low, g, perm)``."""
    n = y.shape[0]
    F = np.zeros((6, n))
    F[0], F[1], F[2], F[4] = y, QD, C, -y  # y, QD, C, alpha = 0, yG = -y, yGbar = 0
    pos = y > 0  # alpha = 0: positives can go up, negatives down (penalties 0 or -inf)
    up, low = np.where(pos, 0.0, -np.inf), np.where(pos, -np.inf, 0.0)
    return F, up, low, np.array(index, dtype=np.int64), np.arange(n, dtype=np.int64)


def _compiled_for(matrix) -> bool:
    """Whether the loop was compiled for this kernel matrix: a writable 2-d ndarray of
    float64 or float32 in the machine's byte order."""
    return (isinstance(matrix, np.ndarray) and matrix.ndim == 2 and matrix.flags.writeable
            and matrix.dtype in (np.dtype(np.float64), np.dtype(np.float32)))


def run_compiled(rows, y: np.ndarray, C: np.ndarray, diagonal: np.ndarray, policy: SMOPolicy,
                 tol: float, max_iter: float):
    """Run the compiled loop, or return None when the kernel is not stored whole.

    Returns
    -------
    tuple or None
        ``(y, C, alpha, yG, perm, n_iter, converged, violation)``, the arrays in the loop's
        order (``perm[p]`` the variable at position ``p``), as the NumPy engines leave them.
    """
    stored = rows.stored_entries()
    if stored is None or not _compiled_for(stored[0]):
        return None
    from . import _smo_numba

    matrix, index = stored
    F, up, low, g, perm = _initial_state(y, diagonal, C, index)
    same_diagonal = bool(np.all(diagonal == diagonal[0]))
    opts = (policy.selection == "second-order", policy.ties == "last",
            policy.curvature_floor == "nonpositive", same_diagonal)
    with interrupts_pass_through():  # a Ctrl-C inside numba's code stays a KeyboardInterrupt
        n_iter, converged, violation = _smo_numba.smo_loop(
            matrix, g, F, up, low, perm, float(tol), float(max_iter), opts,
            bool(policy.shrinking), float(diagonal[0] + diagonal[0]))
    return F[0], F[2], F[3], F[4], perm, int(n_iter), bool(converged), float(violation)


def run_if_chosen(engine, rows, y, C, diagonal, policy, tol, max_iter):
    """:func:`run_compiled` where :func:`choose_engine` chooses the compiled engine (raising as
    it does), else None: ``"compiled"`` of :data:`ebantenna.ml.smo.SMO_ENGINES`."""
    if choose_engine(engine) != "compiled":
        return None
    return run_compiled(rows, y, C, diagonal, policy, tol, max_iter)


SMO_ENGINES["compiled"] = run_if_chosen
