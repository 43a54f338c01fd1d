"""The car families: linear car, car with quadratic drag, car under a global speed limit.

The classic PDDL+ car: actions step the acceleration ``a`` by 1 within [min-a, max-a]; the process
``moving`` integrates ``v += a``, ``d += v`` (and a clock); an event blows the engine above
``v-max``; ``stop`` needs ``d`` in [d-min, d-max], |v| <= v-tol and the clock within the deadline.

Reference plans are bang-coast-bang: ramp ``a`` up to ``max-a`` (one action every GAP seconds),
ramp down to 0 at the cruise speed (linear car), brake at ``min-a``, ramp back to 0 when ``v``
reaches 0, stop. The switching times are found by bisection on an exact simulation: piecewise
polynomial for the linear car, the closed-form solutions of ``v' = a - c v^2`` (tanh / tan /
hyperbolic) for the drag car.
"""

from __future__ import annotations

import math
import random

from gen.common import GAP, Family, Instance, Step, bisect, num, plan_text

# ---------------------------------------------------------------------------------------------
# Domains

_HEAD = """(define (domain {name})
  (:requirements :typing :fluents :time{neg})
  (:predicates (running) (stopped) (engine-blown){preds})
  (:functions (d) (v) (a) (clock) (max-a) (min-a) (v-max) (d-min) (d-max) (v-tol) (deadline){funcs})
"""

_MOVING = """  ;; the car moves while the engine runs: v' = a, d' = v; the clock runs with it
  (:process moving
    :parameters ()
    :precondition (and (running))
    :effect (and (increase (v) (* #t (a)))
                 (increase (d) (* #t (v)))
                 (increase (clock) (* #t 1))))
"""

_DRAG = """  ;; quadratic air drag while moving forward: v' -= drag * v^2
  (:process air-drag
    :parameters ()
    :precondition (and (running) (> (v) 0))
    :effect (and (decrease (v) (* #t (* (^ (v) 2) (drag))))))
"""

_TAIL = """  (:event engine-explodes
    :parameters ()
    :precondition (and (running) (> (v) (v-max)))
    :effect (and (not (running)) (engine-blown)))
  (:action accelerate
    :parameters ()
    :precondition (and (running) (< (a) (max-a)))
    :effect (and (increase (a) 1)))
  (:action decelerate
    :parameters ()
    :precondition (and (running) (> (a) (min-a)))
    :effect (and (decrease (a) 1)))
  (:action stop
    :parameters ()
    :precondition (and (running){stop_extra}
                       (>= (d) (d-min)) (<= (d) (d-max))
                       (<= (v) (v-tol)) (>= (+ (v) (v-tol)) 0)
                       (<= (clock) (deadline)))
    :effect (and (not (running)) (stopped)))
)
"""

_LIMIT = """  ;; ENHSP global constraint: the speed limit holds over the whole trajectory
  (:constraint speed-limit
    :parameters ()
    :condition (and (<= (v) (v-limit))))
"""

_LIMIT_TWIN = """\
  ;; VAL twin of the global constraint: exceeding the limit earns a ticket, and a ticketed
  ;; car may not stop (same actions, same trajectories as the ENHSP domain)
  (:event speeding
    :parameters ()
    :precondition (and (running) (not (ticketed)) (> (v) (v-limit)))
    :effect (and (ticketed)))
"""


def car_domain(kind: str, twin: bool = False) -> str:
    """The domain text: ``kind`` is ``linear``, ``drag`` or ``limit``; ``twin`` for VAL's copy."""
    name = {"linear": "car-linear", "drag": "car-drag", "limit": "car-limit"}[kind]
    funcs = " (drag)" if kind == "drag" else (" (v-limit)" if kind == "limit" else "")
    text = _HEAD.format(
        name=name + ("-val" if twin else ""),
        neg=" :negative-preconditions" if twin else "",
        preds=" (ticketed)" if twin else "",
        funcs=funcs,
    )
    if kind == "limit" and not twin:
        text += _LIMIT
    text += _MOVING
    if kind == "drag":
        text += _DRAG
    if twin:
        text += _LIMIT_TWIN
    return text + _TAIL.format(stop_extra=" (not (ticketed))" if twin else "")


