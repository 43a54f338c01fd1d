"""Grounding: counts computed by hand, static folding, pruning, the process quirk."""

from __future__ import annotations

from artiplan.pddl import load_task, parse_domain, parse_problem
from artiplan.pddl.task import And, Atom, Comparison, Const, ContinuousEffect, FluentRef, Not


def test_counts_by_hand(arm_domain: str, arm_problem: str) -> None:
    task = load_task(arm_domain, arm_problem)
    # start/stop-increase: 2 connected pairs x 2 planes each; events: 3 links x 2 planes;
    # move-increase: only L2, L3 can ever be moved (4), L1 pruned (2); propagate: 1 pair x 2;
    # gravity: 3 links.
    assert (task.stats.actions, task.stats.events, task.stats.processes) == (8, 6, 9)
    assert task.stats.pruned == 2
    # in-use, free-to-move x3, increasing-angle-robot L2/L3 x 2 planes, -gravity x3.
    assert task.stats.facts == 11
    assert len(task.fluents) == 6  # angles only: speeds are static and folded
    assert "(angle L2 z-axis)" in task.fluents
    assert "(increasing-angle-robot L1 z-axis)" not in task.facts


def test_static_folding(arm_domain: str, arm_problem: str) -> None:
    task = load_task(arm_domain, arm_problem)
    start = task.action_by_signature("(start-increase L1 L2 z-axis)")
    # (connected L1 L2) is static and true: only (not (in-use)) is left.
    assert start.precondition == Not(Atom(task.fact_index("(in-use)")))
    move = next(p for p in task.processes if p.signature == "(move-increase L2 xy-axes)")
    fl = task.fluent_index("angle(L2,xy-axes)")
    assert move.continuous == (ContinuousEffect(fl, Const(10.0)),)
    assert task.init_values[task.fluent_index("(angle L2 z-axis)")] == -3.0
    assert task.init_values[task.fluent_index("(angle L3 xy-axes)")] == 0.001
    assert task.goal == And((
        Comparison(">", FluentRef(task.fluent_index("(angle L2 xy-axes)")), Const(265.4)),
        Comparison("<", FluentRef(task.fluent_index("(angle L3 z-axis)")), Const(5.5)),
    ))


def test_process_setting_a_fact_warns_and_goes_to_discrete(arm_domain: str,
                                                           arm_problem: str) -> None:
    domain = parse_domain(arm_domain, "arm.pddl")
    assert any("gravity-increase" in w and "arm.pddl:31:" in w for w in domain.warnings)
    task = load_task(arm_domain, arm_problem)
    grav = next(p for p in task.processes if p.signature == "(gravity-increase L2)")
    assert grav.discrete.add == (task.fact_index("(increasing-angle-gravity L2)"),)


def test_undeclared_function_in_init_warns(arm_domain: str, arm_problem: str) -> None:
    task = load_task(arm_domain, arm_problem)
    assert any("'foo'" in w and "never declared" in w for w in task.warnings)
    problem = parse_problem(arm_problem, "p.pddl")
    assert problem.objects[0].name == "L1"
