"""Routes of the local mu(I) rheology (``docs/derivation_mui.md``) and its :class:`Rheology`.

* "closed-form": Couette flow (the velocity in closed form, eqn. (C2) of the derivation) and
  plane shear without gravity (uniform shear, u = xi); the stress level by Brent's method on
  the closed-form wall-speed condition.
* "numerical": every cell. The rate comes from the inverse law I(mu) on the cell's statics,
  the velocity by adaptive Gauss-Kronrod quadrature (``scipy.integrate.quad``) on intervals
  split geometrically towards the moving wall (where mu -> mu_2 makes the rate peak) and at
  the plug edge (a kink in the rate), and the stress level by Brent's method on
  ``integral of the rate = wall speed``. No compiled kernel: one profile takes milliseconds.

Both return the package's :class:`~cosserat.results.profile.Profile`. A local rheology has no
grain spin and no couple stress of its own: ``omega`` is the material spin of a classical
continuum, half the vorticity, ``-(du/dxi + kappa u)/2`` in the paper's signs (so
``spin_minus_half_vorticity`` is 0), ``m = 0`` and ``sigma_xy = sigma_yx`` (symmetric stress).
The diagnostics message says so, and where the plug is; :func:`plug_mask` gives it pointwise.
"""

from __future__ import annotations

import itertools
import math
import warnings
from typing import Any

import numpy as np
from scipy.integrate import IntegrationWarning, quad, quad_vec
from scipy.optimize import brentq

from .. import config
from ..errors import ConvergenceError, MethodNotAvailableError, ParameterError
from ..model.constitutive import FloatArray
from ..model.mui import GAP_MIN, MuIChannel, MuICouetteFlow, MuIPlaneShear, MuIProblem
from ..model.rheology import Rheology
from ..results.profile import Diagnostics, Fields, Profile
from .assemble import given_grid

REFERENCE = (
    "GDR MiDi, On dense granular flows, Eur. Phys. J. E 14 (2004) 341-365; Jop, Forterre & "
    "Pouliquen, A constitutive law for dense granular flows, Nature 441 (2006) 727-730"
)

_GL_NODES, _GL_WEIGHTS = np.polynomial.legendre.leggauss(12)


# ----------------------------------------------------------------- the velocity, two ways
def _breakpoints(problem: MuIProblem, gap: float) -> FloatArray:
    """Distances t = |xi - moving wall| that split the gap for the quadrature: geometric on
    the width over which mu_2 - mu doubles (the rate peaks at the moving wall), and the plug
    edge. Distances, not xi, so that a layer of width 1e-300 is still resolved."""
    w = problem.peak_width(gap)
    steps = [0.0, 1.0]
    if w < 1.0:
        steps += list(w * 4.0 ** np.arange(0, math.ceil(math.log(1.0 / w, 4.0))))
    plug = problem.plug_extent(gap)
    if plug is not None:
        steps += [abs(e - problem.moving_wall) for e in plug]
    return np.unique(np.clip(np.asarray(steps, dtype=float), 0.0, 1.0))


def _integrand(problem: MuIProblem, gap: float):  # type: ignore[no-untyped-def]
    """f(t) on an array of distances t from the moving wall, whose integral from t to 1 (the
    fixed wall) is I_w u (plane shear) or -I_w u/(Ri + xi) (Couette flow)."""
    if isinstance(problem, MuIPlaneShear):
        return lambda t: problem.rate_times_I_w_at(t, gap)
    Ri = problem.Ri
    return lambda t: problem.inertial_number_at(t, gap) / (Ri + t)


