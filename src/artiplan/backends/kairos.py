"""Kairos (PyPI ``kairos-planner``), a C++ PDDL+ planner, as a backend.

Run as ``kairos solve DOMAIN PROBLEM --threads 1 --no-anytime``: one thread (the runs compare CPU
time, and the machine is shared) and the first plan only (as ENHSP and artiplan stop at their
first plan). Kairos's exit codes: 0 solved, 10 unsolvable (proved), 11 timeout, 12 memory,
13 unsupported, 14 no plan found, 2 invalid input, 1 internal error.
"""

from __future__ import annotations

import math
import shutil
import sys
from pathlib import Path

from artiplan.backends.base import BackendResult, Planner, PlanStatus
from artiplan.backends.convert import plan_from_ipc
from artiplan.backends.runner import TIMEOUT_MESSAGES, Limits, run_limited
from artiplan.errors import ExternalToolError

_EXIT_STATUS = {
    0: PlanStatus.SOLVED,
    10: PlanStatus.UNSOLVABLE_PROVEN,
    11: PlanStatus.TIMEOUT,
    12: PlanStatus.MEMOUT,
    14: PlanStatus.NO_PLAN,
}



def kairos_program() -> str:
    """The ``kairos`` executable: on PATH, or next to the running Python (a venv's bin/).

    Raises:
        ExternalToolError: kairos-planner is not installed.
    """
    found = shutil.which("kairos") or shutil.which("kairos", path=str(Path(sys.executable).parent))
    if found is None:
        raise ExternalToolError(
            "Kairos not found: no 'kairos' command on PATH (pip install kairos-planner)"
        )
    return found


class KairosPlanner(Planner):
    """Kairos with one thread, stopping at its first plan."""

    name = "kairos"

    def check_available(self) -> None:
        kairos_program()

    def command(
        self, domain: Path, problem: Path, time_limit: float | None, memory_limit: float | None
    ) -> list[str]:
        """The kairos command line; its own limits sit above ours, which are enforced."""
        cmd = [kairos_program(), "solve", str(domain), str(problem), "--threads", "1",
               "--no-anytime", "--format", "ipc"]
        if time_limit is not None:
            # Kairos's --timeout is wall-clock time; on a shared machine it would stop the search
            # long before our CPU-time limit. Set it at our wall watchdog; the CPU limit rules.
            wall = Limits(time_limit=time_limit).wall_cap or time_limit
            cmd += ["--timeout", str(math.ceil(wall))]
        if memory_limit is not None:
            cmd += ["--memory", str(int(memory_limit))]
        return cmd

    def solve(
        self,
        domain_path: str | Path,
        problem_path: str | Path,
        *,
        time_limit: float | None = None,
        memory_limit: float | None = None,
    ) -> BackendResult:
        cmd = self.command(
            Path(domain_path).resolve(), Path(problem_path).resolve(), time_limit, memory_limit
        )
        outcome = run_limited(cmd, Limits(time_limit=time_limit, memory_limit=memory_limit))
        text = outcome.stdout + ("\n" + outcome.stderr if outcome.stderr else "")
        if outcome.limit_hit in ("time", "wall"):
            status, message = PlanStatus.TIMEOUT, TIMEOUT_MESSAGES[outcome.limit_hit]
        elif outcome.limit_hit == "memory":
            status, message = PlanStatus.MEMOUT, "memory limit reached"
        else:
            status = _EXIT_STATUS.get(outcome.returncode, PlanStatus.ERROR)
            message = "" if status is PlanStatus.SOLVED else _last_line(outcome.stderr)
        plan = None
        moved = 0
        plan_text = outcome.stdout if status is PlanStatus.SOLVED else ""
        if status is PlanStatus.SOLVED:
            try:
                plan, moved = plan_from_ipc(plan_text)
            except Exception as exc:  # an unreadable plan is the planner's error, not ours
                status, message = PlanStatus.ERROR, f"cannot read Kairos's plan: {exc}"
        return BackendResult(
            status=status, plan=plan, cpu_s=outcome.cpu_s, wall_s=outcome.wall_s,
            peak_mb=outcome.peak_mb, raw_output=text, plan_text=plan_text,
            returncode=outcome.returncode, message=message, extra={"shifted_actions": moved},
        )


def _last_line(text: str) -> str:
    lines = [line for line in text.strip().splitlines() if line.strip()]
    return lines[-1][:300] if lines else ""
