"""artiplan's own planner as a backend: ``python -m artiplan plan`` in a child process.

Run as a separate process like the external planners, so isolation, limits and measurements are
the same for all. The command's exit code is its verdict (shared/docs/conventions.md).
"""

from __future__ import annotations

import os
import sys
import tempfile
from pathlib import Path

from artiplan.backends.base import BackendResult, Planner, PlanResult, PlanStatus
from artiplan.backends.convert import plan_from_val
from artiplan.backends.runner import TIMEOUT_MESSAGES, Limits, run_limited
from artiplan.errors import ExitCode

_EXIT_STATUS = {
    ExitCode.OK: PlanStatus.SOLVED,
    ExitCode.UNSOLVABLE: PlanStatus.UNSOLVABLE_PROVEN,
    ExitCode.NO_PLAN: PlanStatus.NO_PLAN,
    ExitCode.TIME_LIMIT: PlanStatus.TIMEOUT,
    ExitCode.MEMORY_LIMIT: PlanStatus.MEMOUT,
}


class ArtiplanPlanner(Planner):
    """artiplan's exact-time PDDL+ planner (``artiplan plan``), run in a child process."""

    name = "artiplan"

    def command(
        self, domain: Path, problem: Path, plan_file: Path,
        time_limit: float | None, memory_limit: float | None,
    ) -> list[str]:
        """The command line of the child: the same Python, ``-m artiplan plan``."""
        cmd = [sys.executable, "-m", "artiplan", "plan", str(domain), str(problem),
               "-o", str(plan_file)]
        if time_limit is not None:
            # The command limits wall time too; on a shared machine that would stop it before
            # its CPU time is used up. Give it our wall watchdog; the runner's CPU limit rules.
            wall = Limits(time_limit=time_limit).wall_cap or time_limit
            cmd += ["--time-limit", f"{wall:g}"]
        if memory_limit is not None:
            cmd += ["--memory-limit", f"{memory_limit:g}"]
        return cmd

    def plan(
        self, domain: str, problem: str, *, time_limit: float | None = None,
        memory_limit: float | None = None,
    ) -> PlanResult:
        """In-process (no start-up, no files): :func:`artiplan.search.api.plan`."""
        from artiplan.search.api import plan

        return plan(domain, problem, time_limit=time_limit, memory_limit=memory_limit)

    def solve(
        self,
        domain_path: str | Path,
        problem_path: str | Path,
        *,
        time_limit: float | None = None,
        memory_limit: float | None = None,
    ) -> BackendResult:
        with tempfile.TemporaryDirectory(prefix="artiplan-bench-") as tmp:
            plan_file = Path(tmp) / "plan.txt"
            cmd = self.command(
                Path(domain_path).resolve(), Path(problem_path).resolve(), plan_file,
                time_limit, memory_limit,
            )
            env = dict(os.environ, PYTHONHASHSEED="0")  # repeatable runs
            outcome = run_limited(
                cmd, Limits(time_limit=time_limit, memory_limit=memory_limit), env=env
            )
            plan_text = plan_file.read_text() if plan_file.is_file() else ""
        text = outcome.stdout + ("\n" + outcome.stderr if outcome.stderr else "")
        if outcome.limit_hit in ("time", "wall"):
            status, message = PlanStatus.TIMEOUT, TIMEOUT_MESSAGES[outcome.limit_hit]
        elif outcome.limit_hit == "memory":
            status, message = PlanStatus.MEMOUT, "memory limit reached"
        else:
            status = _EXIT_STATUS.get(outcome.returncode, PlanStatus.ERROR)  # type: ignore[call-overload]
            message = "" if status is PlanStatus.SOLVED else text.strip()[-300:]
        plan = None
        if status is PlanStatus.SOLVED:
            try:
                plan = plan_from_val(plan_text)
            except Exception as exc:  # an unreadable plan is the planner's error
                status, message = PlanStatus.ERROR, f"cannot read artiplan's plan: {exc}"
        return BackendResult(
            status=status, plan=plan, cpu_s=outcome.cpu_s, wall_s=outcome.wall_s,
            peak_mb=outcome.peak_mb, raw_output=text, plan_text=plan_text,
            returncode=outcome.returncode, message=message,
        )
