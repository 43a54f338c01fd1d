"""Run artiplan's planner in-process over a suite folder (``artiplan suite DIR --seed 0``).

Usage:
    .venv/bin/python benchmarks/planner_suite.py SUITE_DIR [--time-limit 10] [--jsonl out.jsonl]
        [--only ng,ucm-0.1] [--process N] [--val]

Per problem: status, planning time after parsing (in-process, ``search`` + ``compile`` +
``validate``; wall and CPU seconds: on a shared machine the CPU time is the stable one), time
with loading, plan length and makespan. Per (model, size): solved / proven
unsolvable / unknown, median / max / total time. With ``--process N``, also time N problems
per model as separate ``artiplan plan`` processes (process start included). With ``--val``,
each plan is written next to its problem (``pN-K.plan``) and judged by stock VAL
(``Validate -t 0.001`` under a 60 s CPU and 4 GB memory limit): column ``val``.
"""

from __future__ import annotations

import argparse
import json
import re
import statistics
import subprocess
import sys
import time
from pathlib import Path

from artiplan.pddl import load_task
from artiplan.search.api import PlanStatus, plan_task
from artiplan.semantics.plan import Plan
from artiplan.semantics.plan_io import format_plan


def problems(root: Path, only: set[str] | None) -> list[tuple[str, int, Path, Path]]:
    out = []
    for model_dir in sorted(p for p in root.iterdir() if p.is_dir()):
        if only and model_dir.name not in only:
            continue
        for prob in sorted(model_dir.glob("p*.pddl")):
            m = re.match(r"p(\d+)-\d+", prob.stem)
            size = int(m.group(1)) if m else 0
            out.append((model_dir.name, size, model_dir / "domain.pddl", prob))
    return out


def val_verdict(domain: Path, prob: Path, plan: Plan) -> str:
    """Stock VAL's verdict on ``plan``, written to ``prob`` with suffix ``.plan``."""
    from artiplan.backends.val import validate_with_val

    path = prob.with_suffix(".plan")
    path.write_text(format_plan(plan, events=False))
    return validate_with_val(domain, prob, path, time_limit=60.0, memory_limit=4096.0).verdict


def run_one(domain: Path, prob: Path, limit: float, val: bool = False) -> dict[str, object]:
    t0 = time.perf_counter()
    task = load_task(str(domain), str(prob))
    load_s = time.perf_counter() - t0
    t1 = time.perf_counter()
    c1 = time.process_time()
    res = plan_task(task, time_limit=limit)
    plan_s = time.perf_counter() - t1
    plan_cpu_s = time.process_time() - c1
    noop = False
    if res.plan is not None and res.plan.actions:
        eff = task.action_by_signature(res.plan.actions[-1].signature).effect
        noop = not (eff.add or eff.delete or eff.numeric or eff.conditional)
    return {
        **({"val": val_verdict(domain, prob, res.plan)} if val and res.plan else {}),
        "problem": str(prob), "status": res.status.value, "plan_s": plan_s,
        "plan_cpu_s": plan_cpu_s,
        "with_load_s": plan_s + load_s, "length": res.stats.get("plan_length"),
        "makespan": res.stats.get("makespan"), "expanded": res.stats.get("expanded"),
        "message": res.message, "ends_with_noop": noop,
        "plan": None if res.plan is None else [(a.time, a.signature) for a in res.plan.actions],
    }


def process_time(domain: Path, prob: Path, limit: float) -> float:
    t0 = time.perf_counter()
    subprocess.run([sys.executable, "-m", "artiplan", "plan", str(domain), str(prob),
                    "--time-limit", str(limit)], capture_output=True, check=False)
    return time.perf_counter() - t0


def summary(rows: list[dict[str, object]]) -> str:
    cells: dict[tuple[str, int], list[dict[str, object]]] = {}
    for r in rows:
        cells.setdefault((str(r["model"]), int(r["size"])), []).append(r)  # type: ignore[arg-type]
    lines = ["| model | size | solved | unsolvable | unknown | median s | max s | total s |",
             "|---|---|---|---|---|---|---|---|"]
    for (model, size), rs in sorted(cells.items()):
        times = [float(r["plan_s"]) for r in rs]  # type: ignore[arg-type]
        solved = sum(r["status"] == PlanStatus.SOLVED.value for r in rs)
        unsolv = sum(r["status"] == PlanStatus.UNSOLVABLE_PROVEN.value for r in rs)
        lines.append(f"| {model} | {size} | {solved} | {unsolv} | {len(rs) - solved - unsolv} "
                     f"| {statistics.median(times):.3f} | {max(times):.3f} | {sum(times):.2f} |")
    all_t = [float(r["plan_s"]) for r in rows]  # type: ignore[arg-type]
    all_c = [float(r["plan_cpu_s"]) for r in rows]  # type: ignore[arg-type]
    solved = sum(r["status"] == "solved" for r in rows)
    lines.append(f"\nall: {len(rows)} problems, solved {solved}, "
                 f"median {statistics.median(all_t):.3f} s, max {max(all_t):.3f} s, "
                 f"total {sum(all_t):.2f} s; CPU: median {statistics.median(all_c):.3f} s, "
                 f"max {max(all_c):.3f} s, total {sum(all_c):.2f} s")
    return "\n".join(lines)


def main() -> int:
    ap = argparse.ArgumentParser()
    ap.add_argument("suite", type=Path)
    ap.add_argument("--time-limit", type=float, default=10.0)
    ap.add_argument("--jsonl", type=Path)
    ap.add_argument("--only", default="")
    ap.add_argument("--process", type=int, default=0)
    ap.add_argument("--val", action="store_true", help="judge every plan with stock VAL")
    args = ap.parse_args()
    rows = []
    only = set(args.only.split(",")) if args.only else None
    for model, size, domain, prob in problems(args.suite, only):
        row = {"model": model, "size": size,
               **run_one(domain, prob, args.time_limit, args.val)}
        rows.append(row)
        print(f"{model:9s} {prob.stem:8s} {row['status']:10s} {row['plan_s']:.3f}s "
              f"len={row['length']} mk={row['makespan']} exp={row['expanded']} "
              f"{row.get('val', '')} {row['message']}",
              file=sys.stderr, flush=True)
    if args.jsonl:
        with args.jsonl.open("w") as fh:
            for r in rows:
                fh.write(json.dumps({"schema": 1, **r}) + "\n")
    print(summary(rows))
    if args.val:
        judged = [r for r in rows if "val" in r]
        print(f"stock VAL: {sum(r['val'] == 'valid' for r in judged)}/{len(judged)} plans valid")
    if args.process:
        by_model: dict[str, list[float]] = {}
        for model, _size, domain, prob in problems(args.suite, only):
            if len(by_model.setdefault(model, [])) < args.process:
                by_model[model].append(process_time(domain, prob, args.time_limit))
        for model, ts in sorted(by_model.items()):
            print(f"process start included, {model}: median {statistics.median(ts):.3f} s "
                  f"over {len(ts)} problems")
    return 0


if __name__ == "__main__":
    sys.exit(main())
