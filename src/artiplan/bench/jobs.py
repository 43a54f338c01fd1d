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
    """A planner on a problem with limits: CPU time [s] and memory [MiB]; ``val``: also ask
    stock VAL about the plan (when VAL is installed)."""

    planner: str
    problem: SuiteProblem
    time_limit: float
    memory_limit: float
    val: bool = True


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


def check_with_val(domain_path: str, problem_path: str, plan: Plan) -> Verdict:
    """Stock VAL's verdict on ``plan`` as VAL reads it (a peer's stated end closed by the
    task's no-op action); ``valid`` is None when VAL is missing or could not decide."""
    import tempfile

    from artiplan.backends.convert import close_at_end
    from artiplan.backends.val import val_available, validate_with_val
    from artiplan.pddl import load_task
    from artiplan.semantics.plan_io import format_plan

    if not val_available():
        return Verdict(None, "VAL not installed")
    try:
        closed = close_at_end(plan, load_task(domain_path, problem_path))
        with tempfile.NamedTemporaryFile("w", suffix=".plan") as fh:
            fh.write(format_plan(closed, events=False))
            fh.flush()
            result = validate_with_val(domain_path, problem_path, fh.name, tolerance=TOLERANCE)
    except Exception as exc:  # VAL failing is neither the planner's fault nor a verdict
        return Verdict(None, f"VAL failed: {type(exc).__name__}: {exc}")
    if result.verdict in ("valid", "invalid"):
        return Verdict(result.valid, result.reason)
    return Verdict(None, f"VAL {result.verdict}: {result.reason}")


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
    val = None
    if job.val and plan is not None:
        val = check_with_val(problem.domain, problem.problem, plan)
    return make_row(job, result, verdict, val)


def make_row(
    job: Job, result: BackendResult, verdict: Verdict | None, val: Verdict | None = None
) -> dict[str, Any]:
    """One JSON-ready result row (layout ``SCHEMA``); ``val``: stock VAL's verdict, when asked
    (columns ``val_valid`` and ``val_reason``)."""
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
        "val_valid": val.valid if val else None,
        "val_reason": val.reason[:300] if val else "",
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
