"""ENHSP, the Java PDDL+ planner, as a backend (the jar shipped by the PyPI package up-enhsp).

The jar is located with ``importlib.util.find_spec`` so unified-planning is never imported.
Default settings are ENHSP's own (delta 1.0 for planning, execution, validation and heuristic);
``delta`` overrides all four (``-delta``), e.g. 0.1.
"""

from __future__ import annotations

import importlib.util
import re
import shutil
from pathlib import Path

from artiplan.backends.base import BackendResult, Planner, PlanStatus
from artiplan.backends.convert import plan_from_enhsp
from artiplan.backends.runner import TIMEOUT_MESSAGES, Limits, RunOutcome, run_limited
from artiplan.errors import ExternalToolError

#: Share of the memory limit given to the JVM heap (-Xmx); the rest is the JVM's own memory
#: (metaspace, code cache, threads). The RSS poll enforces the limit itself.
HEAP_SHARE = 0.75


def enhsp_jar() -> Path:
    """Path of ``enhsp.jar`` inside the installed up-enhsp package.

    Raises:
        ExternalToolError: up-enhsp is not installed or has no jar.
    """
    spec = importlib.util.find_spec("up_enhsp")
    if spec is None or not spec.submodule_search_locations:
        raise ExternalToolError(
            "ENHSP not found: the Python package 'up-enhsp' is not installed "
            "(pip install up-enhsp)"
        )
    jar = Path(next(iter(spec.submodule_search_locations))) / "ENHSP" / "enhsp.jar"
    if not jar.is_file():
        raise ExternalToolError(f"ENHSP not found: {jar} does not exist (reinstall up-enhsp)")
    return jar


def java_program() -> str:
    """The ``java`` executable. Raises ExternalToolError when Java is not installed."""
    java = shutil.which("java")
    if java is None:
        raise ExternalToolError(
            "ENHSP needs Java (17 or newer) but 'java' is not on PATH "
            "(e.g. apt-get install openjdk-17-jre-headless)"
        )
    return java


class EnhspPlanner(Planner):
    """ENHSP with its default settings, or with one ``delta`` for every discretisation."""

    def __init__(self, delta: float | None = None, name: str = "enhsp") -> None:
        self.delta = delta
        self.name = name

    def check_available(self) -> None:
        java_program()
        enhsp_jar()

    def command(self, domain: Path, problem: Path, memory_limit: float | None) -> list[str]:
        """The java command line; ``-Xmx`` keeps the heap under the memory limit."""
        cmd = [java_program()]
        if memory_limit is not None:
            cmd.append(f"-Xmx{max(32, int(memory_limit * HEAP_SHARE))}m")
        cmd += ["-jar", str(enhsp_jar()), "-o", str(domain), "-f", str(problem)]
        if self.delta is not None:
            cmd += ["-delta", repr(self.delta)]
        return cmd

    def solve(
        self,
        domain_path: str | Path,
        problem_path: str | Path,
        *,
        time_limit: float | None = None,
        memory_limit: float | None = None,
    ) -> BackendResult:
        cmd = self.command(Path(domain_path).resolve(), Path(problem_path).resolve(), memory_limit)
        outcome = run_limited(cmd, Limits(time_limit=time_limit, memory_limit=memory_limit))
        return _result(outcome)


_PLAN_BLOCK = re.compile(r"Found Plan:\n(.*?)\n\s*\n", re.S)


def _status(outcome: RunOutcome, text: str) -> tuple[PlanStatus, str]:
    """ENHSP's verdict from its exit and output."""
    if outcome.limit_hit in ("time", "wall"):
        return PlanStatus.TIMEOUT, TIMEOUT_MESSAGES[outcome.limit_hit]
    if outcome.limit_hit == "memory" or "OutOfMemoryError" in text:
        return PlanStatus.MEMOUT, "memory limit reached"
    if "Problem Solved" in text and "Found Plan" in text:
        return PlanStatus.SOLVED, ""
    if "Problem unsolvable" in text or "Unsolvable Problem" in text:
        return PlanStatus.UNSOLVABLE_PROVEN, "ENHSP: problem unsolvable"
    exc = re.search(r"^(?:Exception in thread.*|.*(?:Exception|Error): .*)$", text, re.M)
    reason = exc.group(0).strip() if exc else f"ENHSP exited with {outcome.returncode}"
    return PlanStatus.ERROR, reason


def _result(outcome: RunOutcome) -> BackendResult:
    text = outcome.stdout + ("\n" + outcome.stderr if outcome.stderr else "")
    status, message = _status(outcome, text)
    plan = None
    plan_text = ""
    moved = 0
    if status is PlanStatus.SOLVED:
        block = _PLAN_BLOCK.search(outcome.stdout + "\n\n")
        plan_text = block.group(1) if block else ""
        try:
            plan, moved = plan_from_enhsp("Found Plan:\n" + plan_text)
        except Exception as exc:  # an unreadable plan is the planner's error, not ours
            status, message = PlanStatus.ERROR, f"cannot read ENHSP's plan: {exc}"
    return BackendResult(
        status=status, plan=plan, cpu_s=outcome.cpu_s, wall_s=outcome.wall_s,
        peak_mb=outcome.peak_mb, raw_output=text, plan_text=plan_text,
        returncode=outcome.returncode, message=message,
        # ENHSP prints "Problem Solved" only after re-simulating the extracted plan with its
        # execution delta and reaching the goal: its own (discretised) validation.
        extra={"enhsp_accepts": status is PlanStatus.SOLVED, "shifted_actions": moved},
    )