def _quad_intervals(problem: MuIProblem, gap: float, nodes: FloatArray, rtol: float) -> FloatArray:
    """Integral of :func:`_integrand` over each interval of the distances ``nodes`` [-].

    Every interval at once: each is mapped onto [0, 1] and SciPy's adaptive Gauss-Kronrod
    ``quad_vec`` integrates the vector of them, one array evaluation of the law per node (the
    integrand is smooth inside each interval: the breakpoints hold the rate's peak scales and
    the plug edge). The error is controlled in the largest piece's scale (``norm="max"``),
    which is the scale of the velocity they sum to.
    """
    f = _integrand(problem, gap)
    plug = problem.plug_extent(gap)
    t_plug = None if plug is None else min(abs(e - problem.moving_wall) for e in plug)
    a, b = nodes[:-1], nodes[1:]
    live = b > a
    if t_plug is not None:
        live &= a < t_plug
    out = np.zeros(nodes.size - 1)
    if not np.any(live):
        return out
    a, width = a[live], (b - a)[live]

    def pieces(s: float) -> FloatArray:
        return f(a + s * width) * width

    value, _, info = quad_vec(
        pieces,
        0.0,
        1.0,
        epsabs=np.finfo(float).tiny,  # an integrand that is exactly 0 (no flow) converges
        epsrel=rtol,
        norm="max",
        limit=400,
        full_output=True,
    )
    if not info.success:
        # round-off in the smallest pieces (at the plug edge, where I -> 0) can keep the
        # global estimate above the target: integrate piece by piece, each to its own rtol
        return _quad_each(f, nodes, live, rtol, problem)
    out[live] = value
    return out


def _quad_each(f, nodes: FloatArray, live: FloatArray, rtol: float, problem: MuIProblem):  # type: ignore[no-untyped-def]
    """The pieces of :func:`_quad_intervals` one by one with QUADPACK (slower, robust)."""
    out = np.zeros(nodes.size - 1)
    for i in np.flatnonzero(live):
        a, b = nodes[i], nodes[i + 1]
        with warnings.catch_warnings():
            warnings.simplefilter("error", IntegrationWarning)
            try:
                out[i] = quad(
                    lambda t: float(f(np.array([t]))[0]), a, b, epsabs=0.0, epsrel=rtol, limit=200
                )[0]
            except IntegrationWarning as exc:
                raise ConvergenceError(
                    f"mu(I) quadrature at distances [{a:.6g}, {b:.6g}] from the moving wall "
                    f"for {problem.describe()}: {exc}"
                ) from None
    return out


def _numerical_velocity(problem: MuIProblem, gap: float, I_w: float, x: FloatArray, rtol: float):
    """u at ``x`` by quadrature from the fixed wall, and the wall-speed integral G."""
    x = np.asarray(x, dtype=float)
    t_x = np.abs(x - problem.moving_wall)
    nodes = np.unique(np.concatenate([_breakpoints(problem, gap), t_x]))
    pieces = _quad_intervals(problem, gap, nodes, rtol)
    tail = np.concatenate([np.cumsum(pieces[::-1])[::-1], [0.0]])  # int_t^1 f
    tail_x = tail[np.searchsorted(nodes, t_x)]
    if isinstance(problem, MuIPlaneShear):
        return tail_x / I_w, float(tail[0])
    return -(problem.Ri + x) * tail_x / I_w, float(problem.Ri * tail[0])


def _couette_J(problem: MuICouetteFlow, gap: float, x: FloatArray) -> FloatArray:
    """J(xi) = int_xi^xi_c I(mu)/(Ri + xi') dxi' in closed form (derivation, eqn. (C1)) [-]."""
    law, Ri = problem.rheology, problem.Ri
    plug = problem.plug_extent(gap)
    xi_c = 1.0 if plug is None else plug[0]
    g_c = law.mu_2 - law.mu_s if plug is not None else float(problem.saturation_gap(1.0, gap))
    x = np.asarray(x, dtype=float)
    xx = np.minimum(x, xi_c)
    ratio = law.mu_s / law.mu_2
    J = (
        0.5
        * law.I_0
        * (
            2.0 * ratio * np.log((Ri + xx) / (Ri + xi_c))
            + (1.0 - ratio) * np.log(g_c / problem.saturation_gap(xx, gap))
        )
    )
    return np.where(x >= xi_c, 0.0, J)  # the plug is at rest: exactly, not to round-off


def _closed_velocity(problem: MuIProblem, gap: float, I_w: float, x: FloatArray):
    """u at ``x`` and G in closed form (Couette; plane shear without gravity)."""
    x = np.asarray(x, dtype=float)
    if isinstance(problem, MuIPlaneShear):
        return x.copy(), float(problem.rate_times_I_w(np.array([1.0]), gap)[0])
    J = _couette_J(problem, gap, x)
    G = problem.Ri * float(_couette_J(problem, gap, np.array([0.0]))[0])
    return -(problem.Ri + x) * J / I_w, G


