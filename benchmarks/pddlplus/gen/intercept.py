"""The intercept family: a pursuer steering among K compass headings intercepts a moving target.

Processes move both (the target at constant velocity between turns that events make at set
times); the pursuer burns fuel while it moves; ``capture`` needs the squared distance (a product
of fluents: quadratic) within the capture radius, before the target escapes (an event on time).

Reference plans: pick the capture time T, find where the target is then, reach that point with
the two headings that bracket its bearing (one leg each, a halt), wait, capture at T. The
pursuer's speed is set so that it arrives at 0.8 T; the escape time and fuel leave a slack that
shrinks with the size.
"""

from __future__ import annotations

import math
import random

from gen.common import GAP, Family, Instance, Step, num, plan_text

DOMAIN = """(define (domain intercept)
  (:requirements :typing :fluents :time :negative-preconditions)
  (:types heading turn)
  (:predicates (hunting) (thrusting) (pending ?w - turn) (captured) (escaped))
  (:functions (px) (py) (pvx) (pvy) (tx) (ty) (tvx) (tvy) (clock) (speed) (fuel) (burn)
              (radius) (escape-time) (dx ?h - heading) (dy ?h - heading)
              (turn-time ?w - turn) (turn-vx ?w - turn) (turn-vy ?w - turn))
  (:process motion
    :parameters ()
    :precondition (and (hunting))
    :effect (and (increase (px) (* #t (pvx))) (increase (py) (* #t (pvy)))
                 (increase (tx) (* #t (tvx))) (increase (ty) (* #t (tvy)))
                 (increase (clock) (* #t 1))))
  (:process burning
    :parameters ()
    :precondition (and (hunting) (thrusting))
    :effect (and (decrease (fuel) (* #t (burn)))))
  (:event target-turns
    :parameters (?w - turn)
    :precondition (and (hunting) (pending ?w) (>= (clock) (turn-time ?w)))
    :effect (and (not (pending ?w)) (assign (tvx) (turn-vx ?w)) (assign (tvy) (turn-vy ?w))))
  (:event target-escapes
    :parameters ()
    :precondition (and (hunting) (not (escaped)) (>= (clock) (escape-time)))
    :effect (and (escaped)))
  (:event out-of-fuel
    :parameters ()
    :precondition (and (thrusting) (<= (fuel) 0))
    :effect (and (not (thrusting)) (assign (pvx) 0) (assign (pvy) 0)))
  (:action steer
    :parameters (?h - heading)
    :precondition (and (hunting) (> (fuel) 0))
    :effect (and (thrusting) (assign (pvx) (* (speed) (dx ?h))) (assign (pvy) (* (speed) (dy ?h)))))
  (:action halt
    :parameters ()
    :precondition (and (thrusting))
    :effect (and (not (thrusting)) (assign (pvx) 0) (assign (pvy) 0)))
  (:action capture
    :parameters ()
    :precondition (and (hunting) (not (escaped))
                       (<= (+ (* (- (px) (tx)) (- (px) (tx))) (* (- (py) (ty)) (- (py) (ty))))
                           (* (radius) (radius))))
    :effect (and (captured) (not (hunting))))
)
"""

# (headings, target speed, capture radius, turns, escape slack, fuel slack)
SIZES = ((8, 1.0, 3.0, 0, 1.0, 1.0), (8, 1.0, 2.0, 1, 0.8, 0.8), (8, 1.5, 1.5, 1, 0.6, 0.6),
         (8, 1.5, 1.0, 2, 0.5, 0.5), (16, 2.0, 0.8, 2, 0.4, 0.4), (16, 2.0, 0.5, 3, 0.3, 0.3),
         (16, 2.5, 0.4, 3, 0.25, 0.25), (16, 3.0, 0.3, 4, 0.2, 0.2), (16, 3.0, 0.2, 4, 0.15, 0.15),
         (16, 3.5, 0.1, 5, 0.1, 0.1))


def _unit(k: int, n: int) -> tuple[float, float]:
    """Heading k of n, counter-clockwise from +x, rounded as the problem file writes it."""
    angle = 2 * math.pi * k / n
    return round(math.cos(angle), 6), round(math.sin(angle), 6)


def target_at(t: float, start: tuple[float, float], velocity: tuple[float, float],
              turns: list[tuple[float, float, float]]) -> tuple[float, float]:
    """The target's position at ``t``: constant velocity, changed at each (time, vx, vy)."""
    x, y = start
    vx, vy = velocity
    now = 0.0
    for when, nvx, nvy in turns:
        if when >= t:
            break
        x, y = x + vx * (when - now), y + vy * (when - now)
        vx, vy, now = nvx, nvy, when
    return x + vx * (t - now), y + vy * (t - now)


