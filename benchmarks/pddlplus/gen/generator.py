"""The generator families: durative (PDDL 2.1 level 3-4), linear PDDL+, Torricelli (nonlinear).

One generator must run for ``gen-duration`` seconds, burning 1 fuel unit per second; its own tank
holds at most ``capacity`` and starts nearly full, so the fuel of the n tanks can only be poured
in while it runs, one tank at a time. The fuel left at the end (MARGIN) is less than any tank
holds: every tank must be emptied. In the larger instances the capacity is smaller than a tank:
a tank must be poured in several partial pours (a refuel shorter than its duration bound, or a
``stop-refuel`` action), each started when the level is low and stopped before it overflows.

The generator starts one unit below capacity: VAL reads the overflow event's ``fuel > capacity``
as ``fuel - capacity > -0.0001``, so an initial state at capacity would fire it, which VAL forbids
in the initial state.

Reference plans: pour when the level is low (or as soon as a whole tank fits), stop one unit below
capacity; the Torricelli pours are solved in closed form (the level is quadratic in time).
"""

from __future__ import annotations

import math
import random
from dataclasses import dataclass

from gen.common import GAP, Family, Instance, Step, num, plan_text

#: (tanks, small capacity?) per instance, sizes 1..10: small capacities force partial pours.
SIZES = ((1, False), (2, False), (3, False), (4, False), (2, True), (3, True), (4, True),
         (6, True), (8, True), (10, True))
#: Fuel left when the generator stops: less than any tank holds.
MARGIN = 1
#: The level at which a partial pour starts, and the room left under capacity when it stops.
LOW, HEADROOM = 2.0, 1.0

DURATIVE = """(define (domain generator)
  (:requirements :typing :fluents :durative-actions :duration-inequalities :continuous-effects
                 :negative-preconditions)
  (:types generator tank)
  (:predicates (generator-ran) (refueling ?g - generator) (available ?t - tank))
  (:functions (fuel ?g - generator) (capacity ?g - generator) (tank-fuel ?t - tank)
              (gen-duration) (refuel-rate))
  ;; the generator runs for a fixed time, burning 1 unit/s; it may never run dry
  (:durative-action generate
    :parameters (?g - generator)
    :duration (= ?duration (gen-duration))
    :condition (and (over all (>= (fuel ?g) 0)))
    :effect (and (decrease (fuel ?g) (* #t 1))
                 (at end (generator-ran))))
  ;; pour (part of) a tank: at most until it is empty, never above capacity, one at a time
  (:durative-action refuel
    :parameters (?g - generator ?t - tank)
    :duration (and (>= ?duration 0) (<= ?duration (/ (tank-fuel ?t) (refuel-rate))))
    :condition (and (at start (not (refueling ?g))) (at start (available ?t))
                    (over all (<= (fuel ?g) (capacity ?g)))
                    (over all (>= (tank-fuel ?t) 0)))
    :effect (and (at start (refueling ?g)) (at start (not (available ?t)))
                 (at end (not (refueling ?g))) (at end (available ?t))
                 (increase (fuel ?g) (* #t (refuel-rate)))
                 (decrease (tank-fuel ?t) (* #t (refuel-rate)))))
)
"""

