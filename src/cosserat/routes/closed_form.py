"""Closed-form route: plane shear without gravity (``docs/derivation_plane.md``).

* Fully rough walls between identical walls: m = 0 and uniform shear (``vel_g0``,
  ``omega1_g0``).
* Identical walls, not fully rough: m from ``eqn-eta_soln_g0`` (inverted for psi with a
  bracketed Newton iteration), and - derived here, not in the paper - the spin
  ``omega = omega_c (b - a)/(b cos psi - a)`` and the velocity
  ``u - u_c = -2 a eps alpha m omega/(b^2 - a^2) - omega_c Gamma [(xi - 1/2) - eps alpha psi]``,
  ``Gamma = ((1+A) b^2 + (1-A) a^2)/(a (a + b))``.
* Layer at the upper wall (rougher lower wall): m = m0 and ``eqn-soln_aw_vels``,
  ``eqn-omega1_g0aw``; the fully rough limit k -> 0 is taken analytically.
* Layer at the lower wall (rougher upper wall): the mirror image of the previous case.

Everything is evaluated in logarithms where it would over- or underflow: at eps = 1e-6 the
spin varies by exp(-k/(2 eps)) ~ exp(-85000) across the half gap.
"""

from __future__ import annotations

import numpy as np

from ..errors import ConvergenceError, MethodNotAvailableError
from ..model import PlaneShearCase, Problem
from ..model.constitutive import FloatArray
from ..model.rheologies.base import equations_of
from ..model.rheologies.cosserat import CosseratPlane
from ..results.profile import Fields, Profile
from .assemble import make_profile


def solve_plane(
    problem: Problem,
    *,
    points: int | None = None,
    xi: FloatArray | None = None,
    check: bool = True,
) -> Profile:
    """The closed-form profile of the Cosserat model in plane shear without gravity."""
    eq = equations_of(problem, CosseratPlane)
    if eq.B != 0.0:
        raise MethodNotAvailableError(
            "no closed form for plane shear under gravity (B > 0): use method='numerical' "
            "or method='asymptotic'"
        )
    if eq.m_fixed_wall is not None:
        raise MethodNotAvailableError(
            "no closed form with a prescribed m at the fixed wall (m_fixed_wall): "
            "use method='numerical'"
        )
    case = eq.case
    if case is PlaneShearCase.SYMMETRIC:
        evaluate, reference, message = _symmetric(eq)
    elif case is PlaneShearCase.UPPER:
        evaluate = _layer_at_upper(eq)
        reference, message = 0.0, "eqn-soln_aw_vels / eqn-omega1_g0aw (m = m0)"
    else:
        upper_eval = _layer_at_upper(eq.mirrored().equations)

        def evaluate(x: FloatArray) -> Fields:
            f = upper_eval(1.0 - np.asarray(x, dtype=float))
            return f._replace(u=1.0 - f.u, m=-f.m)

        reference, message = 1.0, "mirror image of eqn-soln_aw_vels (layer at the lower wall)"
    return make_profile(
        problem,
        eq.formulation(),
        evaluate,
        method="closed-form",
        points=points,
        xi=xi,
        reference_velocity=reference,
        message=message,
        check=check,
    )


def _uniform_fields(
    x: FloatArray,
    m: FloatArray,
    u: FloatArray,
    omega: FloatArray,
    sigma_yx: float,
    sigma_xy: FloatArray,
    du: FloatArray,
) -> Fields:
    return Fields(
        u=u,
        omega=omega,
        m=m,
        sigma_xy=sigma_xy,
        sigma_yx=np.full_like(x, sigma_yx),
        sigma_yy=np.ones_like(x),
        du_dxi=du,
        kappa=np.zeros_like(x),
    )


