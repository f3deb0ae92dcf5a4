"""Analysis of profiles: shear-layer thickness, wall slip and spin, thickness laws."""

from ..config import DEFAULT_F
from ..results.wall import shear_layer_thickness, wall_omega, wall_slip
from ..routes.laws import asymptotic_thickness, thickness_limit
from .thickness import ThicknessCurve, thickness_curve

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
