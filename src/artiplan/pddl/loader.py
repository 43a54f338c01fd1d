"""Load a task from files or text: parse, check and ground in one call.

Paths are ``str`` or ``os.PathLike`` (``pathlib`` is not imported: ``artiplan plan``'s
start-up)."""

from __future__ import annotations

import os

from artiplan.errors import InputError
from artiplan.pddl import syntax as s
from artiplan.pddl.grounding import ground
from artiplan.pddl.parser import parse_domain, parse_problem
from artiplan.pddl.task import Task

TYPE_CHECKING = False  # read as true by mypy; typing is not imported at run time (start-up)
if TYPE_CHECKING:
    from collections.abc import Callable


def read_source(source: str | os.PathLike[str], default_name: str) -> tuple[str, str]:
    """``(text, filename)`` of a path or of PDDL text (text starts with ``(`` or ``;``)."""
    if isinstance(source, os.PathLike):
        name = os.fspath(source)
        return _read(name), name
    stripped = source.lstrip()
    if stripped.startswith(("(", ";")) or "\n" in source:
        return source, default_name
    return _read(source), source


def _read(path: str) -> str:
    try:
        with open(path, encoding="utf-8") as fh:
            return fh.read()
    except OSError as exc:
        raise InputError(f"cannot read {path}: {exc.strerror or exc}") from exc
    except UnicodeDecodeError as exc:
        raise InputError(f"{path} is not UTF-8 text: {exc}") from exc


def load_domain(source: str | os.PathLike[str]) -> s.Domain:
    """Parse and check a domain given as a path or as text."""
    text, name = read_source(source, "<domain>")
    return parse_domain(text, name)


def load_problem(source: str | os.PathLike[str]) -> s.Problem:
    """Parse a problem given as a path or as text."""
    text, name = read_source(source, "<problem>")
    return parse_problem(text, name)


def load_task(domain: str | os.PathLike[str], problem: str | os.PathLike[str],
              check: Callable[[], None] | None = None) -> Task:
    """Parse, check and ground; ``domain`` and ``problem`` are paths or PDDL text.

    ``check`` is called between operator schemas while grounding (a time limit raises
    from it: grounding a 30-link chain takes seconds on a loaded machine).
    """
    return ground(load_domain(domain), load_problem(problem), check)
