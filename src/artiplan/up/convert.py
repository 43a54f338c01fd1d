"""unified-planning problems and plans <-> PDDL+ text and artiplan plans.

A problem goes through unified-planning's own :class:`~unified_planning.io.PDDLWriter` (its
names are mangled into valid PDDL names; the writer maps them back). Two things differ between
the models, and this module bridges them:

* **The end of a plan.** A PDDL+ plan ends at its last happening (VAL checks the goal there), so
  a plan that waits for a process to complete the goal must end with an action; the paper's
  domains have a no-effect ``observe`` for this. unified-planning's ``TimeTriggeredPlan`` has
  no end marker, and many unified-planning PDDL+ problems have no such action. When a problem
  with processes has no action without effects, the domain artiplan plans with gets one more,
  :data:`END_ACTION`; the plan handed back leaves it out and reports its time as the plan's end
  (``Converted.plan_end``). See :mod:`artiplan.up.ending` for how the validator reads such
  plans.
* **The kind of plan.** Problems with processes get a ``TimeTriggeredPlan`` (times in seconds,
  exact decimals, as artiplan writes them); problems without get a ``SequentialPlan``.
"""

from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction
from typing import Any

from unified_planning.io import PDDLWriter
from unified_planning.model import InstantaneousAction, Problem
from unified_planning.plans import ActionInstance, SequentialPlan, TimeTriggeredPlan

from artiplan.semantics.plan import Plan, TimedAction
from artiplan.semantics.plan_io import format_time

#: Name of the no-effect action added to domains with processes but no such action of their own.
END_ACTION = "artiplan-plan-end"

#: Time [s] between the actions of a ``SequentialPlan`` when it is validated: any gap at least
#: the validator's tolerance reads the same (without processes, time changes nothing).
SEQUENTIAL_GAP = 1.0


class ConversionError(Exception):
    """A problem or plan that cannot be expressed for artiplan (the message says what)."""


@dataclass
class Converted:
    """A unified-planning problem written as PDDL+.

    Attributes:
        problem: The unified-planning problem.
        domain: PDDL+ domain text (with :data:`END_ACTION` when ``end_action`` is set).
        pddl_problem: PDDL+ problem text.
        writer: The writer, which knows the name mapping.
        end_action: The added no-effect action's PDDL name, or None.
        timed: True when the problem has processes (plans are time-triggered).
    """

    problem: Problem
    domain: str
    pddl_problem: str
    writer: PDDLWriter
    end_action: str | None
    timed: bool
    _items: dict[str, Any] | None = None

    def item(self, pddl_name: str) -> Any:
        """The unified-planning action or object a PDDL name stands for (case-insensitive)."""
        if self._items is None:
            self._items = {}
            for a in self.problem.actions:
                self._items[self.writer.get_pddl_name(a).lower()] = a
            for o in self.problem.all_objects:
                self._items[self.writer.get_pddl_name(o).lower()] = o
        try:
            return self._items[pddl_name.lower()]
        except KeyError:
            raise ConversionError(f"the plan names {pddl_name!r}, unknown to the problem") from None


def has_noop(problem: Problem) -> bool:
    """True when the problem has an instantaneous action without effects (VAL's plan end)."""
    return any(isinstance(a, InstantaneousAction) and not a.effects and
               a.simulated_effect is None for a in problem.actions)


def to_pddl(problem: Problem, kind: Any = None, add_end_action: bool = True) -> Converted:
    """Write ``problem`` as PDDL+ text; with ``add_end_action``, add :data:`END_ACTION` when
    the problem has processes and no no-effect action of its own.

    ``kind``: the problem's kind if the caller has it (``problem.kind`` walks the whole problem,
    and unified-planning's writer asks for it five times; it gets this one instead).
    Raises ConversionError when unified-planning's writer cannot write the problem.
    """
    source = problem if kind is None else _KindOnce(problem, kind)
    writer = PDDLWriter(source, needs_requirements=True, rewrite_bool_assignments=True)
    try:
        domain = writer.get_domain()
        pddl_problem = writer.get_problem()
    except Exception as exc:  # the writer raises several UP exception types
        raise ConversionError(f"unified-planning's PDDL writer failed: {exc}") from exc
    timed = len(problem.processes) > 0
    end = None
    if add_end_action and timed and not has_noop(problem):
        end = _fresh_name(writer, END_ACTION)
        domain = _append_action(domain, end)
    return Converted(problem, domain, pddl_problem, writer, end, timed)


