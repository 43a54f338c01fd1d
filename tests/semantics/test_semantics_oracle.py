"""An independent check of the exact simulator: a naive fixed-step simulator (Heun steps of
1 ms, events fired at step ends) on random plans for the project's NG, UCM and UACM encodings.

Heun's method is exact for the quadratic UACM motion, so the two may differ only by what one
step can change: an event or a process switch late by up to 1 ms (up to 0.01 deg at 10 deg/s
per switch). Final angles must agree within 0.1 deg, and the wraps must be the same.
"""

from __future__ import annotations

import random

import pytest

from artiplan.encoding import EncodingOptions, domain_pddl, problem_pddl
from artiplan.model import ArticulatedObject, Configuration
from artiplan.pddl import load_task
from artiplan.pddl.task import Effect, Task
from artiplan.semantics import Plan, TimedAction, evaluate, holds, simulate
from artiplan.tolerances import EXACT

STEP = 1e-3


def _apply(effect: Effect, facts: int, values: list[float]) -> tuple[int, list[float]]:
    """Apply one effect on copies (a conditional effect's condition read exactly)."""
    old = list(values)
    parts = [effect] + [ce.effect for ce in effect.conditional
                        if holds(ce.condition, facts, old, EXACT)]
    for part in parts:
        facts &= ~sum(1 << f for f in part.delete)
    for part in parts:
        facts |= sum(1 << f for f in part.add)
    values = list(values)
    for ne in [ne for part in parts for ne in part.numeric]:
        rhs = evaluate(ne.expr, old)
        if ne.op == "assign":
            values[ne.fluent] = rhs
        elif ne.op == "increase":
            values[ne.fluent] += rhs
        elif ne.op == "decrease":
            values[ne.fluent] -= rhs
    return facts, values


def naive(task: Task, plan: Plan, end: float) -> tuple[list[float], list[str]]:
    """Final values and the names of the events fired, by fixed steps."""
    def on(cond):  # type: ignore[no-untyped-def]
        return lambda f, v: holds(cond, f, v, EXACT)

    events = [(e, on(e.precondition)) for e in task.events]
    procs = [(p, on(p.precondition), [(c.fluent, (lambda r: lambda v: evaluate(r, v))(c.rate))
                                      for c in p.continuous])
             for p in task.processes]
    facts = sum(1 << f for f in task.init_facts)
    values = [0.0 if v is None else v for v in task.init_values]
    fired: list[str] = []

    def settle() -> None:
        nonlocal facts, values
        for _ in range(50):
            on = [e for e, fn in events if fn(facts, values)]
            if not on:
                return
            for e in on:
                fired.append(e.name)
                facts, values = _apply(e.effect, facts, values)

    def rates(vals: list[float]) -> list[float]:
        d = [0.0] * len(vals)
        for _, fn, effs in procs:
            if fn(facts, values):
                for i, r in effs:
                    d[i] += r(vals)
        return d

    actions = sorted(plan.actions, key=lambda a: a.time)
    by_sig = {a.signature.lower(): a for a in task.actions}
    t, k = 0.0, 0
    settle()
    while t < end - 1e-12:
        while k < len(actions) and actions[k].time <= t + 1e-9:
            facts, values = _apply(by_sig[actions[k].signature.lower()].effect, facts, values)
            k += 1
            settle()
        h = min(STEP, end - t)
        k1 = rates(values)
        k2 = rates([v + h * d for v, d in zip(values, k1, strict=True)])
        values = [v + 0.5 * h * (a + b) for v, a, b in zip(values, k1, k2, strict=True)]
        t += h
        settle()
    return values, fired


def random_plan(rng: random.Random, n_links: int) -> Plan:
    actions, t = [], 0.0
    for _ in range(3):
        j = rng.randrange(1, n_links)
        args = (f"L{j}", f"L{j + 1}", rng.choice(["xy-axes", "z-axis"]))
        sign = rng.choice(["increase", "decrease"])
        t += round(rng.uniform(0.2, 1.0), 3)
        actions.append(TimedAction(t, f"start-{sign}", args))
        t += round(rng.uniform(1.0, 6.0), 3)
        actions.append(TimedAction(t, f"stop-{sign}", args))
    return Plan(tuple(actions))


@pytest.mark.parametrize("model", ["ng", "ucm", "uacm"])
def test_exact_simulation_agrees_with_a_fine_fixed_step_one(model: str) -> None:
    rng = random.Random(11)
    opts = {"ucm": {"speed_g": 1.0}, "uacm": {"acceleration": 0.5}}.get(model, {})
    options = EncodingOptions(model, **opts)  # type: ignore[arg-type]
    for n_links in (3, 4):
        obj = ArticulatedObject(n_links)
        init = Configuration(
            tuple(round(rng.uniform(0, 360), 1) for _ in range(n_links)),
            tuple(round(rng.uniform(0, 360), 1) for _ in range(n_links)),
        )
        task = load_task(domain_pddl(obj, options), problem_pddl(obj, init, init, options))
        plan = random_plan(rng, n_links)
        end = plan.makespan + 2.0
        traj = simulate(task, Plan(plan.actions, end=end))
        values, fired = naive(task, plan, end)
        exact = traj.values_at(end)
        for i, name in enumerate(task.fluents):
            if name.startswith("(angle"):
                d = abs(exact[i] - values[i]) % 360.0
                assert min(d, 360.0 - d) < 0.1, (model, n_links, name, exact[i], values[i])
        wraps = sorted(e.name for e in traj.events if e.name.startswith("back-to"))
        assert wraps == sorted(n for n in fired if n.startswith("back-to")), (model, n_links)
