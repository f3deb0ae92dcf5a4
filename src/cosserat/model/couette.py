"""Deprecated module: Couette flow is the cell :class:`~cosserat.model.cells.couette.Couette`
and the Cosserat model's equations on it :mod:`cosserat.model.rheologies.cosserat.couette`. It
keeps the old names importable for one release: :func:`CouetteFlow` (a deprecated alias
returning a :class:`~cosserat.model.problem.Problem`) and the compiled stress functions."""

from __future__ import annotations

from .aliases import CouetteFlow
from .cells.couette import RI_MAX, RI_MIN
from .rheologies.cosserat.couette import outer_wall_couple_stress, shear_stress, shear_stress_dm

__all__ = [
    "RI_MAX",
    "RI_MIN",
    "CouetteFlow",
    "outer_wall_couple_stress",
    "shear_stress",
    "shear_stress_dm",
]
