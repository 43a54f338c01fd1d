"""The PDDL+ language layer: text <-> syntax tree (parser, writer) and grounding to a Task.

    domain = parse_domain(text, "domain.pddl")      # syntax tree, checked; domain.warnings
    problem = parse_problem(text, "problem.pddl")
    task = ground(domain, problem)                  # artiplan.pddl.task.Task
    task = load_task("domain.pddl", "problem.pddl") # paths or PDDL text
    print(write_domain(domain))                     # PDDL text again

Errors are :class:`artiplan.errors.InputError` with file:line:col (exit code 3).
"""

from __future__ import annotations

import importlib

TYPE_CHECKING = False  # read as true by mypy; typing is not imported at run time (start-up)

#: Public name -> the module defining it; imported on first use, so that importing one
#: module of the package (the task, say) does not import the parser and the writer too.
_EXPORTS = {
    "Domain": "syntax", "Problem": "syntax", "Task": "task", "check_problem": "checker",
    "ground": "grounding", "load_domain": "loader", "load_problem": "loader",
    "load_task": "loader", "parse_domain": "parser", "parse_problem": "parser",
    "write_domain": "writer", "write_problem": "writer",
}
__all__ = [
    "Domain",
    "Problem",
    "Task",
    "check_problem",
    "ground",
    "load_domain",
    "load_problem",
    "load_task",
    "parse_domain",
    "parse_problem",
    "write_domain",
    "write_problem",
]

if TYPE_CHECKING:
    from typing import Any

    from artiplan.pddl.checker import check_problem
    from artiplan.pddl.grounding import ground
    from artiplan.pddl.loader import load_domain, load_problem, load_task
    from artiplan.pddl.parser import parse_domain, parse_problem
    from artiplan.pddl.syntax import Domain, Problem
    from artiplan.pddl.task import Task
    from artiplan.pddl.writer import write_domain, write_problem


def __getattr__(name: str) -> Any:
    module = _EXPORTS.get(name)
    if module is None:
        raise AttributeError(f"module 'artiplan.pddl' has no attribute {name!r}")
    return getattr(importlib.import_module(f"artiplan.pddl.{module}"), name)
