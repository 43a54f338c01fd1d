"""Plans with margin: no action within the event gap of an event, the goal held with a margin
at the end (what both validators need to agree; issue: VAL is the judge)."""

from __future__ import annotations

import pytest

from artiplan import plan
from artiplan.encoding.suite import suite_problem
from artiplan.pddl.task import And, Atom, Comparison, Const, FluentRef, Not, Or
from artiplan.semantics.walks import robustness


@pytest.mark.parametrize("variant", ["ng", "ucm-1.0", "uacm-0.5"])
@pytest.mark.parametrize("task", [1, 2, 3])
def test_suite_plans_keep_their_margins(variant: str, task: int) -> None:
    result = plan(*suite_problem(variant, 4, task), time_limit=60)
    assert result.plan is not None, result.message
    margins = result.stats["margins"]
    assert margins["ok"], margins
    assert margins["goal_margin"] is None or margins["goal_margin"] >= 1e-3
    events = result.trajectory.events if result.trajectory is not None else []
    for action in result.plan.actions:
        for event in events:
            assert abs(action.time - event.time) >= 0.015 - 1e-9, (action, event)


def test_robustness_is_the_distance_to_a_change_of_truth() -> None:
    x, y = FluentRef(0), FluentRef(1)
    window = And((Comparison(">", x, Const(10.0)), Comparison("<", x, Const(20.0))))
    assert robustness(window, 0, [12.0, 0.0]) == pytest.approx(2.0)
    assert robustness(window, 0, [25.0, 0.0]) == pytest.approx(-5.0)
    either = Or((Comparison(">=", y, Const(1.0)), window))
    assert robustness(either, 0, [12.0, 4.0]) == pytest.approx(3.0)
    assert robustness(Not(window), 0, [12.0, 0.0]) == pytest.approx(-2.0)
    assert robustness(Atom(0), 0b1, [0.0, 0.0]) == float("inf")
    assert robustness(Comparison("=", x, Const(1.0)), 0, [1.25, 0.0]) == pytest.approx(-0.25)


def test_goal_margin_grows_with_the_events_on_the_path() -> None:
    """VAL's event timing errors add up over a cascade of events: the goal wait runs on
    longer the more events the path has seen (SearchConfig.margin_per_event)."""
    problem = suite_problem("uacm-0.5", 5, 1)
    flat = plan(*problem, time_limit=60, margin_per_event=0.0, improve=False)
    grown = plan(*problem, time_limit=60, margin_per_event=0.004, improve=False)
    assert flat.plan is not None and grown.plan is not None
    assert flat.trajectory is not None and len(flat.trajectory.events) >= 5
    names = [(a.name, a.args) for a in flat.plan.actions]
    assert names == [(a.name, a.args) for a in grown.plan.actions]
    # the final goal wait comes after >= 5 events: >= 0.02 s more than the flat 0.01 s
    assert grown.plan.makespan >= flat.plan.makespan + 0.015, (flat.plan, grown.plan)
