"""Rank the registered rheologies against one measured velocity profile.

Each model (a name of :data:`cosserat.routes.RHEOLOGIES`) is put on the measured cell, its free
parameters are fitted to the profile by bounded nonlinear least squares (SciPy
``least_squares``, trust-region reflective, on ``(u_model - u_data)/sigma``), and the models
are ranked by the Akaike and Bayesian information criteria.

Information criteria, k free parameters, n points (:func:`information_criteria`):

* with the points' uncertainties sigma given (taken as absolute, Gaussian): ``-2 ln L =
  chi^2`` up to a constant, so ``AIC = chi^2 + 2k`` and ``BIC = chi^2 + k ln n``;
* without them (sigma unknown, estimated by its maximum-likelihood value RSS/n):
  ``AIC = n ln(RSS/n) + 2k`` and ``BIC = n ln(RSS/n) + k ln n``.

The constant dropped is the same for every model fitted to the same data, so differences
between models are meaningful and the values themselves are not.

The free parameters (by default the rheology's ``default_free``) are searched over their
declared fit ranges, in the logarithm where the declared scale is "log"
(:mod:`cosserat.model.declare`): no range is written here.

Uncertainties come from the Jacobian at the optimum (forward differences stepping away from any
bound), propagated to the natural units of each parameter. Where a parameter is not
identifiable (at a bound of its range, or the Jacobian is singular along it) its uncertainty is
None and the reason is given, never NaN.
"""

from __future__ import annotations

import inspect
import itertools
import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from scipy.optimize import least_squares

from .. import config
from ..errors import (
    ConvergenceError,
    MethodNotAvailableError,
    NoSolutionError,
    ParameterError,
)
from ..model import Problem, make_problem
from ..model.constitutive import FloatArray
from ..model.rheologies import RHEOLOGIES
from ..results.profile import Profile
from ..routes import models_for, solve
from ..routes.registry import find as find_route
from .fitting import FREE_PARAMETERS as COSSERAT_PARAMETERS
from .fitting import Comparison, model_at, moving_wall, natural_value, with_values
from .measurements import MeasuredProfile

CELL_PARAMETERS = ("eps", "Ri", "B", "nu")
"""Parameters of the cell rather than of the material: d/H, R_i/H, rho_s g H/N, nu [-]."""

NO_SOLUTION_RESIDUAL = 1e3
"""Residual of every point where the model has no solution for trial parameters."""

_SOLVE_ERRORS = (NoSolutionError, ParameterError, ConvergenceError)


# --------------------------------------------------------------------------- the models
def rheology_and_cell(problem: Any) -> tuple[str, str]:
    """(model name, cell name) of a problem.

    Raises
    ------
    ParameterError
        Not a :class:`~cosserat.model.problem.Problem`.
    """
    if not isinstance(problem, Problem):
        raise ParameterError(
            f"{type(problem).__name__} is not a Problem(cell, rheology) of a registered rheology"
        )
    return problem.model, problem.cell_name


def parameter_names(problem: Any) -> list[str]:
    """Every numeric parameter name :func:`set_parameters` accepts for ``problem`` (its
    declared keys, :meth:`~cosserat.model.problem.Problem.declared`)."""
    return [k for k, p in problem.declared().items() if p.numeric]


def get_parameter(problem: Any, name: str) -> Any:
    """Value of parameter ``name`` of ``problem`` (its command-line key; I_w as it drives the
    flow, its default included).

    For the Cosserat model ``delta`` is the moving wall's friction angle [deg] (the fully rough
    wall as its angle) and ``K`` its slip coefficient.
    """
    if problem.model == "cosserat" and name in COSSERAT_PARAMETERS:
        return natural_value(problem, name)
    values = {**problem.values(), **problem.cell_values()}
    if name not in values:
        raise ParameterError(
            f"the {problem.model} rheology on the {problem.cell_name} cell has no parameter "
            f"{name!r}; it has {', '.join(parameter_names(problem))}"
        )
    return values[name]


