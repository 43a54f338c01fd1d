"""The ``projected`` carry option against physics: a vertical-plane turn of L2 changes a
carried link's gamma by cos(theta_3 - theta_2) times the turn, and its azimuth by
-cot(gamma_3) sin(theta_3 - theta_2) times it (the paper's rigid rule adds the whole turn to
gamma whatever the link's azimuth)."""

from __future__ import annotations

import pytest

from artiplan.encoding import EncodingOptions, domain_pddl, problem_pddl
from artiplan.model import ArticulatedObject, Configuration, direction_error
from artiplan.pddl import load_task
from artiplan.semantics import Plan, TimedAction
from artiplan.semantics.validator import validate

TURN_S = 3.0  # s at 10 deg/s: a 30 deg turn of L2 about the normal of its vertical plane


def _predicted(init: Configuration, carry: str) -> Configuration:
    obj = ArticulatedObject(3)
    enc = EncodingOptions("ng", carry=carry)  # type: ignore[arg-type]
    task = load_task(domain_pddl(obj, enc), problem_pddl(obj, init, init, enc))
    plan = Plan((TimedAction(0.0, "start-increase", ("L1", "L2", "z-axis")),
                 TimedAction(TURN_S, "observe")))
    report = validate(task, plan)
    values = report.trajectory.values_at(TURN_S)

    def angle(link: str, plane: str, i: int) -> float:
        try:
            return float(values[report.trajectory.fluent_index(f"(angle {link} {plane})")])
        except KeyError:  # a fluent nothing changes is dropped by grounding
            return init.theta[i] if plane == "xy-axes" else init.gamma[i]

    links = ("L1", "L2", "L3")
    return Configuration(tuple(angle(lk, "xy-axes", i) for i, lk in enumerate(links)),
                         tuple(angle(lk, "z-axis", i) for i, lk in enumerate(links)))


@pytest.mark.parametrize("offset", [45.0, 90.0, 135.0, 180.0])
def test_projected_carry_follows_the_physics(offset: float) -> None:
    from artiplan.world import make_world

    # L2 in the vertical plane at azimuth 0; L3 at azimuth 0 + offset (across the plane, or
    # pointing back in it), both 60 deg from hanging.
    init = Configuration((0.0, 0.0, offset), (60.0, 60.0, 60.0))
    world = make_world(ArticulatedObject(3), init, hands="virtual", seed=0)
    world.hold_and_rotate("L1", "L2", "z-axis", +1, 10.0, reference=init)
    world.run_until(world.time + TURN_S)
    world.stop(release=False)
    physics = world.true_configuration(init)
    rigid = _predicted(init, "rigid")
    projected = _predicted(init, "projected")
    assert rigid.gamma[2] == pytest.approx(90.0, abs=0.1)  # the paper: +30 whatever the azimuth
    # Physics: gamma +30 cos(offset), plus a little gravity; the azimuth turns too.
    err_projected = float(direction_error(projected, physics)[2])
    err_rigid = float(direction_error(rigid, physics)[2])
    # Measured: rigid 11.7 / 31.7 / 52.4 / 61.5 deg, projected 5.0 / 2.7 / 6.1 / 1.5 deg (about
    # 2 deg of it is gravity, which NG leaves out; the rest, factors fixed at the start).
    assert err_projected < 7.0, (projected, physics)
    assert err_rigid > 10.0 and err_projected < err_rigid / 2, (err_rigid, err_projected)
