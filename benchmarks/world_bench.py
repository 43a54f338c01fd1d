"""Measurements of the simulated world (issue 6) -> benchmarks/results/world.md + PNG plots.

Run: .venv/bin/python benchmarks/world_bench.py [--quick]
Sections: gravity (released links vs UCM/UACM fits), perception (error vs noise and frames),
grasps (drift, reached vs commanded, torque; virtual and Baxter), speed (steps/s, real-time factor).
"""

from __future__ import annotations

import argparse
import os
import platform
import random
import subprocess
import time
from datetime import datetime, timezone
from pathlib import Path

os.environ.setdefault("MUJOCO_GL", "egl")

import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import mujoco  # noqa: E402
import numpy as np  # noqa: E402

from artiplan.model import (  # noqa: E402
    ArticulatedObject,
    Configuration,
    direction_error,
    random_configuration,
)
from artiplan.world import PerceptionConfig, World, WorldConfig, make_world, preset  # noqa: E402

ROOT = Path(__file__).resolve().parent
PLOTS = ROOT / "world"
RESULTS = ROOT / "results" / "world.md"


def unwrap_gamma(g: np.ndarray) -> np.ndarray:
    """Gamma [deg] as a continuous signal (a falling link may cross 0/360)."""
    return np.degrees(np.unwrap(np.radians(g)))


def record(world: World, horizon: float, dt: float) -> tuple[np.ndarray, np.ndarray]:
    """Times and (t, n) gamma of every link while nothing holds the object."""
    ts, gs = [world.time], [world.true_configuration().gamma]
    while world.time < horizon - 1e-9:
        world.step(dt)
        ts.append(world.time)
        gs.append(world.true_configuration().gamma)
    g = np.array(gs)
    return np.array(ts), np.column_stack([unwrap_gamma(g[:, i]) for i in range(g.shape[1])])


def fit_ucm(t: np.ndarray, g: np.ndarray) -> tuple[float, float]:
    """Speed v [deg/s] of g0 - v t (least squares) and the RMS residual [deg]."""
    v = -float(np.dot(t, g - g[0]) / np.dot(t, t))
    return v, float(np.sqrt(np.mean((g[0] - v * t - g) ** 2)))


def fit_uacm(t: np.ndarray, g: np.ndarray) -> tuple[float, float]:
    """Acceleration a [deg/s^2] of g0 - a t^2 / 2 (least squares) and the RMS residual."""
    s = 0.5 * t**2
    a = -float(np.dot(s, g - g[0]) / np.dot(s, s))
    return a, float(np.sqrt(np.mean((g[0] - a * s - g) ** 2)))


def gravity_section(quick: bool) -> list[str]:
    lines = ["## Gravity: a released link's gamma over time, with UCM and UACM fits", ""]
    lines += [
        "A 2-link object (L1 clamped horizontal, L2 released horizontal, gamma = 90), and a",
        "4-link chain with L2..L4 released horizontal. UCM fit: g0 - v t; UACM fit: g0 - a t^2/2",
        "(least squares over the window, until the first link reaches gamma = 0).",
        "",
        "| preset | object | link | window [s] | UCM v [deg/s] | UCM RMS [deg] |"
        " UACM a [deg/s^2] | UACM RMS [deg] |",
        "|---|---|---|---|---|---|---|---|",
    ]
    fig, axes = plt.subplots(2, 2, figsize=(11, 7))
    cases = {
        "single": (2, Configuration.from_angles([0, 0], [90, 90])),
        "chain4": (4, Configuration.from_angles([0, 0, 0, 0], [90, 90, 90, 90])),
    }
    for row, name in enumerate(("stiff", "loose")):
        horizon = 10.0 if name == "stiff" else 0.6
        if quick:
            horizon /= 2
        for col, (case, (n, conf)) in enumerate(cases.items()):
            world = World(ArticulatedObject(n), conf, WorldConfig(preset(name)))
            t, g = record(world, horizon, horizon / 200)
            ax = axes[row, col]
            for i in range(1, n):
                gi = g[:, i]
                hit = np.nonzero(gi <= 0.5)[0]
                end = int(hit[0]) if hit.size else len(t)
                end = max(end, 5)
                v, r_u = fit_ucm(t[:end], gi[:end])
                a, r_a = fit_uacm(t[:end], gi[:end])
                lines.append(
                    f"| {name} | {case} | L{i + 1} | {t[end - 1]:.2f} | {v:.3f} | {r_u:.3f} |"
                    f" {a:.3f} | {r_a:.3f} |"
                )
                (line,) = ax.plot(t, gi, label=f"L{i + 1} physics")
                tt = t[:end]
                ax.plot(tt, gi[0] - v * tt, "--", color=line.get_color(), lw=0.8)
                ax.plot(tt, gi[0] - 0.5 * a * tt**2, ":", color=line.get_color(), lw=1.2)
            ax.set_title(f"{name}, {case} (dashed UCM fit, dotted UACM fit)", fontsize=9)
            ax.set_xlabel("time [s]")
            ax.set_ylabel("gamma [deg]")
            ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(PLOTS / "gravity_fits.png", dpi=110)
    plt.close(fig)
    lines += ["", "Plot: `benchmarks/world/gravity_fits.png`.", ""]
    return lines


