"""Routes of the nonlocal granular fluidity model (``docs/derivation_ngf.md``), registered for
the cells its kernel has a branch for (:data:`~cosserat.model.rheologies.ngf.KINDS`).

* "numerical": every cell. The fluidity equation by vertex-centred finite volumes (second
  order, :mod:`cosserat.numerics.ngf`), the stress level by Brent's method on the wall-speed
  integral, on a grid fine enough for the shortest cooperativity length in the gap
  (``resolution`` cells per length, or ``cells`` given), solved also on half the cells for a
  Richardson estimate of the discretisation error (reported in the diagnostics).
* "closed-form", "asymptotic": none exists (the fluidity equation has variable coefficients
  in every cell with a shear layer); these routes raise :class:`MethodNotAvailableError`
  saying so.

The profile is the package's :class:`~cosserat.results.profile.Profile`: as for local mu(I),
it has no ``omega`` or ``m`` (None: no grain spin or couple stress of its own) and the stress is
symmetric. The NGF fields the
profile has no column for are read with :func:`fluidity`, :func:`friction_ratio`,
:func:`shear_rate` and :func:`creep_mask`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from scipy.interpolate import CubicHermiteSpline, CubicSpline
from scipy.optimize import brentq

from .. import config
from ..errors import (
    ConvergenceError,
    MethodNotAvailableError,
    NoSolutionError,
    ParameterError,
    shown,
)
from ..model import Problem
from ..model.constitutive import BoolArray, FloatArray
from ..model.rheologies.base import equations_of
from ..model.rheologies.ngf import KINDS, REFERENCE, NGFFlow
from ..numerics import ngf as kernel
from ..results.profile import Diagnostics, Fields, Profile
from .assemble import given_grid
from .registry import register_route

RESOLUTION = 16.0
"""Default cells per shortest cooperativity length A d/sqrt(max |mu - mu_s|): second-order
error about 2e-6 of the wall speed; after Richardson's extrapolation 1e-9 to 2e-8 (measured
against resolution 256: plane shear under gravity at eps 0.02 1.3e-9, Couette at eps 0.05
1.8e-8), and up to 7e-7 next to a moving wall in a case an independent solver checked (issue
19; 1e-8 at resolution 64): pass ``resolution=64`` where that matters."""
MIN_CELLS = 256
"""Fewest finite-volume cells across the gap."""
MAX_CELLS = 2**21
"""Most cells: beyond, ConvergenceError (a layer too thin for a uniform grid)."""
SATURATION_MARGIN = 1e-12
"""Closest relative approach of the wall's stress ratio to mu_2 with the saturating law."""
XTOL = 1e-15
"""Absolute tolerance of Brent's method on the stress level [-]."""


# ----------------------------------------------------------------- grid and stress level
def _max_excess(eq: NGFFlow, T: float) -> float:
    """max |mu - mu_s| over the gap for the stress level T (mu is monotone or, in the
    channel, V-shaped, so the ends and the centre suffice)."""
    xs = np.array([0.0, 0.5, 1.0])
    return float(np.max(np.abs(eq.friction_ratio(xs, T) - eq.rheology.mu_s)))


def _required_cells(eq: NGFFlow, T: float, resolution: float) -> int:
    """Cells for ``resolution`` cells per shortest cooperativity length, and, with the
    saturating law, per width over which mu_2 - mu doubles at the wall."""
    law = eq.rheology
    length = law.A * eq.eps / math.sqrt(max(_max_excess(eq, T), 1e-300))
    need = resolution / length
    if law.mu_2 is not None:
        wall = eq.moving_wall
        slope = (
            abs(float(eq.friction_ratio(np.array([wall + 1e-7 * (1 - 2 * wall)]), T)[0]) - T) / 1e-7
        )
        if slope > 0.0:
            need = max(need, resolution / ((law.mu_2 - T) / slope))
    n = MIN_CELLS
    while n < need:
        n *= 2
    return n


@dataclass(frozen=True)
class _Level:
    """One solve on n cells: the stress level, the nodal F, the wall-speed integral."""

    n: int
    T: float
    F: FloatArray
    wall_integral: float
    iterations: int
    solves: int


def _args(eq: NGFFlow) -> tuple[Any, ...]:
    law = eq.rheology
    return (
        eq.kind,
        eq.shape,
        law.A * eq.eps,
        law.mu_s,
        law.b,
        0.0 if law.mu_2 is None else law.mu_2,
        eq.fluidity_bc == "local",
    )


