"""Collision checking of Baxter's arms and joint-space motion planning with OMPL.

:class:`ArmChecker` keeps a planning copy of the world's model whose arm geoms have a contact
margin: one ``mj_collision`` call (MuJoCo's broad and narrow phase, the physics' own contact
bits, :mod:`artiplan.world.contacts`) then reports every pair of an arm and an obstacle closer
than that margin, with its signed distance. A configuration is valid when every such pair of
the moving arms is at least the required clearance apart, except the pairs a query allows (the
gripper on the link it is about to grasp, on the final straight leg).

:func:`plan_path` plans one or both arms (7-D or 14-D: the arms are checked against each
other at every state) with OMPL's RRT-Connect within the joint limits, simplifies the path
(shortcuts, OMPL's ``simplifySolution``) and checks every segment again every
:data:`CHECK_STEP_RAD`. The states between the path's waypoints are the straight segments a
rest-to-rest trajectory (:mod:`artiplan.world.timing`) follows exactly.
"""

from __future__ import annotations

import copy
import functools
import math
import time
from collections.abc import Callable, Iterator
from dataclasses import dataclass, field

import mujoco
import numpy as np

from artiplan.world.contacts import all_link_bits
from artiplan.world.rotations import Vec

#: Contacts are computed up to this distance [m] (the planning copy's margin on arm geoms).
MARGIN_M = 0.02
#: Clearance [m] kept on free motions (the simulated arm lags its command by up to ~1 cm).
TRANSFER_CLEARANCE_M = 0.015
#: Clearance [m] kept near the object: grasps, the rotation's sweep, the straight legs.
NEAR_CLEARANCE_M = 0.003
#: Near a start or goal the required clearance is that endpoint's own (less 1 mm), growing by
#: this much [m] per radian of joint-space distance from it up to the full clearance.
RAMP_M_PER_RAD = 0.1
#: Joint-space step [rad, Euclidean] at which paths are checked; OMPL's own motion checks
#: while it searches use the coarser OMPL_STEP_RAD (its path is then checked at the fine one).
CHECK_STEP_RAD = 0.01
OMPL_STEP_RAD = 0.03
#: Time limits [s, wall] of one OMPL query, of one attempt after a path is found, and of a
#: path's simplification; RRT-Connect runs ATTEMPTS times and the fastest path is kept.
PLAN_TIME_S = 2.0
ATTEMPT_S = 0.3
SIMPLIFY_TIME_S = 0.1
ATTEMPTS = 3
#: Share of a query's time kept for what follows RRT-Connect (the shortcut, overrun).
FINISH_SHARE = 0.05
#: ... fewer when a path is already this near (cost ratio) the straight segment's.
GOOD_ENOUGH = 1.3
#: Seed of OMPL's random generators (set once per process, before the first query).
RNG_SEED = 20261122
#: RRT-Connect's step [rad] (its range: the longest edge it adds at once).
RANGE_RAD = 0.5


@dataclass
class Query:
    """What one check is about.

    Attributes:
        hands: The arms whose geoms are checked (the moving ones).
        allowed: Geom pairs (smaller id first) that may touch (a gripper and its link).
        clearance: Required clearance [m], or a function of the configuration (see
            :func:`ramped`).
        pairs: ``all`` pairs of the query's arms, ``solo`` (not against the other arm) or
            ``arms`` (only the arms against each other).
    """

    hands: tuple[str, ...]
    allowed: frozenset[tuple[int, int]] = frozenset()
    clearance: float | Callable[[Vec], float] = TRANSFER_CLEARANCE_M
    pairs: str = "all"


@dataclass
class MotionStats:
    """One planned motion: wall time [s], dimension, waypoints, success, and why it failed
    (``endpoint``: the start or goal keeps no clearance; ``time``: OMPL found no path that
    passes the fine check in its time; empty when it succeeded)."""

    wall_s: float
    dims: int
    waypoints: int
    ok: bool
    checks: int
    why: str = ""

    def to_dict(self) -> dict[str, object]:
        return {"wall_s": round(self.wall_s, 4), "dims": self.dims,
                "waypoints": self.waypoints, "ok": self.ok, "checks": self.checks,
                "why": self.why}


