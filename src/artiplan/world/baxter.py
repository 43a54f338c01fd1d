"""Baxter hands: the dual-arm Baxter of robosuite's wheel, grasping with weld constraints.

The MJCF is located at run time (``importlib.util.find_spec("robosuite")``, never imported and
never copied into the repository) and attached to the scene with ``MjSpec``. Each arm is driven
by its torque motors (robosuite's limits: 50/100/50/50/15/15/15 N m): joint-space PD toward an
inverse-kinematics solution (damped least squares on ``mj_jacBody``) plus the bias forces
(gravity, Coriolis). A grasp welds the hand body to the link at their current relative pose.
Which arm holds and which rotates, and where each grasps, is chosen in
:mod:`artiplan.world.grasping`: reach first (a pairing where both hands reach whenever one
exists), then clearance, then joint-limit room over a +-30 deg turn.

Limits of this implementation (honest): the fingers close for show, the weld holds the link;
by default an arm *jumps* to its grasp (its IK solution is written into the state); with
``approach_s`` > 0 it moves there in simulated time (after backing every opened hand that is
near the object 6 cm off it), and the last few millimetres still jump. Arm contacts are off in
the physics: nothing stops an arm that does pass through an obstacle. With
``avoid_collisions`` the grasps are *chosen* clear of the torso, the other arm, the pedestal,
table, fixture and other links (:mod:`artiplan.world.collision`), at the grasp and at the
rotating arm's poses turned +-30 deg on both planes (the holding arm at its grasp); the grasp
IK is pushed away from obstacles. Not avoided: contacts during the rotation that the sweep's
four sample poses miss (the tracking IK itself is blind to obstacles), arm-vs-link contacts
during the rotation (links are not turned in the check), and collisions on the way of an
approach or a retreat (only measured: ``last_approach_clearance``).
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
from artiplan.world.collision import ArmGeoms, arm_geoms, clearance
from artiplan.world.grasping import (  # noqa: F401 - re-exported (public names)
    REACH_TOLERANCE,
    SWEEP_DEG,
    TRACK_NULLSPACE_GAIN,
    Candidate,
    GraspChoice,
    OutOfReachError,
)
from artiplan.world.hands import Hands
from artiplan.world.rotations import Vec, quat_conj, quat_mul, quat_to_mat
from artiplan.world.servo import ServoGains

ARM_JOINTS = ("s0", "s1", "e0", "e1", "w0", "w1", "w2")
#: A comfortable start: elbows bent, hands in front of the torso.
HOME = (0.0, -0.55, 0.0, 1.2, 0.0, 0.9, 0.0)
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
PATH_CHECKS = 4


class BaxterHands(GraspChoice, Hands):
    """Baxter's two arms as hands: IK + joint PD with bias compensation, welds as grasps."""

    #: The arm adds its own lag: gentler outer-loop gains than the virtual hands' (measured:
    #: kp 1, ki 10 tracked 11 of 12 random 4-link rotations; kp 2, ki 40 oscillates).
    servo_gains = ServoGains(kp=1.0, ki=10.0)
    last_approach_clearance: dict[str, tuple[float, float]]

    def __init__(
        self,
        kp_scale: float = 30.0,
        damping_ratio: float = 1.0,
        approach_s: float = 0.0,
        avoid_collisions: bool = True,
    ) -> None:
        """``kp_scale``: joint stiffness [N m/rad] per N m of motor limit; ``approach_s``: when
        > 0, the arms move to their grasps in this many simulated seconds (gravity acting)
        instead of jumping there; ``avoid_collisions``: score grasps by arm clearance (at the
        grasp and over the rotation's sweep) and push the grasp IK away from obstacles."""
        super().__init__()
        self.kp_scale = kp_scale
        self.damping_ratio = damping_ratio
        self.approach_s = approach_s
        self.avoid_collisions = avoid_collisions

    # -- motions between grasps ------------------------------------------------------------
    def approach(self, pairs: list[tuple[str, str]], advance: Callable[[float], None]) -> None:
        """Move each (hand, link) arm to its grasp in simulated time, advancing the world with
        ``advance(dt)``: first every opened hand still near the object backs off
        :data:`APPROACH_RETREAT_M` along its approach axis (:data:`APPROACH_RETREAT_S`), then
        the arms move to the grasps :meth:`assign` chose (joint-space, smooth) in
        ``approach_s`` seconds, then settle; the final grasp corrects what the falling links
        moved meanwhile. Nothing happens when ``approach_s`` is 0 (the arms jump at grasp)."""
        if self.approach_s <= 0:
            return
        goals: dict[str, Vec] = {}
        for h, link in pairs:
            c = self._chosen(h, link)
            goals[h] = c.q
            self._planned[h] = (link, c.index)  # the grasp then keeps this candidate
        starts = {h: self.data.qpos[self._q[h]].copy() for h in self.names}
        near = [h for h in self.names if self._held[h] is None and self._near_object(h)]
        if near:
            away = {h: self._backed_off(h, APPROACH_RETREAT_M) for h in near}
            self._move({h: starts[h] for h in near}, away, APPROACH_RETREAT_S, advance, 0.0)
            starts.update(away)
        self.last_approach_clearance = {
            h: self._path_clearance(h, dict(pairs)[h], starts, goals) for h in goals
        }
        self._move({h: starts[h] for h in goals}, goals, self.approach_s, advance)

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
        self, hand: str, link: str, starts: dict[str, Vec], goals: dict[str, Vec]
    ) -> tuple[float, float]:
        """Smallest clearance [m] of ``hand``'s arm on its way to ``link`` at
        :data:`PATH_CHECKS` configurations along the joint-space path (both arms moving): to
        the torso, the other arm and the scene; and to those or the object's links (the
        gripper may touch ``link``; the links as they are now)."""
        d = self.ik_data
        robot, links = np.inf, np.inf
        for i in range(1, PATH_CHECKS + 1):
            x = i / (PATH_CHECKS + 1)
            s = x * x * (3.0 - 2.0 * x)
            d.qpos[:] = self.data.qpos
            for h, q in starts.items():
                d.qpos[self._q[h]] = q + s * (goals[h] - q) if h in goals else q
            mujoco.mj_kinematics(self.model, d)
            robot = min(robot, clearance(self.model, d, self.geoms[hand], link, False)[0])
            links = min(links, clearance(self.model, d, self.geoms[hand], link, True)[0])
        return float(robot), float(links)

    def retreat(
        self,
        hands: list[str],
        advance: Callable[[float], None],
        distance: float = RETREAT_M,
        duration_s: float = RETREAT_S,
    ) -> None:
        """Back each of ``hands`` (opened first if it still holds) ``distance`` [m] away along
        its approach axis in ``duration_s`` simulated seconds, advancing the world with
        ``advance(dt)``. :meth:`approach` does a shorter one itself."""
        starts, goals = {}, {}
        for h in hands:
            self._check_hand(h)
            if self._held[h] is not None:
                self.release(h)
            starts[h] = self.data.qpos[self._q[h]].copy()
            goals[h] = self._backed_off(h, distance)
        self._move(starts, goals, duration_s, advance)

    def _move(
        self,
        starts: dict[str, Vec],
        goals: dict[str, Vec],
        duration_s: float,
        advance: Callable[[float], None],
        settle_s: float = APPROACH_SETTLE_S,
    ) -> None:
        """Joint-space smoothstep from ``starts`` to ``goals`` in ``duration_s`` simulated
        seconds, then ``settle_s`` of settling."""
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
        if settle_s > 0:
            advance(settle_s)

    def extend_spec(self, spec: mujoco.MjSpec, obj: ArticulatedObject) -> None:
        attach_baxter(spec, obj)

    def bind(self, model: mujoco.MjModel, data: mujoco.MjData, obj: ArticulatedObject) -> None:
        self.model, self.data = model, data
        self.ik_data = mujoco.MjData(model)
        self._planned: dict[str, tuple[str, int]] = {}
        self._plan: dict[str, tuple[Candidate, float]] = {}
        self._cand_cache: dict[tuple[object, ...], list[Candidate]] = {}
        self._roles = ("", "")
        self._clamped = obj.links[0]
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
        #: Per hand, smallest arm clearance [m] at the intermediate configurations of the
        #: last approach: (torso, other arm, scene; the same or other links).
        self.last_approach_clearance = {}

    # -- grasping ------------------------------------------------------------------------
    def grasp(self, hand: str, link: str) -> None:
        """Close ``hand`` on ``link``: the candidate chosen by :meth:`assign` (re-solved from
        where the arm is after an approach), else the best reachable one; raises
        :class:`OutOfReachError` when no candidate reaches."""
        self._check_hand(hand)
        if self._held[hand] is not None:
            self.release(hand)
        q, miss = self._grasp_solution(hand, link)
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

    def _grasp_solution(self, hand: str, link: str) -> tuple[Vec, float]:
        """(joint angles [rad], miss [m]) of the grasp to close now."""
        planned = self._planned.pop(hand, None)
        plan = self._plan.pop(hand, None)
        if planned is None and plan is not None and plan[0].link == link:
            if plan[1] == self.data.time:  # nothing moved since assign: its solution holds
                return plan[0].q, plan[0].miss
            planned = (link, plan[0].index)
        if planned is not None and planned[0] == link:  # after an approach: same candidate
            pos, quat = self.grasp_poses(hand, link)[planned[1]]
            q_now = self.data.qpos[self._q[hand]].copy()
            avoid = link if self.avoid_collisions else None
            q = self.solve_ik(hand, pos, quat, iterations=150, start=q_now, avoid=avoid)
            miss = self.ik_miss(hand, pos, quat)
            if miss <= REACH_TOLERANCE:
                return q, miss
        best = self.best_grasp(hand, link)  # any reachable candidate, from where it is now
        return best.q, best.miss

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
