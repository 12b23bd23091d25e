"""Which engine runs, NumPy or compiled (numba), wherever the package has both (private).

The SVM's SMO loop (:mod:`ebantenna.ml._smo_compiled`) and the MLP's elementwise steps
(:mod:`ebantenna.ml._mlp_numba`) each have a compiled twin that returns the same bits; the
simulator's strike march (:mod:`ebantenna.simulate._march_numba`, run from
:mod:`ebantenna.simulate._block_march`) has one that finds the same events. One choice governs
them all: ``'auto'`` unless the ``engine`` argument or the environment variable
:data:`ENGINE_VARIABLE` (``EBANTENNA_ENGINE=numpy|compiled|auto``) says otherwise. Each twin is
loaded once per process by :func:`load_compiled`, which says once why it falls back: a logged
INFO when numba is not installed, a :class:`RuntimeWarning` when it is installed but fails (for
instance a numba release that does not support the installed NumPy).
"""

from __future__ import annotations

import contextlib
import importlib
import importlib.util
import logging
import os
import time
import warnings
from dataclasses import dataclass

import numpy as np

__all__ = ["ENGINES", "ENGINE_VARIABLE", "EngineStatus", "requested_engine", "load_compiled",
           "use_compiled"]

logger = logging.getLogger(__name__)

#: The values of the engine choice.
ENGINES = ("auto", "numpy", "compiled")

#: The environment variable that chooses the engine when the call does not.
ENGINE_VARIABLE = "EBANTENNA_ENGINE"


@dataclass(frozen=True)
class EngineStatus:
    """Whether a compiled engine works here, why not, and what loading it cost.

    Attributes
    ----------
    available : bool
        True when numba imported and compiled the loops.
    reason : str
        The sentence said once when it is not available ('' otherwise).
    load_seconds : float
        Wall time of importing numba and compiling the loops, or loading them from numba's
        cache (s); NaN when not available.
    """

    available: bool
    reason: str
    load_seconds: float


def requested_engine(engine: str | None) -> str:
    """``engine``, or :data:`ENGINE_VARIABLE` (default ``'auto'``) when None, checked.

    Raises
    ------
    ValueError
        For a value not in :data:`ENGINES`, naming the argument or the variable.

    Examples
    --------
    >>> requested_engine("numpy")
    'numpy'
    """
    source = "engine"
    if engine is None:
        engine, source = os.environ.get(ENGINE_VARIABLE, "auto"), ENGINE_VARIABLE
    if engine not in ENGINES:
        raise ValueError(f"{source} must be one of {', '.join(map(repr, ENGINES))}; "
                         f"got {engine!r}")
    return engine


def load_compiled(what: str, fallback: str, module: str, check) -> EngineStatus:
    """Import the compiled loops' module (which imports numba and compiles or loads the loops),
    run ``check`` on it and time both; say once why not, when any of it fails.

    Parameters
    ----------
    what : str
        The compiled twin's name in the messages, e.g. ``'compiled SMO engine'``.
    fallback : str
        What runs instead, e.g. ``'SMO runs on the NumPy engines (...)'``.
    module : str
        The module of the loops, relative to :mod:`ebantenna.ml` (e.g. ``'_smo_numba'``) or
        absolute (``'ebantenna.simulate._march_numba'``); its
        ``IMPORT_ERROR`` says why numba did not import there ('' when it did).
    check : callable
        Called with that module; raises when its loops give a known answer wrongly.
    """
    start = time.perf_counter()
    if importlib.util.find_spec("numba") is None:
        reason = (f"numba is not installed: {fallback}; `pip install ebantenna[fast]` adds "
                  f"the {what}")
        logger.info(reason)
        return EngineStatus(False, reason, np.nan)
    try:
        # relative to this package, or absolute (another subpackage's loops)
        with interrupts_pass_through():  # an interrupt while numba loads is no failure of it
            loops = importlib.import_module(module if module.startswith("ebantenna.")
                                            else f"ebantenna.ml.{module}")
            if loops.IMPORT_ERROR:
                raise ImportError(loops.IMPORT_ERROR)
            check(loops)
    except Exception as exc:  # numba is installed but cannot build the loops here
        reason = (f"numba is installed but the {what} failed with NumPy {np.__version__} "
                  f"({type(exc).__name__}: {exc}): {fallback}")
        warnings.warn(reason, RuntimeWarning, stacklevel=3)
        return EngineStatus(False, reason, np.nan)
    return EngineStatus(True, "", time.perf_counter() - start)


def use_compiled(engine: str | None, status, what: str) -> bool:
    """Whether the compiled twin runs: ``engine`` (or the variable) asks for it or leaves it to
    ``'auto'``, and ``status()`` (an :class:`EngineStatus`, loaded once) says it works.

    Raises
    ------
    ValueError
        For an engine not in :data:`ENGINES`.
    RuntimeError
        For ``'compiled'`` when the twin is not available, with the reason.
    """
    engine = requested_engine(engine)
    if engine == "numpy":
        return False
    loaded = status()
    if loaded.available:
        return True
    if engine == "compiled":
        raise RuntimeError(f"the {what} was asked for but {loaded.reason}")
    return False


@contextlib.contextmanager
def interrupts_pass_through():
    """Let an interrupt raised while a compiled function runs reach the caller as itself.

    A signal handler's exception (``KeyboardInterrupt``, or the CLI's ``SignalReceived``) raised
    while numba's own C code runs, loading a compiled function from its cache for instance,
    reaches Python as a :class:`SystemError` caused by it; the interrupt is re-raised instead, so
    that the caller's clean-up for an interrupt runs whatever was running when it came.
    """
    try:
        yield
    except SystemError as exc:
        cause = exc.__cause__ or exc.__context__
        while cause is not None:
            if not isinstance(cause, Exception):  # a BaseException: an interrupt
                raise cause from None
            cause = cause.__cause__ or cause.__context__
        raise
