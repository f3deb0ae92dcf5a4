"""One measured velocity profile: ``fit``, ``fit_model`` and ``rank_models``.

A fit to one profile is a calibration of one run (``docs/calibration.md``): the profile becomes
a :class:`~cosserat.calibration.data.RunData` with one field, ``u``; the problem given says the
starting values and what stays fixed; the engine (:func:`cosserat.calibration.engine.fit`),
its one identifiability rule (:func:`cosserat.calibration.diagnostics.flat_directions`) and
its result (:class:`~cosserat.calibration.result.ModelCalibration`, JSON and
``to_dataframe()``) are those of ``cosserat calibrate``. What this module adds:

* **The data's cell wins.** What the profile's header states (``geometry``, ``eps``, ``Ri``,
  ``B``, ``nu``, the wall's inertial number ``I_w``) is fixed, never fitted: where the problem
  given disagrees, the header's values are used and a :class:`CellMismatchWarning` (also in the
  result's warnings) says so. What the header does not state is taken from the problem (its
  ``I_w`` too: a note in the assumptions says where it came from).
* **Names of one run.** The parameters are named by the model's keys: the moving wall's
  roughness ``tan(delta)/sin(phi)``, ``K`` and the derived ``delta`` [deg]; a plane cell's lower
  wall, where it differs from the moving one, is held at its own values (``delta_lower``).
* **Defaults of one profile** (:data:`SINGLE_RUN_FREE`). The Cosserat model frees ``delta``
  and ``K``, NGF ``A`` and ``b`` (a velocity profile alone does not determine the rest; the
  joint calibration does, with the stresses); the other rheologies free what their
  calibration frees (:meth:`~cosserat.calibration.models.Model.parameters`).
* **Errors.** With the points' errors ``u_err`` they are taken as absolute; without, every
  point weighs the same and the errors are scaled by the residual variance
  ``RSS / (n - k)`` (the likelihood then has sigma at its maximum, ``RSS/n``). The bins are taken
  as independent unless ``bin_correlation`` says otherwise (``calibrate`` estimates it: its
  second-difference estimate needs the points' errors).
* **A profile-likelihood interval** for ``delta`` (``interval_for``): where the refitted
  chi-square rises by one residual variance, one-sided when it reaches the fully rough bound.
"""

from __future__ import annotations

import dataclasses
import math
import time
import warnings
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..analysis.fitting import Comparison, model_at, moving_wall
from ..analysis.measurements import MeasuredProfile
from ..analysis.ranking import model_solve
from ..errors import (
    ConvergenceError,
    MethodNotAvailableError,
    NoSolutionError,
    ParameterError,
)
from ..model import Cosserat, Problem, make_problem
from ..model.build import problem_parameters
from ..model.constitutive import FloatArray
from ..model.parameters import Wall
from ..model.rheologies import RHEOLOGIES
from ..routes import models_for, solve
from .data import Field, RunData
from .engine import Optimum, Setup, setup
from .engine import fit as engine_fit
from .joint import COMPARISON, assemble
from .models import Model
from .noise import Correlation, effective_bins
from .result import Calibration, Estimate, ModelCalibration

SINGLE_RUN_FREE: dict[str, tuple[str, ...]] = {"cosserat": ("delta", "K"), "ngf": ("A", "b")}
"""What a fit to one velocity profile frees by default, where it differs from the model's
calibration (module docstring): a velocity profile alone does not separate the Cosserat
material (phi, L) from the wall's friction, nor NGF's mu_s from its b and A (one flat
direction, about +0.93 mu_s +0.24 b +0.27 A on a 40-grain Couette profile); the stresses of a
joint calibration do."""
CELL_KEYS = {"geometry": "geometry", "eps": "eps", "ri": "Ri", "b": "B", "nu": "nu", "i_w": "I_w"}
"""Header keys (lower case) of a measured profile that fix the cell, by parameter key."""
NEAR_WALL_D = 2.0
"""Without a point this close to the moving wall [d], the wall slip K is constrained only
indirectly (a warning)."""
_MOVING, _LOWER = "wall", "lower"
_FAILURES = (ParameterError, ConvergenceError, NoSolutionError, MethodNotAvailableError)


class CellMismatchWarning(UserWarning):
    """The problem given to a fit disagrees with the cell its data's header states: the
    header's values are used."""


