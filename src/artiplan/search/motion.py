"""Second-order motion for the numeric relaxation: controls, and a position with its speed.

Domains of the PDDL+ literature (the car, a lander) steer a position ``x`` through a chain of
rates: ``x' = k y`` (a process), ``y' = f(u, y)`` (processes), where ``u`` is a *control*, a
fluent only actions write, by constant steps between bounds their preconditions set (``a`` in
-3..3, stepped by accelerate and decelerate). A goal or precondition that wants ``x`` in a box
and ``y`` in a band *at the same time* (a car stopped in a window) cannot be read one comparison
at a time: reaching the box raises the speed, and bringing the speed back takes time and
distance. This module gives the relaxation what it needs for that:

- :func:`find_controls`: every control and the levels it can take (the lattice ``u0 + k step``
  between the bounds the actions' preconditions allow);
- :func:`find_motions`: the position/speed pairs whose speed a control drives;
- :func:`box_time`: the least time [s] of a double integrator into a box of positions and a
  band of speeds, with accelerations bounded (a bang-bang profile with one switch, cruising at
  a speed cap where one applies);
- :class:`MotionGoal`: one conjunction's box, band and caps, and :meth:`MotionGoal.estimate`,
  the fewest control steps (then the least time) that make it by a deadline.

Everything is a relaxation: accelerations are read in the current state with the control at
each level (drag at the current speed), so an estimate may be optimistic, never a proof.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Callable, Sequence

from artiplan.pddl.task import (
    Atom,
    Comparison,
    Condition,
    Const,
    NumExpr,
    Task,
)
from artiplan.records import dataclass, field
from artiplan.search.profile import Profile, Rate, box_profile
from artiplan.semantics.compiled import written_fluents
from artiplan.semantics.walks import conjuncts, fluents_of, linear, linear_difference

Values = tuple[float, ...]
#: Most levels a control may take for the relaxation to step through them.
MAX_LEVELS = 64
#: An estimate longer than this [s] counts as no way (the kernel's horizon is an hour).
HORIZON = 3600.0
#: Share of a speed cap the wait before the next control step keeps clear of [-].
CAP_MARGIN = 0.005


@dataclass(frozen=True)
class Control:
    """A fluent only actions write, by multiples of ``step``, between static bounds.

    Attributes:
        fluent: The fluent's index.
        levels: The values it can take, ascending (its initial value plus multiples of step).
        step: The smallest step of an action on it.
        raise_by: The actions that increase it.
        lower_by: The actions that decrease it.
    """

    fluent: int
    levels: tuple[float, ...]
    step: float
    raise_by: tuple[int, ...] = ()
    lower_by: tuple[int, ...] = ()

    def index(self, value: float) -> int:
        """The level nearest ``value``."""
        return min(range(len(self.levels)), key=lambda i: abs(self.levels[i] - value))


def bound_of(comp: Comparison, fluent: int) -> tuple[str, float, bool] | None:
    """``comp`` as a bound on ``fluent`` alone: (``"hi"`` or ``"lo"``, value, strict), or None
    (``=`` gives None: read it as two bounds with :func:`bounds_of`)."""
    lin = linear_difference(comp)
    if lin is None or set(lin[0]) != {fluent} or comp.op == "=":
        return None
    g, c = lin[0][fluent], lin[1]
    if g == 0.0:
        return None
    at = -c / g
    upper = (comp.op in ("<", "<=")) == (g > 0)
    return ("hi" if upper else "lo"), at, comp.op in ("<", ">")


def bounds_of(comps: Sequence[Comparison], fluent: int) -> tuple[float, float]:
    """The interval [lo, hi] that ``comps`` (each on ``fluent`` alone) allow (strictness
    dropped: a relaxation)."""
    lo, hi = -math.inf, math.inf
    for comp in comps:
        if comp.op == "=":
            lin = linear_difference(comp)
            if lin is not None and set(lin[0]) == {fluent} and lin[0][fluent]:
                at = -lin[1] / lin[0][fluent]
                lo, hi = max(lo, at), min(hi, at)
            continue
        b = bound_of(comp, fluent)
        if b is None:
            continue
        if b[0] == "hi":
            hi = min(hi, b[1])
        else:
            lo = max(lo, b[1])
    return lo, hi


def _single_fluent(comp: Comparison) -> int | None:
    lin = linear_difference(comp)
    if lin is None or len(lin[0]) != 1:
        return None
    return next(iter(lin[0]))


def find_controls(task: Task) -> dict[int, Control]:
    """The controls of ``task`` (see the module's docstring), by fluent."""
    moved = {ce.fluent for p in task.processes for ce in p.continuous}
    banned = set(moved)
    for e in task.events:
        banned |= written_fluents(e.effect)
    steps: dict[int, list[tuple[float, Condition]]] = {}  # fluent -> (step, precondition)
    consts: dict[int, list[float]] = {}
    movers: dict[int, tuple[list[int], list[int]]] = {}
    for ai, a in enumerate(task.actions):
        for ce in a.effect.conditional:
            banned |= written_fluents(ce.effect)
        seen: set[int] = set()
        for ne in a.effect.numeric:
            f = ne.fluent
            if f in seen or not isinstance(ne.expr, Const):
                banned.add(f)
                continue
            seen.add(f)
            if ne.op == "assign":
                consts.setdefault(f, []).append(float(ne.expr.value))
            elif ne.op in ("increase", "decrease"):
                d = float(ne.expr.value) * (1.0 if ne.op == "increase" else -1.0)
                if d:
                    steps.setdefault(f, []).append((d, a.precondition))
                    movers.setdefault(f, ([], []))[0 if d > 0 else 1].append(ai)
            else:
                banned.add(f)
    out: dict[int, Control] = {}
    for f, moves in steps.items():
        if f in banned:
            continue
        levels = _lattice(task.init_values[f], f, moves, consts.get(f, []))
        if levels is not None:
            up, down = movers[f]
            out[f] = Control(f, levels[0], levels[1], tuple(up), tuple(down))
    return out


def _lattice(u0: float | None, f: int, moves: list[tuple[float, Condition]],
             consts: list[float]) -> tuple[tuple[float, ...], float] | None:
    """The levels of control ``f`` and its step (None: unbounded, off a lattice, or too
    many levels)."""
    if u0 is None or not math.isfinite(u0):
        return None
    step = min(abs(d) for d, _ in moves)

    def on(x: float) -> bool:
        k = (x - u0) / step
        return abs(k - round(k)) < 1e-6

    if not all(on(abs(d) + u0) for d, _ in moves) or not all(on(c) for c in consts):
        return None
    hi = max([u0, *consts])
    lo = min([u0, *consts])
    for d, pre in moves:
        comps = [c for c in conjuncts(pre) if isinstance(c, Comparison) and
                 _single_fluent(c) == f]
        bounds = [b for b in (bound_of(c, f) for c in comps) if b is not None]
        side = "hi" if d > 0 else "lo"
        limits = [(at, strict) for s, at, strict in bounds if s == side]
        if not limits:
            return None  # an action moves it without a bound that way
        if d > 0:
            at, strict = min(limits)
            k = math.ceil((at - u0) / step - 1e-6) - 1 if strict else \
                math.floor((at - u0) / step + 1e-6)
            hi = max(hi, u0 + k * step + d)
        else:
            at, strict = max(limits)
            k = math.floor((at - u0) / step + 1e-6) + 1 if strict else \
                math.ceil((at - u0) / step - 1e-6)
            lo = min(lo, u0 + k * step + d)
    n = round((hi - lo) / step) + 1
    if n > MAX_LEVELS or n < 2:
        return None
    return tuple(lo + i * step for i in range(n)), step


@dataclass(frozen=True)
class Motion:
    """``x' = k y`` (processes), with ``y'`` read from a control ``u`` (processes too)."""

    x: int
    y: int
    k: float
    control: Control
    reads: tuple[int, ...] = ()  # the other fluents the speed's rates read


def find_motions(task: Task, controls: dict[int, Control]) -> dict[int, Motion]:
    """The position/speed pairs whose speed a control drives, by position fluent."""
    rates: dict[int, list[NumExpr]] = {}
    for p in task.processes:
        for ce in p.continuous:
            rates.setdefault(ce.fluent, []).append(ce.rate)
    out: dict[int, Motion] = {}
    for x, exprs in rates.items():
        ys: set[int] = set()
        k = 0.0
        for e in exprs:
            lin = linear(e)
            if lin is None or lin[1] != 0.0 or len(lin[0]) != 1:
                break
            (y, c), = lin[0].items()
            ys.add(y)
            k += c
        else:
            if len(ys) != 1 or not k:
                continue
            y = next(iter(ys))
            driven = {u for e in rates.get(y, ()) for u in fluents_of(e) if u in controls}
            if len(driven) == 1 and y != x:
                u = next(iter(driven))
                reads = {j for e in rates.get(y, ()) for j in fluents_of(e)} - {u, y}
                out[x] = Motion(x, y, k, controls[u], tuple(sorted(reads)))
    return out


# ------------------------------------------------------------------------------- the profile


@dataclass(frozen=True)
class Estimate:
    """The way into a motion goal's box: control steps, time [s], the level the control
    should go to first (its index; the current one if no step is due first), and when [s]
    the profile next changes the control if no step is due now (0 otherwise)."""

    steps: int
    time: float
    first: int
    hold: float = 0.0


@functools.lru_cache(maxsize=256)
def _pairs(n: int, c: int) -> tuple[tuple[int, int, int], ...]:
    """(least steps, accelerating level, braking level) from level ``c`` of ``n``, fewest
    first: the control goes to one level, then to the other."""
    return tuple(sorted((min(abs(i - c) + abs(j - i), abs(j - c) + abs(i - j)), i, j)
                        for i in range(n) for j in range(n)))


@dataclass(frozen=True)
class MotionGoal:
    """A conjunction's position box and speed band for one motion, with the speed caps of
    the task (global constraints; events that end the motion for good), in ``x``'s units."""

    motion: Motion
    conds: tuple[int, ...]  # the relaxation's condition indices this estimate stands for
    box: tuple[float, float]
    band: tuple[float, float]  # of x's rate (k * y)
    cap: tuple[float, float]  # of x's rate
    #: the speed's rate per (level, context, the other fluents the rates read)
    _rates: dict[tuple[object, ...], Rate] = field(default_factory=dict, compare=False,
                                                   repr=False)

    def rate(self, values: Values, accel: Callable[[Values], float], level: int,
             context: object = None) -> Rate:
        """The speed's rate at control level ``level`` as a function of the speed (x's rate
        ``k y``), the other values as in ``values`` (tabulated once per level, ``context``:
        what else ``accel`` depends on, and values of the other fluents the rates read)."""
        m = self.motion
        key = (level, context, tuple(values[j] for j in m.reads))
        found = self._rates.get(key)
        if found is None:
            moved = list(values)
            moved[m.control.fluent] = m.control.levels[level]

            def at(w: float) -> float:
                moved[m.y] = w / m.k
                return accel(tuple(moved))

            span = max((abs(b) for b in (*self.cap, *self.band) if math.isfinite(b)),
                       default=1.0)
            found = self._rates[key] = Rate(at, min(self.band[0], -span),
                                            max(self.band[1], span))
        return found

    def estimate(self, values: Values, accel: Callable[[Values], float],
                 deadline: float = math.inf, context: object = None) -> Estimate | None:
        """The way into the box and band with the fewest control steps (then the least time)
        that takes at most ``deadline`` [s]: time ``inf`` if there is none; None if the motion
        does not run (no level moves the speed: the estimate does not apply).

        ``accel(values)`` is the rate of x's rate at ``values`` (the control set to a level),
        ``context`` what else it depends on (hashable: the running processes).
        The control goes to an accelerating level and a braking one, in either order; a
        step is one change of the control by its step."""
        m = self.motion
        u = m.control
        w0 = m.k * values[m.y]
        rates = [self.rate(values, accel, i, context) for i in range(len(u.levels))]
        acc = [r.at(w0) for r in rates]
        if not any(acc) and all(r.const is not None for r in rates):
            return None
        limit = min(deadline, HORIZON)
        c = u.index(values[u.fluent])

        def time(i: int, j: int) -> Profile:
            return box_profile(values[m.x], w0, self.box, self.band, rates[i], rates[j],
                               self.cap)

        n = len(acc)
        if time(max(range(n), key=acc.__getitem__), min(range(n), key=acc.__getitem__)).time \
                > limit:
            return Estimate(0, math.inf, c)
        best = Estimate(0, math.inf, c)
        for least, i, j in _pairs(n, c):
            if least > best.steps and best.time < math.inf:
                break
            prof = time(i, j)
            if prof.time > limit:
                continue
            first, then = (i, j) if prof.up else (j, i)
            steps = abs(first - c) + abs(then - first)
            if best.time == math.inf or (steps, prof.time) < (best.steps, best.time):
                hold = self._hold(values, w0, rates[i], rates[j], prof) \
                    if first == c and steps else 0.0
                best = Estimate(steps, prof.time, first, hold)
        return best

    def _hold(self, values: Values, w0: float, up: Rate, down: Rate, fastest: Profile) -> float:
        """How long the controls may stay as they are: the first phase of the profile that
        ends in the middle of the box, at rest in the band, and keeps ``CAP_MARGIN`` inside
        the speed caps (the fastest profile ends on the box's edge and touches the caps,
        where a rounding of the switch misses the box or fires the event), if it exists."""
        (lo, hi), (yl, yh) = self.box, self.band
        if not (math.isfinite(lo) and math.isfinite(hi)):
            return fastest.first
        mid, rest = 0.5 * (lo + hi), min(max(0.0, yl), yh)
        cap = tuple(c - CAP_MARGIN * c if math.isfinite(c) else c for c in self.cap)
        centred = box_profile(values[self.motion.x], w0, (mid, mid), (rest, rest), up, down,
                              (cap[0], cap[1]))
        return centred.first if centred.up == fastest.up and centred.time < math.inf \
            else fastest.first


@dataclass(frozen=True)
class SpeedLimit:
    """A bound on a speed fluent: from a global constraint (``lost`` empty), or from an event
    beyond it that deletes the facts ``lost`` for good (it binds conjunctions needing one)."""

    fluent: int
    lo: float
    hi: float
    lost: frozenset[int] = frozenset()


def speed_limits(task: Task, speeds: set[int]) -> list[SpeedLimit]:
    """The bounds on ``speeds`` (fluents) that the global constraints and the events set."""
    added = {f for a in (*task.actions, *task.events) for f in a.effect.add}
    out: list[SpeedLimit] = []
    for inv in task.invariants:
        for c in conjuncts(inv):
            y = _single_fluent(c) if isinstance(c, Comparison) else None
            if y in speeds:
                assert y is not None and isinstance(c, Comparison)
                out.append(SpeedLimit(y, *bounds_of([c], y)))
    for e in task.events:
        parts = conjuncts(e.precondition)
        comps = [c for c in parts if isinstance(c, Comparison)]
        if len(comps) != 1 or not all(isinstance(c, (Atom, Comparison)) for c in parts):
            continue
        y = _single_fluent(comps[0])
        b = bound_of(comps[0], y) if y in speeds else None
        lost = frozenset(f for f in e.effect.delete if f not in added)
        if y is None or b is None or not lost:
            continue
        # the event fires beyond the bound: a plan that needs a lost fact stays this side
        out.append(SpeedLimit(y, -math.inf, b[1], lost) if b[0] == "lo" else
                   SpeedLimit(y, b[1], math.inf, lost))
    return out


def motion_goals(conjunction: Sequence[Condition], cond_index: Callable[[Comparison], int],
                 motions: dict[int, Motion], limits: Sequence[SpeedLimit]) -> list[MotionGoal]:
    """The motion goals of one conjunction: its comparisons on a motion's position alone and
    on its speed alone (both must be there, the speed band bounded). ``cond_index`` maps a
    comparison to the relaxation's condition index."""
    by_fluent: dict[int, list[Comparison]] = {}
    facts = {c.fact for c in conjunction if isinstance(c, Atom)}
    for c in conjunction:
        if isinstance(c, Comparison):
            f = _single_fluent(c)
            if f is not None:
                by_fluent.setdefault(f, []).append(c)
    out = []
    for x, m in motions.items():
        xs, ys = by_fluent.get(x, []), by_fluent.get(m.y, [])
        if not xs or not ys:
            continue
        yl, yh = bounds_of(ys, m.y)
        cl, ch = -math.inf, math.inf
        for lim in limits:
            if lim.fluent == m.y and (not lim.lost or lim.lost & facts):
                cl, ch = max(cl, lim.lo), min(ch, lim.hi)
        band = (m.k * yl, m.k * yh) if m.k > 0 else (m.k * yh, m.k * yl)
        cap = (m.k * cl, m.k * ch) if m.k > 0 else (m.k * ch, m.k * cl)
        if not all(math.isfinite(b) for b in band):
            continue
        conds = tuple(sorted({cond_index(c) for c in (*xs, *ys)}))
        out.append(MotionGoal(m, conds, bounds_of(xs, x), band, cap))
    return out


__all__ = ["Control", "Estimate", "Motion", "MotionGoal", "SpeedLimit", "find_controls",
           "find_motions", "motion_goals", "speed_limits"]
