"""The lander family: powered descent with the rocket equation (nonlinear).

Gravity pulls the lander down (h' = v, v' = -g); with the engine on, thrust accelerates it by
thrust / mass while the mass (and the fuel) burns down at a constant rate: v' = T / m(t) with
m linear in time, a logarithm in v and h. An event ends the flight when the lander reaches the
ground (a crash); ``touch-down`` needs a height at most ``touch-height`` and a speed within
``safe-speed``; an event cuts the engine when the fuel runs out.

Reference plans: fall freely, ignite at the moment (found by bisection on the closed-form
solution) that brings the lander to -safe/2 m/s at half the touch height, touch down then. The
fuel leaves a slack over what that burn needs, shrinking with the size (late, "suicide" burns).
"""

from __future__ import annotations

import math
import random

from gen.common import Family, Instance, Step, bisect, num, plan_text

DOMAIN = """(define (domain lander)
  (:requirements :typing :fluents :time :negative-preconditions)
  (:predicates (flying) (engine-on) (landed) (crashed))
  (:functions (h) (v) (mass) (fuel) (gravity) (thrust) (burn-rate) (touch-height) (safe-speed))
  (:process falling
    :parameters ()
    :precondition (and (flying))
    :effect (and (increase (h) (* #t (v))) (decrease (v) (* #t (gravity)))))
  ;; the rocket equation: the same thrust accelerates a lighter lander more
  (:process thrusting
    :parameters ()
    :precondition (and (flying) (engine-on))
    :effect (and (increase (v) (* #t (/ (thrust) (mass))))
                 (decrease (mass) (* #t (burn-rate)))
                 (decrease (fuel) (* #t (burn-rate)))))
  (:event fuel-exhausted
    :parameters ()
    :precondition (and (engine-on) (<= (fuel) 0))
    :effect (and (not (engine-on))))
  (:event crash
    :parameters ()
    :precondition (and (flying) (<= (h) 0))
    :effect (and (not (flying)) (crashed)))
  (:action ignite
    :parameters ()
    :precondition (and (flying) (not (engine-on)) (> (fuel) 0))
    :effect (and (engine-on)))
  (:action cut-off
    :parameters ()
    :precondition (and (engine-on))
    :effect (and (not (engine-on))))
  (:action touch-down
    :parameters ()
    :precondition (and (flying) (<= (h) (touch-height))
                       (>= (+ (v) (safe-speed)) 0) (<= (v) (safe-speed)))
    :effect (and (landed) (not (flying)) (not (engine-on))))
)
"""

# (height, speed down, gravity, initial thrust / weight, touch height, safe speed, fuel slack)
SIZES = ((100, 5, 1.62, 3.0, 5.0, 3.0, 1.0), (200, 10, 1.62, 3.0, 4.0, 2.5, 0.8),
         (400, 15, 1.62, 2.8, 3.0, 2.0, 0.6), (600, 20, 1.62, 2.6, 2.5, 2.0, 0.5),
         (1000, 30, 3.71, 2.6, 2.0, 1.5, 0.4), (1500, 40, 3.71, 2.4, 1.5, 1.5, 0.3),
         (2000, 50, 3.71, 2.3, 1.0, 1.2, 0.2), (3000, 60, 3.71, 2.2, 0.8, 1.0, 0.15),
         (4000, 70, 3.71, 2.1, 0.6, 1.0, 0.1), (5000, 80, 3.71, 2.0, 0.5, 1.0, 0.05))

DRY_MASS = 1000.0  # [kg]
BURN = 5.0  # [kg/s]


def fall(h: float, v: float, g: float, t: float) -> tuple[float, float]:
    """(h, v) after ``t`` s of free fall."""
    return h + v * t - g * t * t / 2, v - g * t


def burn(h: float, v: float, m: float, g: float, thrust: float, b: float,
         t: float) -> tuple[float, float]:
    """(h, v) after ``t`` s with the engine on from mass ``m`` (closed form of the rocket
    equation: v gains (T/b) ln(m0/m), h the integral (T/b^2)(m0 - m - m ln(m0/m)))."""
    m1 = m - b * t
    log = math.log(m / m1)
    return (h + v * t - g * t * t / 2 + thrust / b ** 2 * (m - m1 - m1 * log),
            v + thrust / b * log - g * t)


