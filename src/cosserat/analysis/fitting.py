"""Compare the model with a measured velocity profile, and fit its unknown parameters.

The fit is a bounded nonlinear least-squares problem (SciPy ``least_squares``, trust-region
reflective) on the residuals ``(u_model - u_data)/sigma``, sigma the point's uncertainty (or 1).
Standard errors and correlations come from ``least_squares``' Jacobian J at the optimum (the
covariance is the inverse of the Fisher matrix J^T J); with uncertainties given they are taken as
absolute, otherwise the covariance is scaled by the residual variance. Parameters the data cannot
determine are named, with the reason, in ``FitResult.warnings``, and their standard errors are
None: a flat direction of J^T J (an eigenvalue below :data:`FLAT_RATIO` of the largest, or one
along which the whole allowed range of the parameters changes the fit by less than one residual
variance) names the parameters of its eigenvector, and a correlation above
:data:`CORRELATION_LIMIT` names the pair and its value. Because
the velocity depends strongly and non-linearly on delta near tan(delta) = sin(phi), delta also
gets a profile-likelihood interval (the range where the refitted chi-square rises by less than
one residual variance), which is one-sided when it reaches the fully rough bound.

Parameters are fitted in bounded internal coordinates: ``t = tan(delta)/sin(phi)`` in
(tan 1 deg / sin phi, 1] for delta (so the fully rough wall t = 1 is a bound, whatever phi is),
and K, L, phi, A directly. The ranges are the declared fit ranges of the Cosserat model's
parameters (:meth:`cosserat.model.rheologies.cosserat.Cosserat.declared`), delta's capped at
the fully rough angle.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np
from scipy.optimize import brentq, least_squares

from .. import config
from ..errors import MethodNotAvailableError, NoSolutionError, ParameterError
from ..model import Cosserat, Problem
from ..model.constitutive import FloatArray
from ..model.parameters import FULLY_ROUGH, Wall
from ..results.profile import Profile
from ..routes import solve
from .measurements import MeasuredProfile

FREE_PARAMETERS = ("delta", "K", "L", "phi", "A")
"""The Cosserat model's parameters :func:`fit` can free."""
NO_SOLUTION_RESIDUAL = 1e3
CORRELATION_LIMIT = 0.95
"""|r| above which two fitted parameters are reported as strongly correlated."""
FLAT_RATIO = 1e-8
"""Eigenvalue of J^T J, relative to the largest, below which its direction is flat: the level of
the finite-difference error of the Jacobian, squared (relative step ~1e-4)."""
FLAT_COMPONENT = 0.05
"""Parameters whose share of a flat eigenvector is at least this get no standard error."""


def fit_range(name: str) -> tuple[float, float]:
    """The declared fit range of the Cosserat parameter ``name`` [its unit]."""
    rng = Cosserat.declared()[name].fit_range
    assert rng is not None
    return rng


def moving_wall(problem: Any) -> tuple[float, float]:
    """(xi, u) of the wall that drives the flow, read from the cell's ``wall_velocity``.

    (1, 1) for plane shear (the upper plate), (0, -1) for Couette flow (the inner cylinder),
    whatever the rheology.

    Raises
    ------
    MethodNotAvailableError
        No wall moves (a gravity-driven cell): a velocity over the wall speed is undefined.
    """
    for xi in (1.0, 0.0):
        u = float(problem.wall_velocity(xi))
        if u != 0.0:
            return xi, u
    name = getattr(problem, "cell_name", type(problem).__name__)
    raise MethodNotAvailableError(
        f"the {name} cell: no wall moves, so a profile over the wall speed cannot be "
        "compared with it (the gravity-driven cell needs its own velocity scale)"
    )


def model_profile(problem: Problem, method: str = "numerical", **options: Any) -> Profile:
    return solve(problem, method=method, check=False, points=3, **options)


