"""Stock VAL on the benchmark set: Parser on every domain/problem (and VAL twin), Validate on
every reference plan.

Usage (from the repository root):
    .venv/bin/python benchmarks/pddlplus/check_val.py [--only FAMILY,...] [--out FILE]

Writes ``benchmarks/pddlplus/results/val_check.jsonl`` (one row per instance) and prints a
summary per family. A reference plan is checked on the real files where VAL reads them, else on
the VAL twin (``FAMILY/val/``); families without either are reported as not checked by VAL.
"""

from __future__ import annotations

import argparse
import json
import sys
from collections import defaultdict
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

import valtools  # noqa: E402

SCHEMA = "artiplan.pddlplus-val/1"


def check(entry: dict[str, object]) -> dict[str, object]:
    """Parser and Validate results for one suite entry."""
    dom, prob = HERE / str(entry["domain"]), HERE / str(entry["problem"])
    real = valtools.parse(dom, prob)
    row: dict[str, object] = {
        "schema": SCHEMA, "problem": entry["problem"], "family": entry["family"],
        "size": entry["size"], "parse_errors": real.errors, "parse_warnings": real.warnings,
        "parse_message": real.message,
    }
    target = (dom, prob) if real.errors == 0 else None
    if "val_domain" in entry:
        tdom, tprob = HERE / str(entry["val_domain"]), HERE / str(entry["val_problem"])
        if not tprob.exists():
            tprob = prob
        twin = valtools.parse(tdom, tprob)
        row.update(twin_errors=twin.errors, twin_warnings=twin.warnings, twin_message=twin.message)
        if target is None and twin.errors == 0:
            target = (tdom, tprob)
    if "reference_plan" in entry:
        if target is None:
            row.update(plan_valid=None, plan_message="no VAL-readable model")
        else:
            verdict = valtools.validate(*target, HERE / str(entry["reference_plan"]))
            row.update(plan_valid=verdict.valid, plan_message=verdict.message,
                       plan_value=verdict.value, checked_on="twin" if target[0] != dom else "real")
    return row


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--only", help="comma-separated family names")
    ap.add_argument("--out", type=Path, default=HERE / "results" / "val_check.jsonl")
    args = ap.parse_args(argv)
    entries = json.loads((HERE / "suite.json").read_text())["problems"]
    if args.only:
        entries = [e for e in entries if e["family"] in set(args.only.split(","))]
    args.out.parent.mkdir(parents=True, exist_ok=True)
    rows = []
    with args.out.open("w") as out:
        for entry in entries:
            row = check(entry)
            rows.append(row)
            out.write(json.dumps(row) + "\n")
            out.flush()
            if row.get("plan_valid") is False or (row["parse_errors"] and "twin_errors" not in row):
                print(f"  {row['problem']}: parse {row['parse_errors']} "
                      f"{row['parse_message']} | plan: {row.get('plan_message')}")
    by_family: dict[str, list[dict[str, object]]] = defaultdict(list)
    for row in rows:
        by_family[str(row["family"])].append(row)
    print("| family | VAL parses (0 errors) | twin parses | reference plans valid for VAL |")
    print("|---|---:|---:|---:|")
    for family, group in by_family.items():
        n = len(group)
        parsed = sum(r["parse_errors"] == 0 for r in group)
        twins = [r for r in group if "twin_errors" in r]
        twin = f"{sum(r['twin_errors'] == 0 for r in twins)}/{len(twins)}" if twins else "-"
        valid = sum(r.get("plan_valid") is True for r in group)
        checked = sum(r.get("plan_valid") is not None for r in group)
        print(f"| {family} | {parsed}/{n} | {twin} | {valid}/{checked} (of {n}) |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
