"""Goals: the paper's threshold style and the wrap-correct window style."""

from __future__ import annotations

import re

import pytest

from artiplan.encoding import AngleBound, AngleWindow, goal_links, make_goal
from artiplan.model import ArticulatedObject, Configuration


def _target(n: int, value: float) -> Configuration:
    return Configuration((value,) * n, (value,) * n)


def test_goal_links_every_second_from_l3() -> None:
    assert goal_links(ArticulatedObject(3)) == ("L3",)
    assert goal_links(ArticulatedObject(4)) == ("L3",)
    assert goal_links(ArticulatedObject(8)) == ("L3", "L5", "L7")
    assert goal_links(ArticulatedObject(12)) == ("L3", "L5", "L7", "L9", "L11")
    assert goal_links(ArticulatedObject(2)) == ("L2",)


def test_window_crossing_zero_accepts_358_and_2() -> None:
    w = AngleWindow("L3", "z-axis", 0.0, 5.0)
    assert w.pddl() == "(or (>= (angle L3 z-axis) 355) (<= (angle L3 z-axis) 5))"
    for angle in (358.0, 2.0, 0.0, 355.0, 5.0, -0.005):
        assert w.holds(angle), angle
    for angle in (6.0, 354.0, 180.0):
        assert not w.holds(angle), angle


def test_window_crossing_360_from_above() -> None:
    w = AngleWindow("L3", "xy-axes", 357.5, 5.0)
    assert w.pddl() == "(or (>= (angle L3 xy-axes) 352.5) (<= (angle L3 xy-axes) 2.5))"
    assert w.holds(1.0) and w.holds(359.0) and not w.holds(3.0)


def test_window_inside_the_range_is_two_bounds() -> None:
    w = AngleWindow("L5", "z-axis", 100.3, 5.0)
    assert w.pddl_parts() == ("(>= (angle L5 z-axis) 95.3)", "(<= (angle L5 z-axis) 105.3)")
    assert w.holds(95.3) and w.holds(105.3) and not w.holds(105.4)


def test_window_goal_text_accepts_the_right_angles() -> None:
    """Evaluate the written PDDL disjunction, not only the Python mirror."""
    obj = ArticulatedObject(3)
    text = make_goal(obj, _target(3, 0.0), "window").pddl()
    assert text.count("(or ") == 2  # both planes of L3 wrap
    pattern = r"\(or \(>= \(angle L3 xy-axes\) ([-\d.]+)\) \(<= \(angle L3 xy-axes\) ([-\d.]+)\)\)"
    match = re.search(pattern, text)
    assert match is not None
    lo, hi = float(match.group(1)), float(match.group(2))

    def holds_text(angle: float) -> bool:
        return angle >= lo or angle <= hi

    assert holds_text(358.0) and holds_text(2.0) and not holds_text(10.0)
    assert not holds_text(350.0)


def test_threshold_goal_is_the_papers() -> None:
    obj = ArticulatedObject(5)
    target = Configuration.from_angles([0, 0, 120.5, 0, 200], [0, 0, 30, 0, 5.2])
    goal = make_goal(obj, target, "threshold", seed=0)
    lower = [c for c in goal.conditions if isinstance(c, AngleBound) and c.op == ">"]
    upper = [c for c in goal.conditions if isinstance(c, AngleBound) and c.op == "<"]
    assert [(c.link, c.plane) for c in lower] == [
        ("L3", "xy-axes"),
        ("L3", "z-axis"),
        ("L5", "xy-axes"),
        ("L5", "z-axis"),
    ]
    assert [round(c.value, 6) for c in lower] == [110.5, 20.0, 190.0, -4.8]
    assert len(upper) == 1
    u = upper[0]
    assert round(u.value - target.angle(obj.index(u.link), u.plane), 6) == 10.0
    assert goal.holds(obj, target)
    assert goal.pddl().startswith("(and\n    (> (angle L3 xy-axes) 110.5)")


def test_threshold_upper_bound_depends_on_the_seed() -> None:
    obj = ArticulatedObject(8)
    target = Configuration.from_angles([float(i) for i in range(8)], [float(i) for i in range(8)])
    choices = set()
    for seed in range(20):
        goal = make_goal(obj, target, "threshold", seed=seed)
        upper = [c for c in goal.conditions if isinstance(c, AngleBound) and c.op == "<"]
        choices.add((upper[0].link, upper[0].plane))
        assert goal == make_goal(obj, target, "threshold", seed=seed)
    assert len(choices) > 1


def test_goal_holds_checks_configurations() -> None:
    obj = ArticulatedObject(3)
    goal = make_goal(obj, _target(3, 100.0), "window")
    assert goal.holds(obj, _target(3, 103.0))
    assert not goal.holds(obj, _target(3, 106.0))
    assert goal.links == ("L3",)


def test_bad_goal_style() -> None:
    with pytest.raises(ValueError, match="valid styles"):
        make_goal(ArticulatedObject(3), _target(3, 1.0), "exact")
