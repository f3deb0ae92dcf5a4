"""DOP853 for small non-stiff systems, compiled with numba: the quadrature pass.

The spin and velocity pass (``docs/numerics.md``) integrates two quadratures with nothing stiff
in them. There Radau IIA, order 5 with an order-3 error estimate, pays for an implicit method
it does not need: it took 55-191 steps where this explicit method of order 8 takes 9-50
(``docs/performance.md``). Stiff passes use :mod:`cosserat.numerics.radau`; this is only the
quadrature pass.

The algorithm is that of Hairer, Norsett & Wanner, *Solving Ordinary Differential Equations I*,
2nd ed., Springer 1993, section II.10 (DOP853), in the form of SciPy's
``scipy/integrate/_ivp/rk.py`` (``DOP853``): the same coefficients, the combined 5th/3rd-order
error estimate, the step controller, SciPy's ``select_initial_step``, and the 7th-order dense
output of three extra stages. The terminal event is checked at the end of each step, and the
step in which it fires is kept whole (its dense output stays valid).

Like :func:`cosserat.numerics.radau.radau5`, :func:`dop853` receives the right-hand side as a
numba function and is inlined into its caller, so that the kernels calling it are cached
(``numerics/radau.py``, "Caching").
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from numba import njit
from scipy.integrate._ivp import dop853_coefficients as _coefficients

from .radau import EVENT, MAX_STEPS, NOT_FINITE, STEP_TOO_SMALL, SUCCESS

__all__ = ["dop853", "dop853_eval1"]

N_STAGES = _coefficients.N_STAGES  # 12; 3 more for the dense output
A = np.ascontiguousarray(_coefficients.A, dtype=np.float64)
B = np.ascontiguousarray(_coefficients.B, dtype=np.float64)
C = np.ascontiguousarray(_coefficients.C, dtype=np.float64)
E3 = np.ascontiguousarray(_coefficients.E3, dtype=np.float64)
E5 = np.ascontiguousarray(_coefficients.E5, dtype=np.float64)
D = np.ascontiguousarray(_coefficients.D, dtype=np.float64)
SAFETY, MIN_FACTOR, MAX_FACTOR = 0.9, 0.2, 10.0
EXPONENT = -1.0 / 8.0  # error estimator of order 7
_INITIAL_CAPACITY = 64
_JIT: dict[str, Any] = {"cache": True, "nogil": True, "error_model": "numpy"}
_INLINE: dict[str, Any] = {**_JIT, "inline": "always"}


@njit(**_JIT)
def _store(K: np.ndarray, row: int, values: np.ndarray) -> None:
    """``K[row, :] = values`` as an element loop (a slice assignment makes numba compile its
    shape-mismatch error message, seconds of the first run's compilation)."""
    for j in range(values.shape[0]):
        K[row, j] = values[j]


@njit(**_INLINE)
def dop853(fun, event, t0, t_end, y0, rtol, atol, args, max_steps):
    """Integrate ``y' = fun(t, y, args)`` from ``t0`` to ``t_end`` (either direction).

    Parameters
    ----------
    fun : numba function
        ``fun(t, y, args) -> float64[:]`` of shape (n,).
    event : numba function
        ``event(t, y, args) -> float``, terminal: the integration stops at the end of the step
        in which it goes from > 0 to <= 0.
    t0, t_end : float
    y0 : float64[:]
    rtol : float
    atol : float64[:]
    args : any
        Passed through to ``fun`` and ``event``.
    max_steps : int

    Returns
    -------
    (status, ts, ys, F, nfev, nsteps)
        ``status`` as :mod:`cosserat.numerics.radau` (SUCCESS, EVENT, MAX_STEPS,
        STEP_TOO_SMALL, NOT_FINITE); ``ts`` (k+1,), ``ys`` (k+1, n); ``F`` (k, 7, n) the dense
        output of each step, evaluated by :func:`dop853_eval1`.
    """
    n = y0.shape[0]
    direction = 1.0 if t_end >= t0 else -1.0
    cap = _INITIAL_CAPACITY
    ts = np.empty(cap + 1)
    ys = np.empty((cap + 1, n))
    Fs = np.empty((cap, 7, n))
    K = np.empty((N_STAGES + 4, n))
    ytmp = np.empty(n)
    y = y0.copy()
    t = t0
    ts[0] = t
    for j in range(n):
        ys[0, j] = y[j]
    nsteps = 0
    nfev = 1
    f = fun(t, y, args)
    for j in range(n):
        if not (math.isfinite(f[j]) and math.isfinite(y[j])):
            return NOT_FINITE, ts[:1].copy(), ys[:1].copy(), Fs[:0].copy(), nfev, 0
    # SciPy's select_initial_step (error estimator of order 7)
    interval = abs(t_end - t0)
    d0 = d1 = 0.0
    for j in range(n):
        sc = atol[j] + abs(y[j]) * rtol
        d0 += (y[j] / sc) ** 2
        d1 += (f[j] / sc) ** 2
    d0, d1 = math.sqrt(d0 / n), math.sqrt(d1 / n)
    h0 = 1e-6 if d0 < 1e-5 or d1 < 1e-5 else 0.01 * d0 / d1
    h0 = min(h0, interval)
    for j in range(n):
        ytmp[j] = y[j] + h0 * direction * f[j]
    f1 = fun(t + h0 * direction, ytmp, args)
    nfev += 1
    d2 = 0.0
    for j in range(n):
        sc = atol[j] + abs(y[j]) * rtol
        d2 += ((f1[j] - f[j]) / sc) ** 2
    d2 = math.sqrt(d2 / n) / h0 if h0 > 0.0 else 0.0
    flat = d1 <= 1e-15 and d2 <= 1e-15
    h1 = max(1e-6, h0 * 1e-3) if flat else (0.01 / max(d1, d2)) ** 0.125
    h_abs = min(100.0 * h0, h1, interval)

    status = SUCCESS
    ev_old = event(t, y, args)
    while direction * (t_end - t) > 0.0:
        if nsteps >= max_steps:
            status = MAX_STEPS
            break
        min_step = 10.0 * abs(np.nextafter(t, direction * np.inf) - t)
        h_abs = max(h_abs, min_step)
        rejected = False
        failed = False
        h = 0.0
        t_new = t
        h_next = h_abs
        while True:
            if h_abs < min_step:
                failed = True
                break
            t_new = t + h_abs * direction
            if direction * (t_new - t_end) > 0.0:
                t_new = t_end
            h = t_new - t
            h_abs = abs(h)
            for j in range(n):
                K[0, j] = f[j]
            for s in range(1, N_STAGES):
                for j in range(n):
                    acc = 0.0
                    for r in range(s):
                        acc += A[s, r] * K[r, j]
                    ytmp[j] = y[j] + h * acc
                _store(K, s, fun(t + C[s] * h, ytmp, args))
            for j in range(n):
                acc = 0.0
                for r in range(N_STAGES):
                    acc += B[r] * K[r, j]
                ytmp[j] = y[j] + h * acc
            # np.int64: the literal would compile _store a second time
            _store(K, np.int64(N_STAGES), fun(t_new, ytmp, args))
            nfev += N_STAGES
            err5 = err3 = 0.0
            finite = True
            for j in range(n):
                sc = atol[j] + max(abs(y[j]), abs(ytmp[j])) * rtol
                e5 = 0.0
                e3 = 0.0
                for r in range(N_STAGES + 1):
                    e5 += E5[r] * K[r, j]
                    e3 += E3[r] * K[r, j]
                e5 /= sc
                e3 /= sc
                err5 += e5 * e5
                err3 += e3 * e3
                finite = finite and math.isfinite(ytmp[j])
            # SciPy's _estimate_error_norm: squared 2-norms (not means) over sqrt(n)
            if err5 == 0.0 and err3 == 0.0:
                error = 0.0
            else:
                error = h_abs * err5 / math.sqrt((err5 + 0.01 * err3) * n)
            if not (finite and math.isfinite(error)):
                h_abs *= 0.5
                rejected = True
                continue
            if error < 1.0:
                factor = MAX_FACTOR if error == 0.0 else min(MAX_FACTOR, SAFETY * error**EXPONENT)
                if rejected:
                    factor = min(1.0, factor)
                h_next = h_abs * factor
                break
            h_abs *= max(MIN_FACTOR, SAFETY * error**EXPONENT)
            rejected = True
        if failed:
            status = STEP_TOO_SMALL
            break
        y_new = ytmp.copy()
        f_new = K[N_STAGES].copy()
        # dense output: three extra stages (SciPy's Dop853DenseOutput)
        for s in range(N_STAGES + 1, N_STAGES + 4):
            for j in range(n):
                acc = 0.0
                for r in range(s):
                    acc += A[s, r] * K[r, j]
                ytmp[j] = y[j] + h * acc
            _store(K, s, fun(t + C[s] * h, ytmp, args))
        nfev += 3
        if nsteps == cap:
            ts2 = np.empty(2 * cap + 1)
            ys2 = np.empty((2 * cap + 1, n))
            Fs2 = np.empty((2 * cap, 7, n))
            for i in range(cap + 1):
                ts2[i] = ts[i]
                for j in range(n):
                    ys2[i, j] = ys[i, j]
            for i in range(cap):
                for r in range(7):
                    for j in range(n):
                        Fs2[i, r, j] = Fs[i, r, j]
            ts, ys, Fs, cap = ts2, ys2, Fs2, 2 * cap
        for j in range(n):
            dy = y_new[j] - y[j]
            Fs[nsteps, 0, j] = dy
            Fs[nsteps, 1, j] = h * f[j] - dy
            Fs[nsteps, 2, j] = 2.0 * dy - h * (f_new[j] + f[j])
            for i in range(4):
                acc = 0.0
                for r in range(N_STAGES + 4):
                    acc += D[i, r] * K[r, j]
                Fs[nsteps, 3 + i, j] = h * acc
        nsteps += 1
        ts[nsteps] = t_new
        for j in range(n):
            ys[nsteps, j] = y_new[j]
        t, y, f = t_new, y_new, f_new
        h_abs = h_next
        ev_new = event(t, y, args)
        if ev_old > 0.0 >= ev_new:
            status = EVENT
            break
        ev_old = ev_new
    return (
        status,
        ts[: nsteps + 1].copy(),
        ys[: nsteps + 1].copy(),
        Fs[:nsteps].copy(),
        nfev,
        nsteps,
    )


@njit(**_JIT)
def dop853_eval1(ts, ys, F, t, component):
    """Component ``component`` of the dense output at ``t`` (clipped to the solved interval)."""
    k = ts.shape[0] - 1
    if k == 0:
        return ys[0, component]
    forward = ts[k] >= ts[0]
    # the step containing t: binary search on the monotone ts
    lo, hi = 0, k
    while hi - lo > 1:
        mid = (lo + hi) // 2
        if (ts[mid] <= t) if forward else (ts[mid] >= t):
            lo = mid
        else:
            hi = mid
    h = ts[lo + 1] - ts[lo]
    x = (t - ts[lo]) / h if h != 0.0 else 0.0
    x = min(max(x, 0.0), 1.0)
    out = 0.0
    for i in range(6, -1, -1):
        out = (out + F[lo, i, component]) * (x if (6 - i) % 2 == 0 else 1.0 - x)
    return out + ys[lo, component]
