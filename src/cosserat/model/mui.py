"""Deprecated module: the local mu(I) rheology is :mod:`cosserat.model.rheologies.mui`. It keeps
the old names importable for one release: :class:`MuI`, :data:`GAP_MIN` and the deprecated
aliases :func:`MuIPlaneShear`, :func:`MuICouetteFlow`, :func:`MuIChannel` (each returning a
:class:`~cosserat.model.problem.Problem`)."""

from __future__ import annotations

from .aliases import MuIChannel, MuICouetteFlow, MuIPlaneShear
from .rheologies.mui import GAP_MIN, MuI

__all__ = ["GAP_MIN", "MuI", "MuIChannel", "MuICouetteFlow", "MuIPlaneShear"]
