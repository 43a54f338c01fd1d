"""Old commit against new in one run: coverage, plan quality and in-process planning time.

Each side plans its own suite (written by its own ``artiplan suite``: the encodings may
differ), or with ``--suite DIR`` both sides plan the same files, in a child process,
in-process per problem (``artiplan.plan``, CPU time of the call).
Rounds alternate the order (old, new, new, old, ...) so a machine that gets busier or quieter
during the run favours neither; per problem the fastest round counts.

    git worktree add --detach /tmp/old <commit>
    python benchmarks/planner_old_new.py --old-src /tmp/old/src --rounds 2 \\
        -o benchmarks/results/planner-data/old-new.json

``--plans DIR`` also writes each side's plan text (``DIR/old/<id>.plan``, ``DIR/new/...``, first
round) and counts the problems whose plan text differs.
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

HERE = Path(__file__).resolve()
NEW_SRC = HERE.parents[1] / "src"


def child(suite: str, cold: bool = False) -> None:
    """Plan every problem of ``suite``; one JSON line per problem on stdout (with the plan's
    text). ``cold``: empty the process-wide cache of compiled sources before each problem (as in
    a fresh process)."""
    import artiplan
    from artiplan.bench.suite import load_suite
    from artiplan.semantics.plan_io import format_plan

    for p in load_suite(suite):
        walks = sys.modules.get("artiplan.semantics.walks")  # imported by the first plan
        clear = getattr(getattr(walks, "_code", None), "cache_clear", None)
        if cold and clear is not None:
            clear()
        t = time.process_time()
        r = artiplan.plan(p.domain, p.problem, time_limit=120)
        cpu = time.process_time() - t
        print(json.dumps({
            "id": p.problem_id, "status": r.status.value, "cpu_s": cpu,
            "makespan": r.plan.makespan if r.plan else None,
            "actions": len([a for a in r.plan.actions if a.name != "observe"]) if r.plan else None,
            "text": format_plan(r.plan) if r.plan else None,
        }), flush=True)


def run_side(src: Path, suite: Path, cold: bool = False) -> dict[str, dict[str, Any]]:
    env = dict(os.environ, PYTHONPATH=str(src), PYTHONHASHSEED="0")
    proc = subprocess.run([sys.executable, str(HERE), "--child", str(suite),
                           *(["--cold"] if cold else [])], env=env,
                          capture_output=True, text=True, check=True)
    rows = [json.loads(line) for line in proc.stdout.splitlines() if line.startswith("{")]
    return {r["id"]: r for r in rows}


def write_suite(src: Path, out: Path) -> None:
    env = dict(os.environ, PYTHONPATH=str(src))
    subprocess.run([sys.executable, "-m", "artiplan", "suite", str(out)], env=env, check=True,
                   capture_output=True)


def merge(rounds: list[dict[str, dict[str, Any]]]) -> dict[str, dict[str, Any]]:
    out = {}
    for pid in rounds[0]:
        runs = [r[pid] for r in rounds if pid in r]
        best = min(runs, key=lambda r: r["cpu_s"])
        out[pid] = {**best, "cpu_s": best["cpu_s"], "cpu_all": [r["cpu_s"] for r in runs]}
    return out


def summary(name: str, rows: dict[str, dict[str, Any]]) -> dict[str, Any]:
    solved = [r for r in rows.values() if r["status"] == "solved"]
    cpu = [r["cpu_s"] for r in rows.values()]
    return {"side": name, "problems": len(rows), "solved": len(solved),
            "median_cpu_s": statistics.median(cpu), "total_cpu_s": sum(cpu)}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--child", help=argparse.SUPPRESS)
    ap.add_argument("--old-src", type=Path, help="src/ of the old commit")
    ap.add_argument("--new-src", type=Path, default=NEW_SRC)
    ap.add_argument("--rounds", type=int, default=2, help="rounds per side (alternating)")
    ap.add_argument("-o", "--out", type=Path, help="write the per-problem numbers (JSON)")
    ap.add_argument("--suite", type=Path,
                    help="one suite both sides plan (default: each side writes its own)")
    ap.add_argument("--plans", type=Path, help="write each side's plans here and compare them")
    ap.add_argument("--cold", action="store_true",
                    help="empty the compiled-source cache before each problem (a side that "
                    "has one), as if each problem ran in a fresh process")
    args = ap.parse_args()
    if args.child:
        child(args.child, args.cold)
        return
    if args.old_src is None:
        ap.error("--old-src is required")
    with tempfile.TemporaryDirectory() as tmp:
        suites = {"old": Path(tmp) / "old", "new": Path(tmp) / "new"}
        srcs = {"old": args.old_src, "new": args.new_src}
        for side in ("old", "new"):
            if args.suite:
                suites[side] = args.suite
            else:
                write_suite(srcs[side], suites[side])
        results: dict[str, list[dict[str, dict[str, Any]]]] = {"old": [], "new": []}
        order = ["old", "new"]
        for k in range(args.rounds):
            for side in (order if k % 2 == 0 else order[::-1]):
                print(f"round {k + 1}: {side} ...", file=sys.stderr, flush=True)
                results[side].append(run_side(srcs[side], suites[side], args.cold))
    old, new = merge(results["old"]), merge(results["new"])
    both = [pid for pid in old if old[pid]["status"] == new.get(pid, {}).get("status") == "solved"]
    quality = {"new_better_or_equal": 0, "new_worse": 0}
    for pid in both:
        o, n = old[pid], new[pid]
        worse = n["makespan"] > o["makespan"] + 0.05 and n["actions"] >= o["actions"]
        worse = worse or n["actions"] > o["actions"] and n["makespan"] >= o["makespan"] - 0.05
        quality["new_worse" if worse else "new_better_or_equal"] += 1
    # Per measure, new against old: makespan equal within 1 ms, actions equal.
    def cmp(key: str, tol: float) -> dict[str, int]:
        signs = [(new[p][key] > old[p][key] + tol) - (new[p][key] < old[p][key] - tol)
                 for p in both]
        return {"better": signs.count(-1), "same": signs.count(0), "worse": signs.count(1)}
    per_measure = {"makespan": cmp("makespan", 1e-3), "actions": cmp("actions", 0)}
    same_text = None
    if args.plans:
        for side in ("old", "new"):
            for pid, row in results[side][0].items():
                path = args.plans / side / (pid.replace("/", "_") + ".plan")
                path.parent.mkdir(parents=True, exist_ok=True)
                path.write_text(row["text"] or "")
        first = {side: results[side][0] for side in ("old", "new")}
        differ = sorted(pid for pid in first["old"]
                        if first["old"][pid]["text"] != first["new"].get(pid, {}).get("text"))
        same_text = {"same": len(first["old"]) - len(differ), "differ": differ}
    so, sn = summary("old", old), summary("new", new)
    report = {
        "machine": os.uname().nodename, "date": time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime()),
        "rounds": args.rounds, "cold": args.cold, "old": so, "new": sn,
        "median_ratio_new_old": sn["median_cpu_s"] / so["median_cpu_s"],
        "total_ratio_new_old": sn["total_cpu_s"] / so["total_cpu_s"],
        "quality_on_both_solved": quality,
        "per_measure_on_both_solved": per_measure, "plan_text": same_text,
        "problems": {pid: {side: {k: v for k, v in (rows.get(pid) or {}).items() if k != "text"}
                           for side, rows in (("old", old), ("new", new))} for pid in old},
    }
    text = json.dumps({k: v for k, v in report.items() if k != "problems"}, indent=1)
    print(text)
    if args.out:
        args.out.write_text(json.dumps(report, indent=1) + "\n")


if __name__ == "__main__":
    main()
