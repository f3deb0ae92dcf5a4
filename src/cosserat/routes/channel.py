"""Routes of the Cosserat model in the vertical channel
(:mod:`cosserat.model.rheologies.cosserat.channel`).

* ``solve_numerical``: the compiled kernel :mod:`cosserat.numerics.channel` on the upper half,
  mirrored onto the lower half (u and m even, omega and the shear stresses odd about xi = 1/2).
* ``solve_asymptotic``: the leading order in eps -> 0 (``docs/derivation_channel.md``
  sections 5-6): an exponential layer of constant thickness at walls that are not fully rough,
  the Airy layer of thickness ~ eps^(2/3) at fully rough ones.

The residuals of a profile are recomputed on the upper half in the mapped variables (plane shear
with ``sigma_yx = -tau(xi)``), where the shared :func:`~cosserat.results.diagnostics.residuals`
applies; the lower half is the mirror image by construction.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, replace
from typing import Any

import numpy as np

from .. import config
from ..errors import ConvergenceError, MethodNotAvailableError, NoSolutionError, ParameterError
from ..model import Problem
from ..model.cells.channel import shear_stress
from ..model.constitutive import FloatArray
from ..model.rheologies.base import equations_of
from ..model.rheologies.cosserat import CosseratChannel
from ..numerics import channel as kernel
from ..numerics.radau import dense_eval
from ..results.diagnostics import residuals
from ..results.profile import Fields, Profile
from .airy import I_INFINITY, airy_layer, inner_couple_stress, xi_hat_at_fraction
from .assemble import make_profile
from .asymptotic import require_boundary_conditions
from .numerical import WallResult, tolerances

START_OFFSET = 1e-4
"""s_0 = xi_0 - 1/2 where the couple-stress pass leaves the centre-line series (its error
~ s_0^4 is below round-off, and decays further as the pass relaxes) [-]."""
NEAR_CENTRE_OFFSETS = 10.0
"""A yield event within this many start offsets s_0 of the centre line is undecided: where the
centre-line condition holds the series through the singular point is a real solution there
(doc section 4), so the event is the integration's error, not the model's [-]."""
RETRY_TIGHTENING = 100.0
"""Factor by which rtol and atol are tightened when a yield event is retried [-]."""
MAX_RETRIES = 2
"""Retries of a solve that ended on a yield event (tighter tolerance; s_0/10 if near the
centre) before the event is trusted (away from the centre) or the solve gives up [-]."""


def _channel(problem: Problem) -> CosseratChannel:
    """The problem's equations, checked to be the Cosserat model's in the channel."""
    return equations_of(problem, CosseratChannel)


def parameter_vector(problem: Problem, start_offset: float = START_OFFSET) -> FloatArray:
    """The kernel's parameter vector (indices ``P_*`` of :mod:`cosserat.numerics.channel`)."""
    mat = _channel(problem).material
    p = np.zeros(kernel.N_PARAMS)
    p[kernel.P_A], p[kernel.P_SIN_PHI], p[kernel.P_ALPHA] = mat.A, mat.sin_phi, mat.alpha
    p[kernel.P_EPS] = problem.eps
    p[kernel.P_B_NU] = _channel(problem).B_nu
    p[kernel.P_WALL_GAP] = _channel(problem).wall_gap
    p[kernel.P_C] = _channel(problem).c
    p[kernel.P_MU] = _channel(problem).centre_expansion()  # raises NoSolutionError in words
    p[kernel.P_S0] = start_offset
    p[kernel.P_EPS_K] = problem.eps * _channel(problem).wall.K if _channel(problem).slips else 0.0
    p[kernel.P_Y_SCALE] = _channel(problem).deficit_scale
    return p


def raise_for_status(problem: Problem, status: int, info: FloatArray, rtol: float) -> None:
    """The package's error for a kernel status (a yield event only once :func:`run_kernel` has
    confirmed it away from the centre line)."""
    if status == kernel.OK:
        return
    xi, m = float(info[kernel.I_XI_FAIL]), float(info[kernel.I_M_FAIL])
    if status == kernel.NO_SOLUTION:
        raise NoSolutionError(
            f"no real solution for {problem.describe()}: integrated from the centre line, the "
            f"couple stress reaches the yield bound at xi = {xi:.6g} (|m| = {abs(m):.6g}; "
            f"found again at rtol = {rtol:.3g}), beyond which the second shear stress of "
            f"eqn-nd_sigxy is complex (docs/derivation_channel.md, section 4)"
        )
    if status == kernel.SINGULAR_VELOCITY:
        raise ConvergenceError(f"the velocity conditions are singular for {problem.describe()}")
    budget = "ran out of its step budget" if status == kernel.TOO_MANY_STEPS else "stalled"
    raise ConvergenceError(
        f"the channel integration {budget} at xi = {xi:.6g} for {problem.describe()}"
    )


