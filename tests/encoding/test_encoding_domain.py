"""Shape of every generated construct, read back with a tiny s-expression reader.

The reader here is deliberately independent of artiplan.pddl (a separate parser), so these tests
check the generated text, not another module's reading of it.
"""

from __future__ import annotations

import random
from typing import Union

import pytest

from artiplan.encoding import (
    EncodingOptions,
    domain_pddl,
    gravity_links,
    problem_pddl,
)
from artiplan.encoding.suite import random_pair
from artiplan.model import ArticulatedObject

SExpr = Union[str, list["SExpr"]]  # noqa: UP007 (recursive alias needs a string)


def read_sexpr(text: str) -> SExpr:
    """Parse one s-expression (comments after ';' dropped); lower-cases nothing."""
    lines = [line.split(";", 1)[0] for line in text.splitlines()]
    tokens = " ".join(lines).replace("(", " ( ").replace(")", " ) ").split()
    stack: list[list[SExpr]] = [[]]
    for tok in tokens:
        if tok == "(":
            stack.append([])
        elif tok == ")":
            done = stack.pop()
            stack[-1].append(done)
        else:
            stack[-1].append(tok)
    assert len(stack) == 1 and len(stack[0]) == 1, "unbalanced parentheses"
    return stack[0][0]


def sections(tree: SExpr) -> dict[str, list[list[SExpr]]]:
    """Group a define's sections by keyword (':action' may repeat)."""
    assert isinstance(tree, list) and tree[0] == "define"
    out: dict[str, list[list[SExpr]]] = {}
    for part in tree[2:]:
        assert isinstance(part, list) and isinstance(part[0], str)
        out.setdefault(part[0], []).append(part)
    return out


def construct(tree: SExpr, kind: str, name: str) -> dict[str, SExpr]:
    """The keyword fields (:parameters, :precondition, :effect) of one action/process/event."""
    for part in sections(tree).get(kind, []):
        if part[1] == name:
            fields = part[2:]
            return {str(fields[i]): fields[i + 1] for i in range(0, len(fields), 2)}
    raise AssertionError(f"no {kind} {name}")


def names(tree: SExpr, kind: str) -> set[str]:
    return {str(p[1]) for p in sections(tree).get(kind, [])}


def conjuncts(cond: SExpr) -> list[SExpr]:
    if isinstance(cond, list) and cond and cond[0] == "and":
        return list(cond[1:])
    return [cond]


def typed_params(fields: dict[str, SExpr]) -> list[tuple[str, str]]:
    p = fields[":parameters"]
    assert isinstance(p, list)
    out, i = [], 0
    while i < len(p):
        out.append((str(p[i]), str(p[i + 2])))
        i += 3
    return out


DOMAINS = {m: read_sexpr(domain_pddl(None, EncodingOptions(m))) for m in ("ng", "ucm", "uacm")}

ROBOT_ACTIONS = {"start-increase", "stop-increase", "start-decrease", "stop-decrease", "observe"}
ROBOT_PROCESSES = {"move-increase", "move-decrease", "propagate-increase", "propagate-decrease"}
WRAP_EVENTS = {"back-to-zero", "back-to-360"}


@pytest.mark.parametrize("model", ["ng", "ucm", "uacm"])
def test_every_domain_has_the_papers_robot_constructs(model: str) -> None:
    d = DOMAINS[model]
    assert d[1] == ["domain", f"artiplan-{model}"]
    assert names(d, ":action") == ROBOT_ACTIONS
    assert names(d, ":process") >= ROBOT_PROCESSES
    assert names(d, ":event") >= WRAP_EVENTS
    preds = {str(p[0]) for p in sections(d)[":predicates"][0][1:]}
    assert {"in-use", "free-to-move", "connected", "affects"} <= preds
    assert {"increasing-angle-robot", "decreasing-angle-robot"} <= preds
    funcs = {str(f[0]) for f in sections(d)[":functions"][0][1:]}
    assert {"angle", "speed-i", "speed-d"} <= funcs
    assert sections(d)[":constants"][0][1:] == ["xy-axes", "z-axis", "-", "plane"]


