"""The Cosserat model in cylindrical Couette flow (section "Cylindrical Couette flow";
``docs/derivation_couette.md``).

The cell (:class:`~cosserat.model.cells.couette.Couette`) gives the statics: a uniform normal
stress and a shear stress falling like r^-2 (:func:`~cosserat.model.cells.couette.torque_decay`).
In these variables every equation of the model is the plane-shear one with the curvature
kappa = 1/(Ri + xi):

* couple stress: ``eps alpha (dm/dxi + m/(Ri+xi)) = (s_rt - s_tr)/(2(A+1))`` (the printed
  ``eqn-nd_zangmom_cyl`` lacks the factor 2(A+1) alpha; ``eqn-nd_shsts_cyl`` has it);
* shear stress, integrated from theta-momentum and the couple-stress balance
  (``eqn-nd_shsts_cyl``): the cell's, plus the couple-stress terms this model adds, with the
  friction condition ``s_rt(0) = -tan delta``::

      s_rt = -tan(delta)/(1 + xi/Ri)^2 + 2(A+1) eps alpha (m/(Ri+xi) - m(0) Ri/(Ri+xi)^2)

  whose unknown m(0) is fixed by one scalar root-find;
* conditions: ``s_rt = s_tr`` and ``u = 0`` at the outer cylinder (``eqn-nd_bc1_cyl``), friction
  and ``u = -1 - eps K omega`` at the inner one (``eqn-nd_bc2_cyl``).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np
from numba import njit

from ....errors import NoSolutionError
from ..._cached import cached
from ...cells.couette import torque_decay
from ...constitutive import FloatArray
from ...formulation import Formulation
from ...grids import layered_grid
from ...parameters import Material, Wall
from ..base import Equations
from .plane import WallConstants, wall_constants


@njit(cache=True, nogil=True)
def shear_stress(
    xi: Any, m: Any, m_inner: float, tan_delta: float, Ri: float, couple_factor: float
) -> Any:
    """s_rt from ``eqn-nd_shsts_cyl`` given m(xi) and m(0) = ``m_inner`` [-]: the cell's
    statics (:func:`~cosserat.model.cells.couette.torque_decay`) plus the couple-stress terms.

    ``couple_factor`` = 2(A+1) eps alpha. Compiled (numbers in the solver kernels, arrays
    here); its derivative in m is :func:`shear_stress_dm`.
    """
    r = Ri + xi
    return -tan_delta * torque_decay(xi, Ri) + couple_factor * (m / r - m_inner * Ri / (r * r))


@njit(cache=True)
def shear_stress_dm(xi: float, Ri: float, couple_factor: float) -> float:
    """d s_rt / dm at fixed m(0): ``couple_factor / (Ri + xi)`` (:func:`shear_stress`) [-]."""
    return couple_factor / (Ri + xi)


@njit(cache=True)
def shear_stress_dm_inner(xi: float, Ri: float, couple_factor: float) -> float:
    """d s_rt / d m(0) at fixed m: ``-couple_factor Ri/(Ri + xi)^2`` (:func:`shear_stress`) [-]."""
    r = Ri + xi
    return -couple_factor * Ri / (r * r)


@njit(cache=True)
def outer_wall_couple_stress(
    m_inner: float, tan_delta: float, Ri: float, couple_factor: float, A: float, sin_phi: float
) -> tuple[float, float]:
    """m(1) from s_rt = s_tr at the outer cylinder (``eqn-nd_bc1_cyl``), the negative root,
    and the discriminant (negative: no real m(1)) [-].

    With s_rt(1) = s0 + beta m (``eqn-nd_shsts_cyl``) and the yield condition at a symmetric
    stress, ``s_rt^2 + 2(A+1) m^2 = sin^2 phi``: a quadratic in m.
    """
    r1 = Ri + 1.0
    beta = couple_factor / r1
    s0 = -tan_delta * torque_decay(1.0, Ri) - couple_factor * m_inner * Ri / (r1 * r1)
    qa = beta * beta + 2.0 * (A + 1.0)
    disc = -2.0 * (A + 1.0) * s0 * s0 + qa * sin_phi * sin_phi
    root = math.sqrt(disc) if disc > 0.0 else 0.0
    return (-s0 * beta - root) / qa, disc


@njit(cache=True)
def outer_wall_couple_stress_dm_inner(
    m_inner: float, tan_delta: float, Ri: float, couple_factor: float, A: float, sin_phi: float
) -> float:
    """d m(1) / d m(0) of :func:`outer_wall_couple_stress` (``eqn-nd_bc1_cyl``) [-].

    With ``ds0/dm(0) = -couple_factor Ri/(Ri+1)^2`` and ``d disc = -4(A+1) s0 ds0``:
    ``dm(1) = -(beta ds0 + d disc / (2 sqrt(disc))) / qa``; infinite where disc = 0.
    """
    r1 = Ri + 1.0
    beta = couple_factor / r1
    s0 = -tan_delta * (Ri / r1) ** 2 - couple_factor * m_inner * Ri / (r1 * r1)
    ds0 = -couple_factor * Ri / (r1 * r1)
    qa = beta * beta + 2.0 * (A + 1.0)
    disc = -2.0 * (A + 1.0) * s0 * s0 + qa * sin_phi * sin_phi
    if disc <= 0.0:
        return math.inf
    return -(beta * ds0 - 2.0 * (A + 1.0) * s0 * ds0 / math.sqrt(disc)) / qa


class CosseratCouette(Equations):
    """The Cosserat model on the Couette cell (module docstring): ``problem.equations`` of
    ``Problem(Couette(...), Cosserat(...))``. The walls of both cylinders are the rheology's
    ``wall`` (the paper takes them alike); friction is mobilised at the inner one only, since
    |s_rt| falls like (1 + xi/Ri)^-2 outwards.
    """

    def validate(self) -> None:
        self.wall.tan_delta(self.material, "delta")

    @property
    def material(self) -> Material:
        return self.law.material

    @property
    def wall(self) -> Wall:
        return self.law.wall

    @property
    def Ri(self) -> float:
        return float(self.cell.Ri)

    # ----------------------------------------------------------------- equations
    @cached
    def tan_delta(self) -> float:
        return self.wall.tan_delta(self.material, "delta")

    slip_wall = 0.0
    fixed_wall = 1.0
    reference_velocity = 0.0

    def shear_stress(self, xi: FloatArray, m: FloatArray, m_inner: float) -> FloatArray:
        """s_rt from ``eqn-nd_shsts_cyl`` (:func:`shear_stress`) [-]."""
        x, mm = np.broadcast_arrays(np.asarray(xi, dtype=float), np.asarray(m, dtype=float))
        return shear_stress(x, mm, float(m_inner), self.tan_delta, self.Ri, self.couple_factor)

    @cached
    def couple_factor(self) -> float:
        """2(A+1) eps alpha: the weight of the couple stress in eqn-nd_shsts_cyl [-]."""
        return 2.0 * (self.material.A + 1.0) * self.eps * self.material.alpha

    def formulation(self, m_inner: float) -> Formulation:
        """The ODEs of :mod:`cosserat.model.formulation` for a trial m(0) = ``m_inner``."""
        return Formulation(
            material=self.material,
            eps=self.eps,
            sigma_yx=lambda xi, m: self.shear_stress(xi, m, m_inner),
            sigma_c=self.sigma_c,
            kappa=self.curvature,
        )

    def outer_wall_couple_stress(self, m_inner: float) -> float:
        """m(1) from s_rt = s_tr there (:func:`outer_wall_couple_stress`) [-]."""
        m1, disc = outer_wall_couple_stress(
            float(m_inner),
            self.tan_delta,
            self.Ri,
            self.couple_factor,
            self.material.A,
            self.material.sin_phi,
        )
        if disc < 0.0:
            raise NoSolutionError(
                "no real solution: the outer-wall condition s_rt = s_tr (eqn-nd_bc1_cyl) has no "
                f"real couple stress for m(0) = {m_inner:.6g}"
            )
        return float(m1)

    @property
    def slip_constants(self) -> WallConstants:
        """a, b, m0, k at the inner cylinder (s_rt = -tan delta, sigma_c = 1)."""
        return wall_constants(self.tan_delta, 1.0, self.material)

    @property
    def is_fully_rough(self) -> bool:
        return self.slip_constants.m0 == 0.0

    def outer_couple_stress(self, xi: FloatArray) -> FloatArray:
        """Leading-order couple stress (Appendix, Couette m^(0)) [-].

        m^(0) = -(m0^2 + d^2 [1 - (1 + xi/Ri)^-4])^(1/2) with d^2 = tan^2(delta)/(2(A+1)): the
        value at which the stress is symmetric for s_rt = -tan(delta)/(1 + xi/Ri)^2.
        """
        x = np.asarray(xi, dtype=float)
        d2 = self.tan_delta**2 / (2.0 * (self.material.A + 1.0))
        m0 = self.slip_constants.m0
        return -np.sqrt(m0**2 + d2 * (1.0 - (1.0 + x / self.Ri) ** -4))

    def inner_scale(self) -> float:
        """(L^2 Ri / 4)^(1/3): xi = eps^(2/3) scale * x_hat in the Airy layer (fully rough)."""
        return (self.material.L**2 * self.Ri / 4.0) ** (1.0 / 3.0)

    # ----------------------------------------------------------------- checks and output
    def boundary_errors(self, evaluate: Callable[[FloatArray], Any]) -> dict[str, float]:
        """Every boundary condition as ``lhs - rhs`` on an evaluator [-]."""
        ends = evaluate(np.array([0.0, 1.0]))
        return {
            "sigma_rtheta(0) + tan(delta) [eqn-nd_bc2_cyl]": float(
                ends.sigma_yx[0] + self.tan_delta
            ),
            "u(0) + 1 + eps K omega(0) [eqn-nd_bc2_cyl]": float(
                ends.u[0] + 1.0 + self.eps * self.wall.K * ends.omega[0]
            ),
            "sigma_rtheta(1) - sigma_thetar(1) [eqn-nd_bc1_cyl]": float(
                ends.sigma_yx[1] - ends.sigma_xy[1]
            ),
            "u(1) [eqn-nd_bc1_cyl]": float(ends.u[1]),
        }

    def layer_width(self) -> float:
        const = self.slip_constants
        if const.k > 0.0:
            return min(1.0, 24.0 * self.eps / const.k)
        return min(1.0, 6.0 * self.eps ** (2.0 / 3.0) * self.inner_scale())

    def output_grid(self, n: int) -> FloatArray:
        w = self.layer_width()
        w_m = max(w, min(1.0, 10.0 * self.eps * self.material.alpha))
        return layered_grid(n, [(0.0, w), (1.0, w_m)])

    def describe(self) -> str:
        return (
            f"Couette flow: phi = {self.material.phi:g} deg, L = {self.material.L:g}, "
            f"A = {self.material.A:g}, eps = {self.eps:g}, Ri = {self.Ri:g}; "
            f"walls {self.wall.describe()}"
        )

    def parameters(self) -> dict[str, Any]:
        return {
            "geometry": "couette",
            "rheology": "cosserat",
            "phi": self.material.phi,
            "L": self.material.L,
            "A": self.material.A,
            "eps": self.eps,
            "Ri": self.Ri,
            "delta": self.wall.delta,
            "tan_delta": self.tan_delta,
            "K": self.wall.K,
        }
