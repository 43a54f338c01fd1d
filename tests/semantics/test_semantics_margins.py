"""Plan margins name what stock VAL mis-handles: coincident crossings of two objects."""

from __future__ import annotations

import pytest

from artiplan.encoding import EncodingOptions, domain_pddl, problem_pddl
from artiplan.model import ArticulatedObject, Configuration
from artiplan.pddl import load_task
from artiplan.semantics import validate
from artiplan.semantics.plan_io import parse_plan
from artiplan.semantics.results import margins_of

OBJ = ArticulatedObject(3)
# One turn of L2 (10 deg/s down) carries L3 with it through -0.2, where both wrap.
PLAN = "0: (start-decrease L1 L2 z-axis)\n0.5: (stop-decrease L1 L2 z-axis)\n0.6: (observe)\n"


def _task(init: Configuration, target: Configuration | None = None):  # type: ignore[no-untyped-def]
    options = EncodingOptions("ng")
    return load_task(domain_pddl(OBJ, options),
                     problem_pddl(OBJ, init, target or init, options, "window"))


def _margins(l3: float):  # type: ignore[no-untyped-def]
    task = _task(Configuration.from_angles([0, 0, 0], [0, 1.5, l3]))
    plan = parse_plan(PLAN)
    report = validate(task, plan)
    assert report.trajectory is not None
    return margins_of(task, plan, report.trajectory, 0.015)


@pytest.mark.parametrize(("l3", "coincide"), [(1.5, True), (3.5, False)])
def test_coincident_crossings_of_two_links_are_reported(l3: float, coincide: bool) -> None:
    m = _margins(l3)
    # L2 reaches -0.2 at 0.17 s; L3 at 0.17 s too when it starts at L2's angle, else later.
    assert (m.coincident == (0.17,)) is coincide, m
    assert m.object_event_gap_s is None  # each link wraps once


def test_closest_events_of_one_object() -> None:
    # Down and back up: each link wraps twice, L3 (nearer the boundary) sooner.
    task = _task(Configuration.from_angles([0, 0, 0], [0, 1.5, 3.0]))
    plan = parse_plan("0: (start-decrease L1 L2 z-axis)\n0.5: (stop-decrease L1 L2 z-axis)\n"
                      "0.501: (start-increase L1 L2 z-axis)\n1: (stop-increase L1 L2 z-axis)\n"
                      "1.1: (observe)\n")
    report = validate(task, plan)
    assert report.trajectory is not None
    m = margins_of(task, plan, report.trajectory, 0.015)
    # L3: 3 -> -0.2 at 0.32 s (to 359.8), 358 at 0.5, over 360 at 0.701: 0.381 s apart
    # (L2: 0.17 and 0.851 s)
    assert m.object_event_gap_s == pytest.approx(0.381, abs=1e-6)


def test_separate_pulls_apart_crossings_the_plan_made_coincide() -> None:
    from artiplan.search.separate import separate

    # Turn L3 onto L2's angle (4.5 -> 1.5), then carry both down through -0.2 together.
    task = _task(Configuration.from_angles([0, 0, 0], [0, 1.5, 4.5]),
                 Configuration.from_angles([0, 0, 0], [0, 358.5, 358.5]))
    plan = parse_plan("0: (start-decrease L2 L3 z-axis)\n0.3: (stop-decrease L2 L3 z-axis)\n"
                      "0.301: (start-decrease L1 L2 z-axis)\n0.601: (stop-decrease L1 L2 z-axis)\n"
                      "0.7: (observe)\n")
    report = validate(task, plan)
    assert report.valid and report.trajectory is not None, report.reason
    assert margins_of(task, plan, report.trajectory, 0.015).coincident == (0.471,)
    found = separate(task, plan, report, 0.015, lambda p: validate(task, p), lambda: False)
    assert found is not None
    better, got = found
    assert got.valid and got.trajectory is not None
    assert margins_of(task, better, got.trajectory, 0.015).coincident == ()
    # the tail moved by a few milliseconds, the order of the actions kept
    shifts = [round(b.time - a.time, 6) for a, b in zip(plan.actions, better.actions, strict=True)]
    assert shifts[0] == 0.0 and len(set(shifts[1:])) == 1 and 0 < abs(shifts[-1]) < 0.01


def test_separate_leaves_crossings_of_the_initial_dynamics() -> None:
    from artiplan.search.separate import separate

    # L2 and L3 start at one angle: every shift of the plan moves both alike.
    task = _task(Configuration.from_angles([0, 0, 0], [0, 1.5, 1.5]))
    plan = parse_plan(PLAN)
    report = validate(task, plan)
    assert report.valid and report.trajectory is not None, report.reason
    assert margins_of(task, plan, report.trajectory, 0.015).coincident == (0.17,)
    found = separate(task, plan, report, 0.015, lambda p: validate(task, p), lambda: False)
    assert found is None
