"""The problem classes of release 0.x, kept for one release as deprecated aliases.

``PlaneShear(...)``, ``CouetteFlow(...)``, ``Channel(...)`` (the Cosserat model),
``MuIPlaneShear(...)``, ``MuICouetteFlow(...)``, ``MuIChannel(...)`` and ``NGFPlaneShear(...)``,
``NGFCouetteFlow(...)``, ``NGFChannel(...)`` keep their signatures and return the equivalent
:class:`~cosserat.model.problem.Problem` of a cell and a rheology, with a
:class:`DeprecationWarning` that names the replacement. They are functions now: code that
tested ``isinstance(problem, PlaneShear)`` tests ``problem.cell.name == "plane"`` and
``problem.model == "cosserat"``.
"""

from __future__ import annotations

import dataclasses
import warnings
from typing import Any

from .cells import Couette, Plane, VerticalChannel
from .parameters import Material, Wall
from .problem import Problem
from .rheologies import NGF, Cosserat, MuI


def _warn(old: str, new: str) -> None:
    warnings.warn(
        f"{old}(...) is deprecated and will be removed in the next release: use {new}",
        DeprecationWarning,
        stacklevel=3,
    )


def PlaneShear(
    *,
    material: Material,
    upper: Wall,
    lower: Wall | None = None,
    eps: float,
    B: float = 0.0,
    nu: float = 1.0,
    m_fixed_wall: float | None = None,
) -> Problem:
    """Deprecated: ``Problem(Plane(eps=, B=, nu=), Cosserat(material=, wall=upper, lower=,
    m_fixed_wall=))``."""
    _warn(
        "PlaneShear",
        "Problem(Plane(eps=..., B=..., nu=...), Cosserat(material=..., wall=..., lower=...))",
    )
    law = Cosserat(material=material, wall=upper, lower=lower, m_fixed_wall=m_fixed_wall)
    return Problem(Plane(eps=eps, B=B, nu=nu), law)


def CouetteFlow(*, material: Material, wall: Wall, eps: float, Ri: float) -> Problem:
    """Deprecated: ``Problem(Couette(eps=, Ri=), Cosserat(material=, wall=))``."""
    _warn("CouetteFlow", "Problem(Couette(eps=..., Ri=...), Cosserat(material=..., wall=...))")
    return Problem(Couette(eps=eps, Ri=Ri), Cosserat(material=material, wall=wall))


def Channel(
    *, material: Material, wall: Wall, eps: float, B: float | None = None, nu: float = 1.0
) -> Problem:
    """Deprecated: ``Problem(VerticalChannel(eps=, B=, nu=), Cosserat(material=, wall=))``."""
    _warn(
        "Channel",
        "Problem(VerticalChannel(eps=..., B=..., nu=...), Cosserat(material=..., wall=...))",
    )
    return Problem(VerticalChannel(eps=eps, B=B, nu=nu), Cosserat(material=material, wall=wall))


def MuIPlaneShear(
    *,
    rheology: MuI | None = None,
    eps: float,
    B: float = 0.0,
    nu: float = 1.0,
    I_w: float | None = None,
    stress_ratio: float | None = None,
) -> Problem:
    """Deprecated: ``Problem(Plane(eps=, B=, nu=, I_w=, stress_ratio=), MuI(...))``."""
    _warn("MuIPlaneShear", "Problem(Plane(eps=..., I_w=...), MuI(...))")
    cell = Plane(eps=eps, B=B, nu=nu, I_w=I_w, stress_ratio=stress_ratio)
    return Problem(cell, MuI() if rheology is None else rheology)


def MuICouetteFlow(
    *,
    rheology: MuI | None = None,
    eps: float,
    Ri: float,
    I_w: float | None = None,
    stress_ratio: float | None = None,
) -> Problem:
    """Deprecated: ``Problem(Couette(eps=, Ri=, I_w=, stress_ratio=), MuI(...))``."""
    _warn("MuICouetteFlow", "Problem(Couette(eps=..., Ri=..., I_w=...), MuI(...))")
    cell = Couette(eps=eps, Ri=Ri, I_w=I_w, stress_ratio=stress_ratio)
    return Problem(cell, MuI() if rheology is None else rheology)


