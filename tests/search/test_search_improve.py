"""The anytime improvement phase: never a worse plan than the first, always validated, the same
plan on every run."""

from __future__ import annotations

import random

import pytest

from artiplan.encoding import EncodingOptions, domain_pddl, problem_pddl
from artiplan.encoding.suite import random_pair
from artiplan.model import ArticulatedObject
from artiplan.pddl import load_task
from artiplan.search.api import PlanStatus, plan_task
from artiplan.search.improve import better
from artiplan.semantics import validate


def _task(n: int, options: EncodingOptions, seed: int):  # type: ignore[no-untyped-def]
    obj = ArticulatedObject(n)
    init, target = random_pair(n, random.Random(seed))
    return load_task(domain_pddl(obj, options),
                     problem_pddl(obj, init, target, options, "threshold", seed))


@pytest.mark.parametrize("options", [EncodingOptions("ng"), EncodingOptions("ucm", speed_g=1.0)],
                         ids=lambda o: o.model)
def test_improvement_never_lengthens_the_makespan_and_is_deterministic(
        options: EncodingOptions) -> None:
    improved_any = False
    for seed in (3, 4):  # seed 4: the first plan (21.15 s) has shorter variants
        task = _task(5, options, seed)
        first = plan_task(task, time_limit=60, improve=False)
        runs = [plan_task(task, time_limit=60) for _ in range(2)]
        assert first.status is PlanStatus.SOLVED and runs[0].status is PlanStatus.SOLVED
        assert first.plan is not None and runs[0].plan is not None
        assert runs[0].plan == runs[1].plan  # deterministic: expansion budgets, not seconds
        assert runs[0].stats["improve_expanded"] == runs[1].stats["improve_expanded"]
        assert runs[0].stats["first_makespan"] == pytest.approx(first.plan.makespan)
        assert runs[0].plan.makespan <= first.plan.makespan + 1e-6
        assert validate(task, runs[0].plan).valid
        improved_any |= runs[0].plan.makespan < first.plan.makespan - 1e-3
    assert improved_any


def test_better_prefers_makespan_then_actions_and_prices_extra_actions() -> None:
    assert better(9.0, 3, 10.0, 3)
    assert better(10.0, 2, 10.0, 3)
    assert not better(10.0, 3, 10.0, 3)
    assert not better(9.9, 5, 10.0, 3)  # 1% shorter is not worth two more actions
    assert better(9.0, 5, 10.0, 3, gain=0.05)


def test_the_improvement_budget_follows_the_search_that_found_the_plan() -> None:
    # failed attempts before the winner (another heuristic) do not widen the phase
    from artiplan.search.engine import SearchConfig
    from artiplan.search.improve import ImproveConfig, improve
    from artiplan.search.limits import Limits
    from artiplan.semantics import Kernel, compile_task
    from artiplan.semantics.results import PlanStats

    task = _task(3, EncodingOptions("ng"), 3)
    first = plan_task(task, time_limit=60, improve=False)
    assert first.plan is not None
    ct = compile_task(task)
    budgets = []
    for expanded in (None, 12, 400):
        stats = PlanStats(expanded=1000)
        improve(ct, Kernel(ct), SearchConfig(), Limits(60, None), first.plan, stats,
                lambda outcome: first.plan, lambda found: None, ImproveConfig(maximum=2000),
                expanded=expanded)
        budgets.append(stats.improve_budget)
    assert budgets == [2000, 36, 1200]  # 3 x 1000 capped; 3 x 12; 3 x 400


def _expand(task, weight: float, memo):  # type: ignore[no-untyped-def]
    """A bounded search of ``task`` with time weight ``weight``: its nodes and statistics."""
    from artiplan.search.engine import Search, SearchConfig, initial_node
    from artiplan.search.heuristic import HeuristicConfig, RateHeuristic
    from artiplan.semantics import Kernel, compile_task

    ct = compile_task(task, strict=True)
    kernel = Kernel(ct)
    search = Search(ct, kernel, RateHeuristic(ct, HeuristicConfig(time_weight=weight),
                                              kernel.active),
                    SearchConfig(), lambda: None, accept=lambda outcome: False,
                    successors=memo)
    search.run(initial_node(ct, kernel), 40)
    return [(n.time, n.facts, n.values, n.parent, n.op, n.n_actions, n.last_event)
            for n in search.nodes], search.stats


def test_searches_sharing_successors_expand_the_same_nodes_as_searches_alone() -> None:
    # the improvement's searches share a memo of successors: it must change nothing but time
    task = _task(4, EncodingOptions("ucm", speed_g=1.0), 5)
    memo: dict = {}  # type: ignore[type-arg]
    sizes = []
    for weight in (1.0, 3.0, 1.0):
        shared, stats = _expand(task, weight, memo)
        alone, _ = _expand(task, weight, None)
        assert shared == alone
        sizes.append(len(memo))
    assert sizes[0] > 10
    # the last search repeats the first: every successor from the memo, none computed
    assert sizes[2] == sizes[1] and stats["reused"] >= sizes[0] / 2


def test_a_reweighted_rate_heuristic_evaluates_as_one_built_with_those_weights() -> None:
    from artiplan.search.engine import Search, SearchConfig, initial_node
    from artiplan.search.heuristic import HeuristicConfig, RateHeuristic
    from artiplan.semantics import Kernel, compile_task

    task = _task(4, EncodingOptions("uacm", speed_g=0.5), 6)
    ct = compile_task(task, strict=True)
    kernel = Kernel(ct)
    base = RateHeuristic(ct, HeuristicConfig(), kernel.active)
    search = Search(ct, kernel, base, SearchConfig(), lambda: None, accept=lambda o: False)
    search.run(initial_node(ct, kernel), 30)
    assert len(search.nodes) > 10
    for config in (HeuristicConfig(time_weight=3.0, damage_cost=0.5),
                   HeuristicConfig(time_weight=0.01, damage_cost=5.0)):
        copy, fresh = base.reweighted(config), RateHeuristic(ct, config, kernel.active)
        for node in search.nodes:
            assert copy.evaluate(node.facts, node.values, node.active) == \
                fresh.evaluate(node.facts, node.values, node.active)
        assert copy.config == config and base.config == HeuristicConfig()
