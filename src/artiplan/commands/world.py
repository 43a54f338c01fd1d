"""``artiplan world``: the simulated MuJoCo world (snapshots: camera images and the state)."""

from __future__ import annotations

import argparse
import json
import os
import random
import subprocess
import sys
from pathlib import Path

from artiplan.errors import ExternalToolError, UsageError

CAMERAS = ("overhead", "side", "perspective")


def add_arguments(parser: argparse.ArgumentParser) -> None:
    sub = parser.add_subparsers(dest="world_command", metavar="ACTION")
    snap = sub.add_parser("snapshot", help="render camera images and write the configuration")
    snap.add_argument("configuration", nargs="?", help="configuration JSON (default: random)")
    snap.add_argument("--links", type=int, default=4, help="links of a random object (default 4)")
    snap.add_argument("--preset", choices=("stiff", "loose"), default="stiff")
    snap.add_argument("--hands", choices=("virtual", "baxter"), default="virtual")
    snap.add_argument("--seed", type=int, default=0, help="random configuration and camera noise")
    snap.add_argument("--settle", type=float, default=0.0, help="simulate this many seconds first")
    snap.add_argument("--width", type=int, default=640)
    snap.add_argument("--height", type=int, default=480)
    snap.add_argument("-o", "--out", required=True, help="output folder")
    kb = sub.add_parser(
        "ontology",
        help="perceive a world, fill the OWL knowledge base, reason, write .owl and PDDL+",
    )
    kb.add_argument("--links", type=int, default=4, help="links of the object (default 4)")
    kb.add_argument("--seed", type=int, default=0, help="initial/target configurations, noise")
    kb.add_argument("--model", choices=("ng", "ucm", "uacm"), default="ucm")
    kb.add_argument("--goal-style", choices=("threshold", "window"), default="threshold")
    kb.add_argument("--no-reason", action="store_true", help="skip HermiT (no Java needed)")
    kb.add_argument("-o", "--out", required=True, help="output folder")


def run(args: argparse.Namespace) -> int:
    if args.world_command not in ("snapshot", "ontology"):
        raise UsageError("usage: artiplan world {snapshot,ontology} [options] -o DIR")
    # MuJoCo reads the GL backend at import: choose a headless one before importing the world.
    chosen = "MUJOCO_GL" not in os.environ
    os.environ.setdefault("MUJOCO_GL", "egl")
    if args.world_command == "ontology":
        return _ontology(args)
    try:
        return _snapshot(args)
    except ExternalToolError:
        if not chosen or "mujoco" not in sys.modules or os.environ["MUJOCO_GL"] != "egl":
            raise
        # EGL failed: MuJoCo cannot switch backends in-process, so run again with OSMesa.
        print(
            "artiplan world: EGL rendering failed; retrying with MUJOCO_GL=osmesa", file=sys.stderr
        )
        env = {**os.environ, "MUJOCO_GL": "osmesa"}
        cmd = [sys.executable, "-m", "artiplan", "world", *sys.argv[sys.argv.index("world") + 1 :]]
        return subprocess.run(cmd, env=env).returncode


def _ontology(args: argparse.Namespace) -> int:
    from artiplan.encoding import EncodingOptions, domain_pddl
    from artiplan.model import ArticulatedObject, random_configuration
    from artiplan.world import make_world
    from artiplan.world.ontology import KnowledgeBase

    if not 2 <= args.links <= 30:
        raise UsageError("--links must be between 2 and 30")
    obj = ArticulatedObject(args.links)
    init = random_configuration(obj.n_links, random.Random(args.seed))
    target = random_configuration(obj.n_links, random.Random(args.seed + 1))
    world = make_world(obj, init, seed=args.seed)
    kb = KnowledgeBase(obj)
    kb.record(world.perceive(reference=init))
    kb.set_goal(target, args.goal_style, args.seed)
    if not args.no_reason:
        kb.reason()
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    kb.save(out / "world.owl")
    options = EncodingOptions(model=args.model)
    (out / "domain.pddl").write_text(domain_pddl(obj, options))
    (out / "problem.pddl").write_text(kb.problem(options))
    print(
        f"wrote {out}/world.owl, domain.pddl, problem.pddl; "
        f"{len(kb.affects())} affects facts in the ontology"
    )
    return 0


def _snapshot(args: argparse.Namespace) -> int:
    import imageio.v3 as iio

    from artiplan.model import ArticulatedObject, load_configuration, random_configuration
    from artiplan.world import make_world
    from artiplan.world.render import colour_labels, depth_image

    if args.configuration:
        conf, obj = load_configuration(args.configuration)
    else:
        if not 2 <= args.links <= 30:
            raise UsageError("--links must be between 2 and 30")
        obj = ArticulatedObject(args.links)
        conf = random_configuration(obj.n_links, random.Random(args.seed))
    world = make_world(obj, conf, preset=args.preset, hands=args.hands, seed=args.seed)
    world.run_until(args.settle)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    written = []
    try:
        for cam in CAMERAS:
            rgb = world.render(cam, "rgb", args.width, args.height)
            iio.imwrite(out / f"{cam}_rgb.png", rgb)
            depth = world.render(cam, "depth", args.width, args.height)
            iio.imwrite(out / f"{cam}_depth.png", depth_image(depth))
            seg = world.render(cam, "segmentation", args.width, args.height)
            iio.imwrite(out / f"{cam}_segmentation.png", colour_labels(seg))
            written += [f"{cam}_rgb.png", f"{cam}_depth.png", f"{cam}_segmentation.png"]
    except Exception as exc:  # GL context creation failures surface as various errors
        if "gl" in type(exc).__name__.lower() or "GL" in str(exc) or "EGL" in str(exc):
            raise ExternalToolError(
                f"headless rendering failed ({exc}); try MUJOCO_GL=osmesa"
            ) from exc
        raise
    finally:
        world.close()
    world.true_configuration().save(out / "configuration.json", obj)
    percept = world.perceive()
    (out / "percept.json").write_text(
        json.dumps(
            {
                "schema": "artiplan.percept/1",
                "time": percept.time,
                "configuration": percept.configuration.to_dict(),
                "uncertainty_deg": list(percept.uncertainty_deg),
            },
            indent=2,
        )
        + "\n"
    )
    written += ["configuration.json", "percept.json"]
    print(f"wrote {len(written)} files to {out}: {', '.join(written)}")
    return 0
