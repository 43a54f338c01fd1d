"""``artiplan generate``: one PDDL+ domain and problem, from options or JSON configurations."""

from __future__ import annotations

import argparse
import random
from pathlib import Path

from artiplan.encoding.goals import GOAL_STYLES
from artiplan.encoding.options import MODELS
from artiplan.errors import InputError, UsageError
from artiplan.model import ArticulatedObject, load_configuration


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--links", type=int, default=4, help="number of links (default 4)")
    parser.add_argument("--model", choices=MODELS, default="ng", help="gravity model")
    parser.add_argument("--speed-g", type=float, default=0.1, help="UCM gravity speed [deg/s]")
    parser.add_argument(
        "--acceleration", type=float, default=0.1, help="UACM gravity acceleration [deg/s^2]"
    )
    parser.add_argument("--speed", type=float, default=10.0, help="robot speed [deg/s]")
    parser.add_argument(
        "--reach-time",
        type=float,
        default=None,
        help="seconds the arms need between a release and the next grasp (default: none)",
    )
    parser.add_argument("--carry", choices=("rigid", "projected"), default="rigid",
                        help="how vertical turns move carried links: rigid (the paper, "
                             "default) or projected (docs/encodings.md)")
    parser.add_argument("--seed", type=int, default=0, help="seed of random configurations")
    parser.add_argument("--goal-style", choices=GOAL_STYLES, default="threshold")
    parser.add_argument("--init", type=Path, help="initial configuration (JSON)")
    parser.add_argument("--target", type=Path, help="target configuration (JSON)")
    parser.add_argument("--name", help="problem name (default p<links>)")
    parser.add_argument(
        "-o", "--out", type=Path, default=Path("."), help="output folder (default: .)"
    )


def run(args: argparse.Namespace) -> int:
    from artiplan.encoding import EncodingOptions, domain_pddl, problem_pddl
    from artiplan.encoding.suite import random_pair

    if (args.init is None) != (args.target is None):
        raise UsageError("give both --init and --target, or neither")
    try:
        options = EncodingOptions(
            args.model,
            speed_i=args.speed,
            speed_d=args.speed,
            speed_g=args.speed_g,
            acceleration=args.acceleration,
            reach_time=args.reach_time,
            carry=args.carry,
        )
    except ValueError as exc:
        raise UsageError(str(exc)) from None
    if args.init is not None:
        init, obj = load_configuration(args.init)
        target, tobj = load_configuration(args.target)
        if tobj.n_links != obj.n_links:
            raise InputError(f"{args.target}: {tobj.n_links} links, {args.init}: {obj.n_links}")
    else:
        if args.links < 2:
            raise UsageError("--links must be at least 2")
        obj = ArticulatedObject(args.links)
        init, target = random_pair(obj.n_links, random.Random(args.seed))
    args.out.mkdir(parents=True, exist_ok=True)
    domain_path = args.out / "domain.pddl"
    name = args.name or f"p{obj.n_links}"
    problem_path = args.out / f"{name}.pddl"
    domain_path.write_text(domain_pddl(obj, options))
    problem_path.write_text(
        problem_pddl(obj, init, target, options, args.goal_style, seed=args.seed, name=name)
    )
    print(f"wrote {domain_path} and {problem_path} ({args.model}, {obj.n_links} links)")
    return 0
