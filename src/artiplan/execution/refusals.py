"""Rotations the world refused, planned around (execution, not planning).

Baxter's arms refuse a rotation when no grasp pair keeps clear over the turn or no
collision-free arm motion to the grasps is found (:class:`artiplan.world.NotExecutableError`).
From nearly the same state the same start would be refused again, so the loop remembers it as
(hold link, rotated link, plane, ``increase``/``decrease``) and the next plans do not start it
before the pair has moved (``EncodingOptions.refusals``: a turn of the rotated link or of one
base-ward of it). Planning again after a refusal is part of planning (the motion planner
answering the task planner), not a re-plan after an execution that went wrong: it does not
spend the re-plan budget, up to :data:`MAX_FREE` times a run. That holds whether or not part
of the plan had moved: what moved went as predicted (else the monitor would have re-planned
first), and the refusal says nothing against the prediction. For a plan found only by
ignoring the refusals, whose first rotation may then be refused again from the same state, it
holds only when no arm motion was found: the arm-motion planner is randomised and may find
one the next time (measured: a pair refused 8 times in a row on 6 links went on the 9th); the
grasp choice is not.

A refusal can say more than "not this rotation": that a link cannot be grasped at all now in
its role (every grasp of both hands meets another link or the scene at the grasp or on its
final leg). Then no start that grasps it so is planned before it has moved relative to what
its grasps met (:func:`artiplan.encoding.problem.turns_between`), which saves one refusal per
rotation that grasps it (measured: 13 refusals of L3 in one 6-link run, its grasps meeting
L5 or L6 folded back beside it). Refusals are unlocked by a turn of at least
:data:`artiplan.encoding.domain.CLEAR_DEG` (a link no hand could grasp: of
:data:`artiplan.encoding.domain.CLEAR_FAR_DEG`), in the plans as in the loop's own record,
or, between plans, once the percepts show the chain has moved :data:`MOVED_DEG` away from
where it was refused, whatever moved it (:meth:`Refusals.settled`).
"""

from __future__ import annotations

from dataclasses import dataclass, field

from artiplan.encoding.domain import CLEAR_DEG, CLEAR_FAR_DEG
from artiplan.encoding.problem import Ungraspable, turns_between
from artiplan.execution.dispatch import Rotate
from artiplan.model import ArticulatedObject, Configuration
from artiplan.model.kinematics import relative_turn

#: Slack [deg] on the turn that unlocks refusals (a turn commanded to exactly CLEAR_DEG).
_EPS = 1e-6
#: A refused rotation: (hold link, rotated link, plane, ``increase`` or ``decrease``).
Refusal = tuple[str, str, str, str]
#: At most this many plans a run whose rotation the world refused are planned again without
#: spending the re-plan budget (the default of ``LoopConfig.free_refusals``). 12 before
#: refusals after a move were free too; 20 until session 20, when 3-4 of the 8-9 failed
#: 6-link tasks a run had used them all up (a task reached its goal after 25).
MAX_FREE = 40
#: At most this many times a run the arms go home when caught (no motion to a grasp found).
MAX_ESCAPES = 3
#: A rotation refused again from the state it was refused in (a plan that had to ignore the
#: refusals) is a dead end for the grasp choice: the hands then let go for :data:`WAIT_S`
#: and the chain settles under gravity before planning again, free of the re-plan budget at
#: most this many times a run (after that the wait spends a re-plan).
#: Replayed offline (9 such dead ends of 6-link runs, arms at home; 7 refused again at once):
#: 3 of the 7 had a free pair after 5 s (goal links moved 0-10 deg), 3 after 15 s.
MAX_WAITS = 3
#: Simulated time [s] the hands let go in a dead end (see :data:`MAX_WAITS`).
WAIT_S = 5.0
#: A refused rotation is tried again once the percepts show its rotated link turned this far
#: [deg] in the world, and a link no hand could grasp once it turned this far against some
#: link its grasps met, whatever turned them (gravity while the hands were open, a push):
#: the plans' own unlock counts only the robot's turns, and a refusal of a link's own turn
#: waits for that very turn. Measured on 4-link pushed task 20 (session 25): L2's turn,
#: refused, waited while L2 fell 49 deg in 45 s of dead-end waits, and the plans kept trying
#: the one other link, L3 (folded on L2), refused every 5 s.
MOVED_DEG = 10.0


