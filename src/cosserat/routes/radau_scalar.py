"""Radau IIA (order 5) for one *scalar* stiff ODE, in plain Python floats.

The couple-stress equation is a scalar stiff ODE; SciPy's ``solve_ivp(method="Radau")`` spends
~0.5 ms of NumPy and LU overhead per step on it. For a scalar equation the 3x3 collocation
system decouples, through the eigenvectors of the Radau matrix, into one real and one complex
*scalar* equation, so each Newton iteration is a few float divisions. This module is SciPy's
algorithm (Hairer & Wanner's RADAU5: simplified Newton, embedded error estimate with the
stiffness filter, step-size prediction, Jacobian reuse) specialised to floats: the same
accepted steps as SciPy to round-off, ~10x faster.

Dense output is the collocation polynomial of each step (cubic), as in SciPy.
"""

from __future__ import annotations

import bisect
import functools
import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from scipy.integrate._ivp import radau as _tables

from ..model.constitutive import FloatArray

_C = [float(c) for c in _tables.C]
_E = [float(e) for e in _tables.E]
_T = [[float(x) for x in row] for row in _tables.T]
_TI = [[float(x) for x in row] for row in _tables.TI]
_P = [[float(x) for x in row] for row in _tables.P]
_MU_REAL = float(_tables.MU_REAL)
_MU_COMPLEX = complex(_tables.MU_COMPLEX)
NEWTON_MAXITER = 6
MIN_FACTOR, MAX_FACTOR = 0.2, 10.0
_SQRT3 = math.sqrt(3.0)


class StepFailedError(RuntimeError):
    """The integration could not continue; ``t`` and ``y`` say where it stopped."""

    def __init__(self, message: str, t: float, y: float) -> None:
        super().__init__(f"{message} at t = {t:.6g}")
        self.t, self.y = t, y


@dataclass(frozen=True, eq=False)
class ScalarSolution:
    """Step points and the cubic dense output of each step.

    ``status``: 0 reached the end, 1 stopped by the event (at ``t_event``).
    """

    t: FloatArray  # step points, in integration order
    y: FloatArray
    q: FloatArray  # (steps, 3): y(t) = y_old + q0 x + q1 x^2 + q2 x^3, x = (t - t_old)/h
    status: int
    t_event: float | None
    nfev: int
    njev: int

    @property
    def steps(self) -> int:
        return len(self.t) - 1

    def at(self, t: float) -> float:
        """Dense output at one float (no NumPy: for use inside right-hand sides)."""
        ts = self._ascending
        k = min(max(bisect.bisect_left(ts, t) - 1, 0), len(ts) - 2)
        if self.t[-1] < self.t[0]:
            k = len(ts) - 2 - k
        t_old = float(self.t[k])
        h = float(self.t[k + 1]) - t_old
        x = (t - t_old) / h if h != 0.0 else 0.0
        q0, q1, q2 = self._q[k]
        return self._y[k] + x * (q0 + x * (q1 + x * q2))

    @functools.cached_property
    def _ascending(self) -> list[float]:
        return sorted(self.t.tolist())

    @functools.cached_property
    def _q(self) -> list[tuple[float, float, float]]:
        return [tuple(row) for row in self.q.tolist()]

    @functools.cached_property
    def _y(self) -> list[float]:
        return self.y.tolist()

    def __call__(self, t: float | FloatArray) -> FloatArray:
        """Dense output at ``t`` (scalar or array) within the integrated interval."""
        tt = np.asarray(t, dtype=float)
        ts = self.t
        forward = ts[-1] >= ts[0]
        grid = ts if forward else ts[::-1]
        k = np.clip(np.searchsorted(grid, tt, side="left") - 1, 0, len(ts) - 2)
        if not forward:
            k = len(ts) - 2 - k
        t_old = ts[k]
        h = ts[k + 1] - t_old
        x = np.where(h != 0.0, (tt - t_old) / np.where(h != 0.0, h, 1.0), 0.0)
        q = self.q[k]
        return self.y[k] + x * (q[..., 0] + x * (q[..., 1] + x * q[..., 2]))


