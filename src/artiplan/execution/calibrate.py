"""Identify the gravity models' parameters from the physics, and the robot's reach time.

A release run: the object hangs straight down except the tip link, held horizontal and then
released; its gamma is recorded for ``window_s`` seconds. UCM's ``speed-g`` is the least-
squares slope of the fall (deg/s), UACM's ``acceleration`` the least-squares fit of
``gamma0 - gamma = a t^2 / 2`` (deg/s^2). The fit window matters: a stiff (overdamped) joint
falls at a nearly constant speed, a loose one accelerates and then swings.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from artiplan.model import ArticulatedObject, Configuration

if TYPE_CHECKING:
    from artiplan.world import World


@dataclass(frozen=True)
class Calibration:
    """Gravity parameters identified from a release run.

    Attributes:
        speed_g: UCM angular speed [deg/s].
        acceleration: UACM angular acceleration [deg/s^2].
        window_s: Length of the fitted fall [s].
        start_gamma: Gamma the link was released from [deg].
        times: Sample times [s] of the fall; ``gammas`` the tip link's gamma then [deg].
    """

    speed_g: float
    acceleration: float
    window_s: float
    start_gamma: float
    times: tuple[float, ...] = ()
    gammas: tuple[float, ...] = ()


def release_configuration(n_links: int, start_gamma: float = 90.0) -> Configuration:
    """Every link hanging (gamma 0) except the tip link at ``start_gamma`` [deg]."""
    gamma = (0.0,) * (n_links - 1) + (start_gamma,)
    return Configuration((0.0,) * n_links, gamma)


def fit_fall(times: np.ndarray, gammas: np.ndarray) -> tuple[float, float]:
    """(speed_g [deg/s], acceleration [deg/s^2]) of a fall ``gammas`` [deg] at ``times`` [s]."""
    t = times - times[0]
    drop = gammas[0] - gammas
    speed = float(np.dot(t, drop) / max(np.dot(t, t), 1e-12))
    half_t2 = 0.5 * t**2
    acc = float(np.dot(half_t2, drop) / max(np.dot(half_t2, half_t2), 1e-12))
    # A link that does not fall would give 0: the encodings need positive parameters.
    return max(speed, 1e-3), max(acc, 1e-3)


def calibrate(make: Callable[..., World], obj: ArticulatedObject, *, preset: str = "stiff",
              window_s: float = 5.0, start_gamma: float = 90.0, dt: float = 0.01) -> Calibration:
    """Release the tip link from ``start_gamma`` in a fresh world and fit both models over
    ``window_s`` [s] or until the link is within 10% of rest, whichever comes first.

    ``make`` is a ``make_world``-like factory ``(obj, conf, preset=..., hands="virtual")``.
    """
    world = make(obj, release_configuration(obj.n_links, start_gamma), preset=preset,
                 hands="virtual")
    times, gammas = [0.0], [start_gamma]
    t0 = world.time
    while world.time - t0 < window_s - 1e-9:
        world.run_until(world.time + dt)
        conf = world.true_configuration()
        times.append(world.time - t0)
        gammas.append(min(conf.gamma[-1], 360.0 - conf.gamma[-1]))
    t_arr, g_arr = np.array(times), np.array(gammas)
    # Fit the fall itself: up to where the link first gets near rest (a loose joint swings
    # about 0 afterwards, which neither model describes).
    low = np.nonzero(g_arr < 0.1 * start_gamma)[0]
    if low.size:
        t_arr, g_arr = t_arr[: low[0] + 1], g_arr[: low[0] + 1]
    speed, acc = fit_fall(t_arr, g_arr)
    return Calibration(speed, acc, window_s, start_gamma, tuple(times), tuple(gammas))


def measure_reach(make: Callable[..., World], obj: ArticulatedObject, *, preset: str = "stiff",
                  approach_s: float = 1.0, seed: int = 0,
                  repeats: int | None = None) -> float | None:
    """Reach time [s, simulated] measured on Baxter arms that approach their grasps.

    In a fresh Baxter world (``make``: a ``make_world``-like factory) with the object in the
    release configuration, the arms are sent ``repeats`` times from released to holding
    (L1-L2 then L2-L3 ..., rotating on ``z-axis``), each after a release; the reach time is the
    longest simulated time one ``hold_and_rotate`` took before the rotation could start
    (release -> next grasp ready). None when the arms grasp at once (``approach_s`` = 0).
    ``repeats`` (default: ``max(2, links - 2)``): a longer chain's approaches reach further
    along it. With two on 6 links the longest was 2.752 s or 2.436 s by whether one final
    leg passed near another link (the stiff preset's armature flipped it: session 26),
    against a median of 3.0-3.4 s for the real reaches of the runs; with four
    it is 2.68-2.89 s. 4 links keep their two (2.434 s, median of the runs 2.6-2.8 s).
    """
    if approach_s <= 0:
        return None
    if repeats is None:
        repeats = max(2, obj.n_links - 2)
    world = make(obj, release_configuration(obj.n_links, 0.0), preset=preset, hands="baxter",
                 seed=seed, approach_s=approach_s)
    links = obj.links
    longest = 0.0
    for i in range(repeats):
        hold, turn = links[i % (len(links) - 1)], links[i % (len(links) - 1) + 1]
        world.stop(release=True)
        t0 = world.time
        world.hold_and_rotate(hold, turn, "z-axis", 1, 1.0)
        longest = max(longest, world.time - t0)
        world.run_until(world.time + 0.5)
    world.stop(release=True)
    return round(longest, 3) if longest > 0 else None
