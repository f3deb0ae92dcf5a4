"""The frictional Cosserat model (Mohan, Kesava Rao & Nott, J. Fluid Mech. 457 (2002) 377-409).

The rheology is the material (:class:`~cosserat.model.parameters.Material`: phi, L, A) and, since
friction and slip at a wall are part of the model's closure, its walls
(:class:`~cosserat.model.parameters.Wall`: delta, K): the moving wall (every wall of the Couette
cell and of the channel), and for plane shear optionally a different fixed lower plate and the
couple stress at the wall that does not slip. Its equations on each cell are the helpers of
:mod:`.plane`, :mod:`.couette` and :mod:`.channel` (which wall slips, the slip constants, the
couple-stress terms the model adds to a cell's statics); they read the cells' statics.

The command-line keys are ``phi, L, A`` (material), ``delta, K`` (the moving wall),
``delta_lower, K_lower, m_wall`` (plane shear only).
"""

from __future__ import annotations

import dataclasses
import functools
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, ClassVar, TypeAlias

from ....errors import MethodNotAvailableError, ParameterError
from ...declare import Param, declarations, param
from ...parameters import Material, Wall
from ..base import Equations, Rheology
from .channel import CosseratChannel
from .couette import CosseratCouette
from .plane import CosseratPlane, PlaneShearCase

if TYPE_CHECKING:
    from ...problem import Problem

REFERENCE = (
    "Mohan, Kesava Rao & Nott, A frictional Cosserat model for the slow shearing of "
    "granular materials, J. Fluid Mech. 457 (2002) 377-409"
)


def _lower(p: Param, meaning: str) -> Param:
    return dataclasses.replace(
        p,
        key=f"{p.name}_lower",
        name=f"{p.name}_lower",
        meaning=meaning,
        default=None,
        optional=True,
        cells=("plane",),
    )