# ---------------------------------------------------------------------------------------------
# Exact simulation of the car


def _log_cosh(u: float) -> float:
    """log(cosh(u)) without overflow."""
    u = abs(u)
    return u + math.log1p(math.exp(-2 * u)) - math.log(2)


def _log_sinh(u: float) -> float:
    """log(sinh(u)) for u > 0 without overflow."""
    return u + math.log1p(-math.exp(-2 * u)) - math.log(2)


def _segment(v: float, d: float, a: float, c: float, dt: float) -> tuple[float, float]:
    """(v, d) after ``dt`` seconds at constant ``a`` with drag ``c`` (drag only while v > 0)."""
    if dt <= 0:
        return v, d
    if c == 0 or v <= 0 and a <= 0:
        return v + a * dt, d + v * dt + 0.5 * a * dt * dt
    if v < 0 < a:  # linear up to v = 0, then with drag
        t0 = -v / a
        if t0 >= dt:
            return v + a * dt, d + v * dt + 0.5 * a * dt * dt
        return _segment(0.0, d + v * t0 + 0.5 * a * t0 * t0, a, c, dt - t0)
    if a > 0:  # v' = a - c v^2: tanh below the terminal speed sqrt(a/c), coth above it
        vt = math.sqrt(a / c)
        k = math.sqrt(a * c)
        if abs(v - vt) <= 1e-12 * vt:
            return v, d + v * dt
        if v < vt:
            u0 = math.atanh(v / vt)
            u1 = u0 + k * dt
            return vt * math.tanh(u1), d + (_log_cosh(u1) - _log_cosh(u0)) / c
        u0 = math.atanh(vt / v)
        u1 = u0 + k * dt
        return vt / math.tanh(u1), d + (_log_sinh(u1) - _log_sinh(u0)) / c
    if a == 0:  # v' = -c v^2
        return v / (1 + c * v * dt), d + math.log1p(c * v * dt) / c
    # v' = a - c v^2 with a < 0: tan, until v reaches 0
    k = math.sqrt(-a * c)
    th0 = math.atan(v * math.sqrt(c / -a))
    t0 = th0 / k
    if t0 < dt:
        return _segment(0.0, d - math.log(math.cos(th0)) / c, a, c, dt - t0)
    th1 = th0 - k * dt
    d1 = d + (math.log(math.cos(th1)) - math.log(math.cos(th0))) / c
    return math.sqrt(-a / c) * math.tan(th1), d1


def simulate(
    changes: list[tuple[float, int]], until: float, c: float
) -> tuple[float, float, float]:
    """(v, d, max v) at ``until`` for acceleration changes ``(time, +-1)`` from rest at 0."""
    v = d = 0.0
    a = 0.0
    t = 0.0
    vmax = 0.0
    for time, delta in sorted(changes):
        if time > until:
            break
        v, d = _segment(v, d, a, c, time - t)
        vmax = max(vmax, v)
        t = time
        a += delta
    v, d = _segment(v, d, a, c, until - t)
    return v, d, max(vmax, v)


def _ramp(t: float, n: int, delta: int) -> list[tuple[float, int]]:
    return [(t + i * GAP, delta) for i in range(n)]


