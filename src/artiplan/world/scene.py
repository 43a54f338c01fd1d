"""The simulated world: the articulated object under gravity in MuJoCo, hands, perception.

Typical use (the closed loop of issue 7)::

    world = World(obj, init, WorldConfig(physics=preset("stiff")))
    world.hold_and_rotate("L2", "L3", "z-axis", +1, 10.0)   # start-increase L2 L3 z-axis
    world.run_until(world.time + 3.0)
    world.stop()                                            # stop-increase: release both hands
    percept = world.perceive(reference=predicted)           # (Configuration, uncertainty)

Times in seconds, angles in degrees, lengths in metres.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import mujoco
import numpy as np

from artiplan.model import ArticulatedObject, Configuration
from artiplan.world.hands import Hands, VirtualHands
from artiplan.world.mjcf import SceneLayout, default_layout, scene_xml
from artiplan.world.perception import Percept, PerceptionConfig, estimate, observe
from artiplan.world.presets import JointPhysics, preset
from artiplan.world.rotations import (
    Vec,
    configuration_from_directions,
    link_quat,
    quat_axis_angle,
    quat_conj,
    quat_mul,
    rotation_axis,
)
from artiplan.world.servo import Servo, ServoGains
from artiplan.world.turning import DEFAULT_EXTENT_DEG, EXTRA_DEG, Turn

#: Default of :attr:`WorldConfig.impact_stop_m` for Baxter's worlds (:func:`make_world`) [m].
#: Measured on 6 links (session 20, benchmarks/RESULTS.md): turns stopped so and resumed by
#: a re-grasp; without it a turn went on with both grippers pressing L4 10-12 mm deep until
#: MuJoCo diverged, and grippers pushed neighbouring links 5-10 deg off their goals.
IMPACT_STOP_M = 0.005


@dataclass(frozen=True)
class WorldConfig:
    """Settings of a world.

    Attributes:
        physics: Joint damping/friction and time step (``preset("stiff")`` or ``"loose"``).
        perception: Camera noise and estimation.
        seed: Seeds the camera noise.
        servo: Gains of the hands' pose servo (None: the hands' own ``servo_gains``).
        layout: Where the object, table and cameras are (None: a default for the hands).
        impact_stop_m: Stop a turn's command where it is when an arm penetrates anything
            (another object link, the other arm, the scene) deeper than this [m] while it
            turns, as a robot's collision detection stops an arm on an unexpected force
            (None: turns go on through contacts). The hands keep holding; the loop re-grasps
            for the rest of the turn (:mod:`artiplan.execution.regrasp`).
        strain_stop: Stop a turn's command where it is, as at an impact, when a grasping
            hand's servo integral reaches its bound (:class:`ServoGains`) while the turn
            runs: the hand cannot follow its command (held by a contact, an arm at a joint
            limit, or the two grasps fighting through the chain), as a robot's tracking-error
            limit would. 2 of the 3 6-link runs that diverged in sessions 20-21 had a hand's
            integral at its bound, but on 6 links 21 turns in 20 tasks reached the bound
            and 12/20 were reached with it against 14-16/20 without (session 21,
            benchmarks/RESULTS.md): off by default.
    """

    physics: JointPhysics = field(default_factory=lambda: preset("stiff"))
    perception: PerceptionConfig = field(default_factory=PerceptionConfig)
    seed: int = 0
    servo: ServoGains | None = None
    layout: SceneLayout | None = None
    impact_stop_m: float | None = None
    strain_stop: bool = False


@dataclass
class Motion:
    """A rotation in progress: ``link`` turns about ``axis`` through ``pivot``."""

    hand: str
    link: str
    pivot: Vec
    quat0: Vec
    axis: Vec
    speed_rad_s: float
    t0: float
    hold_link: str = ""
    plane: str = ""
    direction: int = 0
    limit_rad: float = math.inf

    def target(self, t: float) -> tuple[Vec, Vec]:
        """Desired (position, quaternion) of the link's frame at time ``t`` (the turn stops at
        ``limit_rad``)."""
        q = quat_axis_angle(self.axis, min(self.speed_rad_s * (t - self.t0), self.limit_rad))
        return self.pivot, quat_mul(q, self.quat0)


class World:
    """The articulated object clamped at L1, hanging under gravity, with two hands."""

    def __init__(
        self,
        obj: ArticulatedObject,
        conf: Configuration | None = None,
        config: WorldConfig | None = None,
        hands: Hands | None = None,
    ) -> None:
        self.obj = obj
        self.config = config or WorldConfig()
        self.hands = hands or VirtualHands()
        conf = conf or Configuration.hanging(obj.n_links)
        self.layout = self.config.layout or self._default_layout()
        self.model, self.data = self._build(conf)
        self._ids = [self.model.body(link).id for link in obj.links]
        self._qadr = [-1] + [
            int(self.model.jnt_qposadr[self.model.joint(f"J{i}").id])
            for i in range(2, obj.n_links + 1)
        ]
        self._vadr = [-1] + [
            int(self.model.jnt_dofadr[self.model.joint(f"J{i}").id])
            for i in range(2, obj.n_links + 1)
        ]
        self.hands.bind(self.model, self.data, obj)
        self._rng = np.random.default_rng(self.config.seed)
        self._renderers: dict[tuple[int, int], mujoco.Renderer] = {}
        self._motion: Motion | None = None
        #: hand -> (link, fixed desired pose or None when the motion drives it, servo)
        self._goals: dict[str, tuple[str, tuple[Vec, Vec] | None, Servo]] = {}
        self._reference = self._estimate = conf.wrapped()
        #: (degrees, why) when the last turn stops short of its planned extent (else None).
        self.turn_limit: tuple[float, str] | None = None
        #: Turns stopped on impact: (time [s], the geoms, depth [m]) (``impact_stop_m``), or
        #: on strain: (time [s], (hand, "servo bound"), 0.0) (``strain_stop``).
        self.impacts: list[tuple[float, tuple[str, str], float]] = []
        self.set_configuration(conf)

    # -- construction -------------------------------------------------------------------
    def _default_layout(self) -> SceneLayout:
        return default_layout(self.obj, virtual_hands=isinstance(self.hands, VirtualHands))

    def _build(self, conf: Configuration) -> tuple[mujoco.MjModel, mujoco.MjData]:
        xml = scene_xml(self.obj, conf, self.config.physics, self.layout)
        extend = getattr(self.hands, "extend_spec", None)
        if extend is None:
            model = mujoco.MjModel.from_xml_string(xml)
        else:  # hands that bring their own bodies (Baxter) attach them to the spec
            spec = mujoco.MjSpec.from_string(xml)
            extend(spec, self.obj)
            model = spec.compile()
        return model, mujoco.MjData(model)

    # -- state --------------------------------------------------------------------------
    @property
    def time(self) -> float:
        """Simulation time [s]."""
        return float(self.data.time)

    @property
    def base_position(self) -> Vec:
        """World position of L1's base end (the fixture) [m]."""
        return np.asarray(self.layout.anchor) + np.asarray(self.obj.base_position)

    def set_configuration(self, conf: Configuration) -> None:
        """Put the object at ``conf`` at rest (L1's clamp included); hands are released."""
        if conf.n_links != self.obj.n_links:
            raise ValueError(f"object has {self.obj.n_links} links, configuration {conf.n_links}")
        self._motion = None
        self._release_all()
        absolute = [link_quat(t, g) for t, g in zip(conf.theta, conf.gamma, strict=True)]
        self.model.body_quat[self._ids[0]] = absolute[0]
        for i in range(1, self.obj.n_links):
            body_q = self.model.body_quat[self._ids[i]]
            rel = quat_mul(quat_conj(absolute[i - 1]), absolute[i])
            a = self._qadr[i]
            self.data.qpos[a : a + 4] = quat_mul(quat_conj(body_q), rel)
            self.data.qvel[self._vadr[i] : self._vadr[i] + 3] = 0.0
        mujoco.mj_forward(self.model, self.data)
        self._reference = self._estimate = conf.wrapped()

    def link_directions(self) -> Vec:
        """(n, 3) unit vectors, base end -> tip end, of every link now."""
        return np.array([-self.data.xmat[b].reshape(3, 3)[:, 2] for b in self._ids])

    def link_centres(self) -> Vec:
        """(n, 3) world positions of the link centres [m]."""
        half = self.obj.link_length / 2.0
        return np.array([self.data.xpos[b] for b in self._ids]) + half * self.link_directions()

    def true_configuration(self, reference: Configuration | None = None) -> Configuration:
        """The simulator's configuration (ground truth), covers chosen near ``reference``.

        Without a reference, the last configuration set or read is used (perception keeps
        its own previous estimate: the truth does not leak into it).
        """
        ref = reference or self._reference
        conf = configuration_from_directions(self.link_directions(), ref)
        self._reference = conf
        return conf

    # -- time -----------------------------------------------------------------------------
    def step(self, dt: float | None = None) -> None:
        """Advance the simulation by ``dt`` seconds (default: one physics step)."""
        h = self.model.opt.timestep
        n = 1 if dt is None else max(1, int(round(dt / h)))
        t0 = self.time
        for _ in range(n):
            if self._goals:
                self._servo_step(self.time + h, h)
            self.hands.control(h)
            mujoco.mj_step(self.model, self.data)
            self.hands.after_step()
            if self._motion is not None and self.config.impact_stop_m is not None:
                self._impact_stop(self.config.impact_stop_m)
            if self._motion is not None and self.config.strain_stop:
                self._strain_stop()
        # MuJoCo answers a diverging step (bad accelerations) by resetting the whole state:
        # time back to 0, every body at the model's initial pose. Going on from there would
        # act on a world that teleported (measured once on 6 links with Baxter: the loop
        # planned from t = 0.05 s after 78.7 s).
        if self.time < t0:
            raise FloatingPointError(
                f"physics diverged after t = {t0:.3f} s (MuJoCo reset its state)"
                + self._divergence_clues())
        if not np.all(np.isfinite(self.data.qpos)):
            raise FloatingPointError(f"physics diverged at t = {self.time:.3f} s")

    def _impact_stop(self, depth_m: float) -> None:
        """Stop the turn when an arm went deeper than ``depth_m`` [m] into something in the
        step just taken (``WorldConfig.impact_stop_m``)."""
        contacts = getattr(self.hands, "contacts", None)
        if contacts is None or contacts.deepest_now <= depth_m:
            return
        self._stop_turn(f"stopped on impact: {'~'.join(contacts.deepest_pair)} "
                        f"{1000 * contacts.deepest_now:.0f} mm",
                        contacts.deepest_pair, contacts.deepest_now)

    def _strain_stop(self) -> None:
        """Stop the turn when a grasping hand's servo integral sits at its bound
        (``WorldConfig.strain_stop``)."""
        for hand, (link, _, servo) in sorted(self._goals.items()):
            g = servo.gains
            pos = float(np.linalg.norm(servo.int_pos))
            rot = float(np.linalg.norm(servo.int_rot))
            if pos < 0.999 * g.max_int_pos and rot < 0.999 * g.max_int_rot:
                continue
            self._stop_turn(f"stopped on strain: the {hand} hand on {link} cannot follow "
                            f"(servo integral {1000 * pos:.0f} mm, {math.degrees(rot):.0f} deg)",
                            (hand, "servo bound"), 0.0)
            return

    def _stop_turn(self, why: str, what: tuple[str, str], depth_m: float) -> None:
        """Stop the turn's command where it is now, unless it has already ended there: the
        turn ends as at a :attr:`turn_limit` (:attr:`turn_ends` is now), recorded in
        :attr:`impacts` with ``what`` and ``depth_m`` [m]."""
        m = self._motion
        assert m is not None
        done = max(0.0, m.speed_rad_s * (self.time - m.t0))
        if done >= m.limit_rad:
            return
        m.limit_rad = done
        self.turn_limit = (math.degrees(done), f"{why} at t={self.time:.2f} s")
        self.impacts.append((self.time, what, depth_m))

    def _divergence_clues(self) -> str:
        """What MuJoCo said about the diverging step (the joint whose acceleration went bad)
        and how far the hands' servos had wound up: clues to why, for the log."""
        clues = []
        for kind, what in (("BADQPOS", "position"), ("BADQVEL", "velocity"),
                           ("BADQACC", "acceleration")):
            warn = self.data.warning[int(getattr(mujoco.mjtWarning, f"mjWARN_{kind}"))]
            if warn.number > 0 and 0 <= warn.lastinfo < self.model.nv:
                joint = self.model.joint(int(self.model.dof_jntid[warn.lastinfo])).name
                clues.append(f"bad {what} of joint {joint or warn.lastinfo}")
        for hand, (link, _, servo) in sorted(self._goals.items()):
            clues.append(f"{hand} hand on {link}: servo integral "
                         f"{1000 * float(np.linalg.norm(servo.int_pos)):.1f} mm, "
                         f"{math.degrees(float(np.linalg.norm(servo.int_rot))):.1f} deg")
        return f"; {'; '.join(clues)}" if clues else ""

    def run_until(self, t: float) -> None:
        """Advance the simulation until time ``t`` [s] (to the nearest physics step)."""
        if t - self.time >= 0.5 * self.model.opt.timestep:
            self.step(t - self.time)

    # -- actions --------------------------------------------------------------------------
    def hold_and_rotate(
        self,
        hold_link: str,
        rotate_link: str,
        plane: str,
        direction: int,
        speed_deg_s: float = 10.0,
        reference: Configuration | None = None,
        extent_deg: float | None = None,
    ) -> None:
        """Hold ``hold_link`` and turn its neighbour ``rotate_link`` about their joint.

        ``direction`` +1 increases the angle on ``plane``, -1 decreases it, in the double-cover
        representation nearest ``reference`` (the plan's prediction; default: the last one read).
        ``xy-axes`` turns about the world vertical; ``z-axis`` about the horizontal normal of
        the link's vertical plane. The links tip-ward of ``rotate_link`` are carried.
        ``extent_deg``: how far the turn is meant to go (the hands choose grasps that can do
        it; default :data:`artiplan.world.turning.DEFAULT_EXTENT_DEG`). Hands that find no
        way to do it raise a ``RuntimeError`` (nothing is held then); hands that can do only
        part of it set :attr:`turn_limit`, and the turn stops there.
        """
        k, j = self.obj.index(hold_link), self.obj.index(rotate_link)
        if j != k + 1:
            raise ValueError(f"{rotate_link} is not the tip-ward neighbour of {hold_link}")
        if direction not in (1, -1):
            raise ValueError("direction must be +1 (increase) or -1 (decrease)")
        self.stop(release=True)
        conf = self.true_configuration(reference)
        extent = DEFAULT_EXTENT_DEG if extent_deg is None else extent_deg + EXTRA_DEG
        turn = Turn(j, direction * rotation_axis(plane, conf.theta[j - 1]),
                    self.data.xpos[self._ids[j - 1]].copy(), extent)
        hold_hand, rot_hand = self.hands.assign(hold_link, rotate_link, turn)
        limit = getattr(self.hands, "turn_limit", None)
        self.turn_limit = limit
        approach = getattr(self.hands, "approach", None)
        if approach is not None:  # arms that take time to reach (the world runs meanwhile)
            pairs = [(hold_hand, hold_link)] if k > 1 else []
            approach([*pairs, (rot_hand, rotate_link)], self.step)
        conf = self.true_configuration(reference)
        if k > 1:  # L1 is clamped already
            self._grip(hold_hand, hold_link)
        self._grip(rot_hand, rotate_link)
        body = self._ids[j - 1]
        axis = direction * rotation_axis(plane, conf.theta[j - 1])
        link, _, servo = self._goals[rot_hand]
        self._goals[rot_hand] = (link, None, servo)
        self._motion = Motion(
            rot_hand,
            rotate_link,
            self.data.xpos[body].copy(),
            self.data.xquat[body].copy(),
            axis,
            math.radians(speed_deg_s),
            self.time,
            hold_link,
            plane,
            direction,
            math.radians(limit[0]) if limit is not None else math.inf,
        )

    @property
    def turn_ends(self) -> float | None:
        """Simulated time [s] at which the rotation in progress reaches :attr:`turn_limit`
        (its command stops there), or None when it is not limited (or nothing turns)."""
        m = self._motion
        if m is None or not math.isfinite(m.limit_rad):
            return None
        return m.t0 + m.limit_rad / m.speed_rad_s

    @property
    def motion(self) -> tuple[str, str, str, int] | None:
        """The rotation in progress as (hold link, rotated link, plane, direction), or None."""
        m = self._motion
        return None if m is None else (m.hold_link, m.link, m.plane, m.direction)

    def arms_home(self) -> bool:
        """Open both hands and send the arms home by planned, collision-free motions (the
        world runs meanwhile); False when these hands have no such motion (virtual hands), are
        home already, or no path home was found."""
        self.stop(release=True)
        home = getattr(self.hands, "go_home", None)
        return bool(home(self.step)) if home is not None else False

    def stop(self, release: bool = True) -> None:
        """Stop rotating; with ``release`` open both hands (the links become free), else keep
        holding both links where the rotation's command has reached."""
        if self._motion is not None and not release:
            link, _, servo = self._goals[self._motion.hand]
            self._goals[self._motion.hand] = (link, self._motion.target(self.time), servo)
        self._motion = None
        if release:
            self._release_all()

    def _grip(self, hand: str, link: str) -> None:
        """Grasp ``link`` with ``hand`` and keep it where it is (a servo goal)."""
        self.hands.grasp(hand, link)
        body = self.model.body(link).id
        pose = (self.data.xpos[body].copy(), self.data.xquat[body].copy())
        self._goals[hand] = (link, pose, Servo(self.config.servo or self.hands.servo_gains))

    def _release_all(self) -> None:
        self.hands.release_all()
        self._goals.clear()

    def _servo_step(self, t: float, h: float) -> None:
        """Command every grasping hand toward its desired link pose at time ``t``."""
        for hand, (link, fixed, servo) in self._goals.items():
            desired = fixed if fixed is not None else self._motion_target(t)
            body = self.model.body(link).id
            actual = (self.data.xpos[body], self.data.xquat[body])
            pos, quat = servo.command(desired, actual, h)
            self.hands.command(hand, pos, quat)

    def _motion_target(self, t: float) -> tuple[Vec, Vec]:
        assert self._motion is not None
        return self._motion.target(t)

    def release(self) -> None:
        """Open both hands."""
        self.stop(release=True)

    def push(self, link: str, plane: str, delta_deg: float) -> None:
        """A human intervention: turn ``link`` (and the links it carries) by ``delta_deg``
        about its base-ward joint on ``plane``, instantly. Positive increases the angle in the
        representation of the last configuration read. L1 (clamped) cannot be pushed.
        """
        i = self.obj.index(link)
        if i == 1:
            raise ValueError("L1 is clamped to the fixture and cannot be pushed")
        conf = self.true_configuration()
        axis = rotation_axis(plane, conf.theta[i - 1])
        turn = quat_axis_angle(axis, math.radians(delta_deg))
        new_abs = quat_mul(turn, self.data.xquat[self._ids[i - 1]])
        parent = self.data.xquat[self._ids[i - 2]]
        body_q = self.model.body_quat[self._ids[i - 1]]
        a = self._qadr[i - 1]
        rel = quat_mul(quat_conj(parent), new_abs)
        self.data.qpos[a : a + 4] = quat_mul(quat_conj(body_q), rel)
        self.data.qvel[self._vadr[i - 1] : self._vadr[i - 1] + 3] = 0.0
        mujoco.mj_forward(self.model, self.data)
        self._reference = configuration_from_directions(self.link_directions(), conf)

    # -- perception -----------------------------------------------------------------------
    def perceive(
        self, reference: Configuration | None = None, config: PerceptionConfig | None = None
    ) -> Percept:
        """The overhead camera's estimate of the configuration now, with per-link uncertainty.

        Covers are chosen near ``reference`` (the prediction), else near the previous estimate.
        """
        cfg = config or self.config.perception
        centres, axes = observe(self.link_centres(), self.link_directions(), cfg, self._rng)
        ref = reference or self._estimate
        conf, sigma = estimate(centres, axes, self.base_position, self.obj.link_length, cfg, ref)
        self._estimate = conf
        return Percept(self.time, conf, sigma)

    # -- rendering ------------------------------------------------------------------------
    def render(
        self,
        camera: str = "overhead",
        kind: str = "rgb",
        width: int = 640,
        height: int = 480,
        frame: bool = True,
    ) -> Vec:
        """An image from ``camera`` (``overhead``, ``side``, ``perspective``).

        ``kind``: ``rgb`` (H, W, 3) uint8, ``depth`` (H, W) metres, ``segmentation`` (H, W)
        link index (1..n; 0 for everything else). ``frame`` moves the camera so the object
        fills the image.
        """
        from artiplan.world.render import render

        return render(self, camera, kind, width, height, frame)

    def renderer(self, width: int, height: int) -> mujoco.Renderer:
        """A renderer of this size, created once (an OpenGL context is costly)."""
        key = (width, height)
        if key not in self._renderers:
            self._renderers[key] = mujoco.Renderer(self.model, height=height, width=width)
        return self._renderers[key]

    def close(self) -> None:
        """Free the renderers' OpenGL contexts (call before exit when you rendered)."""
        for r in self._renderers.values():
            r.close()
        self._renderers.clear()
