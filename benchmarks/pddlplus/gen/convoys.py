"""The convoys family: vehicles on a road grid whose speed falls with the square of the traffic.

A convoy departs along a road (adding 1 to the road's traffic both ways), its progress grows at
``speed / traffic^2`` -- a rate nonlinear in the fluents, piecewise constant in time -- and it
arrives once its progress covers the road's length, before the deadline. Background traffic 0, 1
or 2 makes roads fast, slow (1/4) or very slow (1/9); two convoys on one road slow each other.

Reference plans: every convoy takes its fastest path (Dijkstra on its own travel times), all
start at once; an exact event-driven simulation of the shared traffic gives the times. The
deadline is the reference makespan plus a slack that shrinks with the size.
"""

from __future__ import annotations

import heapq
import random
from dataclasses import dataclass, field

from gen.common import GAP, Family, Instance, Step, num, plan_text

_DOMAIN = """(define (domain {name})
  (:requirements :typing :fluents :time :negative-preconditions)
  (:types convoy location)
  (:predicates (at ?c - convoy ?l - location) (road ?a - location ?b - location)
               (idle ?c - convoy) (moving ?c - convoy ?a - location ?b - location) (operating))
  (:functions (speed ?c - convoy) (traffic ?a - location ?b - location)
              (length ?a - location ?b - location) (progress ?c - convoy) (clock) (deadline))
  (:process time-passes
    :parameters ()
    :precondition (and (operating))
    :effect (and (increase (clock) (* #t 1))))
  (:action depart
    :parameters (?c - convoy ?a - location ?b - location)
    :precondition (and (at ?c ?a) (idle ?c) (road ?a ?b))
    :effect (and (not (at ?c ?a)) (not (idle ?c)) (moving ?c ?a ?b) (assign (progress ?c) 0)
                 (increase (traffic ?a ?b) 1) (increase (traffic ?b ?a) 1)))
  ;; {comment}
  (:process drive
    :parameters (?c - convoy ?a - location ?b - location)
    :precondition (and (moving ?c ?a ?b))
    :effect (and (increase (progress ?c) (* #t (/ (speed ?c) {square})))))
  (:action arrive
    :parameters (?c - convoy ?a - location ?b - location)
    :precondition (and (moving ?c ?a ?b) (>= (progress ?c) (length ?a ?b))
                       (<= (clock) (deadline)))
    :effect (and (not (moving ?c ?a ?b)) (at ?c ?b) (idle ?c)
                 (decrease (traffic ?a ?b) 1) (decrease (traffic ?b ?a) 1)))
)
"""

DOMAIN = _DOMAIN.format(name="convoys", square="(^ (traffic ?a ?b) 2)",
                        comment="the convoy's speed falls with the square of the road's traffic")
#: VAL twin: the square as a product (VAL has no ^); traffic changes only at actions.
TWIN = _DOMAIN.format(name="convoys-val", square="(* (traffic ?a ?b) (traffic ?a ?b))",
                      comment="VAL twin: traffic^2 as a product")

# (grid width, grid height, convoys, deadline slack)
SIZES = ((3, 2, 1, 0.5), (3, 3, 2, 0.5), (4, 3, 2, 0.4), (4, 4, 3, 0.4), (5, 4, 3, 0.3),
         (5, 5, 4, 0.3), (6, 5, 5, 0.25), (6, 6, 6, 0.2), (7, 6, 7, 0.15), (8, 7, 8, 0.1))

Edge = tuple[str, str]


@dataclass
class Network:
    """Roads both ways: length and background traffic per unordered pair."""

    nodes: list[str]
    length: dict[Edge, float] = field(default_factory=dict)
    base: dict[Edge, int] = field(default_factory=dict)

    def neighbours(self, a: str) -> list[str]:
        return [b for (x, b) in self.length if x == a]


def grid(rng: random.Random, width: int, height: int) -> Network:
    net = Network([f"l{x}-{y}" for y in range(height) for x in range(width)])
    for y in range(height):
        for x in range(width):
            for dx, dy in ((1, 0), (0, 1)):
                if x + dx < width and y + dy < height:
                    a, b = f"l{x}-{y}", f"l{x + dx}-{y + dy}"
                    length = float(rng.randint(5, 15))
                    base = rng.choices((0, 1, 2), weights=(6, 3, 1))[0]
                    for e in ((a, b), (b, a)):
                        net.length[e], net.base[e] = length, base
    return net


def fastest_path(net: Network, speed: float, start: str, goal: str) -> list[str]:
    """Dijkstra on the travel time of a lone convoy: length * (base + 1)^2 / speed."""
    best = {start: 0.0}
    back: dict[str, str] = {}
    queue = [(0.0, start)]
    while queue:
        cost, a = heapq.heappop(queue)
        if a == goal:
            break
        if cost > best[a]:
            continue
        for b in net.neighbours(a):
            step = net.length[(a, b)] * (net.base[(a, b)] + 1) ** 2 / speed
            if cost + step < best.get(b, float("inf")):
                best[b], back[b] = cost + step, a
                heapq.heappush(queue, (cost + step, b))
    path = [goal]
    while path[-1] != start:
        path.append(back[path[-1]])
    return path[::-1]


