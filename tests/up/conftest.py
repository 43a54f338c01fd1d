"""tests/up need unified-planning, the ``up`` extra (``make setup`` installs it): without it they
fail at collection with this message instead of being skipped."""

import importlib.util

if importlib.util.find_spec("unified_planning") is None:
    raise ImportError("tests/up need unified-planning: pip install -e '.[up]' (make setup does)")
