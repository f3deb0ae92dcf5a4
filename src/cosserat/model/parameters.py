"""Material and wall parameters (immutable, validated on construction).

Units and conventions, used everywhere in the package:

* angles (``phi``, ``delta``) are given in degrees ``[deg]``;
* every other parameter here is dimensionless ``[-]``;
* ``L`` and ``A = a2/a1`` are the constants of the yield condition ``eqn-yc2`` with
  ``a1 + a2 = 1/2``, so ``a1 = 1/(2(1+A))``;
* ``K`` is the slip coefficient of the kinematic wall condition ``eqn-bc3``.

``Material()`` and ``Wall()`` are the paper's material and smooth wall: their defaults are those
of :mod:`cosserat.config` (``PHI``, ``L``, ``A``; ``DELTA``, ``K``).

Vary a parameter with :func:`dataclasses.replace`; the copy is validated again.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass
from typing import Literal

from .. import config
from ..errors import ParameterError, shown
from .declare import param, validate

FULLY_ROUGH: Literal["fully-rough"] = "fully-rough"
"""Value of ``Wall.delta`` for a fully rough wall, tan(delta) = sin(phi) (``eqn-bc_fullyrough``)."""
ROUGH_WORDS = ("fully-rough", "fully_rough", "rough")
"""Spellings of a fully rough wall accepted for a wall's delta (any case)."""
PAPER = "Mohan, Kesava Rao & Nott, J. Fluid Mech. 457 (2002): the paper's figures"
L_BOUNDS = (1e-3, 1e4)
"""Admissible L [-]: plane shear at eps = 1e-3 solves with residuals below 5e-8 at L = 1e-3 and
at L = 1e4 (measured); L near 1e-300 divided by zero in the kernels and L = 1e200 overflowed."""


def require_finite(name: str, value: float) -> float:
    """Return ``float(value)``, or raise :class:`ParameterError` if it is not a finite number."""
    try:
        x = float(value)
    except (TypeError, ValueError):
        raise ParameterError(f"{name} must be a number; got {shown(value)}") from None
    if not math.isfinite(x):
        raise ParameterError(f"{name} must be finite; got {shown(value)}")
    return x


def require_open_interval(name: str, value: float, lo: float, hi: float, unit: str = "") -> float:
    """Validate ``lo < value < hi``; the error names the parameter, the bound and the value."""
    x = require_finite(name, value)
    if not lo < x < hi:
        raise ParameterError(f"{name} must satisfy {lo:g} < {name} < {hi:g}{unit}; got {x:g}")
    return x


@dataclass(frozen=True)
class Material:
    """A granular material; ``Material()`` is the paper's (glass beads).

    Parameters
    ----------
    phi : float, default :data:`cosserat.config.PHI`
        Angle of internal friction, ``0 < phi < 90`` [deg].
    L : float, default :data:`cosserat.config.L`
        Ratio of the material length scale to the grain diameter in ``eqn-yc2``,
        ``1e-3 <= L <= 1e4`` (:data:`L_BOUNDS`) [-].
    A : float, default :data:`cosserat.config.A`
        Ratio ``a2/a1`` of the yield-condition constants, ``-1 < A < 1`` [-] (the quadratic
        form in ``eqn-yc2`` must be positive).

    Raises
    ------
    ParameterError
        A value out of its bounds or not a finite number (the message names it).

    Examples
    --------
    >>> from cosserat import Material
    >>> Material()
    Material(phi=28.5, L=10.0, A=0.3333333333333333)
    >>> round(Material(phi=30.0).fully_rough_delta, 3)  # atan(sin(phi)) [deg]
    26.565
    """

    phi: float = param(
        config.PHI,
        "angle of internal friction",
        "deg",
        bounds=(0.0, 90.0),
        fit_range=(10.0, 60.0),
        role="material",
        source=f"glass beads; {PAPER}",
    )
    L: float = param(
        config.L,
        "material length scale over the grain diameter, eqn-yc2",
        bounds=L_BOUNDS,
        closed=(True, True),
        reason="the range where the solvers are verified; L = 1e200 overflows the stress scales",
        fit_range=(0.5, 100.0),
        scale="log",
        role="material",
        source=PAPER,
    )
    A: float = param(
        config.A,
        "ratio a2/a1 of the yield-condition constants, eqn-yc2",
        bounds=(-1.0, 1.0),
        fit_range=(-0.95, 0.95),
        role="material",
        reason="the quadratic form in eqn-yc2 must be positive",
        source=PAPER,
    )

    def __post_init__(self) -> None:
        validate(self)

    @functools.cached_property
    def sin_phi(self) -> float:
        """sin(phi) [-]."""
        return math.sin(math.radians(self.phi))

    @functools.cached_property
    def alpha(self) -> float:
        """alpha = L / sqrt(2(A+1)), the coefficient of eps in ``eqn-nd_zangmom`` [-]."""
        return self.L / math.sqrt(2.0 * (self.A + 1.0))

    @functools.cached_property
    def c2(self) -> float:
        """c^2 = sin^2(phi) / (2(A+1)) of ``eqn-eta_g`` [-]."""
        return self.sin_phi**2 / (2.0 * (self.A + 1.0))

    @functools.cached_property
    def fully_rough_delta(self) -> float:
        """The wall-friction angle of a fully rough wall, atan(sin phi) [deg]."""
        return math.degrees(math.atan(self.sin_phi))