@dataclass
class _Convoy:
    name: str
    speed: float
    path: list[str]
    leg: int = 0  # index of the current / next road in path
    moving: bool = False
    progress: float = 0.0
    ready: float = 0.0  # earliest departure [s]


def simulate(net: Network, convoys: list[_Convoy]) -> list[Step]:
    """The reference plan: depart as soon as ready, arrive GAP after the progress covers the
    road; actions at least GAP apart. Exact: rates change only at actions."""
    traffic = dict(net.base)
    steps: list[Step] = []
    now, last = 0.0, -GAP

    def rate(c: _Convoy) -> float:
        e = (c.path[c.leg], c.path[c.leg + 1])
        return c.speed / traffic[e] ** 2

    while True:
        options = []
        for c in convoys:
            if c.moving:
                e = (c.path[c.leg], c.path[c.leg + 1])
                options.append((now + (net.length[e] - c.progress) / rate(c) + GAP, 1, c))
            elif c.leg < len(c.path) - 1:
                options.append((max(c.ready, now), 0, c))
        if not options:
            return steps
        when, _, c = min(options, key=lambda o: (o[0], o[1], o[2].name))
        when = max(when, last + GAP)
        for other in convoys:
            if other.moving:
                other.progress += rate(other) * (when - now)
        now = last = when
        a, b = c.path[c.leg], c.path[c.leg + 1]
        if c.moving:
            steps.append(Step(when, f"arrive {c.name} {a} {b}"))
            c.moving, c.leg, c.ready = False, c.leg + 1, when + GAP
            delta = -1
        else:
            steps.append(Step(when, f"depart {c.name} {a} {b}"))
            c.moving, c.progress = True, 0.0
            delta = 1
        traffic[(a, b)] += delta
        traffic[(b, a)] += delta


def _problem(name: str, domain: str, net: Network, convoys: list[_Convoy], deadline: float,
             goals: dict[str, str]) -> str:
    objs = f"{' '.join(c.name for c in convoys)} - convoy {' '.join(net.nodes)} - location"
    init = ["(operating) (= (clock) 0)", f"(= (deadline) {num(deadline)})"]
    for c in convoys:
        init.append(f"(at {c.name} {c.path[0]}) (idle {c.name}) (= (speed {c.name}) "
                    f"{num(c.speed)}) (= (progress {c.name}) 0)")
    for (a, b), length in sorted(net.length.items()):
        init.append(f"(road {a} {b}) (= (length {a} {b}) {num(length)}) "
                    f"(= (traffic {a} {b}) {net.base[(a, b)]})")
    goal = " ".join(f"(at {c} {g})" for c, g in goals.items())
    body = "\n    ".join(init)
    return (f"(define (problem {name})\n  (:domain {domain})\n  (:objects {objs})\n"
            f"  (:init\n    {body})\n  (:goal (and {goal})))\n")


def _build() -> list[Instance]:
    rng = random.Random(31)
    out = []
    for size, (width, height, n, slack) in enumerate(SIZES, start=1):
        net = grid(rng, width, height)
        convoys, goals = [], {}
        for i in range(1, n + 1):
            start, goal = rng.sample(net.nodes, 2)
            while abs(net.nodes.index(start) - net.nodes.index(goal)) < width:  # not too close
                start, goal = rng.sample(net.nodes, 2)
            speed = rng.choice((1.0, 1.5, 2.0))
            convoys.append(_Convoy(f"c{i}", speed, fastest_path(net, speed, start, goal)))
            goals[f"c{i}"] = goal
        steps = simulate(net, convoys)
        makespan = max(s.time for s in steps)
        deadline = round(makespan * (1 + slack) + 0.5, 1)
        name = f"convoys-{size:02d}"
        header = (f"reference plan (generator): fastest lone paths, all start at once; makespan "
                  f"{makespan:.3f}, deadline {num(deadline)}")
        out.append(Instance(
            size=size, problem=_problem(name, "convoys", net, convoys, deadline, goals),
            plan=plan_text(steps, header), plan_check="val-twin",
            val_problem=_problem(name, "convoys-val", net, convoys, deadline, goals),
            params={"grid": [width, height], "convoys": n, "deadline": deadline,
                    "deadline_slack": slack, "reference_makespan": round(makespan, 3)},
        ))
    return out


FAMILIES = [
    Family(
        name="convoys",
        summary="convoys on a road grid: progress rate (/ (speed ?c) (^ (traffic ?a ?b) 2)), "
                "nonlinear in the fluents, traffic raised by every convoy on the road; a deadline; "
                "grows the grid and the number of convoys, tightens the deadline",
        features=("processes", "nonlinear", "pow", "division"),
        domain=DOMAIN, build=_build, val_reads=False, val_domain=TWIN,
        notes="VAL cannot read (^ ...); the VAL twin writes the square as a product (exact)",
    ),
]
