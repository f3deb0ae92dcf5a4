"""The NGF fluidity equation, compiled: second-order finite differences and Brent's method
on the stress level (``docs/derivation_ngf.md`` section 5).

On the uniform grid ``xi_j = j/n`` the equation ``(r F')' = r k (F - F_loc)`` is integrated
over the control volume ``[xi_j - h/2, xi_j + h/2]`` of each node (half a cell at a wall),

    -(r_{j+1/2} (F_{j+1} - F_j) - r_{j-1/2} (F_j - F_{j-1})) / h + K_j F_j = S_j,
    K_j = int r k,   S_j = int r k F_loc   (Gauss-Legendre between the kinks of k and F_loc),

with no flux through a wall for ``n . grad F = 0``, or ``F = F_loc`` there. The matrix is
tridiagonal and diagonally dominant (k >= 0): the Thomas algorithm, O(n), in a form without
cancellation (each pivot's excess over its off-diagonal carried apart, as in the GTH
algorithm), so that a small k with zero-flux walls keeps its relative accuracy. The wall-speed
integral of the cell (the trapezoidal rule, second order) is a smooth function of the stress
level T; Brent's method (:mod:`cosserat.numerics.roots`) finds the T at which it equals the
imposed I_w.

Cells (``kind``): 0 plane shear (``shape`` = B nu), 1 Couette flow (``shape`` = Ri),
2 vertical channel (``shape`` unused). The local law: ``mu_2 = 0`` is the linear one. The
statics and the local law are the compiled functions of :mod:`cosserat.model.rheologies.ngf`
(:func:`~cosserat.model.rheologies.ngf.statics`, which calls the cells' compiled statics, and
:func:`~cosserat.model.rheologies.ngf.local_fluidity`), which NGF's equations on arrays use
too.
Status codes: of :func:`fluidity`, 0 solved, 3 singular (a pivot of the tridiagonal solve is
0 or not finite: k = 0 in double precision, so F is not determined); of :func:`stress_level`,
0 converged, 1 no bracket found (the wall speed exceeds what any admissible stress level
gives), 2 Brent did not converge, 3 a fluidity solve on the way was singular.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from ..model.rheologies.ngf import CHANNEL, COUETTE, PLANE, local_fluidity, statics
from .roots import brent_accept, brent_next, brent_start

CONVERGED, NO_BRACKET, NO_CONVERGENCE, SINGULAR = 0, 1, 2, 3
SOLVED = CONVERGED


@njit(cache=True, nogil=True)
def _weight(kind: int, shape: float, x: float) -> float:
    """The factor of F mu in the wall-speed integral (Couette: Ri/(Ri + xi))."""
    if kind == COUETTE:
        return shape / (shape + x)
    return 1.0


_GL = np.array([-1.0 / math.sqrt(3.0), 1.0 / math.sqrt(3.0)])
_GW = np.array([1.0, 1.0])


@njit(cache=True, nogil=True)
def kinks(kind: int, shape: float, T: float, mu_s: float) -> np.ndarray:
    """Where k = |mu - mu_s|/(A eps)^2 or F_loc have a kink: mu = mu_s, and the channel's
    centre line (mu = 0 there, |xi - 1/2| has a kink) [-]; points outside (0, 1) dropped."""
    out = np.full(3, -1.0)
    if kind == PLANE:
        if shape > 0.0:
            out[0] = 1.0 - (T / mu_s - 1.0) / shape
    elif kind == COUETTE:
        out[0] = shape * (math.sqrt(T / mu_s) - 1.0)
    else:
        out[0] = 0.5 - 0.5 * mu_s / T
        out[1] = 0.5
        out[2] = 0.5 + 0.5 * mu_s / T
    out.sort()
    return out


@njit(cache=True, nogil=True)
def _piece(
    kind: int,
    shape: float,
    T: float,
    a: float,
    c: float,
    inv_a2: float,
    mu_s: float,
    b: float,
    mu_2: float,
) -> tuple[float, float]:
    """int_a^c r k and int_a^c r k F_loc by 2-point Gauss-Legendre (no kink inside)."""
    half = 0.5 * (c - a)
    mid = 0.5 * (c + a)
    K = 0.0
    S = 0.0
    for q in range(2):
        mu, s, r = statics(kind, shape, T, mid + half * _GL[q])
        rk = r * abs(mu - mu_s) * inv_a2 * half * _GW[q]
        K += rk
        S += rk * local_fluidity(mu, s, mu_s, b, mu_2)
    return K, S


@njit(cache=True, nogil=True)
def _cell_integrals(
    kind: int,
    shape: float,
    T: float,
    a: float,
    c: float,
    cuts: np.ndarray,
    inv_a2: float,
    mu_s: float,
    b: float,
    mu_2: float,
) -> tuple[float, float]:
    """int_a^c r k and int_a^c r k F_loc, split at the kinks ``cuts`` (sorted), by two-point
    Gauss-Legendre on each piece: exact to O(h^5) per cell, since the integrands are smooth on
    each piece, so the kink's position in its cell leaves no irregular O(h^2) term."""
    K = 0.0
    S = 0.0
    left = a
    for i in range(cuts.size):
        if left < cuts[i] < c:
            dK, dS = _piece(kind, shape, T, left, cuts[i], inv_a2, mu_s, b, mu_2)
            K += dK
            S += dS
            left = cuts[i]
    dK, dS = _piece(kind, shape, T, left, c, inv_a2, mu_s, b, mu_2)
    return K + dK, S + dS


