"""How the loop carries out a planned turn: aligned on the link when it starts, resumed by a
re-grasp when the arms had to stop it short (execution, not planning).

Every turn ends where the plan says on its plane: when the grasp is made (the hands were away,
gravity acted, the arms' approach took its time), the rotated link is perceived and the plan's
clock shifted by how far it is behind (or ahead of) the prediction along the turn, divided by
the turn's speed, so the plan's stop comes that much later (earlier). The monitor then compares
with a prediction that starts where the link is (the other plane's offset is the next turn's
to absorb, as it is aligned in its turn): ahead, the shifted plan is already there; behind,
the shifted plan would still be in the release before the turn, so the link is predicted
where it was seen, the difference fading out as the turn catches the plan up (:func:`align`).

A planned rotation can be longer than one grasp pair can turn without a collision or without
losing the link (Baxter's arms: the fixture, the torso, a neighbouring link, the rotating arm's
reach; :attr:`artiplan.world.scene.World.turn_limit`). The world then stops the turn where its
collision-free part ends. Rather than wait for the monitor to see the link stop and re-plan
(one of the loop's few re-plans per stretch of a turn), the loop re-grasps when the turn's
command stops (:attr:`World.turn_ends`): both hands let go, the arms choose a pair for the rest
of the turn from where the chain is now, approach, and the rotation goes on. The plan's clock
waits meanwhile: the prediction is shifted by the re-grasp's duration, and by the part of the
turn the link lost while it was released (gravity), so the plan's stop still ends the turn
where the plan said. A re-grasp that finds no way is an action failure (the loop re-plans
around the pair, as when a start is refused).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

from artiplan.execution.dispatch import Rotate
from artiplan.execution.predict import Prediction
from artiplan.model import HORIZONTAL_PLANE, VERTICAL_PLANE, Configuration
from artiplan.model.angles import signed_delta_deg

if TYPE_CHECKING:
    from artiplan.world import World

#: A rotation is resumed at most this many times (each re-grasp costs an approach, 2-5 s
#: simulated); after that the turn stays stopped and the monitor has the say.
MAX_REGRASPS = 3
#: ... and only when at least this much [deg] of the planned turn remains (a planning
#: window is 1.5 deg wide either way).
MIN_REMAINING_DEG = 1.0
#: A turn is aligned on its link for at most this much [deg of the turn] (the link behind or
#: ahead of the plan: released, it fell; carried by a vertical turn, it went elsewhere than the
#: model's rigid carry says); more than that is left to the monitor (a push, a fall, a wrong
#: cover). Tried: 45 deg (19 of 105 monitor re-plans of two 6-link Baxter runs had every
#: goal-link offset within it, on a plane a later turn aligned): 1 of the first 6 tasks
#: reached their goals instead of 3, an offset let pass went on growing (a link falling)
#: and the re-plan came later, from a worse state.
MAX_LOST_DEG = 15.0
#: A link this near the vertical [deg] has no reliable azimuth to align a turn about the
#: vertical on.
POLE_DEG = 10.0


@dataclass(frozen=True)
class Resume:
    """A rotation ``step`` at ``speed`` [deg/s] whose command stops at world time ``due`` [s]
    before the plan's stop; ``done`` re-grasps so far."""

    step: Rotate
    speed: float
    due: float
    done: int = 0

    def remaining(self, t0: float, now: float) -> float:
        """Degrees of the planned turn left at world time ``now`` [s] with the plan started
        at ``t0`` [s] (its stop at ``t0`` + start + duration)."""
        assert self.step.duration is not None
        stop = t0 + self.step.action.time + self.step.duration
        return self.speed * (stop - now)


def resume_after(world: World, step: Rotate, speed: float, t0: float, done: int = 0
                 ) -> Resume | None:
    """The resume a rotation just dispatched (or resumed ``done`` times) needs: None when its
    turn is not limited, the plan never stops it, MAX_REGRASPS are used up, or less than
    MIN_REMAINING_DEG of it would be left at the limit."""
    due = getattr(world, "turn_ends", None)
    if due is None or step.duration is None or done >= MAX_REGRASPS:
        return None
    out = Resume(step, speed, float(due), done)
    return out if out.remaining(t0, out.due) >= MIN_REMAINING_DEG else None


def behind_deg(step: Rotate, predicted: Configuration, perceived: Configuration,
               index: int, ahead_max: float = MAX_LOST_DEG) -> float:
    """How far [deg] the rotated link (1-based ``index``) is behind ``predicted`` along
    ``step``'s turn in ``perceived`` (covers chosen near the prediction): negative when it
    is ahead, within -``ahead_max`` and MAX_LOST_DEG; 0 for a turn about the vertical of a
    link within POLE_DEG of it (its azimuth is not observable there)."""
    if step.plane == HORIZONTAL_PLANE:
        g = perceived.angle(index, VERTICAL_PLANE)
        if abs(math.sin(math.radians(g))) < math.sin(math.radians(POLE_DEG)):
            return 0.0
    behind = step.direction * signed_delta_deg(perceived.angle(index, step.plane),
                                               predicted.angle(index, step.plane))
    return min(max(behind, -ahead_max), MAX_LOST_DEG)