@pytest.mark.parametrize("model", ["ng", "ucm", "uacm"])
@pytest.mark.parametrize("sign", ["increase", "decrease"])
def test_start_stop_move_propagate_shape(model: str, sign: str) -> None:
    d = DOMAINS[model]
    flag = "increasing-angle-robot" if sign == "increase" else "decreasing-angle-robot"
    speed = ["speed-i"] if sign == "increase" else ["speed-d"]
    start = construct(d, ":action", f"start-{sign}")
    assert typed_params(start) == [("?l1", "link"), ("?l2", "link"), ("?p", "plane")]
    pre = conjuncts(start[":precondition"])
    assert ["connected", "?l1", "?l2"] in pre and ["not", ["in-use"]] in pre
    eff = conjuncts(start[":effect"])
    assert ["in-use"] in eff and [flag, "?l2", "?p"] in eff
    assert ["not", ["free-to-move", "?l1"]] in eff and ["not", ["free-to-move", "?l2"]] in eff
    stop = construct(d, ":action", f"stop-{sign}")
    assert [flag, "?l2", "?p"] in conjuncts(stop[":precondition"])
    eff = conjuncts(stop[":effect"])
    assert ["not", ["in-use"]] in eff and ["not", [flag, "?l2", "?p"]] in eff
    move = construct(d, ":process", f"move-{sign}")
    assert move[":precondition"] == [flag, "?l", "?p"]
    assert conjuncts(move[":effect"]) == [[sign, ["angle", "?l", "?p"], ["*", "#t", speed]]]
    prop = construct(d, ":process", f"propagate-{sign}")
    assert conjuncts(prop[":precondition"]) == [[flag, "?l1", "?p"], ["affects", "?l1", "?l2"]]
    assert conjuncts(prop[":effect"]) == [[sign, ["angle", "?l2", "?p"], ["*", "#t", speed]]]


@pytest.mark.parametrize("model", ["ng", "ucm", "uacm"])
def test_wrap_events_never_land_on_each_others_boundary(model: str) -> None:
    d = DOMAINS[model]
    m = EncodingOptions(model).margin  # type: ignore[arg-type]
    up = construct(d, ":event", "back-to-zero")
    down = construct(d, ":event", "back-to-360")
    zero, full = ["wrapped-to-zero", "?l", "?p"], ["wrapped-to-360", "?l", "?p"]
    assert conjuncts(up[":precondition"]) == [[">=", ["angle", "?l", "?p"], "360"], ["not", zero]]
    assert conjuncts(up[":effect"]) == [["assign", ["angle", "?l", "?p"], "0"], zero, ["not", full]]
    assert conjuncts(down[":precondition"]) == [
        ["<=", ["angle", "?l", "?p"], f"{-m:g}"], ["not", full]]
    assert conjuncts(down[":effect"]) == [
        ["assign", ["angle", "?l", "?p"], f"{360 - m:g}"], full, ["not", zero]]
    # Landing points are far from the other event's boundary: 100x VAL's slack (1e-4) at least,
    # and more than twice VAL's event window (0.01 s) at the robot's 10 deg/s.
    assert m >= 100 * 1e-4 and m / 10.0 >= 2 * 0.01 - 1e-12


@pytest.mark.parametrize("model", ["ng", "ucm", "uacm"])
def test_a_wrap_is_re_armed_only_a_quarter_turn_away(model: str) -> None:
    # A wrap's flag is cleared by the other wrap or by crossing 90 (up) / 270 (down): far from
    # both wrap boundaries and from the gravity thresholds (0, 180).
    d = DOMAINS[model]
    up = construct(d, ":event", "rearm-back-to-zero")
    down = construct(d, ":event", "rearm-back-to-360")
    assert conjuncts(up[":precondition"]) == [
        ["wrapped-to-zero", "?l", "?p"], [">=", ["angle", "?l", "?p"], "90"]]
    assert conjuncts(up[":effect"]) == [["not", ["wrapped-to-zero", "?l", "?p"]]]
    assert conjuncts(down[":precondition"]) == [
        ["wrapped-to-360", "?l", "?p"], ["<=", ["angle", "?l", "?p"], "270"]]
    assert conjuncts(down[":effect"]) == [["not", ["wrapped-to-360", "?l", "?p"]]]


