"""The articulated object: links, configurations, kinematics (imports nothing below it)."""

from artiplan.model.angles import wrap_deg
from artiplan.model.configuration import Configuration, load_configuration, random_configuration
from artiplan.model.kinematics import (
    direction,
    direction_error,
    forward_kinematics,
)
from artiplan.model.obj import HORIZONTAL_PLANE, PLANES, VERTICAL_PLANE, ArticulatedObject

__all__ = [
    "HORIZONTAL_PLANE",
    "PLANES",
    "VERTICAL_PLANE",
    "ArticulatedObject",
    "Configuration",
    "direction",
    "direction_error",
    "forward_kinematics",
    "load_configuration",
    "random_configuration",
    "wrap_deg",
]