def reference(h0: float, v0: float, g: float, thrust: float, mass: float, touch: float,
              safe: float) -> tuple[float, float]:
    """(ignition time, burn time) that reach v = -safe/2 at h = touch/2."""
    target_v, target_h = -safe / 2, touch / 2

    def burn_time(t_ign: float) -> float:
        h, v = fall(h0, v0, g, t_ign)
        return bisect(lambda s: burn(h, v, mass, g, thrust, BURN, s)[1] - target_v,
                      0.0, 0.95 * mass / BURN)

    def height_error(t_ign: float) -> float:
        h, v = fall(h0, v0, g, t_ign)
        return burn(h, v, mass, g, thrust, BURN, burn_time(t_ign))[0] - target_h

    # the latest useful ignition: free fall to the ground
    t_ground = (v0 + math.sqrt(v0 * v0 + 2 * g * h0)) / g
    t_ign = bisect(height_error, 0.0, t_ground)
    return t_ign, burn_time(t_ign)


def _build() -> list[Instance]:
    rng = random.Random(51)
    out = []
    for size, (base_h, v0, g, twr, touch, safe, slack) in enumerate(SIZES, start=1):
        h0 = base_h + round(rng.uniform(0, 50), 1)
        fuel = 200.0
        for _ in range(30):  # the fuel is part of the mass: iterate to the fixed point
            mass = DRY_MASS + fuel
            thrust = round(twr * g * mass, 1)
            t_ign, t_burn = reference(h0, -v0, g, thrust, mass, touch, safe)
            fuel = round(BURN * t_burn * (1 + slack), 2)
        mass = DRY_MASS + fuel
        thrust = round(twr * g * mass, 1)
        t_ign, t_burn = reference(h0, -v0, g, thrust, mass, touch, safe)
        assert BURN * t_burn < fuel, "the reference burn must fit the fuel"
        init = ["(flying)", f"(= (h) {num(h0)}) (= (v) {num(-v0)})",
                f"(= (mass) {num(mass)}) (= (fuel) {num(fuel)}) (= (burn-rate) {num(BURN)})",
                f"(= (gravity) {num(g)}) (= (thrust) {num(thrust)})",
                f"(= (touch-height) {num(touch)}) (= (safe-speed) {num(safe)})"]
        body = "\n    ".join(init)
        problem = (f"(define (problem lander-{size:02d})\n  (:domain lander)\n"
                   f"  (:init\n    {body})\n  (:goal (and (landed))))\n")
        steps = [Step(t_ign, "ignite"), Step(t_ign + t_burn, "touch-down")]
        header = (f"reference plan (generator): ignite at {t_ign:.6f}, touch down after a "
                  f"{t_burn:.6f} s burn at h = {touch / 2:g}, v = {-safe / 2:g}")
        out.append(Instance(size=size, problem=problem, plan=plan_text(steps, header),
                            plan_check="sim",
                            params={"height": h0, "speed": v0, "gravity": g, "thrust": thrust,
                                    "mass": mass, "fuel": fuel, "touch_height": touch,
                                    "safe_speed": safe, "fuel_slack": slack}))
    return out


FAMILIES = [
    Family(
        name="lander",
        summary="powered descent: gravity and thrust / mass with the mass burning down (the "
                "rocket equation: v' = T/m(t), log solutions), a crash event at the ground, a "
                "touch-down window on height and speed; grows height and speed, tightens the "
                "window and the fuel",
        features=("processes", "events", "nonlinear", "division"),
        domain=DOMAIN, build=_build, val_reads=True, val_integrates=False,
        notes="VAL parses it but does not integrate v' = T/m(t) (\"Quotient polynomials are "
              "not handled yet!\"): reference plans are checked by the generator's closed-form "
              "solution",
    ),
]
