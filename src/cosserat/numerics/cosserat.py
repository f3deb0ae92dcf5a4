"""Compiled kernels of the frictional Cosserat model on its two cells (plane shear, Couette).

One path for every numerical computation: a profile, a thickness curve and a sweep all call
:func:`solve_case` (from Python for one problem; :func:`solve_batch` for many).
It does what ``docs/numerics.md`` describes:

1. **Couple stress** (``eqn-nd_zangmom``, ``eqn-nd_zangmom_cyl``), integrated with Radau IIA
   (:func:`~cosserat.numerics.radau_scalar.radau5_scalar`) from the wall that does not slip
   (the centre in the symmetric case) to the slipping wall, its stable direction, stopped by
   an event where the yield radicand S of ``eqn-nd_sigxy`` reaches zero (no real solution).
   In Couette flow the inner-wall couple stress mu = m(0) of ``eqn-nd_shsts_cyl`` is unknown:
   Newton's method finds the mu for which the integration returns m(0) = mu, each pass giving
   its derivative in mu by internal differentiation (:func:`couette_newton`); a secant
   iteration, then a bracket and Brent's method, take over if Newton's method does not
   converge (:func:`couette_inner_couple_stress`).
2. **Spin and velocity**: ``l = ln(w / w_s)`` and ``P = int e^l G`` from the slipping wall
   inwards (the same integrator), stopped where e^l underflows.
3. **Velocity constants** (u_s, w_s) from the two linear velocity conditions, then the
   **thickness** Delta (``eqn-delta_defn``) by Brent's method on the dense output.

The problem arrives as a parameter vector (indices below, filled by
:func:`cosserat.routes.numerical.parameter_vector`); results leave as a status code and a
vector of scalars (indices ``I_*``), never as NaN in place of an answer. The equations are
those of :mod:`cosserat.model` (the constitutive ufuncs and the cells' statics), called here on
numbers.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from ..model.cells.plane import mean_stress
from ..model.constitutive import (
    RADICAND_ROUNDOFF,
    SQRT_S_FLOOR,
    k_radicand,
    k_spin_ratio,
    k_torque,
    k_torque_gradient,
    k_velocity_ratio,
)
from ..model.rheologies.cosserat.couette import (
    outer_wall_couple_stress,
    outer_wall_couple_stress_dm_inner,
    shear_stress,
    shear_stress_dm,
    shear_stress_dm_inner,
)
from .dop853 import dop853, dop853_eval1
from .radau import EVENT, MAX_STEPS, SUCCESS, dense_eval1
from .radau_scalar import radau5_scalar, sensitivity
from .roots import B as ROOT
from .roots import brackets, brent_accept, brent_next, brent_start

# ----------------------------------------------------------------- parameter vector
P_A = 0  # A of eqn-yc2 [-]
P_SIN_PHI = 1  # sin(phi) [-]
P_ALPHA = 2  # L / sqrt(2(A+1)) [-]
P_EPS = 3  # d_p / H [-]
P_GEOMETRY = 4  # PLANE or COUETTE
P_CASE = 5  # plane: SYMMETRIC, UPPER, LOWER (Couette: UPPER is unused, LOWER... see below)
P_SIGMA_YX = 6  # plane: the constant shear stress [-]
P_B_NU = 7  # plane: B nu [-]
P_TAN_DELTA = 8  # Couette: tan(delta) of the walls [-]
P_RI = 9  # Couette: R_i / H [-]
P_COUPLE = 10  # Couette: 2(A+1) eps alpha [-]
P_M_START = 11  # plane: m at the wall that does not slip (0 at the centre if symmetric) [-]
P_K_SLIP = 12  # slip coefficient K of the slipping wall [-]
P_K_OTHER = 13  # K of the other wall (symmetric case) [-]
P_M0 = 14  # m0 of eqn-a_b_def at the slipping wall (Couette: start of the m(0) search) [-]
P_B_BOUND = 15  # b of eqn-a_b_def at the slipping wall (Couette: scale of the search) [-]
P_MU_GUESS = 16  # Couette: a guess of m(0), or NaN for the leading-order value [-]
N_PARAMS = 17

PLANE = 0.0
COUETTE = 1.0
SYMMETRIC = 0.0  # no gravity, identical walls: both slip, m(1/2) = 0
UPPER = 1.0  # layer at the upper wall (which slips), lower wall fixed
LOWER = 2.0  # layer at the lower wall (which slips), upper wall fixed

# ----------------------------------------------------------------- status codes
OK = 0
NO_SOLUTION = 1  # the couple stress reaches the yield bound inside the gap (or no m(0))
STALLED = 2  # the integrator could not continue (step size underflow, Newton failure)
TOO_MANY_STEPS = 3  # the step budget ran out
SINGULAR_VELOCITY = 4  # the velocity conditions are singular
NO_BRACKET = 5  # Couette: no sign change of m(0; mu) - mu could be bracketed
AT_YIELD_EDGE = 6  # the bound was crossed by round-off (an equilibrium on the bound)

# ----------------------------------------------------------------- result vector
I_U_S = 0  # velocity at the slipping wall [-]
I_W_S = 1  # spin relative to rigid rotation at the slipping wall, w = omega + kappa u [-]
I_U_REF = 2  # u_0 of eqn-delta_defn [-]
I_DELTA = 3  # Delta [d_p], NaN only if DELTA_OK is 0 (see I_DELTA_OK)
I_DELTA_OK = 4  # 1 if the velocity falls to f of its wall value inside the gap
I_MU = 5  # Couette: m(0) [-]
I_XI_FAIL = 6  # where the couple stress left the real domain / the integration stalled [-]
I_M_FAIL = 7  # m there [-]
I_NFEV = 8  # right-hand side evaluations, both passes and every shooting trial
I_NSTEPS = 9  # accepted steps, both passes and every shooting trial
I_NLU = 10  # LU decompositions
I_ITERATIONS = 11  # Couette: trials of m(0)
I_XI_CUT = 12  # where the spin pass stopped (e^l underflows beyond) [-]
I_SINGULAR = 13  # 1 if the couple stress sits on the yield bound at the far end
I_WALL_SLIP = 14  # |u - u_wall| at the slipping wall [-]
I_WALL_OMEGA = 15  # omega at the slipping wall [-]
I_WALL_STRESS = 16  # sigma_yx (s_rt) at the slipping wall [-]
I_STEPS_COUPLE = 17  # accepted steps of the final couple-stress pass
I_STEPS_SPIN = 18  # accepted steps of the spin pass
N_INFO = 19

LOG_UNDERFLOW = -745.0  # e^l underflows below this: the spin is exactly 0 in double precision
SINGULAR_MARGIN = 1e-8  # S below this fraction of its scale at the far end: 1/sqrt singularity
SECANT_STEPS = 12
# Newton on m(0) (couette_newton): passes before giving up to the bracketing search, the
# tolerance of its first pass, the allowed second-order remainder of its last step (a fraction
# of the tolerance on m(0)), and |F''|/2 assumed before two passes have measured it
NEWTON_TRIALS = 8
NEWTON_LOOSE_RTOL = 1e-4
NEWTON_REMAINDER = 0.01
NEWTON_CURVATURE_PRIOR = 1.0
# floor on sqrt(S) in the Jacobian, relative to sigma_c sin(phi) (couple_jac)
JACOBIAN_ROOT_FLOOR = 1e-6
# a torque below this fraction of sigma_c sin(phi) is round-off (_crossed_by_round_off)
ROUND_OFF_TORQUE = 1e-10


# ----------------------------------------------------------------- the cells' statics
@njit(cache=True, nogil=True)
def _shear_stress(xi: float, m: float, p: np.ndarray, mu: float) -> float:
    if p[P_GEOMETRY] == PLANE:
        return p[P_SIGMA_YX]
    return shear_stress(xi, m, mu, p[P_TAN_DELTA], p[P_RI], p[P_COUPLE])


@njit(cache=True, nogil=True)
def _shear_stress_dm(xi: float, p: np.ndarray) -> float:
    if p[P_GEOMETRY] == PLANE:
        return 0.0
    return shear_stress_dm(xi, p[P_RI], p[P_COUPLE])


@njit(cache=True, nogil=True)
def _mean_stress(xi: float, p: np.ndarray) -> float:
    if p[P_GEOMETRY] == PLANE:
        return mean_stress(xi, p[P_B_NU])
    return 1.0  # sigma_c scales the Couette stresses (newdimless)


@njit(cache=True, nogil=True)
def _curvature(xi: float, p: np.ndarray) -> float:
    if p[P_GEOMETRY] == PLANE:
        return 0.0
    return 1.0 / (p[P_RI] + xi)


# ----------------------------------------------------------------- pass 1: couple stress
# args = (p, mu): the parameters and the trial m(0) (Couette; unused in plane shear)


@njit(cache=True, nogil=True)
def couple_rhs(xi, m, args):
    """dm/dxi = torque / (eps alpha) - kappa m (``formulation`` module docstring) [-]."""
    p, mu = args
    syx = _shear_stress(xi, m, p, mu)
    return (
        k_torque(syx, _mean_stress(xi, p), m, p[P_A], p[P_SIN_PHI]) / (p[P_EPS] * p[P_ALPHA])
        - _curvature(xi, p) * m
    )


@njit(cache=True, nogil=True)
def couple_jac(xi, m, args):
    """d(dm/dxi)/dm, analytic (:func:`k_torque_gradient`)."""
    p, mu = args
    syx = _shear_stress(xi, m, p, mu)
    sc = _mean_stress(xi, p)
    A, sp = p[P_A], p[P_SIN_PHI]
    # Near the yield bound dT/dm ~ 1/sqrt(S) is unbounded; Newton needs only an approximate
    # Jacobian, and a bounded one lets a step cross S = 0, where the event stops the pass.
    floor = JACOBIAN_ROOT_FLOOR * sc * sp
    dT_dm, dT_dsyx = k_torque_gradient(syx, sc, m, A, sp, floor)
    dT = dT_dm + dT_dsyx * _shear_stress_dm(xi, p)
    return dT / (p[P_EPS] * p[P_ALPHA]) - _curvature(xi, p)


@njit(cache=True, nogil=True)
def couple_derivatives(xi, m, args):
    """(d(dm/dxi)/dm, d(dm/dxi)/d m(0)) at fixed m: :func:`couple_jac`, and the dependence on
    the inner-wall couple stress m(0) through s_rt in Couette flow (0 in plane shear)."""
    p, mu = args
    syx = _shear_stress(xi, m, p, mu)
    sc = _mean_stress(xi, p)
    A, sp = p[P_A], p[P_SIN_PHI]
    floor = JACOBIAN_ROOT_FLOOR * sc * sp
    dT_dm, dT_dsyx = k_torque_gradient(syx, sc, m, A, sp, floor)
    dT = dT_dm + dT_dsyx * _shear_stress_dm(xi, p)
    ea = p[P_EPS] * p[P_ALPHA]
    dfdm = dT / ea - _curvature(xi, p)
    if p[P_GEOMETRY] == PLANE:
        return dfdm, 0.0
    return dfdm, dT_dsyx * shear_stress_dm_inner(xi, p[P_RI], p[P_COUPLE]) / ea


@njit(cache=True, nogil=True)
def _yield_margin(xi: float, m: float, p: np.ndarray, mu: float) -> float:
    """S over the size of its terms, plus the round-off allowance: <= 0 is no real solution."""
    sc = _mean_stress(xi, p)
    scale = 2.0 * (p[P_A] + 1.0) * (sc * p[P_SIN_PHI]) ** 2
    S = k_radicand(_shear_stress(xi, m, p, mu), sc, m, p[P_A], p[P_SIN_PHI])
    return S / scale + RADICAND_ROUNDOFF


@njit(cache=True, nogil=True)
def couple_event(xi, m, args):
    p, mu = args
    return _yield_margin(xi, m, p, mu)


# ----------------------------------------------------------------- pass 2: spin and velocity
# args = (p, mu, geometry of the pass [xi_slip, span, singular], the couple-stress solution)


@njit(cache=True, nogil=True)
def _map(tau: float, g: np.ndarray) -> tuple[float, float]:
    """xi(tau) and dxi/dtau: linear, or with a square-root Jacobian if the far end is singular."""
    if g[2] != 0.0:
        return g[0] + g[1] * (2.0 * tau - tau * tau), g[1] * 2.0 * (1.0 - tau)
    return g[0] + g[1] * tau, g[1]


@njit(cache=True, nogil=True)
def _spin_rates(xi: float, p: np.ndarray, mu: float, cs) -> tuple[float, float]:
    """(d ln w/dxi, G) = (-F2/(eps alpha) - kappa F1, F1 h) at xi (``formulation``)."""
    ts, hs, ys, Q = cs
    m = dense_eval1(ts, hs, ys, Q, xi, 0)
    syx = _shear_stress(xi, m, p, mu)
    sc = _mean_stress(xi, p)
    F1 = k_velocity_ratio(syx, sc, m, p[P_A], p[P_SIN_PHI])
    F2 = k_spin_ratio(syx, sc, m, p[P_A], p[P_SIN_PHI])
    kappa = _curvature(xi, p)
    h = 1.0 if p[P_GEOMETRY] == PLANE else kappa
    return -F2 / (p[P_EPS] * p[P_ALPHA]) - kappa * F1, F1 * h


@njit(cache=True, nogil=True)
def spin_rhs(tau, y, args):
    p, mu, g, cs = args
    xi, jac = _map(tau, g)
    rate, source = _spin_rates(xi, p, mu, cs)
    ell = y[0]
    # a trial stage may overshoot; l <= 0 on the solution (w is largest at the wall)
    gain = math.exp(min(ell, 700.0)) if ell > LOG_UNDERFLOW else 0.0
    out = np.empty(2)
    out[0] = jac * rate
    out[1] = jac * gain * source
    return out


@njit(cache=True, nogil=True)
def spin_event(tau, y, args):
    return y[0] - LOG_UNDERFLOW


# ----------------------------------------------------------------- velocity conditions
@njit(cache=True, nogil=True)
def wall_constants(
    h_slip: float,
    kappa_slip: float,
    P_fixed: float,
    h_fixed: float,
    u_fixed: float,
    u_wall_slip: float,
    slip_sign: float,
    eps_K: float,
) -> tuple[float, float, bool]:
    """(u_s, w_s, ok) at the slipping wall from the two velocity conditions.

    With ``h u = (h u)_s - w_s P``: no slip at the fixed wall, ``h_f u_f = h_s u_s - w_s P_f``;
    slip ``u_s = u_wall + s eps K omega_s`` (``eqn-nd_bc3u``, ``eqn-nd_bc3l``,
    ``eqn-nd_bc2_cyl``) with ``omega_s = w_s - kappa_s u_s``: Cramer's rule on the 2x2 system.
    """
    a11, a12 = h_slip, -P_fixed
    a21, a22 = 1.0 + slip_sign * eps_K * kappa_slip, -slip_sign * eps_K
    b1, b2 = h_fixed * u_fixed, u_wall_slip
    det = a11 * a22 - a12 * a21
    if not (math.isfinite(det) and abs(det) > 1e-300):
        return 0.0, 0.0, False
    return (b1 * a22 - a12 * b2) / det, (a11 * b2 - a21 * b1) / det, True


@njit(cache=True, nogil=True)
def symmetric_wall_constants(
    P_centre: float, eps: float, K_upper: float, K_lower: float
) -> tuple[float, float, float, bool]:
    """(u_s, w_s, u_c, ok) between identical walls that both slip.

    Upper half: ``u = u_s - w_s P``; u - u_c is odd and omega even about xi = 1/2, so with
    ``u_c = u_s - w_s P_c``: ``u_s = 1 + eps K_u w_s`` (``eqn-nd_bc3u``) and
    ``u(0) = 2 u_c - u_s = -eps K_l w_s`` (``eqn-nd_bc3l``).
    """
    det = eps * (K_upper + K_lower) - 2.0 * P_centre
    if not (math.isfinite(det) and abs(det) > 1e-300):
        return 0.0, 0.0, 0.0, False
    u_s = (eps * K_lower - 2.0 * P_centre) / det
    w_s = -1.0 / det
    return u_s, w_s, u_s - w_s * P_centre, True


# ----------------------------------------------------------------- geometry of a case
@njit(cache=True, nogil=True)
def walls(p: np.ndarray) -> tuple[float, float]:
    """(xi of the slipping wall, xi where the couple-stress pass starts)."""
    if p[P_GEOMETRY] == COUETTE:
        return 0.0, 1.0
    case = p[P_CASE]
    if case == SYMMETRIC:
        return 1.0, 0.5
    if case == UPPER:
        return 1.0, 0.0
    return 0.0, 1.0


@njit(cache=True, nogil=True)
def velocity(xi: float, P: float, p: np.ndarray, info: np.ndarray) -> float:
    """u from the spin-pass quadrature P at xi: ``h u = (h u)_s - w_s P`` [-]."""
    if p[P_GEOMETRY] == COUETTE:
        Ri = p[P_RI]
        return (Ri + xi) * (info[I_U_S] / Ri - info[I_W_S] * P)
    return info[I_U_S] - info[I_W_S] * P


@njit(cache=True, nogil=True)
def velocities(xi, P, p, info):
    """:func:`velocity` at points xi with their quadratures P [-] (a cached entry point)."""
    u = np.empty(xi.size)
    for i in range(xi.size):
        u[i] = velocity(xi[i], P[i], p, info)
    return u


# ----------------------------------------------------------------- one couple-stress pass
@njit(cache=True, nogil=True)
def couple_pass(p, mu, m_start, x_start, x_end, rtol, atol, max_steps):
    """Pass 1 from ``x_start`` to ``x_end``:
    (status, ts, hs, ys, Q, Zs, t_event, nfev, nsteps, nlu) of :func:`radau5_scalar`."""
    status, ts, hs, ys, Q, Zs, t_event, nfev, nlu, nsteps = radau5_scalar(
        couple_rhs,
        couple_jac,
        couple_event,
        x_start,
        x_end,
        m_start,
        rtol,
        atol,
        (p, mu),
        max_steps,
        0.0,
    )
    return status, ts, hs, ys, Q, Zs, t_event, nfev, nsteps, nlu


@njit(cache=True, nogil=True)
def couple_sensitivity(p, mu, ts, hs, ys, Zs, s_start):
    """d m / d m(0) along a Couette couple-stress pass (:func:`sensitivity`): (ss, dQ)."""
    return sensitivity(couple_derivatives, (p, mu), ts, hs, ys, Zs, s_start)


@njit(cache=True, nogil=True)
def _fatal(code: int) -> bool:
    """A shooting trial that stalled or ran out of steps ends the search (it is not a bound)."""
    return code in (STALLED, TOO_MANY_STEPS)


@njit(cache=True, nogil=True)
def _pass_status(status: int) -> int:
    if status == SUCCESS:
        return OK
    if status == EVENT:
        return NO_SOLUTION
    if status == MAX_STEPS:
        return TOO_MANY_STEPS
    return STALLED


# ----------------------------------------------------------------- Couette: m(0)
@njit(cache=True, nogil=True)
def _shoot(mu, args):
    """m(0; mu) - mu, and the pass's status (NO_SOLUTION: mu is not admissible)."""
    p, rtol, atol, max_steps, counters = args
    m1, disc = outer_wall_couple_stress(
        mu, p[P_TAN_DELTA], p[P_RI], p[P_COUPLE], p[P_A], p[P_SIN_PHI]
    )
    counters[3] += 1.0
    if disc < 0.0:
        return 0.0, NO_SOLUTION, 1.0, m1
    status, ts, _, ys, _, _, _, nfev, nsteps, nlu = couple_pass(
        p, mu, m1, 1.0, 0.0, rtol, atol, max_steps
    )
    counters[0] += nfev
    counters[1] += nsteps
    counters[2] += nlu
    code = _pass_status(status)
    if code != OK:
        return 0.0, code, ts[-1], ys[-1, 0]
    return ys[-1, 0] - mu, OK, 0.0, 0.0


