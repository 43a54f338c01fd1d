"""relative_turn: how far a link turned against another between two configurations."""

from __future__ import annotations

import pytest

from artiplan.model import Configuration
from artiplan.model.kinematics import relative_turn


def test_a_chain_carried_whole_has_not_turned_against_itself() -> None:
    then = Configuration((0.0, 30.0, 150.0), (0.0, 60.0, 100.0))
    carried = Configuration((0.0, 80.0, 200.0), (0.0, 60.0, 100.0))  # both turned 50 about z
    assert relative_turn(then, carried, 3, 2) == pytest.approx(0.0, abs=1e-6)
    assert relative_turn(then, carried, 3, 1) == pytest.approx(50.0 * 0.98, abs=2.0)


def test_a_fold_opened_by_its_own_link_is_measured_in_degrees() -> None:
    then = Configuration((0.0, 0.0, 0.0), (0.0, 160.0, 20.0))  # L2 up, L3 folded back down
    opened = Configuration((0.0, 0.0, 0.0), (0.0, 160.0, 45.0))
    assert relative_turn(then, opened, 3, 2) == pytest.approx(25.0, abs=1e-6)
    fell = Configuration((0.0, 0.0, 0.0), (0.0, 130.0, 350.0))  # both fell 30 deg together
    assert relative_turn(then, fell, 3, 2) == pytest.approx(0.0, abs=1e-6)
    assert relative_turn(then, fell, 2, 1) == pytest.approx(30.0, abs=1e-6)
