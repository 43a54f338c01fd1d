"""``artiplan simulate DOMAIN PROBLEM PLAN``: the plan with its events, a trajectory CSV and a
plot of the angles over time (happenings marked)."""

from __future__ import annotations

import argparse
from collections.abc import Callable
from pathlib import Path

from artiplan.errors import ExitCode, UsageError


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("domain", type=Path, help="PDDL+ domain file")
    parser.add_argument("problem", type=Path, help="PDDL+ problem file")
    parser.add_argument("plan", type=Path, help="plan file (VAL format; ENHSP -sp files accepted)")
    parser.add_argument("--plot", type=Path, help="write a PNG of the fluents over time")
    parser.add_argument("--trajectory", type=Path, help="write the trajectory CSV here")
    parser.add_argument("--sample", type=float, help="also sample every DT seconds (CSV rows)")
    parser.add_argument(
        "--extend",
        type=float,
        default=0.0,
        help="keep simulating this many seconds after the plan's end (a prediction)",
    )


def write_output(path: Path, write: Callable[[Path], None]) -> None:
    """``write(path)``, creating missing folders; an unwritable path is a usage error."""
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        write(path)
    except OSError as exc:
        raise UsageError(f"cannot write {str(path)!r}: {exc.strerror or exc}") from None


def run(args: argparse.Namespace) -> int:
    from artiplan.pddl import load_task
    from artiplan.semantics import simulate
    from artiplan.semantics.plan_io import format_plan, read_plan_for, with_events

    if args.sample is not None and not args.sample > 0:
        raise UsageError(f"--sample must be positive, got {args.sample}")
    if not args.extend >= 0:
        raise UsageError(f"--extend must not be negative, got {args.extend}")
    task = load_task(args.domain, args.problem)
    plan = read_plan_for(args.plan, [e.name for e in task.events])
    traj = simulate(task, plan, sample_dt=args.sample, extend=args.extend)
    print(format_plan(with_events(plan, traj.events)), end="")
    if not traj.exact:
        print("; note: some rates are not polynomial: numeric fallback used (RK4, step 0.001 s)")
    if args.trajectory is not None:
        write_output(args.trajectory, traj.to_csv)
        print(f"wrote {args.trajectory}")
    if args.plot is not None:
        from artiplan.viz.trajectory import plot_trajectory

        title = f"{task.domain_name} / {task.problem_name}"
        write_output(args.plot, lambda path: plot_trajectory(traj, path, title=title))
        print(f"wrote {args.plot}")
    return int(ExitCode.OK)