@njit(cache=True, nogil=True)
def couette_inner_couple_stress(p, rtol, atol, max_steps, counters):
    """(status, mu, xi_fail, m_fail): the m(0) for which the couple-stress pass returns m(0).

    F(mu) = m(0; mu) - mu decreases with mu; mu enters only through s_rt with weight
    2(A+1) eps alpha Ri/(Ri + xi)^2, so F is nearly linear and a secant iteration from the
    leading-order value (or a guess) usually converges in a few trials. Trials whose couple
    stress leaves the real domain bound the admissible mu; if F keeps its sign up to such a
    bound, no mu satisfies the conditions: the model has no real solution.
    """
    args = (p, rtol * 0.1, atol * 0.1, max_steps, counters)
    mu0 = p[P_MU_GUESS] if math.isfinite(p[P_MU_GUESS]) else -p[P_M0]
    tol = max(atol, rtol * abs(mu0))
    bound = p[P_B_BOUND]
    # trials kept for the bracket phase
    n_max = 400
    mus = np.empty(n_max)
    gs = np.empty(n_max)
    oks = np.zeros(n_max, dtype=np.bool_)
    n = 0
    xi_fail, m_fail = 0.0, 0.0

    # 1. secant from the start value
    g0, c0, xf, mf = _shoot(mu0, args)
    if _fatal(c0):
        return c0, mu0, xf, mf
    mus[n], gs[n], oks[n] = mu0, g0, c0 == OK
    n += 1
    if c0 == OK:
        if abs(g0) <= tol:
            return OK, mu0, 0.0, 0.0
        mu1 = mu0 + g0
        for _ in range(SECANT_STEPS):
            g1, c1, xf, mf = _shoot(mu1, args)
            if _fatal(c1):
                return c1, mu1, xf, mf
            mus[n], gs[n], oks[n] = mu1, g1, c1 == OK
            n += 1
            if c1 != OK:
                xi_fail, m_fail = xf, mf
                break
            if abs(g1) <= tol:
                return OK, mu1, 0.0, 0.0
            slope = (g1 - g0) / (mu1 - mu0) if mu1 != mu0 else -1.0
            mu0, g0 = mu1, g1
            mu1 = mu1 - g1 / (slope if slope < 0.0 else -1.0)
    else:
        xi_fail, m_fail = xf, mf

    # 2. bracket, using that F decreases and failures lie beyond the admissible mu
    have_ok = False
    for i in range(n):
        have_ok = have_ok or oks[i]
    if not have_ok:
        for j in range(13):
            trial = -2.0 * bound + 3.0 * bound * j / 12.0
            g, c, xf, mf = _shoot(trial, args)
            if _fatal(c):
                return c, trial, xf, mf
            mus[n], gs[n], oks[n] = trial, g, c == OK
            n += 1
            if c == OK:
                have_ok = True
                break
            xi_fail, m_fail = xf, mf
        if not have_ok:
            return NO_SOLUTION, mu0, xi_fail, m_fail
    best = -1
    for i in range(n):
        if oks[i] and (best < 0 or abs(gs[i]) < abs(gs[best])):
            best = i
    mu_s, g_s = mus[best], gs[best]
    step = max(0.05 * bound, abs(g_s))
    up = 1.0 if g_s > 0.0 else -1.0
    have_f = False
    mu_f = 0.0
    for i in range(n):
        beyond = not oks[i] and up * (mus[i] - mu_s) > 0.0
        if beyond and (not have_f or abs(mus[i] - mu_s) < abs(mu_f - mu_s)):
            mu_f, have_f = mus[i], True
    lo = hi = g_lo = g_hi = 0.0
    found = False
    for _ in range(200):  # doubling, then bisection to tol: ~60 trials at most in practice
        trial = mu_s + up * step if not have_f else 0.5 * (mu_s + mu_f)
        g_t, c_t, xf, mf = _shoot(trial, args)
        if _fatal(c_t):
            return c_t, trial, xf, mf
        if c_t != OK:
            mu_f, have_f = trial, True
            xi_fail, m_fail = xf, mf
        elif up * g_t <= 0.0:
            if mu_s < trial:
                lo, hi, g_lo, g_hi = mu_s, trial, g_s, g_t
            else:
                lo, hi, g_lo, g_hi = trial, mu_s, g_t, g_s
            found = True
            break
        else:
            mu_s, g_s, step = trial, g_t, 2.0 * step
        if have_f and abs(mu_f - mu_s) < tol:
            return NO_SOLUTION, mu_s, xi_fail, m_fail
    if not found:
        return NO_BRACKET, mu_s, 0.0, 0.0
    state = brent_start(lo, hi, g_lo, g_hi)
    for _ in range(200):
        trial, done = brent_next(state, tol)
        if done:
            return OK, state[ROOT], 0.0, 0.0
        g_t, c_t, xf, mf = _shoot(trial, args)
        if c_t != OK:  # inside a bracket of admissible trials: not expected
            return (c_t if c_t != NO_SOLUTION else NO_BRACKET), trial, xf, mf
        brent_accept(state, trial, g_t)
    return NO_BRACKET, state[ROOT], 0.0, 0.0


