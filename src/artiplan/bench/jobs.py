"""One benchmark job: a planner on a problem, its plan checked by artiplan's validator.

:func:`run_job` is the single job function shared by the local pool and the Dask cluster: it
takes a picklable :class:`Job` and returns one JSON-ready result row.
"""

from __future__ import annotations

import socket
from dataclasses import dataclass
from datetime import datetime, timezone
from typing import TYPE_CHECKING, Any

from artiplan.backends import get_planner, status_name
from artiplan.backends.base import BackendResult, PlanStatus
from artiplan.bench.results import SCHEMA
from artiplan.bench.suite import SuiteProblem

if TYPE_CHECKING:
    from artiplan.semantics.plan import Plan

#: VAL's tolerance, which the validator uses (shared/docs/stack.md).
TOLERANCE = 0.001


@dataclass(frozen=True)
class Job:
    """A planner on a problem with limits: CPU time [s] and memory [MiB]."""

    planner: str
    problem: SuiteProblem
    time_limit: float
    memory_limit: float


@dataclass(frozen=True)
class Verdict:
    """artiplan's validator on a plan: ``valid`` is None when the validator could not run."""

    valid: bool | None
    reason: str = ""


def check_plan(domain_path: str, problem_path: str, plan: Plan) -> Verdict:
    """Validate ``plan`` with artiplan's validator (VAL's semantics, tolerance 0.001)."""
    from artiplan.pddl import load_task
    from artiplan.semantics import validate

    try:
        task = load_task(domain_path, problem_path)
        report = validate(task, plan, tolerance=TOLERANCE)
    except Exception as exc:  # the validator failing is not the planner's fault
        return Verdict(None, f"validator failed: {type(exc).__name__}: {exc}")
    return Verdict(bool(report.valid), str(getattr(report, "reason", "") or ""))


def final_status(result: BackendResult, verdict: Verdict | None) -> str:
    """The row's status: the planner's, except that a plan counts as solved only when valid."""
    if result.status is not PlanStatus.SOLVED:
        return status_name(result.status)
    if verdict is None or verdict.valid is None:
        return "unvalidated"
    return "solved" if verdict.valid else "invalid"


def plan_text(plan: Plan | None, fallback: str) -> str:
    """The plan in VAL's format (artiplan's writer), or the planner's own text."""
    if plan is None:
        return fallback
    from artiplan.semantics.plan_io import format_plan, format_time

    text = format_plan(plan, events=False)
    if plan.end is not None and plan.end > max((a.time for a in plan.actions), default=-1.0):
        text += f"{format_time(plan.end)}: @PlanEND\n"  # read back as Plan.end by plan_io
    return text


def run_job(job: Job) -> dict[str, Any]:
    """Run the job and return its result row (see :func:`make_row`). Never raises for a
    planner's failure: a missing tool or crash becomes an ``error`` row with a message."""
    from artiplan.errors import ArtiplanError

    problem = job.problem
    try:
        result = get_planner(job.planner).solve(
            problem.domain, problem.problem,
            time_limit=job.time_limit, memory_limit=job.memory_limit,
        )
    except ArtiplanError as exc:
        result = BackendResult(PlanStatus.ERROR, None, 0.0, 0.0, 0.0, message=str(exc))
    except Exception as exc:  # one broken run must not end a sweep of hundreds
        message = f"internal error: {type(exc).__name__}: {exc}"
        result = BackendResult(PlanStatus.ERROR, None, 0.0, 0.0, 0.0, message=message)
    plan = result.plan  # an empty plan (just wait) is a plan too
    verdict = check_plan(problem.domain, problem.problem, plan) if plan is not None else None
    return make_row(job, result, verdict)


def make_row(job: Job, result: BackendResult, verdict: Verdict | None) -> dict[str, Any]:
    """One JSON-ready result row (layout ``SCHEMA``)."""
    problem = job.problem
    plan = result.plan
    actions = [a for a in plan.actions if a.name != "observe"] if plan is not None else []
    row: dict[str, Any] = {
        "schema": SCHEMA,
        "planner": job.planner,
        "model": problem.model,
        "param": problem.param,
        "variant": problem.variant,
        "size": problem.size,
        "task": problem.task,
        "problem_id": problem.problem_id,
        "status": final_status(result, verdict),
        "planner_status": status_name(result.status),
        "cpu_s": round(result.cpu_s, 4),
        "wall_s": round(result.wall_s, 4),
        "peak_mb": round(result.peak_mb, 1),
        "makespan": round(plan.makespan, 6) if plan is not None else None,
        "n_actions": len(actions) if plan is not None else None,
        "valid": verdict.valid if verdict else None,
        "validation": verdict.reason if verdict else "",
        "message": result.message[:500],
        "plan": plan_text(plan, result.plan_text),
        "time_limit": job.time_limit,
        "memory_limit": job.memory_limit,
        "problem": problem.problem,
        "domain": problem.domain,
        "host": socket.gethostname(),
        "time": datetime.now(timezone.utc).isoformat(timespec="seconds"),
    }
    row.update({k: v for k, v in result.extra.items() if k not in row})
    return row
