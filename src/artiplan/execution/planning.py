"""The loop's planning side: perceive, build the problem, call the planner around refusals,
fall back to a simpler model, and move the goal's aim (a mixin of
:class:`artiplan.execution.loop.ClosedLoop`, which owns the state it reads and writes)."""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import replace
from typing import TYPE_CHECKING, Any, cast

from artiplan.encoding import EncodingOptions, GoalSpec, domain_pddl
from artiplan.encoding.options import Fall, Model
from artiplan.encoding.problem import Ungraspable
from artiplan.execution.aim import Aim
from artiplan.execution.config import Intervention, LoopConfig
from artiplan.execution.dispatch import Rotate
from artiplan.execution.predict import Prediction
from artiplan.execution.problem import build_problem, canonical
from artiplan.execution.refusals import MOVED_DEG, WAIT_S, Refusal, Refusals, describe
from artiplan.execution.runlog import RunLog, conf_dict
from artiplan.model import ArticulatedObject, Configuration
from artiplan.semantics import Plan
from artiplan.semantics.plan_io import format_plan
from artiplan.semantics.results import PlanStatus

if TYPE_CHECKING:
    from artiplan.world import World

#: What a plan is made around: refused rotations, ungraspable links (execution.refusals).
Avoid = tuple[frozenset[Refusal], frozenset[Ungraspable]]