#: The next turn of each (1-based link index, plane) still ahead in a plan: (its direction, +1
#: or -1, and its planned extent [deg], inf when the plan never stops it).
Ahead = dict[tuple[int, str], tuple[int, float]]


def aligned_ahead(predicted: Configuration, perceived: Configuration,
                  ahead: Ahead) -> tuple[Configuration, list[str]]:
    """The prediction as the monitor judges it, and what it lets pass: for each (1-based link
    index, plane) that a turn still ahead in the plan rotates, the link's angle on that plane
    as perceived, when that turn's alignment takes the offset: behind the prediction by at
    most MAX_LOST_DEG, or ahead by less than the turn's extent (else the turn would have to
    go the other way). That turn is aligned on the link when it starts (:func:`align`: the
    plan's clock shifts so the turn ends where the plan says), so the offset does not reach
    the goal, and re-planning for it would spend a re-plan on what execution corrects anyway
    (the triangle-table idea: monitor only what the rest of the plan needs). Not about the
    vertical within POLE_DEG of it, where :func:`behind_deg` does not align."""
    theta, gamma = list(predicted.theta), list(predicted.gamma)
    notes = []
    for (index, plane), (direction, extent) in sorted(ahead.items()):
        if plane == HORIZONTAL_PLANE:
            g = perceived.angle(index, VERTICAL_PLANE)
            if abs(math.sin(math.radians(g))) < math.sin(math.radians(POLE_DEG)):
                continue
        seen = perceived.angle(index, plane)
        off = signed_delta_deg(predicted.angle(index, plane), seen)
        behind = -direction * off
        if not -(extent - MIN_REMAINING_DEG) <= behind <= MAX_LOST_DEG:
            continue
        (theta if plane == HORIZONTAL_PLANE else gamma)[index - 1] = seen
        if abs(off) >= 0.05:
            notes.append(f"L{index} {plane} {off:+.1f}")
    return Configuration(tuple(theta), tuple(gamma)), notes


def align(world: World, step: Rotate, pred: Prediction, speed: float,
          ahead_to_end: bool = False) -> float:
    """Shift the plan's clock (``pred.t0``) so the turn ``step`` starting now at ``speed``
    [deg/s] ends where the plan says on its plane; returns how far [deg] the link was behind
    the prediction (negative: ahead). A link behind is predicted where it is until it has
    caught the plan up (:meth:`Prediction.fade`; rigidly with it the links tip-ward of it on a
    turn about the vertical), so the monitor does not take the catch-up for a deviation.

    Behind and ahead are aligned up to MAX_LOST_DEG. With ``ahead_to_end``
    (``LoopConfig.align_ahead``), ahead up to what is left of the turn (to the plan's stop,
    or to the plan's end for a turn it never stops) less MIN_REMAINING_DEG, as the monitor
    let the offset pass before the grasp (:func:`aligned_ahead`): the link is held now and
    cannot run further ahead. Why: in four runs of 4-link task 13, 6 grasps of L3 found it
    15 deg or more ahead of a turn its plan never stops, and 3 of them were followed within
    7 s by a re-plan (L3 off the prediction by 8.7-10.0 deg). Off by default: see
    ``LoopConfig.align_ahead`` for what it measured."""
    now = world.time
    predicted = pred.at(now)
    seen = world.perceive(reference=predicted).configuration
    j = world.obj.index(step.turn)
    ahead_max = MAX_LOST_DEG
    if ahead_to_end:  # what is left of the turn: to the plan's stop, or to its end
        stop = (step.action.time + step.duration if step.duration is not None
                else pred.trajectory.end)
        if stop is not None:
            ahead_max = max(MAX_LOST_DEG, speed * (pred.t0 + stop - now) - MIN_REMAINING_DEG)
    behind = behind_deg(step, predicted, seen, j, ahead_max)
    pred.t0 += behind / speed
    if behind > 0.0:
        off = signed_delta_deg(pred.at(now).angle(j, step.plane), seen.angle(j, step.plane))
        off = max(-behind, min(behind, off))  # no more than the catch-up explains
        rigid = range(j, world.obj.n_links + 1) if step.plane == HORIZONTAL_PLANE else (j,)
        pred.fade(dict.fromkeys(rigid, off), step.plane, now, now + behind / speed)
    return behind
