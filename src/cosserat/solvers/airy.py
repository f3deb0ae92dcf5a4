"""The Airy-function inner layer of fully rough walls (Appendix, ``docs/derivation_plane.md``).

At a fully rough slipping wall m0 = 0, the outer couple stress vanishes like sqrt(distance),
and the expansion fails in a layer of thickness eps^(2/3): there the rescaled couple stress
obeys the Riccati equation ``eqn-asymp_eta_inner``, solved by m_hat = -Ai'/Ai, and

    omega = omega_1 (Ai(x)/Ai(0))^2,    u = u_w (1 - I(x)/I(inf))      (eqn-vel_g_unif),

with x the inner variable and ``I(x) = Ai(0)^-2 int_0^x Ai(z)^2 dz`` (``eqn-defn_I``).
Since d/dz [z Ai^2 - Ai'^2] = Ai^2, the integral is elementary::

    I(x) = (x Ai(x)^2 - Ai'(x)^2 + Ai'(0)^2) / Ai(0)^2,   I(inf) = (Ai'(0)/Ai(0))^2,
    1 - I(x)/I(inf) = (Ai'(x)^2 - x Ai(x)^2) / Ai'(0)^2,

evaluated with the exponentially scaled Airy functions so that nothing underflows.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.optimize import brentq
from scipy.special import airy, airye

from ..constitutive import FloatArray
from ..errors import MethodNotAvailableError
from ..problems.couette import CouetteFlow
from ..problems.plane import PlaneShear
from ..profile import Fields, Profile

_AI0, _AIP0, _, _ = (float(v) for v in airy(0.0))
I_INFINITY = (_AIP0 / _AI0) ** 2
"""I(inf) of ``eqn-defn_I`` = (Ai'(0)/Ai(0))^2 [-]."""


def _log_scale(x: FloatArray) -> FloatArray:
    """-2 zeta(x) = -(4/3) x^(3/2): log of the scaling of Ai^2 for x >= 0."""
    return -(4.0 / 3.0) * np.power(np.maximum(x, 0.0), 1.5)


def velocity_fraction(x: FloatArray) -> FloatArray:
    """1 - I(x)/I(inf) = (Ai'(x)^2 - x Ai(x)^2)/Ai'(0)^2, for x >= 0 [-]."""
    x = np.asarray(x, dtype=float)
    eai, eaip, _, _ = airye(x)
    with np.errstate(under="ignore"):
        return (eaip**2 - x * eai**2) / _AIP0**2 * np.exp(_log_scale(x))


def spin_fraction(x: FloatArray) -> FloatArray:
    """(Ai(x)/Ai(0))^2, for x >= 0 [-]."""
    x = np.asarray(x, dtype=float)
    eai = airye(x)[0]
    with np.errstate(under="ignore"):
        return (eai / _AI0) ** 2 * np.exp(_log_scale(x))


def inner_couple_stress(x: FloatArray) -> FloatArray:
    """m_hat = -Ai'(x)/Ai(x), the decaying solution of ``eqn-asymp_eta_inner`` [-]."""
    eai, eaip, _, _ = airye(np.asarray(x, dtype=float))
    return -eaip / eai


def xi_hat_at_fraction(f: float) -> float:
    """The inner coordinate at which u/u_w = f (1.2748 for f = 0.05; paper: 1.275) [-]."""
    if not 0.0 < f < 1.0:
        raise ValueError(f"f must satisfy 0 < f < 1; got {f:g}")
    hi = 1.0
    while velocity_fraction(np.array(hi)) > f:
        hi *= 2.0
    return float(
        brentq(lambda x: float(velocity_fraction(np.array(x))) - f, 0.0, hi, xtol=1e-15, rtol=1e-15)
    )


def airy_layer(
    x_hat: FloatArray, *, eps: float, scale: float, u_wall: float, slip_sign: float
) -> tuple[FloatArray, FloatArray]:
    """(u, omega) of the Airy layer with u -> 0 far from the wall (``eqn-vel_g_unif``,
    ``eqn-asymp_soln_vels_g__fr_consts``, ``eqn-asymp_soln_vels_cyl_fr``) [-].

    ``omega_1 = -s u_w eps^(-2/3) / (2 scale I(inf))`` at leading order (the wall slip is
    O(eps^(1/3)) and dropped), ``u = u_w (1 - I/I(inf))``.
    """
    omega_1 = -slip_sign * u_wall * eps ** (-2.0 / 3.0) / (2.0 * scale * I_INFINITY)
    return u_wall * velocity_fraction(x_hat), omega_1 * spin_fraction(x_hat)


def solve_plane_fully_rough(
    problem: PlaneShear, *, points: int | None, xi: FloatArray | None, check: bool
) -> Profile:
    """Plane shear under gravity, fully rough upper wall (``eqn-eta_g_unif``,
    ``eqn-asymp_soln_vels_g_fr``, ``eqn-asymp_soln_vels_g__fr_consts``, ``eqn-vel_g_unif``)."""
    from ..analysis.laws import asymptotic_thickness
    from .asymptotic import _profile, require_valid

    eps, mat = problem.eps, problem.material
    B_nu = problem.B * problem.nu
    if B_nu < 10.0 * eps:
        raise MethodNotAvailableError(
            f"the Airy inner layer needs B nu >> eps (the paper: not valid when B nu ~ eps); "
            f"got B nu = {B_nu:g}, eps = {eps:g}: use method='numerical'"
        )
    require_valid(problem, eps * asymptotic_thickness(problem))
    a = 0.5 * problem.tan_delta_upper
    scale = problem.inner_scale()
    inner_amp = (4.0 * a * mat.alpha * B_nu * mat.c2) ** (1.0 / 3.0) * eps ** (1.0 / 3.0)
    sigma_yx = problem.sigma_yx

    def evaluate(x: FloatArray) -> Fields:
        x = np.asarray(x, dtype=float)
        depth = 1.0 - x
        xh = depth * eps ** (-2.0 / 3.0) / scale
        sc = problem.sigma_c(x)
        outer = math.sqrt(mat.c2) * np.sqrt(np.maximum(sc**2 - 1.0, 0.0))
        common = np.sqrt(2.0 * B_nu * mat.c2 * depth)
        m = outer + inner_amp * inner_couple_stress(xh) - common
        u, omega = airy_layer(xh, eps=eps, scale=scale, u_wall=1.0, slip_sign=1.0)
        return Fields(
            u=u,
            omega=omega,
            m=m,
            sigma_xy=np.full_like(x, sigma_yx),
            sigma_yx=np.full_like(x, sigma_yx),
            sigma_yy=sc,
            du_dxi=-2.0 * omega,
            kappa=np.zeros_like(x),
        )

    return _profile(
        problem,
        problem.formulation(),
        evaluate,
        points=points,
        xi=xi,
        reference_velocity=0.0,
        check=check,
        message="Airy inner layer (eqn-eta_g_unif, eqn-vel_g_unif) at leading order in eps",
    )


def solve_couette_fully_rough(
    problem: CouetteFlow, *, points: int | None, xi: FloatArray | None, check: bool
) -> Profile:
    """Couette flow, fully rough cylinders: the Airy inner layer at the inner cylinder with
    x_hat = xi eps^(-2/3) (L^2 Ri/4)^(-1/3) and the composite couple stress of the Appendix."""
    from ..analysis.laws import asymptotic_thickness
    from .asymptotic import _profile, couette_leading_order_fields, require_valid

    require_valid(problem, problem.eps * asymptotic_thickness(problem))
    eps, Ri = problem.eps, problem.Ri
    scale = problem.inner_scale()
    d = problem.tan_delta / math.sqrt(2.0 * (problem.material.A + 1.0))
    inner_amp = eps ** (1.0 / 3.0) * d * (4.0 * problem.material.L / Ri) ** (1.0 / 3.0)

    def evaluate(x: FloatArray) -> Fields:
        x = np.asarray(x, dtype=float)
        xh = x * eps ** (-2.0 / 3.0) / scale
        # composite: outer + inner - common; the inner m_hat = Ai'/Ai solves dm/dx + m^2 = x
        m = (
            problem.outer_couple_stress(x)
            - inner_amp * inner_couple_stress(xh)
            + d * np.sqrt(4.0 * x / Ri)
        )
        u, omega = airy_layer(xh, eps=eps, scale=scale, u_wall=-1.0, slip_sign=-1.0)
        return couette_leading_order_fields(problem, x, m, u, omega)

    form = problem.formulation(float(evaluate(np.array([0.0])).m[0]))
    return _profile(
        problem,
        form,
        evaluate,
        points=points,
        xi=xi,
        reference_velocity=0.0,
        check=check,
        message="Airy inner layer at the inner cylinder (eqn-asymp_soln_vels_cyl_fr)",
    )