def perception_section(quick: bool) -> list[str]:
    noises = [(0.001, 0.5), (0.005, 2.0), (0.01, 5.0)]
    frames = [1, 4, 16, 64]
    trials = 5 if quick else 20
    lines = ["## Perception: direction error of the estimate vs noise and frames", ""]
    lines += [
        f"6-link object, {trials} random configurations per cell, direction-angle error per link",
        "(mean / max over all links and trials) [deg]. `fused` uses positions and orientations,",
        "`orient.` orientations only.",
        "",
        "| noise (pos m, orient deg) | frames | fused mean | fused max | orient. mean |"
        " orient. max |",
        "|---|---|---|---|---|---|",
    ]
    obj = ArticulatedObject(6)
    fig, ax = plt.subplots(figsize=(6, 4))
    for pos, ori in noises:
        means = []
        for f in frames:
            row = []
            for fused in (True, False):
                cfg = PerceptionConfig(pos, ori, f, use_positions=fused)
                errs = []
                for s in range(trials):
                    conf = random_configuration(6, random.Random(s))
                    world = World(obj, conf, WorldConfig(perception=cfg, seed=s))
                    errs.append(direction_error(world.perceive(conf).configuration, conf))
                e = np.concatenate(errs)
                row += [e.mean(), e.max()]
            means.append(row[0])
            lines.append(
                f"| ({pos}, {ori}) | {f} | {row[0]:.3f} | {row[1]:.3f} | {row[2]:.3f} |"
                f" {row[3]:.3f} |"
            )
        ax.loglog(frames, means, "o-", label=f"{pos * 1000:.0f} mm, {ori} deg")
    ax.set_xlabel("frames")
    ax.set_ylabel("mean direction error [deg]")
    ax.legend()
    ax.grid(True, which="both", alpha=0.3)
    fig.tight_layout()
    fig.savefig(PLOTS / "perception_error.png", dpi=110)
    plt.close(fig)
    lines += ["", "Plot: `benchmarks/world/perception_error.png`.", ""]
    return lines


def weld_torque(world: World, hand: str, link: str) -> float:
    """Magnitude of the torque [N m] the weld of ``hand`` on ``link`` transmits now."""
    eq = world.model.equality(f"weld_{hand}_{link}").id
    rows = np.nonzero(
        (world.data.efc_type == int(mujoco.mjtConstraint.mjCNSTR_EQUALITY))
        & (world.data.efc_id == eq)
    )[0]
    if len(rows) < 6:
        return 0.0
    return float(np.linalg.norm(world.data.efc_force[rows[3:6]]))


