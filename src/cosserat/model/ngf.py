"""Deprecated module: the nonlocal granular fluidity model is
:mod:`cosserat.model.rheologies.ngf`. It keeps the old names importable for one release:
:class:`NGF`, its constants and compiled functions, and the deprecated aliases
:func:`NGFPlaneShear`, :func:`NGFCouetteFlow`, :func:`NGFChannel` (each returning a
:class:`~cosserat.model.problem.Problem`)."""

from __future__ import annotations

from .aliases import NGFChannel, NGFCouetteFlow, NGFPlaneShear
from .rheologies.ngf import (
    CHANNEL,
    COUETTE,
    FLUIDITY_BCS,
    NGF,
    NGF_A,
    NGF_B,
    NGF_EXCESS_RTOL,
    NGF_MU_S,
    NGF_RHO_S,
    PLANE,
    local_fluidity,
    local_inertial_number,
    statics,
)

__all__ = [
    "CHANNEL",
    "COUETTE",
    "FLUIDITY_BCS",
    "NGF",
    "NGF_A",
    "NGF_B",
    "NGF_EXCESS_RTOL",
    "NGF_MU_S",
    "NGF_RHO_S",
    "PLANE",
    "NGFChannel",
    "NGFCouetteFlow",
    "NGFPlaneShear",
    "local_fluidity",
    "local_inertial_number",
    "statics",
]
