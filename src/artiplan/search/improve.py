"""Anytime improvement of a first plan: bounded re-searches that keep only better plans.

The first search stops at its first valid plan. This phase searches again, with other heuristic
weightings (time counts more), and prunes every node that cannot beat the best plan so far: a
node at or past the best makespan [s] that has no fewer actions. A goal found this way is kept
if it is better (lower makespan, then fewer actions); the search goes on with the tighter bound.
Budgets count expansions, not seconds, so the same input gives the same plan on every machine;
the time limit only cuts the phase short (the best plan so far is kept). The best candidate the
validator accepts is returned; if none is accepted, the first plan stays.
"""

from __future__ import annotations

from collections.abc import Callable

from artiplan.errors import InvalidPlanError
from artiplan.records import dataclass
from artiplan.search.engine import (
    Node,
    Search,
    SearchConfig,
    SearchOutcome,
    Successors,
    initial_node,
    last_event_after,
)
from artiplan.search.heuristic import Heuristic, HeuristicConfig, RateHeuristic
from artiplan.search.limits import LimitReached, Limits
from artiplan.search.ops import WAIT_GOAL
from artiplan.semantics.compiled import CompiledTask
from artiplan.semantics.kernel import EventLog, Kernel
from artiplan.semantics.plan import Plan
from artiplan.semantics.results import PlanStats
from artiplan.semantics.validator import ValidationReport

#: Makespans closer than this [s] count as equal (VAL's tolerance is 0.001 s).
TIE = 1e-6


@dataclass(frozen=True)
class ImproveConfig:
    """Budget and weightings of the improvement phase.

    Attributes:
        factor: Expansion budget as a multiple of the first search's expansions.
        minimum: Expansion budget at least this (first searches often need only a few).
        maximum: Expansion budget at most this.
        weights: (time weight [actions/s], damage cost) of the successive re-searches.
        time_share: The phase stops once this share of the time limit has passed.
        gain: A plan with more actions must shorten the makespan by at least this share (a few
            extra actions for milliseconds is not a better plan).
    """

    factor: float = 3.0
    minimum: int = 30
    maximum: int = 3000
    weights: tuple[tuple[float, float], ...] = ((1.0, 2.0), (3.0, 2.0))
    time_share: float = 0.9
    gain: float = 0.05


def better(mk: float, n: int, best_mk: float, best_n: int, gain: float = 0.05) -> bool:
    """Lower makespan [s] first, then fewer actions; more actions only for a ``gain`` share."""
    if n > best_n:
        return mk < best_mk * (1.0 - gain) - TIE
    return mk < best_mk - TIE or (mk <= best_mk + TIE and n < best_n)


@dataclass
class _Best:
    makespan: float
    n_actions: int


