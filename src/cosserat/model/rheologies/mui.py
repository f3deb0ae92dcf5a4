"""The local mu(I) rheology, on any cell (``docs/derivation_mui.md``).

mu(I) = mu_s + (mu_2 - mu_s)/(I_0/I + 1), I = gamma_dot d / sqrt(p / rho_s) (GDR MiDi, Eur.
Phys. J. E 14, 341 (2004); tensorial form: Jop, Forterre & Pouliquen, Nature 441, 727 (2006)).
In a one-dimensional shear flow the law says: where the stress ratio mu = |tau|/p exceeds mu_s
the material shears at I(mu) = I_0 (mu - mu_s)/(mu_2 - mu); where mu <= mu_s it is a rigid
plug; mu >= mu_2 has no steady rate at all.

The law reads nothing of a cell but its statics (:mod:`cosserat.model.cells`): the stress ratio
``mu = T q(t)`` at the distance t from the wall where it is largest (T, the stress level, is
the ratio there), the normal stress and the radius of the coordinate lines. Its equations
(:class:`MuIFlow`) therefore hold on every cell, a new one included. Scalings are the cell's:
velocities over the velocity scale (the moving wall's speed, or the channel's centre line),
stresses over the cell's stress scale. The rate scale is the inertial number of that speed,
``I_w = V d / (H sqrt(N / rho_s))`` (the cell's drive); with it ``I = I_w * rate /
sqrt(p / N)``, where ``rate = gamma_dot H / V``.

The unknown stress level is carried as its distance from saturation at the peak wall,
``gap = mu_2 - T`` in (0, mu_2 - mu_s): under fast driving the wall's stress ratio comes within
round-off of mu_2, and ``mu_2 - mu`` is then computed without cancellation.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, ClassVar

import numpy as np

from ... import config
from ...errors import NoSolutionError, ParameterError
from ..constitutive import BoolArray, FloatArray
from ..declare import Constraint, param, validate
from .base import ANY_CELL, Equations, Rheology

GAP_MIN = 1e-300
"""Smallest representable distance of the wall's stress ratio from mu_2 [-]."""
MU_MAX = 10.0
"""Largest friction coefficient mu_s or mu_2 (84 deg) [-]: no granular material comes near, and
mu_2 = 1e300 divided by zero in the Couette quadrature."""
SPREAD_MIN = 1e-4
"""Smallest mu_2 - mu_s [-]: the span of stress ratios the rate lives in. NGF's boundary error
grows like (mu_2 - mu_s)^-2 (1e-14 at 1e-2, 7.7e-13 at 1e-3, 6.5e-11 at 1e-4, measured on plane
shear at eps = 1e-3) and its kernels divided by zero at mu_2 - mu_s = 1e-5."""
EXCESS_RTOL = 1e-7
"""Smallest relative excess (T - mu_s)/mu_s of the wall's stress ratio T over mu_s [-].

The rate is proportional to the excess, computed as (mu_2 - mu_s) - (mu_2 - T) with round-off
~1e-16 mu_2: plane shear without gravity (u = xi exactly) came out with max |u - xi| = 2e-9 at
I_w = 1e-8, 2.3e-7 at 1e-10, 1e-4 at 1e-12, and u = 0 everywhere at 1e-15 (measured at
eps = 1e-3, glass beads). An excess of 1e-7 mu_s keeps the profile to about 1e-9. Through
``T - mu_s ~ (mu_2 - mu_s) I_w / I_0`` it bounds the wall speed: :attr:`MuI.I_w_min`."""


def friction_spread() -> tuple[Constraint, ...]:
    """The constraint ``mu_2 - mu_s >= SPREAD_MIN`` of every rheology with both (mu(I), NGF's
    saturating law)."""
    return (
        Constraint(
            ("mu_2", "mu_s"),
            f"mu_2 - mu_s >= {SPREAD_MIN:g}",
            lambda mu_2, mu_s: mu_2 - mu_s >= SPREAD_MIN * (1.0 - 1e-9),  # mu_s + 1e-4 passes
            "the rate lives between mu_s and mu_2; a narrower span loses the rate to round-off",
        ),
    )


REFERENCE = (
    "GDR MiDi, On dense granular flows, Eur. Phys. J. E 14 (2004) 341-365; Jop, Forterre & "
    "Pouliquen, A constitutive law for dense granular flows, Nature 441 (2006) 727-730"
)
_JOP = "glass beads, Jop, Forterre & Pouliquen, Nature 441 (2006)"


