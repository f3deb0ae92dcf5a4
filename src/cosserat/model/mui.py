"""The local mu(I) rheology on the package's two cells (``docs/derivation_mui.md``).

mu(I) = mu_s + (mu_2 - mu_s)/(I_0/I + 1), I = gamma_dot d / sqrt(p / rho_s) (GDR MiDi, Eur.
Phys. J. E 14, 341 (2004); tensorial form: Jop, Forterre & Pouliquen, Nature 441, 727 (2006)).
In a one-dimensional shear flow the law says: where the stress ratio mu = |tau|/p exceeds mu_s
the material shears at I(mu) = I_0 (mu - mu_s)/(mu_2 - mu); where mu <= mu_s it is a rigid
plug; mu >= mu_2 has no steady rate at all.

Scalings are those of the Cosserat cells (``docs/model.md``): xi across the gap, velocities
over the moving wall's speed V, stresses over N (plane) or over the local pressure (Couette).
The rate scale is one dimensionless number, the inertial number of the wall speed
``I_w = V d / (H sqrt(N / rho_s))``; with it ``I = I_w * rate / sqrt(p / N)``, where
``rate = gamma_dot H / V``.

The unknown stress level is carried as its distance from saturation at the moving wall,
``gap = mu_2 - mu(moving wall)`` in (0, mu_2 - mu_s): under fast driving the wall's stress ratio
comes within round-off of mu_2, and ``mu_2 - mu`` is then computed without cancellation.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from .. import config
from ..errors import NoSolutionError, ParameterError
from .constitutive import FloatArray
from .couette import validate_Ri
from .parameters import require_finite
from .plane import B_MAX, validate_B, validate_eps, validate_nu

GAP_MIN = 1e-300
"""Smallest representable distance of the wall's stress ratio from mu_2 [-]."""


@dataclass(frozen=True)
class MuI:
    """The constants of the local mu(I) law; ``MuI()`` is glass beads (Jop et al. 2006).

    Parameters
    ----------
    mu_s : float, default :data:`cosserat.config.MUI_MU_S` (tan 20.9 deg)
        Static friction coefficient, ``0 < mu_s < mu_2`` [-].
    mu_2 : float, default :data:`cosserat.config.MUI_MU_2` (tan 32.76 deg)
        Limiting friction coefficient as I -> infinity, ``mu_2 > mu_s`` [-].
    I_0 : float, default :data:`cosserat.config.MUI_I0`
        Inertial number at which mu is halfway from mu_s to mu_2, ``I_0 > 0`` [-].

    Raises
    ------
    ParameterError
        A value out of its bounds or not a finite number (the message names it).
    """

    mu_s: float = config.MUI_MU_S
    mu_2: float = config.MUI_MU_2
    I_0: float = config.MUI_I0

    def __post_init__(self) -> None:
        mu_s = require_finite("mu_s", self.mu_s)
        mu_2 = require_finite("mu_2", self.mu_2)
        I_0 = require_finite("I_0", self.I_0)
        if mu_s <= 0.0:
            raise ParameterError(f"mu_s must satisfy mu_s > 0; got {mu_s:g}")
        if mu_2 <= mu_s:
            raise ParameterError(f"mu_2 must satisfy mu_2 > mu_s = {mu_s:g}; got {mu_2:g}")
        if I_0 <= 0.0:
            raise ParameterError(f"I_0 must satisfy I_0 > 0; got {I_0:g}")
        object.__setattr__(self, "mu_s", mu_s)
        object.__setattr__(self, "mu_2", mu_2)
        object.__setattr__(self, "I_0", I_0)

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


def _validate_driving(I_w: float | None, stress_ratio: float | None) -> tuple[float | None, Any]:
    """Exactly one of the wall speed (I_w) and the wall stress ratio drives the cell."""
    if I_w is not None and stress_ratio is not None:
        raise ParameterError(
            "give either I_w (imposed wall speed) or stress_ratio (imposed wall stress), not both"
        )
    if stress_ratio is not None:
        return None, require_finite("stress_ratio", stress_ratio)
    x = require_finite("I_w", config.MUI_I_W if I_w is None else I_w)
    if not 0.0 < x <= config.MUI_I_W_MAX:
        raise ParameterError(
            f"I_w = V d / (H sqrt(N/rho_s)) must satisfy 0 < I_w <= {config.MUI_I_W_MAX:g} "
            f"(dense flow, the range of mu(I)); got {x:g}"
        )
    return x, None


