"""Differential benchmark: artiplan's validator against stock VAL on thousands of plans.

Plans: artiplan's on every suite problem, ENHSP's and Kairos's (the rows of an
``artiplan bench`` run), and mutations of each: one action's time shifted by +-0.001 .. 0.5 s,
the tail of the plan shifted, an action dropped, duplicated, two neighbours swapped, the plan
cut short. Every plan is written once in VAL's format; both validators read that same text
(``Validate -t 0.001`` under a CPU and memory limit; ``artiplan.semantics.validate``).

Rows go to a JSON Lines file as they are judged (a killed run resumes where it stopped); the
summary (agreement, confusion, disagreement classes with a smallest example each) goes to
stdout and ``--summary``.

    python benchmarks/semantics_val.py SUITE_DIR --peers peers.jsonl -o semantics-val.jsonl \\
        --summary benchmarks/results/semantics-val-summary.md
"""

from __future__ import annotations

import argparse
import dataclasses
import hashlib
import json
import random
import sys
import tempfile
import time
from collections import Counter, defaultdict
from collections.abc import Iterator
from pathlib import Path
from typing import Any

from artiplan import plan as artiplan_plan
from artiplan.backends.convert import close_at_end
from artiplan.backends.val import validate_with_val
from artiplan.bench.results import read_rows
from artiplan.bench.suite import load_suite
from artiplan.pddl import load_task
from artiplan.semantics import validate
from artiplan.semantics.plan import Plan
from artiplan.semantics.plan_io import format_plan, parse_plan

SHIFTS = (0.001, 0.005, 0.02, 0.1, 0.5)


def mutations(plan: Plan, key: str) -> Iterator[tuple[str, Plan]]:
    """Deterministic mutations of ``plan`` (seeded by ``key``)."""
    rng = random.Random(hashlib.sha256(key.encode()).hexdigest())
    acts = list(plan.actions)
    n = len(acts)
    if n == 0:
        return

    def mk(new: list[Any]) -> Plan:
        return Plan(tuple(sorted(new, key=lambda a: a.time)), (), None)

    for _ in range(2):
        k, d = rng.randrange(n), rng.choice(SHIFTS) * rng.choice((-1, 1))
        moved = [dataclasses.replace(a, time=round(max(0.0, a.time + d), 6)) if i == k else a
                 for i, a in enumerate(acts)]
        yield f"shift a{k} {d:+g}", mk(moved)
    k, d = rng.randrange(n), rng.choice(SHIFTS) * rng.choice((-1, 1))
    tail = [dataclasses.replace(a, time=round(max(0.0, a.time + d), 6)) if i >= k else a
            for i, a in enumerate(acts)]
    yield f"shift tail a{k}.. {d:+g}", mk(tail)
    k = rng.randrange(n)
    yield f"drop a{k}", mk(acts[:k] + acts[k + 1:])
    k = rng.randrange(n)
    yield f"duplicate a{k}", mk(acts[:k + 1] + [acts[k]] + acts[k + 1:])
    if n >= 2:
        k = rng.randrange(n - 1)
        a, b = acts[k], acts[k + 1]
        swapped = acts[:k] + [dataclasses.replace(a, time=b.time),
                              dataclasses.replace(b, time=a.time)] + acts[k + 2:]
        yield f"swap a{k} a{k + 1}", mk(swapped)
        cut = rng.randrange(1, min(3, n) + 1) if n > 1 else 1
        yield f"cut {cut}", mk(acts[:-cut])


def base_plans(suite: Path, peers: Path | None, time_limit: float) -> Iterator[dict[str, Any]]:
    """(source, problem, domain, plan text) of every base plan."""
    problems = load_suite(suite)
    for p in problems:
        result = artiplan_plan(p.domain, p.problem, time_limit=time_limit)
        if result.plan is not None:
            yield {"source": "artiplan", "problem": p.problem, "domain": p.domain,
                   "problem_id": p.problem_id, "plan": format_plan(result.plan, events=False)}
    if peers is None:
        return
    for row in read_rows(peers):
        if row.get("planner") in ("enhsp", "kairos", "enhsp-delta0.1") and row.get("plan"):
            task = load_task(row["domain"], row["problem"])
            closed = close_at_end(parse_plan(row["plan"], "<peer>"), task)
            yield {"source": row["planner"], "problem": row["problem"], "domain": row["domain"],
                   "problem_id": row["problem_id"], "plan": format_plan(closed, events=False)}


