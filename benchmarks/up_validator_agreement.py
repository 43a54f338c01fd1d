"""``PlanValidator(name="artiplan")`` against ``artiplan.semantics.validate``: suite plans and
their mutants (benchmarks/plan_mutations.py).

Usage:
    .venv/bin/python benchmarks/up_validator_agreement.py SUITE_DIR [--only ng,ucm-0.1]
        [--sizes 3,4] [--time-limit 20] [--seed 0] [--jsonl out.jsonl]

SUITE_DIR is ``artiplan suite DIR`` (seed 0). Per problem: artiplan plans it (in-process, the
code ``artiplan plan`` runs; the plan goes through VAL's text format and back, as a plan file
would), unified-planning reads the PDDL+ (``artiplan.up.read_pddl``), and every mutant is judged
twice: by artiplan's validator on the PDDL+ files, and by the unified-planning engine on the
unified-planning problem and plan. Agreement: the same verdict, the same failure kind and the
same failure time (to 1e-6 s). Prints a table per mutation kind; ``--jsonl`` keeps every row.
"""

from __future__ import annotations

import argparse
import json
import random
import sys
import time
import zlib
from collections import Counter, defaultdict
from pathlib import Path
from typing import Any

sys.path.insert(0, str(Path(__file__).resolve().parent))

from plan_mutations import mutations  # noqa: E402

import artiplan  # noqa: E402
import artiplan.up  # noqa: E402
from artiplan.pddl import load_task  # noqa: E402
from artiplan.semantics import Plan, validate  # noqa: E402
from artiplan.semantics.plan_io import format_plan, parse_plan  # noqa: E402
from artiplan.up.convert import to_pddl, to_up_plan  # noqa: E402


def judge_both(task: Any, up_problem: Any, validator: Any, conv: Any, plan: Plan) -> dict:
    """Both verdicts on ``plan`` and whether they agree."""
    ours = validate(task, plan)
    up_plan, _ = to_up_plan(conv, plan)
    theirs = validator.validate(up_problem, up_plan)
    t_valid = theirs.status.name == "VALID"
    t_kind = (theirs.metrics or {}).get("failure_kind", "")
    t_time = (theirs.metrics or {}).get("failure_time")
    same_time = (ours.time is None and t_time is None) or (
        ours.time is not None and t_time is not None and abs(ours.time - float(t_time)) < 1e-6)
    agree = ours.valid == t_valid and ours.kind == t_kind and (ours.valid or same_time)
    return {"ours": "valid" if ours.valid else ours.kind, "up": "valid" if t_valid else t_kind,
            "up_reason": None if theirs.reason is None else theirs.reason.name, "agree": agree,
            "why": "" if ours.valid else ours.reason}


def run_problem(suite: Path, entry: dict, time_limit: float, seed: int, validator: Any) -> list:
    domain, problem = suite / entry["domain"], suite / entry["problem"]
    res = artiplan.plan(domain, problem, time_limit=time_limit)
    if res.plan is None:
        return [{"problem": entry["problem"], "mutation": "original", "ours": res.status.value,
                 "agree": None}]
    plan = parse_plan(format_plan(res.plan))  # through a plan file's text
    task = load_task(domain, problem)
    up_problem = artiplan.up.read_pddl(domain, problem)
    conv = to_pddl(up_problem)
    rng = random.Random(seed * 1000 + zlib.crc32(entry["problem"].encode()) % 1000)
    rows = []
    for label, mutant in [("original", plan), *mutations(plan, rng)]:
        row = judge_both(task, up_problem, validator, conv, mutant)
        rows.append({"problem": entry["problem"], "mutation": label, **row})
    return rows


def suite_entries(suite: Path, only: str = "", sizes: str = "") -> list[dict]:
    """The problems of ``suite/suite.json``, filtered by models and sizes (comma-separated)."""
    entries = json.loads((suite / "suite.json").read_text())["problems"]
    models = set(filter(None, only.split(",")))
    wanted = {int(s) for s in sizes.split(",") if s}
    return [e for e in entries if (not models or e["model"] in models)
            and (not wanted or e["size"] in wanted)]


def summary(rows: list[dict]) -> str:
    by: dict[str, Counter] = defaultdict(Counter)
    for r in rows:
        if r["agree"] is None:
            continue
        c = by[r["mutation"].split("@")[0]]
        c["plans"] += 1
        c["invalid"] += r["ours"] != "valid"
        c["agree"] += bool(r["agree"])
    lines = ["| mutation | plans | invalid (artiplan) | verdicts agree |", "|---|---|---|---|"]
    total = Counter()
    for kind in sorted(by):
        c = by[kind]
        total.update(c)
        lines.append(f"| {kind} | {c['plans']} | {c['invalid']} | {c['agree']}/{c['plans']} |")
    lines.append(f"| **all** | {total['plans']} | {total['invalid']} | "
                 f"**{total['agree']}/{total['plans']}** |")
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("suite", type=Path)
    ap.add_argument("--only", default="", help="models, comma-separated (default all)")
    ap.add_argument("--sizes", default="", help="sizes, comma-separated (default all)")
    ap.add_argument("--time-limit", type=float, default=20.0)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--jsonl", type=Path, default=None)
    args = ap.parse_args(argv)
    from unified_planning.shortcuts import PlanValidator, get_environment

    get_environment().credits_stream = None
    entries = suite_entries(args.suite, args.only, args.sizes)
    rows: list[dict] = []
    t0 = time.perf_counter()
    with PlanValidator(name="artiplan") as validator:
        for k, entry in enumerate(entries, 1):
            new = run_problem(args.suite, entry, args.time_limit, args.seed, validator)
            rows += new
            bad = [r for r in new if r["agree"] is False]
            print(f"[{k}/{len(entries)}] {entry['problem']}: {len(new)} plans, "
                  f"{len(bad)} disagreements ({time.perf_counter() - t0:.0f} s)", flush=True)
            for r in bad:
                print("   DISAGREE", json.dumps(r), flush=True)
    if args.jsonl:
        args.jsonl.write_text("".join(json.dumps(r) + "\n" for r in rows))
    unsolved = [r["problem"] for r in rows if r["agree"] is None]
    print(summary(rows))
    print(f"problems without a plan: {len(unsolved)} {unsolved[:5]}")
    return 0 if all(r["agree"] is not False for r in rows) else 1


if __name__ == "__main__":
    raise SystemExit(main())