def set_parameters(problem: Any, values: Mapping[str, Any]) -> Any:
    """``problem`` with parameters replaced by key (validated again): the problem's
    :meth:`~cosserat.model.problem.Problem.with_values`, and for the Cosserat model's
    ``delta``, ``K`` and material :func:`cosserat.analysis.fitting.with_values` (a wall made
    rougher than fully rough by a lower phi is clamped to it; both walls change together when
    the plane cell's walls are alike).

    Raises
    ------
    ParameterError
        A name the problem does not have, or a value out of its bounds.
    """
    rest = dict(values)
    if problem.model == "cosserat":
        wall = {k: float(rest.pop(k)) for k in list(rest) if k in COSSERAT_PARAMETERS}
        if wall:
            problem = with_values(problem, wall)
    if not rest:
        return problem
    return problem.with_values(rest)


model_velocity = model_at
"""u / u_wall of a profile at distances from the moving wall [d] (:func:`fitting.model_at`)."""


def model_solve(problem: Any, points: int = 3, **options: Any) -> Profile:
    """The model's profile, in closed form where its rheology has one for this problem, else
    by its numerical route at ``rtol`` = :data:`cosserat.config.RTOL` (unless given): the fit's
    finite-difference steps are far above that. A coarse output grid: the fit evaluates the
    dense solution at the data points."""
    model, cell = rheology_and_cell(problem)
    if find_route(model, cell, "closed-form") is not None and not options:
        try:
            return solve(problem, method="closed-form", check=False, points=points)
        except MethodNotAvailableError:
            pass
    route = find_route(model, cell, "numerical")
    if route is not None and "rtol" in inspect.signature(route).parameters:
        options = {"rtol": config.RTOL, **options}
    return solve(problem, method="numerical", check=False, points=points, **options)


def default_free(model: str, problem: Any) -> tuple[str, ...]:
    """The parameters fitted by default: the rheology's
    :attr:`~cosserat.model.rheologies.base.Rheology.default_free` that this problem has, or else
    every parameter of the rheology with a declared fit range."""
    names = tuple(n for n in RHEOLOGIES[model].default_free if n in parameter_names(problem))
    if names:
        return names
    own = RHEOLOGIES[model].declared(problem.cell_name)
    return tuple(k for k, p in own.items() if p.fittable and p.numeric)


# --------------------------------------------------------------------------- statistics
def information_criteria(
    residuals: FloatArray, k: int, absolute_sigma: bool
) -> tuple[float, float | None, float | None]:
    """(chi^2 or RSS, AIC, BIC) of weighted residuals for k free parameters.

    ``residuals`` are ``(model - data)/sigma`` (sigma = 1 without uncertainties). With
    ``absolute_sigma``: AIC = chi^2 + 2k, BIC = chi^2 + k ln n. Without: AIC = n ln(RSS/n) + 2k,
    BIC = n ln(RSS/n) + k ln n; None when RSS = 0 (a perfect fit has no finite likelihood
    with an estimated sigma).
    """
    r = np.asarray(residuals, dtype=float)
    n = r.size
    s = float(np.sum(r * r))
    if absolute_sigma:
        return s, s + 2.0 * k, s + k * math.log(n)
    if s == 0.0:
        return s, None, None
    base = n * math.log(s / n)
    return s, base + 2.0 * k, base + k * math.log(n)


@dataclass(frozen=True)
class Estimate:
    """A fitted parameter: its value and standard error, or why the error is not given."""

    value: float
    stderr: float | None
    reason: str | None = None

    def to_dict(self) -> dict[str, Any]:
        return {"value": self.value, "stderr": self.stderr, "reason": self.reason}

    def text(self) -> str:
        if self.stderr is None:
            return f"{self.value:.5g} (no error: {self.reason})"
        return f"{self.value:.5g} +- {self.stderr:.2g}"


