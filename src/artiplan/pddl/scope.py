"""Name resolution and checks of conditions and numeric expressions (used by the checker).

Errors raise :class:`~artiplan.errors.InputError` at the offending token; harmless oddities
(unknown or unused requirements, a function initialised but never declared, facts set inside a
process) are returned as warning strings ``file:line:col: text``.
"""

from __future__ import annotations

from artiplan.errors import InputError, SourceLocation
from artiplan.pddl import grammar as g
from artiplan.pddl import syntax as s
from artiplan.pddl.types import TypeHierarchy
from artiplan.records import dataclass


@dataclass(frozen=True)
class Signature:
    """A declared predicate or function: name and parameter types."""

    name: str
    params: tuple[tuple[str, ...], ...]






class Scope:
    """What names mean in a domain (and problem): predicates, functions, objects, variables."""

    def __init__(self, domain: s.Domain, objects: tuple[s.TypedName, ...] = ()) -> None:
        self.types = TypeHierarchy.of(domain)
        self.predicates = {p.name.lower(): _sig(p.name, p.parameters) for p in domain.predicates}
        self.functions = {f.name.lower(): _sig(f.name, f.parameters) for f in domain.functions}
        self.objects: dict[str, tuple[str, ...]] = {}
        for o in (*domain.constants, *objects):
            self.objects[o.name.lower()] = o.types
        self.features: set[str] = set()

    def check_atom(self, atom: s.AtomicFormula, variables: dict[str, tuple[str, ...]]) -> None:
        """Raise unless ``atom`` names a declared predicate with fitting arguments."""
        sig = self.predicates.get(atom.predicate.lower())
        if sig is None:
            raise InputError(f"undeclared predicate '{atom.predicate}'", atom.loc,
                             expected="a predicate declared in :predicates", found=atom.predicate)
        self._check_args(sig, atom.args, variables, atom.loc, "predicate")

    def check_function(self, term: s.FunctionTerm, variables: dict[str, tuple[str, ...]]) -> None:
        """Raise unless ``term`` names a declared function with fitting arguments."""
        sig = self.functions.get(term.name.lower())
        if sig is None:
            raise InputError(f"undeclared function '{term.name}'", term.loc,
                             expected="a function declared in :functions", found=term.name)
        self._check_args(sig, term.args, variables, term.loc, "function")

    def term_type(self, term: s.Term, variables: dict[str, tuple[str, ...]]) -> tuple[str, ...]:
        """The declared type of a variable or object (raises if undeclared)."""
        key = term.name.lower()
        if isinstance(term, s.Variable):
            if key not in variables:
                raise InputError(f"unbound variable '{term.name}'", term.loc,
                                 expected="a parameter or quantified variable", found=term.name)
            return variables[key]
        if key not in self.objects:
            raise InputError(f"undeclared object or constant '{term.name}'", term.loc,
                             expected="an object of :objects or a constant", found=term.name)
        return self.objects[key]

    def _check_args(
        self, sig: Signature, args: tuple[s.Term, ...], variables: dict[str, tuple[str, ...]],
        loc: SourceLocation | None, what: str,
    ) -> None:
        if len(args) != len(sig.params):
            raise InputError(
                f"{what} '{sig.name}' takes {len(sig.params)} argument(s), found {len(args)}",
                loc, expected=f"{len(sig.params)} argument(s)", found=str(len(args)),
            )
        for arg, want in zip(args, sig.params, strict=True):
            have = self.term_type(arg, variables)
            ok = (self.types.compatible(have, want) if isinstance(arg, s.Variable)
                  else self.types.is_subtype(have, want))
            if not ok:
                raise InputError(
                    f"type error: argument '{arg.name}' of {what} '{sig.name}' has type "
                    f"{_show(have)}", arg.loc, expected=_show(want), found=_show(have),
                )


def _show(types: tuple[str, ...]) -> str:
    if not types:
        return g.ROOT_TYPE
    return types[0] if len(types) == 1 else "(either " + " ".join(types) + ")"


def _sig(name: str, params: tuple[s.TypedName, ...]) -> Signature:
    return Signature(name, tuple(p.types for p in params))


def bind(
    scope: Scope, variables: dict[str, tuple[str, ...]], params: tuple[s.TypedName, ...]
) -> dict[str, tuple[str, ...]]:
    """``variables`` extended with ``params`` (their types checked)."""
    out = dict(variables)
    for p in params:
        scope.types.check(p.types, p)
        out[p.name.lower()] = p.types
    return out


def check_formula(scope: Scope, f: s.Formula, variables: dict[str, tuple[str, ...]]) -> None:
    """Check every atom, term and function of a condition; note the features it uses."""
    if isinstance(f, s.AtomicFormula):
        scope.check_atom(f, variables)
    elif isinstance(f, s.Equals):
        scope.features.add("equality")
        scope.term_type(f.left, variables)
        scope.term_type(f.right, variables)
    elif isinstance(f, s.Negation):
        scope.features.add("negative")
        check_formula(scope, f.operand, variables)
    elif isinstance(f, s.Conjunction | s.Disjunction):
        if isinstance(f, s.Disjunction):
            scope.features.add("or")
        for p in f.parts:
            check_formula(scope, p, variables)
    elif isinstance(f, s.Implication):
        scope.features.add("imply")
        check_formula(scope, f.premise, variables)
        check_formula(scope, f.conclusion, variables)
    elif isinstance(f, s.Quantified):
        scope.features.add(f.quantifier)
        check_formula(scope, f.body, bind(scope, variables, f.variables))
    elif isinstance(f, s.Compare):
        check_numeric(scope, f.left, variables, allow_time=False)
        check_numeric(scope, f.right, variables, allow_time=False)
    elif isinstance(f, s.Timed):
        check_formula(scope, f.body, variables)  # type: ignore[arg-type]


def check_numeric(
    scope: Scope, e: s.NumExpr, variables: dict[str, tuple[str, ...]], allow_time: bool
) -> None:
    """Check a numeric expression; ``#t`` is allowed only in continuous effects."""
    if isinstance(e, s.FunctionTerm):
        scope.features.add("functions")
        scope.check_function(e, variables)
    elif isinstance(e, s.Arithmetic):
        for a in e.args:
            check_numeric(scope, a, variables, allow_time)
    elif isinstance(e, s.Minus):
        check_numeric(scope, e.operand, variables, allow_time)
    elif isinstance(e, s.Special) and e.name == g.TIME_SYMBOL and not allow_time:
        raise InputError("#t is only allowed in the continuous effects of a process", e.loc,
                         expected="a numeric expression without #t", found="#t")


def mentions_time(e: s.NumExpr) -> bool:
    """Does ``e`` contain ``#t``?"""
    if isinstance(e, s.Special):
        return e.name == g.TIME_SYMBOL
    if isinstance(e, s.Arithmetic):
        return any(mentions_time(a) for a in e.args)
    if isinstance(e, s.Minus):
        return mentions_time(e.operand)
    return False