def radau_scalar(
    fun: Callable[[float, float], float],
    t0: float,
    t1: float,
    y0: float,
    rtol: float,
    atol: float,
    event: Callable[[float, float], float] | None = None,
    max_steps: int = 20_000,
) -> ScalarSolution:
    """Integrate y' = fun(t, y) from t0 to t1 (either direction).

    ``event(t, y)``: terminal, when it goes from > 0 to <= 0 along the integration (located
    on the dense output by bisection). Raises :class:`StepFailedError` (with the point reached) if
    the step size falls below 1e-13 of the interval or more than ``max_steps`` steps are
    needed: the equation is then singular there (for the couple stress: a start within
    round-off of the yield bound, where dF/dm ~ 1/sqrt(S)).
    """
    direction = 1.0 if t1 >= t0 else -1.0
    nfev = njev = 0

    def f(t: float, y: float) -> float:
        nonlocal nfev
        nfev += 1
        return fun(t, y)

    def jacobian(t: float, y: float, fy: float) -> float:
        nonlocal njev
        njev += 1
        d = 1e-8 * max(abs(y), 1e-3)
        return (f(t, y + d) - fy) / d

    t, y = float(t0), float(y0)
    fy = f(t, y)
    # initial step (Hairer-Norsett-Wanner II.4, as SciPy), error estimator order 3
    interval = abs(t1 - t0)
    scale = atol + abs(y) * rtol
    d0, d1 = abs(y) / scale, abs(fy) / scale
    h0 = 1e-6 if d0 < 1e-5 or d1 < 1e-5 else 0.01 * d0 / d1
    h0 = min(h0, interval)
    f1 = f(t + h0 * direction, y + h0 * direction * fy)
    d2 = abs(f1 - fy) / scale / h0 if h0 > 0 else 0.0
    h1 = max(1e-6, h0 * 1e-3) if d1 <= 1e-15 and d2 <= 1e-15 else (0.01 / max(d1, d2)) ** 0.25
    h_abs = min(100 * h0, h1, interval)

    J = jacobian(t, y, fy)
    current_jac = True
    h_abs_old: float | None = None
    err_old: float | None = None
    lu_h: float | None = None
    ts, ys, qs = [t], [y], []
    q_prev: tuple[float, float, float] | None = None
    ev_old = event(t, y) if event is not None else 1.0
    status, t_event = 0, None

    while direction * (t1 - t) > 0.0:
        if len(ts) > max_steps:
            raise StepFailedError(f"more than {max_steps} steps", t, y)
        min_step = max(10.0 * abs(math.nextafter(t, direction * math.inf) - t), 1e-13 * interval)
        h_abs = max(h_abs, min_step)
        rejected = False
        while True:
            if h_abs < min_step:
                raise StepFailedError(f"the step size fell below {min_step:.1e}", t, y)
            h = h_abs * direction
            t_new = t + h
            if direction * (t_new - t1) > 0:
                t_new = t1
            h = t_new - t
            h_abs = abs(h)
            if q_prev is None:
                z = [0.0, 0.0, 0.0]
            else:  # extrapolate the previous step's collocation polynomial
                h_prev = ts[-1] - ts[-2]
                z = []
                for c in _C:
                    x = (t + h * c - ts[-2]) / h_prev
                    z.append(ys[-2] + x * (q_prev[0] + x * (q_prev[1] + x * q_prev[2])) - y)
            scale = atol + abs(y) * rtol
            converged = False
            while not converged:
                m_real = _MU_REAL / h
                m_cplx = _MU_COMPLEX / h
                lu_real = m_real - J
                lu_cplx = m_cplx - J
                lu_h = h
                converged, n_iter, z, rate = _newton(
                    f, t, y, h, z, scale, rtol, m_real, m_cplx, lu_real, lu_cplx
                )
                if not converged:
                    if current_jac:
                        break
                    J = jacobian(t, y, fy)
                    current_jac = True
            if not converged:
                h_abs *= 0.5
                continue
            y_new = y + z[2]
            ze = (z[0] * _E[0] + z[1] * _E[1] + z[2] * _E[2]) / h
            error = (fy + ze) / lu_real
            scale = atol + max(abs(y), abs(y_new)) * rtol
            err = abs(error) / scale
            safety = 0.9 * (2 * NEWTON_MAXITER + 1) / (2 * NEWTON_MAXITER + n_iter)
            if rejected and err > 1.0:
                error = (f(t, y + error) + ze) / lu_real
                err = abs(error) / scale
            if err > 1.0:
                factor = _predict(h_abs, h_abs_old, err, err_old)
                h_abs *= max(MIN_FACTOR, safety * factor)
                rejected = True
                continue
            break
        recompute_jac = n_iter > 2 and rate is not None and rate > 1e-3
        factor = min(MAX_FACTOR, safety * _predict(h_abs, h_abs_old, err, err_old))
        if not recompute_jac and factor < 1.2:
            factor = 1.0
        f_new = f(t_new, y_new)
        if recompute_jac:
            J = jacobian(t_new, y_new, f_new)
            current_jac = True
        else:
            current_jac = False
        h_abs_old, err_old = h_abs, err
        q = tuple(sum(z[i] * _P[i][j] for i in range(3)) for j in range(3))
        ts.append(t_new)
        ys.append(y_new)
        qs.append(q)
        q_prev = q  # type: ignore[assignment]
        if event is not None:
            ev_new = event(t_new, y_new)
            if ev_old > 0.0 >= ev_new:
                t_event = _locate(event, t, t_new, y, q, ev_old)
                x = (t_event - t) / (t_new - t)
                ts[-1] = t_event
                ys[-1] = y + x * (q[0] + x * (q[1] + x * q[2]))
                qs[-1] = (q[0] * x, q[1] * x * x, q[2] * x**3)
                status = 1
                break
            ev_old = ev_new
        t, y, fy = t_new, y_new, f_new
        h_abs *= factor
    del lu_h
    return ScalarSolution(
        np.array(ts), np.array(ys), np.array(qs).reshape(-1, 3), status, t_event, nfev, njev
    )


