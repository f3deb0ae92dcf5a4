"""Radau IIA (order 5) for small stiff systems, compiled with numba.

One general-n implicit integrator for every stiff initial-value problem of the package: adaptive
steps, the cubic collocation polynomial of each step as dense output, and a terminal event located
on that polynomial. It replaces the pure-Python integrators (``radau_scalar`` and SciPy's
``solve_ivp(method="Radau")``), whose per-step interpreter and NumPy overhead (7-100 us a step)
dominates the cost of the package's small (n = 1-4) systems; compiled, a step of a scalar
problem costs under 1 us (``benchmarks/bench_radau.py``).

The algorithm is that of Hairer & Wanner, *Solving Ordinary Differential Equations II: Stiff and
Differential-Algebraic Problems*, 2nd ed., Springer 1996, section IV.8 (the RADAU5 code), in the
form of SciPy's ``scipy/integrate/_ivp/radau.py``, reproduced decision for decision so that both
take the same steps at the same tolerances:

* the 3-stage collocation system is decoupled through the eigenvectors of the Radau matrix
  (``T``, ``TI``) into one real and one complex n x n system, solved by simplified Newton
  (at most ``NEWTON_MAXITER`` iterations, convergence-rate test of H&W IV.8 (8.10)-(8.11));
* the embedded error estimate is filtered through ``(MU_REAL/h - J)^-1`` (H&W IV.8 (8.19)), with
  the second solve on the first rejected attempt of a step (H&W (8.20));
* the step size follows the predictive (Gustafsson) controller of H&W IV.8 (8.25) with SciPy's
  safety factor, ``MIN_FACTOR`` and ``MAX_FACTOR``;
* the Jacobian is reused across steps while Newton converges fast, and the two LU
  factorisations are reused while the step size is unchanged (SciPy's ``current_jac``,
  ``LU_real``, ``LU_complex`` logic).

Entry points: :func:`radau5` (integrate), :func:`dense_eval` and :func:`dense_eval1` (evaluate
its dense output) and :func:`no_event`.

Caching. Numba does not cache machine code that holds the address of a Python object, and a
numba function passed as an argument is compiled as exactly that. :func:`radau5` called from
Python with function arguments is therefore compiled anew in every process (fine for tests).
Production code calls it from module-level ``@njit(cache=True)`` kernels that pass module-level
jitted functions; :func:`radau5` and its helpers that receive those functions are inlined
(``inline="always"``), so the addresses are dead code and the kernels are cached. Numba keys a
kernel's cache on the kernel's own source file only: after editing this module, delete the
``__pycache__`` of the modules whose kernels call it (or touch them) to recompile.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np
from numba import njit

__all__ = [
    "EVENT",
    "MAX_STEPS",
    "NOT_FINITE",
    "STEP_TOO_SMALL",
    "SUCCESS",
    "dense_eval",
    "dense_eval1",
    "no_event",
    "radau5",
]

SUCCESS = 0  # reached t_end
EVENT = 1  # terminal event triggered; solution truncated at t_event
STEP_TOO_SMALL = -1  # step size fell below 10 ulp of t (or Newton kept failing)
MAX_STEPS = -2  # more than max_steps steps
NOT_FINITE = -3  # fun returned non-finite values that step reduction could not cure

# Radau IIA tableau data, written as in SciPy's radau.py (same formulas, same digits) so that
# both implementations round identically.
_S6 = 6.0**0.5
C = np.array([(4.0 - _S6) / 10.0, (4.0 + _S6) / 10.0, 1.0])
E = np.array([-13.0 - 7.0 * _S6, -13.0 + 7.0 * _S6, -1.0]) / 3.0
MU_REAL = 3.0 + 3.0 ** (2.0 / 3.0) - 3.0 ** (1.0 / 3.0)
MU_COMPLEX = (
    3.0
    + 0.5 * (3.0 ** (1.0 / 3.0) - 3.0 ** (2.0 / 3.0))
    - 0.5j * (3.0 ** (5.0 / 6.0) + 3.0 ** (7.0 / 6.0))
)
T = np.array(
    [
        [0.09443876248897524, -0.14125529502095421, 0.03002919410514742],
        [0.25021312296533332, 0.20412935229379994, -0.38294211275726192],
        [1.0, 1.0, 0.0],
    ]
)
TI = np.array(
    [
        [4.17871859155190428, 0.32768282076106237, 0.52337644549944951],
        [-4.17871859155190428, -0.32768282076106237, 0.47662355450055044],
        [0.50287263494578682, -2.57192694985560522, 0.59603920482822492],
    ]
)
TI_COMPLEX = TI[1] + 1j * TI[2]
# Dense output: y(t_old + x h) = y_old + (Z^T P) [x, x^2, x^3] (collocation polynomial).
P = np.array(
    [
        [13.0 / 3.0 + 7.0 * _S6 / 3.0, -23.0 / 3.0 - 22.0 * _S6 / 3.0, 10.0 / 3.0 + 5.0 * _S6],
        [13.0 / 3.0 - 7.0 * _S6 / 3.0, -23.0 / 3.0 + 22.0 * _S6 / 3.0, 10.0 / 3.0 - 5.0 * _S6],
        [1.0 / 3.0, -8.0 / 3.0, 10.0 / 3.0],
    ]
)

NEWTON_MAXITER = 6
MIN_FACTOR = 0.2
MAX_FACTOR = 10.0
EPS = float(np.finfo(np.float64).eps)
# Output arrays start with room for this many steps and double when full: the production
# problems take 5-150 steps, so one or two allocations per call.
_INITIAL_CAPACITY = 64
# Illinois iterations converge superlinearly; this cap only matters for events with a root
# near t = 0, where "4 ulp of t" is far below the bracket that bisection can reach quickly.
_EVENT_MAXITER = 200

# error_model="numpy": a zero pivot or an overflow must give inf/nan (which the Newton and
# error tests turn into a step reduction), not raise ZeroDivisionError; it also drops the
# per-division checks from the hot loop.
_JIT: dict[str, Any] = {"cache": True, "nogil": True, "error_model": "numpy"}
# Every function that receives fun, jac or event is inlined into its caller at numba-IR level.
# A dispatcher passed as an argument is lowered as the address of a Python object (a "dynamic
# global"), and numba refuses to cache any function whose final machine code still holds one.
# Inlined, the callee's calls of its function arguments become direct calls of the caller's
# global dispatchers and the addresses are dead code, so a module-level entry point
# ``@njit(cache=True) def kernel(...): return radau5(rhs, jac, no_event, ...)`` is cached.
# Inlined code compiles with the caller's flags (error model, nogil), so these functions avoid
# divisions by zero instead of relying on error_model="numpy".
_INLINE: dict[str, Any] = {**_JIT, "inline": "always"}


@njit(cache=True, nogil=True)
def no_event(t: float, y: np.ndarray, args: np.ndarray) -> float:
    """Event function that never triggers: pass it to :func:`radau5` when there is no event."""
    return 1.0


@njit(**_JIT)
def _lu_factor(a: np.ndarray, piv: np.ndarray) -> None:
    """In-place LU factorisation with partial pivoting (LAPACK getrf semantics), float or complex.

    A zero pivot is left in place rather than reported: the solve then returns inf/nan, which
    the Newton iteration treats as a convergence failure and answers with a smaller step,
    as SciPy does after ``lu_factor``'s singular-matrix warning.
    """
    n = a.shape[0]
    for k in range(n):
        p = k
        # |re| + |im| is LAPACK's pivot measure (cabs1): no square root.
        amax = abs(a[k, k].real) + abs(a[k, k].imag)
        for i in range(k + 1, n):
            v = abs(a[i, k].real) + abs(a[i, k].imag)
            if v > amax:
                amax = v
                p = i
        piv[k] = p
        if p != k:
            for j in range(n):
                tmp = a[k, j]
                a[k, j] = a[p, j]
                a[p, j] = tmp
        pivot = a[k, k]
        if pivot != 0.0:
            inv = 1.0 / pivot
            for i in range(k + 1, n):
                lik = a[i, k] * inv
                a[i, k] = lik
                for j in range(k + 1, n):
                    a[i, j] -= lik * a[k, j]


@njit(**_JIT)
def _lu_solve(lu: np.ndarray, piv: np.ndarray, b: np.ndarray) -> None:
    """Solve ``A x = b`` in place from :func:`_lu_factor`'s factors."""
    n = lu.shape[0]
    for k in range(n):
        p = piv[k]
        if p != k:
            tmp = b[k]
            b[k] = b[p]
            b[p] = tmp
    for i in range(n):
        s = b[i]
        for j in range(i):
            s -= lu[i, j] * b[j]
        b[i] = s
    for i in range(n - 1, -1, -1):
        s = b[i]
        for j in range(i + 1, n):
            s -= lu[i, j] * b[j]
        b[i] = s / lu[i, i]