# --------------------------------------------------------------------------- the result
@dataclass(frozen=True)
class SingleFit(ModelCalibration):
    """A calibration of one run (:class:`~cosserat.calibration.result.ModelCalibration`) with
    what a single profile adds: the cell, the fitted problem, its profile and the comparison.

    Attributes
    ----------
    cell : str
    problem : Problem or None
        The fitted problem (every parameter at its best-fit or fixed value).
    profile : Profile or None
        Its solution on 201 points.
    comparison : Comparison or None
        The fitted model beside the data (residuals data minus model).
    absolute_sigma : bool
        The points' errors were given (else unit weights scaled by the residual variance).
    rss : float or None
        Sum of squared residuals (data minus model) [-].
    """

    cell: str = ""
    problem: Any = None
    profile: Any = None
    comparison: Comparison | None = None
    absolute_sigma: bool = True
    rss: float | None = None

    @property
    def n_points(self) -> int:
        return self.n

    @property
    def n_solves(self) -> int:
        """Model solves the fit took."""
        return self.nfev

    @property
    def rms(self) -> float | None:
        """rms(data - model) [-]."""
        return None if self.comparison is None else self.comparison.rms

    @property
    def p_value(self) -> float | None:
        """P(chi^2 >= this) with absolute errors; None without errors (chi^2 = dof then)."""
        return super().p_value if self.absolute_sigma else None

    @property
    def log10_p_value(self) -> float | None:
        return super().log10_p_value if self.absolute_sigma else None

    @property
    def reduced_chi2(self) -> float | None:
        """chi^2/(n - k); without errors RSS/(n - k), the residual variance."""
        if not self.absolute_sigma and self.rss is not None and self.dof > 0:
            return self.rss / self.dof
        return super().reduced_chi2

    @property
    def correlation(self) -> FloatArray:
        """Correlation matrix of the free parameters (in the order of ``covariance_names``) [-]."""
        c = np.asarray(self.covariance if self.covariance is not None else np.zeros((0, 0)))
        d = np.sqrt(np.clip(np.diag(c), 0.0, None))
        with np.errstate(invalid="ignore", divide="ignore"):
            return c / np.outer(d, d)

    def curve(self, distance_d: FloatArray) -> FloatArray:
        """The fitted model's u / u_wall at distances from the moving wall [d] (for plots)."""
        if self.profile is None:
            raise ParameterError(f"model {self.model!r} was not fitted: {self.message}")
        return model_at(self.profile, distance_d)

    def to_dict(self) -> dict[str, Any]:
        """The calibration contract (``docs/calibration.md``) of one model, with the cell,
        the fitted problem, rms, n_points, n_solves and whether the errors were given."""
        out = super().to_dict()
        out.update(
            cell=self.cell,
            rms=self.rms,
            rss=self.rss,
            n_points=self.n,
            n_solves=self.nfev,
            absolute_sigma=self.absolute_sigma,
            problem=None if self.problem is None else self.problem.parameters(),
        )
        return out

    def text(self) -> str:
        """The free parameters (:meth:`shown`), one per line."""
        return "\n".join(f"  {n} = {estimate_text(e)}" for n, e in self.shown().items())

    def shown(self) -> dict[str, Estimate]:
        """The parameters a reader wants: the free ones, the Cosserat wall's as its delta
        rather than its roughness coordinate."""
        out = {}
        for n, e in self.parameters.items():
            if not e.free:
                continue
            if e.key == "roughness" and self.model == "cosserat":
                continue
            out[n] = e
        return out


def estimate_text(e: Estimate) -> str:
    """``value +- stderr [unit]`` or ``value (no error: reason)``."""
    unit = "" if e.unit in ("", "-", "1") else f" {e.unit}"
    if e.stderr is None or not math.isfinite(e.stderr):
        return f"{e.value:.5g}{unit} (no error: {e.reason or 'not determined'})"
    extra = "" if e.interval is None else f", interval [{e.interval[0]:.4g}, {e.interval[1]:.4g}]"
    return f"{e.value:.5g} +- {e.stderr:.2g}{unit}{extra}"


# --------------------------------------------------------------------------- one run
@dataclass
class _Reporting(Setup):
    """A :class:`~cosserat.calibration.engine.Setup` that reports each improvement of
    chi-square to ``progress`` (the command line's progress line)."""

    progress: Callable[[str], None] | None = None
    best: float = math.inf

    def residuals(self, theta: FloatArray) -> FloatArray:
        r = super().residuals(theta)
        chi2 = float(r @ r)
        if self.progress is not None and chi2 < self.best * (1.0 - 1e-6):
            values = ", ".join(
                f"{'delta' if s.key == 'roughness' else s.name} = "
                f"{_delta_of(self, theta) if s.key == 'roughness' else v:.4g}"
                for s, v in zip(self.free, np.atleast_1d(theta), strict=True)
            )
            self.progress(f"{self.nfev} solves, chi-square {chi2:.6g} at {values}")
        self.best = min(self.best, chi2)
        return r


