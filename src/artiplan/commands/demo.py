"""``artiplan demo [-o DIR]``: the foundation's demo on built-in defaults.

A 4-link object, a seeded initial and target configuration, the three PDDL+ encodings with one
problem each, the configurations as JSON, and pictures. (The closed loop replaces this later.)
"""

from __future__ import annotations

import argparse
import random
from pathlib import Path

DEMO_LINKS = 4
DEMO_SEED = 2


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument(
        "-o", "--out", type=Path, default=Path("demo-out"), help="output folder (demo-out)"
    )
    parser.add_argument("--seed", type=int, default=DEMO_SEED, help="configuration seed")


def run(args: argparse.Namespace) -> int:
    from artiplan.encoding import EncodingOptions, domain_pddl, problem_pddl
    from artiplan.encoding.suite import random_pair
    from artiplan.model import ArticulatedObject
    from artiplan.viz.draw import draw_configuration

    out: Path = args.out
    out.mkdir(parents=True, exist_ok=True)
    obj = ArticulatedObject(DEMO_LINKS)
    init, target = random_pair(obj.n_links, random.Random(args.seed))
    written = [out / "initial.json", out / "target.json"]
    init.save(written[0], obj)
    target.save(written[1], obj)
    for model in ("ng", "ucm", "uacm"):
        options = EncodingOptions(model, speed_g=0.5, acceleration=0.5)
        folder = out / model
        folder.mkdir(exist_ok=True)
        (folder / "domain.pddl").write_text(domain_pddl(obj, options))
        problem = problem_pddl(obj, init, target, options, seed=args.seed, name="demo")
        (folder / "problem.pddl").write_text(problem)
        written += [folder / "domain.pddl", folder / "problem.pddl"]
    written.append(
        draw_configuration(
            obj,
            init,
            out / "initial.png",
            target=target,
            title="demo: initial (solid) and target (ghost)",
        )
    )
    written.append(draw_configuration(obj, target, out / "target.png", title="demo: target"))
    print(f"artiplan demo: a {obj.n_links}-link object, seed {args.seed}")
    for path in written:
        print(f"  wrote {path}")
    print("next: plan one of the problems, e.g. with ENHSP or `artiplan plan` when available")
    return 0