@njit(cache=True, nogil=True)
def _newton_trial(p, mu, rtol, atol, max_steps, counters):
    """One pass at m(0) = mu: (code, F, ts, hs, ys, Q, Zs), F(mu) = m(0; mu) - mu."""
    m1, disc = outer_wall_couple_stress(
        mu, p[P_TAN_DELTA], p[P_RI], p[P_COUPLE], p[P_A], p[P_SIN_PHI]
    )
    counters[3] += 1.0
    if disc <= 0.0:
        e1 = np.zeros(1)
        return NO_SOLUTION, 0.0, e1, e1, np.zeros((1, 1)), np.zeros((0, 1, 3)), np.zeros((0, 3))
    status, ts, hs, ys, Q, Zs, _, nfev, nsteps, nlu = couple_pass(
        p, mu, m1, 1.0, 0.0, rtol, atol, max_steps
    )
    counters[0] += nfev
    counters[1] += nsteps
    counters[2] += nlu
    return _pass_status(status), ys[-1, 0] - mu, ts, hs, ys, Q, Zs


@njit(cache=True, nogil=True)
def _newton_slope(p, mu, ts, hs, ys, Zs):
    """(dF/dmu, dm/dmu along the pass, its dense output): dF/dmu = s(0) - 1 with s = dm/dmu,
    the derivative of the computed pass (:func:`couple_sensitivity`), started from dm(1)/dmu
    of ``eqn-nd_bc1_cyl``."""
    s1 = outer_wall_couple_stress_dm_inner(
        mu, p[P_TAN_DELTA], p[P_RI], p[P_COUPLE], p[P_A], p[P_SIN_PHI]
    )
    ss, dQ = couple_sensitivity(p, mu, ts, hs, ys, Zs, s1)
    return ss[-1, 0] - 1.0, ss, dQ