@dataclass
class Refusals:
    """The refusals of one run and whether the last one is free of the re-plan budget.

    Attributes:
        refused: Rotations refused since their pair last moved.
        free: Whether the last failure is a refusal free of the re-plan budget.
        count: Plans made again for free so far.
        caught: Of ``refused``, those refused because no arm motion to the grasps was found
            from where the arms were (they may work once the arms are home).
        stuck: Whether the last refusal was one of those (the arms should go home first).
        relaxed: Whether the plan being executed was found only by ignoring ``refused``:
            its first rotation may be one refused from this very state.
        escapes: Times the arms went home so far.
        homeless: The last way home was not found, and nothing has turned since: from the
            same state it would not be found again (measured: 3 escapes failed within 0.03 s
            of simulated time, which left none for later).
        ungraspable: Links no hand could grasp in a role since they last moved relative to
            what their grasps met (:data:`artiplan.encoding.problem.Ungraspable`).
        waiting: The last refusal was a dead end: the hands should let go for a while
            before planning again (:data:`MAX_WAITS`).
        waits: Times the hands let go so far.
        seen: The configuration each of ``refused`` and ``ungraspable`` was first perceived
            in after its refusal (:meth:`settled`).
        max_free: Plans made again for free at most (``LoopConfig.free_refusals``).
    """

    refused: frozenset[Refusal] = frozenset()
    relaxed: bool = False
    free: bool = False
    count: int = 0
    caught: frozenset[Refusal] = frozenset()
    stuck: bool = False
    escapes: int = 0
    homeless: bool = False
    ungraspable: frozenset[Ungraspable] = frozenset()
    waiting: bool = False
    waits: int = 0
    max_free: int = MAX_FREE
    seen: dict[Refusal | Ungraspable, Configuration] = field(default_factory=dict)

    def refuse(self, step: Rotate, in_time: bool, arms_caught: bool = False,
               blocked: tuple[Ungraspable, ...] = ()) -> None:
        """The world refused ``step``; ``in_time``: the run still has time to plan again;
        ``arms_caught``: no arm motion to its grasps was found from where the arms are;
        ``blocked``: links it could not grasp in their role, whatever the turn."""
        # No arm motion found with no way home to try either (none found, or the escapes
        # used up) is a dead end too: nothing moves until time passes (measured: 27-28 such
        # refusals of one 4-link run in a row at one instant, then 3-4 re-plans spent there).
        home_left = self.escapes < MAX_ESCAPES and not self.homeless
        again = (self.relaxed and (not arms_caught or not home_left)
                 and refusal(step) in self.refused)
        self.refused = self.refused | {refusal(step)}
        self.ungraspable = self.ungraspable | set(blocked)
        self.seen.pop(refusal(step), None)  # measured again from the state refused now
        for u in blocked:
            self.seen.pop(u, None)
        # Refused again from the state it was refused in (the plan ignored the refusals): the
        # grasp choice is deterministic, so only a motion not found (randomised) may go next
        # time (measured: 20 identical grasp refusals in a row at 4.8-5.1 s of one run),
        # or the same rotation once the chain has settled a little (MAX_WAITS).
        # Past MAX_WAITS a dead end still waits, spending the budget: planning again from
        # the very state refused repeats the refusal (measured: 4 re-plans of a 6-link run
        # spent at one instant, 128.2 s, each refused again).
        self.waiting = again and in_time
        self.free = self.count < self.max_free and in_time and (
            arms_caught or not self.relaxed or (self.waiting and self.waits < MAX_WAITS))
        if arms_caught:
            self.caught = self.caught | {refusal(step)}
        self.stuck = arms_caught and home_left

    def escaped(self, moved: bool) -> None:
        """The arms were sent home (``moved``: they went): the rotations refused for want of
        an arm motion are tried again."""
        self.stuck = False
        self.escapes += 1
        self.homeless = not moved
        if moved:
            self.refused = self.refused - self.caught
            self.caught = frozenset()

    def turned(self, step: Rotate, obj: ArticulatedObject, deg: float) -> None:
        """``step`` turned its link by ``deg`` [deg]: from CLEAR_DEG on, the pairs from its
        rotated link on have moved; from CLEAR_FAR_DEG on, also the links it separated from
        what their grasps met (as the plans' ``turned-enough`` and ``turned-far`` have it)."""
        if deg < CLEAR_DEG - _EPS:
            return
        j = obj.index(step.turn)
        self.homeless = False
        self.refused = frozenset(r for r in self.refused if obj.index(r[1]) < j)
        self.caught = self.caught & self.refused
        if deg >= CLEAR_FAR_DEG - _EPS:
            self.ungraspable = frozenset(u for u in self.ungraspable
                                         if j not in turns_between(obj.index(u[0]), u[2]))

    def settled(self, conf: Configuration,
                obj: ArticulatedObject) -> tuple[list[Refusal], list[Ungraspable]]:
        """Forget what the percepts show has moved :data:`MOVED_DEG` or more since the first
        configuration perceived after its refusal (``conf`` is that one for those refused
        since the last call): a refused rotation whose rotated link has turned in the world,
        a link no hand could grasp that has turned against some link its grasps met (as a
        turn between them unlocks it in the plans, :func:`turns_between`).
        Returns those forgotten."""
        pairs = []
        for r in sorted(self.refused):
            then = self.seen.setdefault(r, conf)
            if relative_turn(then, conf, obj.index(r[1]), 1) >= MOVED_DEG:
                pairs.append(r)
        links = []
        for u in sorted(self.ungraspable, key=lambda u: (u[0], u[1], sorted(u[2]))):
            then = self.seen.setdefault(u, conf)
            x = obj.index(u[0])
            if max(relative_turn(then, conf, x, m) for m in u[2]) >= MOVED_DEG:
                links.append(u)
        self.refused = self.refused - set(pairs)
        self.caught = self.caught & self.refused
        self.ungraspable = self.ungraspable - set(links)
        self.seen = {k: c for k, c in self.seen.items()
                     if k in self.refused or k in self.ungraspable}
        return pairs, links


def refusal(step: Rotate) -> Refusal:
    """``step`` as a refused rotation (see :func:`artiplan.encoding.problem_pddl`)."""
    return (step.hold, step.turn, step.plane, "increase" if step.direction > 0 else "decrease")


def describe(r: Refusal) -> str:
    """The refused rotation as its start action, e.g. ``(start-increase L2 L3 z-axis)``."""
    hold, turn, plane, sign = r
    return f"(start-{sign} {hold} {turn} {plane})"
