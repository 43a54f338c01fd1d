"""``OneshotPlanner(name="artiplan")``: a unified-planning problem -> artiplan's planner -> a plan.

The problem is written as PDDL+ (:mod:`artiplan.up.convert`), planned by
:func:`artiplan.plan` in this process under the time limit, and the plan mapped back. The
planner's statistics go into the result's ``metrics`` (strings, as unified-planning wants them):
``engine_internal_time`` [s] (conversion and planning), artiplan's counters and phase times, and
``plan_end`` [s] when the plan ends by waiting (:mod:`artiplan.up.ending`).
"""

from __future__ import annotations

import time
import traceback
from dataclasses import dataclass, field
from typing import IO, Any

from unified_planning.engines import (
    LogLevel,
    LogMessage,
    PlanGenerationResult,
    PlanGenerationResultStatus,
)

from artiplan.errors import InputError
from artiplan.search.api import PlanResult, PlanStatus
from artiplan.search.api import plan as artiplan_plan
from artiplan.semantics.plan_io import format_time
from artiplan.up.convert import ConversionError, Converted, to_pddl, to_up_plan
from artiplan.up.kinds import SUPPORTED_KIND, supports

Status: Any = PlanGenerationResultStatus

#: artiplan's outcome -> unified-planning's. NO_PLAN is not a proof (waits stop only at
#: critical times), hence "incompletely".
STATUS = {
    PlanStatus.SOLVED: Status.SOLVED_SATISFICING,
    PlanStatus.UNSOLVABLE_PROVEN: Status.UNSOLVABLE_PROVEN,
    PlanStatus.NO_PLAN: Status.UNSOLVABLE_INCOMPLETELY,
    PlanStatus.TIMEOUT: Status.TIMEOUT,
    PlanStatus.MEMOUT: Status.MEMOUT,
    PlanStatus.ERROR: Status.INTERNAL_ERROR,
}


@dataclass(frozen=True)
class PlannerSettings:
    """How the engine plans.

    Attributes:
        memory_limit: Memory limit [MB] (growth of this process during the search), or None.
        options: artiplan planner options (:data:`artiplan.search.api.OPTIONS`).
        check_kind: Refuse problems whose kind is not supported (False: try anyway).
    """

    memory_limit: float | None = None
    options: dict[str, Any] = field(default_factory=dict)
    check_kind: bool = True


def solve(
    engine: str, problem: Any, timeout: float | None, settings: PlannerSettings,
    output_stream: IO[str] | None = None, kind: Any = None,
) -> PlanGenerationResult:
    """Plan for ``problem`` within ``timeout`` [s] (conversion included); ``kind``: the
    problem's kind, if the caller computed it."""
    t0 = time.perf_counter()
    kind = problem.kind if kind is None else kind
    if settings.check_kind and not supports(kind):
        missing = sorted(kind.features - SUPPORTED_KIND.features)
        return _result(engine, Status.UNSUPPORTED_PROBLEM, t0,
                       f"artiplan does not support these problem features: {', '.join(missing)}")
    try:
        conv = to_pddl(problem, kind)
    except ConversionError as exc:
        return _result(engine, Status.UNSUPPORTED_PROBLEM, t0, str(exc))
    left = None if timeout is None else max(0.0, timeout - (time.perf_counter() - t0))
    try:
        result = artiplan_plan(conv.domain, conv.pddl_problem, time_limit=left,
                               memory_limit=settings.memory_limit, **settings.options)
    except InputError as exc:
        return _result(engine, Status.UNSUPPORTED_PROBLEM, t0,
                       f"artiplan cannot read unified-planning's PDDL for this problem: {exc}")
    except Exception:  # a bug in artiplan: report it as the engine's internal error
        return _result(engine, Status.INTERNAL_ERROR, t0, traceback.format_exc())
    return _planned(engine, conv, result, t0, output_stream)


def _planned(
    engine: str, conv: Converted, result: PlanResult, t0: float, stream: IO[str] | None
) -> PlanGenerationResult:
    status = STATUS[result.status]
    plan = None
    metrics = {k: _text(v) for k, v in result.stats.items() if isinstance(v, (int, float, str))}
    if result.status is PlanStatus.SOLVED and result.plan is not None:
        try:
            plan, end = to_up_plan(conv, result.plan)
        except ConversionError as exc:
            return _result(engine, Status.INTERNAL_ERROR, t0, f"plan not mapped back: {exc}")
        if end is not None:
            metrics["plan_end"] = format_time(end)
    summary = f"artiplan: {result.status.value}" + (f": {result.message}" if result.message else "")
    if stream is not None:
        stream.write(summary + "\n")
    return _result(engine, status, t0, summary, metrics, plan)


def _result(
    engine: str, status: Any, t0: float, message: str, metrics: dict[str, str] | None = None,
    plan: Any = None,
) -> PlanGenerationResult:
    metrics = dict(metrics or {})
    metrics["engine_internal_time"] = _text(time.perf_counter() - t0)
    level = LogLevel.INFO if plan is not None else LogLevel.WARNING
    return PlanGenerationResult(status, plan, engine, metrics, [LogMessage(level, message)])


def _text(value: Any) -> str:
    return f"{value:.6f}" if isinstance(value, float) else str(value)
