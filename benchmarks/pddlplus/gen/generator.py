"""The generator families: durative (PDDL 2.1 level 3-4), linear PDDL+, Torricelli (nonlinear).

One generator must run for ``gen-duration`` seconds, burning 1 fuel unit per second; its tank
holds at most ``capacity``; it starts full, so the fuel of the n tanks can only be poured in while
it runs, one tank at a time, each at a moment when the tank's contents fit. The final margin is
smaller than any tank: every tank is needed. It starts one unit below capacity (VAL reads the
overflow event's ``fuel > capacity`` as ``fuel - capacity > -0.0001``: an initial state at
capacity would fire it, which VAL forbids in the initial state).

Reference plans start each refuel as soon as the whole tank fits under ``capacity - 1``.
"""

from __future__ import annotations

import random

from gen.common import GAP, Family, Instance, Step, num, plan_text

#: Number of tanks per instance (sizes 1..10).
TANKS = (1, 2, 3, 4, 5, 6, 8, 10, 12, 15)
#: Fuel left when the generator stops: less than any tank holds.
MARGIN = 1

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
  ;; pour a tank in, at most until it is empty, never above capacity, one tank at a time
  (:durative-action refuel
    :parameters (?g - generator ?t - tank)
    :duration (and (>= ?duration 0) (<= ?duration (/ (tank-fuel ?t) (refuel-rate))))
    :condition (and (at start (not (refueling ?g))) (at start (available ?t))
                    (over all (<= (fuel ?g) (capacity ?g)))
                    (over all (>= (tank-fuel ?t) 0)))
    :effect (and (at start (refueling ?g)) (at start (not (available ?t)))
                 (at end (not (refueling ?g)))
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
    comment="a tank pours at a constant rate until it is empty",
    rate="(refuel-rate)", tank_rate="(refuel-rate)", empty="0")
TORRICELLI = _PPLUS.format(
    name="generator-torricelli", tank="tank-fuel", funcs=" (flow ?t - tank) (reserve)",
    comment="Torricelli's law: the outflow is flow * sqrt(level), until the reserve is reached",
    rate="(* (flow ?t) (^ (tank-fuel ?t) 0.5))", tank_rate="(* (flow ?t) (^ (tank-fuel ?t) 0.5))",
    empty="(reserve)")
#: VAL twin of TORRICELLI: the state holds r = sqrt(level), which falls linearly (r' = -flow/2),
#: and the outflow flow * r is polynomial; same actions, same trajectories for level = r^2.
TORRICELLI_TWIN = _PPLUS.format(
    name="generator-torricelli-val", tank="tank-root", funcs=" (flow ?t - tank) (reserve-root)",
    comment="VAL twin: tank-root = sqrt(level) falls at flow/2; outflow flow * tank-root",
    rate="(* (flow ?t) (tank-root ?t))", tank_rate="(* 0.5 (flow ?t))", empty="(reserve-root)")


def _objects(n: int) -> tuple[str, list[str]]:
    tanks = [f"t{i}" for i in range(1, n + 1)]
    return f"gen - generator {' '.join(tanks)} - tank", tanks


def _problem(name: str, domain: str, n: int, init: list[str]) -> str:
    objects, _ = _objects(n)
    body = "\n    ".join(init)
    return (f"(define (problem {name})\n  (:domain {domain})\n  (:objects {objects})\n"
            f"  (:init\n    {body})\n  (:goal (and (generator-ran))))\n")


def _linear_schedule(cap: int, durations: list[int]) -> list[float]:
    """Refuel start times: level cap - 1 - t; tank i (net +1/s for ``durations[i]`` s) starts
    when it fits under cap - 1."""
    starts, t = [], 0.0
    level = float(cap - 1)
    for x in durations:
        wait = max(0.0, level - (cap - 1 - x))
        t += wait
        starts.append(t)
        level = cap - 1.0 if wait > 0 else level + x
        t += x
    return starts


def _build_linear(kind: str) -> list[Instance]:
    rng = random.Random(21)
    out = []
    for size, n in enumerate(TANKS, start=1):
        xs = [rng.randint(10, 30) for _ in range(n)]  # refuel durations [s] at rate 2
        cap = max(xs) + rng.randint(5, 15)
        duration = cap - 1 + 2 * sum(xs) - MARGIN
        starts = _linear_schedule(cap, xs)
        init = ["(= (fuel gen) %d) (= (capacity gen) %d)" % (cap - 1, cap),
                f"(= (gen-duration) {duration}) (= (refuel-rate) 2)"]
        init += [f"(= (tank-fuel t{i}) {2 * x}) (available t{i})" for i, x in enumerate(xs, 1)]
        params = {"tanks": n, "capacity": cap, "gen_duration": duration,
                  "tank_fuel": [2 * x for x in xs]}
        if kind == "durative":
            name = f"generator-{size:02d}"
            problem = _problem(name, "generator", n, init)
            steps = [Step(0.0, "generate gen", float(duration))]
            steps += [Step(s, f"refuel gen t{i}", float(x)) for i, (s, x) in
                      enumerate(zip(starts, xs), 1)]
        else:
            name = f"generator-pplus-{size:02d}"
            init += ["(idle gen) (= (gen-time gen) 0)"]
            problem = _problem(name, "generator-pplus", n, init)
            steps = [Step(0.0, "start-generator gen")]
            steps += [Step(s + GAP, f"start-refuel gen t{i}") for i, s in enumerate(starts, 1)]
            steps.append(Step(duration + GAP, "stop-generator gen"))
        header = f"reference plan (generator): {n} tanks, each poured when it fits under capacity - 1"
        out.append(Instance(size=size, problem=problem, plan=plan_text(steps, header),
                            params=params))
    return out


def _torricelli_level(level0: float, root0: float, flow: float, t: float) -> float:
    """Generator fuel t s into a pour: burn 1/s, inflow = root0^2 - (root0 - flow t / 2)^2."""
    root = root0 - flow * t / 2
    return level0 - t + root0 ** 2 - root ** 2


def _build_torricelli() -> list[Instance]:
    rng = random.Random(23)
    out = []
    for size, n in enumerate(TANKS, start=1):
        roots = [rng.randint(5, 8) for _ in range(n)]  # sqrt of the tank's contents
        flows = [round(rng.uniform(0.5, 2.0), 2) for _ in range(n)]
        delivered = [r * r - 1 for r in roots]  # down to the reserve 1 (= root 1)
        cap = max(delivered) + rng.randint(5, 15)
        duration = cap - 1 + sum(delivered) - MARGIN
        t, level, starts = 0.0, float(cap - 1), []
        for root, flow, amount in zip(roots, flows, delivered):
            wait = max(0.0, level - (cap - 1 - amount))
            t += wait + GAP
            level -= wait + GAP
            starts.append(t)
            pour = 2 * (root - 1) / flow
            peak = max(_torricelli_level(level, root, flow, s * pour / 200) for s in range(201))
            assert peak <= cap - 1 + 1e-9 and level - pour + amount >= 0
            level = _torricelli_level(level, root, flow, pour)
            t += pour
        assert t + GAP < duration, "every pour must end before the generator stops"
        base = ["(= (fuel gen) %d) (= (capacity gen) %d)" % (cap - 1, cap),
                f"(= (gen-duration) {duration})", "(idle gen) (= (gen-time gen) 0)"]
        tanks = [f"(= (flow t{i}) {num(f)}) (available t{i})" for i, f in enumerate(flows, 1)]
        real = base + ["(= (reserve) 1)"] + tanks + [
            f"(= (tank-fuel t{i}) {r * r})" for i, r in enumerate(roots, 1)]
        twin = base + ["(= (reserve-root) 1)"] + tanks + [
            f"(= (tank-root t{i}) {r})" for i, r in enumerate(roots, 1)]
        name = f"generator-torricelli-{size:02d}"
        steps = [Step(0.0, "start-generator gen")]
        steps += [Step(s, f"start-refuel gen t{i}") for i, s in enumerate(starts, 1)]
        steps.append(Step(duration + GAP, "stop-generator gen"))
        header = f"reference plan (generator): {n} tanks, each poured when it fits under capacity - 1"
        out.append(Instance(
            size=size, problem=_problem(name, "generator-torricelli", n, real),
            plan=plan_text(steps, header), plan_check="val-twin",
            val_problem=_problem(name, "generator-torricelli-val", n, twin),
            params={"tanks": n, "capacity": cap, "gen_duration": duration,
                    "tank_fuel": [r * r for r in roots], "flow": flows},
        ))
    return out


FAMILIES = [
    Family(
        name="generator",
        summary="durative actions (PDDL 2.1 level 3-4): fixed-duration generate with a #t "
                "continuous effect, refuel with an inequality duration (<= tank / rate), "
                "over all conditions, required concurrency; grows the number of tanks",
        features=("durative-actions", "duration-inequalities", "continuous-effects",
                  "required-concurrency"),
        domain=DURATIVE, build=lambda: _build_linear("durative"),
    ),
    Family(
        name="generator_pplus",
        summary="the same generator as linear PDDL+ (processes, events for empty tank, "
                "running dry and overflow); grows the number of tanks",
        features=("processes", "events", "linear"),
        domain=LINEAR, build=lambda: _build_linear("pplus"),
    ),
    Family(
        name="torricelli",
        summary="nonlinear generator: tanks drain by Torricelli's law, flow * (^ level 0.5), "
                "until a reserve; grows the number of tanks",
        features=("processes", "events", "nonlinear", "pow"),
        domain=TORRICELLI, build=_build_torricelli, val_reads=False,
        val_domain=TORRICELLI_TWIN,
        notes="VAL cannot read (^ ...); the VAL twin holds sqrt(level), which falls linearly, "
              "so its flow is polynomial (exact, same trajectories)",
    ),
]