def _one_minus_exp_ratio(z: FloatArray | float) -> FloatArray:
    """(1 - exp(-z))/z, with its limit 1 at z = 0."""
    z = np.asarray(z, dtype=float)
    small = z < 1e-8
    safe = np.where(small, 1.0, z)
    return np.where(small, 1.0 - 0.5 * z, -np.expm1(-safe) / safe)


def _layer_at_upper(problem: CosseratPlane):
    """``eqn-soln_aw_vels``: m = m0, omega = omega_1 exp(-k(1-xi)/eps), no slip at xi = 0."""
    eps, K = problem.eps, problem.upper.K
    tan_d = problem.tan_delta_upper
    const = problem.slip_constants
    k = const.k
    # (eps/k)(1 - exp(-k xi/eps)) = xi * (1 - e^{-z})/z with z = k xi/eps (-> xi as k -> 0)
    omega_1 = -1.0 / (2.0 * _one_minus_exp_ratio(k / eps) + eps * K)

    def evaluate(x: FloatArray) -> Fields:
        x = np.asarray(x, dtype=float)
        with np.errstate(under="ignore"):
            decay = np.exp(-k * (1.0 - x) / eps)
        omega = omega_1 * decay
        u = -2.0 * omega_1 * decay * x * _one_minus_exp_ratio(k * x / eps)
        return _uniform_fields(
            x, np.full_like(x, const.m0), u, omega, -tan_d, np.full_like(x, -tan_d), -2.0 * omega
        )

    return evaluate


def _symmetric(problem: CosseratPlane):
    """Identical walls without gravity: m(1/2) = 0, both walls slip."""
    eps, mat = problem.eps, problem.material
    A, ea = mat.A, eps * mat.alpha
    K_up, K_low = problem.upper.K, problem.lower_wall.K
    tan_d = problem.tan_delta_upper
    a, b, m0, _ = problem.slip_constants

    if m0 == 0.0:  # fully rough: vel_g0, omega1_g0 (K_up = K_low gives -1/(2 + 2 eps K))
        omega_1 = -1.0 / (2.0 + eps * (K_up + K_low))
        u_c = 0.5 * (1.0 + eps * (K_up - K_low) * omega_1)

        def evaluate_rough(x: FloatArray) -> Fields:
            x = np.asarray(x, dtype=float)
            omega = np.full_like(x, omega_1)
            u = u_c - 2.0 * omega_1 * (x - 0.5)
            return _uniform_fields(
                x, np.zeros_like(x), u, omega, -tan_d, np.full_like(x, -tan_d), -2.0 * omega
            )

        return evaluate_rough, u_c, "vel_g0 / omega1_g0 (fully rough: m = 0, uniform shear)"

    c = np.sqrt((b - a) / (b + a))
    gamma = ((1.0 + A) * b * b + (1.0 - A) * a * a) / (a * (a + b))
    ln_b_minus_a = np.log(b - a)

    def half(x: FloatArray) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray]:
        """On 1/2 <= x <= 1: m, psi, ln(b cos psi - a) and the scaled velocity part."""
        X = (x - 0.5) / ea
        y = _solve_log_gap(X, c, m0 / a)
        s = np.exp(y)
        t = c - s
        psi = 2.0 * np.arctan(t)
        m = 2.0 * b * t / (1.0 + t * t)
        ln_d = np.log(b + a) + y + np.log(2.0 * c - s) - np.log1p(t * t)
        return m, psi, ln_d, x - 0.5 - ea * psi

    _, _, ln_d1, lin_1 = half(np.array([1.0]))
    # U = (u - u_c)/omega_1 at the wall; omega/omega_1 = exp(ln_d1 - ln_d).
    m_1 = half(np.array([1.0]))[0]
    ratio_c = np.exp(ln_d1 - ln_b_minus_a)  # omega_c / omega_1
    U_1 = float((-2.0 * a * ea * m_1 / m0**2 - ratio_c * gamma * lin_1)[0])
    # u(1) - u(0) = 2 omega_1 U_1 = 1 + eps (K_up + K_low) omega_1; 2 u_c = 1 + eps(K_up-K_low)w1
    omega_1 = 1.0 / (2.0 * U_1 - eps * (K_up + K_low))
    u_c = 0.5 * (1.0 + eps * (K_up - K_low) * omega_1)

    def evaluate(x: FloatArray) -> Fields:
        x = np.asarray(x, dtype=float)
        low = x < 0.5
        m, psi, ln_d, lin = half(np.where(low, 1.0 - x, x))
        with np.errstate(under="ignore"):
            omega = omega_1 * np.exp(ln_d1[0] - ln_d)
        u_rel = -2.0 * a * ea * m * omega / m0**2 - omega_1 * ratio_c[0] * gamma * lin
        u = u_c + np.where(low, -u_rel, u_rel)
        # sxy + A syx = -2(A+1) b cos(psi) (eqn-nd_sigxy with S = 4(A+1)^2 (b^2 - m^2))
        sigma_xy = A * tan_d - 2.0 * (A + 1.0) * b * np.cos(psi)
        du = -omega * ((1.0 + A) + (1.0 - A) * a / (b * np.cos(psi)))
        return _uniform_fields(x, np.where(low, -m, m), u, omega, -tan_d, sigma_xy, du)

    return evaluate, u_c, "eqn-eta_soln_g0 with the spin and velocity of docs/derivation_plane.md"


