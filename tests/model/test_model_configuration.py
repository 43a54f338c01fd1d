"""Object and configuration basics: sets, JSON round trips, seeded randomness, snapping."""

from __future__ import annotations

import json
import random
from pathlib import Path

import pytest

from artiplan.model import (
    HORIZONTAL_PLANE,
    VERTICAL_PLANE,
    ArticulatedObject,
    Configuration,
    load_configuration,
    random_configuration,
    wrap_deg,
)
from artiplan.model.angles import in_window_deg, signed_delta_deg


def test_links_joints_up_down_affects() -> None:
    obj = ArticulatedObject(5)
    assert obj.links == ("L1", "L2", "L3", "L4", "L5")
    assert obj.joints == (("L1", "L2"), ("L2", "L3"), ("L3", "L4"), ("L4", "L5"))
    assert obj.up("L3") == ("L1", "L2")
    assert obj.down("L3") == ("L4", "L5")
    assert obj.up("L1") == () and obj.down("L5") == ()
    # 2 <= j < m <= n: L1 carries nothing (it never moves).
    assert obj.affects() == (
        ("L2", "L3"),
        ("L2", "L4"),
        ("L2", "L5"),
        ("L3", "L4"),
        ("L3", "L5"),
        ("L4", "L5"),
    )
    with pytest.raises(ValueError, match="valid links are L1..L5"):
        obj.index("L9")


def test_object_rejects_bad_sizes() -> None:
    with pytest.raises(ValueError):
        ArticulatedObject(1)
    with pytest.raises(ValueError):
        ArticulatedObject(3, link_length=0.0)


def test_configuration_json_round_trip(tmp_path: Path) -> None:
    obj = ArticulatedObject(4, link_length=0.2, base_position=(0.1, 0.2, 0.3))
    conf = random_configuration(4, random.Random(3))
    path = tmp_path / "c.json"
    conf.save(path, obj)
    data = json.loads(path.read_text())
    assert data["schema"] == "artiplan.configuration/1"
    assert [x["name"] for x in data["links"]] == ["L1", "L2", "L3", "L4"]
    back, back_obj = load_configuration(path)
    assert back == conf
    assert back_obj == obj
    assert Configuration.load(path) == conf


def test_configuration_without_object_gets_the_default_object(tmp_path: Path) -> None:
    path = tmp_path / "c.json"
    Configuration.hanging(3).save(path)
    conf, obj = load_configuration(path)
    assert obj == ArticulatedObject(3) and conf == Configuration.hanging(3)


def test_object_json_round_trip(tmp_path: Path) -> None:
    obj = ArticulatedObject(7, thickness=0.02, mass=0.1)
    obj.save(tmp_path / "o.json")
    assert ArticulatedObject.load(tmp_path / "o.json") == obj


def test_bad_configuration_json() -> None:
    with pytest.raises(ValueError, match="links"):
        Configuration.from_dict({"angles": []})
    with pytest.raises(ValueError):
        Configuration((1.0, 2.0), (1.0,))


def test_random_configuration_is_seeded_one_decimal_in_range() -> None:
    a = random_configuration(12, random.Random(42))
    b = random_configuration(12, random.Random(42))
    c = random_configuration(12, random.Random(43))
    assert a == b
    assert a != c
    for x in a.theta + a.gamma:
        assert 0.0 <= x < 360.0
        assert round(x, 1) == x


def test_angle_access_and_replacement() -> None:
    conf = Configuration.from_angles([10, 20, 30], [40, 50, 60])
    assert conf.angle(2, HORIZONTAL_PLANE) == 20.0
    assert conf.angle(3, VERTICAL_PLANE) == 60.0
    changed = conf.with_angle(2, VERTICAL_PLANE, 99.0)
    assert changed.gamma == (40.0, 99.0, 60.0) and changed.theta == conf.theta
    with pytest.raises(ValueError, match="unknown plane"):
        conf.angle(1, "yz")


def test_wrap_and_discretise() -> None:
    assert wrap_deg(360.0) == 0.0
    assert wrap_deg(-0.5) == pytest.approx(359.5)
    assert wrap_deg(725.0) == pytest.approx(5.0)
    assert 0.0 <= wrap_deg(-1e-18) < 360.0
    conf = Configuration.from_angles([358.0, 14.0], [-8.0, 46.0])
    assert conf.wrapped().gamma[0] == pytest.approx(352.0)
    snapped = conf.discretised(15.0)
    assert snapped.theta == (0.0, 15.0) and snapped.gamma == (345.0, 45.0)


def test_angle_window_across_the_wrap() -> None:
    assert signed_delta_deg(358.0, 2.0) == pytest.approx(4.0)
    assert in_window_deg(358.0, 0.0, 5.0) and in_window_deg(2.0, 0.0, 5.0)
    assert not in_window_deg(6.0, 0.0, 5.0)
