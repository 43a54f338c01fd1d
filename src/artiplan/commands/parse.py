"""``artiplan parse DOMAIN [PROBLEM]``: check PDDL+ files, report warnings, print them back."""

from __future__ import annotations

import argparse
import sys

from artiplan.errors import ExitCode
from artiplan.pddl import check_problem, load_domain, load_problem, write_domain, write_problem


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """Options of ``artiplan parse``."""
    parser.add_argument("domain", help="PDDL+ domain file")
    parser.add_argument("problem", nargs="?", help="PDDL+ problem file (checked against DOMAIN)")
    parser.add_argument("--print", action="store_true", dest="print_back",
                        help="print the parsed files back as PDDL on stdout")


def run(args: argparse.Namespace) -> int:
    """Check the files; print a summary or (``--print``) the files back."""
    domain = load_domain(args.domain)
    warnings = list(domain.warnings)
    problem = None
    if args.problem is not None:
        problem = load_problem(args.problem)
        warnings += check_problem(domain, problem)
    for w in warnings:
        print(f"warning: {w}", file=sys.stderr)
    if args.print_back:
        sys.stdout.write(write_domain(domain))
        if problem is not None:
            sys.stdout.write("\n" + write_problem(problem))
        return int(ExitCode.OK)
    kinds = [sum(op.kind == k for op in domain.operators)
             for k in ("action", "process", "event", "durative-action")]
    print(f"domain {domain.name}: {len(domain.types)} types, {len(domain.predicates)} "
          f"predicates, {len(domain.functions)} functions, {kinds[0]} actions, {kinds[1]} "
          f"processes, {kinds[2]} events" + (f", {kinds[3]} durative actions" if kinds[3] else ""))
    if problem is not None:
        print(f"problem {problem.name}: {len(problem.objects)} objects, {len(problem.init)} "
              f"initial facts and values, goal {'given' if problem.goal else 'missing'}")
    print(f"ok ({len(warnings)} warning{'s' if len(warnings) != 1 else ''})")
    return int(ExitCode.OK)
