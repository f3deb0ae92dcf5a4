"""Compiled kernel of the frictional Cosserat model in the vertical channel.

The upper half, xi in [1/2, 1], in the mapped variables of :mod:`cosserat.model.channel` (the
mirror image x -> -x, in which the equations are those of plane shear with
``sigma_yx = -tau(xi)``, ``tau = B nu (xi - 1/2)``, ``sigma_c = 1``;
``docs/derivation_channel.md``).
The passes are those of :mod:`cosserat.numerics.cosserat`:

1. **Couple stress**, as ``y = c - m_hat`` (its deficit from the centre-line value c, which
   keeps the radicand S of ``eqn-nd_sigxy`` free of cancellation near the centre, where S
   vanishes), integrated with Radau IIA from ``xi_0 = 1/2 + s_0`` (started on the regular series
   ``y = mu s_0^2`` through the singular point, doc section 4) to the wall: its stable direction.
   An event stops it where S reaches zero (no real solution). Its absolute tolerance is atol
   times ``P_Y_SCALE``, the scale of y (``y ~ tau^2``, tiny when B nu is small; doc section 4).
2. **Spin and velocity**: ``l = ln(omega_hat / omega_hat_w)`` and ``P = int_1^xi e^l F1`` from
   the wall to xi_0 with DOP853, stopped where e^l underflows; the piece from xi_0 to the centre,
   where ``omega_hat ~ s^p``, is added in closed form.
3. **Velocity constants** from ``u_hat(1/2) = 0`` (centre-line velocity 1) and the slip condition
   ``u_hat(1) = 1 + eps K omega_hat(1)`` (or no slip), then **Delta** by Brent's method.

Status codes, never NaN in place of an answer (codes as in :mod:`cosserat.numerics.cosserat`).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from ..model.cells.channel import shear_stress
from ..model.rheologies.cosserat.channel import k_channel_radicand, k_torque_numerator
from .dop853 import dop853, dop853_eval1
from .radau import EVENT, MAX_STEPS, SUCCESS, dense_eval1, radau5
from .roots import B as ROOT
from .roots import brackets, brent_accept, brent_next, brent_start

# ----------------------------------------------------------------- parameter vector
P_A = 0  # A of eqn-yc2 [-]
P_SIN_PHI = 1  # sin(phi) [-]
P_ALPHA = 2  # L / sqrt(2(A+1)) [-]
P_EPS = 3  # d_p / H [-]
P_B_NU = 4  # slope of the shear stress, 2 tau_w [-]
P_WALL_GAP = 5  # sin(phi) - tau_w >= 0 [-]
P_C = 6  # couple stress at the centre line, sqrt(sin^2 phi / (2(A+1))) [-]
P_MU = 7  # series coefficient: y = mu s^2 near the centre [-]
P_S0 = 8  # where the couple-stress pass starts, xi_0 - 1/2 [-]
P_EPS_K = 9  # eps K at the walls, 0 if they do not slip [-]
P_Y_SCALE = 10  # scale of the deficit y across the half channel, absolute tolerance unit [-]
N_PARAMS = 11

# ----------------------------------------------------------------- status codes
OK = 0
NO_SOLUTION = 1
STALLED = 2
TOO_MANY_STEPS = 3
SINGULAR_VELOCITY = 4

# ----------------------------------------------------------------- result vector
I_U_S = 0  # u_hat at the wall [-]
I_W_S = 1  # omega_hat at the wall [-]
I_P_C = 2  # P at the centre line [-]
I_DELTA = 3  # Delta [d_p]
I_DELTA_OK = 4
I_XI_FAIL = 5
I_M_FAIL = 6  # m_hat there [-]
I_NFEV = 7
I_NSTEPS = 8
I_NLU = 9
I_XI_CUT = 10  # where the spin pass stopped [-]
I_STEPS_COUPLE = 11
I_STEPS_SPIN = 12
I_P_EXP = 13  # exponent p of omega_hat ~ s^p at xi_0 [-]
N_INFO = 14

LOG_UNDERFLOW = -745.0
JACOBIAN_ROOT_FLOOR = 1e-6
RADICAND_ROUNDOFF = 1e-12


@njit(cache=True, nogil=True)
def _state(xi: float, y: float, p: np.ndarray) -> tuple[float, float, float]:
    """(tau, numerator, S) at (xi, y) on the upper half (:mod:`cosserat.model.channel`)."""
    Bn = p[P_B_NU]
    tau = shear_stress(xi, Bn)
    num = k_torque_numerator(tau, p[P_WALL_GAP], 1.0 - xi, Bn, y, p[P_C], p[P_A], p[P_SIN_PHI])
    return tau, num, k_channel_radicand(tau, num, p[P_A])


@njit(cache=True, nogil=True)
def couple_rhs(xi, yv, p):
    """dy/dxi = -torque/(eps alpha), torque = numerator/(sqrt(S) + (1+A) tau) [-]."""
    tau, num, S = _state(xi, yv[0], p)
    root = math.sqrt(S) if S > 0.0 else 0.0
    den = root + (1.0 + p[P_A]) * tau
    out = np.empty(1)
    out[0] = 0.0 if den <= 0.0 else -num / den / (p[P_EPS] * p[P_ALPHA])
    return out


@njit(cache=True, nogil=True)
def couple_jac(xi, yv, p):
    """d(dy/dxi)/dy = -2(A+1) m_hat/(eps alpha sqrt(S)), sqrt(S) floored at a small fraction of
    its own scale (1+A) tau (sqrt(S) ~ kappa s on the series, kappa -> (1+A) B nu as eps -> 0):
    a floor fixed in units of sin(phi) would exceed sqrt(S) itself near the centre when B nu is
    small, and Newton's iteration would then stall on a wrong Jacobian."""
    tau, _, S = _state(xi, yv[0], p)
    m = p[P_C] - yv[0]
    floor = JACOBIAN_ROOT_FLOOR * (1.0 + p[P_A]) * tau
    out = np.empty((1, 1))
    root = max(math.sqrt(S) if S > 0.0 else 0.0, floor)
    out[0, 0] = -2.0 * (p[P_A] + 1.0) * m / (root * p[P_EPS] * p[P_ALPHA])
    return out