@njit(cache=True, nogil=True)
def couette_newton(p, rtol, atol, max_steps, counters):
    """(found, mu, ts, hs, ys, Q): m(0) by Newton's method, and its final couple-stress pass.

    Each pass returns F(mu) = m(0; mu) - mu (:func:`_newton_trial`) and, by internal
    differentiation, dF/dmu (:func:`_newton_slope`), so each pass is one Newton step. Only the
    last pass needs the final tolerance (rtol/10, as every trial of
    :func:`couette_inner_couple_stress`): the first runs at ``NEWTON_LOOSE_RTOL`` (unless the
    caller gave a guess of m(0)), and a pass whose Newton step will still be large runs at a
    tolerance a hundred times below the error of m(0) expected after it. The result is
    accepted when |F| <= tol (``tol`` as in :func:`couette_inner_couple_stress`), or when the
    final pass's own Newton step is so small that its second-order remainder, estimated from
    the previous step (``c |step|^2``, with ``c`` the smaller of |F|/|previous step|^2 and
    |change of dF/dmu|/(2 |previous step|), both upper estimates of |F''|/2 up to the passes'
    errors), is below ``NEWTON_REMAINDER`` tol: then the step is taken on the computed
    solution itself, through its linearisation ``m + step dm/dmu`` (exact to first order for
    the discrete equations).
    A step whose pass leaves the real domain is halved (the root lies between the last
    admissible trial and it, F decreasing), and no later step goes beyond it. Anything else
    unexpected (a first pass outside the real domain, a pass that fails otherwise, dF/dmu >= 0,
    a step beyond the yield scale, no convergence in ``NEWTON_TRIALS`` passes) returns
    found = False, and the caller falls back to the bracketing search.
    """
    e1 = np.zeros(1)
    e2 = np.zeros((1, 1))
    e3 = np.zeros((0, 1, 3))
    final_rtol, final_atol = rtol * 0.1, atol * 0.1
    guess = math.isfinite(p[P_MU_GUESS])
    mu = p[P_MU_GUESS] if guess else -p[P_M0]
    tol = max(atol, rtol * abs(mu))
    bound = p[P_B_BOUND]
    pass_rtol = final_rtol if guess else max(final_rtol, NEWTON_LOOSE_RTOL)
    prev_step = math.nan
    prev_dF = math.nan
    mu_ok = math.nan  # the last admissible trial
    limit = math.nan  # the nearest trial beyond the real domain (F decreases; failures bound mu)
    for _ in range(NEWTON_TRIALS):
        final = pass_rtol <= final_rtol
        code, F, ts, hs, ys, Q, Zs = _newton_trial(
            p, mu, pass_rtol, final_atol * (pass_rtol / final_rtol), max_steps, counters
        )
        if code == NO_SOLUTION and math.isfinite(mu_ok):
            # the step left the real domain: halve it, and never step that far again
            limit = mu
            mu = 0.5 * (mu_ok + mu)
            prev_step = math.nan
            continue
        if code != OK or not math.isfinite(F):
            break
        if final and abs(F) <= tol:
            return True, mu, ts, hs, ys, Q
        dF, ss, dQ = _newton_slope(p, mu, ts, hs, ys, Zs)
        if not (math.isfinite(dF) and dF < 0.0):
            break
        step = -F / dF
        if not abs(step) <= bound:
            break
        curv = math.inf
        if math.isfinite(prev_step) and prev_step != 0.0:
            curv = min(abs(F) / prev_step**2, 0.5 * abs(dF - prev_dF) / abs(prev_step))
        if final and curv * step * step <= NEWTON_REMAINDER * tol:
            for i in range(ys.shape[0]):
                ys[i, 0] += step * ss[i, 0]
            for i in range(Q.shape[0]):
                for j in range(3):
                    Q[i, 0, j] += step * dQ[i, 0, j]
            return True, mu + step, ts, hs, ys, Q
        if math.isfinite(limit) and (mu + step - limit) * (mu - limit) <= 0.0:
            step = 0.5 * (limit - mu)  # not beyond a trial known to leave the real domain
        # the next pass: final if its own step should be small enough, else a looser one
        c = curv if math.isfinite(curv) else NEWTON_CURVATURE_PRIOR
        F_next = c * step * step
        if c * (F_next / dF) ** 2 <= NEWTON_REMAINDER * tol:
            pass_rtol = final_rtol
        else:
            scale = max(abs(mu), atol)
            pass_rtol = min(max(0.01 * F_next / scale, final_rtol), NEWTON_LOOSE_RTOL)
        prev_step, prev_dF = step, dF
        mu_ok = mu
        mu += step
    return False, mu, e1, e1, e2, e3