@njit(**_INLINE)
def _eval(fun: Callable, t: float, y: np.ndarray, args: object, out: np.ndarray) -> bool:
    """``out[:] = fun(t, y, args)``; False if any value is not finite."""
    v = fun(t, y, args)
    ok = True
    for j in range(out.shape[0]):
        out[j] = v[j]
        if not math.isfinite(v[j]):
            ok = False
    return ok


@njit(**_INLINE)
def _eval_jac(jac: Callable, t: float, y: np.ndarray, args: object, out: np.ndarray) -> None:
    v = jac(t, y, args)
    n = out.shape[0]
    for i in range(n):
        for j in range(n):
            out[i, j] = v[i, j]


@njit(**_JIT)
def _rms(v: np.ndarray, scale: np.ndarray) -> float:
    """SciPy's ``norm(v / scale)``: the root-mean-square of the scaled vector."""
    s = 0.0
    for j in range(v.shape[0]):
        r = v[j] / scale[j]
        s += r * r
    return math.sqrt(s / v.shape[0])


@njit(**_JIT)
def _rms3(dw: np.ndarray, scale: np.ndarray) -> float:
    """SciPy's ``norm(dW / scale)`` for the (3, n) Newton increment."""
    s = 0.0
    for i in range(3):
        for j in range(dw.shape[1]):
            r = dw[i, j] / scale[j]
            s += r * r
    return math.sqrt(s / (3 * dw.shape[1]))