@njit(cache=True, nogil=True)
def fluidity(
    kind: int,
    shape: float,
    T: float,
    n: int,
    a_eps: float,
    mu_s: float,
    b: float,
    mu_2: float,
    dirichlet: bool,
    F: np.ndarray,
) -> tuple[float, int]:
    """Solve for F on the n + 1 nodes (into ``F``); return (the wall-speed integral, status).

    Vertex-centred finite volumes: on the control volume of node j (half cells at the walls)
    ``-[r F']`` + ``(int r k) F_j = int r k F_loc``, the fluxes by central differences and the
    coefficient integrals by Gauss-Legendre between the kinks (:func:`kinks`), so the error is
    a regular O(h^2) wherever mu crosses mu_s. The integral is ``int_0^1 F mu`` (plane),
    ``Ri int_0^1 F mu/(Ri + xi)`` (Couette) or ``int_0^{1/2} F mu`` (channel, n even), each by
    the trapezoidal rule. Status SOLVED, or SINGULAR (F and the integral NaN) if a pivot is
    0 or not finite.
    """
    h = 1.0 / n
    inv_a2 = 1.0 / (a_eps * a_eps)
    cuts = kinks(kind, shape, T, mu_s)
    lower = np.empty(n + 1)  # -(sub-diagonal) >= 0
    upper = np.empty(n + 1)  # -(super-diagonal) >= 0
    excess = np.empty(n + 1)  # diagonal minus the two above: K_j >= 0 (1 in a Dirichlet row)
    pivot = np.empty(n + 1)
    rhs = np.empty(n + 1)
    mus = np.empty(n + 1)
    for j in range(n + 1):
        x = j * h
        mus[j] = statics(kind, shape, T, x)[0]
        if (j == 0 or j == n) and dirichlet:
            mu, s, _ = statics(kind, shape, T, x)
            lower[j], excess[j], upper[j] = 0.0, 1.0, 0.0
            rhs[j] = local_fluidity(mu, s, mu_s, b, mu_2)
            continue
        a = max(x - 0.5 * h, 0.0)
        c = min(x + 0.5 * h, 1.0)
        K, S = _cell_integrals(kind, shape, T, a, c, cuts, inv_a2, mu_s, b, mu_2)
        lower[j] = statics(kind, shape, T, a)[2] / h if j > 0 else 0.0
        upper[j] = statics(kind, shape, T, c)[2] / h if j < n else 0.0
        excess[j] = K
        rhs[j] = S
    # The Thomas algorithm without cancellation (the GTH form): the pivot d_j = u_j + e_j keeps
    # its excess over the super-diagonal apart, e_j = K_j + l_j e_{j-1}/d_{j-1}, which is the
    # subtraction (l_j + u_j + K_j) - l_j u_{j-1}/d_{j-1} done exactly by hand (d - u = e).
    # Every term is >= 0, so a small sum of K (a cooperativity length
    # far beyond the gap with zero-flux walls) is not lost against the O(1/h) fluxes, and a
    # pivot is 0 only if k = 0 in double precision: then F is not determined (status SINGULAR).
    e_prev = 0.0
    for j in range(n + 1):
        e = excess[j]
        if j > 0:
            w = lower[j] / pivot[j - 1]
            e += w * e_prev
            rhs[j] += w * rhs[j - 1]
        d = upper[j] + e
        if not (d > 0.0 and math.isfinite(d)):
            F[:] = math.nan
            return math.nan, SINGULAR
        pivot[j] = d
        e_prev = e
    F[n] = rhs[n] / pivot[n]
    for j in range(n - 1, -1, -1):
        F[j] = (rhs[j] + upper[j] * F[j + 1]) / pivot[j]
    last = n // 2 if kind == CHANNEL else n
    total = 0.0
    for j in range(last + 1):
        f = F[j] * mus[j] * _weight(kind, shape, j * h)
        total += 0.5 * f if (j == 0 or j == last) else f
    return total * h, SOLVED