class _Evaluator:
    """Dense output of a mu(I) profile: plain data, so the profile pickles as it is."""

    def __init__(self, problem: MuIProblem, gap: float, I_w: float, numerical: bool, rtol: float):
        self.problem, self.gap, self.I_w = problem, gap, I_w
        self.numerical, self.rtol = numerical, rtol

    def velocity(self, x: FloatArray) -> FloatArray:
        x = np.atleast_1d(np.asarray(x, dtype=float))
        if self.numerical:
            return _numerical_velocity(self.problem, self.gap, self.I_w, x, self.rtol)[0]
        return _closed_velocity(self.problem, self.gap, self.I_w, x)[0]

    def plug(self, x: FloatArray) -> FloatArray:
        """True where the material is a plug at rest (|tau|/p <= mu_s)."""
        return self.problem.plug(np.atleast_1d(np.asarray(x, dtype=float)), self.gap)

    def __call__(self, x: FloatArray) -> Fields:
        x = np.atleast_1d(np.asarray(x, dtype=float))
        p, gap = self.problem, self.gap
        u = self.velocity(x)
        kappa = p.curvature(x)
        rate = p.rate_times_I_w(x, gap) / self.I_w
        # plane: du/dxi = rate; Couette: (Ri + xi) d(u/(Ri + xi))/dxi = rate
        du = rate + kappa * u
        mu = p.friction_ratio(x, gap)
        sigma_c = p.sigma_c(x)
        sigma = -mu * sigma_c
        return Fields(
            u=u,
            omega=-0.5 * (du + kappa * u),
            m=np.zeros_like(x),
            sigma_xy=sigma,
            sigma_yx=sigma.copy(),
            sigma_yy=sigma_c,
            du_dxi=du,
            kappa=kappa,
        )


# ----------------------------------------------------------------- the stress level
def _stress_level(problem: MuIProblem, G_of_gap, rtol: float) -> tuple[float, float, int]:  # type: ignore[no-untyped-def]
    """gap = mu_2 - mu(moving wall) and I_w; the root-find's iterations (0 if imposed)."""
    if problem.stress_ratio is not None:
        gap = problem.gap_of_stress_ratio()
        return gap, G_of_gap(gap), 0
    I_w = problem.I_w
    assert I_w is not None
    law = problem.rheology
    hi = math.log(law.mu_2 - law.mu_s)  # G = 0: the wall's stress ratio is mu_s
    lo = math.log(GAP_MIN)
    if G_of_gap(GAP_MIN) < I_w:
        raise ConvergenceError(
            f"{problem.describe()}: the wall speed needs the stress ratio at the moving wall "
            f"closer to mu_2 than {GAP_MIN:g}, which double precision cannot resolve; lower I_w"
        )
    # G grows like ln(1/gap) near mu_2 and like (mu - mu_s)^2 near mu_s: a start in ln(gap)
    z, info = brentq(
        lambda z: G_of_gap(math.exp(z)) - I_w,
        lo,
        hi,
        xtol=1e-15,
        rtol=max(4.0 * np.finfo(float).eps, 1e-3 * rtol),
        maxiter=400,
        full_output=True,
    )
    if not info.converged:
        raise ConvergenceError(f"{problem.describe()}: the stress-level root-find did not converge")
    return math.exp(z), I_w, int(info.iterations)