@njit(cache=True, nogil=True)
def couple_event(xi, yv, p):
    """S over its scale 2(A+1) sin^2 phi, plus the round-off allowance: <= 0 ends the pass."""
    _, _, S = _state(xi, yv[0], p)
    return S / (2.0 * (p[P_A] + 1.0) * p[P_SIN_PHI] ** 2) + RADICAND_ROUNDOFF


@njit(cache=True, nogil=True)
def flow_ratios(xi: float, y: float, p: np.ndarray) -> tuple[float, float]:
    """(F1, F2) of ``eqn-nd_fr1``-``eqn-nd_fr2`` on the paper's root in mapped variables:
    F1 = (A+1)(sqrt(S) + (1-A) tau)/sqrt(S), F2 = -2(A+1) m_hat/sqrt(S) [-]."""
    tau, _, S = _state(xi, y, p)
    A = p[P_A]
    root = max(math.sqrt(S) if S > 0.0 else 0.0, 1e-150)
    return (A + 1.0) * (root + (1.0 - A) * tau) / root, -2.0 * (A + 1.0) * (p[P_C] - y) / root


@njit(cache=True, nogil=True)
def _rates(xi: float, p: np.ndarray, cs) -> tuple[float, float]:
    """(d ln omega_hat/dxi, F1) at xi from the couple-stress solution."""
    ts, hs, ys, Q = cs
    y = dense_eval1(ts, hs, ys, Q, xi, 0)
    F1, F2 = flow_ratios(xi, y, p)
    return -F2 / (p[P_EPS] * p[P_ALPHA]), F1