def _singular(eq: NGFFlow, T: float) -> ConvergenceError:
    """The error for a fluidity solve whose tridiagonal system is singular at double precision."""
    law = eq.rheology
    excess = _max_excess(eq, T)
    length = law.A * eq.eps / math.sqrt(excess) if excess > 0.0 else math.inf
    return ConvergenceError(
        f"{eq.describe()}: the fluidity equation is singular in double precision at the "
        f"stress level {T:.17g} (max |mu - mu_s| = {excess:.3g} over the gap, the cooperativity "
        f"length {length:.3g} gaps): k = |mu - mu_s|/(A eps)^2 vanishes there, so the flow "
        "cannot be told from rest and g is not determined"
    )


def _fluidity(eq: NGFFlow, T: float, n: int, F: FloatArray) -> float:
    """The wall-speed integral at the stress level T on n cells (F filled in)."""
    kind, shape, a_eps, mu_s, b, mu_2, dirichlet = _args(eq)
    G, status = kernel.fluidity(kind, shape, T, n, a_eps, mu_s, b, mu_2, dirichlet, F)
    if status != kernel.SOLVED:
        raise _singular(eq, T)
    return float(G)


def _solve_at(eq: NGFFlow, n: int, hint: float | None) -> _Level:
    """The stress level (imposed, or for the wall speed I_w) and F on n cells."""
    kind, shape, a_eps, mu_s, b, mu_2, dirichlet = _args(eq)
    F = np.empty(n + 1)
    if eq.I_w is None:
        T = eq.check_imposed_level()
        return _Level(n, T, F, _fluidity(eq, T, n, F), 0, 1)
    top = math.inf if mu_2 == 0.0 else mu_2 - SATURATION_MARGIN * (mu_2 - mu_s)
    if hint is not None:
        lo, hi = mu_s + (hint - mu_s) * (1 - 1e-3), min(mu_s + (hint - mu_s) * (1 + 1e-3), top)
    else:
        lo, hi = mu_s, min(2.0 * mu_s, top)
    args = (kind, shape, n, a_eps, mu_s, b, mu_2, dirichlet, eq.I_w)
    T, status, iterations, solves = kernel.stress_level(*args, lo, hi, XTOL, 200, F)
    if status == kernel.NO_BRACKET and hi < top:  # the hint was too low (saturating law)
        T, status, iterations, more = kernel.stress_level(*args, mu_s, top, XTOL, 200, F)
        solves += more
    if status == kernel.SINGULAR:
        raise _singular(eq, T)
    if status == kernel.NO_BRACKET:
        if mu_2 == 0.0:
            raise ConvergenceError(
                f"{eq.describe()}: no stress level up to {T:.3g} gives the wall speed"
            )
        reach = _fluidity(eq, top, n, F)
        raise NoSolutionError(
            f"{eq.describe()}: I_w = {eq.I_w:g} is beyond the fastest steady NGF flow "
            f"with the saturating local law in this cell (I_w -> about {reach:.3g} as the stress "
            f"ratio at the {eq.wall_name} tends to mu_2 = {mu_2:.6g}; beyond mu_2 the "
            "local law has no rate, and the fluidity stays finite because it diffuses away "
            "from the wall)"
        )
    if status != kernel.CONVERGED:
        raise ConvergenceError(f"{eq.describe()}: the stress-level root-find did not converge")
    return _Level(n, T, F, _fluidity(eq, T, n, F), iterations, solves)


# ----------------------------------------------------------------- the velocity
def _nodes(n: int) -> FloatArray:
    return np.linspace(0.0, 1.0, n + 1)


def _cumtrapz(f: FloatArray, h: float) -> FloatArray:
    return np.concatenate([[0.0], np.cumsum(0.5 * h * (f[1:] + f[:-1]))])


def _sign(eq: NGFFlow, x: FloatArray) -> FloatArray:
    """Sign of the shear: du/dxi >= 0 except in the channel's lower half-flow (xi > 1/2)."""
    if eq.cell.name == "channel":
        return np.where(x > 0.5, -1.0, 1.0)
    return np.ones_like(x)


