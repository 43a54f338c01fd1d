"""End to end on virtual hands: a re-plan starts from what is perceived; the loop reaches
3-link NG and UCM goals."""

from __future__ import annotations

import random
from typing import Any

import numpy as np
import pytest

from artiplan.encoding import EncodingOptions
from artiplan.encoding.suite import random_pair
from artiplan.execution import Intervention, LoopConfig, run_loop
from artiplan.execution.runlog import conf_from
from artiplan.model import ArticulatedObject, direction_error


def _world(n: int, seed: int):  # type: ignore[no-untyped-def]
    from artiplan.world import make_world

    obj = ArticulatedObject(n)
    init, target = random_pair(n, random.Random(seed))
    return make_world(obj, init, hands="virtual", seed=seed), target


def test_replan_starts_from_the_perceived_state() -> None:
    world, target = _world(3, 4)
    push = Intervention(0.0, "L3", "z-axis", 25.0, fraction=0.3)
    # Every offset judged: the push is what a later turn of L3 could align away.
    cfg = LoopConfig(EncodingOptions("ng"), interventions=(push,), max_replans=2,
                     monitor_ahead=False)
    log = run_loop(world, target, cfg, seed=4)
    assert log.interventions and log.replans
    assert "L3 off the prediction" in log.replans[0]["reason"]
    t = log.replans[0]["time"]
    before = [s for s in log.samples if s["plan"] == 0 and s["time"] <= t][-1]
    start = conf_from(log.plans[1]["start"])
    # The new plan's initial state is the percept (within noise), not the old prediction.
    assert direction_error(start, conf_from(before["perceived"]))[2] < 1.5
    assert direction_error(start, conf_from(before["predicted"]))[2] > 15.0
    assert log.plans[1]["start_time"] == pytest.approx(t, abs=1e-3)


@pytest.mark.slow
@pytest.mark.ci
@pytest.mark.parametrize("model", ["ng", "ucm"])
def test_loop_reaches_a_three_link_goal(model: str) -> None:
    world, target = _world(3, 6)
    cfg = LoopConfig(EncodingOptions(model, speed_g=0.9))
    log = run_loop(world, target, cfg, seed=6)
    assert log.success
    assert len(log.replans) <= cfg.budget(3)
    assert log.final["max_goal_error"] <= cfg.accept_deg
    # The goal really holds in the world (ground truth), not only in the percept.
    truth = world.true_configuration()
    assert float(np.max(direction_error(truth, target)[2:3])) <= cfg.accept_deg + 1.0


def test_a_diverging_physics_ends_the_run_as_failed() -> None:
    """MuJoCo resets its whole state when a step diverges (time back to 0, every body at its
    initial pose): the world raises instead of going on, and the loop ends the run, failed,
    saying why, rather than planning from a teleported object."""
    world, target = _world(3, 4)
    seen: list[float] = []
    when: list[float] = []

    def blow_up(w, kind, _label):  # type: ignore[no-untyped-def]
        seen.append(w.time)
        if kind == "monitor" and w.time > 0.5 and not when:
            when.append(w.time)
            w.data.qvel[:] = 1e30  # MuJoCo's check of bad velocities resets the state

    log = run_loop(world, target, LoopConfig(EncodingOptions("ng")), seed=4, observer=blow_up)
    assert not log.success
    assert "physics diverged" in log.final["error"]
    # With clues to why: the joint MuJoCo flagged and how far the hands' servos had wound up.
    assert "bad velocity of joint" in log.final["error"]
    assert "servo integral" in log.final["error"]
    assert log.final["time"] == pytest.approx(when[0])  # not the reset clock
    assert all(b >= a for a, b in zip(seen, seen[1:], strict=False))  # time never went back


def test_plans_are_sought_with_short_turns_first() -> None:
    """LoopConfig.max_turn_deg: the loop's plans turn no link further than the cap at once
    while such a plan is found within capped_time_limit, else it plans without the cap."""
    from artiplan.model import Configuration
    from artiplan.world import make_world

    obj = ArticulatedObject(3)
    init = Configuration((0.0, 0.0, 0.0), (90.0, 90.0, 90.0))
    target = Configuration((0.0, 0.0, 100.0), (90.0, 90.0, 90.0))

    def longest_turn(cfg: LoopConfig, lines: list[str]) -> float:
        world = make_world(obj, init, hands="virtual", seed=1)
        log = run_loop(world, target, cfg, progress=lines.append, seed=1)
        assert log.success
        acts = log.plans[0]["actions"]
        end = acts[-1]["time"]
        return 10.0 * max(
            next((b["time"] for b in acts[i + 1:]
                  if b["action"] == a["action"].replace("start", "stop")), end) - a["time"]
            for i, a in enumerate(acts) if a["action"].startswith("(start"))

    lines: list[str] = []
    assert longest_turn(LoopConfig(EncodingOptions("ng"), max_turn_deg=60.0), lines) <= 60.0
    assert not any("planning with longer ones" in line for line in lines)
    # No time to find a capped plan: planned without the cap, and said so.
    cfg = LoopConfig(EncodingOptions("ng"), max_turn_deg=60.0, capped_time_limit=1e-9)
    assert longest_turn(cfg, lines) > 90.0
    assert any("planning with longer ones" in line for line in lines)