def model_at(profile: Profile, distance_d: FloatArray) -> FloatArray:
    """u / u_wall of ``profile`` at distances from the moving wall in grain diameters [-]."""
    xw, uw = moving_wall(profile.problem)
    d = np.asarray(distance_d, dtype=float) * profile.problem.eps
    xi = d if xw == 0.0 else 1.0 - d
    return profile.velocity_at(np.clip(xi, 0.0, 1.0)) / uw


@dataclass(frozen=True)
class Comparison:
    """The model beside a measured profile."""

    measured: MeasuredProfile
    profile: Profile
    model: FloatArray
    residuals: FloatArray
    rms: float
    chi2: float | None

    def model_curve(self, distance_d: FloatArray) -> FloatArray:
        """The model's u / u_wall at distances from the moving wall [d_p] (for plots)."""
        return model_at(self.profile, distance_d)

    def to_dict(self) -> dict[str, Any]:
        return {
            "problem": self.profile.problem.parameters(),
            "distance_d": self.measured.distance_d.tolist(),
            "u_over_uw": self.measured.u_over_uw.tolist(),
            "model": self.model.tolist(),
            "residuals": self.residuals.tolist(),
            "rms": self.rms,
            "chi2": self.chi2,
            "n_points": self.measured.n,
        }


def compare(
    problem: Problem, measured: MeasuredProfile, method: str = "numerical", **options: Any
) -> Comparison:
    """Model minus data at the measured points; RMS and (with uncertainties) chi-square."""
    measured.xi(problem.eps, moving_wall(problem)[0])  # checks the points lie in the gap
    prof = model_profile(problem, method, **options)
    model = model_at(prof, measured.distance_d)
    res = measured.u_over_uw - model
    chi2 = None if measured.u_err is None else float(np.sum((res / measured.u_err) ** 2))
    return Comparison(measured, prof, model, res, float(np.sqrt(np.mean(res**2))), chi2)


# --------------------------------------------------------------------------- parameters
def _moving(problem: Problem) -> Wall:
    return problem.rheology.wall  # type: ignore[attr-defined, no-any-return]


def natural_value(problem: Problem, name: str) -> float:
    """Current value of a fittable parameter of the Cosserat model (delta in degrees, fully
    rough as its angle)."""
    mat = problem.rheology.material  # type: ignore[attr-defined]
    if name == "delta":
        wall = _moving(problem)
        return mat.fully_rough_delta if wall.is_fully_rough else float(wall.delta)
    if name == "K":
        return _moving(problem).K
    return float(getattr(mat, name))


def with_values(problem: Problem, values: dict[str, float]) -> Problem:
    """``problem`` (of the Cosserat model) with the moving wall's delta, K and the material's
    L, phi, A replaced (:meth:`~cosserat.model.problem.Problem.with_values`).

    delta = "fully-rough" when tan(delta) reaches sin(phi), and a wall left rougher than fully
    rough by a lower phi is clamped to it. Between identical plane walls both walls change
    together (a plane cell's lower wall follows the moving one unless it was given).
    """
    law: Cosserat = problem.rheology  # type: ignore[assignment]
    mat = law.material
    material = replace(
        mat, phi=values.get("phi", mat.phi), L=values.get("L", mat.L), A=values.get("A", mat.A)
    )
    old = law.wall
    delta: float | str = old.delta
    if "delta" in values:
        tan_d = math.tan(math.radians(values["delta"]))
        rough = tan_d >= material.sin_phi * (1.0 - config.FULLY_ROUGH_RTOL)
        delta = FULLY_ROUGH if rough else values["delta"]
    elif not old.is_fully_rough and math.tan(math.radians(float(old.delta))) > material.sin_phi:
        delta = FULLY_ROUGH  # phi changed below the wall's friction: clamp
    new = {"phi": material.phi, "L": material.L, "A": material.A, "delta": delta}
    new["K"] = values.get("K", old.K)
    if law.lower is not None and law.lower == law.wall:
        new["delta_lower"], new["K_lower"] = delta, new["K"]
    return problem.with_values(new)