@dataclass(frozen=True)
class _Nodal:
    """A solution on nodes: the stress level, I_w, F, and the velocity in its integrated form
    ``prim`` (u; in Couette flow W = u/(Ri + xi)) with its derivative ``dprim``."""

    x: FloatArray
    T: float
    I_w: float
    F: FloatArray
    prim: FloatArray
    dprim: FloatArray


def _nodal(eq: NGFFlow, level: _Level, I_w: float) -> _Nodal:
    """The velocity of one level on its nodes, by the trapezoidal rule (second order).

    Plane and channel: ``u' = sign F mu / I_w``, u(0) = 0. Couette: ``W = u/(Ri + xi)`` with
    ``W' = F mu/((Ri + xi) I_w)``, W(1) = 0 (u = (Ri + xi) W).
    """
    x = _nodes(level.n)
    h = 1.0 / level.n
    rate = level.F * eq.friction_ratio(x, level.T) / I_w  # |gamma_dot| H / V
    if eq.cell.name == "couette":
        dW = rate / eq.radius(x)
        # summed from the outer wall, so that the creep tail keeps its relative accuracy
        W = -_cumtrapz(dW[::-1], h)[::-1]
        return _Nodal(x, level.T, I_w, level.F, W, dW)
    du = _sign(eq, x) * rate
    return _Nodal(x, level.T, I_w, level.F, _cumtrapz(du, h), du)


def _extrapolate(fine: _Nodal, coarse: _Nodal) -> _Nodal:
    """Richardson's extrapolation on the coarse nodes: the scheme's error is a regular O(h^2)
    (the kinks are integrated exactly), so this removes it.

    T and I_w as ``(4 fine - coarse)/3``. F, the velocity's primitive and its derivative each
    keep one sign across the gap (per half-channel for the rate), and in a creep tail they
    fall exponentially, where the error *relative* to the value is what stays regular: they
    are extrapolated in the logarithm of their magnitude, which equals the linear formula to
    O(h^4) where the relative difference is small and never changes a sign in a tail.
    """

    def mix(a: float, b: float) -> float:
        return (4.0 * a - b) / 3.0

    def mix_log(a: FloatArray, b: FloatArray) -> FloatArray:
        both = (a != 0.0) & (b != 0.0) & (np.sign(a) == np.sign(b))
        out = a.copy()  # zeros (a wall value, the channel's centre rate) stay as they are
        aa, bb = np.abs(a[both]), np.abs(b[both])
        out[both] = np.sign(a[both]) * aa * np.exp((np.log(aa) - np.log(bb)) / 3.0)
        return out

    return _Nodal(
        coarse.x,
        mix(fine.T, coarse.T),
        mix(fine.I_w, coarse.I_w),
        mix_log(fine.F[::2], coarse.F),
        mix_log(fine.prim[::2], coarse.prim),
        mix_log(fine.dprim[::2], coarse.dprim),
    )


class _Evaluator:
    """Dense output of an NGF profile: plain arrays, so the profile pickles as it is.

    The velocity by cubic Hermite interpolation of its nodal values and rates (its derivative
    gives the rate between nodes), the fluidity by a cubic spline through its nodal values.
    """

    def __init__(self, eq: NGFFlow, nodal: _Nodal, n: int):
        self.eq, self.T, self.I_w, self.n = eq, nodal.T, nodal.I_w, n
        self.nodes = nodal.x
        self.F = nodal.F
        self._prim = CubicHermiteSpline(nodal.x, nodal.prim, nodal.dprim)
        self._F: CubicSpline | None = None  # built on first use

    def velocity(self, x: FloatArray) -> FloatArray:
        x = np.atleast_1d(np.asarray(x, dtype=float))
        p = self._prim(x)
        return p * self.eq.radius(x) if self.eq.cell.name == "couette" else p

    def fluidity(self, x: FloatArray) -> FloatArray:
        """F(xi) = I_w g H / V: the fluidity in units of sqrt(N/rho_s)/d [-]."""
        if self._F is None:
            self._F = CubicSpline(self.nodes, self.F)
        return self._F(np.atleast_1d(np.asarray(x, dtype=float)))

    def friction_ratio(self, x: FloatArray) -> FloatArray:
        return self.eq.friction_ratio(np.atleast_1d(np.asarray(x, dtype=float)), self.T)

    def shear_rate(self, x: FloatArray) -> FloatArray:
        """|gamma_dot| H / V = g mu H / V, from the velocity's dense output [-]."""
        x = np.atleast_1d(np.asarray(x, dtype=float))
        return np.abs(self._prim(x, 1)) * self.eq.radius(x)

    def creep(self, x: FloatArray) -> BoolArray:
        return self.eq.creep(np.atleast_1d(np.asarray(x, dtype=float)), self.T)

    def __call__(self, x: FloatArray) -> Fields:
        x = np.atleast_1d(np.asarray(x, dtype=float))
        p = self.eq
        u = self.velocity(x)
        kappa = p.curvature(x)
        rate = _sign(p, x) * self.shear_rate(x)
        du = rate + kappa * u  # Couette: (Ri + xi) d(u/(Ri + xi))/dxi = rate
        mu = self.friction_ratio(x)
        s = p.pressure(x)
        sigma = -_sign(p, x) * mu * s
        return Fields(
            u=u,
            omega=None,
            m=None,
            sigma_xy=sigma,
            sigma_yx=sigma.copy(),
            sigma_yy=s,
            du_dxi=du,
            kappa=kappa,
        )


