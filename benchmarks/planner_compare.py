"""Compare artiplan's in-process suite run with a peer's ``artiplan bench`` rows (ENHSP, Kairos).

Usage:
    .venv/bin/python benchmarks/planner_compare.py ARTIPLAN.jsonl BENCH.jsonl [--planner enhsp]

ARTIPLAN.jsonl: written by ``benchmarks/planner_suite.py --jsonl``. BENCH.jsonl: ``artiplan bench``
results (problems matched by ``model/file``, so two copies of the same suite seed match).
Per problem both attempted: who solved it (a peer's plan counts if our validator accepts it),
time ratio (our CPU seconds in-process against the peer's CPU seconds), and plan quality where
both solved: makespan and number of actions. Our trailing no-op ``observe`` is not counted as an
action (it plays the role of ENHSP's ``@PlanEND``).
"""

from __future__ import annotations

import argparse
import json
import statistics
import sys
from pathlib import Path


def load(path: Path) -> list[dict[str, object]]:
    return [json.loads(line) for line in path.read_text().splitlines() if line.strip()]


def _key(row: dict[str, object]) -> str:
    """``model/pN-T.pddl``: the same problem in two copies of the suite (same seed)."""
    path = Path(str(row["problem"]))
    return f"{path.parent.name}/{path.name}"


def main() -> int:
    ap = argparse.ArgumentParser()
    ap.add_argument("ours", type=Path)
    ap.add_argument("bench", type=Path)
    ap.add_argument("--planner", default="enhsp")
    args = ap.parse_args()
    ours = {_key(r): r for r in load(args.ours)}
    peer = [r for r in load(args.bench) if r.get("planner") == args.planner]
    both = better_mk = better_len = 0
    ratios: list[float] = []
    t_ours = t_peer = 0.0
    solved_ours = solved_peer = accepted_own = 0
    for r in peer:
        o = ours.get(_key(r))
        if o is None:
            continue
        ok_o = o["status"] == "solved"
        ok_p = r["status"] == "solved" and bool(r.get("valid"))
        solved_ours += ok_o
        solved_peer += ok_p
        accepted_own += bool(r.get("enhsp_accepts")) and r.get("makespan") is not None
        ours_s = float(o.get("plan_cpu_s", o["plan_s"]))  # type: ignore[arg-type]
        t_ours += ours_s
        t_peer += float(r["cpu_s"] or 0.0)  # type: ignore[arg-type]
        if ok_o and ok_p:
            both += 1
            ratios.append(float(r["cpu_s"]) / max(ours_s, 1e-6))  # type: ignore[arg-type]
            n_ours = int(o["length"]) - int(bool(o.get("ends_with_noop", True)))  # type: ignore[arg-type]
            better_mk += float(o["makespan"]) <= float(r["makespan"]) + 1e-6  # type: ignore[arg-type]
            better_len += n_ours <= int(r["n_actions"])  # type: ignore[arg-type]
    print(f"problems attempted by both: {len(peer)}")
    own = f"; plans its own validation accepts: {accepted_own}" if args.planner == "enhsp" else ""
    print(f"solved: artiplan {solved_ours}, {args.planner} {solved_peer} (our validator){own}")
    print(f"time: artiplan {t_ours:.1f} s CPU in-process, {args.planner} {t_peer:.1f} s CPU "
          f"(timeouts counted at their CPU time); ratio {t_peer / max(t_ours, 1e-9):.0f}x")
    if ratios:
        print(f"per problem solved by both ({both}): median speed-up "
              f"{statistics.median(ratios):.0f}x")
        print(f"plan quality where both solved: makespan no worse on {better_mk}/{both}, "
              f"actions no worse on {better_len}/{both}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
