"""unified-planning's own test problems: ``up_test_cases`` (shipped with unified-planning) and the
examples of ``unified_planning.test.examples``.

``up_test_cases`` packages import a sibling module as ``utils`` (unified-planning's report script
puts that folder on ``sys.path``; so does :func:`load_cases`). Modules that fail to load are
returned with the error. One is known: ``builtin.processes.constant_derivative`` calls
``Process.add_derivative``, which unified-planning 1.3.0 does not have; :func:`constant_derivative`
rebuilds that case with ``add_increase_continuous_effect`` (the same derivative).
"""

from __future__ import annotations

import importlib
import os
import pkgutil
import sys
from typing import Any

from unified_planning.model import Event, Fluent, InstantaneousAction, Problem, Process
from unified_planning.shortcuts import GE, Not, RealType
from unified_planning.test import TestCase


def load_cases() -> tuple[dict[str, Any], dict[str, str]]:
    """(name -> TestCase, module -> load error) for every case that loads."""
    import up_test_cases

    folder = os.path.dirname(up_test_cases.__file__)
    if folder not in sys.path:
        sys.path.append(folder)
    cases: dict[str, Any] = {}
    errors: dict[str, str] = {}
    root = importlib.import_module("up_test_cases.builtin")
    for info in pkgutil.walk_packages(root.__path__, "up_test_cases.builtin."):
        try:
            module = importlib.import_module(info.name)
            get = module.__dict__.get("get_test_cases")
            if get is None or hasattr(get, "func"):  # a folder's discovery partial
                continue
            for name, case in get().items():
                cases[f"{info.name.removeprefix('up_test_cases.')}:{name}"] = case
        except Exception as exc:  # noqa: BLE001 - any failure is reported with its module
            errors[info.name] = f"{type(exc).__name__}: {exc}"
    if any("add_derivative" in e for e in errors.values()):
        cases["builtin.processes.constant_derivative:basic (rebuilt)"] = constant_derivative()
    from unified_planning.test.examples import get_example_problems

    for name, case in get_example_problems().items():
        cases[f"examples:{name}"] = case
    return cases, errors


def constant_derivative() -> TestCase:
    """``up_test_cases.builtin.processes.constant_derivative``'s problem, as written there
    but with ``add_increase_continuous_effect(d, 1)`` for ``add_derivative(d, 1)``."""
    x = Fluent("on")
    d = Fluent("d", RealType())
    a = InstantaneousAction("turn_on")
    a.add_precondition(Not(x))
    a.add_effect(x, True)
    evt = Event("turn_off_automatically")
    evt.add_precondition(GE(d, 200))
    evt.add_effect(x, False)
    b = Process("moving")
    b.add_precondition(x)
    b.add_increase_continuous_effect(d, 1)
    problem = Problem("basic")
    problem.add_fluent(x)
    problem.add_fluent(d)
    problem.add_action(a)
    problem.add_process(b)
    problem.add_event(evt)
    problem.set_initial_value(x, False)
    problem.set_initial_value(d, 0)
    problem.add_goal(GE(d, 10))
    return TestCase(problem=problem, solvable=True)