def _mirror(x: FloatArray) -> tuple[FloatArray, FloatArray]:
    """(points on the upper half, +1 where x >= 1/2 else -1)."""
    upper = x >= 0.5
    return np.where(upper, x, 1.0 - x), np.where(upper, 1.0, -1.0)


def physical_fields(
    x: FloatArray,
    u_hat: FloatArray,
    w_hat: FloatArray,
    m_hat: FloatArray,
    sigma_xy_hat: FloatArray,
    du_hat: FloatArray,
    problem: Problem,
    sign: FloatArray,
) -> Fields:
    """Channel fields at x from mapped ones at the mirrored points (u, m even; omega,
    shear stresses and du/dxi odd about 1/2; mapped -> physical: u = 1 - u_hat and every
    other field changes sign)."""
    return Fields(
        u=1.0 - u_hat,
        omega=-sign * w_hat,
        m=-m_hat,
        sigma_xy=-sign * sigma_xy_hat,
        sigma_yx=_channel(problem).sigma_yx(x),
        sigma_yy=np.ones_like(x),
        du_dxi=-sign * du_hat,
        kappa=np.zeros_like(x),
    )


@dataclass(frozen=True, eq=False)
class ChannelSolution:
    """Dense solution of the channel kernel on [0, 1] (plain arrays: it pickles)."""

    problem: Problem
    params: FloatArray
    info: FloatArray
    couple: tuple[FloatArray, FloatArray, FloatArray, FloatArray]
    spin: tuple[FloatArray, FloatArray, FloatArray]
    info_f: float = config.DEFAULT_F
    rtol: float = math.nan
    """The relative tolerance of the solve that succeeded (tighter than asked after a retry)."""
    retries: int = 0
    """How many retries a spurious yield event took (:func:`run_kernel`)."""

    def _deficit(self, h: FloatArray) -> FloatArray:
        """y = c - m_hat on the upper half (the series inside xi_0)."""
        p = self.params
        s = h - 0.5
        series = p[kernel.P_MU] * s * s
        inner = s < p[kernel.P_S0]
        dense = dense_eval(*self.couple, np.where(inner, 0.5 + p[kernel.P_S0], h))[:, 0]
        return np.where(inner, series, dense)

    def mapped(self, h: FloatArray) -> Fields:
        """Fields in the mapped variables at points h of [1/2, 1]."""
        p, info = self.params, self.info
        y = self._deficit(h)
        ell, P = kernel.spin_pass_at(h, p, *self.spin, info)
        tau, sqrt_S, F1 = kernel.arrays_at(h, y, p)
        with np.errstate(under="ignore"):
            w_hat = info[kernel.I_W_S] * np.exp(ell)
        u_hat = info[kernel.I_U_S] - info[kernel.I_W_S] * P
        A = _channel(self.problem).material.A
        return Fields(
            u=u_hat,
            omega=w_hat,
            m=p[kernel.P_C] - y,
            sigma_xy=A * tau - sqrt_S,
            sigma_yx=-tau,
            sigma_yy=np.ones_like(h),
            du_dxi=-w_hat * F1,
            kappa=np.zeros_like(h),
        )

    def __call__(self, xi: FloatArray) -> Fields:
        x = np.asarray(xi, dtype=float)
        h, sign = _mirror(x)
        f = self.mapped(h)
        w_hat, m_hat = f.spin()
        return physical_fields(x, f.u, w_hat, m_hat, f.sigma_xy, f.du_dxi, self.problem, sign)

    def velocity(self, xi: FloatArray) -> FloatArray:
        h, _ = _mirror(np.asarray(xi, dtype=float))
        _, P = kernel.spin_pass_at(h, self.params, *self.spin, self.info)
        return 1.0 - (self.info[kernel.I_U_S] - self.info[kernel.I_W_S] * P)

    def thickness(self, f: float) -> float:
        """Delta for the fraction f (``eqn-delta_defn`` with u_0 = u(1/2)) [d_p]."""
        if f == self.info_f and self.info[kernel.I_DELTA_OK]:
            return float(self.info[kernel.I_DELTA])
        delta, ok = kernel.thickness_of(self.params, *self.spin, self.info, float(f))
        if not ok:
            raise ParameterError(
                f"f = {f:g}: the velocity does not fall to this fraction of its wall value "
                f"within the half channel, so Delta (eqn-delta_defn) is not defined"
            )
        return float(delta)


