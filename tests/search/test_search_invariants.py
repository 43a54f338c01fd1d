"""Threatened invariants (search/invariants.py): a thermostat under a global constraint."""

from __future__ import annotations

import math

from artiplan.pddl import load_task
from artiplan.search.api import PlanStatus, plan
from artiplan.search.invariants import Threats
from artiplan.semantics import Kernel, compile_task
from artiplan.semantics.validator import validate

# Two rooms, one heater's worth of power, every room in its band until the horizon.
DOMAIN = """(define (domain thermostat)
  (:requirements :typing :fluents :time :negative-preconditions)
  (:types room)
  (:predicates (heating ?r - room) (on-shift) (shift-done) (in-building ?r - room))
  (:functions (temp ?r - room) (heat-rate ?r - room) (loss-rate ?r - room)
              (t-low ?r - room) (t-high ?r - room) (clock) (horizon) (power-used) (max-power))
  (:constraint comfort :parameters (?r - room)
    :condition (and (>= (temp ?r) (t-low ?r)) (<= (temp ?r) (t-high ?r))))
  (:process cooling :parameters (?r - room) :precondition (and (on-shift) (in-building ?r))
    :effect (and (decrease (temp ?r) (* #t (loss-rate ?r)))))
  (:process heat :parameters (?r - room) :precondition (and (on-shift) (heating ?r))
    :effect (and (increase (temp ?r) (* #t (heat-rate ?r)))))
  (:process shift-clock :parameters () :precondition (and (on-shift))
    :effect (and (increase (clock) (* #t 1))))
  (:action heater-on :parameters (?r - room)
    :precondition (and (on-shift) (not (heating ?r)) (< (power-used) (max-power)))
    :effect (and (heating ?r) (increase (power-used) 1)))
  (:action heater-off :parameters (?r - room) :precondition (and (heating ?r))
    :effect (and (not (heating ?r)) (decrease (power-used) 1)))
  (:action end-shift :parameters () :precondition (and (on-shift) (>= (clock) (horizon)))
    :effect (and (not (on-shift)) (shift-done))))
"""
PROBLEM = """(define (problem thermostat-2) (:domain thermostat)
  (:objects r1 r2 - room)
  (:init (on-shift) (= (clock) 0) (= (horizon) 80) (= (power-used) 0) (= (max-power) 1)
    (in-building r1) (= (temp r1) 20.2) (= (heat-rate r1) 0.4) (= (loss-rate r1) 0.07)
    (= (t-low r1) 19.3) (= (t-high r1) 21.3)
    (in-building r2) (= (temp r2) 20.1) (= (heat-rate r2) 0.43) (= (loss-rate r2) 0.2)
    (= (t-low r2) 18.9) (= (t-high r2) 20.9))
  (:goal (and (shift-done))))
"""


def _setup() -> tuple[Threats, Kernel, dict[str, int], dict[str, int]]:
    ct = compile_task(load_task(DOMAIN, PROBLEM), strict=True)  # as the planner reads it
    kernel = Kernel(ct)
    threats = Threats(ct, kernel, lead=0.032)
    acts = {f"{a.name} {' '.join(a.args)}": a.index for a in ct.actions}
    fluents = {str(f): i for i, f in enumerate(ct.task.fluents)}
    return threats, kernel, acts, fluents


def test_a_thermostat_that_needs_many_switches_is_planned_and_valid() -> None:
    result = plan(DOMAIN, PROBLEM, time_limit=60)
    assert result.status is PlanStatus.SOLVED, result.message
    assert result.plan is not None
    ons = [a.args[0] for a in result.plan.actions if a.name == "heater-on"]
    # r2 loses 0.2 K/s in a 1.2 K band for 80 s: it must be heated again and again
    assert ons.count("r2") >= 3 and "r1" in ons
    assert result.plan.actions[-1].name == "end-shift"
    report = validate(load_task(DOMAIN, PROBLEM), result.plan)
    assert report.valid, report.reason


def test_the_threat_is_the_room_that_leaves_its_band_first_and_heating_it_saves_it() -> None:
    threats, kernel, acts, fluents = _setup()
    ct = threats.ct
    values = ct.init_values
    dt, comps = threats.first(values, kernel.active(ct.init_facts, values))
    # r1 reaches 19.3 after 0.9 / 0.07 = 12.9 s, r2 reaches 18.9 after 1.2 / 0.2 = 6 s
    assert math.isclose(dt, 6.0, abs_tol=1e-6)
    assert [ct.comps.items[c].fluents for c in comps] == [{fluents["(temp r2)"]}]
    assert threats.rescues(ct.init_facts, values, comps, dt) == [acts["heater-on r2"]]


def test_a_rescue_blocked_by_the_power_limit_makes_the_release_preferred() -> None:
    threats, kernel, acts, _ = _setup()
    ct = threats.ct
    _, low_r2 = threats.first(ct.init_values, kernel.active(ct.init_facts, ct.init_values))
    # r1's heater takes the only unit of power: heating r2 needs r1's heater off first
    facts, values = ct.actions[acts["heater-on r1"]].effect(ct.init_facts, ct.init_values)
    dt, comps = threats.first(values, kernel.active(facts, values))
    # r1 now reaches 21.3 first (1.1 K at 0.33 K/s): switching it off saves it
    assert math.isclose(dt, 1.1 / 0.33, abs_tol=1e-6) and comps != low_r2
    assert threats.rescues(facts, values, comps, dt) == [acts["heater-off r1"]]
    # r2 (6 s to its floor) is saved by its heater, which the power limit blocks
    assert threats.rescues(facts, values, low_r2, 6.0) == [acts["heater-off r1"]]
    free = ct.actions[acts["heater-off r1"]].effect(facts, values)
    assert threats.rescues(*free, low_r2, 6.0) == [acts["heater-on r2"]]


def test_the_search_is_offered_a_wait_to_lead_seconds_before_the_threat() -> None:
    threats, kernel, acts, _ = _setup()
    ct = threats.ct
    seconds, saving, close = threats.advice(0.0, ct.init_facts, ct.init_values,
                                            kernel.active(ct.init_facts, ct.init_values))
    assert saving == [] and not close and math.isclose(seconds, 6.0 - 0.032, abs_tol=2e-6)
    # 6 s later r2 is 0.032 s from its floor: heating it is the rescue, unless the search
    # says no (the threat came from its own last action)
    flow = kernel.flow_of(kernel.active(ct.init_facts, ct.init_values), ct.init_values)
    later = flow.values(ct.init_values, 6.0 - 0.032)
    active = kernel.active(ct.init_facts, later)
    assert threats.advice(5.968, ct.init_facts, later, active) == (
        0.0, [acts["heater-on r2"]], True)
    assert threats.advice(5.968, ct.init_facts, later, active, rescue=False) == (0.0, [], True)
