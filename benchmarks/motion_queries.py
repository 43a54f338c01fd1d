"""Arm-motion queries of closed-loop runs: every ``plan_path`` call, its wall time and outcome.

Reads the per-task logs that ``execution_loop.py --logs DIR`` writes (``task-K.json``, their
``motions``), prints per run and over all runs the wall-time median, 95th percentile
(nearest rank) and maximum, successes and failures by dimension and reason, and writes one
JSON line per query to ``--out`` (run, task, wall, dims, waypoints, ok, checks, why).

Usage:
    .venv/bin/python benchmarks/motion_queries.py NAME=LOGDIR [NAME=LOGDIR ...] --out OUT.jsonl
"""

from __future__ import annotations

import argparse
import collections
import json
import math
import statistics
from pathlib import Path
from typing import Any


def nearest_rank(values: list[float], share: float) -> float:
    """The ``share`` quantile of ``values`` by nearest rank (a value that occurred)."""
    ordered = sorted(values)
    return ordered[max(0, math.ceil(share * len(ordered)) - 1)]


def summary(label: str, queries: list[dict[str, Any]]) -> str:
    """One line: count, median / p95 / max wall [s], failures by (dims, why)."""
    wall = [q["wall_s"] for q in queries]
    ok = [q["wall_s"] for q in queries if q["ok"]]
    failed = collections.Counter(f"{q['dims']}-D {q['why']}" for q in queries if not q["ok"])
    return (f"{label}: {len(wall)} queries, wall median {statistics.median(wall):.3f} s, "
            f"p95 {nearest_rank(wall, 0.95):.3f} s, max {max(wall):.3f} s; "
            f"successful {len(ok)} (median {statistics.median(ok) if ok else math.nan:.3f} s); "
            f"failed {sum(failed.values())} ({', '.join(f'{k}: {v}' for k, v in failed.items())})")


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("runs", nargs="+", help="NAME=LOGDIR of execution_loop.py --logs")
    ap.add_argument("--out", type=Path, help="write every query as a JSON line here")
    args = ap.parse_args(argv)
    everything: list[dict[str, Any]] = []
    for spec in args.runs:
        name, _, folder = spec.partition("=")
        queries = []
        for path in sorted(Path(folder).glob("task-*.json"), key=lambda p: int(p.stem[5:])):
            task = int(path.stem[5:])
            for m in json.loads(path.read_text())["motions"]:
                queries.append({"run": name, "task": task, **m})
        if not queries:
            raise SystemExit(f"{folder}: no task-K.json with motions")
        print(summary(name, queries))
        everything.extend(queries)
    if len(args.runs) > 1:
        print(summary("all", everything))
    if args.out is not None:
        args.out.write_text("".join(json.dumps(q) + "\n" for q in everything))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