@dataclass
class _Coordinates:
    """Map between the free natural parameters and bounded internal coordinates."""

    names: list[str]
    base: Problem

    def phi_of(self, theta: FloatArray) -> float:
        return (
            float(theta[self.names.index("phi")])
            if "phi" in self.names
            else (self.base.rheology.material.phi)  # type: ignore[attr-defined]
        )

    def to_natural(self, theta: FloatArray) -> dict[str, float]:
        out = {}
        phi = self.phi_of(theta)
        for name, value in zip(self.names, theta, strict=True):
            if name == "delta":
                out[name] = math.degrees(math.atan(value * math.sin(math.radians(phi))))
            else:
                out[name] = float(value)
        return out

    def to_internal(self, natural: dict[str, float]) -> FloatArray:
        phi = natural.get("phi", self.base.rheology.material.phi)  # type: ignore[attr-defined]
        out = []
        for name in self.names:
            if name == "delta":
                t = math.tan(math.radians(natural[name])) / math.sin(math.radians(phi))
                out.append(min(t, 1.0))
            else:
                out.append(natural[name])
        return np.asarray(out, dtype=float)

    def natural_ranges(self, natural: dict[str, float]) -> FloatArray:
        """The allowed range of each free parameter in natural units [deg for angles]."""
        phi = natural.get("phi", self.base.rheology.material.phi)  # type: ignore[attr-defined]
        rough = math.degrees(math.atan(math.sin(math.radians(phi))))
        return np.asarray(
            [
                rough - fit_range("delta")[0] if n == "delta" else fit_range(n)[1] - fit_range(n)[0]
                for n in self.names
            ]
        )

    def bounds(self) -> tuple[FloatArray, FloatArray]:
        lo, hi = [], []
        for name in self.names:
            lowest = math.tan(math.radians(fit_range("delta")[0]))
            b = (max(1e-6, lowest), 1.0) if name == "delta" else fit_range(name)
            lo.append(b[0])
            hi.append(b[1])
        return np.asarray(lo), np.asarray(hi)


# --------------------------------------------------------------------------- fit
@dataclass(frozen=True)
class FitParameter:
    """A fitted value [its unit: deg for angles], its standard error (None when the data cannot
    determine it, with the reason) and an optional profile-likelihood interval."""

    value: float
    stderr: float | None
    interval: tuple[float, float] | None = None
    reason: str | None = None

    def to_dict(self) -> dict[str, Any]:
        return {
            "value": self.value,
            "stderr": self.stderr,
            "interval": None if self.interval is None else list(self.interval),
            "reason": self.reason,
        }


@dataclass
class FitResult:
    """Best-fit parameters with uncertainties (angles in degrees).

    ``covariance`` and ``correlation`` hold NaN where a parameter is not identifiable (its
    ``stderr`` is None); :meth:`FitResult.to_dict` writes None there.
    """

    parameters: dict[str, FitParameter]
    problem: Problem
    comparison: Comparison
    chi2: float
    reduced_chi2: float
    n_points: int
    n_solves: int
    covariance: FloatArray
    correlation: FloatArray
    warnings: list[str] = field(default_factory=list)
    absolute_sigma: bool = False

    @property
    def rms(self) -> float:
        return self.comparison.rms

    def to_dict(self) -> dict[str, Any]:
        """Plain data (JSON): the parameters, the fit statistics, the warnings, the
        correlation matrix (None where a parameter is not identifiable) and the problem."""
        return {
            "parameters": {k: v.to_dict() for k, v in self.parameters.items()},
            "rms": self.rms,
            "chi2": self.chi2,
            "reduced_chi2": self.reduced_chi2,
            "n_points": self.n_points,
            "n_solves": self.n_solves,
            "warnings": list(self.warnings),
            "correlation": {
                "names": list(self.parameters),
                "matrix": [
                    [None if not np.isfinite(r) else round(float(r), 6) for r in row]
                    for row in self.correlation
                ],
            },
            "problem": self.problem.parameters(),
        }


