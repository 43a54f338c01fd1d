"""Benchmark: parse + ground the suite's largest (12-link) problems; median of several runs.

Usage: .venv/bin/python benchmarks/pddl_ground.py [--runs 15] [--size 12]
Prints one Markdown table row per model setting (the bar: under 0.5 s for 12-link UACM).
"""

from __future__ import annotations

import argparse
import statistics
import time

from artiplan.encoding import SUITE_MODELS, domain_pddl, make_task, problem_pddl
from artiplan.model import ArticulatedObject
from artiplan.pddl import ground, parse_domain, parse_problem


def measure(domain_text: str, problem_text: str, runs: int) -> tuple[list[float], list[float]]:
    """Per run: (parse seconds, parse + ground seconds)."""
    parse_s, total_s = [], []
    for _ in range(runs):
        t0 = time.perf_counter()
        domain = parse_domain(domain_text, "domain.pddl")
        problem = parse_problem(problem_text, "problem.pddl")
        t1 = time.perf_counter()
        ground(domain, problem)
        t2 = time.perf_counter()
        parse_s.append(t1 - t0)
        total_s.append(t2 - t0)
    return parse_s, total_s


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--runs", type=int, default=15)
    ap.add_argument("--size", type=int, default=12)
    ap.add_argument("--task", type=int, default=1)
    args = ap.parse_args()
    suite_task = make_task(args.size, args.task)
    obj = ArticulatedObject(args.size)
    print("| model | problem | facts | fluents | actions | events | processes | "
          "parse median [s] | parse+ground median [s] | max [s] |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for label, options in SUITE_MODELS:
        dtext = domain_pddl(None, options)
        ptext = problem_pddl(obj, suite_task.initial, suite_task.target, options, "threshold",
                             seed=suite_task.seed, name=suite_task.name)
        parse_s, total_s = measure(dtext, ptext, args.runs)
        st = ground(parse_domain(dtext), parse_problem(ptext)).stats
        print(f"| {label} | {suite_task.name} | {st.facts} | {st.fluents} | {st.actions} | "
              f"{st.events} | {st.processes} | {statistics.median(parse_s):.4f} | "
              f"{statistics.median(total_s):.4f} | {max(total_s):.4f} |")


if __name__ == "__main__":
    main()
