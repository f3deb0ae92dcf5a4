"""Numerical route: every problem, every eps in (0, 0.5], on the compiled core.

This layer only validates, translates a problem into the kernel's parameter vector, calls
:func:`cosserat.numerics.cosserat.solve_case` (one problem) or ``solve_batch`` (many), turns
status codes into the package's errors and wraps the result as a
:class:`~cosserat.results.profile.Profile` (``docs/numerics.md``).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from .. import config
from ..errors import ConvergenceError, NoSolutionError, ParameterError, shown
from ..model import PlaneShearCase, Problem
from ..model.constitutive import FloatArray
from ..model.formulation import Formulation
from ..numerics import cosserat as kernel
from ..numerics.radau import dense_eval
from ..numerics.runtime import map_batches
from ..results.profile import Fields, Profile
from .assemble import fields_from_state, make_profile

DEFAULT_RTOL = config.RTOL

_CASES = {
    PlaneShearCase.SYMMETRIC: kernel.SYMMETRIC,
    PlaneShearCase.UPPER: kernel.UPPER,
    PlaneShearCase.LOWER: kernel.LOWER,
}


def tolerances(rtol: float, atol: float | None) -> tuple[float, float]:
    """Validated (rtol, atol); atol defaults to ``config.ATOL_OVER_RTOL`` times rtol."""
    lo, hi = config.RTOL_RANGE
    if not (isinstance(rtol, int | float) and lo <= rtol <= hi):
        raise ParameterError(
            f"rtol must satisfy {lo:g} <= rtol <= {hi:g} (relative tolerance of the "
            f"integration); got {shown(rtol)}"
        )
    if atol is None:
        return float(rtol), float(rtol) * config.ATOL_OVER_RTOL
    if not (isinstance(atol, int | float) and 0.0 < atol <= 1.0):
        raise ParameterError(f"atol must satisfy 0 < atol <= 1; got {shown(atol)}")
    return float(rtol), float(atol)


def parameter_vector(problem: Problem, mu_guess: float | None = None) -> FloatArray:
    """The kernel's parameter vector (indices ``P_*`` of :mod:`cosserat.numerics.cosserat`)
    for the Cosserat model on the plane or Couette cell."""
    eq = problem.equations
    p = np.zeros(kernel.N_PARAMS)
    mat = eq.material
    p[kernel.P_A], p[kernel.P_SIN_PHI], p[kernel.P_ALPHA] = mat.A, mat.sin_phi, mat.alpha
    p[kernel.P_EPS] = eq.eps
    const = eq.slip_constants
    p[kernel.P_M0], p[kernel.P_B_BOUND] = const.m0, const.b
    p[kernel.P_MU_GUESS] = math.nan if mu_guess is None else float(mu_guess)
    if problem.cell_name == "couette":
        p[kernel.P_GEOMETRY] = kernel.COUETTE
        p[kernel.P_TAN_DELTA] = eq.tan_delta
        p[kernel.P_RI] = eq.Ri
        p[kernel.P_COUPLE] = eq.couple_factor
        p[kernel.P_K_SLIP] = eq.wall.K
        return p
    case = eq.case
    p[kernel.P_GEOMETRY] = kernel.PLANE
    p[kernel.P_CASE] = _CASES[case]
    p[kernel.P_SIGMA_YX] = eq.sigma_yx
    p[kernel.P_B_NU] = eq.B * eq.nu
    p[kernel.P_M_START] = 0.0 if case is PlaneShearCase.SYMMETRIC else eq.m_at_fixed_wall
    p[kernel.P_K_SLIP] = eq.slipping.K
    p[kernel.P_K_OTHER] = eq.lower_wall.K
    return p


def raise_for_status(problem: Problem, status: int, info: FloatArray) -> None:
    """Turn a kernel status code into the package's error, saying where and why."""
    if status == kernel.OK:
        return
    xi, m = float(info[kernel.I_XI_FAIL]), float(info[kernel.I_M_FAIL])
    if status == kernel.NO_SOLUTION:
        if problem.cell_name == "couette":
            raise NoSolutionError(
                f"no real solution for {problem.describe()}: for no couple stress m(0) at the "
                f"inner cylinder does the couple-stress balance, integrated from the outer "
                f"cylinder (eqn-nd_bc1_cyl), stay inside the yield surface across the gap (the "
                f"last admissible trial left it at xi = {xi:.6g}, m = {m:.6g}); see "
                f"docs/derivation_couette.md, 'existence'"
            )
        raise NoSolutionError(
            f"no real solution for {problem.describe()}: the couple stress reaches the yield "
            f"bound at xi = {xi:.6g} (m = {m:.6g}), beyond which the second shear stress of "
            f"eqn-nd_sigxy is complex; the couple-stress balance cannot be continued to the "
            f"slipping wall"
        )
    if status == kernel.AT_YIELD_EDGE:
        raise ConvergenceError(
            f"cannot decide whether {problem.describe()} has a real solution: the computed "
            f"couple stress crossed its yield bound (the radicand of eqn-nd_sigxy) at xi = "
            f"{xi:.6g} (m = {m:.6g}) while relaxing towards the value where the stress is "
            f"symmetric, which an exact solution cannot do; that value lies within the "
            f"tolerance of its yield bound, at the edge of the model's real domain (a nearly "
            f"frictionless wall; docs/numerics.md, 'Where it stops working')"
        )
    if status == kernel.SINGULAR_VELOCITY:
        raise ConvergenceError(
            f"the velocity boundary conditions are singular for {problem.describe()}"
        )
    if status == kernel.NO_BRACKET:
        raise ConvergenceError(
            f"Couette: cannot bracket the inner-wall couple stress m(0) for {problem.describe()}"
        )
    budget = "ran out of its step budget" if status == kernel.TOO_MANY_STEPS else "stalled"
    raise ConvergenceError(
        f"the integration {budget} at xi = {xi:.6g} (m = {m:.6g}) for {problem.describe()}: "
        f"the couple stress is close to its yield bound there, where the couple-stress equation "
        f"is singular (dF/dm ~ 1/sqrt(S)); the problem is at the edge of the model's real "
        f"domain (a nearly frictionless wall, or a very small inner cylinder at small eps; "
        f"docs/numerics.md, 'Where it stops working')"
    )