def _delta_of(s: Setup, theta: FloatArray) -> float:
    """The moving wall's delta [deg] at ``theta`` (from its roughness and phi)."""
    nat = s.natural(theta)
    phi = nat.get("phi", 0.0)
    return math.degrees(math.atan(nat["roughness"] * math.sin(math.radians(phi))))


def _header_cell(measured: MeasuredProfile) -> dict[str, Any]:
    return {CELL_KEYS[k]: v for k, v in measured.meta.items() if k in CELL_KEYS and v is not None}


def data_problem(problem: Problem, measured: MeasuredProfile) -> tuple[Problem, list[str]]:
    """``problem`` with the cell the data's header states (module docstring), and a note for
    every value the header changed.

    Raises
    ------
    ParameterError
        The header's values are not a valid cell for the problem's rheology.
    """
    header = _header_cell(measured)
    declared = problem.declared()
    notes = []
    geometry = header.pop("geometry", None)
    if geometry is not None and geometry != problem.cell_name:
        notes.append(
            f"the data's header says geometry {geometry}; the problem given is on the "
            f"{problem.cell_name} cell: the data's cell is used"
        )
        keep = {
            k: v
            for k, v in problem.values().items()
            if declared[k].role not in ("cell", "drive") and v is not None
        }
        applies = problem_parameters(problem.model, str(geometry))
        keep = {k: v for k, v in keep.items() if k in applies}
        cell = {k: v for k, v in header.items() if k in applies}
        problem = make_problem(problem.model, str(geometry), {**keep, **cell})
        declared = problem.declared()
    current = {**problem.values(), **problem.cell_values()}
    change = {}
    for key, value in header.items():
        if key not in declared:
            continue
        if key not in current or not math.isclose(
            float(value), float(current[key]), rel_tol=1e-9, abs_tol=1e-12
        ):
            change[key] = float(value)
            if key in current and current[key] is not None:
                notes.append(
                    f"the data's header gives {key} = {float(value):g}; the problem given has "
                    f"{key} = {float(current[key]):g}: the data's value is used"
                )
    if change:
        problem = problem.with_values(change)
    return problem, notes


def _roughness(law: Cosserat, wall: Wall) -> float:
    """tan(delta)/sin(phi) of a Cosserat wall (1: fully rough) [-]."""
    if wall.is_fully_rough:
        return 1.0
    s = law.material.sin_phi
    return min(math.tan(math.radians(float(wall.delta))) / s, 1.0)


def run_of(
    measured: MeasuredProfile, problem: Problem, name: str = "profile", rho: float = 0.0
) -> tuple[RunData, dict[str, float]]:
    """The :class:`RunData` of one profile on ``problem``'s cell (the header already applied,
    :func:`data_problem`), and the problem's values of the calibration's slots (what is not
    freed is fixed at them)."""
    model = Model(problem.model, local_spin=False)
    values = {k: v for k, v in problem.values().items() if v is not None}
    slots: dict[str, float] = {}
    walls = {"moving": _MOVING, "fixed": _MOVING}
    keys = {p.key for p in model.parameters()}
    law = problem.rheology
    if isinstance(law, Cosserat):  # problem.model == "cosserat"
        slots["roughness[wall]"] = _roughness(law, law.wall)
        slots["K[wall]"] = float(law.wall.K)
        lower = law.lower
        if problem.cell_name == "plane" and lower is not None and lower != law.wall:
            walls["fixed"] = _LOWER
            slots["roughness[lower]"] = _roughness(law, lower)
            slots["K[lower]"] = float(lower.K)
        for k in ("delta", "K", "delta_lower", "K_lower"):
            values.pop(k, None)
    for k in list(values):
        if k in keys:
            slots[k] = float(values.pop(k))
    I_w = values.pop("I_w", None)
    if model.rate_dependent and I_w is None:
        I_w = problem.cell_values().get("I_w")
    order = np.argsort(measured.distance_d, kind="stable")
    s = np.asarray(measured.distance_d, dtype=float)[order]
    u = np.asarray(measured.u_over_uw, dtype=float)[order]
    se = (
        np.ones_like(u)
        if measured.u_err is None
        else np.asarray(measured.u_err, dtype=float)[order]
    )
    source = "given" if measured.u_err is not None else "no errors given"
    run = RunData(
        name=name,
        cell=problem.cell_name,
        gap_d=1.0 / problem.eps,
        cell_values=values,
        I_w=None if I_w is None else float(I_w),
        material="material",
        walls=walls,
        fields={"u": Field("u", s, u, se, Correlation(float(rho), source))},
        meta=dict(measured.meta),
    )
    return run, slots


