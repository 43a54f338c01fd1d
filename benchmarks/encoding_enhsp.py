"""ENHSP on the generated suite: does it parse, search and find plans, per model?

Runs the ENHSP jar (PyPI up-enhsp) with its default settings on the first tasks of the smallest
sizes of a freshly written suite, and checks each plan it prints with artiplan's validator (VAL
semantics, tolerance 0.001). Usage:

    .venv/bin/python benchmarks/encoding_enhsp.py [--sizes 3,4] [--tasks 5] [--timeout 30]

Prints one Markdown table row per run. Bounded: every run has a wall-clock timeout.
"""

from __future__ import annotations

import argparse
import importlib.util
import re
import subprocess
import tempfile
import time
from pathlib import Path

from artiplan.encoding import write_suite
from artiplan.pddl import load_task
from artiplan.semantics import validate
from artiplan.semantics.plan import Plan, TimedAction
from artiplan.semantics.plan_io import parse_enhsp_output

MODELS = ["ng", "ucm-0.1", "ucm-0.5", "ucm-1.0", "uacm-0.1", "uacm-0.5"]


def enhsp_jar() -> Path:
    spec = importlib.util.find_spec("up_enhsp")
    assert spec is not None and spec.submodule_search_locations
    return Path(next(iter(spec.submodule_search_locations))) / "ENHSP" / "enhsp.jar"


def run_one(domain: Path, problem: Path, timeout: float) -> tuple[str, float, str]:
    start = time.monotonic()
    try:
        proc = subprocess.run(
            ["java", "-jar", str(enhsp_jar()), "-o", str(domain), "-f", str(problem), "-pt"],
            capture_output=True,
            text=True,
            timeout=timeout,
        )
    except subprocess.TimeoutExpired:
        return "timeout", time.monotonic() - start, ""
    wall = time.monotonic() - start
    out = proc.stdout + proc.stderr
    if "Exception" in out:
        return "exception", wall, out
    if "Problem Solved" in out:
        return "solved", wall, out
    if "unsolvable" in out.lower():
        return "unsolvable", wall, out
    return "no-plan", wall, out


_STEP = re.compile(r"\((\d+(?:\.\d+)?),\(([^()]*)\)\)")


def simulated_plan(out: str, events: set[str], delta: float = 1.0) -> Plan | None:
    """The plan from ENHSP's ``Plan under Validation/Simulation`` line (printed with ``-pt``).

    ENHSP's ``-----waiting---- [t]`` lines misstate the last wait of some plans (``[0]`` after
    seven one-second waits); this line lists every step, so the end is the last wait + delta.
    """
    line = next((x for x in out.splitlines() if x.startswith("Plan under Validation")), None)
    if line is None:
        return None
    actions, end = [], 0.0
    for t, body in _STEP.findall(line):
        name, *args = body.split()
        if name.startswith("------>"):
            end = float(t) + delta
        elif name not in events:
            actions.append(TimedAction(float(t), name, tuple(args)))
            end = max(end, float(t))
    return Plan(tuple(actions), (), end)


def check_plan(domain: Path, problem: Path, out: str) -> str:
    """Validate ENHSP's plan under VAL's semantics.

    As conventions.md asks, actions ENHSP puts at one instant (stop X, start Y) are spread
    0.001 s apart in their order; an ``observe`` ends the plan at ENHSP's end time.
    """
    events = set(re.findall(r"\(:event (\S+)", domain.read_text()))
    plan = simulated_plan(out, events) or parse_enhsp_output(out)
    actions: list[TimedAction] = []
    for a in plan.actions:
        t = a.time
        if actions and t <= actions[-1].time + 1e-9:
            t = actions[-1].time + 0.001
        actions.append(TimedAction(t, a.name, a.args))
    end = plan.end if plan.end is not None else 0.0
    end = max(end, actions[-1].time if actions else 0.0) + 0.001
    actions.append(TimedAction(end, "observe"))
    report = validate(load_task(domain, problem), Plan(tuple(actions), (), None))
    return "valid" if report.valid else f"invalid ({report.kind}: {report.reason[:70]})"


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--sizes", default="3")
    ap.add_argument("--tasks", type=int, default=5)
    ap.add_argument("--timeout", type=float, default=30.0)
    ap.add_argument("--models", default=",".join(MODELS))
    args = ap.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        root = Path(tmp)
        write_suite(root, seed=0)
        print("| model | problem | ENHSP | wall [s] | plan under VAL semantics |")
        print("|---|---|---|---|---|")
        for model in args.models.split(","):
            for size in (int(s) for s in args.sizes.split(",")):
                for task in range(1, args.tasks + 1):
                    domain = root / model / "domain.pddl"
                    problem = root / model / f"p{size}-{task}.pddl"
                    status, wall, out = run_one(domain, problem, args.timeout)
                    verdict = check_plan(domain, problem, out) if status == "solved" else "-"
                    print(f"| {model} | p{size}-{task} | {status} | {wall:.1f} | {verdict} |")


if __name__ == "__main__":
    main()