@dataclass
class ArmChecker:
    """Validity of arm configurations in a planning copy of ``model`` (see module docstring).

    Attributes:
        qadr: Per hand, the qpos addresses of its 7 arm joints.
        arm: Per hand, its collision geoms; ``gripper`` the subset on the gripper.
        links: Link name -> its capsule geom.
    """

    model: mujoco.MjModel
    qadr: dict[str, np.ndarray]
    arm: dict[str, np.ndarray]
    gripper: dict[str, np.ndarray]
    links: dict[str, int]
    #: qpos address -> angle of each finger joint when open.
    fingers_open: dict[int, float] = field(default_factory=dict)
    data: mujoco.MjData = field(init=False)
    checks: int = 0
    stats: list[MotionStats] = field(default_factory=list)

    def __post_init__(self) -> None:
        self.model = copy.deepcopy(self.model)
        bits = all_link_bits(len(self.links))
        for hand in self.arm:
            self.model.geom_margin[self.arm[hand]] = MARGIN_M
            self.model.geom_conaffinity[self.gripper[hand]] |= bits  # all links, in Python
        for b in range(self.model.nbody):
            start, num = int(self.model.body_geomadr[b]), int(self.model.body_geomnum[b])
            if num > 0:
                self.model.body_conaffinity[b] = int(
                    np.bitwise_or.reduce(self.model.geom_conaffinity[start : start + num]))
                self.model.body_margin[b] = float(self.model.geom_margin[start : start + num].max())
        self.data = mujoco.MjData(self.model)
        # geom -> index of the arm it belongs to (-1: none); a plain list: the check reads a
        # few contacts each time, where numpy's per-call overhead (isin, masks) cost more
        # than MuJoCo's collision itself
        self._owner: list[int] = [-1] * self.model.ngeom
        for k, hand in enumerate(self.arm):
            for g in self.arm[hand]:
                self._owner[int(g)] = k
        self._names = list(self.arm)

    def sync(self, qpos: Vec) -> None:
        """Take the world's state (links, both arms) as the scene to check against, the
        fingers open (as they are whenever an arm moves to a grasp)."""
        self.data.qpos[:] = qpos
        for adr, value in self.fingers_open.items():
            self.data.qpos[adr] = value

    def set_arms(self, q: dict[str, Vec]) -> None:
        for hand, qh in q.items():
            self.data.qpos[self.qadr[hand]] = qh

    def contacts(self, query: Query) -> list[tuple[int, int, float]]:
        """(arm geom, other geom, signed distance [m]) of every pair within :data:`MARGIN_M`
        that involves one of ``query.hands`` and is not allowed, in the current ``data``
        (after :meth:`set_arms`)."""
        m, d = self.model, self.data
        mujoco.mj_kinematics(m, d)
        mujoco.mj_collision(m, d)
        self.checks += 1
        n = int(d.ncon)
        if n == 0:
            return []
        owner = self._owner
        ks = {self._names.index(h) for h in query.hands}
        mode, allowed = query.pairs, query.allowed
        out = []
        for (a, b), dd in zip(d.contact.geom[:n].tolist(), d.contact.dist[:n].tolist(),
                              strict=True):
            o1, o2 = owner[a], owner[b]
            if o1 not in ks and o2 not in ks:
                continue
            if (mode == "solo" and o1 >= 0 and o2 >= 0) or (mode == "arms"
                                                           and (o1 < 0 or o2 < 0)):
                continue
            if ((a, b) if a < b else (b, a)) in allowed:
                continue
            out.append((a, b, dd) if o1 >= 0 else (b, a, dd))
        return out

    def nearest(self, q: dict[str, Vec], query: Query) -> tuple[float, int, int]:
        """Smallest clearance [m] of the query's arms at ``q`` (:data:`MARGIN_M` when nothing
        is nearer), the arm's geom and the other geom of that pair (-1, -1 when none)."""
        self.set_arms(q)
        best, arm, other = MARGIN_M, -1, -1
        for a, b, dist in self.contacts(query):
            if dist < best:
                best, arm, other = dist, a, b
        return best, arm, other

    def clearance(self, q: dict[str, Vec], query: Query) -> tuple[float, str]:
        """Smallest clearance [m] of the query's arms at ``q`` (:data:`MARGIN_M` when nothing
        is nearer) and the closest pair's geom names."""
        best, a, b = self.nearest(q, query)
        return best, (f"{self.model.geom(a).name}~{self.model.geom(b).name}" if a >= 0 else "")

    def valid(self, q: dict[str, Vec], query: Query, flat: Vec | None = None) -> bool:
        """Whether ``q`` keeps the query's clearance (``flat``: q stacked, for ramps)."""
        need = query.clearance
        if not callable(need):
            _seen(need)
        self.set_arms(q)
        found = self.contacts(query)
        if not found:
            return True
        nearest = min(dist for _, _, dist in found)
        if callable(need):
            # a ramp never asks more than its full clearance: evaluate it only when needed
            if isinstance(need, Ramp) and nearest >= need.full:
                return True
            need = _seen(need(flat if flat is not None else np.concatenate(list(q.values()))))
        return nearest >= need

    def split(self, hands: tuple[str, ...], flat: Vec) -> dict[str, Vec]:
        """A stacked configuration (7 joints per hand, in ``hands`` order) per hand."""
        return {h: flat[7 * i : 7 * i + 7] for i, h in enumerate(hands)}

    def segment_valid(self, a: Vec, b: Vec, query: Query, step: float = CHECK_STEP_RAD) -> bool:
        """Whether the straight joint-space segment a -> b keeps the clearance at every
        ``step`` [rad] (ends included)."""
        return all(self.valid(self.split(query.hands, q), query, q)
                   for q in segment_points(a, b, step))

    def path_valid(self, path: list[Vec], query: Query) -> bool:
        return all(self.segment_valid(a, b, query) for a, b in zip(path, path[1:], strict=False))

    def path_clearance(self, path: list[Vec], query: Query, stop_below: float = -math.inf,
                       step: float = CHECK_STEP_RAD) -> float:
        """Smallest clearance [m] of the query's arms along the joint-space ``path``, checked
        at the points :meth:`segment_valid` checks (:data:`MARGIN_M` when nothing is nearer;
        the query's own clearance is not used). Stops at the first point nearer than
        ``stop_below``. One pass answers "valid at c?" for every c (``>= c``), where
        :meth:`path_valid` needs one pass per clearance."""
        best = MARGIN_M
        for a, b in zip(path, path[1:], strict=False):
            for q in segment_points(a, b, step):
                best = min(best, self.nearest(self.split(query.hands, q), query)[0])
                if best < stop_below:
                    return best
        return best


