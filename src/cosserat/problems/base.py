"""The governing equations of steady Cosserat shear between two walls, in one place.

Plane shear and cylindrical Couette flow share one structure once written in the wall-normal
coordinate ``xi`` (``y/H`` or ``(r - Ri)/H``) with the curvature ``kappa = 1/(Ri + xi)`` (zero in
plane shear). With ``sigma_yx`` the shear stress on planes parallel to the walls
(``sigma_r_theta``), ``sigma_xy`` the other one (``sigma_theta_r``) and ``sigma_c`` the mean stress
(derivations in ``docs/derivation_plane.md`` and ``docs/derivation_couette.md``):

* couple-stress (angular-momentum) balance, ``eqn-nd_zangmom`` / ``eqn-nd_zangmom_cyl``::

      eps alpha (dm/dxi + kappa m) = (sigma_yx - sigma_xy) / (2 (A+1))

* flow rule, ``eqn-nd_fr1``-``eqn-nd_fr2`` / ``eqn-nd_fr1_cyl``-``eqn-nd_fr2_cyl``. With the spin
  relative to the local rigid rotation, ``w = omega + kappa u`` (``w = omega`` in plane shear),
  they separate into one homogeneous equation for ``w`` and one quadrature for ``u``::

      d ln w / dxi = -F2 / (eps alpha) - kappa F1
      d (h u) / dxi = -w F1 h,          h = 1 (plane), 1/(Ri + xi) (Couette)

  so ``w`` is an exponential of an integral (integrate the exponent, never ``w`` itself) and
  ``u`` follows by one quadrature.

The problem classes (:mod:`cosserat.problems.plane`, :mod:`cosserat.problems.couette`) supply
``sigma_yx(xi, m)``, ``sigma_c(xi)`` and ``kappa(xi)``; the solvers use only this module.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from ..constitutive import (
    FloatArray,
    radicand,
    spin_ratio,
    velocity_ratio,
)
from ..parameters import Material

# Floor on sqrt(S), the denominator of the flow-rule ratios; S = 0 only on the yield bound.
_SQRT_S_FLOOR = 1e-150


def _torque_conjugate(tau: Any, sc: Any, m: Any, root: Any, material: Material) -> Any:
    """[(sc sin phi - tau)(sc sin phi + tau) - 2(A+1) m^2] / (sqrt(S) + (1+A) tau)."""
    A, sc_sin = material.A, sc * material.sin_phi
    return ((sc_sin - tau) * (sc_sin + tau) - 2.0 * (A + 1.0) * m * m) / (root + (1.0 + A) * tau)


def _torque_direct(tau: Any, root: Any, material: Material) -> Any:
    """(sqrt(S) - (1+A) tau)/(2(A+1)), used only where tau <= 0 (no cancellation there)."""
    return (root - (1.0 + material.A) * tau) / (2.0 * (material.A + 1.0))


@dataclass(frozen=True)
class Stresses:
    """Stress state at given points [-]."""

    sigma_yx: FloatArray
    sigma_xy: FloatArray
    sigma_c: FloatArray
    radicand: FloatArray


@dataclass(frozen=True)
class Formulation:
    """The ODEs of one problem: stress closure and curvature (see module docstring).

    Parameters
    ----------
    material : Material
    eps : float
        d_p / H [-].
    sigma_yx : callable (xi, m) -> array
        Shear stress on planes parallel to the walls [-].
    sigma_c : callable xi -> array
        Mean (= every normal) stress [-].
    kappa : callable xi -> array, or None
        Curvature 1/(Ri + xi) [-]; None for plane shear.
    """

    material: Material
    eps: float
    sigma_yx: Callable[[FloatArray, FloatArray], FloatArray]
    sigma_c: Callable[[FloatArray], FloatArray]
    kappa: Callable[[FloatArray], FloatArray] | None = None

    @property
    def eps_alpha(self) -> float:
        return self.eps * self.material.alpha

    def curvature(self, xi: ArrayLike) -> FloatArray:
        x = np.asarray(xi, dtype=float)
        return np.zeros_like(x) if self.kappa is None else self.kappa(x)

    def velocity_weight(self, xi: ArrayLike) -> FloatArray:
        """h of ``d(h u)/dxi = -w F1 h``: 1 in plane shear, 1/(Ri + xi) in Couette flow."""
        x = np.asarray(xi, dtype=float)
        return np.ones_like(x) if self.kappa is None else self.kappa(x)

    def stresses(self, xi: ArrayLike, m: ArrayLike) -> Stresses:
        """Stresses with the paper's root of ``eqn-nd_sigxy``; S clipped at 0 (no raising).

        Callers that must not accept S < 0 check ``radicand`` themselves (the numerical solver
        stops on it with an event; the profile builders call ``check_radicand``).
        """
        x = np.asarray(xi, dtype=float)
        mm = np.asarray(m, dtype=float)
        syx = np.broadcast_to(self.sigma_yx(x, mm), np.broadcast(x, mm).shape)
        sc = np.broadcast_to(self.sigma_c(x), syx.shape)
        S = radicand(syx, sc, mm, self.material)
        sxy = syx - 2.0 * (self.material.A + 1.0) * self.torque(syx, sc, mm, S)
        return Stresses(np.asarray(syx, float), sxy, np.asarray(sc, float), S)

    def torque(self, syx: FloatArray, sc: FloatArray, m: FloatArray, S: FloatArray) -> FloatArray:
        """(syx - sxy)/(2(A+1)) on the paper's root, free of cancellation [-].

        Directly, ``(syx - sxy) = sqrt(S) - (1+A) tau`` with tau = -syx, which cancels near
        a fully rough wall (there both terms equal (1+A) sin phi). Multiplying by the
        conjugate, ``S - (1+A)^2 tau^2 = 2(A+1)[(sc sin phi - tau)(sc sin phi + tau) - 2(A+1)m^2]``,
        so for tau > 0 (``docs/numerics.md``)::

            (syx - sxy)/(2(A+1)) = [(sc sin phi - tau)(sc sin phi + tau) - 2(A+1) m^2]
                                   / (sqrt(S) + (1+A) tau)
        """
        root = np.sqrt(np.maximum(S, 0.0))
        tau = -syx
        with np.errstate(divide="ignore", invalid="ignore"):
            conj = _torque_conjugate(tau, sc, m, root, self.material)
        direct = _torque_direct(tau, root, self.material)
        return np.where(tau > 0.0, conj, direct)

    def dm_dxi(self, xi: ArrayLike, m: ArrayLike) -> FloatArray:
        """Couple-stress balance solved for dm/dxi (module docstring) [-]."""
        x = np.asarray(xi, dtype=float)
        mm = np.asarray(m, dtype=float)
        syx = np.broadcast_to(self.sigma_yx(x, mm), np.broadcast(x, mm).shape)
        sc = np.broadcast_to(self.sigma_c(x), syx.shape)
        S = radicand(syx, sc, mm, self.material)
        return self.torque(syx, sc, mm, S) / self.eps_alpha - self.curvature(x) * mm

    # ------------------------------------------------------------ fast paths on Python floats
    # The ODE solvers call these once per stage on scalars; NumPy's per-call overhead would
    # dominate (~40 us against ~3 us). They evaluate the same formulas (the helpers below and
    # constitutive.radicand) with math.sqrt.
    def dm_dxi_scalar(self, xi: float, m: float) -> float:
        """:meth:`dm_dxi` for one point [-]."""
        syx = float(self.sigma_yx(xi, m))
        sc = float(self.sigma_c(xi))
        S = float(radicand(syx, sc, m, self.material))
        root = math.sqrt(S) if S > 0.0 else 0.0
        tau = -syx
        if tau > 0.0:
            t = _torque_conjugate(tau, sc, m, root, self.material)
        else:
            t = _torque_direct(tau, root, self.material)
        kappa = 0.0 if self.kappa is None else float(self.kappa(xi))
        return float(t) / self.eps_alpha - kappa * m

    def spin_rates_scalar(self, xi: float, m: float) -> tuple[float, float]:
        """(d ln w/dxi, G) of :meth:`log_spin_rate` and :meth:`velocity_source` at one point."""
        syx = float(self.sigma_yx(xi, m))
        sc = float(self.sigma_c(xi))
        S = float(radicand(syx, sc, m, self.material))
        denom = -max(math.sqrt(S) if S > 0.0 else 0.0, _SQRT_S_FLOOR)
        sxy = denom - self.material.A * syx
        F1 = float(velocity_ratio(sxy, syx, self.material, denom))
        F2 = float(spin_ratio(sxy, syx, m, self.material, denom))
        if self.kappa is None:
            return -F2 / self.eps_alpha, F1
        kappa = float(self.kappa(xi))
        return -F2 / self.eps_alpha - kappa * F1, F1 * kappa

    def flow_ratios(self, xi: ArrayLike, m: ArrayLike) -> tuple[FloatArray, FloatArray]:
        """(F1, F2) of the flow rule at (xi, m), with sqrt(S) floored away from 0."""
        st = self.stresses(xi, m)
        A = self.material.A
        # sxy + A syx = -sqrt(S); the floor only matters exactly on the yield bound.
        denom = -np.maximum(np.sqrt(np.maximum(st.radicand, 0.0)), _SQRT_S_FLOOR)
        sxy = denom - A * st.sigma_yx
        F1 = velocity_ratio(sxy, st.sigma_yx, self.material, denom)
        F2 = spin_ratio(sxy, st.sigma_yx, m, self.material, denom)
        return F1, F2

    def log_spin_rate(self, xi: ArrayLike, m: ArrayLike) -> FloatArray:
        """d ln w / dxi = -F2/(eps alpha) - kappa F1 [-]."""
        F1, F2 = self.flow_ratios(xi, m)
        return -F2 / self.eps_alpha - self.curvature(xi) * F1

    def velocity_source(self, xi: ArrayLike, m: ArrayLike) -> FloatArray:
        """G = F1 h of ``d(h u)/dxi = -w G`` [-]."""
        F1, _ = self.flow_ratios(xi, m)
        return F1 * self.velocity_weight(xi)
