"""Replay the dead ends of closed-loop runs: the same rotation refused for its grasps 3 or more
times in a row. For each, rebuild the world at the configuration perceived just before, let
the released chain settle under gravity for W s (0, 5, 15) and ask for the grasp pair again;
print whether one is free and how far the links moved. Measures what
``execution.refusals.MAX_WAITS`` / ``WAIT_S`` can expect, offline.

The arms start at home, not where the run had them: a proxy, as in ``grasp_replay.py``.

Usage: .venv/bin/python benchmarks/dead_end_replay.py LOGDIR [LOGDIR ...] [--links 6]
"""

from __future__ import annotations

import argparse
import json
import re
from pathlib import Path

import numpy as np

from artiplan.model import ArticulatedObject, Configuration, direction_error
from artiplan.world import make_world
from artiplan.world.pairs import NotExecutableError

ACTION = re.compile(r"\(start-(?:increase|decrease) (L\d+) (L\d+) ")
WAITS_S = (0.0, 5.0, 15.0)


def dead_ends(root: Path) -> list[tuple[str, float, str, str, Configuration]]:
    """(case name, time [s], hold link, rotated link, configuration perceived before)."""
    out = []
    for path in sorted(root.glob("task-*.json"), key=lambda p: int(p.stem.split("-")[1])):
        log = json.loads(path.read_text())
        refused = [h for h in log["happenings"]
                   if not h["ok"] and h["action"].startswith("(start")]
        for i in range(len(refused) - 2):
            h = refused[i]
            if (refused[i + 1]["action"] != h["action"] or refused[i + 2]["action"] != h["action"]
                    or "no collision-free grasps" not in h["did"]
                    or (i > 0 and refused[i - 1]["action"] == h["action"])):
                continue
            m = ACTION.match(h["action"])
            before = [s for s in log["samples"] if s["time"] <= h["time"] + 1e-6]
            if m is None or not before:
                continue
            p = before[-1]["perceived"]
            out.append((f"{root.name}/{path.stem}", h["time"], m[1], m[2],
                        Configuration(tuple(p["theta"]), tuple(p["gamma"]))))
    return out


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("logs", type=Path, nargs="+")
    ap.add_argument("--links", type=int, default=6)
    args = ap.parse_args()
    obj = ArticulatedObject(args.links)
    cases = [c for root in args.logs for c in dead_ends(root)]
    print(f"{len(cases)} dead ends")
    freed = dict.fromkeys(WAITS_S, 0)
    for name, t, hold, rot, conf in cases:
        out = []
        for wait in WAITS_S:
            world = make_world(obj, conf, hands="baxter", preset="stiff", avoid_collisions=True)
            world.run_until(world.time + wait)
            moved = direction_error(conf, world.perceive().configuration)
            try:
                world.hands.assign(hold, rot)
                ok = "free"
                freed[wait] += 1
            except NotExecutableError:
                ok = "refused"
            out.append(f"W={wait:g} s: {ok} (links moved up to {np.max(moved[1:]):.0f} deg)")
        print(f"{name}@{t:.1f} hold {hold} turn {rot}: " + " | ".join(out), flush=True)
    print("free pairs: " + ", ".join(f"after {w:g} s {n}/{len(cases)}" for w, n in freed.items()))


if __name__ == "__main__":
    main()
