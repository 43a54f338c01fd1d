"""Check a domain, and a problem against its domain: declarations, arities, types, operators.

Errors raise :class:`~artiplan.errors.InputError` at the offending token; harmless oddities
(unknown or unused requirements, a function initialised but never declared, facts set inside a
process) are returned as warning strings ``file:line:col: text``.
"""

from __future__ import annotations

from artiplan.errors import InputError, SourceLocation
from artiplan.pddl import grammar as g
from artiplan.pddl import syntax as s
from artiplan.pddl.scope import Scope, bind, check_formula, check_numeric, mentions_time

Variables = dict[str, tuple[str, ...]]


def _where(loc: SourceLocation | None) -> str:
    return f"{loc}: " if loc is not None else ""


def check_domain(domain: s.Domain) -> list[str]:
    """Check ``domain``; returns the warnings."""
    scope = Scope(domain)
    warnings: list[str] = []
    for t in domain.types:
        scope.types.check(t.types, t)
    if domain.types:
        scope.features.add("types")
    for c in domain.constants:
        scope.types.check(c.types, c)
    for params in (*(p.parameters for p in domain.predicates),
                   *(f.parameters for f in domain.functions)):
        for p in params:
            scope.types.check(p.types, p)
    for what, decls in (("predicate", domain.predicates), ("function", domain.functions)):
        seen: set[str] = set()
        for d in decls:
            if d.name.lower() in seen:
                raise InputError(f"{what} '{d.name}' declared twice", d.loc,
                                 expected=f"one declaration of '{d.name}'", found=d.name)
            seen.add(d.name.lower())
    names: set[tuple[str, str]] = set()
    for op in domain.operators:
        key = (op.kind, op.name.lower())
        if key in names:
            raise InputError(f"{op.kind} '{op.name}' defined twice", op.loc,
                             expected="a new name", found=op.name)
        names.add(key)
        scope.features.add(op.kind)
        warnings.extend(check_operator(scope, op))
    warnings.extend(requirement_warnings(domain.requirements, scope.features, domain.loc))
    return warnings


def check_operator(scope: Scope, op: s.Operator) -> list[str]:
    """Check one operator; returns warnings (facts set by a process)."""
    variables = bind(scope, {}, op.parameters)
    seen: set[str] = set()
    for p in op.parameters:
        if p.name.lower() in seen:
            raise InputError(f"parameter '{p.name}' appears twice", p.loc,
                             expected="distinct parameter names", found=p.name)
        seen.add(p.name.lower())
    if op.kind == "durative-action":
        variables = {**variables, g.DURATION_SYMBOL: ()}
    if op.precondition is not None:
        check_formula(scope, op.precondition, variables)
    if op.duration is not None:
        check_formula(scope, op.duration, variables)
    warnings: list[str] = []
    if op.effect is not None:
        check_effect(scope, op, op.effect, variables, warnings)
    return warnings


def check_effect(
    scope: Scope, op: s.Operator, e: s.EffectNode, variables: Variables, warnings: list[str]
) -> None:
    """Check an effect of ``op``; continuous effects only in processes (and durative actions)."""
    if isinstance(e, s.AddEffect | s.DeleteEffect):
        scope.check_atom(e.atom, variables)
        if op.kind == "process":
            warnings.append(
                f"{_where(e.loc)}process '{op.name}' sets a fact "
                f"'{e.atom.predicate}': not PDDL+ (VAL rejects it); read as ENHSP does, the "
                "fact is set at every instant the process is active"
            )
    elif isinstance(e, s.NumericAssignment):
        scope.features.add("functions")
        scope.check_function(e.target, variables)
        continuous = mentions_time(e.expr)
        if continuous:
            scope.features.add("continuous")
            if op.kind == "action" or op.kind == "event":
                raise InputError(f"#t in the effect of {op.kind} '{op.name}'", e.loc,
                                 expected="a discrete update (only processes change "
                                 "continuously)", found=e.op)
            if e.op not in ("increase", "decrease"):
                raise InputError(f"continuous effects must increase or decrease, not {e.op}",
                                 e.loc, expected="increase or decrease", found=e.op)
        elif op.kind == "process":
            raise InputError(f"process '{op.name}' has a discrete numeric effect", e.loc,
                             expected="(increase|decrease f (* #t rate))", found=e.op)
        check_numeric(scope, e.expr, variables, allow_time=continuous)
    elif isinstance(e, s.EffectConjunction):
        for p in e.parts:
            check_effect(scope, op, p, variables, warnings)
    elif isinstance(e, s.ForallEffect):
        scope.features.add("forall-effect")
        check_effect(scope, op, e.body, bind(scope, variables, e.variables), warnings)
    elif isinstance(e, s.WhenEffect):
        scope.features.add("when")
        check_formula(scope, e.condition, variables)
        check_effect(scope, op, e.effect, variables, warnings)
    elif isinstance(e, s.Timed):
        check_effect(scope, op, e.body, variables, warnings)  # type: ignore[arg-type]


