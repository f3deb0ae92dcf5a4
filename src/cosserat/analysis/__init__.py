"""Analysis of profiles: shear-layer thickness, wall slip and spin, thickness laws."""

from .laws import asymptotic_thickness, thickness_limit
from .thickness import (
    DEFAULT_F,
    ThicknessCurve,
    shear_layer_thickness,
    thickness_curve,
    wall_omega,
    wall_slip,
)

__all__ = [
    "DEFAULT_F",
    "ThicknessCurve",
    "asymptotic_thickness",
    "shear_layer_thickness",
    "thickness_curve",
    "thickness_limit",
    "wall_omega",
    "wall_slip",
]