def _free_names(model: Model, problem: Problem, free: Sequence[str] | None) -> list[str]:
    """The calibration's keys of ``free`` (delta -> roughness for the Cosserat model)."""
    params = model.parameters()
    keys = [p.key for p in params]
    shown = ["delta" if k == "roughness" else k for k in keys]
    if free is None:
        default = SINGLE_RUN_FREE.get(model.name)
        names = list(default) if default else [p.key for p in params if p.default_free]
    else:
        names = list(dict.fromkeys(free))
    if "I_w" in names:
        raise ParameterError(
            "I_w is what the data's wall speed fixes (or the problem's value): it is not fitted; "
            f"free parameters must be among {', '.join(shown)}"
        )
    bad = [n for n in names if n not in shown and n not in keys]
    if bad or not names:
        raise ParameterError(
            f"free parameters must be among {', '.join(shown)}; got {', '.join(names) or 'none'}"
        )
    return ["roughness" if n == "delta" else n for n in names]


def _rename(name: str) -> str:
    """A slot's name in a one-run fit: ``K[wall]`` -> ``K``, ``K[lower]`` -> ``K_lower``."""
    if name.endswith(f"[{_MOVING}]"):
        return name[: -len(_MOVING) - 2]
    if name.endswith(f"[{_LOWER}]"):
        return name[: -len(_LOWER) - 2] + "_lower"
    return name


def _unit_weights(s: Setup, opt: Optimum) -> tuple[Setup, Optimum, float]:
    """Without errors: every point's error the residual standard deviation sqrt(RSS/dof), the
    residuals and Jacobian scaled alike (the fit itself does not change)."""
    rss = float(opt.residuals @ opt.residuals)
    dof = max(s.n - len(s.free), 1)
    sigma = math.sqrt(rss / dof) if rss > 0.0 else 1.0
    run = s.runs[0]
    f = run.fields["u"]
    scaled = dataclasses.replace(
        run, fields={"u": Field("u", f.s, f.value, np.full(f.n, sigma), f.correlation)}
    )
    s2 = Setup(s.model, [scaled], s.fields, s.slots, nfev=s.nfev)
    opt2 = dataclasses.replace(opt, residuals=opt.residuals / sigma, jacobian=opt.jacobian / sigma)
    return s2, opt2, rss