def segment_points(a: Vec, b: Vec, step: float = CHECK_STEP_RAD) -> Iterator[Vec]:
    """The configurations a segment a -> b is checked at: every ``step`` [rad] or less, ends
    included (:meth:`ArmChecker.segment_valid`, :meth:`ArmChecker.path_clearance`)."""
    n = max(1, int(np.ceil(np.linalg.norm(b - a) / step)))
    for i in range(n + 1):
        yield a + (i / n) * (b - a)


def _seen(need: float) -> float:
    """``need`` [m], a clearance the checks can see (not beyond :data:`MARGIN_M`)."""
    if need > MARGIN_M:
        raise ValueError(f"a clearance of {need} m is beyond the contact margin "
                         f"({MARGIN_M} m): pairs that far apart are not seen")
    return need


class Ramp:
    """Required clearance [m] at q: ``full``, relaxed near each (configuration, its clearance)
    endpoint to that clearance less 1 mm, growing by :data:`RAMP_M_PER_RAD` per radian away
    (never more than ``full``)."""

    def __init__(self, endpoints: list[tuple[Vec, float]], full: float) -> None:
        self.full = full
        self._near = [(np.asarray(e, dtype=float), c) for e, c in endpoints if c < full]

    def __call__(self, q: Vec) -> float:
        out = self.full
        for e, c in self._near:
            step = q - e
            out = min(out, c - 0.001 + RAMP_M_PER_RAD * math.sqrt(float(np.dot(step, step))))
        return out


def ramped(endpoints: list[tuple[Vec, float]], full: float = TRANSFER_CLEARANCE_M) -> Ramp:
    """The :class:`Ramp` of ``endpoints`` (configuration, its clearance [m]) up to ``full``."""
    return Ramp(endpoints, full)


def plan_path(
    checker: ArmChecker,
    query: Query,
    start: Vec,
    goal: Vec,
    bounds: tuple[Vec, Vec],
    time_s: float = PLAN_TIME_S,
) -> list[Vec] | None:
    """A collision-free joint-space path start -> goal (stacked per ``query.hands``) with
    RRT-Connect within ``bounds`` (lower, upper [rad]), simplified and checked again; None
    when OMPL finds none or the endpoints are invalid. The whole query aims to end within
    ``time_s`` [s] wall. The query's time and
    size are appended to ``checker.stats``."""
    t0, checks0 = time.perf_counter(), checker.checks
    path: list[Vec] | None = None
    why = ""
    if checker.segment_valid(start, goal, query):  # the straight segment is free: done
        path = [start, goal]
    elif _endpoint_ok(checker, query, start) and _endpoint_ok(checker, query, goal):
        # the whole query within time_s: what the checks took so far, and a share kept for
        # the shortcut and OMPL's own overrun (queries ran 5-60 ms over their limit)
        left = (time_s - (time.perf_counter() - t0)) * (1.0 - FINISH_SHARE)
        path = _ompl(checker, query, start, goal, bounds, max(0.0, left))
        if path is not None:
            path = shortcut(checker, query, path)
        else:
            why = "time"
    else:
        why = "endpoint"
    checker.stats.append(MotionStats(time.perf_counter() - t0, len(start),
                                     len(path) if path else 0, path is not None,
                                     checker.checks - checks0, why))
    return path


