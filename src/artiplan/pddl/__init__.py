"""The PDDL+ language layer: text <-> syntax tree (parser, writer) and grounding to a Task.

    domain = parse_domain(text, "domain.pddl")      # syntax tree, checked; domain.warnings
    problem = parse_problem(text, "problem.pddl")
    task = ground(domain, problem)                  # artiplan.pddl.task.Task
    task = load_task("domain.pddl", "problem.pddl") # paths or PDDL text
    print(write_domain(domain))                     # PDDL text again

Errors are :class:`artiplan.errors.InputError` with file:line:col (exit code 3).
"""

from artiplan.pddl.checker import check_problem
from artiplan.pddl.grounding import ground
from artiplan.pddl.loader import load_domain, load_problem, load_task
from artiplan.pddl.parser import parse_domain, parse_problem
from artiplan.pddl.syntax import Domain, Problem
from artiplan.pddl.task import Task
from artiplan.pddl.writer import write_domain, write_problem

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
