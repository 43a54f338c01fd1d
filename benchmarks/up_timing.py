"""Time through unified-planning against ``artiplan plan`` on the suite, up-enhsp alongside.

Usage:
    .venv/bin/python benchmarks/up_timing.py SUITE_DIR [--only ng,ucm-0.1] [--sizes 3,4]
        [--time-limit 20] [--reps 2] [--cli N] [--enhsp-sizes 3,4,5] [--enhsp-timeout 10]
        [--jsonl out.jsonl]

Per problem, the unified-planning problem is read first (``artiplan.up.read_pddl``; that is the
user's modelling step, not timed). Then, ``--reps`` times each, alternating (best run kept):

* ``direct``: ``artiplan.plan(domain_path, problem_path)`` in this process: the code that
  ``artiplan plan`` runs, from the files (parsing and grounding included);
* ``up``: ``with OneshotPlanner(name="artiplan") as p: p.solve(problem, timeout=...)``: engine
  creation, unified-planning's kind check, writing PDDL+, artiplan's parse, ground and search,
  the plan mapped back.

Wall and CPU seconds of this process. ``--cli N``: also the ``artiplan plan`` command as a child
process (Python start-up included) on the first N problems of each model. ``--enhsp-sizes``:
``OneshotPlanner(name="enhsp")`` (a Java child process; its CPU from the children's rusage) on
those sizes, its plan judged by ``PlanValidator(name="artiplan", params={"end": "first-goal"})``.
"""

from __future__ import annotations

import argparse
import json
import resource
import statistics
import subprocess
import sys
import time
from pathlib import Path
from typing import Any

sys.path.insert(0, str(Path(__file__).resolve().parent))

from up_validator_agreement import suite_entries  # noqa: E402

import artiplan  # noqa: E402
import artiplan.up  # noqa: E402


def _clock() -> tuple[float, float, float]:
    kids = resource.getrusage(resource.RUSAGE_CHILDREN)
    return time.perf_counter(), time.process_time(), kids.ru_utime + kids.ru_stime


def _since(t: tuple[float, float, float]) -> tuple[float, float, float]:
    now = _clock()
    return now[0] - t[0], now[1] - t[1], now[2] - t[2]


def time_direct(domain: Path, problem: Path, limit: float) -> dict:
    t = _clock()
    res = artiplan.plan(domain, problem, time_limit=limit)
    wall, cpu, _ = _since(t)
    mk = res.plan.makespan if res.plan is not None else None
    return {"status": res.status.value, "wall": wall, "cpu": cpu, "makespan": mk}


def time_up(up_problem: Any, limit: float, name: str = "artiplan") -> dict:
    from unified_planning.shortcuts import OneshotPlanner

    t = _clock()
    with OneshotPlanner(name=name) as planner:
        res = planner.solve(up_problem, timeout=limit)
    wall, cpu, child = _since(t)
    mk = None
    if res.plan is not None and hasattr(res.plan, "timed_actions"):
        mk = max((float(s) for s, _, _ in res.plan.timed_actions), default=0.0)
    return {"status": res.status.name, "wall": wall, "cpu": cpu + child, "makespan": mk,
            "plan": res.plan, "metrics": res.metrics or {}}


def time_cli(domain: Path, problem: Path, limit: float) -> dict:
    exe = Path(sys.executable).with_name("artiplan")
    t = _clock()
    proc = subprocess.run([str(exe), "plan", str(domain), str(problem), "-o", "/dev/null",
                           "--time-limit", str(limit)], capture_output=True, text=True)
    wall, _, child = _since(t)
    return {"exit": proc.returncode, "wall": wall, "cpu": child}


def best(runs: list[dict]) -> dict:
    return min(runs, key=lambda r: r["wall"])


def run_entry(suite: Path, entry: dict, args: argparse.Namespace, cli: bool) -> dict:
    from unified_planning.shortcuts import PlanValidator

    domain, problem = suite / entry["domain"], suite / entry["problem"]
    up_problem = artiplan.up.read_pddl(domain, problem)
    direct, through = [], []
    for _ in range(args.reps):
        direct.append(time_direct(domain, problem, args.time_limit))
        through.append(time_up(up_problem, args.time_limit))
    d, u = best(direct), best(through)
    row = {"problem": entry["problem"], "model": entry["model"], "size": entry["size"],
           "direct": d, "up": {k: v for k, v in u.items() if k not in ("plan", "metrics")},
           "ratio_wall": u["wall"] / d["wall"], "ratio_cpu": u["cpu"] / max(d["cpu"], 1e-9),
           "same_makespan": d["makespan"] is not None and u["makespan"] is not None
           and abs(d["makespan"] - u["makespan"]) < 1e-6}
    if cli:
        row["cli"] = time_cli(domain, problem, args.time_limit)
    if entry["size"] in args.enhsp_sizes:
        e = time_up(up_problem, args.enhsp_timeout, "enhsp")
        verdict = None
        if e["plan"] is not None:
            with PlanValidator(name="artiplan", params={"end": "first-goal"}) as v:
                verdict = v.validate(up_problem, e["plan"]).status.name
        row["enhsp"] = {"status": e["status"], "wall": e["wall"], "cpu": e["cpu"],
                        "artiplan_verdict": verdict}
    return row


