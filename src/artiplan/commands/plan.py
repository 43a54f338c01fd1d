"""``artiplan plan DOMAIN PROBLEM``: plan with artiplan's exact-time PDDL+ planner.

Prints the plan in VAL's format with the predicted events as ``; t: (event)`` lines (the paper's
Fig. 6 style) on stdout; progress and statistics go to stderr. ``-o`` writes the plan file.
Exit codes: 0 solved, 5 proven unsolvable, 6 no plan found, 7 time limit, 8 memory limit,
3 bad input, 9 ``--planner enhsp|kairos`` unavailable, 1 internal error (a plan the validator
rejects is one: it is never printed as solved). A peer's plan (``--planner enhsp|kairos``) is
judged by artiplan's validator like any other: an invalid one is still printed and written,
marked by a first comment line, and the exit code is 4 with the reason on stderr.
"""

from __future__ import annotations

import sys

from artiplan.commands import FilePath
from artiplan.errors import ExitCode, UsageError

TYPE_CHECKING = False  # read as true by mypy; typing is not imported at run time (start-up)
if TYPE_CHECKING:
    import argparse
    from collections.abc import Mapping
    from typing import Any

PLANNERS = ("artiplan", "enhsp", "kairos")


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("domain", type=FilePath, help="PDDL+ domain file")
    parser.add_argument("problem", type=FilePath, help="PDDL+ problem file")
    parser.add_argument("-o", "--out", type=FilePath, help="write the plan (VAL format) here")
    parser.add_argument("--time-limit", type=float, help="wall and CPU limit [s]")
    parser.add_argument("--memory-limit", type=float, help="memory limit [MB]")
    parser.add_argument("--trajectory", type=FilePath, help="write the trajectory CSV here")
    parser.add_argument("--stats", type=FilePath, help="write the statistics (JSON) here")
    parser.add_argument("--planner", default="artiplan", choices=PLANNERS,
                        help="artiplan (default), or an external baseline")
    parser.add_argument("--epsilon", type=float, default=0.001,
                        help="separation of successive actions [s] (default 0.001)")
    parser.add_argument("--time-weight", type=float, default=0.1,
                        help="heuristic cost of one second of plan, in actions (default 0.1)")
    parser.add_argument("-q", "--quiet", action="store_true", help="no progress lines on stderr")


def _check(args: argparse.Namespace) -> None:
    for name in ("time_limit", "memory_limit"):
        v = getattr(args, name)
        if v is not None and not v > 0:
            raise UsageError(f"--{name.replace('_', '-')} must be positive, got {v}")
    if not args.epsilon > 0:
        raise UsageError(f"--epsilon must be positive, got {args.epsilon}")


def _cap_address_space(limit_mb: float) -> None:
    """Hard stop for runaway memory: the current address space plus the limit (plus slack)."""
    import resource  # here: only with --memory-limit

    try:
        with open("/proc/self/status") as fh:
            vm = next(int(line.split()[1]) for line in fh if line.startswith("VmSize:"))
        cap = vm * 1024 + int(limit_mb * 1.25 * 2**20) + 256 * 2**20
        soft, hard = resource.getrlimit(resource.RLIMIT_AS)
        if hard == resource.RLIM_INFINITY or cap < hard:
            resource.setrlimit(resource.RLIMIT_AS, (cap, hard))
    except (OSError, ValueError, StopIteration):  # not Linux: the RSS check still applies
        pass