class _ChannelEvaluator(_Evaluator):
    """The channel's profile is symmetric: Delta is found on the half-gap at the wall xi = 1."""

    def thickness(self, f: float) -> float:
        """Delta: the distance from the wall, in grains, where u = 1 - f (u_0 = 1) [-]."""
        target = 1.0 - f
        d = brentq(
            lambda t: float(self.velocity(np.array([1.0 - t]))[0]) - target,
            0.0,
            0.5,
            xtol=1e-15 * self.eq.eps,
            rtol=4 * np.finfo(float).eps,
            maxiter=400,
        )
        return float(d) / self.eq.eps


# ----------------------------------------------------------------- the profile
def _grid(eq: NGFFlow, T: float, points: int | None, xi: FloatArray | None) -> FloatArray:
    if xi is not None:
        return given_grid(xi)
    n = max(int(points or config.OUTPUT_POINTS), 3)
    parts = [np.linspace(0.0, 1.0, n)]
    extent = eq.creep_extent(T)
    if extent is not None:
        parts.append(np.array(extent))
    return np.unique(np.clip(np.concatenate(parts), 0.0, 1.0))


def _wall_fluidity_errors(eq: NGFFlow, ev: _Evaluator) -> dict[str, float]:
    """The fluidity's wall condition at both walls, from the nodal solution: for
    ``n . grad g = 0`` the one-sided fourth-order dF/dxi times the wall's cooperativity length
    over max F (dimensionless); for ``g = g_loc``, F - F_loc over max F."""
    F = ev.F
    h = 1.0 / (F.size - 1)
    scale = float(np.max(F))
    out = {}
    for wall, f in ((0.0, F[:5]), (1.0, F[::-1][:5])):
        if eq.fluidity_bc == "local":
            loc = float(eq.local_fluidity(np.array([wall]), ev.T)[0])
            out[f"g - g_loc at xi = {wall:g} (over max g)"] = float(f[0] - loc) / scale
        else:
            ell = float(
                eq.rheology.cooperativity_length(eq.friction_ratio(np.array([wall]), ev.T), eq.eps)[
                    0
                ]
            )
            # one-sided, fourth order: its own error stays below the scheme's
            slope = float(np.dot([-25.0, 48.0, -36.0, 16.0, -3.0], f)) / (12.0 * h)
            out[f"n.grad g at xi = {wall:g} (times xi_c/max g)"] = slope * min(ell, 1.0) / scale
    return out


