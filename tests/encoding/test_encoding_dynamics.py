"""The generated domains behave as designed under VAL's semantics.

Uses artiplan's PDDL parser and plan simulator/validator (artiplan.pddl, artiplan.semantics) on
hand-written plans: wrap-around without bouncing, UCM's constant-speed fall that stops at rest,
UACM's quadratic fall whose speed resets when the link is grasped, the reach time.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from artiplan.encoding import EncodingOptions, domain_pddl, problem_pddl, write_suite
from artiplan.model import ArticulatedObject, Configuration
from artiplan.pddl import ground, load_task, parse_domain, parse_problem
from artiplan.semantics import simulate, validate
from artiplan.semantics.plan_io import parse_plan

OBJ = ArticulatedObject(4)
INIT = Configuration.from_angles([0, 5, 5, 355], [0, 90, 350, 180])
TARGET = Configuration.from_angles([0, 0, 355, 345], [0, 0, 0, 0])
PLAN = """0: (start-decrease L1 L2 xy-axes)
1: (stop-decrease L1 L2 xy-axes)
2.5: (start-increase L2 L3 z-axis)
3: (stop-increase L2 L3 z-axis)
4.5: (observe)
"""


def _run(options: EncodingOptions, plan: str = PLAN, init: Configuration = INIT):  # type: ignore[no-untyped-def]
    task = load_task(domain_pddl(OBJ, options), problem_pddl(OBJ, init, TARGET, options, "window"))
    return validate(task, parse_plan(plan))


def _angle(report, link: str, plane: str, t: float) -> float:  # type: ignore[no-untyped-def]
    return float(report.trajectory.value(f"(angle {link} {plane})", t))


def _events(report) -> list[tuple[float, str, tuple[str, ...]]]:  # type: ignore[no-untyped-def]
    return [(round(e.time, 4), e.name, tuple(e.args)) for e in report.trajectory.events]


def test_ng_wraps_once_below_zero_and_propagates() -> None:
    report = _run(EncodingOptions("ng"))
    assert report.valid, report.reason
    # 5 - 10 t reaches -0.2 (the margin) at t = 0.52: one wrap per carried angle, no bounce.
    assert _events(report) == [
        (0.52, "back-to-360", ("L2", "xy-axes")),
        (0.52, "back-to-360", ("L3", "xy-axes")),
    ]
    assert _angle(report, "L2", "xy-axes", 1.0) == pytest.approx(355.0)
    assert _angle(report, "L3", "xy-axes", 1.0) == pytest.approx(355.0)  # carried
    assert _angle(report, "L4", "xy-axes", 1.0) == pytest.approx(345.0)  # carried, no wrap
    assert _angle(report, "L3", "z-axis", 3.0) == pytest.approx(355.0)
    assert _angle(report, "L4", "z-axis", 3.0) == pytest.approx(185.0)
    assert _angle(report, "L2", "z-axis", 4.5) == pytest.approx(90.0)  # no gravity


def test_ng_wraps_above_360_onto_zero() -> None:
    plan = "0: (start-increase L3 L4 z-axis)\n2: (stop-increase L3 L4 z-axis)\n"
    init = Configuration.from_angles([0, 5, 5, 355], [0, 90, 350, 355])
    report = _run(EncodingOptions("ng"), plan, init)
    assert _events(report) == [(0.5, "back-to-zero", ("L4", "z-axis"))]
    assert _angle(report, "L4", "z-axis", 2.0) == pytest.approx(15.0)


def test_ucm_falls_at_constant_speed_and_stops_at_rest() -> None:
    obj = ArticulatedObject(3)
    init = Configuration.from_angles([0, 0, 0], [0, 30, 0])
    opts = EncodingOptions("ucm", speed_g=1.0)
    task = load_task(domain_pddl(obj, opts), problem_pddl(obj, init, init, opts, "window"))
    traj = simulate(task, parse_plan("60: (observe)\n"))
    assert traj.value("(angle L2 z-axis)", 10.0) == pytest.approx(20.0)
    assert traj.value("(angle L2 z-axis)", 60.0) == pytest.approx(0.0, abs=1e-3)  # rest, no wrap
    # L3 hangs at rest: carried below 0 it wraps to 359.8 once (the margin: 0.2 deg), then its
    # own fall toward 360 cancels the carry exactly, so it stays hanging; when L2 rests (30 s)
    # L3 rises the last 0.2 deg and wraps onto 0. One wrap each way, no bouncing.
    assert traj.value("(angle L3 z-axis)", 10.0) == pytest.approx(359.8)
    assert traj.value("(angle L3 z-axis)", 60.0) == pytest.approx(0.0, abs=1e-3)
    assert [(round(e.time, 3), e.name, e.args) for e in traj.events] == [
        (0.2, "back-to-360", ("L3", "z-axis")),
        (0.2, "start-gravity-increase", ("L3",)),  # 359.8: gravity pulls it up to 360
        (30.0, "stop-gravity-decrease", ("L2",)),  # L2 at rest
        (30.2, "back-to-zero", ("L3", "z-axis")),
        (30.2, "stop-gravity-increase", ("L3",)),
    ]


def test_ucm_held_links_feel_no_gravity() -> None:
    report = _run(EncodingOptions("ucm", speed_g=1.0))
    assert report.valid, report.reason
    # 0-1 s: L1, L2 held; L3 (350) rises at 1 deg/s; L2 (held) keeps 90.
    assert _angle(report, "L2", "z-axis", 1.0) == pytest.approx(90.0)
    assert _angle(report, "L3", "z-axis", 1.0) == pytest.approx(351.0)
    # 1-2.5 s: hands free, L2 falls (and carries L3 down, cancelling L3's own rise).
    assert _angle(report, "L2", "z-axis", 2.5) == pytest.approx(88.5)
    assert _angle(report, "L3", "z-axis", 2.5) == pytest.approx(351.0)
    # 2.5-3 s: L2, L3 held: only L4 feels gravity; rotation +10 deg/s carries it.
    assert _angle(report, "L4", "z-axis", 3.0) - _angle(report, "L4", "z-axis", 2.5) == (
        pytest.approx(5.0 + 0.5)
    )


def test_uacm_speed_grows_and_resets_when_grasped() -> None:
    report = _run(EncodingOptions("uacm", acceleration=1.0))
    assert report.valid, report.reason
    # The problem starts with the flags its angles imply (no event at time 0, which VAL
    # forbids), and holding a link does not touch them: no gravity event at all here.
    assert not [e for e in _events(report) if "gravity" in e[1] and e[2] == ("L2",)]
    assert _angle(report, "L2", "z-axis", 1.0) == pytest.approx(90.0)  # held from 0 to 1 s
    # From rest speed: 90 - a t^2 / 2 with t = 1.5 s.
    assert _angle(report, "L2", "z-axis", 2.5) == pytest.approx(90.0 - 1.5**2 / 2)
    # Held from 2.5 to 3: no change; released at 3 with speed 0 again (reset).
    assert _angle(report, "L2", "z-axis", 3.0) == pytest.approx(88.875)
    assert _angle(report, "L2", "z-axis", 4.5) == pytest.approx(88.875 - 1.5**2 / 2)


def test_uacm_acceleration_is_a_real_parameter() -> None:
    slow = _run(EncodingOptions("uacm", acceleration=0.1))
    fast = _run(EncodingOptions("uacm", acceleration=0.5))
    drop_slow = 90.0 - _angle(slow, "L2", "z-axis", 2.5)
    drop_fast = 90.0 - _angle(fast, "L2", "z-axis", 2.5)
    assert drop_fast == pytest.approx(5 * drop_slow)


def test_exactly_180_stays() -> None:
    obj = ArticulatedObject(3)
    init = Configuration.from_angles([0, 0, 0], [0, 180, 180])
    for opts in (EncodingOptions("ucm", speed_g=1.0), EncodingOptions("uacm", acceleration=1.0)):
        task = load_task(domain_pddl(obj, opts), problem_pddl(obj, init, init, opts, "window"))
        traj = simulate(task, parse_plan("20: (observe)\n"))
        assert traj.value("(angle L2 z-axis)", 20.0) == pytest.approx(180.0, abs=1e-3)
        assert traj.value("(angle L3 z-axis)", 20.0) == pytest.approx(180.0, abs=1e-3)


def test_reach_time_delays_the_next_grasp() -> None:
    opts = EncodingOptions("ucm", speed_g=1.0, reach_time=2.0)
    report = _run(opts)  # next grasp 1.5 s after the release: too early
    assert not report.valid and "start-increase" in report.reason
    late = PLAN.replace("2.5:", "3.5:").replace("3: (stop", "4: (stop").replace("4.5:", "5:")
    assert _run(opts, late).valid


def test_every_suite_file_parses_and_grounds(tmp_path: Path) -> None:
    write_suite(tmp_path)
    for folder in sorted(p for p in tmp_path.iterdir() if p.is_dir()):
        domain = parse_domain((folder / "domain.pddl").read_text(), str(folder / "domain.pddl"))
        for path in sorted(folder.glob("p*.pddl")):
            problem = parse_problem(path.read_text(), str(path))
            if path.name in ("p3-1.pddl", "p12-5.pddl"):
                task = ground(domain, problem)
                assert task is not None
