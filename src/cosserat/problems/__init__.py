"""Problems: one module per geometry, each stating its equations and boundary conditions."""

from __future__ import annotations

from typing import TypeAlias

from .plane import PlaneShear, PlaneShearCase

Problem: TypeAlias = PlaneShear

__all__ = ["PlaneShear", "PlaneShearCase", "Problem"]
