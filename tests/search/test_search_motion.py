"""Second-order motion in the numeric relaxation: controls, the double integrator's least time,
and plans that need the acceleration raised more than once (search/motion.py)."""

from __future__ import annotations

import math

import pytest

from artiplan.pddl import load_task
from artiplan.search.api import PlanStatus, plan
from artiplan.search.motion import find_controls, find_motions, speed_limits
from artiplan.search.numeric import NumericHeuristic
from artiplan.search.profile import Rate, box_profile, point_time, profile
from artiplan.semantics import Kernel, compile_task
from artiplan.semantics.validator import validate

# The car of the PDDL+ literature with a deadline (the benchmark set's car_linear, smaller):
# a in -max..max, v' = a, d' = v, an engine that blows above v-max, a stop window and a clock.
CAR = """(define (domain car-deadline)
  (:requirements :typing :fluents :time)
  (:predicates (running) (stopped) (engine-blown))
  (:functions (d) (v) (a) (clock) (max-a) (min-a) (v-max) (d-min) (d-max) (v-tol) (deadline))
  (:process moving :parameters () :precondition (and (running))
    :effect (and (increase (v) (* #t (a))) (increase (d) (* #t (v)))
                 (increase (clock) (* #t 1))))
  (:event engine-explodes :parameters () :precondition (and (running) (> (v) (v-max)))
    :effect (and (not (running)) (engine-blown)))
  (:action accelerate :parameters () :precondition (and (running) (< (a) (max-a)))
    :effect (and (increase (a) 1)))
  (:action decelerate :parameters () :precondition (and (running) (> (a) (min-a)))
    :effect (and (decrease (a) 1)))
  (:action stop :parameters ()
    :precondition (and (running) (>= (d) (d-min)) (<= (d) (d-max))
                       (<= (v) (v-tol)) (>= (+ (v) (v-tol)) 0) (<= (clock) (deadline)))
    :effect (and (not (running)) (stopped))))
"""


def problem(max_a: int, window: tuple[float, float], deadline: float, v_max: float = 30.0,
            v_tol: float = 0.2) -> str:
    return f"""(define (problem car-p) (:domain car-deadline)
  (:init (running) (= (d) 0) (= (v) 0) (= (a) 0) (= (clock) 0) (= (max-a) {max_a})
    (= (min-a) {-max_a}) (= (v-max) {v_max}) (= (d-min) {window[0]}) (= (d-max) {window[1]})
    (= (v-tol) {v_tol}) (= (deadline) {deadline}))
  (:goal (and (stopped))))
"""


# 50 m in 11 s, rest to rest: a = 1 up and -2 down takes sqrt(3 * 50) = 12.2 s, a = +-2 takes
# 10 s. The plan must accelerate twice and brake four times.
TWICE = problem(2, (49.0, 51.0), 11.0)


def test_controls_are_the_fluents_actions_step_between_bounds() -> None:
    task = load_task(CAR, TWICE)
    controls = find_controls(task)
    a = task.fluents.index("(a)")
    assert set(controls) == {a}
    assert controls[a].levels == (-2.0, -1.0, 0.0, 1.0, 2.0)
    names = {task.actions[i].name for i in controls[a].raise_by}
    assert names == {"accelerate"}
    motions = find_motions(task, controls)
    d, v = task.fluents.index("(d)"), task.fluents.index("(v)")
    assert set(motions) == {d} and motions[d].y == v and motions[d].k == 1.0
    # the engine blows above v-max and nothing restarts it: a speed limit for stop
    (limit,) = speed_limits(task, {v})
    assert limit.hi == 30.0 and limit.lost