def test_margin_scales_with_the_robot_speed() -> None:
    assert EncodingOptions("ng").margin == pytest.approx(0.2)
    assert EncodingOptions("ng", speed_i=50.0).margin == pytest.approx(1.0)
    assert EncodingOptions("ng", speed_i=0.1, speed_d=0.1).margin == pytest.approx(0.01)


def test_hysteresis_covers_links_carried_by_falling_links() -> None:
    # Carried by falling links a link turns far faster than the robot: the gravity flags'
    # hysteresis is sized for 50 deg/s (twice VAL's 0.01 s window), and never below the
    # wrap margin; the wrap margin stays the robot's.
    assert EncodingOptions("ucm").hysteresis == pytest.approx(1.0)
    assert EncodingOptions("uacm").hysteresis == pytest.approx(1.0)
    assert EncodingOptions("uacm").margin == pytest.approx(0.2)
    assert EncodingOptions("uacm", speed_i=100.0).hysteresis == pytest.approx(2.0)


@pytest.mark.parametrize("model", ["ng", "ucm", "uacm"])
def test_no_process_reads_a_changing_fluent(model: str) -> None:
    """Every process starts and stops at a happening: its precondition reads facts and the
    fluents only actions change (VAL misses a process switch between happenings)."""
    changing = {"'angle'", "'gravity-speed'", "'reach-clock'"}
    d = read_sexpr(domain_pddl(None, EncodingOptions(model, reach_time=1.0)))  # type: ignore[arg-type]
    for part in sections(d)[":process"]:
        fields = {str(part[i]): part[i + 1] for i in range(2, len(part), 2)}
        pre = str(fields[":precondition"])
        assert not any(f"[{name}" in pre for name in changing), (part[1], pre)


@pytest.mark.parametrize("model", ["ng", "ucm", "uacm"])
def test_processes_have_only_continuous_effects(model: str) -> None:
    for part in sections(DOMAINS[model]).get(":process", []):
        fields = {str(part[i]): part[i + 1] for i in range(2, len(part), 2)}
        for eff in conjuncts(fields[":effect"]):
            assert isinstance(eff, list) and eff[0] in ("increase", "decrease"), (part[1], eff)
            assert isinstance(eff[2], list) and eff[2][0] == "*" and "#t" in eff[2], eff


def test_observe_has_no_effect() -> None:
    for d in DOMAINS.values():
        obs = construct(d, ":action", "observe")
        assert obs[":parameters"] == [] and obs[":effect"] == ["and"]


def test_ng_has_no_gravity() -> None:
    d = DOMAINS["ng"]
    assert not any("gravity" in n for n in names(d, ":process") | names(d, ":event"))


