"""The plan's prediction as configurations: read a trajectory's angle fluents at any time."""

from __future__ import annotations

from dataclasses import dataclass

from artiplan.model import HORIZONTAL_PLANE, VERTICAL_PLANE, ArticulatedObject, Configuration
from artiplan.model.angles import wrap_deg
from artiplan.semantics import Trajectory


@dataclass(frozen=True)
class Fade:
    """An offset [deg] on one angle (1-based link ``index``, ``plane``) that is ``offset`` at
    world time ``t_from`` [s] and shrinks linearly to 0 at ``t_to`` [s]."""

    t_from: float
    t_to: float
    index: int
    plane: str
    offset: float

    def at(self, t: float) -> float:
        if not self.t_from <= t < self.t_to:
            return 0.0
        return self.offset * (self.t_to - t) / (self.t_to - self.t_from)


class Prediction:
    """A trajectory of the plan, started at simulated time ``t0`` [s] of the world."""

    def __init__(
        self, obj: ArticulatedObject, trajectory: Trajectory, t0: float, start: Configuration
    ) -> None:
        self.obj, self.trajectory, self.t0 = obj, trajectory, t0
        self._start = start
        #: Offsets that bring the prediction to where links were seen (see :meth:`fade`).
        self.fades: list[Fade] = []
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
        for f in self.fades:
            off = f.at(t)
            if off:
                angles = theta if f.plane == HORIZONTAL_PLANE else gamma
                angles[f.index - 1] = wrap_deg(angles[f.index - 1] + off)
        return Configuration(tuple(theta), tuple(gamma))

    def fade(self, offsets: dict[int, float], plane: str, t_from: float, t_to: float) -> None:
        """From world time ``t_from`` [s] on, predict the angles on ``plane`` of the links
        ``offsets`` names (1-based) off the plan by their offset [deg], the offset shrinking
        linearly to none at ``t_to`` [s]: a turn that starts behind its prediction and catches
        it up at its own speed (execution.regrasp). Expired fades are dropped."""
        self.fades = [f for f in self.fades if f.t_to > t_from]
        if t_to > t_from:
            self.fades += [Fade(t_from, t_to, i, plane, off) for i, off in offsets.items()]
