"""Approach motions of Baxter's arms (mixin of :class:`artiplan.world.baxter.BaxterHands`).

An approach backs opened hands that are still near the object off the links, moves each arm in
joint space to a pre-grasp pose a few centimetres back along the hand's approach axis from its
grasp (a detour through a further-backed waypoint exists but is off: :data:`DETOURS_M`), then
straight in along that axis through IK waypoints. The
path is checked at a few sampled configurations only; arm contacts are off in the physics.
"""

from __future__ import annotations

from collections.abc import Callable

import mujoco
import numpy as np

from artiplan.world.collision import clearance
from artiplan.world.grasping import REACH_TOLERANCE, Candidate, GraspChoice
from artiplan.world.rotations import Vec, quat_to_mat

ARM_JOINTS = ("s0", "s1", "e0", "e1", "w0", "w1", "w2")
#: Interval [s] between joint-target updates of an approach motion.
APPROACH_DT = 0.02
#: Time [s] the arms get to settle on their grasps after an approach.
APPROACH_SETTLE_S = 0.2
#: Default retreat after a release: this far [m] back along the hand's approach axis, in
#: this many simulated seconds.
RETREAT_M = 0.1
RETREAT_S = 0.5
#: An approach first backs every opened hand whose grasp point is nearer than RETREAT_NEAR
#: [m] to a link APPROACH_RETREAT_M [m] along its approach axis, in APPROACH_RETREAT_S [s].
RETREAT_NEAR = 0.06
APPROACH_RETREAT_M = 0.06
APPROACH_RETREAT_S = 0.24
#: Joint configurations checked for clearance along an approach (evenly spaced, ends excluded).
PATH_CHECKS = 8
#: ... and on the last leg also this far (smoothstep parameter) along it.
END_CHECK = 0.94
#: Pre-grasp pose: this far [m] back along the approach axis from the grasp, reached in this
#: share of ``approach_s``; the rest goes straight in through PREGRASP_STEPS IK waypoints.
PREGRASP_M = 0.07
PREGRASP_SHARE = 0.75
PREGRASP_STEPS = 3
#: A first leg through an obstacle may go through the pre-grasp pose backed this far [m] more
#: (or the start backed the first distance). Off: measured (world.md), detours of (0.12, 0.24)
#: took 7 -> 6 of 24 approaches out of contact on 4 links but 7 -> 9 into it on 6 links (the
#: simulated arm lags the sampled path).
DETOURS_M: tuple[float, ...] = ()


def _along(path: list[Vec], s: float) -> tuple[Vec, Vec]:
    """Point and slope d/ds of the piecewise-linear ``path`` (equal shares) at ``s`` in [0, 1]."""
    m = len(path) - 1
    if m == 0:
        return path[0].copy(), np.zeros_like(path[0])
    k = min(int(s * m), m - 1)
    step = path[k + 1] - path[k]
    return path[k] + (s * m - k) * step, m * step