def reference_car(big_a: int, cruise: float | None, d_target: float, c: float) -> dict[str, object]:
    """A bang-coast-bang plan stopping at ``d_target`` with v = 0 (see the module docstring).

    ``cruise`` is the speed at which the linear car ramps ``a`` down to 0 (None: no cruise, the
    drag car accelerates until it brakes). Returns the changes, stop time, final state, top speed.
    """
    up = _ramp(0.0, big_a, +1)
    if cruise is not None:
        def v_after_cruise_ramp(t1: float) -> float:
            return simulate(up + _ramp(t1, big_a, -1), t1 + big_a * GAP, c)[0] - cruise
        t1 = bisect(v_after_cruise_ramp, big_a * GAP, 10 * cruise / big_a + 10)
        head = up + _ramp(t1, big_a, -1)
        brake_n = big_a
        earliest = t1 + big_a * GAP
    else:
        head, brake_n, earliest = up, 2 * big_a, big_a * GAP

    def finish(t2: float) -> tuple[list[tuple[float, int]], float]:
        brake = head + _ramp(t2, brake_n, -1)
        start = t2 + brake_n * GAP

        def v_end(t3: float) -> float:
            return simulate(brake + _ramp(t3, big_a, +1), t3 + big_a * GAP, c)[0]

        v_now = simulate(brake, start, c)[0]
        # a car already at rest (too early a brake, only as a bisection bound) ramps at once
        t3 = start if v_end(start) <= 0 else bisect(v_end, start, start + 2 * v_now / big_a + 1)
        return brake + _ramp(t3, big_a, +1), t3 + big_a * GAP

    def d_error(t2: float) -> float:
        changes, end = finish(t2)
        return simulate(changes, end, c)[1] - d_target

    t2 = bisect(d_error, earliest, earliest + 20 * d_target / max(cruise or 1.0, 1.0) + 100, 80)
    changes, end = finish(t2)
    v, d, vmax = simulate(changes, end, c)
    return {"changes": changes, "end": end, "v": v, "d": d, "vmax": vmax}


# ---------------------------------------------------------------------------------------------
# Instances


def _problem(name: str, domain: str, values: dict[str, float]) -> str:
    init = " ".join(f"(= ({k}) {num(x)})" for k, x in values.items())
    return (f"(define (problem {name})\n  (:domain {domain})\n  (:init (running)\n    {init})\n"
            "  (:goal (and (stopped))))\n")


def _plan(ref: dict[str, object]) -> str:
    steps = [Step(t, "accelerate" if delta > 0 else "decelerate")
             for t, delta in ref["changes"]]  # type: ignore[attr-defined]
    steps.append(Step(float(ref["end"]) + GAP, "stop"))  # type: ignore[arg-type]
    return plan_text(steps, f"reference plan (generator): stops at d = {ref['d']:.6f}, "
                            f"v = {ref['v']:.2e}, top speed {ref['vmax']:.4f}")


# (distance, window width, max-a, v-max (linear) / drag coefficient, v-tol, deadline slack)
_LINEAR = [(30, 10, 1, 12, 0.5, 1.0), (50, 6, 1, 14, 0.3, 0.8), (80, 4, 2, 16, 0.2, 0.6),
           (120, 3, 2, 18, 0.1, 0.5), (200, 2, 3, 20, 0.1, 0.4), (300, 1.5, 3, 24, 0.05, 0.3),
           (500, 1, 4, 28, 0.05, 0.25), (800, 0.6, 4, 32, 0.02, 0.2),
           (1200, 0.4, 5, 36, 0.02, 0.15), (2000, 0.2, 5, 40, 0.01, 0.1)]
_DRAGS = [(30, 10, 1, 0.02, 0.5, 1.0), (50, 6, 1, 0.02, 0.3, 0.8), (80, 4, 2, 0.02, 0.2, 0.6),
          (120, 3, 2, 0.015, 0.1, 0.5), (200, 2, 3, 0.015, 0.1, 0.4),
          (300, 1.5, 3, 0.01, 0.05, 0.3),
          (500, 1, 4, 0.01, 0.05, 0.25), (800, 0.6, 4, 0.008, 0.02, 0.2),
          (1200, 0.4, 5, 0.006, 0.02, 0.15), (2000, 0.2, 5, 0.005, 0.01, 0.1)]


