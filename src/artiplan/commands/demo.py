"""``artiplan demo``: the paper's illustrative example, closed loop, on built-in defaults.

A 4-link object in the simulated world, a target from a fixed seed, the UCM model with
``speed-g`` identified from the physics, ``window`` goals; plans with artiplan's planner,
prints the plan as the paper's Fig. 6 does, executes it with the hands while monitoring the
prediction, re-plans when needed. Writes to ``-o DIR`` (default ``demo-out/``): the run log and
its JSON Schema, the plans, a plot of predicted vs perceived angles, snapshots at every action
(``snapshots/`` and ``snapshots.png``), an animation from the overhead camera
(``animation.gif``) and, under ``encodings/``, the three PDDL+ encodings of the example.
"""

from __future__ import annotations

import argparse
import os
import random
import time
from pathlib import Path
from typing import Any

from artiplan.errors import ExternalToolError, UsageError

DEMO_LINKS = 4
DEMO_SEED = 1
#: The scripted human intervention of ``--intervene``: (link, plane, angle [deg], when as a
#: fraction of the first plan's makespan).
INTERVENTION = ("L3", "z-axis", 25.0, 0.3)
#: Seconds Baxter's arms take to move to a grasp (simulated); the reach time is measured from it.
APPROACH_S = 1.0


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("-o", "--out", type=Path, default=Path("demo-out"),
                        help="output folder (default demo-out)")
    parser.add_argument("--intervene", action="store_true",
                        help=f"a human pushes {INTERVENTION[0]} by {INTERVENTION[2]:g} deg on "
                             f"{INTERVENTION[1]} at {100 * INTERVENTION[3]:.0f}%% of the first "
                             "plan")
    parser.add_argument("--model", choices=("ng", "ucm", "uacm"), default="ucm")
    parser.add_argument("--links", type=int, default=DEMO_LINKS, help="links (default 4)")
    parser.add_argument("--hands", choices=("baxter", "virtual"), default=None,
                        help="baxter (default up to 6 links; longer objects: virtual hands, "
                             "with a warning; falls back to virtual hands if unavailable)")
    parser.add_argument("--preset", choices=("stiff", "loose"), default="stiff")
    parser.add_argument("--seed", type=int, default=DEMO_SEED, help="configuration seed")
    parser.add_argument("--goal", choices=("window", "threshold"), default="window",
                        help="goal style (default window: goal links within 5 deg)")
    parser.add_argument("--reach-time", type=float, default=None,
                        help="seconds between a release and the next grasp, modelled in PDDL+ "
                             "(default: measured on the simulated Baxter; virtual hands or "
                             "--no-approach: none)")
    parser.add_argument("--approach", type=float, default=APPROACH_S,
                        help=f"seconds Baxter's arms take to move to a grasp (default "
                             f"{APPROACH_S:g}; the reach time is measured with it)")
    parser.add_argument("--no-approach", action="store_true",
                        help="Baxter's arms jump to their grasps (no reach time)")
    parser.add_argument("--carry", choices=("rigid", "projected"), default="rigid",
                        help="how vertical turns move carried links in the plans: rigid (the "
                             "paper, default) or projected (see docs/encodings.md)")
    parser.add_argument("--no-animation", action="store_true",
                        help="skip camera frames (no OpenGL needed)")


def run(args: argparse.Namespace) -> int:
    if not 3 <= args.links <= 12:
        raise UsageError("--links must be between 3 and 12")
    if args.reach_time is not None and args.reach_time < 0:
        raise UsageError("--reach-time must be >= 0")
    if args.approach < 0:
        raise UsageError("--approach must be >= 0")
    os.environ.setdefault("MUJOCO_GL", "egl")  # before MuJoCo is imported
    out: Path = args.out
    out.mkdir(parents=True, exist_ok=True)
    from artiplan.encoding.suite import random_pair
    from artiplan.model import ArticulatedObject

    obj = ArticulatedObject(args.links)
    limit_note = _choose_hands(args)
    init, target = random_pair(obj.n_links, random.Random(args.seed))
    written = _write_encodings(out / "encodings", obj, init, target, args.seed)
    world, hands_note = _make_world(obj, init, args)
    config, calib_note = _loop_config(obj, world, args)
    print(f"artiplan demo: {obj.n_links}-link object, seed {args.seed}, model "
          f"{args.model.upper()}, preset {args.preset}, hands {world.hands.kind}")
    for note in (limit_note, hands_note, calib_note):
        if note:
            print(note)
    written += _execute(out, world, target, config, args, hands_note)
    for path in written:
        print(f"  wrote {path}")
    return 0


def _write_encodings(folder: Path, obj: Any, init: Any, target: Any, seed: int) -> list[Path]:
    """The foundation's demo output: three encodings, one problem each, and drawings."""
    from artiplan.encoding import EncodingOptions, domain_pddl, problem_pddl
    from artiplan.viz.draw import draw_configuration

    folder.mkdir(parents=True, exist_ok=True)
    written = [folder / "initial.json", folder / "target.json"]
    init.save(written[0], obj)
    target.save(written[1], obj)
    for model in ("ng", "ucm", "uacm"):
        options = EncodingOptions(model, speed_g=0.5, acceleration=0.5)
        sub = folder / model
        sub.mkdir(exist_ok=True)
        (sub / "domain.pddl").write_text(domain_pddl(obj, options))
        (sub / "problem.pddl").write_text(
            problem_pddl(obj, init, target, options, seed=seed, name="demo"))
        written += [sub / "domain.pddl", sub / "problem.pddl"]
    written.append(draw_configuration(obj, init, folder / "initial.png", target=target,
                                      title="demo: initial (solid) and target (ghost)"))
    written.append(draw_configuration(obj, target, folder / "target.png", title="demo: target"))
    return written