def improve(
    ct: CompiledTask, kernel: Kernel, config: SearchConfig, limits: Limits, first: Plan,
    stats: PlanStats, extract: Callable[[SearchOutcome], Plan],
    validate: Callable[[Plan], ValidationReport | None], settings: ImproveConfig = ImproveConfig(),
    heuristic: Callable[..., Heuristic] = RateHeuristic, expanded: int | None = None,
    successors: Successors | None = None,
) -> tuple[Plan, ValidationReport | None]:
    """Search for a plan better than ``first``; returns it with its validator report (None
    when ``first`` is kept: the caller validated it already). The ``improve_*`` statistics
    go to ``stats``. The budget is ``settings.factor`` times ``expanded``, the expansions of
    the search that found ``first`` (default: ``stats.expanded``, every search so far): the
    phase searches with that search's heuristic, and attempts that failed before it (another
    heuristic, a coarser grid) say nothing about how hard a better plan is to find.

    ``validate(plan)`` returns a report, or None when validation is off (candidates are then
    trusted, as the first plan was). ``successors``: the memo of the searches that found
    ``first``, if they ran with ``config`` and the same heuristic groups (else a new one).
    """
    done = stats.expanded if expanded is None else expanded
    budget = int(min(settings.maximum, max(settings.minimum, settings.factor * done)))
    best = _Best(first.makespan, len(first.actions))
    candidates: list[Plan] = []
    stats.improve_budget, stats.improve_expanded = budget, 0

    def prune(node: Node) -> bool:
        """No descendant can be better: times only grow, action counts too."""
        if node.n_actions > best.n_actions:
            return node.time >= best.makespan * (1.0 - settings.gain) - TIE
        return node.time >= best.makespan - TIE and node.n_actions >= best.n_actions

    def accept(outcome: SearchOutcome) -> bool:
        found = extract(outcome)
        if better(found.makespan, len(found.actions), best.makespan, best.n_actions,
                  settings.gain):
            best.makespan, best.n_actions = found.makespan, len(found.actions)
            candidates.append(found)
        return False  # search on, under the tighter bound

    def check() -> None:
        limits.check()
        if limits.time_limit is not None and \
                limits.elapsed() > settings.time_share * limits.time_limit:
            raise LimitReached("time", "improvement stopped by the time limit")

    # the searches below start from the same initial node with the same settings: a path one
    # of them computed, the others take (pruning and heuristics only choose among them)
    memo: Successors = {} if successors is None else successors
    try:
        probe = Search(ct, kernel, heuristic(ct, HeuristicConfig(), kernel.active), config,
                       check, accept, prune, successors=memo)
        try:
            stats.improve_probes = _probe(probe, lambda: best.makespan)
        finally:
            stats.reused += int(probe.stats["reused"])
        for weight, damage in settings.weights:
            left = budget - stats.improve_expanded
            if left <= 0:
                break
            heur = heuristic(ct, HeuristicConfig(time_weight=weight, damage_cost=damage),
                             kernel.active)
            search = Search(ct, kernel, heur, config, check, accept, prune, successors=memo)
            try:
                search.run(initial_node(ct, kernel), left)
            finally:
                stats.improve_expanded += int(search.stats["expanded"])
                stats.reused += int(search.stats["reused"])
    except (LimitReached, MemoryError, InvalidPlanError):
        stats.improve_cut = True
    stats.improve_candidates = len(candidates)
    for found in reversed(candidates):  # best first: usually one validation
        report = validate(found)
        if report is None or report.valid:
            return found, report
        stats.improve_rejected.append(report.reason)
    return first, None


def _probe(search: Search, horizon: Callable[[], float]) -> int:
    """One action at time 0, then wait until the goal holds: plans that let one motion run.

    The greedy search's order hides these when its heuristic prefers another joint (a start
    nearer the base moves the links after it too). Waits stop at ``horizon()`` [s] (the best
    makespan so far). Returns the number of probes.
    """
    ct, probes = search.ct, 0
    root = initial_node(ct, search.kernel)
    search.nodes.append(root)
    for act in ct.actions:
        if act.noop or root.facts & act.forb or act.req & ~root.facts:
            continue
        search.check_limits()
        probes += 1
        child = search.successor(root, 0, search.applies[act.index])
        if child is None or search.prune is not None and search.prune(child):
            continue
        search.nodes.append(child)
        log: EventLog = []
        try:
            res = search.waits.until(child.time, child.facts, child.values, ct.goal,
                                     ct.goal_comps, log, child.active,
                                     search.config.max_wait_steps, search.goal_margin(child),
                                     horizon=horizon())
        except InvalidPlanError:
            continue
        if res is None:
            continue
        t, facts, values, active = res
        search.nodes.append(Node(t, facts, values, child.ready, len(search.nodes) - 1, WAIT_GOAL,
                                 log, False, active, n_actions=child.n_actions,
                                 last_event=last_event_after(child, log, search.ct.rearms),
                                 n_events=child.n_events + len(log)))
        closing = search.closing(search.nodes[-1])
        if closing is not None:
            search.accept(SearchOutcome(len(search.nodes) - 1, search.nodes,
                                        None if closing is True else closing,  # type: ignore[arg-type]
                                        search.stats))
    return probes
