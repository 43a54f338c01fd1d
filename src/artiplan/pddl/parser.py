"""Parse PDDL+ domain and problem text into the syntax tree (:mod:`artiplan.pddl.syntax`).

``parse_domain`` also checks the domain on its own (declared predicates, functions, types,
constants, variables; arities); ``parse_problem`` checks syntax only, and
:func:`artiplan.pddl.checker.check_problem` checks a problem against its domain.
"""

from __future__ import annotations

from artiplan.errors import InputError
from artiplan.pddl import grammar as g
from artiplan.pddl import syntax as s
from artiplan.pddl.checker import check_domain
from artiplan.pddl.formulas import (
    expect_list,
    expect_name,
    fail,
    read_atom,
    read_effect,
    read_formula,
    read_num,
    read_term,
    read_type,
    read_typed_list,
)
from artiplan.pddl.lexer import SExpr, SList, Token, is_number, read_sexpr
from artiplan.records import replace


def parse_domain(text: str, filename: str = "<domain>") -> s.Domain:
    """Parse and check a domain; warnings are in ``Domain.warnings``."""
    quirks: list[str] = []
    top = read_sexpr(text, filename, quirks)
    name = _define_header(top, "domain")
    fields: dict[str, object] = {}
    operators: list[s.Operator] = []
    for section in top.items[2:]:
        lst = expect_list(section, "a domain section")
        key = _section_key(lst, g.DOMAIN_SECTIONS)
        if key in g.OPERATOR_SECTIONS:
            operators.append(_read_operator(lst, g.OPERATOR_SECTIONS[key]))
            if key == ":constraint":
                quirks.append(f"{lst.loc}: (:constraint {operators[-1].name} ...) is ENHSP's "
                              "global constraint, an extension (read as an invariant: it must "
                              "hold over the whole trajectory)")
            continue
        if key in fields:
            raise fail(f"section {key} appears twice", lst.items[0], expected="one " + key)
        fields[key] = _read_domain_section(key, lst)
    domain = s.Domain(
        name=name,
        requirements=fields.get(":requirements", ()),  # type: ignore[arg-type]
        types=fields.get(":types", ()),  # type: ignore[arg-type]
        constants=fields.get(":constants", ()),  # type: ignore[arg-type]
        predicates=fields.get(":predicates", ()),  # type: ignore[arg-type]
        functions=fields.get(":functions", ()),  # type: ignore[arg-type]
        operators=tuple(operators),
        loc=top.loc,
    )
    return replace(domain, warnings=(*quirks, *check_domain(domain)))


def parse_problem(text: str, filename: str = "<problem>") -> s.Problem:
    """Parse a problem (syntax only; see :func:`artiplan.pddl.checker.check_problem`)."""
    quirks: list[str] = []
    top = read_sexpr(text, filename, quirks)
    name = _define_header(top, "problem")
    fields: dict[str, object] = {}
    for section in top.items[2:]:
        lst = expect_list(section, "a problem section")
        key = _section_key(lst, g.PROBLEM_SECTIONS)
        if key in fields:
            raise fail(f"section {key} appears twice", lst.items[0], expected="one " + key)
        fields[key] = _read_problem_section(key, lst)
    if ":domain" not in fields:
        raise InputError("the problem names no domain", top.loc, expected="(:domain NAME)",
                         found="no :domain section")
    init: tuple[s.InitElement, ...] = ()
    warnings: list[str] = quirks
    if ":init" in fields:
        found: tuple[tuple[s.InitElement, ...], list[str]] = fields[":init"]  # type: ignore[assignment]
        init, warnings = found[0], [*quirks, *found[1]]
    return s.Problem(
        name=name,
        domain_name=fields[":domain"],  # type: ignore[arg-type]
        requirements=fields.get(":requirements", ()),  # type: ignore[arg-type]
        objects=fields.get(":objects", ()),  # type: ignore[arg-type]
        init=init,
        goal=fields.get(":goal"),  # type: ignore[arg-type]
        metric=fields.get(":metric"),  # type: ignore[arg-type]
        loc=top.loc,
        warnings=tuple(warnings),
    )