@dataclass
class ModelFit:
    """One model fitted to the measured profile (``status`` "ok"), or why it could not be."""

    model: str
    cell: str
    status: str
    message: str = ""
    problem: Any = None
    profile: Profile | None = None
    parameters: dict[str, Estimate] = field(default_factory=dict)
    n: int = 0
    k: int = 0
    chi2: float | None = None
    reduced_chi2: float | None = None
    aic: float | None = None
    bic: float | None = None
    absolute_sigma: bool = False
    model_u: FloatArray | None = None
    residuals: FloatArray | None = None
    warnings: list[str] = field(default_factory=list)
    solves: int = 0

    @property
    def ok(self) -> bool:
        return self.status == "ok"

    def comparison(self, measured: MeasuredProfile) -> Comparison:
        """The fitted model beside ``measured``, as :func:`cosserat.analysis.fitting.compare`
        gives it (residuals data minus model; chi^2 only with absolute uncertainties)."""
        if self.profile is None or self.model_u is None or self.residuals is None:
            raise MethodNotAvailableError(f"{self.model} was not fitted: {self.message}")
        model = np.asarray(self.model_u, dtype=float)
        residuals = measured.u_over_uw - model
        chi2 = self.chi2 if self.absolute_sigma else None
        rms = float(np.sqrt(np.mean(residuals**2)))
        return Comparison(measured, self.profile, model, residuals, rms, chi2)

    def curve(self, distance_d: FloatArray) -> FloatArray:
        """The fitted model's u/u_wall at distances from the moving wall [d] (for plots)."""
        if self.profile is None:
            raise ParameterError(f"model {self.model!r} was not fitted: {self.message}")
        return model_velocity(self.profile, distance_d)

    def to_dict(self) -> dict[str, Any]:
        return {
            "model": self.model,
            "cell": self.cell,
            "status": self.status,
            "message": self.message,
            "n": self.n,
            "k": self.k,
            "chi2": self.chi2,
            "reduced_chi2": self.reduced_chi2,
            "aic": self.aic,
            "bic": self.bic,
            "absolute_sigma": self.absolute_sigma,
            "parameters": {k: v.to_dict() for k, v in self.parameters.items()},
            "problem": None if self.problem is None else self.problem.parameters(),
            "warnings": list(self.warnings),
            "solves": self.solves,
        }


def _bounds(name: str, problem: Any, start: float) -> tuple[tuple[float, float], bool]:
    """The search range of ``name`` and whether it is searched in its logarithm: the declared
    fit range and scale (delta's capped at the fully rough angle); a parameter without one
    searches between 1e-3 and 1e3 times its starting value, in the logarithm."""
    declared = problem.declared().get(name)
    if declared is not None and declared.fit_range is not None:
        lo, hi = declared.fit_range
        if name == "delta" and problem.model == "cosserat":
            hi = min(hi, problem.rheology.material.fully_rough_delta)
        return (lo, hi), declared.scale == "log"
    if start > 0.0:
        return (start * 1e-3, start * 1e3), True
    if start < 0.0:
        return (start * 1e3, start * 1e-3), False
    return (-1.0, 1.0), False


class _Coordinates:
    """Internal coordinates: the logarithm where the range's declared scale is "log"."""

    def __init__(
        self, names: Sequence[str], bounds: Sequence[tuple[float, float]], log: Sequence[bool]
    ):
        self.names = list(names)
        self.log = np.array([bool(x) for x in log], dtype=bool)
        lo = np.array([b[0] for b in bounds], dtype=float)
        hi = np.array([b[1] for b in bounds], dtype=float)
        self.lo = np.where(self.log, np.log(np.where(self.log, lo, 1.0)), lo)
        self.hi = np.where(self.log, np.log(np.where(self.log, hi, 1.0)), hi)

    def natural(self, theta: FloatArray) -> FloatArray:
        return np.where(self.log, np.exp(theta), theta)

    def internal(self, values: FloatArray) -> FloatArray:
        v = np.asarray(values, dtype=float)
        return np.clip(np.where(self.log, np.log(np.where(self.log, v, 1.0)), v), self.lo, self.hi)

    def dnatural(self, theta: FloatArray) -> FloatArray:
        """d natural / d internal for each coordinate."""
        return np.where(self.log, np.exp(theta), 1.0)


class _Objective:
    def __init__(self, measured: MeasuredProfile, base: Any, coords: _Coordinates, options: dict):
        self.measured, self.base, self.coords, self.options = measured, base, coords, options
        self.sigma = measured.u_err if measured.u_err is not None else np.ones(measured.n)
        self.solves = 0

    def problem(self, theta: FloatArray) -> Any:
        values = self.coords.natural(theta)
        return set_parameters(self.base, dict(zip(self.coords.names, values, strict=True)))

    def __call__(self, theta: FloatArray) -> FloatArray:
        self.solves += 1
        try:
            prof = model_solve(self.problem(theta), **self.options)
            u = model_velocity(prof, self.measured.distance_d)
        except _SOLVE_ERRORS:
            return np.full(self.measured.n, NO_SOLUTION_RESIDUAL)
        return (u - self.measured.u_over_uw) / self.sigma