_PPLUS = """(define (domain {name})
  (:requirements :typing :fluents :time :negative-preconditions)
  (:types generator tank)
  (:predicates (idle ?g - generator) (generating ?g - generator) (generator-ran)
               (spilled ?g - generator) (busy ?g - generator)
               (refueling ?g - generator ?t - tank) (available ?t - tank))
  (:functions (fuel ?g - generator) (capacity ?g - generator) ({tank} ?t - tank)
              (gen-time ?g - generator) (gen-duration){funcs})
  (:action start-generator
    :parameters (?g - generator)
    :precondition (and (idle ?g))
    :effect (and (not (idle ?g)) (generating ?g)))
  (:process generate
    :parameters (?g - generator)
    :precondition (and (generating ?g))
    :effect (and (decrease (fuel ?g) (* #t 1))
                 (increase (gen-time ?g) (* #t 1))))
  (:event generator-fails
    :parameters (?g - generator)
    :precondition (and (generating ?g) (< (fuel ?g) 0))
    :effect (and (not (generating ?g))))
  (:action stop-generator
    :parameters (?g - generator)
    :precondition (and (generating ?g) (not (spilled ?g)) (>= (gen-time ?g) (gen-duration)))
    :effect (and (not (generating ?g)) (generator-ran)))
  (:action start-refuel
    :parameters (?g - generator ?t - tank)
    :precondition (and (available ?t) (not (busy ?g)))
    :effect (and (not (available ?t)) (busy ?g) (refueling ?g ?t)))
  (:action stop-refuel
    :parameters (?g - generator ?t - tank)
    :precondition (and (refueling ?g ?t))
    :effect (and (not (refueling ?g ?t)) (not (busy ?g)) (available ?t)))
  ;; {comment}
  (:process refuel
    :parameters (?g - generator ?t - tank)
    :precondition (and (refueling ?g ?t))
    :effect (and (increase (fuel ?g) (* #t {rate}))
                 (decrease ({tank} ?t) (* #t {tank_rate}))))
  (:event tank-empty
    :parameters (?g - generator ?t - tank)
    :precondition (and (refueling ?g ?t) (<= ({tank} ?t) {empty}))
    :effect (and (not (refueling ?g ?t)) (not (busy ?g))))
  (:event overflow
    :parameters (?g - generator)
    :precondition (and (not (spilled ?g)) (> (fuel ?g) (capacity ?g)))
    :effect (and (spilled ?g)))
)
"""

LINEAR = _PPLUS.format(
    name="generator-pplus", tank="tank-fuel", funcs=" (refuel-rate)",
    comment="a tank pours at a constant rate until it is empty or the pour is stopped",
    rate="(refuel-rate)", tank_rate="(refuel-rate)", empty="0")
TORRICELLI = _PPLUS.format(
    name="generator-torricelli", tank="tank-fuel", funcs=" (flow ?t - tank) (reserve)",
    comment="Torricelli's law: the outflow is flow * sqrt(level), down to the reserve",
    rate="(* (flow ?t) (^ (tank-fuel ?t) 0.5))", tank_rate="(* (flow ?t) (^ (tank-fuel ?t) 0.5))",
    empty="(reserve)")
#: VAL twin of TORRICELLI: the state holds r = sqrt(level), which falls linearly (r' = -flow/2),
#: and the outflow flow * r is polynomial; same actions, same trajectories for level = r^2.
TORRICELLI_TWIN = _PPLUS.format(
    name="generator-torricelli-val", tank="tank-root", funcs=" (flow ?t - tank) (reserve-root)",
    comment="VAL twin: tank-root = sqrt(level) falls at flow/2; outflow flow * tank-root",
    rate="(* (flow ?t) (tank-root ?t))", tank_rate="(* 0.5 (flow ?t))", empty="(reserve-root)")


@dataclass(frozen=True)
class Pour:
    """Tank ``tank`` (1-based) pours from ``start`` [s] for ``length`` [s]; ``empties`` if the
    pour ends because the tank reached empty (or its reserve)."""

    tank: int
    start: float
    length: float
    empties: bool


def linear_pours(cap: int, amounts: list[int], rate: float = 2.0) -> tuple[list[Pour], float]:
    """Pours for the linear generator (net +1/s while pouring at rate 2); and the final level.

    A pour starts as soon as it fits under ``cap - HEADROOM`` (at the latest when the level is
    LOW) and lasts until the tank is empty or the level reaches ``cap - HEADROOM``.
    """
    t, level = 0.0, float(cap - 1)
    pours: list[Pour] = []
    for i, amount in enumerate(amounts, start=1):
        left = float(amount)
        while left > 1e-9:
            length = min(left / rate, cap - HEADROOM - LOW)
            wait = max(0.0, level - (cap - HEADROOM - length))
            if pours and t + wait < pours[-1].start + pours[-1].length + GAP:
                wait += GAP
            t += wait
            level -= wait
            left -= rate * length
            pours.append(Pour(i, t, length, left <= 1e-9))
            t += length
            level += (rate - 1) * length
    return pours, level


def _tor_level(level0: float, root0: float, flow: float, t: float) -> float:
    """Generator fuel ``t`` s into a Torricelli pour: burn 1/s, inflow root0^2 - root(t)^2."""
    root = root0 - flow * t / 2
    return level0 - t + root0 ** 2 - root ** 2


