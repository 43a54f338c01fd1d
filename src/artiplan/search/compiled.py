"""The task compiled for search: conditions and effects as generated Python functions.

The planner evaluates conditions millions of times, so each condition of a
:class:`~artiplan.pddl.task.Task` is turned into one Python ``lambda F, V: ...`` where ``F`` is the
set of true facts as an ``int`` bit mask and ``V`` the tuple of fluent values. Effects become
functions ``(F, V) -> (F2, V2)`` (PDDL 2.1: every expression read in the state before the
happening, deletes before adds). Comparisons are also kept as *linear forms* (``sum a_i v_i + b``
compared with 0) so that the exact wait computation can find the moment they change truth value.

This is the search's fast private view of the task; the reference semantics (and the final check
of every plan) is :mod:`artiplan.semantics`.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field

from artiplan.pddl.task import (
    And,
    Atom,
    BinOp,
    Comparison,
    Condition,
    Const,
    Effect,
    FluentRef,
    GroundAction,
    Neg,
    Not,
    NumExpr,
    Or,
    Task,
    Truth,
)
from artiplan.semantics.expressions import expr_source as semantics_expr_source
from artiplan.tolerances import VAL_SLACK

CondFn = Callable[[int, tuple[float, ...]], bool]
EffectFn = Callable[[int, tuple[float, ...]], tuple[int, tuple[float, ...]]]
#: A linear form ``({fluent: coefficient}, constant)``; ``None`` where the expression is not linear.
Linear = tuple[dict[int, float], float]


def linearize(expr: NumExpr) -> Linear | None:
    """``expr`` as ``sum a_i v_i + b``, or ``None`` if it is not linear in the fluents."""
    if isinstance(expr, Const):
        return {}, float(expr.value)
    if isinstance(expr, FluentRef):
        return {expr.index: 1.0}, 0.0
    if isinstance(expr, Neg):
        inner = linearize(expr.operand)
        return None if inner is None else ({k: -a for k, a in inner[0].items()}, -inner[1])
    left, right = linearize(expr.left), linearize(expr.right)
    if left is None or right is None:
        return None
    if expr.op in "+-":
        sign = 1.0 if expr.op == "+" else -1.0
        coeffs = dict(left[0])
        for k, a in right[0].items():
            coeffs[k] = coeffs.get(k, 0.0) + sign * a
        return {k: a for k, a in coeffs.items() if a != 0.0}, left[1] + sign * right[1]
    if expr.op == "*":
        if not left[0]:
            return {k: left[1] * a for k, a in right[0].items()}, left[1] * right[1]
        if not right[0]:
            return {k: right[1] * a for k, a in left[0].items()}, left[1] * right[1]
        return None
    if expr.op == "/" and not right[0] and right[1] != 0.0:
        return {k: a / right[1] for k, a in left[0].items()}, left[1] / right[1]
    return None


def fluents_of(expr: NumExpr) -> set[int]:
    """Fluent indices an expression reads."""
    if isinstance(expr, FluentRef):
        return {expr.index}
    if isinstance(expr, Neg):
        return fluents_of(expr.operand)
    if isinstance(expr, BinOp):
        return fluents_of(expr.left) | fluents_of(expr.right)
    return set()


def expr_source(expr: NumExpr) -> str:
    """Python source of a numeric expression over ``V`` (the compiled functions' argument)."""
    return semantics_expr_source(expr, "V")


@dataclass(frozen=True)
class CompiledComparison:
    """``p op 0`` with ``p = left - right``: a condition the waits watch."""

    op: str
    expr: NumExpr  # p
    linear: Linear | None
    fluents: frozenset[int]


@dataclass(frozen=True)
class Slack:
    """How comparisons are read (as :mod:`artiplan.semantics` reads them): ``x > c`` iff
    ``x - c > -strict``; ``x >= c`` iff ``x - c >= -eps``; ``x = c`` iff ``|x - c| <= eps``."""

    strict: float = 1e-4
    eps: float = 1e-9

    def offset(self, op: str) -> float:
        """``p op 0`` is read as ``p + offset op 0``."""
        return {">": self.strict, "<": -self.strict, ">=": self.eps, "<=": -self.eps}.get(op, 0.0)


#: VAL's reading: goal, action and event preconditions (``semantics.VAL_TOLERANCES``)
VAL_READING = Slack(VAL_SLACK, VAL_SLACK)
#: exact up to rounding: process preconditions (``semantics`` settles flows this way)
SNAP_SLACK = Slack(-1e-9, 1e-9)


@dataclass
class ComparisonTable:
    """Distinct comparisons of the task, numbered; conditions refer to them by number.

    The waits look for the exact roots of ``p`` (``p = left - right``): that is where the
    reference semantics fires events and switches processes.
    """

    items: list[CompiledComparison] = field(default_factory=list)
    index: dict[tuple[str, str], int] = field(default_factory=dict)

    def add(self, comp: Comparison) -> int:
        p: NumExpr = BinOp("-", comp.left, comp.right)
        key = (comp.op, repr(p))
        if key not in self.index:
            self.index[key] = len(self.items)
            self.items.append(
                CompiledComparison(comp.op, p, linearize(p), frozenset(fluents_of(p)))
            )
        return self.index[key]


def condition_source(
    cond: Condition, comps: ComparisonTable, used: set[int], slack: Slack = VAL_READING
) -> str:
    """Python source of a condition over ``F`` (fact mask) and ``V``; records comparisons."""
    if isinstance(cond, Truth):
        return "True" if cond.value else "False"
    if isinstance(cond, Atom):
        return f"(F & {1 << cond.fact} != 0)"
    if isinstance(cond, Not):
        return f"(not {condition_source(cond.operand, comps, used, slack)})"
    if isinstance(cond, (And, Or)):
        if not cond.parts:
            return "True" if isinstance(cond, And) else "False"
        glue = " and " if isinstance(cond, And) else " or "
        return "(" + glue.join(condition_source(p, comps, used, slack) for p in cond.parts) + ")"
    used.add(comps.add(cond))
    left, right = expr_source(cond.left), expr_source(cond.right)
    if cond.op == "=":
        return f"(abs({left} - {right}) <= {slack.eps!r})"
    off = slack.offset(cond.op)
    return f"({left} - {right} + {off!r} {cond.op} 0.0)"


def compile_condition(
    cond: Condition, comps: ComparisonTable, slack: Slack = VAL_READING
) -> tuple[CondFn, frozenset[int]]:
    """A condition as a function ``(F, V) -> bool`` plus the comparisons it reads."""
    used: set[int] = set()
    src = condition_source(cond, comps, used, slack)
    fn: CondFn = eval(f"lambda F, V: {src}")  # noqa: S307 - source generated from the task
    return fn, frozenset(used)


def fact_literals(cond: Condition) -> tuple[int, int] | None:
    """(required mask, forbidden mask) of the facts at the top level of ``cond``; None if false.

    Only the top-level conjunction is read; the rest of the condition is checked by its function.
    Used to skip operators cheaply before evaluating their full condition.
    """
    req = forb = 0
    parts = cond.parts if isinstance(cond, And) else (cond,)
    for part in parts:
        if isinstance(part, Truth) and not part.value:
            return None  # can never hold
        if isinstance(part, Atom):
            req |= 1 << part.fact
        elif isinstance(part, Not) and isinstance(part.operand, Atom):
            forb |= 1 << part.operand.fact
    return req, forb


def _effect_lines(eff: Effect, indent: str, comps: ComparisonTable, lines: list[str]) -> None:
    add = sum(1 << f for f in eff.add)
    dele = sum(1 << f for f in eff.delete)
    if add:
        lines.append(f"{indent}add |= {add}")
    if dele:
        lines.append(f"{indent}dele |= {dele}")
    for ne in eff.numeric:
        e, i = expr_source(ne.expr), ne.fluent
        rhs = {
            "assign": e,
            "increase": f"W[{i}] + {e}",
            "decrease": f"W[{i}] - {e}",
            "scale-up": f"W[{i}] * {e}",
            "scale-down": f"W[{i}] / {e}",
        }[ne.op]
        lines.append(f"{indent}W[{i}] = {rhs}")
    for ce in eff.conditional:
        used: set[int] = set()
        lines.append(f"{indent}if {condition_source(ce.condition, comps, used)}:")
        lines.append(f"{indent}    pass")
        _effect_lines(ce.effect, indent + "    ", comps, lines)


def compile_effect(eff: Effect, comps: ComparisonTable) -> EffectFn:
    """An effect as ``(F, V) -> (F2, V2)``; expressions read the state before the happening."""
    lines = ["def _eff(F, V):", "    add = 0", "    dele = 0", "    W = list(V)"]
    _effect_lines(eff, "    ", comps, lines)
    lines.append("    return (F & ~dele) | add, tuple(W)")
    namespace: dict[str, object] = {}
    exec("\n".join(lines), namespace)  # noqa: S102 - source generated from the task
    return namespace["_eff"]  # type: ignore[return-value]


def written_fluents(eff: Effect) -> set[int]:
    """Fluents an instantaneous effect may change."""
    out = {ne.fluent for ne in eff.numeric}
    for ce in eff.conditional:
        out |= written_fluents(ce.effect)
    return out


def is_noop(action: GroundAction) -> bool:
    """True for an action with no effect at all (the domains' ``observe``)."""
    eff = action.effect
    return not (eff.add or eff.delete or eff.numeric or eff.conditional)


@dataclass(frozen=True)
class CompiledOp:
    """An action or event: precondition and effect compiled, with a cheap fact filter."""

    index: int
    signature: str
    name: str
    args: tuple[str, ...]
    pre: CondFn
    pre_comps: frozenset[int]
    req: int
    forb: int
    effect: EffectFn
    noop: bool


@dataclass(frozen=True)
class CompiledProcess:
    """A process: its precondition, and per fluent its rate as a linear form (or raw)."""

    index: int
    signature: str
    pre: CondFn
    pre_comps: frozenset[int]
    req: int
    forb: int
    rates: tuple[tuple[int, Linear | None, NumExpr], ...]
    pre_class: int = 0  # processes with equal preconditions share a class


def _compile_op(i: int, op: GroundAction, comps: ComparisonTable) -> CompiledOp:
    pre, used = compile_condition(op.precondition, comps)
    lits = fact_literals(op.precondition) or (0, 0)
    return CompiledOp(
        i,
        op.signature,
        op.name,
        op.args,
        pre,
        used,
        lits[0],
        lits[1],
        compile_effect(op.effect, comps),
        is_noop(op),
    )


@dataclass
class CompiledTask:
    """Everything the search evaluates, compiled once per task."""

    task: Task
    comps: ComparisonTable
    actions: list[CompiledOp]
    events: list[CompiledOp]
    processes: list[CompiledProcess]
    goal: CondFn
    goal_comps: frozenset[int]
    init_facts: int
    init_values: tuple[float, ...]
    #: comparison ids watched while waiting: goal, action, event and process preconditions
    watched: frozenset[int]
    #: comparison ids that can change the dynamics (event and process preconditions)
    dynamic: frozenset[int]
    fluent_comps: dict[int, tuple[int, ...]]

    @property
    def n_fluents(self) -> int:
        return len(self.task.fluents)


def compile_task(task: Task) -> CompiledTask:
    """Compile ``task`` for search (a few milliseconds per hundred operators)."""
    comps = ComparisonTable()
    actions = [_compile_op(i, a, comps) for i, a in enumerate(task.actions)]
    events = [_compile_op(i, e, comps) for i, e in enumerate(task.events)]
    processes = []
    # processes with equal preconditions (a link's gravity carried to each tip-ward link) share
    # one compiled condition and one class, so their truth is computed once per state
    classes: dict[Condition, int] = {}
    shared: dict[int, tuple[CondFn, frozenset[int]]] = {}
    for i, p in enumerate(task.processes):
        cls = classes.setdefault(p.precondition, len(classes))
        if cls not in shared:
            shared[cls] = compile_condition(p.precondition, comps, SNAP_SLACK)
        pre, used = shared[cls]
        lits = fact_literals(p.precondition) or (0, 0)
        rates = tuple((ce.fluent, linearize(ce.rate), ce.rate) for ce in p.continuous)
        processes.append(CompiledProcess(i, p.signature, pre, used, lits[0], lits[1], rates, cls))
    goal, goal_comps = compile_condition(task.goal, comps)
    dynamic = frozenset().union(*(e.pre_comps for e in events), *(p.pre_comps for p in processes))
    watched = dynamic | goal_comps | frozenset().union(*(a.pre_comps for a in actions))
    fluent_comps: dict[int, list[int]] = {}
    for cid in sorted(watched):
        for f in comps.items[cid].fluents:
            fluent_comps.setdefault(f, []).append(cid)
    init_values = tuple(float("nan") if v is None else float(v) for v in task.init_values)
    return CompiledTask(
        task=task,
        comps=comps,
        actions=actions,
        events=events,
        processes=processes,
        goal=goal,
        goal_comps=goal_comps,
        init_facts=sum(1 << f for f in task.init_facts),
        init_values=init_values,
        watched=watched,
        dynamic=dynamic,
        fluent_comps={f: tuple(c) for f, c in fluent_comps.items()},
    )
