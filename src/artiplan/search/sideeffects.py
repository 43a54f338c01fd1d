"""Side effects in the heuristic: what else moves when a process is used to reach a goal.

Choosing a process to reach one goal fluent also runs its companions (a rotation carries the
links tip-ward; a grasp releases or stops gravity): reaching the goal that way may undo goals
already reached. A mixin of :class:`artiplan.search.heuristic.RateHeuristic`.
"""

from __future__ import annotations

from collections.abc import Callable

from artiplan.search.intervals import Jump, contains, displace
from artiplan.semantics.compiled import CompiledTask
from artiplan.semantics.walks import Linear

Moves = tuple[tuple[int, tuple[Linear, ...]], ...]


class SideEffects:
    """Goal fluents moved by running or switched-on processes, and the goals that undoes."""

    ct: CompiledTask
    groups: list  # GoalGroup (defined with the heuristic)
    jumps: dict[int, tuple[Jump, ...]]
    pre_lits: list[tuple[int, ...]]
    n_actions: int
    relaxed_events: list[int]
    proc_lits: list[tuple[int, ...]]
    active_fn: Callable[[int, tuple[float, ...]], tuple[int, ...]] | None
    damage_cost: float
    _after: dict[tuple[int, ...], Moves]
    _state: tuple[int, tuple[float, ...], tuple[list[float], list[int]] | None]
    _moves_cache: dict[tuple[int, ...], Moves]
    _active_set: set[int]
    _active_moves: Moves

    def _side_effects(self) -> None:
        """Processes switched on together (same trigger fact) and the goal fluents they move."""
        self.goal_of_fluent = {g.fluent: gi for gi, g in enumerate(self.groups)
                               if g.fluent is not None}
        self.proc_key: list[int] = []
        moves: dict[int, dict[int, list[Linear]]] = {}
        for p in self.ct.processes:
            key = (p.req & -p.req).bit_length() - 1 if p.req else -1 - p.index
            self.proc_key.append(key)
            for fluent, _, lin in p.rates:
                if lin is not None and fluent in self.goal_of_fluent:
                    moves.setdefault(key, {}).setdefault(fluent, []).append(lin)
        self.key_moves: dict[int, Moves] = {
            k: tuple((f, tuple(ls)) for f, ls in sorted(v.items())) for k, v in moves.items()}
        # how many goal fluents the processes an action switches on move (its "reach"):
        # among helpful actions, the one that moves most goals is tried first (base of a chain)
        self.reach: list[int] = []
        for a in self.ct.task.actions:
            fluents: set[int] = set()
            for fact in a.effect.add:
                fluents.update(f for f, _ in self.key_moves.get(fact, ()))
            self.reach.append(len(fluents))

    def _chain(
        self, lits: tuple[int, ...], costs: tuple[list[float], list[int]]
    ) -> tuple[int, ...]:
        """The relaxed plan's actions that make ``lits`` true, supporters first."""
        cost, supp = costs
        out: list[int] = []

        def visit(ls: tuple[int, ...], depth: int) -> None:
            for lit in ls:
                a = supp[lit]
                if cost[lit] == 0.0 or a < 0 or a in out or depth > 4:
                    continue
                visit(self.pre_lits[a], depth + 1)
                out.append(a)

        visit(lits, 0)
        return tuple(out)

    def _after_moves(self, chain: tuple[int, ...]) -> Moves:
        """Goal-fluent moves of the processes running after ``chain`` is applied now."""
        found = self._after.get(chain)
        if found is None:
            facts, values, _ = self._state
            for a in chain:
                op = (self.ct.actions[a] if a < self.n_actions
                      else self.ct.events[self.relaxed_events[a - self.n_actions]])
                facts, values = op.effect(facts, values)
            assert self.active_fn is not None
            found = self._after[chain] = self._moves_of(self.active_fn(facts, values))
        return found

    def _moves_of(self, active: tuple[int, ...]) -> Moves:
        """Goal fluents the running processes move, with their rates (cached per set)."""
        found = self._moves_cache.get(active)
        if found is None:
            moves: dict[int, list[Linear]] = {}
            for p in active:
                for fluent, _, lin in self.ct.processes[p].rates:
                    if lin is not None and fluent in self.goal_of_fluent:
                        moves.setdefault(fluent, []).append(lin)
            found = tuple((f, tuple(ls)) for f, ls in sorted(moves.items()))
            if len(self._moves_cache) < 50_000:
                self._moves_cache[active] = found
        return found

    def _damage(
        self, p: int, fluent: int, seconds: float, values: tuple[float, ...],
        satisfied: list[bool],
    ) -> float:
        """Goals already reached that running ``p``'s group for ``seconds`` would undo.

        The group of a running process is everything running (waiting runs it all); that of a
        process to switch on, the processes switched on with it (same trigger fact).
        """
        damage = 0.0
        if p in self._active_set:
            moves = self._active_moves
        elif self.active_fn is not None and self._state[2] is not None:
            moves = self._after_moves(self._chain(self.proc_lits[p], self._state[2]))
        else:
            moves = self.key_moves.get(self.proc_key[p], ())
        for f2, lins in moves:
            gi = self.goal_of_fluent[f2]
            if f2 == fluent or not satisfied[gi]:
                continue
            r = sum(c + sum(a * values[j] for j, a in cs.items()) for cs, c in lins)
            if r == 0.0:
                continue
            x = displace(values[f2], 1.0 if r > 0 else -1.0, abs(r) * seconds,
                         self.jumps.get(f2, ()))
            if not contains(self.groups[gi].target, x):
                damage += self.damage_cost
        return damage

