"""The engine choice checked before a command's work (private): see :mod:`ebantenna._engines`."""

from __future__ import annotations

from .._engines import ENGINE_VARIABLE, requested_engine
from ._mlp_compiled import engine_status as mlp_status
from ._smo_compiled import engine_status as smo_status

__all__ = ["check_engine"]


def check_engine() -> str:
    """The engine ``EBANTENNA_ENGINE`` chooses (``'auto'`` unset), refused now if it cannot be
    honoured.

    A command calls this before any work: an unknown name, or ``compiled`` where the compiled
    engines do not load (numba missing or broken), would otherwise stop it part-way.

    Raises
    ------
    ValueError
        Naming the variable: an unknown engine, or ``compiled`` without its engines.

    Examples
    --------
    >>> check_engine() in ("auto", "numpy", "compiled")
    True
    """
    engine = requested_engine(None)
    if engine != "compiled":
        return engine
    for status in (smo_status(), mlp_status()):
        if not status.available:
            raise ValueError(f"{ENGINE_VARIABLE}=compiled asks for the compiled engines, but "
                             f"{status.reason}; set {ENGINE_VARIABLE}=auto (or numpy) to run "
                             "on NumPy")
    return engine