@pytest.mark.parametrize("model", ["ucm", "uacm"])
def test_gravity_processes_start_and_stop_at_happenings(model: str) -> None:
    """No process reads a changing angle: flags set by angle events, "feels gravity" changed
    only by actions (VAL loses process switches between happenings, see semantics.md)."""
    d = DOMAINS[model]
    rate = ["speed-g"] if model == "ucm" else ["gravity-speed", "?l"]
    for sign in ("increase", "decrease"):
        flag = f"{sign[:-1]}ing-angle-gravity"
        fall = construct(d, ":process", f"gravity-{sign}")
        assert conjuncts(fall[":effect"]) == [[sign, ["angle", "?l", "z-axis"], ["*", "#t", rate]]]
        pre = conjuncts(fall[":precondition"])
        assert [flag, "?l"] in pre and "['angle'" not in str(pre)
        prop = construct(d, ":process", f"propagate-gravity-{sign}")
        assert ["affects", "?l1", "?l2"] in conjuncts(prop[":precondition"])
        assert conjuncts(prop[":effect"])[0][1] == ["angle", "?l2", "z-axis"]
        start = construct(d, ":event", f"start-gravity-{sign}")
        stop = construct(d, ":event", f"stop-gravity-{sign}")
        # Self-falsifying: the flag is in the precondition and flipped by the effect.
        assert ["not", [flag, "?l"]] in conjuncts(start[":precondition"])
        assert [flag, "?l"] in conjuncts(start[":effect"])
        assert [flag, "?l"] in conjuncts(stop[":precondition"])
        assert ["not", [flag, "?l"]] in conjuncts(stop[":effect"])
        # The events read the angle only: no action can trigger them.
        assert "held-index" not in str(start) + str(stop)
    dec = conjuncts(construct(d, ":event", "start-gravity-decrease")[":precondition"])
    assert [">", ["angle", "?l", "z-axis"], "1"] in dec  # at rest within the margin: stays
    assert ["<", ["angle", "?l", "z-axis"], "179"] in dec  # near 180: stays
    # Rest sets the angle to exactly 0; the vertical passed upward is a separate event.
    rest = construct(d, ":event", "stop-gravity-decrease")
    assert ["<=", ["angle", "?l", "z-axis"], "0"] in conjuncts(rest[":precondition"])
    assert ["assign", ["angle", "?l", "z-axis"], "0"] in conjuncts(rest[":effect"])
    passed = construct(d, ":event", "pass-gravity-decrease")
    assert [">=", ["angle", "?l", "z-axis"], "180"] in conjuncts(passed[":precondition"])
    assert ["not", ["decreasing-angle-gravity", "?l"]] in conjuncts(passed[":effect"])


def test_uacm_speed_starts_at_zero_grows_with_acceleration_and_resets() -> None:
    d = DOMAINS["uacm"]
    acc = construct(d, ":process", "gravity-accelerate")
    assert conjuncts(acc[":effect"]) == [
        ["increase", ["gravity-speed", "?l"], ["*", "#t", ["acceleration"]]]
    ]
    for sign in ("increase", "decrease"):
        for kind in ("start", "stop"):
            eff = conjuncts(construct(d, ":event", f"{kind}-gravity-{sign}")[":effect"])
            assert ["assign", ["gravity-speed", "?l"], "0"] in eff
        # A grasp resets the speeds of every link the rotated link does not carry.
        start = conjuncts(construct(d, ":action", f"start-{sign}")[":effect"])
        assert [
            "forall",
            ["?l", "-", "link"],
            ["when", ["not", ["affects", "?l2", "?l"]], ["assign", ["gravity-speed", "?l"], "0"]],
        ] in start


def _problem(model: str, n: int = 4, **kw: float) -> SExpr:
    obj = ArticulatedObject(n)
    init, target = random_pair(n, random.Random(5))
    return read_sexpr(problem_pddl(obj, init, target, EncodingOptions(model, **kw)))  # type: ignore[arg-type]


def _init(tree: SExpr) -> list[SExpr]:
    return list(sections(tree)[":init"][0][1:])


@pytest.mark.parametrize("model", ["ng", "ucm", "uacm"])
def test_problem_facts_and_values(model: str) -> None:
    p = _problem(model, 4, acceleration=0.5, speed_g=1.0)
    init = _init(p)
    assert sections(p)[":domain"][0][1] == f"artiplan-{model}"
    assert sections(p)[":objects"][0][1:] == ["L1", "L2", "L3", "L4", "-", "link"]
    assert [x for x in init if x[0] == "connected"] == [
        ["connected", "L1", "L2"],
        ["connected", "L2", "L3"],
        ["connected", "L3", "L4"],
    ]
    assert [x for x in init if x[0] == "affects"] == [
        ["affects", "L2", "L3"],
        ["affects", "L2", "L4"],
        ["affects", "L3", "L4"],
    ]
    assert ["=", ["speed-i"], "10"] in init and ["=", ["speed-d"], "10"] in init
    angles = [x for x in init if x[0] == "=" and x[1][0] == "angle"]
    assert len(angles) == 8
    assert all(0.0 <= float(x[2]) < 360.0 for x in angles)
    if model == "ucm":
        assert ["=", ["speed-g"], "1"] in init
    if model == "uacm":
        assert ["=", ["acceleration"], "0.5"] in init
        assert ["=", ["gravity-speed", "L3"], "0"] in init


