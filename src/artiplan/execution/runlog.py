"""The run log: a JSON record of one closed-loop run, its JSON Schema and a tiny validator.

Times are simulated seconds of the world unless a key ends in ``_wall_s`` (wall clock); angles
and errors in degrees. Configurations are ``{"theta": [...], "gamma": [...]}``, L1 first.
"""

from __future__ import annotations

import json
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from artiplan.model import Configuration

SCHEMA_RUN_LOG = "artiplan.run-log/1"

_NUM: dict[str, Any] = {"type": "number"}
_CONF: dict[str, Any] = {
    "type": "object",
    "required": ["theta", "gamma"],
    "properties": {"theta": {"type": "array", "items": _NUM},
                   "gamma": {"type": "array", "items": _NUM}},
}
_PLAN = {
    "type": "object",
    "required": ["index", "start_time", "reason", "status", "latency_wall_s", "actions", "text"],
    "properties": {
        "index": {"type": "integer", "minimum": 0},
        "start_time": _NUM,
        "reason": {"type": "string"},
        "status": {"type": "string"},
        "latency_wall_s": {"type": "number", "minimum": 0},
        "makespan": {"type": ["number", "null"]},
        "text": {"type": "string"},
        "actions": {"type": "array", "items": {
            "type": "object", "required": ["time", "action"],
            "properties": {"time": _NUM, "action": {"type": "string"}}}},
    },
}
_SAMPLE = {
    "type": "object",
    "required": ["time", "plan", "kind", "predicted", "perceived", "errors"],
    "properties": {
        "time": _NUM,
        "plan": {"type": "integer"},
        "kind": {"enum": ["monitor", "happening", "final", "intervention"]},
        "predicted": _CONF,
        "perceived": _CONF,
        "errors": {"type": "array", "items": _NUM},
        "aligned_ahead": {"type": "array", "items": {"type": "string"}},
    },
}
_REPLAN = {
    "type": "object",
    "required": ["time", "reason", "latency_wall_s"],
    "properties": {"time": _NUM, "reason": {"type": "string"},
                   "latency_wall_s": {"type": "number", "minimum": 0}},
}
#: JSON Schema (draft 2020-12 subset) of a run log.
RUN_LOG_SCHEMA: dict[str, Any] = {
    "$schema": "https://json-schema.org/draft/2020-12/schema",
    "$id": "https://artiplan.invalid/schemas/run-log-1.json",
    "title": "artiplan closed-loop run log",
    "type": "object",
    "required": ["schema", "settings", "object", "initial", "target", "goal_links", "plans",
                 "samples", "happenings", "replans", "interventions", "final", "success"],
    "properties": {
        "schema": {"const": SCHEMA_RUN_LOG},
        "settings": {"type": "object"},
        "object": {"type": "object"},
        "initial": _CONF,
        "target": _CONF,
        "goal_links": {"type": "array", "items": {"type": "string"}},
        "plans": {"type": "array", "items": _PLAN},
        "samples": {"type": "array", "items": _SAMPLE},
        "happenings": {"type": "array", "items": {
            "type": "object", "required": ["time", "plan", "action", "ok", "did"],
            "properties": {"time": _NUM, "plan": {"type": "integer"},
                           "action": {"type": "string"}, "ok": {"type": "boolean"},
                           "did": {"type": "string"}}}},
        "replans": {"type": "array", "items": _REPLAN},
        "refusals": {"type": "array", "items": _REPLAN},
        "carry_replans": {"type": "array", "items": _REPLAN},
        "interventions": {"type": "array", "items": {
            "type": "object", "required": ["time", "link", "plane", "delta_deg"]}},
        "final": {"type": "object", "required": ["time", "perceived", "goal_errors", "success"],
                  "properties": {"time": _NUM, "perceived": _CONF,
                                 "goal_errors": {"type": "object"},
                                 "success": {"type": "boolean"}}},
        "success": {"type": "boolean"},
        "wall_s": {"type": "number", "minimum": 0},
        "collisions": {"type": "array", "items": {
            "type": "object", "required": ["geoms", "start", "end", "depth_m"],
            "properties": {"geoms": {"type": "array", "items": {"type": "string"}},
                           "start": _NUM, "end": _NUM,
                           "depth_m": {"type": "number", "minimum": 0}, "deepest": _NUM}}},
        "motions": {"type": "array", "items": {
            "type": "object", "required": ["wall_s", "dims", "ok"],
            "properties": {"wall_s": {"type": "number", "minimum": 0},
                           "dims": {"type": "integer"}, "ok": {"type": "boolean"}}}},
    },
}


