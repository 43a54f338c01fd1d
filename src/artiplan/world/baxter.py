"""Baxter hands: the dual-arm Baxter of robosuite's wheel, grasping with weld constraints.

The MJCF is located at run time (``importlib.util.find_spec("robosuite")``, never imported and
never copied into the repository) and attached to the scene with ``MjSpec``. Each arm is driven
by its torque motors (robosuite's limits: 50/100/50/50/15/15/15 N m): joint-space PD toward an
inverse-kinematics solution (damped least squares on ``mj_jacBody``) plus the bias forces
(gravity, Coriolis). A grasp welds the hand body to the link at their current relative pose.

Limits of this implementation (honest): the fingers close for show, the weld holds the link;
by default an arm *jumps* to its grasp (its IK solution is written into the state); with
``approach_s`` > 0 it moves there in simulated time, and the last few millimetres still jump;
:meth:`BaxterHands.retreat` backs the opened hands away in simulated time (called by whoever
sequences motions: the world itself does not). Arm contacts are off in the physics; collisions
are avoided by choosing, among the candidate grasps, IK solutions clear of the torso, the other
arm, the table, fixture and other links (:mod:`artiplan.world.collision`), not during the
rotation (the tracking IK is blind to obstacles).
"""

from __future__ import annotations

from collections.abc import Callable

import mujoco
import numpy as np

from artiplan.model import ArticulatedObject
from artiplan.world.baxter_model import (  # noqa: F401 - re-exported (public names)
    BAXTER_BASE,
    PREFIX,
    attach_baxter,
    baxter_layout,
    baxter_xml_path,
)
from artiplan.world.collision import ArmGeoms, arm_geoms, clearance, repulsion
from artiplan.world.hands import Hands
from artiplan.world.rotations import Vec, quat_axis_angle, quat_conj, quat_mul, quat_to_mat
from artiplan.world.servo import ServoGains

ARM_JOINTS = ("s0", "s1", "e0", "e1", "w0", "w1", "w2")
#: A comfortable start: elbows bent, hands in front of the torso.
HOME = (0.0, -0.55, 0.0, 1.2, 0.0, 0.9, 0.0)
#: A grasp whose IK solution misses the grasp point by more than this [m] is refused.
REACH_TOLERANCE = 0.01
#: Interval [s] between joint-target updates of an approach motion.
APPROACH_DT = 0.02
#: Time [s] the arms get to settle on their grasps after an approach.
APPROACH_SETTLE_S = 0.2
#: Default retreat after a release: this far [m] back along the hand's approach axis, in
#: this many simulated seconds.
RETREAT_M = 0.1
RETREAT_S = 0.5
#: Pull of the IK's null-space term toward mid-range joint angles [rad per iteration].
NULLSPACE_GAIN = 0.05
#: The same while tracking, called every 2 ms step: small, or the arm's self-motion outruns
#: its motors (0.05 per call saturated every joint).
TRACK_NULLSPACE_GAIN = 0.0005
#: Grasps with a joint closer than this to a limit [rad] score worse (less room to rotate).
LIMIT_MARGIN = 0.3
#: The rotating hand's grasps are checked for joint-limit room this far [deg] into a turn
#: either way (the planner's rotations are tens of degrees).
SWEEP_DEG = 30.0
#: Score per radian of missing room in that sweep (0.3 rad short ~ a 3 cm miss).
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


class OutOfReachError(RuntimeError):
    """Baxter cannot put a hand on the link (use virtual hands for long chains)."""