class ApproachMotion(GraspChoice):
    """Mixin: approach paths to the grasps and joint-space moves along waypoints."""

    approach_s: float
    _held: dict[str, str | None]
    _planned: dict[str, tuple[str, int]]
    _target_q: dict[str, Vec]
    _target_qd: dict[str, Vec]
    last_approach_clearance: dict[str, tuple[float, float]]
    last_pregrasp: dict[str, Vec]

    def approach(self, pairs: list[tuple[str, str]], advance: Callable[[float], None]) -> None:
        """Move each (hand, link) arm to its grasp in simulated time, advancing the world with
        ``advance(dt)``: first every opened hand still near the object backs off
        :data:`APPROACH_RETREAT_M` along its approach axis (:data:`APPROACH_RETREAT_S`), then
        the arms move in joint space to their pre-grasp poses (:data:`PREGRASP_M` back along
        the approach axis from the grasps :meth:`assign` chose; through a further-backed
        waypoint if :data:`DETOURS_M` is set and that is clearer) in :data:`PREGRASP_SHARE`
        of ``approach_s`` seconds, then straight in (IK waypoints) in the rest, then settle;
        the final grasp corrects what the falling links moved meanwhile. Nothing happens when
        ``approach_s`` is 0 (the arms jump at grasp)."""
        if self.approach_s <= 0:
            return
        links = dict(pairs)
        finals: dict[str, list[Vec]] = {}
        for h, link in pairs:
            c = self._chosen(h, link)
            finals[h] = self._final_leg(h, c)
            self._planned[h] = (link, c.index)  # the grasp then keeps this candidate
        starts = {h: self.data.qpos[self._q[h]].copy() for h in self.names}
        near = [h for h in self.names if self._held[h] is None and self._near_object(h)]
        if near:
            away = {h: self._backed_off(h, APPROACH_RETREAT_M) for h in near}
            self._move({h: [starts[h], away[h]] for h in near}, APPROACH_RETREAT_S, advance, 0.0)
            starts.update(away)
        firsts = {h: [starts[h], finals[h][0]] for h in finals}
        for h, link in pairs:  # a detour when the direct leg passes through an obstacle
            firsts[h] = self._clearer_leg(h, link, firsts, finals[h])
        self.last_pregrasp = {h: finals[h][0] for h in finals}
        self.last_approach_clearance = {
            h: self._path_clearance(h, links[h], [firsts, finals]) for h in finals
        }
        t_first = PREGRASP_SHARE * self.approach_s
        self._move(firsts, t_first, advance, 0.0)
        self._move(finals, self.approach_s - t_first, advance)

    def _final_leg(self, hand: str, c: Candidate) -> list[Vec]:
        """Joint angles [rad] from the pre-grasp pose to the grasp ``c``: IK waypoints on the
        straight line along the hand's approach axis (solved backwards from ``c.q`` so they
        stay on its branch); just ``[c.q]`` if the pre-grasp pose is out of reach."""
        axis = quat_to_mat(c.quat)[:, 2]
        path, q = [c.q], c.q
        for i in range(1, PREGRASP_STEPS + 1):
            pos = c.pos - (i / PREGRASP_STEPS) * PREGRASP_M * axis
            q = self.solve_ik(hand, pos, c.quat, iterations=100, start=q)
            if self.ik_miss(hand, pos, c.quat) > REACH_TOLERANCE:
                return [c.q, c.q]
            path.insert(0, q)
        return path

    def _clearer_leg(
        self, hand: str, link: str, firsts: dict[str, list[Vec]], final: list[Vec]
    ) -> list[Vec]:
        """``hand``'s first leg: direct to the pre-grasp pose or, when the direct leg's
        sampled clearance (robot, scene and other links) is negative, through the clearest of
        a few waypoints: the pre-grasp pose or the start backed :data:`DETOURS_M` further."""
        direct = self._path_clearance(hand, link, [firsts])[1]
        if direct >= 0 or np.array_equal(final[0], final[-1]):
            return firsts[hand]
        best, leg = direct, firsts[hand]
        for end, dists in ((final[0], DETOURS_M), (firsts[hand][0], DETOURS_M[:1])):
            pos, quat = self._hand_pose(hand, end)
            for dist in dists:
                via_pos = pos - dist * quat_to_mat(quat)[:, 2]
                via = self.solve_ik(hand, via_pos, quat, iterations=100, start=end)
                detour = [firsts[hand][0], via, final[0]]
                score = self._path_clearance(hand, link, [{**firsts, hand: detour}])[1]
                if score > best:
                    best, leg = score, detour
        return leg

    def _hand_pose(self, hand: str, q: Vec) -> tuple[Vec, Vec]:
        """World pose (position [m], wxyz) of ``hand`` with its arm at ``q``."""
        d = self.ik_data
        d.qpos[:] = self.data.qpos
        d.qpos[self._q[hand]] = q
        mujoco.mj_kinematics(self.model, d)
        return d.xpos[self._hand[hand]].copy(), d.xquat[self._hand[hand]].copy()

    def _chosen(self, hand: str, link: str) -> Candidate:
        """The grasp :meth:`assign` chose for (hand, link) if it is still current, else the
        best one now."""
        plan = self._plan.get(hand)
        if plan is not None and plan[0].link == link and plan[1] == self.data.time:
            return plan[0]
        return self.best_grasp(hand, link)

    def _near_object(self, hand: str) -> bool:
        """Whether ``hand``'s grasp point is within :data:`RETREAT_NEAR` of a link."""
        r_h = self.data.xmat[self._hand[hand]].reshape(3, 3)
        point = self.data.xpos[self._hand[hand]] + self._depth * r_h[:, 2]
        for link, gid in self.geoms[hand].links.items():
            b = self.model.body(link).id
            base, u = self.data.xpos[b], -self.data.xmat[b].reshape(3, 3)[:, 2]
            length = 2.0 * float(self.model.geom_size[gid, 1])
            t = float(np.clip(np.dot(point - base, u), 0.0, length))
            if np.linalg.norm(point - base - t * u) < RETREAT_NEAR:
                return True
        return False

    def _backed_off(self, hand: str, distance: float) -> Vec:
        """Joint angles [rad] putting ``hand`` ``distance`` [m] back along its approach axis."""
        r_h = self.data.xmat[self._hand[hand]].reshape(3, 3)
        pos = self.data.xpos[self._hand[hand]] - distance * r_h[:, 2]
        start = self.data.qpos[self._q[hand]].copy()
        quat = self.data.xquat[self._hand[hand]].copy()
        return self.solve_ik(hand, pos, quat, iterations=100, start=start)

    def _path_clearance(
        self, hand: str, link: str, legs: list[dict[str, list[Vec]]]
    ) -> tuple[float, float]:
        """Smallest clearance [m] of ``hand``'s arm on its way to ``link`` at
        :data:`PATH_CHECKS` configurations along each leg (per hand, joint-space waypoints;
        both arms moving; the last leg also at :data:`END_CHECK` of the way): to the torso,
        the other arm and the scene; and to those or the object's links (the gripper may touch
        ``link``; the links as they are now)."""
        d = self.ik_data
        robot, links = np.inf, np.inf
        for j, leg in enumerate(legs):
            xs = [i / (PATH_CHECKS + 1) for i in range(1, PATH_CHECKS + 1)]
            for x in xs + ([END_CHECK] if j == len(legs) - 1 else []):
                s = x * x * (3.0 - 2.0 * x)
                d.qpos[:] = self.data.qpos
                for h, path in leg.items():
                    d.qpos[self._q[h]] = _along(path, s)[0]
                mujoco.mj_kinematics(self.model, d)
                robot = min(robot, clearance(self.model, d, self.geoms[hand], link, False)[0])
                links = min(links, clearance(self.model, d, self.geoms[hand], link, True)[0])
        return float(robot), float(links)

    def _move(
        self,
        paths: dict[str, list[Vec]],
        duration_s: float,
        advance: Callable[[float], None],
        settle_s: float = APPROACH_SETTLE_S,
    ) -> None:
        """Each hand's arm along its joint-space waypoints (piecewise linear, timed by one
        smoothstep) in ``duration_s`` simulated seconds, then ``settle_s`` of settling."""
        n = max(1, int(round(duration_s / APPROACH_DT)))
        dt = duration_s / n
        for i in range(1, n + 1):
            x = i / n
            s = x * x * (3.0 - 2.0 * x)  # smoothstep: start and stop at rest
            ds = 6.0 * x * (1.0 - x) / duration_s  # its rate [1/s]
            for h, path in paths.items():
                self._target_q[h], slope = _along(path, s)
                self._target_qd[h] = ds * slope
            advance(dt)
        for h in paths:
            self._target_qd[h] = np.zeros(len(ARM_JOINTS))
        if settle_s > 0:
            advance(settle_s)
