"""Fidelity of the gravity models against physics (mission.md row 14).

For every task and model: execute the first plan open-loop (no re-planning) and measure the
prediction error per link (direction angle between predicted and perceived: RMS and max over
time, and at the final happening) and whether the goal was reached; for UCM and UACM once with
the paper's parameters (``speed-g`` 0.5 deg/s, ``acceleration`` 0.5 deg/s^2: before calibration)
and once with parameters identified from a release run (after). Then the same tasks closed-loop
(re-planning, calibrated, no model fallback): success, re-plans, simulated and wall time.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import dataclass, replace
from typing import Any, cast

from artiplan.encoding import EncodingOptions
from artiplan.encoding.options import Carry, Model
from artiplan.encoding.suite import make_task
from artiplan.execution.calibrate import calibrate
from artiplan.execution.config import LoopConfig
from artiplan.execution.loop import run_loop
from artiplan.execution.runlog import RunLog
from artiplan.model import ArticulatedObject

SCHEMA_FIDELITY = "artiplan.fidelity/1"
PAPER_SPEED_G, PAPER_ACCELERATION = 0.5, 0.5


@dataclass(frozen=True)
class FidelityConfig:
    """What the experiment runs.

    Attributes:
        tasks: Tasks per size (seeded, ``make_task(size, k, seed)``).
        sizes: Object sizes (links).
        preset: Joint physics (``stiff`` or ``loose``).
        hands: ``virtual`` or ``baxter``.
        seed: Suite seed of the tasks.
        models: Gravity models to measure.
        closed_loop: Also run with re-planning.
        plan_time_limit: Wall limit of one planner call [s].
        carry: The encodings' carry rule (``rigid``: the paper's; ``projected``: see
            ``EncodingOptions.carry``); a projected run's parameters are labelled so.
    """

    tasks: int = 20
    sizes: tuple[int, ...] = (4, 6)
    preset: str = "stiff"
    hands: str = "virtual"
    seed: int = 7
    models: tuple[str, ...] = ("ng", "ucm", "uacm")
    closed_loop: bool = True
    plan_time_limit: float = 30.0
    carry: str = "rigid"


def prediction_errors(log: RunLog) -> dict[str, Any]:
    """Per-link RMS and max direction error over the first plan's samples, and at its end [deg]
    (L1, clamped, excluded); ``None`` values when there was no plan. The summary's
    ``goal_*`` columns take the worst goal link; the others every moving link, including
    carried tip links whose prediction the model's per-angle propagation gets wrong."""
    samples = [s for s in log.samples if s["plan"] == 0]
    if not samples:
        return {"rms": None, "max": None, "end": None}
    n = len(samples[0]["errors"])
    cols = [[s["errors"][i] for s in samples] for i in range(1, n)]
    rms = [math.sqrt(sum(e * e for e in c) / len(c)) for c in cols]
    return {"rms": [round(x, 3) for x in rms], "max": [round(max(c), 3) for c in cols],
            "end": [round(c[-1], 3) for c in cols]}


def _options(model: str, speed_g: float, acceleration: float) -> EncodingOptions:
    return EncodingOptions(cast(Model, model), speed_g=round(speed_g, 4),
                           acceleration=round(acceleration, 4))


def _label(calibration: str, carry: str) -> str:
    """The table's parameters column: the calibration, and the carry rule unless rigid."""
    if carry == "rigid":
        return calibration
    return f"{carry} carry" if calibration == "-" else f"{calibration}, {carry} carry"


def _settings(model: str, cal: Any) -> list[tuple[str, EncodingOptions]]:
    """(calibration label, options) pairs to run open-loop for ``model``."""
    if model == "ng":
        return [("-", _options("ng", 1.0, 1.0))]
    return [("paper", _options(model, PAPER_SPEED_G, PAPER_ACCELERATION)),
            ("calibrated", _options(model, cal.speed_g, cal.acceleration))]


