"""Progress bars for long work: shown on a terminal, silent otherwise."""

from __future__ import annotations

import sys

from tqdm.auto import tqdm

__all__ = ["progress"]


def progress(iterable=None, *, total=None, desc=None, enabled=None, **kwargs):
    """Wrap ``iterable`` in a :mod:`tqdm` bar that only appears when stderr is a terminal.

    Parameters
    ----------
    iterable : iterable, optional
        What to iterate over.
    total : int, optional
        Number of steps, when ``iterable`` has no length.
    desc : str, optional
        Label in front of the bar.
    enabled : bool, optional
        Force the bar on (True) or off (False); by default on only for a terminal.
    """
    if enabled is None:
        enabled = sys.stderr.isatty()
    return tqdm(iterable, total=total, desc=desc, disable=not enabled, leave=False, **kwargs)
