"""Approach motions of Baxter's arms (mixin of :class:`artiplan.world.baxter.BaxterHands`).

An approach has three motions, each planned and checked before the arms move:

1. every opened hand still near the object backs off :data:`APPROACH_RETREAT_M` along its
   approach axis (its gripper may touch the link it just let go of);
2. the transfer: the moving arms go in joint space (14-D when both move, the arms checked
   against each other at every state) to their pre-grasp poses, :data:`PREGRASP_M` back along
   each hand's approach axis from its grasp, planned with OMPL's RRT-Connect against the
   torso, the other arm, the table, pedestal, fixture and every link
   (:func:`artiplan.world.motion.plan_path`), keeping
   :data:`~artiplan.world.motion.TRANSFER_CLEARANCE_M`; when the 14-D query finds nothing,
   one arm moves and then the other (each 7-D, the other arm an obstacle where it stands);
3. the final straight legs in along the approach axes (IK waypoints, checked when the pair was
   chosen, every link but the one each gripper closes on).

Each motion is timed rest-to-rest per segment within Baxter's joint limits
(:class:`artiplan.world.timing.TimedPath`) and followed by the joint servos, whose set-points
are sampled from it at every physics step. ``approach_s`` is a lower bound on the three
motions' total (the transfer is slowed down uniformly when they are faster); the arms then
settle :data:`APPROACH_SETTLE_S`. Planning statistics (wall time per motion) are in
``checker.stats``.
"""

from __future__ import annotations

from collections.abc import Callable

import mujoco
import numpy as np

from artiplan.world.grasping import Candidate
from artiplan.world.motion import NEAR_CLEARANCE_M, Query, plan_path, ramped
from artiplan.world.pairs import (  # noqa: F401 - re-exported (public names)
    APPROACH_RETREAT_M,
    PREGRASP_M,
    PREGRASP_STEPS,
    RETREAT_NEAR,
    NoArmMotionError,
    NotExecutableError,
    PairChoice,
    along,
)
from artiplan.world.rotations import Vec, quat_to_mat
from artiplan.world.timing import Limits, TimedPath

ARM_JOINTS = ("s0", "s1", "e0", "e1", "w0", "w1", "w2")
#: Interval [s] at which an approach hands control back to the world's ``advance``.
APPROACH_DT = 0.02
#: Time [s] the arms get to settle on their grasps after an approach.
APPROACH_SETTLE_S = 0.2
#: A final straight leg (7 cm in to the grasp, checked at 3 mm from every other link) that
#: passes nearer than SLOW_NEAR_M [m] to anything but its link takes at least
#: FINAL_LEG_MIN_S [s]. At its own pace (0.6-0.7 s) the simulated arm lagged its path by enough
#: to touch a neighbouring link in 2 of 12 6-link cases (1.9 and 0.2 mm deep); at 0.9 s still
#: 2, at 1.2 s 1 (0.2 mm) (benchmarks/world_collision.py --approach 1.0). Every leg slowed
#: made every reach 0.5-0.6 s longer, and the loop's runs worse in that run (4 links 18/20, 6
#: links 1 of the first 9), so only the legs that pass near something are.
FINAL_LEG_MIN_S = 1.2
SLOW_NEAR_M = 0.01
#: Default retreat after a release: this far [m] back along the hand's approach axis, in at
#: least this many simulated seconds.
RETREAT_M = 0.1
RETREAT_S = 0.5
#: Lower bound [s] of the back-off at the start of an approach (kept for the old name).
APPROACH_RETREAT_S = 0.0
#: Share of ``approach_s`` the transfer takes at least (kept for the old name).
PREGRASP_SHARE = 0.75
#: How far [m] arms sent home (:meth:`ApproachMotion.go_home`) first back off along their
#: approach axes.
ESCAPE_RETREAT_M = 0.15
#: Wall time [s] of each one-arm query when both arms' transfer is planned one by one.
ONE_ARM_TIME_S = 1.0