def run(args: argparse.Namespace) -> int:
    _check(args)
    if args.planner != "artiplan":
        return _external(args)
    from artiplan.search.api import PlanStatus, plan
    from artiplan.semantics.plan_io import format_plan, write_plan

    if args.memory_limit is not None:
        _cap_address_space(args.memory_limit)
    if not args.quiet:
        print(f"artiplan plan: {args.problem} ({args.domain})", file=sys.stderr)
    # The limit is the process's: Python's start-up and the imports count too.
    limit = None if args.time_limit is None else max(0.0, args.time_limit - _since_start(args))
    result = plan(args.domain, args.problem, time_limit=limit,
                  memory_limit=args.memory_limit, epsilon=args.epsilon,
                  time_weight=args.time_weight, on_progress=None if args.quiet else _alive)
    if result.status is PlanStatus.TIMEOUT and args.time_limit is not None:
        result.message = (f"time limit of {args.time_limit:g} s reached (process wall "
                          f"{_since_start(args):.2f} s)")
    if args.stats is not None:
        _write_stats(args.stats, result.status.value, result.message, result.stats)
    if not args.quiet:
        _progress(result.status.value, result.stats, result.message)
    margins = result.stats.get("margins") or {}
    if margins and not margins.get("ok", True):
        print(f"artiplan plan: warning: small margin: {margins.get('note')} (validators may "
              "disagree on this plan)", file=sys.stderr)
    if margins and margins.get("coincident"):
        times = ", ".join(f"{t:g}" for t in margins["coincident"][:3])
        print(f"artiplan plan: warning: two objects' events coincide at t = {times} s (stock "
              "VAL often rejects such an instant: benchmarks/results/semantics.md)",
              file=sys.stderr)
    if result.stats.get("initial_events"):
        print("artiplan plan: warning: events are enabled in the initial state ("
              + ", ".join(result.stats["initial_events"][:3]) + "): they fire at time 0, but "
              "VAL refuses such a problem whatever the plan", file=sys.stderr)
    if result.status is PlanStatus.SOLVED:
        assert result.plan is not None
        print(format_plan(result.plan), end="")
        if args.out is not None:
            write_plan(result.plan, args.out)
        if args.trajectory is not None and result.trajectory is not None:
            result.trajectory.to_csv(args.trajectory)
        return int(ExitCode.OK)
    print(f"artiplan plan: {result.status.value}: {result.message}", file=sys.stderr)
    return int(result.status.exit_code)


def _since_start(args: argparse.Namespace) -> float:
    """Wall seconds since the command started (the process's start-up included when it is
    the entry point: see ``artiplan.cli``)."""
    import time

    return max(0.0, time.time() - getattr(args, "started_at", time.time()))


def _alive(elapsed: float, stats: Mapping[str, Any]) -> None:
    """A progress line of a long search (every few seconds)."""
    keys = ("attempts", "expanded", "generated", "duplicates", "events")
    parts = " ".join(f"{k}={int(stats[k])}" for k in keys if k in stats)
    print(f"artiplan plan: {elapsed:.0f} s {parts}", file=sys.stderr, flush=True)


def _progress(status: str, stats: Mapping[str, Any], message: str) -> None:
    keys = ("expanded", "generated", "evaluated", "plan_length", "makespan", "search_s",
            "heuristic_s", "total_s")
    parts = [f"{k}={stats[k]:.4g}" if isinstance(stats[k], float) else f"{k}={stats[k]}"
             for k in keys if k in stats]
    print(f"artiplan plan: {status} " + " ".join(parts), file=sys.stderr)


def _write_stats(path: str, status: str, message: str, stats: Mapping[str, Any]) -> None:
    import json

    doc = {"schema": 1, "status": status, "message": message,
           **{k: v for k, v in stats.items()
              if isinstance(v, (int, float, str, bool, list, dict))}}
    with open(path, "w") as fh:
        fh.write(json.dumps(doc, indent=2, sort_keys=True) + "\n")


def _external(args: argparse.Namespace) -> int:
    """Run a baseline planner through ``artiplan.backends`` and print its plan."""
    try:
        from artiplan.backends import get_planner
    except ImportError:
        print(f"artiplan plan: --planner {args.planner} needs artiplan.backends, which is not "
              "available in this installation", file=sys.stderr)
        return int(ExitCode.EXTERNAL_TOOL)
    planner = get_planner(args.planner)
    res = planner.solve(args.domain, args.problem, time_limit=args.time_limit,
                        memory_limit=args.memory_limit)
    status = getattr(res.status, "value", str(res.status))
    if args.stats is not None:
        _write_stats(args.stats, status, res.message,
                     {"cpu_s": res.cpu_s, "wall_s": res.wall_s, "peak_mb": res.peak_mb})
    print(f"artiplan plan: {args.planner}: {status} (wall {res.wall_s:.2f} s)", file=sys.stderr)
    if res.plan is not None and status == "solved":
        from artiplan.backends.convert import close_at_end
        from artiplan.pddl import load_task
        from artiplan.semantics import validate
        from artiplan.semantics.plan_io import format_plan

        task = load_task(args.domain, args.problem)
        plan = close_at_end(res.plan, task)
        report = validate(task, plan)
        text = format_plan(plan)
        if not report.valid:
            print(f"artiplan plan: {args.planner}'s plan is INVALID: {report.reason}",
                  file=sys.stderr)
            text = f"; INVALID (artiplan validate): {report.reason}\n" + text
        print(text, end="")
        if args.out is not None:
            with open(args.out, "w") as fh:
                fh.write(text)
        return int(ExitCode.OK if report.valid else ExitCode.INVALID_PLAN)
    from artiplan.search.api import PlanStatus

    try:
        return int(PlanStatus(status).exit_code)
    except ValueError:
        return int(ExitCode.EXTERNAL_TOOL)
