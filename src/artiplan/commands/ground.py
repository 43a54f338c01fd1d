"""``artiplan ground DOMAIN PROBLEM``: ground a PDDL+ problem; counts and time."""

from __future__ import annotations

import argparse
import sys
import time

from artiplan.errors import ExitCode
from artiplan.pddl import ground, load_domain, load_problem


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """Options of ``artiplan ground``."""
    parser.add_argument("domain", help="PDDL+ domain file")
    parser.add_argument("problem", help="PDDL+ problem file")
    parser.add_argument("--list", action="store_true", dest="list_operators",
                        help="print every ground action, event and process")
    parser.add_argument("--facts", action="store_true", dest="list_facts",
                        help="print every fact and numeric fluent (with its initial value)")


def run(args: argparse.Namespace) -> int:
    """Parse and ground; print counts and times (and the operators with ``--list``)."""
    start = time.perf_counter()
    domain = load_domain(args.domain)
    problem = load_problem(args.problem)
    parsed = time.perf_counter()
    task = ground(domain, problem)
    for w in task.warnings:
        print(f"warning: {w}", file=sys.stderr)
    st = task.stats
    print(f"{task.domain_name} / {task.problem_name}")
    print(f"facts {st.facts}, fluents {st.fluents}, actions {st.actions}, events {st.events}, "
          f"processes {st.processes}, pruned {st.pruned}")
    print(f"parse {parsed - start:.4f} s, ground {st.seconds:.4f} s")
    if args.list_operators:
        for title, ops in (("actions", task.actions), ("events", task.events),
                           ("processes", task.processes)):
            print(f"{title}:")
            for op in ops:
                print(f"  {op.signature}")
    if args.list_facts:
        print("facts:")
        for i, name in enumerate(task.facts):
            print(f"  {name}{'  (initially true)' if i in task.init_facts else ''}")
        print("fluents:")
        for name, value in zip(task.fluents, task.init_values, strict=True):
            print(f"  {name} = {'undefined' if value is None else f'{value:g}'}")
    return int(ExitCode.OK)