def _stats(xs: list[float]) -> str:
    if not xs:
        return "-"
    gm = statistics.geometric_mean(xs)
    return f"{statistics.median(xs):.2f} / {gm:.2f} / {max(xs):.2f}"


def summary(rows: list[dict]) -> str:
    lines = ["| model | problems | same plan | direct wall median [s] | up wall median [s] | "
             "up/direct wall: median / geo-mean / max | up/direct CPU: median / geo-mean / max |",
             "|---|---|---|---|---|---|---|"]
    groups: dict[str, list[dict]] = {}
    for r in rows:
        groups.setdefault(r["model"], []).append(r)
    groups["**all**"] = rows
    for model, rs in groups.items():
        ok = [r for r in rs if r["direct"]["status"] == "solved"]
        lines.append(
            f"| {model} | {len(rs)} | {sum(r['same_makespan'] for r in rs)} | "
            f"{statistics.median([r['direct']['wall'] for r in ok]):.3f} | "
            f"{statistics.median([r['up']['wall'] for r in ok]):.3f} | "
            f"{_stats([r['ratio_wall'] for r in ok])} | {_stats([r['ratio_cpu'] for r in ok])} |")
    return "\n".join(lines)


def summary_side(rows: list[dict]) -> str:
    cli = [r for r in rows if "cli" in r]
    en = [r for r in rows if "enhsp" in r]
    out = []
    if cli:
        out.append(f"`artiplan plan` as a process, {len(cli)} problems: median wall "
                   f"{statistics.median([r['cli']['wall'] for r in cli]):.3f} s, CPU "
                   f"{statistics.median([r['cli']['cpu'] for r in cli]):.3f} s; through UP "
                   f"on the same problems: median wall "
                   f"{statistics.median([r['up']['wall'] for r in cli]):.3f} s")
    if en:
        solved = [r for r in en if r["enhsp"]["status"] == "SOLVED_SATISFICING"]
        valid = [r for r in solved if r["enhsp"]["artiplan_verdict"] == "VALID"]
        out.append(f"up-enhsp on {len(en)} problems: reported solved {len(solved)}, valid (exact "
                   f"time, first-goal) {len(valid)}; median wall "
                   f"{statistics.median([r['enhsp']['wall'] for r in en]):.2f} s; artiplan "
                   f"through UP on the same: median wall "
                   f"{statistics.median([r['up']['wall'] for r in en]):.3f} s")
    return "\n\n".join(out)


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("suite", type=Path)
    ap.add_argument("--only", default="")
    ap.add_argument("--sizes", default="")
    ap.add_argument("--time-limit", type=float, default=20.0)
    ap.add_argument("--reps", type=int, default=2)
    ap.add_argument("--cli", type=int, default=0)
    ap.add_argument("--enhsp-sizes", default="")
    ap.add_argument("--enhsp-timeout", type=float, default=10.0)
    ap.add_argument("--jsonl", type=Path, default=None)
    args = ap.parse_args(argv)
    args.enhsp_sizes = {int(s) for s in args.enhsp_sizes.split(",") if s}
    from unified_planning.shortcuts import get_environment

    get_environment().credits_stream = None
    entries = suite_entries(args.suite, args.only, args.sizes)
    warm = entries[0]
    run_entry(args.suite, warm, argparse.Namespace(**{**vars(args), "enhsp_sizes": set()}), False)
    rows, seen = [], {}
    for k, entry in enumerate(entries, 1):
        seen[entry["model"]] = seen.get(entry["model"], 0) + 1
        row = run_entry(args.suite, entry, args, seen[entry["model"]] <= args.cli)
        rows.append(row)
        print(f"[{k}/{len(entries)}] {entry['problem']}: direct {row['direct']['wall']:.3f} s, "
              f"up {row['up']['wall']:.3f} s (x{row['ratio_wall']:.2f})"
              + (f", enhsp {row['enhsp']['status']} {row['enhsp']['wall']:.1f} s"
                 if "enhsp" in row else ""), flush=True)
    if args.jsonl:
        args.jsonl.write_text("".join(json.dumps(r) + "\n" for r in rows))
    print(summary(rows))
    print(summary_side(rows))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
