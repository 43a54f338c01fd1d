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
near the object 6 cm off it) through a pre-grasp pose 7 cm back along the hand's approach
axis, then straight in (:mod:`artiplan.world.approach`); the last few millimetres still
jump. Arm contacts are off in the physics: nothing stops an arm that does pass through an
obstacle. With ``avoid_collisions`` the grasps are *chosen* clear of the torso, the other arm,
the pedestal, table, fixture and other links (:mod:`artiplan.world.collision`), at the grasp
and at the rotating arm's poses turned +-30 deg on both planes (the holding arm at its grasp);
the grasp IK is pushed away from obstacles. Not avoided: contacts during the rotation that
the sweep's four sample poses miss (the tracking IK itself is blind to obstacles), arm-vs-link
contacts during the rotation (links are not turned in the check), and collisions on the way
of a retreat or of an approach (measured only: ``last_approach_clearance``).
"""

from __future__ import annotations

from collections.abc import Callable

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
)
from artiplan.world.baxter_model import (  # noqa: F401 - re-exported (public names)
    BAXTER_BASE,
    PREFIX,
    attach_baxter,
    baxter_layout,
    baxter_xml_path,
)
from artiplan.world.collision import ArmGeoms, arm_geoms
from artiplan.world.grasping import (  # noqa: F401 - re-exported (public names)
    REACH_TOLERANCE,
    SWEEP_DEG,
    TRACK_NULLSPACE_GAIN,
    Candidate,
    OutOfReachError,
)
from artiplan.world.hands import Hands
from artiplan.world.rotations import Vec, quat_conj, quat_mul, quat_to_mat
from artiplan.world.servo import ServoGains

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

    # -- motions between grasps (the approach itself: :mod:`artiplan.world.approach`) ------
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
        self._move({h: [starts[h], goals[h]] for h in hands}, duration_s, advance)

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
        #: Per hand, the pre-grasp joint angles [rad] of the last approach.
        self.last_pregrasp = {}

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