# ----------------------------------------------------------------- thickness
@njit(cache=True, nogil=True)
def _excess(tau, args):
    """u(xi(tau)) - u_0 - f (u_s - u_0): zero at the thickness (``eqn-delta_defn``)."""
    p, g, sp, info, f = args
    ts, ys, F = sp
    xi, _ = _map(tau, g)
    P = ys[-1, 1] if tau >= ts[-1] else dop853_eval1(ts, ys, F, tau, 1)
    u0 = info[I_U_REF]
    return velocity(xi, P, p, info) - u0 - f * (info[I_U_S] - u0)


@njit(cache=True, nogil=True)
def thickness(p, g, sp, info, f):
    """(Delta [d_p], ok): distance from the slipping wall, over eps, where the velocity
    relative to u_0 has fallen to the fraction f of its wall value (``eqn-delta_defn``)."""
    args = (p, g, sp, info, f)
    g0 = _excess(0.0, args)
    if g0 == 0.0:
        return 0.0, True
    # the far end of the pass: the centre (symmetric) or the fixed wall
    g1 = _excess(1.0, args)
    if not brackets(g0, g1):
        return math.nan, False
    state = brent_start(0.0, 1.0, g0, g1)
    ok = False
    for _ in range(400):
        tau, ok = brent_next(state, 4e-16)
        if ok:
            break
        brent_accept(state, tau, _excess(tau, args))
    xi, _ = _map(state[ROOT], g)
    return abs(xi - g[0]) / p[P_EPS], ok


@njit(cache=True, nogil=True)
def _crossed_by_round_off(ts: np.ndarray, ys: np.ndarray, p: np.ndarray) -> bool:
    """True if the couple stress reached the yield bound while drifting towards it.

    In plane shear the couple stress relaxes towards the value where the stress is symmetric
    (torque 0), which lies inside the bound (``S = ((1+A) syx)^2 >= 0`` there). An exact
    solution drifting outwards is below that equilibrium and cannot cross it, so it cannot
    reach the bound: if the computed one does, the equilibrium is within the tolerance of the
    bound (a nearly frictionless wall) and round-off decided, not the model. A genuine crossing
    (under gravity the bound closes in on a couple stress that lags behind) arrives drifting
    inwards. Judged at the last accepted point before the event.
    """
    if p[P_GEOMETRY] != PLANE or ts.size < 2:
        return False
    xi, m = ts[-2], ys[-2, 0]
    direction = 1.0 if ts[-1] > ts[0] else -1.0
    rate = k_torque(p[P_SIGMA_YX], _mean_stress(xi, p), m, p[P_A], p[P_SIN_PHI])
    outward = rate * direction * (1.0 if m >= 0.0 else -1.0)
    # a start at the equilibrium (the fixed wall, eqn-nd_bc4) has a torque of round-off size
    return outward > ROUND_OFF_TORQUE * _mean_stress(xi, p) * p[P_SIN_PHI]


# ----------------------------------------------------------------- one case
@njit(cache=True, nogil=True)
def _empty_solution():
    """(couple-stress, spin) solutions of a case that stopped before them."""
    couple = (np.zeros(1), np.zeros(0), np.zeros((1, 1)), np.zeros((0, 1, 3)))
    spin = (np.zeros(1), np.zeros((1, 2)), np.zeros((0, 7, 2)))
    return couple, spin


@njit(cache=True, nogil=True)
def _after_couple_pass(p, mu, status, cs, counters, info, rtol, atol, f, max_steps):
    """From a couple-stress pass to the case's result (:func:`solve_case`): the pass's status,
    then the spin pass, the velocity constants and the thickness."""
    ts1, _, ys1, _ = cs
    xs, x0 = walls(p)
    m_start = ys1[0, 0]
    g = np.zeros(3)
    _, no_spin = _empty_solution()
    code = _pass_status(status)
    if code == NO_SOLUTION and _crossed_by_round_off(ts1, ys1, p):
        code = AT_YIELD_EDGE
    if code != OK:
        info[I_XI_FAIL], info[I_M_FAIL] = ts1[-1], ys1[-1, 0]
        info[I_NFEV], info[I_NSTEPS], info[I_NLU] = counters[0], counters[1], counters[2]
        return code, info, cs, no_spin, g

    # pass 2 from the slipping wall to the far end (x0)
    sc0 = _mean_stress(x0, p)
    S0 = k_radicand(_shear_stress(x0, m_start, p, mu), sc0, m_start, p[P_A], p[P_SIN_PHI])
    singular = S0 <= SINGULAR_MARGIN * 2.0 * (p[P_A] + 1.0) * (sc0 * p[P_SIN_PHI]) ** 2
    g[0], g[1], g[2] = xs, x0 - xs, 1.0 if singular else 0.0
    info[I_SINGULAR] = g[2]
    # P ~ eps G and G carries the velocity weight h (1/(Ri + xi) in Couette flow): its absolute
    # tolerance scales with h, or at large Ri the velocity u = (u_s h_s - w_s P)/h loses the
    # digits atol did not ask for.
    h_min = 1.0 if p[P_GEOMETRY] == PLANE else min(_curvature(xs, p), _curvature(x0, p))
    status2, ts2, ys2, F2, nfev2, nsteps2 = dop853(
        spin_rhs,
        spin_event,
        0.0,
        1.0,
        np.zeros(2),
        rtol,
        np.array([rtol, atol * p[P_EPS] * h_min]),
        (p, mu, g, cs),
        max_steps,
    )
    counters[0] += nfev2
    counters[1] += nsteps2
    info[I_NFEV], info[I_NSTEPS], info[I_NLU] = counters[0], counters[1], counters[2]
    info[I_STEPS_SPIN] = nsteps2
    sp = (ts2, ys2, F2)
    if status2 != SUCCESS and status2 != EVENT:
        info[I_XI_FAIL] = _map(ts2[-1], g)[0]
        return (TOO_MANY_STEPS if status2 == MAX_STEPS else STALLED), info, cs, sp, g
    info[I_XI_CUT] = _map(ts2[-1], g)[0]
    P_far = ys2[-1, 1]  # at the far end, or constant beyond the underflow cut

    eps = p[P_EPS]
    if p[P_GEOMETRY] == COUETTE:
        Ri = p[P_RI]
        u_s, w_s, ok = wall_constants(
            1.0 / Ri, 1.0 / Ri, P_far, 1.0 / (Ri + 1.0), 0.0, -1.0, -1.0, eps * p[P_K_SLIP]
        )
        u_ref, u_wall = 0.0, -1.0
    elif p[P_CASE] == SYMMETRIC:
        u_s, w_s, u_ref, ok = symmetric_wall_constants(P_far, eps, p[P_K_SLIP], p[P_K_OTHER])
        u_wall = 1.0
    else:
        upper = p[P_CASE] == UPPER
        u_fixed = 0.0 if upper else 1.0
        u_wall = 1.0 - u_fixed
        u_s, w_s, ok = wall_constants(
            1.0, 0.0, P_far, 1.0, u_fixed, u_wall, 1.0 if upper else -1.0, eps * p[P_K_SLIP]
        )
        u_ref = u_fixed
    if not ok:
        return SINGULAR_VELOCITY, info, cs, sp, g
    info[I_U_S], info[I_W_S], info[I_U_REF] = u_s, w_s, u_ref
    kappa_s = _curvature(xs, p)
    info[I_WALL_SLIP] = abs(u_s - u_wall)
    info[I_WALL_OMEGA] = w_s - kappa_s * u_s
    info[I_WALL_STRESS] = _shear_stress(xs, ys1[-1, 0], p, mu)
    delta, delta_ok = thickness(p, g, sp, info, f)
    info[I_DELTA] = delta
    info[I_DELTA_OK] = 1.0 if delta_ok else 0.0
    return OK, info, cs, sp, g