@dataclass(frozen=True, kw_only=True)
class Cosserat(Rheology):
    """The frictional Cosserat model: a material and its walls; ``Cosserat()`` is the paper's
    glass beads between smooth walls.

    Parameters
    ----------
    material : Material
        phi [deg], L [-], A [-] (``eqn-yc2``).
    wall : Wall
        The moving wall: the upper plate in plane shear, both cylinders in Couette flow, both
        walls of the channel (delta [deg] or "fully-rough", K [-]).
    lower : Wall, optional
        Plane shear only: the fixed lower plate (delta_L, K_L); default: as ``wall``.
    m_fixed_wall : float, optional
        Plane shear only: the couple stress m at the wall that does not slip, replacing
        ``eqn-nd_bc4`` there (the paper's sensitivity study, figure 5) [-].

    Examples
    --------
    >>> from cosserat import Cosserat, Material, Wall
    >>> Cosserat(material=Material(phi=30.0), wall=Wall.fully_rough()).values()["delta"]
    'fully-rough'
    """

    name: ClassVar[str] = "cosserat"
    title: ClassVar[str] = "frictional Cosserat model"
    reference: ClassVar[str] = REFERENCE
    rate_dependent: ClassVar[bool] = False
    couple_stresses: ClassVar[bool] = True
    default_free: ClassVar[tuple[str, ...]] = ("delta", "K")
    equations: ClassVar[Mapping[str, type[Equations]]] = {
        "plane": CosseratPlane,
        "couette": CosseratCouette,
        "channel": CosseratChannel,
    }

    material: Material = field(default_factory=Material)
    wall: Wall = field(default_factory=Wall)
    lower: Wall | None = None
    m_fixed_wall: float | None = param(
        None,
        "couple stress at the wall that does not slip (default: sigma_xy = sigma_yx there, "
        "eqn-nd_bc4)",
        key="m_wall",
        optional=True,
        role="option",
        cells=("plane",),
        source="the paper's sensitivity study, figure 5",
    )

    def __post_init__(self) -> None:
        for name, cls in (("material", Material), ("wall", Wall)):
            if not isinstance(getattr(self, name), cls):
                raise ParameterError(
                    f"{name} must be a {cls.__name__}; got {type(getattr(self, name)).__name__}"
                )
        if self.lower is not None and not isinstance(self.lower, Wall):
            raise ParameterError(f"lower must be a Wall; got {type(self.lower).__name__}")
        m = declarations(self)["m_fixed_wall"].check(self.m_fixed_wall, "m_fixed_wall")
        object.__setattr__(self, "m_fixed_wall", m)

    @property
    def lower_wall(self) -> Wall:
        """The fixed lower plate of plane shear (``wall`` unless ``lower`` is given)."""
        return self.wall if self.lower is None else self.lower

    # ----------------------------------------------------------------- declarations
    @classmethod
    def declared(cls, cell: str | None = None) -> dict[str, Param]:
        out = _declared_cosserat()
        return {k: p for k, p in out.items() if cell is None or p.applies_to(cell)}

    @classmethod
    def _declared_all(cls) -> dict[str, Param]:
        wall = declarations(Wall)
        out: dict[str, Param] = {p.cli_key: p for p in declarations(Material).values()}
        out.update({p.cli_key: p for p in wall.values()})
        out["delta_lower"] = _lower(
            wall["delta"],
            "angle of wall friction of the fixed lower plate, or fully-rough (default: as delta)",
        )
        out["K_lower"] = _lower(
            wall["K"], "slip coefficient of the fixed lower plate (default: as K)"
        )
        m = declarations(cls)["m_fixed_wall"]
        out[m.cli_key] = m
        return out

    def values(self) -> dict[str, Any]:
        mat, wall, low = self.material, self.wall, self.lower
        return {
            "phi": mat.phi,
            "L": mat.L,
            "A": mat.A,
            "delta": wall.delta,
            "K": wall.K,
            "delta_lower": None if low is None else low.delta,
            "K_lower": None if low is None else low.K,
            "m_wall": self.m_fixed_wall,
        }

    @classmethod
    def from_values(cls, values: Mapping[str, Any]) -> Cosserat:
        known = cls.declared()
        unknown = sorted(k for k in values if k not in known)
        if unknown:
            raise ParameterError(
                f"unknown parameter(s) {', '.join(unknown)} of the cosserat rheology; it has "
                f"{', '.join(known)}"
            )
        v = {k: x for k, x in values.items() if x is not None}
        material = Material(**{k: v[k] for k in ("phi", "L", "A") if k in v})
        wall = Wall(**{k: v[k] for k in ("delta", "K") if k in v})
        lower = None
        if "delta_lower" in v or "K_lower" in v:
            try:
                lower = Wall(v.get("delta_lower", wall.delta), v.get("K_lower", wall.K))
            except ParameterError as exc:
                raise ParameterError(f"lower wall (delta_lower, K_lower): {exc}") from None
        return cls(material=material, wall=wall, lower=lower, m_fixed_wall=v.get("m_wall"))

    def with_values(self, values: Mapping[str, Any]) -> Cosserat:
        current = self.values()
        unknown = sorted(k for k in values if k not in current)
        if unknown:
            raise ParameterError(
                f"unknown parameter(s) {', '.join(unknown)} of the cosserat rheology; it has "
                f"{', '.join(current)}"
            )
        return self.from_values({**current, **values})

    def describe(self) -> str:
        m = self.material
        return f"phi = {m.phi:g} deg, L = {m.L:g}, A = {m.A:g}; walls {self.wall.describe()}"


@functools.cache
def _declared_cosserat() -> dict[str, Param]:
    """:meth:`Cosserat.declared` for every cell, computed once."""
    return Cosserat._declared_all()


CosseratEquations: TypeAlias = CosseratPlane | CosseratCouette | CosseratChannel
"""The Cosserat model's equations on any of its cells."""


def cosserat_equations(problem: Problem) -> CosseratEquations:
    """``problem.equations``, checked to be the Cosserat model's on one of its cells.

    Raises
    ------
    MethodNotAvailableError
        The problem is another rheology's (the message names it).
    """
    eq = problem.equations
    if not isinstance(eq, CosseratPlane | CosseratCouette | CosseratChannel):
        raise MethodNotAvailableError(
            f"this route solves the Cosserat model; {problem.describe()} is another rheology"
        )
    return eq


__all__ = [
    "REFERENCE",
    "Cosserat",
    "CosseratChannel",
    "CosseratCouette",
    "CosseratEquations",
    "CosseratPlane",
    "PlaneShearCase",
    "cosserat_equations",
]