class MuIFlow(Equations):
    """mu(I) on any cell: the stress ratio, the rate and the plug from the cell's statics
    (module docstring); ``problem.equations`` of ``Problem(cell, MuI(...))``.

    Distances ``t`` run from the cell's :attr:`~cosserat.model.cells.base.Cell.peak_wall` (the
    wall of the largest stress ratio): in distances, a layer of width 1e-300 at that wall is
    resolved.
    """

    def validate(self) -> None:
        """Refuse a drive too slow for double precision (:data:`EXCESS_RTOL`)."""
        law, I_w, T = self.rheology, self.I_w, self.stress_ratio
        if T is None and I_w is not None and I_w < law.I_w_min:
            raise ParameterError(
                f"I_w must satisfy I_w >= {EXCESS_RTOL:g} mu_s I_0/(mu_2 - mu_s) = "
                f"{law.I_w_min:.3g}; got {I_w:g}: a slower wall puts the stress ratio within "
                f"{EXCESS_RTOL:g} mu_s of mu_s, where the excess that drives the flow has too "
                "few significant digits in double precision (raise I_w or lower I_0)"
            )
        if T is not None and law.mu_s < T < law.mu_s * (1.0 + EXCESS_RTOL):
            raise ParameterError(
                f"{self.cell.level_name}: the imposed stress ratio {T:.17g} is within "
                f"{EXCESS_RTOL:g} mu_s of mu_s = {law.mu_s:.17g}, where the excess that drives "
                "the flow has too few significant digits in double precision; impose at least "
                f"mu_s (1 + {EXCESS_RTOL:g}) or at most mu_s"
            )

    @property
    def rheology(self) -> MuI:
        return self.law

    @property
    def peak_wall(self) -> float:
        """xi of the wall where the stress ratio is largest [-]."""
        return float(self.cell.peak_wall)

    @property
    def wall_name(self) -> str:
        return str(self.cell.peak_wall_name)

    @property
    def I_w(self) -> float | None:
        """The wall's inertial number that drives the flow; None when the stress is imposed."""
        return self.cell.wall_inertial_number

    @property
    def stress_ratio(self) -> float | None:
        """The imposed stress level (the largest stress ratio), or None [-]."""
        return self.cell.imposed_level()

    @property
    def stress_controlled(self) -> bool:
        return self.stress_ratio is not None

    def gap_of_stress_ratio(self) -> float:
        """mu_2 - T for an imposed stress level T [-].

        Raises
        ------
        NoSolutionError
            T >= mu_2 (no steady rate at the peak wall), or T <= mu_s (the whole gap is a
            plug: nothing moves, and a velocity over the velocity scale is undefined).
        """
        T, law = self.stress_ratio, self.rheology
        assert T is not None
        where = f"at the {self.wall_name} (xi = {self.peak_wall:g}), where it is largest"
        if T >= law.mu_2:
            law.inertial_number(np.array([T]), where)
        if T <= law.mu_s:
            raise NoSolutionError(
                f"stress ratio {T:.6g} <= mu_s = {law.mu_s:.6g} {where}: the whole gap is a "
                "plug held by static friction, nothing moves, and u = v/V is undefined"
            )
        return law.mu_2 - T

    # ----------------------------------------------------------------- the law on the statics
    def saturation_gap_at(self, t: FloatArray, gap: float) -> FloatArray:
        """mu_2 - mu at the distance t from the peak wall for the wall gap ``gap``:
        ``mu_2 (1 - q) + gap q`` with q the cell's ratio shape [-]."""
        q, one_minus_q = self.cell.ratio_shape(np.asarray(t, dtype=float))
        return self.rheology.mu_2 * one_minus_q + gap * q

    def inertial_number_at(self, t: FloatArray, gap: float) -> FloatArray:
        """I(mu) at the distance ``t`` from the peak wall, 0 in the plug [-]."""
        g = self.saturation_gap_at(np.asarray(t, dtype=float), gap)
        law = self.rheology
        # mu - mu_s = (mu_2 - mu_s) - (mu_2 - mu): no cancellation near mu_2
        return law.inertial_number_from_gap(law.mu_2 - law.mu_s - g, g)

    def rate_times_I_w_at(self, t: FloatArray, gap: float) -> FloatArray:
        """I_w |r d(u/r)/dxi| = sqrt(p/N) I(mu) at the distance t from the peak wall [-]."""
        tt = np.asarray(t, dtype=float)
        return np.sqrt(self.cell.normal_stress_at(tt)) * self.inertial_number_at(tt, gap)

    def integrand_at(self, t: FloatArray, gap: float) -> FloatArray:
        """|d(u/r)/dxi| I_w at the distance t: the rate over the radius [-]
        (:meth:`rate_times_I_w_at` over the cell's radius, in one pass: the quadratures call it
        for every node)."""
        tt = np.asarray(t, dtype=float)
        cell, law = self.cell, self.rheology
        q, one_minus_q = cell.ratio_shape(tt)
        g = law.mu_2 * one_minus_q + gap * q
        rate = np.sqrt(cell.normal_stress_at(tt)) * law.inertial_number_from_gap(
            law.mu_2 - law.mu_s - g, g
        )
        return rate if cell.straight else rate / cell.radius_at(tt)

    def saturation_gap(self, xi: FloatArray | float, gap: float) -> FloatArray:
        """mu_2 - mu(xi) for the wall gap ``gap`` [-]."""
        return self.saturation_gap_at(self.cell.distance(xi), gap)

    def friction_ratio(self, xi: FloatArray, gap: float) -> FloatArray:
        """mu(xi) = |tau|/p across the gap for the wall gap ``gap`` [-]."""
        return self.rheology.mu_2 - self.saturation_gap(xi, gap)

    def inertial_number(self, xi: FloatArray, gap: float) -> FloatArray:
        """I(mu(xi)), 0 in the plug [-]."""
        return self.inertial_number_at(self.cell.distance(xi), gap)

    def rate_times_I_w(self, xi: FloatArray, gap: float) -> FloatArray:
        """I_w |r d(u/r)/dxi| at xi [-] (:meth:`rate_times_I_w_at`)."""
        return self.rate_times_I_w_at(self.cell.distance(xi), gap)

    def shear_sign(self, xi: FloatArray, gap: float) -> FloatArray:
        """The sign of r d(u/r)/dxi: opposite to that of sigma_yx [-]."""
        return -np.sign(self.cell.shear_stress(np.asarray(xi, dtype=float), 1.0))

    def plug(self, xi: FloatArray, gap: float) -> BoolArray:
        """True where |tau|/p <= mu_s: the material does not flow there."""
        x = np.asarray(xi, dtype=float)
        return (self.rheology.mu_2 - self.rheology.mu_s) - self.saturation_gap(x, gap) <= 0.0

    def plug_extent(self, gap: float) -> tuple[float, float] | None:
        """The interval of xi where mu <= mu_s (a plug at rest or riding the flow), or None [-]."""
        return self.cell.region_below(self.rheology.mu_2 - gap, self.rheology.mu_s)

    def peak_width(self, gap: float) -> float:
        """Width over which mu_2 - mu doubles from the peak wall (quadrature breakpoints):
        ``gap/(mu_2 slope)`` with the slope of the cell's ratio shape there, or where
        ``mu_2 (1 - q) = gap`` if the cell states no slope or the shape starts flat
        (:meth:`~cosserat.model.cells.Cell.distance_of_complement`) [-]."""
        slope = self.cell.ratio_slope
        mu_2 = self.rheology.mu_2
        if slope is not None and slope > 0.0:
            return min(1.0, gap / (mu_2 * slope))
        return min(1.0, self.cell.distance_of_complement(gap / mu_2))

    # ----------------------------------------------------------------- records
    def _driving(self) -> str:
        if self.stress_ratio is not None:
            return f"stress ratio {self.stress_ratio:g} at the {self.wall_name}"
        return f"I_w = {self.I_w:g}"

    def describe(self) -> str:
        cell = self.cell
        keys = tuple(k for k, p in cell.declared().items() if p.role == "cell")
        scale = "; velocity scaled by the centre line" if cell.moving_wall is None else ""
        return (
            f"{cell.title}, mu(I): {self.rheology.describe()}, {cell.describe(keys)}; no slip; "
            f"{self._driving()}{scale}"
        )

    def parameters(self) -> dict[str, Any]:
        out: dict[str, Any] = {"geometry": self.cell.name, "rheology": "mui"}
        out.update(self.rheology.values())
        out.update(self.problem.cell_values())
        if self.cell.moving_wall is None:
            xs, us = self.cell.velocity_scale
            out["velocity_scale"] = f"u({xs:g}) = {us:g}"
        return out


