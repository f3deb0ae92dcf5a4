"""Routes of the local mu(I) rheology (``docs/derivation_mui.md``).

* "numerical": every cell, a new one included: it reads only the cell's statics
  (:class:`~cosserat.model.rheologies.mui.MuIFlow`). The rate comes from the inverse law I(mu) on
  the statics, the velocity by adaptive Gauss-Kronrod quadrature (``scipy.integrate.quad_vec``)
  on intervals split geometrically towards the wall of the largest stress ratio (where
  mu -> mu_2 makes the rate peak) and at the plug edge (a kink in the rate), and the stress level
  by Brent's method on ``the velocity at the scale point = its value there`` (the wall speed, or
  the channel's centre line).
* "closed-form": plane shear without gravity (uniform shear, u = xi), Couette flow (eqn. (C2)
  of the derivation) and the channel (``docs/derivation_channel.md`` section 7); the stress
  level by Brent's method on the closed-form condition.

Both return the package's :class:`~cosserat.results.profile.Profile`. A local rheology has no
grain spin and no couple stress of its own: the profile's ``omega`` and ``m`` are None (absent,
not zero), and ``sigma_xy = sigma_yx`` (symmetric stress). The diagnostics message says so, and
where the plug is; :func:`plug_mask` gives it pointwise.

With W = u/r (r the cell's radius, 1 between plane walls) and t the distance from the wall of
the largest stress ratio, ``I_w |dW/dxi| = sqrt(p/N) I(mu)/r``, integrated from the wall at rest
(u = 0): ``u(xi) = sign(u_s) r(xi) Phi(t)/I_w`` with ``Phi(t) = |int_{t_rest}^t sqrt(p) I/r|``,
and the velocity scale ``u(xi_s) = u_s`` fixes ``I_w = r(xi_s) Phi(t_s)/|u_s|``.
"""

from __future__ import annotations

import math
import warnings
from typing import Any

import numpy as np
from scipy.integrate import IntegrationWarning, quad, quad_vec
from scipy.optimize import brentq

from .. import config
from ..errors import ConvergenceError, MethodNotAvailableError, ParameterError
from ..model import Problem
from ..model.cells.plane import Plane
from ..model.constitutive import BoolArray, FloatArray
from ..model.rheologies import ANY_CELL
from ..model.rheologies.base import equations_of
from ..model.rheologies.mui import GAP_MIN, REFERENCE, MuIFlow
from ..numerics.mui import CONVERGED, plane_pieces
from ..results.profile import Diagnostics, Fields, Profile
from .assemble import given_grid
from .registry import register_route

_GL_NODES, _GL_WEIGHTS = np.polynomial.legendre.leggauss(12)
_QUAD_LIMIT = 400
"""Most subintervals of the velocity quadrature (``quad_vec``'s ``limit``)."""


# ----------------------------------------------------------------- where the velocity is fixed
def _rest(eq: MuIFlow) -> float:
    """t of a wall at rest, where the integration of the velocity starts [-]."""
    for wall in (0.0, 1.0):
        if eq.cell.wall_velocity(wall) == 0.0:
            return float(eq.cell.distance(np.array([wall]))[0])
    raise ParameterError(f"the {eq.cell.name} cell has no wall at rest to integrate from")


def _scale(eq: MuIFlow) -> tuple[float, float, float]:
    """(xi, t, u) of the point that scales the velocity [-]."""
    xs, us = eq.cell.velocity_scale
    return float(xs), float(eq.cell.distance(np.array([xs]))[0]), float(us)


# ----------------------------------------------------------------- the velocity, two ways
def _breakpoints(eq: MuIFlow, gap: float) -> FloatArray:
    """Distances t from the peak wall that split [0, span] for the quadrature: geometric on
    the width over which mu_2 - mu doubles (the rate peaks there), and the plug edge.
    Distances, not xi, so that a layer of width 1e-300 is still resolved."""
    span = eq.cell.span
    w = eq.peak_width(gap)
    steps = [0.0, span]
    if w < span:
        steps += list(w * 4.0 ** np.arange(0, math.ceil(math.log(span / w, 4.0))))
    plug = eq.plug_extent(gap)
    if plug is not None:
        steps += [float(t) for t in eq.cell.distance(np.array(plug))]
    return np.unique(np.clip(np.asarray(steps, dtype=float), 0.0, span))


