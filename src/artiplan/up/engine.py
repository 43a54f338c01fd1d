"""The unified-planning engine ``artiplan``: a one-shot planner and a plan validator.

One class serves both operation modes because unified-planning looks engines up by name:
``OneshotPlanner(name="artiplan")`` and ``PlanValidator(name="artiplan")`` get the same class.

Parameters (``params={...}``; values may be strings, as in an ``up.ini`` file):

* planning: ``memory_limit`` [MB], and artiplan's planner options (``epsilon``, ``time_weight``,
  ``goal_margin``, ``value_precision``, ``fallback_step``, ``validate``, ``improve``; see
  :data:`artiplan.search.api.OPTIONS`);
* validating: ``end`` (``auto``, ``last-happening``, ``first-goal``: :mod:`artiplan.up.ending`),
  ``tolerance`` [s] (default 0.001), ``horizon`` [s] (default 3600).

There is no ``AnytimePlanner``: artiplan's improvement phase (:mod:`artiplan.search.improve`)
validates its candidates only when it ends and returns the best, so it cannot hand plans out as
it finds them without a change to the search.
"""

from __future__ import annotations

import warnings
from typing import IO, Any

from unified_planning.engines import Credits, Engine, OptimalityGuarantee
from unified_planning.engines.mixins import OneshotPlannerMixin, PlanValidatorMixin
from unified_planning.exceptions import UPUsageError
from unified_planning.plans import PlanKind

from artiplan.search.api import OPTIONS
from artiplan.up import kinds
from artiplan.up.ending import END_RULES
from artiplan.up.planner import PlannerSettings, solve
from artiplan.up.validator import ValidatorSettings, check

NAME = "artiplan"

CREDITS = Credits(
    name="artiplan",
    author="the artiplan authors",
    contact="see the artiplan README",
    website="https://pypi.org/project/artiplan/",
    license="MIT",
    short_description="artiplan: an exact-time PDDL+ planner and validator (VAL's semantics).",
    long_description=(
        "artiplan plans for PDDL+ problems (processes, events, linear and nonlinear continuous "
        "change) in exact time: waits end at polynomial roots, not clock steps. Its validator "
        "follows VAL's rules and explains the first failure."
    ),
)

_BOOL_OPTIONS = {k for k, kind in OPTIONS.items() if kind is bool}
_INT_OPTIONS = {k for k, kind in OPTIONS.items() if kind is int}
_VALIDATOR_PARAMS = {"end", "tolerance", "horizon"}
_PARAMS = {"memory_limit", *OPTIONS, *_VALIDATOR_PARAMS}


def _bool(name: str, value: Any) -> bool:
    if isinstance(value, bool):
        return value
    text = str(value).strip().lower()
    if text in ("true", "1", "yes", "on"):
        return True
    if text in ("false", "0", "no", "off"):
        return False
    raise UPUsageError(f"artiplan: parameter {name} must be true or false, not {value!r}")


def _number(name: str, value: Any, kind: type = float) -> Any:
    try:
        return kind(value)
    except (TypeError, ValueError):
        raise UPUsageError(f"artiplan: parameter {name} must be a number, not {value!r}") from None


def parse_params(params: dict[str, Any]) -> tuple[PlannerSettings, ValidatorSettings]:
    """The engine's settings from its ``params``; UPUsageError names the valid ones."""
    unknown = set(params) - _PARAMS
    if unknown:
        raise UPUsageError(f"artiplan: unknown parameter(s) {sorted(unknown)}; valid: "
                           f"{sorted(_PARAMS)}")
    options: dict[str, Any] = {}
    for key in set(params) & set(OPTIONS):
        value = params[key]
        if key in _BOOL_OPTIONS:
            options[key] = _bool(key, value)
        else:
            options[key] = _number(key, value, int if key in _INT_OPTIONS else float)
    memory = params.get("memory_limit")
    planner = PlannerSettings(None if memory is None else _number("memory_limit", memory),
                              options)
    end = str(params.get("end", "auto"))
    if end not in END_RULES:
        raise UPUsageError(f"artiplan: parameter end must be one of {list(END_RULES)}, "
                           f"not {end!r}")
    validator = ValidatorSettings(
        end=end,
        tolerance=_number("tolerance", params.get("tolerance", 0.001)),
        horizon=_number("horizon", params.get("horizon", ValidatorSettings.horizon)),
    )
    return planner, validator


