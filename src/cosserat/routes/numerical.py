"""Numerical route: every problem, every eps in (0, 0.5] (engine in :mod:`.engine`)."""

from __future__ import annotations

from typing import Any

import numpy as np
from scipy.optimize import brentq

from ..errors import ConvergenceError, NoSolutionError, ParameterError
from ..model.constitutive import FloatArray
from ..model.couette import CouetteFlow
from ..model.plane import PlaneShear, PlaneShearCase
from ..results.profile import Fields, Profile
from .assemble import fields_from_state, make_profile
from .engine import (
    integrate_couple_stress,
    integrate_spin,
    symmetric_wall_constants,
    wall_constants_from_conditions,
)

DEFAULT_RTOL = 1e-8


def _tolerances(rtol: float, atol: float | None) -> tuple[float, float]:
    if not 1e-13 <= rtol <= 1e-2:
        raise ParameterError(f"rtol must satisfy 1e-13 <= rtol <= 1e-2; got {rtol:g}")
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
        u_s, w_s, u_c = symmetric_wall_constants(P_c, eps, K_up, K_low)

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

        def velocity(x: FloatArray) -> FloatArray:
            x = np.asarray(x, dtype=float)
            upper = u_s - w_s * sq(np.where(x >= 0.5, x, 1.0 - x))[1]
            return np.where(x < 0.5, 2.0 * u_c - upper, upper)

        reference = u_c
    else:
        xs, xn = problem.slip_wall, problem.fixed_wall
        assert xn is not None
        cs = integrate_couple_stress(form, xn, xs, problem.m_at_fixed_wall, rtol, atol)
        sq = integrate_spin(form, cs, xs, xn, rtol, atol)
        P_n = float(sq(np.array([xn]))[1][0])
        K = problem.slipping.K
        # u = u_s - w_s P(xi): no slip at xn; u_s = u_wall + s eps K w_s (eqn-nd_bc3u/3l)
        u_s, w_s = wall_constants_from_conditions(
            h_slip=1.0,
            kappa_slip=0.0,
            P_fixed=P_n,
            h_fixed=1.0,
            u_fixed=problem.wall_velocity(xn),
            u_wall_slip=problem.wall_velocity(xs),
            slip_sign=problem.slip_sign(xs),
            eps_K=eps * K,
        )

        def evaluate(x: FloatArray) -> Fields:
            x = np.asarray(x, dtype=float)
            ell, P = sq(x)
            with np.errstate(under="ignore"):
                w = w_s * np.exp(ell)
            return fields_from_state(form, x, cs(x), u_s - w_s * P, w)

        def velocity(x: FloatArray) -> FloatArray:
            return u_s - w_s * sq(np.asarray(x, dtype=float))[1]

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
        velocity=velocity,
    )


def solve_couette(
    problem: CouetteFlow,
    *,
    rtol: float = DEFAULT_RTOL,
    atol: float | None = None,
    points: int | None = None,
    xi: FloatArray | None = None,
    check: bool = True,
    m_inner_guess: float | None = None,
) -> Profile:
    """Couette flow: the couple stress from the outer cylinder inwards for a trial m(0), with
    m(0) fixed by a secant iteration on ``m(0; mu) - mu`` (``eqn-nd_shsts_cyl``); then spin and
    velocity from the inner cylinder outwards. ``m_inner_guess`` (e.g. from a neighbouring
    eps in a sweep) replaces the leading-order starting value."""
    rtol, atol = _tolerances(rtol, atol)
    mu, cs, form, iterations = _couette_shooting(problem, rtol, atol, m_inner_guess)
    sq = integrate_spin(form, cs, 0.0, 1.0, rtol, atol)
    P_1 = float(sq(np.array([1.0]))[1][0])
    Ri, eps, K = problem.Ri, problem.eps, problem.wall.K
    u_s, w_s = wall_constants_from_conditions(
        h_slip=1.0 / Ri,
        kappa_slip=1.0 / Ri,
        P_fixed=P_1,
        h_fixed=1.0 / (Ri + 1.0),
        u_fixed=problem.wall_velocity(1.0),
        u_wall_slip=problem.wall_velocity(0.0),
        slip_sign=problem.slip_sign(0.0),
        eps_K=eps * K,
    )

    def evaluate(x: FloatArray) -> Fields:
        x = np.asarray(x, dtype=float)
        ell, P = sq(x)
        with np.errstate(under="ignore"):
            w = w_s * np.exp(ell)
        u = (Ri + x) * (u_s / Ri - w_s * P)
        return fields_from_state(form, x, cs(x), u, w)

    def velocity(x: FloatArray) -> FloatArray:
        x = np.asarray(x, dtype=float)
        return (Ri + x) * (u_s / Ri - w_s * sq(x)[1])

    stats = {
        "couple_stress_nfev": cs.nfev,
        "couple_stress_steps": cs.steps,
        "spin_nfev": sq.nfev,
        "spin_cutoff_xi": sq.xi_cut,
        "m_inner": mu,
        "shooting_iterations": iterations,
    }
    return make_profile(
        problem,
        form,
        evaluate,
        method="numerical",
        points=points,
        xi=xi,
        reference_velocity=problem.reference_velocity,
        rtol=rtol,
        atol=atol,
        message="secant on m(0); Radau IIA couple stress (outer to inner) + DOP853 spin",
        stats=stats,
        check=check,
        velocity=velocity,
    )


