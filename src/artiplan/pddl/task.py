"""The grounded, indexed PDDL+ task: what grounding produces and everything below consumes.

Facts (ground atoms) and numeric fluents are numbered; conditions, effects and rates refer to
them by index. Quantifiers are expanded, ``imply`` is rewritten as ``or``, static facts and static
numeric fluents are folded into constants, and operators that can never apply are pruned.

Names keep the spelling of the files (``L2``), but comparisons are case-insensitive upstream.
A fact prints as ``(in-use L2)``; a fluent as ``(angle L2 z-axis)`` and, in trajectory CSV
columns, as ``angle(L2,z-axis)`` (shared/docs/conventions.md).

This module is a contract shared by ``pddl`` (producer), ``semantics`` and ``search`` (consumers):
extend it by adding fields with defaults, never by renaming.
"""

from __future__ import annotations

from artiplan.records import dataclass, field

TYPE_CHECKING = False  # read as true by mypy; typing is not imported at run time (start-up)
if TYPE_CHECKING:
    from typing import Literal

# --------------------------------------------------------------------------- numeric expressions


@dataclass(frozen=True)
class Const:
    """A numeric constant."""

    value: float


@dataclass(frozen=True)
class FluentRef:
    """The current value of numeric fluent ``index``."""

    index: int


@dataclass(frozen=True)
class BinOp:
    """``left op right`` with op one of ``+ - * /`` or ``^`` (power)."""

    op: Literal["+", "-", "*", "/", "^"]
    left: NumExpr
    right: NumExpr


@dataclass(frozen=True)
class Neg:
    """Unary minus."""

    operand: NumExpr


NumExpr = Const | FluentRef | BinOp | Neg

# ----------------------------------------------------------------------------------- conditions


@dataclass(frozen=True)
class Atom:
    """Fact ``fact`` holds."""

    fact: int


@dataclass(frozen=True)
class Not:
    operand: Condition


@dataclass(frozen=True)
class And:
    parts: tuple[Condition, ...]


@dataclass(frozen=True)
class Or:
    parts: tuple[Condition, ...]


if TYPE_CHECKING:
    ComparisonOp = Literal["<", "<=", ">", ">=", "="]


@dataclass(frozen=True)
class Comparison:
    """``left op right`` between numeric expressions."""

    op: ComparisonOp
    left: NumExpr
    right: NumExpr


@dataclass(frozen=True)
class Truth:
    """A constant condition (static parts folded away)."""

    value: bool


TRUE = Truth(True)
FALSE = Truth(False)

Condition = Atom | Not | And | Or | Comparison | Truth

# -------------------------------------------------------------------------------------- effects

if TYPE_CHECKING:
    NumericOp = Literal["assign", "increase", "decrease", "scale-up", "scale-down"]


@dataclass(frozen=True)
class NumericEffect:
    """``(op fluent expr)``; ``expr`` is evaluated in the state *before* the happening."""

    op: NumericOp
    fluent: int
    expr: NumExpr


@dataclass(frozen=True)
class ConditionalEffect:
    """``(when condition effect)``; the condition is evaluated before the happening."""

    condition: Condition
    effect: Effect


@dataclass(frozen=True)
class Effect:
    """An instantaneous effect: delete, then add (PDDL 2.1), numeric updates, conditional parts."""

    add: tuple[int, ...] = ()
    delete: tuple[int, ...] = ()
    numeric: tuple[NumericEffect, ...] = ()
    conditional: tuple[ConditionalEffect, ...] = ()


EMPTY_EFFECT = Effect()


@dataclass(frozen=True)
class ContinuousEffect:
    """While the owning process is active: d(fluent)/dt += ``rate``.

    ``(increase f (* #t e))`` gives rate ``e``; ``(decrease f (* #t e))`` gives ``Neg(e)``.
    """

    fluent: int
    rate: NumExpr


# ------------------------------------------------------------------------------------ operators


@dataclass(frozen=True)
class GroundAction:
    """A ground action or event (events have ``kind == 'event'``)."""

    name: str
    args: tuple[str, ...]
    precondition: Condition
    effect: Effect
    kind: Literal["action", "event"] = "action"

    @property
    def signature(self) -> str:
        """``(start-increase L1 L2 z-axis)``: how plans and logs print it."""
        return "(" + " ".join((self.name, *self.args)) + ")"


