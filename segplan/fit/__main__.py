"""``python -m segplan.fit [--check]`` (see :mod:`segplan.fit.store`)."""

import sys

from .store import main

__all__: list[str] = []

sys.exit(main())
