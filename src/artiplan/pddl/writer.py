"""Print syntax trees back as PDDL text: ``parse(write(tree)) == tree``.

Conditions and effects print on one line, except that a top-level ``and`` of an operator, goal or
``:init`` puts one part per line, so the output reads like hand-written PDDL.
"""

from __future__ import annotations

from artiplan.pddl import syntax as s

INDENT = "  "


def fmt_number(value: float) -> str:
    """Shortest text that reads back as exactly ``value`` (``10`` rather than ``10.0``)."""
    if value.is_integer() and abs(value) < 1e15:
        return str(int(value))
    return repr(value)


def fmt_type(types: tuple[str, ...]) -> str:
    """``t`` or ``(either t u)``."""
    return types[0] if len(types) == 1 else "(either " + " ".join(types) + ")"


def fmt_typed(names: tuple[s.TypedName, ...]) -> str:
    """``a b - t c - (either u v) d``: consecutive names of one type share a ``- type``."""
    groups: list[tuple[tuple[str, ...], list[str]]] = []
    for n in names:
        if groups and groups[-1][0] == n.types:
            groups[-1][1].append(n.name)
        else:
            groups.append((n.types, [n.name]))
    parts = []
    for i, (types, group) in enumerate(groups):
        text = " ".join(group)
        if types:
            text += " - " + fmt_type(types)
        elif i < len(groups) - 1:
            text += " - object"  # an untyped group before a typed one would take its type
        parts.append(text)
    return " ".join(parts)


def fmt_term(term: s.Term) -> str:
    """A term as written."""
    return term.name


def fmt_num(e: s.NumExpr) -> str:
    """A numeric expression on one line."""
    if isinstance(e, s.Number):
        return fmt_number(e.value)
    if isinstance(e, s.FunctionTerm):
        return "(" + " ".join((e.name, *(fmt_term(a) for a in e.args))) + ")"
    if isinstance(e, s.Arithmetic):
        return "(" + " ".join((e.op, *(fmt_num(a) for a in e.args))) + ")"
    if isinstance(e, s.Minus):
        return f"(- {fmt_num(e.operand)})"
    return "(total-time)" if e.name == "total-time" else e.name


def fmt_atom(a: s.AtomicFormula) -> str:
    """``(predicate term...)``."""
    return "(" + " ".join((a.predicate, *(fmt_term(t) for t in a.args))) + ")"


def fmt_formula(f: s.Formula) -> str:
    """A condition on one line."""
    if isinstance(f, s.AtomicFormula):
        return fmt_atom(f)
    if isinstance(f, s.Equals):
        return f"(= {fmt_term(f.left)} {fmt_term(f.right)})"
    if isinstance(f, s.Negation):
        return f"(not {fmt_formula(f.operand)})"
    if isinstance(f, s.Conjunction | s.Disjunction):
        word = "and" if isinstance(f, s.Conjunction) else "or"
        return "(" + " ".join((word, *(fmt_formula(p) for p in f.parts))) + ")"
    if isinstance(f, s.Implication):
        return f"(imply {fmt_formula(f.premise)} {fmt_formula(f.conclusion)})"
    if isinstance(f, s.Quantified):
        return f"({f.quantifier} ({fmt_typed(f.variables)}) {fmt_formula(f.body)})"
    if isinstance(f, s.Compare):
        return f"({f.op} {fmt_num(f.left)} {fmt_num(f.right)})"
    return f"({f.when} {_fmt_timed_body(f)})"


def _fmt_timed_body(f: s.Timed) -> str:
    body = f.body
    if isinstance(body, s.AddEffect | s.DeleteEffect | s.NumericAssignment | s.EffectConjunction
                  | s.ForallEffect | s.WhenEffect):
        return fmt_effect(body)
    return fmt_formula(body)


def fmt_effect(e: s.EffectNode) -> str:
    """An effect on one line."""
    if isinstance(e, s.AddEffect):
        return fmt_atom(e.atom)
    if isinstance(e, s.DeleteEffect):
        return f"(not {fmt_atom(e.atom)})"
    if isinstance(e, s.NumericAssignment):
        return f"({e.op} {fmt_num(e.target)} {fmt_num(e.expr)})"
    if isinstance(e, s.EffectConjunction):
        return "(" + " ".join(("and", *(fmt_effect(p) for p in e.parts))) + ")"
    if isinstance(e, s.ForallEffect):
        return f"(forall ({fmt_typed(e.variables)}) {fmt_effect(e.body)})"
    if isinstance(e, s.WhenEffect):
        return f"(when {fmt_formula(e.condition)} {fmt_effect(e.effect)})"
    return f"({e.when} {_fmt_timed_body(e)})"


