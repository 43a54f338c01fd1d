"""``python -m artiplan`` runs the command line."""

import sys

from artiplan.cli import main

sys.exit(main())