def MuIChannel(
    *, rheology: MuI | None = None, eps: float, B: float = 1.0, nu: float = 1.0
) -> Problem:
    """Deprecated: ``Problem(VerticalChannel(eps=, B=, nu=), MuI(...))`` (its default B = 1
    stays here; a channel cell without B is driven by I_w)."""
    _warn("MuIChannel", "Problem(VerticalChannel(eps=..., B=..., nu=...), MuI(...))")
    return Problem(VerticalChannel(eps=eps, B=B, nu=nu), MuI() if rheology is None else rheology)


def _ngf(rheology: NGF | None, fluidity_bc: str) -> NGF:
    law = NGF() if rheology is None else rheology
    if not isinstance(law, NGF):
        return law  # Problem says what is wrong with it
    return dataclasses.replace(law, fluidity_bc=fluidity_bc)


def NGFPlaneShear(
    *,
    rheology: NGF | None = None,
    eps: float,
    B: float = 0.0,
    nu: float = 1.0,
    I_w: float | None = None,
    stress_ratio: float | None = None,
    fluidity_bc: str = "neumann",
) -> Problem:
    """Deprecated: ``Problem(Plane(eps=, B=, nu=, I_w=, stress_ratio=), NGF(...,
    fluidity_bc=))``."""
    _warn("NGFPlaneShear", "Problem(Plane(eps=..., I_w=...), NGF(..., fluidity_bc=...))")
    cell = Plane(eps=eps, B=B, nu=nu, I_w=I_w, stress_ratio=stress_ratio)
    return Problem(cell, _ngf(rheology, fluidity_bc))


def NGFCouetteFlow(
    *,
    rheology: NGF | None = None,
    eps: float,
    Ri: float,
    I_w: float | None = None,
    stress_ratio: float | None = None,
    fluidity_bc: str = "neumann",
) -> Problem:
    """Deprecated: ``Problem(Couette(eps=, Ri=, I_w=, stress_ratio=), NGF(...,
    fluidity_bc=))``."""
    _warn("NGFCouetteFlow", "Problem(Couette(eps=..., Ri=..., I_w=...), NGF(...))")
    cell = Couette(eps=eps, Ri=Ri, I_w=I_w, stress_ratio=stress_ratio)
    return Problem(cell, _ngf(rheology, fluidity_bc))


def NGFChannel(
    *,
    rheology: NGF | None = None,
    eps: float,
    B: float | None = None,
    nu: float = 1.0,
    I_w: float | None = None,
    fluidity_bc: str = "neumann",
) -> Problem:
    """Deprecated: ``Problem(VerticalChannel(eps=, B=, nu=, I_w=), NGF(..., fluidity_bc=))``."""
    _warn("NGFChannel", "Problem(VerticalChannel(eps=..., B=... or I_w=...), NGF(...))")
    cell = VerticalChannel(eps=eps, B=B, nu=nu, I_w=I_w)
    return Problem(cell, _ngf(rheology, fluidity_bc))


ALIASES: dict[str, Any] = {
    f.__name__: f
    for f in (
        PlaneShear,
        CouetteFlow,
        Channel,
        MuIPlaneShear,
        MuICouetteFlow,
        MuIChannel,
        NGFPlaneShear,
        NGFCouetteFlow,
        NGFChannel,
    )
}
"""Every deprecated problem class name -> its alias."""

__all__ = [
    "ALIASES",
    "Channel",
    "CouetteFlow",
    "MuIChannel",
    "MuICouetteFlow",
    "MuIPlaneShear",
    "NGFChannel",
    "NGFCouetteFlow",
    "NGFPlaneShear",
    "PlaneShear",
]
