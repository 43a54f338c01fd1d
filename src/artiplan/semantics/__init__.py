"""artiplan.semantics: states, expressions, exact continuous dynamics, events, the plan
simulator and the validator with VAL's semantics.

The public API is re-exported here; see each module for the details.
"""

from artiplan.semantics.dynamics import (
    DEFAULT_FLOW,
    Flow,
    FlowConfig,
    active_processes,
    crossing_time,
    make_flow,
    point_holds,
    right_holds,
    settled_flow,
)
from artiplan.semantics.expressions import (
    EXACT,
    VAL_TOLERANCES,
    Tolerances,
    compile_condition,
    compile_expr,
    evaluate,
    format_condition,
    format_expr,
    holds,
    holds_values,
)
from artiplan.semantics.happenings import (
    EventError,
    apply_action,
    apply_actions,
    apply_effects,
    fire_events,
)
from artiplan.semantics.interference import interferes
from artiplan.semantics.plan import Plan, TimedAction, TimedEvent
from artiplan.semantics.simulator import AdvanceResult, Segment, advance, next_critical_time
from artiplan.semantics.state import State, initial_state
from artiplan.semantics.trajectory import Trajectory, TrajectoryRow
from artiplan.semantics.validator import ValidationReport, resolve, simulate, validate

__all__ = [
    "DEFAULT_FLOW",
    "EXACT",
    "VAL_TOLERANCES",
    "AdvanceResult",
    "EventError",
    "Flow",
    "FlowConfig",
    "Plan",
    "Segment",
    "State",
    "TimedAction",
    "TimedEvent",
    "Tolerances",
    "Trajectory",
    "TrajectoryRow",
    "ValidationReport",
    "active_processes",
    "advance",
    "apply_action",
    "apply_actions",
    "apply_effects",
    "compile_condition",
    "compile_expr",
    "crossing_time",
    "evaluate",
    "fire_events",
    "format_condition",
    "format_expr",
    "holds",
    "holds_values",
    "initial_state",
    "interferes",
    "make_flow",
    "next_critical_time",
    "point_holds",
    "resolve",
    "right_holds",
    "settled_flow",
    "simulate",
    "validate",
]
