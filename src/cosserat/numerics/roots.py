"""Brent's root finder, compiled, in reverse communication (Brent 1973, "Algorithms for
minimization without derivatives", ch. 4; the algorithm of SciPy's ``brentq``).

The caller owns the loop and evaluates its own function, so no function is passed as a value
(numba cannot cache code whose loop calls a first-class function under a branch)::

    state = brent_start(a, b, fa, fb)         # fa, fb of opposite signs
    for _ in range(maxiter):
        x, done = brent_next(state, xtol)
        if done:
            break
        brent_accept(state, x, f(x))
    root = state[B]
"""

from __future__ import annotations

import numpy as np
from numba import njit

MACHINE_EPS = 2.220446049250313e-16

# state vector: the best estimate b, the previous one a, the counterpoint c (f(b) f(c) < 0),
# the last two steps d and e
A, B, C, FA, FB, FC, D, E = range(8)


@njit(cache=True, nogil=True)
def brackets(fa: float, fb: float) -> bool:
    """True if fa and fb are finite and of opposite signs (or one is zero)."""
    return np.isfinite(fa) and np.isfinite(fb) and fa * fb <= 0.0


@njit(cache=True, nogil=True)
def brent_start(a: float, b: float, fa: float, fb: float) -> np.ndarray:
    """The state of a search on [a, b]; the caller checks :func:`brackets` first."""
    s = np.empty(8)
    s[A], s[B], s[C] = a, b, a
    s[FA], s[FB], s[FC] = fa, fb, fa
    s[D] = s[E] = b - a
    return s


@njit(cache=True, nogil=True)
def brent_next(s: np.ndarray, xtol: float) -> tuple[float, bool]:
    """The next point to evaluate, or (root, True) once the bracket is below
    ``xtol + 4 eps |root|``."""
    if s[FB] * s[FC] > 0.0:
        s[C], s[FC] = s[A], s[FA]
        s[D] = s[E] = s[B] - s[A]
    if abs(s[FC]) < abs(s[FB]):
        s[A], s[B], s[C] = s[B], s[C], s[B]
        s[FA], s[FB], s[FC] = s[FB], s[FC], s[FB]
    tol = 2.0 * MACHINE_EPS * abs(s[B]) + 0.5 * xtol
    m = 0.5 * (s[C] - s[B])
    if abs(m) <= tol or s[FB] == 0.0:
        return s[B], True
    if abs(s[E]) >= tol and abs(s[FA]) > abs(s[FB]):
        r_ab = s[FB] / s[FA]
        if s[A] == s[C]:  # secant
            p = 2.0 * m * r_ab
            q = 1.0 - r_ab
        else:  # inverse quadratic interpolation
            q = s[FA] / s[FC]
            r = s[FB] / s[FC]
            p = r_ab * (2.0 * m * q * (q - r) - (s[B] - s[A]) * (r - 1.0))
            q = (q - 1.0) * (r - 1.0) * (r_ab - 1.0)
        if p > 0.0:
            q = -q
        else:
            p = -p
        if 2.0 * p < min(3.0 * m * q - abs(tol * q), abs(s[E] * q)):
            s[E] = s[D]
            s[D] = p / q
        else:
            s[D] = s[E] = m
    else:
        s[D] = s[E] = m
    step = s[D] if abs(s[D]) > tol else (tol if m > 0.0 else -tol)
    return s[B] + step, False


@njit(cache=True, nogil=True)
def brent_accept(s: np.ndarray, x: float, fx: float) -> None:
    """Record f(x) at the point :func:`brent_next` asked for."""
    s[A], s[FA] = s[B], s[FB]
    s[B], s[FB] = x, fx
