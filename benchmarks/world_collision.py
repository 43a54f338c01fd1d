"""Arm clearance of Baxter's grasps (issue 6): distance from each arm to the torso, the other
arm, pedestal/table/fixture and the object, at the grasp and after a 30 deg rotation; held
link drift, rotation reached, and the wall time of choosing the grasps.

Run: .venv/bin/python benchmarks/world_collision.py [--seeds N] [--links 4 6] [--no-avoid]
     [--approach S]
Prints a markdown table (paste into benchmarks/results/world.md). With ``--approach S`` it
measures the approaches instead: per case two successive hold-and-rotates (the second starts
with both hands on the object), the arms moving in S simulated seconds; it counts approaches
whose simulated arms (checked every 20 ms) come into contact, and the reach times.
"""

from __future__ import annotations

import argparse
import json
import random
import time
from dataclasses import replace

import numpy as np

from artiplan.model import ArticulatedObject, direction_error, random_configuration
from artiplan.world import make_world
from artiplan.world.collision import arm_geoms, clearance


def robot_and_scene(world, hand: str, verbose: bool) -> tuple[float, float]:
    """(clearance to torso/other arm/scene [m], clearance including the object's links [m])."""
    hands = world.hands
    geoms = arm_geoms(world.model, hand, list(world.obj.links))
    held = hands.held(hand)
    no_links, pair = clearance(world.model, world.data, geoms, held, with_links=False)
    if no_links < 0 and verbose:
        print(f"  {hand}: {pair} {no_links:.3f} t={world.time:.1f}")
    return no_links, clearance(world.model, world.data, geoms, held)[0]


def case(n: int, seed: int, avoid: bool, verbose: bool) -> dict[str, float] | None:
    rng = random.Random(seed)
    conf = random_configuration(n, rng)
    world = make_world(
        ArticulatedObject(n), conf, hands="baxter", preset="stiff", seed=seed,
        avoid_collisions=avoid,
    )
    k = rng.randint(1, n - 1)
    plane = rng.choice(["z-axis", "xy-axes"])
    sign = rng.choice([1, -1])
    t0 = time.perf_counter()
    try:  # without an approach, hold_and_rotate is the grasp choice (assign + grasp)
        world.hold_and_rotate(f"L{k}", f"L{k + 1}", plane, sign, 10.0)
    except RuntimeError as exc:
        if verbose:
            print(f"  seed {seed}: {exc}")
        return None
    choice = time.perf_counter() - t0
    hands = ("left", "right") if k > 1 else (world._motion.hand,)
    at_grasp = [robot_and_scene(world, h, verbose) for h in hands]
    start = world.true_configuration()
    world.run_until(world.time + 3.0)
    after = [robot_and_scene(world, h, verbose) for h in hands]
    world.stop(release=False)
    end = world.true_configuration()
    expected = start.with_angle(k + 1, plane, start.angle(k + 1, plane) + 30.0 * sign)
    return {
        "grasp": min(c[0] for c in at_grasp),
        "after": min(c[0] for c in after),
        "all": min(c[1] for c in at_grasp + after),
        "drift": float(direction_error(start, end)[k - 1]),
        "miss": float(direction_error(expected, end)[k]),
        "choice": choice,
    }


def physical_link_clearance(world, geoms, hand: str, target: str) -> float:
    """Like the links clearance, but not counting a gripper inside a link it has just let go
    of and not yet left (the physics has no contact for that pair: the fingers had closed on
    the link) - the arm's other parts still count against it."""
    off = set(getattr(world.hands, "_no_contact", {}).get(hand, set())) - {target}
    if not off:
        return clearance(world.model, world.data, geoms, target)[0]
    rest = replace(geoms, links={k: v for k, v in geoms.links.items() if k not in off})
    body = replace(geoms, arm=tuple(g for g in geoms.arm if g not in geoms.gripper),
                   links={k: v for k, v in geoms.links.items() if k in off})
    return min(clearance(world.model, world.data, rest, target)[0],
               clearance(world.model, world.data, body, None, True, False, False)[0])


