"""artiplan's planner on objects beyond the paper: 16, 20 and 30 links, 5 tasks per model.

Usage:
    .venv/bin/python benchmarks/planner_large.py OUTDIR [--time-limit 60] [--val] [--models M..]

``--val`` writes every plan next to its problem (``pN-S.plan``) and records stock VAL's verdict
(``Validate -t 0.001`` under a 60 s CPU and 4 GB memory limit) in the row.

Writes the problems with ``artiplan generate`` (seeds 1..5; UCM speed-g 0.5 deg/s, UACM
acceleration 0.5 deg/s^2) into OUTDIR, plans in-process after parsing, prints one JSON line per
problem and a summary per (model, size).
"""

from __future__ import annotations

import argparse
import json
import statistics
import subprocess
import sys
import time
from pathlib import Path

from artiplan.pddl import load_task
from artiplan.search.api import plan_task
from artiplan.semantics.plan import Plan
from artiplan.semantics.plan_io import format_plan

SIZES = (16, 20, 30)
MODELS = {"ng": [], "ucm": ["--speed-g", "0.5"], "uacm": ["--acceleration", "0.5"]}


def generate(out: Path) -> None:
    for model, extra in MODELS.items():
        for n in SIZES:
            for seed in range(1, 6):
                if not (out / model / f"p{n}-{seed}.pddl").exists():
                    subprocess.run(
                        [sys.executable, "-m", "artiplan", "generate", "--links", str(n),
                         "--model", model, "--seed", str(seed), "--name", f"p{n}-{seed}",
                         "-o", str(out / model), *extra],
                        check=True, capture_output=True)


def _val(folder: Path, name: str, plan: Plan) -> str:
    """Stock VAL's verdict on ``plan`` (written to ``folder/name.plan``)."""
    from artiplan.backends.val import validate_with_val

    path = folder / f"{name}.plan"
    path.write_text(format_plan(plan, events=False))
    result = validate_with_val(folder / "domain.pddl", folder / f"{name}.pddl", path,
                               time_limit=60.0, memory_limit=4096.0)
    return result.verdict


def main() -> int:
    ap = argparse.ArgumentParser()
    ap.add_argument("outdir", type=Path)
    ap.add_argument("--time-limit", type=float, default=60.0)
    ap.add_argument("--val", action="store_true", help="check every plan with stock VAL")
    ap.add_argument("--models", nargs="+", choices=list(MODELS), default=list(MODELS),
                    help="run only these models (default: all)")
    args = ap.parse_args()
    generate(args.outdir)
    rows = []
    for model in args.models:
        for n in SIZES:
            for seed in range(1, 6):
                t0 = time.perf_counter()
                task = load_task(str(args.outdir / model / "domain.pddl"),
                                 str(args.outdir / model / f"p{n}-{seed}.pddl"))
                load_s = time.perf_counter() - t0
                t1 = time.perf_counter()
                res = plan_task(task, time_limit=args.time_limit)
                row = {"model": model, "size": n, "task": seed, "status": res.status.value,
                       "plan_s": time.perf_counter() - t1, "load_s": load_s,
                       "length": res.stats.get("plan_length"),
                       "makespan": res.stats.get("makespan"),
                       "expanded": res.stats.get("expanded"),
                       "validate_s": res.stats.get("validate_s")}
                if args.val and res.plan is not None:
                    row["val"] = _val(args.outdir / model, f"p{n}-{seed}", res.plan)
                rows.append(row)
                print(json.dumps(row), flush=True)
    print("| model | size | solved | median s | max s | VAL valid |")
    print("|---|---|---|---|---|---|")
    for model in args.models:
        for n in SIZES:
            rs = [r for r in rows if r["model"] == model and r["size"] == n]
            ts = [float(r["plan_s"]) for r in rs]  # type: ignore[arg-type]
            solved = sum(r["status"] == "solved" for r in rs)
            val = sum(r.get("val") == "valid" for r in rs) if args.val else "-"
            print(f"| {model} | {n} | {solved}/5 | {statistics.median(ts):.2f} | {max(ts):.2f} "
                  f"| {val} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