class _Objective:
    """Residuals as a function of internal coordinates, counting the model solves."""

    def __init__(
        self,
        measured: MeasuredProfile,
        base: Problem,
        coords: _Coordinates,
        fixed: dict[str, float],
        method: str,
        options: dict[str, Any],
    ):
        self.measured, self.base, self.coords = measured, base, coords
        self.fixed, self.method, self.options = fixed, method, options
        self.sigma = measured.u_err if measured.u_err is not None else np.ones(measured.n)
        self.solves = 0
        self.best = math.inf
        self.progress: Callable[[str], None] | None = None

    def problem(self, theta: FloatArray) -> Problem:
        return with_values(self.base, {**self.fixed, **self.coords.to_natural(theta)})

    def __call__(self, theta: FloatArray) -> FloatArray:
        self.solves += 1
        try:
            prof = model_profile(self.problem(theta), self.method, **self.options)
        except (NoSolutionError, ParameterError):
            return np.full(self.measured.n, NO_SOLUTION_RESIDUAL)
        res = (model_at(prof, self.measured.distance_d) - self.measured.u_over_uw) / self.sigma
        chi2 = float(np.sum(res**2))
        if self.progress is not None and chi2 < self.best * (1.0 - 1e-6):
            values = ", ".join(f"{k} = {v:.4g}" for k, v in self.coords.to_natural(theta).items())
            self.progress(f"{self.solves} solves, chi-square {chi2:.6g} at {values}")
        self.best = min(self.best, chi2)
        return res


def _least_squares(obj: _Objective, theta0: FloatArray) -> Any:
    lo, hi = obj.coords.bounds()
    theta0 = np.clip(theta0, lo, hi)
    return least_squares(
        obj,
        theta0,
        bounds=(lo, hi),
        method="trf",
        x_scale="jac",
        diff_step=config.FIT_DIFF_STEP,  # relative; well above the model's rtol
        xtol=config.FIT_XTOL,
        ftol=config.FIT_FTOL,
        gtol=config.FIT_GTOL,
        max_nfev=config.FIT_MAX_NFEV,
    )