@dataclass(frozen=True)
class GroundProcess:
    """A ground process: while ``precondition`` holds, its continuous effects act.

    ``discrete`` is only non-empty for files that (like the paper's Fig. 7) set facts inside a
    process: the parser warns, and the semantics makes those facts true at every instant the
    process is active.
    """

    name: str
    args: tuple[str, ...]
    precondition: Condition
    continuous: tuple[ContinuousEffect, ...]
    discrete: Effect = EMPTY_EFFECT

    @property
    def signature(self) -> str:
        return "(" + " ".join((self.name, *self.args)) + ")"


@dataclass(frozen=True)
class Metric:
    direction: Literal["minimize", "maximize"]
    expr: NumExpr | None  # None: total-time
    uses_total_time: bool = False


@dataclass(frozen=True)
class GroundingStats:
    """Counts and time of grounding, for ``artiplan ground`` and planner statistics."""

    facts: int = 0
    fluents: int = 0
    actions: int = 0
    events: int = 0
    processes: int = 0
    pruned: int = 0
    seconds: float = 0.0


@dataclass(frozen=True)
class Task:
    """A grounded PDDL+ task.

    Attributes:
        domain_name, problem_name: From the files.
        facts: Printed names of the ground atoms, indexed by fact id (static facts excluded).
        fluents: Printed names of the numeric fluents (``(angle L2 z-axis)``), indexed by id.
        init_facts: Fact ids true initially.
        init_values: Initial value of every fluent; ``None`` where the problem leaves it
            undefined (reading it is an error, as in VAL).
        goal: The goal condition.
        actions, events, processes: The ground operators.
        metric: The problem's ``:metric``, if any.
        stats: Grounding counts and time.
        warnings: Harmless oddities found while parsing and grounding, for the user to read.
        invariants: Conditions that must hold on every stretch of time (ENHSP's global
            constraints, the ``over all`` conditions of durative actions).
        durative: Names of the durative actions, compiled into ``NAME@start``/``NAME@end``
            actions and a ``NAME@during`` process (:mod:`artiplan.pddl.durative`); plans name
            them with a duration, ``t: (NAME args) [d]``.
    """

    domain_name: str
    problem_name: str
    facts: tuple[str, ...]
    fluents: tuple[str, ...]
    init_facts: frozenset[int]
    init_values: tuple[float | None, ...]
    goal: Condition
    actions: tuple[GroundAction, ...]
    events: tuple[GroundAction, ...]
    processes: tuple[GroundProcess, ...]
    metric: Metric | None = None
    stats: GroundingStats = field(default_factory=GroundingStats)
    warnings: tuple[str, ...] = ()
    invariants: tuple[Condition, ...] = ()
    durative: tuple[str, ...] = ()

    def fluent_index(self, name: str) -> int:
        """Index of a fluent given as ``(angle L2 z-axis)`` or ``angle(L2,z-axis)``,
        case-insensitively."""
        key = _canonical(name)
        for i, f in enumerate(self.fluents):
            if _canonical(f) == key:
                return i
        raise KeyError(f"no numeric fluent {name!r} in task {self.problem_name!r}")

    def fact_index(self, name: str) -> int:
        """Index of a fact given as ``(in-use L2)``, case-insensitively."""
        key = _canonical(name)
        for i, f in enumerate(self.facts):
            if _canonical(f) == key:
                return i
        raise KeyError(f"no fact {name!r} in task {self.problem_name!r}")

    def action_by_signature(self, signature: str) -> GroundAction:
        """The ground action printed as ``signature`` (case-insensitive)."""
        key = _canonical(signature)
        for a in self.actions:
            if _canonical(a.signature) == key:
                return a
        raise KeyError(f"no ground action {signature!r}")


def fluent_column(name: str) -> str:
    """``(angle L2 z-axis)`` -> ``angle(L2,z-axis)`` (the trajectory CSV column name)."""
    parts = name.strip().strip("()").split()
    if not parts:
        return name
    return f"{parts[0]}({','.join(parts[1:])})" if len(parts) > 1 else parts[0]


def _canonical(name: str) -> str:
    """Case- and spacing-insensitive key: ``angle(L2,z-axis)`` == ``(ANGLE l2  z-axis)``."""
    s = name.strip().lower()
    if not s.startswith("("):
        s = s.replace("(", " ").replace(",", " ").replace(")", " ")
    return " ".join(s.strip("()").split())
