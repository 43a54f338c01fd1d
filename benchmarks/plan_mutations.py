"""Mutated plans for differential validation: small, labelled changes of a valid plan.

A library (``mutations(plan, rng)``) and a command that writes them next to a plan file:

    .venv/bin/python benchmarks/plan_mutations.py PLAN [--seed 0] [-o DIR]

Kinds (each label says what changed; times are kept >= 0 and at 6 decimals):

* ``shift{+-d}@i``: action i moved by d in {0.001, 0.01, 0.1, 0.5} s, both ways (one random
  action per delta and sign; the last action is always among those shifted, since it is where
  the goal is checked);
* ``drop@i``: action i removed (every action; the first, last and a random one for long plans);
* ``dup@i`` / ``dup+eps@i``: action i repeated at the same time / 0.001 s later;
* ``swap@i``: actions i and i+1 exchange their times (order changes);
* ``cut@k``: only the first k actions kept (k = 0 .. n-1; at most 4 of them).

Events predicted in the plan are dropped (validators recompute them). Used by
``benchmarks/up_validator_agreement.py``; meant to be reused for a differential benchmark
against VAL.
"""

from __future__ import annotations

import argparse
import random
from dataclasses import replace
from pathlib import Path

from artiplan.semantics.plan import Plan, TimedAction
from artiplan.semantics.plan_io import format_plan, read_plan

DELTAS = (0.001, 0.01, 0.1, 0.5)
#: Drops, duplicates and swaps per plan at most (first, last and random ones beyond that).
MAX_PER_KIND = 4


def _plan(actions: list[TimedAction]) -> Plan:
    return Plan(tuple(sorted(actions, key=lambda a: a.time)))


def _at(a: TimedAction, t: float) -> TimedAction:
    return replace(a, time=round(max(0.0, t), 6))


def _positions(n: int, rng: random.Random) -> list[int]:
    """Indices to mutate: all of them for short plans, else first, last and random ones."""
    if n <= MAX_PER_KIND:
        return list(range(n))
    middle = rng.sample(range(1, n - 1), min(MAX_PER_KIND - 2, n - 2))
    return sorted({0, n - 1, *middle})


def mutations(plan: Plan, rng: random.Random) -> list[tuple[str, Plan]]:
    """Labelled mutants of ``plan`` (deterministic for a given ``rng`` state)."""
    acts = sorted(plan.actions, key=lambda a: a.time)
    n = len(acts)
    out: list[tuple[str, Plan]] = []
    for d in DELTAS:
        for sign in (1, -1):
            picks = {n - 1, rng.randrange(n)} if n else set()
            for i in sorted(picks):
                moved = [_at(a, a.time + sign * d) if k == i else a for k, a in enumerate(acts)]
                out.append((f"shift{sign * d:+g}@{i}", _plan(moved)))
    for i in _positions(n, rng):
        out.append((f"drop@{i}", _plan(acts[:i] + acts[i + 1:])))
        out.append((f"dup@{i}", _plan([*acts, acts[i]])))
        out.append((f"dup+eps@{i}", _plan([*acts, _at(acts[i], acts[i].time + 0.001)])))
    for i in _positions(n - 1, rng) if n > 1 else []:
        swapped = list(acts)
        swapped[i], swapped[i + 1] = (_at(acts[i], acts[i + 1].time),
                                      _at(acts[i + 1], acts[i].time))
        out.append((f"swap@{i}", _plan(swapped)))
    cuts = list(range(n)) if n <= MAX_PER_KIND else sorted({0, n - 1, *rng.sample(range(n), 2)})
    for k in cuts:
        out.append((f"cut@{k}", _plan(acts[:k])))
    return out


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("plan", type=Path)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("-o", "--out", type=Path, default=None,
                    help="folder for the mutants (default: next to the plan)")
    args = ap.parse_args(argv)
    out = args.out or args.plan.parent / f"{args.plan.stem}-mutants"
    out.mkdir(parents=True, exist_ok=True)
    plan = read_plan(args.plan)
    for label, mutant in mutations(plan, random.Random(args.seed)):
        (out / f"{label}.plan").write_text(format_plan(mutant, events=False))
    print(f"wrote {len(list(out.glob('*.plan')))} mutants to {out}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
