"""Which arm holds, which rotates, and the grasp pair: chosen only if it is collision-free
(mixin of :class:`artiplan.world.baxter.BaxterHands`, on top of the candidates of
:mod:`artiplan.world.grasping`).

Pairs of candidates are tried in score order (reach, joint-limit room over the turn,
nearness, the arms' clearance to each other at the grasps). With ``avoid_collisions`` a pair
is taken only when, in the planning copy of the scene (:class:`artiplan.world.motion.ArmChecker`,
every link where it is now):

- both final straight legs (pre-grasp pose to grasp, the arms moving together) and the grasps
  keep :data:`~artiplan.world.motion.NEAR_CLEARANCE_M` from the torso, the other arm, the
  scene and every link but the one each gripper closes on (when the arms approach at all);
- at every :data:`~artiplan.world.turning.STEP_DEG` of the planned turn (the rotated link and
  the links it carries turned with it, the rotating arm at its tracking IK solution, the
  holding arm at its grasp) both arms keep that clearance too.

If no pair passes, :class:`NotExecutableError` says why; the world then reports the action as
failed and the closed loop re-plans around that pair (as around a grasp out of reach).
"""

from __future__ import annotations

import mujoco
import numpy as np

from artiplan.world.grasping import (
    INFEASIBLE,
    KEEP,
    LIMIT_MARGIN,
    REACH_TOLERANCE,
    SWEEP_WEIGHT,
    TIERS,
    TRACK_NULLSPACE_GAIN,
    Candidate,
    GraspChoice,
)
from artiplan.world.motion import CHECK_STEP_RAD, NEAR_CLEARANCE_M, ArmChecker, Query
from artiplan.world.rotations import Vec, quat_to_mat
from artiplan.world.turning import Turn, turned_joint, turned_pose

#: Pre-grasp pose: this far [m] back along the approach axis from the grasp; the final leg
#: goes straight in through PREGRASP_STEPS IK waypoints.
PREGRASP_M = 0.07
PREGRASP_STEPS = 3
#: The final leg is one joint-space segment when that keeps the hand this near [m] the line.
LEG_TOLERANCE_M = 0.003
#: An approach first backs every opened hand whose grasp point is nearer than RETREAT_NEAR
#: [m] to a link APPROACH_RETREAT_M [m] along its approach axis.
RETREAT_NEAR = 0.06
APPROACH_RETREAT_M = 0.06
#: Candidates per hand tried in pairs when collisions are checked, and at most this many
#: pairs checked per pairing of hands.
KEEP_CHECKED = 4
MAX_PAIRS = 16
#: IK iterations per turned pose (warm-started from the previous degree).
TURN_IK_ITERATIONS = 30
#: Score per share of the planned turn the rotating hand cannot follow (a whole turn missed
#: weighs like a 1 cm collision-margin shortfall times 50: following comes first).
SHORT_WEIGHT = 2.0
#: A pair whose turn is collision-free for less than this [deg] is not taken (the world
#: stops a turn where its collision-free part ends: the loop sees it and re-plans).
MIN_TURN_DEG = 5.0
#: A turned pose with a joint nearer than this [rad] to its limit is not followed (the servo
#: fights the limit; e1 there is a straight, singular elbow: measured, the tracking diverged).
ROOM_MIN = 0.1


#: A link no hand can grasp now in a role: (link, ``hold`` or ``turn``, the 1-based indices
#: of what its grasps met: object links, 1 for the fixed scene and the clamped L1).
Blocked = tuple[str, str, frozenset[int]]


class NotExecutableError(RuntimeError):
    """No grasp pair lets the arms do the action without a collision (or no collision-free
    motion to it was found).

    Attributes:
        blocked: The action's links that no hand can grasp now in their role, whatever the
            turn (every reachable grasp of both hands meets something at the grasp or on its
            final leg), with what they meet: no other action grasping them that way can be
            done before one of them has moved relative to the other (read by the execution
            loop, which does not import the world).
    """

    def __init__(self, message: str, blocked: tuple[Blocked, ...] = ()) -> None:
        super().__init__(message)
        self.blocked = blocked