def _define_header(top: SList, kind: str) -> str:
    if top.head() != "define":
        at = top.items[0] if top.items else top
        raise fail("expected (define ...)", at, expected="'define'")
    if len(top.items) < 2:
        raise fail(f"expected ({kind} NAME)", top, expected=f"({kind} NAME)")
    header = expect_list(top.items[1], f"({kind} NAME)")
    if header.head() != kind or len(header.items) != 2:
        raise fail(f"expected ({kind} NAME)", header.items[0] if header.items else header,
                   expected=f"({kind} NAME)")
    return expect_name(header.items[1], f"a {kind} name").text


def _section_key(lst: SList, allowed: tuple[str, ...]) -> str:
    head = lst.head()
    if head not in allowed:
        at = lst.items[0] if lst.items else lst
        raise fail("unknown section", at, expected="one of " + " ".join(allowed))
    return head


def _read_domain_section(key: str, lst: SList) -> object:
    items = lst.items[1:]
    if key == ":requirements":
        return _read_requirements(items)
    if key in (":types", ":constants"):
        return read_typed_list(items, variables=False)
    if key == ":predicates":
        return tuple(_read_predicate(expect_list(p, "a predicate declaration")) for p in items)
    return _read_functions(items)


def _read_requirements(items: tuple[SExpr, ...]) -> tuple[str, ...]:
    out = []
    for item in items:
        if not isinstance(item, Token) or not item.text.startswith(":"):
            raise fail("expected a requirement", item, expected="a :keyword")
        out.append(item.text)
    return tuple(out)


def _read_predicate(lst: SList) -> s.PredicateDecl:
    if not lst.items:
        raise fail("empty predicate declaration", lst, expected="(NAME ?vars...)")
    name = expect_name(lst.items[0], "a predicate name")
    return s.PredicateDecl(name.text, read_typed_list(lst.items[1:], variables=True), lst.loc)


def _read_functions(items: tuple[SExpr, ...]) -> tuple[s.FunctionDecl, ...]:
    """``(f ?x - t) (g) - number (h)``: a ``- number`` after a group types the group."""
    out: list[s.FunctionDecl] = []
    pending: list[s.FunctionDecl] = []
    i = 0
    while i < len(items):
        item = items[i]
        if isinstance(item, Token) and item.text == "-":
            if not pending or i + 1 >= len(items):
                raise fail("a '-' must follow function declarations", item,
                           expected="(f ...) - number")
            rtype = read_type(items[i + 1])
            if len(rtype) != 1 or rtype[0].lower() != g.NUMBER_TYPE:
                raise fail("functions return numbers", items[i + 1], expected="number")
            out.extend(s.FunctionDecl(f.name, f.parameters, rtype[0], f.loc) for f in pending)
            pending = []
            i += 2
            continue
        lst = expect_list(item, "a function declaration")
        if not lst.items:
            raise fail("empty function declaration", lst, expected="(NAME ?vars...)")
        name = expect_name(lst.items[0], "a function name")
        pending.append(
            s.FunctionDecl(name.text, read_typed_list(lst.items[1:], variables=True), None,
                           lst.loc)
        )
        i += 1
    out.extend(pending)
    return tuple(out)


def _read_operator(lst: SList, kind: str) -> s.Operator:
    if len(lst.items) < 2:
        raise fail("an operator needs a name", lst, expected="a name")
    name = expect_name(lst.items[1], "an operator name")
    allowed = g.OPERATOR_FIELDS[kind]
    seen: dict[str, object] = {}
    items = lst.items[2:]
    if len(items) % 2:
        raise fail("operator fields come in pairs", items[-1],
                   expected="':keyword value' pairs")
    for key_expr, value in zip(items[::2], items[1::2], strict=True):
        if not isinstance(key_expr, Token) or key_expr.lower not in allowed:
            raise fail(f"unknown field of :{kind}", key_expr, expected=" ".join(allowed))
        key = key_expr.lower
        if key in seen:
            raise fail(f"field {key} appears twice", key_expr, expected=f"one {key}")
        if key == ":parameters":
            seen[key] = read_typed_list(expect_list(value, "a parameter list").items, True)
        elif key == ":effect":
            seen[key] = read_effect(value)
        else:
            seen[key] = read_formula(value)
    return s.Operator(
        kind=kind,  # type: ignore[arg-type]
        name=name.text,
        parameters=seen.get(":parameters", ()),  # type: ignore[arg-type]
        precondition=seen.get(":precondition", seen.get(":condition")),  # type: ignore[arg-type]
        effect=seen.get(":effect"),  # type: ignore[arg-type]
        duration=seen.get(":duration"),  # type: ignore[arg-type]
        loc=lst.loc,
    )


