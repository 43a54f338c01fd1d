"""Reading conditions, effects, numeric expressions and typed lists from S-expressions.

Each function takes the S-expression of one construct of :mod:`artiplan.pddl.grammar` and returns
its syntax-tree node, or raises :class:`~artiplan.errors.InputError` at the offending token.
"""

from __future__ import annotations

from artiplan.errors import InputError
from artiplan.pddl import grammar as g
from artiplan.pddl import syntax as s
from artiplan.pddl.lexer import SExpr, SList, Token, describe, is_number


def fail(message: str, at: SExpr, expected: str | None = None) -> InputError:
    """An :class:`InputError` at ``at`` (a token or a list), found = its text."""
    return InputError(message, at.loc, expected=expected, found=describe(at))


def expect_list(expr: SExpr, what: str) -> SList:
    """``expr`` as a list, or an error naming ``what`` was expected."""
    if not isinstance(expr, SList):
        raise fail(f"expected {what}", expr, expected=f"'(' starting {what}")
    return expr


def expect_name(expr: SExpr, what: str) -> Token:
    """A plain name (not a variable, number or parenthesis)."""
    if not isinstance(expr, Token) or expr.text.startswith("?") or is_number(expr.text):
        raise fail(f"expected {what}", expr, expected=what)
    return expr


def check_arity(lst: SList, lo: int, hi: int | None, what: str) -> None:
    """Raise unless ``lst`` has ``lo`` to ``hi`` (None: any number of) arguments."""
    n = len(lst.items) - 1
    if n < lo or (hi is not None and n > hi):
        want = f"{lo}" if hi == lo else f"{lo} or more" if hi is None else f"{lo} to {hi}"
        at: SExpr = lst.items[hi + 1] if hi is not None and n > hi else lst
        raise InputError(
            f"'{what}' takes {want} argument(s), found {n}", at.loc,
            expected=f"{want} argument(s)", found=describe(at),
        )


# ----------------------------------------------------------------------------------- typed lists


def read_type(expr: SExpr) -> tuple[str, ...]:
    """``NAME`` or ``(either NAME+)``."""
    if isinstance(expr, SList):
        if expr.head() != "either" or len(expr.items) < 2:
            raise fail("expected a type", expr, expected="a type name or (either ...)")
        return tuple(expect_name(t, "a type name").text for t in expr.items[1:])
    return (expect_name(expr, "a type name").text,)


def read_typed_list(items: tuple[SExpr, ...], variables: bool) -> tuple[s.TypedName, ...]:
    """``a b - t c - (either u v) d``: names (or ``?variables``) with their types."""
    out: list[s.TypedName] = []
    pending: list[Token] = []
    i = 0
    while i < len(items):
        item = items[i]
        if isinstance(item, Token) and item.text == "-":
            if not pending or i + 1 >= len(items):
                raise fail("a '-' must follow names and precede a type", item,
                           expected="a name before '-' and a type after it")
            types = read_type(items[i + 1])
            out.extend(s.TypedName(t.text, types, t.loc) for t in pending)
            pending = []
            i += 2
            continue
        what = "a ?variable" if variables else "a name"
        tok = expect_name(item, what) if not variables else _expect_variable(item)
        pending.append(tok)
        i += 1
    out.extend(s.TypedName(t.text, (), t.loc) for t in pending)
    return tuple(out)


def _expect_variable(expr: SExpr) -> Token:
    if not isinstance(expr, Token) or not expr.text.startswith("?") or len(expr.text) < 2:
        raise fail("expected a variable", expr, expected="a ?variable")
    return expr


def read_term(expr: SExpr) -> s.Term:
    """A ``?variable`` or an object/constant name."""
    if isinstance(expr, Token) and expr.text.startswith("?") and len(expr.text) > 1:
        return s.Variable(expr.text, expr.loc)
    tok = expect_name(expr, "an object, constant or ?variable")
    return s.Name(tok.text, tok.loc)


def read_atom(lst: SList) -> s.AtomicFormula:
    """``(predicate term...)``."""
    name = expect_name(lst.items[0], "a predicate name")
    return s.AtomicFormula(name.text, tuple(read_term(t) for t in lst.items[1:]), lst.loc)


# ---------------------------------------------------------------------------- numeric expressions


def read_num(expr: SExpr) -> s.NumExpr:
    """A numeric expression (``NEXP`` in the grammar)."""
    if isinstance(expr, Token):
        low = expr.lower
        if is_number(expr.text):
            return s.Number(float(expr.text), expr.loc)
        if low in (g.TIME_SYMBOL, g.DURATION_SYMBOL, g.TOTAL_TIME):
            return s.Special(low, expr.loc)  # type: ignore[arg-type]
        return s.FunctionTerm(expect_name(expr, "a number or numeric expression").text, (),
                              expr.loc)
    if not expr.items:
        raise fail("empty numeric expression", expr, expected="a numeric expression")
    head = expr.head()
    if head in g.ARITHMETIC:
        lo, hi = g.ARITHMETIC[head]
        check_arity(expr, lo, hi, head)
        args = tuple(read_num(a) for a in expr.items[1:])
        if head == "-" and len(args) == 1:
            return s.Minus(args[0], expr.loc)
        return s.Arithmetic(head, args, expr.loc)  # type: ignore[arg-type]
    if head == g.TOTAL_TIME and len(expr.items) == 1:
        return s.Special("total-time", expr.loc)
    name = expect_name(expr.items[0], "a function name or arithmetic operator")
    return s.FunctionTerm(name.text, tuple(read_term(t) for t in expr.items[1:]), expr.loc)