class Planning:
    """Planning methods of the closed loop (see the module docstring)."""

    world: World
    obj: ArticulatedObject
    target: Configuration
    config: LoopConfig
    encoding: EncodingOptions
    domain: str
    goal: GoalSpec
    kb: Any
    aim: Aim | None
    refusals: Refusals
    log: RunLog
    planner: Any
    lead: float
    pending: list[Intervention]
    current_plan: Plan
    _final_conf: Configuration | None
    _turn: tuple[Rotate, float, float] | None
    swung: frozenset[str]
    carry_free: bool
    progress: Callable[[str], None]

    def _learn_aim(self) -> None:
        """The plan just executed ended short of the goal: the next plans of its model aim
        off the target by what it missed by (see :class:`artiplan.execution.aim.Aim`)."""
        if self.aim is None or self._final_conf is None:
            return
        model = self.encoding.model
        used = self.aim.observe(self.obj, model, self.target, self._final_conf, self.goal.links)
        if used:
            self.progress("aiming " + ", ".join(
                f"{lk} {off:+.1f} deg" for lk, off in self.aim.of(model).items())
                + f" on the vertical plane in the next {model.upper()} plans (residuals "
                + ", ".join(f"{lk} {r:+.1f}" for lk, r in used.items()) + ")")

    def _learn_sag(self, link: str, predicted: Configuration, perceived: Configuration) -> None:
        """The monitor fired on ``link``: if it is a goal link a gravity-free (NG) plan left
        released and it sank, the next NG plans aim it higher (``Aim.observe_sag``). Not a
        link a vertical turn of this plan has carried: what the rigid carry rule gets wrong
        is not sag (measured: a 4-link push task learned +8.8 deg so and overshot by 7.6)."""
        model = self.encoding.model
        if self.aim is None or model != "ng" or link not in self.goal.links:
            return
        turn = self._turn[0] if self._turn is not None else None
        if turn is not None and link in (turn.hold, turn.turn):
            return
        if link in self.swung:  # carried through a vertical turn: the carry rule's error
            return
        sank = self.aim.observe_sag(self.obj, model, predicted, perceived, link)
        if sank is not None:
            self.progress(f"{link} sank {sank:+.1f} deg released: aiming it "
                          f"{self.aim.of(model)[link]:+.1f} deg on the vertical plane in the "
                          "next NG plans")

    def _fall_back(self) -> bool:
        """Switch to the fallback model (see ``LoopConfig.fallback_model``); False when there
        is none or it is in use already."""
        model = self.config.fallback_model
        if model is None or model == self.encoding.model:
            return False
        self._use_model(cast(Model, model), self.encoding.fall if model == "ucm" else "uniform")
        self.progress(f"falling back to the {model.upper()} model for the next plans")
        return True

    def _own_model(self) -> None:
        """Back to the configured model after a plan the fallback model made
        (``LoopConfig.fallback_scope`` ``plan``)."""
        own = self.config.encoding
        if self.encoding.model != own.model:
            self._use_model(own.model, own.fall)
            self.progress(f"back to the {own.model.upper()} model")

    def _use_model(self, model: Model, fall: Fall) -> None:
        """Plan with ``model`` (its ``fall`` rule: only UCM's is not uniform) from now on."""
        self.encoding = replace(self.encoding, model=model, fall=fall)
        self.domain = domain_pddl(self.obj, self.encoding)

    def _perceive_for_planning(self) -> Configuration:
        """Perceive; through the knowledge base when configured (percept in, query out)."""
        percept = self.world.perceive()
        if self.kb is None:
            return percept.configuration
        self.kb.record(percept)
        conf, _ = self.kb.latest_configuration(None)
        return conf

    def _plan(self, reason: str, counted: bool = True) -> Prediction | None:
        """Perceive, build the problem, plan; log it (a re-plan when ``counted``, else a plan
        again after a refusal or a carried link's error). None when no plan was found."""
        if (self.refusals.stuck or self.refusals.waiting) and self.log.samples:
            # the links refused now are measured from before the arms or the chain move
            last = self.log.samples[-1]["perceived"]
            self._settle(Configuration(tuple(last["theta"]), tuple(last["gamma"])))
        if self.refusals.stuck:
            self._escape()
        elif self.refusals.waiting:
            self._wait()
        start = canonical(self._perceive_for_planning())
        if self.config.fallback_scope == "plan":
            self._own_model()
        t = time.perf_counter()
        result = self._solve(start)
        latency = time.perf_counter() - t
        index = len(self.log.plans)
        entry = {"time": round(self.world.time, 4), "reason": reason,
                 "latency_wall_s": round(latency, 4)}
        if index and counted:
            self.log.replans.append(entry)
        elif index and self.carry_free:
            self.log.carry_replans.append(entry)
        elif index:
            self.log.refusals.append(entry)
        if self.config.advance_latency:
            self.world.run_until(self.world.time + latency)
        t0 = self.world.time
        solved = _solved(result)
        record: dict[str, Any] = {
            "index": index, "start_time": round(t0, 4), "reason": reason,
            "model": self.encoding.model,
            "aim": self.aim.of(self.encoding.model) if self.aim is not None else {},
            "status": result.status.value, "latency_wall_s": round(latency, 4),
            "makespan": result.stats.get("makespan"), "start": conf_dict(start),
            "message": result.message,
            "text": format_plan(result.plan) if solved and result.plan else "",
            "actions": [{"time": round(t0 + a.time, 6), "action": a.signature}
                        for a in (result.plan.actions if solved and result.plan else ())],
        }
        self.log.plans.append(record)
        self.progress(f"plan {index} ({reason}): {result.status.value} in {latency:.2f} s wall, "
                      f"{len(record['actions'])} actions")
        if not solved or result.plan is None:
            return None
        for line in record["text"].splitlines():
            self.progress(f"    {line}")
        self.current_plan: Plan = result.plan
        if index == 0:  # interventions given as a fraction of the first plan's makespan
            span = max(result.plan.makespan, result.plan.end or 0.0)
            self.pending = sorted(
                (replace(iv, time=t0 + iv.fraction * span) if iv.fraction is not None else iv
                 for iv in self.pending), key=lambda i: i.time)
        return Prediction(self.obj, result.trajectory, t0, start)

    def _settle(self, conf: Configuration) -> None:
        """Forget the refusals the chain has since moved away from (:meth:`Refusals.settled`),
        saying so."""
        pairs, links = self.refusals.settled(conf, self.obj)
        for r in pairs:
            self.progress(f"{describe(r)} may be tried again: {r[1]} has turned "
                          f"{MOVED_DEG:g} deg or more since it was refused")
        for u in links:
            self.progress(f"{u[0]} may be grasped to {u[1]} it again: it has turned "
                          f"{MOVED_DEG:g} deg or more against what its grasps met")

    def _escape(self) -> None:
        """The arms found no way to the grasps from where they are (caught in the chain, say):
        both go home first by planned motions, and the rotations refused for that may be
        planned again."""
        t = self.world.time
        home = getattr(self.world, "arms_home", None)
        moved = bool(home()) if home is not None else False
        self.refusals.escaped(moved)
        did = (f"both arms home ({self.world.time - t:.2f} s)" if moved
               else "no path home found (or home already): arms left where they are")
        self.log.happenings.append({"time": round(t, 4), "plan": len(self.log.plans) - 1,
                                    "action": "(arms-home)", "ok": moved, "did": did})
        self.progress(f"t={t:7.2f} s  arms caught: {did}")

    def _wait(self) -> None:
        """A dead end (a rotation refused again from where it was refused): the hands stay
        open for WAIT_S and the chain settles under gravity; the same rotation may then find
        a free grasp pair (execution.refusals.MAX_WAITS)."""
        t = self.world.time
        self.world.run_until(t + WAIT_S)
        self.refusals.waiting = False
        self.refusals.waits += 1
        self.refusals.homeless = False  # the chain has moved: a way home may be found now
        did = f"hands open for {WAIT_S:g} s: the chain settles before planning again"
        self.log.happenings.append({"time": round(t, 4), "plan": len(self.log.plans) - 1,
                                    "action": "(wait)", "ok": True, "did": did})
        self.progress(f"t={t:7.2f} s  dead end: {did}")

    def _solve(self, start: Configuration) -> Any:
        """Plan from ``start``; not starting with a rotation the world has refused since the
        chain last moved (it would be refused again from nearly the same state), ignoring
        those refusals if that finds no plan, or only one longer than the run has time left
        for (measured: a plan around two refusals turned L2 for 695 s, 70 times round). A
        model that finds no plan makes way for the fallback model, from then on, before the
        refusals are ignored: its search is smaller (measured: around two refusals UCM found
        none where NG found one; twice 60 s of UCM search on a 6-link state found none).
        Before ignoring them all, only the rotations refused for want of an arm motion are
        ignored: the arm-motion planner is randomised and they cost no budget when refused
        again, while the grasps' and the turns' refusals would come again from this state
        (measured: a 6-link run spent its whole re-plan budget in 0.1 s of simulated time
        on 6 such refusals of the same two rotations)."""
        r = self.refusals
        self._settle(start)
        every = (r.refused, r.ungraspable)
        certain: Avoid = (r.refused - r.caught, r.ungraspable)
        none: Avoid = (frozenset(), frozenset())
        tiers = [every] + ([certain] if certain not in (every, none) else []) \
            + ([none] if every != none else [])
        left = self.config.max_time - self.world.time
        first, first_relaxed, result = None, False, None
        for avoid in tiers:
            result = self._solve_with(start, avoid)
            if not _solved(result) and self._fall_back():
                result = self._solve_with(start, avoid)
            if not _solved(result):
                continue
            if first is None:
                first, first_relaxed = result, avoid != every
            span = max(result.plan.makespan, result.plan.end or 0.0)
            if span <= left:
                if avoid != none:
                    self.progress("planned without " + ", ".join(
                        [f"starting with {describe(ref)}" for ref in sorted(avoid[0])]
                        + [f"grasping {u[0]} to {u[1]} it" for u in sorted(
                            avoid[1], key=lambda u: (u[0], u[1]))]) + " (refused from here)")
                self.refusals.relaxed = avoid != every
                return result
            self.progress(f"a plan of {span:.0f} s, more than the {left:.0f} s left: "
                          + ("planning again without the refusals" if avoid != none
                             else "taken"))
        self.refusals.relaxed = first_relaxed
        return first or result

    def _solve_with(self, start: Configuration, avoid: Avoid) -> Any:
        """One planner call from ``start`` with the model in use, not starting the refused
        rotations ``avoid[0]`` nor grasping the links ``avoid[1]`` (before they have moved)."""
        enc = replace(self.encoding, refusals=True) if avoid[0] or avoid[1] else self.encoding
        cfg = self.config
        if cfg.max_turn_deg is not None:  # first with short turns (LoopConfig.max_turn_deg)
            result = self._call(start, replace(enc, max_turn_deg=cfg.max_turn_deg), avoid,
                                min(cfg.capped_time_limit, cfg.plan_time_limit))
            if _solved(result):
                return result
            self.progress(f"no plan with turns of at most {cfg.max_turn_deg:g} deg "
                          f"({result.status.value}): planning with longer ones")
        return self._call(start, enc, avoid, cfg.plan_time_limit)

    def _call(self, start: Configuration, enc: EncodingOptions, avoid: Avoid,
              limit: float) -> Any:
        """The planner on ``enc``'s domain and the problem from ``start`` around ``avoid``,
        within ``limit`` [s] wall."""
        domain = self.domain if enc == self.encoding else domain_pddl(self.obj, enc)
        goal = self.aim.goal(self.goal, enc.model) if self.aim is not None else self.goal
        problem = build_problem(self.obj, start, self.target, enc, goal,
                                hands_away=self.lead > 0.0, refused=avoid[0],
                                ungraspable=avoid[1])
        return self.planner.plan(domain, problem, time_limit=limit)


def _solved(result: Any) -> bool:
    return bool(result.status is PlanStatus.SOLVED and result.plan is not None)
