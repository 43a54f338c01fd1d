"""The thermostat family: keep every room in its comfort band for a whole shift (a global
constraint), switching heaters under a power limit.

Rooms lose heat at a constant rate; a heater that is on adds its rate (processes). ENHSP's global
constraint ``(:constraint comfort :parameters (?r - room) :condition ...)`` requires every room
within [t-low, t-high] over the whole trajectory; at most ``max-power`` heaters run at once; the
shift ends (``end-shift``) once the clock reaches the horizon, with every room at least at its
``t-goal`` (a goal on the temperatures: without one ENHSP's relevance analysis drops them and
calls the initial state invalid).

Reference plans: a hysteresis controller (on at low + 15% of the band, off at high - 15%); a
room that finds no free power waits for the next heater to go off; the power limit is the
smallest under which this controller keeps every room in its band.
"""

from __future__ import annotations

import random
from dataclasses import dataclass

from gen.common import GAP, Family, Instance, Step, num, plan_text

_DOMAIN = """(define (domain {name})
  (:requirements :typing :fluents :time :negative-preconditions)
  (:types room)
  (:predicates (heating ?r - room) (on-shift) (shift-done) (in-building ?r - room){preds})
  (:functions (temp ?r - room) (heat-rate ?r - room) (loss-rate ?r - room)
              (t-low ?r - room) (t-high ?r - room) (t-goal ?r - room)
              (clock) (horizon) (power-used) (max-power))
{constraint}\
  ;; (in-building ?r) is static; it is here because stock VAL's Validate crashes (SIGSEGV) on
  ;; a process whose precondition does not mention its parameter
  (:process cooling
    :parameters (?r - room)
    :precondition (and (on-shift) (in-building ?r))
    :effect (and (decrease (temp ?r) (* #t (loss-rate ?r)))))
  (:process heat
    :parameters (?r - room)
    :precondition (and (on-shift) (heating ?r))
    :effect (and (increase (temp ?r) (* #t (heat-rate ?r)))))
  (:process shift-clock
    :parameters ()
    :precondition (and (on-shift))
    :effect (and (increase (clock) (* #t 1))))
  (:action heater-on
    :parameters (?r - room)
    :precondition (and (on-shift) (not (heating ?r)) (< (power-used) (max-power)))
    :effect (and (heating ?r) (increase (power-used) 1)))
  (:action heater-off
    :parameters (?r - room)
    :precondition (and (heating ?r))
    :effect (and (not (heating ?r)) (decrease (power-used) 1)))
  (:action end-shift
    :parameters ()
    :precondition (and (on-shift) (>= (clock) (horizon)){end_extra})
    :effect (and (not (on-shift)) (shift-done)))
)
"""

_CONSTRAINT = """\
  ;; ENHSP global constraint: every room stays in its band over the whole trajectory
  (:constraint comfort
    :parameters (?r - room)
    :condition (and (>= (temp ?r) (t-low ?r)) (<= (temp ?r) (t-high ?r))))
"""

_TWIN_EVENTS = """  ;; VAL twin of the global constraint: leaving a band makes the shift a failure
  (:event too-cold
    :parameters (?r - room)
    :precondition (and (on-shift) (not (uncomfortable)) (< (temp ?r) (t-low ?r)))
    :effect (and (uncomfortable)))
  (:event too-hot
    :parameters (?r - room)
    :precondition (and (on-shift) (not (uncomfortable)) (> (temp ?r) (t-high ?r)))
    :effect (and (uncomfortable)))
"""

DOMAIN = _DOMAIN.format(name="thermostat", preds="", constraint=_CONSTRAINT, end_extra="")
TWIN = _DOMAIN.format(name="thermostat-val", preds=" (uncomfortable)", constraint=_TWIN_EVENTS,
                      end_extra=" (not (uncomfortable))")

# (rooms, band width [deg C], horizon [s])
SIZES = ((1, 4.0, 30), (1, 3.0, 60), (2, 3.0, 60), (2, 2.0, 90), (3, 2.0, 120), (3, 1.5, 150),
         (4, 1.5, 180), (5, 1.2, 200), (6, 1.0, 240), (8, 1.0, 300))
HYSTERESIS = 0.15  # share of the band


@dataclass
class Room:
    name: str
    temp: float
    heat: float
    loss: float
    low: float
    high: float
    on: bool = False

    @property
    def margin(self) -> float:
        return HYSTERESIS * (self.high - self.low)