@njit(cache=True, nogil=True)
def spin_rhs(t, yv, args):
    """(l, P)' in the pass variable t in [0, 1], xi = 1 - (1 - xi_0) t."""
    p, cs = args
    span = 0.5 - p[P_S0]
    xi = 1.0 - span * t
    rate, F1 = _rates(xi, p, cs)
    ell = yv[0]
    gain = math.exp(min(ell, 700.0)) if ell > LOG_UNDERFLOW else 0.0
    out = np.empty(2)
    out[0] = -span * rate
    out[1] = -span * gain * F1
    return out


@njit(cache=True, nogil=True)
def spin_event(t, yv, args):
    return yv[0] - LOG_UNDERFLOW


@njit(cache=True, nogil=True)
def xi_of(t: float, p: np.ndarray) -> float:
    return 1.0 - (0.5 - p[P_S0]) * t


@njit(cache=True, nogil=True)
def _pass_status(status: int) -> int:
    if status == SUCCESS:
        return OK
    if status == EVENT:
        return NO_SOLUTION
    if status == MAX_STEPS:
        return TOO_MANY_STEPS
    return STALLED


@njit(cache=True, nogil=True)
def velocity_hat(P: float, info: np.ndarray) -> float:
    """u_hat = u_hat_w - omega_hat_w P [-]."""
    return info[I_U_S] - info[I_W_S] * P


@njit(cache=True, nogil=True)
def spin_pass_at(xi, p, ts, ys, F, info):
    """(l, P) at points xi of [1/2, 1]: the DOP853 dense output, beyond the underflow cut
    (-inf, P there), and inside xi_0 the closed-form tail l = l_0 + p ln(s/s_0)."""
    n = xi.size
    ell = np.empty(n)
    P = np.empty(n)
    span = 0.5 - p[P_S0]
    t_end = ts[-1]
    reached = t_end >= 1.0
    pexp = info[I_P_EXP]
    for i in range(n):
        t = (1.0 - xi[i]) / span
        if t <= t_end:
            ell[i] = dop853_eval1(ts, ys, F, max(t, 0.0), 0)
            P[i] = dop853_eval1(ts, ys, F, max(t, 0.0), 1)
        elif not reached:
            ell[i] = -np.inf
            P[i] = ys[-1, 1]
        else:
            s = max(xi[i] - 0.5, 0.0)
            s0 = p[P_S0]
            ell0 = ys[-1, 0]
            ell[i] = ell0 + pexp * math.log(s / s0) if s > 0.0 else -np.inf
            # P(xi) = P_0 - int_xi^xi_0 e^l F1 = P_0 - e^l0 F1_0 s0 (1 - (s/s0)^(p+1))/(p+1)
            frac = (s / s0) ** (pexp + 1.0) if s > 0.0 else 0.0
            P[i] = ys[-1, 1] + (info[I_P_C] - ys[-1, 1]) * (1.0 - frac)
    return ell, P


@njit(cache=True, nogil=True)
def _excess(t, args):
    """u_hat(xi(t)) - f u_hat_w: zero at the thickness (``eqn-delta_defn``, u_0 = u(1/2))."""
    _, sp, info, f = args
    ts, ys, F = sp
    P = ys[-1, 1] if t >= ts[-1] else dop853_eval1(ts, ys, F, t, 1)
    return velocity_hat(P, info) - f * info[I_U_S]


@njit(cache=True, nogil=True)
def thickness(p, sp, info, f):
    """(Delta [d_p], ok): distance from the wall, over eps, where u(1/2) - u has fallen to
    f of its wall value."""
    args = (p, sp, info, f)
    g0 = _excess(0.0, args)
    if g0 == 0.0:
        return 0.0, True
    # the far end of the pass (xi_0, or the underflow cut, beyond which u_hat is constant)
    t_far = sp[0][-1]
    g_far = _excess(t_far, args)
    if not brackets(g0, g_far):
        return math.nan, False
    state = brent_start(0.0, t_far, g0, g_far)
    ok = False
    for _ in range(400):
        t, ok = brent_next(state, 4e-16)
        if ok:
            break
        brent_accept(state, t, _excess(t, args))
    return (1.0 - xi_of(state[ROOT], p)) / p[P_EPS], ok


