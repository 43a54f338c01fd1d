"""Hands: what grasps links, holds them and moves them (Baxter's grippers or virtual hands).

A grasp is a weld equality switched on at run time from the current relative pose (so nothing
snaps). A hand is commanded with the desired world pose of the *grasped link's frame* (its
base-end joint, see :mod:`artiplan.world.mjcf`); each implementation realises that pose its own
way: virtual hands move a mocap body, Baxter solves inverse kinematics.
"""

from __future__ import annotations

from abc import ABC, abstractmethod

import mujoco
import numpy as np

from artiplan.model import ArticulatedObject
from artiplan.world.mjcf import HAND_NAMES
from artiplan.world.rotations import Vec
from artiplan.world.servo import ServoGains
from artiplan.world.turning import Turn


class Hands(ABC):
    """Two hands, ``left`` and ``right``, that grasp links of the object.

    Lifecycle: the world builds its model, then calls :meth:`bind`; before every physics step
    it calls :meth:`control`.
    """

    names: tuple[str, str] = HAND_NAMES
    #: Gains of the world's pose servo that suit these hands.
    servo_gains: ServoGains = ServoGains()

    data: mujoco.MjData  #: set by :meth:`bind`

    def __init__(self) -> None:
        self._held: dict[str, str | None] = {h: None for h in self.names}
        #: (hand, link) -> id of the weld equality that is the grasp (set by :meth:`bind`).
        self._weld: dict[tuple[str, str], int] = {}

    @property
    def kind(self) -> str:
        """Short name: ``virtual`` or ``baxter``."""
        return type(self).__name__.replace("Hands", "").lower()

    @abstractmethod
    def bind(self, model: mujoco.MjModel, data: mujoco.MjData, obj: ArticulatedObject) -> None:
        """Look up ids in a freshly built model."""

    @abstractmethod
    def grasp(self, hand: str, link: str) -> None:
        """Close ``hand`` on ``link`` where the link is now (weld from the current pose)."""

    def release(self, hand: str) -> None:
        """Open ``hand``: switch off the weld that was the grasp; the link becomes free."""
        self._check_hand(hand)
        link = self._held[hand]
        if link is not None:
            self.data.eq_active[self._weld[(hand, link)]] = 0
        self._held[hand] = None

    @abstractmethod
    def command(self, hand: str, pos: Vec, quat: Vec) -> None:
        """Desired world pose (position [m], quaternion wxyz) of the held link's frame."""

    def control(self, dt: float) -> None:  # noqa: B027 - optional hook
        """Called before every physics step of ``dt`` seconds (controllers, IK)."""

    def after_step(self) -> None:  # noqa: B027 - optional hook
        """Called after every physics step (e.g. to log contacts)."""

    def held(self, hand: str) -> str | None:
        """The link ``hand`` holds, or None."""
        return self._held[hand]

    def assign(
        self, hold_link: str, rotate_link: str, turn: Turn | None = None
    ) -> tuple[str, str]:
        """(hand that holds, hand that rotates) for a rotation ``turn`` of ``rotate_link``;
        the default: left holds, right rotates (virtual hands collide with nothing)."""
        return self.names[0], self.names[1]

    def release_all(self) -> None:
        for h in self.names:
            if self._held[h] is not None:
                self.release(h)

    def _check_hand(self, hand: str) -> None:
        if hand not in self.names:
            raise ValueError(f"unknown hand {hand!r}; valid hands: {', '.join(self.names)}")


class VirtualHands(Hands):
    """Mocap bodies welded to links: no arms, exact and fast (any chain length)."""

    def bind(self, model: mujoco.MjModel, data: mujoco.MjData, obj: ArticulatedObject) -> None:
        self.model, self.data = model, data
        self._mocap = {h: int(model.body_mocapid[model.body(f"hand_{h}").id]) for h in self.names}
        self._weld = {
            (h, link): model.equality(f"weld_{h}_{link}").id
            for h in self.names
            for link in obj.links
        }
        self._held = {h: None for h in self.names}

    def grasp(self, hand: str, link: str) -> None:
        self._check_hand(hand)
        if self._held[hand] is not None:
            self.release(hand)
        body = self.model.body(link).id
        mid = self._mocap[hand]
        # Put the hand exactly on the link frame, so the weld's relative pose is the identity.
        self.data.mocap_pos[mid] = self.data.xpos[body]
        self.data.mocap_quat[mid] = self.data.xquat[body]
        eq = self._weld[(hand, link)]
        self.model.eq_data[eq, :3] = 0.0
        self.model.eq_data[eq, 3:6] = 0.0
        self.model.eq_data[eq, 6:10] = (1.0, 0.0, 0.0, 0.0)
        self.data.eq_active[eq] = 1
        self._held[hand] = link

    def command(self, hand: str, pos: Vec, quat: Vec) -> None:
        mid = self._mocap[hand]
        self.data.mocap_pos[mid] = pos
        self.data.mocap_quat[mid] = np.asarray(quat) / np.linalg.norm(quat)
