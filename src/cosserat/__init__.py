"""cosserat: the frictional Cosserat model of slow granular shear flow.

Mohan, Kesava Rao & Nott, "A frictional Cosserat model for the slow shearing of granular
materials". Give a material, walls and a cell; get velocity, spin, stress, stress-asymmetry and
couple-stress profiles, the shear-layer thickness and the wall slip::

    >>> from cosserat import Material, Wall, PlaneShear, solve, shear_layer_thickness
    >>> problem = PlaneShear(material=Material(phi=28.5), upper=Wall(delta=20.0), eps=1e-3)
    >>> profile = solve(problem)                      # method="numerical" by default
    >>> round(shear_layer_thickness(profile), 2)
    17.67
"""

from . import _jit_cache  # noqa: F401  (before any compiled function is defined)
from ._version import __version__
from .analysis import shear_layer_thickness, wall_omega, wall_slip
from .config import DEFAULT_F
from .errors import (
    ConvergenceError,
    CosseratError,
    MethodNotAvailableError,
    NoSolutionError,
    ParameterError,
)
from .model import Channel, CouetteFlow, PlaneShear, PlaneShearCase, Problem
from .model.parameters import FULLY_ROUGH, Material, Wall
from .results.profile import Diagnostics, Fields, Profile
from .routes import METHODS, solve

__all__ = [
    "DEFAULT_F",
    "FULLY_ROUGH",
    "METHODS",
    "Channel",
    "ConvergenceError",
    "CosseratError",
    "CouetteFlow",
    "Diagnostics",
    "Fields",
    "Material",
    "MethodNotAvailableError",
    "NoSolutionError",
    "ParameterError",
    "PlaneShear",
    "PlaneShearCase",
    "Problem",
    "Profile",
    "Wall",
    "__version__",
    "shear_layer_thickness",
    "solve",
    "wall_omega",
    "wall_slip",
]
