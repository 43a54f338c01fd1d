"""Object model -> PDDL+ domains and problems (NG, UCM, UACM) and the paper's benchmark suite."""

from artiplan.encoding.domain import WRAP_MARGIN, domain_name, domain_pddl
from artiplan.encoding.goals import (
    GOAL_STYLES,
    AngleBound,
    AngleWindow,
    GoalSpec,
    goal_links,
    make_goal,
)
from artiplan.encoding.gravity import gravity_links
from artiplan.encoding.options import MODELS, EncodingOptions
from artiplan.encoding.problem import problem_pddl
from artiplan.encoding.suite import SIZES, SUITE_MODELS, make_task, suite_tasks, write_suite

__all__ = [
    "GOAL_STYLES",
    "MODELS",
    "SIZES",
    "SUITE_MODELS",
    "WRAP_MARGIN",
    "AngleBound",
    "AngleWindow",
    "EncodingOptions",
    "GoalSpec",
    "domain_name",
    "domain_pddl",
    "goal_links",
    "gravity_links",
    "make_goal",
    "make_task",
    "problem_pddl",
    "suite_tasks",
    "write_suite",
]
