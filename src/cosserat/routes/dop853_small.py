"""DOP853 for a *small* non-stiff system, in plain Python floats.

The spin/velocity pass integrates two quadratures; SciPy's DOP853 spends most of its time in
NumPy overhead for arrays of length 2. This is SciPy's algorithm (Dormand-Prince 8(5,3): the
same error estimate, step control and 7th-order dense output) with lists of floats, so it takes
the same steps ~5x faster.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from scipy.integrate._ivp import dop853_coefficients as _c

from ..model.constitutive import FloatArray

_NS = _c.N_STAGES  # 12
_A = [[float(x) for x in row] for row in _c.A]
_B = [float(x) for x in _c.B]
_C = [float(x) for x in _c.C]
_E3 = [float(x) for x in _c.E3]
_E5 = [float(x) for x in _c.E5]
_D = [[float(x) for x in row] for row in _c.D]
SAFETY, MIN_FACTOR, MAX_FACTOR = 0.9, 0.2, 10.0
_EXPONENT = -1.0 / 8.0


@dataclass(frozen=True)
class SmallSolution:
    """Step points and the 7th-order dense output of each step (``F`` of SciPy)."""

    t: FloatArray  # (steps + 1,)
    y: FloatArray  # (steps + 1, n)
    F: FloatArray  # (steps, 7, n)
    status: int  # 0: reached the end; 1: stopped by the event
    nfev: int

    def __call__(self, t: float | FloatArray) -> FloatArray:
        """Dense output, shape (n,) for a scalar t or (len(t), n)."""
        tt = np.atleast_1d(np.asarray(t, dtype=float))
        ts = self.t
        forward = ts[-1] >= ts[0]
        grid = ts if forward else ts[::-1]
        k = np.clip(np.searchsorted(grid, tt, side="left") - 1, 0, len(ts) - 2)
        if not forward:
            k = len(ts) - 2 - k
        h = ts[k + 1] - ts[k]
        x = ((tt - ts[k]) / np.where(h != 0.0, h, 1.0))[:, None]
        F = self.F[k]  # (m, 7, n)
        out = np.zeros((tt.size, self.y.shape[1]))
        for i in range(6, -1, -1):
            out = (out + F[:, i, :]) * (x if (6 - i) % 2 == 0 else 1.0 - x)
        out += self.y[k]
        return out[0] if np.ndim(t) == 0 else out


def dop853_small(
    fun: Callable[[float, list[float]], list[float]],
    t0: float,
    t1: float,
    y0: list[float],
    rtol: float,
    atol: list[float],
    event: Callable[[float, list[float]], float] | None = None,
    max_steps: int = 100_000,
) -> SmallSolution:
    """Integrate y' = fun(t, y) from t0 to t1; ``event`` is terminal: integration stops at
    the end of the step in which it goes from > 0 to <= 0 (the step is kept whole)."""
    n = len(y0)
    direction = 1.0 if t1 >= t0 else -1.0
    nfev = 0

    def f(t: float, y: list[float]) -> list[float]:
        nonlocal nfev
        nfev += 1
        return fun(t, y)

    t, y = float(t0), [float(v) for v in y0]
    fy = f(t, y)
    h_abs = _initial_step(f, t, y, fy, t1, direction, rtol, atol)
    ts, ys, Fs = [t], [y], []
    status = 0
    ev_old = event(t, y) if event is not None else 1.0
    while direction * (t1 - t) > 0.0:
        if len(ts) > max_steps:
            raise RuntimeError(f"dop853_small: more than {max_steps} steps")
        min_step = 10.0 * abs(math.nextafter(t, direction * math.inf) - t)
        h_abs = max(h_abs, min_step)
        rejected = False
        while True:
            if h_abs < min_step:
                raise RuntimeError("Required step size is less than spacing between numbers.")
            t_new = t + h_abs * direction
            if direction * (t_new - t1) > 0:
                t_new = t1
            h = t_new - t
            h_abs = abs(h)
            K = [fy]
            for s in range(1, _NS):
                a = _A[s]
                yi = [y[j] + h * sum(a[r] * K[r][j] for r in range(s)) for j in range(n)]
                K.append(f(t + _C[s] * h, yi))
            y_new = [y[j] + h * sum(_B[r] * K[r][j] for r in range(_NS)) for j in range(n)]
            f_new = f(t_new, y_new)
            K.append(f_new)
            err5 = err3 = 0.0
            for j in range(n):
                sc = atol[j] + max(abs(y[j]), abs(y_new[j])) * rtol
                e5 = sum(_E5[r] * K[r][j] for r in range(_NS + 1)) / sc
                e3 = sum(_E3[r] * K[r][j] for r in range(_NS + 1)) / sc
                err5 += e5 * e5
                err3 += e3 * e3
            err5 /= n
            err3 /= n
            if err5 == 0.0 and err3 == 0.0:
                error = 0.0
            else:
                error = h_abs * err5 / math.sqrt((err5 + 0.01 * err3) * n)
            if error < 1.0:
                factor = MAX_FACTOR if error == 0.0 else min(MAX_FACTOR, SAFETY * error**_EXPONENT)
                if rejected:
                    factor = min(1.0, factor)
                h_next = h_abs * factor
                break
            h_abs *= max(MIN_FACTOR, SAFETY * error**_EXPONENT)
            rejected = True
        # dense output: three extra stages (SciPy's Dop853DenseOutput)
        for s in range(_NS + 1, len(_C)):
            a = _A[s]
            yi = [y[j] + h * sum(a[r] * K[r][j] for r in range(s)) for j in range(n)]
            K.append(f(t + _C[s] * h, yi))
        F = []
        for j in range(n):
            dy = y_new[j] - y[j]
            col = [dy, h * fy[j] - dy, 2.0 * dy - h * (f_new[j] + fy[j])]
            col += [h * sum(_D[i][r] * K[r][j] for r in range(len(K))) for i in range(4)]
            F.append(col)
        F_step = [[F[j][i] for j in range(n)] for i in range(7)]
        ts.append(t_new)
        ys.append(y_new)
        Fs.append(F_step)
        if event is not None:
            ev_new = event(t_new, y_new)
            if ev_old > 0.0 >= ev_new:  # stop after this step; its dense output stays valid
                status = 1
                break
            ev_old = ev_new
        t, y, fy = t_new, y_new, f_new
        h_abs = h_next
    return SmallSolution(np.array(ts), np.array(ys), np.array(Fs).reshape(-1, 7, n), status, nfev)


def _initial_step(f, t, y, fy, t1, direction, rtol, atol):  # type: ignore[no-untyped-def]
    """SciPy's select_initial_step (error estimator order 7)."""
    n = len(y)
    interval = abs(t1 - t)
    if interval == 0.0:
        return 0.0
    sc = [atol[j] + abs(y[j]) * rtol for j in range(n)]
    d0 = math.sqrt(sum((y[j] / sc[j]) ** 2 for j in range(n)) / n)
    d1 = math.sqrt(sum((fy[j] / sc[j]) ** 2 for j in range(n)) / n)
    h0 = 1e-6 if d0 < 1e-5 or d1 < 1e-5 else 0.01 * d0 / d1
    h0 = min(h0, interval)
    y1 = [y[j] + h0 * direction * fy[j] for j in range(n)]
    f1 = f(t + h0 * direction, y1)
    d2 = math.sqrt(sum(((f1[j] - fy[j]) / sc[j]) ** 2 for j in range(n)) / n) / h0
    h1 = max(1e-6, h0 * 1e-3) if d1 <= 1e-15 and d2 <= 1e-15 else (0.01 / max(d1, d2)) ** 0.125
    return min(100 * h0, h1, interval)
