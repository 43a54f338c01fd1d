"""unified-planning's own engine report (``up_test_cases/report.py``) for the ``artiplan`` engine.

Usage:
    .venv/bin/python benchmarks/up_report.py [report options, e.g. -m oneshot validation -t 10]

Registers the engine (``import artiplan.up``), puts ``up_test_cases`` on the path as its report
expects, and runs the report with ``artiplan`` as the engine (other engines with
``--engines-too NAME ...`` before the report's options). Its cases are unified-planning's
builtin test cases and ``unified_planning.test`` examples; kinds the engine does not support are
reported as such by the harness.
"""

from __future__ import annotations

import os
import runpy
import sys

import up_test_cases

import artiplan.up  # noqa: F401  (registers "artiplan")


def main() -> None:
    folder = os.path.dirname(up_test_cases.__file__)
    sys.path.insert(0, folder)
    args = sys.argv[1:]
    engines = ["artiplan"]
    if args[:1] == ["--engines-too"]:
        args = args[1:]
        while args and not args[0].startswith("-"):
            engines.append(args.pop(0))
    sys.argv = [os.path.join(folder, "report.py"), *engines, *args]
    runpy.run_path(sys.argv[0], run_name="__main__")


if __name__ == "__main__":
    main()