def _endpoint_ok(checker: ArmChecker, query: Query, q: Vec) -> bool:
    return checker.valid(checker.split(query.hands, q), query, q)


@functools.lru_cache(maxsize=1)
def _seed_once() -> None:
    """Seed OMPL once per process (reproducible runs: its generators derive from the seed)."""
    from ompl import util as ou

    ou.RNG.setSeed(RNG_SEED)


def shortcut(checker: ArmChecker, query: Query, path: list[Vec]) -> list[Vec]:
    """``path`` with waypoints dropped greedily: from each kept waypoint straight to the
    furthest later one the segment to which is collision-free."""
    out, i = [path[0]], 0
    while i < len(path) - 1:
        j = len(path) - 1
        while j > i + 1 and not checker.segment_valid(path[i], path[j], query):
            j -= 1
        out.append(path[j])
        i = j
    return out


def path_cost(path: list[Vec]) -> float:
    """Rank of a path by its duration, roughly: per segment, the slowest joint's
    distance over 1.5 rad/s plus a start-stop allowance [s]."""
    return sum(float(np.abs(b - a).max()) / 1.5 + 0.5 for a, b in zip(path, path[1:], strict=False))


def _ompl(
    checker: ArmChecker, query: Query, start: Vec, goal: Vec, bounds: tuple[Vec, Vec],
    time_s: float,
) -> list[Vec] | None:
    """RRT-Connect until :data:`ATTEMPTS` paths are found (each simplified and checked at
    the fine step), the fastest kept; the attempts stop once ``time_s`` is used up (or,
    with a path, one is near enough the straight segment's cost). Until a first path passes
    the fine check, one that fails it uses up no attempt: RRT-Connect starts again while
    time is left."""
    from ompl import base as ob
    from ompl import geometric as og
    from ompl import util as ou

    ou.setLogLevel(ou.LOG_NONE)
    _seed_once()
    n = len(start)
    space = ob.RealVectorStateSpace(n)
    box = ob.RealVectorBounds(n)
    for i in range(n):
        box.setLow(i, float(bounds[0][i]))
        box.setHigh(i, float(bounds[1][i]))
    space.setBounds(box)
    setup = og.SimpleSetup(space)

    def valid(state: object) -> bool:
        q = np.array([state[i] for i in range(n)])  # type: ignore[index]
        return bool(checker.valid(checker.split(query.hands, q), query, q))

    setup.setStateValidityChecker(valid)
    s, g = space.allocState(), space.allocState()
    for i in range(n):
        s[i], g[i] = float(start[i]), float(goal[i])
    setup.setStartAndGoalStates(s, g)
    si = setup.getSpaceInformation()
    si.setStateValidityCheckingResolution(OMPL_STEP_RAD / space.getMaximumExtent())
    planner = og.RRTConnect(si)
    planner.setRange(RANGE_RAD)
    setup.setPlanner(planner)
    best: list[Vec] | None = None
    t_end = time.perf_counter() + time_s
    found = 0
    while found < ATTEMPTS:
        left = t_end - time.perf_counter()
        if left <= 0:
            break
        setup.clear()
        solved = setup.solve(left if best is None else min(left, ATTEMPT_S))
        if not bool(solved) or not setup.haveExactSolutionPath():
            found += best is not None  # a later attempt found nothing in its time
            continue
        setup.simplifySolution(SIMPLIFY_TIME_S)
        p = setup.getSolutionPath()
        path = [np.array([p.getState(k)[i] for i in range(n)]) for k in range(p.getStateCount())]
        path[0], path[-1] = start.copy(), goal.copy()
        passes = checker.path_valid(path, query)
        found += best is not None or passes  # no attempt used up until a first path passes
        if not passes:
            continue
        if best is None or path_cost(path) < path_cost(best):
            best = path
        if path_cost(best) <= GOOD_ENOUGH * path_cost([start, goal]):
            break
    return best