def fit(
    measured: MeasuredProfile,
    problem: Problem,
    free: Sequence[str] = ("delta", "K"),
    *,
    method: str = "numerical",
    interval_for: Sequence[str] = ("delta",),
    progress: Callable[[str], None] | None = None,
    **options: Any,
) -> FitResult:
    """Fit the ``free`` parameters of ``problem`` to ``measured``.

    Parameters
    ----------
    measured : MeasuredProfile
    problem : Problem
        The Cosserat model on a cell with a moving wall, at the starting values; parameters
        not in ``free`` stay fixed.
    free : sequence of {"delta", "K", "L", "phi", "A"}
        delta is the moving wall's friction angle [deg], K its slip coefficient.
    method : str
        Solution route for the model ("numerical"; "closed-form" for gravity-free plane shear).
    interval_for : sequence of str
        Parameters that also get a profile-likelihood interval (default: delta).
    """
    if getattr(problem, "model", None) != "cosserat":
        raise ParameterError(
            "fit() fits the Cosserat model's walls and material; "
            "cosserat.analysis.ranking.fit_model fits any registered model"
        )
    names = list(dict.fromkeys(free))
    bad = [n for n in names if n not in FREE_PARAMETERS]
    if bad or not names:
        raise ParameterError(
            f"free parameters must be among {', '.join(FREE_PARAMETERS)}; got {', '.join(free)}"
        )
    if measured.n <= len(names):
        raise ParameterError(f"{measured.n} points cannot determine {len(names)} parameters")
    measured.xi(problem.eps, moving_wall(problem)[0])
    if "rtol" not in options and method == "numerical":
        options["rtol"] = config.RTOL  # well below the finite-difference steps
    coords = _Coordinates(names, problem)
    start = {n: natural_value(problem, n) for n in names}
    obj = _Objective(measured, problem, coords, {}, method, options)
    obj.progress = progress
    if progress:
        progress(f"fitting {', '.join(names)} to {measured.n} points")
    res = _least_squares(obj, coords.to_internal(start))
    obj.progress = None
    best_problem = obj.problem(res.x)
    comparison = compare(best_problem, measured, method, **options)
    obj.solves += 1

    n, p = measured.n, len(names)
    chi2 = float(np.sum(res.fun**2))
    dof = max(n - p, 1)
    absolute = measured.u_err is not None
    scale = 1.0 if absolute else chi2 / dof
    # the Jacobian in natural units (delta in degrees), by the chain rule through to_natural
    grad = np.zeros((p, p))
    nat0 = coords.to_natural(res.x)
    for j in range(p):
        h = 1e-7 * max(1.0, abs(res.x[j]))
        th = res.x.copy()
        th[j] -= h
        nat1 = coords.to_natural(th)
        grad[:, j] = [(nat0[k] - nat1[k]) / h for k in names]
    jac = np.asarray(res.jac) @ np.linalg.inv(grad)
    cov, flat = _covariance(jac, coords.natural_ranges(nat0), scale)
    warnings: list[str] = []
    undefined: dict[str, str] = {}
    for direction in flat:
        message, involved = direction.describe(names)
        warnings.append(message)
        for name in involved:
            undefined.setdefault(name, direction.reason(names, name))
    bad = np.array([k in undefined for k in names])
    cov[bad, :] = np.nan
    cov[:, bad] = np.nan
    with np.errstate(invalid="ignore"):
        stderr = np.sqrt(np.diag(cov))
        corr = cov / np.outer(stderr, stderr)
    params = {
        k: FitParameter(
            nat0[k],
            None if k in undefined else float(stderr[i]),
            reason=undefined.get(k),
        )
        for i, k in enumerate(names)
    }

    # profile-likelihood intervals
    for name in interval_for:
        if name not in names:
            continue
        if progress:
            progress(f"profile likelihood for {name}")
        lo_hi = _profile_interval(
            measured, problem, names, name, nat0, chi2, scale, method, options, obj, progress
        )
        params[name] = replace(params[name], interval=lo_hi)

    warnings += _diagnose(
        names, params, corr, measured, problem, chi2, dof, absolute, res.x, coords, comparison
    )
    if progress:
        free_text = ", ".join(
            f"{k} = {v.value:.4g}" + ("" if v.stderr is None else f" +- {v.stderr:.2g}")
            for k, v in params.items()
        )
        progress(
            f"done after {obj.solves} solves: {free_text}; reduced chi-square "
            f"{chi2 / dof:.3g}" + (f"; {len(warnings)} warning(s)" if warnings else "")
        )
    return FitResult(
        params,
        best_problem,
        comparison,
        chi2,
        chi2 / dof,
        n,
        obj.solves,
        cov,
        corr,
        warnings,
        absolute,
    )


@dataclass(frozen=True)
class FlatDirection:
    """A direction of the (range-scaled) parameters along which the fit hardly changes."""

    eigenvalue: float
    largest: float
    vector: FloatArray

    def components(self, names: Sequence[str]) -> list[tuple[str, float]]:
        """(name, component) of the eigenvector's main components, largest first."""
        order = np.argsort(-np.abs(self.vector))
        sign = np.sign(self.vector[order[0]]) or 1.0
        return [
            (names[i], float(sign * self.vector[i]))
            for i in order
            if abs(self.vector[i]) >= FLAT_COMPONENT
        ]

    def describe(self, names: Sequence[str]) -> tuple[str, list[str]]:
        """The warning and the parameters it makes undefined."""
        parts = self.components(names)
        involved = [k for k, _ in parts]
        combo = " ".join(
            f"{'-' if c < 0 else '+' if j else ''} {abs(c):.2f} {k}".strip()
            for j, (k, c) in enumerate(parts)
        )
        if len(involved) == 1:
            what = f"{involved[0]} is not identifiable from these data"
            why = f"the fit hardly depends on {involved[0]}"
        else:
            names_text = f"{', '.join(involved[:-1])} and {involved[-1]}"
            what = f"{names_text} are not identifiable from these data"
            why = "changing them together along it leaves the fit nearly unchanged"
        return (
            f"{what}: the Fisher matrix J^T J has a flat direction along {combo} "
            f"(eigenvalue {self.eigenvalue:.2g} against a largest of {self.largest:.2g}, with "
            f"each parameter scaled by its allowed range): {why}, so the standard errors of "
            f"{', '.join(involved)} are undefined (None)",
            involved,
        )

    def reason(self, names: Sequence[str], name: str) -> str:
        others = [k for k, _ in self.components(names) if k != name]
        if not others:
            return "not identifiable: the fit hardly depends on it"
        return f"not identifiable: trades off with {', '.join(others)} (flat direction of J^T J)"