@pytest.mark.parametrize("model", ["ng", "ucm", "uacm"])
def test_every_symbol_a_problem_uses_is_declared(model: str) -> None:
    d, p = DOMAINS[model], _problem(model)
    preds = {str(x[0]) for x in sections(d)[":predicates"][0][1:]}
    funcs = {str(x[0]) for x in sections(d)[":functions"][0][1:]}
    for fact in _init(p):
        if fact[0] == "=":
            assert fact[1][0] in funcs, fact
        else:
            assert fact[0] in preds, fact
    goal_symbols = set()

    def walk(e: SExpr) -> None:
        if isinstance(e, list):
            if e and e[0] == "angle":
                goal_symbols.update(e[1:])
            for x in e:
                walk(x)

    walk(sections(p)[":goal"][0][1])
    assert goal_symbols <= {"L1", "L2", "L3", "L4", "xy-axes", "z-axis"}


# ------------------------------------------------------------------ the gravity rule, in PDDL


def evaluate(expr: SExpr, values: dict[tuple[str, ...], float], binding: dict[str, str]) -> float:
    if isinstance(expr, str):
        return float(expr)
    if expr[0] in "+-*/" and len(expr) == 3:
        a, b = (evaluate(x, values, binding) for x in expr[1:])
        return {"+": a + b, "-": a - b, "*": a * b, "/": a / b}[str(expr[0])]
    key = tuple(binding.get(str(x), str(x)) for x in expr)
    return values[key]


def compare(cond: SExpr, values: dict[tuple[str, ...], float], binding: dict[str, str]) -> bool:
    op, a, b = cond
    x, y = evaluate(a, values, binding), evaluate(b, values, binding)
    return {">": x > y, "<": x < y, ">=": x >= y, "<=": x <= y}[str(op)]


def feels_in_pddl(model: str, n: int, rotated: str | None) -> list[str]:
    """Links whose gravity-process 'feels gravity' comparison holds, evaluated from the text.

    The state comes from the generated problem's :init, after applying start-increase's
    numeric effect when a link is rotated (its ?l2; ?l1 is the base-ward neighbour).
    """
    d = DOMAINS[model]
    p = _problem(model, n)
    values = {tuple(str(t) for t in x[1]): float(x[2]) for x in _init(p) if x[0] == "="}
    if rotated is not None:
        start = construct(d, ":action", "start-increase")
        for eff in conjuncts(start[":effect"]):
            if eff[0] == "assign":
                key = tuple(str(t) for t in eff[1])
                values[key] = evaluate(eff[2], values, {"?l2": rotated})
    proc = construct(d, ":process", "gravity-decrease")
    feels = [
        c
        for c in conjuncts(proc[":precondition"])
        if isinstance(c, list) and "link-index" in str(c) and c[0] in (">", "<", ">=", "<=")
    ]
    assert len(feels) == 1, feels
    return [f"L{i}" for i in range(1, n + 1) if compare(feels[0], values, {"?l": f"L{i}"})]


@pytest.mark.parametrize("model", ["ucm", "uacm"])
@pytest.mark.parametrize("n", [3, 5, 8])
def test_gravity_rule_when_lk_and_lk1_are_held(model: str, n: int) -> None:
    obj = ArticulatedObject(n)
    # Hands free: every link but the clamped base.
    assert feels_in_pddl(model, n, None) == list(obj.links[1:])
    assert gravity_links(obj) == obj.links[1:]
    for k in range(1, n):
        held = (f"L{k}", f"L{k + 1}")
        expected = [f"L{j}" for j in range(k + 2, n + 1)]  # only links tip-ward of both hands
        assert list(gravity_links(obj, held)) == expected
        assert feels_in_pddl(model, n, f"L{k + 1}") == expected