def test_point_time_is_the_bang_bang_optimum() -> None:
    # rest to rest over 50 with +-2: 2 * sqrt(50 / 2), switching half way
    found = point_time(50.0, 0.0, 0.0, 2.0, 2.0)
    t, up, first = found.time, found.up, found.first
    assert t == pytest.approx(10.0) and up and first == pytest.approx(5.0)
    # a cap at 4: 2 s up (then a cruise needs another level), 2 s down, 42 m cruising
    found = point_time(50.0, 0.0, 0.0, 2.0, 2.0, vhi=4.0)
    t, _, first = found.time, found.up, found.first
    assert t == pytest.approx(4.0 + 42.0 / 4.0) and first == pytest.approx(2.0)
    # moving at 10 toward a point 10 ahead, braking at 1: overshoot by 40, then come back
    found = point_time(10.0, 10.0, 0.0, 1.0, 1.0)
    t, up, _ = found.time, found.up, found.first
    assert t == pytest.approx(10.0 + 2.0 * math.sqrt(40.0)) and not up
    # cannot accelerate: cruise, then brake
    found = point_time(100.0, 18.0, 0.0, 0.0, 3.0)
    t, _, first = found.time, found.up, found.first
    assert t == pytest.approx((100.0 - 54.0) / 18.0 + 6.0, rel=1e-6)
    assert first == pytest.approx((100.0 - 54.0) / 18.0, rel=1e-6)


def test_point_time_is_symmetric_under_mirroring() -> None:
    """Negating positions and speeds and swapping the two rates mirrors a peak into a valley:
    the least time is the same and the first phase's direction flips."""
    import random

    rnd = random.Random(7)
    for _ in range(300):
        dist, y0, yf = rnd.uniform(-50, 50), rnd.uniform(-10, 10), rnd.uniform(-10, 10)
        al, be = rnd.uniform(0.2, 4.0), rnd.uniform(0.2, 4.0)
        vhi = rnd.uniform(max(y0, yf, 0.0) + 0.1, 20.0)
        vlo = rnd.uniform(-20.0, min(y0, yf, 0.0) - 0.1)
        a = point_time(dist, y0, yf, al, be, vhi, vlo)
        b = point_time(-dist, -y0, -yf, be, al, -vlo, -vhi)
        assert a.time == pytest.approx(b.time, rel=1e-9, abs=1e-9)
        assert a.first == pytest.approx(b.first, rel=1e-9, abs=1e-9)
        assert a.up != b.up


def test_a_tabulated_rate_agrees_with_the_closed_form_and_sees_drag() -> None:
    up = Rate(lambda w: 2.0 + 1e-9 * w * w, -20.0, 20.0)  # nearly constant: tabulated
    down = Rate(lambda w: -2.0 - 1e-9 * w * w, -20.0, 20.0)
    assert up.const is None
    found = profile(50.0, 0.0, 0.0, up, down)
    t, up_first, first = found.time, found.up, found.first
    assert t == pytest.approx(10.0, rel=1e-3) and up_first and first == pytest.approx(5.0, 1e-3)
    # drag c = 0.02 at a = 1: terminal speed 1/sqrt(0.02) = 7.07; the level holds it
    drag = Rate(lambda w: 1.0 - 0.02 * w * w if w > 0 else 1.0, -20.0, 20.0)
    assert drag.reach(0.0, True) == pytest.approx(math.sqrt(50.0), abs=0.2)
    brake = Rate(lambda w: -1.0 - 0.02 * w * w if w > 0 else -1.0, -20.0, 20.0)
    far = profile(500.0, 0.0, 0.0, drag, brake)
    assert far.time > 500.0 / math.sqrt(50.0)  # never faster than the terminal speed
    assert far.first > far.time - 10.0  # the level holds the cruise: brake only at the end
    # coasting with drag alone (a = 0) never brings 10 m/s down to 0.05 in a minute
    coast = Rate(lambda w: -0.02 * w * w if w > 0 else 0.0, -20.0, 20.0)
    assert coast.between(10.0, 0.05)[0] > 60.0


def test_box_profile_takes_the_nearest_end() -> None:
    two, minus_two = Rate(lambda w: 2.0, -5, 5), Rate(lambda w: -2.0, -5, 5)
    t = box_profile(0.0, 0.0, (49.0, 51.0), (-0.2, 0.2), two, minus_two).time
    assert t < point_time(50.0, 0.0, 0.0, 2.0, 2.0).time
    assert box_profile(50.0, 0.1, (49.0, 51.0), (-0.2, 0.2), two, minus_two).time == 0.0


