"""PDDL 2.1 durative actions (levels 3-4) compiled into PDDL+, on the syntax tree.

A durative action ``N`` with parameters ``P`` becomes, with ``N@running P`` a new predicate and
``N@clock P`` a new numeric fluent:

* action ``N@start P``: precondition its ``at start`` conditions and ``(not (N@running P))``
  (no overlapping runs of one instance); effect its ``at start`` effects, ``(N@running P)``,
  clock := 0, and the duration's bounds when they read fluents (stored in ``N@min``/``N@max``:
  PDDL 2.1 evaluates them at the start);
* process ``N@during P``: while running, the clock grows at 1 s/s and the action's continuous
  effects (``(increase f (* #t r))``) act;
* action ``N@end P``: precondition running, the clock within the duration's bounds, its
  ``at end`` conditions; effect its ``at end`` effects (``?duration`` read as the clock) and
  running off;
* constraint ``N@overall P``: ``(imply (N@running P) C)`` for its ``over all`` conditions, an
  invariant checked on every open stretch of time (so an ``over all`` must hold strictly
  inside the action's interval, as PDDL 2.1 says).

Fixed durations ``(= ?duration d)`` get a window of +-:data:`END_SLACK` seconds (a grid step
and a half of the plan's 6 decimals), so the end falls on the plan's grid; the plan written
says the duration it ran. Plans name the durative action: ``t: (N args) [d]``
(:func:`artiplan.pddl.task.Task.durative`).
"""

from __future__ import annotations

from artiplan.errors import InputError
from artiplan.pddl import grammar as g
from artiplan.pddl import syntax as s
from artiplan.records import replace

#: Half-width [s] of a fixed duration's window for the end (1.5 grid steps of 1e-6 s).
END_SLACK = 1.5e-6

START, END, DURING, RUNNING, CLOCK, MIN, MAX, OVERALL = (
    "@start", "@end", "@during", "@running", "@clock", "@min", "@max", "@overall")


def compile_durative(domain: s.Domain) -> tuple[s.Domain, tuple[str, ...]]:
    """The domain with every durative action compiled (module docstring), and their names."""
    durative = [op for op in domain.operators if op.kind == "durative-action"]
    if not durative:
        return domain, ()
    predicates, functions, operators = list(domain.predicates), list(domain.functions), []
    for op in domain.operators:
        if op.kind != "durative-action":
            operators.append(op)
            continue
        parts = _Parts.of(op)
        predicates.append(s.PredicateDecl(op.name + RUNNING, op.parameters, op.loc))
        functions.append(s.FunctionDecl(op.name + CLOCK, op.parameters, None, op.loc))
        functions += [s.FunctionDecl(op.name + k, op.parameters, None, op.loc)
                      for k, bound in ((MIN, parts.low), (MAX, parts.high))
                      if bound is not None and _reads_fluents(bound)]
        operators += parts.operators()
    return replace(domain, predicates=tuple(predicates), functions=tuple(functions),
                   operators=tuple(operators)), tuple(op.name for op in durative)


def _reads_fluents(e: s.NumExpr) -> bool:
    if isinstance(e, s.FunctionTerm):
        return True
    if isinstance(e, s.Arithmetic):
        return any(_reads_fluents(a) for a in e.args)
    return isinstance(e, s.Minus) and _reads_fluents(e.operand)


