"""Read a PDDL+ domain and problem into a unified-planning problem.

unified-planning's own :class:`~unified_planning.io.PDDLReader` wants a domain's operators in
a fixed order (every action, then every process, then every event); the paper's domains and
artiplan's encodings mix them. :func:`read_pddl` parses with artiplan's parser, prints the
domain back with its operators in that order, and hands both texts to unified-planning's reader.
"""

from __future__ import annotations

import dataclasses
from pathlib import Path

from unified_planning.io import PDDLReader
from unified_planning.model import Problem

from artiplan.pddl import load_domain, write_domain

#: unified-planning's reader order of operator kinds.
_ORDER = {"action": 0, "durative-action": 0, "process": 1, "event": 2}


def reordered_domain(domain: str | Path) -> str:
    """The domain (path or text) printed back with actions, then processes, then events."""
    parsed = load_domain(domain)
    ops = tuple(sorted(parsed.operators, key=lambda op: _ORDER.get(op.kind, 0)))
    return write_domain(dataclasses.replace(parsed, operators=ops))


def read_pddl(domain: str | Path, problem: str | Path) -> Problem:
    """A unified-planning problem from PDDL+ (paths or text).

    Raises artiplan's InputError (file:line:col) when artiplan's parser refuses the domain.
    """
    problem_text = _text(problem)
    return PDDLReader().parse_problem_string(reordered_domain(domain), problem_text)


def _text(source: str | Path) -> str:
    """PDDL text given as text or as a path (text starts with ``(`` or ``;``, or has lines)."""
    if isinstance(source, str) and (source.lstrip().startswith(("(", ";")) or "\n" in source):
        return source
    return Path(source).read_text(encoding="utf-8")