class NoArmMotionError(NotExecutableError):
    """The grasps were chosen, but no collision-free arm motion to them was found from where
    the arms are: the arms may be caught in the chain, and from elsewhere (home) it may work."""

    #: Read by the execution loop (which does not import the world): a way out may exist.
    arms_caught = True


def along(path: list[Vec], s: float) -> Vec:
    """Point of the piecewise-linear ``path`` (equal shares) at ``s`` in [0, 1]."""
    m = len(path) - 1
    if m == 0:
        return path[0].copy()
    k = min(int(s * m), m - 1)
    return path[k] + (s * m - k) * (path[k + 1] - path[k])


class PairChoice(GraspChoice):
    """Mixin: the holding/rotating pair of grasps, checked for collisions."""

    checker: ArmChecker
    approach_s: float
    #: Per hand, the joint angles [rad] of its home pose (idle arms go there).
    home: dict[str, Vec]
    turn_limit: tuple[float, str] | None = None
    _target_q: dict[str, Vec]
    _held: dict[str, str | None]
    _link_index: dict[str, int]
    #: The other geom of the last failed check (:meth:`_why`).
    _hit: int = -1
    #: Per (hand, link) of the current :meth:`assign`: None when some grasp passed its own
    #: grasp and final-leg checks, else the indices of what they met (:data:`Blocked`).
    _static: dict[tuple[str, str], frozenset[int] | None]

    # -- what the arms do: turned poses and the final leg ----------------------------------
    def _turn_path(self, c: Candidate, turn: Turn) -> None:
        """The rotating arm's joint angles at every step of ``turn`` (tracking-like IK, each
        from the previous) as far as the hand can follow it, into ``c.sweep``;
        ``c.sweep_score``: SHORT_WEIGHT per share of the turn it cannot follow (out of reach,
        or within ROOM_MIN of a joint limit: an arm at a limit drags or loses the link; the
        loop sees that and re-plans), plus the room missing to a joint limit at the
        tightest step."""
        q, room = c.q, np.inf
        path: list[Vec] = []
        steps = turn.steps()
        for deg in steps:
            pos, quat = turned_pose(turn, deg, c.pos, c.quat)
            q = self.solve_ik(c.hand, pos, quat, iterations=TURN_IK_ITERATIONS, start=q,
                              nullspace=10 * TRACK_NULLSPACE_GAIN)
            here = self.room(c.hand, q)
            if self.ik_miss(c.hand, pos, quat) > REACH_TOLERANCE or here < ROOM_MIN:
                break
            path.append(q)
            room = min(room, here)
        c.sweep = path
        short = 1.0 - len(path) / len(steps)
        c.sweep_score = SHORT_WEIGHT * short
        if path:
            c.sweep_score += SWEEP_WEIGHT * 4.0 * max(0.0, LIMIT_MARGIN - float(room))

    def _leg(self, c: Candidate) -> list[Vec]:
        """Joint angles [rad] from the pre-grasp pose to the grasp ``c`` (cached in ``c.leg``):
        IK waypoints on the straight line along the hand's approach axis, solved backwards
        from ``c.q`` so they stay on its branch; ``[c.q, c.q]`` if the pre-grasp pose is out
        of reach (the arm then goes to the grasp itself)."""
        if c.leg:
            return c.leg
        axis = quat_to_mat(c.quat)[:, 2]
        path, q = [c.q], c.q
        for i in range(1, PREGRASP_STEPS + 1):
            pos = c.pos - (i / PREGRASP_STEPS) * PREGRASP_M * axis
            q = self.solve_ik(c.hand, pos, c.quat, iterations=100, start=q)
            if self.ik_miss(c.hand, pos, c.quat) > REACH_TOLERANCE:
                c.leg = [c.q, c.q]
                return c.leg
            path.insert(0, q)
        # One joint-space segment when it keeps the hand within LEG_TOLERANCE_M of the line
        # (a rest-to-rest trajectory stops at every waypoint).
        d = self.ik_data
        straight = True
        for i in range(1, PREGRASP_STEPS):
            s = i / PREGRASP_STEPS
            d.qpos[self._q[c.hand]] = path[0] + s * (path[-1] - path[0])
            mujoco.mj_kinematics(self.model, d)
            target = c.pos - (1.0 - s) * PREGRASP_M * axis
            straight &= float(np.linalg.norm(d.xpos[self._hand[c.hand]] - target)) < LEG_TOLERANCE_M
        c.leg = [path[0], path[-1]] if straight else path
        return c.leg

    def parked(self, moving: tuple[str, ...]) -> dict[str, Vec]:
        """Where the arms not in ``moving`` will be during the action: home when the arms
        approach (:meth:`idle_goals`), else where they are commanded now."""
        out = {h: self._target_q[h].copy() for h in self.names if h not in moving}
        if self.approach_s > 0:
            out.update(self.idle_goals(moving, out))
        return out

    def idle_goals(self, moving: tuple[str, ...], now: dict[str, Vec]) -> dict[str, Vec]:
        """Arms not in ``moving`` that are away from home (``now``: their joint angles) go
        home, out of the object's way: {hand: home}."""
        return {h: self.home[h].copy() for h in self.names
                if h not in moving and float(np.abs(now[h] - self.home[h]).max()) > 0.05}

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

    # -- collision checks of a pair ---------------------------------------------------------
    def grip_pairs(self, grips: dict[str, str]) -> frozenset[tuple[int, int]]:
        """Geom pairs a gripper may touch: each hand's gripper and the link it grasps."""
        out = set()
        for h, link in grips.items():
            lg = self.checker.links[link]
            out |= {(min(int(g), lg), max(int(g), lg)) for g in self.checker.gripper[h]}
        return frozenset(out)

    def _free(
        self, cands: list[Candidate], rot: Candidate | None, turn: Turn | None, pairs: str
    ) -> tuple[str, float]:
        """('' or why not, how far [deg] the turn is collision-free): ``cands`` (one or both
        arms' candidates; ``rot`` the rotating one) checked as the module docstring says.
        ``pairs``: ``solo`` (everything but the other arm), ``arms`` (only the arms against
        each other) or ``all``. A collision at the grasp or on the final leg: -1; a turn
        collision-free to its end (or no turn): the turn's extent (inf)."""
        moving = tuple(c.hand for c in cands)
        chk = self.checker
        chk.sync(self.data.qpos)
        chk.set_arms(self.parked(moving))
        hands = moving if pairs == "solo" else self.names
        query = Query(hands, self.grip_pairs({c.hand: c.link for c in cands}),
                      NEAR_CLEARANCE_M, pairs)
        q_grasp = {c.hand: c.q for c in cands}
        why = self._why(chk, q_grasp, query)
        if why:
            return f"at the grasp ({why})", -1.0
        if self.approach_s > 0:
            legs = {c.hand: self._leg(c) for c in cands}
            span = max(float(np.linalg.norm(leg[-1] - leg[0])) for leg in legs.values())
            n = max(2, int(np.ceil(span / CHECK_STEP_RAD)))
            for i in range(n + 1):
                why = self._why(chk, {h: along(leg, i / n) for h, leg in legs.items()}, query)
                if why:
                    return f"final leg {i}/{n} in contact ({why})", -1.0
        if turn is None:
            return "", np.inf
        steps = turn.steps()
        followed = steps[: len(rot.sweep)] if rot is not None else steps
        base = chk.data.qpos.copy()
        safe = 0.0
        try:
            for i, deg in enumerate(followed):
                adr, quat = turned_joint(self.model, self.data, turn, deg)
                chk.data.qpos[adr : adr + 4] = quat
                q = {**q_grasp, **({rot.hand: rot.sweep[i]} if rot is not None else {})}
                why = self._why(chk, q, query)
                if why:
                    return f"turned {deg:.0f} deg ({why})", safe
                safe = deg
        finally:
            chk.data.qpos[:] = base
        if len(followed) < len(steps):
            assert rot is not None
            return f"the {rot.hand} arm follows the turn only {safe:.0f} deg", safe
        return "", turn.degrees

    def _why(self, chk: ArmChecker, q: dict[str, Vec], query: Query) -> str:
        """'' when ``q`` keeps the query's clearance, else the nearest pair and its clearance
        (the other geom kept in ``_hit``)."""
        if chk.valid(q, query):
            return ""
        clear, arm, self._hit = chk.nearest(q, query)
        pair = f"{chk.model.geom(arm).name}~{chk.model.geom(self._hit).name}" if arm >= 0 else ""
        return f"{pair} {clear * 1000:.0f} mm"

    def _met(self, geom: int) -> int:
        """1-based index of the object link ``geom`` belongs to; 1 (fixed, as the clamped
        L1) for the scene, the torso or the other arm."""
        for link, g in self.checker.links.items():
            if g == geom:
                return self._link_index[link]
        return 1

    def _pair_score(self, hold: Candidate | None, rot: Candidate, q_hold: Vec) -> float:
        """Order of the pairs: both candidates' scores plus the arms' clearance to each other
        at the grasps (within CLEARANCE_MARGIN)."""
        from artiplan.world.grasping import CLEARANCE_MARGIN, CLEARANCE_WEIGHT

        score = rot.total + (hold.total if hold is not None else 0.0)
        if not self.avoid_collisions:
            return score
        self.checker.sync(self.data.qpos)
        q = {self._other(rot.hand): q_hold, rot.hand: rot.q}
        grips = {rot.hand: rot.link, **({hold.hand: hold.link} if hold is not None else {})}
        clear, _ = self.checker.clearance(q, Query((rot.hand,), self.grip_pairs(grips)))
        return score + CLEARANCE_WEIGHT * max(0.0, CLEARANCE_MARGIN - clear)

    # -- choosing -----------------------------------------------------------------------------
    def _free_best(
        self, hand: str, link: str, keep: int, turn: Turn | None, rotating: bool,
        tiers: int = 1,
    ) -> tuple[list[Candidate], str]:
        """Up to ``keep`` candidates of ``hand`` on ``link`` that are collision-free on their
        own (the other arm aside), best total score first, and why the first one examined was
        not (''). The rotating hand's turn path is solved for each examined candidate (its
        sweep score only adds, so they are examined in score order until none can enter the
        best ``keep``). Without ``avoid_collisions``: the best one, unchecked."""
        first, examined = "", 0
        met: frozenset[int] | None = frozenset()
        for tier in range(1, TIERS + 1):
            if tier < tiers:
                continue  # the pair needs the wider set: start with it
            cands = self.candidates(hand, link, tier)
            reachable = [c for c in cands if c.reachable]
            if not self.avoid_collisions or not reachable:
                if tier < TIERS and self.avoid_collisions:
                    continue  # none reaches: maybe a tilted or shallow grasp does
                best = min(cands, key=lambda c: c.total)
                if rotating and best.reachable and not best.sweep:
                    self._sweep(best)
                return [best], ""
            done: list[Candidate] = []
            for c in reachable:
                if len(done) >= keep and c.score >= sorted(d.total for d in done)[keep - 1]:
                    break
                if c.solo is None or c.turn_of is not turn:
                    self._check_alone(c, turn, rotating)
                    examined += 1
                if c.solo:
                    first = first or c.solo
                if met is not None:
                    met = met | {self._met(c.hit)} if c.safe < 0 and c.hit >= 0 else None
                if c.safe < min_turn(turn):
                    continue
                done.append(c)
            if done:
                self._static[(hand, link)] = None
                return sorted(done, key=lambda c: c.total)[:keep], ""
        before = self._static.get((hand, link), frozenset())
        self._static[(hand, link)] = None if before is None or met is None else before | met
        first = (f"none of the {examined} reachable grasps of {link} by the {hand} hand is "
                 f"free, the best: {first}")
        return [], first

    def _check_alone(self, c: Candidate, turn: Turn | None, rotating: bool) -> None:
        """``c.solo``: why ``c`` collides on its own ('' if it does not): grasp and final leg
        first (cheap), then the turn (the rotating hand's turn path is solved for it)."""
        c.turn_of = turn
        c.solo, c.safe = self._free([c], None, None, "solo")
        c.hit = self._hit if c.safe < 0 else -1
        if rotating and turn is not None and not c.solo:
            self._turn_path(c, turn)
        elif rotating and turn is None and not c.sweep:
            self._sweep(c)
        if not c.solo and turn is not None:
            c.solo, c.safe = self._free([c], c if rotating else None, turn, "solo")

    def plan_pair(
        self, hold_hand: str, hold_link: str | None, rot_hand: str, rot_link: str,
        turn: Turn | None = None,
    ) -> tuple[float, Candidate | None, Candidate | None, str, float]:
        """(score, holding candidate, rotating candidate, '' or why none is free, how far
        [deg] the turn is collision-free) of the best pair; ``hold_link`` None: the holding
        arm grasps nothing (L1 is clamped). With ``avoid_collisions`` the best pair whose
        grasps and final legs are collision-free (the candidates free on their own,
        :meth:`_free_best`, then the pairs of those, the arms against each other, in score
        order): the first one free over the whole turn, else the one that gets furthest
        (SHORT_WEIGHT per share of the turn missed), if at least :func:`min_turn`;
        (inf, None, None, why, -1) when there is none."""
        out = self._plan_pair(hold_hand, hold_link, rot_hand, rot_link, turn, 1)
        full = turn.degrees if turn is not None else np.inf
        for tiers in range(2, TIERS + 1):
            # Tier 2 while no pair does the whole turn; the rarer grasps of tiers 3-5 only
            # while there is no pair at all (a part of the turn is done and re-grasped; the
            # demo spent 13% more CPU on them for the same run).
            if out[2] is not None and (out[4] >= full or tiers > 2):
                break
            again = self._plan_pair(hold_hand, hold_link, rot_hand, rot_link, turn, tiers)
            if again[2] is not None and (out[2] is None or again[0] < out[0]):
                out = again
        return out

    def _plan_pair(
        self, hold_hand: str, hold_link: str | None, rot_hand: str, rot_link: str,
        turn: Turn | None, tiers: int,
    ) -> tuple[float, Candidate | None, Candidate | None, str, float]:
        """:meth:`plan_pair` with candidates of tiers up to ``tiers``."""
        keep = KEEP_CHECKED if self.avoid_collisions else 1
        rots, why_r = self._free_best(rot_hand, rot_link, keep, turn, True, tiers)
        holds: list[Candidate | None] = [None]
        why_h = ""
        if hold_link is not None:
            holds, why_h = self._free_best(hold_hand, hold_link, keep, turn, False, tiers)  # type: ignore[assignment]
        if not rots or not holds:
            return INFEASIBLE * 10, None, None, why_r or why_h, -1.0
        pairs = []
        for h in holds:
            q_hold = h.q if h is not None else self._target_q[hold_hand]
            pairs += [(self._pair_score(h, r, q_hold), k, h, r) for k, r in enumerate(rots)]
        pairs.sort(key=lambda p: (p[0], p[1]))
        if not self.avoid_collisions or not pairs[0][3].reachable:
            return pairs[0][0], pairs[0][2], pairs[0][3], "", np.inf
        first, best = "", None
        full = turn.degrees if turn is not None else np.inf
        for score, _, h, r in pairs[:MAX_PAIRS]:
            # One arm: the idle one where it is parked (against the arm and the turned links).
            why, safe = self._free([r], r, turn, "all") if h is None else \
                self._free([h, r], r, turn, "arms")
            # The limit and its reason: the pair's, or a candidate's own if that comes first.
            for c in (r, h):
                if c is not None and c.safe < safe:
                    why, safe = c.solo or "", c.safe
            if safe >= full:
                return score, h, r, "", safe
            first = first or why
            if safe >= min_turn(turn):
                total = score + SHORT_WEIGHT * (1.0 - safe / full)
                if best is None or total < best[0]:
                    best = (total, h, r, why, safe)
        if best is not None:
            return best
        n = min(len(pairs), MAX_PAIRS)
        return INFEASIBLE * 10, None, None, f"none of {n} pairs is free, the best: {first}", -1.0

    def best_grasp(self, hand: str, link: str) -> Candidate:
        """The best candidate for ``hand`` alone, the other arm where it is now."""
        other = self._other(hand)
        q_other = self.data.qpos[self._q[other]].copy()
        if link == self._roles[1]:
            best = self.plan_pair(other, None, hand, link)[2]
            if best is not None:
                return best
        cands = self.candidates(hand, link)[: KEEP if self.avoid_collisions else 1]
        return min(cands, key=lambda c: self._pair_score(None, c, q_other))

    def assign(
        self, hold_link: str, rotate_link: str, turn: Turn | None = None
    ) -> tuple[str, str]:
        """Which arm holds and which rotates: a pairing in which both grasps reach and (with
        ``avoid_collisions``) nothing collides over ``turn`` if there is one, then the better
        score. Remembers the chosen grasps (for :meth:`approach` and :meth:`grasp`) and the
        roles (where the grasp points are). Raises :class:`NotExecutableError` when no pair
        is collision-free."""
        self._roles = (hold_link, rotate_link)
        self._static = {}
        clamped = hold_link == self._clamped  # L1: held by the fixture, not by a hand
        best: tuple[float, str, Candidate | None, str, Candidate | None, str, float] | None = None
        for hold_hand, rot_hand in (self.names, self.names[::-1]):
            s, h, r, why, safe = self.plan_pair(hold_hand, None if clamped else hold_link,
                                                rot_hand, rotate_link, turn)
            if best is None or s < best[0] or (s == best[0] and not why):
                best = (s, hold_hand, h, rot_hand, r, why, safe)
        assert best is not None
        _, hold_hand, h, rot_hand, r, why, safe = best
        if r is None:
            raise NotExecutableError(
                f"no collision-free grasps to hold {hold_link} and rotate {rotate_link}"
                f" ({why})", self._blocked(hold_link, rotate_link, clamped))
        #: How far [deg] the turn may go (None: all of it): the world stops it there.
        self.turn_limit = (safe, why) if turn is not None and safe < turn.degrees else None
        self._plan = {rot_hand: (r, self.data.time)}
        if h is not None:
            self._plan[hold_hand] = (h, self.data.time)
        return hold_hand, rot_hand


    def _blocked(self, hold_link: str, rotate_link: str, clamped: bool) -> tuple[Blocked, ...]:
        """The action's links no hand could grasp in their role in the :meth:`assign` just
        made (see :attr:`NotExecutableError.blocked`)."""
        out = []
        for link, role in ((hold_link, "hold"), (rotate_link, "turn")):
            if role == "hold" and clamped:
                continue
            met = [self._static.get((h, link)) for h in self.names]
            if all(m is not None for m in met):
                out.append((link, role, frozenset().union(*met)))  # type: ignore[arg-type]
        return tuple(out)


def min_turn(turn: Turn | None) -> float:
    """The least a turn must go collision-free [deg] for its pair to be taken: MIN_TURN_DEG
    (all of a shorter turn)."""
    if turn is None:
        return 0.0
    return min(MIN_TURN_DEG, turn.degrees)
