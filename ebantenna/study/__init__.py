"""The whole study end to end (``ebantenna reproduce``): one module per report section, each a
pure ``compute`` returning a frozen result and a ``render`` that writes it."""

from .reproduce import StudyResult, default_cache_dir, reproduce

__all__ = ["reproduce", "StudyResult", "default_cache_dir"]