def _choose_hands(args: argparse.Namespace) -> str:
    """Baxter up to the lengths it serves: asked for beyond them, a usage error (exit 2);
    by default there, virtual hands and a warning (returned)."""
    from artiplan.world.baxter_model import BAXTER_MAX_LINKS

    if args.links <= BAXTER_MAX_LINKS:
        args.hands = args.hands or "baxter"
        return ""
    if args.hands == "baxter":
        raise UsageError(f"--hands baxter serves objects of up to {BAXTER_MAX_LINKS} links (a "
                         f"longer chain hangs below its reach); --links {args.links}: use "
                         "--hands virtual")
    if args.hands is None:
        args.hands = "virtual"
        return (f"!!! WARNING: Baxter serves objects of up to {BAXTER_MAX_LINKS} links; "
                f"running the {args.links}-link object with VIRTUAL hands. !!!")
    return ""


def _make_world(obj: Any, init: Any, args: argparse.Namespace) -> tuple[Any, str]:
    from artiplan.world import make_world

    if args.hands == "baxter":
        try:
            return make_world(obj, init, preset=args.preset, hands="baxter", seed=args.seed,
                              approach_s=_approach(args)), ""
        except (ImportError, ValueError, RuntimeError) as exc:
            note = ("!!! WARNING: Baxter arms are not available in this build "
                    f"({type(exc).__name__}: {exc}); running with VIRTUAL hands instead. !!!")
            return make_world(obj, init, preset=args.preset, hands="virtual",
                              seed=args.seed), note
    return make_world(obj, init, preset=args.preset, hands="virtual", seed=args.seed), ""


def _approach(args: argparse.Namespace) -> float:
    return 0.0 if args.no_approach else float(args.approach)


def _loop_config(obj: Any, world: Any, args: argparse.Namespace) -> tuple[Any, str]:
    from artiplan.encoding import EncodingOptions
    from artiplan.execution import Intervention, LoopConfig
    from artiplan.execution.calibrate import calibrate, measure_reach
    from artiplan.world import make_world

    calib = calibrate(make_world, obj, preset=args.preset)
    reach, how = args.reach_time, "given"
    approach = float(getattr(world.hands, "approach_s", 0.0) or 0.0)
    if reach is None and approach > 0:
        reach = measure_reach(make_world, obj, preset=args.preset, approach_s=approach)
        how = f"measured on the simulated Baxter, {approach:g} s approach"
    enc = EncodingOptions(args.model, speed_g=round(calib.speed_g, 3),
                          acceleration=round(calib.acceleration, 3), reach_time=reach,
                          carry=args.carry)
    link, plane, delta, fraction = INTERVENTION
    interventions = ((Intervention(0.0, link, plane, delta, fraction=fraction),)
                     if args.intervene else ())
    config = LoopConfig(encoding=enc, goal_style=args.goal, interventions=interventions)
    note = (f"calibrated from a release run: speed-g {enc.speed_g:g} deg/s (UCM), "
            f"acceleration {enc.acceleration:g} deg/s^2 (UACM); reach time "
            + (f"{reach:.2f} s ({how})" if reach is not None else "none (instant grasps)"))
    return config, note


def _execute(out: Path, world: Any, target: Any, config: Any, args: argparse.Namespace,
             hands_note: str) -> list[Path]:
    from artiplan.execution import ClosedLoop
    from artiplan.execution.runlog import write_schema
    from artiplan.viz.execution import FrameRecorder, contact_sheet, plot_run

    recorder = None
    if not args.no_animation:
        try:
            recorder = FrameRecorder(world, every=2)
        except Exception as exc:  # GL context failures surface as various exception types
            raise ExternalToolError(f"headless rendering failed ({exc}); try MUJOCO_GL=osmesa "
                                    "or --no-animation") from exc
    t0 = time.perf_counter()
    loop = ClosedLoop(world, target, config, progress=print, seed=args.seed,
                      observer=recorder.observe if recorder else None)
    log = loop.run()
    log.settings["note"] = hands_note
    print(f"done in {time.perf_counter() - t0:.1f} s wall, {world.time:.1f} s simulated: goal "
          f"{'REACHED' if log.success else 'NOT reached'}, {len(log.replans)} re-plan(s), "
          f"max goal-link error {log.final.get('max_goal_error', float('nan')):.1f} deg")
    written = [log.save(out / "run-log.json"), write_schema(out / "run-log.schema.json")]
    for p in log.plans:
        path = out / f"plan-{p['index']}.txt"
        path.write_text(f"; {p['reason']} (t = {p['start_time']} s)\n{p['text']}")
        written.append(path)
    written.append(plot_run(log.to_dict(), out / "angles.png"))
    if recorder is not None:
        shots = recorder.write_snapshots(out / "snapshots")
        written += shots
        if shots:
            written.append(contact_sheet(shots, out / "snapshots.png"))
        written.append(recorder.write_gif(out / "animation.gif"))
        recorder.close()
    return written