def _covariance(
    jac: FloatArray, ranges: FloatArray, scale: float
) -> tuple[FloatArray, list[FlatDirection]]:
    """Covariance of the internal coordinates from the Jacobian of the residuals, and the flat
    directions of the Fisher matrix J^T J (left out of the pseudo-inverse).

    The columns are scaled by the parameters' allowed ranges, so that the eigenvalues compare
    like with like: an eigenvalue ``lam`` means moving by a whole range along its eigenvector
    raises chi-square by ``lam`` residual variances. A direction is flat when ``lam`` is below
    :data:`FLAT_RATIO` of the largest (numerically singular) or below one (the whole range is
    within one standard error).
    """
    scaled = jac * ranges
    lam, vec = np.linalg.eigh(scaled.T @ scaled)  # chi-square units; ascending
    largest = float(max(lam[-1], np.finfo(float).tiny))
    flat_mask = (lam <= FLAT_RATIO * largest) | (lam < scale)
    keep = ~flat_mask
    cov = (vec[:, keep] / lam[keep]) @ vec[:, keep].T * np.outer(ranges, ranges) * scale
    variance = scale if scale > 0 else 1.0
    flat = [
        FlatDirection(float(max(lam[k], 0.0)) / variance, largest / variance, vec[:, k])
        for k in np.flatnonzero(flat_mask)
    ]
    return cov, flat


def _profile_interval(
    measured: MeasuredProfile,
    problem: Problem,
    names: list[str],
    name: str,
    best: dict[str, float],
    chi2_min: float,
    scale: float,
    method: str,
    options: dict[str, Any],
    counter: _Objective,
    progress: Callable[[str], None] | None = None,
) -> tuple[float, float]:
    """Where the refitted chi-square rises by ``scale`` (one residual variance) [units of name]."""
    others = [n for n in names if n != name]
    phi = best.get("phi", problem.rheology.material.phi)  # type: ignore[attr-defined]
    upper_bound = (
        math.degrees(math.atan(math.sin(math.radians(phi))))
        if name == "delta"
        else fit_range(name)[1]
    )
    lower_bound = fit_range(name)[0]
    start = {k: best[k] for k in others}
    cache: dict[float, float] = {}

    def excess(value: float) -> float:
        """Refitted chi-square rise over one residual variance, minus 1 (deterministic: every
        refit starts from the best fit)."""
        if value in cache:
            return cache[value]
        if others:
            coords = _Coordinates(others, problem)
            obj = _Objective(measured, problem, coords, {name: value}, method, options)
            res = _least_squares(obj, coords.to_internal(start))
            chi2 = float(np.sum(res.fun**2))
        else:
            coords = _Coordinates([name], problem)
            obj = _Objective(measured, problem, coords, {}, method, options)
            chi2 = float(np.sum(obj(coords.to_internal({name: value})) ** 2))
        counter.solves += obj.solves
        cache[value] = (chi2 - chi2_min) / scale - 1.0
        if progress:
            progress(
                f"profile likelihood for {name}: at {name} = {value:.4g} the refit chi-square "
                f"rises by {cache[value] + 1.0:.3g} residual variances ({counter.solves} solves)"
            )
        return cache[value]

    center = best[name]
    ends = []
    for direction, limit in ((-1.0, lower_bound), (1.0, upper_bound)):
        step = max(abs(center) * 1e-3, 0.05 if name == "delta" else 1e-3)
        inner = center
        found = None
        while step < 1e3:
            trial = center + direction * step
            if (trial - limit) * direction >= 0:
                if excess(limit) < 0:
                    found = limit  # the interval reaches the bound: one-sided
                    break
                trial = limit
            if excess(trial) > 0:
                if excess(inner) < 0:
                    found = brentq(excess, *sorted((inner, trial)), xtol=1e-4 * max(1, abs(center)))
                else:  # a refit found a lower minimum than the fit: keep the bracket end
                    found = trial
                break
            inner, step = trial, step * 2
        ends.append(found if found is not None else limit)
    return float(ends[0]), float(ends[1])