def check_grid(problem: Problem) -> FloatArray:
    """Points of the upper half for the residual check: the layer-resolving grid, and a
    geometric grading towards the centre line, where the spin rate grows like 1/s."""
    grid = _channel(problem).output_grid(config.CHECK_POINTS)
    grid = grid[grid >= 0.5]
    near = 0.5 + np.geomspace(10.0 * START_OFFSET, 0.05, 60)
    return np.unique(np.concatenate([near, grid[grid > near[-1]]]))


def _mapped_evaluator(evaluate: Any) -> Any:
    """The mapped fields on the upper half from a channel evaluator (physical fields)."""

    def mapped(h: FloatArray) -> Fields:
        f = evaluate(h)
        return Fields(
            u=1.0 - f.u,
            omega=-f.omega,
            m=-f.m,
            sigma_xy=-f.sigma_xy,
            sigma_yx=-f.sigma_yx,
            sigma_yy=f.sigma_yy,
            du_dxi=-f.du_dxi,
            kappa=f.kappa,
        )

    return mapped


def _finish(
    problem: Problem, evaluate: Any, *, method: str, points: int | None,
    xi: FloatArray | None, check: bool, **kw: Any,
) -> Profile:  # fmt: skip
    """make_profile, then the channel's own residuals (mapped upper half) and wall errors."""
    profile = make_profile(
        problem,
        _channel(problem).mapped_formulation(),
        evaluate,
        method=method,
        points=points,
        xi=xi,
        reference_velocity=problem.reference_velocity,
        check=False,
        **kw,
    )
    if not check:
        return profile
    res = residuals(
        _channel(problem).mapped_formulation(), _mapped_evaluator(evaluate), check_grid(problem)
    )
    bc = _channel(problem).boundary_errors(evaluate)
    return replace(profile, diagnostics=replace(profile.diagnostics, residuals=res, bc_errors=bc))


def solve_numerical(
    problem: Problem,
    *,
    rtol: float = config.RTOL,
    atol: float | None = None,
    points: int | None = None,
    xi: FloatArray | None = None,
    check: bool = True,
) -> Profile:
    """The channel on the compiled core (module docstring; ``docs/derivation_channel.md``)."""
    rtol, atol = tolerances(rtol, atol)
    sol = run_kernel(problem, rtol, atol)
    info = sol.info
    stats = {
        "nfev": int(info[kernel.I_NFEV]),
        "steps": int(info[kernel.I_NSTEPS]),
        "lu_decompositions": int(info[kernel.I_NLU]),
        "couple_stress_steps": int(info[kernel.I_STEPS_COUPLE]),
        "spin_steps": int(info[kernel.I_STEPS_SPIN]),
        "spin_cutoff_xi": float(info[kernel.I_XI_CUT]),
        "centre_exponent": float(info[kernel.I_P_EXP]),
        "start_offset": float(sol.params[kernel.P_S0]),
        "retries": sol.retries,
        "rtol_used": sol.rtol,
    }
    return _finish(
        problem,
        sol,
        method="numerical",
        points=points,
        xi=xi,
        check=check,
        rtol=rtol,
        atol=atol,
        message=(
            "compiled: Radau IIA couple stress from the centre line (series start), DOP853 "
            "spin and velocity from the wall; velocity scaled by the centre-line velocity"
        ),
        stats=stats,
        velocity=sol.velocity,
    )


