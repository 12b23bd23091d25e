"""What every effect shares: a name, its parameters as a dict, construction from a dict."""

from __future__ import annotations

from dataclasses import asdict, fields
from typing import ClassVar


class Effect:
    """Shared behaviour: a name, parameters as a dict, construction from a dict."""

    name: ClassVar[str]

    def parameters(self) -> dict:
        """The effect's parameters (for saving scenes and metadata)."""
        return asdict(self)

    @classmethod
    def from_parameters(cls, params: dict):
        """Build the effect from a dict of its parameters, rejecting unknown keys."""
        if not isinstance(params, dict):
            raise TypeError(
                f"parameters of effect {cls.name!r} must be a table/dict, got {params!r}"
            )
        valid = {f.name for f in fields(cls)}
        unknown = sorted(set(params) - valid)
        if unknown:
            allowed = ", ".join(sorted(valid)) or "none"
            raise ValueError(
                f"unknown parameter(s) {', '.join(unknown)} for effect {cls.name!r}; "
                f"allowed: {allowed}"
            )
        return cls(**params)


def check_rng(rng):
    """``rng`` if it is a :class:`numpy.random.Generator` (an effect's stream), else a
    TypeError naming it."""
    import numpy as np

    if not isinstance(rng, np.random.Generator):
        raise TypeError(f"rng must be a numpy.random.Generator, got {type(rng).__name__}")
    return rng


def check_samples(n_samples, rows: int = 1) -> int:
    """``n_samples`` if it is a count >= 0 whose ``rows`` float64 rows fit the memory budget."""
    from ..._budget import check_allocation
    from ..._validate import check_int

    n_samples = check_int("n_samples", n_samples, minimum=0)
    check_allocation(8 * rows * n_samples, parameter="n_samples", what="the samples")
    return n_samples


def check_bodies(obj=None, probe=None) -> None:
    """Refuse an ``obj`` that is not a :class:`~ebantenna.probe.Material` or a ``probe`` that is
    not a :class:`~ebantenna.probe.Probe` (None: not given), naming it."""
    from ...probe import Material, Probe

    if obj is not None and not isinstance(obj, Material):
        raise TypeError(f"obj must be a Material (ebantenna.probe.material(name)), got "
                        f"{type(obj).__name__}")
    if probe is not None and not isinstance(probe, Probe):
        raise TypeError(f"probe must be a Probe, got {type(probe).__name__}")