@njit(cache=True, nogil=True)
def solve_plane_case(p, rtol, atol, f, max_steps):
    """:func:`solve_case` for plane shear (compiled without the Couette search)."""
    info = np.zeros(N_INFO)
    info[I_DELTA] = math.nan
    counters = np.zeros(4)  # nfev, nsteps, nlu, trials
    xs, x0 = walls(p)
    status, ts1, hs1, ys1, Q1, _, _, nfev, nsteps, nlu = couple_pass(
        p, 0.0, p[P_M_START], x0, xs, rtol, atol, max_steps
    )
    counters[0] += nfev
    counters[1] += nsteps
    counters[2] += nlu
    info[I_STEPS_COUPLE] = nsteps
    cs = (ts1, hs1, ys1, Q1)
    return _after_couple_pass(p, 0.0, status, cs, counters, info, rtol, atol, f, max_steps)


@njit(cache=True, nogil=True)
def solve_couette_case(p, rtol, atol, f, max_steps):
    """:func:`solve_case` for Couette flow: m(0) by Newton's method (:func:`couette_newton`),
    or by the bracketing search (:func:`couette_inner_couple_stress`) if that fails."""
    info = np.zeros(N_INFO)
    info[I_DELTA] = math.nan
    counters = np.zeros(4)  # nfev, nsteps, nlu, trials
    found, mu, ts1, hs1, ys1, Q1 = couette_newton(p, rtol, atol, max_steps, counters)
    status = SUCCESS
    if found:
        info[I_STEPS_COUPLE] = ts1.size - 1
    else:
        code, mu, xf, mf = couette_inner_couple_stress(p, rtol, atol, max_steps, counters)
        if code != OK:
            info[I_MU] = mu
            info[I_ITERATIONS] = counters[3]
            info[I_XI_FAIL], info[I_M_FAIL] = xf, mf
            cs, sp = _empty_solution()
            return code, info, cs, sp, np.zeros(3)
        m1, _ = outer_wall_couple_stress(
            mu, p[P_TAN_DELTA], p[P_RI], p[P_COUPLE], p[P_A], p[P_SIN_PHI]
        )
        status, ts1, hs1, ys1, Q1, _, _, nfev, nsteps, nlu = couple_pass(
            p, mu, m1, 1.0, 0.0, rtol * 0.1, atol * 0.1, max_steps
        )
        counters[0] += nfev
        counters[1] += nsteps
        counters[2] += nlu
        info[I_STEPS_COUPLE] = nsteps
    info[I_MU] = mu
    info[I_ITERATIONS] = counters[3]
    cs = (ts1, hs1, ys1, Q1)
    return _after_couple_pass(p, mu, status, cs, counters, info, rtol, atol, f, max_steps)


@njit(cache=True, nogil=True)
def solve_case(p, rtol, atol, f, max_steps):
    """Solve one problem: (status, info, couple-stress solution, spin solution, pass geometry).

    ``info`` holds the scalars ``I_*``; the solutions are (ts, hs, ys, Q) of
    :func:`~cosserat.numerics.radau_scalar.radau5_scalar`, the spin one (ts, ys, F) of
    :func:`~cosserat.numerics.dop853.dop853` in the pass variable tau with
    xi(tau) given by the pass geometry ``[xi_slip, span, singular]``. One problem of a known
    cell is cheaper to compile through :func:`solve_plane_case` or :func:`solve_couette_case`
    (a first run compiles only what it calls).
    """
    if p[P_GEOMETRY] == COUETTE:
        return solve_couette_case(p, rtol, atol, f, max_steps)
    return solve_plane_case(p, rtol, atol, f, max_steps)


@njit(cache=True, nogil=True)
def solve_batch(params, rtol, atol, f, max_steps):
    """Wall quantities of many problems (rows of ``params``).

    Returns (status[n], info[n, N_INFO]); a failed case has its status code and the info
    gathered before it stopped, never NaN in place of an answer that was computed. It releases
    the GIL, so threads run batches in parallel (:func:`cosserat.numerics.runtime.map_batches`):
    the parallelism of a ``prange``, without compiling the solver a second time for numba's
    parallel target (~10 s on a machine's first run).
    """
    n = params.shape[0]
    status = np.empty(n, dtype=np.int64)
    info = np.zeros((n, N_INFO))
    for i in range(n):
        code, row, _, _, _ = solve_case(params[i], rtol, atol, f, max_steps)
        status[i] = code
        for j in range(N_INFO):
            info[i, j] = row[j]
    return status, info


@njit(cache=True, nogil=True)
def thickness_of(p, g, ts, ys, F, info, f):
    """Delta for another fraction f from a solved case (a cached entry point)."""
    return thickness(p, g, (ts, ys, F), info, f)


@njit(cache=True, nogil=True)
def spin_pass_at(xi, g, ts, ys, F):
    """(l, P) of the spin pass at points xi (the far side of the cut: -inf, P_cut) [-]."""
    n = xi.size
    ell = np.empty(n)
    P = np.empty(n)
    reach = abs(_map(ts[-1], g)[0] - g[0])
    for i in range(n):
        d = abs(xi[i] - g[0])
        if d > reach * (1.0 + 1e-15) and reach < abs(g[1]):
            ell[i] = -np.inf
            P[i] = ys[-1, 1]
            continue
        frac = min(max((xi[i] - g[0]) / g[1], 0.0), 1.0)
        tau = 1.0 - math.sqrt(1.0 - frac) if g[2] != 0.0 else frac
        tau = min(tau, ts[-1])
        ell[i] = dop853_eval1(ts, ys, F, tau, 0)
        P[i] = dop853_eval1(ts, ys, F, tau, 1)
    return ell, P


# ----------------------------------------------------------------- fields at many points
# rows of fields_at's output, in the order of cosserat.results.profile.Fields
F_U, F_OMEGA, F_M, F_SIGMA_XY, F_SIGMA_YX, F_SIGMA_YY, F_DU_DXI, F_KAPPA = range(8)
N_FIELDS = 8


@njit(cache=True, nogil=True)
def _radau_step(ts: np.ndarray, t: float, hint: int) -> int:
    """:func:`~cosserat.numerics.radau._step_index` (the step with ts[i] < t <= ts[i + 1],
    the first one at ts[0]), trying ``hint`` first: sorted points cost no search."""
    k = ts.shape[0] - 1
    s = 1.0 if ts[k] >= ts[0] else -1.0
    st = s * t
    if 0 <= hint < k and st <= s * ts[hint + 1] and (hint == 0 or st > s * ts[hint]):
        return hint
    lo = 0
    hi = k - 1
    while lo < hi:
        mid = (lo + hi) >> 1
        if st <= s * ts[mid + 1]:
            hi = mid
        else:
            lo = mid + 1
    return lo