def test_gravity_links_examples() -> None:
    obj = ArticulatedObject(6)
    assert gravity_links(obj, ("L2", "L3")) == ("L4", "L5", "L6")
    assert gravity_links(obj, ("L5", "L6")) == ()
    assert gravity_links(obj, ("L1", "L2")) == ("L3", "L4", "L5", "L6")


def test_feels_comparison_has_a_margin_against_vals_slack() -> None:
    # Equal integer indices must compare "not greater" even with a 1e-4 slack on '>'.
    pre = conjuncts(construct(DOMAINS["ucm"], ":process", "gravity-increase")[":precondition"])
    assert [">", ["link-index", "?l"], ["+", ["held-index"], "0.5"]] in pre


def test_reach_time_option() -> None:
    d = read_sexpr(domain_pddl(None, EncodingOptions("ucm", reach_time=2.0)))
    assert "hands-ready" in names(d, ":event") and "reach" in names(d, ":process")
    start = construct(d, ":action", "start-increase")
    assert ["not", ["reaching"]] in conjuncts(start[":precondition"])
    p = read_sexpr(
        problem_pddl(
            ArticulatedObject(3),
            *random_pair(3, random.Random(1)),
            EncodingOptions("ucm", reach_time=2.0),
        )
    )
    assert ["=", ["reach-time"], "2"] in _init(p)
    assert "reaching" not in domain_pddl(None, EncodingOptions("ucm"))


def test_options_validation() -> None:
    with pytest.raises(ValueError, match="valid models"):
        EncodingOptions("xyz")  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="positive"):
        EncodingOptions("ucm", speed_g=0.0)
    with pytest.raises(ValueError, match="gravity plane"):
        EncodingOptions("ucm", gravity_plane="yz")


def test_custom_planes() -> None:
    opts = EncodingOptions("ucm", planes=("xy-axes", "z-axis", "yz-plane"))
    d = read_sexpr(domain_pddl(None, opts))
    assert sections(d)[":constants"][0][1:] == ["xy-axes", "z-axis", "yz-plane", "-", "plane"]
    obj = ArticulatedObject(3)
    pair = random_pair(3, random.Random(1))
    # A configuration holds theta and gamma only: a third plane has no initial angle.
    with pytest.raises(ValueError, match="valid planes"):
        problem_pddl(obj, *pair, opts)
    # One plane: only its angles and goals.
    text = problem_pddl(obj, *pair, EncodingOptions("ucm", planes=("z-axis",)))
    assert "xy-axes" not in text and "(angle L3 z-axis)" in text


def test_a_turn_cap_splits_long_turns_and_bounds_the_plans_end() -> None:
    """With ``max_turn_deg`` no turn goes further than the cap: a 3-link NG task whose plan
    turns a link 100 deg at once needs two turns of at most 60 deg when capped at 60."""
    from artiplan.backends import get_planner
    from artiplan.encoding import problem_pddl
    from artiplan.model import Configuration

    obj = ArticulatedObject(3)
    init = Configuration((0.0, 0.0, 0.0), (90.0, 90.0, 90.0))
    target = Configuration((0.0, 0.0, 100.0), (90.0, 90.0, 90.0))

    def longest(cap: float | None) -> float:
        enc = EncodingOptions("ng", max_turn_deg=cap)
        text = domain_pddl(obj, enc)
        if cap is not None:
            assert text.count(f"(<= (turned) {cap:g})") == 3  # both stops and observe
        result = get_planner("artiplan").plan(
            text, problem_pddl(obj, init, target, enc, goal_style="window"), time_limit=60)
        assert result.plan is not None
        acts = result.plan.actions
        end = acts[-1].time  # a turn may go on to the plan's end
        turns = [next((b.time for b in acts[i + 1:] if b.name == a.name.replace("start", "stop")
                       and b.args == a.args), end) - a.time
                 for i, a in enumerate(acts) if a.name.startswith("start")]
        return max(turns) * enc.speed_i

    assert longest(None) > 90.0
    assert longest(60.0) <= 60.0 + 1e-6
    with pytest.raises(ValueError, match="max_turn_deg"):
        EncodingOptions("ng", max_turn_deg=0.0)