def test_the_estimate_asks_for_the_second_acceleration_and_sees_a_lost_deadline() -> None:
    task = load_task(CAR, TWICE)
    ct = compile_task(task, strict=True)
    kernel = Kernel(ct)
    heur = NumericHeuristic(ct, active_fn=kernel.active)
    (goal,) = next(o.motion for o in heur.ops if o.motion)
    facts, values, active = kernel.settle(0.0, ct.init_facts, ct.init_values, [])

    def accel(v: tuple[float, ...]) -> float:
        return heur._flow(v, kernel.active(facts, v)).get(goal.motion.y, 0.0)

    est = goal.estimate(values, accel, 11.0, facts)
    assert est is not None
    # up to +2 (two steps), down to -2 (four): a = 1 cannot make 11 s
    assert est.steps == 6 and est.time <= 11.0
    assert goal.motion.control.levels[est.first] == 2.0
    late = goal.estimate(values, accel, 9.0, facts)  # 10 s at the least
    assert late is not None and late.time == math.inf
    # the relaxation prefers accelerating, and a state with a = 1 costs more than a = 2
    ev = heur.evaluate(facts, values, active)
    assert {ct.actions[i].name for i in ev.preferred} == {"accelerate"}
    a = task.fluents.index("(a)")
    one = list(values)
    one[a] = 1.0
    two = list(values)
    two[a] = 2.0
    assert heur.evaluate(facts, tuple(two), active).h < heur.evaluate(facts, tuple(one),
                                                                      active).h


def test_a_car_that_must_accelerate_twice_is_planned() -> None:
    result = plan(CAR, TWICE, time_limit=60)
    assert result.status is PlanStatus.SOLVED, result.message
    assert result.plan is not None
    names = [a.name for a in result.plan.actions]
    assert names.count("accelerate") >= 2 and names.count("decelerate") >= 4
    assert names[-1] == "stop" and result.plan.makespan <= 11.0
    report = validate(load_task(CAR, TWICE), result.plan)
    assert report.valid, report.reason


def test_a_braking_level_cannot_cruise() -> None:
    brake = Rate(lambda w: -3.0, -20.0, 20.0)
    hold = Rate(lambda w: 0.0, -20.0, 20.0)
    # from 18 at -3 the car stops in 54: exactly that far is braking only
    assert profile(54.0, 18.0, 0.0, brake, brake).time == pytest.approx(6.0)
    # farther needs a level that holds the speed first; braking all along cannot get there
    assert profile(100.0, 18.0, 0.0, brake, brake).time == math.inf
    assert profile(100.0, 18.0, 0.0, hold, brake).time == pytest.approx(46.0 / 18.0 + 6.0)


def test_the_relaxation_asks_for_a_wait_until_the_switch() -> None:
    # two accelerations done: at +-2 over 50 m the car speeds up for 5 s, then brakes
    task = load_task(CAR, TWICE)
    ct = compile_task(task, strict=True)
    kernel = Kernel(ct)
    heur = NumericHeuristic(ct, active_fn=kernel.active)
    a = task.fluents.index("(a)")
    values = list(ct.init_values)
    values[a] = 2.0
    facts, state, active = kernel.settle(0.0, ct.init_facts, tuple(values), [])
    ev = heur.evaluate(facts, state, active)
    assert ev.hold == pytest.approx(5.0, abs=0.05)
    assert not ev.preferred or {ct.actions[i].name for i in ev.preferred} <= {"decelerate"}


def test_a_car_with_drag_is_planned_in_few_expansions() -> None:
    from pathlib import Path

    family = Path(__file__).parents[2] / "benchmarks" / "pddlplus" / "car_drag"
    domain, prob = family / "domain.pddl", family / "p05.pddl"
    result = plan(domain, prob, time_limit=60)
    assert result.status is PlanStatus.SOLVED, result.message
    assert result.plan is not None and result.stats.expanded <= 200
    names = [a.name for a in result.plan.actions]
    assert names.count("accelerate") >= 2 and names[-1] == "stop"
    report = validate(load_task(domain.read_text(), prob.read_text()), result.plan)
    assert report.valid, report.reason
