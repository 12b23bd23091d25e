"""The whole study end to end (``ebantenna reproduce``) and the accuracy-versus-time report
(``ebantenna bench``)."""

from .reproduce import StudyResult, default_cache_dir, reproduce

__all__ = ["reproduce", "StudyResult", "default_cache_dir"]