@dataclass(frozen=True)
class MuI(Rheology):
    """The local mu(I) law; ``MuI()`` is glass beads (Jop et al. 2006).

    Parameters
    ----------
    mu_s : float, default :data:`cosserat.config.MUI_MU_S` (tan 20.9 deg)
        Static friction coefficient, ``0 < mu_s < 10`` [-].
    mu_2 : float, default :data:`cosserat.config.MUI_MU_2` (tan 32.76 deg)
        Limiting friction coefficient as I -> infinity, ``mu_2 < 10`` and
        ``mu_2 - mu_s >= 1e-4`` (:data:`SPREAD_MIN`) [-].
    I_0 : float, default :data:`cosserat.config.MUI_I0`
        Inertial number at which mu is halfway from mu_s to mu_2, ``I_0 > 0`` [-].

    Raises
    ------
    ParameterError
        A value out of its bounds or not a finite number (the message names it).

    Examples
    --------
    >>> from cosserat import MuI
    >>> round(MuI().mu_s, 4), MuI().I_0
    (0.3819, 0.279)
    """

    name: ClassVar[str] = "mui"
    title: ClassVar[str] = "local mu(I) rheology"
    reference: ClassVar[str] = REFERENCE
    default_free: ClassVar[tuple[str, ...]] = ("mu_s", "I_w")
    equations: ClassVar[dict[str, type[Equations]]] = {ANY_CELL: MuIFlow}
    constraints: ClassVar[tuple[Constraint, ...]] = friction_spread()

    mu_s: float = param(
        config.MUI_MU_S,
        "static friction coefficient",
        bounds=(0.0, MU_MAX),
        reason=f"a friction angle below {math.degrees(math.atan(MU_MAX)):.0f} deg",
        fit_range=(0.05, 1.2),
        role="material",
        source=f"tan 20.9 deg: {_JOP}",
    )
    mu_2: float = param(
        config.MUI_MU_2,
        "limiting friction coefficient as I -> infinity, above mu_s",
        bounds=(0.0, MU_MAX),
        reason=f"a friction angle below {math.degrees(math.atan(MU_MAX)):.0f} deg",
        fit_range=(0.06, 2.0),
        role="material",
        source=f"tan 32.76 deg: {_JOP}",
    )
    I_0: float = param(
        config.MUI_I0,
        "inertial number at which mu is halfway from mu_s to mu_2",
        bounds=(0.0, math.inf),
        fit_range=(1e-4, 10.0),
        scale="log",
        role="material",
        source=_JOP,
    )

    def __post_init__(self) -> None:
        validate(self)

    @property
    def I_w_min(self) -> float:
        """Smallest admissible wall inertial number, ``EXCESS_RTOL mu_s I_0/(mu_2 - mu_s)``
        (4.07e-8 for glass beads) [-]: the wall's stress ratio then exceeds mu_s by
        :data:`EXCESS_RTOL` mu_s (to first order in I_w/I_0)."""
        return EXCESS_RTOL * self.mu_s * self.I_0 / (self.mu_2 - self.mu_s)

    def friction(self, inertial_number: FloatArray) -> FloatArray:
        """mu(I) = mu_s + (mu_2 - mu_s) I/(I_0 + I) [-] for I >= 0 [-]."""
        i = np.asarray(inertial_number, dtype=float)
        return self.mu_s + (self.mu_2 - self.mu_s) * i / (self.I_0 + i)

    def inertial_number(self, mu: FloatArray, where: str = "") -> FloatArray:
        """The inverse law I(mu) = I_0 (mu - mu_s)/(mu_2 - mu), 0 where mu <= mu_s [-].

        Raises
        ------
        NoSolutionError
            Some mu >= mu_2: mu(I) < mu_2 for every finite I, so no steady rate carries it.
        """
        m = np.asarray(mu, dtype=float)
        if np.any(m >= self.mu_2):
            raise NoSolutionError(
                f"stress ratio |tau|/p = {float(np.max(m)):.6g} >= mu_2 = {self.mu_2:.6g}"
                f"{' ' + where if where else ''}: mu(I) < mu_2 for every finite inertial number, "
                "so no steady shear rate carries this stress (the material accelerates)"
            )
        return self.inertial_number_from_gap(m - self.mu_s, self.mu_2 - m)

    def inertial_number_from_gap(self, excess: FloatArray, gap: FloatArray) -> FloatArray:
        """I from ``excess = mu - mu_s`` and ``gap = mu_2 - mu > 0`` (no cancellation) [-]."""
        e = np.asarray(excess, dtype=float)
        return np.where(e > 0.0, self.I_0 * np.maximum(e, 0.0) / gap, 0.0)

    def describe(self) -> str:
        return f"mu_s = {self.mu_s:.6g}, mu_2 = {self.mu_2:.6g}, I_0 = {self.I_0:g}"


__all__ = [
    "EXCESS_RTOL",
    "GAP_MIN",
    "MU_MAX",
    "REFERENCE",
    "SPREAD_MIN",
    "MuI",
    "MuIFlow",
    "friction_spread",
]