# ----------------------------------------------------------------- profiles
def _grid(problem: MuIProblem, gap: float, points: int | None, xi: FloatArray | None) -> FloatArray:
    if xi is not None:
        return given_grid(xi)
    n = max(int(points or config.OUTPUT_POINTS), 3)
    plug = problem.plug_extent(gap)
    if plug is None:
        parts = [np.linspace(0.0, 1.0, n)]
    else:
        flow = (plug[1], 1.0) if plug[0] == 0.0 else (0.0, plug[0])
        n_plug = max(n // 4, 2)
        parts = [np.linspace(*flow, n - n_plug + 1), np.linspace(*plug, n_plug)]
    w = problem.peak_width(gap)
    if w < 0.01:  # a boundary layer at the moving wall: points geometric into it
        d = np.geomspace(w * 1e-2, 0.1, max(n // 8, 4))
        parts.append(d if problem.moving_wall == 0.0 else 1.0 - d)
    return np.unique(np.clip(np.concatenate(parts), 0.0, 1.0))


def _check(problem: MuIProblem, ev: _Evaluator) -> tuple[dict[str, float], dict[str, float]]:
    """Residuals recomputed on the evaluator, and the wall conditions (``lhs - rhs``).

    "velocity": the integral form of the velocity equation over the intervals of a check
    grid, with 12-point Gauss-Legendre quadrature of the law (independent of the route's
    quadrature), relative to the wall speed. "law": |mu(I) - |sigma_yx|/sigma_yy| where the
    material flows, with I recovered from the returned du/dxi.
    """
    grid = _grid(problem, ev.gap, config.CHECK_POINTS, None)
    a, b = grid[:-1], grid[1:]
    half = 0.5 * (b - a)
    nodes = (0.5 * (a + b))[:, None] + half[:, None] * _GL_NODES[None, :]
    weights = half[:, None] * _GL_WEIGHTS[None, :]
    rate = (problem.rate_times_I_w(nodes.ravel(), ev.gap) / ev.I_w).reshape(nodes.shape)
    ends = ev(grid)
    r = 1.0 / ends.kappa if isinstance(problem, MuICouetteFlow) else np.ones_like(grid)
    if isinstance(problem, MuICouetteFlow):
        rate = rate / (problem.Ri + nodes)
    jump = ends.u[1:] / r[1:] - ends.u[:-1] / r[:-1]
    velocity = float(np.max(np.abs(jump - np.sum(weights * rate, axis=1)) * r[1:]))
    flowing = ~ev.plug(grid)
    recovered = (ends.du_dxi - ends.kappa * ends.u) * ev.I_w / np.sqrt(ends.sigma_yy)
    law = problem.rheology
    mu_back = law.friction(recovered[flowing])
    mu_stress = np.abs(ends.sigma_yx[flowing]) / ends.sigma_yy[flowing]
    law_res = float(np.max(np.abs(mu_back - mu_stress))) if np.any(flowing) else 0.0
    u_ends = ev.velocity(np.array([0.0, 1.0]))
    mw, fw = problem.moving_wall, problem.fixed_wall
    bc = {
        f"u - u_wall at the moving wall (xi = {mw:g}) [no slip]": float(
            u_ends[int(mw)] - problem.wall_velocity(mw)
        ),
        f"u - u_wall at the fixed wall (xi = {fw:g}) [no slip]": float(
            u_ends[int(fw)] - problem.wall_velocity(fw)
        ),
    }
    return {"velocity": velocity, "law": law_res}, bc


def _profile(
    problem: MuIProblem,
    *,
    method: str,
    points: int | None,
    xi: FloatArray | None,
    check: bool,
    rtol: float,
) -> Profile:
    numerical = method == "numerical"

    def G(gap: float) -> float:
        if numerical:
            return _numerical_velocity(problem, gap, 1.0, np.array([0.0]), rtol)[1]
        return _closed_velocity(problem, gap, 1.0, np.array([0.0]))[1]

    gap, I_w, iterations = _stress_level(problem, G, rtol)
    ev = _Evaluator(problem, gap, I_w, numerical, rtol)
    grid = _grid(problem, gap, points, xi)
    f = ev(grid)
    for name, values in f._asdict().items():
        if not np.all(np.isfinite(values)):
            raise ConvergenceError(f"the {method} mu(I) solution has non-finite {name}")
    res, bc = _check(problem, ev) if check else ({}, {})
    law = problem.rheology
    T = law.mu_2 - gap
    plug = problem.plug_extent(gap)
    plug_text = (
        "no plug: the whole gap flows"
        if plug is None
        else f"plug at rest (|tau|/p <= mu_s, u = 0 exactly) on xi in "
        f"[{plug[0]:.6g}, {plug[1]:.6g}]"
    )
    how = (
        "velocity by adaptive quadrature of the rate, stress level by Brent's method"
        if numerical
        else "velocity in closed form (docs/derivation_mui.md)"
    )
    message = (
        f"local mu(I) (Jop et al. 2006), {how}; stress ratio at the moving wall "
        f"|tau|/p = {T:.12g} (mu_2 - it = {gap:.6g}), I_w = {I_w:.12g}; {plug_text}. "
        "No grain spin or couple stress in this rheology: omega = -(du/dxi + kappa u)/2 is half "
        "the vorticity (the material spin), m = 0, sigma_xy = sigma_yx (symmetric stress)."
    )
    stats: dict[str, Any] = {
        "stress_ratio": T,
        "gap_to_mu_2": gap,
        "I_w": I_w,
        "plug": None if plug is None else [float(plug[0]), float(plug[1])],
        "root_iterations": iterations,
    }
    return Profile(
        problem=problem,  # type: ignore[arg-type]
        xi=grid,
        **f._asdict(),
        slip_wall=float(problem.slip_wall),
        reference_velocity=problem.reference_velocity,
        diagnostics=Diagnostics(
            method=method,
            rtol=rtol if numerical else None,
            atol=None,
            residuals=res,
            bc_errors=bc,
            message=message,
            stats=stats,
        ),
        evaluator=ev,
        velocity=ev.velocity,
    )


def _rtol(rtol: float) -> float:
    lo, hi = config.RTOL_RANGE
    if not lo <= rtol <= hi:
        raise ParameterError(f"rtol must satisfy {lo:g} <= rtol <= {hi:g}; got {rtol:g}")
    return float(rtol)


def solve_numerical(
    problem: MuIProblem,
    *,
    points: int | None = None,
    xi: FloatArray | None = None,
    check: bool = True,
    rtol: float = config.MUI_RTOL,
) -> Profile:
    """The mu(I) profile by quadrature of the rate and a root-find on the stress level.

    Parameters
    ----------
    problem : MuIPlaneShear or MuICouetteFlow
    points : int, optional
        About this many output points (default :data:`cosserat.config.OUTPUT_POINTS`),
        concentrated in the flowing region; or ``xi``, an explicit grid.
    check : bool
        Recompute the residuals and the wall conditions (default True).
    rtol : float
        Relative tolerance of the quadratures [-] (default :data:`cosserat.config.MUI_RTOL`).

    Raises
    ------
    NoSolutionError
        An imposed stress ratio >= mu_2 (no steady rate) or <= mu_s (no flow at all).
    ConvergenceError
        A quadrature or the root-find failed, saying where.
    """
    return _profile(
        problem, method="numerical", points=points, xi=xi, check=check, rtol=_rtol(rtol)
    )


def solve_closed_form(
    problem: MuIProblem,
    *,
    points: int | None = None,
    xi: FloatArray | None = None,
    check: bool = True,
) -> Profile:
    """The mu(I) profile in closed form: Couette flow, and plane shear without gravity.

    Raises
    ------
    MethodNotAvailableError
        Plane shear under gravity (use method="numerical").
    NoSolutionError
        As :func:`solve_numerical`.
    """
    if isinstance(problem, MuIPlaneShear) and problem.B * problem.nu != 0.0:
        raise MethodNotAvailableError(
            "no closed form for mu(I) plane shear under gravity (B > 0): use method='numerical'"
        )
    return _profile(
        problem, method="closed-form", points=points, xi=xi, check=check, rtol=config.MUI_RTOL
    )


def plug_mask(profile: Profile, xi: FloatArray | None = None) -> FloatArray:
    """True where a mu(I) profile is a plug at rest (|tau|/p <= mu_s), on ``profile.xi`` or
    at ``xi``.

    Raises
    ------
    ParameterError
        The profile is not a mu(I) profile.
    """
    ev = profile.evaluator
    if not isinstance(ev, _Evaluator | _ChannelEvaluator):
        raise ParameterError("plug_mask: not a mu(I) profile (plugs are a mu(I) notion)")
    return ev.plug(profile.xi if xi is None else np.asarray(xi, dtype=float))


# ----------------------------------------------------------------- the vertical channel
def _channel_J_numerical(problem: MuIChannel, x: FloatArray, rtol: float) -> FloatArray:
    """I_w u(x) by adaptive quadrature of the rate I(mu) from the wall, piece by piece between
    the sorted distances from the centre line (the plug edge a breakpoint) [-]."""
    t_s = problem.plug_half_width
    t = np.maximum(np.abs(np.asarray(x, dtype=float) - 0.5), t_s)
    nodes = np.unique(np.concatenate([t, [0.5]]))[::-1]  # from the wall inwards
    Bn = problem.B * problem.nu
    law = problem.rheology

    def rate(tt: float) -> float:
        return float(law.inertial_number(np.array([Bn * tt]))[0])

    pieces = [0.0]
    for hi, lo in itertools.pairwise(nodes):
        with warnings.catch_warnings():
            warnings.simplefilter("error", IntegrationWarning)
            try:
                val, _ = quad(rate, lo, hi, epsabs=0.0, epsrel=rtol, limit=200)
            except IntegrationWarning as exc:
                raise ConvergenceError(
                    f"mu(I) channel: the quadrature of the rate on [{lo:.6g}, {hi:.6g}] failed "
                    f"({exc})"
                ) from None
        pieces.append(val)
    J_nodes = np.cumsum(pieces)
    return np.interp(t, nodes[::-1], J_nodes[::-1])


class _ChannelEvaluator:
    """Dense output of a mu(I) channel profile (plain data: the profile pickles as it is)."""

    def __init__(self, problem: MuIChannel, numerical: bool, rtol: float) -> None:
        self.problem, self.numerical, self.rtol = problem, numerical, rtol
        self.I_w = float(self.J(np.array([0.5]))[0])

    def J(self, x: FloatArray) -> FloatArray:
        if self.numerical:
            return _channel_J_numerical(self.problem, x, self.rtol)
        return self.problem.closed_form_J(x)

    def velocity(self, x: FloatArray) -> FloatArray:
        return self.J(np.atleast_1d(np.asarray(x, dtype=float))) / self.I_w

    def plug(self, x: FloatArray) -> FloatArray:
        return self.problem.plug(np.atleast_1d(np.asarray(x, dtype=float)))

    def thickness(self, f: float) -> float:
        """Delta: distance from a wall, over eps, where 1 - u = f (u_0 = u(1/2) = 1) [d_p]."""
        if not 0.0 < f < 1.0:
            raise ParameterError(f"f must satisfy 0 < f < 1; got {f:g}")
        span = 0.5 - self.problem.plug_half_width

        def g(d: float) -> float:
            return float(self.velocity(np.array([1.0 - d]))[0]) - (1.0 - f)

        d = brentq(g, 0.0, span, xtol=1e-15, rtol=4 * np.finfo(float).eps, maxiter=400)
        return float(d) / self.problem.eps

    def __call__(self, x: FloatArray) -> Fields:
        x = np.atleast_1d(np.asarray(x, dtype=float))
        p = self.problem
        u = self.velocity(x)
        du = -np.sign(x - 0.5) * p.rate_times_I_w(x) / self.I_w
        sigma = p.sigma_yx(x)
        return Fields(
            u=u,
            omega=-0.5 * du,
            m=np.zeros_like(x),
            sigma_xy=sigma,
            sigma_yx=sigma.copy(),
            sigma_yy=p.sigma_c(x),
            du_dxi=du,
            kappa=np.zeros_like(x),
        )


def _channel_profile(
    problem: MuIChannel, *, method: str, points: int | None, xi: FloatArray | None, check: bool,
    rtol: float,
) -> Profile:  # fmt: skip
    numerical = method == "numerical"
    ev = _ChannelEvaluator(problem, numerical, rtol)
    t_s = problem.plug_half_width
    if xi is None:
        n = points or config.OUTPUT_POINTS
        grid = np.unique(np.concatenate([np.linspace(0.0, 1.0, n), [0.5 - t_s, 0.5 + t_s]]))
    else:
        grid = given_grid(xi)
    f = ev(grid)
    for name, values in f._asdict().items():
        if not np.all(np.isfinite(values)):
            raise ConvergenceError(f"the {method} mu(I) channel solution has non-finite {name}")
    res: dict[str, float] = {}
    bc: dict[str, float] = {}
    if check:
        # velocity: u(b) - u(a) - int_a^b du/dxi on intervals of the upper half (GL-12)
        cg = np.unique(np.concatenate([np.linspace(0.5, 1.0, 401), [0.5 + t_s]]))
        a, b = cg[:-1], cg[1:]
        half = 0.5 * (b - a)
        nodes = (0.5 * (a + b))[:, None] + half[:, None] * _GL_NODES[None, :]
        integral = np.sum(half[:, None] * _GL_WEIGHTS[None, :] * ev(nodes.ravel()).du_dxi.reshape(
            nodes.shape), axis=1)  # fmt: skip
        res["velocity"] = float(np.max(np.abs(ev.velocity(b) - ev.velocity(a) - integral)))
        ends = ev(np.array([0.0, 0.5, 1.0]))
        probe = np.linspace(0.0, 0.5, 11)
        bc = {
            "u at the lower wall [no slip]": float(ends.u[0]),
            "u at the upper wall [no slip]": float(ends.u[2]),
            "u(1/2) - 1 [centre-line velocity scale]": float(ends.u[1] - 1.0),
            "max |u(xi) - u(1 - xi)| [symmetry]": float(
                np.max(np.abs(ev.velocity(probe) - ev.velocity(1.0 - probe)))
            ),
        }
    how = (
        "velocity by adaptive quadrature of the rate"
        if numerical
        else "velocity in closed form (docs/derivation_channel.md, section 7)"
    )
    message = (
        f"local mu(I) (Jop et al. 2006) in the vertical channel, {how}; wall stress ratio "
        f"B nu/2 = {problem.wall_stress_ratio:.12g}; plug at rest (|tau|/p <= mu_s) on "
        f"|xi - 1/2| <= {t_s:.6g}; velocity scaled by the centre line, whose inertial number is "
        f"I_w = {ev.I_w:.12g}. No grain spin or couple stress in this rheology: omega = "
        "-(du/dxi)/2 is half the vorticity, m = 0, sigma_xy = sigma_yx."
    )
    return Profile(
        problem=problem,  # type: ignore[arg-type]
        xi=grid,
        **f._asdict(),
        slip_wall=1.0,
        reference_velocity=problem.reference_velocity,
        diagnostics=Diagnostics(
            method=method,
            rtol=rtol if numerical else None,
            atol=None,
            residuals=res,
            bc_errors=bc,
            message=message,
            stats={"I_w": ev.I_w, "plug": [0.5 - t_s, 0.5 + t_s]},
        ),
        evaluator=ev,
        velocity=ev.velocity,
    )


def solve_channel_numerical(
    problem: MuIChannel,
    *,
    points: int | None = None,
    xi: FloatArray | None = None,
    check: bool = True,
    rtol: float = config.MUI_RTOL,
) -> Profile:
    """The mu(I) channel by adaptive quadrature of the rate (``docs/derivation_channel.md``
    section 7); the centre-line velocity scales u, and its inertial number I_w is reported."""
    return _channel_profile(
        problem, method="numerical", points=points, xi=xi, check=check, rtol=_rtol(rtol)
    )


def solve_channel_closed_form(
    problem: MuIChannel,
    *,
    points: int | None = None,
    xi: FloatArray | None = None,
    check: bool = True,
) -> Profile:
    """The mu(I) channel in closed form (``docs/derivation_channel.md`` section 7)."""
    return _channel_profile(
        problem, method="closed-form", points=points, xi=xi, check=check, rtol=config.MUI_RTOL
    )


MUI = Rheology(
    name="mui",
    title="local mu(I) rheology",
    reference=REFERENCE,
    cells={"plane": MuIPlaneShear, "couette": MuICouetteFlow, "channel": MuIChannel},
    routes={
        "numerical": {
            MuIPlaneShear: solve_numerical,
            MuICouetteFlow: solve_numerical,
            MuIChannel: solve_channel_numerical,
        },
        "closed-form": {
            MuIPlaneShear: solve_closed_form,
            MuICouetteFlow: solve_closed_form,
            MuIChannel: solve_channel_closed_form,
        },
    },
    picklable=frozenset(
        {solve_numerical, solve_closed_form, solve_channel_numerical, solve_channel_closed_form}
    ),
)
"""Local mu(I) on plane shear and Couette flow, through the seam (``docs/architecture.md``)."""

__all__ = [
    "MUI",
    "REFERENCE",
    "plug_mask",
    "solve_channel_closed_form",
    "solve_channel_numerical",
    "solve_closed_form",
    "solve_numerical",
]