def _start(obj: _Objective, theta0: FloatArray, grid: int) -> FloatArray:
    """The best of the model's defaults and a coarse grid over the ranges (a fit of a
    nonlinear model from one start can stop in a local minimum)."""
    best, cost = theta0, float(np.sum(obj(theta0) ** 2))
    c = obj.coords
    axes = [np.linspace(lo, hi, grid + 2)[1:-1] for lo, hi in zip(c.lo, c.hi, strict=True)]
    for point in itertools.product(*axes):
        th = np.asarray(point, dtype=float)
        value = float(np.sum(obj(th) ** 2))
        if value < cost:
            best, cost = th, value
    return best


def _jacobian(obj: _Objective, theta: FloatArray, f0: FloatArray) -> FloatArray:
    """Forward differences at the optimum, stepping away from any bound."""
    c = obj.coords
    J = np.empty((f0.size, theta.size))
    for j in range(theta.size):
        h = config.FIT_DIFF_STEP * (c.hi[j] - c.lo[j])
        if theta[j] + h > c.hi[j]:
            h = -h
        th = theta.copy()
        th[j] += h
        J[:, j] = (obj(th) - f0) / h
    return J


def fit_model(
    measured: MeasuredProfile,
    problem: Any,
    free: Sequence[str] | None = None,
    *,
    grid: int = 3,
    **options: Any,
) -> ModelFit:
    """Fit the ``free`` parameters of ``problem`` (any registered rheology) to ``measured``.

    Parameters
    ----------
    measured : MeasuredProfile
        u over the moving wall's velocity against the distance from it [d].
    problem : problem of a registered rheology
        The cell and the starting values; parameters not in ``free`` stay fixed.
    free : sequence of str, optional
        Parameter names (:func:`parameter_names`); default :func:`default_free`. Empty: the
        model is compared as it is (k = 0).
    grid : int
        Points per parameter of the coarse start grid (0: start from the defaults only).
    **options
        Passed to the model's numerical route (e.g. ``rtol``).

    Returns
    -------
    ModelFit
        ``status`` "ok"; a model with no solution anywhere on the start grid raises.

    Raises
    ------
    ParameterError
        Unknown parameter name, or too few points for the free parameters.
    NoSolutionError
        The model has no solution at the best start found.
    """
    model, cell = rheology_and_cell(problem)
    names = list(dict.fromkeys(default_free(model, problem) if free is None else free))
    known = parameter_names(problem)
    bad = [n for n in names if n not in known]
    if bad:
        raise ParameterError(
            f"model {model!r} has no parameter(s) {', '.join(bad)}; it has {', '.join(known)}"
        )
    if measured.n <= len(names):
        raise ParameterError(f"{measured.n} points cannot determine {len(names)} parameters")
    measured.xi(problem.eps, moving_wall(problem)[0])  # the points lie in the gap
    start = np.array([float(get_parameter(problem, n)) for n in names], dtype=float)
    ranges = [_bounds(n, problem, s) for n, s in zip(names, start, strict=True)]
    coords = _Coordinates(names, [r for r, _ in ranges], [log for _, log in ranges])
    obj = _Objective(measured, problem, coords, dict(options))
    absolute = measured.u_err is not None
    warnings: list[str] = []
    if names:
        theta0 = _start(obj, coords.internal(start), grid) if grid else coords.internal(start)
        res = least_squares(
            obj,
            theta0,
            bounds=(coords.lo, coords.hi),
            method="trf",
            x_scale="jac",
            diff_step=config.FIT_DIFF_STEP,
            xtol=config.FIT_XTOL,
            ftol=config.FIT_FTOL,
            gtol=config.FIT_GTOL,
            max_nfev=config.FIT_MAX_NFEV,
        )
        theta = res.x
        if not res.success:
            warnings.append(f"the least-squares search stopped: {res.message}")
    else:
        theta = np.zeros(0)
    best = obj.problem(theta)
    profile = model_solve(best, points=201, **options)
    u = model_velocity(profile, measured.distance_d)
    sigma = obj.sigma
    resid = (u - measured.u_over_uw) / sigma
    if np.all(np.abs(resid) >= NO_SOLUTION_RESIDUAL * 0.999):
        raise NoSolutionError(f"model {model!r} has no solution near the data")
    n, k = measured.n, len(names)
    chi2, aic, bic = information_criteria(resid, k, absolute)
    dof = n - k
    params = _estimates(obj, theta, resid, chi2 / dof, absolute, warnings)
    if aic is None:
        warnings.append("the residuals are exactly zero: AIC and BIC are undefined")
    if absolute and chi2 / dof > 3.0:
        warnings.append(
            f"poor fit: reduced chi-square {chi2 / dof:.3g} >> 1: the model does not describe "
            "these data within their uncertainties"
        )
    return ModelFit(
        model=model,
        cell=cell,
        status="ok",
        problem=best,
        profile=profile,
        parameters=params,
        n=n,
        k=k,
        chi2=chi2,
        reduced_chi2=chi2 / dof,
        aic=aic,
        bic=bic,
        absolute_sigma=absolute,
        model_u=u,
        residuals=u - measured.u_over_uw,
        warnings=warnings,
        solves=obj.solves + 1,
    )