@njit(cache=True, nogil=True)
def solve_case(p, rtol, atol, f, max_steps):
    """Solve the channel: (status, info, couple-stress solution, spin solution)."""
    info = np.zeros(N_INFO)
    info[I_DELTA] = math.nan
    x0 = 0.5 + p[P_S0]
    y0 = np.array([p[P_MU] * p[P_S0] ** 2])
    status, ts1, hs1, ys1, Q1, _, nfev, _, nlu, nsteps = radau5(
        couple_rhs, couple_jac, couple_event, x0, 1.0, y0, rtol, np.array([atol * p[P_Y_SCALE]]), p,
        max_steps, 0.0,
    )  # fmt: skip
    info[I_NFEV], info[I_NSTEPS], info[I_NLU] = nfev, nsteps, nlu
    info[I_STEPS_COUPLE] = nsteps
    cs = (ts1, hs1, ys1, Q1)
    no_spin = (np.zeros(1), np.zeros((1, 2)), np.zeros((0, 7, 2)))
    code = _pass_status(status)
    if code != OK:
        info[I_XI_FAIL], info[I_M_FAIL] = ts1[-1], p[P_C] - ys1[-1, 0]
        return code, info, cs, no_spin

    status2, ts2, ys2, F2, nfev2, nsteps2 = dop853(
        spin_rhs, spin_event, 0.0, 1.0, np.zeros(2), rtol, np.array([rtol, atol * p[P_EPS]]),
        (p, cs), max_steps,
    )  # fmt: skip
    info[I_NFEV] += nfev2
    info[I_NSTEPS] += nsteps2
    info[I_STEPS_SPIN] = nsteps2
    sp = (ts2, ys2, F2)
    if status2 != SUCCESS and status2 != EVENT:
        info[I_XI_FAIL] = xi_of(ts2[-1], p)
        return (TOO_MANY_STEPS if status2 == MAX_STEPS else STALLED), info, cs, sp
    info[I_XI_CUT] = xi_of(ts2[-1], p)
    P_c = ys2[-1, 1]
    if status2 == SUCCESS:
        # the tail from xi_0 to the centre: omega_hat ~ s^pexp there (doc section 4)
        s0 = p[P_S0]
        rate, F1 = _rates(x0, p, cs)
        pexp = s0 * rate
        info[I_P_EXP] = pexp
        P_c = P_c - math.exp(ys2[-1, 0]) * F1 * s0 / (pexp + 1.0)
    info[I_P_C] = P_c
    det = P_c - p[P_EPS_K]
    if not (math.isfinite(det) and abs(det) > 1e-300):
        return SINGULAR_VELOCITY, info, cs, sp
    w_s = 1.0 / det
    info[I_W_S] = w_s
    info[I_U_S] = 1.0 + p[P_EPS_K] * w_s
    delta, ok = thickness(p, sp, info, f)
    info[I_DELTA] = delta
    info[I_DELTA_OK] = 1.0 if ok else 0.0
    return OK, info, cs, sp


@njit(cache=True, nogil=True)
def thickness_of(p, ts, ys, F, info, f):
    """Delta for another fraction f from a solved case (a cached entry point)."""
    return thickness(p, (ts, ys, F), info, f)


@njit(cache=True, nogil=True)
def arrays_at(xi, y, p):
    """(tau, sqrt(S), F1) at points of the upper half in the mapped variables [-]."""
    n = xi.size
    tau = np.empty(n)
    root = np.empty(n)
    F1 = np.empty(n)
    for i in range(n):
        t, _, S = _state(xi[i], y[i], p)
        tau[i] = t
        root[i] = math.sqrt(S) if S > 0.0 else 0.0
        F1[i] = flow_ratios(xi[i], y[i], p)[0]
    return tau, root, F1