class _MuICell:
    """What the two mu(I) cells share: driving, the stress level, the plug test."""

    rheology: MuI
    eps: float
    I_w: float | None
    stress_ratio: float | None
    moving_wall: float
    fixed_wall: float
    reference_velocity = 0.0

    @property
    def slip_wall(self) -> float:
        """xi of the moving wall: the shear layer's wall (mu(I) has no wall slip) [-]."""
        return self.moving_wall

    @property
    def stress_controlled(self) -> bool:
        return self.stress_ratio is not None

    def gap_of_stress_ratio(self) -> float:
        """mu_2 - mu at the moving wall for an imposed ``stress_ratio`` [-].

        Raises
        ------
        NoSolutionError
            stress_ratio >= mu_2 (no steady rate at the moving wall), or stress_ratio <= mu_s
            (the whole gap is a plug: the walls do not move relative to each other, and a
            velocity over the wall speed is undefined).
        """
        assert self.stress_ratio is not None
        T, law = self.stress_ratio, self.rheology
        where = f"at the {self.wall_name} (xi = {self.moving_wall:g}), where it is largest"
        if T >= law.mu_2:
            law.inertial_number(np.array([T]), where)
        if T <= law.mu_s:
            raise NoSolutionError(
                f"stress ratio {T:.6g} <= mu_s = {law.mu_s:.6g} {where}: the whole gap is a "
                "plug, the moving wall does not move, and u = v/V is undefined"
            )
        return law.mu_2 - T

    wall_name = "moving wall"

    def saturation_gap_at(self, t: FloatArray, gap: float) -> FloatArray:  # pragma: no cover
        raise NotImplementedError

    def rate_times_I_w_at(self, t: FloatArray, gap: float) -> FloatArray:  # pragma: no cover
        raise NotImplementedError

    def friction_ratio(self, xi: FloatArray, gap: float) -> FloatArray:
        """mu(xi) = |tau|/p across the gap for the wall gap ``gap`` [-]."""
        return self.rheology.mu_2 - self.saturation_gap(xi, gap)

    def inertial_number(self, xi: FloatArray, gap: float) -> FloatArray:
        """I(mu(xi)), 0 in the plug [-]."""
        return self.inertial_number_at(np.abs(np.asarray(xi, dtype=float) - self.moving_wall), gap)

    def inertial_number_at(self, t: FloatArray, gap: float) -> FloatArray:
        """I(mu) at the distance ``t`` from the moving wall, 0 in the plug [-].

        In distances, so that a layer of width 1e-300 at the wall is resolved.
        """
        g = self.saturation_gap_at(np.asarray(t, dtype=float), gap)
        law = self.rheology
        # mu - mu_s = (mu_2 - mu_s) - (mu_2 - mu): no cancellation near mu_2
        return law.inertial_number_from_gap(law.mu_2 - law.mu_s - g, g)

    def saturation_gap(self, xi: FloatArray, gap: float) -> FloatArray:
        """mu_2 - mu(xi) for the wall gap ``gap`` [-]."""
        return self.saturation_gap_at(np.abs(np.asarray(xi, dtype=float) - self.moving_wall), gap)

    def rate_times_I_w(self, xi: FloatArray, gap: float) -> FloatArray:
        """I_w times the shear rate gamma_dot H / V at xi [-] (:meth:`rate_times_I_w_at`)."""
        return self.rate_times_I_w_at(np.abs(np.asarray(xi, dtype=float) - self.moving_wall), gap)

    def plug(self, xi: FloatArray, gap: float) -> FloatArray:
        """True where |tau|/p <= mu_s: the material does not flow there."""
        x = np.asarray(xi, dtype=float)
        return (self.rheology.mu_2 - self.rheology.mu_s) - self.saturation_gap(x, gap) <= 0.0

    @staticmethod
    def _common_parameters(law: MuI, eps: float, I_w: float | None, T: float | None) -> dict:
        return {
            "rheology": "mui",
            "mu_s": law.mu_s,
            "mu_2": law.mu_2,
            "I_0": law.I_0,
            "eps": eps,
            "I_w": I_w,
            "stress_ratio": T,
        }

    def _driving(self) -> str:
        if self.stress_ratio is not None:
            return f"stress ratio {self.stress_ratio:g} at the {self.wall_name}"
        return f"I_w = {self.I_w:g}"


