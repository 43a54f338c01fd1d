"""Arm contacts in the physics: which geoms collide with which, and a log of the collisions.

MuJoCo lets two geoms collide when ``contype`` of one shares a bit with ``conaffinity`` of the
other. The bits of the scene (:mod:`artiplan.world.mjcf`: the environment 1, the links 2) are
kept; Baxter's scene adds its own (:func:`assign_bits`):

=========  ====================================================================
bit        geoms
=========  ====================================================================
``ENV``    floor, table (collide with links, and now with the arms)
``LINK``   every link (collides with the environment and with the arms but the fingers)
``LEFT``   the left arm's collision shapes; ``RIGHT`` the right arm's
``TORSO``  torso and head (not against the shoulder and e0 housings mounted in its hull)
``SCENE``  pedestal and fixture (collide with the arms only: L1 sits in the fixture)
link bit   one per link (:func:`link_bit`): the gripper collides with the links through
           these, and the one it holds is switched off while it holds it
=========  ====================================================================

So each arm collides with the torso, the other arm, the table, floor, pedestal, fixture and
every link; a gripper not with the link it grasps (the weld holds that one); an arm not with
itself (robosuite's shapes of neighbouring joints overlap). Collisions that still happen are
real and :class:`ContactLog` records them: which geoms, when, how deep.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import mujoco
import numpy as np

ENV, LINK, LEFT, RIGHT, TORSO, SCENE = 1, 2, 4, 8, 16, 32
#: Bit of the first link (L1); link i (1-based) has bit 1 << (LINK_BIT0 + i - 1).
LINK_BIT0 = 6
#: Penetrations shallower than this [m] are resting touches, not logged as collisions.
LOG_DEPTH_M = 0.0005


def link_bit(index: int) -> int:
    """Contact bit of link ``index`` (1-based)."""
    return 1 << (LINK_BIT0 + index - 1)


def all_link_bits(n_links: int) -> int:
    """The bits of links 1..n."""
    return sum(link_bit(i) for i in range(1, n_links + 1))


def arm_bits(hand: str, part: str, n_links: int) -> tuple[int, int]:
    """(contype, conaffinity) of one of ``hand``'s collision geoms; ``part`` is ``shoulder``
    (mounted in the torso's hull: not against it), ``gripper`` (links by their own bits) or
    ``arm``."""
    own, other = (LEFT, RIGHT) if hand == "left" else (RIGHT, LEFT)
    aff = ENV | other | SCENE
    if part != "shoulder":
        aff |= TORSO
    aff |= all_link_bits(n_links) if part == "gripper" else LINK
    return own, aff


def refresh_body_bits(model: mujoco.MjModel, bodies: set[int]) -> None:
    """Recompute the body-level filter bits (the OR of their geoms' bits, which MuJoCo's broad
    phase reads) after geoms' bits changed at run time."""
    for b in bodies:
        start, num = int(model.body_geomadr[b]), int(model.body_geomnum[b])
        if num <= 0:
            continue
        model.body_contype[b] = int(np.bitwise_or.reduce(model.geom_contype[start : start + num]))
        model.body_conaffinity[b] = int(
            np.bitwise_or.reduce(model.geom_conaffinity[start : start + num])
        )


@dataclass
class Collision:
    """One collision: a geom pair in contact from ``start`` to ``end`` [s, simulated], as deep
    as ``depth_m`` [m] at ``deepest`` [s]."""

    geoms: tuple[str, str]
    start: float
    end: float
    depth_m: float
    deepest: float

    def to_dict(self) -> dict[str, object]:
        return {"geoms": list(self.geoms), "start": round(self.start, 4),
                "end": round(self.end, 4), "depth_m": round(self.depth_m, 5),
                "deepest": round(self.deepest, 4)}


@dataclass
class ContactLog:
    """Collisions of the arms in the physics (call :meth:`update` after every step).

    A collision starts when an arm geom penetrates another geom by more than
    :data:`LOG_DEPTH_M` and ends at the first step it does not touch it any more.
    """

    arm_geoms: frozenset[int]
    names: dict[int, str]
    events: list[Collision] = field(default_factory=list)
    _open: dict[tuple[int, int], Collision] = field(default_factory=dict)
    #: The deepest penetration [m] of an arm in the step just read (0: none), and its geoms.
    deepest_now: float = 0.0
    deepest_pair: tuple[str, str] = ("", "")

    def update(self, data: mujoco.MjData) -> None:
        """Read the contacts of the step just taken."""
        n = int(data.ncon)
        touching: set[tuple[int, int]] = set()
        self.deepest_now = 0.0
        if n:
            pairs = data.contact.geom[:n]
            dists = data.contact.dist[:n]
            for (g1, g2), dist in zip(pairs, dists, strict=True):
                a, b = int(g1), int(g2)
                if a not in self.arm_geoms and b not in self.arm_geoms:
                    continue
                key = (min(a, b), max(a, b))
                touching.add(key)
                if -float(dist) > self.deepest_now:
                    self.deepest_now = -float(dist)
                    self.deepest_pair = (self.names[key[0]], self.names[key[1]])
                self._touch(key, float(dist), float(data.time))
        for key in [k for k in self._open if k not in touching]:
            del self._open[key]

    def _touch(self, key: tuple[int, int], dist: float, now: float) -> None:
        event = self._open.get(key)
        if event is None:
            if -dist < LOG_DEPTH_M:
                return
            event = Collision((self.names[key[0]], self.names[key[1]]), now, now, -dist, now)
            self._open[key] = event
            self.events.append(event)
        event.end = now
        if -dist > event.depth_m:
            event.depth_m, event.deepest = -dist, now

    def since(self, t: float) -> list[Collision]:
        """Collisions that went on at or after ``t`` [s]."""
        return [e for e in self.events if e.end >= t]
