"""``artiplan suite OUTDIR``: write the paper's 240-problem benchmark suite."""

from __future__ import annotations

import argparse

from artiplan.encoding.goals import GOAL_STYLES
from artiplan.errors import UsageError


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("outdir", help="folder to write (created if missing)")
    parser.add_argument("--seed", type=int, default=0, help="suite seed (default 0)")
    parser.add_argument(
        "--goal-style",
        choices=GOAL_STYLES,
        default="threshold",
        help="threshold: the paper's goals (default); window: +-5 deg of the target",
    )


def run(args: argparse.Namespace) -> int:
    from artiplan.encoding.suite import SUITE_MODELS, write_suite

    if args.seed < 0:
        raise UsageError("--seed must be >= 0")
    written = write_suite(args.outdir, seed=args.seed, goal_style=args.goal_style)
    problems = sum(1 for p in written if p.name.startswith("p"))
    print(
        f"wrote {problems} problems and {len(SUITE_MODELS)} domains to {args.outdir} "
        f"(seed {args.seed}, {args.goal_style} goals); index: {written[-1]}"
    )
    return 0