@dataclass(frozen=True, kw_only=True)
class MuIPlaneShear(_MuICell):
    """Plane shear of a mu(I) material between walls; the upper wall (xi = 1) moves.

    The upper wall moves at speed V under the normal stress N; no slip at either wall.
    Statics (as in :class:`~cosserat.model.plane.PlaneShear`): the shear stress is uniform,
    ``tau/N = T``, and ``p/N = 1 + B nu (1 - xi)``, so ``mu(xi) = T/(1 + B nu (1 - xi))`` is
    largest at the moving wall; with gravity a plug forms at the bottom where mu <= mu_s.

    Parameters
    ----------
    rheology : MuI
    eps : float
        Grain diameter over gap d/H, ``0 < eps <= 0.5`` [-] (only Delta, in grain diameters,
        uses it: the profile in xi depends on I_w, not on eps).
    B : float
        Gravity parameter rho_p g H / N, ``0 <= B <= 1e6`` [-].
    nu : float
        Solids fraction, ``0 < nu <= 1`` [-]; only B nu enters.
    I_w : float, default :data:`cosserat.config.MUI_I_W`
        Inertial number of the wall speed, V d / (H sqrt(N / rho_s)), ``0 < I_w <= 1`` [-].
    stress_ratio : float, optional
        Instead of I_w: the imposed tau/N at the moving wall [-]; the wall speed is then an
        output (``NoSolutionError`` from the routes if it is not in (mu_s, mu_2)).
    """

    rheology: MuI = MuI()
    eps: float
    B: float = 0.0
    nu: float = 1.0
    I_w: float | None = None
    stress_ratio: float | None = None

    moving_wall = 1.0
    fixed_wall = 0.0
    wall_name = "moving upper wall"

    def __post_init__(self) -> None:
        if not isinstance(self.rheology, MuI):
            raise ParameterError(f"rheology must be a MuI; got {type(self.rheology).__name__}")
        object.__setattr__(self, "eps", validate_eps(self.eps))
        object.__setattr__(self, "B", validate_B(self.B))
        object.__setattr__(self, "nu", validate_nu(self.nu))
        I_w, T = _validate_driving(self.I_w, self.stress_ratio)
        object.__setattr__(self, "I_w", I_w)
        object.__setattr__(self, "stress_ratio", T)

    @staticmethod
    def wall_velocity(xi_wall: float) -> float:
        """u of the wall: 1 at the moving upper wall, 0 at the fixed lower one [-]."""
        return 1.0 if xi_wall == 1.0 else 0.0

    def curvature(self, xi: FloatArray) -> FloatArray:
        return np.zeros_like(np.asarray(xi, dtype=float))

    def sigma_c(self, xi: FloatArray) -> FloatArray:
        """p/N = 1 + B nu (1 - xi) (``eqn-nd_ymom`` with ``eqn-nd_bc1``) [-]."""
        return 1.0 + self.B * self.nu * (1.0 - np.asarray(xi, dtype=float))

    def saturation_gap_at(self, t: FloatArray, gap: float) -> FloatArray:
        """mu_2 - mu = (mu_2 B nu t + gap)/(1 + B nu t) at t = 1 - xi [-]."""
        g = self.B * self.nu * np.asarray(t, dtype=float)
        return (self.rheology.mu_2 * g + gap) / (1.0 + g)

    def rate_times_I_w_at(self, t: FloatArray, gap: float) -> FloatArray:
        """I_w du/dxi = sqrt(p/N) I(mu) at t = 1 - xi [-]."""
        tt = np.asarray(t, dtype=float)
        return np.sqrt(1.0 + self.B * self.nu * tt) * self.inertial_number_at(tt, gap)

    def plug_extent(self, gap: float) -> tuple[float, float] | None:
        """[0, xi_p] where mu <= mu_s (at the fixed lower wall), or None [-].

        xi_p = 1 - (T/mu_s - 1)/(B nu), T = mu_2 - gap.
        """
        T, law = self.rheology.mu_2 - gap, self.rheology
        if self.B * self.nu == 0.0 or T / law.mu_s - 1.0 >= self.B * self.nu:
            return None
        return (0.0, 1.0 - (T / law.mu_s - 1.0) / (self.B * self.nu))

    def peak_width(self, gap: float) -> float:
        """Width over which mu_2 - mu doubles from the moving wall (quadrature breakpoints)."""
        if self.B * self.nu == 0.0:
            return 1.0
        return min(1.0, gap / (self.rheology.mu_2 * self.B * self.nu))

    def describe(self) -> str:
        return (
            f"plane shear, mu(I): {self.rheology.describe()}, eps = {self.eps:g}, "
            f"B = {self.B:g}, nu = {self.nu:g}; no slip; {self._driving()}"
        )

    def parameters(self) -> dict[str, Any]:
        out = {"geometry": "plane"}
        out.update(self._common_parameters(self.rheology, self.eps, self.I_w, self.stress_ratio))
        out.update({"B": self.B, "nu": self.nu})
        return out


