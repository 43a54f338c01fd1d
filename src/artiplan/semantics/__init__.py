"""artiplan.semantics: PDDL+ semantics, once: the kernel (compiled task, exact flows, events,
the passing of time) shared by the validator and the planner, plans and their files.

Modules, bottom up: ``walks`` (the expression and condition walks), ``polynomial`` (roots),
``compiled`` (the task as functions over a fact bit mask and a value tuple), ``flow`` (exact
polynomial flows and the numeric fallback), ``kernel`` (instants and the passing of time),
``validator`` (the kernel plus diagnostics), ``plan``/``plan_io`` (plans and their files),
``trajectory`` (what a simulation records), ``interference`` (mutex).
"""

from __future__ import annotations

import importlib

TYPE_CHECKING = False  # read as true by mypy; typing is not imported at run time (start-up)

#: Public name -> the module defining it, imported on first use (importing one kernel module
#: does not import the validator, the trajectory and the plan files too).
_EXPORTS = {
    "CompiledTask": "compiled", "compile_task": "compiled", "interferes": "interference",
    "EventError": "kernel", "Kernel": "kernel", "Segment": "kernel", "ZenoError": "kernel",
    "Plan": "plan", "TimedAction": "plan", "TimedEvent": "plan", "State": "state",
    "Trajectory": "trajectory", "TrajectoryRow": "trajectory",
    "ValidationReport": "validator", "resolve": "validator", "simulate": "validator",
    "validate": "validator", "evaluate": "walks", "format_condition": "walks",
    "format_expr": "walks", "holds": "walks", "robustness": "walks",
}
__all__ = ["CompiledTask", "EventError", "Kernel", "Plan", "Segment", "State", "TimedAction",
           "TimedEvent", "Trajectory", "TrajectoryRow", "ValidationReport", "ZenoError",
           "compile_task", "evaluate", "format_condition", "format_expr", "holds", "interferes",
           "resolve", "robustness", "simulate", "validate"]

if TYPE_CHECKING:
    from typing import Any

    from artiplan.semantics.compiled import CompiledTask, compile_task
    from artiplan.semantics.interference import interferes
    from artiplan.semantics.kernel import EventError, Kernel, Segment, ZenoError
    from artiplan.semantics.plan import Plan, TimedAction, TimedEvent
    from artiplan.semantics.state import State
    from artiplan.semantics.trajectory import Trajectory, TrajectoryRow
    from artiplan.semantics.validator import ValidationReport, resolve, simulate, validate
    from artiplan.semantics.walks import (
        evaluate,
        format_condition,
        format_expr,
        holds,
        robustness,
    )


def __getattr__(name: str) -> Any:
    module = _EXPORTS.get(name)
    if module is None:
        raise AttributeError(f"module 'artiplan.semantics' has no attribute {name!r}")
    return getattr(importlib.import_module(f"artiplan.semantics.{module}"), name)
