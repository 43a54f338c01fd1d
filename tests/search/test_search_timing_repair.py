"""The timing repair's own solver: sequential quadratic programming, no scipy."""

from __future__ import annotations

import math
from pathlib import Path

from artiplan.pddl import load_task
from artiplan.search.timing import (
    Repair,
    _cholesky,
    _qp_step,
    _solve_lower,
    _solve_upper,
    repair_times,
)
from artiplan.semantics import Kernel, compile_task
from artiplan.semantics.plan import Plan, TimedAction
from artiplan.semantics.validator import validate

FAMILIES = Path(__file__).resolve().parents[2] / "benchmarks" / "pddlplus"


def test_the_step_is_the_shortest_that_meets_every_row() -> None:
    # d0 >= 1, d1 >= 2, d0 + d1 >= 1 (slack at the answer): the nearest point is (1, 2)
    eye = [[1.0, 0.0], [0.0, 1.0]]
    d, lam = _qp_step(eye, [([1.0, 0.0], 1.0), ([0.0, 1.0], 2.0), ([1.0, 1.0], 1.0)])
    assert math.isclose(d[0], 1.0, abs_tol=1e-6) and math.isclose(d[1], 2.0, abs_tol=1e-6)
    # multipliers: the two binding rows carry the step (d = lam0 * a0 + lam1 * a1), the slack
    # one none
    assert math.isclose(lam[0], 1.0, abs_tol=1e-6) and math.isclose(lam[1], 2.0, abs_tol=1e-6)
    assert lam[2] == 0.0


def test_the_step_follows_the_curvature_estimate() -> None:
    # d0 + d1 >= 1 with B = diag(1, 4): d1 costs four times as much, so d = (0.8, 0.2)
    d, _ = _qp_step([[1.0, 0.0], [0.0, 4.0]], [([1.0, 1.0], 1.0)])
    assert math.isclose(d[0], 0.8, abs_tol=1e-6) and math.isclose(d[1], 0.2, abs_tol=1e-6)


def test_conflicting_rows_give_a_finite_compromise() -> None:
    d, _ = _qp_step([[1.0]], [([1.0], 1.0), ([-1.0], 0.0)])  # d >= 1 and d <= 0
    assert math.isfinite(d[0]) and -0.1 < d[0] < 1.1


def test_a_row_no_step_changes_is_left_out() -> None:
    d, lam = _qp_step([[1.0]], [([0.0], 5.0), ([1.0], 0.5)])
    assert math.isclose(d[0], 0.5, abs_tol=1e-9) and lam[0] == 0.0


def test_cholesky_and_triangular_solves_invert_the_matrix() -> None:
    a = [[4.0, 2.0, 0.4], [2.0, 3.0, 0.5], [0.4, 0.5, 2.0]]
    low = _cholesky(a)
    b = [1.0, -2.0, 0.5]
    x = _solve_upper(low, _solve_lower(low, b))  # a^-1 b
    back = [sum(a[i][k] * x[k] for k in range(3)) for i in range(3)]
    assert all(math.isclose(u, v, abs_tol=1e-12) for u, v in zip(back, b, strict=True))


def test_a_capture_inside_a_radius_is_timed() -> None:
    # intercept p08: steer at 35 s and capture right after misses the target by ~72 (squared
    # distance over the radius); the distance is a parabola in time, and steps that ignore its
    # curvature zigzag past the minimum until the budget is gone (the first version of this
    # solver did). The repaired skeleton must be valid for the validator.
    domain, problem = FAMILIES / "intercept" / "domain.pddl", FAMILIES / "intercept" / "p08.pddl"
    task = load_task(domain, problem)
    ct = compile_task(task)
    index = {(a.name, a.args): a.index for a in ct.actions}
    skeleton = [index[("steer", ("h1",))], index[("capture", ())]]
    guess = [35.0, 35.001]
    evals: list[int] = []
    fixed = repair_times(ct, Kernel(ct), skeleton, guess, Repair(), evals=evals)
    assert fixed is not None
    assert evals[0] <= Repair().max_evals + 10
    found = Plan(tuple(TimedAction(round(t, 6), ct.actions[a].name, ct.actions[a].args)
                       for a, t in zip(skeleton, fixed, strict=True)))
    report = validate(task, found)
    assert report.valid, report.reason