def _solve_log_gap(X: FloatArray, c: float, r: float) -> FloatArray:
    """Invert ``eqn-eta_soln_g0`` for y = ln(c - tan(psi/2)) at X = (xi - 1/2)/(alpha eps).

    ``g(y) = 2 atan(c - e^y) + (ln(2c - e^y) - y)/r - X = 0`` with r = m0/a; g decreases from
    +inf (y -> -inf) to -X (y = ln c), so a bracketed Newton iteration converges from the
    large-X asymptote ``y0 = ln(2c) + r (2 atan c - X)``. Working with y keeps full relative
    precision in c - tan(psi/2), which underflows for X >~ 700/r.
    """
    X = np.asarray(X, dtype=float)
    hi = np.full_like(X, np.log(c))
    y0 = np.log(2.0 * c) + r * (2.0 * np.arctan(c) - X)
    lo = np.minimum(y0 - 2.0 * c * r - 1.0, hi - 1.0)
    y = np.clip(y0, lo, hi)

    def g_and_slope(y: FloatArray) -> tuple[FloatArray, FloatArray, FloatArray]:
        s = np.exp(y)
        t = c - s
        log_term = np.log(2.0 * c - s)
        g = 2.0 * np.arctan(t) + (log_term - y) / r - X
        slope = -2.0 * s / (1.0 + t * t) - (s / (2.0 * c - s) + 1.0) / r
        # size of the terms of g, for its round-off: t = c - s cancels, so count c + s
        size = 2.0 * (c + s) + (np.abs(log_term) + np.abs(y)) / r + X
        return g, slope, size

    converged = np.zeros(X.shape, dtype=bool)
    for _ in range(200):
        g, slope, size = g_and_slope(y)
        step = y - g / slope
        # |g| at the round-off level of its terms, a bracket a few ulps wide, or a Newton
        # step that no longer moves y by more than a few ulps
        converged |= (
            (np.abs(g) <= 4e-16 * size)
            | (hi - lo <= 4.0 * np.spacing(np.abs(y)))
            | (np.abs(step - y) <= 4.0 * np.spacing(np.abs(y)))
        )
        if np.all(converged):
            return y
        lo = np.where(g > 0.0, y, lo)
        hi = np.where(g <= 0.0, y, hi)
        inside = (step >= lo) & (step <= hi)
        y = np.where(converged, y, np.where(inside, step, 0.5 * (lo + hi)))
    raise ConvergenceError("closed form: inversion of eqn-eta_soln_g0 did not converge")
