"""Closed-loop success rate over seeded tasks (issue 7's bar), written as JSON Lines + summary.

Usage: .venv/bin/python benchmarks/execution_loop.py [--tasks 20] [--links 4] [--model ucm]
       [--preset stiff] [--hands virtual] [--intervene] [--plan-tol 1.5]
       [--approach 1.0] [--start 1] [--logs DIR] -o FILE.jsonl
``--approach S`` (Baxter): the arms move to each grasp in S simulated seconds; the reach time is
then measured on the simulated Baxter (``measure_reach``) and used as the encodings'
``reach_time`` (unless ``--reach-time`` is given).
The intervention: at 40% of the first plan's makespan a human turns L3 by +20 deg on z-axis.
"""

from __future__ import annotations

import argparse
import json
import statistics
import time
from dataclasses import replace
from pathlib import Path


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--tasks", type=int, default=20)
    ap.add_argument("--links", type=int, default=4)
    ap.add_argument("--model", default="ucm")
    ap.add_argument("--preset", default="stiff")
    ap.add_argument("--hands", default="virtual")
    ap.add_argument("--intervene", action="store_true")
    ap.add_argument("--plan-tol", type=float, default=None,
                    help="planning goal half-width [deg] (default: LoopConfig's)")
    ap.add_argument("--seed", type=int, default=7, help="suite seed of the tasks")
    ap.add_argument("--advance-latency", action="store_true")
    ap.add_argument("--reach-time", type=float, default=None)
    ap.add_argument("--approach", type=float, default=0.0,
                    help="Baxter arms approach their grasps in this many seconds")
    ap.add_argument("--no-compensate", action="store_true",
                    help="dispatch starts at their planned times (the approach delays them)")
    ap.add_argument("--fallback", default=None, choices=("ng", "ucm", "uacm", "none"),
                    help="the model the loop falls back to (default: LoopConfig's; none: keep)")
    ap.add_argument("--fallback-after", type=int, default=None,
                    help="switch to NG from this many re-plans on (default: LoopConfig's)")
    ap.add_argument("--fallback-scope", choices=("run", "plan"), default=None,
                    help="the fallback model stays for the run, or makes only the plans the "
                         "model in use finds none for (default: LoopConfig's)")
    ap.add_argument("--carry", choices=("rigid", "projected"), default="rigid",
                    help="the encodings' carry rule (EncodingOptions.carry)")
    ap.add_argument("--fall", choices=("uniform", "torque"), default="uniform",
                    help="UCM's fall speeds (EncodingOptions.fall)")
    ap.add_argument("--max-replans", type=int, default=None,
                    help="re-plan budget of a run (default: LoopConfig.budget, "
                         "5 up to 4 links, 8 on 6)")
    ap.add_argument("--no-monitor-ahead", action="store_true",
                    help="judge every offset, also those a turn ahead aligns away")
    ap.add_argument("--no-aim", action="store_true",
                    help="plans aim at the target itself, not off it by what plans that "
                         "ended short missed by (LoopConfig.aim)")
    ap.add_argument("--free-carry-replans", type=int, default=None,
                    help="re-plans after a carried link's error free of the budget "
                         "(default: LoopConfig's; 0: they count)")
    ap.add_argument("--free-refusals", type=int, default=None,
                    help="plans made again after a refusal free of the budget "
                         "(default: LoopConfig's)")
    ap.add_argument("--threshold", type=float, default=None,
                    help="the monitor's threshold on goal links [deg] (default: LoopConfig's)")
    ap.add_argument("--impact-stop", type=float, default=None, metavar="MM",
                    help="Baxter: stop a turn on an arm contact deeper than MM [mm] and "
                         "re-grasp (default: make_world's; 0: off)")
    ap.add_argument("--strain-stop", action="store_true",
                    help="Baxter: stop a turn when a hand's servo integral reaches its bound")
    ap.add_argument("--stall-deg", type=float, default=None,
                    help="a turn whose link lags it by this much [deg] when the monitor "
                         "fires is refused from there (default: LoopConfig's; 0: off)")
    ap.add_argument("--align-ahead", action="store_true",
                    help="a link ahead of its turn at the grasp is aligned on as far as the "
                         "turn has left, not only 15 deg (LoopConfig.align_ahead)")
    ap.add_argument("--max-turn", type=float, default=None,
                    help="plans first sought with turns of at most this [deg] (0: never; "
                         "default: LoopConfig's)")
    ap.add_argument("--start", type=int, default=1, help="first task index")
    ap.add_argument("--logs", type=Path, default=None,
                    help="also write each run's full log here as task-K.json (for diagnosis)")
    ap.add_argument("-o", "--out", type=Path, required=True)
    args = ap.parse_args()

    from artiplan.encoding import EncodingOptions
    from artiplan.encoding.suite import make_task
    from artiplan.execution import Intervention, LoopConfig, run_loop
    from artiplan.execution.calibrate import calibrate, measure_reach
    from artiplan.model import ArticulatedObject
    from artiplan.world import make_world

    obj = ArticulatedObject(args.links)
    cal = calibrate(make_world, obj, preset=args.preset)
    reach = args.reach_time
    if reach is None and args.approach > 0:
        reach = measure_reach(make_world, obj, preset=args.preset, approach_s=args.approach)
        print(f"measured reach time on the simulated Baxter: {reach} s", flush=True)
    enc = EncodingOptions(args.model, speed_g=round(cal.speed_g, 3),
                          acceleration=round(cal.acceleration, 3), reach_time=reach,
                          carry=args.carry, fall=args.fall)
    ivs = (Intervention(0.0, "L3", "z-axis", 20.0, fraction=0.4),) if args.intervene else ()
    config = LoopConfig(encoding=enc, interventions=ivs,
                        advance_latency=args.advance_latency,
                        compensate_approach=not args.no_compensate)
    if args.plan_tol is not None:
        config = replace(config, plan_tolerance_deg=args.plan_tol)
    if args.fallback is not None:
        config = replace(config, fallback_model=None if args.fallback == "none" else args.fallback)
    if args.fallback_after is not None:
        config = replace(config, fallback_after=args.fallback_after)
    if args.fallback_scope is not None:
        config = replace(config, fallback_scope=args.fallback_scope)
    if args.no_monitor_ahead:
        config = replace(config, monitor_ahead=False)
    if args.no_aim:
        config = replace(config, aim=False)
    if args.max_turn is not None:
        config = replace(config, max_turn_deg=args.max_turn or None)
    if args.free_carry_replans is not None:
        config = replace(config, free_carry_replans=args.free_carry_replans)
    if args.free_refusals is not None:
        config = replace(config, free_refusals=args.free_refusals)
    if args.threshold is not None:
        config = replace(config, threshold_deg=args.threshold)
    if args.stall_deg is not None:
        config = replace(config, stall_deg=args.stall_deg or None)
    if args.align_ahead:
        config = replace(config, align_ahead=True)
    if args.max_replans is not None:
        config = replace(config, max_replans=args.max_replans)
    impact = {} if args.impact_stop is None else {
        "impact_stop_m": args.impact_stop / 1000.0 if args.impact_stop > 0 else None}
    rows = []
    args.out.parent.mkdir(parents=True, exist_ok=True)
    with args.out.open("a" if args.start > 1 else "w") as fh:
        for k in range(args.start, args.start + args.tasks):
            task = make_task(args.links, k, seed=args.seed)
            world = make_world(obj, task.initial, preset=args.preset, hands=args.hands, seed=k,
                               approach_s=args.approach,
                               strain_stop=args.strain_stop, **impact)
            t0 = time.perf_counter()
            log = run_loop(world, task.target, config, seed=task.seed)
            row = {"schema": "artiplan.execution-bench/1", "task": k, "success": log.success,
                   "replans": len(log.replans), "interventions": len(log.interventions),
                   "reasons": [r["reason"] for r in log.replans],
                   "refusals": len(log.refusals),
                   "carry_replans": len(log.carry_replans),
                   "regrasps": sum(h["ok"] for h in log.happenings
                                   if h["action"].endswith("resumed")),
                   "impact_stops": sum(h["action"].endswith("stopped")
                                       for h in log.happenings),
                   "stalls": sum("stalled" in r["reason"]
                                 for r in log.replans + log.refusals),
                   "collisions": len(log.collisions),
                   "latency_wall_s": [r["latency_wall_s"] for r in log.replans],
                   "sim_s": round(log.final["time"] if log.final.get("error")
                                  else world.time, 3),
                   "wall_s": round(time.perf_counter() - t0, 3),
                   "max_goal_error": log.final.get("max_goal_error"),
                   "error": log.final.get("error"),
                   "hands": world.hands.kind, "model": args.model, "preset": args.preset,
                   "approach_s": args.approach, "reach_time": reach,
                   "compensate": not args.no_compensate, "carry": args.carry, "fall": args.fall,
                   "max_replans": config.budget(args.links), "monitor_ahead": config.monitor_ahead,
                   "fallback": config.fallback_model,
                   "fallback_scope": config.fallback_scope, "fallback_after": config.fallback_after,
                   "max_turn_deg": config.max_turn_deg,
                   "aim": config.aim, "free_carry_replans": config.free_carry_replans,
                   "free_refusals": config.free_refusals, "threshold": config.threshold_deg,
                   "impact_stop_mm": None if world.config.impact_stop_m is None
                   else 1000.0 * world.config.impact_stop_m,
                   "strain_stop": world.config.strain_stop, "stall_deg": config.stall_deg,
                   "align_ahead": config.align_ahead}
            rows.append(row)
            if args.logs is not None:
                args.logs.mkdir(parents=True, exist_ok=True)
                log.save(args.logs / f"task-{k}.json")
            fh.write(json.dumps(row) + "\n")
            fh.flush()  # a run stopped early keeps its finished tasks
            print(json.dumps(row), flush=True)
    lat = [x for r in rows for x in r["latency_wall_s"]]
    print(f"success {sum(r['success'] for r in rows)}/{len(rows)}, re-plans mean "
          f"{statistics.mean(r['replans'] for r in rows):.2f} max "
          f"{max(r['replans'] for r in rows)}, refusals planned around "
          f"{sum(r['refusals'] for r in rows)}, plans again after a carried link's error "
          f"{sum(r['carry_replans'] for r in rows)}, turns resumed by a re-grasp "
          f"{sum(r['regrasps'] for r in rows)}, interventions applied "
          f"{sum(r['interventions'] for r in rows)}, re-plan latency median "
          f"{statistics.median(lat) if lat else float('nan'):.3f} s max "
          f"{max(lat) if lat else float('nan'):.3f} s, calibrated speed-g {enc.speed_g} "
          f"acceleration {enc.acceleration}")


if __name__ == "__main__":
    main()