def _profile(
    eq: NGFFlow,
    *,
    points: int | None,
    xi: FloatArray | None,
    check: bool,
    cells: int | None,
    resolution: float,
    extrapolate: bool,
) -> Profile:
    if cells is not None:
        if int(cells) != cells or cells < 8 or cells % 4 or cells > MAX_CELLS:
            raise ParameterError(
                f"cells must be a multiple of 4 in [8, {MAX_CELLS}]; got {shown(cells)}"
            )
        half = _solve_at(eq, int(cells) // 2, None)
        level = _solve_at(eq, int(cells), half.T)
    else:
        if not 1.0 <= resolution <= 1e4:
            raise ParameterError(
                f"resolution must satisfy 1 <= resolution <= 1e4; got {resolution:g}"
            )
        # a coarse stress level, then the grid it needs (and half of it, for the estimate)
        level = _solve_at(eq, MIN_CELLS, None)
        n, first = MIN_CELLS, True
        while (need := _required_cells(eq, level.T, resolution)) > n or first:
            first = False
            if need > MAX_CELLS:
                raise ConvergenceError(
                    f"{eq.describe()}: resolving the shortest cooperativity length (and, "
                    f"with mu_2, the peak of g_loc at the wall) needs {need} cells across the "
                    f"gap, more than {MAX_CELLS}; lower the resolution or the driving"
                )
            n = max(need, n)
            half = _solve_at(eq, n // 2, level.T)
            level = _solve_at(eq, n, half.T)
    I_w = eq.I_w if eq.I_w is not None else level.wall_integral
    I_w_half = eq.I_w if eq.I_w is not None else half.wall_integral
    fine, coarse = _nodal(eq, level, I_w), _nodal(eq, half, I_w_half)
    nodal = _extrapolate(fine, coarse) if extrapolate else fine
    cls = _ChannelEvaluator if eq.cell.name == "channel" else _Evaluator
    ev = cls(eq, nodal, level.n)
    grid = _grid(eq, ev.T, points, xi)
    f = ev(grid)
    for name, values in f._asdict().items():
        if values is not None and not np.all(np.isfinite(values)):
            raise ConvergenceError(f"the NGF solution has non-finite {name}")
    law = eq.rheology
    residuals: dict[str, float] = {}
    bc: dict[str, float] = {}
    if check:
        u_fine, u_coarse = (
            ev.eq.radius(n.x) * n.prim if eq.cell.name == "couette" else n.prim
            for n in (fine, coarse)
        )
        residuals["discretisation (u, second order, Richardson estimate)"] = float(
            np.max(np.abs(u_fine[::2] - u_coarse)) / 3.0
        )
        residuals["discretisation (stress level, second order, Richardson estimate)"] = (
            abs(level.T - half.T) / 3.0
        )
        ends = ev.velocity(np.array([0.0, 1.0]))
        for wall, u_end in zip((0.0, 1.0), ends, strict=True):
            bc[f"u - u_wall at xi = {wall:g} [no slip]"] = float(u_end - eq.wall_velocity(wall))
        bc.update(_wall_fluidity_errors(eq, ev))
    extent = eq.creep_extent(ev.T)
    creep_text = (
        "no creeping region: mu > mu_s across the gap"
        if extent is None
        else f"creeping region (mu <= mu_s: g_loc = 0, it moves only by the fluidity that "
        f"diffuses in, u != 0) on xi in [{extent[0]:.6g}, {extent[1]:.6g}]"
    )
    form = "linear local law" if law.mu_2 is None else f"saturating local law (mu_2 = {law.mu_2:g})"
    message = (
        f"nonlocal granular fluidity (Henann & Kamrin 2013), {form}; second-order finite "
        f"volumes on {level.n} cells"
        + (f" and {half.n}, Richardson-extrapolated" if extrapolate else "")
        + f", stress level by Brent's method; stress ratio at the {eq.wall_name} "
        f"{ev.T:.12g}, I_w = {ev.I_w:.12g}; {creep_text}. No grain spin or "
        "couple stress in this rheology: the profile has no omega or m, and sigma_xy = sigma_yx "
        "(symmetric stress)."
    )
    stats: dict[str, Any] = {
        "stress_ratio": ev.T,
        "I_w": ev.I_w,
        "cells": level.n,
        "extrapolated": extrapolate,
        "creep": None if extent is None else [float(extent[0]), float(extent[1])],
        "root_iterations": level.iterations,
        "fluidity_solves": level.solves + half.solves,
    }
    if eq.cell.name == "channel":
        stats["B_nu"] = 2.0 * ev.T
    return Profile(
        problem=eq.problem,
        xi=grid,
        **f._asdict(),
        slip_wall=float(eq.slip_wall),
        reference_velocity=eq.reference_velocity,
        diagnostics=Diagnostics(
            method="numerical",
            rtol=None,
            atol=None,
            residuals=residuals,
            bc_errors=bc,
            message=message,
            stats=stats,
        ),
        evaluator=ev,
        velocity=ev.velocity,
    )


@register_route("ngf", tuple(KINDS), "numerical")
def solve_numerical(
    problem: Problem,
    *,
    points: int | None = None,
    xi: FloatArray | None = None,
    check: bool = True,
    cells: int | None = None,
    resolution: float = RESOLUTION,
    extrapolate: bool = True,
) -> Profile:
    """The NGF profile: finite volumes for the fluidity, Brent's method for the stress level.

    Parameters
    ----------
    eq : NGFPlaneShear, NGFCouetteFlow or NGFChannel
    points : int, optional
        About this many output points (default :data:`cosserat.config.OUTPUT_POINTS`), or
        ``xi``, an explicit grid.
    check : bool
        Report the Richardson error estimate and the wall conditions (default True).
    cells : int, optional
        Cells across the gap (a multiple of 4); default: enough for ``resolution``.
    resolution : float
        Cells per shortest cooperativity length when ``cells`` is not given (default 16).
    extrapolate : bool
        Return Richardson's extrapolation of the solutions on n and n/2 cells (default; its
        error is O(h^3) or smaller, 1e-9 to 2e-8 of the wall speed at the default resolution and
        up to 7e-7 next to a moving wall: see ``RESOLUTION``), or the second-order
        solution on n cells (False). The diagnostics give the second-order solution's error
        estimate either way.

    Raises
    ------
    NoSolutionError
        An imposed stress level <= mu_s (nothing flows) or >= mu_2 (saturating law), or a wall
        speed beyond the fastest steady flow of the saturating law.
    ConvergenceError
        The grid would need more than :data:`MAX_CELLS` cells, or the root-find failed.
    """
    return _profile(
        equations_of(problem, NGFFlow),
        points=points,
        xi=xi,
        check=check,
        cells=cells,
        resolution=float(resolution),
        extrapolate=bool(extrapolate),
    )


def _not_available(method: str, why: str):
    def route(
        problem: Problem,
        *,
        points: int | None = None,
        xi: FloatArray | None = None,
        check: bool = True,
    ) -> Profile:
        raise MethodNotAvailableError(
            f"no {method} route for the ngf rheology on the {problem.cell_name} cell: {why}; "
            "use method='numerical'"
        )

    route.__name__ = f"solve_{method.replace('-', '_')}"
    return route


solve_closed_form = _not_available(
    "closed-form",
    "the fluidity equation has coefficients that vary across the gap (|mu - mu_s| and g_loc "
    "follow the statics) and no closed-form solution in these cells",
)
solve_asymptotic = _not_available(
    "asymptotic",
    "no matched asymptotics of the NGF cells are implemented in this package",
)


# ----------------------------------------------------------------- NGF fields of a profile
def _evaluator(profile: Profile, what: str) -> _Evaluator:
    ev = profile.evaluator
    if not isinstance(ev, _Evaluator):
        raise ParameterError(f"{what}: not an NGF profile")
    return ev


def _at(profile: Profile, xi: FloatArray | None) -> FloatArray:
    return profile.xi if xi is None else np.asarray(xi, dtype=float)


def fluidity(profile: Profile, xi: FloatArray | None = None) -> FloatArray:
    """The granular fluidity g H / V of an NGF profile, on ``profile.xi`` or at ``xi`` [-]."""
    ev = _evaluator(profile, "fluidity")
    return ev.fluidity(_at(profile, xi)) / ev.I_w


def friction_ratio(profile: Profile, xi: FloatArray | None = None) -> FloatArray:
    """mu = |tau|/p of an NGF profile, from the statics at its stress level [-]."""
    return _evaluator(profile, "friction_ratio").friction_ratio(_at(profile, xi))


def shear_rate(profile: Profile, xi: FloatArray | None = None) -> FloatArray:
    """|gamma_dot| H / V = g mu H / V of an NGF profile [-]."""
    return _evaluator(profile, "shear_rate").shear_rate(_at(profile, xi))


def creep_mask(profile: Profile, xi: FloatArray | None = None) -> BoolArray:
    """True where an NGF profile creeps: mu <= mu_s, g_loc = 0, yet g > 0 and the material
    moves (the local rheology would have a plug at rest there)."""
    return _evaluator(profile, "creep_mask").creep(_at(profile, xi))


register_route("ngf", tuple(KINDS), "closed-form")(solve_closed_form)
register_route("ngf", tuple(KINDS), "asymptotic")(solve_asymptotic)

__all__ = [
    "REFERENCE",
    "creep_mask",
    "fluidity",
    "friction_ratio",
    "shear_rate",
    "solve_asymptotic",
    "solve_closed_form",
    "solve_numerical",
]