class BaxterHands(Hands):
    """Baxter's two arms as hands: IK + joint PD with bias compensation, welds as grasps."""

    #: The arm adds its own lag: gentler outer-loop gains than the virtual hands' (measured:
    #: kp 1, ki 10 tracked 11 of 12 random 4-link rotations; kp 2, ki 40 oscillates).
    servo_gains = ServoGains(kp=1.0, ki=10.0)

    def __init__(
        self,
        kp_scale: float = 30.0,
        damping_ratio: float = 1.0,
        approach_s: float = 0.0,
        avoid_collisions: bool = False,
    ) -> None:
        """``kp_scale``: joint stiffness [N m/rad] per N m of motor limit; ``approach_s``: when
        > 0, the arms move to their grasps in this many simulated seconds (gravity acting)
        instead of jumping there; ``avoid_collisions``: score grasps by arm clearance and push
        the grasp IK away from obstacles. Off by default: with it on, the closed-loop demo on
        Baxter lost its goal (grasps clear of the torso turned out worse for tracking the
        rotation), and the loop's measured results were taken without it."""
        super().__init__()
        self.kp_scale = kp_scale
        self.damping_ratio = damping_ratio
        self.approach_s = approach_s
        self.avoid_collisions = avoid_collisions

    def approach(self, pairs: list[tuple[str, str]], advance: Callable[[float], None]) -> None:
        """Move each (hand, link) arm to its grasp in ``approach_s`` seconds of simulation
        (joint-space, smooth), advancing the world with ``advance(dt)``; the final grasp
        corrects what the falling links moved meanwhile."""
        if self.approach_s <= 0:
            return
        starts = {h: self.data.qpos[self._q[h]].copy() for h, _ in pairs}
        goals: dict[str, Vec] = {}
        for h, link in pairs:  # the second arm's grasp avoids the first arm's goal
            q, _, _, index = self._search_grasp(h, link, goals)
            goals[h] = q
            self._planned[h] = (link, index)  # the grasp then keeps this candidate
        self._move(starts, goals, self.approach_s, advance)

    def retreat(
        self,
        hands: list[str],
        advance: Callable[[float], None],
        distance: float = RETREAT_M,
        duration_s: float = RETREAT_S,
    ) -> None:
        """Back each of ``hands`` (opened first if it still holds) ``distance`` [m] away along
        its approach axis in ``duration_s`` simulated seconds, advancing the world with
        ``advance(dt)``, so the next approach starts clear of the object. The world does not
        call this itself: callers that simulate motions between grasps do."""
        starts, goals = {}, {}
        for h in hands:
            self._check_hand(h)
            if self._held[h] is not None:
                self.release(h)
            r_h = self.data.xmat[self._hand[h]].reshape(3, 3)
            pos = self.data.xpos[self._hand[h]] - distance * r_h[:, 2]
            starts[h] = self.data.qpos[self._q[h]].copy()
            goals[h] = self.solve_ik(
                h, pos, self.data.xquat[self._hand[h]].copy(), iterations=100, start=starts[h]
            )
        self._move(starts, goals, duration_s, advance)

    def _move(
        self,
        starts: dict[str, Vec],
        goals: dict[str, Vec],
        duration_s: float,
        advance: Callable[[float], None],
    ) -> None:
        """Joint-space smoothstep from ``starts`` to ``goals`` in ``duration_s`` simulated
        seconds, then :data:`APPROACH_SETTLE_S` of settling."""
        n = max(1, int(round(duration_s / APPROACH_DT)))
        dt = duration_s / n
        for i in range(1, n + 1):
            x = i / n
            s = x * x * (3.0 - 2.0 * x)  # smoothstep: start and stop at rest
            ds = 6.0 * x * (1.0 - x) / duration_s  # its rate [1/s]
            for h in goals:
                self._target_q[h] = starts[h] + s * (goals[h] - starts[h])
                self._target_qd[h] = ds * (goals[h] - starts[h])
            advance(dt)
        for h in goals:
            self._target_qd[h] = np.zeros(len(ARM_JOINTS))
        advance(APPROACH_SETTLE_S)

    def extend_spec(self, spec: mujoco.MjSpec, obj: ArticulatedObject) -> None:
        attach_baxter(spec, obj)

    def bind(self, model: mujoco.MjModel, data: mujoco.MjData, obj: ArticulatedObject) -> None:
        self.model, self.data = model, data
        self.ik_data = mujoco.MjData(model)
        self._planned: dict[str, tuple[str, int]] = {}
        self._rotating: str | None = None
        self._grasp_cache: dict[tuple[object, ...], tuple[Vec, Vec, float]] = {}
        self.geoms: dict[str, ArmGeoms] = {
            h: arm_geoms(model, h, list(obj.links), PREFIX) for h in self.names
        }
        self._hand = {h: model.body(f"{PREFIX}{h}_hand").id for h in self.names}
        self._q = {}
        self._v = {}
        self._act = {}
        for h in self.names:
            joints = [model.joint(f"{PREFIX}{h}_{j}") for j in ARM_JOINTS]
            self._q[h] = np.array([int(model.jnt_qposadr[j.id]) for j in joints])
            self._v[h] = np.array([int(model.jnt_dofadr[j.id]) for j in joints])
            self._act[h] = np.array(
                [model.actuator(f"{PREFIX}torq_{h}_j{i}").id for i in range(len(ARM_JOINTS))]
            )
        self._limits = {h: model.actuator_ctrlrange[self._act[h], 1].copy() for h in self.names}
        self._weld = {
            (h, link): model.equality(f"weld_{h}_{link}").id
            for h in self.names
            for link in obj.links
        }
        self._lo = {
            h: model.jnt_range[[model.joint(f"{PREFIX}{h}_{j}").id for j in ARM_JOINTS], 0]
            for h in self.names
        }
        self._hi = {
            h: model.jnt_range[[model.joint(f"{PREFIX}{h}_{j}").id for j in ARM_JOINTS], 1]
            for h in self.names
        }
        for h in self.names:
            sign = np.array([1, 1, 1, 1, 1, 1, 1.0]) if h == "right" else np.ones(7)
            data.qpos[self._q[h]] = sign * np.array(HOME)
        self._target_q = {h: data.qpos[self._q[h]].copy() for h in self.names}
        mujoco.mj_forward(model, data)
        # Turn each torque motor into a PD servo inside MuJoCo: force = kp (ctrl - q) - kv qd,
        # clipped to the motor's limit as a whole. Velocity feedback in the actuator is
        # integrated implicitly (stable on light wrist joints); kv = 2 zeta sqrt(kp * M_ii).
        full = np.zeros((model.nv, model.nv))
        mujoco.mj_fullM(model, data, full)
        self._kp, self._kv = {}, {}
        for h in self.names:
            inertia = np.diag(full)[self._v[h]]
            kp = self.kp_scale * self._limits[h]
            kv = 2.0 * self.damping_ratio * np.sqrt(kp * inertia)
            self._kp[h], self._kv[h] = kp, kv
            for i, a in enumerate(self._act[h]):
                model.actuator_gaintype[a] = int(mujoco.mjtGain.mjGAIN_FIXED)
                model.actuator_biastype[a] = int(mujoco.mjtBias.mjBIAS_AFFINE)
                model.actuator_gainprm[a, :3] = (kp[i], 0.0, 0.0)
                model.actuator_biasprm[a, :3] = (0.0, -kp[i], -kv[i])
                model.actuator_forcerange[a] = (-self._limits[h][i], self._limits[h][i])
                model.actuator_forcelimited[a] = 1
                model.actuator_ctrllimited[a] = 0
        self._grip_offset: dict[str, tuple[Vec, Vec]] = {}
        # Fingers (when the grippers are attached): position actuators, open or on the link.
        self._fingers: dict[str, list[tuple[int, float, float]]] = {h: [] for h in self.names}
        self._depth = 0.03
        for h in self.names:
            for side, open_, closed in (("l", 0.0115, -0.003), ("r", -0.0115, 0.003)):
                name = f"{PREFIX}{h}_gripper_gripper_{side}_finger_joint"
                aid = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_ACTUATOR, name)
                if aid >= 0:
                    self._fingers[h].append((aid, open_, closed))
            eef = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_BODY, f"{PREFIX}{h}_gripper_eef")
            if eef >= 0:  # grasp point: between the finger pads, on the hand's z axis
                r_h = data.xmat[self._hand[h]].reshape(3, 3)
                self._depth = float((r_h.T @ (data.xpos[eef] - data.xpos[self._hand[h]]))[2])
        self._held = {h: None for h in self.names}
        self.last_torque = {h: np.zeros(7) for h in self.names}
        self._target_qd = {h: np.zeros(len(ARM_JOINTS)) for h in self.names}
        #: How far [m] each hand jumped at its last grasp (0 after a perfect approach).
        self.last_jump_m = {h: 0.0 for h in self.names}

    # -- grasping ------------------------------------------------------------------------
    def assign(self, hold_link: str, rotate_link: str) -> tuple[str, str]:
        """Which arm holds and which rotates, chosen by reach (the pairing with the smaller
        worse IK miss). Remembers ``rotate_link``: its grasps are scored over the rotation."""
        self._rotating = rotate_link
        straight = max(
            self._best_grasp("left", hold_link)[2], self._best_grasp("right", rotate_link)[2]
        )
        swapped = max(
            self._best_grasp("right", hold_link)[2], self._best_grasp("left", rotate_link)[2]
        )
        return ("left", "right") if straight <= swapped else ("right", "left")

    def _centre(self, link: str) -> Vec:
        b = self.model.body(link).id
        half = 0.5 * float(self.model.geom(f"{link}_geom").size[1]) * 2.0
        return self.data.xpos[b] - half * self.data.xmat[b].reshape(3, 3)[:, 2]

    def grasp_poses(self, hand: str, link: str, n_turns: int = 8) -> list[tuple[Vec, Vec]]:
        """Candidate hand poses at the link's centre: the hand's z axis (its approach)
        perpendicular to the link, turned about it in ``n_turns`` steps, x along +-link."""
        b = self.model.body(link).id
        u = -self.data.xmat[b].reshape(3, 3)[:, 2]
        centre = self._centre(link)
        shoulder = self.data.xpos[self.model.body(f"{PREFIX}{hand}_upper_shoulder").id]
        z0 = centre - shoulder
        z0 -= np.dot(z0, u) * u
        if np.linalg.norm(z0) < 1e-6:
            z0 = np.cross(u, [1.0, 0.0, 0.0])
        z0 /= np.linalg.norm(z0)
        poses = []
        for i in range(n_turns):
            a = 2.0 * np.pi * i / n_turns
            z = np.cos(a) * z0 + np.sin(a) * np.cross(u, z0)
            for x in (u, -u):
                mat = np.column_stack([x, np.cross(z, x), z])
                quat = np.empty(4)
                mujoco.mju_mat2Quat(quat, mat.ravel())
                poses.append((centre - self._depth * z, quat))
        return poses

    def _best_grasp(
        self, hand: str, link: str, others: dict[str, Vec] | None = None
    ) -> tuple[Vec, Vec, float]:
        """(joint angles, IK target position, miss [m]) of the best candidate grasp;
        ``others``: joint angles of the other arm to assume (default: where it is now).
        Cached per state: :meth:`assign` and :meth:`grasp` ask for the same grasps."""
        key = (hand, link, self.data.time, self.data.qpos.tobytes(), repr(others))
        cached = self._grasp_cache.get(key)
        if cached is None:
            cached = self._grasp_cache[key] = self._search_grasp(hand, link, others)[:3]
            while len(self._grasp_cache) > 8:  # only the current motion's grasps matter
                self._grasp_cache.pop(next(iter(self._grasp_cache)))
        return cached

    def _search_grasp(
        self, hand: str, link: str, others: dict[str, Vec] | None
    ) -> tuple[Vec, Vec, float, int]:
        """Solve the IK of every candidate grasp pose and score it (see :meth:`_best_grasp`);
        also returns the chosen candidate's index in :meth:`grasp_poses`."""
        best: tuple[Vec, Vec, float, int] | None = None
        best_score = np.inf
        q_now = self.data.qpos[self._q[hand]].copy()
        for index, (pos, quat) in enumerate(self.grasp_poses(hand, link)):
            q = self.solve_ik(hand, pos, quat, iterations=150, avoid=self._avoid(link))
            miss = self._ik_miss(hand, pos, quat)  # leaves ik_data's kinematics at q
            for h, q_other in (others or {}).items():
                if h != hand:
                    self.ik_data.qpos[self._q[h]] = q_other
                    mujoco.mj_kinematics(self.model, self.ik_data)
            clear = clearance(self.model, self.ik_data, self.geoms[hand], held=link)[0]
            room = self._room(hand, q)
            if link == self._rotating and miss <= REACH_TOLERANCE:
                sweep = self._sweep_room(hand, link, pos, quat, q)
                score_sweep = SWEEP_WEIGHT * max(0.0, LIMIT_MARGIN - sweep)
            else:
                score_sweep = 0.0
            # Prefer reachable, collision-free, away from limits, then close to where the arm
            # is now.
            weight = CLEARANCE_WEIGHT if self.avoid_collisions else 0.0
            score = miss + weight * max(0.0, CLEARANCE_MARGIN - clear)
            score += 1.0 if miss > REACH_TOLERANCE else 0.0
            score += 0.05 * max(0.0, LIMIT_MARGIN - room) + score_sweep
            score += 0.002 * float(np.linalg.norm(q - q_now))
            if score < best_score:
                best, best_score = (q, pos, miss, index), score
        assert best is not None
        return best

    def _avoid(self, link: str) -> str | None:
        """The link the grasp IK may touch while it steers clear of the rest (None: no steering)."""
        return link if self.avoid_collisions else None

    def _room(self, hand: str, q: Vec) -> float:
        """Smallest distance [rad] of ``q`` to a joint limit of ``hand``'s arm."""
        return float(np.minimum(q - self._lo[hand], self._hi[hand] - q).min())

    def _sweep_room(self, hand: str, link: str, pos: Vec, quat: Vec, q: Vec) -> float:
        """Joint-limit room [rad] left when the grasp (pos, quat) on ``link`` is turned by
        +-SWEEP_DEG about the link's joint, about the vertical and the horizontal normal (the
        two rotation planes); an unreachable turned pose counts as no room. A grasp whose
        arm meets a limit mid-rotation drags the held link (the 1-in-12 failures)."""
        pivot = self.data.xpos[self.model.body(link).id]
        u = -self.data.xmat[self.model.body(link).id].reshape(3, 3)[:, 2]
        normal = np.cross(u, [0.0, 0.0, 1.0])
        axes = [np.array([0.0, 0.0, 1.0])]
        if np.linalg.norm(normal) > 1e-3:
            axes.append(normal / np.linalg.norm(normal))
        room = np.inf
        for axis in axes:
            for sign in (1.0, -1.0):
                turn = quat_axis_angle(axis, sign * np.radians(SWEEP_DEG))
                t_pos = pivot + quat_to_mat(turn) @ (pos - pivot)
                t_quat = quat_mul(turn, quat)
                # Tracking-like: nearly no null-space drift (the servo's IK has almost none).
                q_t = self.solve_ik(
                    hand, t_pos, t_quat, iterations=40, start=q, nullspace=TRACK_NULLSPACE_GAIN
                )
                if self._ik_miss(hand, t_pos, t_quat) > REACH_TOLERANCE:
                    return 0.0
                room = min(room, self._room(hand, q_t))
        return float(room)

    def grasp(self, hand: str, link: str) -> None:
        self._check_hand(hand)
        if self._held[hand] is not None:
            self.release(hand)
        planned = self._planned.pop(hand, None)
        if planned is not None and planned[0] == link:  # after an approach: same candidate
            pos, quat = self.grasp_poses(hand, link)[planned[1]]
            q_now = self.data.qpos[self._q[hand]].copy()
            q = self.solve_ik(
                hand, pos, quat, iterations=150, start=q_now, avoid=self._avoid(link)
            )
            miss = self._ik_miss(hand, pos, quat)
        else:
            q, pos, miss = self._best_grasp(hand, link)
        if miss > REACH_TOLERANCE:
            raise OutOfReachError(f"Baxter's {hand} hand cannot reach {link} ({miss:.3f} m short)")
        # The arm jumps the rest of the way to the grasp (all of it without an approach).
        before = self.data.xpos[self._hand[hand]].copy()
        self.data.qpos[self._q[hand]] = q
        self.data.qvel[self._v[hand]] = 0.0
        self._target_q[hand] = q
        mujoco.mj_forward(self.model, self.data)
        hb, lb = self._hand[hand], self.model.body(link).id
        self.last_jump_m[hand] = float(np.linalg.norm(self.data.xpos[hb] - before))
        self._target_qd[hand] = np.zeros(len(ARM_JOINTS))
        # Weld relative pose: the link's pose in the hand's frame, as it is now.
        r_h = self.data.xmat[hb].reshape(3, 3)
        rel_pos = r_h.T @ (self.data.xpos[lb] - self.data.xpos[hb])
        rel_quat = quat_mul(quat_conj(self.data.xquat[hb]), self.data.xquat[lb])
        eq = self._weld[(hand, link)]
        self.model.eq_data[eq, 0:3] = 0.0
        self.model.eq_data[eq, 3:6] = rel_pos
        self.model.eq_data[eq, 6:10] = rel_quat
        self.data.eq_active[eq] = 1
        self._grip_offset[hand] = (rel_pos, rel_quat)
        self._held[hand] = link

    # -- motion --------------------------------------------------------------------------
    def command(self, hand: str, pos: Vec, quat: Vec) -> None:
        """Desired link pose -> desired hand pose (through the grip offset) -> IK target."""
        rel_pos, rel_quat = self._grip_offset[hand]
        hand_quat = quat_mul(quat, quat_conj(rel_quat))
        hand_pos = pos - quat_to_mat(hand_quat) @ rel_pos
        self._target_q[hand] = self.solve_ik(
            hand,
            hand_pos,
            hand_quat,
            iterations=2,
            start=self._target_q[hand],
            nullspace=TRACK_NULLSPACE_GAIN,
        )

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
    ) -> Vec:
        """Joint angles [rad] putting ``hand`` at (pos, quat): damped least squares. With
        ``avoid`` (the link the hand will hold), the null space also pushes the arm away from
        the torso, the other arm, the scene and the other links."""
        m, d = self.model, self.ik_data
        d.qpos[:] = self.data.qpos
        qa, va, body = self._q[hand], self._v[hand], self._hand[hand]
        if start is not None:
            d.qpos[qa] = start
        jp, jr = np.zeros((3, m.nv)), np.zeros((3, m.nv))
        err = np.zeros(6)
        q_err = np.empty(4)
        push = np.zeros(len(qa))
        for it in range(iterations):
            mujoco.mj_kinematics(m, d)
            mujoco.mj_comPos(m, d)
            err[:3] = pos - d.xpos[body]
            mujoco.mju_mulQuat(q_err, quat, quat_conj(d.xquat[body]))
            mujoco.mju_quat2Vel(err[3:], q_err, 1.0)
            if np.linalg.norm(err[:3]) < 1e-5 and np.linalg.norm(err[3:]) < 1e-4:
                break
            mujoco.mj_jacBody(m, d, jp, jr, body)
            jac = np.vstack([jp[:, va], jr[:, va]])
            jjt = jac @ jac.T + damping**2 * np.eye(6)
            dq = jac.T @ np.linalg.solve(jjt, err)
            # Null space: drift toward mid-range, away from joint limits (the arm has 7 dof).
            mid = 0.5 * (self._lo[hand] + self._hi[hand])
            toward = nullspace * (mid - d.qpos[qa]) / (self._hi[hand] - self._lo[hand])
            if avoid is not None and it % AVOID_EVERY == 0:
                push = AVOID_GAIN * repulsion(m, d, self.geoms[hand], va, avoid, AVOID_MARGIN)
            toward = toward + push
            dq += toward - jac.T @ np.linalg.solve(jjt, jac @ toward)
            step = np.linalg.norm(dq)
            if step > 0.2:  # rad: keep steps small so the linearisation holds
                dq *= 0.2 / step
            d.qpos[qa] = np.clip(d.qpos[qa] + dq, self._lo[hand], self._hi[hand])
        return d.qpos[qa].copy()

    def _ik_miss(self, hand: str, pos: Vec, quat: Vec) -> float:
        """Pose error of the last IK solution: metres + 0.1 m per radian."""
        mujoco.mj_kinematics(self.model, self.ik_data)
        d_pos = float(np.linalg.norm(self.ik_data.xpos[self._hand[hand]] - pos))
        q_err = quat_mul(quat, quat_conj(self.ik_data.xquat[self._hand[hand]]))
        d_rot = 2.0 * float(np.arccos(min(1.0, abs(q_err[0]))))
        return d_pos + 0.1 * d_rot

    def control(self, dt: float) -> None:
        """Servo set-points: the IK targets plus feed-forward; the motors' PD runs inside
        MuJoCo and their force is clipped to Baxter's limits."""
        d = self.data
        for h in self.names:
            va, act = self._v[h], self._act[h]
            kp, kv = self._kp[h], self._kv[h]
            # Feed-forward (bias forces the gravity compensation leaves, desired velocity)
            # folded into the servo's set-point.
            ff = d.qfrc_bias[va] - d.qfrc_gravcomp[va] + kv * self._target_qd[h]
            d.ctrl[act] = self._target_q[h] + ff / kp
            self.last_torque[h] = d.actuator_force[act].copy()
            for aid, open_, closed in self._fingers[h]:
                d.ctrl[aid] = closed if self._held[h] is not None else open_
