"""Problems: one module per geometry, each stating its equations and boundary conditions;
:func:`build_problem` makes one from named parameters."""

from __future__ import annotations

from typing import TypeAlias

from .build import build_problem
from .channel import Channel, ChannelCase
from .couette import CouetteFlow
from .plane import PlaneShear, PlaneShearCase

Problem: TypeAlias = PlaneShear | CouetteFlow

__all__ = [
    "Channel",
    "ChannelCase",
    "CouetteFlow",
    "PlaneShear",
    "PlaneShearCase",
    "Problem",
    "build_problem",
]