def _estimates(
    obj: _Objective,
    theta: FloatArray,
    resid: FloatArray,
    reduced: float,
    absolute: bool,
    warnings: list[str],
) -> dict[str, Estimate]:
    """Values and standard errors in natural units (None with the reason where not defined)."""
    c = obj.coords
    values = c.natural(theta)
    if not c.names:
        return {}
    J = _jacobian(obj, theta, resid)
    scale = 1.0 if absolute else reduced
    reasons: dict[int, str] = {}
    span = c.hi - c.lo
    for j in range(theta.size):
        if theta[j] <= c.lo[j] + 1e-6 * span[j] or theta[j] >= c.hi[j] - 1e-6 * span[j]:
            lo, hi = c.natural(c.lo)[j], c.natural(c.hi)[j]
            reasons[j] = f"at a bound of its range [{lo:.4g}, {hi:.4g}]"
    _, sv, vt = np.linalg.svd(J, full_matrices=False)
    stderr = np.full(theta.size, np.nan)
    null = sv <= 1e-8 * sv[0] if sv[0] > 0.0 else np.ones(sv.size, bool)
    if not np.any(null):
        cov = (vt.T / sv**2) @ vt * scale
        d = c.dnatural(theta)
        stderr = np.sqrt(np.abs(np.diag(cov))) * d
    else:
        weak = np.any(np.abs(vt[null]) > 0.3, axis=0)
        for j in np.flatnonzero(weak):
            reasons.setdefault(
                int(j),
                "not identifiable: the profile does not change along it (singular Jacobian)",
            )
        warnings.append(
            "the profile does not change along some combination of the free parameters (a "
            "singular Jacobian): fix one of " + ", ".join(c.names[j] for j in np.flatnonzero(weak))
        )
    out = {}
    for j, name in enumerate(c.names):
        e = float(stderr[j])
        if j in reasons or not math.isfinite(e):
            out[name] = Estimate(
                float(values[j]),
                None,
                reasons.get(
                    j,
                    "not identifiable: its standard error is not finite (the free parameters "
                    "are degenerate together)",
                ),
            )
        else:
            out[name] = Estimate(float(values[j]), e)
    return out