def bracket(dx: float, dy: float, k: int) -> tuple[int, float, int, float]:
    """Headings (j, j+1) of k around the bearing of (dx, dy), and the leg lengths a, b >= 0 with
    a u_j + b u_j+1 = (dx, dy)."""
    bearing = math.atan2(dy, dx) % (2 * math.pi)
    j = int(bearing / (2 * math.pi / k)) % k
    (ux, uy), (wx, wy) = _unit(j, k), _unit((j + 1) % k, k)
    det = ux * wy - uy * wx
    a = (dx * wy - dy * wx) / det
    b = (ux * dy - uy * dx) / det
    return j, max(a, 0.0), (j + 1) % k, max(b, 0.0)


def _build() -> list[Instance]:
    rng = random.Random(41)
    out = []
    for size, (k, vt, radius, n_turns, esc_slack, fuel_slack) in enumerate(SIZES, start=1):
        dist = 20 + 5 * size
        ang = rng.uniform(0, 2 * math.pi)
        start = (round(dist * math.cos(ang), 2), round(dist * math.sin(ang), 2))
        head = rng.uniform(0, 2 * math.pi)
        velocity = (round(vt * math.cos(head), 4), round(vt * math.sin(head), 4))
        capture = round(dist / 2 + rng.uniform(0, dist / 4), 2)  # T [s]
        turns = []
        for when in sorted(rng.uniform(0.1, 0.95) * capture for _ in range(n_turns)):
            head += rng.choice((-1, 1)) * rng.uniform(math.pi / 6, math.pi / 2)
            turns.append((round(when, 2), round(vt * math.cos(head), 4),
                          round(vt * math.sin(head), 4)))
        gx, gy = target_at(capture, start, velocity, turns)
        j, a, j2, b = bracket(gx, gy, k)
        speed = round((a + b) / (0.8 * capture), 4)
        t1, t2 = a / speed, (a + b) / speed
        burn = 1.0
        fuel = round(burn * t2 * (1 + fuel_slack), 2)
        escape = round(capture * (1 + esc_slack), 2)
        steps = [Step(0.0, f"steer h{j}")]
        if b > 1e-9:
            steps.append(Step(max(t1, GAP), f"steer h{j2}"))
        steps += [Step(max(t2, steps[-1].time + GAP), "halt"), Step(capture, "capture")]
        init = ["(hunting) (= (clock) 0)",
                "(= (px) 0) (= (py) 0) (= (pvx) 0) (= (pvy) 0)",
                f"(= (tx) {num(start[0])}) (= (ty) {num(start[1])}) "
                f"(= (tvx) {num(velocity[0])}) (= (tvy) {num(velocity[1])})",
                f"(= (speed) {num(speed)}) (= (fuel) {num(fuel)}) (= (burn) {num(burn)})",
                f"(= (radius) {num(radius)}) (= (escape-time) {num(escape)})"]
        init += [f"(= (dx h{i}) {num(_unit(i, k)[0])}) (= (dy h{i}) {num(_unit(i, k)[1])})"
                 for i in range(k)]
        init += [f"(pending w{i}) (= (turn-time w{i}) {num(w)}) (= (turn-vx w{i}) {num(vx)}) "
                 f"(= (turn-vy w{i}) {num(vy)})" for i, (w, vx, vy) in enumerate(turns, 1)]
        turn_objs = " ".join(f"w{i}" for i in range(1, n_turns + 1))
        objs = f"{' '.join(f'h{i}' for i in range(k))} - heading" + (
            f" {turn_objs} - turn" if turn_objs else "")
        body = "\n    ".join(init)
        problem = (f"(define (problem intercept-{size:02d})\n  (:domain intercept)\n"
                   f"  (:objects {objs})\n  (:init\n    {body})\n  (:goal (and (captured))))\n")
        header = (f"reference plan (generator): meet the target at t = {capture} at "
                  f"({gx:.4f}, {gy:.4f}) via headings h{j}, h{j2}")
        out.append(Instance(size=size, problem=problem, plan=plan_text(steps, header),
                            params={"headings": k, "target_speed": vt, "radius": radius,
                                    "turns": n_turns, "escape_time": escape, "fuel": fuel,
                                    "pursuer_speed": speed}))
    return out


FAMILIES = [
    Family(
        name="intercept",
        summary="a pursuer with K discrete headings intercepts a target that turns at timed "
                "events: linear motion, a quadratic capture condition (squared distance as "
                "products), fuel, an escape deadline; grows headings, target speed and turns, "
                "shrinks the capture radius and the slack",
        features=("processes", "events", "nonlinear-conditions", "assign-effects"),
        domain=DOMAIN, build=_build,
    ),
]
