"""artiplan inside unified-planning: ``OneshotPlanner(name="artiplan")`` and
``PlanValidator(name="artiplan")`` for PDDL+ problems (processes, events, continuous change).

Install with ``pip install "artiplan[up]"``. Importing this package registers the engine with
unified-planning's factory (unified-planning 1.3 has no entry-point mechanism for third-party
engines: its factory knows a fixed list of modules, plus ``up.ini`` files next to the user's
script or in the home folder)::

    import artiplan.up  # registers "artiplan"
    from unified_planning.shortcuts import OneshotPlanner, PlanValidator

    with OneshotPlanner(name="artiplan") as planner:
        result = planner.solve(problem, timeout=60)
    with PlanValidator(name="artiplan") as validator:
        print(validator.validate(problem, result.plan))

Modules: :mod:`~artiplan.up.engine` (the engine and its parameters), :mod:`~artiplan.up.planner`,
:mod:`~artiplan.up.validator`, :mod:`~artiplan.up.convert` (problems and plans both ways),
:mod:`~artiplan.up.ending` (where a plan without an end marker ends), :mod:`~artiplan.up.kinds`
(the supported problem kinds), :mod:`~artiplan.up.reader` (PDDL+ files -> unified-planning).
"""

from __future__ import annotations

from typing import Any

try:
    import unified_planning  # noqa: F401
except ImportError as exc:  # pragma: no cover - depends on the installation
    raise ImportError(
        "artiplan.up needs unified-planning: pip install 'artiplan[up]'"
    ) from exc

from artiplan.up.engine import NAME, ArtiplanEngine
from artiplan.up.reader import read_pddl


def register(environment: Any = None) -> None:
    """Add the ``artiplan`` engine to ``environment``'s factory (default: the global one).

    Idempotent: a second call changes nothing.
    """
    from unified_planning.environment import get_environment

    factory = (environment or get_environment()).factory
    if NAME not in factory.engines:
        factory.add_engine(NAME, "artiplan.up.engine", "ArtiplanEngine")


register()

__all__ = ["NAME", "ArtiplanEngine", "read_pddl", "register"]
