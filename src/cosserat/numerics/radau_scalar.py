"""Radau IIA (order 5) for one stiff equation, compiled with numba, without allocations.

The couple-stress balance of the Cosserat kernels is a single stiff equation. The general
:func:`~cosserat.numerics.radau.radau5` takes it as a system of size one: its right-hand side
returns a new array (two heap allocations per stage evaluation, seven to ten per step) and its
linear algebra loops over n x n matrices of one element. :func:`radau5_scalar` is the same
algorithm for n = 1, written on floats: the right-hand side, its derivative and the event
return floats, the LU factorisations are a real and a complex reciprocal. Every arithmetic
operation is :func:`radau5`'s, in the same order, so both take the same steps and return the
same numbers to the last bit (``tests/numerics/test_radau_scalar.py``), at about a third of the
cost per step (``benchmarks/bench_speed.py``), and it compiles in a fraction of the time.

It also returns the stage values of every accepted step (``Zs``): with them the derivative of
the computed solution with respect to a parameter of the equation follows without another
integration (:func:`sensitivity`, internal differentiation of the collocation equations).

Entry points: :func:`radau5_scalar`, :func:`sensitivity`. The dense output is
:func:`~cosserat.numerics.radau.radau5`'s (``ts, hs, ys[:, None], Q[:, None, :]``) and is
evaluated by :func:`~cosserat.numerics.radau.dense_eval` and ``dense_eval1``.

Caching: as :func:`radau5`, the integrator is inlined into the kernel that calls it
(``numerics/radau.py``, "Caching").
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np
from numba import njit

from .radau import (
    _EVENT_MAXITER,
    _INITIAL_CAPACITY,
    EPS,
    EVENT,
    MAX_FACTOR,
    MAX_STEPS,
    MIN_FACTOR,
    MU_COMPLEX,
    MU_REAL,
    NEWTON_MAXITER,
    NOT_FINITE,
    STEP_TOO_SMALL,
    SUCCESS,
    TI,
    TI_COMPLEX,
    C,
    E,
    P,
    T,
    _predict_factor,
)

__all__ = ["RADAU_A", "radau5_scalar", "sensitivity"]

_JIT: dict[str, Any] = {"cache": True, "nogil": True, "error_model": "numpy"}
_INLINE: dict[str, Any] = {**_JIT, "inline": "always"}

_S6 = 6.0**0.5
# The Radau IIA matrix (Hairer & Wanner II, Table IV.5.6): the collocation equations are
# Z_i = h sum_j A_ij f(t + c_j h, y + Z_j); radau5 solves them in the eigenbasis T of A.
RADAU_A = np.array(
    [
        [(88.0 - 7.0 * _S6) / 360.0, (296.0 - 169.0 * _S6) / 1800.0, (-2.0 + 3.0 * _S6) / 225.0],
        [(296.0 + 169.0 * _S6) / 1800.0, (88.0 + 7.0 * _S6) / 360.0, (-2.0 - 3.0 * _S6) / 225.0],
        [(16.0 - _S6) / 36.0, (16.0 + _S6) / 36.0, 1.0 / 9.0],
    ]
)


@njit(**_JIT)
def _rms1(v: float, scale: float) -> float:
    """``radau._rms`` for n = 1 (the same operations)."""
    r = v / scale
    return math.sqrt(r * r / 1)


@njit(**_JIT)
def _rms3(z0: float, z1: float, z2: float, scale: float) -> float:
    """``radau._rms3`` for n = 1 (the same operations, in the same order)."""
    s = 0.0
    r = z0 / scale
    s += r * r
    r = z1 / scale
    s += r * r
    r = z2 / scale
    s += r * r
    return math.sqrt(s / 3)


@njit(**_INLINE)
def _initial_step(
    fun: Callable,
    args: object,
    t0: float,
    y0: float,
    f0: float,
    t_bound: float,
    direction: float,
    rtol: float,
    atol: float,
) -> float:
    """``radau._initial_step`` for n = 1."""
    interval = abs(t_bound - t0)
    scale = atol + abs(y0) * rtol
    d0 = _rms1(y0, scale)
    d1 = _rms1(f0, scale)
    h0 = 1e-6 if d0 < 1e-5 or d1 < 1e-5 else 0.01 * d0 / d1
    h0 = min(h0, interval)
    ytmp = y0 + h0 * direction * f0
    ftmp = fun(t0 + h0 * direction, ytmp, args)
    ftmp -= f0
    d2 = _rms1(ftmp, scale) / h0
    dmax = d1 if math.isnan(d2) else max(d1, d2)
    if (d1 <= 1e-15 and d2 <= 1e-15) or dmax == 0.0:
        h1 = max(1e-6, h0 * 1e-3)
    else:
        h1 = (0.01 / dmax) ** 0.25
    return min(100.0 * h0, h1, interval)


@njit(**_INLINE)
def _locate_event(
    event: Callable,
    args: object,
    t_old: float,
    h: float,
    y_old: float,
    q0: float,
    q1: float,
    q2: float,
    a: float,
    ga: float,
    b: float,
    gb: float,
) -> float:
    """``radau._locate_event`` for n = 1 (Illinois on the step's dense output)."""
    side = 0
    width_ref = abs(b - a)
    count = 0
    force_bisect = False
    for _ in range(_EVENT_MAXITER):
        if gb == 0.0 or abs(b - a) <= 4.0 * EPS * max(abs(a), abs(b)):
            break
        c = a + 0.5 * (b - a) if force_bisect else b - gb * (b - a) / (gb - ga)
        if not (c - a) * (b - c) > 0.0:
            c = a + 0.5 * (b - a)
        if c in (a, b):
            break
        x = (c - t_old) / h
        gc = event(c, y_old + x * (q0 + x * (q1 + x * q2)), args)
        if gc > 0.0:
            a, ga = c, gc
            if side == 1:
                gb *= 0.5
            side = 1
        else:
            b, gb = c, gc
            if side == -1:
                ga *= 0.5
            side = -1
        count += 1
        force_bisect = False
        if count == 3:
            force_bisect = abs(b - a) > 0.5 * width_ref
            width_ref = abs(b - a)
            count = 0
    return b


@njit(**_JIT)
def _grow(
    ts: np.ndarray, hs: np.ndarray, ys: np.ndarray, Qs: np.ndarray, Zs: np.ndarray
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """The output arrays at twice their capacity (element loops: no broadcasting code)."""
    cap = ts.shape[0]
    ts2 = np.empty(2 * cap)
    hs2 = np.empty(2 * cap)
    ys2 = np.empty((2 * cap, 1))
    Qs2 = np.empty((2 * cap, 1, 3))
    Zs2 = np.empty((2 * cap, 3))
    for i in range(cap):
        ts2[i] = ts[i]
        hs2[i] = hs[i]
        ys2[i, 0] = ys[i, 0]
        for m in range(3):
            Qs2[i, 0, m] = Qs[i, 0, m]
            Zs2[i, m] = Zs[i, m]
    return ts2, hs2, ys2, Qs2, Zs2


@njit(**_JIT)
def _trim(
    ts: np.ndarray, hs: np.ndarray, ys: np.ndarray, Qs: np.ndarray, Zs: np.ndarray, k: int
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Copies of the first k steps (element loops: no broadcasting code to compile)."""
    ts2 = np.empty(k + 1)
    hs2 = np.empty(k)
    ys2 = np.empty((k + 1, 1))
    Qs2 = np.empty((k, 1, 3))
    Zs2 = np.empty((k, 3))
    for i in range(k + 1):
        ts2[i] = ts[i]
        ys2[i, 0] = ys[i, 0]
    for i in range(k):
        hs2[i] = hs[i]
        for m in range(3):
            Qs2[i, 0, m] = Qs[i, 0, m]
            Zs2[i, m] = Zs[i, m]
    return ts2, hs2, ys2, Qs2, Zs2


@njit(**_INLINE)
def radau5_scalar(
    fun: Callable,
    jac: Callable,
    event: Callable,
    t0: float,
    t_end: float,
    y0: float,
    rtol: float,
    atol: float,
    args: object,
    max_steps: int,
    first_step: float,
) -> tuple[int, np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray, float, int, int, int]:
    """Integrate ``y' = fun(t, y, args)`` for one unknown, with Radau IIA of order 5.

    :func:`~cosserat.numerics.radau.radau5` for n = 1 (its docstring has the details), with
    float-valued ``fun``, ``jac`` (dfun/dy) and ``event``, a float ``y0`` and ``atol``.

    Returns
    -------
    status : int
        As :func:`radau5`.
    ts, hs, ys, Q : arrays
        As :func:`radau5` (``ys`` of shape (k + 1, 1), ``Q`` (k, 1, 3)).
    Zs : float64[k, 3]
        The converged stage increments of each accepted step:
        ``y(ts[i] + C[j] hs[i]) = ys[i] + Zs[i, j]``.
    t_event : float
    nfev, nlu, nsteps : int
        Evaluations of ``fun``, LU factorisations (two per factorised step), accepted steps.
    """
    t = float(t0)
    t_bound = float(t_end)
    rtol = max(float(rtol), 100.0 * EPS)
    direction = 1.0 if t_bound >= t else -1.0

    cap = _INITIAL_CAPACITY
    ts = np.empty(cap)
    hs = np.empty(cap)
    ys = np.empty((cap, 1))
    Qs = np.empty((cap, 1, 3))
    Zs = np.empty((cap, 3))

    y = float(y0)
    f = 0.0
    ys[0, 0] = y
    ts[0] = t
    nfev = 0
    nlu = 0
    nsteps = 0
    status = SUCCESS
    t_event = math.nan
    running = True

    g_old = event(t, y, args)
    if g_old <= 0.0:
        status = EVENT
        t_event = t
        running = False
    else:
        f = fun(t, y, args)
        nfev += 1
        if not (math.isfinite(y) and math.isfinite(f)):
            status = NOT_FINITE
            running = False
        elif t == t_bound:
            running = False

    J = 0.0
    h_abs = 0.0
    newton_tol = max(10.0 * EPS / rtol, min(0.03, rtol**0.5))
    if running:
        J = jac(t, y, args)
        if first_step > 0.0:
            h_abs = min(first_step, abs(t_bound - t))
        else:
            h_abs = _initial_step(fun, args, t, y, f, t_bound, direction, rtol, atol)
            nfev += 1

    current_jac = True
    lu_valid = False
    LUr = 0.0
    LUc = 0j
    h_abs_old_stored = math.nan
    err_old_stored = math.nan
    h_abs_cur = h_abs
    h_abs_old = math.nan
    err_old = math.nan
    err = 0.0
    safety = 0.0
    rate = math.nan
    n_iter = 0
    h = 0.0
    t_new = t
    y_new = y
    f_new = 0.0
    z0 = z1 = z2 = 0.0

    while running and direction * (t_bound - t) > 0.0:
        if nsteps >= max_steps:
            status = MAX_STEPS
            break
        min_step = 10.0 * abs(math.nextafter(t, direction * math.inf) - t)
        if h_abs < min_step:
            h_abs_cur = min_step
            h_abs_old = math.nan
            err_old = math.nan
        else:
            h_abs_cur = h_abs
            h_abs_old = h_abs_old_stored
            err_old = err_old_stored

        rejected = False
        accepted = False
        failed_nonfinite = False
        while True:
            if h_abs_cur < min_step:
                status = NOT_FINITE if failed_nonfinite else STEP_TOO_SMALL
                break
            h = h_abs_cur * direction
            t_new = t + h
            if direction * (t_new - t_bound) > 0.0:
                t_new = t_bound
            h = t_new - t
            h_abs_cur = abs(h)

            # Newton's starting guess: the previous step's collocation polynomial
            s0 = s1 = s2 = 0.0
            if nsteps > 0:
                i0 = nsteps - 1
                t_old = ts[i0]
                h_prev = hs[i0]
                q0, q1, q2 = Qs[i0, 0, 0], Qs[i0, 0, 1], Qs[i0, 0, 2]
                x = (t + h * C[0] - t_old) / h_prev
                s0 = ys[i0, 0] + x * (q0 + x * (q1 + x * q2)) - y
                x = (t + h * C[1] - t_old) / h_prev
                s1 = ys[i0, 0] + x * (q0 + x * (q1 + x * q2)) - y
                x = (t + h * C[2] - t_old) / h_prev
                s2 = ys[i0, 0] + x * (q0 + x * (q1 + x * q2)) - y

            scale = atol + abs(y) * rtol

            converged = False
            nonfinite = False
            while True:
                if not lu_valid:
                    m_real = MU_REAL / h
                    m_cplx = MU_COMPLEX / h
                    LUr = -J
                    LUc = complex(-J)
                    LUr += m_real
                    LUc += m_cplx
                    nlu += 2
                    lu_valid = True
                # simplified Newton in the eigenbasis of A (radau._newton for n = 1)
                m_real = MU_REAL / h
                m_cplx = MU_COMPLEX / h
                z0, z1, z2 = s0, s1, s2
                w0 = TI[0, 0] * s0 + TI[0, 1] * s1 + TI[0, 2] * s2
                w1 = TI[1, 0] * s0 + TI[1, 1] * s1 + TI[1, 2] * s2
                w2 = TI[2, 0] * s0 + TI[2, 1] * s1 + TI[2, 2] * s2
                dw_norm_old = math.nan
                rate = math.nan
                converged = False
                nonfinite = False
                k = 0
                for k in range(NEWTON_MAXITER):
                    f0 = fun(t + h * C[0], y + z0, args)
                    f1 = fun(t + h * C[1], y + z1, args)
                    f2 = fun(t + h * C[2], y + z2, args)
                    nfev += 3
                    if not (math.isfinite(f0) and math.isfinite(f1) and math.isfinite(f2)):
                        nonfinite = True
                        break
                    br = TI[0, 0] * f0 + TI[0, 1] * f1 + TI[0, 2] * f2 - m_real * w0
                    bc = (
                        TI_COMPLEX[0] * f0
                        + TI_COMPLEX[1] * f1
                        + TI_COMPLEX[2] * f2
                        - m_cplx * complex(w1, w2)
                    )
                    br = br / LUr
                    bc = bc / LUc
                    d0, d1, d2 = br, bc.real, bc.imag
                    dw_norm = _rms3(d0, d1, d2, scale)
                    if not math.isfinite(dw_norm):
                        nonfinite = True
                        break
                    if k > 0:
                        rate = dw_norm / dw_norm_old
                        if rate >= 1.0 or rate ** (NEWTON_MAXITER - k) / (1.0 - rate) * dw_norm > (
                            newton_tol
                        ):
                            break
                    w0 += d0
                    w1 += d1
                    w2 += d2
                    z0 = T[0, 0] * w0 + T[0, 1] * w1 + T[0, 2] * w2
                    z1 = T[1, 0] * w0 + T[1, 1] * w1 + T[1, 2] * w2
                    z2 = T[2, 0] * w0 + T[2, 1] * w1 + T[2, 2] * w2
                    if dw_norm == 0.0 or (k > 0 and rate / (1.0 - rate) * dw_norm < newton_tol):
                        converged = True
                        break
                    dw_norm_old = dw_norm
                n_iter = k + 1
                if converged or current_jac:
                    break
                J = jac(t, y, args)
                current_jac = True
                lu_valid = False

            if not converged:
                h_abs_cur *= 0.5
                lu_valid = False
                failed_nonfinite = nonfinite
                continue

            y_new = y + z2
            ze = (z0 * E[0] + z1 * E[1] + z2 * E[2]) / h
            err_vec = f + ze
            err_vec = err_vec / LUr
            scale = atol + max(abs(y), abs(y_new)) * rtol
            err = _rms1(err_vec, scale)
            safety = 0.9 * (2 * NEWTON_MAXITER + 1) / (2 * NEWTON_MAXITER + n_iter)

            if rejected and err > 1.0:
                f_new = fun(t, y + err_vec, args)
                nfev += 1
                err_vec = f_new + ze
                err_vec = err_vec / LUr
                err = _rms1(err_vec, scale)
            if math.isnan(err):
                err = math.inf

            if err > 1.0:
                factor = _predict_factor(h_abs_cur, h_abs_old, err, err_old)
                h_abs_cur *= max(MIN_FACTOR, safety * factor)
                lu_valid = False
                rejected = True
                failed_nonfinite = False
                continue

            f_new = fun(t_new, y_new, args)
            nfev += 1
            if not math.isfinite(f_new):
                h_abs_cur *= 0.5
                lu_valid = False
                failed_nonfinite = True
                continue
            accepted = True
            break

        if not accepted:
            break

        recompute_jac = n_iter > 2 and rate > 1e-3
        factor = _predict_factor(h_abs_cur, h_abs_old, err, err_old)
        factor = min(MAX_FACTOR, safety * factor)
        if not recompute_jac and factor < 1.2:
            factor = 1.0
        else:
            lu_valid = False
        if recompute_jac:
            J = jac(t_new, y_new, args)
            current_jac = True
        else:
            current_jac = False

        h_abs_old_stored = h_abs
        err_old_stored = err
        h_abs = h_abs_cur * factor

        if nsteps + 1 >= ts.shape[0]:
            ts, hs, ys, Qs, Zs = _grow(ts, hs, ys, Qs, Zs)
        ts[nsteps + 1] = t_new
        hs[nsteps] = h
        ys[nsteps + 1, 0] = y_new
        for m in range(3):
            Qs[nsteps, 0, m] = z0 * P[0, m] + z1 * P[1, m] + z2 * P[2, m]
        Zs[nsteps, 0], Zs[nsteps, 1], Zs[nsteps, 2] = z0, z1, z2
        nsteps += 1

        g_new = event(t_new, y_new, args)
        if g_old > 0.0 and g_new <= 0.0:
            i0 = nsteps - 1
            q0, q1, q2 = Qs[i0, 0, 0], Qs[i0, 0, 1], Qs[i0, 0, 2]
            t_event = _locate_event(
                event, args, t, h, ys[i0, 0], q0, q1, q2, t, g_old, t_new, g_new
            )
            x = (t_event - t) / h
            ts[nsteps] = t_event
            ys[nsteps, 0] = ys[i0, 0] + x * (q0 + x * (q1 + x * q2))
            status = EVENT
            break
        g_old = g_new

        t = t_new
        y = y_new
        f = f_new

    ts, hs, ys, Qs, Zs = _trim(ts, hs, ys, Qs, Zs, nsteps)
    return status, ts, hs, ys, Qs, Zs, t_event, nfev, nlu, nsteps


@njit(**_INLINE)
def sensitivity(
    derivatives: Callable,
    args: object,
    ts: np.ndarray,
    hs: np.ndarray,
    ys: np.ndarray,
    Zs: np.ndarray,
    s0: float,
) -> tuple[np.ndarray, np.ndarray]:
    """Derivative of a :func:`radau5_scalar` solution with respect to a parameter p.

    Internal differentiation (Bock 1981; Hairer & Wanner II, section IV.8 for the method):
    each accepted step solves the collocation equations
    ``Z_i = h sum_j A_ij f(t + c_j h, y + Z_j; p)``; differentiating them at the converged
    stages gives, for ``dZ = dZ/dp`` and ``s = dy/dp`` at the step's start, the 3 x 3 linear
    system ``(I - h A diag(J_j)) dZ = h A (J s + g)``, ``J_j = df/dy``, ``g_j = df/dp`` at the
    stages, and ``s_new = s + dZ_3``. This is the exact derivative of the computed solution on
    its step sequence (to the Newton tolerance), with no error control of its own and no
    second integration: the cost is three evaluations of ``derivatives`` per step.

    Parameters
    ----------
    derivatives : numba function
        ``(t, y, args) -> (float, float)``: the derivatives of ``fun`` in y and in p.
    ts, hs, ys, Zs : arrays
        As returned by :func:`radau5_scalar` (every step accepted and whole: not after an event).
    s0 : float
        dy/dp at ``ts[0]``.

    Returns
    -------
    ss : float64[k + 1, 1]
        dy/dp at ``ts``.
    dQ : float64[k, 1, 3]
        Its dense output, in the form of ``Q``: ``dy/dp(t) = ss[i] + dQ[i] @ [x, x^2, x^3]``.
    """
    k = hs.shape[0]
    ss = np.empty((k + 1, 1))
    dQ = np.empty((k, 1, 3))
    s = s0
    ss[0, 0] = s
    M = np.empty((3, 3))
    r = np.empty(3)
    Jv = np.empty(3)
    rhs = np.empty(3)
    for i in range(k):
        t, h, y = ts[i], hs[i], ys[i, 0]
        for j in range(3):
            tj = t + C[j] * h
            yj = y + Zs[i, j]
            dfdy, dfdp = derivatives(tj, yj, args)
            Jv[j] = dfdy
            rhs[j] = dfdy * s + dfdp
        for a in range(3):
            r[a] = h * (RADAU_A[a, 0] * rhs[0] + RADAU_A[a, 1] * rhs[1] + RADAU_A[a, 2] * rhs[2])
            for b in range(3):
                M[a, b] = (1.0 if a == b else 0.0) - h * RADAU_A[a, b] * Jv[b]
        _solve3(M, r)
        s += r[2]
        ss[i + 1, 0] = s
        for m in range(3):
            dQ[i, 0, m] = r[0] * P[0, m] + r[1] * P[1, m] + r[2] * P[2, m]
    return ss, dQ


@njit(**_JIT)
def _solve3(M: np.ndarray, r: np.ndarray) -> None:
    """Solve ``M x = r`` in place (3 x 3, Gaussian elimination with partial pivoting)."""
    for c in range(3):
        p = c
        for i in range(c + 1, 3):
            if abs(M[i, c]) > abs(M[p, c]):
                p = i
        if p != c:
            for j in range(3):
                M[c, j], M[p, j] = M[p, j], M[c, j]
            r[c], r[p] = r[p], r[c]
        for i in range(c + 1, 3):
            lik = M[i, c] / M[c, c]
            for j in range(c, 3):
                M[i, j] -= lik * M[c, j]
            r[i] -= lik * r[c]
    for i in range(2, -1, -1):
        s = r[i]
        for j in range(i + 1, 3):
            s -= M[i, j] * r[j]
        r[i] = s / M[i, i]
