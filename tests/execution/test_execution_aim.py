"""Goal windows moved by the residuals of plans that ended short (execution.aim)."""

from __future__ import annotations

import pytest

from artiplan.encoding import make_goal
from artiplan.encoding.goals import AngleWindow, GoalSpec
from artiplan.execution.aim import VERTICAL, Aim
from artiplan.execution.problem import canonical
from artiplan.model import ArticulatedObject, Configuration

OBJ = ArticulatedObject(6)
TARGET = Configuration((10.0, 40.0, 100.0, 200.0, 300.0, 20.0),
                       (30.0, 60.0, 120.0, 80.0, 110.0, 40.0))


def _with(gammas: dict[int, float], thetas: dict[int, float] | None = None) -> Configuration:
    g = list(TARGET.gamma)
    t = list(TARGET.theta)
    for i, v in gammas.items():
        g[i] = v
    for i, v in (thetas or {}).items():
        t[i] = v
    return Configuration(tuple(t), tuple(g))


def _centres(goal: GoalSpec, link: str) -> dict[str, float]:
    return {c.plane: c.centre for c in goal.conditions
            if isinstance(c, AngleWindow) and c.link == link}


def test_a_sagging_residual_aims_higher_next_time() -> None:
    aim = Aim()
    goal = make_goal(OBJ, canonical(TARGET), "window", tolerance=1.5)
    links = goal.links
    # L3 ended 6 deg low, L5 2 deg high: the next NG plans aim L3 6 higher, L5 2 lower.
    used = aim.observe(OBJ, "ng", TARGET, _with({2: 114.0, 4: 112.0}), links)
    assert used == {lk: pytest.approx(r) for lk, r in
                    {"L3": -6.0, "L5": 2.0}.items() if lk in links}
    moved = aim.goal(goal, "ng")
    for lk, off in (("L3", 6.0), ("L5", -2.0)):
        if lk not in links:
            continue
        before, after = _centres(goal, lk), _centres(moved, lk)
        assert after[VERTICAL] == pytest.approx(before[VERTICAL] + off)
        # Only the vertical plane moves: sag is on it; theta residuals were unbiased.
        assert {p: v for p, v in after.items() if p != VERTICAL} == \
            {p: v for p, v in before.items() if p != VERTICAL}
    # Another model's plans aim at the target itself.
    assert aim.goal(goal, "ucm") == goal


def test_residuals_accumulate_and_are_clipped() -> None:
    aim = Aim(limit_deg=10.0)
    links = ("L3",)
    aim.observe(OBJ, "ng", TARGET, _with({2: 114.0}), links)
    # The next plan, aimed 6 deg up, still ended 3 low: the offset grows (integral action).
    aim.observe(OBJ, "ng", TARGET, _with({2: 117.0}), links)
    assert aim.of("ng") == {"L3": pytest.approx(9.0)}
    aim.observe(OBJ, "ng", TARGET, _with({2: 116.0}), links)
    assert aim.of("ng") == {"L3": pytest.approx(10.0)}
    # An overshoot brings it back.
    aim.observe(OBJ, "ng", TARGET, _with({2: 124.0}), links)
    assert aim.of("ng") == {"L3": pytest.approx(6.0)}


def test_far_off_or_polar_links_teach_nothing() -> None:
    aim = Aim(max_error_deg=25.0, pole_deg=10.0)
    # L3 40 deg low: not a residual of a plan that nearly reached.
    assert aim.observe(OBJ, "ng", TARGET, _with({2: 80.0}), ("L3",)) == {}
    # A target 5 deg from straight down: gamma there is not a sag's measure.
    polar = Configuration(TARGET.theta, (30.0, 60.0, 5.0, 80.0, 110.0, 40.0))
    near = Configuration(TARGET.theta, (30.0, 60.0, 2.0, 80.0, 110.0, 40.0))
    assert aim.observe(OBJ, "ng", polar, near, ("L3",)) == {}
    assert aim.of("ng") == {}


def test_the_other_cover_gives_the_same_residual() -> None:
    # (theta + 180, 360 - gamma) is the same direction: the residual is read on canonical covers.
    aim = Aim()
    flipped = _with({2: 360.0 - 114.0}, {2: TARGET.theta[2] + 180.0})
    assert aim.observe(OBJ, "ng", TARGET, flipped, ("L3",)) == {"L3": pytest.approx(-6.0)}


def test_moved_windows_stay_off_the_poles() -> None:
    high = Configuration(TARGET.theta, (30.0, 60.0, 169.0, 80.0, 110.0, 40.0))
    goal = make_goal(OBJ, canonical(high), "window", tolerance=1.5)
    aim = Aim()
    aim.observe(OBJ, "ng", high, Configuration(TARGET.theta, (30.0, 60.0, 159.0, 80.0, 110.0,
                                                             40.0)), ("L3",))
    assert aim.of("ng") == {"L3": pytest.approx(10.0)}
    centre = _centres(aim.goal(goal, "ng"), "L3")[VERTICAL]
    assert centre == pytest.approx(178.5)  # 169 + 10, clamped at 180 - 1.5


def test_a_released_goal_link_that_sank_is_aimed_higher() -> None:
    aim = Aim()
    predicted = TARGET
    # L3 sank 9 deg while released (an NG plan predicts it stays): aim it 9 higher.
    assert aim.observe_sag(OBJ, "ng", predicted, _with({2: 111.0}), "L3") == pytest.approx(-9.0)
    assert aim.of("ng") == {"L3": pytest.approx(9.0)}
    # Not sag: it rose, it moved mostly sideways, or it is far off (a push, a lost grasp).
    assert aim.observe_sag(OBJ, "ng", predicted, _with({4: 119.0}), "L5") is None
    sideways = _with({4: 107.0}, {4: TARGET.theta[4] + 12.0})
    assert aim.observe_sag(OBJ, "ng", predicted, sideways, "L5") is None
    assert aim.observe_sag(OBJ, "ng", predicted, _with({4: 70.0}), "L5") is None
    assert aim.of("ng") == {"L3": pytest.approx(9.0)}
    # Sinking again adds up (and stays within the limit).
    aim.observe_sag(OBJ, "ng", predicted, _with({2: 115.0}), "L3")
    assert aim.of("ng") == {"L3": pytest.approx(10.0)}
