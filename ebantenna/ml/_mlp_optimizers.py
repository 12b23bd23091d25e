"""The optimisers' engine: :mod:`ebantenna.ml.optimizers`' updates in place, or compiled (private).

The public :class:`~ebantenna.ml.optimizers.Momentum` and :class:`~ebantenna.ml.optimizers.Adam`
write their formulas as they stand; each line makes a new array. A training loop updates the
parameters once per mini-batch, so the estimators' engine runs the same operations on two
temporaries per parameter array allocated once (``out=``), and, for Adam on C-ordered float64
arrays with numba installed, as one compiled loop per array
(:func:`ebantenna.ml._mlp_numba.adam_step`): one pass over the memory instead of twelve. The
operations and their order are the reference's, so are the results: the tests hold both equal
bit for bit.
"""

from __future__ import annotations

import numpy as np

from .optimizers import Adam, Momentum

__all__ = ["InPlaceMomentum", "InPlaceAdam"]


class InPlaceMomentum(Momentum):
    """:class:`~ebantenna.ml.optimizers.Momentum`, its update written into two temporaries.

    Examples
    --------
    >>> p = [np.array([1.0])]
    >>> opt = InPlaceMomentum(p, learning_rate=0.1, momentum=0.0, nesterov=False)
    >>> opt.update(p, [np.array([2.0])]); p[0]
    array([0.8])
    """

    def __init__(self, params, learning_rate: float, momentum: float = 0.9,
                 nesterov: bool = True):
        super().__init__(params, learning_rate, momentum, nesterov)
        self._steps = [np.empty_like(p) for p in params]
        self._scratch = [np.empty_like(p) for p in params]

    def update(self, params, grads) -> None:
        """Move ``params`` in place: the reference's operations, in its order."""
        for p, g, v, step, tmp in zip(params, grads, self.velocities, self._steps,
                                      self._scratch, strict=True):
            np.multiply(g, self.learning_rate, out=step)  # lr * g
            v *= self.momentum
            v -= step
            if self.nesterov:
                np.multiply(v, self.momentum, out=tmp)
                np.subtract(tmp, step, out=step)
                p += step
            else:
                p += v


class InPlaceAdam(Adam):
    """:class:`~ebantenna.ml.optimizers.Adam`, its update in place or as one compiled loop.

    Parameters
    ----------
    params, learning_rate, beta_1, beta_2, epsilon
        As for :class:`~ebantenna.ml.optimizers.Adam`.
    compiled : module or None
        The compiled loops (:func:`ebantenna.ml._mlp_compiled.compiled_kernels`), or None for
        NumPy calls only; both give the reference's bits.

    Examples
    --------
    >>> p = [np.array([1.0])]
    >>> opt = InPlaceAdam(p, learning_rate=0.1)
    >>> opt.update(p, [np.array([3.0])]); np.round(p[0], 6)
    array([0.9])
    """

    def __init__(self, params, learning_rate: float = 1e-3, beta_1: float = 0.9,
                 beta_2: float = 0.999, epsilon: float = 1e-8, *, compiled=None):
        super().__init__(params, learning_rate, beta_1, beta_2, epsilon)
        self._steps = [np.empty_like(p) for p in params]
        self._scratch = [np.empty_like(p) for p in params]
        self._compiled = compiled

    def update(self, params, grads) -> None:
        """Move ``params`` in place: the reference's operations, in its order."""
        lr_t = self.learning_rate_at_step()
        for p, g, m, v, step, tmp in zip(params, grads, self.ms, self.vs, self._steps,
                                         self._scratch, strict=True):
            if self._compiled is not None and _flat_views(p, g):
                self._compiled.adam_step(p.reshape(-1), g.reshape(-1), m.reshape(-1),
                                         v.reshape(-1), self.beta_1, self.beta_2,
                                         1 - self.beta_1, 1 - self.beta_2, lr_t, self.epsilon)
                continue
            # m = beta_1 m + (1 - beta_1) g; v = beta_2 v + (1 - beta_2) g g;
            # p -= lr_t m / (sqrt(v) + eps): in place on two temporaries
            np.multiply(g, 1 - self.beta_1, out=tmp)
            m *= self.beta_1
            m += tmp
            np.multiply(g, 1 - self.beta_2, out=tmp)
            tmp *= g
            v *= self.beta_2
            v += tmp
            np.sqrt(v, out=tmp)
            tmp += self.epsilon
            np.multiply(m, lr_t, out=step)
            step /= tmp
            p -= step


def _flat_views(*arrays) -> bool:
    """Whether every array is C-ordered float64 (``reshape(-1)`` is then a view)."""
    return all(a.dtype == np.float64 and a.flags.c_contiguous for a in arrays)
