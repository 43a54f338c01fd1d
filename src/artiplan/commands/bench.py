"""``artiplan bench SUITE_DIR``: run planners on a suite; one JSON line per run; resumable.

Example: ``artiplan bench suite/ --planners artiplan,enhsp,kairos --time-limit 60 --jobs 2
--out results.jsonl``. Killed and restarted with the same ``--out``, it runs only what is missing.
"""

from __future__ import annotations

import argparse
import os
import sys

from artiplan.errors import ExitCode, UsageError


def _names(text: str) -> list[str]:
    return [item.strip() for item in text.split(",") if item.strip()]


def _sizes(text: str) -> list[int]:
    try:
        return [int(item) for item in _names(text)]
    except ValueError:
        raise argparse.ArgumentTypeError(f"sizes must be integers, got {text!r}") from None


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("suite_dir", metavar="SUITE_DIR", help="folder with suite.json")
    parser.add_argument(
        "--planners", default="artiplan,enhsp,kairos", type=_names,
        help="comma-separated: artiplan, enhsp, enhsp-delta0.1, kairos (default: %(default)s)",
    )
    parser.add_argument("--time-limit", type=float, default=300.0,
                        help="CPU-time limit per run [s] (default: %(default)s, the paper's)")
    parser.add_argument("--memory-limit", type=float, default=8192.0,
                        help="memory limit per run [MiB] (default: %(default)s, the paper's)")
    parser.add_argument("--jobs", "-j", type=int, default=1,
                        help="runs at once on this machine (default: %(default)s)")
    parser.add_argument("-o", "--out", default="results.jsonl",
                        help="JSON Lines results file, appended to (default: %(default)s)")
    parser.add_argument("--scheduler", metavar="tcp://HOST:PORT",
                        help="run the jobs on this Dask distributed scheduler instead")
    parser.add_argument("--models", type=_names,
                        help="only these models or variants, e.g. ng,ucm-0.1,uacm")
    parser.add_argument("--sizes", type=_sizes, help="only these sizes, e.g. 3,4,5")
    parser.add_argument("--check-tools", action="store_true",
                        help="fail at once (exit 9) if a planner's program is missing")
    parser.add_argument("--no-val", action="store_true",
                        help="do not ask stock VAL about the plans (default: ask when installed)")


def run(args: argparse.Namespace) -> int:
    from artiplan.backends import get_planner
    from artiplan.bench.jobs import Job
    from artiplan.bench.run import RunConfig, run_jobs
    from artiplan.bench.suite import load_suite, on_disk, select

    if args.time_limit <= 0 or args.memory_limit <= 0 or args.jobs < 1:
        raise UsageError("--time-limit, --memory-limit and --jobs must be positive")
    planners = [get_planner(name) for name in args.planners]  # unknown names: exit 2
    if args.check_tools:
        for planner in planners:
            planner.check_available()
    problems = select(on_disk(load_suite(args.suite_dir), args.suite_dir), args.models,
                      args.sizes)
    if not problems:
        raise UsageError("no problem of the suite matches --models/--sizes")
    # Problem-major order: every planner meets each problem before the next one, so a partial
    # run compares planners on the same problems.
    jobs = [
        Job(p.name, problem, args.time_limit, args.memory_limit, val=not args.no_val)
        for problem in problems for p in planners
    ]
    try:
        written = run_jobs(jobs, args.out, RunConfig(jobs=args.jobs, scheduler=args.scheduler))
    except KeyboardInterrupt:
        # Every finished run is already on disk. Exit at once: the worker threads die with the
        # process and take their planners with them (parent-death signal), instead of waiting
        # for the running planners to reach their limits.
        print(f"\nartiplan bench: interrupted; rerun the same command to resume ({args.out})",
              file=sys.stderr, flush=True)
        os._exit(130)
    print(f"artiplan bench: {written} new runs written to {args.out}", file=sys.stderr)
    return int(ExitCode.OK)
