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

The Cosserat model's equations on each cell (:mod:`cosserat.model.rheologies.cosserat.plane`,
:mod:`cosserat.model.rheologies.cosserat.couette`) supply
``sigma_yx(xi, m)``, ``sigma_c(xi)`` and ``kappa(xi)``; the solvers use only this module.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from .constitutive import FloatArray, flow_ratios, radicand, torque, yield_margin
from .parameters import Material


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

    Every method works on Python floats (the ODE right-hand sides call them per stage, where
    NumPy's per-call overhead would dominate) and on arrays. ``material`` may also be an
    array-valued stand-in with ``A``, ``sin_phi`` and ``alpha`` (the batched engine).

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

    material: Material | Any
    eps: float | Any
    sigma_yx: Callable[[Any, Any], Any]
    sigma_c: Callable[[Any], Any]
    kappa: Callable[[Any], Any] | None = None

    @property
    def eps_alpha(self) -> Any:
        return self.eps * self.material.alpha

    def curvature(self, xi: Any) -> Any:
        if self.kappa is None:
            return 0.0 * xi
        return self.kappa(xi)

    def velocity_weight(self, xi: Any) -> Any:
        """h of ``d(h u)/dxi = -w F1 h``: 1 in plane shear, 1/(Ri + xi) in Couette flow."""
        return 1.0 + 0.0 * xi if self.kappa is None else self.kappa(xi)

    def stresses(self, xi: ArrayLike, m: ArrayLike) -> Stresses:
        """Stresses with the paper's root of ``eqn-nd_sigxy``; S clipped at 0 (no raising).

        Callers that must not accept S < 0 check ``radicand`` themselves (the numerical solver
        stops on it with an event; the profile builders call ``check_radicand``).
        """
        x = np.asarray(xi, dtype=float)
        mm = np.asarray(m, dtype=float)
        syx = np.broadcast_to(self.sigma_yx(x, mm), np.broadcast(x, mm).shape).astype(float)
        sc = np.broadcast_to(self.sigma_c(x), syx.shape).astype(float)
        S = radicand(syx, sc, mm, self.material)
        sxy = syx - 2.0 * (self.material.A + 1.0) * torque(syx, sc, mm, self.material)
        return Stresses(syx, sxy, sc, S)

    def dm_dxi(self, xi: Any, m: Any) -> Any:
        """Couple-stress balance solved for dm/dxi (module docstring) [-]."""
        t = torque(self.sigma_yx(xi, m), self.sigma_c(xi), m, self.material)
        return t / self.eps_alpha - self.curvature(xi) * m

    def yield_margin(self, xi: Any, m: Any) -> Any:
        """>= 0 where the second shear stress is real (:func:`constitutive.yield_margin`)."""
        return yield_margin(self.sigma_yx(xi, m), self.sigma_c(xi), m, self.material)

    def flow_ratios(self, xi: Any, m: Any) -> tuple[Any, Any]:
        """(F1, F2) of the flow rule at (xi, m)."""
        return flow_ratios(self.sigma_yx(xi, m), self.sigma_c(xi), m, self.material)

    def spin_rates(self, xi: Any, m: Any) -> tuple[Any, Any]:
        """(d ln w / dxi, G) = (-F2/(eps alpha) - kappa F1, F1 h) [-] (module docstring)."""
        F1, F2 = self.flow_ratios(xi, m)
        if self.kappa is None:
            return -F2 / self.eps_alpha, F1
        kappa = self.kappa(xi)
        return -F2 / self.eps_alpha - kappa * F1, F1 * kappa

    def log_spin_rate(self, xi: Any, m: Any) -> Any:
        """d ln w / dxi = -F2/(eps alpha) - kappa F1 [-]."""
        return self.spin_rates(xi, m)[0]

    def velocity_source(self, xi: Any, m: Any) -> Any:
        """G = F1 h of ``d(h u)/dxi = -w G`` [-]."""
        return self.spin_rates(xi, m)[1]