def fit(
    measured: MeasuredProfile,
    problem: Problem,
    free: Sequence[str] | None = None,
    *,
    method: str = "numerical",
    interval_for: Sequence[str] = ("delta",),
    progress: Callable[[str], None] | None = None,
    starts: int | None = None,
    seed: int = 0,
    bin_correlation: float = 0.0,
    name: str | None = None,
    **options: Any,
) -> SingleFit:
    """Fit the ``free`` parameters of ``problem`` to ``measured``: a calibration of one run
    (module docstring).

    Parameters
    ----------
    measured : MeasuredProfile
        u over the moving wall's velocity against the distance from it [d]; its header's cell
        (geometry, eps, Ri, B, nu, I_w) is fixed and wins over ``problem``'s.
    problem : Problem
        Any registered rheology on a cell with a moving wall, at the starting values;
        parameters not in ``free`` stay fixed at its values.
    free : sequence of str, optional
        Parameter keys; for the Cosserat model ``delta`` is the moving wall's friction angle
        [deg] (fitted as its roughness tan(delta)/sin(phi)), ``K`` its slip coefficient.
        Default: :data:`SINGLE_RUN_FREE`, else the model's calibration defaults.
    method : str
        Solution route of the returned profile and comparison ("numerical", or "closed-form"
        where the problem has one); the fit itself uses the calibration's solver.
    interval_for : sequence of str
        Parameters that also get a profile-likelihood interval (default: delta).
    progress : callable, optional
        ``progress(message)`` at the start, per profile-likelihood step, and at the end.
    starts : int, optional
        Latin-hypercube starts besides the problem's values (default ``4 k + 4``; 0: the
        problem's values only).
    seed : int
        Seed of the start design.
    bin_correlation : float
        Lag-1 correlation of neighbouring points' errors, ``0 <= rho < 1`` (0: independent).
    name : str, optional
        The run's name in the warnings (default: the header's label, else "profile").
    **options
        Passed to the route of the returned profile (e.g. ``rtol``).

    Returns
    -------
    SingleFit

    Raises
    ------
    ParameterError
        A parameter the model does not have, ``I_w`` freed, too few points, points outside
        the gap, or a header that is not a valid cell.
    ConvergenceError
        The model has no solution at any start.
    """
    t0 = time.perf_counter()
    if not isinstance(problem, Problem):
        raise ParameterError(
            f"{type(problem).__name__} is not a Problem(cell, rheology) of a registered rheology"
        )
    if not 0.0 <= bin_correlation < 1.0:
        raise ParameterError(f"bin_correlation must satisfy 0 <= rho < 1; got {bin_correlation:g}")
    problem, notes = data_problem(problem, measured)
    for note in notes:
        warnings.warn(note, CellMismatchWarning, stacklevel=2)
    model = Model(problem.model, local_spin=False)
    names = _free_names(model, problem, free)
    if measured.n <= len(names):
        raise ParameterError(f"{measured.n} points cannot determine {len(names)} parameters")
    measured.xi(problem.eps, moving_wall(problem)[0])  # the points lie in the gap
    label = name or str(measured.meta.get("label") or "profile")
    run, values = run_of(measured, problem, label, bin_correlation)
    # a plane cell's other wall kind (``[lower]``) is held at its own values
    freed = {k for k in values if k.split("[")[0] in names and not k.endswith(f"[{_LOWER}]")}
    fix = {k: v for k, v in values.items() if k not in freed}
    start = {k: v for k, v in values.items() if k in freed}
    s = setup(model, [run], ("u",), fix=fix, free=names, start=start)
    renamed = [dataclasses.replace(sl, name=_rename(sl.name)) for sl in s.slots]
    watched = _Reporting(model, s.runs, s.fields, renamed, progress=progress)
    s = watched
    shown = ", ".join("delta" if n == "roughness" else n for n in names)
    if progress:
        progress(f"fitting {shown} to {measured.n} points")
    opt = engine_fit(s, starts=starts, seed=seed)
    watched.progress = None  # the search is over: refits and Jacobians are not improvements
    rss = float(opt.residuals @ opt.residuals)
    absolute = measured.u_err is not None
    if not absolute:
        s, opt, rss = _unit_weights(s, opt)
    mc = assemble(s, opt, t0)
    params = {
        (_rename(n) if e.derived else n): dataclasses.replace(e, name=_rename(e.name))
        for n, e in mc.parameters.items()
    }
    # the free parameters first, in the order asked for (delta for the Cosserat roughness)
    first = ["delta" if n == "roughness" and "delta" in params else n for n in names]
    params = {**{n: params[n] for n in first}, **params}
    extra: list[str] = list(notes)
    if not absolute:
        n = s.n
        ll = -0.5 * n * (math.log(2.0 * math.pi * rss / n) + 1.0) if rss > 0.0 else None
        mc = dataclasses.replace(mc, log_likelihood=ll)
    # the profile-likelihood intervals
    scale = 1.0  # one residual variance: the residuals are whitened (or scaled) already
    for key in interval_for:
        slot_name = "roughness" if key == "delta" else key
        if slot_name not in names or key not in params:
            continue
        if progress:
            progress(f"profile likelihood for {key}")
        j = list(mc.covariance_names).index(slot_name)
        guess = math.sqrt(max(float(np.asarray(mc.covariance)[j, j]), 0.0))
        lo_hi = _profile_interval(s, opt, slot_name, key, scale, progress, guess)
        params[key] = dataclasses.replace(params[key], interval=lo_hi)
    best = model.problem(run, s.run_values(s.runs[0], opt.theta))
    profile = (
        model_solve(best, points=201, **options)
        if method == "numerical"
        else solve(best, method=method, check=False, points=201, **options)
    )
    curve = model_at(profile, measured.distance_d)
    residuals = measured.u_over_uw - curve
    chi2_c = None if measured.u_err is None else float(np.sum((residuals / measured.u_err) ** 2))
    comparison = Comparison(
        measured, profile, curve, residuals, float(np.sqrt(np.mean(residuals**2))), chi2_c
    )
    if absolute:
        rss = float(np.sum(residuals**2))
    if (
        model.name == "cosserat"
        and "K" in names
        and float(np.min(measured.distance_d)) > NEAR_WALL_D
    ):
        extra.append(
            f"no point within {NEAR_WALL_D:g} grain diameters of the moving wall (nearest: "
            f"{float(np.min(measured.distance_d)):.3g}): K, the wall slip, is constrained only "
            "indirectly"
        )
    assumptions = list(mc.assumptions)
    if not absolute:
        assumptions.append(
            "no errors given: every point weighs the same, and the errors are scaled by the "
            "residual variance RSS/(n - k); AIC and BIC use sigma at its maximum-likelihood "
            "value sqrt(RSS/n)"
        )
    if model.rate_dependent and "I_w" not in _header_cell(measured):
        assumptions.append(
            f"I_w = {run.I_w:.4g} fixed at the problem's value: the data's header does not "
            "give it (add '# I_w: ...' or the wall speed)"
        )
    result = SingleFit(
        **{f.name: getattr(mc, f.name) for f in dataclasses.fields(ModelCalibration)},
        cell=problem.cell_name,
        problem=best,
        profile=profile,
        comparison=comparison,
        absolute_sigma=absolute,
        rss=rss,
    )
    result = dataclasses.replace(
        result,
        parameters=params,
        warnings=[*extra, *mc.warnings],
        assumptions=assumptions,
        nfev=s.nfev,
        seconds=time.perf_counter() - t0,
    )
    if progress:
        progress(
            f"done after {result.nfev} solves: "
            + "; ".join(f"{k} = {estimate_text(e)}" for k, e in result.shown().items())
            + (f"; {len(result.warnings)} warning(s)" if result.warnings else "")
        )
    return result