@njit(**_JIT)
def _predict_factor(h_abs: float, h_abs_old: float, err: float, err_old: float) -> float:
    """Step-size factor of the predictive controller (H&W IV.8 (8.25); SciPy's predict_factor).

    ``h_abs_old`` or ``err_old`` NaN stands for SciPy's None (no previous step: one-step rule).
    """
    if math.isnan(err_old) or math.isnan(h_abs_old) or err == 0.0:
        multiplier = 1.0
    else:
        multiplier = h_abs / h_abs_old * (err_old / err) ** 0.25
    if err == 0.0:
        return math.inf
    return min(1.0, multiplier) * err**-0.25


@njit(**_INLINE)
def _initial_step(
    fun: Callable,
    args: object,
    t0: float,
    y0: np.ndarray,
    f0: np.ndarray,
    t_bound: float,
    direction: float,
    rtol: float,
    atol: np.ndarray,
    scale: np.ndarray,
    ytmp: np.ndarray,
    ftmp: np.ndarray,
) -> float:
    """SciPy's ``select_initial_step`` (H&W I, II.4) for an error estimator of order 3."""
    n = y0.shape[0]
    interval = abs(t_bound - t0)
    for j in range(n):
        scale[j] = atol[j] + abs(y0[j]) * rtol
    d0 = _rms(y0, scale)
    d1 = _rms(f0, scale)
    h0 = 1e-6 if d0 < 1e-5 or d1 < 1e-5 else 0.01 * d0 / d1
    h0 = min(h0, interval)
    for j in range(n):
        ytmp[j] = y0[j] + h0 * direction * f0[j]
    _eval(fun, t0 + h0 * direction, ytmp, args, ftmp)
    for j in range(n):
        ftmp[j] -= f0[j]
    d2 = _rms(ftmp, scale) / h0
    # Python's max(d1, nan) is d1: SciPy ignores a NaN trial derivative.
    dmax = d1 if math.isnan(d2) else max(d1, d2)
    if (d1 <= 1e-15 and d2 <= 1e-15) or dmax == 0.0:
        h1 = max(1e-6, h0 * 1e-3)
    else:
        h1 = (0.01 / dmax) ** 0.25
    return min(100.0 * h0, h1, interval)