class ApproachMotion(PairChoice):
    """Mixin: planned, timed approach motions to the grasps."""

    limits: Limits
    _planned: dict[str, tuple[str, int]]
    _target_qd: dict[str, Vec]
    _target_qdd: dict[str, Vec]
    _no_contact: dict[str, set[str]]
    _active: tuple[float, TimedPath, tuple[str, ...]] | None
    close_in: Callable[[str, str], None]
    last_approach_clearance: dict[str, tuple[float, float]]
    last_pregrasp: dict[str, Vec]
    #: Per approach: hand -> world positions [m] of its grasp point along the planned motion.
    last_paths: list[dict[str, list[Vec]]]

    def approach(self, pairs: list[tuple[str, str]], advance: Callable[[float], None]) -> None:
        """Move each (hand, link) arm to the grasp :meth:`assign` chose, in simulated time
        (the world advancing by ``advance(dt)``): back-off, planned transfer, straight leg,
        settling (module docstring). Raises :class:`NotExecutableError` when no
        collision-free transfer is found. Nothing happens when ``approach_s`` is 0 (the arms
        jump at grasp)."""
        if self.approach_s <= 0:
            return
        cands = {h: self._chosen(h, link) for h, link in pairs}
        legs = {h: self._leg(c) for h, c in cands.items()}
        for h, link in pairs:
            self._planned[h] = (link, cands[h].index)  # the grasp then keeps this candidate
        moving = tuple(h for h in self.names if h in legs)
        backoff = self._plan_backoff()
        starts = {h: self._actual(h) for h in self.names}
        if backoff is not None:
            starts.update(backoff.split_end())
        goals = {h: legs[h][0] for h in moving}
        goals.update(self.idle_goals(moving, starts))  # an idle arm goes home, out of the way
        travelling = tuple(h for h in self.names if h in goals)
        transfer = self._plan_transfer(travelling, starts, goals, legs, cands)
        steps = max(len(leg) for leg in legs.values()) - 1
        final = TimedPath([np.concatenate([along(legs[h], k / steps) for h in moving])
                           for k in range(steps + 1)], self.limits)
        spent = final.duration + (backoff.path.duration if backoff else 0.0)
        transfer = TimedPath(transfer.waypoints, self.limits, self.approach_s - spent)
        self.last_pregrasp = {h: legs[h][0] for h in moving}
        self._record_paths([backoff, _Stage(travelling, transfer), _Stage(moving, final)])
        if backoff is not None:
            self._run(backoff.hands, backoff.path, advance, 0.0)
        self._run(travelling, transfer, advance, 0.0)
        floor = self.approach_s - transfer.duration - (backoff.path.duration if backoff else 0.0)
        final = self._retarget(moving, cands, final, floor)
        for h in moving:
            self.close_in(h, cands[h].link)
        self._run(moving, final, advance, APPROACH_SETTLE_S)

    def retreat(
        self,
        hands: list[str],
        advance: Callable[[float], None],
        distance: float = RETREAT_M,
        duration_s: float = RETREAT_S,
    ) -> None:
        """Back each of ``hands`` (opened first if it still holds) ``distance`` [m] away along
        its approach axis in at least ``duration_s`` simulated seconds (more if the joint
        limits need it), then settle; the world advances by ``advance(dt)``."""
        for h in hands:
            self._check_hand(h)  # type: ignore[attr-defined]
            if self._held[h] is not None:
                self.release(h)  # type: ignore[attr-defined]
        moving = tuple(h for h in self.names if h in hands)
        path = [np.concatenate([self._actual(h) for h in moving]),
                np.concatenate([self._backed_off(h, distance) for h in moving])]
        self._run(moving, TimedPath(path, self.limits, duration_s), advance)

    def go_home(self, advance: Callable[[float], None]) -> bool:
        """Both open arms home (:attr:`home`) by planned motions, in simulated time (the world
        advancing by ``advance(dt)``): they back off :data:`ESCAPE_RETREAT_M`, then one
        collision-free transfer (14-D, else one arm after the other), timed within the joint
        limits, then settling. The way out when the arms are caught in the chain (no motion
        to a grasp found from where they are). False, nothing moved, when the arms are home
        already, a hand still holds, or no path home is found."""
        if any(self._held[h] is not None for h in self.names):
            return False
        starts = {h: self._actual(h) for h in self.names}
        goals = self.idle_goals((), starts)
        if not goals:
            return False
        moving = tuple(h for h in self.names if h in goals)
        # further back than an approach's back-off: an arm caught in the chain gets out first
        backoff = self._plan_backoff(ESCAPE_RETREAT_M, moving)
        if backoff is not None:
            starts.update(backoff.split_end())
        path = self._transfer_path(moving, starts, goals, {})
        if path is None:
            return False
        home = TimedPath(path, self.limits)
        self._record_paths([backoff, _Stage(moving, home)])
        if backoff is not None:
            self._run(backoff.hands, backoff.path, advance, 0.0)
        self._run(moving, home, advance)
        return True

    # -- planning the three motions ---------------------------------------------------------
    def _plan_backoff(self, distance: float = APPROACH_RETREAT_M,
                      near: tuple[str, ...] | None = None) -> _Stage | None:
        """The back-off ``distance`` [m] along their approach axes of the opened hands
        ``near`` (default: those near the object); None if there is none."""
        if near is None:
            near = tuple(h for h in self.names if self._held[h] is None and self._near_object(h))
        if not near:
            return None
        start = np.concatenate([self._actual(h) for h in near])
        goal = np.concatenate([self._backed_off(h, distance) for h in near])
        self.checker.sync(self.data.qpos)
        query = Query(near, self._contacts_off(near), NEAR_CLEARANCE_M)
        path = plan_path(self.checker, self._ramp(query, start, goal), start, goal,
                         self._bounds(near))
        if path is None:  # nothing better found: straight back (the physics has the say)
            path = [start, goal]
        return _Stage(near, TimedPath(path, self.limits))

    def _plan_transfer(
        self, moving: tuple[str, ...], starts: dict[str, Vec], goals: dict[str, Vec],
        legs: dict[str, list[Vec]], cands: dict[str, Candidate],
    ) -> TimedPath:
        """The collision-free joint-space motion of ``moving`` from ``starts`` to ``goals``
        (the pre-grasp poses; home for an idle arm)."""
        # A leg out of reach ends the transfer on the grasp itself: its gripper meets its link.
        gripping = {h: cands[h].link for h in legs if np.array_equal(legs[h][0], legs[h][-1])}
        path = self._transfer_path(moving, starts, goals, gripping)
        if path is None:
            raise NoArmMotionError(
                "no collision-free arm motion found to the pre-grasp poses of "
                + ", ".join(f"{h} on {cands[h].link}" for h in legs))
        return TimedPath(path, self.limits)

    def _transfer_path(
        self, moving: tuple[str, ...], starts: dict[str, Vec], goals: dict[str, Vec],
        gripping: dict[str, str],
    ) -> list[Vec] | None:
        """Stacked waypoints of a collision-free joint-space motion of ``moving`` from
        ``starts`` to ``goals`` (14-D when both move, else or failing that one arm after the
        other), or None; ``gripping``: hand -> the link its gripper may meet."""
        chk = self.checker
        chk.sync(self.data.qpos)
        chk.set_arms(starts)
        start = np.concatenate([starts[h] for h in moving])
        goal = np.concatenate([goals[h] for h in moving])
        # Not the links the grippers have just let go of: the ramp lets them out of those
        # near the start only (afterwards the physics collides with them again).
        query = self._ramp(Query(moving, self.grip_pairs(gripping)), start, goal)
        path = plan_path(chk, query, start, goal, self._bounds(moving))
        if path is None and len(moving) == 2:
            path = self._one_by_one(moving, starts, goals, gripping)
        return path

    def _one_by_one(
        self, moving: tuple[str, ...], starts: dict[str, Vec], goals: dict[str, Vec],
        gripping: dict[str, str],
    ) -> list[Vec] | None:
        """Both arms' transfer as one arm's motion and then the other's, each planned in 7-D
        with the other arm standing still where it is (an obstacle), in either order; the
        stacked waypoints (one arm still on each segment), or None. The fallback when the
        14-D query finds nothing in its time: RRT-Connect in 14-D can miss a passage that
        each arm alone finds at once (an arm that must wait for the other to clear)."""
        chk = self.checker
        for order in (moving, moving[::-1]):
            q = {h: starts[h].copy() for h in moving}
            path = [np.concatenate([q[h] for h in moving])]
            for h in order:
                chk.sync(self.data.qpos)
                chk.set_arms(q)
                grips = self.grip_pairs({h: gripping[h]} if h in gripping else {})
                query = self._ramp(Query((h,), grips), q[h], goals[h])
                leg = plan_path(chk, query, q[h], goals[h], self._bounds((h,)),
                                ONE_ARM_TIME_S)
                if leg is None:
                    break
                for wp in leg[1:]:
                    q[h] = wp
                    path.append(np.concatenate([q[a] for a in moving]))
            else:
                return path
        return None

    def _retarget(
        self, moving: tuple[str, ...], cands: dict[str, Candidate], final: TimedPath,
        floor: float = 0.0,
    ) -> TimedPath:
        """The final legs again, to where the grasps are now (the links moved while the arms
        travelled): one segment from each pre-grasp pose to its grasp re-solved, if that is
        collision-free, timed at its own pace but at least ``floor`` [s] (what is left of
        ``approach_s``), else the legs as planned."""
        start = np.concatenate([self._actual(h) for h in moving])
        goal = []
        for h in moving:
            c = cands[h]
            pos, quat = self.grasp_poses(h, c.link)[c.index]
            goal.append(self.solve_ik(h, pos, quat, iterations=150, start=c.q))
        path = [start, np.concatenate(goal)]
        chk = self.checker
        chk.sync(self.data.qpos)
        query = Query(moving, self.grip_pairs({h: cands[h].link for h in moving}),
                      NEAR_CLEARANCE_M)
        # One pass answers both: collision-free (NEAR_CLEARANCE_M), and whether it passes near.
        clear = chk.path_clearance(path, query, stop_below=NEAR_CLEARANCE_M)
        if clear < NEAR_CLEARANCE_M:
            return final
        # Timed on its own (one segment, rest to rest), not stretched to the planned legs'
        # duration: those stop at each IK waypoint when the joint-space line is not straight
        # enough, 1.3-1.6 s for 7 cm; not faster than FINAL_LEG_MIN_S when it passes near.
        if clear < SLOW_NEAR_M:
            floor = max(floor, FINAL_LEG_MIN_S)
        return TimedPath(path, self.limits, floor)

    def _contacts_off(self, hands: tuple[str, ...]) -> frozenset[tuple[int, int]]:
        """The geom pairs of ``hands``' grippers and the links the physics lets them touch now
        (a link let go of and not yet left): the checks allow them too."""
        out: frozenset[tuple[int, int]] = frozenset()
        for h in hands:
            for link in self._no_contact[h]:
                out |= self.grip_pairs({h: link})
        return out

    def _ramp(self, query: Query, start: Vec, goal: Vec) -> Query:
        """``query`` with its clearance relaxed near a start or goal nearer than it."""
        chk = self.checker
        full = float(query.clearance) if not callable(query.clearance) else NEAR_CLEARANCE_M
        ends = []
        for q in (start, goal):
            clear, _ = chk.clearance(chk.split(query.hands, q), Query(query.hands, query.allowed))
            ends.append((q, clear))
        return Query(query.hands, query.allowed, ramped(ends, full))

    def _actual(self, hand: str) -> Vec:
        """Where ``hand``'s arm is [rad] (not where it was commanded: a tracking arm lags),
        within its joint limits. Motions start here."""
        q = self.data.qpos[self._q[hand]]
        return np.clip(q, self._lo[hand], self._hi[hand])

    def _bounds(self, hands: tuple[str, ...]) -> tuple[Vec, Vec]:
        lo = np.concatenate([self._lo[h] for h in hands])
        hi = np.concatenate([self._hi[h] for h in hands])
        return lo, hi

    def _chosen(self, hand: str, link: str) -> Candidate:
        """The grasp :meth:`assign` chose for (hand, link) if it is still current, else the
        best one now."""
        plan = self._plan.get(hand)
        if plan is not None and plan[0].link == link and plan[1] == self.data.time:
            return plan[0]
        return self.best_grasp(hand, link)

    # -- moving ----------------------------------------------------------------------------
    def _run(
        self, hands: tuple[str, ...], path: TimedPath, advance: Callable[[float], None],
        settle_s: float = APPROACH_SETTLE_S,
    ) -> None:
        """Follow ``path`` (stacked joint angles of ``hands``) in simulated time: the servo
        set-points are sampled from it at every physics step (:meth:`control`), the world
        advanced in :data:`APPROACH_DT` chunks; then ``settle_s`` of settling."""
        self._active = (float(self.data.time), path, hands)
        end = self.data.time + path.duration
        while self.data.time < end - 1e-9:
            advance(min(APPROACH_DT, end - self.data.time))
        self._active = None
        q_end, _ = path.at(path.duration)
        for i, h in enumerate(hands):
            self._target_q[h] = q_end[7 * i : 7 * i + 7].copy()
            self._target_qd[h] = np.zeros(len(ARM_JOINTS))
            self._target_qdd[h] = np.zeros(len(ARM_JOINTS))
        if settle_s > 0:
            advance(settle_s)

    def _follow(self, dt: float) -> None:
        """Set-points of the arms on an active path at the end of the coming step."""
        if self._active is None:
            return
        t0, path, hands = self._active
        q, qd, qdd = path.state(float(self.data.time) + dt - t0)
        for i, h in enumerate(hands):
            self._target_q[h] = q[7 * i : 7 * i + 7]
            self._target_qd[h] = qd[7 * i : 7 * i + 7]
            self._target_qdd[h] = qdd[7 * i : 7 * i + 7]

    def _record_paths(self, stages: list[_Stage | None]) -> None:
        """The grasp points' planned traces (for pictures), a sample every 0.05 rad."""
        traces: dict[str, list[Vec]] = {h: [] for h in self.names}
        for stage in stages:
            if stage is None:
                continue
            wps = stage.path.waypoints
            for a, b in zip(wps, wps[1:], strict=False):
                n = max(1, int(np.ceil(np.linalg.norm(b - a) / 0.05)))
                for i in range(n + 1):
                    q = a + (i / n) * (b - a)
                    for k, h in enumerate(stage.hands):
                        pos, quat = self._hand_pose(h, q[7 * k : 7 * k + 7])
                        traces[h].append(pos + self._depth * quat_to_mat(quat)[:, 2])
        self.last_paths.append({h: t for h, t in traces.items() if t})

    def _hand_pose(self, hand: str, q: Vec) -> tuple[Vec, Vec]:
        """World pose (position [m], wxyz) of ``hand`` with its arm at ``q``."""
        d = self.ik_data
        d.qpos[:] = self.data.qpos
        d.qpos[self._q[hand]] = q
        mujoco.mj_kinematics(self.model, d)
        return d.xpos[self._hand[hand]].copy(), d.xquat[self._hand[hand]].copy()


class _Stage:
    """One motion of an approach: which hands, along which timed path."""

    def __init__(self, hands: tuple[str, ...], path: TimedPath) -> None:
        self.hands, self.path = hands, path

    def split_end(self) -> dict[str, Vec]:
        end = self.path.waypoints[-1]
        return {h: end[7 * i : 7 * i + 7].copy() for i, h in enumerate(self.hands)}