def _profile_interval(
    s: Setup,
    opt: Optimum,
    slot_name: str,
    key: str,
    scale: float,
    progress: Callable[[str], None] | None,
    guess: float = 0.0,
) -> tuple[float, float]:
    """Where the refitted chi-square rises by ``scale`` over its minimum, in the natural unit
    of ``key`` (delta [deg] from the roughness with the refit's phi); an end at the search
    range's bound where it rises less (one-sided). ``guess``: the slot's standard error in the
    fit's coordinate, the first step of the search (else 1e-3 of the range)."""
    names = s.names
    j = names.index(slot_name)
    lo, hi = s.bounds()
    chi2_min = float(opt.residuals @ opt.residuals)
    best = s.natural(opt.theta)
    cache: dict[float, tuple[float, dict[str, float]]] = {}

    def refit(y: float) -> tuple[float, dict[str, float]]:
        """(chi^2 rise over ``scale`` minus 1, natural values) with the slot at ``y``."""
        if y in cache:
            return cache[y]
        slots = []
        for sl in s.slots:
            if sl.name == slot_name:
                sl = dataclasses.replace(sl, free=False, value=sl.natural(y))
            elif sl.free:
                sl = dataclasses.replace(sl, value=best[sl.name])
            slots.append(sl)
        sub = Setup(s.model, s.runs, s.fields, slots)
        try:
            if sub.free:
                o = engine_fit(sub, starts=0, with_jacobian=False)
                r, nat = o.residuals, sub.natural(o.theta)
            else:
                r, nat = sub.residuals(np.zeros(0)), sub.natural(np.zeros(0))
        except _FAILURES:
            r, nat = np.full(s.n, 1e3), sub.natural(sub.start())
        s.nfev += sub.nfev
        cache[y] = ((float(r @ r) - chi2_min) / scale - 1.0, nat)
        if progress:
            progress(
                f"profile likelihood for {key}: at {slot_name} = {sl_natural(y):.4g} the refit "
                f"chi-square rises by {cache[y][0] + 1.0:.3g} ({s.nfev} solves)"
            )
        return cache[y]

    def sl_natural(y: float) -> float:
        return s.free[j].natural(y)

    def excess(y: float) -> float:
        return refit(y)[0]

    def natural(y: float) -> float:
        nat = refit(y)[1]
        v = s.free[j].natural(y)
        if key == "delta":
            phi = nat.get("phi", best.get("phi", 0.0))
            return math.degrees(math.atan(v * math.sin(math.radians(phi))))
        return v

    from scipy.optimize import brentq

    center = float(opt.theta[j])
    width = float(hi[j] - lo[j])
    ends = []
    for direction, limit in ((-1.0, float(lo[j])), (1.0, float(hi[j]))):
        step = guess if 0.0 < guess < width else 1e-3 * width
        inner, found = center, None
        while True:
            trial = center + direction * step
            if (trial - limit) * direction >= 0.0:
                trial = limit
            if excess(trial) > 0.0:
                found = (
                    brentq(excess, *sorted((inner, trial)), xtol=1e-5 * width)
                    if excess(inner) < 0.0
                    else trial
                )
                break
            if trial == limit:
                found = limit  # the interval reaches the bound: one-sided
                break
            inner, step = trial, step * 2.0
        ends.append(natural(found))
    return float(min(ends)), float(max(ends))