@dataclass(frozen=True, kw_only=True)
class MuICouetteFlow(_MuICell):
    """Cylindrical Couette flow of a mu(I) material; the inner cylinder (xi = 0) turns.

    Variables and signs of :class:`~cosserat.model.couette.CouetteFlow`: ``xi = (r - R_i)/H``,
    ``u = -v_theta/V_i`` (-1 at the inner wall), stresses over the local pressure p, which is
    uniform across the gap at leading order in the Froude number (``docs/derivation_couette.md``).
    The torque fixes ``tau(r) = tau_i (R_i/r)^2``, so ``mu(xi) = mu_i (Ri/(Ri + xi))^2`` and a
    plug at rest fills ``xi >= Ri (sqrt(mu_i/mu_s) - 1)`` when that is inside the gap.

    Parameters
    ----------
    rheology : MuI
    eps : float
        Grain diameter over gap d/H, ``0 < eps <= 0.5`` [-] (for Delta in grain diameters).
    Ri : float
        Inner radius over gap R_i/H, ``1e-3 <= Ri <= 1e6`` [-].
    I_w : float, default :data:`cosserat.config.MUI_I_W`
        Inertial number of the inner wall's speed, V_i d / (H sqrt(p / rho_s)), at the depth
        (pressure p) of the profile, ``0 < I_w <= 1`` [-].
    stress_ratio : float, optional
        Instead of I_w: the imposed tau_i/p at the inner cylinder (the torque) [-].
    """

    rheology: MuI = MuI()
    eps: float
    Ri: float
    I_w: float | None = None
    stress_ratio: float | None = None

    moving_wall = 0.0
    fixed_wall = 1.0
    wall_name = "turning inner cylinder"

    def __post_init__(self) -> None:
        if not isinstance(self.rheology, MuI):
            raise ParameterError(f"rheology must be a MuI; got {type(self.rheology).__name__}")
        object.__setattr__(self, "eps", validate_eps(self.eps))
        object.__setattr__(self, "Ri", validate_Ri(self.Ri))
        I_w, T = _validate_driving(self.I_w, self.stress_ratio)
        object.__setattr__(self, "I_w", I_w)
        object.__setattr__(self, "stress_ratio", T)

    @staticmethod
    def wall_velocity(xi_wall: float) -> float:
        """u of the wall: -1 at the turning inner cylinder, 0 at the outer one [-]."""
        return -1.0 if xi_wall == 0.0 else 0.0

    def curvature(self, xi: FloatArray) -> FloatArray:
        return 1.0 / (self.Ri + np.asarray(xi, dtype=float))

    def sigma_c(self, xi: FloatArray) -> FloatArray:
        """p over the local pressure: 1 [-]."""
        return np.ones_like(np.asarray(xi, dtype=float))

    def saturation_gap_at(self, t: FloatArray, gap: float) -> FloatArray:
        """mu_2 - mu = mu_2 xi (2 Ri + xi)/(Ri + xi)^2 + gap (Ri/(Ri + xi))^2 at xi = t [-]."""
        x = np.asarray(t, dtype=float)
        r2 = (self.Ri + x) ** 2
        return (self.rheology.mu_2 * x * (2.0 * self.Ri + x) + gap * self.Ri**2) / r2

    def rate_times_I_w_at(self, t: FloatArray, gap: float) -> FloatArray:
        """I_w (Ri + xi) d(u/(Ri + xi))/dxi = I(mu) at xi = t [-] (the rate r d(v/r)/dr)."""
        return self.inertial_number_at(t, gap)

    def plug_extent(self, gap: float) -> tuple[float, float] | None:
        """[xi_c, 1] where mu <= mu_s (at the fixed outer cylinder), or None [-]."""
        xi_c = self.Ri * (math.sqrt((self.rheology.mu_2 - gap) / self.rheology.mu_s) - 1.0)
        return (xi_c, 1.0) if xi_c < 1.0 else None

    def peak_width(self, gap: float) -> float:
        """Width over which mu_2 - mu doubles from the inner wall (quadrature breakpoints)."""
        return min(1.0, gap * self.Ri / (2.0 * self.rheology.mu_2))

    def describe(self) -> str:
        return (
            f"Couette flow, mu(I): {self.rheology.describe()}, eps = {self.eps:g}, "
            f"Ri = {self.Ri:g}; no slip; {self._driving()}"
        )

    def parameters(self) -> dict[str, Any]:
        out = {"geometry": "couette"}
        out.update(self._common_parameters(self.rheology, self.eps, self.I_w, self.stress_ratio))
        out["Ri"] = self.Ri
        return out