def _read_problem_section(key: str, lst: SList) -> object:
    items = lst.items[1:]
    if key == ":domain":
        if len(items) != 1:
            raise fail("expected (:domain NAME)", lst, expected="(:domain NAME)")
        return expect_name(items[0], "a domain name").text
    if key == ":requirements":
        return _read_requirements(items)
    if key == ":objects":
        return read_typed_list(items, variables=False)
    if key == ":init":
        return _read_init(items)
    if key == ":goal":
        if len(items) != 1:
            raise fail("expected one goal condition", lst, expected="(:goal CONDITION)")
        return read_formula(items[0])
    return _read_metric(lst)


def _read_init(items: tuple[SExpr, ...]) -> tuple[tuple[s.InitElement, ...], list[str]]:
    out: list[s.InitElement] = []
    warnings: list[str] = []
    for item in items:
        lst = expect_list(item, "an initial fact or (= (f ...) value)")
        head = lst.head()
        if head == "=":
            out.append(_read_init_value(lst))
        elif head == "not":
            warnings.append(f"{lst.loc}: '(not ...)' in :init ignored (the closed world makes "
                            "every unlisted fact false)")
        elif head == "at" and len(lst.items) == 3 and is_number(_text(lst.items[1])):
            raise fail("timed initial literals are not supported", lst,
                       expected="a fact or (= (f ...) value)")
        else:
            atom = read_atom(lst) if lst.items else None
            if atom is None:
                raise fail("empty initial fact", lst, expected="(predicate objects...)")
            for t in atom.args:
                if isinstance(t, s.Variable):
                    raise InputError("variables are not allowed in :init", t.loc,
                                     expected="an object", found=t.name)
            out.append(atom)
    return tuple(out), warnings


def _text(expr: SExpr) -> str:
    return expr.text if isinstance(expr, Token) else ""


def _read_init_value(lst: SList) -> s.InitValue:
    if len(lst.items) != 3:
        raise fail("expected (= (f ...) value)", lst, expected="(= (f objects...) number)")
    target = read_num(lst.items[1])
    value = read_num(lst.items[2])
    if isinstance(value, s.Minus) and isinstance(value.operand, s.Number):
        value = s.Number(-value.operand.value, value.loc)
    if not isinstance(target, s.FunctionTerm):
        raise fail("expected a function term", lst.items[1], expected="(f objects...)")
    if not isinstance(value, s.Number):
        raise fail("initial values must be numbers", lst.items[2], expected="a number")
    for t in target.args:
        if isinstance(t, s.Variable):
            raise InputError("variables are not allowed in :init", t.loc,
                             expected="an object", found=t.name)
    return s.InitValue(target, value.value, lst.loc)


def _read_metric(lst: SList) -> s.MetricSpec:
    if len(lst.items) != 3:
        raise fail("expected (:metric minimize|maximize EXPR)", lst,
                   expected="(:metric minimize|maximize EXPR)")
    direction = lst.items[1]
    if not isinstance(direction, Token) or direction.lower not in g.METRIC_DIRECTIONS:
        raise fail("expected minimize or maximize", direction, expected="minimize or maximize")
    return s.MetricSpec(direction.lower, read_num(lst.items[2]), lst.loc)  # type: ignore[arg-type]


__all__ = ["parse_domain", "parse_problem", "read_term"]
