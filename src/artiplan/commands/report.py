"""``artiplan report RESULTS.jsonl -o report/``: Table 1, PAR10, cactus plot, comparisons."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from artiplan.errors import ExitCode, InputError


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("results", nargs="+", metavar="RESULTS.jsonl",
                        help="results of `artiplan bench` (several files are merged)")
    parser.add_argument("-o", "--out", default="report",
                        help="report folder (default: %(default)s)")
    parser.add_argument("--planners", type=lambda t: [x for x in t.split(",") if x],
                        help="only these planners, in this order")


def run(args: argparse.Namespace) -> int:
    from artiplan.bench.results import read_rows
    from artiplan.viz.report import write_report

    rows = []
    for path in args.results:
        if not Path(path).is_file():
            raise InputError(f"{path}: no such results file")
        rows += read_rows(path)
    if args.planners:
        rows = [r for r in rows if r["planner"] in args.planners]
    if not rows:
        raise InputError(f"{', '.join(args.results)}: no result rows")
    written = write_report(rows, Path(args.out), source=", ".join(args.results))
    print(f"artiplan report: {len(written)} files in {args.out}/ (start at index.md)",
          file=sys.stderr)
    return int(ExitCode.OK)
