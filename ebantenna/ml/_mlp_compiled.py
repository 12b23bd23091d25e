"""Whether the multilayer perceptron's elementwise steps run compiled (private).

:func:`compiled_kernels` gives :mod:`ebantenna.ml._mlp_numba` (the loops numba compiles, the
``fast`` extra) when the engine choice of :mod:`ebantenna._engines` allows it and the
loops compile, else None: the NumPy calls. numba is imported only then, the first time a network
is trained, not when :mod:`ebantenna.ml` is imported.
"""

from __future__ import annotations

import functools

from .._engines import EngineStatus, load_compiled, use_compiled

__all__ = ["ACTIVATION_CODES", "compiled_kernels", "engine_status"]

#: The activations' codes in :func:`ebantenna.ml._mlp_numba.derivative_and_bias_gradient`.
ACTIVATION_CODES = {"identity": 0, "tanh": 1, "logistic": 2, "relu": 3}


@functools.cache
def _status() -> EngineStatus:
    """Compile the loops once per process; say once why not."""
    return load_compiled(
        "compiled MLP loops",
        "the MLP's elementwise steps run as NumPy calls (the same numbers, slower)",
        "_mlp_numba",
        lambda loops: loops.smoke_test(),
    )


#: Whether the compiled MLP loops load here (loaded once per process).
engine_status = _status


def compiled_kernels(engine: str | None = None):
    """:mod:`ebantenna.ml._mlp_numba` when its loops are to run, else None.

    Parameters
    ----------
    engine : {'auto', 'numpy', 'compiled'} or None
        None reads the environment variable ``EBANTENNA_ENGINE`` (default ``'auto'``), which
        chooses the SMO engine too: the compiled loops when numba works, NumPy otherwise.

    Raises
    ------
    ValueError
        For another value.
    RuntimeError
        For ``'compiled'`` when numba is missing or fails (the reason in the message).

    Examples
    --------
    >>> compiled_kernels("numpy") is None
    True
    """
    if use_compiled(engine, _status, "compiled MLP loops"):
        from . import _mlp_numba

        return _mlp_numba
    return None
