"""Exit codes and the exception hierarchy shared by every command.

The codes are a public interface (shared/docs/conventions.md): users' scripts test them.
Every error that reaches the command line maps to exactly one code.
"""

from __future__ import annotations

from enum import IntEnum

from artiplan.records import dataclass


class ExitCode(IntEnum):
    """Process exit codes, the same for every ``artiplan`` command."""

    OK = 0  #: done: solved, valid, written
    INTERNAL = 1  #: unexpected internal error (a bug)
    USAGE = 2  #: bad options
    BAD_INPUT = 3  #: a file that does not parse or type-check
    INVALID_PLAN = 4  #: the plan is invalid (validate)
    UNSOLVABLE = 5  #: proven unsolvable (plan)
    NO_PLAN = 6  #: search finished without a plan and without a proof
    TIME_LIMIT = 7  #: time limit reached
    MEMORY_LIMIT = 8  #: memory limit reached
    EXTERNAL_TOOL = 9  #: an external tool is missing or failed (java, ENHSP, kairos, a renderer)


class ArtiplanError(Exception):
    """Base class of every error artiplan reports to users; carries its exit code."""

    exit_code: ExitCode = ExitCode.INTERNAL


class UsageError(ArtiplanError):
    """Bad command-line options or API arguments."""

    exit_code = ExitCode.USAGE


@dataclass(frozen=True)
class SourceLocation:
    """Where in an input file something was found (1-based line and column)."""

    file: str
    line: int
    column: int

    def __str__(self) -> str:
        return f"{self.file}:{self.line}:{self.column}"


class InputError(ArtiplanError):
    """An input file that does not parse or type-check.

    The message reads ``file:line:col: expected X, found 'Y'`` so editors can jump to it.
    """

    exit_code = ExitCode.BAD_INPUT

    def __init__(
        self,
        message: str,
        location: SourceLocation | None = None,
        expected: str | None = None,
        found: str | None = None,
    ) -> None:
        self.location = location
        self.expected = expected
        self.found = found
        self.detail = message
        parts = []
        if location is not None:
            parts.append(f"{location}:")
        parts.append(message)
        if expected is not None:
            parts.append(f"(expected {expected}")
            parts[-1] += f", found {found!r})" if found is not None else ")"
        super().__init__(" ".join(parts))


class InvalidPlanError(ArtiplanError):
    """A plan that fails validation."""

    exit_code = ExitCode.INVALID_PLAN


class ExternalToolError(ArtiplanError):
    """A tool artiplan calls (java, ENHSP, kairos, a renderer) is missing or failed."""

    exit_code = ExitCode.EXTERNAL_TOOL