def _diagnose(
    names: list[str],
    params: dict[str, FitParameter],
    corr: FloatArray,
    measured: MeasuredProfile,
    problem: Problem,
    chi2: float,
    dof: int,
    absolute: bool,
    theta: FloatArray,
    coords: _Coordinates,
    comparison: Comparison,
) -> list[str]:
    out = []
    lo, hi = coords.bounds()
    for i, name in enumerate(names):
        margin = 1e-6 * (hi[i] - lo[i])
        if theta[i] >= hi[i] - margin or theta[i] <= lo[i] + margin:
            what = "the fully rough bound tan(delta) = sin(phi)" if name == "delta" else "a bound"
            advice = (
                "use the profile-likelihood interval"
                if params[name].interval is not None
                else f"a profile-likelihood interval (interval_for including {name}) is"
                " the meaningful range"
            )
            out.append(f"{name} is at {what}: its standard error is not meaningful; {advice}")
        p = params[name]
        if p.stderr is not None and p.stderr > max(abs(p.value), 1e-3):
            out.append(
                f"{name} is poorly determined by these data (standard error "
                f"{p.stderr:.3g} against value {p.value:.3g})"
            )
    for i in range(len(names)):
        for j in range(i + 1, len(names)):
            if np.isfinite(corr[i, j]) and abs(corr[i, j]) > CORRELATION_LIMIT:
                out.append(
                    f"{names[i]} and {names[j]} are strongly correlated (r = {corr[i, j]:+.3f}, "
                    f"|r| > {CORRELATION_LIMIT}): the data constrain mainly a combination of "
                    f"them, and their standard errors are dominated by it"
                )
    if "K" in names and measured.distance_d.min() > 2.0:
        out.append(
            f"no point within 2 grain diameters of the moving wall (nearest: "
            f"{measured.distance_d.min():.3g}): K, the wall slip, is constrained only "
            f"indirectly"
        )
    reduced = chi2 / dof
    if absolute and reduced > 3.0:
        out.append(
            f"poor fit: reduced chi-square = {reduced:.3g} >> 1; the model does not "
            f"describe these data within their uncertainties, and the parameter errors "
            f"are not meaningful"
        )
    signs = np.sign(comparison.residuals[np.argsort(measured.distance_d)])
    signs = signs[signs != 0]
    if signs.size >= 10:
        runs = 1 + int(np.sum(signs[1:] != signs[:-1]))
        n_pos, n_neg = int(np.sum(signs > 0)), int(np.sum(signs < 0))
        if n_pos and n_neg:
            mean = 1 + 2 * n_pos * n_neg / (n_pos + n_neg)
            var = (mean - 1) * (mean - 2) / (n_pos + n_neg - 1)
            z = (runs - mean) / math.sqrt(max(var, 1e-12))
            if z < -3.0:
                out.append(
                    f"systematic misfit: the residuals change sign only {runs} times "
                    f"(expected about {mean:.0f} for random scatter; z = {z:.1f})"
                )
    return out


__all__ = [
    "Comparison",
    "FitParameter",
    "FitResult",
    "FlatDirection",
    "compare",
    "fit",
    "fit_range",
    "model_at",
    "moving_wall",
    "with_values",
]