def _couette_shooting(  # type: ignore[no-untyped-def]
    problem: CouetteFlow, rtol: float, atol: float, guess: float | None = None
):
    """Find mu = m(0) with m(0; mu) = mu. Returns (mu, couple stress, formulation, iterations).

    F(mu) = m(0; mu) - mu decreases with mu. mu enters only through s_rt, with weight
    2(A+1) eps alpha Ri/(Ri + xi)^2, so F is nearly linear and a secant iteration from the
    leading-order value m^(0)(0) usually converges in a few steps. Trials whose couple stress
    leaves the real domain (``NoSolutionError``) bound the admissible mu; if F keeps its sign
    all the way to such a bound, no mu satisfies the conditions and the model has no real
    solution, which is reported as such.
    """
    cache: dict[float, tuple[float, Any, Any] | None] = {}

    def shoot(mu: float) -> float | None:
        if mu not in cache:
            form = problem.formulation(mu)
            try:
                cs = integrate_couple_stress(
                    form,
                    1.0,
                    0.0,
                    problem.outer_wall_couple_stress(mu),
                    rtol * 0.1,
                    atol * 0.1,
                )
            except NoSolutionError:
                cache[mu] = None
            else:
                cache[mu] = (float(cs(np.array([0.0]))[0]) - mu, cs, form)
        hit = cache[mu]
        return None if hit is None else hit[0]

    mu0 = float(problem.outer_couple_stress(np.array([0.0]))[0]) if guess is None else guess
    tol = max(atol, rtol * abs(mu0))

    def done(mu: float):  # type: ignore[no-untyped-def]
        _, cs, form = cache[mu]  # type: ignore[misc]
        return mu, cs, form, len(cache)

    # 1. secant from the leading-order value
    g0 = shoot(mu0)
    if g0 is not None:
        mu1 = mu0 + g0
        for _ in range(12):
            if abs(g0) <= tol:  # type: ignore[arg-type]
                return done(mu0)
            g1 = shoot(mu1)
            if g1 is None:
                break
            if abs(g1) <= tol:
                return done(mu1)
            slope = (g1 - g0) / (mu1 - mu0) if mu1 != mu0 else -1.0  # type: ignore[operator]
            mu0, g0, mu1 = mu1, g1, mu1 - g1 / (slope if slope < 0.0 else -1.0)

    # 2. bracket, using that F decreases and failures lie below the admissible mu
    bound = problem.slip_constants.b
    ok = {mu: v[0] for mu, v in cache.items() if v is not None}
    if not ok:
        for trial in np.linspace(-2.0 * bound, bound, 13):
            if (g := shoot(float(trial))) is not None:
                ok[float(trial)] = g
                break
        else:
            raise NoSolutionError(
                f"no real solution for {problem.describe()}: for every trial couple stress at "
                f"the inner cylinder, m(0) in [{-2 * bound:.3g}, {bound:.3g}], the couple-stress "
                f"balance integrated from the outer cylinder leaves the yield surface inside "
                f"the gap"
            )
    failed = [mu for mu, v in cache.items() if v is None]
    mu_s = min(ok, key=lambda m: abs(ok[m]))
    g_s = ok[mu_s]
    step = max(0.05 * bound, abs(g_s))
    # walk towards the root (up if F > 0) until F changes sign, doubling the step; once a
    # trial leaves the real domain, bisect between it and the last real trial instead
    up = 1.0 if g_s > 0.0 else -1.0
    beyond = [m for m in failed if up * (m - mu_s) > 0.0]
    mu_f = min(beyond, key=lambda m: abs(m - mu_s)) if beyond else None
    for _ in range(200):  # doubling, then bisection to tol: ~60 trials at most in practice
        trial = mu_s + up * step if mu_f is None else 0.5 * (mu_s + mu_f)
        g_t = shoot(trial)
        if g_t is None:
            mu_f = trial
        elif up * g_t <= 0.0:
            lo, hi = sorted((mu_s, trial))
            break
        else:
            mu_s, step = trial, 2 * step
        if mu_f is not None and abs(mu_f - mu_s) < tol:
            raise NoSolutionError(
                f"no real solution for {problem.describe()}: the couple stress at the inner "
                f"cylinder would have to be {'above' if up > 0 else 'below'} m(0) = {mu_s:.6g}, "
                f"where the couple-stress balance integrated from the outer cylinder already "
                f"leaves the yield surface inside the gap"
            )
    else:
        raise ConvergenceError(f"Couette: cannot bracket m(0) for {problem.describe()}")
    root = brentq(lambda mu: float(shoot(mu)), lo, hi, xtol=tol, rtol=4.0 * np.finfo(float).eps)  # type: ignore[arg-type]
    shoot(root)
    return done(root)