def judge_ours(domain: str, problem: str, text: str) -> dict[str, Any]:
    """Our validator's verdict on one plan text."""
    task = load_task(domain, problem)
    t = time.perf_counter()
    try:
        ours = validate(task, parse_plan(text, "<mutant>"))
        mine = {"ours": ours.valid, "ours_kind": ours.kind, "ours_reason": ours.reason[:300]}
    except Exception as exc:  # a crash of ours is a finding, not a verdict
        mine = {"ours": None, "ours_kind": "crash", "ours_reason": f"{type(exc).__name__}: {exc}"}
    return {**mine, "ours_s": round(time.perf_counter() - t, 4)}


def rejudge(src: Path, out: Path) -> None:
    """Our validator again on every row of ``src`` (VAL's verdict on the same text does not
    depend on our code, so it is kept): the agreement of today's validator, rows to ``out``."""
    rows = read_rows_any(src)
    with out.open("w") as fh:
        for k, row in enumerate(rows, 1):
            row = {**row, **judge_ours(row["domain"], row["problem"], row["plan"])}
            fh.write(json.dumps(row) + "\n")
            if k % 250 == 0:
                print(f"{k}/{len(rows)} plans re-judged", file=sys.stderr, flush=True)


def rejudge_both(src: Path, out: Path, suite: Path, val_limit: float) -> None:
    """Both validators again on every row of ``src``, with the domains and problems of
    ``suite`` (today's encodings; the same problem ids): rows to ``out``, resumable."""
    rows = read_rows_any(src)
    done = {(r["source"], r["problem_id"], r["mutation"]) for r in read_rows_any(out)}
    with out.open("a") as fh:
        for k, row in enumerate(rows, 1):
            if (row["source"], row["problem_id"], row["mutation"]) in done:
                continue
            old_domain, old_problem = Path(row["domain"]), Path(row["problem"])
            model = old_domain.parent.name
            domain = suite / model / "domain.pddl"
            problem = suite / model / old_problem.name
            row = {**row, "domain": str(domain), "problem": str(problem),
                   **judge(str(domain), str(problem), row["plan"], val_limit)}
            fh.write(json.dumps(row) + "\n")
            fh.flush()
            if k % 250 == 0:
                print(f"{k}/{len(rows)} plans judged again", file=sys.stderr, flush=True)


def judge(domain: str, problem: str, text: str, val_limit: float) -> dict[str, Any]:
    """Both verdicts on one plan text."""
    mine = judge_ours(domain, problem, text)
    with tempfile.NamedTemporaryFile("w", suffix=".plan") as fh:
        fh.write(text)
        fh.flush()
        val = validate_with_val(domain, problem, fh.name, time_limit=val_limit,
                                memory_limit=2048)
    return {**mine, "val": val.verdict, "val_reason": val.reason[:300],
            "val_cpu_s": round(val.cpu_s, 4)}


def run(args: argparse.Namespace) -> None:
    out = Path(args.out)
    done = {(r["source"], r["problem"], r["mutation"]) for r in read_rows_any(out)}
    with out.open("a") as fh:
        for base in base_plans(Path(args.suite), Path(args.peers) if args.peers else None,
                               args.time_limit):
            plan = parse_plan(base["plan"], "<base>")
            key = f"{base['source']}|{base['problem']}"
            variants = [("original", plan), *mutations(plan, key)]
            for name, mutant in variants:
                if (base["source"], base["problem"], name) in done:
                    continue
                text = format_plan(mutant, events=False)
                row = {"schema": "artiplan-semantics-val/1", "source": base["source"],
                       "problem": base["problem"], "problem_id": base["problem_id"],
                       "domain": base["domain"], "mutation": name, "plan": text,
                       **judge(base["domain"], base["problem"], text, args.val_time_limit)}
                fh.write(json.dumps(row) + "\n")
                fh.flush()
                done.add((base["source"], base["problem"], name))
            print(f"{len(done)} plans judged ({base['source']} {base['problem_id']})",
                  file=sys.stderr, flush=True)


def read_rows_any(path: Path) -> list[dict[str, Any]]:
    if not path.is_file():
        return []
    rows = []
    for line in path.read_text().splitlines():
        try:
            rows.append(json.loads(line))
        except json.JSONDecodeError:
            continue  # a line cut by a kill
    return rows


