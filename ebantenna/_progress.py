"""Progress bars for long work: shown on a terminal, silent otherwise."""

from __future__ import annotations

import importlib.util
import sys

import tqdm.std

from ._signals import raise_pending

__all__ = ["bar_class", "progress"]


def bar_class():
    """The progress-bar class: tqdm's notebook bar where it can draw, else the plain text bar.

    :mod:`tqdm.auto` picks the notebook bar inside Jupyter, and without ipywidgets that bar only
    warns ("IProgress not found"). So the automatic choice is made only when ipywidgets can be
    imported; otherwise the plain bar, which writes text to stderr, is used everywhere.
    """
    if importlib.util.find_spec("ipywidgets") is None:
        return tqdm.std.tqdm
    # imported here: tqdm.auto already warns on import inside a kernel without ipywidgets
    from tqdm.auto import tqdm as auto_bar

    return auto_bar


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

    Each step (an item of ``iterable``, or a call of the bar's ``update``) first raises a stop
    signal that a library caught and went on from (``ebantenna._signals.raise_pending``).
    """
    if enabled is None:
        enabled = sys.stderr.isatty()
    if iterable is not None:
        if total is None and hasattr(iterable, "__len__"):
            total = len(iterable)
        iterable = _checked(iterable)
    bar = bar_class()(iterable, total=total, desc=desc, disable=not enabled, leave=False, **kwargs)
    update = bar.update

    def checked_update(n=1):  # a stop a library swallowed is raised again at the next step
        raise_pending()
        return update(n)

    bar.update = checked_update
    return bar


def _checked(iterable):
    """``iterable``'s items, raising before each a signal that a library caught and went on
    from (``ebantenna._signals``)."""
    for item in iterable:
        raise_pending()
        yield item
