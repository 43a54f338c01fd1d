"""The PDDL+ syntax tree: what the parser builds and the writer prints.

Every node is a frozen dataclass. Names keep the spelling of the file (``L2``); code that compares
names lower-cases them (PDDL is case-insensitive). Each node may carry the
:class:`~artiplan.errors.SourceLocation` it was read from in ``loc``; locations (and warnings) are
excluded from equality, so ``parse(write(tree)) == tree`` holds.
"""

from __future__ import annotations

from artiplan.errors import SourceLocation
from artiplan.records import dataclass, field

TYPE_CHECKING = False  # read as true by mypy; typing is not imported at run time (start-up)
if TYPE_CHECKING:
    from typing import Literal


def _loc() -> SourceLocation | None:
    return field(default=None, compare=False, repr=False)


# ---------------------------------------------------------------------------------------- terms


@dataclass(frozen=True)
class Variable:
    """A parameter or quantified variable, ``name`` with its ``?``."""

    name: str
    loc: SourceLocation | None = _loc()


@dataclass(frozen=True)
class Name:
    """An object or constant named in an atom or function term."""

    name: str
    loc: SourceLocation | None = _loc()


Term = Variable | Name


@dataclass(frozen=True)
class TypedName:
    """A declared name with its type: ``either`` lists several; empty when untyped."""

    name: str
    types: tuple[str, ...] = ()
    loc: SourceLocation | None = _loc()


# ---------------------------------------------------------------------------- numeric expressions


@dataclass(frozen=True)
class Number:
    """A numeric literal."""

    value: float
    loc: SourceLocation | None = _loc()


@dataclass(frozen=True)
class FunctionTerm:
    """``(f a1 ... an)``: the value of a numeric fluent."""

    name: str
    args: tuple[Term, ...] = ()
    loc: SourceLocation | None = _loc()


@dataclass(frozen=True)
class Arithmetic:
    """``(op a b ...)``: ``+`` and ``*`` may be n-ary, ``-``, ``/`` and ``^`` binary."""

    op: Literal["+", "-", "*", "/", "^"]
    args: tuple[NumExpr, ...]
    loc: SourceLocation | None = _loc()


@dataclass(frozen=True)
class Minus:
    """Unary minus ``(- a)``."""

    operand: NumExpr
    loc: SourceLocation | None = _loc()


@dataclass(frozen=True)
class Special:
    """``#t`` (time in continuous effects), ``?duration`` or ``total-time``."""

    name: Literal["#t", "?duration", "total-time"]
    loc: SourceLocation | None = _loc()


NumExpr = Number | FunctionTerm | Arithmetic | Minus | Special

# ------------------------------------------------------------------------------------ conditions


@dataclass(frozen=True)
class AtomicFormula:
    """``(p t1 ... tn)``."""

    predicate: str
    args: tuple[Term, ...] = ()
    loc: SourceLocation | None = _loc()


@dataclass(frozen=True)
class Equals:
    """``(= t1 t2)`` between objects (not numbers)."""

    left: Term
    right: Term
    loc: SourceLocation | None = _loc()


@dataclass(frozen=True)
class Negation:
    """``(not f)``."""
    operand: Formula
    loc: SourceLocation | None = _loc()


@dataclass(frozen=True)
class Conjunction:
    """``(and f...)``; ``()`` reads as an empty conjunction."""
    parts: tuple[Formula, ...]
    loc: SourceLocation | None = _loc()


@dataclass(frozen=True)
class Disjunction:
    """``(or f...)``."""
    parts: tuple[Formula, ...]
    loc: SourceLocation | None = _loc()


@dataclass(frozen=True)
class Implication:
    """``(imply premise conclusion)``."""
    premise: Formula
    conclusion: Formula
    loc: SourceLocation | None = _loc()


@dataclass(frozen=True)
class Quantified:
    """``(exists (vars) body)`` or ``(forall (vars) body)``."""

    quantifier: Literal["exists", "forall"]
    variables: tuple[TypedName, ...]
    body: Formula
    loc: SourceLocation | None = _loc()


@dataclass(frozen=True)
class Compare:
    """``(op e1 e2)`` between numeric expressions."""

    op: Literal["<", "<=", ">", ">=", "="]
    left: NumExpr
    right: NumExpr
    loc: SourceLocation | None = _loc()


@dataclass(frozen=True)
class Timed:
    """``(at start c)``, ``(at end c)``, ``(over all c)`` in durative actions (conditions or
    effects)."""

    when: Literal["at start", "at end", "over all"]
    body: Formula | EffectNode
    loc: SourceLocation | None = _loc()