@dataclass(frozen=True)
class Wall:
    """A wall bounding the granular material; ``Wall()`` is the paper's smooth wall.

    Parameters
    ----------
    delta : float or "fully-rough", default :data:`cosserat.config.DELTA`
        Angle of wall friction ``0 < delta < 90`` [deg], or :data:`FULLY_ROUGH` for a wall with
        tan(delta) = sin(phi) exactly (``eqn-bc_fullyrough``). That tan(delta) <= sin(phi) is
        checked where the wall meets a material (in the problem classes).
    K : float, default :data:`cosserat.config.K`
        Slip coefficient of ``eqn-bc3``, ``K >= 0`` [-]: 0 means no slip relative to the wall,
        1/2 a grain rolling without sliding.

    Raises
    ------
    ParameterError
        A value out of its bounds or not a finite number (the message names it).

    Examples
    --------
    >>> from cosserat import Wall
    >>> Wall()
    Wall(delta=20.0, K=0.5)
    >>> Wall.fully_rough().is_fully_rough
    True
    """

    delta: float | Literal["fully-rough"] = param(
        config.DELTA,
        "angle of wall friction, or fully-rough: tan delta = sin phi",
        "deg",
        bounds=(0.0, 90.0),
        choices=(FULLY_ROUGH,),
        fit_range=(1.0, 45.0),
        role="wall",
        source=f"smooth walls; {PAPER}",
    )
    K: float = param(
        config.K,
        "slip coefficient of eqn-bc3; 0: no slip, 1/2: a grain rolling without sliding",
        bounds=(0.0, math.inf),
        closed=(True, False),
        fit_range=(0.0, 10.0),
        role="wall",
        source=PAPER,
    )

    def __post_init__(self) -> None:
        if isinstance(self.delta, str) and self.delta.strip().lower() in ROUGH_WORDS:
            object.__setattr__(self, "delta", FULLY_ROUGH)
        validate(self)

    @classmethod
    def fully_rough(cls, K: float = config.K) -> Wall:
        """A fully rough wall, tan(delta) = sin(phi) (``eqn-bc_fullyrough``), slip coefficient
        ``K`` [-] (default :data:`cosserat.config.K`)."""
        return cls(FULLY_ROUGH, K)

    @property
    def is_fully_rough(self) -> bool:
        """True if the wall was declared fully rough."""
        return self.delta == FULLY_ROUGH

    def tan_delta(self, material: Material, name: str = "delta") -> float:
        """tan(delta) against ``material``, validated ``tan(delta) <= sin(phi)`` [-].

        A value within :data:`cosserat.config.FULLY_ROUGH_RTOL` (relative) of sin(phi) is taken
        as fully rough, so that ``Wall(material.fully_rough_delta)`` behaves like
        ``Wall.fully_rough()`` despite round-off in atan/tan.
        """
        s = material.sin_phi
        if self.is_fully_rough:
            return s
        t = math.tan(math.radians(float(self.delta)))
        if t > s * (1.0 + config.FULLY_ROUGH_RTOL):
            raise ParameterError(
                f"{name} must satisfy tan({name}) <= sin(phi), i.e. {name} <= "
                f"{material.fully_rough_delta:.6g} deg for phi = {material.phi:g} deg "
                f"(a wall cannot be rougher than fully rough, eqn-bc_fullyrough); "
                f"got {name} = {self.delta:g} deg"
            )
        return s if t > s * (1.0 - config.FULLY_ROUGH_RTOL) else t

    def describe(self) -> str:
        d = "fully rough" if self.is_fully_rough else f"delta = {self.delta:g} deg"
        return f"{d}, K = {self.K:g}"
