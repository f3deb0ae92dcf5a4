"""Compiled quadrature of the mu(I) rate on plane shear (``routes.mui``'s velocity integral).

The numerical mu(I) route integrates the rate ``sqrt(p) I(mu)`` over the pieces between its
breakpoints with SciPy's adaptive Gauss-Kronrod ``quad_vec`` (21 points, the pieces as one
vector, error in the max norm). Each evaluation of that vector is a handful of NumPy calls on
a few dozen numbers, so a solve spends most of its time in Python (``docs/performance.md``,
``cosserat validate``). :func:`plane_pieces` is the same algorithm compiled for the plane
cell: the same nodes, weights, error estimate, subdivision order (the intervals of largest
error first, up to 128 at a time, as ``quad_vec`` takes them), stopping rules and the same
floating-point operations in the same order, so its integrals are ``quad_vec``'s to the last
bit (``tests/test_mui.py`` checks it over many problems). Only a converged result is
returned as such; the caller redoes anything else with ``quad_vec`` itself.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from ..model.constitutive import FloatArray

CONVERGED = 0
"""``quad_vec``'s status "Target precision reached"; any other status makes the caller
integrate with ``quad_vec`` itself."""

_PARALLEL = 128
"""Intervals ``quad_vec`` subdivides per pass at most (its ``parallel_count``)."""

# Gauss-Kronrod 21 points: nodes, the 10-point Gauss weights, the 21-point Kronrod weights,
# exactly as scipy.integrate._quad_vec writes them
_X = np.array([
    0.995657163025808080735527280689003, 0.973906528517171720077964012084452,
    0.930157491355708226001207180059508, 0.865063366688984510732096688423493,
    0.780817726586416897063717578345042, 0.679409568299024406234327365114874,
    0.562757134668604683339000099272694, 0.433395394129247190799265943165784,
    0.294392862701460198131126603103866, 0.148874338981631210884826001129720,
    0.0,
    -0.148874338981631210884826001129720, -0.294392862701460198131126603103866,
    -0.433395394129247190799265943165784, -0.562757134668604683339000099272694,
    -0.679409568299024406234327365114874, -0.780817726586416897063717578345042,
    -0.865063366688984510732096688423493, -0.930157491355708226001207180059508,
    -0.973906528517171720077964012084452, -0.995657163025808080735527280689003,
])  # fmt: skip
_W = np.array([
    0.066671344308688137593568809893332, 0.149451349150580593145776339657697,
    0.219086362515982043995534934228163, 0.269266719309996355091226921569469,
    0.295524224714752870173892994651338, 0.295524224714752870173892994651338,
    0.269266719309996355091226921569469, 0.219086362515982043995534934228163,
    0.149451349150580593145776339657697, 0.066671344308688137593568809893332,
])  # fmt: skip
_V = np.array([
    0.011694638867371874278064396062192, 0.032558162307964727478818972459390,
    0.054755896574351996031381300244580, 0.075039674810919952767043140916190,
    0.093125454583697605535065465083366, 0.109387158802297641899210590325805,
    0.123491976262065851077958109831074, 0.134709217311473325928054001771707,
    0.142775938577060080797094273138717, 0.147739104901338491374841515972068,
    0.149445554002916905664936468389821, 0.147739104901338491374841515972068,
    0.142775938577060080797094273138717, 0.134709217311473325928054001771707,
    0.123491976262065851077958109831074, 0.109387158802297641899210590325805,
    0.093125454583697605535065465083366, 0.075039674810919952767043140916190,
    0.054755896574351996031381300244580, 0.032558162307964727478818972459390,
    0.011694638867371874278064396062192,
])  # fmt: skip
_EPS = float(np.finfo(float).eps)
_TINY = float(np.finfo(float).tiny)


@njit(cache=True, nogil=True, error_model="numpy")
def _rates(s, a, width, B_nu, mu_2, mu_s, I_0, gap, out):  # pragma: no cover - compiled
    """The pieces' integrands at the point s of [0, 1]: ``integrand_at(a + s width) width``
    of ``MuIFlow`` on the plane cell, operation for operation (``ratio_shape``,
    ``normal_stress_at``, ``inertial_number_from_gap``)."""
    excess_scale = mu_2 - mu_s
    for k in range(a.size):
        t = a[k] + s * width[k]
        g = B_nu * t
        q = 1.0 / (1.0 + g)
        one_minus_q = g / (1.0 + g)
        sat = mu_2 * one_minus_q + gap * q
        e = excess_scale - sat
        inertial = I_0 * max(e, 0.0) / sat if e > 0.0 else 0.0
        out[k] = math.sqrt(1.0 + B_nu * t) * inertial * width[k]


@njit(cache=True, nogil=True, error_model="numpy")
def _max_abs(x):  # pragma: no cover - compiled
    """``np.amax(abs(x))``: NaN if any element is NaN."""
    m = abs(x[0])
    for k in range(1, x.size):
        v = abs(x[k])
        if v != v or m != m:
            m = math.nan
        elif v > m:
            m = v
    return m


@njit(cache=True, nogil=True, error_model="numpy")
def _gk21(lo, hi, a, width, B_nu, mu_2, mu_s, I_0, gap, out):  # pragma: no cover - compiled
    """``scipy.integrate._quad_vec._quadrature_gk`` with the 21-point rule on [lo, hi]:
    the integral into ``out``; returns (err, round_err)."""
    m = a.size
    fv = np.empty((21, m))
    c = 0.5 * (lo + hi)
    h = 0.5 * (hi - lo)
    s_k = np.zeros(m)
    s_k_abs = np.zeros(m)
    for i in range(21):
        _rates(c + h * _X[i], a, width, B_nu, mu_2, mu_s, I_0, gap, fv[i])
        vv = _V[i]
        for k in range(m):
            s_k[k] += vv * fv[i, k]
            s_k_abs[k] += vv * abs(fv[i, k])
    s_g = np.zeros(m)
    for i in range(10):
        for k in range(m):
            s_g[k] += _W[i] * fv[2 * i + 1, k]
    s_k_dabs = np.zeros(m)
    for i in range(21):
        for k in range(m):
            s_k_dabs[k] += _V[i] * abs(fv[i, k] - s_k[k] / 2.0)
    tmp = np.empty(m)
    for k in range(m):
        tmp[k] = (s_k[k] - s_g[k]) * h
    err = _max_abs(tmp)
    for k in range(m):
        tmp[k] = s_k_dabs[k] * h
    dabs = _max_abs(tmp)
    if dabs != 0 and err != 0:
        err = dabs * min(1.0, (200 * err / dabs) ** 1.5)
    scale = 50 * _EPS * h
    for k in range(m):
        tmp[k] = scale * s_k_abs[k]
    round_err = _max_abs(tmp)
    if round_err > 2.2250738585072014e-308:  # sys.float_info.min
        err = max(err, round_err)
    for k in range(m):
        out[k] = h * s_k[k]
    return err, round_err


@njit(cache=True, nogil=True, error_model="numpy")
def _pop(errs, lows, live, n):  # pragma: no cover - compiled
    """The live interval that ``heapq`` pops first from ``(-err, lo, hi)``: the largest
    error, then the lowest start."""
    best = -1
    for j in range(n):
        if not live[j]:
            continue
        if best < 0 or -errs[j] < -errs[best] or (-errs[j] == -errs[best] and lows[j] < lows[best]):
            best = j
    return best


@njit(cache=True, nogil=True, error_model="numpy")
def plane_pieces(
    a: FloatArray,
    width: FloatArray,
    B_nu: float,
    mu_2: float,
    mu_s: float,
    I_0: float,
    gap: float,
    epsrel: float,
    limit: int,
) -> tuple[FloatArray, int]:  # pragma: no cover - compiled
    """The integrals of the plane cell's mu(I) rate over the pieces ``[a, a + width]`` of
    distance from the peak wall, as ``routes.mui._quad_intervals`` asks ``quad_vec`` for them
    (each piece mapped onto [0, 1], ``epsabs`` the smallest normal float, ``norm="max"``).

    Parameters
    ----------
    a, width : ndarray
        The pieces' starts and widths (each width > 0) [-].
    B_nu : float
        The plane cell's B nu (p = 1 + B nu t) [-].
    mu_2, mu_s, I_0 : float
        The mu(I) law [-].
    gap : float
        mu_2 minus the stress ratio at the peak wall [-].
    epsrel : float
        Relative tolerance [-].
    limit : int
        Largest number of subintervals (``quad_vec``'s ``limit``).

    Returns
    -------
    (ndarray, int)
        The integrals, and ``quad_vec``'s status (:data:`CONVERGED` or not).
    """
    m = a.size
    cap = limit + 2 * _PARALLEL + 2
    errs = np.empty(cap)
    lows = np.empty(cap)
    highs = np.empty(cap)
    ints = np.empty((cap, m))
    live = np.zeros(cap, dtype=np.bool_)
    busy = np.zeros(cap, dtype=np.bool_)  # popped, its integral still to be read this pass
    total = np.empty(m)
    err0, rounding_error = _gk21(0.0, 1.0, a, width, B_nu, mu_2, mu_s, I_0, gap, total)
    global_error = err0
    ints[0, :] = total
    errs[0], lows[0], highs[0], live[0] = err0, 0.0, 1.0, True
    n_used, n_live = 1, 1
    status = 1  # NOT_CONVERGED
    picked = np.empty(_PARALLEL, dtype=np.int64)
    s1 = np.empty(m)
    s2 = np.empty(m)
    while n_live > 0 and n_live < limit:
        tol = max(_TINY, epsrel * _max_abs(total))
        count = 0
        err_sum = 0.0
        for j in range(_PARALLEL):
            if n_live == 0:
                break
            if j > 0 and err_sum > global_error - tol / 8:
                break
            best = _pop(errs, lows, live, n_used)
            live[best] = False
            busy[best] = True
            n_live -= 1
            picked[count] = best
            count += 1
            err_sum += errs[best]
        for j in range(count):
            old = picked[j]
            lo, hi, old_err = lows[old], highs[old], errs[old]
            mid = 0.5 * (lo + hi)
            err1, round1 = _gk21(lo, mid, a, width, B_nu, mu_2, mu_s, I_0, gap, s1)
            err2, round2 = _gk21(mid, hi, a, width, B_nu, mu_2, mu_s, I_0, gap, s2)
            for k in range(m):
                total[k] += s1[k] + s2[k] - ints[old, k]
            global_error += err1 + err2 - old_err
            rounding_error += round1 + round2
            for lo_, hi_, e_, s_ in ((lo, mid, err1, s1), (mid, hi, err2, s2)):
                slot = -1
                for q in range(n_used):  # reuse a freed slot, else a new one
                    if not live[q] and not busy[q]:
                        slot = q
                        break
                if slot < 0:
                    slot = n_used
                    n_used += 1
                errs[slot], lows[slot], highs[slot], live[slot] = e_, lo_, hi_, True
                ints[slot, :] = s_
                n_live += 1
        for j in range(count):
            busy[picked[j]] = False
        if n_live >= 2:
            tol = max(_TINY, epsrel * _max_abs(total))
            if global_error < tol / 8:
                status = CONVERGED
                break
            if global_error < rounding_error:
                status = 2
                break
        if not (math.isfinite(global_error) and math.isfinite(rounding_error)):
            status = 3
            break
    return total, status
