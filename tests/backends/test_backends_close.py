"""A peer's plan that ends by waiting is closed with the task's no-op, so VAL's rules accept it."""

from __future__ import annotations

from artiplan.backends.convert import close_at_end
from artiplan.encoding import EncodingOptions, domain_pddl, problem_pddl
from artiplan.model import ArticulatedObject, Configuration
from artiplan.pddl import load_task
from artiplan.semantics import validate
from artiplan.semantics.plan import Plan, TimedAction

NOOP_FREE = """(define (domain d) (:requirements :strips)
  (:predicates (p)) (:action a :parameters () :precondition () :effect (p)))"""
NOOP_FREE_PROBLEM = "(define (problem q) (:domain d) (:init) (:goal (p)))"


def _task_and_waiting_plan():  # type: ignore[no-untyped-def]
    obj = ArticulatedObject(3)
    init = Configuration.from_angles([0, 0, 0], [0, 90, 90])
    # L3's vertical angle has to drop below 60: a rotation of L2 carries L3 at 10 deg/s.
    target = init.with_angle(3, "z-axis", 55.0).with_angle(2, "z-axis", 55.0)
    opts = EncodingOptions("ng")
    task = load_task(
        domain_pddl(obj, opts),
        problem_pddl(obj, init, target, opts, goal_style="window", seed=0),
    )
    plan = Plan((TimedAction(0.0, "start-decrease", ("L1", "L2", "z-axis")),), end=3.5)
    return task, plan


def test_a_plan_ending_by_waiting_gets_the_noop_at_its_end() -> None:
    task, plan = _task_and_waiting_plan()
    closed = close_at_end(plan, task)
    assert [a.name for a in closed.actions] == ["start-decrease", "observe"]
    assert closed.actions[-1].time == 3.5
    assert closed.end is None
    assert validate(task, closed).valid
    # Without the closing action VAL's rules check the goal at time 0, where it does not hold.
    assert not validate(task, Plan(plan.actions)).valid


def test_plans_without_a_later_end_or_tasks_without_a_noop_stay_as_they_are() -> None:
    task, plan = _task_and_waiting_plan()
    ended = Plan(plan.actions, end=0.0)
    assert close_at_end(ended, task) == ended
    other = load_task(NOOP_FREE, NOOP_FREE_PROBLEM)
    assert close_at_end(plan, other) == plan