def _plug_distance(eq: MuIFlow, gap: float) -> float | None:
    """The distance from the peak wall beyond which the material is a plug, or None."""
    plug = eq.plug_extent(gap)
    if plug is None:
        return None
    return float(np.min(eq.cell.distance(np.array(plug))))


def _quad_intervals(eq: MuIFlow, gap: float, nodes: FloatArray, rtol: float) -> FloatArray:
    """Integral of ``eq.integrand_at`` over each interval of the distances ``nodes`` [-].

    Every interval at once: each is mapped onto [0, 1] and SciPy's adaptive Gauss-Kronrod
    ``quad_vec`` integrates the vector of them, one array evaluation of the law per node (the
    integrand is smooth inside each interval: the breakpoints hold the rate's peak scales and
    the plug edge). The error is controlled in the largest piece's scale (``norm="max"``),
    which is the scale of the velocity they sum to.
    """

    integrand = eq.integrand_at

    def f(t: FloatArray) -> FloatArray:
        return integrand(t, gap)

    t_plug = _plug_distance(eq, gap)
    a, b = nodes[:-1], nodes[1:]
    live = b > a
    if t_plug is not None:
        live &= a < t_plug
    out = np.zeros(nodes.size - 1)
    if not np.any(live):
        return out
    a, width = a[live], (b - a)[live]
    cell = eq.cell
    if isinstance(cell, Plane) and cell.straight:
        # the same quadrature compiled (numerics.mui): quad_vec's integrals to the last bit
        law = eq.rheology
        value, status = plane_pieces(
            a, width, float(cell.B_nu), float(law.mu_2), float(law.mu_s), float(law.I_0),
            float(gap), float(rtol), _QUAD_LIMIT,
        )  # fmt: skip
        if status == CONVERGED:
            out[live] = value
            return out
        # anything else as quad_vec itself does it (the same status, then its fallback)

    def pieces(s: float) -> FloatArray:
        return integrand(a + s * width, gap) * width

    value, _, info = quad_vec(
        pieces,
        0.0,
        1.0,
        epsabs=np.finfo(float).tiny,  # an integrand that is exactly 0 (no flow) converges
        epsrel=rtol,
        norm="max",
        limit=_QUAD_LIMIT,
        full_output=True,
    )
    if not info.success:
        # round-off in the smallest pieces (at the plug edge, where I -> 0) can keep the
        # global estimate above the target: integrate piece by piece, each to its own rtol
        return _quad_each(f, nodes, live, rtol, eq, gap)
    out[live] = value
    return out


def _rounding(eq: MuIFlow, gap: float, a: float, b: float) -> float:
    """The integral over [a, b] of the integrand's own rounding error: the excess mu - mu_s
    is known to about eps (mu_2 - mu_s), so I = I_0 excess/(mu_2 - mu) to about
    I_0 eps (mu_2 - mu_s)/(mu_2 - mu), largest at a (nearest the peak wall) [-]. A piece
    cannot be integrated more precisely than this."""
    law, t = eq.rheology, np.array([a])
    g = float(eq.saturation_gap_at(t, gap)[0])
    scale = math.sqrt(float(eq.cell.normal_stress_at(t)[0])) / float(eq.cell.radius_at(t)[0])
    return 8.0 * np.finfo(float).eps * (b - a) * law.I_0 * (law.mu_2 - law.mu_s) / g * scale


def _quad_each(f, nodes: FloatArray, live: BoolArray, rtol: float, eq: MuIFlow, gap: float):
    """The pieces of :func:`_quad_intervals` one by one with QUADPACK (slower, robust), each
    to its own rtol or to the rounding of its integrand (:func:`_rounding`)."""
    out = np.zeros(nodes.size - 1)
    for i in np.flatnonzero(live):
        a, b = nodes[i], nodes[i + 1]
        floor = _rounding(eq, gap, a, b)
        with warnings.catch_warnings():
            warnings.simplefilter("error", IntegrationWarning)
            try:
                out[i] = quad(
                    lambda t: float(f(np.array([t]))[0]), a, b, epsabs=floor, epsrel=rtol,
                    limit=200,
                )[0]  # fmt: skip
            except IntegrationWarning as exc:
                raise ConvergenceError(
                    f"mu(I) quadrature at distances [{a:.6g}, {b:.6g}] from the "
                    f"{eq.wall_name} for {eq.describe()}: {exc}"
                ) from None
    return out