def controller(rooms: list[Room], horizon: float, power: int) -> tuple[list[Step], float]:
    """The hysteresis plan and the lowest (temp - t-low) / band it reaches. Exact (linear)."""
    now, last = 0.0, -GAP
    steps: list[Step] = []
    worst = 1.0
    waiting: list[Room] = []

    def coldness(r: Room) -> float:
        return (r.temp - r.low) / (r.high - r.low)

    while True:
        used = sum(r.on for r in rooms)
        options: list[tuple[float, int, float, Room]] = []
        for r in rooms:
            if r.on:
                options.append((now + (r.high - r.margin - r.temp) / (r.heat - r.loss), 1, 0, r))
            elif r in waiting:
                if used < power:  # power is free again: the coldest waiting room first
                    options.append((now, 0, coldness(r), r))
            else:
                options.append((now + max(r.temp - r.low - r.margin, 0.0) / r.loss, 2, 0, r))
        at, _, _, room = min(options, key=lambda o: (o[0], o[1], o[2], o[3].name))
        when = min(max(at, last + GAP), horizon)
        for r in rooms:
            r.temp += ((r.heat if r.on else 0.0) - r.loss) * (when - now)
            worst = min(worst, coldness(r))
        now = when
        if when >= horizon:
            return steps, worst
        if room.on:
            room.on = False
            steps.append(Step(when, f"heater-off {room.name}"))
        elif used < power:
            room.on = True
            if room in waiting:
                waiting.remove(room)
            steps.append(Step(when, f"heater-on {room.name}"))
        else:
            waiting.append(room)
            continue
        last = when


def _rooms(rng: random.Random, n: int, band: float) -> list[Room]:
    rooms = []
    for i in range(1, n + 1):
        low = round(rng.uniform(18, 21), 1)
        loss = round(rng.uniform(0.05, 0.2), 3)
        heat = round(loss + rng.uniform(0.15, 0.4), 3)
        temp = round(low + band * rng.uniform(0.4, 0.6), 2)
        rooms.append(Room(f"r{i}", temp, heat, loss, low, round(low + band, 1)))
    return rooms


def _problem(name: str, domain: str, rooms: list[Room], horizon: float, power: int) -> str:
    init = ["(on-shift) (= (clock) 0)", f"(= (horizon) {num(horizon)})",
            f"(= (power-used) 0) (= (max-power) {power})"]
    for r in rooms:
        init.append(f"(in-building {r.name}) (= (temp {r.name}) {num(r.temp)}) "
                    f"(= (heat-rate {r.name}) {num(r.heat)}) "
                    f"(= (loss-rate {r.name}) {num(r.loss)})")
        init.append(f"(= (t-low {r.name}) {num(r.low)}) (= (t-high {r.name}) {num(r.high)}) "
                    f"(= (t-goal {r.name}) {num(r.low + r.margin / 3)})")
    goal = " ".join(f"(>= (temp {r.name}) (t-goal {r.name}))" for r in rooms)
    body = "\n    ".join(init)
    objs = " ".join(r.name for r in rooms)
    return (f"(define (problem {name})\n  (:domain {domain})\n  (:objects {objs} - room)\n"
            f"  (:init\n    {body})\n  (:goal (and (shift-done) {goal})))\n")


def _build() -> list[Instance]:
    rng = random.Random(61)
    out = []
    for size, (n, band, horizon) in enumerate(SIZES, start=1):
        rooms = _rooms(rng, n, band)
        initial = [Room(**vars(r)) for r in rooms]
        for power in range(1, n + 1):  # the tightest limit the controller survives
            trial = [Room(**vars(r)) for r in initial]
            steps, worst = controller(trial, horizon, power)
            if worst > 0.05 and all(r.temp >= r.low + r.margin / 3 + 0.01 for r in trial):
                break
        else:
            raise AssertionError(f"thermostat size {size}: no power limit works")
        steps.append(Step(horizon + GAP, "end-shift"))
        name = f"thermostat-{size:02d}"
        header = (f"reference plan (generator): hysteresis control, {len(steps) - 1} switches, "
                  f"power limit {power} of {n}, coldest point {worst:.0%} of the band")
        out.append(Instance(
            size=size, problem=_problem(name, "thermostat", initial, horizon, power),
            plan=plan_text(steps, header), plan_check="val-twin",
            val_problem=_problem(name, "thermostat-val", initial, horizon, power),
            params={"rooms": n, "band": band, "horizon": horizon, "max_power": power,
                    "switches": len(steps) - 1},
        ))
    return out


FAMILIES = [
    Family(
        name="thermostat",
        summary="HVAC under an ENHSP global constraint (:constraint comfort, parameterised by "
                "room: every room in its band over the whole trajectory), heaters switched "
                "under a power limit until a horizon; grows rooms and horizon, narrows the band",
        features=("processes", "linear", "global-constraints"),
        domain=DOMAIN, build=_build, val_reads=False, val_domain=TWIN,
        notes="VAL cannot read ENHSP's :constraint; the VAL twin turns it into events that "
              "mark the shift a failure; ENHSP needs a goal on the temperatures (its "
              "relevance analysis otherwise drops them and calls the initial state invalid); "
              "ENHSP rejects forall inside :constraint, so the constraint is parameterised",
    ),
]
