"""The unified-planning problem kinds artiplan plans for and validates.

Each feature below is one artiplan reads through unified-planning's PDDL writer and that its
tests exercise (tests/up/). Left out, so that ``supports()`` refuses them:

* ``CONTINUOUS_TIME``: in unified-planning 1.3 a PDDL+ problem does not have it (processes and
  events set ``PROCESSES``/``EVENTS``); it comes with durative actions, timed effects and timed
  goals, which artiplan does not plan for.
* ``DISCRETE_TIME``, ``TIMED_*``, ``INTERMEDIATE_CONDITIONS_AND_EFFECTS``, scheduling,
  hierarchical, multi-agent, TAMP, contingent problems.
* ``OBJECT_FLUENTS``, ``BOUNDED_TYPES``, action parameters that are not objects, state
  invariants and trajectory constraints, oversubscription, simulated effects, undefined initial
  values.

Quality metrics are accepted and not optimised: plans are satisficing (artiplan's improvement
phase shortens makespan, then action count).
"""

from __future__ import annotations

from unified_planning.model import ProblemKind

FEATURES: dict[str, tuple[str, ...]] = {
    "PROBLEM_CLASS": ("ACTION_BASED",),
    "PROBLEM_TYPE": ("SIMPLE_NUMERIC_PLANNING", "GENERAL_NUMERIC_PLANNING"),
    "TIME": ("PROCESSES", "EVENTS"),
    "CONDITIONS_KIND": ("NEGATIVE_CONDITIONS", "DISJUNCTIVE_CONDITIONS", "EQUALITIES",
                        "EXISTENTIAL_CONDITIONS", "UNIVERSAL_CONDITIONS"),
    "EFFECTS_KIND": ("CONDITIONAL_EFFECTS", "INCREASE_EFFECTS", "DECREASE_EFFECTS",
                     "INCREASE_CONTINUOUS_EFFECTS", "DECREASE_CONTINUOUS_EFFECTS",
                     "NON_LINEAR_CONTINUOUS_EFFECTS", "STATIC_FLUENTS_IN_BOOLEAN_ASSIGNMENTS",
                     "STATIC_FLUENTS_IN_NUMERIC_ASSIGNMENTS", "FLUENTS_IN_BOOLEAN_ASSIGNMENTS",
                     "FLUENTS_IN_NUMERIC_ASSIGNMENTS", "FORALL_EFFECTS"),
    "TYPING": ("FLAT_TYPING", "HIERARCHICAL_TYPING"),
    "FLUENTS_TYPE": ("INT_FLUENTS", "REAL_FLUENTS"),
    "QUALITY_METRICS": ("ACTIONS_COST", "PLAN_LENGTH", "MAKESPAN", "FINAL_VALUE"),
    "ACTIONS_COST_KIND": ("STATIC_FLUENTS_IN_ACTIONS_COST", "FLUENTS_IN_ACTIONS_COST",
                          "INT_NUMBERS_IN_ACTIONS_COST", "REAL_NUMBERS_IN_ACTIONS_COST"),
}


def supported_kind() -> ProblemKind:
    """The kind of every problem artiplan accepts (unified-planning's problem-kind version 3)."""
    kind = ProblemKind(version=3)
    for category, features in FEATURES.items():
        setter = getattr(kind, "set_" + category.lower())
        for feature in features:
            setter(feature)
    return kind


SUPPORTED_KIND = supported_kind()


def supports(kind: ProblemKind) -> bool:
    """True when every feature of ``kind`` is one artiplan handles."""
    return bool(kind <= SUPPORTED_KIND)
