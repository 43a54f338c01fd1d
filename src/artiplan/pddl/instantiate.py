"""Instantiate syntax-tree conditions, expressions and effects under a variable binding.

The result uses the indexed forms of :mod:`artiplan.pddl.task`: static facts fold to
``TRUE``/``FALSE``, static numeric fluents to ``Const``, equality is decided, quantifiers are
expanded over the typed objects and ``imply`` becomes ``or``.
"""

from __future__ import annotations

from artiplan.errors import InputError
from artiplan.pddl import grammar as g
from artiplan.pddl import syntax as s
from artiplan.pddl import task as t
from artiplan.pddl.renumber import fluents_in_num
from artiplan.pddl.simplify import make_and, make_arith, make_compare, make_not, make_or
from artiplan.records import dataclass, field

Binding = dict[str, str]
Key = tuple[str, ...]


@dataclass
class GroundContext:
    """What instantiation needs to know, and the fact and fluent numbering it builds.

    Keys are lower-case tuples ``(name, arg1, ...)``; ``display`` maps lower-case names to the
    spelling of the files.
    """

    objects_by_type: dict[str, tuple[str, ...]]
    display: dict[str, str]
    static_predicates: frozenset[str]
    static_facts: frozenset[Key]
    static_values: dict[Key, float]
    static_functions: frozenset[str]
    fact_ids: dict[Key, int] = field(default_factory=dict)
    fluent_ids: dict[Key, int] = field(default_factory=dict)
    #: Fluent ids of static functions the problem leaves undefined.
    undefined: set[int] = field(default_factory=set)
    #: ``id(expr)`` -> the rate of a continuous effect's expression (None if not continuous).
    rates: dict[int, s.NumExpr | None] = field(default_factory=dict)

    def fact(self, key: Key) -> int:
        """The id of the fact ``key``, numbering it on first use."""
        i = self.fact_ids.get(key)
        if i is None:
            i = self.fact_ids[key] = len(self.fact_ids)
        return i

    def fluent(self, key: Key) -> int:
        """The id of the fluent ``key``, numbering it on first use."""
        i = self.fluent_ids.get(key)
        if i is None:
            i = self.fluent_ids[key] = len(self.fluent_ids)
        return i

    def objects_of(self, types: tuple[str, ...]) -> tuple[str, ...]:
        """Objects of a type, or of the union of an ``either`` list."""
        if len(types) <= 1:
            return self.objects_by_type.get(types[0].lower() if types else g.ROOT_TYPE, ())
        merged: dict[str, None] = {}
        for ty in types:
            merged.update(dict.fromkeys(self.objects_by_type.get(ty.lower(), ())))
        return tuple(merged)

    def name(self, key: Key) -> str:
        """``(name arg...)`` in the files' spelling."""
        return "(" + " ".join(self.display.get(k, k) for k in key) + ")"


def term_value(term: s.Term, binding: Binding) -> str:
    """The lower-case object a term denotes under ``binding``."""
    key = term.name.lower()
    if isinstance(term, s.Variable):
        return binding[key]
    return key


def atom_key(atom: s.AtomicFormula, binding: Binding) -> Key:
    """The lower-case key ``(predicate, object...)`` of a ground atom."""
    return (atom.predicate.lower(), *(term_value(a, binding) for a in atom.args))


def expand(
    ctx: GroundContext, variables: tuple[s.TypedName, ...], binding: Binding
) -> list[Binding]:
    """All extensions of ``binding`` with objects for ``variables``."""
    out = [binding]
    for v in variables:
        objs = ctx.objects_of(v.types)
        out = [{**b, v.name.lower(): o} for b in out for o in objs]
    return out


def ground_condition(ctx: GroundContext, f: s.Formula, binding: Binding) -> t.Condition:
    """The indexed, simplified form of ``f`` under ``binding``."""
    if isinstance(f, s.AtomicFormula):
        key = atom_key(f, binding)
        if key[0] in ctx.static_predicates:
            return t.TRUE if key in ctx.static_facts else t.FALSE
        return t.Atom(ctx.fact(key))
    if isinstance(f, s.Conjunction):
        return make_and([ground_condition(ctx, p, binding) for p in f.parts])
    if isinstance(f, s.Compare):
        left, right = ground_num(ctx, f.left, binding), ground_num(ctx, f.right, binding)
        if ctx.undefined and not ctx.undefined.isdisjoint(
            (*fluents_in_num(left), *fluents_in_num(right))
        ):
            return t.FALSE  # reads a value nothing ever defines: can never be checked true
        return make_compare(f.op, left, right)
    if isinstance(f, s.Negation):
        return make_not(ground_condition(ctx, f.operand, binding))
    if isinstance(f, s.Disjunction):
        return make_or([ground_condition(ctx, p, binding) for p in f.parts])
    if isinstance(f, s.Implication):
        return make_or([make_not(ground_condition(ctx, f.premise, binding)),
                        ground_condition(ctx, f.conclusion, binding)])
    if isinstance(f, s.Equals):
        same = term_value(f.left, binding) == term_value(f.right, binding)
        return t.TRUE if same else t.FALSE
    if isinstance(f, s.Quantified):
        parts = [ground_condition(ctx, f.body, b) for b in expand(ctx, f.variables, binding)]
        return make_and(parts) if f.quantifier == "forall" else make_or(parts)
    raise InputError("timed conditions belong to durative actions, which artiplan does not "
                     "ground", f.loc, expected="a PDDL+ condition", found="(at/over ...)")


