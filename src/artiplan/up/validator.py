"""``PlanValidator(name="artiplan")``: a unified-planning plan checked with artiplan's validator.

The problem is written as PDDL+ (:mod:`artiplan.up.convert`, without any added action), the plan
becomes an artiplan plan, and :func:`artiplan.semantics.validate` judges it with VAL's
semantics (exact event times; ``tolerance`` [s] between interfering happenings). Where the plan
ends follows the ``end`` rule (:mod:`artiplan.up.ending`). The result carries
unified-planning's reason (``INAPPLICABLE_ACTION`` with the action, ``UNSATISFIED_GOALS``,
``MUTEX_CONFLICT``; none for an event triggered twice or a numeric error), the explanation in
its log (the failed condition and the values it read) and, in ``metrics``: ``reason``,
``failure_kind``, ``failure_time`` [s], ``end_rule`` and ``plan_end`` [s].
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from typing import Any

from unified_planning.engines import (
    FailedValidationReason,
    LogLevel,
    LogMessage,
    ValidationResult,
    ValidationResultStatus,
)

from artiplan.errors import InputError
from artiplan.pddl import load_task
from artiplan.semantics import Plan, ValidationReport, validate
from artiplan.semantics.plan_io import format_time
from artiplan.up.convert import ConversionError, from_up_plan, has_noop, to_pddl
from artiplan.up.ending import DEFAULT_HORIZON, END_RULES, goal_times
from artiplan.up.kinds import SUPPORTED_KIND, supports

_REASON = {
    "precondition": FailedValidationReason.INAPPLICABLE_ACTION,
    "bad-operator": FailedValidationReason.INAPPLICABLE_ACTION,
    "goal": FailedValidationReason.UNSATISFIED_GOALS,
    "mutex": FailedValidationReason.MUTEX_CONFLICT,
}


@dataclass(frozen=True)
class ValidatorSettings:
    """How the engine validates.

    Attributes:
        end: Where a plan ends: ``auto``, ``last-happening`` (VAL) or ``first-goal`` (ENHSP).
        tolerance: VAL's ``-t``: interfering happenings closer than this [s] are a mutex.
        horizon: ``first-goal``: how long [s] after the last action the goal may come.
        check_kind: Answer UNKNOWN for problems whose kind is not supported.
    """

    end: str = "auto"
    tolerance: float = 0.001
    horizon: float = DEFAULT_HORIZON
    check_kind: bool = True


def end_rule(problem: Any, requested: str) -> str:
    """The rule in force: ``requested``, or for ``auto`` the one :mod:`ending` describes."""
    if requested != "auto":
        return requested
    return "last-happening" if has_noop(problem) or not problem.processes else "first-goal"


def check(
    engine: str, problem: Any, plan: Any, settings: ValidatorSettings, kind: Any = None
) -> ValidationResult:
    """Validate ``plan`` for ``problem`` (``kind``: the problem's kind, if computed already)."""
    assert settings.end in END_RULES
    kind = problem.kind if kind is None else kind
    if settings.check_kind and not supports(kind):
        missing = sorted(kind.features - SUPPORTED_KIND.features)
        return _unknown(engine, f"artiplan does not support these features: {', '.join(missing)}")
    try:
        conv = to_pddl(problem, kind, add_end_action=False)
        ap_plan, instances = from_up_plan(conv, plan)
        task = load_task(conv.domain, conv.pddl_problem)
    except (ConversionError, InputError) as exc:
        return _unknown(engine, f"artiplan cannot read this problem or plan: {exc}")
    rule = end_rule(problem, settings.end)
    report = validate(task, ap_plan, settings.tolerance)
    end = None
    if not report.valid and report.kind == "goal" and rule == "first-goal":
        report, end = _first_goal(task, ap_plan, report, settings)
    return _result(engine, report, instances, rule, end, ap_plan)


def _first_goal(
    task: Any, plan: Plan, failed: ValidationReport, settings: ValidatorSettings
) -> tuple[ValidationReport, float | None]:
    """The plan ended at the first instant after its last action where the goal holds."""
    final = failed.trajectory.final_state if failed.trajectory is not None else None
    times = goal_times(task, final, settings.horizon) if final is not None else iter(())
    for t in times:
        report = validate(task, dataclasses.replace(plan, end=t), settings.tolerance)
        if report.valid:
            return report, t
    failed.reason += f"; nor is it reached within {settings.horizon:g} s after the last action"
    return failed, None


def _result(
    engine: str, report: ValidationReport, instances: list[Any], rule: str, end: float | None,
    plan: Plan,
) -> ValidationResult:
    metrics = {"end_rule": rule}
    if report.valid:
        last = end if end is not None else plan.makespan
        metrics["plan_end"] = format_time(last)
        return ValidationResult(ValidationResultStatus.VALID, engine,
                                [LogMessage(LogLevel.INFO, f"Plan valid ({rule})")],
                                metrics=metrics)
    metrics.update(reason=report.reason, failure_kind=report.kind)
    if report.time is not None:
        metrics["failure_time"] = format_time(report.time)
    reason = _REASON.get(report.kind)
    action = None
    if reason is FailedValidationReason.INAPPLICABLE_ACTION and report.line:
        action = instances[report.line - 1]
    return ValidationResult(ValidationResultStatus.INVALID, engine,
                            [LogMessage(LogLevel.INFO, report.summary())], reason=reason,
                            inapplicable_action=action, metrics=metrics)


def _unknown(engine: str, message: str) -> ValidationResult:
    return ValidationResult(ValidationResultStatus.UNKNOWN, engine,
                            [LogMessage(LogLevel.WARNING, message)])
