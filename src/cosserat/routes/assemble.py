"""Turn a route's dense evaluator into a checked :class:`~cosserat.profile.Profile`."""

from __future__ import annotations

import weakref
from collections.abc import Callable, Mapping
from typing import Any

import numpy as np

from .. import config
from ..errors import ConvergenceError, MethodNotAvailableError, ParameterError
from ..model import Problem
from ..model.constitutive import FloatArray, check_radicand, radicand
from ..model.formulation import Formulation
from ..model.rheologies.cosserat import cosserat_equations
from ..results.diagnostics import Deferred, DeferredResiduals
from ..results.profile import Diagnostics, Evaluator, Fields, Profile, assembled


def given_grid(xi: FloatArray) -> FloatArray:
    """A caller's output grid ``xi``, checked: 1-D, strictly increasing (no NaN), in [0, 1] [-].

    Raises
    ------
    ParameterError
        Otherwise, saying which.
    """
    grid = np.asarray(xi, dtype=float)
    # one comparison of neighbours (np.diff made a third array: 3x the cost at 2,001 points);
    # a NaN compares false, so it is refused here too
    if grid.ndim != 1 or grid.size < 2 or not (grid[1:] > grid[:-1]).all():
        raise ParameterError("xi must be a strictly increasing 1-D array of at least two points")
    if grid[0] < 0.0 or grid[-1] > 1.0:
        raise ParameterError(f"xi must lie in [0, 1]; got [{grid[0]:g}, {grid[-1]:g}]")
    return grid


def profile_grid(eq: Any, points: int | None, xi: FloatArray | None) -> FloatArray:
    """The output grid of a profile: ``xi`` checked (:func:`given_grid`), or about ``points``
    points resolving the layers (``eq.output_grid``), made once per problem [-].

    The layered grid costs more than a plane solve's kernel; a problem solved again (a
    benchmark, a sweep over tolerances) reuses it. The caller gets its own copy.
    """
    if xi is not None:
        return given_grid(xi)
    n = points or config.OUTPUT_POINTS
    grids = _GRIDS.get(eq)
    if grids is None:
        grids = _GRIDS[eq] = {}
    grid = grids.get(n)
    if grid is None:
        grid = grids[n] = eq.output_grid(n)
    return grid.copy()


_GRIDS: weakref.WeakKeyDictionary[Any, dict[int, FloatArray]] = weakref.WeakKeyDictionary()
"""Output grids per problem (its equations helper) and size."""


def check_fields(problem: Problem, method: str, grid: FloatArray, f: Fields) -> None:
    """Refuse fields a profile must not carry: a stress from a negative radicand (beyond
    round-off) or a non-finite value.

    Raises
    ------
    NoSolutionError
        The couple stress exceeds its yield bound somewhere (saying where).
    ConvergenceError, MethodNotAvailableError
        A field is not finite (the asymptotic route: its terms overflow).
    """
    material = cosserat_equations(problem).material
    _, f_m = f.spin()
    check_radicand(radicand(f.sigma_yx, f.sigma_yy, f_m, material), f.sigma_yy, f_m, material, grid)
    for name, values in f._asdict().items():
        if not np.isfinite(values).all():
            if method == "asymptotic":
                raise MethodNotAvailableError(
                    f"the leading-order expansion gives non-finite {name} for "
                    f"{problem.describe()} (its terms leave the range of doubles): use "
                    f"method='numerical'"
                )
            raise ConvergenceError(
                f"the {method} solution produced non-finite {name} for {problem.describe()}"
            )


def make_profile(
    problem: Problem,
    form: Formulation | Callable[[], Formulation],
    evaluate: Evaluator,
    *,
    method: str,
    points: int | None,
    xi: FloatArray | None = None,
    reference_velocity: float,
    rtol: float | None = None,
    atol: float | None = None,
    message: str = "",
    stats: Mapping[str, Any] | None = None,
    check: bool = True,
    velocity: Callable[[FloatArray], FloatArray] | None = None,
) -> Profile:
    """Evaluate on the output grid, verify, and package.

    The returned fields are always checked (:func:`check_fields`). ``check`` adds the
    boundary errors and the ODE residuals on a layer-resolving check grid, both computed when
    first read (:class:`~cosserat.results.diagnostics.Deferred`); sweeps that need only wall
    quantities may skip both. ``form`` may be a callable that makes the formulation when the
    residuals are read. The numerical route of the Cosserat model makes its profiles with
    less Python (:func:`cosserat.routes.numerical.solve_plane`), to the same effect.
    """
    eq = cosserat_equations(problem)
    grid = profile_grid(eq, points, xi)
    f = evaluate(grid)
    check_fields(problem, method, grid, f)
    res: Mapping[str, float]
    bc: Mapping[str, float]
    if check:
        # both computed when first read: the residuals (DeferredResiduals), then the
        # boundary conditions on the evaluator
        res = DeferredResiduals(form, evaluate, lambda: eq.output_grid(config.CHECK_POINTS))
        bc = Deferred(lambda: eq.boundary_errors(evaluate))
    else:
        res, bc = {}, {}
    # every field named: assembled() skips the frozen dataclasses' __init__ (3-5 us)
    diag = assembled(
        Diagnostics,
        {
            "method": method,
            "rtol": rtol,
            "atol": atol,
            "residuals": res,
            "bc_errors": bc,
            "message": message,
            "stats": dict(stats or {}),
        },
    )
    return assembled(
        Profile,
        {
            "problem": problem,
            "xi": grid,
            "u": f.u,
            "omega": f.omega,
            "m": f.m,
            "sigma_xy": f.sigma_xy,
            "sigma_yx": f.sigma_yx,
            "sigma_yy": f.sigma_yy,
            "du_dxi": f.du_dxi,
            "kappa": f.kappa,
            "slip_wall": float(problem.slip_wall),
            "reference_velocity": float(reference_velocity),
            "diagnostics": diag,
            "evaluator": evaluate,
            "velocity": velocity,
            "recipe": None,
        },
    )


def fields_from_state(
    form: Formulation, xi: FloatArray, m: FloatArray, u: FloatArray, w: FloatArray
) -> Fields:
    """Fields from (m, u, w) using the constitutive law for the stresses and du/dxi.

    ``w = omega + kappa u``; the flow rule gives ``du/dxi = -w F1 + kappa u``.
    """
    st = form.stresses(xi, m)
    F1, _ = form.flow_ratios(xi, m)
    kappa = form.curvature(xi)
    return Fields(
        u=u,
        omega=w - kappa * u,
        m=np.asarray(m, dtype=float),
        sigma_xy=st.sigma_xy,
        sigma_yx=st.sigma_yx,
        sigma_yy=st.sigma_c,
        du_dxi=-w * F1 + kappa * u,
        kappa=kappa,
    )
