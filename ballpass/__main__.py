"""``python -m ballpass`` runs the ``ballpass`` command."""

import sys

from .cli import main

sys.exit(main())
