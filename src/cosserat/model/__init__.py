"""The model: cells (:mod:`.cells`), rheologies (:mod:`.rheologies`) and the problem they make
together (:class:`Problem`), every parameter declared once (:mod:`.declare`); problems from
names by :func:`make_problem`."""

from __future__ import annotations

from .aliases import (
    Channel,
    CouetteFlow,
    MuIChannel,
    MuICouetteFlow,
    MuIPlaneShear,
    NGFChannel,
    NGFCouetteFlow,
    NGFPlaneShear,
    PlaneShear,
)
from .build import make_problem, problem_parameters
from .cells import CELLS, Cell, Couette, Plane, VerticalChannel
from .parameters import FULLY_ROUGH, Material, Wall
from .problem import Problem
from .rheologies import NGF, RHEOLOGIES, Cosserat, Equations, MuI, Rheology
from .rheologies.cosserat.channel import ChannelCase
from .rheologies.cosserat.plane import PlaneShearCase

__all__ = [
    "CELLS",
    "FULLY_ROUGH",
    "NGF",
    "RHEOLOGIES",
    "Cell",
    "Channel",
    "ChannelCase",
    "Cosserat",
    "Couette",
    "CouetteFlow",
    "Equations",
    "Material",
    "MuI",
    "MuIChannel",
    "MuICouetteFlow",
    "MuIPlaneShear",
    "NGFChannel",
    "NGFCouetteFlow",
    "NGFPlaneShear",
    "Plane",
    "PlaneShear",
    "PlaneShearCase",
    "Problem",
    "Rheology",
    "VerticalChannel",
    "Wall",
    "make_problem",
    "problem_parameters",
]