class _KindOnce:
    """``problem`` with its kind computed once: the writer reads everything else through it.

    unified-planning's writer only checks ``isinstance`` for hierarchical problems, which
    artiplan does not accept, so a delegating object writes the same text.
    """

    def __init__(self, problem: Problem, kind: Any) -> None:
        self._problem = problem
        self.kind = kind

    def __getattr__(self, name: str) -> Any:
        return getattr(self._problem, name)


def _fresh_name(writer: PDDLWriter, base: str) -> str:
    name, k = base, 0
    while _named(writer, name):
        k += 1
        name = f"{base}-{k}"
    return name


def _named(writer: PDDLWriter, name: str) -> bool:
    try:
        writer.get_item_named(name)
    except Exception:
        return False
    return True


def _append_action(domain: str, name: str) -> str:
    """``domain`` with a no-effect action before its closing parenthesis."""
    body = domain.rstrip()
    if not body.endswith(")"):
        raise ConversionError("unexpected PDDL domain text: no closing parenthesis")
    action = f" (:action {name}\n  :parameters ()\n  :precondition (and)\n  :effect (and))\n"
    return body[:-1] + action + ")\n"


def to_up_plan(conv: Converted, plan: Plan) -> tuple[Any, float | None]:
    """artiplan's plan as a unified-planning plan, and its end [s] if it ends with
    :data:`END_ACTION` (which the returned plan leaves out)."""
    em = conv.problem.environment.expression_manager
    items: list[tuple[Fraction, ActionInstance]] = []
    end = None
    for ta in sorted(plan.actions, key=lambda a: a.time):
        if conv.end_action is not None and ta.name.lower() == conv.end_action.lower():
            end = ta.time
            continue
        action = conv.item(ta.name)
        params = tuple(em.ObjectExp(conv.item(arg)) for arg in ta.args)
        items.append((Fraction(format_time(ta.time)), ActionInstance(action, params)))
    if conv.timed:
        return TimeTriggeredPlan([(t, ai, None) for t, ai in items]), end
    return SequentialPlan([ai for _, ai in items]), end


def from_up_plan(conv: Converted, up_plan: Any) -> tuple[Plan, list[ActionInstance]]:
    """A unified-planning plan as an artiplan plan, and its action instances in plan order
    (``TimedAction.line`` is the 1-based position there, so failures point back to them).

    Raises ConversionError for plans artiplan cannot read: durative actions, a
    ``SequentialPlan`` for a problem with processes (it has no times), other plan kinds.
    """
    if isinstance(up_plan, TimeTriggeredPlan):
        timed = list(up_plan.timed_actions)
        if any(d is not None for _, _, d in timed):
            raise ConversionError("the plan has durative actions, which artiplan does not read")
        entries = [(float(t), ai) for t, ai, _ in timed]
    elif isinstance(up_plan, SequentialPlan):
        if conv.timed:
            raise ConversionError("a SequentialPlan has no times, but the problem has processes: "
                                  "give a TimeTriggeredPlan")
        entries = [(k * SEQUENTIAL_GAP, ai) for k, ai in enumerate(up_plan.actions)]
    else:
        raise ConversionError(f"artiplan reads TimeTriggeredPlan and SequentialPlan, not "
                              f"{type(up_plan).__name__}")
    actions = []
    instances = []
    for k, (t, ai) in enumerate(entries, 1):
        args = []
        for p in ai.actual_parameters:
            if not p.is_object_exp():
                raise ConversionError(f"parameter {p} of {ai} is not an object")
            args.append(_pddl_name(conv, p.object()))
        name = _pddl_name(conv, ai.action)
        actions.append(TimedAction(t, name, tuple(args), line=k))
        instances.append(ai)
    return Plan(tuple(actions)), instances


def _pddl_name(conv: Converted, item: Any) -> str:
    """The PDDL name of ``item``; its own name if the problem does not have it (the validator
    then reports a bad operator, as VAL does)."""
    try:
        return str(conv.writer.get_pddl_name(item))
    except Exception:
        return str(item.name)
