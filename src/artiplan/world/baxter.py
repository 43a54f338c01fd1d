"""Baxter hands: the dual-arm Baxter of robosuite's wheel, grasping with weld constraints.

The MJCF is located at run time (``importlib.util.find_spec("robosuite")``, never imported and
never copied into the repository) and attached to the scene with ``MjSpec``. Each arm is driven
by its torque motors (robosuite's limits: 50/100/50/50/15/15/15 N m): joint-space PD toward an
inverse-kinematics solution (damped least squares on ``mj_jacBody``) plus the bias forces
(gravity, Coriolis). A grasp welds the hand body to the link at their current relative pose.
Which arm holds and which rotates, and where each grasps, is chosen in
:mod:`artiplan.world.grasping` and :mod:`artiplan.world.pairs`: reach first, then (with
``avoid_collisions``) a pair whose final legs, grasps and every degree of the planned turn are
collision-free, then joint-limit room.

Arm contacts are on in the physics (:mod:`artiplan.world.contacts`): the arms collide with the
torso, each other, the table, pedestal, fixture and the object; a gripper not with the link it
holds. Every collision that happens is logged (``contacts.events``: geoms, when, how deep).

By default an arm *jumps* to its grasp (its IK solution is written into the state); with
``approach_s`` > 0 it moves there in simulated time along motions planned with OMPL and timed
within Baxter's joint limits (:mod:`artiplan.world.approach`); the last millimetres (the links
fell meanwhile) still jump. Not covered: the tracking IK during a rotation is not itself
collision-aware (the turn was checked on the grasp choice's IK solutions every degree, the
carried links turned rigidly, which they are not in the physics).
"""

from __future__ import annotations

import mujoco
import numpy as np

from artiplan.model import ArticulatedObject
from artiplan.world.approach import (  # noqa: F401 - re-exported (public names)
    APPROACH_DT,
    APPROACH_RETREAT_M,
    APPROACH_RETREAT_S,
    APPROACH_SETTLE_S,
    ARM_JOINTS,
    PREGRASP_M,
    PREGRASP_SHARE,
    RETREAT_M,
    RETREAT_S,
    ApproachMotion,
    NotExecutableError,
)
from artiplan.world.baxter_model import (  # noqa: F401 - re-exported (public names)
    BAXTER_BASE,
    BAXTER_MAX_LINKS,
    PREFIX,
    attach_baxter,
    baxter_layout,
    baxter_xml_path,
)
from artiplan.world.collision import ArmGeoms, arm_geoms
from artiplan.world.contacts import ContactLog, link_bit, refresh_body_bits
from artiplan.world.grasping import (  # noqa: F401 - re-exported (public names)
    REACH_TOLERANCE,
    SWEEP_DEG,
    TRACK_NULLSPACE_GAIN,
    Candidate,
    OutOfReachError,
)
from artiplan.world.hands import Hands
from artiplan.world.motion import ArmChecker, Query
from artiplan.world.rotations import Vec, quat_conj, quat_mul, quat_to_mat
from artiplan.world.servo import ServoGains
from artiplan.world.timing import Limits

#: Physics steps between checks whether a gripper has left a link it let go of.
GRIP_CHECK_STEPS = 5
#: A grasp's last jump may put the arm at most this deep [m] into anything (see
#: :meth:`BaxterHands._check_jump`).
JUMP_PENETRATION_M = 0.005
#: A comfortable start: elbows bent, hands in front of the torso.
HOME = (0.0, -0.55, 0.0, 1.2, 0.0, 0.9, 0.0)


