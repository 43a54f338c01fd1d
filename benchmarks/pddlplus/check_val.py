"""Stock VAL on the benchmark set: Parser on every domain/problem (and VAL twin), Validate on
every reference plan.

Usage (from the repository root):
    .venv/bin/python benchmarks/pddlplus/check_val.py [--only FAMILY,...] [--out FILE]

Writes ``benchmarks/pddlplus/results/val_check.jsonl`` (one row per instance) and prints a
summary per family. A reference plan is checked on the real files where VAL reads them, else on
the VAL twin (``FAMILY/val/``); families without either are reported as not checked by VAL.
Each reference plan is also given to Kairos's validator (``kairos validate``, on the real
files): a second opinion, and the only one where VAL cannot integrate.

``--negatives`` instead checks that VAL and ``kairos validate`` *reject* broken variants of a
reference plan per family: the twins must catch what the real models forbid.
"""

from __future__ import annotations

import argparse
import json
import re
import sys
import tempfile
from collections import defaultdict
from collections.abc import Callable
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
        second = valtools.kairos_validate(dom, prob, HERE / str(entry["reference_plan"]))
        row.update(kairos_valid=second.valid, kairos_message=second.message)
    return row


Lines = list[str]


def _timed(line: str) -> tuple[float, str] | None:
    found = re.match(r"([0-9.]+): (.*)", line)
    return (float(found.group(1)), found.group(2)) if found else None


def _shift(lines: Lines, pick: Callable[[int, str], bool], dt: float) -> Lines:
    out = []
    for i, line in enumerate(lines):
        timed = _timed(line)
        if timed and pick(i, timed[1]):
            line = f"{timed[0] + dt:.6f}: {timed[1]}"
        out.append(line)
    return out


def _first_ramp(lines: Lines, name: str) -> set[int]:
    """Indices of the first run of consecutive ``name`` actions."""
    idx = [i for i, ln in enumerate(lines) if f"({name})" in ln]
    run = [idx[0]]
    for i in idx[1:]:
        if i != run[-1] + 1:
            break
        run.append(i)
    return set(run)


def _drop_cycle(lines: Lines, room: str) -> Lines:
    on = [i for i, ln in enumerate(lines) if f"heater-on {room})" in ln][1]
    off = next(i for i, ln in enumerate(lines) if f"heater-off {room})" in ln and i > on)
    return [ln for i, ln in enumerate(lines) if i not in (on, off)]


def _after_first_brake(lines: Lines) -> Callable[[int, str], bool]:
    first = min(_first_ramp(lines, "decelerate"))
    return lambda i, a: i > first and a in ("(accelerate)", "(stop)")


#: (instance, what breaks, mutation): each broken plan must be rejected by VAL.
NEGATIVES: list[tuple[str, str, Callable[[Lines], Lines]]] = [
    ("car_linear/p05", "final ramp and stop 0.3 s late: the car rolls backwards",
     lambda ls: _shift(ls, _after_first_brake(ls), 0.3)),
    ("car_drag/p06", "final ramp and stop 0.3 s late: the car rolls backwards",
     lambda ls: _shift(ls, _after_first_brake(ls), 0.3)),
    ("car_limit/p10", "cruise ramp-down 0.5 s late: above the speed limit",
     lambda ls: _shift(ls, lambda i, a: i in _first_ramp(ls, "decelerate"), 0.5)),
    ("generator/p04", "refuel t2 started at 5 s: overflow",
     lambda ls: [re.sub(r"^[0-9.]+: (\(refuel gen t2\))", r"5.000000: \1", ln) for ln in ls]),
    ("generator_pplus/p04", "refuel t1 started at 1 s: overflow",
     lambda ls: [re.sub(r"^[0-9.]+: (\(start-refuel gen t1\))", r"1.000000: \1", ln)
                 for ln in ls]),
    ("torricelli/p04", "refuel t1 started at 1 s: overflow",
     lambda ls: [re.sub(r"^[0-9.]+: (\(start-refuel gen t1\))", r"1.000000: \1", ln)
                 for ln in ls]),
    ("convoys/p04", "the first arrival 1 s early: the road is not covered",
     lambda ls: _shift(ls, lambda i, a: i == next(k for k, x in enumerate(ls) if "(arrive" in x),
                       -1.0)),
    ("intercept/p06", "capture 0.5 s late: the target is out of reach",
     lambda ls: _shift(ls, lambda i, a: a == "(capture)", 0.5)),
    ("lander/p08", "touch-down 1 s late: the burn has lifted it above the window",
     lambda ls: _shift(ls, lambda i, a: a == "(touch-down)", 1.0)),
    ("rover/p05", "first charge stopped 10 s early: too little energy for what follows",
     lambda ls: _shift(ls, lambda i, a: i == next(k for k, x in enumerate(ls)
                                                   if "(stow-panels)" in x), -10.0)),
    ("thermostat/p05", "one heating cycle of r1 dropped: r1 gets too cold",
     lambda ls: _drop_cycle(ls, "r1")),
]


def negatives(entries: list[dict[str, object]]) -> int:
    """Check that VAL (real files or twin, where it can) and ``kairos validate`` (real files)
    reject every broken plan of NEGATIVES; returns how many verdicts were not a rejection."""
    by_stem = {str(e["problem"]).removesuffix(".pddl"): e for e in entries}
    missed = 0
    for stem, what, mutate in NEGATIVES:
        entry = by_stem[stem]
        lines = (HERE / str(entry["reference_plan"])).read_text().splitlines()
        with tempfile.NamedTemporaryFile("w", suffix=".plan", delete=False) as handle:
            handle.write("\n".join(mutate(lines)) + "\n")
        plan = Path(handle.name)
        dom, prob = HERE / str(entry["domain"]), HERE / str(entry["problem"])
        checks = [("kairos", valtools.kairos_validate(dom, prob, plan))]
        if entry["reference_check"] == "val":
            checks.insert(0, ("VAL", valtools.validate(dom, prob, plan)))
        elif entry["reference_check"] == "val-twin":
            twin = HERE / str(entry["val_domain"]), HERE / str(entry["val_problem"])
            checks.insert(0, ("VAL twin", valtools.validate(*twin, plan)))
        plan.unlink()
        print(f"{stem}: {what}")
        for tool, verdict in checks:
            ok = verdict.valid is False
            missed += not ok
            print(f"  {tool}: {'rejected' if ok else 'NOT REJECTED'}: {verdict.message[:110]}")
    return missed


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--only", help="comma-separated family names")
    ap.add_argument("--out", type=Path, default=HERE / "results" / "val_check.jsonl")
    ap.add_argument("--negatives", action="store_true",
                    help="check that VAL rejects broken variants of reference plans")
    args = ap.parse_args(argv)
    entries = json.loads((HERE / "suite.json").read_text())["problems"]
    if args.negatives:
        return 1 if negatives(entries) else 0
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
    print("| family | VAL parses (0 errors) | twin parses | reference plans valid for VAL "
          "| valid for `kairos validate` |")
    print("|---|---:|---:|---:|---:|")
    for family, group in by_family.items():
        n = len(group)
        parsed = sum(r["parse_errors"] == 0 for r in group)
        twins = [r for r in group if "twin_errors" in r]
        twin = f"{sum(r['twin_errors'] == 0 for r in twins)}/{len(twins)}" if twins else "-"
        valid = sum(r.get("plan_valid") is True for r in group)
        checked = sum(r.get("plan_valid") is not None for r in group)
        second = sum(r.get("kairos_valid") is True for r in group)
        print(f"| {family} | {parsed}/{n} | {twin} | {valid}/{checked} (of {n}) | {second}/{n} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
