"""The planner's (strict) and the validator's view of one task: the second one compiled is the
first one re-read (``compiled._reread``); it must be what a full compile gives."""

from __future__ import annotations

import random
from pathlib import Path

import pytest

from artiplan.pddl import load_task
from artiplan.pddl.task import Task
from artiplan.semantics import cache
from artiplan.semantics.compiled import CompiledTask, _compile, compile_task
from artiplan.tolerances import VAL

ROOT = Path(__file__).resolve().parents[2]
FAMILIES = ROOT / "benchmarks" / "pddlplus"


def _suite_tasks(tmp: Path) -> list[Task]:
    from artiplan.encoding.suite import write_suite

    write_suite(tmp, seed=0)
    out = []
    for family in ("ng", "ucm-0.5", "uacm-0.5"):
        for name in ("p3-1.pddl", "p5-2.pddl"):
            out.append(load_task(tmp / family / "domain.pddl", tmp / family / name))
    return out


def _family_tasks() -> list[Task]:
    out = []
    for family in ("car_limit", "intercept", "thermostat", "generator", "torricelli"):
        out.append(load_task(FAMILIES / family / "domain.pddl", FAMILIES / family / "p01.pddl"))
    return out


def _agree(fn_a, fn_b, n_facts: int, n_values: int, rng: random.Random) -> None:  # type: ignore[no-untyped-def]
    for _ in range(200):
        facts = rng.getrandbits(max(1, n_facts))
        values = tuple(rng.choice((0.0, 1.0, -1.0, 45.0, 90.0, 1e-10, rng.uniform(-400, 400)))
                       for _ in range(n_values))
        try:
            a = fn_a(facts, values)
        except (ZeroDivisionError, ValueError, OverflowError) as exc:
            with pytest.raises(type(exc)):
                fn_b(facts, values)
            continue
        assert fn_b(facts, values) == a


def _same(derived: CompiledTask, full: CompiledTask) -> None:
    assert derived.strict == full.strict
    assert derived.comps.items == full.comps.items
    for name in ("goal_comps", "init_facts", "dynamic", "watched", "fluent_comps", "guards",
                 "rearms", "spaced"):
        assert getattr(derived, name) == getattr(full, name), name
    rng = random.Random(7)
    n_facts, n_values = len(full.task.facts), len(full.task.fluents)
    _agree(derived.goal, full.goal, n_facts, n_values, rng)
    assert len(derived.actions) == len(full.actions)
    for a, b in zip(derived.actions, full.actions, strict=True):
        assert (a.signature, a.pre_comps, a.req, a.forb, a.noop, a.writes, a.resets) == \
            (b.signature, b.pre_comps, b.req, b.forb, b.noop, b.writes, b.resets)
        _agree(a.pre, b.pre, n_facts, n_values, rng)
        _agree(a.effect, b.effect, n_facts, n_values, rng)
        _agree(a.parts, b.parts, n_facts, n_values, rng)
    for a, b in zip(derived.events, full.events, strict=True):
        assert a.signature == b.signature
        _agree(a.pre, b.pre, n_facts, n_values, rng)
    assert [p.signature for p in derived.processes] == [p.signature for p in full.processes]
    assert len(derived.invariants) == len(full.invariants)


@pytest.mark.parametrize("first_strict", [True, False])
def test_the_second_view_is_what_a_full_compile_gives(tmp_path: Path, first_strict: bool) -> None:
    for task in _suite_tasks(tmp_path) + _family_tasks():
        first = compile_task(task, VAL, strict=first_strict)
        second = compile_task(task, VAL, strict=not first_strict)
        assert cache.cached(task, ("compiled", VAL, not first_strict)) is second
        assert second.comps is first.comps  # re-read, not compiled again
        _same(second, _compile(task, VAL, not first_strict))
        # the first view is unchanged by the second (its operators are not the copies)
        assert all(a is not b for a, b in zip(first.actions, second.actions, strict=True))
        assert first.strict is first_strict


def test_a_full_memo_drops_its_least_recently_used_half(tmp_path: Path) -> None:
    """When the per-task memo is full it drops dead tasks' entries, then the least recently
    used half, not everything: a full clear dropped the planner's view of a task just before
    the validator's view came to re-read it (a test here failed or passed by how many entries
    the tests before it had left)."""
    task = _suite_tasks(tmp_path)[0]
    cache._MEMO.clear()
    built: list[int] = []

    def filler(i: int) -> int:
        return cache.per_task(task, ("filler", i), lambda: built.append(i) or i)

    for i in range(cache._MAX_ENTRIES):
        filler(i)
    filler(0)  # used again: the most recent now
    filler(cache._MAX_ENTRIES)  # one more: the memo is full
    built.clear()
    for i in (0, cache._MAX_ENTRIES - 1, cache._MAX_ENTRIES):
        filler(i)
    assert built == []  # kept: used last, or among the newest
    filler(1)
    assert built == [1]  # among the least recently used half: dropped
