"""Benchmark: simulate / validate a 20-happening plan on the suite's problems; median of runs.

Usage: .venv/bin/python benchmarks/semantics_sim.py [--runs 15] [--sizes 4,12]
The plan: 10 rotations (start at t, stop 1.7 s later, 0.5 s apart) over joints and planes in
turn, so angles wrap (events), gravity switches on and off with the held link (UCM/UACM), and
the trajectory has tens of critical instants. Prints one Markdown row per (size, model).
The bar (issue 3): simulating a 20-happening plan under 0.1 s.
"""

from __future__ import annotations

import argparse
import statistics
import time

from artiplan.encoding import SUITE_MODELS, domain_pddl, make_task, problem_pddl
from artiplan.model import ArticulatedObject
from artiplan.pddl import load_task
from artiplan.semantics import Plan, TimedAction, simulate, validate


def twenty_happenings(n_links: int) -> Plan:
    """Ten start/stop pairs on joints L1-L2, L2-L3, ... (cycled), both planes alternately."""
    actions = []
    t = 0.0
    for k in range(10):
        j = 1 + k % (n_links - 1)
        plane = "z-axis" if k % 2 else "xy-axes"
        sign = "increase" if k % 3 else "decrease"
        args = (f"L{j}", f"L{j + 1}", plane)
        actions.append(TimedAction(round(t, 6), f"start-{sign}", args))
        actions.append(TimedAction(round(t + 1.7, 6), f"stop-{sign}", args))
        t += 2.2
    return Plan(tuple(actions))


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--runs", type=int, default=15)
    ap.add_argument("--sizes", default="4,12")
    args = ap.parse_args()
    print("| links | model | happenings | events | flow segments | simulate median wall [s] | "
          "simulate median CPU [s] | validate median wall [s] | max wall [s] |")
    print("|---|---|---|---|---|---|---|---|---|")
    for size in (int(s) for s in args.sizes.split(",")):
        st = make_task(size, 1)
        obj = ArticulatedObject(size)
        plan = twenty_happenings(size)
        for label, options in SUITE_MODELS:
            task = load_task(
                domain_pddl(None, options),
                problem_pddl(obj, st.initial, st.target, options, "threshold", seed=st.seed),
            )
            sim, cpu, val = [], [], []
            for _ in range(args.runs):
                c0, t0 = time.process_time(), time.perf_counter()
                traj = simulate(task, plan)
                c1, t1 = time.process_time(), time.perf_counter()
                validate(task, plan)
                t2 = time.perf_counter()
                sim.append(t1 - t0)
                cpu.append(c1 - c0)
                val.append(t2 - t1)
            print(f"| {size} | {label} | {len(plan)} | {len(traj.events)} | "
                  f"{len(traj.segments)} | {statistics.median(sim):.4f} | "
                  f"{statistics.median(cpu):.4f} | {statistics.median(val):.4f} | "
                  f"{max(max(sim), max(val)):.4f} |")


if __name__ == "__main__":
    main()
