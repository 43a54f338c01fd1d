"""Settings of the closed loop (frozen dataclasses: no module-level mutable settings)."""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from artiplan.encoding import EncodingOptions
from artiplan.model import PLANES


@dataclass(frozen=True)
class Intervention:
    """A scripted human intervention: at ``time`` [s, simulated] turn ``link`` by ``delta_deg``
    [deg] on ``plane`` (the links tip-ward are carried), as :meth:`World.push` does.

    With ``fraction`` set, ``time`` is ignored and the push happens at that fraction of the
    first plan's makespan (so it always falls inside the execution).
    """

    time: float
    link: str
    plane: str
    delta_deg: float
    fraction: float | None = None

    def __post_init__(self) -> None:
        if self.plane not in PLANES:
            raise ValueError(f"unknown plane {self.plane!r}; valid: {', '.join(PLANES)}")
        if self.time < 0:
            raise ValueError("intervention time must be >= 0")


@dataclass(frozen=True)
class LoopConfig:
    """How the loop plans, monitors and re-plans.

    Attributes:
        encoding: PDDL+ model and its parameters (speeds, gravity, reach time).
        goal_style: ``window`` or ``threshold`` (see :func:`artiplan.encoding.make_goal`).
        plan_tolerance_deg: Half-width [deg] of the planning goal's windows (tighter than the
            acceptance tolerance, leaving a margin for execution error).
        accept_deg: Success: every goal link within this direction error [deg] of the target
            in the perceived state at the final happening.
        threshold_deg: The monitor fires when a goal link's direction error against the
            prediction passes this [deg].
        other_threshold_deg: The same for the other links (None: ``threshold_deg``); wider by
            default because the PDDL+ model mispredicts carried links by design.
        monitor_dt: Perception and monitoring period between happenings [s, simulated].
        max_replans: At most this many re-plans a run (None: :meth:`budget` of the chain's
            length, 5 up to 4 links, 8 on 6).
        replan: Re-plan at all (False: execute the first plan open-loop).
        plan_time_limit: Wall-clock limit of one planner call [s].
        planner: The planner the loop calls (``artiplan`` in-process; ``enhsp``, ``kairos``:
            :func:`artiplan.backends.get_planner`).
        advance_latency: Let the world run on (hands released) for the measured planning
            latency before a new plan starts, instead of freezing simulated time while planning.
        settle_s: Simulated time the world runs before the first percept [s].
        interventions: Scripted pushes.
        max_time: Simulated-time budget of the whole run [s].
        fallback_model: After a plan ends without the goal, plan with this model from then on
            (None: keep the model). A short active approach (NG) does not rely on a gravity
            prediction the physics has just contradicted (plans that wait for gravity to bring
            a link into its window are the brittle ones).
        fallback_after: Also switch to the fallback model from this many re-plans on, whatever
            their reasons (a model the physics keeps contradicting is not worth re-using).
        fallback_scope: ``run``: the switches above last for the rest of the run. ``plan``:
            the fallback model makes only the plans the model in use finds none for (around
            refusals, say); the next plan is the model's own again, and neither a missed goal
            nor the re-plan count switches models.
        use_ontology: Go through the world's OWL knowledge base: each re-plan's percept is
            recorded in it and the initial state (and the target) read back by a query, as the
            paper's architecture does (False: straight from the percept).
        monitor_tip_links: Also monitor links tip-ward of every goal link. They cannot move a
            goal link in the model, and the model mispredicts carried links, so by default
            their errors are logged but do not trigger re-plans.
        monitor_ahead: Let pass a link's offset on a plane that a turn still ahead in the plan
            rotates it on, up to what that turn's alignment takes (``execution.regrasp``:
            ``aligned_ahead``): execution corrects it, a re-plan is not needed for it.
        max_turn_deg: Plans are sought first with no turn longer than this [deg]
            (``EncodingOptions.max_turn_deg``), for at most ``capped_time_limit`` [s] wall;
            if none is found, without the cap (None: never capped). A planner that may turn as
            long as it likes used turns of up to 3 revolutions as clocks, waiting for gravity
            to bring carried goal links into their windows.
        capped_time_limit: See ``max_turn_deg``.
        aim: After a plan ends without the goal, the next plans of the same model aim the goal
            links' vertical-plane windows off the target by what that plan missed by
            (``execution.aim``; on 6 links NG plans left goal links 4-5 deg low, sagging).
        free_carry_replans: A re-plan because a link that a vertical turn carried is off the
            prediction at the first percept after the turn stops spends no re-plan budget, up
            to this many a run (0: it does). The models' carry rule mispredicts such links by
            design (on 6 links by 46-142 deg after long turns, 8 of 10 failed runs spent
            budget so), so planning again from where they are is part of executing a plan
            of that model, as a receding horizon would, not a sign the execution went wrong.
            The same for a plan that ends short only on goal links such a turn carried (no
            percept judged them after it stopped: the plan ended with it).
        free_refusals: Plans made again after a refused rotation spend no re-plan budget, up
            to this many a run (``execution.refusals.MAX_FREE``; 0: they all do).
        stall_deg: When the monitor fires on the link a turn in progress rotates, lagging
            that turn by at least this much [deg] along its plane, the turn is taken as
            refused from there (``execution.refusals``): the link does not follow the hand
            (it meets the chain or the scene, or the arms stopped it short for good), so the
            next plans turn it so only once its pair has moved, and planning again is free
            of the budget like any refusal. Without this the same turn was planned again
            and stalled at the same angle (measured: one 6-link task spent 3 of its 5
            re-plans on L5 stalling at 111 deg). None (the default): such a lag is a re-plan
            like any. Off because measured worse: with 6.0, 20 seeded 6-link Baxter tasks
            reached at most 12/20 (17 of them run: 9 reached; 0-3 stalls a task, most
            failures elsewhere) where the same code without it reached 14-16/20.
        align_ahead: A rotated link found ahead of its turn at the grasp is aligned on as
            far as the turn has left (:func:`artiplan.execution.regrasp.align`), not only
            MAX_LOST_DEG, as the monitor let that offset pass before the grasp. False (the
            default): up to MAX_LOST_DEG either way. Off because not shown better: on 4
            links it took the re-plan that followed such grasps of task 13 but not the
            task (19/20 plain, 18/20 with the push, as without it); on 6 links it acted 10
            times in 20 tasks, 9 of them with no re-plan within 10 s, and the run reached
            14/20 where the same code without it reached 16-17/20 (session 24,
            RESULTS.md; runs differ by 1-3 tasks on unchanged code).
        compensate_approach: With hands that approach their grasps in simulated time and a
            ``reach_time`` in the encoding: plans start with the hands away (the first grasp
            waits ``reach_time`` too), each start is dispatched ``reach_time`` early, and the
            prediction is shifted by the remaining lateness (False: dispatch at the planned
            time, the approach delays the action).
    """

    encoding: EncodingOptions = field(default_factory=lambda: EncodingOptions("ucm", speed_g=0.5))
    goal_style: str = "window"
    plan_tolerance_deg: float = 1.5
    accept_deg: float = 5.0
    threshold_deg: float = 8.0
    other_threshold_deg: float | None = 45.0
    monitor_dt: float = 0.25
    max_replans: int | None = None
    replan: bool = True
    plan_time_limit: float = 60.0
    planner: str = "artiplan"
    advance_latency: bool = False
    settle_s: float = 0.0
    interventions: tuple[Intervention, ...] = ()
    max_time: float = 600.0
    fallback_model: str | None = "ng"
    fallback_after: int = 2
    fallback_scope: str = "run"
    use_ontology: bool = True
    monitor_tip_links: bool = False
    compensate_approach: bool = True
    monitor_ahead: bool = True
    max_turn_deg: float | None = 180.0
    capped_time_limit: float = 10.0
    aim: bool = True
    free_carry_replans: int = 10
    free_refusals: int = 40
    stall_deg: float | None = None
    align_ahead: bool = False

    def __post_init__(self) -> None:
        if self.threshold_deg <= 0 or self.accept_deg <= 0 or self.plan_tolerance_deg <= 0:
            raise ValueError("threshold, acceptance and planning tolerances must be positive")
        if self.stall_deg is not None and self.stall_deg <= 0:
            raise ValueError("stall_deg must be positive (None: off)")
        if self.monitor_dt <= 0:
            raise ValueError("monitor_dt must be positive")
        if self.fallback_scope not in ("run", "plan"):
            raise ValueError(f"unknown fallback_scope {self.fallback_scope!r}; valid: run, plan")
        if (self.max_replans is not None and self.max_replans < 0) \
                or self.free_carry_replans < 0 or self.free_refusals < 0:
            raise ValueError("max_replans, free_carry_replans and free_refusals must be >= 0")

    def budget(self, n_links: int) -> int:
        """Re-plans a run may spend on a chain of ``n_links`` links: ``max_replans``, or by
        default ``max(5, ceil(1.25 n))``. Longer chains carry more links through each turn and
        the monitor fires more often just past its threshold: on 6 links with Baxter, 5 re-plans
        reached 14-16/20 seeded tasks, 8 reached 16/20 and 17/20 (session 23, RESULTS.md)."""
        if self.max_replans is not None:
            return self.max_replans
        return max(5, math.ceil(1.25 * n_links))
