"""Numerical route: every problem, every eps in (0, 0.5], on the compiled core.

This layer only validates, translates a problem into the kernel's parameter vector, calls
:func:`cosserat.numerics.cosserat.solve_case` (one problem; ``solve_plane_case`` or
``solve_couette_case``), ``solve_batch`` (the wall quantities of many) or ``predict_batch``
(chosen fields of many at given points: :func:`predict`, :func:`predict_many`), turns status
codes into the package's errors and wraps the result as a
:class:`~cosserat.results.profile.Profile` (``docs/numerics.md``).
"""

from __future__ import annotations

import math
import weakref
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from .. import config
from ..errors import ConvergenceError, NoSolutionError, ParameterError, shown
from ..model import PlaneShearCase, Problem
from ..model.constitutive import RADICAND_ROUNDOFF, FloatArray
from ..model.formulation import Formulation
from ..model.rheologies.base import equations_of
from ..model.rheologies.cosserat import (
    CosseratCouette,
    CosseratPlane,
    cosserat_equations,
)
from ..numerics import cosserat as kernel
from ..numerics.runtime import map_batches
from ..results.diagnostics import Deferred, DeferredResiduals
from ..results.profile import PENDABLE, Diagnostics, Fields, Profile, assembled, pending
from .assemble import check_fields, profile_grid

DEFAULT_RTOL = config.RTOL
_DEFAULT_TOLERANCES = (float(DEFAULT_RTOL), float(DEFAULT_RTOL) * config.ATOL_OVER_RTOL)
SCREEN_SLACK = RADICAND_ROUNDOFF * (1.0 - 1e-6)
"""The compiled screen of a profile's radicand check flags S < -SCREEN_SLACK * scale: a hair
stricter than the check itself (``RADICAND_ROUNDOFF``), which then decides in Python."""

_CASES = {
    PlaneShearCase.SYMMETRIC: kernel.SYMMETRIC,
    PlaneShearCase.UPPER: kernel.UPPER,
    PlaneShearCase.LOWER: kernel.LOWER,
}


def tolerances(rtol: float, atol: float | None) -> tuple[float, float]:
    """Validated (rtol, atol); atol defaults to ``config.ATOL_OVER_RTOL`` times rtol."""
    if rtol is DEFAULT_RTOL and atol is None:  # the default call: config.RTOL, in range
        return _DEFAULT_TOLERANCES
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
    for the Cosserat model on the plane or Couette cell (a new array)."""
    eq = cosserat_equations(problem)
    found = _VECTORS.get(eq)
    if found is None:
        found = _VECTORS[eq] = _parameter_vector(problem, eq)
    p = found.copy()
    if mu_guess is not None:
        p[kernel.P_MU_GUESS] = float(mu_guess)
    return p


_VECTORS: weakref.WeakKeyDictionary[Any, FloatArray] = weakref.WeakKeyDictionary()
"""The parameter vector of each problem (its equations helper), made once: every caller gets
a copy, so no kernel or caller can change another's."""