def classify(row: dict[str, Any]) -> str:
    """A short name of the disagreement (or agreement) class."""
    if row["val"] not in ("valid", "invalid"):
        return f"VAL {row['val']}"
    if row["ours"] is None:
        return "ours crashed"
    if row["ours"] == (row["val"] == "valid"):
        return "agree"
    side = "ours valid, VAL invalid" if row["ours"] else "ours invalid, VAL valid"
    reason = row["val_reason"] if row["ours"] else f"{row['ours_kind']}: {row['ours_reason']}"
    for word in ("twice", "initial state", "goal", "precondition", "mutex", "Bad plan",
                 "bad-operator", "event", "error"):
        if word.lower() in reason.lower():
            return f"{side} ({word})"
    return f"{side} (other)"


def summarise(rows: list[dict[str, Any]]) -> str:
    decided = [r for r in rows if r["val"] in ("valid", "invalid") and r["ours"] is not None]
    agree = sum(classify(r) == "agree" for r in decided)
    lines = [f"plans judged: {len(rows)}; both decided: {len(decided)}; agree: {agree} "
             f"({100.0 * agree / max(1, len(decided)):.2f}%); over all plans: "
             f"{100.0 * agree / max(1, len(rows)):.2f}%", ""]
    by_source: dict[str, Counter[str]] = defaultdict(Counter)
    for r in rows:
        by_source[r["source"]][classify(r)] += 1
        by_source[r["source"]]["n"] += 1
    lines.append("| source | plans | agree | classes |")
    lines.append("|---|---:|---:|---|")
    for source, c in sorted(by_source.items()):
        classes = ", ".join(f"{k}: {v}" for k, v in c.most_common() if k not in ("n", "agree"))
        lines.append(f"| {source} | {c['n']} | {c['agree']} | {classes} |")
    lines += ["", "| verdicts (ours / VAL) | plans |", "|---|---:|"]
    confusion = Counter((r["ours"], r["val"]) for r in rows)
    for (o, v), n in sorted(confusion.items(), key=lambda kv: -kv[1]):
        lines.append(f"| {o} / {v} | {n} |")
    classes: dict[str, list[dict[str, Any]]] = defaultdict(list)
    for r in rows:
        c = classify(r)
        if c != "agree":
            classes[c].append(r)
    for name, members in sorted(classes.items(), key=lambda kv: -len(kv[1])):
        smallest = min(members, key=lambda r: (r["plan"].count("\n"), len(r["plan"])))
        lines += ["", f"### {name}: {len(members)}", "",
                  f"smallest: {smallest['source']} {smallest['problem_id']} "
                  f"({smallest['mutation']})", "", "```", smallest["plan"].rstrip(), "```",
                  f"ours: {smallest['ours_kind']} {smallest['ours_reason']}",
                  f"VAL: {smallest['val']} {smallest['val_reason']}"]
    return "\n".join(lines) + "\n"


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("suite", help="suite folder (artiplan suite)")
    ap.add_argument("--peers", help="artiplan bench results with ENHSP/Kairos plans (JSONL)")
    ap.add_argument("-o", "--out", default="semantics-val.jsonl")
    ap.add_argument("--summary", help="also write the summary (Markdown) here")
    ap.add_argument("--time-limit", type=float, default=60.0, help="artiplan's limit [s]")
    ap.add_argument("--val-time-limit", type=float, default=20.0, help="VAL's CPU limit [s]")
    ap.add_argument("--only-summary", action="store_true", help="summarise the rows, no runs")
    ap.add_argument("--rejudge", metavar="ROWS",
                    help="re-run only our validator on the rows of this file (VAL's verdicts "
                    "kept) and write them to --out")
    ap.add_argument("--rejudge-both", metavar="ROWS",
                    help="re-run both validators on the plan texts of this file, with the "
                    "domains and problems of SUITE (today's encodings), rows to --out")
    args = ap.parse_args()
    if args.rejudge_both:
        rejudge_both(Path(args.rejudge_both), Path(args.out), Path(args.suite),
                     args.val_time_limit)
    elif args.rejudge:
        rejudge(Path(args.rejudge), Path(args.out))
    elif not args.only_summary:
        run(args)
    text = summarise(read_rows_any(Path(args.out)))
    print(text)
    if args.summary:
        Path(args.summary).write_text(text)


if __name__ == "__main__":
    main()