def conf_dict(conf: Configuration) -> dict[str, list[float]]:
    """A configuration as the log holds it (rounded to 1e-4 deg)."""
    return {"theta": [round(v, 4) for v in conf.theta],
            "gamma": [round(v, 4) for v in conf.gamma]}


def conf_from(d: dict[str, list[float]]) -> Configuration:
    """Inverse of :func:`conf_dict`."""
    return Configuration(tuple(d["theta"]), tuple(d["gamma"]))


@dataclass
class RunLog:
    """Everything one run records (see :data:`RUN_LOG_SCHEMA`)."""

    settings: dict[str, Any]
    object: dict[str, Any]
    initial: dict[str, list[float]]
    target: dict[str, list[float]]
    goal_links: list[str]
    plans: list[dict[str, Any]] = field(default_factory=list)
    samples: list[dict[str, Any]] = field(default_factory=list)
    happenings: list[dict[str, Any]] = field(default_factory=list)
    replans: list[dict[str, Any]] = field(default_factory=list)
    interventions: list[dict[str, Any]] = field(default_factory=list)
    final: dict[str, Any] = field(default_factory=dict)
    success: bool = False
    wall_s: float = 0.0
    #: Arm collisions in the physics (Baxter): geoms, start/end/deepest time [s], depth [m].
    collisions: list[dict[str, Any]] = field(default_factory=list)
    #: Planned arm motions (Baxter): wall time [s], dimension (7/14), waypoints, success.
    motions: list[dict[str, Any]] = field(default_factory=list)
    #: Plans made again because the world refused one of the last plan's rotations (not
    #: re-plans, up to LoopConfig.free_refusals a run): time, reason, latency.
    refusals: list[dict[str, Any]] = field(default_factory=list)
    #: Plans made again because a link a vertical turn carried was off the prediction when
    #: the turn stopped (not re-plans, up to LoopConfig.free_carry_replans a run).
    carry_replans: list[dict[str, Any]] = field(default_factory=list)

    def to_dict(self) -> dict[str, Any]:
        return {"schema": SCHEMA_RUN_LOG, **self.__dict__}

    def save(self, path: str | Path) -> Path:
        """Write the log as indented JSON."""
        p = Path(path)
        p.write_text(json.dumps(self.to_dict(), indent=1) + "\n")
        return p


_TYPES: dict[str, tuple[type, ...]] = {
    "object": (dict,), "array": (list,), "string": (str,), "boolean": (bool,),
    "integer": (int,), "number": (int, float), "null": (type(None),),
}


def _type_ok(value: Any, name: str) -> bool:
    if name in ("integer", "number") and isinstance(value, bool):
        return False
    return isinstance(value, _TYPES[name])


def schema_errors(value: Any, schema: dict[str, Any], path: str = "$") -> list[str]:
    """Errors of ``value`` against ``schema`` (the subset used here: type, required,
    properties, items, enum, const, minimum); an empty list when it validates."""
    errors: list[str] = []
    types = schema.get("type")
    if types is not None:
        names = types if isinstance(types, list) else [types]
        if not any(_type_ok(value, t) for t in names):
            return [f"{path}: expected {'/'.join(names)}, found {type(value).__name__}"]
    if "const" in schema and value != schema["const"]:
        errors.append(f"{path}: expected {schema['const']!r}, found {value!r}")
    if "enum" in schema and value not in schema["enum"]:
        errors.append(f"{path}: expected one of {schema['enum']}, found {value!r}")
    if "minimum" in schema and isinstance(value, (int, float)) and value < schema["minimum"]:
        errors.append(f"{path}: {value} < minimum {schema['minimum']}")
    if isinstance(value, dict):
        errors += [f"{path}: missing {k!r}" for k in schema.get("required", []) if k not in value]
        for k, sub in schema.get("properties", {}).items():
            if k in value:
                errors += schema_errors(value[k], sub, f"{path}.{k}")
    if isinstance(value, list) and "items" in schema:
        for i, item in enumerate(value):
            errors += schema_errors(item, schema["items"], f"{path}[{i}]")
    return errors


def write_schema(path: str | Path) -> Path:
    """Write :data:`RUN_LOG_SCHEMA` as a JSON Schema file."""
    p = Path(path)
    p.write_text(json.dumps(RUN_LOG_SCHEMA, indent=1) + "\n")
    return p