class BaxterHands(ApproachMotion, Hands):
    """Baxter's two arms as hands: IK + joint PD with bias compensation, welds as grasps."""

    #: The arm adds its own lag: gentler outer-loop gains than the virtual hands' (measured:
    #: kp 1, ki 10 tracked 11 of 12 random 4-link rotations; kp 2, ki 40 oscillates).
    servo_gains = ServoGains(kp=1.0, ki=10.0)
    last_approach_clearance: dict[str, tuple[float, float]]
    last_pregrasp: dict[str, Vec]

    def __init__(
        self,
        kp_scale: float = 30.0,
        damping_ratio: float = 1.0,
        approach_s: float = 0.0,
        avoid_collisions: bool = True,
        limits: Limits | None = None,
    ) -> None:
        """``kp_scale``: joint stiffness [N m/rad] per N m of motor limit; ``approach_s``: when
        > 0, the arms move to their grasps in simulated time (gravity acting) along planned
        motions taking at least this many seconds, instead of jumping there;
        ``avoid_collisions``: choose only collision-free grasp pairs (final legs, grasps, the
        planned turn), push the grasp IK away from obstacles; ``limits``: the joint limits
        the motions are timed with (default Baxter's, :mod:`artiplan.world.timing`)."""
        super().__init__()
        self.kp_scale = kp_scale
        self.damping_ratio = damping_ratio
        self.approach_s = approach_s
        self.avoid_collisions = avoid_collisions
        self.limits = limits or Limits()

    def extend_spec(self, spec: mujoco.MjSpec, obj: ArticulatedObject) -> None:
        attach_baxter(spec, obj)

    def bind(self, model: mujoco.MjModel, data: mujoco.MjData, obj: ArticulatedObject) -> None:
        self.model, self.data = model, data
        self.ik_data = mujoco.MjData(model)
        self._planned: dict[str, tuple[str, int]] = {}
        self._plan: dict[str, tuple[Candidate, float]] = {}
        self._cand_cache: dict[tuple[object, ...], list[Candidate]] = {}
        self._static = {}
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
        self.home = {h: self._target_q[h].copy() for h in self.names}
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
        self._target_qdd = {h: np.zeros(len(ARM_JOINTS)) for h in self.names}
        self._acc_vec, self._acc_out = np.zeros(model.nv), np.zeros(model.nv)
        #: How far [m] each hand jumped at its last grasp (0 after a perfect approach).
        self.last_jump_m = {h: 0.0 for h in self.names}
        #: Per hand, smallest arm clearance [m] at the intermediate configurations of the
        #: last approach: (torso, other arm, scene; the same or other links).
        self.last_approach_clearance = {}
        #: Per hand, the pre-grasp joint angles [rad] of the last approach.
        self.last_pregrasp = {}
        #: Per approach, each moving hand's planned grasp-point trace [m] (for pictures).
        self.last_paths = []
        #: Per hand, the links its gripper has no contacts with (held, closing in on, or let
        #: go of and not yet left); the link it is closing in on.
        self._no_contact: dict[str, set[str]] = {h: set() for h in self.names}
        self._closing: dict[str, str] = {}
        self._steps = 0
        self._active = None
        self._link_index = {link: i for i, link in enumerate(obj.links, start=1)}
        self.checker = ArmChecker(
            model, dict(self._q),
            {h: np.array(self.geoms[h].arm) for h in self.names},
            {h: np.array(self.geoms[h].gripper) for h in self.names},
            dict(self.geoms[self.names[0]].links),
            {int(model.jnt_qposadr[model.actuator_trnid[aid, 0]]): open_
             for h in self.names for aid, open_, _ in self._fingers[h]},
        )
        arm_ids = [g for h in self.names for g in self.geoms[h].arm]
        #: Collisions of the arms in the physics (geoms, when, how deep).
        self.contacts = ContactLog(
            frozenset(arm_ids), {g: model.geom(g).name for g in range(model.ngeom)}
        )

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
        if self.avoid_collisions:
            self._check_jump(hand, link, q)
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
        self._grip_contacts(hand, link, False)
        self._closing.pop(hand, None)
        eq = self._weld[(hand, link)]
        self.model.eq_data[eq, 0:3] = 0.0
        self.model.eq_data[eq, 3:6] = rel_pos
        self.model.eq_data[eq, 6:10] = rel_quat
        self.data.eq_active[eq] = 1
        self._grip_offset[hand] = (rel_pos, rel_quat)
        self._held[hand] = link

    def _check_jump(self, hand: str, link: str, q: Vec) -> None:
        """Refuse a grasp whose last jump (the IK solved again where the link is now) would
        put the arm more than JUMP_PENETRATION_M into the other arm, the robot, the scene or
        another link: measured, a gripper written 3-4 cm into the other gripper made MuJoCo's
        step diverge (it then resets the whole state)."""
        other = self._other(hand)
        grips = {hand: link}
        held = self._held[other]
        if held is not None:
            grips[other] = held
        chk = self.checker
        chk.sync(self.data.qpos)
        clear, pair = chk.clearance({hand: q}, Query((hand,), self.grip_pairs(grips), 0.0))
        if clear < -JUMP_PENETRATION_M:
            raise NotExecutableError(f"the {hand} hand's grasp of {link} would put it "
                                     f"{-1000 * clear:.0f} mm into {pair}")

    def release(self, hand: str) -> None:
        """Open ``hand``: the weld goes off; its gripper collides with the link again once it
        has left it (:meth:`after_step`)."""
        super().release(hand)

    def close_in(self, hand: str, link: str) -> None:
        """The gripper's final leg to ``link`` begins: no contacts between them (the fingers
        straddle the link before they close; the grasp then welds it)."""
        self._closing[hand] = link
        self._grip_contacts(hand, link, False)

    def _grip_contacts(self, hand: str, link: str, on: bool) -> None:
        """Switch contacts between ``hand``'s gripper and ``link`` on or off."""
        off = self._no_contact[hand]
        if on == (link not in off):
            return
        bit = link_bit(self._link_index[link])
        ids = np.array(self.geoms[hand].gripper, dtype=int)
        if on:
            self.model.geom_conaffinity[ids] |= bit
            off.discard(link)
        else:
            self.model.geom_conaffinity[ids] &= ~bit
            off.add(link)
        refresh_body_bits(self.model, {int(self.model.geom_bodyid[g]) for g in ids})

    def after_step(self) -> None:
        """Log the arms' collisions of the step just taken; every GRIP_CHECK_STEPS steps,
        switch a gripper's contacts with a link it let go of back on once it is clear."""
        self.contacts.update(self.data)
        self._steps += 1
        if self._steps % GRIP_CHECK_STEPS:
            return
        for h in self.names:
            for link in list(self._no_contact[h]):
                if link in (self._held[h], self._closing.get(h)):
                    continue
                lg = self.geoms[h].links[link]
                if all(mujoco.mj_geomDistance(self.model, self.data, int(g), lg, 0.002, None)
                       >= 0.002 for g in self.geoms[h].gripper):
                    self._grip_contacts(h, link, True)

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
        self._follow(dt)
        for h in self.names:
            va, act = self._v[h], self._act[h]
            kp, kv = self._kp[h], self._kv[h]
            # Feed-forward (bias forces the gravity compensation leaves, desired velocity)
            # folded into the servo's set-point.
            ff = d.qfrc_bias[va] - d.qfrc_gravcomp[va] + kv * self._target_qd[h]
            if self._target_qdd[h].any():  # inertia feed-forward along a planned motion
                self._acc_vec[:] = 0.0
                self._acc_vec[va] = self._target_qdd[h]
                mujoco.mj_mulM(self.model, d, self._acc_out, self._acc_vec)
                ff = ff + self._acc_out[va]
            d.ctrl[act] = self._target_q[h] + ff / kp
            self.last_torque[h] = d.actuator_force[act].copy()
            for aid, open_, closed in self._fingers[h]:
                d.ctrl[aid] = closed if self._held[h] is not None else open_