# --------------------------------------------------------------------------- ranking
@dataclass
class Ranking:
    """Every model's fit to one profile, best (lowest AIC) first."""

    measured: MeasuredProfile
    cell: str
    fits: list[ModelFit]

    @property
    def ranked(self) -> list[ModelFit]:
        """The fitted models by AIC (then BIC), failures last."""
        ok = [f for f in self.fits if f.ok and f.aic is not None]
        rest = [f for f in self.fits if f not in ok]
        return sorted(ok, key=lambda f: (f.aic, f.bic)) + rest

    @property
    def best(self) -> ModelFit | None:
        r = self.ranked
        return r[0] if r and r[0].ok and r[0].aic is not None else None

    def by_bic(self) -> list[ModelFit]:
        ok = [f for f in self.fits if f.ok and f.bic is not None]
        return sorted(ok, key=lambda f: f.bic)  # type: ignore[arg-type,return-value]

    def weights(self) -> dict[str, float]:
        """Akaike weights exp(-dAIC/2), normalised over the fitted models."""
        ok = [f for f in self.fits if f.ok and f.aic is not None]
        if not ok:
            return {}
        a0 = min(f.aic for f in ok)  # type: ignore[type-var]
        w = {f.model: math.exp(-0.5 * (f.aic - a0)) for f in ok}  # type: ignore[operator]
        total = sum(w.values())
        return {k: v / total for k, v in w.items()}

    def to_dict(self) -> dict[str, Any]:
        best = self.best
        return {
            "cell": self.cell,
            "n_points": self.measured.n,
            "uncertainties": self.measured.u_err is not None,
            "best": None if best is None else best.model,
            "akaike_weights": self.weights(),
            "fits": [f.to_dict() for f in self.ranked],
        }

    def to_text(self) -> str:
        w = self.weights()
        a0 = min((f.aic for f in self.fits if f.ok and f.aic is not None), default=0.0)
        what = "chi2" if self.measured.u_err is not None else "RSS"
        lines = [
            f"{self.measured.n} points on the {self.cell} cell; "
            + (
                "uncertainties given: chi2 = sum((model - data)/u_err)^2, AIC = chi2 + 2k, "
                "BIC = chi2 + k ln n"
                if self.measured.u_err is not None
                else "no uncertainties: RSS = sum((model - data)^2), AIC = n ln(RSS/n) + 2k, "
                "BIC = n ln(RSS/n) + k ln n"
            ),
            f"{'rank':<5}{'model':<10}{'k':>3}{what:>12}{'red.' + what:>11}{'AIC':>11}"
            f"{'dAIC':>9}{'BIC':>11}{'weight':>8}",
        ]
        for i, f in enumerate(self.ranked, start=1):
            if not f.ok:
                lines.append(f"{'-':<5}{f.model:<10}not fitted: {f.message}")
                continue
            lines.append(
                f"{i:<5}{f.model:<10}{f.k:>3}{f.chi2:>12.5g}{f.reduced_chi2:>11.4g}"
                + (
                    f"{f.aic:>11.5g}{f.aic - a0:>9.3g}{f.bic:>11.5g}{w.get(f.model, 0.0):>8.3f}"
                    if f.aic is not None
                    else f"{'undefined':>11}"
                )
            )
        for f in self.ranked:
            if not f.ok:
                continue
            lines.append(
                f"  {f.model}: " + "; ".join(f"{k} = {v.text()}" for k, v in f.parameters.items())
                if f.parameters
                else f"  {f.model}: no free parameter"
            )
            lines += [f"    note: {w_}" for w_ in f.warnings]
        return "\n".join(lines) + "\n"

    def plot(self, title: str = ""):  # type: ignore[no-untyped-def]
        """The data with error bars and every fitted model (linear and log velocity axes)."""
        from ..viz.plotting import new_figure, style

        meas = self.measured
        fitted = [f for f in self.ranked if f.ok]
        d_max = float(meas.distance_d.max()) * 1.05 + 1e-9
        eps = min(f.problem.eps for f in fitted) if fitted else 1.0
        d = np.linspace(0.0, min(d_max, 1.0 / eps), 300)
        fig, axes = new_figure(1, 2, width=6.6, height=3.0)
        with style():
            for j, ax in enumerate(axes[0]):
                ax.errorbar(
                    meas.distance_d,
                    meas.u_over_uw,
                    yerr=meas.u_err,
                    fmt="o",
                    color="k",
                    markerfacecolor="none",
                    capsize=2,
                    label=meas.label,
                )
                for i, f in enumerate(fitted):
                    ax.plot(
                        d,
                        f.curve(d),
                        linestyle=["-", "--", "-.", ":"][i % 4],
                        label=f"{f.model} (AIC {f.aic:.4g})" if f.aic is not None else f.model,
                    )
                ax.set_xlabel(r"distance from the moving wall [$d$]")
                ax.set_ylabel(r"$u/u_w$")
                if j == 1:
                    pos = meas.u_over_uw[meas.u_over_uw > 0]
                    ax.set_yscale("log")
                    ax.set_ylim(max(float(pos.min()) / 3 if pos.size else 1e-4, 1e-8), 1.5)
                else:
                    ax.legend()
            if title:
                fig.suptitle(title, fontsize=8)
            fig.tight_layout()
        return fig


