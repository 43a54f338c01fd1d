"""External and internal planners behind one interface, run under the same limits.

``get_planner(name)`` returns a :class:`Planner`; names: ``artiplan``, ``enhsp`` (ENHSP's default
settings, delta 1.0), ``enhsp-delta0.1`` (ENHSP with ``-delta 0.1``), ``kairos``.
"""

from __future__ import annotations

from collections.abc import Callable

from artiplan.backends.base import BackendResult, Planner, PlanStatus, status_name
from artiplan.errors import UsageError

__all__ = [
    "BackendResult", "Planner", "PlanStatus", "PLANNER_NAMES", "get_planner", "status_name",
]


def _artiplan() -> Planner:
    from artiplan.backends.artiplan_backend import ArtiplanPlanner

    return ArtiplanPlanner()


def _enhsp() -> Planner:
    from artiplan.backends.enhsp import EnhspPlanner

    return EnhspPlanner()


def _enhsp_fine() -> Planner:
    from artiplan.backends.enhsp import EnhspPlanner

    return EnhspPlanner(delta=0.1, name="enhsp-delta0.1")


def _kairos() -> Planner:
    from artiplan.backends.kairos import KairosPlanner

    return KairosPlanner()


_FACTORIES: dict[str, Callable[[], Planner]] = {
    "artiplan": _artiplan,
    "enhsp": _enhsp,
    "enhsp-delta0.1": _enhsp_fine,
    "kairos": _kairos,
}

#: Valid planner names, in the order reports list them.
PLANNER_NAMES: tuple[str, ...] = tuple(_FACTORIES)


def get_planner(name: str) -> Planner:
    """The planner called ``name``.

    Raises:
        UsageError: unknown name (the message lists the valid ones).
    """
    try:
        factory = _FACTORIES[name]
    except KeyError:
        raise UsageError(
            f"unknown planner {name!r}; valid planners: {', '.join(PLANNER_NAMES)}"
        ) from None
    return factory()