@dataclass(frozen=True, eq=False)
class NumericalSolution:
    """The dense solution of the compiled kernel: the fields anywhere in [0, 1].

    Plain arrays and the problem, so it pickles (Dask and multiprocessing ship profiles).

    Attributes
    ----------
    problem : Problem
        The Cosserat model on the plane or Couette cell.
    params, info : ndarray
        The kernel's parameter and result vectors (``P_*``, ``I_*``).
    couple : tuple of ndarray
        Radau dense output (ts, hs, ys, Q) of the couple stress, in xi.
    spin : tuple of ndarray
        DOP853 dense output (ts, ys, F) of (l, P), in the pass variable tau with xi(tau) from
        ``geometry``.
    geometry : ndarray
        [xi of the slipping wall, span, singular] of the spin pass.
    """

    problem: Problem
    params: FloatArray
    info: FloatArray
    couple: tuple[FloatArray, FloatArray, FloatArray, FloatArray]
    spin: tuple[FloatArray, FloatArray, FloatArray]
    geometry: FloatArray

    @property
    def mu(self) -> float:
        return float(self.info[kernel.I_MU])

    def formulation(self) -> Formulation:
        if self.problem.cell_name == "couette":
            return self.problem.equations.formulation(self.mu)
        return self.problem.equations.formulation()

    @property
    def symmetric(self) -> bool:
        return (
            self.problem.cell_name == "plane"
            and self.problem.equations.case is PlaneShearCase.SYMMETRIC
        )

    def _half(self, x: FloatArray) -> FloatArray:
        """Points mapped onto the solved half (symmetric case) [-]."""
        return np.where(x >= 0.5, x, 1.0 - x) if self.symmetric else x

    def _state(self, x: FloatArray) -> tuple[FloatArray, FloatArray, FloatArray]:
        """(m, u, w) at points x of the solved part of the gap."""
        m = dense_eval(*self.couple, x)[:, 0]
        ell, P = kernel.spin_pass_at(x, self.geometry, *self.spin)
        u = kernel.velocities(x, P, self.params, self.info)
        with np.errstate(under="ignore"):
            w = self.info[kernel.I_W_S] * np.exp(ell)
        return m, u, w

    def __call__(self, xi: FloatArray) -> Fields:
        x = np.asarray(xi, dtype=float)
        h = self._half(x)
        m, u, w = self._state(h)
        f = fields_from_state(self.formulation(), h, m, u, w)
        if not self.symmetric:
            return f
        # u - u_c odd and omega even about xi = 1/2, m odd (eqn-nd_bc6)
        low = x < 0.5
        u_c = self.info[kernel.I_U_REF]
        return f._replace(
            u=np.where(low, 2.0 * u_c - f.u, f.u),
            m=np.where(low, -f.m, f.m),
            du_dxi=f.du_dxi,
        )

    def velocity(self, xi: FloatArray) -> FloatArray:
        """u only (cheaper than the fields) [-]."""
        x = np.asarray(xi, dtype=float)
        h = self._half(x)
        _, P = kernel.spin_pass_at(h, self.geometry, *self.spin)
        u = kernel.velocities(h, P, self.params, self.info)
        if self.symmetric:
            u = np.where(x < 0.5, 2.0 * self.info[kernel.I_U_REF] - u, u)
        return u

    def thickness(self, f: float) -> float:
        """Delta for the velocity fraction f (``eqn-delta_defn``), by the compiled kernel."""
        if f == self.info_f and self.info[kernel.I_DELTA_OK]:
            return float(self.info[kernel.I_DELTA])
        delta, ok = kernel.thickness_of(self.params, self.geometry, *self.spin, self.info, float(f))
        if not ok:
            raise ParameterError(
                f"f = {f:g}: the velocity does not fall to this fraction of its wall value "
                f"within the gap, so Delta (eqn-delta_defn) is not defined; choose a larger f"
            )
        return float(delta)

    info_f: float = config.DEFAULT_F


