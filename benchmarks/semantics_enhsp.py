"""Agreement between artiplan's validator (exact time, VAL rules) and ENHSP's own simulation.

ENHSP 0.1.1's ``-ival -inputplan`` flags are parsed but never used (its jar reads them into
fields nothing reads), so ENHSP cannot validate a plan given to it. What ENHSP does validate is
its own plan: with ``-pt`` it re-simulates the plan with its validation step (delta 1.0) and
saves the numeric state after every step (``*.npt``). This script runs ENHSP (``-pe -pt -sp``)
on small suite problems, validates the plan it writes with :func:`artiplan.semantics.validate`
(the ``@PlanEND`` time is where the goal is checked), and compares, at every ENHSP step, each
fluent of ENHSP's trace with our trajectory (angles compared on the circle), and the events.

    .venv/bin/python benchmarks/semantics_enhsp.py [--sizes 3,4] [--tasks 1,2] [--timeout 60]

Prints one Markdown row per run. Bounded: every ENHSP run has a wall-clock timeout.
"""

from __future__ import annotations

import argparse
import importlib.util
import re
import subprocess
import tempfile
import time
from pathlib import Path

from artiplan.encoding import SUITE_MODELS, domain_pddl, make_task, problem_pddl
from artiplan.model import ArticulatedObject
from artiplan.pddl import load_task
from artiplan.semantics import Plan, TimedAction, simulate, validate
from artiplan.semantics.plan_io import read_plan


def enhsp_jar() -> Path:
    spec = importlib.util.find_spec("up_enhsp")
    assert spec is not None and spec.submodule_search_locations
    return Path(next(iter(spec.submodule_search_locations))) / "ENHSP" / "enhsp.jar"


_PAIR = re.compile(r"(\([^()]*\))=(\S+)")


def read_trace(path: Path) -> list[dict[str, float]]:
    """ENHSP's numeric plan trace: one dict (fluent name -> value, and '(time)') per step."""
    out = []
    for line in path.read_text().splitlines():
        if "(time)=" not in line:
            continue
        out.append({name: float(v) for name, v in _PAIR.findall(line)})
    return out


def circular(a: float, b: float) -> float:
    d = abs(a - b) % 360.0
    return min(d, 360.0 - d)


def spaced(plan: Plan, eps: float = 0.001) -> Plan:
    """ENHSP's same-time actions are sequential; VAL's are parallel: space them ``eps`` apart
    in the order listed (the conventions' repair)."""
    out, last = [], None
    for a in plan.actions:
        t = a.time if last is None or a.time > last.time + 1e-9 else last.time + eps
        shifted = TimedAction(round(t, 6), a.name, a.args, a.duration)
        out.append(shifted)
        last = shifted
    return Plan(tuple(out), plan.events, plan.end)


def compare(task, traj, trace):  # type: ignore[no-untyped-def]
    """Largest difference [deg or units] between ENHSP's trace and our trajectory."""
    worst, where = 0.0, ""
    last_per_time = {step["(time)"]: step for step in trace}  # after the happenings at t
    for step in last_per_time.values():
        t = step["(time)"]
        ours = traj.values_at(t)
        for name, v in step.items():
            if name == "(time)":
                continue
            try:
                i = task.fluent_index(name)
            except KeyError:
                continue
            d = circular(v, ours[i]) if name.startswith("(angle") else abs(v - ours[i])
            if d > worst:
                worst, where = d, f"{name} at {t:g}"
    return worst, where


def run(domain: Path, problem: Path, timeout: float, workdir: Path):  # type: ignore[no-untyped-def]
    sp = workdir / "plan.sp"
    cmd = ["java", "-jar", str(enhsp_jar()), "-o", str(domain), "-f", str(problem),
           "-pe", "-pt", "-sp", str(sp)]
    t0 = time.monotonic()
    try:
        proc = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout, cwd=workdir)
    except subprocess.TimeoutExpired:
        return "timeout", time.monotonic() - t0, None, None
    wall = time.monotonic() - t0
    if "Problem Solved" not in proc.stdout or not sp.exists():
        status = "error" if "Exception" in proc.stdout + proc.stderr else "no plan"
        return status, wall, None, None
    traces = sorted(problem.parent.glob(problem.name + "*.npt"))
    return "solved", wall, sp, (traces[-1] if traces else None)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--sizes", default="3,4")
    ap.add_argument("--tasks", default="1,2")
    ap.add_argument("--models", default="ng,ucm-0.1,ucm-1.0,uacm-0.1,uacm-0.5")
    ap.add_argument("--timeout", type=float, default=60.0)
    args = ap.parse_args()
    models = dict(SUITE_MODELS)
    print("| problem | model | ENHSP | wall [s] | actions | end [s] | artiplan validate | "
          "events ENHSP / ours | max diff of ENHSP trace vs ours |")
    print("|---|---|---|---|---|---|---|---|---|")
    for size in (int(s) for s in args.sizes.split(",")):
        for k in (int(s) for s in args.tasks.split(",")):
            st = make_task(size, k)
            obj = ArticulatedObject(size)
            for label in args.models.split(","):
                opts = models[label]
                with tempfile.TemporaryDirectory() as tmp:
                    d, p = Path(tmp) / "domain.pddl", Path(tmp) / f"p{size}-{k}.pddl"
                    d.write_text(domain_pddl(None, opts))
                    p.write_text(problem_pddl(obj, st.initial, st.target, opts, "threshold",
                                              seed=st.seed))
                    status, wall, sp, npt = run(d, p, args.timeout, Path(tmp))
                    row = f"| p{size}-{k} | {label} | {status} | {wall:.1f} |"
                    if sp is None:
                        print(row + " | | | | |", flush=True)
                        continue
                    task = load_task(d, p)
                    plan = read_plan(sp, [e.name for e in task.events])
                    trace = read_trace(npt) if npt else []
                    # ENHSP's @PlanEND is sometimes short of the waiting its own trace does.
                    end = max([plan.end or 0.0, *(s["(time)"] for s in trace)])
                    if end != plan.end:
                        plan = Plan(plan.actions, plan.events, end)
                    report = validate(task, plan)
                    verdict = "valid" if report.valid else f"INVALID: {report.reason}"
                    if report.kind == "mutex":
                        plan = spaced(plan)
                        report = validate(task, plan)
                        verdict += "; spaced 0.001 s: " + (
                            "valid" if report.valid else f"INVALID: {report.reason}")
                    if not report.valid and report.kind == "goal":
                        # ENHSP's files drop the last wait step: try one more step (1 s).
                        later = validate(task, Plan(plan.actions, plan.events, end + 1.0))
                        verdict += f"; at end + 1 s: {'valid' if later.valid else 'invalid'}"
                    diff, where = compare(task, simulate(task, plan), trace)
                    print(f"{row} {len(plan.actions)} | {plan.end} | {verdict} | "
                          f"{len(plan.events)} / {len(report.events)} | {diff:.4f} ({where}) |",
                          flush=True)


if __name__ == "__main__":
    main()