def run_fidelity(config: FidelityConfig, make_world: Callable[..., Any],
                 progress: Callable[[str], None] | None = None) -> list[dict[str, Any]]:
    """Every run as a row (``schema``, size, task, model, calibration, mode, errors, ...)."""
    say = progress or (lambda _s: None)
    rows: list[dict[str, Any]] = []
    for size in config.sizes:
        obj = ArticulatedObject(size)
        cal = calibrate(make_world, obj, preset=config.preset)
        say(f"{size} links, {config.preset}: calibrated speed-g {cal.speed_g:.3f} deg/s, "
            f"acceleration {cal.acceleration:.3f} deg/s^2")
        for k in range(1, config.tasks + 1):
            task = make_task(size, k, seed=config.seed)
            for model in config.models:
                carry = cast(Carry, config.carry)
                runs = [("open", _label(label, carry), replace(opts, carry=carry))
                        for label, opts in _settings(model, cal)]
                if config.closed_loop:
                    runs.append(("closed", runs[-1][1], runs[-1][2]))
                for mode, label, opts in runs:
                    loop = LoopConfig(encoding=opts, replan=mode == "closed", fallback_model=None,
                                      plan_time_limit=config.plan_time_limit)
                    world = make_world(obj, task.initial, preset=config.preset,
                                       hands=config.hands, seed=k)
                    t0 = time.perf_counter()
                    log = run_loop(world, task.target, loop, seed=task.seed)
                    row = _row(config, size, k, model, label, mode, opts, log, world)
                    row["wall_s"] = round(time.perf_counter() - t0, 3)
                    rows.append(row)
                    say(f"{size} links task {k:2d} {model:4s} {label:10s} {mode:6s}: "
                        f"{'ok ' if row['success'] else 'MISS'} rms {row['rms_mean']} "
                        f"replans {row['replans']}")
    return rows


def _row(config: FidelityConfig, size: int, task: int, model: str, label: str, mode: str,
         opts: EncodingOptions, log: RunLog, world: Any) -> dict[str, Any]:
    errs = prediction_errors(log)
    rms, mx, end = errs["rms"], errs["max"], errs["end"]
    goal = [obj_index - 2 for obj_index in (int(lk[1:]) for lk in log.goal_links)]  # L1 dropped
    return {
        "schema": SCHEMA_FIDELITY, "preset": config.preset, "hands": world.hands.kind,
        "size": size, "task": task, "model": model, "calibration": label, "mode": mode,
        "carry": opts.carry,
        "speed_g": opts.speed_g if model == "ucm" else None,
        "acceleration": opts.acceleration if model == "uacm" else None,
        "planned": bool(log.plans and log.plans[0]["status"] == "solved"),
        "success": log.success, "replans": len(log.replans),
        "rms_per_link": rms, "max_per_link": mx, "end_per_link": end,
        "rms_mean": round(sum(rms) / len(rms), 3) if rms else None,
        "max": max(mx) if mx else None, "end_max": max(end) if end else None,
        "goal_rms": round(max(rms[i] for i in goal), 3) if rms else None,
        "goal_end": round(max(end[i] for i in goal), 3) if end else None,
        "sim_s": round(world.time, 3),
        "latency_wall_s": [p["latency_wall_s"] for p in log.plans],
    }


def summarise(rows: list[dict[str, Any]]) -> list[dict[str, Any]]:
    """One line per (preset, size, model, calibration): means over tasks; open-loop errors and
    goal rate next to closed-loop success and re-plans."""
    keys = sorted({(r["preset"], r["size"], r["model"], r["calibration"]) for r in rows},
                  key=lambda k: (k[0], k[1], ["ng", "ucm", "uacm"].index(k[2]), k[3] != "paper"))
    out = []
    for key in keys:
        group = [r for r in rows if (r["preset"], r["size"], r["model"], r["calibration"]) == key]
        open_ = [r for r in group if r["mode"] == "open" and r["rms_mean"] is not None]
        closed = [r for r in group if r["mode"] == "closed"]
        out.append({
            "preset": key[0], "size": key[1], "model": key[2], "calibration": key[3],
            "tasks": len({r["task"] for r in group}), "planned": len(open_),
            "rms_deg": _mean(r["rms_mean"] for r in open_),
            "max_deg": _mean(r["max"] for r in open_),
            "end_deg": _mean(r["end_max"] for r in open_),
            "goal_rms_deg": _mean(r["goal_rms"] for r in open_),
            "goal_end_deg": _mean(r["goal_end"] for r in open_),
            "open_goal_pct": _pct(r["success"] for r in group if r["mode"] == "open"),
            "closed_success_pct": _pct(r["success"] for r in closed) if closed else None,
            "closed_replans": _mean(r["replans"] for r in closed) if closed else None,
            "closed_sim_s": _mean(r["sim_s"] for r in closed) if closed else None,
            "closed_wall_s": _mean(r["wall_s"] for r in closed) if closed else None,
        })
    return out


def _mean(xs: Any) -> float | None:
    v = [x for x in xs if x is not None]
    return round(sum(v) / len(v), 2) if v else None


def _pct(xs: Any) -> float | None:
    v = list(xs)
    return round(100.0 * sum(bool(x) for x in v) / len(v), 1) if v else None
