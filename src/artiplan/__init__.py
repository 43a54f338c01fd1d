"""artiplan: reshape articulated objects with a dual-arm robot, planning in PDDL+ with gravity.

The pipeline, one sub-package a stage: ``model`` -> ``encoding`` -> ``pddl`` -> ``semantics`` ->
``search`` -> ``backends`` -> ``world`` -> ``execution`` -> ``bench`` -> ``viz``.
"""

from __future__ import annotations

TYPE_CHECKING = False  # read as true by mypy; typing is not imported at run time (start-up)
if TYPE_CHECKING:
    from typing import Any

__version__ = "0.1.0"


def plan(domain: str, problem: str, **options: Any) -> Any:
    """Plan with artiplan's own PDDL+ planner; see :func:`artiplan.search.api.plan`.

    Imported lazily so that ``import artiplan`` stays cheap.
    """
    from artiplan.search.api import plan as _plan

    return _plan(domain, problem, **options)


__all__ = ["__version__", "plan"]
