"""One memory budget for every allocation that grows with what a user asks for.

Before an array whose size follows from user input is made (a scalogram's frequency grid, a mesh,
a batch of simulations, an array read from a file's header), its size is estimated and checked
here. A request over the budget is refused with an error that names the parameter, the estimate
and the budget, instead of a :class:`MemoryError` (or the operating system's out-of-memory
killer) part-way through the work.

The budget is, by default, half of the memory this process may still take when the check runs:
the memory the operating system reports as available, or less where the process's own limits
are lower (its address-space limit ``RLIMIT_AS``, as ``ulimit -v`` sets it, less what it has
already mapped; a container's cgroup v2 ``memory.max``, less the group's ``memory.current``).
Half, because the NumPy code that fills an array makes temporaries of about its size
and the machine keeps running other programs. With that default, a request of at most
:data:`UNCHECKED_BYTES` (1 MiB) is allowed without reading the system's state: the reading (three
files under ``/proc`` and ``/sys``) costs more than such an allocation, and the package's feature
and simulation steps ask for many of them; a process with less than that left fails in Python's
own allocations first. Set ``EBANTENNA_MEMORY_BUDGET`` (bytes, or a number
with ``K``, ``M``, ``G`` or ``T``, powers of 1024) or call :func:`set_memory_budget` to choose it.
"""

from __future__ import annotations

import os
import re

__all__ = ["MemoryBudgetError", "memory_budget", "set_memory_budget", "check_allocation",
           "DEFAULT_FRACTION", "UNCHECKED_BYTES"]

#: The fraction of available memory one allocation may take, unless the budget is set.
DEFAULT_FRACTION = 0.5

#: With the default budget, requests up to this size (bytes) are allowed without reading the
#: system's memory (see the module's text). A budget set by the user is checked at every size.
UNCHECKED_BYTES = 2**20

#: Used when the operating system does not report its available memory.
_FALLBACK_AVAILABLE = 2 * 1024**3

_UNITS = {"": 1, "K": 1024, "M": 1024**2, "G": 1024**3, "T": 1024**4}
_chosen: int | None = None


class MemoryBudgetError(ValueError):
    """A requested size is over the memory budget; the message names the parameter."""


def _available_bytes() -> int:
    """Memory available to a new allocation: ``MemAvailable`` on Linux, free pages elsewhere."""
    try:
        with open("/proc/meminfo", encoding="ascii") as meminfo:
            for line in meminfo:
                if line.startswith("MemAvailable:"):
                    return int(line.split()[1]) * 1024
    except (OSError, ValueError, IndexError):
        pass
    try:
        return os.sysconf("SC_AVPHYS_PAGES") * os.sysconf("SC_PAGE_SIZE")
    except (AttributeError, ValueError, OSError):
        return _FALLBACK_AVAILABLE


def _address_space_left() -> int | None:
    """What ``RLIMIT_AS`` leaves this process (the limit less its mapped size), or None."""
    try:
        import resource
    except ImportError:  # not on this platform
        return None
    try:
        limit = resource.getrlimit(resource.RLIMIT_AS)[0]
    except (OSError, ValueError):
        return None
    if limit == resource.RLIM_INFINITY or limit < 0:
        return None
    mapped = 0
    try:
        with open("/proc/self/statm", encoding="ascii") as statm:
            mapped = int(statm.read().split()[0]) * os.sysconf("SC_PAGE_SIZE")
    except (OSError, ValueError, IndexError, AttributeError):
        pass
    return max(limit - mapped, 0)


def _cgroup_left(root: str = "/sys/fs/cgroup") -> int | None:
    """What the cgroup v2 ``memory.max`` of this process's group leaves it, or None."""
    try:
        with open("/proc/self/cgroup", encoding="ascii") as cgroup:
            line = next((ln for ln in cgroup if ln.startswith("0::")), None)
        if line is None:
            return None
        folder = os.path.join(root, line.strip()[3:].lstrip("/"))
        with open(os.path.join(folder, "memory.max"), encoding="ascii") as f:
            text = f.read().strip()
        if text == "max":
            return None
        used = 0
        try:
            with open(os.path.join(folder, "memory.current"), encoding="ascii") as f:
                used = int(f.read().strip())
        except (OSError, ValueError):
            pass
        return max(int(text) - used, 0)
    except (OSError, ValueError):
        return None


