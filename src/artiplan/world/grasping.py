"""Grasp choice for Baxter's arms: candidate hand poses along a link, their inverse
kinematics, and a score that puts reach first, then arm clearance, then joint-limit room.

Candidates: grasp points at the link's centre and a quarter of the link further from the joint
it shares with the other grasped link (more reach, more room between two hands on neighbouring
links); at each point the hand's approach axis is perpendicular to the link, turned about it in
8 steps, fingers either way (16 poses per point). The rotating hand's candidates are also
solved at the grasp turned +-:data:`SWEEP_DEG` about the link's joint (both rotation planes).

With ``avoid_collisions`` the grasp IK is pushed away from the torso, pedestal, table, fixture
and other links, and the holding/rotating pair is chosen jointly: the arms' distance to each
other at the grasps and at the turned poses (holding arm at its grasp) enter the score.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import mujoco
import numpy as np

from artiplan.world.collision import ArmGeoms, clearance, repulsion
from artiplan.world.rotations import Vec, quat_axis_angle, quat_conj, quat_mul, quat_to_mat

try:  # the LAPACK gufunc np.linalg.solve calls: the same result without its per-call checks,
    # which cost more than the 6x6 solve itself in the grasp IK (~300 000 calls in a demo)
    from numpy.linalg import _umath_linalg

    def _solve(a: np.ndarray, b: np.ndarray) -> np.ndarray:
        """``np.linalg.solve(a, b)`` for a non-singular float64 ``a`` and a 2-D ``b``."""
        return _umath_linalg.solve(a, b, signature="dd->d")
except ImportError:  # pragma: no cover - a numpy without it
    _solve = np.linalg.solve

#: A grasp whose IK solution misses the grasp point by more than this [m] is refused.
REACH_TOLERANCE = 0.01
#: Score of an unreachable candidate (above any sum of the other terms: reach comes first),
#: plus MISS_WEIGHT per metre of miss (among unreachable ones the nearest miss wins: the link
#: may come into reach while the arms approach).
UNREACHABLE = 10.0
MISS_WEIGHT = 20.0
#: A candidate missing by less than this [m] is solved again from mid-range joint angles (the
#: damped least squares can stall near the workspace's edge from the arm's current angles).
RETRY_MISS = 0.05
#: Grasp points along the link [fraction of its length from the base-end joint]: the centre
#: first, then a quarter length away from the joint shared with the other grasped link.
CENTRE, OFF_CENTRE = 0.5, 0.25
#: A second tier of grasps (tried when the first gives no collision-free pair): the approach
#: axis tilted this far [deg] along the link either way, and one more point on the held link
#: (toward the rotated one) and on the rotated link (toward its pivot; not nearer than this:
#: at 0.25 the rotation's tracking diverged, world.md).
TILT_DEG = 30.0
NEAR_PIVOT = 0.35
#: Tier 3 (tried when tiers 1-2 give no pair at all): tiers 1-2's points and tilts with every
#: approach turned this far [steps of the n_turns turn about the link] further: 16 approach
#: directions instead of 8. Replayed on 40 static refusals of failed 6-link tasks
#: (benchmarks/grasp_replay.py, session 28) it found a pair for 26 where tiers 1-2 found 15
#: and the old tiers 3-4 (ends, shallow) added 6: in folded chains the free approach is often
#: between two of the 8 (the neighbouring link 5-25 mm into the gripper at both).
HALF_STEP = 0.5
#: Tier 4 (tried when tiers 1-3 give none): points near the link's ends,
#: END_NEAR of its length from a joint: both ends of the held link, the far end of the rotated
#: one (not near its pivot: the turn's tracking diverged there, world.md). Replayed on 30
#: static refusals of 6-link runs (benchmarks/grasp_replay.py), points at 0.15 and 0.85 on
#: both links found a pair for 24 where tiers 1-2 found 6: in a folded chain the links beside
#: a link's middle leave no room for Baxter's gripper, its ends do.
END_NEAR = 0.15
#: Tier 5 (tried when tiers 1-4 give none): shallow grasps, the tier-1
#: points and approaches with the link this much [m] nearer the fingertips (its axis 4 mm
#: inside their ends, the pads still on its near half). The gripper base is then 14 mm from
#: the link instead of 4 mm and the fingertips stop inside it: in folded 6-link chains
#: Baxter's grasps of L3/L5 met a neighbouring link with the base or a fingertip 5-17 mm deep
#: (143 refusals in 20 tasks, RESULTS.md, session 15).
SHALLOW_M = 0.010
#: The last tier tried. Tiers 4-5 are off: in the closed loop (as tiers 3-4, session 15) they
#: cut 6-link static refusals from 143 to 93 in 20 tasks but reached no more tasks (7/20), and
#: cost the demo 7% more wall time. benchmarks/grasp_replay.py --tiers 5 and setting this to 5
#: (pairs.py reads it too) try them.
TIERS = 3
#: Pull of the IK's null-space term toward mid-range joint angles [rad per iteration].
NULLSPACE_GAIN = 0.05
#: The same while tracking, called every 2 ms step: small, or the arm's self-motion outruns
#: its motors (0.05 per call saturated every joint).
TRACK_NULLSPACE_GAIN = 0.0005
#: Grasps with a joint closer than this to a limit [rad] score worse (less room to rotate).
LIMIT_MARGIN = 0.3
#: The rotating hand's grasps are checked this far [deg] into a turn either way (the
#: planner's rotations are tens of degrees).
SWEEP_DEG = 30.0
#: Score per radian of missing room in that sweep, summed over its turned poses (0.3 rad
#: short ~ a 3 cm miss).
SWEEP_WEIGHT = 0.1
#: Grasps whose arm comes closer than this [m] to the torso, the other arm, the pedestal,
#: table, fixture or another link score worse, by CLEARANCE_WEIGHT per metre inside it (a
#: candidate 1 cm in collision scores like one missing its grasp point by 4 cm).
CLEARANCE_MARGIN = 0.02
CLEARANCE_WEIGHT = 4.0
#: The grasp IK's null-space push away from obstacles nearer than AVOID_MARGIN [m]: gain
#: [rad per metre of intrusion per iteration], recomputed every AVOID_EVERY iterations (each
#: check costs a few hundred geom distances).
AVOID_GAIN = 2.0
AVOID_MARGIN = 0.05
AVOID_EVERY = 10
#: The IK stops when the hand is this near its target [m, rad]. 0.1 mm / 1 mrad cut the grasp
#: choice's time by ~15-28% but changed which grasps win (a 4-link case collided again): kept
#: strict.
IK_TOL_M = 1e-5
IK_TOL_RAD = 1e-4
#: Candidates per hand tried jointly with the other hand's (KEEP x KEEP pairs).
KEEP = 3
#: Score of a pairing without any collision-free pair (above every other score).
INFEASIBLE = 100.0


class OutOfReachError(RuntimeError):
    """Baxter cannot put a hand on the link (use virtual hands for long chains)."""


@dataclass
class Candidate:
    """One candidate grasp of ``link`` by ``hand``.

    Attributes:
        index: Position in :meth:`GraspChoice.grasp_poses`.
        pos, quat: The hand's target pose (world, [m] and wxyz).
        q: The IK solution [rad] (the arm's 7 joints).
        miss: Its pose error [m + 0.1 m/rad].
        score: Reach, clearance (without the other arm), limit room, nearness.
        sweep: Arm joint angles at the turned grasps (rotating hand only): every
            :data:`artiplan.world.turning.STEP_DEG` of the planned turn, or at +-SWEEP_DEG on
            both planes when the turn is not known.
        sweep_score: Missing joint-limit room over the sweep, and the share of a planned
            turn the arm cannot follow (:meth:`artiplan.world.pairs.PairChoice._turn_path`).
        leg: Joint angles [rad] of the final straight leg, pre-grasp pose first (computed
            when the candidate's pair is checked).
        solo: '' when the candidate is collision-free on its own (final leg, grasp, turn;
            the other arm aside), else why not; None until checked (for ``turn_of``).
        safe: How far [deg] its turn is collision-free on its own (-1: not even the grasp).
        hit: With ``safe`` -1, the geom the arm met at the grasp or on its final leg (-1:
            none).
    """

    hand: str
    link: str
    index: int
    pos: Vec
    quat: Vec
    q: Vec
    miss: float
    score: float
    sweep: list[Vec] = field(default_factory=list)
    sweep_score: float = 0.0
    leg: list[Vec] = field(default_factory=list)
    solo: str | None = None
    safe: float = float("inf")
    turn_of: object = None
    hit: int = -1

    @property
    def reachable(self) -> bool:
        return self.miss <= REACH_TOLERANCE

    @property
    def total(self) -> float:
        return self.score + self.sweep_score


class GraspChoice:
    """Mixin of :class:`artiplan.world.baxter.BaxterHands`: IK and the choice of grasps."""

    model: mujoco.MjModel
    data: mujoco.MjData
    ik_data: mujoco.MjData
    names: tuple[str, str]
    geoms: dict[str, ArmGeoms]
    avoid_collisions: bool
    _q: dict[str, np.ndarray]
    _v: dict[str, np.ndarray]
    _hand: dict[str, int]
    _lo: dict[str, Vec]
    _hi: dict[str, Vec]
    _depth: float
    _clamped: str
    #: (hold link, rotate link) of the last :meth:`assign` (sets where the grasp points are).
    _roles: tuple[str, str] = ("", "")
    #: hand -> (candidate, simulation time) chosen by :meth:`assign`.
    _plan: dict[str, tuple[Candidate, float]]
    _cand_cache: dict[tuple[object, ...], list[Candidate]]

    def _other(self, hand: str) -> str:
        return self.names[1] if hand == self.names[0] else self.names[0]

    # -- candidates ------------------------------------------------------------------------
    def grasp_fractions(self, link: str) -> tuple[float, ...]:
        """Grasp points on ``link`` [fraction of its length from its base-end joint]."""
        hold, rotate = self._roles
        if link == hold:  # the shared joint is at its tip
            return (CENTRE, CENTRE - OFF_CENTRE)
        if link == rotate:  # ... at its base (nearer it the turn's tracking failed: world.md)
            return (CENTRE, CENTRE + OFF_CENTRE)
        return (CENTRE, CENTRE - OFF_CENTRE, CENTRE + OFF_CENTRE)

    def extra_fractions(self, link: str) -> tuple[float, ...]:
        """More grasp points on ``link``, tried only when the first ones give no
        collision-free pair (:meth:`grasp_poses`, tier 2)."""
        hold, rotate = self._roles
        if link == hold:
            return (CENTRE + OFF_CENTRE,)
        if link == rotate:
            return (NEAR_PIVOT,)
        return ()

    def end_fractions(self, link: str) -> tuple[float, ...]:
        """Grasp points near ``link``'s ends (tier 4): not near the rotated link's pivot."""
        if link == self._roles[1]:
            return (1.0 - END_NEAR,)
        return (END_NEAR, 1.0 - END_NEAR)

    def grasp_poses(self, hand: str, link: str, n_turns: int = 8,
                    tiers: int | None = None) -> list[tuple[Vec, Vec]]:
        """Candidate hand poses on ``link``. Tier 1 (the first :meth:`tier_size`): at each of
        :meth:`grasp_fractions`, the hand's z axis (its approach) perpendicular to the link,
        turned about it in ``n_turns`` steps, x along +-link. Tier 2: the same points with the
        approach axis tilted TILT_DEG either way along the link, and :meth:`extra_fractions`
        perpendicular. Tier 3: tiers 1-2's points and tilts with the approaches turned
        HALF_STEP of a step further about the link. Tier 4: :meth:`end_fractions`
        perpendicular. Tier 5: the tier-1 poses SHALLOW_M shallower (the link nearer the
        fingertips).
        Only tiers 1 to ``tiers`` (default :data:`TIERS`). Consecutive poses differ by half a
        turn about the hand's axis."""
        b = self.model.body(link).id
        u = -self.data.xmat[b].reshape(3, 3)[:, 2]
        length = 2.0 * float(self.model.geom(f"{link}_geom").size[1])
        shoulder = self.data.xpos[self.model.body(f"baxter_{hand}_upper_shoulder").id]
        sets = [s for tier in self._tier_sets(link)[: TIERS if tiers is None else tiers]
                for s in tier]
        poses = []
        for f, t, depth, phase in sets:
            point = self.data.xpos[b] + f * length * u
            z0 = point - shoulder
            z0 -= np.dot(z0, u) * u
            if np.linalg.norm(z0) < 1e-6:
                z0 = np.cross(u, [1.0, 0.0, 0.0])
            z0 /= np.linalg.norm(z0)
            for i in range(n_turns):
                a = 2.0 * np.pi * (i + phase) / n_turns
                z = np.cos(a) * z0 + np.sin(a) * np.cross(u, z0)
                z = np.cos(t) * z + np.sin(t) * u
                along = u - np.dot(u, z) * z
                along /= np.linalg.norm(along)
                for x in (along, -along):
                    mat = np.column_stack([x, np.cross(z, x), z])
                    quat = np.empty(4)
                    mujoco.mju_mat2Quat(quat, mat.ravel())
                    poses.append((point - depth * z, quat))
        return poses

    def _tier_sets(self, link: str) -> list[list[tuple[float, float, float, float]]]:
        """Per tier (1 to 5), its (grasp point [fraction of the link], tilt of the approach
        along the link [rad], depth of the grasp point from the hand [m], phase of the turns
        about the link [steps]); each gives ``n_turns`` approaches, either finger way
        (:meth:`grasp_poses`)."""
        tilt, deep = np.radians(TILT_DEG), self._depth
        first = [(f, 0.0, deep, 0.0) for f in self.grasp_fractions(link)]
        second = ([(f, t, deep, 0.0) for t in (tilt, -tilt) for f in self.grasp_fractions(link)]
                  + [(f, 0.0, deep, 0.0) for f in self.extra_fractions(link)])
        return [
            first,
            second,
            [(f, t, d, HALF_STEP) for f, t, d, _ in first + second],
            [(f, 0.0, deep, 0.0) for f in self.end_fractions(link)],
            [(f, 0.0, deep + SHALLOW_M, 0.0) for f in self.grasp_fractions(link)],
        ]

    def tier_size(self, link: str, n_turns: int = 8) -> int:
        """How many of :meth:`grasp_poses` are tier 1."""
        return self.tier_end(link, 1, n_turns)

    def tier_end(self, link: str, tier: int, n_turns: int = 8) -> int:
        """How many of :meth:`grasp_poses` are in tiers 1 to ``tier`` (0 for tier 0)."""
        return 2 * n_turns * sum(len(sets) for sets in self._tier_sets(link)[: max(0, tier)])

    def candidates(self, hand: str, link: str, tier: int = 1) -> list[Candidate]:
        """The candidate grasps of ``link`` by ``hand`` in tiers 1 to ``tier`` (see
        :meth:`grasp_poses`), solved and scored, best first (the other arm ignored: the pair
        is checked in :mod:`artiplan.world.pairs`). Cached per state and tier; a tier adds
        its own poses to the tier before's candidates."""
        key = (hand, link, self._roles, self.data.time, self.data.qpos.tobytes())
        cached = self._cand_cache.get((*key, tier))
        if cached is not None:
            return cached
        before = self.candidates(hand, link, tier - 1) if tier > 1 else []
        poses = self.grasp_poses(hand, link, tiers=tier)
        out = self._solve_candidates(hand, link, poses, self.tier_end(link, tier - 1),
                                     self.tier_end(link, tier))
        out = sorted(before + out, key=lambda c: c.score)
        self._cand_cache[(*key, tier)] = out
        while len(self._cand_cache) > 16:  # only the current motion's grasps matter
            self._cand_cache.pop(next(iter(self._cand_cache)))
        return out

    def _solve_candidates(
        self, hand: str, link: str, poses: list[tuple[Vec, Vec]], start: int, stop: int
    ) -> list[Candidate]:
        """Candidates of ``poses[start:stop]`` (IK, reach, clearance, limit room)."""
        out: list[Candidate] = []
        q_now = self.data.qpos[self._q[hand]].copy()
        for index in range(start, stop):
            pos, quat = poses[index]
            q, miss = self._flipped(hand, out[-1]) if index % 2 and out else (None, 0.0)
            if q is None:
                q, miss = self._solve_grasp(hand, link, pos, quat)
            else:  # put ik_data's kinematics at q
                self.ik_data.qpos[self._q[hand]] = q
                mujoco.mj_kinematics(self.model, self.ik_data)
            score = miss + (UNREACHABLE + MISS_WEIGHT * miss if miss > REACH_TOLERANCE else 0.0)
            if self.avoid_collisions:
                clear = clearance(self.model, self.ik_data, self.geoms[hand], link, True, False)
                score += CLEARANCE_WEIGHT * max(0.0, CLEARANCE_MARGIN - clear[0])
            score += 0.05 * max(0.0, LIMIT_MARGIN - self.room(hand, q))
            score += 0.002 * float(np.linalg.norm(q - q_now))  # stay near where the arm is
            out.append(Candidate(hand, link, index, pos, quat, q, miss, score))
        return out

    def _solve_grasp(self, hand: str, link: str, pos: Vec, quat: Vec) -> tuple[Vec, float]:
        """(IK solution [rad], miss) of a grasp pose; a near miss is solved again from
        mid-range. Leaves ``ik_data``'s kinematics at the solution."""
        avoid = link if self.avoid_collisions else None
        q = self.solve_ik(hand, pos, quat, iterations=150, avoid=avoid)
        miss = self.ik_miss(hand, pos, quat)
        if REACH_TOLERANCE < miss < RETRY_MISS:
            mid = 0.5 * (self._lo[hand] + self._hi[hand])
            q2 = self.solve_ik(hand, pos, quat, iterations=200, start=mid, avoid=avoid)
            miss2 = self.ik_miss(hand, pos, quat)
            if miss2 < miss:
                return q2, miss2
            self.ik_data.qpos[self._q[hand]] = q
            mujoco.mj_kinematics(self.model, self.ik_data)
        return q, miss

    def _flipped(self, hand: str, c: Candidate) -> tuple[Vec | None, float]:
        """The solution of ``c``'s pose turned half a turn about the hand's axis (fingers the
        other way): the same arm with w2 +-pi (w2's axis is the hand's z axis), when that is
        within w2's range; (None, 0) otherwise."""
        for step in (np.pi, -np.pi):
            w2 = c.q[6] + step
            if self._lo[hand][6] <= w2 <= self._hi[hand][6]:
                q = c.q.copy()
                q[6] = w2
                return q, c.miss
        return None, 0.0

    def _sweep(self, c: Candidate) -> None:
        """Turn the grasp +-SWEEP_DEG about the link's joint, about the vertical and the
        horizontal normal (the two rotation planes): the arm's joint angles there, and the
        joint-limit room missing there, summed (an unreachable turned pose counts as no
        room). A grasp whose arm meets a limit mid-rotation drags the held link."""
        b = self.model.body(c.link).id
        pivot = self.data.xpos[b]
        u = -self.data.xmat[b].reshape(3, 3)[:, 2]
        normal = np.cross(u, [0.0, 0.0, 1.0])
        axes = [np.array([0.0, 0.0, 1.0])]
        if np.linalg.norm(normal) > 1e-3:
            axes.append(normal / np.linalg.norm(normal))
        missing = 0.0
        for axis in axes:
            for sign in (1.0, -1.0):
                turn = quat_axis_angle(axis, sign * np.radians(SWEEP_DEG))
                t_pos = pivot + quat_to_mat(turn) @ (c.pos - pivot)
                t_quat = quat_mul(turn, c.quat)
                # Tracking-like: nearly no null-space drift (the servo's IK has almost none).
                q_t = self.solve_ik(
                    c.hand, t_pos, t_quat, iterations=40, start=c.q, nullspace=TRACK_NULLSPACE_GAIN
                )
                c.sweep.append(q_t)
                reached = self.ik_miss(c.hand, t_pos, t_quat) <= REACH_TOLERANCE
                room = self.room(c.hand, q_t) if reached else 0.0
                # Summed over the turned poses: only one of them will be the rotation, so a
                # grasp with room in more of them is the safer bet.
                missing += max(0.0, LIMIT_MARGIN - room)
        c.sweep_score = SWEEP_WEIGHT * missing

    # -- inverse kinematics ---------------------------------------------------------------
    def room(self, hand: str, q: Vec) -> float:
        """Smallest distance [rad] of ``q`` to a joint limit of ``hand``'s arm."""
        return float(np.minimum(q - self._lo[hand], self._hi[hand] - q).min())

    def solve_ik(
        self,
        hand: str,
        pos: Vec,
        quat: Vec,
        iterations: int = 50,
        start: Vec | None = None,
        damping: float = 1e-2,
        nullspace: float = NULLSPACE_GAIN,
        avoid: str | None = None,
        tol: tuple[float, float] = (IK_TOL_M, IK_TOL_RAD),
    ) -> Vec:
        """Joint angles [rad] putting ``hand`` at (pos, quat): damped least squares, until
        within ``tol`` [m, rad] or ``iterations``. With
        ``avoid`` (the link the hand will hold), the null space also pushes the arm away from
        the torso, the scene and the other links (not the other arm: the pair's choice
        handles that)."""
        m, d = self.model, self.ik_data
        d.qpos[:] = self.data.qpos
        qa, va, body = self._q[hand], self._v[hand], self._hand[hand]
        if start is not None:
            d.qpos[qa] = start
        jp, jr = np.zeros((3, m.nv)), np.zeros((3, m.nv))
        err = np.zeros(6)
        q_err = np.empty(4)
        conj = np.empty(4)
        push = np.zeros(len(qa))
        mid = 0.5 * (self._lo[hand] + self._hi[hand])
        span = self._hi[hand] - self._lo[hand]
        lo, hi = self._lo[hand], self._hi[hand]
        jac = np.empty((6, len(va)))
        damp = damping**2 * np.eye(6)
        rhs = np.empty((6, 2))
        tol_p2, tol_r2 = tol[0] ** 2, tol[1] ** 2
        for it in range(iterations):
            mujoco.mj_kinematics(m, d)
            mujoco.mj_comPos(m, d)
            err[:3] = pos - d.xpos[body]
            mujoco.mju_negQuat(conj, d.xquat[body])
            mujoco.mju_mulQuat(q_err, quat, conj)
            mujoco.mju_quat2Vel(err[3:], q_err, 1.0)
            if err[:3] @ err[:3] < tol_p2 and err[3:] @ err[3:] < tol_r2:
                break
            mujoco.mj_jacBody(m, d, jp, jr, body)
            jac[:3], jac[3:] = jp[:, va], jr[:, va]
            # Null space: drift toward mid-range, away from joint limits (the arm has 7 dof).
            toward = nullspace * (mid - d.qpos[qa]) / span
            if avoid is not None and it % AVOID_EVERY == 0:
                push = AVOID_GAIN * repulsion(
                    m, d, self.geoms[hand], va, avoid, AVOID_MARGIN, with_other=False
                )
            toward = toward + push
            rhs[:, 0], rhs[:, 1] = err, jac @ toward
            sol = _solve(jac @ jac.T + damp, rhs)  # SPD: never singular
            dq = jac.T @ (sol[:, 0] - sol[:, 1]) + toward
            step2 = float(dq @ dq)
            if step2 > 0.04:  # 0.2 rad: keep steps small so the linearisation holds
                dq *= 0.2 / step2**0.5
            d.qpos[qa] = np.minimum(np.maximum(d.qpos[qa] + dq, lo), hi)
        return d.qpos[qa].copy()

    def ik_miss(self, hand: str, pos: Vec, quat: Vec) -> float:
        """Pose error of the last IK solution: metres + 0.1 m per radian."""
        mujoco.mj_kinematics(self.model, self.ik_data)
        d_pos = float(np.linalg.norm(self.ik_data.xpos[self._hand[hand]] - pos))
        q_err = quat_mul(quat, quat_conj(self.ik_data.xquat[self._hand[hand]]))
        d_rot = 2.0 * float(np.arccos(min(1.0, abs(q_err[0]))))
        return d_pos + 0.1 * d_rot