def check_problem(domain: s.Domain, problem: s.Problem) -> list[str]:
    """Check ``problem`` against ``domain``; returns the warnings (the problem's own included)."""
    warnings = list(problem.warnings)
    if problem.domain_name.lower() != domain.name.lower():
        warnings.append(f"{_where(problem.loc)}problem '{problem.name}' names domain "
                        f"'{problem.domain_name}', but the domain is '{domain.name}'")
    scope = Scope(domain, problem.objects)
    warnings += _check_objects(scope, domain, problem)
    warnings += _check_init(scope, problem)
    if problem.goal is not None:
        check_formula(scope, problem.goal, {})
    if problem.metric is not None:
        check_numeric(scope, problem.metric.expr, {}, allow_time=False)
    warnings.extend(requirement_warnings(problem.requirements, None, problem.loc))
    return warnings


def _check_objects(scope: Scope, domain: s.Domain, problem: s.Problem) -> list[str]:
    warnings = []
    constants = {c.name.lower() for c in domain.constants}
    seen: set[str] = set()
    for o in problem.objects:
        scope.types.check(o.types, o)
        key = o.name.lower()
        if key in seen:
            raise InputError(f"object '{o.name}' declared twice", o.loc,
                             expected="distinct object names", found=o.name)
        if key in constants:
            warnings.append(f"{_where(o.loc)}object '{o.name}' repeats a domain constant")
        seen.add(key)
    return warnings


def _check_init(scope: Scope, problem: s.Problem) -> list[str]:
    warnings = []
    undeclared: set[str] = set()
    values: set[tuple[str, ...]] = set()
    for item in problem.init:
        if isinstance(item, s.AtomicFormula):
            if item.predicate.lower() not in scope.predicates:
                if item.predicate.lower() not in undeclared:
                    undeclared.add(item.predicate.lower())
                    warnings.append(f"{_where(item.loc)}predicate '{item.predicate}' is in :init "
                                    "but never declared in the domain (ignored)")
                continue
            scope.check_atom(item, {})
        elif item.target.name.lower() in scope.functions:
            scope.check_function(item.target, {})
            fkey = (item.target.name.lower(), *(a.name.lower() for a in item.target.args))
            if fkey in values:
                warnings.append(f"{_where(item.loc)}{item.target.name} is initialised twice; "
                                "the last value is used")
            values.add(fkey)
        elif item.target.name.lower() not in undeclared:
            undeclared.add(item.target.name.lower())
            warnings.append(f"{_where(item.loc)}function '{item.target.name}' is initialised "
                            "but never declared in the domain (ignored)")
    return warnings


def requirement_warnings(
    requirements: tuple[str, ...], features: set[str] | None, loc: SourceLocation | None
) -> list[str]:
    """Warnings for unknown requirements, and (if ``features`` is given) unused ones."""
    out = []
    for r in requirements:
        key = r.lower()
        if key not in g.REQUIREMENTS:
            out.append(f"{_where(loc)}unknown requirement {r} (ignored)")
            continue
        uses = g.REQUIREMENTS[key]
        if features is not None and uses and key not in g.UMBRELLA_REQUIREMENTS and not (
            set(uses) & features
        ):
            out.append(f"{_where(loc)}requirement {r} is declared but not used by the domain")
    return out
