"""The closed loop: perceive -> PDDL+ problem -> plan -> dispatch -> monitor -> re-plan.

Simulated time is the world's clock: actions are dispatched at their planned times on it.
Arms that take time to reach their grasps (Baxter with ``approach_s`` > 0) move inside the
dispatch of a ``start-*`` action. With a ``reach_time`` in the encoding (the measured one), the
plan already leaves that gap after each release (and, the hands being away, before the first
grasp): the loop dispatches each start ``reach_time`` early, so the grasp is ready at the
planned time, and shifts the prediction by whatever lateness remains.
Planning latency is measured on the wall clock and logged; with
``LoopConfig.advance_latency`` the world also runs on (hands released) for that long before the
new plan starts, else simulated time stands still while the planner thinks. The planning side
(problem, planner calls around refusals, fallback model, aim) is in :mod:`.planning`.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import asdict
from typing import TYPE_CHECKING, Any

from artiplan.backends import get_planner
from artiplan.encoding import domain_pddl, make_goal
from artiplan.execution.aim import Aim
from artiplan.execution.config import Intervention, LoopConfig
from artiplan.execution.dispatch import (
    ActionFailed,
    Rotate,
    Step,
    Stop,
    dispatch,
    plan_steps,
    rotate,
)
from artiplan.execution.monitor import Monitor, goal_errors
from artiplan.execution.planning import Planning
from artiplan.execution.predict import Prediction
from artiplan.execution.problem import canonical
from artiplan.execution.refusals import Refusals
from artiplan.execution.regrasp import (
    Ahead,
    Resume,
    align,
    aligned_ahead,
    behind_deg,
    resume_after,
)
from artiplan.execution.runlog import RunLog, conf_dict
from artiplan.model import Configuration

if TYPE_CHECKING:
    from artiplan.world import World

Progress = Callable[[str], None]
#: Wall time [s] after which a long execution prints a line even when nothing happened.
HEARTBEAT_S = 10.0
#: Called with (world, kind, label) after every percept (kind ``monitor``), action (``action``,
#: its signature), intervention and the final check; e.g. to record camera frames.
Observer = Callable[["World", str, str], None]
_EPS = 1e-6


class ClosedLoop(Planning):
    """One run of the loop on ``world`` toward ``target``; call :meth:`run`."""

    def __init__(self, world: World, target: Configuration, config: LoopConfig,
                 progress: Progress | None = None, seed: int = 0,
                 observer: Observer | None = None) -> None:
        self.world, self.obj, self.target, self.config = world, world.obj, target, config
        self._say = progress or (lambda _line: None)
        self._said = time.perf_counter()
        self._collisions_seen = 0
        self.observer = observer or (lambda _w, _k, _l: None)
        enc = config.encoding
        #: The OWL knowledge base (percepts in, initial state and target out), if used.
        self.kb: Any = None
        if config.use_ontology:
            from artiplan.world.ontology import KnowledgeBase

            self.kb = KnowledgeBase(self.obj)
            self.kb.set_goal(target, config.goal_style, seed)
            target, _, _ = self.kb.target()
            self.target = target
        # Goals on canonical covers, like the problems (see execution.problem.canonical).
        self.goal = make_goal(self.obj, canonical(target), config.goal_style, seed,
                              planes=enc.planes, tolerance=config.plan_tolerance_deg)
        self.domain = domain_pddl(self.obj, enc)
        self.monitor = Monitor(self.obj, config.threshold_deg, self.goal.links,
                               config.other_threshold_deg, config.monitor_tip_links)
        self.encoding = enc
        #: How early [s] a ``start-*`` is dispatched: the modelled reach time, when the hands
        #: really approach their grasps in simulated time (else they grasp at once: 0).
        approaching = float(getattr(world.hands, "approach_s", 0.0) or 0.0) > 0.0
        self.lead = (enc.reach_time or 0.0) if approaching and config.compensate_approach else 0.0
        self.pending = sorted(config.interventions, key=lambda i: i.time)
        self.replans = 0
        #: Rotations the world refused, planned around (:mod:`artiplan.execution.refusals`).
        self.refusals = Refusals(max_free=self.config.free_refusals)
        #: Goal windows moved by the residuals of plans that ended short (execution.aim).
        self.aim = Aim() if config.aim else None
        self._final_conf: Configuration | None = None
        self.planner = get_planner(self.config.planner)
        #: Links carried by the vertical-plane rotation in progress (see Monitor.check).
        self.carried: frozenset[str] = frozenset()
        #: Links carried by a vertical-plane rotation so far in the plan being executed.
        self.swung: frozenset[str] = frozenset()
        #: Links a vertical turn carried that no percept has judged since it stopped.
        self.unjudged: frozenset[str] = frozenset()
        #: The last re-plan reason is such a link off the prediction, free of the budget.
        self.carry_free = False
        #: Plans made again for free so (``LoopConfig.free_carry_replans``).
        self.carry_count = 0
        #: The rotation in progress when the arms stop it short (execution.regrasp).
        self.resume: Resume | None = None
        #: The next turn of each (link index, plane) still ahead in the plan being executed.
        self._ahead: Ahead = {}
        #: The turn in progress: its step, the world time it started [s], speed [deg/s].
        self._turn: tuple[Rotate, float, float] | None = None
        #: Re-grasps of the turn in progress so far (execution.regrasp.MAX_REGRASPS).
        self._regrasps = 0
        #: Turns the world stopped on impact so far (``WorldConfig.impact_stop_m``).
        self._impacts_seen = len(getattr(world, "impacts", ()))
        self.log = RunLog(
            settings={**_settings(config), "hands": world.hands.kind,
                      "physics": asdict(world.config.physics)},
            object=self.obj.to_dict(),
            initial=conf_dict(world.true_configuration()),
            target=conf_dict(target),
            goal_links=list(self.goal.links),
        )

    # -- the run --------------------------------------------------------------------------
    def run(self) -> RunLog:
        """Plan, execute, monitor and re-plan until success, failure or the re-plan budget."""
        wall0 = time.perf_counter()
        t_start = self.world.time
        motions0 = len(getattr(getattr(self.world.hands, "checker", None), "stats", []))
        self.world.run_until(self.world.time + self.config.settle_s)
        try:
            self._loop()
        except FloatingPointError as exc:  # the physics diverged: the run ends, failed
            self._diverged(str(exc))
        if not self.log.final:
            self._final_check()
        self.world.stop(release=True)
        self._record_arms(t_start, motions0)
        self.log.wall_s = round(time.perf_counter() - wall0, 4)
        return self.log

    def _loop(self) -> None:
        """Plan, execute and re-plan until the goal is reached or the budget is gone."""
        reason = "initial"
        counted = False
        while True:
            prediction = self._plan(reason, counted)
            if prediction is None:
                return
            self.refusals.free = self.carry_free = False
            outcome = self._execute(prediction)
            if outcome is None:  # plan finished: check the goal at the final happening
                if self._final_check():
                    return
                carried = self._missed_carried()
                if not (self.carry_free or self._may_replan()):
                    return
                reason = "goal not reached at the final happening"
                if self.carry_free:  # the carry rule's error, not sag nor the model's gravity
                    reason += f"; {carried} off when the vertical turn carrying it stopped"
                else:
                    self._learn_aim()
                    if self.config.fallback_scope == "run":
                        self._fall_back()
            else:
                reason = outcome
            self._turn_close()
            self.world.stop(release=True)
            self.carried = self.unjudged = frozenset()
            # A rotation the world refused: planning again without it is part of planning
            # (the motion planner answering the task planner), not a re-plan after an
            # execution the prediction got wrong (execution.refusals, free_refusals a run).
            # The same for a link the model's carry rule mispredicted (free_carry_replans).
            counted = not (self.refusals.free or self.carry_free)
            if not counted:
                if self.carry_free:
                    self.carry_count += 1
                else:
                    self.refusals.count += 1
                continue
            self.replans += 1
            if self.replans >= self.config.fallback_after and self.config.fallback_scope == "run":
                self._fall_back()

    def _missed_carried(self) -> str:
        """At a final check that missed: when every goal link off the target was carried by
        a vertical turn not judged since it stopped (or still going when the plan ended), the
        next plan is free of the budget like a carried link the monitor caught
        (``LoopConfig.free_carry_replans``; sets ``carry_free``). The links, or ''."""
        errs = self.log.final.get("goal_errors", {})
        off = sorted(lk for lk, e in errs.items() if e > self.config.accept_deg)
        judged_last = self.carried | self.unjudged
        if (off and set(off) <= judged_last
                and self.carry_count < self.config.free_carry_replans
                and self.world.time < self.config.max_time):
            self.carry_free = True
            return ", ".join(off)
        return ""

    def _turn_close(self) -> None:
        """The turn in progress (if any) ends now: the refusals it unlocks are unlocked when
        its command went far enough (to where the arms stopped it short, if they did), as
        the plans' ``turned-enough`` and ``turned-far`` rules have it."""
        if self._turn is None:
            return
        step, t0, speed = self._turn
        self._turn = None
        end = self.world.time
        stops = getattr(self.world, "turn_ends", None)
        if stops is not None:
            end = min(end, float(stops))
        self.refusals.turned(step, self.obj, speed * (end - t0))

    def _diverged(self, message: str) -> None:
        """The simulation diverged: the run fails, with what was last perceived before (the
        world's own clock may have been reset)."""
        last = self.log.samples[-1] if self.log.samples else {"time": 0.0,
                                                               "perceived": self.log.initial}
        self.log.final = {"time": last["time"], "perceived": last["perceived"],
                          "goal_errors": {}, "success": False,
                          "replans": self.replans, "error": message}
        self.log.success = False
        self.progress(f"run ended: {message}")

    def _record_arms(self, t_start: float, motions0: int) -> None:
        """Copy the arms' collisions and planned motions of this run into the log."""
        hands = self.world.hands
        contacts = getattr(hands, "contacts", None)
        if contacts is not None:
            self.log.collisions = [e.to_dict() for e in contacts.since(t_start)]
        checker = getattr(hands, "checker", None)
        if checker is not None:
            self.log.motions = [m.to_dict() for m in checker.stats[motions0:]]
        if self.log.collisions:
            deepest = max(self.log.collisions, key=lambda c: c["depth_m"])
            self.progress(f"arm collisions in the physics: {len(self.log.collisions)} (deepest "
                          f"{1000 * deepest['depth_m']:.1f} mm, {'~'.join(deepest['geoms'])} "
                          f"at t={deepest['deepest']:.2f} s)")
        elif contacts is not None:
            self.progress("arm collisions in the physics: none")

    def progress(self, line: str) -> None:
        """Print a progress line (and remember when, for :meth:`_heartbeat`)."""
        self._said = time.perf_counter()
        self._say(line)

    def _heartbeat(self, index: int, done: int, total: int) -> None:
        """A line when nothing was printed for HEARTBEAT_S of wall time (long executions),
        and one per arm collision that started since the last look."""
        contacts = getattr(self.world.hands, "contacts", None)
        if contacts is not None:
            for e in contacts.events[self._collisions_seen:]:
                self.progress(f"t={e.start:7.2f} s  arm collision: {'~'.join(e.geoms)} "
                              f"({1000 * e.depth_m:.1f} mm deep so far)")
            self._collisions_seen = len(contacts.events)
        if time.perf_counter() - self._said > HEARTBEAT_S:
            self.progress(f"t={self.world.time:7.2f} s  executing plan {index}: {done} of "
                          f"{total} actions dispatched, still monitoring")

    def _may_end_plan(self) -> bool:
        """Whether the failure just seen may end the plan: planning again is free of the
        budget (a carried link's error, a refusal: a stalled turn's too) or within it."""
        return self.carry_free or self.refusals.free or self._may_replan()

    def _may_replan(self) -> bool:
        return self.config.replan and self.replans < self.config.budget(self.obj.n_links) \
            and self.world.time < self.config.max_time

    # -- execution ------------------------------------------------------------------------
    def _execute(self, pred: Prediction) -> str | None:
        """Dispatch the plan on the world, monitoring in between. Returns a re-plan reason, or
        None when the plan ran to its end."""
        plan_ = self.current_plan
        actions = plan_steps(plan_, self.obj)  # mapped once: typed rotations, stops, observes
        span = max(plan_.makespan, plan_.end or 0.0)
        index, i = len(self.log.plans) - 1, 0
        # The world advances in physics steps (and not at all for less than half a step): a
        # time is reached when it is within half a step.
        tol = 0.5 * float(self.world.model.opt.timestep) + _EPS
        next_mon = self.world.time
        self.resume = None
        self.swung = frozenset()
        while True:
            end = pred.t0 + span  # the prediction shifts when a grasp is late
            t_act = self._due(actions[i], pred) if i < len(actions) else end
            t_int = self.pending[0].time if self.pending else float("inf")
            t_res = self.resume.due if self.resume is not None else float("inf")
            t_next = min(t_act, next_mon, t_int, t_res)
            self.world.run_until(t_next)
            now = self.world.time
            if t_int <= now + tol:
                self._intervene(self.pending.pop(0), index)
                next_mon = now  # look again at once
                continue
            self._impacted(pred, index)
            t_res = self.resume.due if self.resume is not None else float("inf")
            self._ahead = self._turns_ahead(actions[i:], pred)
            if t_res <= now + tol and (i >= len(actions) or t_act > now + tol):
                reason = self._observe(pred, index, "happening")
                if reason is not None and self._may_end_plan():
                    return reason
                failure = self._regrasp(pred, index)
                if failure is not None and self._may_end_plan():
                    return failure
                next_mon = self.world.time
                continue
            happening = i < len(actions) and t_act <= now + tol
            reason = self._observe(pred, index, "happening" if happening else "monitor")
            if reason is not None and self._may_end_plan():
                return reason
            if happening:
                while i < len(actions) and self._due(actions[i], pred) <= now + tol:
                    failure = self._dispatch(actions[i], pred, index)
                    i += 1
                    if failure is not None and (self.refusals.free or self._may_replan()):
                        return failure
            if i >= len(actions) and now >= pred.t0 + span - tol:
                return None
            if t_next >= next_mon - tol:
                next_mon = now + self.config.monitor_dt
                self._heartbeat(index, i, len(actions))
            if now > self.config.max_time:
                return None

    def _observe(self, pred: Prediction, index: int, kind: str) -> str | None:
        """Perceive, compare with the prediction, log; a reason when the monitor fires."""
        now = self.world.time
        predicted = pred.at(now)
        percept = self.world.perceive(reference=predicted)
        judged, passed = aligned_ahead(predicted, percept.configuration, self._ahead)
        verdict = self.monitor.check(judged, percept.configuration, self.carried)
        # Links whose carrying turn has stopped are judged now, once as "just carried".
        fresh, self.unjudged = self.unjudged - self.carried, self.unjudged & self.carried
        sample = {
            "time": round(now, 4), "plan": index, "kind": kind, "predicted": conf_dict(predicted),
            "perceived": conf_dict(percept.configuration),
            "errors": [round(e, 3) for e in verdict.errors]}
        if passed:  # offsets a turn ahead aligns away: not judged (errors without them)
            sample["aligned_ahead"] = passed
        self.log.samples.append(sample)
        self.observer(self.world, "monitor", kind)
        if not verdict.fired:
            return None
        self._learn_sag(verdict.worst_link, predicted, percept.configuration)
        reason = (f"{verdict.worst_link} off the prediction by {verdict.worst_error:.1f} deg "
                  f"(threshold {verdict.threshold:g})")
        if (verdict.worst_link in fresh and self.carry_count < self.config.free_carry_replans
                and now < self.config.max_time):
            self.carry_free = True
            reason += " when the vertical turn carrying it stopped"
        else:
            reason += self._stalled(verdict.worst_link, judged, percept.configuration)
        return reason

    def _stalled(self, link: str, predicted: Configuration, seen: Configuration) -> str:
        """The monitor fired on ``link``: when the turn in progress rotates it and it lags
        that turn by ``LoopConfig.stall_deg`` or more along its plane, the turn is refused
        from here (closed first, so that what it did turn unlocks what it should, then
        refused: :meth:`Refusals.refuse`). What to add to the reason, or ''."""
        if self.config.stall_deg is None or self._turn is None:
            return ""
        step = self._turn[0]
        if step.turn != link:
            return ""
        lag = behind_deg(step, predicted, seen, self.obj.index(link))
        if lag < self.config.stall_deg:
            return ""
        self._turn_close()
        self.refusals.refuse(step, self.world.time < self.config.max_time)
        return (f"; {step.action.signature} stalled {lag:.1f} deg behind its turn, "
                "refused from here")

    def _turns_ahead(self, steps: list[Step], pred: Prediction) -> Ahead:
        """The next turn of each (link, plane) still to start (a pending re-grasp first,
        then the dispatches), each aligned on its link when it starts
        (:func:`aligned_ahead`); none when ``LoopConfig.monitor_ahead`` is off."""
        out: Ahead = {}
        if not self.config.monitor_ahead:
            return out
        if self.resume is not None:
            r = self.resume.step
            out[(self.obj.index(r.turn), r.plane)] = (
                r.direction, self.resume.remaining(pred.t0, self.resume.due))
        for s in steps:
            if isinstance(s, Rotate):
                extent = math.inf if s.duration is None else self._speed(s) * s.duration
                out.setdefault((self.obj.index(s.turn), s.plane), (s.direction, extent))
        return out

    def _due(self, step: Step, pred: Prediction) -> float:
        """World time [s] to dispatch ``step``: a rotation ``lead`` early (its reach)."""
        early = self.lead if isinstance(step, Rotate) else 0.0
        return pred.t0 + step.action.time - early

    def _dispatch(self, step: Step, pred: Prediction, index: int) -> str | None:
        enc = self.encoding
        now = self.world.time
        action = step.action
        planned = pred.t0 + action.time
        if isinstance(step, (Rotate, Stop)):
            self._turn_close()
        try:
            did, ok = dispatch(self.world, step, (enc.speed_i, enc.speed_d),
                               pred.at(max(now, planned))), True
        except ActionFailed as exc:
            did, ok = str(exc), False
            if isinstance(step, Rotate):  # planned around at the next re-plan
                self.refusals.refuse(step, self.world.time < self.config.max_time,
                                     exc.arms_caught, exc.blocked)
        if ok and self.world.time > now:  # the arms approached: the rotation starts now
            shift = self.world.time - planned
            did += f" (reach {self.world.time - now:.2f} s, {shift:+.2f} s off the plan)"
            pred.t0 += shift
        if ok and isinstance(step, Rotate):
            did += f" ({self._align(step, pred, self._speed(step)):+.1f} deg behind at the grasp)"
            self._turn = (step, self.world.time, self._speed(step))
        self.unjudged |= self.carried  # any dispatch ends the turn in progress
        self.carried = _carried(self.obj.links, step) if ok else frozenset()
        self.swung |= self.carried
        if isinstance(step, Rotate) or not ok:  # a new turn, a stop or a failure
            self.resume = None
        if ok and isinstance(step, Rotate):
            self._regrasps = 0
            self.resume = resume_after(self.world, step, self._speed(step), pred.t0)
        self.log.happenings.append({"time": round(now, 4), "plan": index,
                                    "action": action.signature, "ok": ok, "did": did})
        self.progress(f"t={now:7.2f} s  {action.signature}: {did}")
        self.observer(self.world, "action", action.signature)
        return None if ok else f"action failed: {did}"

    def _align(self, step: Rotate, pred: Prediction, speed: float) -> float:
        """:func:`artiplan.execution.regrasp.align` on this run's world."""
        return align(self.world, step, pred, speed, self.config.align_ahead)

    def _speed(self, step: Rotate) -> float:
        """The rotation speed [deg/s] of ``step`` (the encoding's speed-i or speed-d)."""
        return self.encoding.speed_i if step.direction > 0 else self.encoding.speed_d

    def _impacted(self, pred: Prediction, index: int) -> None:
        """The world stopped the turn in progress on impact (``WorldConfig.impact_stop_m``):
        logged, and resumed by a re-grasp like a turn stopped at its collision-free limit
        (within :data:`~artiplan.execution.regrasp.MAX_REGRASPS`)."""
        impacts = getattr(self.world, "impacts", ())
        if len(impacts) <= self._impacts_seen:
            return
        self._impacts_seen = len(impacts)
        limit = getattr(self.world, "turn_limit", None)
        why = limit[1] if limit is not None else "stopped on impact"
        if self._turn is not None:
            step, _, speed = self._turn
            self.resume = resume_after(self.world, step, speed, pred.t0, self._regrasps)
            label = f"{step.action.signature} stopped"
        else:
            label = "turn stopped"
        self.log.happenings.append({"time": round(self.world.time, 4), "plan": index,
                                    "action": label, "ok": True, "did": why})
        self.progress(f"t={self.world.time:7.2f} s  {label}: {why}")

    def _regrasp(self, pred: Prediction, index: int) -> str | None:
        """Resume the rotation the arms stopped short (:mod:`artiplan.execution.regrasp`):
        re-grasp for the rest of its planned turn, shift the prediction by the re-grasp's
        duration and by what the link lost meanwhile. A reason when that fails."""
        r, self.resume = self.resume, None
        assert r is not None
        now = self.world.time
        remaining = r.remaining(pred.t0, now)
        step = r.step
        label = f"{step.action.signature} resumed"
        self._turn_close()
        try:
            did, ok = rotate(self.world, step, r.speed, pred.at(now), remaining), True
        except ActionFailed as exc:
            did, ok = str(exc), False
            self.refusals.refuse(step, self.world.time < self.config.max_time,
                                 exc.arms_caught, exc.blocked)
        if ok:
            waited = self.world.time - now
            pred.t0 += waited
            lost = self._align(step, pred, r.speed)
            self._turn = (step, self.world.time, r.speed)
            did = (f"re-grasp for the last {remaining:.0f} deg: {did} ({waited:.2f} s, "
                   f"{lost:+.1f} deg behind after it)")
            self._regrasps = r.done + 1
            self.resume = resume_after(self.world, step, r.speed, pred.t0, self._regrasps)
        self.log.happenings.append({"time": round(now, 4), "plan": index, "action": label,
                                    "ok": ok, "did": did})
        self.progress(f"t={now:7.2f} s  {label}: {did}")
        self.observer(self.world, "action", label)
        return None if ok else f"action failed: {did}"

    def _intervene(self, iv: Intervention, index: int) -> None:
        self.world.push(iv.link, iv.plane, iv.delta_deg)
        self.log.interventions.append({"time": round(self.world.time, 4), "link": iv.link,
                                       "plane": iv.plane, "delta_deg": iv.delta_deg})
        self.progress(f"t={self.world.time:7.2f} s  human pushes {iv.link} by "
                      f"{iv.delta_deg:+g} deg on {iv.plane}")
        self.observer(self.world, "intervention", f"push {iv.link} {iv.delta_deg:+g} deg")

    def _final_check(self) -> bool:
        """Hold still, perceive, judge the goal (every goal link within ``accept_deg``)."""
        self.world.stop(release=False)
        percept = self.world.perceive()
        self._final_conf = percept.configuration
        errs = goal_errors(self.obj, self.target, percept.configuration, self.goal.links)
        ok = all(e <= self.config.accept_deg for e in errs.values())
        self.log.final = {"time": round(self.world.time, 4),
                          "perceived": conf_dict(percept.configuration),
                          "goal_errors": {k: round(v, 3) for k, v in errs.items()},
                          "max_goal_error": round(max(errs.values(), default=0.0), 3),
                          "success": ok, "replans": self.replans}
        self.log.success = ok
        self.progress(f"t={self.world.time:7.2f} s  goal {'reached' if ok else 'NOT reached'}: "
                      + ", ".join(f"{k} {v:.1f} deg" for k, v in errs.items()))
        self.observer(self.world, "final", "goal reached" if ok else "goal not reached")
        return ok


def _carried(links: tuple[str, ...], step: Step) -> frozenset[str]:
    """Links tip-ward of the rotated one while ``step`` runs a ``z-axis`` rotation (a
    horizontal rotation carries links rigidly, as the model says; a vertical one does not)."""
    if not isinstance(step, Rotate) or step.plane != "z-axis":
        return frozenset()
    return frozenset(links[links.index(step.turn) + 1:])


def _settings(config: LoopConfig) -> dict[str, Any]:
    d = asdict(config)
    d["interventions"] = [asdict(i) for i in config.interventions]
    return d


def run_loop(world: World, target: Configuration, config: LoopConfig | None = None,
             progress: Progress | None = None, seed: int = 0,
             observer: Observer | None = None) -> RunLog:
    """Run the closed loop once; see :class:`ClosedLoop`."""
    return ClosedLoop(world, target, config or LoopConfig(), progress, seed, observer).run()