class ArtiplanEngine(Engine, OneshotPlannerMixin, PlanValidatorMixin):
    """artiplan in unified-planning: ``OneshotPlanner`` and ``PlanValidator`` (module doc)."""

    def __init__(self, **params: Any) -> None:
        Engine.__init__(self)
        OneshotPlannerMixin.__init__(self)
        self._planner, self._validator = parse_params(params)

    @property
    def name(self) -> str:
        return NAME

    @staticmethod
    def supported_kind() -> Any:
        return kinds.supported_kind()

    @staticmethod
    def supports(problem_kind: Any) -> bool:
        return kinds.supports(problem_kind)

    @staticmethod
    def supports_plan(plan_kind: Any) -> bool:
        return plan_kind in (PlanKind.TIME_TRIGGERED_PLAN, PlanKind.SEQUENTIAL_PLAN)

    @staticmethod
    def satisfies(optimality_guarantee: Any) -> bool:
        return bool(optimality_guarantee == OptimalityGuarantee.SATISFICING)

    @staticmethod
    def get_credits(**kwargs: Any) -> Credits | None:
        """The credits, when the environment prints them (unified-planning inspects the call
        stack before it looks at the stream: a few ms a call, skipped when nothing prints)."""
        from unified_planning.environment import get_environment

        return CREDITS if get_environment().credits_stream is not None else None

    # unified-planning's solve() and validate() compute problem.kind for their check and then
    # call _solve/_validate, which need it again (to write PDDL+). These do the same checks with
    # one computation of the kind; _solve and _validate remain for callers that use them.
    def solve(
        self, problem: Any, heuristic: Any = None, timeout: float | None = None,
        output_stream: IO[str] | None = None, warm_start_plan: Any = None, **kwargs: Any,
    ) -> Any:
        kind = self._checked_kind(problem, "solve")
        if not kind.has_quality_metrics() and self.optimality_metric_required:
            raise UPUsageError("The problem has no quality metrics but the engine is required "
                               "to be optimal!")
        return self._plan(problem, kind, heuristic, timeout, output_stream)

    def validate(self, problem: Any, plan: Any) -> Any:
        kind = self._checked_kind(problem, "validate")
        if not self.skip_checks and not self.supports_plan(plan.kind):
            self._failed_check(f"{self.name} cannot validate this kind of plan!")
        return check(self.name, problem, plan, self._validator_settings(), kind)

    def _checked_kind(self, problem: Any, what: str) -> Any:
        kind = problem.kind
        if not self.skip_checks and not self.supports(kind):
            self._failed_check(f"We cannot establish whether {self.name} can {what} this "
                               "problem!")
        return kind

    def _failed_check(self, message: str) -> None:
        if self.error_on_failed_checks:
            raise UPUsageError(message)
        warnings.warn(message, stacklevel=4)

    def _plan(
        self, problem: Any, kind: Any, heuristic: Any, timeout: float | None,
        output_stream: IO[str] | None,
    ) -> Any:
        if heuristic is not None:
            warnings.warn("artiplan ignores the heuristic argument: it uses its own", stacklevel=3)
        settings = self._planner
        if self.skip_checks:
            settings = PlannerSettings(settings.memory_limit, settings.options, False)
        return solve(self.name, problem, timeout, settings, output_stream, kind)

    def _validator_settings(self) -> ValidatorSettings:
        v = self._validator
        return ValidatorSettings(v.end, v.tolerance, v.horizon, False) if self.skip_checks else v

    def _solve(
        self, problem: Any, heuristic: Any = None, timeout: float | None = None,
        output_stream: IO[str] | None = None,
    ) -> Any:
        return self._plan(problem, problem.kind, heuristic, timeout, output_stream)

    def _validate(self, problem: Any, plan: Any) -> Any:
        return check(self.name, problem, plan, self._validator_settings())


__all__ = ["CREDITS", "NAME", "ArtiplanEngine", "parse_params"]