@njit(**_INLINE)
def _newton(
    fun: Callable,
    args: object,
    t: float,
    y: np.ndarray,
    h: float,
    Z0: np.ndarray,
    Z: np.ndarray,
    W: np.ndarray,
    F: np.ndarray,
    dW: np.ndarray,
    ytmp: np.ndarray,
    scale: np.ndarray,
    tol: float,
    LUr: np.ndarray,
    pivr: np.ndarray,
    LUc: np.ndarray,
    pivc: np.ndarray,
    br: np.ndarray,
    bc: np.ndarray,
) -> tuple[bool, int, float, bool, int]:
    """Simplified Newton on the transformed collocation system (SciPy's solve_collocation_system).

    Works in the eigenbasis ``W = TI Z`` of the Radau matrix, so each iteration is one real and
    one complex n x n solve with the factors of ``MU_REAL/h - J`` and ``MU_COMPLEX/h - J``.
    Returns ``(converged, n_iter, rate, nonfinite, nfev)``; ``Z`` holds the last iterate and
    ``rate`` is NaN (SciPy's None) until two iterations have been made.
    """
    n = y.shape[0]
    m_real = MU_REAL / h
    m_cplx = MU_COMPLEX / h
    for j in range(n):
        for i in range(3):
            Z[i, j] = Z0[i, j]
        for i in range(3):
            W[i, j] = TI[i, 0] * Z0[0, j] + TI[i, 1] * Z0[1, j] + TI[i, 2] * Z0[2, j]
    dw_norm_old = math.nan
    rate = math.nan
    converged = False
    nonfinite = False
    nfev = 0
    k = 0
    for k in range(NEWTON_MAXITER):
        finite = True
        for i in range(3):
            for j in range(n):
                ytmp[j] = y[j] + Z[i, j]
            fi = fun(t + h * C[i], ytmp, args)
            for j in range(n):
                F[i, j] = fi[j]
                if not math.isfinite(fi[j]):
                    finite = False
        nfev += 3
        if not finite:
            nonfinite = True
            break
        for j in range(n):
            br[j] = TI[0, 0] * F[0, j] + TI[0, 1] * F[1, j] + TI[0, 2] * F[2, j] - m_real * W[0, j]
            bc[j] = (
                TI_COMPLEX[0] * F[0, j]
                + TI_COMPLEX[1] * F[1, j]
                + TI_COMPLEX[2] * F[2, j]
                - m_cplx * complex(W[1, j], W[2, j])
            )
        _lu_solve(LUr, pivr, br)
        _lu_solve(LUc, pivc, bc)
        for j in range(n):
            dW[0, j] = br[j]
            dW[1, j] = bc[j].real
            dW[2, j] = bc[j].imag
        dw_norm = _rms3(dW, scale)
        # SciPy lets a NaN increment run on until fun sees it; stopping here is equivalent
        # and cheaper (a singular LU or a non-finite Jacobian ends up here).
        if not math.isfinite(dw_norm):
            nonfinite = True
            break
        if k > 0:
            rate = dw_norm / dw_norm_old
            # H&W (8.11): diverging, or cannot reach tol within the remaining iterations.
            if rate >= 1.0 or rate ** (NEWTON_MAXITER - k) / (1.0 - rate) * dw_norm > tol:
                break
        for j in range(n):
            for i in range(3):
                W[i, j] += dW[i, j]
            for i in range(3):
                Z[i, j] = T[i, 0] * W[0, j] + T[i, 1] * W[1, j] + T[i, 2] * W[2, j]
        # H&W (8.10): the remaining error of the iterate, estimated from the contraction rate.
        if dw_norm == 0.0 or (k > 0 and rate / (1.0 - rate) * dw_norm < tol):
            converged = True
            break
        dw_norm_old = dw_norm
    return converged, k + 1, rate, nonfinite, nfev


@njit(**_JIT)
def _dense_point(
    t: float, t_old: float, h: float, y_old: np.ndarray, q: np.ndarray, out: np.ndarray
) -> None:
    """``out`` = the step's collocation polynomial at ``t`` (Horner in x = (t - t_old)/h)."""
    x = (t - t_old) / h
    for j in range(out.shape[0]):
        out[j] = y_old[j] + x * (q[j, 0] + x * (q[j, 1] + x * q[j, 2]))