def ground_num(ctx: GroundContext, e: s.NumExpr, binding: Binding) -> t.NumExpr:
    """The indexed form of a numeric expression (static fluents folded to constants)."""
    if isinstance(e, s.Number):
        return t.Const(e.value)
    if isinstance(e, s.FunctionTerm):
        key = (e.name.lower(), *(term_value(a, binding) for a in e.args))
        if key[0] in ctx.static_functions:
            if key in ctx.static_values:
                return t.Const(ctx.static_values[key])
            ctx.undefined.add(ctx.fluent(key))
        return t.FluentRef(ctx.fluent(key))
    if isinstance(e, s.Arithmetic):
        args = [ground_num(ctx, a, binding) for a in e.args]
        out = args[0]
        for a in args[1:]:
            out = make_arith(e.op, out, a)
        return out
    if isinstance(e, s.Minus):
        operand = ground_num(ctx, e.operand, binding)
        return t.Const(-operand.value) if isinstance(operand, t.Const) else t.Neg(operand)
    raise InputError(f"{e.name} is not allowed here", e.loc, expected="a numeric expression",
                     found=e.name)


@dataclass
class EffectParts:
    """An effect being collected: its parts in the order found."""

    add: list[int] = field(default_factory=list)
    delete: list[int] = field(default_factory=list)
    numeric: list[t.NumericEffect] = field(default_factory=list)
    conditional: list[t.ConditionalEffect] = field(default_factory=list)
    continuous: list[t.ContinuousEffect] = field(default_factory=list)

    def effect(self) -> t.Effect:
        """The collected instantaneous parts as a task ``Effect`` (duplicates dropped)."""
        return t.Effect(tuple(dict.fromkeys(self.add)), tuple(dict.fromkeys(self.delete)),
                        tuple(self.numeric), tuple(self.conditional))


def ground_effect(
    ctx: GroundContext, e: s.EffectNode, binding: Binding, out: EffectParts
) -> None:
    """Collect the instantiated parts of ``e`` into ``out``."""
    if isinstance(e, s.EffectConjunction):
        for p in e.parts:
            ground_effect(ctx, p, binding, out)
    elif isinstance(e, s.AddEffect):
        out.add.append(ctx.fact(atom_key(e.atom, binding)))
    elif isinstance(e, s.DeleteEffect):
        out.delete.append(ctx.fact(atom_key(e.atom, binding)))
    elif isinstance(e, s.NumericAssignment):
        _numeric(ctx, e, binding, out)
    elif isinstance(e, s.ForallEffect):
        for b in expand(ctx, e.variables, binding):
            ground_effect(ctx, e.body, b, out)
    elif isinstance(e, s.WhenEffect):
        cond = ground_condition(ctx, e.condition, binding)
        if cond == t.FALSE:
            return
        if cond == t.TRUE:
            ground_effect(ctx, e.effect, binding, out)
            return
        inner = EffectParts()
        ground_effect(ctx, e.effect, binding, inner)
        if inner.continuous:
            raise InputError("conditional continuous effects are not supported", e.loc,
                             expected="continuous effects outside (when ...)", found="(when ...)")
        out.conditional.append(t.ConditionalEffect(cond, inner.effect()))
    else:
        raise InputError("timed effects belong to durative actions, which artiplan does not "
                         "ground", e.loc, expected="a PDDL+ effect", found="(at ...)")


def _numeric(ctx: GroundContext, e: s.NumericAssignment, binding: Binding,
             out: EffectParts) -> None:
    target = e.target
    key = (target.name.lower(), *(term_value(a, binding) for a in target.args))
    fluent = ctx.fluent(key)
    if id(e.expr) not in ctx.rates:
        ctx.rates[id(e.expr)] = time_rate(e.expr)
    rate_expr = ctx.rates[id(e.expr)]
    if rate_expr is None:
        out.numeric.append(t.NumericEffect(e.op, fluent, ground_num(ctx, e.expr, binding)))
        return
    rate = ground_num(ctx, rate_expr, binding)
    if e.op == "decrease":
        rate = t.Const(-rate.value) if isinstance(rate, t.Const) else t.Neg(rate)
    out.continuous.append(t.ContinuousEffect(fluent, rate))


def time_rate(e: s.NumExpr) -> s.NumExpr | None:
    """For ``#t``, ``(* #t r)``, ``(* r #t)`` (or n-ary with one ``#t``) the rate ``r``;
    ``None`` if ``e`` does not mention ``#t``; an error if it is not linear in ``#t``."""
    if isinstance(e, s.Special) and e.name == g.TIME_SYMBOL:
        return s.Number(1.0, e.loc)
    if isinstance(e, s.Arithmetic) and e.op == "*":
        times = [a for a in e.args if isinstance(a, s.Special) and a.name == g.TIME_SYMBOL]
        rest = tuple(a for a in e.args if a not in times)
        if len(times) == 1 and not any(_has_time(a) for a in rest):
            return rest[0] if len(rest) == 1 else s.Arithmetic("*", rest, e.loc)
    if _has_time(e):
        raise InputError("a continuous effect must be (* #t rate)", e.loc,
                         expected="(* #t rate) or (* rate #t)", found="another use of #t")
    return None


def _has_time(e: s.NumExpr) -> bool:
    if isinstance(e, s.Special):
        return e.name == g.TIME_SYMBOL
    if isinstance(e, s.Arithmetic):
        return any(_has_time(a) for a in e.args)
    if isinstance(e, s.Minus):
        return _has_time(e.operand)
    return False