def run_kernel(
    problem: Problem, rtol: float, atol: float, f: float = config.DEFAULT_F
) -> ChannelSolution:
    """Solve on the compiled kernel; raise the package's error if it fails.

    A yield event (S reaching zero, no real solution beyond it) is only reported as
    :class:`NoSolutionError` once a solve at a tolerance tighter by ``RETRY_TIGHTENING`` finds it
    again away from the centre line (or rtol is already at its floor). An event within
    ``NEAR_CENTRE_OFFSETS`` start offsets of the centre line is undecided (the series there is a
    real solution, doc section 4): it is retried with a tighter tolerance and s_0/10, and if it
    persists the solve raises :class:`ConvergenceError`, saying where and why, not
    NoSolutionError.
    """
    s0 = START_OFFSET
    floor = config.RTOL_RANGE[0]
    tried: list[str] = []
    far_events = 0
    for attempt in range(MAX_RETRIES + 1):
        p = parameter_vector(problem, s0)
        status, info, couple, spin = kernel.solve_case(p, rtol, atol, f, config.MAX_STEPS)
        if status == kernel.OK:
            return ChannelSolution(problem, p, info, couple, spin, float(f), rtol, attempt)
        if status != kernel.NO_SOLUTION:
            raise_for_status(problem, int(status), info, rtol)
        xi_fail = float(info[kernel.I_XI_FAIL])
        near = xi_fail - 0.5 < NEAR_CENTRE_OFFSETS * s0
        tried.append(f"xi = {xi_fail:.9g} at rtol = {rtol:.3g}, s_0 = {s0:.3g}")
        if not near:
            far_events += 1
            if far_events >= 2 or rtol <= floor:
                raise_for_status(problem, int(status), info, rtol)
        tighter = max(rtol / RETRY_TIGHTENING, floor)
        atol *= tighter / rtol
        rtol = tighter
        if near:
            s0 /= 10.0
    raise ConvergenceError(
        f"cannot decide whether {problem.describe()} has a real solution: integrated from the "
        f"centre line, the couple stress met the yield bound ({'; '.join(tried)}), within "
        f"{NEAR_CENTRE_OFFSETS:g} start offsets s_0 of the centre line or at a place that "
        f"moved with the tolerance; the series through the centre line is a real solution "
        f"there when eps alpha B nu (1 - A) <= 2 c (1 + A) (docs/derivation_channel.md, "
        f"section 4), so the integration could not resolve the narrow band between the couple "
        f"stress and its bound: try a tighter rtol"
    )


def wall_quantities(
    problems: Sequence[Problem],
    rtol: float = config.RTOL,
    f: float = config.DEFAULT_F,
    *,
    atol: float | None = None,
) -> list[WallResult]:
    """Delta, wall slip, wall spin and wall stress of each channel, as
    :func:`cosserat.routes.numerical.wall_quantities` reports them for the other cells (one
    compiled solve each; a failure is a status and its message, never NaN)."""
    rtol, atol = tolerances(rtol, atol)
    if not 0.0 < f < 1.0:
        raise ParameterError(f"f must satisfy 0 < f < 1; got {f:g}")
    out = []
    for pr in problems:
        if not (isinstance(pr, Problem) and pr.model == "cosserat" and pr.cell_name == "channel"):
            raise ParameterError(
                "expected the Cosserat model on the channel cell; got "
                f"{getattr(pr, 'model', type(pr).__name__)} on {getattr(pr, 'cell_name', '?')}"
            )
        try:
            sol = run_kernel(pr, rtol, atol, f)
        except NoSolutionError as exc:
            out.append(WallResult("no-solution", None, None, None, None, str(exc)))
            continue
        except ConvergenceError as exc:
            out.append(WallResult("error", None, None, None, None, str(exc)))
            continue
        info = sol.info
        slip = abs(1.0 - info[kernel.I_U_S])  # u at the wall = 1 - u_hat_w
        omega = -float(info[kernel.I_W_S])
        stress = _channel(pr).wall_stress
        if not info[kernel.I_DELTA_OK]:
            message = f"f = {f:g}: Delta is not defined (the velocity does not fall to f)"
            out.append(WallResult("error", None, slip, omega, stress, message))
            continue
        out.append(WallResult("ok", float(info[kernel.I_DELTA]), slip, omega, stress))
    return out


# ----------------------------------------------------------------- asymptotic route
THIN_LAYER = 0.1
"""The expansion needs eps Delta at most this fraction of the channel width."""


def asymptotic_thickness(problem: Problem, f: float = config.DEFAULT_F) -> float:
    """Leading-order Delta [d_p]: -ln f / k (walls not fully rough: independent of eps), or
    x_f eps^(-1/3) (L^2/4)^(1/3) at fully rough slipping walls (doc sections 5-6)."""
    k = _channel(problem).slip_constants.k
    if k > 0.0:
        return -math.log(f) / k
    return xi_hat_at_fraction(f) * problem.eps ** (-1.0 / 3.0) * _channel(problem).inner_scale()