@njit(cache=True, nogil=True)
def _dop853_step(ts: np.ndarray, t: float, hint: int) -> int:
    """The step :func:`~cosserat.numerics.dop853.dop853_eval1` evaluates at t (the last one
    with ts[i] <= t, forwards), trying ``hint`` first."""
    k = ts.shape[0] - 1
    if 0 <= hint < k and ts[hint] <= t and (hint == k - 1 or ts[hint + 1] > t):
        return hint
    lo, hi = 0, k
    while hi - lo > 1:
        mid = (lo + hi) // 2
        if ts[mid] <= t:
            lo = mid
        else:
            hi = mid
    return lo


# The field loop below is split into passes over the points so that LLVM vectorises the
# arithmetic (4 points per AVX2 instruction): the searches for each point's steps are
# sequential, the rest is branch-free. The vectorised loops index with a range's own counter
# from 0 (on slices): numba checks any other index for a negative value (wraparound), and
# that check alone kept the loops scalar. error_model="numpy": a division by zero gives inf
# instead of a Python exception, which numba checks for before each division, and which keeps
# a loop from being vectorised; no divisor here is zero (step lengths, the span, r = Ri + xi,
# the floored sqrt(S), (1+A) tau + sqrt(S) with tau > 0), and a non-finite field would be
# flagged by the screen. (The options are written out at each decorator: mypy's numba stubs
# do not accept them as **kwargs.)


@njit(cache=True, nogil=True, error_model="numpy")
def _couple_run(ts, hs, ys, Q, i, tp, m):
    """m at the points ``tp``, all in Radau step i: :func:`dense_eval1`'s operations
    (a point on the step's end takes the stored value) [-]."""
    t0, t1, hh = ts[i], ts[i + 1], hs[i]
    y0, y1 = ys[i, 0], ys[i + 1, 0]
    c0, c1, c2 = Q[i, 0, 0], Q[i, 0, 1], Q[i, 0, 2]
    for q in range(tp.shape[0]):
        t = tp[q]
        s = (t - t0) / hh
        v = y0 + s * (c0 + s * (c1 + s * c2))
        m[q] = y1 if t == t1 else v


@njit(cache=True, nogil=True, error_model="numpy")
def _spin_run(ts, ys, F, i, tau, ell, P):
    """(l, P) at the points ``tau``, all in DOP853 step i: :func:`dop853_eval1`'s
    operations for both components [-]."""
    t0 = ts[i]
    hh = ts[i + 1] - t0
    nonzero = hh != 0.0
    e6, e5, e4, e3 = F[i, 6, 0], F[i, 5, 0], F[i, 4, 0], F[i, 3, 0]
    e2, e1, e0 = F[i, 2, 0], F[i, 1, 0], F[i, 0, 0]
    p6, p5, p4, p3 = F[i, 6, 1], F[i, 5, 1], F[i, 4, 1], F[i, 3, 1]
    p2, p1, p0 = F[i, 2, 1], F[i, 1, 1], F[i, 0, 1]
    y0, y1 = ys[i, 0], ys[i, 1]
    for q in range(tau.shape[0]):
        x = (tau[q] - t0) / hh if nonzero else 0.0
        x = 0.0 if x < 0.0 else x
        x = 1.0 if x > 1.0 else x
        y = 1.0 - x
        # out = (out + F[j]) * (x if (6 - j) is even else 1 - x), j = 6 ... 0
        o = ((((((e6 * x + e5) * y + e4) * x + e3) * y + e2) * x + e1) * y + e0) * x
        r = ((((((p6 * x + p5) * y + p4) * x + p3) * y + p2) * x + p1) * y + p0) * x
        ell[q] = o + y0
        P[q] = r + y1


BLOCK = 256
"""Points per block of :func:`fields_checked`: its scratch (8 x BLOCK numbers, 16 kB) stays in the
first-level cache and is allocated once per call. Scratch the size of the grid (256 kB at
2,001 points) cost more than the arithmetic: freed at the top of the heap, glibc's malloc gave
it back to the system and every call faulted it in again."""


