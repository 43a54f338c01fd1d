"""The solar rover family: a rover charges its battery from a sun that rises and sets, drives
between waypoints, images targets and transmits the images before night.

The sun's intensity rises linearly until noon and falls linearly until dusk (processes; events
at noon and dusk); with the panels deployed the battery gains ``charge-eff * sun``, so the
charge is quadratic in time (second-order change: a rate that itself changes continuously).
Driving drains the battery at a constant power while the progress grows; a rover whose battery
runs dry on the road is stranded (an event). Imaging and transmitting cost energy; transmitting
needs daylight.

Reference plans: a nearest-neighbour tour; before each leg the rover charges exactly as much as
the leg, the image and the transmission need (the stop time solves the quadratic charge).
Noon is set as early as lets that tour finish before dusk with the family's slack.
"""

from __future__ import annotations

import math
import random
from dataclasses import dataclass

from gen.common import GAP, Family, Instance, Step, bisect, num, plan_text

DOMAIN = """(define (domain solar-rover)
  (:requirements :typing :fluents :time :negative-preconditions)
  (:types waypoint)
  (:predicates (at ?w - waypoint) (road ?a - waypoint ?b - waypoint) (parked)
               (driving ?a - waypoint ?b - waypoint) (charging) (target ?w - waypoint)
               (imaged ?w - waypoint) (sent ?w - waypoint)
               (mission) (morning) (afternoon) (night) (stranded))
  (:functions (battery) (capacity) (sun) (sun-rate) (clock) (noon) (charge-eff)
              (dist ?a - waypoint ?b - waypoint) (progress) (speed) (drive-power)
              (image-cost) (send-cost))
  (:process mission-clock
    :parameters ()
    :precondition (and (mission))
    :effect (and (increase (clock) (* #t 1))))
  (:process sun-rises
    :parameters ()
    :precondition (and (morning))
    :effect (and (increase (sun) (* #t (sun-rate)))))
  (:process sun-sets
    :parameters ()
    :precondition (and (afternoon))
    :effect (and (decrease (sun) (* #t (sun-rate)))))
  (:event noon-passes
    :parameters ()
    :precondition (and (morning) (>= (clock) (noon)))
    :effect (and (not (morning)) (afternoon)))
  (:event dusk
    :parameters ()
    :precondition (and (afternoon) (<= (sun) 0))
    :effect (and (not (afternoon)) (night)))
  ;; the panels turn sunlight into charge: a rate that itself changes in time
  (:process charge
    :parameters ()
    :precondition (and (charging))
    :effect (and (increase (battery) (* #t (* (charge-eff) (sun))))))
  (:event battery-full
    :parameters ()
    :precondition (and (charging) (>= (battery) (capacity)))
    :effect (and (not (charging))))
  (:process drive
    :parameters (?a - waypoint ?b - waypoint)
    :precondition (and (driving ?a ?b))
    :effect (and (increase (progress) (* #t (speed))) (decrease (battery) (* #t (drive-power)))))
  (:event battery-dead
    :parameters (?a - waypoint ?b - waypoint)
    :precondition (and (driving ?a ?b) (<= (battery) 0))
    :effect (and (not (driving ?a ?b)) (stranded)))
  (:action deploy-panels
    :parameters ()
    :precondition (and (parked) (not (charging)) (not (night)) (< (battery) (capacity)))
    :effect (and (charging)))
  (:action stow-panels
    :parameters ()
    :precondition (and (charging))
    :effect (and (not (charging))))
  (:action depart
    :parameters (?a - waypoint ?b - waypoint)
    :precondition (and (at ?a) (road ?a ?b) (parked) (not (charging)) (> (battery) 0))
    :effect (and (not (at ?a)) (not (parked)) (driving ?a ?b) (assign (progress) 0)))
  (:action arrive
    :parameters (?a - waypoint ?b - waypoint)
    :precondition (and (driving ?a ?b) (>= (progress) (dist ?a ?b)))
    :effect (and (not (driving ?a ?b)) (at ?b) (parked)))
  (:action take-image
    :parameters (?w - waypoint)
    :precondition (and (at ?w) (parked) (target ?w) (not (imaged ?w))
                       (>= (battery) (image-cost)))
    :effect (and (imaged ?w) (decrease (battery) (image-cost))))
  (:action transmit
    :parameters (?w - waypoint)
    :precondition (and (imaged ?w) (parked) (not (sent ?w)) (not (night))
                       (>= (battery) (send-cost)))
    :effect (and (sent ?w) (decrease (battery) (send-cost))))
)
"""