def _parameter_vector(problem: Problem, eq: Any) -> FloatArray:
    """:func:`parameter_vector` without a guess of m(0), made from the equations."""
    p = np.zeros(kernel.N_PARAMS)
    mat = eq.material
    p[kernel.P_A], p[kernel.P_SIN_PHI], p[kernel.P_ALPHA] = mat.A, mat.sin_phi, mat.alpha
    p[kernel.P_EPS] = eq.eps
    const = eq.slip_constants
    p[kernel.P_M0], p[kernel.P_B_BOUND] = const.m0, const.b
    p[kernel.P_MU_GUESS] = math.nan
    if isinstance(eq, CosseratCouette):
        p[kernel.P_GEOMETRY] = kernel.COUETTE
        p[kernel.P_TAN_DELTA] = eq.tan_delta
        p[kernel.P_RI] = eq.Ri
        p[kernel.P_COUPLE] = eq.couple_factor
        p[kernel.P_K_SLIP] = eq.wall.K
        return p
    plane = equations_of(problem, CosseratPlane)
    case = plane.case
    p[kernel.P_GEOMETRY] = kernel.PLANE
    p[kernel.P_CASE] = _CASES[case]
    p[kernel.P_SIGMA_YX] = plane.sigma_yx
    p[kernel.P_B_NU] = plane.B * plane.nu
    p[kernel.P_M_START] = 0.0 if case is PlaneShearCase.SYMMETRIC else plane.m_at_fixed_wall
    p[kernel.P_K_SLIP] = plane.slipping.K
    p[kernel.P_K_OTHER] = plane.lower_wall.K
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
        eq = cosserat_equations(self.problem)
        if isinstance(eq, CosseratCouette):
            return eq.formulation(self.mu)
        return equations_of(self.problem, CosseratPlane).formulation()

    @property
    def symmetric(self) -> bool:
        return (
            self.problem.cell_name == "plane"
            and equations_of(self.problem, CosseratPlane).case is PlaneShearCase.SYMMETRIC
        )

    def _half(self, x: FloatArray) -> FloatArray:
        """Points mapped onto the solved half (symmetric case) [-]."""
        return np.where(x >= 0.5, x, 1.0 - x) if self.symmetric else x

    def __call__(self, xi: FloatArray) -> Fields:
        x = np.asarray(xi, dtype=float)
        # fields_checked, not fields_at (the same numbers): the profile's own entry point, so a
        # first solve compiles one field loop, not two
        out, _, _ = kernel.fields_checked(
            np.ascontiguousarray(x.ravel()),
            self.params,
            self.info,
            *self.couple,
            self.geometry,
            *self.spin,
            0.0,
        )
        if x.ndim == 1:
            return Fields(*out)
        return Fields(*(row.reshape(x.shape) for row in out))

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


class _Inputs:
    """What every solve of one problem passes to the kernel, made once per problem: the
    parameter vector (no guess of m(0)), the slipping wall, and the default output grid
    (made on its first use: a caller with its own points never pays for it)."""

    __slots__ = ("couette", "equations", "grid", "params", "slip_wall")

    def __init__(self, problem: Problem) -> None:
        eq = cosserat_equations(problem)
        params = _VECTORS.get(eq)
        if params is None:
            params = _VECTORS[eq] = _parameter_vector(problem, eq)
        self.equations: Any = eq
        self.params: FloatArray = params
        self.slip_wall = float(problem.slip_wall)
        self.couette = isinstance(eq, CosseratCouette)
        self.grid: FloatArray | None = None

    def output_grid(self, points: int | None, xi: FloatArray | None) -> FloatArray:
        """The profile's grid (:func:`~.assemble.profile_grid`), a new array."""
        if xi is not None or points is not None:
            return profile_grid(self.equations, points, xi)
        if self.grid is None:
            self.grid = profile_grid(self.equations, None, None)
        return self.grid.copy()


_INPUTS: weakref.WeakKeyDictionary[Any, _Inputs] = weakref.WeakKeyDictionary()
""":class:`_Inputs` per problem (its equations helper)."""


def _inputs(problem: Problem) -> _Inputs:
    """The problem's :class:`_Inputs` (the first call checks it is the Cosserat model's)."""
    found = _INPUTS.get(problem.equations)
    if found is None:
        found = _Inputs(problem)
        _INPUTS[found.equations] = found
    return found


def run_kernel(
    problem: Problem,
    rtol: float,
    atol: float,
    mu_guess: float | None = None,
    f: float = config.DEFAULT_F,
) -> NumericalSolution:
    """Solve ``problem`` on the compiled core; raise the package's error if it fails."""
    return _run(_inputs(problem), problem, rtol, atol, mu_guess, f)


def _run(
    inputs: _Inputs,
    problem: Problem,
    rtol: float,
    atol: float,
    mu_guess: float | None = None,
    f: float = config.DEFAULT_F,
) -> NumericalSolution:
    """:func:`run_kernel` with the problem's inputs at hand."""
    p = inputs.params.copy()  # the caller's own (NumericalSolution.params)
    if mu_guess is not None:
        p[kernel.P_MU_GUESS] = float(mu_guess)
    # one cell's entry point: a first run compiles only that cell's search
    solve_case = kernel.solve_couette_case if inputs.couette else kernel.solve_plane_case
    status, info, couple, spin, geometry = solve_case(p, rtol, atol, f, config.MAX_STEPS)
    if status != kernel.OK:
        raise_for_status(problem, int(status), info)
    # the frozen dataclass's __init__ without its object.__setattr__ per field (no
    # __post_init__; every field given)
    sol = object.__new__(NumericalSolution)
    sol.__dict__.update(
        problem=problem, params=p, info=info, couple=couple, spin=spin, geometry=geometry,
        info_f=float(f),
    )  # fmt: skip
    return sol