def test_a_plan_that_ends_short_moves_the_next_plans_aim() -> None:
    """LoopConfig.aim: a plan that ends without the goal (here: an acceptance tighter than
    execution can meet) makes the next plan of the same model aim each goal link's vertical
    window off the target by minus what was missed there."""
    from artiplan.execution.problem import canonical
    from artiplan.model import Configuration
    from artiplan.world import make_world

    obj = ArticulatedObject(3)
    init = Configuration((0.0, 0.0, 0.0), (90.0, 90.0, 90.0))
    target = Configuration((0.0, 0.0, 100.0), (90.0, 90.0, 120.0))
    cfg = LoopConfig(EncodingOptions("ng"), accept_deg=0.01, max_replans=1)
    log = run_loop(make_world(obj, init, hands="virtual", seed=1), target, cfg, seed=1)
    assert [r["reason"] for r in log.replans] == ["goal not reached at the final happening"]
    assert log.plans[0]["aim"] == {}
    aim = log.plans[1]["aim"]
    assert aim, "the re-plan aims off the target"
    start = canonical(conf_from(log.plans[1]["start"]))  # where plan 0 ended (a new percept)
    for lk, off in aim.items():
        i = obj.index(lk) - 1
        missed = start.gamma[i] - canonical(target).gamma[i]  # L3 ends about 1.7 deg low
        assert abs(missed) > 1.0
        assert off == pytest.approx(-missed, abs=0.4)  # percept noise: a few tenths
    off = LoopConfig(EncodingOptions("ng"), accept_deg=0.01, max_replans=1, aim=False)
    log = run_loop(make_world(obj, init, hands="virtual", seed=1), target, off, seed=1)
    assert log.plans[1]["aim"] == {}


def test_only_a_released_goal_link_sinking_under_ng_moves_the_aim() -> None:
    """The monitor's firings teach the aim (``ClosedLoop._learn_sag``) only when the plan is
    gravity-free (NG), the link is a goal link, no hand holds it right now and no vertical
    turn of the plan has carried it."""
    from dataclasses import replace as dc_replace

    from artiplan.execution.dispatch import Rotate
    from artiplan.execution.loop import ClosedLoop
    from artiplan.model import Configuration
    from artiplan.semantics import TimedAction
    from artiplan.world import make_world

    obj = ArticulatedObject(3)
    init = Configuration((0.0, 0.0, 0.0), (90.0, 90.0, 90.0))
    target = Configuration((0.0, 0.0, 100.0), (90.0, 90.0, 120.0))
    sunk = Configuration((0.0, 0.0, 100.0), (90.0, 90.0, 112.0))

    def loop(model: str) -> ClosedLoop:
        world = make_world(obj, init, hands="virtual", seed=1)
        return ClosedLoop(world, target, LoopConfig(EncodingOptions(model), use_ontology=False))

    ng = loop("ng")
    assert "L3" in ng.goal.links
    turn = Rotate(TimedAction(0.0, "start-increase", ("L2", "L3", "z-axis")), "L2", "L3",
                  "z-axis", 1, 1.0)
    ng._turn = (turn, 0.0, 10.0)  # L3 in a hand: what it does is the turn's, not sag
    ng._learn_sag("L3", target, sunk)
    assert ng.aim is not None and ng.aim.of("ng") == {}
    ng._turn = None
    ng.swung = frozenset({"L3"})  # carried by a vertical turn of L2 earlier in this plan
    ng._learn_sag("L3", target, sunk)
    assert ng.aim.of("ng") == {}
    ng.swung = frozenset()
    ng._learn_sag("L3", target, sunk)
    assert ng.aim.of("ng") == {"L3": pytest.approx(8.0)}
    ucm = loop("ucm")  # a model with gravity: its errors are not the missing sag
    ucm._learn_sag("L3", target, sunk)
    assert ucm.aim is not None and ucm.aim.offsets == {}
    off = ClosedLoop(make_world(obj, init, hands="virtual", seed=1), target,
                     dc_replace(LoopConfig(EncodingOptions("ng")), aim=False, use_ontology=False))
    off._learn_sag("L3", target, sunk)
    assert off.aim is None


