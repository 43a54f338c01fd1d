"""The OWL knowledge base: inferred `affects`, percepts in, the PDDL+ problem out."""

from __future__ import annotations

import random

import pytest

from artiplan.encoding import EncodingOptions, problem_pddl
from artiplan.model import ArticulatedObject, random_configuration
from artiplan.world.ontology import KnowledgeBase
from artiplan.world.perception import PerceptionConfig
from artiplan.world.scene import World, WorldConfig


def test_connected_is_asserted_and_affects_is_not_before_reasoning() -> None:
    kb = KnowledgeBase(ArticulatedObject(5))
    assert kb.connected() == {("L1", "L2"), ("L2", "L3"), ("L3", "L4"), ("L4", "L5")}
    assert kb.affects() == set()


@pytest.mark.slow
@pytest.mark.ci
def test_reasoner_infers_affects_exactly_as_the_conventions_define_it(tmp_path) -> None:
    obj = ArticulatedObject(6)
    kb = KnowledgeBase(obj)
    kb.reason()  # HermiT on Java: ~1-2 s
    expected = {(f"L{j}", f"L{m}") for j in range(2, 7) for m in range(j + 1, 7)}
    assert kb.affects() == expected
    assert kb.affects() == set(obj.affects())
    out = tmp_path / "world.owl"
    kb.save(out)
    assert "affects" in out.read_text()


@pytest.mark.parametrize("model", ["ng", "ucm"])
def test_problem_from_the_ontology_equals_the_one_from_the_truth_without_noise(model: str) -> None:
    obj = ArticulatedObject(5)
    init = random_configuration(5, random.Random(4))
    target = random_configuration(5, random.Random(5))
    exact = PerceptionConfig(position_sigma_m=0.0, orientation_sigma_deg=0.0, frames=1)
    world = World(obj, init, WorldConfig(perception=exact))
    kb = KnowledgeBase(obj)
    kb.record(world.perceive(reference=init))
    kb.set_goal(target, "threshold", seed=3)
    options = EncodingOptions(model=model)
    expected = problem_pddl(obj, init, target, options, goal_style="threshold", seed=3)
    assert kb.problem(options) == expected


def test_the_latest_observation_wins() -> None:
    obj = ArticulatedObject(3)
    kb = KnowledgeBase(obj)
    a, b = random_configuration(3, random.Random(1)), random_configuration(3, random.Random(2))
    kb.record_percept(b, time=2.0)
    kb.record_percept(a, time=1.0)
    conf, t = kb.latest_configuration()
    assert conf == b and t == 2.0
