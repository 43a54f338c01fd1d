"""The knowledge base: an OWL ontology (owlready2) of the object, what perception saw, the goal.

Classes: ``ArticulatedObject``, ``Link`` (``BaseLink``: the clamped L1), ``Joint``, ``Plane``,
``Fixture``, ``AngleObservation`` (a perceived angle of a link on a plane, with time stamp [s]
and uncertainty [deg]), ``TargetAngle`` and ``Goal``. ``connected`` links neighbours base ->
tip. ``affects`` is never asserted: two SWRL rules let the reasoner (HermiT, Java) infer it,
exactly as the conventions define it, (affects l_j l_m) for 2 <= j < m <= n:

* ``connected(?z, ?a), connected(?a, ?b) -> affects(?a, ?b)`` (a link with a base-ward
  neighbour, i.e. not the base, carries its tip-ward neighbour), and
* ``affects(?a, ?b), connected(?b, ?c) -> affects(?a, ?c)`` (and everything beyond it).

:meth:`KnowledgeBase.problem` queries the ontology (SPARQL) for the object, the latest
perceived configuration and the target and hands them to :func:`artiplan.encoding.problem_pddl`.
The ontology saves as RDF/XML that Protege opens.
"""

from __future__ import annotations

import types
from pathlib import Path
from typing import Any

import owlready2 as owl

from artiplan.encoding import EncodingOptions, problem_pddl
from artiplan.errors import ExternalToolError
from artiplan.model import PLANES, ArticulatedObject, Configuration
from artiplan.world.perception import Percept

IRI = "http://artiplan.example.org/world.owl"
RULES = (
    "connected(?z, ?a), connected(?a, ?b) -> affects(?a, ?b)",
    "affects(?a, ?b), connected(?b, ?c) -> affects(?a, ?c)",
)


def _declare(onto: Any) -> None:
    """The T-box (classes, properties, rules) in ``onto``."""
    with onto:
        thing = owl.Thing

        def cls(name: str, base: Any = thing) -> Any:
            return types.new_class(name, (base,))

        def prop(name: str, kind: Any, domain: Any, range_: Any, functional: bool) -> Any:
            bases = (kind, owl.FunctionalProperty) if functional else (kind,)
            p: Any = types.new_class(name, bases)
            p.domain, p.range = [domain], [range_]
            return p

        art, link, joint, plane = (cls(n) for n in ("ArticulatedObject", "Link", "Joint", "Plane"))
        base, fixture = cls("BaseLink", link), cls("Fixture")
        obs, target, goal = cls("AngleObservation"), cls("TargetAngle"), cls("Goal")
        obj_p, data_p = owl.ObjectProperty, owl.DataProperty
        prop("hasLink", obj_p, art, link, False)
        prop("connected", obj_p, link, link, False)
        prop("affects", obj_p, link, link, False)
        prop("clampedTo", obj_p, base, fixture, True)
        prop("joins", obj_p, joint, link, False)
        prop("linkIndex", data_p, link, int, True)
        prop("linkLength", data_p, art, float, True)
        prop("linkThickness", data_p, art, float, True)
        prop("linkMass", data_p, art, float, True)
        prop("ofLink", obj_p, obs, link, True)
        prop("onPlane", obj_p, obs, plane, True)
        prop("angleDeg", data_p, obs, float, True)
        prop("uncertaintyDeg", data_p, obs, float, True)
        prop("timeStamp", data_p, obs, float, True)
        prop("targetOf", obj_p, target, link, True)
        prop("targetPlane", obj_p, target, plane, True)
        prop("targetDeg", data_p, target, float, True)
        prop("hasTarget", obj_p, goal, target, False)
        prop("goalStyle", data_p, goal, str, True)
        prop("goalSeed", data_p, goal, int, True)
        for text in RULES:
            owl.Imp().set_as_rule(text)