def approach_case(n: int, seed: int, avoid: bool, approach_s: float) -> dict[str, object]:
    """Two successive hold-and-rotates (30 deg on z-axis each). Measured here, independently of
    the code's own samples: the simulated arms' smallest clearance every 20 ms of each
    approach (to torso, other arm, scene; and to those or the other links, fingers included),
    and the clearance to the other links when the approach ends, just before the grasp."""
    rng = random.Random(seed)
    conf = random_configuration(n, rng)
    world = make_world(
        ArticulatedObject(n), conf, hands="baxter", preset="stiff", seed=seed,
        avoid_collisions=avoid, approach_s=approach_s,
    )
    hands = world.hands
    grasp = hands.grasp
    at_end: list[float] = []

    def measured_grasp(hand: str, link: str) -> None:
        geoms = arm_geoms(world.model, hand, list(world.obj.links))
        at_end.append(clearance(world.model, world.data, geoms, link)[0])
        grasp(hand, link)

    hands.grasp = measured_grasp
    approach = hands.approach
    path: dict[str, list[float]] = {"robot": [], "links": [], "touch": []}

    def measured_approach(pairs, advance) -> None:
        geoms = {h: arm_geoms(world.model, h, list(world.obj.links)) for h, _ in pairs}
        robot, links, touch = np.inf, np.inf, np.inf

        def measured_advance(dt: float) -> None:
            nonlocal robot, links, touch
            advance(dt)
            for h, link in pairs:  # the simulated arm itself, every 20 ms
                robot = min(robot, clearance(world.model, world.data, geoms[h], link, False)[0])
                links = min(links, clearance(world.model, world.data, geoms[h], link)[0])
                touch = min(touch, physical_link_clearance(world, geoms[h], h, link))

        approach(pairs, measured_advance)
        path["robot"].append(robot)
        path["links"].append(links)
        path["touch"].append(touch)

    hands.approach = measured_approach
    k = rng.randint(2, n - 2)
    clear, links, reach, drift, miss = [], [], [], [], []
    refused = ""
    try:
        for hold in (k, k + 1):
            t0 = world.time
            sign = rng.choice([1, -1])
            world.hold_and_rotate(f"L{hold}", f"L{hold + 1}", "z-axis", sign, 10.0)
            reach.append(world.time - t0)
            clear.append(path["robot"][-1])
            links.append(path["links"][-1])
            start = world.true_configuration()
            world.run_until(world.time + 3.0)
            world.stop(release=False)
            end = world.true_configuration()
            target = start.angle(hold + 1, "z-axis") + 30.0 * sign
            expected = start.with_angle(hold + 1, "z-axis", target)
            drift.append(float(direction_error(start, end)[hold - 1]))
            miss.append(float(direction_error(expected, end)[hold]))
            world.stop(release=True)
    except RuntimeError as exc:  # out of reach, or (motion planning) no collision-free way
        refused = f"{type(exc).__name__}: {exc}"
    stats = getattr(hands, "checker", None)
    contacts = getattr(hands, "contacts", None)
    out: dict[str, object] = {
        "seed": seed, "refused": refused, "approaches": len(clear),
        "robot": clear, "links": links, "touch": path["touch"], "reach": reach,
        "tips": sum(c < 0 for c in at_end), "tips_min": min(at_end, default=np.inf),
        "drift": drift, "reached": sum(m < 2.0 for m in miss),
        "plan_wall_s": [m.wall_s for m in stats.stats] if stats is not None else [],
        "collisions": [e.to_dict() for e in contacts.events] if contacts is not None else [],
    }
    return out