# (grid width, grid height, targets, capacity, deadline slack)
SIZES = ((2, 2, 1, 60, 1.0), (3, 2, 1, 50, 0.8), (3, 2, 2, 50, 0.6), (3, 3, 2, 45, 0.5),
         (3, 3, 3, 40, 0.4), (4, 3, 3, 40, 0.3), (4, 3, 4, 35, 0.25), (4, 4, 5, 35, 0.2),
         (4, 4, 6, 30, 0.15), (5, 4, 8, 30, 0.1))
SUN0, SUN_RATE, EFF = 0.2, 0.02, 0.5  # initial sun, its rate [1/s], charge per sun unit
SPEED, POWER, IMAGE, SEND = 1.0, 1.0, 3.0, 5.0
BATTERY0, RESERVE = 5.0, 1.0  # initial charge; what every leg keeps in hand


@dataclass(frozen=True)
class Sun:
    """sun(t) = SUN0 + r t until noon, then falls at r until dusk (0)."""

    noon: float

    def at(self, t: float) -> float:
        peak = SUN0 + SUN_RATE * self.noon
        return SUN0 + SUN_RATE * t if t <= self.noon else max(peak - SUN_RATE * (t - self.noon), 0)

    @property
    def dusk(self) -> float:
        return self.noon + (SUN0 + SUN_RATE * self.noon) / SUN_RATE

    def energy(self, t0: float, t1: float) -> float:
        """Charge gained from t0 to t1 with the panels out: EFF * integral of sun (exact)."""
        total = 0.0
        for a, b in ((t0, min(t1, self.noon)), (max(t0, self.noon), min(t1, self.dusk))):
            if b > a:
                total += (self.at(a) + self.at(b)) / 2 * (b - a)  # sun is linear on each piece
        return EFF * total


def tour(rng: random.Random, width: int, height: int, n: int) -> tuple[
        list[str], dict[tuple[str, str], float], list[str], list[str]]:
    """Waypoints of a grid, road lengths, targets, and the nearest-neighbour path through them."""
    nodes = [f"w{x}-{y}" for y in range(height) for x in range(width)]
    dist: dict[tuple[str, str], float] = {}
    for y in range(height):
        for x in range(width):
            for dx, dy in ((1, 0), (0, 1)):
                if x + dx < width and y + dy < height:
                    a, b = f"w{x}-{y}", f"w{x + dx}-{y + dy}"
                    dist[(a, b)] = dist[(b, a)] = float(rng.randint(4, 12))
    targets = rng.sample(nodes[1:], n)
    path, here, left = [nodes[0]], nodes[0], list(targets)
    while left:
        legs = {t: _shortest(dist, here, t) for t in left}
        lengths = {t: sum(dist[e] for e in zip(p, p[1:], strict=False)) for t, p in legs.items()}
        nxt = min(left, key=lambda t: (lengths[t], t))
        path += legs[nxt][1:]
        here = nxt
        left.remove(nxt)
    return nodes, dist, targets, path


def _shortest(dist: dict[tuple[str, str], float], a: str, b: str) -> list[str]:
    best, back, todo = {a: 0.0}, {}, [a]
    while todo:
        todo.sort(key=lambda n: best[n])
        u = todo.pop(0)
        for (x, y), d in dist.items():
            if x == u and best[u] + d < best.get(y, math.inf):
                best[y], back[y] = best[u] + d, u
                todo.append(y)
    out = [b]
    while out[-1] != a:
        out.append(back[out[-1]])
    return out[::-1]


def reference(path: list[str], dist: dict[tuple[str, str], float], targets: list[str],
              capacity: float, sun: Sun) -> tuple[list[Step], float] | None:
    """The tour's plan and its last action's time; None if it cannot finish before dusk."""
    t, battery = 0.0, BATTERY0
    steps: list[Step] = []
    todo = set(targets)
    for k, here in enumerate(path):
        if here in todo:
            need = IMAGE + SEND + RESERVE
            t, battery = _charge(steps, t, battery, need, capacity, sun)
            if not math.isfinite(t):
                return None
            steps += [Step(t, f"take-image {here}"), Step(t + GAP, f"transmit {here}")]
            t, battery = t + 2 * GAP, battery - IMAGE - SEND
            todo.discard(here)
            if t >= sun.dusk:
                return None
        if k + 1 < len(path):
            leg = dist[(here, path[k + 1])]
            t, battery = _charge(steps, t, battery, POWER * leg / SPEED + RESERVE, capacity, sun)
            if not math.isfinite(t):
                return None
            steps.append(Step(t, f"depart {here} {path[k + 1]}"))
            t += leg / SPEED + GAP
            battery -= POWER * (t - steps[-1].time)
            steps.append(Step(t, f"arrive {here} {path[k + 1]}"))
            t += GAP
    return steps, steps[-1].time


