"""The type hierarchy of a domain and the typed objects of a problem (names lower-cased)."""

from __future__ import annotations

from artiplan.errors import InputError
from artiplan.pddl import grammar as g
from artiplan.pddl import syntax as s
from artiplan.records import dataclass


@dataclass(frozen=True)
class TypeHierarchy:
    """``ancestors[t]``: ``t``, its super-types and ``object``, all lower-case."""

    ancestors: dict[str, frozenset[str]]

    @classmethod
    def of(cls, domain: s.Domain) -> TypeHierarchy:
        """The hierarchy declared by ``domain`` (undeclared parents become types)."""
        parents: dict[str, set[str]] = {g.ROOT_TYPE: set()}
        for decl in domain.types:
            parents.setdefault(decl.name.lower(), set()).update(x.lower() for x in decl.types)
        for decl in domain.types:
            for p in decl.types:
                # A parent never declared itself (`a - vehicle`) is declared implicitly.
                parents.setdefault(p.lower(), set())
        ancestors: dict[str, frozenset[str]] = {}
        for t in parents:
            seen, todo = {t, g.ROOT_TYPE}, [t]
            while todo:
                for p in parents.get(todo.pop(), ()):
                    if p not in seen:
                        seen.add(p)
                        todo.append(p)
            ancestors[t] = frozenset(seen)
        return cls(ancestors)

    def check(self, types: tuple[str, ...], at: s.TypedName | None = None) -> None:
        """Raise if a type in ``types`` is not declared."""
        for t in types:
            if t.lower() not in self.ancestors:
                loc = at.loc if at is not None else None
                raise InputError(f"undeclared type '{t}'", loc, expected="a type declared in "
                                 ":types", found=t)

    def compatible(self, have: tuple[str, ...], want: tuple[str, ...]) -> bool:
        """Could a value of type ``have`` (possibly ``either``) be of type ``want``?"""
        have_l = [h.lower() for h in have] or [g.ROOT_TYPE]
        want_l = [w.lower() for w in want] or [g.ROOT_TYPE]
        for h in have_l:
            for w in want_l:
                if w in self.ancestors.get(h, ()) or h in self.ancestors.get(w, ()):
                    return True
        return False

    def is_subtype(self, have: tuple[str, ...], want: tuple[str, ...]) -> bool:
        """Is every value of type ``have`` of type ``want``? (for objects, whose type is known)"""
        have_l = [h.lower() for h in have] or [g.ROOT_TYPE]
        want_l = {w.lower() for w in want} or {g.ROOT_TYPE}
        return any(want_l & self.ancestors.get(h, frozenset()) for h in have_l)


def objects_by_type(
    hierarchy: TypeHierarchy, objects: tuple[s.TypedName, ...]
) -> dict[str, tuple[str, ...]]:
    """Lower-case type -> lower-case object names of that type (sub-types included), in order."""
    out: dict[str, dict[str, None]] = {t: {} for t in hierarchy.ancestors}
    for o in objects:
        key = o.name.lower()
        types = [t.lower() for t in o.types] or [g.ROOT_TYPE]
        seen: set[str] = set()
        for t in types:
            seen |= hierarchy.ancestors.get(t, frozenset({t, g.ROOT_TYPE}))
        for t in seen:
            out.setdefault(t, {})[key] = None
    return {t: tuple(v) for t, v in out.items()}