def run_kernel(
    problem: Problem,
    rtol: float,
    atol: float,
    mu_guess: float | None = None,
    f: float = config.DEFAULT_F,
) -> NumericalSolution:
    """Solve ``problem`` on the compiled core; raise the package's error if it fails."""
    p = parameter_vector(problem, mu_guess)
    status, info, couple, spin, geometry = kernel.solve_case(p, rtol, atol, f, config.MAX_STEPS)
    raise_for_status(problem, int(status), info)
    return NumericalSolution(problem, p, info, couple, spin, geometry, float(f))


def _stats(info: FloatArray) -> dict[str, Any]:
    return {
        "nfev": int(info[kernel.I_NFEV]),
        "steps": int(info[kernel.I_NSTEPS]),
        "lu_decompositions": int(info[kernel.I_NLU]),
        "couple_stress_steps": int(info[kernel.I_STEPS_COUPLE]),
        "spin_steps": int(info[kernel.I_STEPS_SPIN]),
        "spin_cutoff_xi": float(info[kernel.I_XI_CUT]),
    }


def solve_plane(
    problem: Problem,
    *,
    rtol: float = DEFAULT_RTOL,
    atol: float | None = None,
    points: int | None = None,
    xi: FloatArray | None = None,
    check: bool = True,
) -> Profile:
    """Plane shear, any case (``docs/numerics.md``).

    The couple stress is integrated from the non-slipping wall (or from the centre, where
    m(1/2) = 0 in the symmetric case) to the slipping wall; spin and velocity from the slipping
    wall back.
    """
    rtol, atol = tolerances(rtol, atol)
    sol = run_kernel(problem, rtol, atol)
    message = "compiled: Radau IIA couple stress (stable direction), DOP853 spin and velocity"
    return _profile(sol, rtol, atol, points, xi, check, message, _stats(sol.info))


def solve_couette(
    problem: Problem,
    *,
    rtol: float = DEFAULT_RTOL,
    atol: float | None = None,
    points: int | None = None,
    xi: FloatArray | None = None,
    check: bool = True,
    m_inner_guess: float | None = None,
) -> Profile:
    """Couette flow: m(0) by a compiled secant/Brent iteration on ``m(0; mu) - mu``
    (``eqn-nd_shsts_cyl``), the couple stress from the outer cylinder inwards for each trial;
    then spin and velocity from the inner cylinder outwards. ``m_inner_guess`` (e.g. from a
    neighbouring eps in a sweep) replaces the leading-order starting value."""
    rtol, atol = tolerances(rtol, atol)
    if m_inner_guess is not None and not math.isfinite(float(m_inner_guess)):
        raise ParameterError(f"m_inner_guess must be finite; got {shown(m_inner_guess)}")
    sol = run_kernel(problem, rtol, atol, m_inner_guess)
    stats = _stats(sol.info)
    stats["m_inner"] = sol.mu
    stats["shooting_iterations"] = int(sol.info[kernel.I_ITERATIONS])
    message = (
        "compiled: secant/Brent on m(0); Radau IIA couple stress (outer to inner), "
        "DOP853 spin and velocity"
    )
    return _profile(sol, rtol, atol, points, xi, check, message, stats)


