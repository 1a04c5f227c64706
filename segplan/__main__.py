"""``python -m segplan``: the ``segplan`` command line (see :mod:`segplan.cli`)."""

import sys

from .cli import main

sys.exit(main())
