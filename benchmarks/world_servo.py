"""Stability and lag of the virtual hands' pose servo, per pair of gains.

Usage: .venv/bin/python benchmarks/world_servo.py --links 6 [--cases 24] [--seed 1]
       [--gains 2,40 2,10 ...]
Each case: a random configuration (theta, gamma uniform), a random hold L_k / rotate L_k+1,
plane and sense; the turn runs 8 s at 10 deg/s (stiff preset, virtual hands). A case counts as
unstable when any joint speed passes 1 rad/s (a steady 10 deg/s turn is 0.17 rad/s); the lag
is the mean angle [deg] between the rotated link's commanded and actual orientation after 1 s.
"""

from __future__ import annotations

import argparse

import mujoco
import numpy as np

from artiplan.model import ArticulatedObject, Configuration
from artiplan.world import ServoGains, VirtualHands, World, WorldConfig, preset
from artiplan.world.rotations import quat_conj


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--links", type=int, default=6)
    ap.add_argument("--cases", type=int, default=24)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--gains", nargs="+", default=["2,40", "2,20", "2,10"],
                    help="kp,ki pairs")
    args = ap.parse_args()
    n = args.links
    rng = np.random.default_rng(args.seed)
    cases = []
    for _ in range(args.cases):
        conf = Configuration(tuple(rng.uniform(0, 360, n)), tuple(rng.uniform(0, 360, n)))
        k = int(rng.integers(1, n))
        plane = ("xy-axes", "z-axis")[int(rng.integers(2))]
        cases.append((conf, k, plane, int(rng.choice([-1, 1]))))
    for kp, ki in (tuple(map(float, g.split(","))) for g in args.gains):
        unstable, lags = 0, []
        for conf, k, plane, sense in cases:
            w = World(ArticulatedObject(n), conf,
                      WorldConfig(physics=preset("stiff"), servo=ServoGains(kp, ki)),
                      VirtualHands())
            w.hold_and_rotate(f"L{k}", f"L{k + 1}", plane, sense, 10.0, extent_deg=80)
            body = w.model.body(f"L{k + 1}").id
            fastest, lag = 0.0, []
            for s in range(160):
                w.run_until(w.time + 0.05)
                fastest = max(fastest, float(abs(w.data.qvel).max()))
                if s >= 20:
                    _, q = w._motion.target(w.time)  # noqa: SLF001 - a benchmark's look inside
                    e, v = np.empty(4), np.empty(3)
                    mujoco.mju_mulQuat(e, q, quat_conj(w.data.xquat[body]))
                    mujoco.mju_quat2Vel(v, e, 1.0)
                    lag.append(np.degrees(np.linalg.norm(v)))
            unstable += fastest > 1.0
            lags.append(float(np.mean(lag)))
        print(f"links {n} kp={kp:g} ki={ki:g}: unstable {unstable}/{len(cases)}, "
              f"lag mean {np.mean(lags):.2f} deg, worst case {np.max(lags):.2f} deg", flush=True)


if __name__ == "__main__":
    main()