def _process_available() -> int:
    """The least of: available memory, what RLIMIT_AS leaves, what the cgroup leaves."""
    limits = [_available_bytes(), _address_space_left(), _cgroup_left()]
    return min(n for n in limits if n is not None)


def _parse(text: str) -> int:
    match = re.fullmatch(r"\s*(\d+(?:\.\d+)?)\s*([KMGT]?)(?:i?B)?\s*", text, flags=re.IGNORECASE)
    if not match or float(match[1]) <= 0:
        raise ValueError(
            f"EBANTENNA_MEMORY_BUDGET must be a positive size such as 4G or 500000000, got {text!r}"
        )
    return int(float(match[1]) * _UNITS[match[2].upper()])


def memory_budget() -> int:
    """The budget in bytes: the one set, else ``$EBANTENNA_MEMORY_BUDGET``, else half of what
    the process may still take (available memory, ``RLIMIT_AS``, cgroup ``memory.max``).

    Examples
    --------
    >>> memory_budget() > 0
    True
    """
    if _chosen is not None:
        return _chosen
    text = os.environ.get("EBANTENNA_MEMORY_BUDGET")
    if text:
        return _parse(text)
    return int(DEFAULT_FRACTION * _process_available())


def set_memory_budget(nbytes: int | None) -> None:
    """Set the budget to ``nbytes`` bytes, or back to its default with ``None``.

    Examples
    --------
    >>> set_memory_budget(10**6); memory_budget()
    1000000
    >>> set_memory_budget(None)
    """
    global _chosen
    if nbytes is not None:
        if isinstance(nbytes, bool | float) or not hasattr(nbytes, "__index__"):
            raise TypeError(f"nbytes must be a positive int or None, got "
                            f"{type(nbytes).__name__}")
        nbytes = nbytes.__index__()  # a NumPy integer too
        if nbytes <= 0:
            shown = nbytes if nbytes.bit_length() < 64 else f"-2**{nbytes.bit_length() - 1} or less"
            raise ValueError(f"nbytes must be a positive int or None, got {shown}")
    _chosen = nbytes


def _size(nbytes: float) -> str:
    for unit in ("B", "KiB", "MiB", "GiB", "TiB"):
        if nbytes < 1024 or unit == "TiB":
            return f"{nbytes:.3g} {unit}" if unit != "B" else f"{int(nbytes)} B"
        nbytes /= 1024
    raise AssertionError("unreachable")


def _petabytes(nbytes) -> str:
    """``nbytes`` in PiB, for an int of any size (``10**400 / 1024**5`` overflows a float)."""
    if isinstance(nbytes, int) and nbytes.bit_length() > 1000:
        return f"2**{nbytes.bit_length() - 1} bytes or more"
    return f"{float(nbytes) / 1024**5:.3g} PiB"


def check_allocation(nbytes, *, parameter: str, what: str) -> None:
    """Raise :class:`MemoryBudgetError` if ``nbytes`` (any size of number) exceeds the budget.

    ``parameter`` is the argument the user passed that sets the size, ``what`` the array it makes.

    Examples
    --------
    >>> check_allocation(8 * 10**3, parameter="n_points", what="the grid")
    >>> check_allocation(8 * 10**15, parameter="n_points", what="the grid")
    Traceback (most recent call last):
    ...
    ebantenna._budget.MemoryBudgetError: n_points asks for the grid of about 7.11 PiB...
    """
    if not nbytes >= 0:  # NaN, or a negative size: an estimate gone wrong, never "fits"
        raise ValueError(f"{parameter}: the size of {what} is not a size in bytes, got {nbytes!r}")
    if nbytes <= UNCHECKED_BYTES and _chosen is None and not os.environ.get(
            "EBANTENNA_MEMORY_BUDGET"):
        return  # the default budget: not worth reading the system's state for (module text)
    budget = memory_budget()
    if nbytes > budget:
        size = _size(float(nbytes)) if nbytes < 1024**5 else _petabytes(nbytes)
        raise MemoryBudgetError(
            f"{parameter} asks for {what} of about {size}, over the memory budget of "
            f"{_size(budget)} (set EBANTENNA_MEMORY_BUDGET or ebantenna.set_memory_budget "
            "to change it)"
        )