def test_a_carried_link_off_when_its_turn_stops_is_planned_again_for_free() -> None:
    """``LoopConfig.free_carry_replans``: the first percept after a vertical turn stops judges
    the links it carried; one off the prediction then is planned again without spending the
    re-plan budget (the carry rule's known error), up to the cap; later percepts, links still
    carried, and other links spend it as before."""
    from dataclasses import replace as dc_replace

    from artiplan.execution.loop import ClosedLoop
    from artiplan.model import Configuration
    from artiplan.world import make_world

    obj = ArticulatedObject(4)
    init = Configuration((0.0, 0.0, 90.0, 90.0), (90.0, 90.0, 90.0, 90.0))
    world = make_world(obj, init, hands="virtual", seed=1)
    loop = ClosedLoop(world, init, LoopConfig(EncodingOptions("ng"), use_ontology=False,
                                              free_carry_replans=1))
    truth = world.true_configuration()
    # The model carried L3 up by 30 deg on its vertical plane; the world did not.
    model = Configuration(truth.theta, (truth.gamma[0], truth.gamma[1], truth.gamma[2] + 30.0,
                                        truth.gamma[3]))

    class Constant:  # the plan's prediction: the model's configuration at any time
        def at(self, t: float) -> Configuration:
            return model

    pred: Any = Constant()
    plain = loop._observe(pred, 0, "monitor")
    assert plain is not None and plain.startswith("L3 off the prediction by ")
    assert not loop.carry_free and not plain.endswith("stopped")
    loop.unjudged, loop.carried = frozenset({"L3", "L4"}), frozenset({"L3", "L4"})
    assert loop._observe(pred, 0, "monitor") is None  # still carried: not judged yet
    assert loop.unjudged == {"L3", "L4"}
    loop.carried = frozenset()  # the turn stopped
    fresh = loop._observe(pred, 0, "monitor")
    assert fresh is not None and fresh.endswith("when the vertical turn carrying it stopped")
    assert loop.carry_free and loop.unjudged == frozenset()
    loop.carry_free = False
    again = loop._observe(pred, 0, "monitor")  # judged once already: a plain re-plan
    assert again is not None and not loop.carry_free
    loop.unjudged, loop.carry_count = frozenset({"L3"}), 1  # the cap is spent
    assert loop._observe(pred, 0, "monitor") is not None and not loop.carry_free
    off = ClosedLoop(make_world(obj, init, hands="virtual", seed=1), init,
                     dc_replace(loop.config, free_carry_replans=0))
    off.unjudged = frozenset({"L3"})
    assert off._observe(pred, 0, "monitor") is not None and not off.carry_free


def test_a_plan_ending_with_a_carried_goal_link_off_is_planned_again_for_free() -> None:
    """The final check misses only on goal links a vertical turn carried and no percept has
    judged since (the plan ended as the turn stopped): the next plan is free of the budget,
    as when the monitor catches such a link; any other goal link off makes it a re-plan."""
    from artiplan.execution.loop import ClosedLoop
    from artiplan.model import Configuration
    from artiplan.world import make_world

    obj = ArticulatedObject(6)
    init = Configuration((0.0,) * 6, (90.0,) * 6)
    loop = ClosedLoop(make_world(obj, init, hands="virtual", seed=1), init,
                      LoopConfig(EncodingOptions("ng"), use_ontology=False))
    loop.log.final = {"goal_errors": {"L3": 30.0, "L5": 2.0}}
    assert loop._missed_carried() == "" and not loop.carry_free  # L3 was not carried
    loop.unjudged = frozenset({"L3", "L4", "L5", "L6"})
    assert loop._missed_carried() == "L3" and loop.carry_free
    loop.carry_free, loop.unjudged = False, frozenset({"L5", "L6"})
    loop.log.final = {"goal_errors": {"L3": 30.0, "L5": 9.0}}
    assert loop._missed_carried() == "" and not loop.carry_free  # L3 off and not carried
    loop.carried = frozenset({"L3", "L4", "L5", "L6"})  # the turn was still going
    assert loop._missed_carried() == "L3, L5" and loop.carry_free
    loop.carry_free, loop.carry_count = False, loop.config.free_carry_replans
    assert loop._missed_carried() == "" and not loop.carry_free  # the free ones are used up


def test_the_replan_budget_grows_with_the_chain_unless_it_is_set() -> None:
    cfg = LoopConfig(EncodingOptions("ng"))
    assert [cfg.budget(n) for n in (3, 4, 5, 6, 8, 12)] == [5, 5, 7, 8, 10, 15]
    fixed = LoopConfig(EncodingOptions("ng"), max_replans=2)
    assert fixed.budget(3) == fixed.budget(12) == 2
    assert LoopConfig(EncodingOptions("ng"), max_replans=0).budget(6) == 0
    with pytest.raises(ValueError, match="max_replans"):
        LoopConfig(EncodingOptions("ng"), max_replans=-1)
