"""Arm clearance of Baxter's grasps (issue 6): distance from each arm to the torso, the other
arm, pedestal/table/fixture and the object, at the grasp and after a 30 deg rotation.

Run: .venv/bin/python benchmarks/world_collision.py [--seeds N]
Prints a markdown table (paste into benchmarks/results/world.md).
"""

from __future__ import annotations

import argparse
import random
import time

import numpy as np

from artiplan.model import ArticulatedObject, direction_error, random_configuration
from artiplan.world import make_world
from artiplan.world.collision import arm_geoms, clearance


def robot_and_scene(world, hand: str) -> tuple[float, float]:
    """(clearance to torso/other arm/scene [m], clearance including the object's links [m])."""
    hands = world.hands
    geoms = arm_geoms(world.model, hand, list(world.obj.links))
    held = hands.held(hand)
    no_links, pair = clearance(world.model, world.data, geoms, held, with_links=False)
    if no_links < 0:
        print(f"  {hand}: {pair} {no_links:.3f} t={world.time:.1f}")
    return no_links, clearance(world.model, world.data, geoms, held)[0]


def case(n: int, seed: int, avoid: bool = True) -> dict[str, float] | None:
    rng = random.Random(seed)
    conf = random_configuration(n, rng)
    world = make_world(
        ArticulatedObject(n),
        conf,
        hands="baxter",
        preset="stiff",
        seed=seed,
        avoid_collisions=avoid,
    )
    k = rng.randint(1, n - 1)
    plane = rng.choice(["z-axis", "xy-axes"])
    sign = rng.choice([1, -1])
    try:
        world.hold_and_rotate(f"L{k}", f"L{k + 1}", plane, sign, 10.0)
    except RuntimeError:
        return None
    hands = ("left", "right") if k > 1 else (world._motion.hand,)
    at_grasp = [robot_and_scene(world, h) for h in hands]
    start = world.true_configuration()
    world.run_until(world.time + 3.0)
    after = [robot_and_scene(world, h) for h in hands]
    world.stop(release=False)
    end = world.true_configuration()
    return {
        "grasp": min(c[0] for c in at_grasp),
        "robot": min(c[0] for c in at_grasp + after),
        "all": min(c[1] for c in at_grasp + after),
        "drift": float(direction_error(start, end)[k - 1]),
    }


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--seeds", type=int, default=12)
    parser.add_argument(
        "--no-avoid", action="store_true", help="baseline: grasp choice and IK blind to obstacles"
    )
    args = parser.parse_args()
    print(
        "| links | cases | unreachable | robot/scene min / median [m] | colliding (<0) |"
        " at grasp min / colliding | incl. object min [m] | colliding incl. object |"
        " drift>0.5 | wall [s] |"
    )
    print("|---|---|---|---|---|---|---|---|---|---|")
    for n in (4, 6):
        t0 = time.perf_counter()
        res = [case(n, s, avoid=not args.no_avoid) for s in range(args.seeds)]
        ok = [r for r in res if r is not None]
        rob = np.array([r["robot"] for r in ok])
        gr = np.array([r["grasp"] for r in ok])
        alls = np.array([r["all"] for r in ok])
        drift = np.array([r["drift"] for r in ok])
        print(
            f"| {n} | {len(res)} | {len(res) - len(ok)} |"
            f" {rob.min():.3f} / {np.median(rob):.3f} | {int((rob < 0).sum())} |"
            f" {gr.min():.3f} / {int((gr < 0).sum())} | {alls.min():.3f} |"
            f" {int((alls < 0).sum())} | {int((drift > 0.5).sum())} |"
            f" {time.perf_counter() - t0:.0f} |"
        )


if __name__ == "__main__":
    main()