@njit(cache=True, nogil=True, error_model="numpy")
def fields_checked(xi, p, info, ts1, hs1, ys1, Q1, g, ts2, ys2, F2, slack):
    """:func:`fields_at`, and where a profile's checks must look: (out, first, finite).

    ``first`` is the first point whose yield radicand S (``eqn-nd_sigxy``, of the returned
    sigma_yx, sigma_yy and m) is below ``-slack`` times its scale 2(A+1)(sigma_c sin phi)^2,
    or NaN (-1 if none); ``finite`` is False if any field is not finite. A slack a little
    below the profile check's round-off allowance (``RADICAND_ROUNDOFF``) flags every point
    that check could reject and a few it accepts: the caller runs that check only on a flag,
    so its decision and message are the same, and an unflagged profile costs no Python.

    Passes over blocks of points (the comment above :data:`BLOCK`). One compiled body: the
    route calls it for the profile and for the evaluator (:func:`fields_at` is this without
    the screen, for :func:`predict_batch`), so a first solve compiles and emits it once.
    """
    n = xi.shape[0]
    out = np.empty((N_FIELDS, n))
    work = np.empty((6, BLOCK))
    h_, tp_, tau_, m_, w_, P_ = work[0], work[1], work[2], work[3], work[4], work[5]
    steps = np.empty((2, BLOCK), dtype=np.int64)
    i1_, i2_ = steps[0], steps[1]
    couette = p[P_GEOMETRY] == COUETTE
    symmetric = not couette and p[P_CASE] == SYMMETRIC
    k1 = ts1.shape[0] - 1
    lo1 = min(ts1[0], ts1[k1])
    hi1 = max(ts1[0], ts1[k1])
    k2 = ts2.shape[0] - 1
    tau_end = ts2[k2]
    g0, g1, singular = g[0], g[1], g[2] != 0.0
    reach = abs(_map(tau_end, g)[0] - g0)
    cut = reach < abs(g1)
    reach_tol = reach * (1.0 + 1e-15)
    P_cut = ys2[k2, 1]
    w_s = info[I_W_S]
    A, sp = p[P_A], p[P_SIN_PHI]
    Ri, tan_delta, couple = p[P_RI], p[P_TAN_DELTA], p[P_COUPLE]
    mu_Ri = info[I_MU] * Ri if couette else 0.0
    u_s = info[I_U_S]
    u_s_Ri = u_s / Ri if couette else 0.0
    syx_plane, B_nu = p[P_SIGMA_YX], p[P_B_NU]
    two_uc = 2.0 * info[I_U_REF]
    a2m1 = A * A - 1.0
    two_a1 = 2.0 * (A + 1.0)
    four_a1sq = 4.0 * (A + 1.0) ** 2
    one_a = 1.0 + A
    bound = -slack * 2.0 * (A + 1.0)
    flagged = 0
    nonfinite = 0
    # int64, not the literal 0: numba would compile the step searches twice (Literal[int](0)
    # and int64), for nothing
    i1 = np.int64(0)
    i2 = np.int64(0)
    s1 = 1.0 if ts1[k1] >= ts1[0] else -1.0  # the direction of the couple-stress pass
    for start in range(0, n, BLOCK):
        nb = min(BLOCK, n - start)
        end = start + nb
        xb = xi[start:end]
        o_u, o_omega, o_m = out[F_U, start:end], out[F_OMEGA, start:end], out[F_M, start:end]
        o_sxy, o_syx = out[F_SIGMA_XY, start:end], out[F_SIGMA_YX, start:end]
        o_syy, o_du, o_kappa = (
            out[F_SIGMA_YY, start:end],
            out[F_DU_DXI, start:end],
            out[F_KAPPA, start:end],
        )
        # 1. each point on the solved half (h), in the couple-stress pass (tp: dense_eval's
        # clipping) and in the spin pass (tau), then the steps they fall in: the last point's
        # step or the next (_radau_step's and _dop853_step's conditions), else a search (sorted
        # points need none)
        for j in range(nb):
            x = xb[j]
            h = 1.0 - x if symmetric and x < 0.5 else x
            h_[j] = h
            tp = hi1 if h > hi1 else h
            tp_[j] = lo1 if tp < lo1 else tp
            frac = (h - g0) / g1
            frac = 0.0 if frac < 0.0 else frac
            frac = 1.0 if frac > 1.0 else frac
            tau = 1.0 - math.sqrt(1.0 - frac) if singular else frac
            tau_[j] = tau_end if tau > tau_end else tau
        for j in range(nb):
            if k1 > 0:
                t = tp_[j]
                st = s1 * t
                if i1 < k1 - 1 and st > s1 * ts1[i1 + 1]:
                    if i1 + 1 < k1 - 1 and st > s1 * ts1[i1 + 2]:
                        i1 = _radau_step(ts1, t, i1)
                    else:
                        i1 += 1
                elif i1 > 0 and st <= s1 * ts1[i1]:
                    i1 = _radau_step(ts1, t, i1)
            i1_[j] = i1
            if cut and abs(h_[j] - g0) > reach_tol:
                i2_[j] = -1  # beyond the cut: e^l underflows (spin_pass_at: l = -inf)
            else:
                if k2 > 0:
                    t = tau_[j]
                    if i2 < k2 - 1 and ts2[i2 + 1] <= t:
                        if i2 + 1 < k2 - 1 and ts2[i2 + 2] <= t:
                            i2 = _dop853_step(ts2, t, i2)
                        else:
                            i2 += 1
                    elif i2 > 0 and ts2[i2] > t:
                        i2 = _dop853_step(ts2, t, i2)
                i2_[j] = i2

        # 2. the couple stress m and the spin pass's (l, P), on runs of points in one step
        a = 0
        while a < nb:
            b = a + 1
            while b < nb and i1_[b] == i1_[a]:
                b += 1
            if k1 == 0:
                for j in range(a, b):
                    m_[j] = ys1[0, 0]
            else:
                _couple_run(ts1, hs1, ys1, Q1, i1_[a], tp_[a:b], m_[a:b])
            a = b
        a = 0
        while a < nb:
            b = a + 1
            while b < nb and i2_[b] == i2_[a]:
                b += 1
            i = i2_[a]
            if i < 0:
                for j in range(a, b):
                    P_[j] = P_cut
            elif k2 == 0:
                for j in range(a, b):
                    w_[j] = ys2[0, 0]
                    P_[j] = ys2[0, 1]
            else:
                _spin_run(ts2, ys2, F2, i, tau_[a:b], w_[a:b], P_[a:b])
            a = b
        for j in range(nb):  # w = w_s e^l, 0 beyond the cut
            w_[j] = w_s * 0.0 if i2_[j] < 0 else w_s * math.exp(w_[j])

        # 3. the fields (the arithmetic of velocity, _shear_stress, _mean_stress, _curvature,
        # k_velocity_ratio and k_torque, in the same order of operations, with S and sqrt(S)
        # computed once) and the screen of fields_checked
        for j in range(nb):
            h = h_[j]
            m = m_[j]
            w = w_[j]
            P = P_[j]
            if couette:
                r = Ri + h
                u = r * (u_s_Ri - w_s * P)
                decay = Ri / r
                syx = -tan_delta * (decay * decay) + couple * (m / r - mu_Ri / (r * r))
                sc = 1.0
                kappa = 1.0 / r
            else:
                u = u_s - w_s * P
                syx = syx_plane
                sc = 1.0 + B_nu * (1.0 - h)
                kappa = 0.0
            sc_sin = sc * sp
            S = a2m1 * syx * syx + 2.0 * (A + 1.0) * sc_sin * sc_sin - four_a1sq * m * m
            root = math.sqrt(S if S > 0.0 else 0.0)
            denom = -(root if root > SQRT_S_FLOOR else SQRT_S_FLOOR)
            F1 = one_a * ((denom - A * syx) + syx) / denom
            tau = -syx
            t_pos = ((sc_sin - tau) * (sc_sin + tau) - two_a1 * m * m) / (root + one_a * tau)
            t_neg = (root - one_a * tau) / two_a1
            sxy = syx - two_a1 * (t_pos if tau > 0.0 else t_neg)
            omega = w - kappa * u
            du = -w * F1 + kappa * u
            low = symmetric and xb[j] < 0.5
            u = two_uc - u if low else u
            m = -m if low else m
            o_u[j] = u
            o_omega[j] = omega
            o_m[j] = m
            o_sxy[j] = sxy
            o_syx[j] = syx
            o_syy[j] = sc
            o_du[j] = du
            o_kappa[j] = kappa
            # S of the returned fields is this S ((-m)(-m) = m m); NaN compares false
            flagged += 0 if S >= bound * sc_sin * sc_sin else 1
            # counted, not summed: an integer count vectorises, a float sum would not
            z = ((u + omega) + (m + sxy)) + ((syx + sc) + (du + kappa))
            nonfinite += 0 if z - z == 0.0 else 1
    first = -1
    if flagged:
        for q in range(n):
            sc_sin = out[F_SIGMA_YY, q] * sp
            S = k_radicand(out[F_SIGMA_YX, q], out[F_SIGMA_YY, q], out[F_M, q], A, sp)
            if not S >= bound * sc_sin * sc_sin:
                first = q
                break
    return out, first, nonfinite == 0


@njit(cache=True, nogil=True)
def fields_at(xi, p, info, ts1, hs1, ys1, Q1, g, ts2, ys2, F2):
    """The fields of a solved case at points ``xi`` in [0, 1]: float64[N_FIELDS, n] [-].

    Rows ``F_*`` (u, omega, m, sigma_xy, sigma_yx, sigma_yy, du/dxi, kappa), from the dense
    outputs of both passes (``(ts1, hs1, ys1, Q1)`` of the couple stress, ``(ts2, ys2, F2)``
    of the spin pass with geometry ``g``), the velocity constants in ``info`` and the stresses
    of the constitutive law (``eqn-nd_sigxy``, the flow rule ``eqn-nd_fr1``): the arithmetic of
    :func:`cosserat.routes.assemble.fields_from_state`, compiled. Between identical walls (the
    symmetric case) the solved upper half is reflected: u - u_c odd, m odd, the rest even
    (``eqn-nd_bc6``). Points in any order; sorted points are cheapest (no search for the step
    of each point).
    """
    return fields_checked(xi, p, info, ts1, hs1, ys1, Q1, g, ts2, ys2, F2, 0.0)[0]


@njit(cache=True, nogil=True)
def predict_batch(params, xi, starts, rows, rtol, atol, f, max_steps):
    """Chosen fields of many problems at their own points, and nothing else.

    Problem i (row ``params[i]``) is solved (:func:`solve_case`) and its fields ``rows``
    (indices ``F_*``) evaluated at ``xi[starts[i]:starts[i + 1]]`` (:func:`fields_at`).
    Returns (status[n], info[n, N_INFO], out[len(rows), xi.size]); the columns of a failed
    case are left at 0 and its status says why (never NaN in place of an answer). Releases the
    GIL, like :func:`solve_batch`.
    """
    n = params.shape[0]
    status = np.empty(n, dtype=np.int64)
    info = np.zeros((n, N_INFO))
    out = np.zeros((rows.shape[0], xi.shape[0]))
    for i in range(n):
        code, row, cs, sp, g = solve_case(params[i], rtol, atol, f, max_steps)
        status[i] = code
        for j in range(N_INFO):
            info[i, j] = row[j]
        if code != OK:
            continue
        a, b = starts[i], starts[i + 1]
        values = fields_at(xi[a:b], params[i], row, cs[0], cs[1], cs[2], cs[3], g, *sp)
        for r in range(rows.shape[0]):
            for q in range(b - a):
                out[r, a + q] = values[rows[r], q]
    return status, info, out
