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