# ------------------------------------------------------------------------------------ conditions


def _is_object_term(expr: SExpr) -> bool:
    return (isinstance(expr, Token) and not is_number(expr.text)
            and expr.lower not in (g.TIME_SYMBOL, g.DURATION_SYMBOL, g.TOTAL_TIME))


def read_formula(expr: SExpr) -> s.Formula:
    """A goal description (``GD`` in the grammar)."""
    lst = expect_list(expr, "a condition")
    if not lst.items:
        return s.Conjunction((), lst.loc)
    head = lst.head()
    if head in g.CONNECTIVES:
        lo, hi = g.CONNECTIVES[head]
        check_arity(lst, lo, hi, head)
        parts = tuple(read_formula(p) for p in lst.items[1:])
        if head == "and":
            return s.Conjunction(parts, lst.loc)
        if head == "or":
            return s.Disjunction(parts, lst.loc)
        if head == "not":
            return s.Negation(parts[0], lst.loc)
        return s.Implication(parts[0], parts[1], lst.loc)
    if head in g.QUANTIFIERS:
        check_arity(lst, 2, 2, head)
        params = read_typed_list(expect_list(lst.items[1], "a variable list").items, True)
        return s.Quantified(head, params, read_formula(lst.items[2]), lst.loc)  # type: ignore[arg-type]
    if head in g.COMPARISONS:
        check_arity(lst, 2, 2, head)
        a, b = lst.items[1], lst.items[2]
        if head == "=" and _is_object_term(a) and _is_object_term(b):
            return s.Equals(read_term(a), read_term(b), lst.loc)
        return s.Compare(head, read_num(a), read_num(b), lst.loc)  # type: ignore[arg-type]
    if _is_timed(lst):
        when = _time_specifier(lst)
        return s.Timed(when, read_formula(lst.items[2]), lst.loc)  # type: ignore[arg-type]
    return read_atom(lst)


def _is_timed(lst: SList) -> bool:
    """``(at start ...)``, ``(at end ...)``, ``(over all ...)``; ``(at truck depot)`` is an atom
    of a predicate named ``at``."""
    head = lst.head()
    if head not in g.TIME_SPECIFIERS or len(lst.items) < 2:
        return False
    second = lst.items[1]
    return isinstance(second, Token) and second.lower in g.TIME_SPECIFIERS[head]


def _time_specifier(lst: SList) -> str:
    head = lst.head() or ""
    check_arity(lst, 2, 2, head)
    second = lst.items[1]
    table = g.TIME_SPECIFIERS[head]
    if not isinstance(second, Token) or second.lower not in table:
        raise fail(f"bad time specifier after '{head}'", second,
                   expected=" or ".join(f"'{head} {w}'" for w in table))
    return table[second.lower]


# --------------------------------------------------------------------------------------- effects


def read_effect(expr: SExpr) -> s.EffectNode:
    """An effect (``EFFECT`` in the grammar), continuous ones included."""
    lst = expect_list(expr, "an effect")
    if not lst.items:
        return s.EffectConjunction((), lst.loc)
    head = lst.head()
    if head == "and":
        return s.EffectConjunction(tuple(read_effect(p) for p in lst.items[1:]), lst.loc)
    if head == "not":
        check_arity(lst, 1, 1, "not")
        inner = expect_list(lst.items[1], "an atom")
        return s.DeleteEffect(read_atom(inner), lst.loc)
    if head == "forall":
        check_arity(lst, 2, 2, "forall")
        params = read_typed_list(expect_list(lst.items[1], "a variable list").items, True)
        return s.ForallEffect(params, read_effect(lst.items[2]), lst.loc)
    if head == "when":
        check_arity(lst, 2, 2, "when")
        return s.WhenEffect(read_formula(lst.items[1]), read_effect(lst.items[2]), lst.loc)
    if head in g.ASSIGN_OPS:
        check_arity(lst, 2, 2, head)
        target = read_num(lst.items[1])
        if not isinstance(target, s.FunctionTerm):
            raise fail(f"'{head}' needs a function term to change", lst.items[1],
                       expected="(function args...)")
        return s.NumericAssignment(head, target, read_num(lst.items[2]), lst.loc)  # type: ignore[arg-type]
    if _is_timed(lst):
        when = _time_specifier(lst)
        return s.Timed(when, read_effect(lst.items[2]), lst.loc)  # type: ignore[arg-type]
    if head in g.CONNECTIVES or head in g.QUANTIFIERS or head in g.COMPARISONS:
        raise fail(f"'{head}' is not an effect", lst,
                   expected="an atom, (not atom), and, forall, when or a numeric update")
    return s.AddEffect(read_atom(lst), lst.loc)