def approach_table(args: argparse.Namespace) -> None:
    """Per link count: the approach measurements (see :func:`approach_case`); every case's
    row also goes to ``--jsonl`` when given."""
    print("| links | cases | refused (no collision-free way / out of reach) |"
          " approaches through torso/arm/scene | path clearance min [m] |"
          " cases with an approach within another link (not counting the one just let go of) |"
          " arms within a link at approach end (of grasps) |"
          " drift > 0.5 deg (of rotations) | reached within 2 deg | reach time median / max [s] |"
          " physics collisions (events / cases) | planning per motion median / p95 / max [s] |"
          " wall [s] |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for n in args.links:
        t0 = time.perf_counter()
        rows = [approach_case(n, s, not args.no_avoid, args.approach) for s in range(args.seeds)]
        if args.jsonl:
            with open(args.jsonl, "a") as fh:
                for r in rows:
                    fh.write(json.dumps({"n_links": n, **r}, default=float) + "\n")
        robot = [c for r in rows for c in r["robot"]]
        reach = [x for r in rows for x in r["reach"]]
        plans = [x for r in rows for x in r["plan_wall_s"]]
        refused = [r["refused"] for r in rows if r["refused"]]
        no_way = sum("NotExecutable" in x for x in refused)
        events = sum(len(r["collisions"]) for r in rows)
        hit = sum(bool(r["collisions"]) for r in rows)
        p50, p95 = np.percentile(plans, [50, 95]) if plans else (float("nan"),) * 2
        print(
            f"| {n} | {len(rows)} | {no_way} / {len(refused) - no_way} |"
            f" {sum(c < 0 for c in robot)} of {len(robot)} |"
            f" {min(robot, default=float('nan')):.3f} |"
            f" {sum(any(c < 0 for c in r['links']) for r in rows)}"
            f" ({sum(any(c < 0 for c in r['touch']) for r in rows)}) |"
            f" {sum(r['tips'] for r in rows)} of {len(robot)} |"
            f" {sum(d > 0.5 for r in rows for d in r['drift'])} of"
            f" {sum(len(r['drift']) for r in rows)} |"
            f" {sum(r['reached'] for r in rows)} |"
            f" {np.median(reach) if reach else float('nan'):.2f} /"
            f" {max(reach, default=float('nan')):.2f} |"
            f" {events} / {hit} | {p50:.2f} / {p95:.2f} /"
            f" {max(plans, default=float('nan')):.2f} |"
            f" {time.perf_counter() - t0:.0f} |",
            flush=True,
        )


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--seeds", type=int, default=12)
    parser.add_argument("--links", type=int, nargs="+", default=[4, 6])
    parser.add_argument(
        "--no-avoid", action="store_true", help="baseline: grasp choice and IK blind to obstacles"
    )
    parser.add_argument("--approach", type=float, default=0.0, help="measure approaches")
    parser.add_argument("-v", "--verbose", action="store_true")
    parser.add_argument("--jsonl", default="", help="append each approach case as JSON here")
    args = parser.parse_args()
    if args.approach > 0:
        approach_table(args)
        return
    print(
        "| links | cases | unreachable | colliding at grasp | colliding after rotation |"
        " colliding (either) | robot/scene min / median [m] | colliding incl. object |"
        " drift>0.5 | reached within 2 | grasp choice mean / max [s] | wall [s] |"
    )
    print("|---|---|---|---|---|---|---|---|---|---|---|---|")
    for n in args.links:
        t0 = time.perf_counter()
        res = [case(n, s, not args.no_avoid, args.verbose) for s in range(args.seeds)]
        ok = [r for r in res if r is not None]
        gr = np.array([r["grasp"] for r in ok])
        af = np.array([r["after"] for r in ok])
        rob = np.minimum(gr, af)
        alls = np.array([r["all"] for r in ok])
        drift = np.array([r["drift"] for r in ok])
        miss = np.array([r["miss"] for r in ok])
        choice = np.array([r["choice"] for r in ok])
        print(
            f"| {n} | {len(res)} | {len(res) - len(ok)} | {int((gr < 0).sum())} |"
            f" {int((af < 0).sum())} | {int((rob < 0).sum())} |"
            f" {rob.min():.3f} / {np.median(rob):.3f} | {int((alls < 0).sum())} |"
            f" {int((drift > 0.5).sum())} | {int((miss < 2.0).sum())} |"
            f" {choice.mean():.2f} / {choice.max():.2f} | {time.perf_counter() - t0:.0f} |",
            flush=True,
        )


if __name__ == "__main__":
    main()
