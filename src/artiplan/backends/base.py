"""The planner interface every backend implements, and the result it returns.

One small abstract class (:class:`Planner`) with one method (:meth:`Planner.solve`) returning a
small typed value (:class:`BackendResult`). Every backend runs its planner as a separate process
under the same limits (:mod:`artiplan.backends.runner`), so their numbers compare.
"""

from __future__ import annotations

import abc
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

from artiplan.semantics.results import PlanResult, PlanStatus

if TYPE_CHECKING:
    from artiplan.semantics.plan import Plan

def status_name(status: PlanStatus) -> str:
    """The short name of a status as written in result rows (``solved``, ``no-plan``, ...)."""
    return str(status.value)


@dataclass(frozen=True)
class BackendResult:
    """What one planner run produced.

    ``cpu_s``: CPU time of the planner process and its children [s] (user + system);
    ``wall_s``: elapsed time [s]; ``peak_mb``: peak resident memory of the process tree [MiB];
    ``plan``: the plan converted to artiplan's :class:`~artiplan.semantics.plan.Plan`, or None;
    ``plan_text``: the plan as the planner wrote it (its own format); ``raw_output``: the
    planner's stdout and stderr; ``extra``: backend-specific facts (e.g. ENHSP's own verdict).
    """

    status: PlanStatus
    plan: Plan | None
    cpu_s: float
    wall_s: float
    peak_mb: float
    raw_output: str = ""
    plan_text: str = ""
    returncode: int | None = None
    message: str = ""
    extra: dict[str, Any] = field(default_factory=dict)


class Planner(abc.ABC):
    """A planner that solves a PDDL+ problem given as two files.

    Subclasses set :attr:`name` and implement :meth:`solve`.
    """

    #: The name used on the command line (``--planners NAME``) and in result rows.
    name: str = ""

    @abc.abstractmethod
    def solve(
        self,
        domain_path: str | Path,
        problem_path: str | Path,
        *,
        time_limit: float | None = None,
        memory_limit: float | None = None,
    ) -> BackendResult:
        """Plan for the problem.

        Args:
            domain_path: PDDL+ domain file.
            problem_path: PDDL+ problem file.
            time_limit: CPU-time limit in [s] (None: none).
            memory_limit: memory limit in [MiB] (None: none).

        Raises:
            ExternalToolError: the planner's program is missing (exit code 9).
        """

    def check_available(self) -> None:  # noqa: B027 - optional hook, most planners need nothing
        """Raise :class:`~artiplan.errors.ExternalToolError` if the planner cannot run here."""

    def plan(
        self, domain: str, problem: str, *, time_limit: float | None = None,
        memory_limit: float | None = None,
    ) -> PlanResult:
        """Plan for PDDL+ text (what a closed loop needs): the plan, closed as VAL reads it,
        with the validator's trajectory of it (the prediction to monitor against).

        By default the text goes to :meth:`solve` through temporary files; a plan the
        validator rejects is reported as ``ERROR`` with the reason.
        """
        import tempfile

        from artiplan.backends.convert import close_at_end
        from artiplan.pddl import load_task
        from artiplan.semantics import validate

        with tempfile.TemporaryDirectory(prefix="artiplan-plan-") as tmp:
            d, p = Path(tmp) / "domain.pddl", Path(tmp) / "problem.pddl"
            d.write_text(domain)
            p.write_text(problem)
            res = self.solve(d, p, time_limit=time_limit, memory_limit=memory_limit)
        if res.status is not PlanStatus.SOLVED or res.plan is None:
            return PlanResult(res.status, message=res.message)
        task = load_task(domain, problem)
        found = close_at_end(res.plan, task)
        report = validate(task, found)
        if not report.valid:
            return PlanResult(PlanStatus.ERROR, message=f"{self.name}'s plan is invalid: "
                              f"{report.reason}")
        return PlanResult(PlanStatus.SOLVED, found, report.trajectory)
