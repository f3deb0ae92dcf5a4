"""Deprecated module: plane shear is the cell :class:`~cosserat.model.cells.plane.Plane` and the
Cosserat model's equations on it :mod:`cosserat.model.rheologies.cosserat.plane`. It keeps the
old names importable for one release: :func:`PlaneShear` (a deprecated alias returning a
:class:`~cosserat.model.problem.Problem`), :class:`PlaneShearCase`, :class:`WallConstants`,
:func:`wall_constants`, :func:`mean_stress` and :data:`B_MAX`."""

from __future__ import annotations

from .aliases import PlaneShear
from .cells.plane import B_MAX, mean_stress
from .rheologies.cosserat.plane import PlaneShearCase, WallConstants, wall_constants

__all__ = [
    "B_MAX",
    "PlaneShear",
    "PlaneShearCase",
    "WallConstants",
    "mean_stress",
    "wall_constants",
]
