"""Replay the static grasp refusals of closed-loop runs: for each action Baxter refused because
every grasp met something at the grasp or on its final leg, rebuild the world at the
configuration perceived just before and ask for the grasp pair again (no turn: the grasps,
their final legs and a +-30 deg sweep). Measures a grasp change offline, in seconds per case
instead of an hour per closed-loop run.

The arms start at home, not where the run had them, so a replay is a proxy: it tests the
grasps against the object, the scene and each other, not the way the arms got there.

Usage: .venv/bin/python benchmarks/grasp_replay.py LOGDIR [LOGDIR ...] [--max 40]
       [--tiers N] [--shallow-m M] [--turns N] [--more-points F,F] [--links 6]
Prints one line per case (free or why not) and the count of pairs found.
"""

from __future__ import annotations

import argparse
import json
import re
import time
from pathlib import Path
from typing import Any

from artiplan.model import ArticulatedObject, Configuration
from artiplan.world import grasping, make_world, pairs
from artiplan.world.pairs import NotExecutableError

ACTION = re.compile(r"\(start-(?:increase|decrease) (L\d+) (L\d+) ")


def cases(root: Path) -> list[tuple[str, str, str, Configuration]]:
    """(task name, hold link, rotate link, perceived configuration) of each static refusal."""
    out = []
    for path in sorted(root.glob("task-*.json"), key=lambda p: int(p.stem.split("-")[1])):
        log: dict[str, Any] = json.loads(path.read_text())
        for h in log["happenings"]:
            did = h["did"]
            if h["ok"] or "no collision-free grasps" not in did:
                continue
            if "at the grasp" not in did and "final leg" not in did:
                continue
            m = ACTION.match(h["action"])
            before = [s for s in log["samples"] if s["time"] <= h["time"] + 1e-6]
            if m is None or not before:
                continue
            p = before[-1]["perceived"]
            conf = Configuration(tuple(p["theta"]), tuple(p["gamma"]))
            out.append((f"{root.name}/{path.stem}@{h['time']:.1f}", m[1], m[2], conf))
    return out


def variant(args: argparse.Namespace) -> None:
    """Patch the grasp choice for a variant (experiments only: nothing here is the product)."""
    choice = grasping.GraspChoice
    if args.tiers is not None:  # stop at that tier (grasping.grasp_poses: what each adds)
        grasping.TIERS = pairs.TIERS = args.tiers  # type: ignore[misc]
    if args.shallow_m is not None:
        grasping.SHALLOW_M = args.shallow_m  # type: ignore[misc]
    if args.turns != 8:
        n = args.turns
        for name, keep in (("grasp_poses", 2), ("tier_size", 1), ("tier_end", 2)):
            real = getattr(choice, name)  # drop any n_turns given: always n

            def fixed(self, *a, _real=real, _keep=keep, **k):  # type: ignore[no-untyped-def]
                k.pop("n_turns", None)
                return _real(self, *a[:_keep], n_turns=n, **k)

            setattr(choice, name, fixed)
    if args.more_points:
        more = tuple(float(f) for f in args.more_points.split(","))
        real_f = choice.grasp_fractions
        choice.grasp_fractions = lambda self, link: real_f(self, link) + more  # type: ignore


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("logs", type=Path, nargs="+")
    ap.add_argument("--max", type=int, default=40, help="cases at most (spread over the logs)")
    ap.add_argument("--links", type=int, default=6)
    ap.add_argument("--tiers", type=int, default=None,
                    help="grasp tiers 1 to N only (default: all, grasping.TIERS)")
    ap.add_argument("--shallow-m", type=float, default=None, help="grasping.SHALLOW_M [m]")
    ap.add_argument("--turns", type=int, default=8,
                    help="approach directions about the link per grasp point")
    ap.add_argument("--more-points", default="",
                    help="more tier-1 grasp points on both links [fractions from the base joint]")
    args = ap.parse_args()
    variant(args)
    every = [c for root in args.logs for c in cases(root)]
    step = max(1, len(every) // args.max)
    chosen = every[::step][: args.max]
    free = 0
    t0 = time.perf_counter()
    for name, hold, rot, conf in chosen:
        world = make_world(ArticulatedObject(args.links), conf, hands="baxter", preset="stiff",
                           avoid_collisions=True)
        t = time.perf_counter()
        try:
            hold_hand, rot_hand = world.hands.assign(hold, rot)
            free += 1
            why = f"free: {hold_hand} holds, {rot_hand} turns"
        except NotExecutableError as exc:
            why = "refused: " + str(exc).split("(", 1)[-1][:110]
        print(f"{name} hold {hold} turn {rot}: {why} ({time.perf_counter() - t:.1f} s)",
              flush=True)
    print(f"{free}/{len(chosen)} pairs found ({len(every)} static refusals in the logs; "
          f"{time.perf_counter() - t0:.0f} s wall, tiers {args.tiers or grasping.TIERS})")


if __name__ == "__main__":
    main()