ROUNDING_EXCESS = 64.0 * np.finfo(float).eps
"""An excess of the peak stress ratio over mu_s below this fraction of mu_2 - mu_s is rounding:
the rate there is noise of its own size, and the velocity integral is taken as 0 (no flow)."""


def _numerical_velocity(eq: MuIFlow, gap: float, I_w: float, x: FloatArray, rtol: float):
    """u at ``x`` by quadrature from the wall at rest, and the scale integral G (module
    docstring: I_w = G). A stress level within rounding of mu_s (:data:`ROUNDING_EXCESS`;
    met only while the root-find brackets the level) gives no flow."""
    x = np.asarray(x, dtype=float)
    law = eq.rheology
    if law.mu_2 - law.mu_s - gap <= ROUNDING_EXCESS * (law.mu_2 - law.mu_s):
        return np.zeros_like(x), 0.0
    cell = eq.cell
    xs, ts, us = _scale(eq)
    t_x = cell.distance(x)
    nodes = np.unique(np.concatenate([_breakpoints(eq, gap), t_x, [ts]]))
    pieces = _quad_intervals(eq, gap, nodes, rtol)
    if _rest(eq) == 0.0:  # int_0^t f
        phi = np.concatenate([[0.0], np.cumsum(pieces)])
    else:  # int_t^span f
        phi = np.concatenate([np.cumsum(pieces[::-1])[::-1], [0.0]])
    phi_x = phi[np.searchsorted(nodes, t_x)]
    G = float(cell.radius(np.array([xs]))[0] * phi[np.searchsorted(nodes, ts)] / abs(us))
    return math.copysign(1.0, us) * cell.radius(x) * phi_x / I_w, G


def _plane_closed(eq: MuIFlow, gap: float, I_w: float, x: FloatArray):
    """Plane shear without gravity: uniform shear, u = xi; G = I(T)."""
    return x.copy(), float(eq.rate_times_I_w(np.array([1.0]), gap)[0])


def _couette_J(eq: MuIFlow, gap: float, x: FloatArray) -> FloatArray:
    """J(xi) = int_xi^xi_c I(mu)/(Ri + xi') dxi' in closed form (derivation, eqn. (C1)) [-]."""
    law, Ri = eq.rheology, eq.cell.Ri
    plug = eq.plug_extent(gap)
    xi_c = 1.0 if plug is None else plug[0]
    g_c = law.mu_2 - law.mu_s if plug is not None else float(eq.saturation_gap(1.0, gap))
    x = np.asarray(x, dtype=float)
    xx = np.minimum(x, xi_c)
    ratio = law.mu_s / law.mu_2
    J = (
        0.5
        * law.I_0
        * (
            2.0 * ratio * np.log((Ri + xx) / (Ri + xi_c))
            + (1.0 - ratio) * np.log(g_c / eq.saturation_gap(xx, gap))
        )
    )
    return np.where(x >= xi_c, 0.0, J)  # the plug is at rest: exactly, not to round-off


def _couette_closed(eq: MuIFlow, gap: float, I_w: float, x: FloatArray):
    Ri = eq.cell.Ri
    J = _couette_J(eq, gap, x)
    G = Ri * float(_couette_J(eq, gap, np.array([0.0]))[0])
    return -(Ri + x) * J / I_w, G


