"""Results: the one profile type of every route, its diagnostics and its wall quantities."""

from .profile import Diagnostics, Evaluator, Fields, Profile
from .wall import shear_layer_thickness, wall_omega, wall_slip

__all__ = [
    "Diagnostics",
    "Evaluator",
    "Fields",
    "Profile",
    "shear_layer_thickness",
    "wall_omega",
    "wall_slip",
]