class _Parts:
    """A durative action's conditions, effects and duration bounds, split by time."""

    def __init__(self, op: s.Operator) -> None:
        self.op = op
        self.args = tuple(s.Variable(p.name, p.loc) for p in op.parameters)
        self.start_pre: list[s.Formula] = []
        self.end_pre: list[s.Formula] = []
        self.overall: list[s.Formula] = []
        self.start_eff: list[s.EffectNode] = []
        self.end_eff: list[s.EffectNode] = []
        self.continuous: list[s.EffectNode] = []
        self.low: s.NumExpr | None = None
        self.high: s.NumExpr | None = None

    @classmethod
    def of(cls, op: s.Operator) -> _Parts:
        parts = cls(op)
        for f in _conjuncts(op.precondition):
            parts._condition(f)
        for e in _effects(op.effect):
            parts._effect(e)
        for f in _conjuncts(op.duration):
            parts._duration(f)
        return parts

    def _condition(self, f: s.Formula) -> None:
        if not isinstance(f, s.Timed):
            raise InputError(f"a condition of durative action '{self.op.name}' needs a time",
                             f.loc, expected="(at start c), (at end c) or (over all c)",
                             found="an untimed condition")
        body: s.Formula = f.body  # type: ignore[assignment]  # a condition's body
        {"at start": self.start_pre, "at end": self.end_pre, "over all": self.overall}[
            f.when].append(body)

    def _effect(self, e: s.EffectNode) -> None:
        if isinstance(e, s.Timed):
            if e.when == "over all":
                raise InputError("an effect cannot be 'over all'", e.loc,
                                 expected="(at start e) or (at end e)", found="(over all ...)")
            body: s.EffectNode = e.body  # type: ignore[assignment]  # an effect's body
            (self.start_eff if e.when == "at start" else self.end_eff).append(body)
        elif isinstance(e, s.NumericAssignment) and _mentions(e.expr, g.TIME_SYMBOL):
            self.continuous.append(e)
        else:
            raise InputError(f"an effect of durative action '{self.op.name}' needs a time",
                             e.loc, expected="(at start e), (at end e) or (increase f (* #t r))",
                             found="an untimed effect")

    def _duration(self, f: s.Formula) -> None:
        if not (isinstance(f, s.Compare) and isinstance(f.left, s.Special)
                and f.left.name == g.DURATION_SYMBOL):
            raise InputError("a duration constraint compares ?duration with an expression",
                             f.loc, expected="(= ?duration e), (<= ?duration e) or "
                             "(>= ?duration e)", found="another constraint")
        if f.op in ("=", "<=", "<"):
            self.high = f.right
        if f.op in ("=", ">=", ">"):
            self.low = f.right

    # ------------------------------------------------------------------------------ output
    def _atom(self, suffix: str) -> s.AtomicFormula:
        return s.AtomicFormula(self.op.name + suffix, self.args, self.op.loc)

    def _fluent(self, suffix: str) -> s.FunctionTerm:
        return s.FunctionTerm(self.op.name + suffix, self.args, self.op.loc)

    def _bound(self, suffix: str, e: s.NumExpr | None) -> s.NumExpr | None:
        return None if e is None else (self._fluent(suffix) if _reads_fluents(e) else e)

    def operators(self) -> list[s.Operator]:
        op, loc = self.op, self.op.loc
        running, clock = self._atom(RUNNING), self._fluent(CLOCK)
        fixed = self.low is not None and self.low == self.high
        start_eff = [*self.start_eff, s.AddEffect(running, loc),
                     s.NumericAssignment("assign", clock, s.Number(0.0, loc), loc)]
        for suffix, bound in ((MIN, self.low), (MAX, self.high)):
            if bound is not None and _reads_fluents(bound):
                start_eff.append(s.NumericAssignment("assign", self._fluent(suffix), bound, loc))
        if any(_mentions_effect(e, g.DURATION_SYMBOL) for e in self.start_eff):
            if not fixed:
                raise InputError(f"?duration in an 'at start' effect of '{op.name}' needs a "
                                 "fixed duration", loc, expected="(= ?duration e)",
                                 found="an inequality")
            assert self.low is not None
            start_eff = [_subst_effect(e, self.low) for e in start_eff]
        window = []
        slack = s.Number(END_SLACK if fixed else 0.0, loc)
        low, high = self._bound(MIN, self.low), self._bound(MAX, self.high)
        if low is not None:
            window.append(s.Compare(">=", clock, s.Arithmetic("-", (low, slack), loc), loc))
        if high is not None:
            window.append(s.Compare("<=", clock, s.Arithmetic("+", (high, slack), loc), loc))
        end_eff = [_subst_effect(e, clock) for e in self.end_eff]
        during = [s.NumericAssignment("increase", clock, s.Arithmetic(
            "*", (s.Special("#t", loc), s.Number(1.0, loc)), loc), loc),
            *[_subst_effect(e, clock) for e in self.continuous]]
        out = [
            s.Operator("action", op.name + START, op.parameters,
                       s.Conjunction((*self.start_pre, s.Negation(running, loc)), loc),
                       s.EffectConjunction(tuple(start_eff), loc), loc=loc),
            s.Operator("process", op.name + DURING, op.parameters, running,
                       s.EffectConjunction(tuple(during), loc), loc=loc),
            s.Operator("action", op.name + END, op.parameters,
                       s.Conjunction((running, *window, *self.end_pre), loc),
                       s.EffectConjunction((*end_eff, s.DeleteEffect(running, loc)), loc),
                       loc=loc),
        ]
        if self.overall:
            out.append(s.Operator("constraint", op.name + OVERALL, op.parameters,
                                  s.Implication(running, s.Conjunction(tuple(self.overall), loc),
                                                loc), loc=loc))
        return out


def _conjuncts(f: s.Formula | None) -> list[s.Formula]:
    if f is None:
        return []
    if isinstance(f, s.Conjunction):
        return [c for p in f.parts for c in _conjuncts(p)]
    return [f]


def _effects(e: s.EffectNode | None) -> list[s.EffectNode]:
    if e is None:
        return []
    if isinstance(e, s.EffectConjunction):
        return [x for p in e.parts for x in _effects(p)]
    if isinstance(e, s.Timed) and isinstance(e.body, s.EffectConjunction):
        return [s.Timed(e.when, x, e.loc) for x in _effects(e.body)]
    return [e]


def _mentions(e: s.NumExpr, symbol: str) -> bool:
    if isinstance(e, s.Special):
        return e.name == symbol
    if isinstance(e, s.Arithmetic):
        return any(_mentions(a, symbol) for a in e.args)
    return isinstance(e, s.Minus) and _mentions(e.operand, symbol)


def _mentions_effect(e: s.EffectNode, symbol: str) -> bool:
    if isinstance(e, s.NumericAssignment):
        return _mentions(e.expr, symbol)
    if isinstance(e, s.EffectConjunction):
        return any(_mentions_effect(p, symbol) for p in e.parts)
    if isinstance(e, s.ForallEffect):
        return _mentions_effect(e.body, symbol)
    if isinstance(e, s.WhenEffect):
        return _mentions_effect(e.effect, symbol)
    return False


def _subst(e: s.NumExpr, value: s.NumExpr) -> s.NumExpr:
    """``e`` with ``?duration`` replaced by ``value``."""
    if isinstance(e, s.Special) and e.name == g.DURATION_SYMBOL:
        return value
    if isinstance(e, s.Arithmetic):
        return replace(e, args=tuple(_subst(a, value) for a in e.args))
    if isinstance(e, s.Minus):
        return replace(e, operand=_subst(e.operand, value))
    return e


def _subst_effect(e: s.EffectNode, value: s.NumExpr) -> s.EffectNode:
    if isinstance(e, s.NumericAssignment):
        return replace(e, expr=_subst(e.expr, value))
    if isinstance(e, s.EffectConjunction):
        return replace(e, parts=tuple(_subst_effect(p, value) for p in e.parts))
    if isinstance(e, s.ForallEffect):
        return replace(e, body=_subst_effect(e.body, value))
    if isinstance(e, s.WhenEffect):
        return replace(e, effect=_subst_effect(e.effect, value))
    return e