@njit(**_INLINE)
def _locate_event(
    event: Callable,
    args: object,
    t_old: float,
    h: float,
    y_old: np.ndarray,
    q: np.ndarray,
    a: float,
    ga: float,
    b: float,
    gb: float,
    ytmp: np.ndarray,
) -> float:
    """Root of the event on one step's dense output, bracketed by ``ga > 0 >= gb``.

    Illinois (modified regula falsi) with a bisection step whenever three iterations failed to
    halve the bracket, to a bracket of 4 ulp of t. Returns the end of the final bracket on which
    the event has triggered (value <= 0), so the truncated state satisfies the event condition.
    """
    side = 0
    width_ref = abs(b - a)
    count = 0
    force_bisect = False
    for _ in range(_EVENT_MAXITER):
        if gb == 0.0 or abs(b - a) <= 4.0 * EPS * max(abs(a), abs(b)):
            break
        c = a + 0.5 * (b - a) if force_bisect else b - gb * (b - a) / (gb - ga)
        if not (c - a) * (b - c) > 0.0:  # outside, on an end, or nan
            c = a + 0.5 * (b - a)
        if c in (a, b):  # adjacent floats
            break
        _dense_point(c, t_old, h, y_old, q, ytmp)
        gc = event(c, ytmp, args)
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
    ts: np.ndarray, hs: np.ndarray, ys: np.ndarray, Qs: np.ndarray
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    cap = ts.shape[0]
    n = ys.shape[1]
    ts2 = np.empty(2 * cap)
    hs2 = np.empty(2 * cap)
    ys2 = np.empty((2 * cap, n))
    Qs2 = np.empty((2 * cap, n, 3))
    ts2[:cap] = ts
    hs2[:cap] = hs
    ys2[:cap] = ys
    Qs2[:cap] = Qs
    return ts2, hs2, ys2, Qs2