def _build(kind: str) -> list[Instance]:
    rng = random.Random({"linear": 11, "drag": 12, "limit": 13}[kind])
    rows = _DRAGS if kind == "drag" else _LINEAR
    out = []
    for size, (dist, width, big_a, knob, vtol, slack) in enumerate(rows, start=1):
        center = dist + round(rng.uniform(0.1, 0.9), 2)
        c = knob if kind == "drag" else 0.0
        if kind == "drag":
            v_max = round(1.25 * math.sqrt(big_a / c), 1)
            cruise = None
        elif kind == "limit":
            v_limit = float(knob)
            v_max = round(1.5 * knob, 1)
            cruise = min(0.97 * v_limit, 0.8 * math.sqrt(big_a * center))
        else:
            v_max = float(knob)
            cruise = min(0.9 * v_max, 0.8 * math.sqrt(big_a * center))
        ref = reference_car(big_a, cruise, center, c)
        deadline = round(float(ref["end"]) * (1 + slack) + 2 * GAP, 2)  # type: ignore[arg-type]
        values = {"d": 0, "v": 0, "a": 0, "clock": 0, "max-a": big_a, "min-a": -big_a,
                  "v-max": v_max, "d-min": center - width / 2, "d-max": center + width / 2,
                  "v-tol": vtol, "deadline": deadline}
        if kind == "drag":
            values["drag"] = c
        if kind == "limit":
            values["v-limit"] = v_limit
        params: dict[str, object] = {
            "distance": center, "window": width, "max_a": big_a, "v_tol": vtol,
            "deadline": deadline, "deadline_slack": slack, "v_max": v_max}
        if kind == "drag":
            params["drag"] = c
        if kind == "limit":
            params["v_limit"] = v_limit
        name = f"car-{kind}-{size:02d}"
        dom = {"linear": "car-linear", "drag": "car-drag", "limit": "car-limit"}[kind]
        problem = _problem(name, dom, values)
        twin = _problem(name, dom + "-val", values) if kind == "limit" else None
        out.append(Instance(size=size, problem=problem, plan=_plan(ref), params=params,
                            val_problem=twin,
                            plan_check={"linear": "val", "drag": "sim", "limit": "val-twin"}[kind]))
    return out


FAMILIES = [
    Family(
        name="car_linear",
        summary="linear PDDL+ car: step changes of a, processes v' = a, d' = v, an event above "
                "v-max, a stop window on d and v and a deadline; grows distance, a/v bounds, "
                "window tightness (the last windows miss ENHSP's 1 s grid)",
        features=("processes", "events", "linear"),
        domain=car_domain("linear"), build=lambda: _build("linear"),
    ),
    Family(
        name="car_drag",
        summary="car with quadratic drag (process v' -= (^ v 2) * drag, active while v > 0): "
                "nonlinear ODE (tanh / tan solutions), otherwise as car_linear",
        features=("processes", "events", "nonlinear", "pow"),
        domain=car_domain("drag"), build=lambda: _build("drag"), val_reads=False,
        val_integrates=False,
        notes="VAL cannot read (^ ...); VAL does not integrate v' = a - c v^2 either "
              "(\"Differential equations of this nature are not handled\"), so no VAL twin: "
              "reference plans are checked by the generator's closed-form simulation",
    ),
    Family(
        name="car_limit",
        summary="linear car under an ENHSP global constraint (:constraint speed-limit, v <= "
                "v-limit over the whole trajectory) and a deadline that forces cruising near "
                "the limit",
        features=("processes", "events", "linear", "global-constraints"),
        domain=car_domain("limit"), build=lambda: _build("limit"), val_reads=False,
        val_domain=car_domain("limit", twin=True),
        notes="VAL cannot read ENHSP's :constraint; the VAL twin compiles it into an event that "
              "tickets the car, and a ticketed car may not stop",
    ),
]