Formula = (
    AtomicFormula | Equals | Negation | Conjunction | Disjunction | Implication | Quantified
    | Compare | Timed
)

# --------------------------------------------------------------------------------------- effects


@dataclass(frozen=True)
class AddEffect:
    """An atom made true."""
    atom: AtomicFormula
    loc: SourceLocation | None = _loc()


@dataclass(frozen=True)
class DeleteEffect:
    """``(not atom)`` in an effect."""

    atom: AtomicFormula
    loc: SourceLocation | None = _loc()


@dataclass(frozen=True)
class NumericAssignment:
    """``(op (f ...) expr)``; continuous when ``expr`` mentions ``#t``."""

    op: Literal["assign", "increase", "decrease", "scale-up", "scale-down"]
    target: FunctionTerm
    expr: NumExpr
    loc: SourceLocation | None = _loc()


@dataclass(frozen=True)
class EffectConjunction:
    """``(and effect...)``."""
    parts: tuple[EffectNode, ...]
    loc: SourceLocation | None = _loc()


@dataclass(frozen=True)
class ForallEffect:
    """``(forall (vars) effect)``."""
    variables: tuple[TypedName, ...]
    body: EffectNode
    loc: SourceLocation | None = _loc()


@dataclass(frozen=True)
class WhenEffect:
    """``(when condition effect)``."""
    condition: Formula
    effect: EffectNode
    loc: SourceLocation | None = _loc()


EffectNode = (
    AddEffect | DeleteEffect | NumericAssignment | EffectConjunction | ForallEffect | WhenEffect
    | Timed
)

# ------------------------------------------------------------------------------ domain, problem


@dataclass(frozen=True)
class PredicateDecl:
    """A predicate declaration ``(name ?x - type ...)``."""
    name: str
    parameters: tuple[TypedName, ...] = ()
    loc: SourceLocation | None = _loc()


@dataclass(frozen=True)
class FunctionDecl:
    """A numeric fluent declaration; ``return_type`` is ``number`` if written, else ``None``."""

    name: str
    parameters: tuple[TypedName, ...] = ()
    return_type: str | None = None
    loc: SourceLocation | None = _loc()


if TYPE_CHECKING:
    OperatorKind = Literal["action", "process", "event", "durative-action", "constraint"]


@dataclass(frozen=True)
class Operator:
    """An ``:action``, ``:process``, ``:event``, ``:durative-action`` or ENHSP's global
    ``:constraint`` (an invariant over the whole trajectory).

    For durative actions ``duration`` holds the ``:duration`` constraint and ``precondition`` the
    ``:condition``; for a constraint ``precondition`` holds its ``:condition``.
    """

    kind: OperatorKind
    name: str
    parameters: tuple[TypedName, ...] = ()
    precondition: Formula | None = None
    effect: EffectNode | None = None
    duration: Formula | None = None
    loc: SourceLocation | None = _loc()


@dataclass(frozen=True)
class Domain:
    """A parsed domain; ``warnings`` lists harmless oddities found while reading it."""

    name: str
    requirements: tuple[str, ...] = ()
    types: tuple[TypedName, ...] = ()
    constants: tuple[TypedName, ...] = ()
    predicates: tuple[PredicateDecl, ...] = ()
    functions: tuple[FunctionDecl, ...] = ()
    operators: tuple[Operator, ...] = ()
    loc: SourceLocation | None = _loc()
    warnings: tuple[str, ...] = field(default=(), compare=False, repr=False)


@dataclass(frozen=True)
class InitValue:
    """``(= (f a ...) v)`` in ``:init``."""

    target: FunctionTerm
    value: float
    loc: SourceLocation | None = _loc()


InitElement = AtomicFormula | InitValue


@dataclass(frozen=True)
class MetricSpec:
    """``(:metric minimize|maximize expr)``."""
    direction: Literal["minimize", "maximize"]
    expr: NumExpr
    loc: SourceLocation | None = _loc()


@dataclass(frozen=True)
class Problem:
    """A parsed problem."""

    name: str
    domain_name: str
    requirements: tuple[str, ...] = ()
    objects: tuple[TypedName, ...] = ()
    init: tuple[InitElement, ...] = ()
    goal: Formula | None = None
    metric: MetricSpec | None = None
    loc: SourceLocation | None = _loc()
    warnings: tuple[str, ...] = field(default=(), compare=False, repr=False)