def fit_model(
    measured: MeasuredProfile,
    problem: Any,
    free: Sequence[str] | None = None,
    *,
    grid: int = 3,
    **options: Any,
) -> SingleFit:
    """:func:`fit` without profile-likelihood intervals (what :func:`rank_models` runs for
    each model). ``grid`` = 0 starts from the problem's values only; otherwise the
    calibration's Latin-hypercube starts are used (the old start grid's role)."""
    return fit(
        measured,
        problem,
        free,
        interval_for=(),
        starts=0 if grid == 0 else None,
        **options,
    )


# --------------------------------------------------------------------------- ranking
@dataclass
class Ranking:
    """Every model's fit to one profile (each a :class:`SingleFit`), best (lowest AIC) first.

    AIC and BIC are those of the calibration (``-2 ln L + 2k``, ``-2 ln L + k ln n``, the full
    Gaussian likelihood): they differ from ``chi^2 + 2k`` by a constant that is the same for
    every model fitted to the same points, so their differences and the Akaike weights are
    those of ``chi^2 + 2k``.
    """

    measured: MeasuredProfile
    cell: str
    fits: list[SingleFit]

    @property
    def ranked(self) -> list[SingleFit]:
        """The fitted models by AIC (then BIC), failures last."""
        ok = [f for f in self.fits if f.ok and f.aic is not None]
        rest = [f for f in self.fits if f not in ok]
        return sorted(ok, key=lambda f: (f.aic, f.bic)) + rest

    @property
    def best(self) -> SingleFit | None:
        r = self.ranked
        return r[0] if r and r[0].ok and r[0].aic is not None else None

    def by_bic(self) -> list[SingleFit]:
        ok = [(f.bic, f) for f in self.fits if f.ok and f.bic is not None]
        return [f for _, f in sorted(ok, key=lambda bf: bf[0])]

    @property
    def calibration(self) -> Calibration:
        """The same fits as one :class:`~cosserat.calibration.result.Calibration` (its JSON
        contract, weights and ``to_dataframe()``)."""
        runs = [f.internal[0].runs[0] for f in self.fits if f.ok and f.internal is not None]
        return Calibration(runs[:1], list(self.fits), list(COMPARISON))

    @property
    def bin_correlation(self) -> Correlation:
        """The lag-1 correlation of the bins' errors the fits used (rho = 0: independent)."""
        for f in self.fits:
            if f.ok and f.internal is not None:
                return f.internal[0].runs[0].fields["u"].correlation
        return Correlation(0.0, "given")

    def weights(self) -> dict[str, float]:
        """Akaike weights exp(-dAIC/2), normalised over the fitted models."""
        return self.calibration.weights("aic")

    def to_dataframe(self) -> Any:
        return self.calibration.to_dataframe()

    def to_dict(self) -> dict[str, Any]:
        best = self.best
        return {
            "cell": self.cell,
            "n_points": self.measured.n,
            "uncertainties": self.measured.u_err is not None,
            "best": None if best is None else best.model,
            "akaike_weights": self.weights(),
            "comparison": list(COMPARISON),
            "fits": [f.to_dict() for f in self.ranked],
        }

    def to_text(self) -> str:
        w = self.weights()
        a0 = min((f.aic for f in self.fits if f.ok and f.aic is not None), default=0.0)
        absolute = self.measured.u_err is not None
        what = "chi2" if absolute else "RSS"
        rho = self.bin_correlation
        whitened = (
            f"uncertainties given, neighbouring bins' errors AR(1)-correlated with rho = "
            f"{rho.rho:.2f} ({rho.source}; {effective_bins(self.measured.n, rho.rho):.1f} "
            "effective bins): chi2 = sum of the squared whitened residuals, "
            if rho.rho > 0.0
            else "uncertainties given: chi2 = sum((model - data)/u_err)^2, "
        )
        lines = [
            f"{self.measured.n} points on the {self.cell} cell; "
            + (
                whitened + "AIC = chi2 + 2k + c, BIC = chi2 + k ln n + c"
                if absolute
                else "no uncertainties: RSS = sum((model - data)^2), AIC = n ln(RSS/n) + 2k + c, "
                "BIC = n ln(RSS/n) + k ln n + c"
            )
            + " (c: the same for every model)",
            f"{'rank':<5}{'model':<10}{'k':>3}{what:>12}{'red.' + what:>11}{'AIC':>11}"
            f"{'dAIC':>9}{'BIC':>11}{'weight':>8}",
        ]
        for i, f in enumerate(self.ranked, start=1):
            if not f.ok:
                lines.append(f"{'-':<5}{f.model:<10}not fitted: {f.message}")
                continue
            value = f.chi2 if absolute else f.rss
            lines.append(
                f"{i:<5}{f.model:<10}{f.k:>3}{value:>12.5g}{f.reduced_chi2:>11.4g}"
                + (
                    f"{f.aic:>11.5g}{f.aic - a0:>9.3g}{f.bic:>11.5g}{w.get(f.model, 0.0):>8.3f}"
                    if f.aic is not None
                    else f"{'undefined':>11}"
                )
            )
        for f in self.ranked:
            if not f.ok:
                continue
            shown = f.shown()
            lines.append(
                f"  {f.model}: " + "; ".join(f"{k} = {estimate_text(v)}" for k, v in shown.items())
                if shown
                else f"  {f.model}: no free parameter"
            )
            lines += [f"    note: {w_}" for w_ in f.warnings]
        return "\n".join(lines) + "\n"

    def plot(self, title: str = ""):
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


