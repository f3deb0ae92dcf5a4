"""Problems: one module per geometry, each stating its equations and boundary conditions."""

from __future__ import annotations

from typing import TypeAlias

from .couette import CouetteFlow
from .plane import PlaneShear, PlaneShearCase

Problem: TypeAlias = PlaneShear | CouetteFlow

__all__ = ["CouetteFlow", "PlaneShear", "PlaneShearCase", "Problem"]