MuIProblem = MuIPlaneShear | MuICouetteFlow


@dataclass(frozen=True, kw_only=True)
class MuIChannel:
    """Fully developed gravity flow of a mu(I) material between two vertical walls.

    The conventions of :class:`~cosserat.model.channel.Channel` (``docs/derivation_channel.md``
    sections 0-1 and 7): x down, ``xi = y/H``, walls at rest at 0 and 1, p = N uniform and
    ``mu(xi) = |tau|/p = B nu |xi - 1/2|``. A plug of half-width ``t_s = mu_s/(B nu)`` rides on
    the centre line, the material shears where mu > mu_s, no slip at the walls. The velocity is
    scaled by the centre-line velocity, ``u(1/2) = 1``; the inertial number of that velocity,
    ``I_w = V d/(H sqrt(N/rho_s))``, is then fixed by the stress (an output of the routes).

    Parameters
    ----------
    rheology : MuI
    eps : float
        Grain diameter over channel width d/H, ``0 < eps <= 0.5`` [-] (only Delta, in grain
        diameters, uses it).
    B : float
        rho_p g H / N with N the wall normal stress [-]: the wall stress ratio is B nu / 2.
        Default 1: a wall stress ratio of 0.5, inside (mu_s, mu_2) = (0.382, 0.643) of the
        default glass beads, where mu(I) flows (unlike the Cosserat channel, whose default is
        Janssen's B nu = 2 tan(delta) = 0.73: for mu(I) that is a plug).
    nu : float
        Solids fraction, ``0 < nu <= 1`` [-]; only B nu enters.

    Raises
    ------
    ParameterError
        A parameter out of its bounds.
    NoSolutionError
        ``B nu/2 <= mu_s`` (the whole channel is a plug held by static friction: no flow, and
        u = v/V is undefined) or ``B nu/2 >= mu_2`` (no steady rate carries the wall stress).
    """

    rheology: MuI = MuI()
    eps: float
    B: float = 1.0
    nu: float = 1.0

    slip_wall = 1.0
    reference_velocity = 1.0

    def __post_init__(self) -> None:
        if not isinstance(self.rheology, MuI):
            raise ParameterError(f"rheology must be a MuI; got {type(self.rheology).__name__}")
        object.__setattr__(self, "eps", validate_eps(self.eps))
        B = require_finite("B", self.B)
        if not 0.0 < B <= B_MAX:
            raise ParameterError(
                f"B = rho_p g H / N must satisfy 0 < B <= {B_MAX:g} in the channel (gravity "
                f"drives the flow); got {B:g}"
            )
        object.__setattr__(self, "B", B)
        object.__setattr__(self, "nu", validate_nu(self.nu))
        law, mu_w = self.rheology, self.wall_stress_ratio
        if mu_w >= law.mu_2:
            law.inertial_number(np.array([mu_w]), "at the walls, where it is largest")
        if mu_w <= law.mu_s:
            raise NoSolutionError(
                f"no flow: the wall stress ratio B nu/2 = {mu_w:.6g} <= mu_s = {law.mu_s:.6g}, so "
                "|tau|/p <= mu_s everywhere and the whole channel is a plug held by static "
                "friction; the centre-line velocity is 0 and u = v/V is undefined"
            )

    @property
    def wall_stress_ratio(self) -> float:
        """mu at the walls, B nu / 2 [-]."""
        return 0.5 * self.B * self.nu

    @property
    def plug_half_width(self) -> float:
        """t_s = mu_s/(B nu): the plug is |xi - 1/2| <= t_s [-]."""
        return self.rheology.mu_s / (self.B * self.nu)

    @staticmethod
    def wall_velocity(xi_wall: float) -> float:
        """The walls are at rest [-]."""
        return 0.0

    def curvature(self, xi: FloatArray) -> FloatArray:
        return np.zeros_like(np.asarray(xi, dtype=float))

    def sigma_c(self, xi: FloatArray) -> FloatArray:
        """p/N = 1 across the channel (y-momentum) [-]."""
        return np.ones_like(np.asarray(xi, dtype=float))

    def sigma_yx(self, xi: FloatArray) -> FloatArray:
        """tau/N = B nu (xi - 1/2) (x-momentum with symmetry) [-]."""
        return self.B * self.nu * (np.asarray(xi, dtype=float) - 0.5)

    def friction_ratio(self, xi: FloatArray) -> FloatArray:
        """mu(xi) = B nu |xi - 1/2| [-]."""
        return np.abs(self.sigma_yx(xi))

    def plug(self, xi: FloatArray) -> FloatArray:
        """True where mu <= mu_s: the plug on the centre line."""
        return self.friction_ratio(xi) <= self.rheology.mu_s

    def rate_times_I_w(self, xi: FloatArray) -> FloatArray:
        """I_w |du/dxi| = I(mu(xi)) (p = N), 0 in the plug [-]."""
        return self.rheology.inertial_number(self.friction_ratio(xi))

    def closed_form_J(self, xi: FloatArray) -> FloatArray:
        """J(xi) = I_w u(xi) in closed form (``docs/derivation_channel.md`` section 7) [-].

        ``I_0 [-(1/2 - t_lo) + ((mu_2 - mu_s)/(B nu)) ln((mu_2 - B nu t_lo)/(mu_2 - B nu/2))]``
        with ``t_lo = max(|xi - 1/2|, t_s)``; u is even about 1/2.
        """
        law, Bn = self.rheology, self.B * self.nu
        t_lo = np.maximum(np.abs(np.asarray(xi, dtype=float) - 0.5), self.plug_half_width)
        log = np.log1p(Bn * (0.5 - t_lo) / (law.mu_2 - 0.5 * Bn))
        return law.I_0 * (-(0.5 - t_lo) + (law.mu_2 - law.mu_s) / Bn * log)

    def describe(self) -> str:
        return (
            f"vertical channel, mu(I): {self.rheology.describe()}, eps = {self.eps:g}, "
            f"B = {self.B:g}, nu = {self.nu:g}; no slip; velocity scaled by the centre line"
        )

    def parameters(self) -> dict[str, Any]:
        return {
            "geometry": "channel",
            "rheology": "mui",
            "mu_s": self.rheology.mu_s,
            "mu_2": self.rheology.mu_2,
            "I_0": self.rheology.I_0,
            "eps": self.eps,
            "B": self.B,
            "nu": self.nu,
            "velocity_scale": "centre-line velocity, u(1/2) = 1",
        }


__all__ = ["GAP_MIN", "MuI", "MuIChannel", "MuICouetteFlow", "MuIPlaneShear", "MuIProblem"]