def rank_models(
    measured: MeasuredProfile,
    cell_parameters: Mapping[str, Any],
    models: Sequence[str] | None = None,
    free: Mapping[str, Sequence[str]] | None = None,
    *,
    cell: str | None = None,
    model_parameters: Mapping[str, Mapping[str, Any]] | None = None,
    grid: int = 3,
    bin_correlation: float = 0.0,
) -> Ranking:
    """Fit every model to ``measured`` (:func:`fit_model`) and rank them by AIC and BIC.

    Parameters
    ----------
    measured : MeasuredProfile
        Distance from the moving wall [d], u over the wall's velocity [-], optional errors.
    cell_parameters : mapping
        ``geometry`` (plane | couette; or give ``cell``), ``eps`` = d/H, and ``Ri`` (Couette),
        ``B`` and ``nu`` (plane) as they apply, and ``I_w``, the wall's inertial number, for
        the rate-dependent models [-]; the profile's header wins where it states them.
    models : sequence of str, optional
        Registered rheologies; default every one defined on the cell.
    free : mapping of model name to parameter names, optional
        Parameters to fit for each model (default :func:`fit`'s).
    cell : str, optional
    model_parameters : mapping of model name to mapping, optional
        Fixed values or starting values of model parameters (e.g. ``{"cosserat":
        {"delta": "fully-rough"}}``).
    grid : int
        0: start each fit from the model's defaults only.
    bin_correlation : float
        Lag-1 correlation of neighbouring points' errors, ``0 <= rho < 1``, for every model
        (:func:`fit`; 0: independent).

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
    fits: list[SingleFit] = []
    header_I_w = _header_cell(measured).get("I_w")
    for m in names:
        try:
            given = dict(params)
            if not RHEOLOGIES[m].rate_dependent:
                given.pop("I_w", None)
            elif "I_w" not in given and header_I_w is not None:
                given["I_w"] = float(header_I_w)  # what the data fix, not a problem's default
            start = {**given, **dict((model_parameters or {}).get(m, {}))}
            problem = make_problem(m, cell, start)
            moving_wall(problem)
        except (MethodNotAvailableError, ParameterError) as exc:
            # the model is not defined on this cell, or needs what the cell does not give
            fits.append(SingleFit(model=m, cell=cell, status="failed", message=str(exc)))
            continue
        try:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore", CellMismatchWarning)  # said in its warnings
                fits.append(
                    fit_model(
                        measured,
                        problem,
                        None if free is None else free.get(m),
                        grid=grid,
                        bin_correlation=bin_correlation,
                    )
                )
        except (MethodNotAvailableError, NoSolutionError, ConvergenceError) as exc:
            fits.append(SingleFit(model=m, cell=cell, status="failed", message=str(exc)))
    return Ranking(measured, cell, fits)


__all__ = [
    "SINGLE_RUN_FREE",
    "CellMismatchWarning",
    "Ranking",
    "SingleFit",
    "data_problem",
    "estimate_text",
    "fit",
    "fit_model",
    "rank_models",
    "run_of",
]
