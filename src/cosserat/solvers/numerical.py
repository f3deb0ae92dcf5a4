"""Numerical route: every problem, every eps in (0, 0.5] (engine in :mod:`.engine`)."""

from __future__ import annotations

import numpy as np

from ..constitutive import FloatArray
from ..problems.plane import PlaneShear, PlaneShearCase
from ..profile import Fields, Profile
from .assemble import fields_from_state, make_profile
from .engine import integrate_couple_stress, integrate_spin, solve_linear_2x2

DEFAULT_RTOL = 1e-8


def _tolerances(rtol: float, atol: float | None) -> tuple[float, float]:
    if not 1e-13 <= rtol <= 1e-2:
        raise ValueError(f"rtol must satisfy 1e-13 <= rtol <= 1e-2; got {rtol:g}")
    return rtol, (rtol * 1e-2 if atol is None else atol)


def solve_plane(
    problem: PlaneShear,
    *,
    rtol: float = DEFAULT_RTOL,
    atol: float | None = None,
    points: int | None = None,
    xi: FloatArray | None = None,
    check: bool = True,
) -> Profile:
    """Plane shear, any case (``docs/numerics.md``).

    The couple stress is integrated from the non-slipping wall (or from the centre, where
    m(1/2) = 0 in the symmetric case) to the slipping wall; spin and velocity from the slipping
    wall back.
    """
    rtol, atol = _tolerances(rtol, atol)
    form = problem.formulation()
    eps = problem.eps
    if problem.case is PlaneShearCase.SYMMETRIC:
        cs = integrate_couple_stress(form, 0.5, 1.0, 0.0, rtol, atol)
        sq = integrate_spin(form, cs, 1.0, 0.5, rtol, atol)
        P_c = float(sq(np.array([0.5]))[1][0])
        K_up, K_low = problem.upper.K, problem.lower_wall.K
        # u(xi) = u_s - w_s P(xi) on the upper half, mirrored (u - u_c odd, omega even):
        #   u_s = 1 + eps K_up w_s  (eqn-nd_bc3u);  u(0) = 2 u_c - u_s = -eps K_low w_s.
        u_s, w_s = solve_linear_2x2(
            [[1.0, -eps * K_up], [1.0, eps * K_low - 2.0 * P_c]], [1.0, 0.0], "symmetric plane"
        )
        u_c = u_s - w_s * P_c

        def upper_half(x: FloatArray) -> Fields:
            m = cs(x)
            ell, P = sq(x)
            with np.errstate(under="ignore"):
                w = w_s * np.exp(ell)
            return fields_from_state(form, x, m, u_s - w_s * P, w)

        def evaluate(x: FloatArray) -> Fields:
            x = np.asarray(x, dtype=float)
            f = upper_half(np.where(x >= 0.5, x, 1.0 - x))
            low = x < 0.5
            return f._replace(u=np.where(low, 2.0 * u_c - f.u, f.u), m=np.where(low, -f.m, f.m))

        reference = u_c
    else:
        xs, xn = problem.slip_wall, problem.fixed_wall
        assert xn is not None
        cs = integrate_couple_stress(form, xn, xs, problem.m_at_fixed_wall, rtol, atol)
        sq = integrate_spin(form, cs, xs, xn, rtol, atol)
        P_n = float(sq(np.array([xn]))[1][0])
        K = problem.slipping.K
        # u = u_s - w_s P(xi):  u(xn) = wall velocity (no slip);
        #   u_s = u_wall(xs) + s eps K w_s  (eqn-nd_bc3u / eqn-nd_bc3l).
        u_s, w_s = solve_linear_2x2(
            [[1.0, -P_n], [1.0, -problem.slip_sign(xs) * eps * K]],
            [problem.wall_velocity(xn), problem.wall_velocity(xs)],
            "plane",
        )

        def evaluate(x: FloatArray) -> Fields:
            x = np.asarray(x, dtype=float)
            ell, P = sq(x)
            with np.errstate(under="ignore"):
                w = w_s * np.exp(ell)
            return fields_from_state(form, x, cs(x), u_s - w_s * P, w)

        reference = problem.reference_velocity

    stats = {
        "couple_stress_nfev": cs.nfev,
        "couple_stress_steps": cs.steps,
        "spin_nfev": sq.nfev,
        "spin_cutoff_xi": sq.xi_cut,
    }
    return make_profile(
        problem,
        form,
        evaluate,
        method="numerical",
        points=points,
        xi=xi,
        reference_velocity=reference,
        rtol=rtol,
        atol=atol,
        message="Radau IIA couple stress (stable direction) + DOP853 spin/velocity quadrature",
        stats=stats,
        check=check,
    )