def _stats(info: FloatArray) -> dict[str, Any]:
    return {
        "nfev": int(info[kernel.I_NFEV]),
        "steps": int(info[kernel.I_NSTEPS]),
        "lu_decompositions": int(info[kernel.I_NLU]),
        "couple_stress_steps": int(info[kernel.I_STEPS_COUPLE]),
        "spin_steps": int(info[kernel.I_STEPS_SPIN]),
        "spin_cutoff_xi": float(info[kernel.I_XI_CUT]),
    }


PLANE_MESSAGE = "compiled: Radau IIA couple stress (stable direction), DOP853 spin and velocity"
COUETTE_MESSAGE = (
    "compiled: Newton (secant/Brent as fallback) on m(0); Radau IIA couple stress "
    "(outer to inner), DOP853 spin and velocity"
)


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
    inputs = _inputs(problem)
    return _profile(inputs, _run(inputs, problem, rtol, atol), rtol, atol, points, xi, check)


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
    """Couette flow: m(0) by compiled Newton iterations on ``m(0; mu) - mu``
    (``eqn-nd_shsts_cyl``; secant/Brent if they fail), the couple stress from the outer
    cylinder inwards for each trial; then spin and velocity from the inner cylinder outwards.
    ``m_inner_guess`` (e.g. from a neighbouring eps in a sweep) replaces the leading-order
    starting value."""
    rtol, atol = tolerances(rtol, atol)
    if m_inner_guess is not None and not math.isfinite(float(m_inner_guess)):
        raise ParameterError(f"m_inner_guess must be finite; got {shown(m_inner_guess)}")
    inputs = _inputs(problem)
    sol = _run(inputs, problem, rtol, atol, m_inner_guess)
    return _profile(inputs, sol, rtol, atol, points, xi, check)


def _profile(
    inputs: _Inputs,
    sol: NumericalSolution,
    rtol: float,
    atol: float,
    points: int | None,
    xi: FloatArray | None,
    check: bool,
) -> Profile:
    """The checked :class:`Profile` of a kernel solution: what
    :func:`~.assemble.make_profile` makes, with less Python (``docs/performance.md``).

    The fields at the output grid and the compiled screen of the profile's checks in one
    call (``kernel.fields_checked``): a point it flags sends the profile through
    :func:`~.assemble.check_fields`, which decides and words any refusal. The fields' arrays
    (rows of the kernel's one array) and the :class:`Diagnostics` are made on first read
    (:func:`~cosserat.results.profile.pending`, :func:`_rest`); the residuals and boundary
    errors when first read, as in every route.
    """
    problem = sol.problem
    grid = inputs.output_grid(points, xi)
    out, first, finite = kernel.fields_checked(
        grid if xi is None else np.ascontiguousarray(grid),
        sol.params,
        sol.info,
        *sol.couple,
        sol.geometry,
        *sol.spin,
        SCREEN_SLACK,
    )
    if first >= 0 or not finite:
        check_fields(problem, "numerical", grid, Fields(*out))
    return pending(
        Profile,
        {
            "problem": problem,
            "xi": grid,
            "slip_wall": inputs.slip_wall,
            "reference_velocity": float(sol.info[kernel.I_U_REF]),
            "evaluator": sol,
            "velocity": sol.velocity,
            "recipe": None,
        },
        _LEFT,
        _rest,
        inputs,
        sol,
        out,
        rtol,
        atol,
        check,
    )


_LEFT = frozenset(PENDABLE)
"""The fields of a numerical profile made on first read (:func:`_rest`)."""