def _channel_J(eq: MuIFlow, gap: float, x: FloatArray) -> FloatArray:
    """J(xi) = I_w u(xi) in the channel (``docs/derivation_channel.md`` section 7) [-]:
    ``I_0 [-(1/2 - t_lo) + ((mu_2 - mu_s)/(B nu)) ln((mu_2 - B nu t_lo)/(mu_2 - B nu/2))]``
    with ``t_lo = max(|xi - 1/2|, t_s)``, B nu = 2T and t_s = mu_s/(B nu); even about 1/2."""
    law = eq.rheology
    Bn = 2.0 * (law.mu_2 - gap)
    t_lo = np.maximum(np.abs(np.asarray(x, dtype=float) - 0.5), law.mu_s / Bn)
    log = np.log1p(Bn * (0.5 - t_lo) / gap)
    return law.I_0 * (-(0.5 - t_lo) + (law.mu_2 - law.mu_s) / Bn * log)


def _channel_closed(eq: MuIFlow, gap: float, I_w: float, x: FloatArray):
    return _channel_J(eq, gap, x) / I_w, float(_channel_J(eq, gap, np.array([0.5]))[0])


CLOSED_FORMS = {"plane": _plane_closed, "couette": _couette_closed, "channel": _channel_closed}
"""The cells with a closed-form mu(I) velocity: ``(u at x, G)`` for a wall gap and I_w."""


class _Evaluator:
    """Dense output of a mu(I) profile: plain data, so the profile pickles as it is."""

    def __init__(self, eq: MuIFlow, gap: float, I_w: float, numerical: bool, rtol: float):
        self.eq, self.gap, self.I_w = eq, gap, I_w
        self.numerical, self.rtol = numerical, rtol

    def velocity(self, x: FloatArray) -> FloatArray:
        x = np.atleast_1d(np.asarray(x, dtype=float))
        if self.numerical:
            return _numerical_velocity(self.eq, self.gap, self.I_w, x, self.rtol)[0]
        return CLOSED_FORMS[self.eq.cell.name](self.eq, self.gap, self.I_w, x)[0]

    def plug(self, x: FloatArray) -> BoolArray:
        """True where the material is a plug (|tau|/p <= mu_s)."""
        return self.eq.plug(np.atleast_1d(np.asarray(x, dtype=float)), self.gap)

    def __call__(self, x: FloatArray) -> Fields:
        x = np.atleast_1d(np.asarray(x, dtype=float))
        eq, gap, cell = self.eq, self.gap, self.eq.cell
        u = self.velocity(x)
        kappa = cell.curvature(x)
        rate = eq.shear_sign(x, gap) * eq.rate_times_I_w(x, gap) / self.I_w
        # r d(u/r)/dxi = rate, so du/dxi = rate + kappa u
        du = rate + kappa * u
        # the stress from the same stress ratio the plug test reads (one rounding, not two)
        sign = np.sign(cell.shear_stress(x, 1.0))
        sigma = sign * eq.friction_ratio(x, gap) * cell.normal_stress(x)
        return Fields(
            u=u,
            omega=None,
            m=None,
            sigma_xy=sigma,
            sigma_yx=sigma.copy(),
            sigma_yy=cell.normal_stress(x),
            du_dxi=du,
            kappa=kappa,
        )


