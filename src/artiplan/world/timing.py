"""Timed joint trajectories within Baxter's joint velocity, acceleration and jerk limits.

A path of joint-space waypoints is timed segment by segment with Ruckig (jerk-limited,
time-optimal, phase-synchronised): every segment starts and ends at rest, so all joints move
in proportion and the arm stays exactly on the straight segment the planner checked
(:mod:`artiplan.world.motion`). Stopping at each waypoint costs some time against a
path-following parametrisation (TOPP), which would leave the checked segments at the corners.

Limits: velocities are Baxter's (its URDF, ``baxter_description``: 1.5 rad/s for s0-e1,
4.0 rad/s for the wrist joints). Baxter publishes no acceleration limits; the values here
(3 rad/s^2 for s0-e1, 6 rad/s^2 for the wrist, jerk 10x that per second) are chosen so the
simulated torque-limited arm tracks its command closely (benchmarks/results/world.md).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from artiplan.world.rotations import Vec

#: Baxter's joint velocity limits [rad/s], s0 s1 e0 e1 w0 w1 w2.
VELOCITY = (1.5, 1.5, 1.5, 1.5, 4.0, 4.0, 4.0)
#: Acceleration [rad/s^2] and jerk [rad/s^3] limits used (see the module docstring).
ACCELERATION = (6.0, 6.0, 6.0, 6.0, 12.0, 12.0, 12.0)
JERK = (60.0, 60.0, 60.0, 60.0, 120.0, 120.0, 120.0)


@dataclass(frozen=True)
class Limits:
    """Per-joint limits of one arm; ``scale`` multiplies velocity, acceleration and jerk."""

    velocity: tuple[float, ...] = VELOCITY
    acceleration: tuple[float, ...] = ACCELERATION
    jerk: tuple[float, ...] = JERK
    scale: float = 1.0

    def stacked(self, arms: int) -> tuple[list[float], list[float], list[float]]:
        s = self.scale
        return ([v * s for v in self.velocity] * arms, [a * s for a in self.acceleration] * arms,
                [j * s for j in self.jerk] * arms)


class TimedPath:
    """A path of waypoints timed rest-to-rest per segment; :meth:`at` samples it.

    ``stretch`` >= 1 slows the whole path down uniformly (same geometry, limits kept).
    """

    def __init__(self, waypoints: list[Vec], limits: Limits, min_duration: float = 0.0) -> None:
        from ruckig import InputParameter, Result, Ruckig, Synchronization, Trajectory

        self.waypoints = [np.asarray(w, dtype=float) for w in waypoints]
        n = len(self.waypoints[0])
        if n % 7:
            raise ValueError(f"waypoints of {n} joints: expected 7 per arm")
        vel, acc, jerk = limits.stacked(n // 7)
        otg = Ruckig(n)
        self._segments: list[tuple[float, object]] = []  # (start time, ruckig trajectory)
        t = 0.0
        for a, b in zip(self.waypoints, self.waypoints[1:], strict=False):
            if np.allclose(a, b, atol=1e-9):
                continue
            inp = InputParameter(n)
            inp.current_position, inp.target_position = list(a), list(b)
            inp.max_velocity, inp.max_acceleration, inp.max_jerk = vel, acc, jerk
            inp.synchronization = Synchronization.Phase
            traj = Trajectory(n)
            result = otg.calculate(inp, traj)
            if result not in (Result.Working, Result.Finished):
                raise RuntimeError(f"Ruckig could not time a segment: {result}")
            self._segments.append((t, traj))
            t += float(traj.duration)
        self.natural = t
        self.stretch = max(1.0, min_duration / t) if t > 0 else 1.0
        self.duration = t * self.stretch

    def at(self, t: float) -> tuple[Vec, Vec]:
        """(joint angles [rad], velocities [rad/s]) at ``t`` [s] from the start (held at the
        ends outside [0, duration])."""
        q, qd, _ = self.state(t)
        return q, qd

    def state(self, t: float) -> tuple[Vec, Vec, Vec]:
        """(angles [rad], velocities [rad/s], accelerations [rad/s^2]) at ``t`` [s]."""
        if not self._segments or t >= self.duration:
            zero = np.zeros_like(self.waypoints[-1])
            return self.waypoints[-1].copy(), zero, zero.copy()
        tau = min(max(t, 0.0), self.duration) / self.stretch
        k = len(self._segments) - 1
        while k > 0 and self._segments[k][0] > tau:
            k -= 1
        t0, traj = self._segments[k]
        local = min(tau - t0, float(traj.duration))  # type: ignore[attr-defined]
        pos, vel, acc = traj.at_time(local)  # type: ignore[attr-defined]
        k2 = self.stretch**2
        return np.asarray(pos), np.asarray(vel) / self.stretch, np.asarray(acc) / k2
