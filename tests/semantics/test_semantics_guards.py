"""Guard facts: facts only events read, as "fired once until re-armed" (the wrap flags)."""

from __future__ import annotations

from artiplan.encoding import EncodingOptions, domain_pddl, problem_pddl
from artiplan.model import ArticulatedObject, Configuration
from artiplan.pddl import load_task
from artiplan.semantics.compiled import guard_facts

OBJ = ArticulatedObject(3)
INIT = Configuration.from_angles([0, 0, 0], [0, 1.5, 3.0])


def _task(model: str, domain_edit=lambda d: d):  # type: ignore[no-untyped-def]
    options = EncodingOptions(model)  # type: ignore[arg-type]
    return load_task(domain_edit(domain_pddl(OBJ, options)),
                     problem_pddl(OBJ, INIT, INIT, options, "window"))


def test_the_wrap_flags_are_guards_and_only_their_re_arms_are_quiet() -> None:
    for model in ("ng", "ucm", "uacm"):
        task = _task(model)
        guards, rearms = guard_facts(task)
        names = {task.facts[i] for i in range(len(task.facts)) if guards >> i & 1}
        assert names == {f"(wrapped-to-{w} L{k} {p})" for w in ("zero", "360")
                         for k in (1, 2, 3) for p in ("xy-axes", "z-axis")}, model
        assert {task.events[i].name for i in rearms} == {"rearm-back-to-zero",
                                                         "rearm-back-to-360"}
        assert len(rearms) == 2 * 3 * 2


def test_a_flag_an_action_reads_is_not_a_guard() -> None:
    # Let start-increase require a wrap flag: the flag then changes what can be done.
    def edit(domain: str) -> str:
        return domain.replace("(connected ?l1 ?l2)\n      (not (in-use)))",
                              "(connected ?l1 ?l2)\n      (not (in-use))\n"
                              "      (not (wrapped-to-zero ?l2 ?p)))", 1)
    task = _task("ng", edit)
    guards, rearms = guard_facts(task)
    names = {task.facts[i] for i in range(len(task.facts)) if guards >> i & 1}
    assert not any(n.startswith("(wrapped-to-zero L2") or n.startswith("(wrapped-to-zero L3")
                   for n in names), names
    assert "(wrapped-to-360 L2 z-axis)" in names
    assert all(not (task.events[i].name == "rearm-back-to-zero" and task.events[i].args[0] != "L1")
               for i in rearms)
