"""Configurations: absolute angles (theta, gamma) [deg] for every link.

theta_l lies on the horizontal plane (``xy-axes``), counter-clockwise from +x seen from above;
gamma_l on the vertical plane (``z-axis``), measured from straight down (0 hangs, 90 is
horizontal, 180 points up). See shared/docs/conventions.md.
"""

from __future__ import annotations

import json
import random
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from artiplan.errors import InputError
from artiplan.model.angles import wrap_deg
from artiplan.model.obj import HORIZONTAL_PLANE, VERTICAL_PLANE, ArticulatedObject

SCHEMA_CONFIGURATION = "artiplan.configuration/1"


@dataclass(frozen=True)
class Configuration:
    """Absolute orientation of every link, base (L1) first.

    Attributes:
        theta: Horizontal-plane angle per link [deg].
        gamma: Vertical-plane angle per link [deg], 0 = hanging down.
    """

    theta: tuple[float, ...]
    gamma: tuple[float, ...]

    def __post_init__(self) -> None:
        if len(self.theta) != len(self.gamma):
            raise ValueError(f"theta has {len(self.theta)} values but gamma has {len(self.gamma)}")
        if len(self.theta) < 2:
            raise ValueError("a configuration needs at least 2 links")

    @property
    def n_links(self) -> int:
        return len(self.theta)

    @classmethod
    def from_angles(cls, theta: Sequence[float], gamma: Sequence[float]) -> Configuration:
        return cls(tuple(float(t) for t in theta), tuple(float(g) for g in gamma))

    @classmethod
    def hanging(cls, n_links: int) -> Configuration:
        """Every link hanging straight down (gravity's rest)."""
        return cls((0.0,) * n_links, (0.0,) * n_links)

    def angle(self, link_index: int, plane: str) -> float:
        """Angle [deg] of link ``link_index`` (1-based) on ``plane``."""
        if plane == HORIZONTAL_PLANE:
            return self.theta[link_index - 1]
        if plane == VERTICAL_PLANE:
            return self.gamma[link_index - 1]
        raise ValueError(
            f"unknown plane {plane!r}; valid planes: {HORIZONTAL_PLANE}, {VERTICAL_PLANE}"
        )

    def with_angle(self, link_index: int, plane: str, value: float) -> Configuration:
        """A copy with one angle replaced."""
        theta, gamma = list(self.theta), list(self.gamma)
        target = theta if plane == HORIZONTAL_PLANE else gamma
        if plane not in (HORIZONTAL_PLANE, VERTICAL_PLANE):
            raise ValueError(f"unknown plane {plane!r}")
        target[link_index - 1] = float(value)
        return Configuration(tuple(theta), tuple(gamma))

    def wrapped(self) -> Configuration:
        """Every angle mapped into [0, 360)."""
        return Configuration(
            tuple(wrap_deg(t) for t in self.theta), tuple(wrap_deg(g) for g in self.gamma)
        )

    def discretised(self, step: float) -> Configuration:
        """Every angle snapped to the nearest multiple of ``step`` [deg], wrapped to [0, 360)."""
        if step <= 0:
            raise ValueError("step must be positive")

        def snap(a: float) -> float:
            return wrap_deg(round(a / step) * step)

        return Configuration(tuple(snap(t) for t in self.theta), tuple(snap(g) for g in self.gamma))

    def to_dict(self, obj: ArticulatedObject | None = None) -> dict[str, Any]:
        d: dict[str, Any] = {
            "schema": SCHEMA_CONFIGURATION,
            "links": [
                {"name": f"L{i + 1}", "theta": t, "gamma": g}
                for i, (t, g) in enumerate(zip(self.theta, self.gamma, strict=True))
            ],
        }
        if obj is not None:
            d["object"] = obj.to_dict()
        return d

    @classmethod
    def from_dict(cls, d: dict[str, Any]) -> Configuration:
        try:
            links = d["links"]
            return cls(
                tuple(float(x["theta"]) for x in links), tuple(float(x["gamma"]) for x in links)
            )
        except (KeyError, TypeError, ValueError) as exc:
            raise ValueError(
                "a configuration needs 'links': [{'name','theta','gamma'}, ...]"
            ) from exc

    def save(self, path: str | Path, obj: ArticulatedObject | None = None) -> None:
        Path(path).write_text(json.dumps(self.to_dict(obj), indent=2) + "\n")

    @classmethod
    def load(cls, path: str | Path) -> Configuration:
        return cls.from_dict(json.loads(Path(path).read_text()))


def load_configuration(path: str | Path) -> tuple[Configuration, ArticulatedObject]:
    """Read a configuration file and the object it describes (default object when absent).

    Raises:
        InputError: The file is missing, is not JSON, or does not describe a configuration
            (exit code 3 on the command line).
    """
    try:
        d = json.loads(Path(path).read_text())
        conf = Configuration.from_dict(d)
        obj = (
            ArticulatedObject.from_dict(d["object"])
            if "object" in d
            else ArticulatedObject(conf.n_links)
        )
    except FileNotFoundError:
        raise InputError(f"{path}: no such file") from None
    except (OSError, ValueError, TypeError) as exc:  # JSONDecodeError is a ValueError
        raise InputError(f"{path}: {exc}") from None
    if obj.n_links != conf.n_links:
        raise InputError(f"{path}: object has {obj.n_links} links, configuration {conf.n_links}")
    return conf, obj


def random_configuration(n_links: int, rng: random.Random) -> Configuration:
    """theta, gamma uniform in [0, 360) with one decimal, for every link.

    Uses the standard library's Mersenne Twister so a seed gives the same configuration on every
    platform and Python version.
    """

    def draw() -> float:
        return round(rng.uniform(0.0, 360.0), 1) % 360.0

    theta, gamma = [], []
    for _ in range(n_links):
        theta.append(draw())
        gamma.append(draw())
    return Configuration(tuple(theta), tuple(gamma))