# ----------------------------------------------------------------- the stress level
def _stress_level(eq: MuIFlow, G_of_gap, rtol: float) -> tuple[float, float, int]:
    """gap = mu_2 - T and I_w; the root-find's iterations (0 if the level is imposed)."""
    if eq.stress_ratio is not None:
        gap = eq.gap_of_stress_ratio()
        return gap, G_of_gap(gap), 0
    I_w = eq.I_w
    assert I_w is not None
    law = eq.rheology
    hi = math.log(law.mu_2 - law.mu_s)  # G = 0: the wall's stress ratio is mu_s
    lo = math.log(GAP_MIN)
    if G_of_gap(GAP_MIN) < I_w:
        raise ConvergenceError(
            f"{eq.describe()}: the wall speed needs the stress ratio at the {eq.wall_name} "
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
        raise ConvergenceError(f"{eq.describe()}: the stress-level root-find did not converge")
    return math.exp(z), I_w, int(info.iterations)


# ----------------------------------------------------------------- profiles
def _grid(eq: MuIFlow, gap: float, points: int | None, xi: FloatArray | None) -> FloatArray:
    if xi is not None:
        return given_grid(xi)
    n = max(int(points or config.OUTPUT_POINTS), 3)
    plug = eq.plug_extent(gap)
    if plug is None:
        parts = [np.linspace(0.0, 1.0, n)]
    elif eq.cell.symmetric:  # a plug riding on the centre line
        parts = [np.linspace(0.0, 1.0, n), np.array(plug)]
    else:
        flow = (plug[1], 1.0) if plug[0] == 0.0 else (0.0, plug[0])
        n_plug = max(n // 4, 2)
        parts = [np.linspace(*flow, n - n_plug + 1), np.linspace(*plug, n_plug)]
    w = eq.peak_width(gap)
    if w < 0.01:  # a boundary layer at the peak wall: points geometric into it
        d = eq.cell.position(np.geomspace(w * 1e-2, 0.1, max(n // 8, 4)))
        parts += [d, 1.0 - d] if eq.cell.symmetric else [d]
    return np.unique(np.clip(np.concatenate(parts), 0.0, 1.0))


def _check(eq: MuIFlow, ev: _Evaluator) -> tuple[dict[str, float], dict[str, float]]:
    """Residuals recomputed on the evaluator, and the wall conditions (``lhs - rhs``).

    "velocity": the integral form of the velocity equation, ``u/r`` across each interval of a
    check grid against 12-point Gauss-Legendre quadrature of the law (independent of the
    route's quadrature), relative to the velocity scale. "law": |mu(I) - |sigma_yx|/sigma_yy|
    where the material flows, with I recovered from the returned du/dxi.
    """
    cell = eq.cell
    grid = _grid(eq, ev.gap, config.CHECK_POINTS, None)
    a, b = grid[:-1], grid[1:]
    half = 0.5 * (b - a)
    nodes = (0.5 * (a + b))[:, None] + half[:, None] * _GL_NODES[None, :]
    weights = half[:, None] * _GL_WEIGHTS[None, :]
    flat = nodes.ravel()
    rate = eq.shear_sign(flat, ev.gap) * eq.rate_times_I_w(flat, ev.gap) / ev.I_w
    rate = (rate / cell.radius(flat)).reshape(nodes.shape)
    ends = ev(grid)
    r = cell.radius(grid)
    jump = ends.u[1:] / r[1:] - ends.u[:-1] / r[:-1]
    velocity = float(np.max(np.abs(jump - np.sum(weights * rate, axis=1)) * r[1:]))
    flowing = ~ev.plug(grid)
    recovered = np.abs(ends.du_dxi - ends.kappa * ends.u) * ev.I_w / np.sqrt(ends.sigma_yy)
    law = eq.rheology
    mu_back = law.friction(recovered[flowing])
    mu_stress = np.abs(ends.sigma_yx[flowing]) / ends.sigma_yy[flowing]
    law_res = float(np.max(np.abs(mu_back - mu_stress))) if np.any(flowing) else 0.0
    u_ends = ev.velocity(np.array([0.0, 1.0]))
    bc = {
        f"u - u_wall at xi = {w:g} [no slip]": float(u_ends[i] - cell.wall_velocity(w))
        for i, w in enumerate((0.0, 1.0))
    }
    xs, _, us = _scale(eq)
    if xs not in (0.0, 1.0):
        bc[f"u({xs:g}) - {us:g} [velocity scale]"] = float(ev.velocity(np.array([xs]))[0] - us)
    if cell.symmetric:
        probe = np.linspace(0.0, 0.5, 11)
        bc["max |u(xi) - u(1 - xi)| [symmetry]"] = float(
            np.max(np.abs(ev.velocity(probe) - ev.velocity(1.0 - probe)))
        )
    return {"velocity": velocity, "law": law_res}, bc


def _profile(
    problem: Problem,
    *,
    method: str,
    points: int | None,
    xi: FloatArray | None,
    check: bool,
    rtol: float,
) -> Profile:
    eq = equations_of(problem, MuIFlow)
    numerical = method == "numerical"
    closed = CLOSED_FORMS.get(eq.cell.name)

    def G(gap: float) -> float:
        if numerical or closed is None:
            return _numerical_velocity(eq, gap, 1.0, np.array([0.0]), rtol)[1]
        return closed(eq, gap, 1.0, np.array([0.0]))[1]

    gap, I_w, iterations = _stress_level(eq, G, rtol)
    ev = _Evaluator(eq, gap, I_w, numerical, rtol)
    grid = _grid(eq, gap, points, xi)
    f = ev(grid)
    for name, values in f._asdict().items():
        if values is not None and not np.all(np.isfinite(values)):
            raise ConvergenceError(f"the {method} mu(I) solution has non-finite {name}")
    res, bc = _check(eq, ev) if check else ({}, {})
    law = eq.rheology
    T = law.mu_2 - gap
    plug = eq.plug_extent(gap)
    if plug is None:
        plug_text = "no plug: the whole gap flows"
    elif eq.cell.symmetric:
        plug_text = (
            f"plug (|tau|/p <= mu_s, no shear) on the centre line, xi in "
            f"[{plug[0]:.6g}, {plug[1]:.6g}]"
        )
    else:
        plug_text = (
            f"plug at rest (|tau|/p <= mu_s, u = 0 exactly) on xi in [{plug[0]:.6g}, {plug[1]:.6g}]"
        )
    how = (
        "velocity by adaptive quadrature of the rate, stress level by Brent's method"
        if numerical
        else "velocity in closed form (docs/derivation_mui.md)"
    )
    message = (
        f"local mu(I) (Jop et al. 2006), {how}; stress ratio at the {eq.wall_name} "
        f"|tau|/p = {T:.12g} (mu_2 - it = {gap:.6g}), I_w = {I_w:.12g}; {plug_text}. "
        "No grain spin or couple stress in this rheology: the profile has no omega or m, and "
        "sigma_xy = sigma_yx (symmetric stress)."
    )
    stats: dict[str, Any] = {
        "stress_ratio": T,
        "gap_to_mu_2": gap,
        "I_w": I_w,
        "plug": None if plug is None else [float(plug[0]), float(plug[1])],
        "root_iterations": iterations,
    }
    return Profile(
        problem=problem,
        xi=grid,
        **f._asdict(),
        slip_wall=float(eq.slip_wall),
        reference_velocity=eq.reference_velocity,
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


@register_route("mui", ANY_CELL, "numerical")
def solve_numerical(
    problem: Problem,
    *,
    points: int | None = None,
    xi: FloatArray | None = None,
    check: bool = True,
    rtol: float = config.MUI_RTOL,
) -> Profile:
    """The mu(I) profile on any cell by quadrature of the rate and a root-find on the stress
    level (module docstring).

    Parameters
    ----------
    problem : Problem
        mu(I) on a cell (``Problem(cell, MuI(...))``).
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


@register_route("mui", tuple(CLOSED_FORMS), "closed-form")
def solve_closed_form(
    problem: Problem,
    *,
    points: int | None = None,
    xi: FloatArray | None = None,
    check: bool = True,
) -> Profile:
    """The mu(I) profile in closed form: Couette flow, the channel, and plane shear without
    gravity.

    Raises
    ------
    MethodNotAvailableError
        Plane shear under gravity (use method="numerical").
    NoSolutionError
        As :func:`solve_numerical`.
    """
    if isinstance(problem.cell, Plane) and problem.cell.B_nu != 0.0:
        raise MethodNotAvailableError(
            "no closed form for mu(I) plane shear under gravity (B > 0): use method='numerical'"
        )
    return _profile(
        problem, method="closed-form", points=points, xi=xi, check=check, rtol=config.MUI_RTOL
    )


def plug_mask(profile: Profile, xi: FloatArray | None = None) -> BoolArray:
    """True where a mu(I) profile is a plug (|tau|/p <= mu_s), on ``profile.xi`` or at ``xi``.

    Raises
    ------
    ParameterError
        The profile is not a mu(I) profile.
    """
    ev = profile.evaluator
    if not isinstance(ev, _Evaluator):
        raise ParameterError("plug_mask: not a mu(I) profile (plugs are a mu(I) notion)")
    return ev.plug(profile.xi if xi is None else np.asarray(xi, dtype=float))


__all__ = [
    "CLOSED_FORMS",
    "REFERENCE",
    "plug_mask",
    "solve_closed_form",
    "solve_numerical",
]