def grasp_case(hands: str, n: int, pre: str, seed: int) -> dict[str, float] | None:
    rng = random.Random(seed)
    conf = random_configuration(n, rng)
    approach = 1.0 if hands == "baxter+approach" else 0.0
    kind = "baxter" if approach else hands
    world = make_world(
        ArticulatedObject(n), conf, hands=kind, preset=pre, seed=seed, approach_s=approach
    )
    k = rng.randint(1, n - 1)
    plane = rng.choice(["z-axis", "xy-axes"])
    sign = rng.choice([1, -1])
    try:
        world.hold_and_rotate(f"L{k}", f"L{k + 1}", plane, sign, 10.0)
    except RuntimeError:
        return None
    start = world.true_configuration()  # at the grasp: after the approach, if any
    rot_hand = world._motion.hand if world._motion else "right"
    torques, motor = [], []
    t_end = world.time + 3.0
    while world.time < t_end - 1e-9:
        world.step(0.05)
        torques.append(weld_torque(world, rot_hand, f"L{k + 1}"))
        if kind == "baxter":
            motor.append(max(float(np.max(np.abs(world.hands.last_torque[h])))
                             for h in ("left", "right")))
    world.stop(release=False)
    end = world.true_configuration()
    expected = start.with_angle(k + 1, plane, start.angle(k + 1, plane) + 30.0 * sign)
    moved = float(direction_error(start, end)[k])
    return {
        "drift": float(direction_error(start, end)[k - 1]),
        "miss": float(direction_error(expected, end)[k]),
        "commanded": float(direction_error(start, expected)[k]),
        "moved": moved,
        "weld_torque": float(np.mean(torques[len(torques) // 4 :])),
        "motor_max": float(max(motor)) if motor else float("nan"),
    }


def grasp_section(quick: bool) -> list[str]:
    lines = ["## Grasps: hold one link, rotate its neighbour by a commanded 30 deg at 10 deg/s", ""]
    lines += [
        "Random configurations and (hold, rotate, plane, direction) per seed; `baxter+approach`:",
        "the arms move to their grasps in 1 s + 0.2 s settling of simulated time first (measured",
        "from the grasp on). drift: held link's",
        "direction change; miss: direction error of the rotated link against the commanded",
        "rotation; moved/commanded: direction change reached and commanded (a theta turn moves a",
        "direction by less than 30 deg when gamma is off 90); weld torque: mean torque the",
        "rotating grasp transmits (steady part); motor: Baxter's largest joint torque.",
        "",
        "| hands | links | preset | cases | unreachable | pass (miss<2, drift<0.5) |"
        " drift mean/max [deg] | miss mean/max [deg] | weld torque mean/max [N m] |"
        " motor max [N m] |",
        "|---|---|---|---|---|---|---|---|---|---|",
    ]
    seeds = 4 if quick else 12
    cases = (("virtual", 4), ("virtual", 8), ("baxter", 4), ("baxter", 6), ("baxter+approach", 4))
    for hands, n in cases:
        for pre in ("stiff", "loose"):
            if hands != "virtual" and pre == "loose" and quick:
                continue
            res = [grasp_case(hands, n, pre, s) for s in range(seeds)]
            ok = [r for r in res if r is not None]
            if not ok:
                continue
            dr = np.array([r["drift"] for r in ok])
            mi = np.array([r["miss"] for r in ok])
            tq = np.array([r["weld_torque"] for r in ok])
            mm = np.array([r["motor_max"] for r in ok])
            passed = int(np.sum((dr < 0.5) & (mi < 2.0)))
            motor = f"{np.nanmax(mm):.1f}" if hands != "virtual" else "-"
            lines.append(
                f"| {hands} | {n} | {pre} | {len(res)} | {len(res) - len(ok)} | {passed} |"
                f" {dr.mean():.3f} / {dr.max():.3f} | {mi.mean():.3f} / {mi.max():.3f} |"
                f" {tq.mean():.3f} / {tq.max():.3f} | {motor} |"
            )
    lines.append("")
    return lines


def speed_section(quick: bool) -> list[str]:
    lines = ["## Speed: physics steps per second and real-time factor (time step 2 ms)", ""]
    lines += [
        "| hands | links | state | sim time [s] | wall [s] | steps/s | real-time factor |",
        "|---|---|---|---|---|---|---|",
    ]
    horizon = 1.0 if quick else 3.0
    for hands, sizes in (("virtual", (4, 8, 12)), ("baxter", (4, 6))):
        for n in sizes:
            for state in ("free", "rotating"):
                conf = random_configuration(n, random.Random(n))
                world = make_world(ArticulatedObject(n), conf, hands=hands)
                if state == "rotating":
                    try:
                        world.hold_and_rotate("L1", "L2", "xy-axes", 1, 10.0)
                    except RuntimeError:
                        continue
                t0 = time.perf_counter()
                world.step(horizon)
                wall = time.perf_counter() - t0
                steps = horizon / world.model.opt.timestep
                lines.append(
                    f"| {hands} | {n} | {state} | {horizon:.1f} | {wall:.3f} |"
                    f" {steps / wall:,.0f} | {horizon / wall:.1f} |"
                )
    lines.append("")
    return lines


def header(cmd: str) -> list[str]:
    cpu = next(
        (ln.split(":", 1)[1].strip() for ln in Path("/proc/cpuinfo").read_text().splitlines()
         if ln.startswith("model name")), platform.processor())
    load = os.getloadavg()
    rev = subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True,
                         text=True, cwd=ROOT).stdout.strip()
    return [
        "# The simulated world: measurements (issue 6)",
        "",
        f"- Date: {datetime.now(timezone.utc):%Y-%m-%d %H:%M} UTC; commit {rev}",
        f"- Machine: {os.cpu_count()} cores, {cpu}; MuJoCo {mujoco.__version__}",
        f"- Load: load average {load[0]:.2f} {load[1]:.2f} {load[2]:.2f} at the start (other",
        "  helpers share the 2 cores: wall-clock numbers are pessimistic)",
        f"- Command: `{cmd}`",
        "",
    ]


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--quick", action="store_true", help="fewer trials (a smoke run)")
    ap.add_argument("--sections", default="gravity,perception,grasps,speed")
    args = ap.parse_args()
    PLOTS.mkdir(parents=True, exist_ok=True)
    cmd = ".venv/bin/python benchmarks/world_bench.py" + (" --quick" if args.quick else "")
    lines = header(cmd)
    funcs = {
        "gravity": gravity_section,
        "perception": perception_section,
        "grasps": grasp_section,
        "speed": speed_section,
    }
    for name in args.sections.split(","):
        t0 = time.perf_counter()
        lines += funcs[name](args.quick)
        print(f"{name}: {time.perf_counter() - t0:.1f} s", flush=True)
    RESULTS.parent.mkdir(parents=True, exist_ok=True)
    RESULTS.write_text("\n".join(lines) + "\n")
    print(f"wrote {RESULTS}")


if __name__ == "__main__":
    main()