def _rest(
    name: str | None,
    inputs: _Inputs,
    sol: NumericalSolution,
    out: FloatArray,
    rtol: float,
    atol: float,
    check: bool,
) -> dict[str, Any]:
    """What :func:`_profile` leaves to first read of ``name`` (None: all of it): the eight
    fields, the rows of ``out`` in the order of :class:`Fields`; or the diagnostics, their
    residuals and boundary errors computed when read
    (:class:`~cosserat.results.diagnostics.Deferred`)."""
    values: dict[str, Any] = {}
    if name != "diagnostics":
        # indexed, not iterated: iterating a 2-D array costs twice as much per row
        for i, field in enumerate(Fields._fields):
            values[field] = out[i]
    if name is not None and name != "diagnostics":
        return values
    eq = inputs.equations
    info = sol.info
    stats = _stats(info)
    if inputs.couette:
        stats["m_inner"] = sol.mu
        stats["shooting_iterations"] = int(info[kernel.I_ITERATIONS])
    res: Mapping[str, float]
    bc: Mapping[str, float]
    if check:
        res = DeferredResiduals(sol.formulation, sol, lambda: eq.output_grid(config.CHECK_POINTS))
        bc = Deferred(lambda: eq.boundary_errors(sol))
    else:
        res, bc = {}, {}
    values["diagnostics"] = assembled(
        Diagnostics,
        {
            "method": "numerical",
            "rtol": rtol,
            "atol": atol,
            "residuals": res,
            "bc_errors": bc,
            "message": COUETTE_MESSAGE if inputs.couette else PLANE_MESSAGE,
            "stats": stats,
        },
    )
    return values


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


# ----------------------------------------------------------------- predictions (likelihoods)
FIELDS = Fields._fields
"""The fields :func:`predict` can return (those of :class:`~cosserat.results.profile.Fields`)."""
PREDICT_FIELDS = ("u", "omega", "sigma_yx", "sigma_yy")
"""What :func:`predict` returns unless told: the measured fields the model predicts."""


@dataclass(frozen=True)
class Prediction:
    """Fields of one problem at given points (:func:`predict_many`), or why there are none.

    Attributes
    ----------
    status : str
        "ok", "no-solution" (the model has no real solution) or "error" (the solver could not
        finish); ``message`` says why.
    values : dict of str to ndarray, or None
        Each requested field at the points [-]; None unless ``status`` is "ok".
    message : str
    m_inner : float or None
        Couette flow: the inner-wall couple stress m(0), a good ``m_inner_guess`` for a nearby
        problem (the next step of a sampler); None in plane shear or without a solution.
    """

    status: str
    values: dict[str, FloatArray] | None
    message: str = ""
    m_inner: float | None = None


def _field_rows(fields: Sequence[str]) -> np.ndarray:
    if isinstance(fields, str):
        fields = (fields,)
    unknown = [name for name in fields if name not in FIELDS]
    if unknown or not fields:
        raise ParameterError(
            f"fields must name some of {', '.join(FIELDS)}; got {', '.join(map(repr, fields))}"
        )
    return np.array([FIELDS.index(name) for name in fields], dtype=np.int64)


def _points(xi: Any) -> FloatArray:
    x = np.ascontiguousarray(xi, dtype=float)
    if x.ndim != 1 or not np.all(np.isfinite(x)) or np.any((x < 0.0) | (x > 1.0)):
        raise ParameterError("xi must be a 1-D array of finite points in [0, 1] (any order)")
    return x


def _point_sets(xi: Any, n: int) -> list[FloatArray]:
    """One array of points per problem: from one array shared by all, or one per problem."""
    shared = isinstance(xi, np.ndarray) and xi.dtype != object and xi.ndim == 1
    if not shared and isinstance(xi, Sequence) and len(xi) > 0:
        shared = all(isinstance(v, int | float | np.number) for v in xi)
    if shared:
        return [_points(xi)] * n
    sets = [_points(x) for x in xi]
    if len(sets) != n:
        raise ParameterError(
            f"xi must be one array of points, or one per problem ({n}); got {len(sets)}"
        )
    return sets