def _tor_hits(level0: float, root0: float, flow: float, target: float) -> float | None:
    """The first time > 0 the pour's level reaches ``target`` (a quadratic), or None."""
    # level(t) = level0 - t + root0^2 - (root0 - flow t/2)^2
    #          = level0 + (flow root0 - 1) t - flow^2 t^2 / 4
    a, b, c = -flow * flow / 4, flow * root0 - 1, level0 - target
    disc = b * b - 4 * a * c
    if disc < 0:
        return None
    roots = sorted(((-b + s * math.sqrt(disc)) / (2 * a)) for s in (1, -1))
    later = [r for r in roots if r > 1e-9]
    return later[0] if later else None


def torricelli_pours(cap: int, roots: list[int], flows: list[float]) -> tuple[list[Pour], float]:
    """Pours for the Torricelli generator (reserve = 1, i.e. root 1); and the final level."""
    t, level = 0.0, float(cap - 1)
    pours: list[Pour] = []
    for i, (first_root, flow) in enumerate(zip(roots, flows, strict=True), start=1):
        root = float(first_root)
        while root > 1 + 1e-9:
            to_reserve = 2 * (root - 1) / flow
            # start at the level that keeps the pour above LOW and, if it runs to the reserve,
            # under cap - HEADROOM; else as low as LOW and stop at cap - HEADROOM
            peak_t = min(max((flow * root - 1) * 2 / flow ** 2, 0.0), to_reserve)
            rise = _tor_level(0.0, root, flow, peak_t)
            fall = min(0.0, _tor_level(0.0, root, flow, to_reserve))
            start_level = min(level, cap - HEADROOM - rise) if rise <= cap - HEADROOM - LOW \
                else min(level, LOW)
            start_level = max(start_level, LOW - fall)
            wait = max(0.0, level - start_level)
            if pours and t + wait < pours[-1].start + pours[-1].length + GAP:
                wait += GAP
            t += wait
            level -= wait
            hit = _tor_hits(level, root, flow, cap - HEADROOM)
            # a stop within 0.05 s of the reserve would race the tank-empty event: let it empty
            # (the level then ends within 0.05 s of flow of cap - HEADROOM, still under cap)
            empties = hit is None or hit >= to_reserve - 0.05
            length = to_reserve if empties or hit is None else hit
            new_root = root - flow * length / 2
            low_point = min(level, _tor_level(level, root, flow, length))  # concave: ends
            assert low_point >= LOW / 2, f"tank t{i} would run the generator dry"
            level = _tor_level(level, root, flow, length)
            pours.append(Pour(i, t, length, empties))
            root = 1.0 if pours[-1].empties else new_root
            t += length
    return pours, level


def _objects(n: int) -> str:
    return f"gen - generator {' '.join(f't{i}' for i in range(1, n + 1))} - tank"


def _problem(name: str, domain: str, n: int, init: list[str]) -> str:
    body = "\n    ".join(init)
    return (f"(define (problem {name})\n  (:domain {domain})\n  (:objects {_objects(n)})\n"
            f"  (:init\n    {body})\n  (:goal (and (generator-ran))))\n")


def _pplus_steps(pours: list[Pour], duration: float) -> list[Step]:
    steps = [Step(0.0, "start-generator gen")]
    for p in pours:
        steps.append(Step(p.start, f"start-refuel gen t{p.tank}"))
        if not p.empties:
            steps.append(Step(p.start + p.length, f"stop-refuel gen t{p.tank}"))
    return [*steps, Step(duration + GAP, "stop-generator gen")]


