"""``python -m ebantenna``: the same as the ``ebantenna`` command."""

from .cli import main

raise SystemExit(main())