def _charge(steps: list[Step], t: float, battery: float, need: float, capacity: float,
            sun: Sun) -> tuple[float, float]:
    """Deploy, charge until the battery holds ``need``, stow; returns (time, battery)."""
    if battery >= need:
        return t, battery
    if t + GAP >= sun.dusk:
        return math.inf, battery
    assert need < capacity - 0.5, "a leg must fit in the battery"
    start = t
    if sun.energy(start, sun.dusk) < need + 0.05 - battery:
        return math.inf, battery
    stop = bisect(lambda s: battery + sun.energy(start, s) - need - 0.05, start + GAP, sun.dusk)
    steps += [Step(start, "deploy-panels"), Step(stop, "stow-panels")]
    return stop + GAP, battery + sun.energy(start, stop)


def _fits(noon: float, path: list[str], dist: dict[tuple[str, str], float], targets: list[str],
          capacity: float, slack: float) -> tuple[list[Step], float] | None:
    """The reference plan if it ends before dusk / (1 + slack) with this noon, else None."""
    sun = Sun(noon)
    plan = reference(path, dist, targets, capacity, sun)
    if plan is None or not math.isfinite(plan[1]) or plan[1] * (1 + slack) > sun.dusk:
        return None
    return plan


def _build() -> list[Instance]:
    rng = random.Random(71)
    out = []
    for size, (width, height, n, capacity, slack) in enumerate(SIZES, start=1):
        nodes, dist, targets, path = tour(rng, width, height, n)
        task = (path, dist, targets, float(capacity), slack)
        lo, hi = 1.0, 400.0  # the earliest noon (to 0.5 s) whose day still fits the tour
        assert _fits(hi, *task) is not None, f"rover size {size}: even a long day is too short"
        while hi - lo > 0.25:
            mid = (lo + hi) / 2
            lo, hi = (lo, mid) if _fits(mid, *task) is not None else (mid, hi)
        noon = math.ceil(hi * 2) / 2
        found = _fits(noon, *task)
        assert found is not None
        steps, end = found
        init = ["(mission) (morning) (parked) (= (clock) 0)",
                f"(at {nodes[0]}) (= (battery) {num(BATTERY0)}) (= (capacity) {capacity})",
                f"(= (sun) {num(SUN0)}) (= (sun-rate) {num(SUN_RATE)}) (= (noon) {num(noon)}) "
                f"(= (charge-eff) {num(EFF)})",
                f"(= (speed) {num(SPEED)}) (= (drive-power) {num(POWER)}) (= (progress) 0)",
                f"(= (image-cost) {num(IMAGE)}) (= (send-cost) {num(SEND)})"]
        init += [f"(target {w})" for w in targets]
        init += [f"(road {a} {b}) (= (dist {a} {b}) {num(d)})"
                 for (a, b), d in sorted(dist.items())]
        body = "\n    ".join(init)
        goal = " ".join(f"(sent {w})" for w in targets)
        problem = (f"(define (problem solar-rover-{size:02d})\n  (:domain solar-rover)\n"
                   f"  (:objects {' '.join(nodes)} - waypoint)\n  (:init\n    {body})\n"
                   f"  (:goal (and {goal})))\n")
        header = (f"reference plan (generator): nearest-neighbour tour of {n} targets, charging "
                  f"just enough before each leg; ends at {end:.3f}, dusk at {Sun(noon).dusk:g}")
        out.append(Instance(size=size, problem=problem, plan=plan_text(steps, header),
                            params={"grid": [width, height], "targets": n, "capacity": capacity,
                                    "noon": noon, "dusk": Sun(noon).dusk, "slack": slack}))
    return out


FAMILIES = [
    Family(
        name="rover",
        summary="solar rover: the sun rises and sets (processes, noon and dusk events), the "
                "battery charges at eff * sun (quadratic in time: a rate that changes "
                "continuously), driving drains it, images are sent before night; grows "
                "targets and grid, shrinks the battery and the day",
        features=("processes", "events", "polynomial"),
        domain=DOMAIN, build=_build,
    ),
]
