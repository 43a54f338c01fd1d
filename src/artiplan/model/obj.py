"""The articulated object: an ordered chain of rigid links joined by ball joints."""

from __future__ import annotations

import json
from dataclasses import asdict, dataclass
from pathlib import Path
from typing import Any

#: Plane names as the paper's PDDL+ models spell them.
HORIZONTAL_PLANE = "xy-axes"  #: theta: rotation about the world vertical
VERTICAL_PLANE = "z-axis"  #: gamma: the vertical plane, where gravity acts
PLANES: tuple[str, str] = (HORIZONTAL_PLANE, VERTICAL_PLANE)

SCHEMA_OBJECT = "artiplan.object/1"


@dataclass(frozen=True)
class ArticulatedObject:
    """A chain of ``n_links`` links L1 (base, clamped) .. Ln (tip).

    Attributes:
        n_links: Number of links, at least 2.
        link_length: Length of every link in [m] (the paper: 0.15).
        thickness: Link thickness (diameter of its capsule) in [m].
        mass: Mass of one link in [kg] (used by the physics world only).
        base_position: Base end of L1 in the world frame, [m].
    """

    n_links: int
    link_length: float = 0.15
    thickness: float = 0.03
    mass: float = 0.05
    base_position: tuple[float, float, float] = (0.0, 0.0, 0.0)

    def __post_init__(self) -> None:
        if self.n_links < 2:
            raise ValueError(f"an articulated object needs at least 2 links, got {self.n_links}")
        if self.link_length <= 0 or self.thickness <= 0 or self.mass <= 0:
            raise ValueError("link_length, thickness and mass must be positive")

    @property
    def links(self) -> tuple[str, ...]:
        """Link names L1 .. Ln, base to tip."""
        return tuple(f"L{i}" for i in range(1, self.n_links + 1))

    @property
    def joints(self) -> tuple[tuple[str, str], ...]:
        """Joints as pairs of neighbouring links (l_k, l_k+1), base to tip."""
        names = self.links
        return tuple((names[i], names[i + 1]) for i in range(self.n_links - 1))

    @property
    def base(self) -> str:
        """The clamped base link: never rotated, no gravity, named by no goal."""
        return "L1"

    def index(self, link: str) -> int:
        """1-based index of ``link`` (``'L3'`` -> 3)."""
        try:
            i = self.links.index(link)
        except ValueError:
            raise ValueError(
                f"unknown link {link!r}; valid links are L1..L{self.n_links}"
            ) from None
        return i + 1

    def up(self, link: str) -> tuple[str, ...]:
        """Links base-ward of ``link`` (L1 .. l_j-1)."""
        return self.links[: self.index(link) - 1]

    def down(self, link: str) -> tuple[str, ...]:
        """Links tip-ward of ``link`` (l_j+1 .. Ln)."""
        return self.links[self.index(link) :]

    def affects(self) -> tuple[tuple[str, str], ...]:
        """Pairs (l_j, l_m), 2 <= j < m <= n: moving l_j carries l_m."""
        names = self.links
        return tuple(
            (names[j], names[m]) for j in range(1, self.n_links) for m in range(j + 1, self.n_links)
        )

    def to_dict(self) -> dict[str, Any]:
        d = asdict(self)
        d["base_position"] = list(self.base_position)
        return {"schema": SCHEMA_OBJECT, **d}

    @classmethod
    def from_dict(cls, d: dict[str, Any]) -> ArticulatedObject:
        d = {k: v for k, v in d.items() if k != "schema"}
        if "base_position" in d:
            d["base_position"] = tuple(float(x) for x in d["base_position"])
        return cls(**d)

    def save(self, path: str | Path) -> None:
        Path(path).write_text(json.dumps(self.to_dict(), indent=2) + "\n")

    @classmethod
    def load(cls, path: str | Path) -> ArticulatedObject:
        return cls.from_dict(json.loads(Path(path).read_text()))