def _predict(h_abs: float, h_abs_old: float | None, err: float, err_old: float | None) -> float:
    if err_old is None or h_abs_old is None or err == 0.0:
        multiplier = 1.0
    else:
        multiplier = h_abs / h_abs_old * (err_old / err) ** 0.25
    return min(1.0, multiplier) * (err**-0.25 if err > 0 else math.inf)


_T00, _T01, _T02 = _T[0]
_T10, _T11, _T12 = _T[1]
_T20, _T21, _T22 = _T[2]
_TI00, _TI01, _TI02 = _TI[0]
_TIC0, _TIC1, _TIC2 = (complex(_TI[1][j], _TI[2][j]) for j in range(3))
_TI10, _TI11, _TI12 = _TI[1]
_TI20, _TI21, _TI22 = _TI[2]
_C0, _C1, _C2 = _C


def _newton(f, t, y, h, z, scale, rtol, m_real, m_cplx, lu_real, lu_cplx):  # type: ignore[no-untyped-def]
    """Simplified Newton on the decoupled collocation system (SciPy's
    solve_collocation_system for n = 1, written out for floats)."""
    tol = max(10 * 2.220446049250313e-16 / rtol, min(0.03, rtol**0.5))
    z0, z1, z2 = z
    w0 = _TI00 * z0 + _TI01 * z1 + _TI02 * z2
    w1 = _TI10 * z0 + _TI11 * z1 + _TI12 * z2
    w2 = _TI20 * z0 + _TI21 * z1 + _TI22 * z2
    dw_norm_old = None
    rate = None
    converged = False
    k = 0
    for k in range(NEWTON_MAXITER):
        F0 = f(t + h * _C0, y + z0)
        F1 = f(t + h * _C1, y + z1)
        F2 = f(t + h * _C2, y + z2)
        if not (math.isfinite(F0) and math.isfinite(F1) and math.isfinite(F2)):
            break
        f_real = _TI00 * F0 + _TI01 * F1 + _TI02 * F2 - m_real * w0
        f_cplx = _TIC0 * F0 + _TIC1 * F1 + _TIC2 * F2 - m_cplx * complex(w1, w2)
        dw0 = f_real / lu_real
        dwc = f_cplx / lu_cplx
        dw1, dw2 = dwc.real, dwc.imag
        dw_norm = math.sqrt((dw0 * dw0 + dw1 * dw1 + dw2 * dw2) / 3.0) / scale
        if dw_norm_old is not None:
            rate = dw_norm / dw_norm_old
        if rate is not None and (
            rate >= 1 or rate ** (NEWTON_MAXITER - k) / (1 - rate) * dw_norm > tol
        ):
            break
        w0 += dw0
        w1 += dw1
        w2 += dw2
        z0 = _T00 * w0 + _T01 * w1 + _T02 * w2
        z1 = _T10 * w0 + _T11 * w1 + _T12 * w2
        z2 = _T20 * w0 + _T21 * w1 + _T22 * w2
        if dw_norm == 0 or (rate is not None and rate / (1 - rate) * dw_norm < tol):
            converged = True
            break
        dw_norm_old = dw_norm
    return converged, k + 1, [z0, z1, z2], rate


def _locate(event, t_old, t_new, y_old, q, ev_old):  # type: ignore[no-untyped-def]
    """Bisection for the event's zero on the step's dense output."""
    lo, hi = 0.0, 1.0
    h = t_new - t_old
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        ym = y_old + mid * (q[0] + mid * (q[1] + mid * q[2]))
        if event(t_old + mid * h, ym) > 0.0:
            lo = mid
        else:
            hi = mid
    return t_old + hi * h
