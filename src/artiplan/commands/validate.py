"""``artiplan validate DOMAIN PROBLEM PLAN``: validate a plan with VAL's semantics.

Exit 0 valid, 4 invalid (the first reason is printed), 3 bad input.
"""

from __future__ import annotations

import argparse
from pathlib import Path

from artiplan.errors import ExitCode, UsageError


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("domain", type=Path, help="PDDL+ domain file")
    parser.add_argument("problem", type=Path, help="PDDL+ problem file")
    parser.add_argument("plan", type=Path, help="plan file (VAL format; ENHSP -sp files accepted)")
    parser.add_argument(
        "--tolerance",
        type=float,
        default=0.001,
        help="actions closer than this [s] must not interfere (VAL -t; default 0.001)",
    )
    parser.add_argument("--trajectory", type=Path, help="write the trajectory CSV here")
    parser.add_argument(
        "-v", "--verbose", action="store_true", help="print the plan with its events"
    )


def run(args: argparse.Namespace) -> int:
    from artiplan.pddl import load_task
    from artiplan.semantics import validate
    from artiplan.semantics.plan_io import format_plan, read_plan_for, with_events

    if not args.tolerance > 0:
        raise UsageError(f"--tolerance must be positive, got {args.tolerance}")
    task = load_task(args.domain, args.problem)
    plan = read_plan_for(args.plan, [e.name for e in task.events])
    report = validate(task, plan, args.tolerance)
    if args.verbose:
        print(format_plan(with_events(plan, report.events)), end="")
    if args.trajectory is not None and report.trajectory is not None:
        from artiplan.commands.simulate import write_output

        write_output(args.trajectory, report.trajectory.to_csv)
    if report.trajectory is not None and not report.trajectory.exact:
        print(
            "note: some rates are not polynomial: numeric fallback used (RK4, step 0.001 s; "
            "crossing times to 1e-9 s)"
        )
    if report.valid:
        print(f"Plan valid (makespan {plan.makespan:.6f} s, {len(report.events)} events)")
        return int(ExitCode.OK)
    print(report.summary())
    return int(ExitCode.INVALID_PLAN)