def _build_linear(kind: str) -> list[Instance]:
    rng = random.Random(21)
    out = []
    for size, (n, small) in enumerate(SIZES, start=1):
        amounts = [2 * rng.randint(10, 30) for _ in range(n)]  # pour times 10..30 s at rate 2
        cap = rng.randint(10, 16) if small else max(amounts) // 2 + rng.randint(5, 15)
        duration = cap - 1 + sum(amounts) - MARGIN
        pours, _ = linear_pours(cap, amounts)
        end = pours[-1].start + pours[-1].length
        assert end + GAP < duration
        init = [f"(= (fuel gen) {cap - 1}) (= (capacity gen) {cap})",
                f"(= (gen-duration) {duration}) (= (refuel-rate) 2)"]
        init += [f"(= (tank-fuel t{i}) {x}) (available t{i})" for i, x in enumerate(amounts, 1)]
        params = {"tanks": n, "capacity": cap, "gen_duration": duration, "tank_fuel": amounts,
                  "pours": len(pours)}
        if kind == "durative":
            name = f"generator-{size:02d}"
            problem = _problem(name, "generator", n, init)
            steps = [Step(0.0, "generate gen", float(duration))]
            steps += [Step(p.start, f"refuel gen t{p.tank}", p.length) for p in pours]
        else:
            name = f"generator-pplus-{size:02d}"
            init += ["(idle gen) (= (gen-time gen) 0)"]
            problem = _problem(name, "generator-pplus", n, init)
            steps = _pplus_steps(pours, duration)
        header = (f"reference plan (generator): {n} tanks in {len(pours)} pours, each started "
                  f"when it fits and stopped {HEADROOM:g} under capacity")
        out.append(Instance(size=size, problem=problem, plan=plan_text(steps, header),
                            params=params))
    return out


def _build_torricelli() -> list[Instance]:
    rng = random.Random(23)
    out = []
    for size, (n, small) in enumerate(SIZES, start=1):
        roots = [rng.randint(5, 8) for _ in range(n)]  # sqrt of the tank's contents
        flows = [round(rng.uniform(0.5, 2.0), 2) for _ in range(n)]
        delivered = [r * r - 1 for r in roots]  # down to the reserve 1 (= root 1)
        cap = rng.randint(16, 22) if small else max(delivered) + rng.randint(5, 15)
        duration = cap - 1 + sum(delivered) - MARGIN
        pours, _ = torricelli_pours(cap, roots, flows)
        assert pours[-1].start + pours[-1].length + GAP < duration
        base = [f"(= (fuel gen) {cap - 1}) (= (capacity gen) {cap})",
                f"(= (gen-duration) {duration})", "(idle gen) (= (gen-time gen) 0)"]
        tanks = [f"(= (flow t{i}) {num(f)}) (available t{i})" for i, f in enumerate(flows, 1)]
        real = base + ["(= (reserve) 1)"] + tanks + [
            f"(= (tank-fuel t{i}) {r * r})" for i, r in enumerate(roots, 1)]
        twin = base + ["(= (reserve-root) 1)"] + tanks + [
            f"(= (tank-root t{i}) {r})" for i, r in enumerate(roots, 1)]
        name = f"generator-torricelli-{size:02d}"
        header = (f"reference plan (generator): {n} tanks in {len(pours)} pours "
                  "(closed-form Torricelli levels)")
        out.append(Instance(
            size=size, problem=_problem(name, "generator-torricelli", n, real),
            plan=plan_text(_pplus_steps(pours, duration), header), plan_check="val-twin",
            val_problem=_problem(name, "generator-torricelli-val", n, twin),
            params={"tanks": n, "capacity": cap, "gen_duration": duration,
                    "tank_fuel": [r * r for r in roots], "flow": flows, "pours": len(pours)},
        ))
    return out


FAMILIES = [
    Family(
        name="generator",
        summary="durative actions (PDDL 2.1 level 3-4): fixed-duration generate with a #t "
                "continuous effect, refuel with an inequality duration (<= tank / rate), "
                "over all conditions, required concurrency; grows the tanks, then shrinks the "
                "capacity so that tanks need several partial pours (durations inside the bound)",
        features=("durative-actions", "duration-inequalities", "continuous-effects",
                  "required-concurrency"),
        domain=DURATIVE, build=lambda: _build_linear("durative"),
    ),
    Family(
        name="generator_pplus",
        summary="the same generator as linear PDDL+ (processes; events for an empty tank, "
                "running dry and overflow; stop-refuel for partial pours)",
        features=("processes", "events", "linear"),
        domain=LINEAR, build=lambda: _build_linear("pplus"),
    ),
    Family(
        name="torricelli",
        summary="nonlinear generator: tanks drain by Torricelli's law, flow * (^ level 0.5), "
                "down to a reserve; partial pours stop at a level reached along a quadratic",
        features=("processes", "events", "nonlinear", "pow"),
        domain=TORRICELLI, build=_build_torricelli, val_reads=False,
        val_domain=TORRICELLI_TWIN,
        notes="VAL cannot read (^ ...); the VAL twin holds sqrt(level), which falls linearly, "
              "so its flow is polynomial (exact, same trajectories)",
    ),
]