class KnowledgeBase:
    """An OWL ontology in its own owlready2 world (instances do not share state)."""

    def __init__(self, obj: ArticulatedObject) -> None:
        self.obj = obj
        self.world = owl.World()
        self.onto = self.world.get_ontology(IRI)
        _declare(self.onto)
        self._n_obs = 0
        self._populate()

    def _populate(self) -> None:
        o, obj = self.onto, self.obj
        with o:
            self.object = o.ArticulatedObject("object")
            self.object.linkLength = float(obj.link_length)
            self.object.linkThickness = float(obj.thickness)
            self.object.linkMass = float(obj.mass)
            self.links = {}
            for i, name in enumerate(obj.links, start=1):
                ind = (o.BaseLink if i == 1 else o.Link)(name)
                ind.linkIndex = i
                self.object.hasLink.append(ind)
                self.links[name] = ind
            self.links[obj.base].clampedTo = o.Fixture("fixture")
            for a, b in obj.joints:
                self.links[a].connected.append(self.links[b])
                o.Joint(f"J_{a}_{b}").joins = [self.links[a], self.links[b]]
            self.planes = {p: o.Plane(p.replace("-", "_")) for p in PLANES}

    # -- updates ------------------------------------------------------------------------
    def record_percept(
        self, conf: Configuration, time: float, uncertainty_deg: tuple[float, ...] | None = None
    ) -> None:
        """Add one observation per link and plane (angles [deg], time [s], uncertainty [deg])."""
        sig = uncertainty_deg or (0.0,) * conf.n_links
        with self.onto:
            for i, name in enumerate(self.obj.links, start=1):
                for p in PLANES:
                    self._n_obs += 1
                    ob = self.onto.AngleObservation(f"obs{self._n_obs}")
                    ob.ofLink, ob.onPlane = self.links[name], self.planes[p]
                    ob.angleDeg = float(conf.angle(i, p))
                    ob.uncertaintyDeg = float(sig[i - 1])
                    ob.timeStamp = float(time)

    def record(self, percept: Percept) -> None:
        """Add what :meth:`artiplan.world.World.perceive` reported."""
        self.record_percept(percept.configuration, percept.time, percept.uncertainty_deg)

    def set_goal(self, target: Configuration, style: str = "threshold", seed: int = 0) -> None:
        """The target configuration and how the goal is built from it."""
        with self.onto:
            goal = self.onto.Goal("goal")
            goal.goalStyle, goal.goalSeed = style, int(seed)
            goal.hasTarget = []
            for i, name in enumerate(self.obj.links, start=1):
                for p in PLANES:
                    t = self.onto.TargetAngle(f"target_{name}_{p.replace('-', '_')}")
                    t.targetOf, t.targetPlane = self.links[name], self.planes[p]
                    t.targetDeg = float(target.angle(i, p))
                    goal.hasTarget.append(t)

    # -- reasoning and queries ----------------------------------------------------------
    def reason(self) -> None:
        """Run HermiT (Java) and keep the inferred facts (``affects``)."""
        try:
            with self.onto:
                owl.sync_reasoner_hermit(self.world, infer_property_values=True, debug=0)
        except (OSError, owl.OwlReadyJavaError) as exc:
            raise ExternalToolError(f"the OWL reasoner (HermiT, Java) failed: {exc}") from exc

    def affects(self) -> set[tuple[str, str]]:
        """The (l_j, l_m) pairs the ontology holds (after :meth:`reason`: the inferred ones)."""
        rows = self.world.sparql(f"PREFIX : <{IRI}#> SELECT ?a ?b WHERE {{ ?a :affects ?b . }}")
        return {(a.name, b.name) for a, b in rows}

    def connected(self) -> set[tuple[str, str]]:
        rows = self.world.sparql(f"PREFIX : <{IRI}#> SELECT ?a ?b WHERE {{ ?a :connected ?b . }}")
        return {(a.name, b.name) for a, b in rows}

    def latest_configuration(self, decimals: int | None = 1) -> tuple[Configuration, float]:
        """The newest observation of every angle (and its time [s]), rounded to ``decimals``."""
        rows = self.world.sparql(
            f"""PREFIX : <{IRI}#>
            SELECT ?i ?plane ?angle ?t WHERE {{
              ?o a :AngleObservation ; :ofLink ?l ; :onPlane ?plane ;
                 :angleDeg ?angle ; :timeStamp ?t .
              ?l :linkIndex ?i .
            }}"""
        )
        return self._configuration(rows, decimals, "observation")

    def target(self, decimals: int | None = None) -> tuple[Configuration, str, int]:
        """The target configuration, goal style and seed."""
        rows = self.world.sparql(
            f"""PREFIX : <{IRI}#>
            SELECT ?i ?plane ?angle WHERE {{
              ?g a :Goal ; :hasTarget ?x . ?x :targetOf ?l ; :targetPlane ?plane ;
                 :targetDeg ?angle . ?l :linkIndex ?i .
            }}"""
        )
        conf, _ = self._configuration([(*r, 0.0) for r in rows], decimals, "target")
        goal = self.onto.Goal("goal")
        return conf, str(goal.goalStyle), int(goal.goalSeed)

    def _configuration(
        self, rows: Any, decimals: int | None, what: str
    ) -> tuple[Configuration, float]:
        best: dict[tuple[int, str], tuple[float, float]] = {}
        names = {v.name: k for k, v in self.planes.items()}
        for i, plane, angle, t in rows:
            key = (int(i), names[plane.name])
            if key not in best or t >= best[key][1]:
                best[key] = (float(angle), float(t))
        n = self.obj.n_links
        missing = [k for k in ((i, p) for i in range(1, n + 1) for p in PLANES) if k not in best]
        if missing:
            raise ValueError(f"the ontology has no {what} of {missing[:3]}...")

        def val(i: int, p: str) -> float:
            a = best[(i, p)][0]
            return round(a, decimals) if decimals is not None else a

        conf = Configuration(
            tuple(val(i, PLANES[0]) for i in range(1, n + 1)),
            tuple(val(i, PLANES[1]) for i in range(1, n + 1)),
        )
        return conf, max(t for _, t in best.values())

    def problem(self, options: EncodingOptions, decimals: int | None = 1) -> str:
        """The PDDL+ problem from the ontology: latest percept -> initial state; the goal."""
        init, _ = self.latest_configuration(decimals)
        target, style, seed = self.target()
        inferred = self.affects()
        if inferred and inferred != set(self.obj.affects()):
            # The encoding derives affects from the chain; the reasoner must agree with it.
            raise ValueError(f"the ontology's affects {sorted(inferred)} disagree with the chain")
        return problem_pddl(self.obj, init, target, options, goal_style=style, seed=seed)

    def save(self, path: str | Path) -> None:
        """Write the ontology as RDF/XML (opens in Protege)."""
        self.onto.save(file=str(path), format="rdfxml")
