"""The plan's prediction as configurations: read a trajectory's angle fluents at any time."""

from __future__ import annotations

from artiplan.model import HORIZONTAL_PLANE, VERTICAL_PLANE, ArticulatedObject, Configuration
from artiplan.semantics import Trajectory


class Prediction:
    """A trajectory of the plan, started at simulated time ``t0`` [s] of the world."""

    def __init__(
        self, obj: ArticulatedObject, trajectory: Trajectory, t0: float, start: Configuration
    ) -> None:
        self.obj, self.trajectory, self.t0 = obj, trajectory, t0
        self._start = start
        self._index: list[tuple[int | None, int | None]] = []
        for link in obj.links:
            pair = (self._find(link, HORIZONTAL_PLANE), self._find(link, VERTICAL_PLANE))
            self._index.append(pair)

    def _find(self, link: str, plane: str) -> int | None:
        try:
            return self.trajectory.fluent_index(f"(angle {link} {plane})")
        except KeyError:  # a fluent nothing changes may have been dropped by grounding
            return None

    def at(self, t: float) -> Configuration:
        """Predicted configuration at world time ``t`` [s] (angles as the model holds them)."""
        values = self.trajectory.values_at(max(0.0, t - self.t0))
        theta, gamma = [], []
        for i, (ix, iz) in enumerate(self._index):
            theta.append(values[ix] if ix is not None else self._start.theta[i])
            gamma.append(values[iz] if iz is not None else self._start.gamma[i])
        return Configuration(tuple(theta), tuple(gamma))