@njit(**_INLINE)
def radau5(
    fun: Callable,
    jac: Callable,
    event: Callable,
    t0: float,
    t_end: float,
    y0: np.ndarray,
    rtol: float,
    atol: np.ndarray,
    args: object,
    max_steps: int,
    first_step: float,
) -> tuple[int, np.ndarray, np.ndarray, np.ndarray, np.ndarray, float, int, int, int, int]:
    """Integrate ``y' = fun(t, y, args)`` from ``t0`` to ``t_end`` with Radau IIA of order 5.

    Parameters
    ----------
    fun : numba dispatcher
        ``fun(t, y, args) -> float64[:]`` of shape (n,), a new array (it is copied at once).
    jac : numba dispatcher
        ``jac(t, y, args) -> float64[:, :]`` of shape (n, n), ``d fun_i / d y_j``.
    event : numba dispatcher
        ``event(t, y, args) -> float``: terminal event, triggered when its value goes from
        > 0 to <= 0 (``solve_ivp``'s ``direction = -1, terminal = True``). Pass
        :func:`no_event` when there is none.
    t0, t_end : float
        Integration interval; ``t_end < t0`` integrates backwards.
    y0 : float64[:]
        Initial state, shape (n,).
    rtol : float
        Relative tolerance.
    atol : float64[:]
        Absolute tolerances, shape (n,).
    args : float64[:]
        Parameters passed through, unchanged, to ``fun``, ``jac`` and ``event`` (any numba
        value works, e.g. a tuple of arrays and floats).
    max_steps : int
        Maximum number of accepted steps.
    first_step : float
        Initial step size (clipped to the interval); ``<= 0`` chooses it as SciPy's
        ``select_initial_step`` does.

    Returns
    -------
    status : int
        :data:`SUCCESS`, :data:`EVENT`, :data:`STEP_TOO_SMALL`, :data:`MAX_STEPS` or
        :data:`NOT_FINITE` (the last trial steps failed because ``fun`` was not finite, or
        ``fun(t0, y0)`` itself is not).
    ts : float64[k + 1]
        Step boundaries: ``ts[0] = t0``, ``ts[-1]`` = ``t_end``, the event time, or where the
        integration stopped.
    hs : float64[k]
        Signed step sizes that scale each step's dense output.
    ys : float64[k + 1, n]
        Solution at ``ts``.
    Q : float64[k, n, 3]
        Dense output: ``y(t) = ys[i] + Q[i] @ [x, x**2, x**3]``, ``x = (t - ts[i]) / hs[i]``
        for ``t`` in step ``i`` (SciPy's ``RadauDenseOutput``). On :data:`EVENT` the last step
        is truncated at ``t_event`` but keeps its full ``hs[-1]``.
    t_event : float
        Event time (``nan`` unless ``status == EVENT``).
    nfev, njev, nlu, nsteps : int
        Evaluations of ``fun`` and ``jac``, LU factorisations, accepted steps.

    Notes
    -----
    Hairer & Wanner, Solving ODEs II, section IV.8, as implemented in SciPy's
    ``scipy/integrate/_ivp/radau.py``; see the module docstring. If the event is already
    <= 0 at ``t0`` the result is :data:`EVENT` at ``t0`` with no step. Non-finite values of
    ``fun`` in a trial step count as a Newton failure: the step is halved and retried. As in
    SciPy, ``rtol`` below 100 machine epsilons is raised to it; ``atol`` should be positive.
    The event time is located on the step's dense output by Illinois iterations to 4 ulp; the
    truncated state ``ys[-1]`` is the dense output at ``t_event``, where the event is <= 0.
    """
    n = y0.shape[0]
    t = float(t0)
    t_bound = float(t_end)
    # SciPy raises rtol below 100 eps to 100 eps (with a warning): the Newton tolerance and the
    # error estimate are meaningless below it.
    rtol = max(float(rtol), 100.0 * EPS)
    direction = 1.0 if t_bound >= t else -1.0

    cap = _INITIAL_CAPACITY
    ts = np.empty(cap)
    hs = np.empty(cap)
    ys = np.empty((cap, n))
    Qs = np.empty((cap, n, 3))

    # Work arrays, allocated once: inside the step loop only fun and jac allocate.
    y = np.empty(n)
    f = np.empty(n)
    y_new = np.empty(n)
    f_new = np.empty(n)
    ytmp = np.empty(n)
    scale = np.empty(n)
    ze = np.empty(n)
    err_vec = np.empty(n)
    br = np.empty(n)
    bc = np.empty(n, dtype=np.complex128)
    J = np.empty((n, n))
    LUr = np.empty((n, n))
    LUc = np.empty((n, n), dtype=np.complex128)
    pivr = np.empty(n, dtype=np.int64)
    pivc = np.empty(n, dtype=np.int64)
    Z0 = np.empty((3, n))
    Z = np.empty((3, n))
    W = np.empty((3, n))
    F = np.empty((3, n))
    dW = np.empty((3, n))

    finite_y0 = True
    for j in range(n):
        y[j] = y0[j]
        ys[0, j] = y0[j]
        if not math.isfinite(y0[j]):
            finite_y0 = False
    ts[0] = t
    nfev = 0
    njev = 0
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
        v = fun(t, y, args)
        if v.shape[0] != n:
            raise ValueError("fun must return an array of shape (n,)")
        nfev += 1
        ok = finite_y0
        for j in range(n):
            f[j] = v[j]
            if not math.isfinite(v[j]):
                ok = False
        if not ok:
            status = NOT_FINITE
            running = False
        elif t == t_bound:
            running = False

    h_abs = 0.0
    newton_tol = max(10.0 * EPS / rtol, min(0.03, rtol**0.5))
    if running:
        Jv = jac(t, y, args)
        if Jv.shape[0] != n or Jv.shape[1] != n:
            raise ValueError("jac must return an array of shape (n, n)")
        for i in range(n):
            for j in range(n):
                J[i, j] = Jv[i, j]
        njev += 1
        if first_step > 0.0:
            h_abs = min(first_step, abs(t_bound - t))
        else:
            h_abs = _initial_step(
                fun, args, t, y, f, t_bound, direction, rtol, atol, scale, ytmp, f_new
            )
            nfev += 1

    current_jac = True
    lu_valid = False
    h_abs_old_stored = math.nan  # SciPy's self.h_abs_old (NaN: None)
    err_old_stored = math.nan  # SciPy's self.error_norm_old
    h_abs_cur = h_abs
    h_abs_old = math.nan
    err_old = math.nan
    err = 0.0
    safety = 0.0
    rate = math.nan
    n_iter = 0
    h = 0.0
    t_new = t

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

            # Newton's starting guess: the previous step's collocation polynomial, extrapolated.
            if nsteps > 0:
                i0 = nsteps - 1
                t_old = ts[i0]
                h_prev = hs[i0]
                for i in range(3):
                    x = (t + h * C[i] - t_old) / h_prev
                    for j in range(n):
                        q = Qs[i0, j]
                        Z0[i, j] = ys[i0, j] + x * (q[0] + x * (q[1] + x * q[2])) - y[j]
            else:
                Z0[:, :] = 0.0

            for j in range(n):
                scale[j] = atol[j] + abs(y[j]) * rtol

            converged = False
            nonfinite = False
            while True:
                if not lu_valid:
                    m_real = MU_REAL / h
                    m_cplx = MU_COMPLEX / h
                    for i in range(n):
                        for j in range(n):
                            LUr[i, j] = -J[i, j]
                            LUc[i, j] = -J[i, j]
                        LUr[i, i] += m_real
                        LUc[i, i] += m_cplx
                    _lu_factor(LUr, pivr)
                    _lu_factor(LUc, pivc)
                    nlu += 2
                    lu_valid = True
                converged, n_iter, rate, nonfinite, nf = _newton(
                    fun, args, t, y, h, Z0, Z, W, F, dW, ytmp, scale, newton_tol,
                    LUr, pivr, LUc, pivc, br, bc,
                )  # fmt: skip
                nfev += nf
                if converged or current_jac:
                    break
                # A stale Jacobian may be why Newton failed: refresh it before cutting h.
                _eval_jac(jac, t, y, args, J)
                njev += 1
                current_jac = True
                lu_valid = False

            if not converged:
                h_abs_cur *= 0.5
                lu_valid = False
                failed_nonfinite = nonfinite
                continue

            for j in range(n):
                y_new[j] = y[j] + Z[2, j]
                ze[j] = (Z[0, j] * E[0] + Z[1, j] * E[1] + Z[2, j] * E[2]) / h
                err_vec[j] = f[j] + ze[j]
            # H&W (8.19): the raw embedded estimate is filtered through (MU_REAL/h - J)^-1 so
            # that it stays bounded for stiff components.
            _lu_solve(LUr, pivr, err_vec)
            for j in range(n):
                scale[j] = atol[j] + max(abs(y[j]), abs(y_new[j])) * rtol
            err = _rms(err_vec, scale)
            safety = 0.9 * (2 * NEWTON_MAXITER + 1) / (2 * NEWTON_MAXITER + n_iter)

            if rejected and err > 1.0:
                # H&W (8.20): after a rejection, one more filtering pass, evaluated at
                # y + err, removes the estimate's spurious growth for very stiff problems.
                for j in range(n):
                    ytmp[j] = y[j] + err_vec[j]
                _eval(fun, t, ytmp, args, f_new)
                nfev += 1
                for j in range(n):
                    err_vec[j] = f_new[j] + ze[j]
                _lu_solve(LUr, pivr, err_vec)
                err = _rms(err_vec, scale)
            if math.isnan(err):
                err = math.inf

            if err > 1.0:
                factor = _predict_factor(h_abs_cur, h_abs_old, err, err_old)
                h_abs_cur *= max(MIN_FACTOR, safety * factor)
                lu_valid = False
                rejected = True
                failed_nonfinite = False
                continue

            if not _eval(fun, t_new, y_new, args, f_new):
                nfev += 1
                h_abs_cur *= 0.5
                lu_valid = False
                failed_nonfinite = True
                continue
            nfev += 1
            accepted = True
            break

        if not accepted:
            break

        recompute_jac = n_iter > 2 and rate > 1e-3
        factor = _predict_factor(h_abs_cur, h_abs_old, err, err_old)
        factor = min(MAX_FACTOR, safety * factor)
        # Keeping h (and so the LU factors) is cheaper than a small increase.
        if not recompute_jac and factor < 1.2:
            factor = 1.0
        else:
            lu_valid = False
        if recompute_jac:
            _eval_jac(jac, t_new, y_new, args, J)
            njev += 1
            current_jac = True
        else:
            current_jac = False

        # SciPy records the step size proposed at the start of this step (before rejections)
        # as the controller's previous step; kept so that both take the same steps.
        h_abs_old_stored = h_abs
        err_old_stored = err
        h_abs = h_abs_cur * factor

        if nsteps + 1 >= ts.shape[0]:
            ts, hs, ys, Qs = _grow(ts, hs, ys, Qs)
        ts[nsteps + 1] = t_new
        hs[nsteps] = h
        for j in range(n):
            ys[nsteps + 1, j] = y_new[j]
            for m in range(3):
                Qs[nsteps, j, m] = Z[0, j] * P[0, m] + Z[1, j] * P[1, m] + Z[2, j] * P[2, m]
        nsteps += 1

        g_new = event(t_new, y_new, args)
        if g_old > 0.0 and g_new <= 0.0:
            i0 = nsteps - 1
            t_event = _locate_event(event, args, t, h, ys[i0], Qs[i0], t, g_old, t_new, g_new, ytmp)
            _dense_point(t_event, t, h, ys[i0], Qs[i0], ytmp)
            ts[nsteps] = t_event
            for j in range(n):
                ys[nsteps, j] = ytmp[j]
            status = EVENT
            break
        g_old = g_new

        t = t_new
        for j in range(n):
            y[j] = y_new[j]
            f[j] = f_new[j]

    k = nsteps
    return (
        status,
        ts[: k + 1].copy(),
        hs[:k].copy(),
        ys[: k + 1].copy(),
        Qs[:k].copy(),
        t_event,
        nfev,
        njev,
        nlu,
        nsteps,
    )


