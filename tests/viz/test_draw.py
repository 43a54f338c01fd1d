"""``artiplan draw``: a PNG of the object, the clamp, and a target ghost."""

from __future__ import annotations

import random
from pathlib import Path

import numpy as np
import pytest
from PIL import Image

from artiplan.cli import main
from artiplan.encoding.suite import random_pair
from artiplan.model import ArticulatedObject, Configuration
from artiplan.viz.draw import draw_configuration


def _pixels(path: Path) -> np.ndarray:
    with Image.open(path) as im:
        assert im.format == "PNG"
        return np.asarray(im.convert("RGB"), dtype=np.int16)


def test_draw_writes_a_png_and_the_ghost_shows(tmp_path: Path) -> None:
    obj = ArticulatedObject(4)
    init, target = random_pair(4, random.Random(2))
    plain = draw_configuration(obj, init, tmp_path / "a.png")
    ghost = draw_configuration(obj, init, tmp_path / "b.png", target=target)
    a, b = _pixels(plain), _pixels(ghost)
    assert a.shape[0] > 300 and a.shape[1] > 300
    assert (a != 255).any()  # something is drawn
    assert (np.abs(a - b).sum(axis=2) > 30).sum() > 500  # the ghost adds visible pixels


def test_draw_command(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    obj = ArticulatedObject(3)
    Configuration.hanging(3).save(tmp_path / "c.json", obj)
    Configuration.from_angles([0, 90, 90], [0, 90, 180]).save(tmp_path / "t.json", obj)
    out = tmp_path / "x" / "c.png"
    rc = main(
        ["draw", str(tmp_path / "c.json"), "--target", str(tmp_path / "t.json"), "-o", str(out)]
    )
    assert rc == 0 and out.is_file()
    assert str(out) in capsys.readouterr().out


def test_draw_bad_input(tmp_path: Path) -> None:
    (tmp_path / "bad.json").write_text('{"links": [{"theta": 1}]}')
    assert main(["draw", str(tmp_path / "bad.json"), "-o", str(tmp_path / "o.png")]) == 3
    assert main(["draw", str(tmp_path / "missing.json"), "-o", str(tmp_path / "o.png")]) == 3
    Configuration.hanging(3).save(tmp_path / "c3.json")
    Configuration.hanging(4).save(tmp_path / "c4.json")
    rc = main(
        [
            "draw",
            str(tmp_path / "c3.json"),
            "--target",
            str(tmp_path / "c4.json"),
            "-o",
            str(tmp_path / "o.png"),
        ]
    )
    assert rc == 3


def test_angle_wraps_run_to_the_band_edges_and_cover_flips_break() -> None:
    import math

    from artiplan.viz.execution import wrap_breaks

    # 350 -> 10 deg in 1 s: up through 360 at t = 0.5 s, on from 0.
    t, v = wrap_breaks([0.0, 1.0], [350.0, 10.0])
    assert t[:4] == [0.0, 0.5, 0.5, 0.5] and v[1] == 360.0 and math.isnan(v[2])
    assert v[3] == 0.0 and (t[-1], v[-1]) == (1.0, 10.0)
    # ... and down through 0 the other way round.
    t, v = wrap_breaks([0.0, 2.0], [5.0, 355.0])
    assert v[1] == 0.0 and t[1] == 1.0 and v[3] == 360.0
    # A jump of ~180 deg is a change of representation, not a wrap: the line just breaks.
    t, v = wrap_breaks([0.0, 1.0, 2.0], [88.0, 270.0, 272.0])
    assert len(v) == 4 and math.isnan(v[1]) and v[2:] == [270.0, 272.0]
    # Nothing to do for a smooth series.
    assert wrap_breaks([0.0, 1.0], [10.0, 20.0]) == ([0.0, 1.0], [10.0, 20.0])


def test_a_change_of_double_cover_is_found_and_not_drawn() -> None:
    import math

    from artiplan.viz.execution import cover_flips, wrap_breaks

    thetas, gammas = [88.0, 89.0, 269.5, 270.0], [124.0, 125.0, 235.5, 236.0]
    assert cover_flips(thetas, gammas) == {2}
    assert cover_flips([10.0, 20.0, 30.0], [100.0, 110.0, 120.0]) == set()
    _, v = wrap_breaks([0.0, 1.0, 2.0, 3.0], gammas, {2})
    assert math.isnan(v[2]) and v[3] == 235.5