@njit(cache=True, nogil=True)
def stress_level(
    kind: int,
    shape: float,
    n: int,
    a_eps: float,
    mu_s: float,
    b: float,
    mu_2: float,
    dirichlet: bool,
    target: float,
    lo: float,
    hi: float,
    xtol: float,
    maxiter: int,
    F: np.ndarray,
) -> tuple[float, int, int, int]:
    """The stress level T in (lo, hi) whose wall-speed integral is ``target``, with F there.

    ``lo`` is a level with integral 0 (mu_s: nothing flows) or a tighter lower bracket whose
    integral is below target; ``hi`` an upper guess, doubled away from mu_s (linear law) until
    the integral exceeds ``target``, or, with the saturating law, the largest level allowed.
    Returns (T, status, Brent iterations, fluidity solves); with status SINGULAR, T is the
    level whose fluidity solve was singular.
    """
    solves = 0
    if lo > mu_s:
        g, status = fluidity(kind, shape, lo, n, a_eps, mu_s, b, mu_2, dirichlet, F)
        solves += 1
        if status != SOLVED:
            return lo, SINGULAR, 0, solves
        f_lo = g - target
        if f_lo > 0.0:
            lo, f_lo = mu_s, -target
    else:
        f_lo = -target
    g, status = fluidity(kind, shape, hi, n, a_eps, mu_s, b, mu_2, dirichlet, F)
    solves += 1
    if status != SOLVED:
        return hi, SINGULAR, 0, solves
    f_hi = g - target
    grow = 0
    while f_hi < 0.0:
        if mu_2 != 0.0 or grow >= 60:
            return hi, NO_BRACKET, 0, solves
        lo, f_lo = hi, f_hi
        hi = mu_s + 2.0 * (hi - mu_s)
        g, status = fluidity(kind, shape, hi, n, a_eps, mu_s, b, mu_2, dirichlet, F)
        solves += 1
        if status != SOLVED:
            return hi, SINGULAR, 0, solves
        f_hi = g - target
        grow += 1
    state = brent_start(lo, hi, f_lo, f_hi)
    for it in range(maxiter):
        x, done = brent_next(state, xtol)
        if done:
            g, status = fluidity(kind, shape, x, n, a_eps, mu_s, b, mu_2, dirichlet, F)
            return x, (CONVERGED if status == SOLVED else SINGULAR), it, solves + 1
        g, status = fluidity(kind, shape, x, n, a_eps, mu_s, b, mu_2, dirichlet, F)
        solves += 1
        if status != SOLVED:
            return x, SINGULAR, it, solves
        brent_accept(state, x, g - target)
    return state[1], NO_CONVERGENCE, maxiter, solves


__all__ = [
    "CHANNEL",
    "CONVERGED",
    "COUETTE",
    "NO_BRACKET",
    "NO_CONVERGENCE",
    "PLANE",
    "SINGULAR",
    "SOLVED",
    "fluidity",
    "local_fluidity",
    "statics",
    "stress_level",
]
