"""cosserat: the frictional Cosserat model of slow granular shear flow, beside local mu(I) and
nonlocal granular fluidity.

Mohan, Kesava Rao & Nott, "A frictional Cosserat model for the slow shearing of granular
materials". A problem is a cell (the experiment: :class:`Plane`, :class:`Couette`,
:class:`VerticalChannel`) and a rheology (the law: :class:`Cosserat`, :class:`MuI`,
:class:`NGF`); solve it for velocity, spin, stress, stress-asymmetry and couple-stress profiles,
the shear-layer thickness and the wall slip::

    >>> from cosserat import Cosserat, Material, Plane, Problem, Wall, solve
    >>> from cosserat import shear_layer_thickness
    >>> problem = Problem(Plane(eps=1e-3), Cosserat(material=Material(phi=28.5), wall=Wall(20.0)))
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
from .model import (
    NGF,
    Channel,
    ChannelCase,
    Cosserat,
    Couette,
    CouetteFlow,
    MuI,
    Plane,
    PlaneShear,
    PlaneShearCase,
    Problem,
    VerticalChannel,
    make_problem,
    problem_parameters,
)
from .model.parameters import FULLY_ROUGH, Material, Wall
from .results.profile import Diagnostics, Fields, Profile
from .routes import METHODS, solve

__all__ = [
    "DEFAULT_F",
    "FULLY_ROUGH",
    "METHODS",
    "NGF",
    "Channel",
    "ChannelCase",
    "ConvergenceError",
    "Cosserat",
    "CosseratError",
    "Couette",
    "CouetteFlow",
    "Diagnostics",
    "Fields",
    "Material",
    "MethodNotAvailableError",
    "MuI",
    "NoSolutionError",
    "ParameterError",
    "Plane",
    "PlaneShear",
    "PlaneShearCase",
    "Problem",
    "Profile",
    "VerticalChannel",
    "Wall",
    "__version__",
    "make_problem",
    "problem_parameters",
    "shear_layer_thickness",
    "solve",
    "wall_omega",
    "wall_slip",
]