def _predict(
    problems: Sequence[Problem],
    xi: Any,
    fields: Sequence[str],
    rtol: float,
    atol: float | None,
    m_inner_guesses: Sequence[float | None] | None,
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    rtol, atol = tolerances(rtol, atol)
    rows = _field_rows(fields)
    for pr in problems:
        if not (
            isinstance(pr, Problem)
            and pr.rheology.name == "cosserat"
            and pr.cell_name in ("plane", "couette")
        ):
            raise ParameterError(
                f"cannot predict {pr!r} here: give the Cosserat model on the plane or Couette "
                f"cell (other problems: solve(problem, xi=...))"
            )
    n = len(problems)
    point_sets = _point_sets(xi, n)
    guesses = [None] * n if m_inner_guesses is None else list(m_inner_guesses)
    if len(guesses) != n:
        raise ParameterError(f"m_inner_guesses must have one entry per problem ({n})")
    for g in guesses:
        if g is not None and not math.isfinite(float(g)):
            raise ParameterError(f"an m_inner guess must be finite or None; got {g!r}")
    params = np.stack([parameter_vector(pr, g) for pr, g in zip(problems, guesses, strict=True)])
    starts = np.zeros(n + 1, dtype=np.int64)
    starts[1:] = np.cumsum([x.size for x in point_sets])
    points = np.concatenate(point_sets) if n else np.zeros(0)
    status, info, out = kernel.predict_batch(
        params, points, starts, rows, rtol, atol, config.DEFAULT_F, config.MAX_STEPS
    )
    return status, info, out, starts, rows


def predict_many(
    problems: Sequence[Problem],
    xi: Any,
    fields: Sequence[str] = PREDICT_FIELDS,
    *,
    rtol: float = DEFAULT_RTOL,
    atol: float | None = None,
    m_inner_guesses: Sequence[float | None] | None = None,
) -> list[Prediction]:
    """The ``fields`` of many problems at points ``xi``, in one compiled call.

    What a likelihood needs and nothing else: no :class:`Profile`, no output grid, no
    residuals or boundary errors; the numbers are those of ``solve(problem).evaluate(xi)``
    (the same kernel, the same field evaluation). One call for all the problems of all the
    walkers of a sampler costs no Python per problem beyond building its parameter vector.

    Parameters
    ----------
    problems : sequence of Problem
        The Cosserat model on the plane or Couette cell.
    xi : array or sequence of arrays
        Points in [0, 1], any order: one array for every problem, or one per problem [-].
    fields : sequence of str
        Names among :data:`FIELDS` (default :data:`PREDICT_FIELDS`).
    rtol, atol : float
        As :func:`cosserat.solve`.
    m_inner_guesses : sequence of float or None, optional
        Couette flow: a guess of m(0) per problem (None: the leading-order value), e.g. the
        ``m_inner`` of the previous prediction of the same run; it saves passes.

    Returns
    -------
    list of Prediction
        One per problem, in order; a problem without a solution has its status and message
        (those :func:`cosserat.solve` would raise) and no values.

    Raises
    ------
    ParameterError
        A problem this kernel does not solve, unknown fields, points outside [0, 1].
    """
    if not problems:
        _field_rows(fields)
        return []
    status, info, out, starts, rows = _predict(problems, xi, fields, rtol, atol, m_inner_guesses)
    names = [FIELDS[r] for r in rows]
    result = []
    for i, pr in enumerate(problems):
        couette = pr.cell_name == "couette"
        if status[i] != kernel.OK:
            wall = _wall_result(pr, int(status[i]), info[i], config.DEFAULT_F)
            result.append(Prediction(wall.status, None, wall.message))
            continue
        a, b = starts[i], starts[i + 1]
        values = {name: out[k, a:b] for k, name in enumerate(names)}
        m_inner = float(info[i, kernel.I_MU]) if couette else None
        result.append(Prediction("ok", values, "", m_inner))
    return result


def predict(
    problem: Problem,
    xi: Any,
    fields: Sequence[str] = PREDICT_FIELDS,
    *,
    rtol: float = DEFAULT_RTOL,
    atol: float | None = None,
    m_inner_guess: float | None = None,
) -> dict[str, FloatArray]:
    """The ``fields`` of one problem at points ``xi`` (:func:`predict_many` for one problem).

    Returns a dict of arrays (one per field, in the order of ``xi``) and raises as
    :func:`cosserat.solve` does where there is no solution (``NoSolutionError``,
    ``ConvergenceError``).
    """
    x = _points(xi)
    status, info, out, _, rows = _predict([problem], x, fields, rtol, atol, [m_inner_guess])
    raise_for_status(problem, int(status[0]), info[0])
    return {FIELDS[r]: out[k] for k, r in enumerate(rows)}