@njit(**_JIT)
def _step_index(ts: np.ndarray, t: float) -> int:
    """Step ``i`` with ``t`` in ``[ts[i], ts[i + 1]]`` (the lower one on a boundary, as SciPy)."""
    k = ts.shape[0] - 1
    s = 1.0 if ts[k] >= ts[0] else -1.0
    st = s * t
    lo = 0
    hi = k - 1
    while lo < hi:
        mid = (lo + hi) >> 1
        if st <= s * ts[mid + 1]:
            hi = mid
        else:
            lo = mid + 1
    return lo


@njit(**_JIT)
def dense_eval(
    ts: np.ndarray, hs: np.ndarray, ys: np.ndarray, Q: np.ndarray, t: np.ndarray
) -> np.ndarray:
    """Evaluate :func:`radau5`'s dense output at the points ``t``.

    Parameters
    ----------
    ts, hs, ys, Q : arrays
        As returned by :func:`radau5`.
    t : float64[:]
        Points, shape (m,), in any order; points outside ``[min(ts), max(ts)]`` (round-off)
        are clipped to it.

    Returns
    -------
    float64[m, n]
        The solution at ``t``.
    """
    m = t.shape[0]
    n = ys.shape[1]
    k = ts.shape[0] - 1
    out = np.empty((m, n))
    if k == 0:
        for p in range(m):
            for j in range(n):
                out[p, j] = ys[0, j]
        return out
    t_lo = min(ts[0], ts[k])
    t_hi = max(ts[0], ts[k])
    for p in range(m):
        tp = min(max(t[p], t_lo), t_hi)
        i = _step_index(ts, tp)
        if tp == ts[i + 1]:
            # the step's end: ys itself rather than the polynomial, which matches it only
            # to round-off
            for j in range(n):
                out[p, j] = ys[i + 1, j]
            continue
        x = (tp - ts[i]) / hs[i]
        for j in range(n):
            out[p, j] = ys[i, j] + x * (Q[i, j, 0] + x * (Q[i, j, 1] + x * Q[i, j, 2]))
    return out


@njit(**_JIT)
def dense_eval1(
    ts: np.ndarray, hs: np.ndarray, ys: np.ndarray, Q: np.ndarray, t: float, component: int
) -> float:
    """One component of :func:`radau5`'s dense output at one point ``t`` (clipped as
    :func:`dense_eval`): the allocation-free path for use inside right-hand sides."""
    k = ts.shape[0] - 1
    if k == 0:
        return ys[0, component]
    tp = min(max(t, min(ts[0], ts[k])), max(ts[0], ts[k]))
    i = _step_index(ts, tp)
    if tp == ts[i + 1]:
        return ys[i + 1, component]
    x = (tp - ts[i]) / hs[i]
    return ys[i, component] + x * (
        Q[i, component, 0] + x * (Q[i, component, 1] + x * Q[i, component, 2])
    )