def _block(head: str, lines: list[str], depth: int) -> str:
    """``(head`` then one line per item, indented, closing on the last line."""
    pad = INDENT * (depth + 1)
    if not lines:
        return f"({head})"
    return f"({head}\n" + "\n".join(pad + line for line in lines) + ")"


def _multiline_formula(f: s.Formula, depth: int) -> str:
    if isinstance(f, s.Conjunction) and len(f.parts) > 1:
        return _block("and", [fmt_formula(p) for p in f.parts], depth)
    return fmt_formula(f)


def _multiline_effect(e: s.EffectNode, depth: int) -> str:
    if isinstance(e, s.EffectConjunction) and len(e.parts) > 1:
        return _block("and", [fmt_effect(p) for p in e.parts], depth)
    return fmt_effect(e)


def _fmt_operator(op: s.Operator) -> str:
    pad = INDENT * 2
    lines = [f"{INDENT}(:{op.kind} {op.name}", f"{pad}:parameters ({fmt_typed(op.parameters)})"]
    if op.duration is not None:
        lines.append(f"{pad}:duration {fmt_formula(op.duration)}")
    if op.precondition is not None:
        key = ":condition" if op.kind in ("durative-action", "constraint") else ":precondition"
        lines.append(f"{pad}{key} {_multiline_formula(op.precondition, 2)}")
    if op.effect is not None:
        lines.append(f"{pad}:effect {_multiline_effect(op.effect, 2)}")
    return "\n".join(lines) + ")"


def _fmt_functions(functions: tuple[s.FunctionDecl, ...]) -> list[str]:
    out = []
    for f in functions:
        head = "(" + " ".join(filter(None, (f.name, fmt_typed(f.parameters)))) + ")"
        out.append(head + (f" - {f.return_type}" if f.return_type else ""))
    return out


def write_domain(domain: s.Domain) -> str:
    """The PDDL text of ``domain``."""
    parts = [f"(define (domain {domain.name})"]
    if domain.requirements:
        parts.append(f"{INDENT}(:requirements {' '.join(domain.requirements)})")
    if domain.types:
        parts.append(f"{INDENT}(:types {fmt_typed(domain.types)})")
    if domain.constants:
        parts.append(f"{INDENT}(:constants {fmt_typed(domain.constants)})")
    if domain.predicates:
        preds = ["(" + " ".join(filter(None, (p.name, fmt_typed(p.parameters)))) + ")"
                 for p in domain.predicates]
        parts.append(INDENT + _block(":predicates", preds, 1))
    if domain.functions:
        parts.append(INDENT + _block(":functions", _fmt_functions(domain.functions), 1))
    parts.extend(_fmt_operator(op) for op in domain.operators)
    return "\n".join(parts) + ")\n"


def _fmt_init(item: s.InitElement) -> str:
    if isinstance(item, s.InitValue):
        return f"(= {fmt_num(item.target)} {fmt_number(item.value)})"
    return fmt_atom(item)


def write_problem(problem: s.Problem) -> str:
    """The PDDL text of ``problem``."""
    parts = [f"(define (problem {problem.name})", f"{INDENT}(:domain {problem.domain_name})"]
    if problem.requirements:
        parts.append(f"{INDENT}(:requirements {' '.join(problem.requirements)})")
    if problem.objects:
        parts.append(f"{INDENT}(:objects {fmt_typed(problem.objects)})")
    parts.append(INDENT + _block(":init", [_fmt_init(i) for i in problem.init], 1))
    if problem.goal is not None:
        parts.append(f"{INDENT}(:goal {_multiline_formula(problem.goal, 1)})")
    if problem.metric is not None:
        parts.append(f"{INDENT}(:metric {problem.metric.direction} "
                     f"{fmt_num(problem.metric.expr)})")
    return "\n".join(parts) + ")\n"