def measured_cell(measured: MeasuredProfile, **given: Any) -> dict[str, Any]:
    """The cell parameters a measured profile's header states (``geometry``, ``eps``, ``Ri``,
    ``B``, ``nu``), with ``given`` values (not None) taking precedence: what
    :func:`rank_models` takes as ``cell_parameters``.

    Raises
    ------
    ParameterError
        No geometry or no eps in the header or ``given``.
    """
    names = {"geometry": "geometry", "eps": "eps", "ri": "Ri", "b": "B", "nu": "nu"}
    out = {names[k]: v for k, v in measured.meta.items() if k in names}
    out.update({k: v for k, v in given.items() if v is not None})
    for key in ("geometry", "eps"):
        if out.get(key) is None:
            raise ParameterError(
                f"the cell's {key} is neither in the profile's header ('# {key}: ...') nor given"
            )
    return out


def rank_models(
    measured: MeasuredProfile,
    cell_parameters: Mapping[str, Any],
    models: Sequence[str] | None = None,
    free: Mapping[str, Sequence[str]] | None = None,
    *,
    cell: str | None = None,
    model_parameters: Mapping[str, Mapping[str, Any]] | None = None,
    grid: int = 3,
) -> Ranking:
    """Fit every model to ``measured`` and rank them by AIC and BIC.

    Parameters
    ----------
    measured : MeasuredProfile
        Distance from the moving wall [d], u over the wall's velocity [-], optional errors.
    cell_parameters : mapping
        ``geometry`` (plane | couette; or give ``cell``), ``eps`` = d/H, and ``Ri`` (Couette),
        ``B`` and ``nu`` (plane) as they apply [-].
    models : sequence of str, optional
        Registered rheologies; default every one defined on the cell.
    free : mapping of model name to parameter names, optional
        Parameters to fit for each model (default :func:`default_free`).
    model_parameters : mapping of model name to mapping, optional
        Fixed values or starting values of model parameters (e.g. ``{"cosserat":
        {"delta": "fully-rough"}}``).
    grid : int
        Points per free parameter of the coarse start grid.

    Returns
    -------
    Ranking
        A model that cannot be fitted (no such cell, no solution) is listed with the reason.
    """
    cell = cell or str(cell_parameters.get("geometry") or measured.meta.get("geometry") or "")
    if not cell:
        raise ParameterError("say which cell: geometry = plane | couette in the cell parameters")
    params = {k: v for k, v in cell_parameters.items() if k != "geometry"}
    names = models_for(cell) if models is None else list(models)
    for m in names:
        if m not in RHEOLOGIES:
            raise ParameterError(f"unknown model {m!r}: registered are {', '.join(RHEOLOGIES)}")
    fits = []
    for m in names:
        try:
            start = {**params, **dict((model_parameters or {}).get(m, {}))}
            problem = make_problem(m, cell, start)
        except (MethodNotAvailableError, ParameterError) as exc:
            # the model is not defined on this cell, or needs what the cell does not give
            fits.append(ModelFit(model=m, cell=cell, status="failed", message=str(exc)))
            continue
        try:
            fits.append(
                fit_model(measured, problem, None if free is None else free.get(m), grid=grid)
            )
        except (MethodNotAvailableError, NoSolutionError, ConvergenceError) as exc:
            fits.append(ModelFit(model=m, cell=cell, status="failed", message=str(exc)))
    return Ranking(measured, cell, fits)


__all__ = [
    "Estimate",
    "ModelFit",
    "Ranking",
    "default_free",
    "fit_model",
    "get_parameter",
    "information_criteria",
    "measured_cell",
    "model_velocity",
    "moving_wall",
    "parameter_names",
    "rank_models",
    "set_parameters",
]
