"""Where the plans aim: the goal windows shifted by the residuals execution left before.

A plan that ends without the goal tells the loop how far off its model leaves the goal links.
On 6-link chains that residual is not noise: after NG plans (the fallback model, no gravity)
the goal links ended 4-5 deg low on the vertical plane in 92% of the cases (sessions 15-16
logs: released links sag at the fall speed while the hands work elsewhere), after UCM plans
about 0. So the next plans with the same model aim each goal link's vertical-plane window
higher by what the last ones missed by (integral action, per model and link), while the
acceptance is still judged against the true target. A gravity-free plan whose goal link the
monitor finds sunk mid-plan teaches the same (``Aim.observe_sag``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace

from artiplan.encoding.goals import AngleWindow, GoalSpec
from artiplan.execution.monitor import goal_errors
from artiplan.execution.problem import canonical
from artiplan.model import ArticulatedObject, Configuration
from artiplan.model.angles import signed_delta_deg

#: The vertical plane: the angle a released link sags on.
VERTICAL = "z-axis"


@dataclass
class Aim:
    """Offsets [deg] added to the goal links' vertical-plane window centres, per model.

    Attributes:
        gain: Fraction of each observed residual added to the offset (1: integral action).
        limit_deg: Offsets stay within +-this [deg].
        max_error_deg: A residual is used only when the link's direction error is below this
            [deg] (a link far off says nothing about the bias of a plan that reached nearly).
        pole_deg: Nor within this [deg] of a pole (gamma 0 or 180), where gamma is not a
            sag's measure and a shifted window could cross the pole.
        offsets: (model, link) -> offset [deg]; positive aims higher (gamma up).
    """

    gain: float = 1.0
    limit_deg: float = 10.0
    max_error_deg: float = 25.0
    pole_deg: float = 10.0
    offsets: dict[tuple[str, str], float] = field(default_factory=dict)

    def observe(self, obj: ArticulatedObject, model: str, target: Configuration,
                perceived: Configuration, links: tuple[str, ...]) -> dict[str, float]:
        """Learn from a plan of ``model`` that ended at ``perceived`` short of ``target``.

        Returns:
            The residuals used [deg, perceived minus target gamma on canonical covers], by link.
        """
        errs = goal_errors(obj, target, perceived, links)
        tgt, got = canonical(target), canonical(perceived)
        used: dict[str, float] = {}
        for lk in links:
            i = obj.index(lk) - 1
            g_t = tgt.gamma[i]
            if errs[lk] >= self.max_error_deg or not self.pole_deg < g_t < 180.0 - self.pole_deg:
                continue
            residual = got.gamma[i] - g_t
            self._add(model, lk, residual)
            used[lk] = round(residual, 3)
        return used

    def observe_sag(self, obj: ArticulatedObject, model: str, predicted: Configuration,
                    perceived: Configuration, link: str) -> float | None:
        """Learn from the monitor firing on goal ``link`` of a plan of ``model`` (one without
        gravity, NG: it predicts a released link stays where it was turned) when the link sank
        on the vertical plane: the next plans aim higher by what it sank so far.

        Only a sinking (gamma down, at least twice the arc it moved sideways), not near a pole
        nor far off: anything else is not sag (a push, a lost grasp). Returns the residual
        used [deg, perceived minus predicted gamma], or None.
        """
        i = obj.index(link) - 1
        err = float(goal_errors(obj, predicted, perceived, (link,))[link])
        pred, got = canonical(predicted), canonical(perceived)
        g_p = pred.gamma[i]
        if err >= self.max_error_deg or not self.pole_deg < g_p < 180.0 - self.pole_deg:
            return None
        down = got.gamma[i] - g_p
        side = signed_delta_deg(pred.theta[i], got.theta[i]) * math.sin(math.radians(g_p))
        if down >= 0.0 or abs(down) < 2.0 * abs(side):
            return None
        self._add(model, link, down)
        return round(down, 3)

    def _add(self, model: str, link: str, residual: float) -> None:
        key = (model, link)
        off = self.offsets.get(key, 0.0) - self.gain * residual
        self.offsets[key] = max(-self.limit_deg, min(self.limit_deg, off))

    def goal(self, goal: GoalSpec, model: str) -> GoalSpec:
        """``goal`` with the vertical-plane windows of ``model``'s offset links moved (their
        centres kept inside [half-width, 180 - half-width]: a window stays on one side of
        each pole, as the canonical covers the problems start from)."""
        if not any(m == model for m, _ in self.offsets):
            return goal

        def moved(c: AngleWindow) -> AngleWindow:
            centre = c.centre + self.offsets.get((model, c.link), 0.0)
            return replace(c, centre=max(c.half_width, min(180.0 - c.half_width, centre)))

        conds = tuple(moved(c) if isinstance(c, AngleWindow) and c.plane == VERTICAL
                      and (model, c.link) in self.offsets else c for c in goal.conditions)
        return replace(goal, conditions=conds)

    def of(self, model: str) -> dict[str, float]:
        """The offsets in use for ``model`` [deg], by link (for the log)."""
        return {lk: round(v, 3) for (m, lk), v in sorted(self.offsets.items()) if m == model}
