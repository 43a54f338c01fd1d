"""The planner on a general PDDL+ domain (a linear car): numeric heuristic, timing repair."""

from __future__ import annotations

import math

from artiplan.pddl import load_task
from artiplan.search.api import PlanStatus, plan
from artiplan.search.numeric import NumericHeuristic, _time_to
from artiplan.search.timing import Repair, repair_times
from artiplan.semantics import Kernel, compile_task
from artiplan.semantics.plan import Plan, TimedAction
from artiplan.semantics.validator import validate

# The car of the PDDL+ literature: `a` moved by actions, v' = a, d' = v; stop in a window.
CAR = """(define (domain car)
  (:requirements :typing :fluents :time)
  (:predicates (running) (stopped))
  (:functions (d) (v) (a) (d-min) (d-max) (v-tol))
  (:process moving :parameters () :precondition (and (running))
    :effect (and (increase (v) (* #t (a))) (increase (d) (* #t (v)))))
  (:action accelerate :parameters () :precondition (and (running) (< (a) 1))
    :effect (and (increase (a) 1)))
  (:action decelerate :parameters () :precondition (and (running) (> (a) -1))
    :effect (and (decrease (a) 1)))
  (:action stop :parameters ()
    :precondition (and (running) (>= (d) (d-min)) (<= (d) (d-max))
                       (<= (v) (v-tol)) (>= (+ (v) (v-tol)) 0))
    :effect (and (not (running)) (stopped))))
"""
PROBLEM = """(define (problem car-1) (:domain car)
  (:init (running) (= (d) 0) (= (v) 0) (= (a) 0) (= (d-min) 9) (= (d-max) 11) (= (v-tol) 0.3))
  (:goal (and (stopped))))
"""


def test_the_car_is_planned_and_the_plan_is_valid() -> None:
    result = plan(CAR, PROBLEM, time_limit=60)
    assert result.status is PlanStatus.SOLVED, result.message
    assert result.plan is not None
    names = [a.name for a in result.plan.actions]
    assert names[0] == "accelerate" and names[-1] == "stop"
    assert "decelerate" in names
    report = validate(load_task(CAR, PROBLEM), result.plan)
    assert report.valid, report.reason


def test_the_heuristic_chains_distance_speed_and_acceleration() -> None:
    ct = compile_task(load_task(CAR, PROBLEM))
    heur = NumericHeuristic(ct)
    kernel = Kernel(ct)
    values = tuple(ct.init_values)
    ev = heur.evaluate(ct.init_facts, values, kernel.active(ct.init_facts, values))
    assert math.isfinite(ev.h) and ev.h > 0
    # only accelerating starts the chain d <- v <- a (stop's window is far, a = 0 already)
    preferred = {ct.actions[i].name for i in ev.preferred}
    assert preferred == {"accelerate"}


def test_timing_repair_moves_a_skeleton_onto_valid_times() -> None:
    task = load_task(CAR, PROBLEM)
    ct = compile_task(task)
    index = {a.name: a.index for a in ct.actions}
    skeleton = [index[n] for n in ("accelerate", "decelerate", "decelerate", "accelerate", "stop")]
    # guessed times: the car stops far too early (d about 4 at t=5)
    guess = [0.0, 2.0, 2.001, 4.0, 5.0]
    bad = Plan(tuple(TimedAction(t, ct.actions[a].name, ()) for a, t in zip(skeleton, guess,
                                                                             strict=True)))
    assert not validate(task, bad).valid
    fixed = repair_times(ct, Kernel(ct), skeleton, guess, Repair())
    assert fixed is not None
    good = Plan(tuple(TimedAction(round(t, 6), ct.actions[a].name, ())
                      for a, t in zip(skeleton, fixed, strict=True)))
    report = validate(task, good)
    assert report.valid, report.reason


def test_second_order_time_to_a_need() -> None:
    # need 2 at rate 0 with acceleration 1: t^2/2 = 2 -> t = 2
    t = _time_to(2.0, 0.0, 1.0)
    assert t is not None and abs(t - 2.0) < 1e-9
    # a rate that points the wrong way and decelerates further never gets there
    assert _time_to(2.0, -1.0, -1.0) is None


def test_fractional_powers_are_real_or_undefined() -> None:
    import pytest

    from artiplan.semantics.walks import DomainError, power

    assert power(4.0, 0.5) == 2.0
    assert power(-2.0, 2) == 4.0
    assert power(-1e-12, 0.5) == 0.0  # a level drained to 0, rounded below it
    with pytest.raises(DomainError):
        power(-1.0, 0.5)
    with pytest.raises(ZeroDivisionError):  # callers treat both as "undefined here"
        power(-1.0, 0.5)


def test_a_time_only_worse_condition_is_a_deadline_and_a_switchable_one_is_not() -> None:
    # clock only grows (a deadline for `clock <= 5`); `temp` cools or heats by actions
    domain = """(define (domain d) (:requirements :fluents :time)
      (:predicates (on) (heating) (done))
      (:functions (clock) (temp))
      (:process tick :parameters () :precondition (on) :effect (increase (clock) (* #t 1)))
      (:process cool :parameters () :precondition (on) :effect (decrease (temp) (* #t 1)))
      (:process heat :parameters () :precondition (and (on) (heating))
        :effect (increase (temp) (* #t 3)))
      (:action heater-on :parameters () :precondition (not (heating)) :effect (heating))
      (:action finish :parameters ()
        :precondition (and (<= (clock) 5) (>= (temp) 1)) :effect (done)))"""
    problem = """(define (problem p) (:domain d)
      (:init (on) (= (clock) 0) (= (temp) 3)) (:goal (done)))"""
    ct = compile_task(load_task(domain, problem))
    heur = NumericHeuristic(ct)
    kinds = {heur.conds[k].op: k in heur.deadlines for k in range(len(heur.conds))}
    assert kinds["<="] is True  # clock <= 5
    assert kinds[">="] is False  # temp >= 1: the heater turns it around


def test_a_repair_never_imports_scipy() -> None:
    # scipy.optimize costs most of a second of CPU to import, more than most plans: the
    # repair's solver is our own. A fresh interpreter, since another test may have imported
    # scipy already.
    import subprocess
    import sys

    child = f"""
import sys
from artiplan.pddl import load_task
from artiplan.search.timing import Repair, repair_times
from artiplan.semantics import Kernel, compile_task
ct = compile_task(load_task({CAR!r}, {PROBLEM!r}))
ix = {{a.name: a.index for a in ct.actions}}
# the second stop needs (running), which the first deletes: no time can fix that
assert repair_times(ct, Kernel(ct), [ix["stop"], ix["stop"]], [0.0, 5.0], Repair()) is None
sk = [ix[n] for n in ("accelerate", "decelerate", "decelerate", "accelerate", "stop")]
assert repair_times(ct, Kernel(ct), sk, [0.0, 2.0, 2.001, 4.0, 5.0], Repair()) is not None
print(sorted(m for m in sys.modules if m.split(".")[0] in ("scipy", "numpy")))
"""
    out = subprocess.run([sys.executable, "-c", child], capture_output=True, text=True,
                         check=True).stdout.strip()
    assert out == "[]"
