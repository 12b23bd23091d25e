"""Temporary files the package writes before renaming them into place, and who wrote them.

A writer that must never leave half a file (a recording, a session's manifest, a data set)
writes under a temporary name and renames it. Such a name begins with :data:`TEMPORARY_PREFIX`
and holds the writer's process id, so that a later run removes only what the package itself
left, and only once the process that wrote it has ended: a user's own file is never touched,
whatever its name.
"""

from __future__ import annotations

import os

#: The start of every temporary file name the package writes.
TEMPORARY_PREFIX = ".ebantenna-tmp"


def process_running(pid: int) -> bool:
    """Whether process ``pid`` may still be running (True when it cannot be told)."""
    if pid == os.getpid():
        return True
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except (PermissionError, OverflowError, OSError):
        return True  # someone else's process, or cannot tell: leave its file alone
    return True