def _profile(
    sol: NumericalSolution,
    rtol: float,
    atol: float,
    points: int | None,
    xi: FloatArray | None,
    check: bool,
    message: str,
    stats: dict[str, Any],
) -> Profile:
    """The checked :class:`Profile` of a kernel solution (``routes/assemble.py``)."""
    return make_profile(
        sol.problem,
        sol.formulation(),
        sol,
        method="numerical",
        points=points,
        xi=xi,
        reference_velocity=float(sol.info[kernel.I_U_REF]),
        rtol=rtol,
        atol=atol,
        message=message,
        stats=stats,
        check=check,
        velocity=sol.velocity,
    )


# ----------------------------------------------------------------- many problems at once
BATCHED = ("plane", "couette")
"""The cells the batch kernel solves for the Cosserat model."""


def is_batched(problem: Any) -> bool:
    """True for a problem of the Cosserat model on a cell of :data:`BATCHED`."""
    return (
        isinstance(problem, Problem)
        and problem.model == "cosserat"
        and problem.cell_name in BATCHED
    )


def _name(problem: Any) -> str:
    if isinstance(problem, Problem):
        return f"the {problem.model} rheology on the {problem.cell_name} cell"
    return f"a {type(problem).__name__}"


@dataclass(frozen=True)
class WallResult:
    """Wall quantities of one problem (dimensionless; ``None`` where there is no solution).

    ``status`` is "ok", "no-solution" (the model has no real solution) or "error" (the solver
    could not finish; ``message`` says why).
    """

    status: str
    Delta: float | None
    wall_slip: float | None
    wall_omega: float | None
    wall_stress: float | None  # sigma_yx (sigma_r_theta) at the slipping wall
    message: str = ""
    m_inner: float | None = None


def wall_quantities(
    problems: Sequence[Problem],
    rtol: float = DEFAULT_RTOL,
    f: float = config.DEFAULT_F,
    *,
    atol: float | None = None,
) -> list[WallResult]:
    """Delta, wall slip, wall spin and wall stress for every problem, in parallel.

    The same compiled kernel as :func:`solve`, called for the whole batch (``solve_batch``,
    on as many threads as cores). A case that fails is reported with its
    status and the message :func:`solve` would raise; no NaN stands in for an answer.
    """
    rtol, atol = tolerances(rtol, atol)
    if not 0.0 < f < 1.0:
        raise ParameterError(f"f must satisfy 0 < f < 1; got {f:g}")
    if not problems:
        return []
    for pr in problems:
        if not is_batched(pr):
            raise ParameterError(
                f"the batch kernel solves the Cosserat model on the plane and Couette cells; "
                f"got {_name(pr)}"
            )
    params = np.stack([parameter_vector(pr) for pr in problems])
    status, info = map_batches(params, rtol, atol, float(f), config.MAX_STEPS)
    out = []
    for pr, code, row in zip(problems, status, info, strict=True):
        out.append(_wall_result(pr, int(code), row, f))
    return out


def _wall_result(problem: Problem, code: int, row: FloatArray, f: float) -> WallResult:
    if code != kernel.OK:
        try:
            raise_for_status(problem, code, row)
        except NoSolutionError as exc:
            return WallResult("no-solution", None, None, None, None, str(exc))
        except ConvergenceError as exc:
            return WallResult("error", None, None, None, None, str(exc))
    m_inner = float(row[kernel.I_MU]) if problem.cell_name == "couette" else None
    if not row[kernel.I_DELTA_OK]:
        return WallResult(
            "error",
            None,
            float(row[kernel.I_WALL_SLIP]),
            float(row[kernel.I_WALL_OMEGA]),
            float(row[kernel.I_WALL_STRESS]),
            f"f = {f:g}: the velocity does not fall to this fraction of its wall value within "
            f"the gap, so Delta is not defined",
            m_inner,
        )
    return WallResult(
        "ok",
        float(row[kernel.I_DELTA]),
        float(row[kernel.I_WALL_SLIP]),
        float(row[kernel.I_WALL_OMEGA]),
        float(row[kernel.I_WALL_STRESS]),
        "",
        m_inner,
    )
