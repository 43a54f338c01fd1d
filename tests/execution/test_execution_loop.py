"""End to end on virtual hands: a re-plan starts from what is perceived; the loop reaches
3-link NG and UCM goals."""

from __future__ import annotations

import random

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
    cfg = LoopConfig(EncodingOptions("ng"), interventions=(push,), max_replans=2)
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
    assert len(log.replans) <= cfg.max_replans
    assert log.final["max_goal_error"] <= cfg.accept_deg
    # The goal really holds in the world (ground truth), not only in the percept.
    truth = world.true_configuration()
    assert float(np.max(direction_error(truth, target)[2:3])) <= cfg.accept_deg + 1.0
