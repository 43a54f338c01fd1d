"""The planner on reach-time encodings: the hands' ``hands-ready`` event unblocks the grasps.

Before the heuristic counted unblocking events as achievers, every state with the hands away
looked like a dead end (no action deletes ``(reaching)``), so the search never released the
hands: it spun a link for 695 s instead of a 15 s two-rotation plan.
"""

from __future__ import annotations

from artiplan.encoding import EncodingOptions, domain_pddl, make_goal
from artiplan.encoding.suite import make_task
from artiplan.execution.problem import build_problem, canonical
from artiplan.model import ArticulatedObject
from artiplan.search.api import PlanStatus, plan


def _solve(k: int, reach_time: float | None, hands_away: bool) -> float:
    obj = ArticulatedObject(4)
    enc = EncodingOptions("ucm", speed_g=0.948, reach_time=reach_time)
    task = make_task(4, k, seed=7)
    goal = make_goal(obj, canonical(task.target), "window", task.seed, planes=enc.planes,
                     tolerance=2.5)
    problem = build_problem(obj, task.initial, task.target, enc, goal, hands_away=hands_away)
    result = plan(domain_pddl(obj, enc), problem, time_limit=60)
    assert result.status is PlanStatus.SOLVED and result.plan is not None
    return result.plan.makespan


def test_reach_time_plans_release_and_regrasp() -> None:
    # Task 1 of the closed-loop benchmark: two rotations of L3 (xy, then z) in ~12 s.
    without = _solve(1, None, False)
    assert without < 20.0
    for reach, away in ((1.2, False), (1.2, True), (0.1, True)):
        with_reach = _solve(1, reach, away)
        # At most the reach waits (one before the first grasp, one per re-grasp) and a few
        # seconds of slower rotations on top: nowhere near a spin of hundreds of seconds.
        assert with_reach < without + 3 * reach + 5.0, (reach, away, with_reach)
