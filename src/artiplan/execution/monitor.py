"""The monitor: compares what is perceived with what the plan predicted (direction angles)."""

from __future__ import annotations

import math
from dataclasses import dataclass

from artiplan.model import ArticulatedObject, Configuration, direction_error


@dataclass(frozen=True)
class Verdict:
    """One comparison: per-link direction errors [deg] (L1 first), whether it fired, the link
    nearest (or furthest past) its threshold and that threshold [deg]."""

    errors: tuple[float, ...]
    fired: bool
    worst_link: str
    threshold: float = 0.0

    @property
    def max_error(self) -> float:
        """Largest per-link error [deg], L1 (clamped) excluded."""
        return max(self.errors[1:], default=0.0)

    @property
    def worst_error(self) -> float:
        """Error of :attr:`worst_link` [deg]."""
        return self.errors[int(self.worst_link[1:]) - 1]


class Monitor:
    """Fires when any link's direction error passes its threshold [deg].

    Goal links (and, without ``goal_links``, every link) use ``threshold_deg``; the other
    links ``other_threshold_deg`` (default: the same); without ``tip_links`` the links tip-ward
    of every goal link are not monitored (infinite threshold). A wider threshold off the goal
    tolerates the PDDL+ model's known geometric gap on carried links (it adds a rotation's angle
    to every carried link's angle) while still catching a human moving a link that matters.
    L1 is clamped and not monitored. Noise below the threshold never fires it: the decision is
    a plain comparison of the perceived and predicted link directions.
    """

    def __init__(self, obj: ArticulatedObject, threshold_deg: float,
                 goal_links: tuple[str, ...] = (),
                 other_threshold_deg: float | None = None, tip_links: bool = True) -> None:
        if threshold_deg <= 0 or (other_threshold_deg is not None and other_threshold_deg <= 0):
            raise ValueError("thresholds must be positive")
        self.obj, self.threshold_deg = obj, threshold_deg
        other = threshold_deg if other_threshold_deg is None else other_threshold_deg
        self.other = other
        last_goal = max((obj.index(lk) for lk in goal_links), default=obj.n_links)
        self.thresholds = tuple(
            threshold_deg if not goal_links or lk in goal_links
            else other if tip_links or obj.index(lk) < last_goal else float("inf")
            for lk in obj.links
        )

    def check(self, predicted: Configuration, perceived: Configuration,
              carried: frozenset[str] = frozenset()) -> Verdict:
        """Compare one percept with the prediction at the same time.

        Links in ``carried`` (carried by a vertical-plane rotation now in progress, whose effect
        on them the model gets wrong) are not judged meanwhile: stopping mid-rotation to
        re-plan would only start the same rotation again; whatever error remains (or a push)
        is caught at the first percept after the rotation stops.
        """
        errs = tuple(float(e) for e in direction_error(predicted, perceived))
        limits = [math.inf if lk in carried else t
                  for lk, t in zip(self.obj.links, self.thresholds, strict=True)]
        # Worst link relative to its own threshold (L1 excluded).
        ratios = [errs[i] / limits[i] for i in range(1, len(errs))]
        if not ratios:
            return Verdict(errs, False, self.obj.links[0], 0.0)
        k = max(range(len(ratios)), key=ratios.__getitem__)
        return Verdict(errs, ratios[k] > 1.0, self.obj.links[k + 1], limits[k + 1])


def goal_errors(
    obj: ArticulatedObject, target: Configuration, perceived: Configuration, links: tuple[str, ...]
) -> dict[str, float]:
    """Direction error [deg] of each goal link between the perceived state and the target."""
    errs = direction_error(target, perceived)
    return {lk: float(errs[obj.index(lk) - 1]) for lk in links}