class _AsymptoticEvaluator:
    """Leading-order fields with the channel's thickness law attached."""

    def __init__(self, problem: Problem) -> None:
        self.problem = problem

    def thickness(self, f: float) -> float:
        """Delta of the leading-order profile for the fraction f [d_p]."""
        if not 0.0 < f < 1.0:
            raise ParameterError(f"f must satisfy 0 < f < 1; got {f:g}")
        if _channel(self.problem).is_fully_rough:
            return asymptotic_thickness(self.problem, f)
        # the exponential layer: u_hat = u_hat_w e^(-k d/eps) falls to f u_hat_w at d = eps Delta
        return asymptotic_thickness(self.problem, f)

    def mapped(self, h: FloatArray) -> Fields:
        pr = self.problem
        mat, eps = _channel(pr).material, pr.eps
        d = 1.0 - h
        tau = shear_stress(np.asarray(h, dtype=float), _channel(pr).B_nu)
        m_outer = -_channel(pr).outer_couple_stress(h)
        if _channel(pr).is_fully_rough:
            scale = _channel(pr).inner_scale()
            x_hat = d * eps ** (-2.0 / 3.0) / scale
            a = 0.5 * mat.sin_phi
            gamma = 4.0 * mat.c2  # m_outer^2 ~ gamma d at the wall (doc section 6)
            amp = (2.0 * a * mat.alpha * gamma * eps) ** (1.0 / 3.0)
            # additive composite (as eqn-eta_g_unif); its Airy correction decays only like
            # amp/(4 x_hat) = O(eps) outside the layer, and on the centre line the outer
            # solution lies on the yield bound b, so the correction is kept below b - m^(0)
            correction = amp * inner_couple_stress(x_hat) - np.sqrt(gamma * d)
            b = np.sqrt(np.maximum(mat.c2 + tau**2 * (mat.A - 1.0) / (4.0 * (mat.A + 1.0)), 0.0))
            room = np.maximum(b - m_outer, 0.0)
            m_hat = m_outer + np.minimum(correction, room)
            u_hat, w_hat = airy_layer(x_hat, eps=eps, scale=scale, u_wall=1.0, slip_sign=1.0)
        else:
            k = _channel(pr).slip_constants.k
            K = _channel(pr).wall.K if _channel(pr).slips else 0.0
            with np.errstate(under="ignore"):
                decay = np.exp(-k * d / eps)
            u_hat = (2.0 / k) / (K + 2.0 / k) * decay
            w_hat = -decay / (eps * (K + 2.0 / k))
            m_hat = m_outer
        return Fields(
            u=u_hat,
            omega=w_hat,
            m=m_hat,
            sigma_xy=-tau,
            sigma_yx=-tau,
            sigma_yy=np.ones_like(h),
            du_dxi=-2.0 * w_hat,
            kappa=np.zeros_like(h),
        )

    def __call__(self, xi: FloatArray) -> Fields:
        x = np.asarray(xi, dtype=float)
        h, sign = _mirror(x)
        f = self.mapped(h)
        w_hat, m_hat = f.spin()
        return physical_fields(x, f.u, w_hat, m_hat, f.sigma_xy, f.du_dxi, self.problem, sign)


def solve_asymptotic(
    problem: Problem,
    *,
    points: int | None = None,
    xi: FloatArray | None = None,
    check: bool = True,
) -> Profile:
    """Leading order in eps (``docs/derivation_channel.md`` sections 5-6).

    Raises
    ------
    MethodNotAvailableError
        The layer is not thin (eps Delta > 0.1 of the width), the leading-order profile
        leaves the yield surface, or at fully rough walls the Airy layer misses a boundary
        condition by more than :data:`~cosserat.routes.asymptotic.AIRY_BC_TOL`.
    """
    thickness = problem.eps * asymptotic_thickness(problem)
    if thickness > THIN_LAYER:
        raise MethodNotAvailableError(
            f"the small-eps asymptotics need a layer much thinner than the channel, but the "
            f"leading-order layer is {thickness:.3g} widths thick (> {THIN_LAYER:g}): use "
            f"method='numerical'"
        )
    order = (
        "Airy inner layer of thickness ~ eps^(2/3) at the fully rough walls"
        if _channel(problem).is_fully_rough
        else "exponential layer of constant thickness eps/k at the walls"
    )
    try:
        profile = _finish(
            problem,
            _AsymptoticEvaluator(problem),
            method="asymptotic",
            points=points,
            xi=xi,
            check=check,
            message=f"leading order in eps: {order}; velocity scaled by the centre-line velocity",
        )
    except NoSolutionError as exc:
        raise MethodNotAvailableError(
            f"the leading-order asymptotic profile leaves the yield surface ({exc}): use "
            f"method='numerical'"
        ) from None
    if _channel(problem).is_fully_rough:
        return require_boundary_conditions(_channel(problem), profile)
    return profile


__all__ = [
    "I_INFINITY",
    "ChannelSolution",
    "asymptotic_thickness",
    "parameter_vector",
    "solve_asymptotic",
    "solve_numerical",
    "wall_quantities",
]
