"""The models fitted to one run's velocity: the only module of validation that fits.

Every call to the fitting machinery (:func:`cosserat.calibration.single.rank_models`,
:class:`~cosserat.calibration.single.Ranking`, :func:`~cosserat.analysis.fitting.moving_wall`)
is here, so that moving validation onto another fitting engine changes this module only. The
rest of validation sees :class:`RunFits` and :class:`FitSummary`: plain numbers, the fitted
velocity, the fitted spin as the run's analysis would measure it
(:mod:`~cosserat.studies.validate.forward`, which reads the fitted profile), and the warnings
a referee asks for.

**Correlated bins.** A run's velocity bins are not independent: the fits, their chi^2, AIC,
BIC and Akaike weights use the calibration engine's error model (``calibration.noise``: AR(1)
correlation between neighbouring bins) with the run's lag-1 correlation of u
(:func:`bin_correlation`: the sidecar's ``bin_correlation.u``, else estimated from the profile
as ``cosserat calibrate`` does). Each fit reports rho and the effective number of bins
``n (1 - rho)/(1 + rho)`` beside its chi^2, and :meth:`RunFits.weight_notes` the Akaike
weights with the correlation and with independent bins (each model fitted again with rho = 0,
as validate fitted before it took the correlation into account). The warnings:

* **misfit**: with the data's standard errors, a fit with p(chi^2, n - k) < :data:`P_SIGNIFICANT`
  misses the data; the warning says by how much and where it misses most (in the creep tail
  where the measured u < :data:`~cosserat.studies.validate.measures.BAND_U`, or in the band);
* **pinned**: every material or wall parameter with a fit range that the fit held at its
  declared default, named with its value;
* **fixed from the run's stresses** (:func:`cosserat_fix`, a note, not a warning): on a plane
  run that carries its stresses, the Cosserat fit does not search phi or the moving wall's
  delta, which the stresses measure, but fixes them as the spin scan does
  (:func:`~cosserat.studies.validate.spin_scan.angles`): the model's shear stress over the
  moving wall's normal stress is uniform, ``T = |sigma_yx|/N`` (eqn-nd_xmom), and equals
  ``sin phi`` at a fully rough wall (eqn-nd_bc2, eqn-bc_fullyrough), so sin phi is ``T`` of the
  material's runs whose two walls are fully rough, pooled, and a smoother wall's ``tan delta``
  its wall kind's ``T``, pooled (:mod:`~cosserat.studies.validate.stresses`: ``T`` measured by
  the moving wall's contact ratio, the band's ``T`` the cross-check; a consistency test and the
  PDG scale factor); a fully rough wall has ``tan delta = sin phi``. K and the material length L,
  which the stresses do not give, are fitted (as in the spin scan's joint calibration). The
  band's stress ratio is not a fair estimate of mu(I)'s or NGF's mu_s, and they are not fixed
  from it: mu_s is the ratio where the flow stops (I -> 0), while the band (u >= BAND_U) spans
  the ratios from the wall's ``T`` down to its edge, so its mean is above mu_s in mu(I) (an
  upper bound, not an estimate: fixing it puts mu(I)'s band edge inside the measured band), and
  NGF flows below mu_s by its nonlocal term, so its band ratio does not bound mu_s at all.
  ``fit_angles`` (``cosserat validate --fit-angles``) restores the fits of one profile (phi at
  its declared default, delta and K fitted). A run without its stresses, on another cell, or of
  a material without a fully rough run keeps those fits, and its ``cosserat_fix`` says why.
* **contradicts the measured stress ratio**: the band's |shear|/normal stress ratio of the run
  (:func:`~cosserat.studies.validate.measures.band_stress_ratio`) against the model's own
  (sin phi for the Cosserat model, mu_s for mu(I) and nonlocal fluidity), whether fitted or
  pinned: flagged when they differ by more than :data:`STRESS_SIGMAS` errors of the measured
  ratio and more than :data:`STRESS_RELATIVE` of it (the model's ratio in the band is only
  about its yield value: the relative margin allows for that). Where the stresses fixed the
  Cosserat fit's angles, the comparison is of like with like: the model's ``T`` (the moving
  wall's tan delta, sin phi when fully rough) against the run's own ``T`` measured as the fixed
  one is, on its moving wall (``_shear_contradiction``; its band's ``T`` only where the run
  gives no wall ratio). ``T = tan delta`` holds only at a wall where the material next to it
  yields, i.e. where the wall slips; a wall that holds the material (its first bin moves with
  it) carries any ``T`` up to ``tan delta``. So where the moving wall holds (its first bin's
  slip ``1 - u``, over the wall speed, within :data:`HOLDS_SIGMAS` of its standard error of
  0, as ``measures.FAR_SLIP_SIGMAS`` for the fixed wall), a measured ``T`` below the model's
  is what the wall condition allows and is not flagged (referee 12, point 6: the layer runs'
  rough moving wall, slip 0.009 +- 0.006 and 0.005 +- 0.009, carries T = 0.21 and 0.20
  under sin phi = 0.31); a ``T`` above it is flagged at any wall.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from scipy.stats import chi2 as chi2_dist

from ..._text import significance
from ...analysis.corpus import Run
from ...calibration.noise import RHO_MAX, Correlation, effective_bins, estimate_rho
from ...calibration.single import Ranking, rank_models
from ...errors import CosseratError, ParameterError
from ...model.constitutive import FloatArray
from .measures import BAND_U, FAR_SLIP_SIGMAS, P_SIGNIFICANT, StressRatio

STRESS_SIGMAS = 3.0
"""A model's band stress ratio contradicts the measured one beyond this many errors [-] ..."""
STRESS_RELATIVE = 0.1
"""... and beyond this fraction of the measured ratio [-]."""
HOLDS_SIGMAS = FAR_SLIP_SIGMAS
"""The moving wall holds the material (does not slip) when its first bin's slip ``1 - u``
[V] is within this many of its standard errors of 0 [-]: a measured ``T`` below the model's
``tan delta`` is then allowed (module docstring; the fixed wall's slip rule,
``measures.FAR_SLIP_SIGMAS``)."""

ADMISSIBLE_EDGES = {
    ("cosserat", "roughness", "upper"): "a fully rough wall",
    ("cosserat", "delta", "upper"): "a fully rough wall",
    ("cosserat", "K", "lower"): "K -> 0, a wall without slip",
}
"""Ends of a wall parameter's search range that are the edge of the model's admissible set
(a limit the model reaches, not a search cut the data push past): a fit there still
predicts, so it is not flagged by :attr:`FitSummary.unfit_reason`."""

BAND_RATIO: dict[str, tuple[str, str, Callable[[float], float]]] = {
    "cosserat": ("phi", "sin phi", lambda phi: math.sin(math.radians(phi))),
    "mui": ("mu_s", "mu_s", lambda mu: mu),
    "ngf": ("mu_s", "mu_s", lambda mu: mu),
}
"""Each rheology's stress ratio in a slowly shearing band: (parameter, what, its value)."""


FIT_ANGLES_FREE = ("K", "L")
"""What a Cosserat fit to one profile frees when the run's stresses fix phi and the moving
wall's delta (:func:`cosserat_fix`): the wall's slip K and the material length L, as the spin
scan's joint calibration does."""


@dataclass(frozen=True)
class StressFix:
    """What a run's stresses fix in its Cosserat fit (module docstring), or why nothing.

    Attributes
    ----------
    phi : float or None
        Angle of internal friction [deg] (None: not fixed, ``reason`` says why).
    delta : float or str
        The moving wall's angle of wall friction [deg], or ``"fully-rough"`` (tan delta =
        sin phi).
    sources : mapping of str to str
        Where phi and delta come from.
    T, T_se : float
        The run's T = |sigma_yx| / N from its band bins (the cross-check,
        :func:`~cosserat.studies.validate.stresses.shear_stress`) and its error [-].
    reason : str
        Why nothing is fixed ("" when phi is).
    wall, wall_se : float
        The run's T measured on its moving wall (its contacts' |shear|/normal, the estimator,
        :func:`~cosserat.studies.validate.stresses.wall_ratio`) and its error [-]; NaN where
        the run does not give it.
    model_se : float
        The error of the fixed model's T (:attr:`tan_delta`): the pooled sin phi's or the wall
        kind's pooled tan delta's [-].
    slip, slip_se : float
        The moving wall's slip, ``1 - u`` of the run's bin nearest it (u over the wall speed),
        and its standard error [-]; NaN where the run does not give it.
    """

    phi: float | None = None
    delta: float | str = "fully-rough"
    sources: dict[str, str] = field(default_factory=dict)
    T: float = math.nan
    T_se: float = math.nan
    reason: str = ""
    wall: float = math.nan
    wall_se: float = math.nan
    model_se: float = 0.0
    slip: float = math.nan
    slip_se: float = math.nan

    @property
    def holds(self) -> bool:
        """Whether the moving wall holds the material: its first bin's slip within
        :data:`HOLDS_SIGMAS` standard errors of 0 (False where the slip is not measured)."""
        return (
            math.isfinite(self.slip)
            and math.isfinite(self.slip_se)
            and self.slip_se > 0.0
            and abs(self.slip) <= HOLDS_SIGMAS * self.slip_se
        )

    @property
    def tan_delta(self) -> float:
        """The fixed model's T: tan delta of the moving wall (sin phi when fully rough) [-];
        NaN when nothing is fixed."""
        if self.phi is None:
            return math.nan
        if self.delta == "fully-rough":
            return math.sin(math.radians(self.phi))
        return math.tan(math.radians(float(self.delta)))

    def values(self) -> dict[str, float | str]:
        """The problem's values: ``phi`` and ``delta`` (empty when nothing is fixed)."""
        return {} if self.phi is None else {"phi": self.phi, "delta": self.delta}

    def text(self) -> str:
        """One line: what is fixed and from what, or why nothing is."""
        if self.phi is None:
            return f"phi and delta not fixed from the stresses: {self.reason}"
        delta = (
            "delta fully rough (tan delta = sin phi)"
            if self.delta == "fully-rough"
            else f"delta = {float(self.delta):.4g} deg"
        )
        own = []
        if math.isfinite(self.wall):
            own.append(f"{self.wall:.3g} +- {self.wall_se:.2g} on its moving wall")
        if math.isfinite(self.T):
            own.append(
                f"{self.T:.3g} +- {self.T_se:.2g} from its band's |sigma_yx|/N (the cross-check)"
            )
        mine = f"; this run's T = |sigma_yx|/N: {', '.join(own)}" if own else ""
        t = self.wall if math.isfinite(self.wall) else self.T
        if self.holds and math.isfinite(t) and t < self.tan_delta:
            mine += (
                f"; the moving wall holds the material (its first bin's slip {self.slip:.2g} "
                f"+- {self.slip_se:.2g} of the wall speed, within {HOLDS_SIGMAS:g} se of 0), so "
                f"T = {t:.3g} below tan delta = {self.tan_delta:.3g} is what the wall condition "
                "allows (T = tan delta only where the material at the wall yields), not a "
                "contradiction"
            )
        return (
            f"fixed from the run's stresses (not fitted): phi = {self.phi:.4g} deg "
            f"({self.sources.get('phi', '')}); {delta} ({self.sources.get('delta', '')})" + mine
        )


def cosserat_fix(run: Run, runs: Sequence[Run]) -> StressFix:
    """phi and the moving wall's delta of ``run``'s Cosserat fit from the stresses (module
    docstring): :func:`~cosserat.studies.validate.spin_scan.angles` with ``runs``, the corpus
    (phi from its material's fully rough runs); the run itself must measure its T, on its
    moving wall (the estimator) or in its band (the cross-check; NaN where it has no band
    stress bins). Never raises: where the stresses fix nothing, the result's ``reason`` says
    why."""
    from .spin_scan import angles
    from .stresses import ShearStress, shear_stress, wall_ratio

    if run.cell != "plane":
        return StressFix(
            reason=f"a {run.cell} run (the relations T = sin phi, tan delta are plane shear's)"
        )
    w, w_se = wall_ratio(run) or (math.nan, math.nan)
    try:
        t = shear_stress(run)
    except CosseratError:
        if not math.isfinite(w):
            return StressFix(
                reason="the run carries neither its moving wall's stress ratio nor its band's "
                "stresses"
            )
        t = ShearStress(math.nan, math.nan, 0, math.nan)
    try:
        a = angles(run, runs)
    except CosseratError as exc:
        return StressFix(reason=" ".join(str(exc).split()))
    moving = a.roughness["moving"]
    delta: float | str = "fully-rough" if moving >= 1.0 else a.delta("moving")
    sources = {"phi": a.phi_source, "delta": a.delta_source["moving"]}
    model_se = a.tan_delta_se.get("moving")
    if model_se is None:  # fully rough: sin phi's error
        model_se = math.radians(a.phi_se) * math.cos(math.radians(a.phi))
    slip, slip_se = moving_wall_slip(run)
    return StressFix(a.phi, delta, sources, t.value, t.stderr, "", w, w_se, model_se, slip, slip_se)


def moving_wall_slip(run: Run) -> tuple[float, float]:
    """The moving wall's slip, ``1 - u`` of the run's bin nearest it (u over the wall speed),
    and its standard error [-] (NaN, NaN without the bins' errors)."""
    m = run.measured()
    if m.u_err is None or not len(m.distance_d):
        return math.nan, math.nan
    i = int(np.argmin(m.distance_d))
    return 1.0 - float(m.u_over_uw[i]), float(m.u_err[i])


@dataclass
class FitSummary:
    """One model's fit to a run, as validation uses it."""

    model: str
    ok: bool
    message: str
    chi2: float | None
    dof: int
    reduced_chi2: float | None
    p_value: float | None
    parameters: dict[str, tuple[float, float | None]]
    pinned: dict[str, float]
    band_ratio: tuple[str, float, bool] | None
    warnings: list[str]
    contradiction: str = ""
    """The stress contradiction's warning ("" when the fit agrees with the measured ratio)."""
    at_bound: dict[str, str] = field(default_factory=dict)
    """Free wall parameters that ended at an end of their search range that is not an edge of
    the admissible set (:data:`ADMISSIBLE_EDGES`), name -> "lower" or "upper"."""
    rho: float = 0.0
    """Lag-1 correlation of the bins' errors the fit used [-] (0: independent)."""
    n_bins: int = 0
    """Bins fitted."""
    unidentified: dict[str, str] = field(default_factory=dict)
    """Free parameters the data do not determine (the engine's identifiability rule, or at a
    bound), name -> why: they have no error."""
    fixed: dict[str, tuple[float | str, str]] = field(default_factory=dict)
    """Parameters fixed from the run's stresses (:func:`cosserat_fix`), name -> (value
    [deg], source)."""

    @property
    def bounded(self) -> list[str]:
        """Free parameters at an end of their search range that is not an edge of the
        admissible set (:data:`ADMISSIBLE_EDGES`), or on the edge of the region where the
        model has a solution."""
        out = set(self.at_bound)
        for k, why in self.unidentified.items():
            side = (
                "lower" if "at the lower end" in why else "upper" if "at the upper" in why else ""
            )
            if (
                side and (self.model, k, side) not in ADMISSIBLE_EDGES
            ) or "edge of the region" in why:
                out.add(k)
        return sorted(out)

    @property
    def effective_bins(self) -> float:
        """Bins' worth of independent information, ``n (1 - rho)/(1 + rho)`` [-]."""
        return effective_bins(self.n_bins, self.rho)

    @property
    def significance(self) -> str:
        """The chi^2's p-value, or z and chi^2/dof below 1e-6 (``cosserat._text.significance``);
        "" without absolute errors."""
        if self.chi2 is None or self.p_value is None or self.dof < 1:
            return ""
        return significance(self.chi2, self.dof)

    @property
    def unfit_reason(self) -> str:
        """Why this fit cannot supply a prediction to test the model ("" when it can): it
        contradicts the measured stress ratio, or a wall parameter sits at a bound."""
        why = []
        if self.contradiction:
            what = self.band_ratio[0] if self.band_ratio else "its stress ratio"
            ratio = f" = {self.band_ratio[1]:.3g}" if self.band_ratio else ""
            where = "T" if what == "T = tan delta" else "band stress ratio"
            why.append(f"its {what}{ratio} contradicts the measured {where}")
        if self.at_bound:
            why.append(
                "wall parameter at a bound ("
                + ", ".join(f"{k} at its {b} end" for k, b in sorted(self.at_bound.items()))
                + ")"
            )
        return f"the {self.model} fit: " + " and ".join(why) if why else ""

    def to_dict(self) -> dict[str, Any]:
        return {
            "model": self.model,
            "p_value": self.p_value,
            "significance": self.significance,
            "bin_correlation": self.rho,
            "effective_bins": self.effective_bins,
            "unidentified": self.unidentified,
            "pinned": self.pinned,
            "fixed_from_stresses": {
                k: {"value": v, "source": src} for k, (v, src) in self.fixed.items()
            },
            "band_stress_ratio": None
            if self.band_ratio is None
            else {
                "what": self.band_ratio[0],
                "value": self.band_ratio[1],
                "pinned": self.band_ratio[2],
            },
        }


@dataclass
class RunFits:
    """Every model's fit to one run's velocity (a wrapper of the fitting engine's result)."""

    ranking: Ranking
    summaries: list[FitSummary] = field(default_factory=list)
    correlation: Correlation = field(default_factory=lambda: Correlation(0.0, "given"))
    """The lag-1 correlation of the bins' errors the fits used (:func:`bin_correlation`)."""
    independent_weights: dict[str, float] = field(default_factory=dict)
    """Akaike weights of the same models fitted with independent bins (empty when rho = 0)."""

    @property
    def models(self) -> list[str]:
        """The models fitted successfully, best (lowest AIC) first."""
        return [f.model for f in self.ranking.ranked if f.ok]

    @property
    def best(self) -> str | None:
        b = self.ranking.best
        return None if b is None else b.model

    def summary(self, model: str) -> FitSummary | None:
        return next((s for s in self.summaries if s.model == model), None)

    def curve(self, model: str, distance_d: FloatArray) -> FloatArray:
        """The fitted u/u_wall at distances from the moving wall [d]."""
        return self._fit(model).curve(np.asarray(distance_d, dtype=float))

    def spin_departure(self, model: str, run: Run, stencil: str = "analysis") -> FloatArray:
        """The fitted model's omega - half vorticity as the run's analysis would report it
        (:func:`~cosserat.studies.validate.forward.forward_departure`: bin averages and the
        analysis' stencil, the first layer at each wall by ``stencil``), per row of the run,
        in its units (omega d / V) and sign. A rheology without a grain spin of its own turns
        with the material: its point departure is 0, its measured one is not (the binning
        and the stencil)."""
        from .forward import forward_departure

        return forward_departure(self._fit(model).profile, run, stencil)

    def spin_null(self, model: str, run: Run, stencil: str = "analysis") -> FloatArray:
        """What the run's analysis would report for the fitted model's velocity if the grains
        turned with the material (omega = half the vorticity at every point), per row
        (:func:`~cosserat.studies.validate.forward.null_departure`) [-]."""
        from .forward import null_departure

        return null_departure(self._fit(model).profile, run, stencil)

    def spin_point(self, model: str, run: Run) -> FloatArray:
        """The fitted model's point omega - half vorticity (analytic derivatives) at the run's
        bin centres, per row, in its units and sign [-]."""
        from .forward import bin_edges, model_fields

        bins = bin_edges(run)
        out = np.empty(bins.centre.size)
        out[bins.order] = model_fields(self._fit(model).profile, run).point_departure(bins.centre)
        return out

    def weight_notes(self) -> list[str]:
        """The Akaike weights with the bins' correlation and with independent bins (one line;
        none when the bins are taken as independent)."""
        if self.correlation.rho <= 0.0 or not self.independent_weights:
            return []
        n = self.ranking.measured.n

        def text(w: dict[str, float]) -> str:
            return ", ".join(f"{m} {w.get(m, 0.0):.3f}" for m in self.models)

        return [
            f"Akaike weights with the bins' correlation (rho = {self.correlation.rho:.2f}, "
            f"{self.correlation.source}; {effective_bins(n, self.correlation.rho):.1f} "
            f"effective bins of {n}): {text(self.ranking.weights())}; with independent bins "
            f"(rho = 0, each model fitted again): {text(self.independent_weights)}"
        ]

    def to_dict(self) -> dict[str, Any]:
        """The fitting engine's record, each fit with its p-value, pinned parameters, band
        stress ratio and every warning of :func:`fit_run`; the bins' correlation and the
        Akaike weights with independent bins."""
        out = self.ranking.to_dict()
        out["bin_correlation"] = {
            "rho": self.correlation.rho,
            "source": self.correlation.source,
            "effective_bins": effective_bins(self.ranking.measured.n, self.correlation.rho),
        }
        out["akaike_weights_independent_bins"] = dict(self.independent_weights)
        for entry in out["fits"]:
            s = self.summary(entry["model"])
            if s is not None:
                entry.update(s.to_dict())
                entry["warnings"] = list(s.warnings)
        return out

    def to_text(self) -> str:
        return self.ranking.to_text()

    def _fit(self, model: str) -> Any:
        for f in self.ranking.fits:
            if f.model == model and f.ok:
                return f
        raise KeyError(model)


def fit_run(
    run: Run,
    models: Sequence[str] | None,
    grid: int,
    stress: StressRatio | None,
    independent_bins: bool = False,
    fix: StressFix | None = None,
) -> RunFits:
    """Fit ``models`` (default: every one defined on the run's cell) to the run's velocity;
    with ``independent_bins`` and correlated bins, fit them again with independent bins for
    the notes' comparison of Akaike weights (it doubles to triples the fits' cost).

    ``fix``: what the run's stresses fix in the Cosserat fit (:func:`cosserat_fix`): phi and
    the moving wall's delta held at its values, :data:`FIT_ANGLES_FREE` fitted, and the stress
    check made on ``T``; None or a fix with ``phi`` None: the fits of one profile
    (:data:`~cosserat.calibration.single.SINGLE_RUN_FREE`, phi at its declared default).

    Raises
    ------
    CosseratError
        The run cannot be fitted (the message says why).
    """
    names = models
    if names is not None:
        from ...routes import cells_for

        names = [m for m in names if run.cell in cells_for(m)]
    measured = run.measured()
    corr = bin_correlation(run)
    fixing = fix is not None and fix.phi is not None
    given: dict[str, Any] = (
        {"model_parameters": {"cosserat": fix.values()}, "free": {"cosserat": FIT_ANGLES_FREE}}
        if fixing and fix is not None
        else {}
    )
    ranking = rank_models(
        measured, run.cell_parameters(), names, grid=grid, bin_correlation=corr.rho, **given
    )
    out = RunFits(ranking, correlation=corr)
    if independent_bins and corr.rho > 0.0:
        out.independent_weights = _independent_weights(run, names, grid, measured, given)
    for f in ranking.fits:
        if not f.ok:
            out.summaries.append(
                FitSummary(
                    f.model, False, f.message, None, 0, None, None, {}, {}, None, list(f.warnings)
                )
            )
            continue
        dof = f.n - f.k
        p = (
            float(chi2_dist.sf(f.chi2, dof))
            if f.absolute_sigma and f.chi2 is not None and dof > 0
            else None
        )
        warnings = list(f.warnings)
        if p is not None and p < P_SIGNIFICANT:
            warnings.append(_misfit_text(f, measured, dof, corr.rho))
        values = f.problem.values()
        free = {k for k, e in f.parameters.items() if e.free}
        declared = f.problem.declared()
        fixed: dict[str, tuple[float | str, str]] = {}
        if f.model == "cosserat" and fix is not None:
            if fixing:
                fixed = {k: (v, fix.sources.get(k, "")) for k, v in fix.values().items()}
            warnings.append(fix.text())
        pinned = {
            k: float(v)
            for k, v in values.items()
            if k in declared
            and k not in fixed
            and declared[k].role in ("material", "wall")
            and declared[k].numeric
            and declared[k].fit_range is not None
            and k not in free
            and isinstance(v, int | float)
        }
        if pinned:
            warnings.append(
                "pinned (held at the declared default, not fitted): "
                + ", ".join(f"{k} = {v:.4g}" for k, v in pinned.items())
            )
        band, contradiction = None, ""
        at_bound = {
            k: str(e.at_bound)
            for k, e in f.parameters.items()
            if e.free
            and e.role == "wall"
            and e.at_bound
            and not e.derived
            and (f.model, k, e.at_bound) not in ADMISSIBLE_EDGES
        }
        if fixed and fix is not None:
            band = ("T = tan delta", fix.tan_delta, True)
            text = _shear_contradiction(fix)
            if text:
                warnings.append(text)
                contradiction = text
        elif f.model in BAND_RATIO and BAND_RATIO[f.model][0] in values:
            key, what, ratio = BAND_RATIO[f.model]
            band = (what, float(ratio(float(values[key]))), key in pinned)
            text = _stress_contradiction(
                key, float(values[key]), what, band[1], key in pinned, stress, f.model
            )
            if text:
                warnings.append(text)
                contradiction = text
        params = {k: (e.value, e.stderr) for k, e in f.parameters.items() if e.free}
        out.summaries.append(
            FitSummary(
                f.model,
                True,
                "",
                f.chi2,
                dof,
                f.reduced_chi2,
                p,
                params,
                pinned,
                band,
                warnings,
                contradiction,
                at_bound,
                corr.rho,
                f.n,
                {k: e.reason for k, e in f.parameters.items() if e.free and e.stderr is None},
                fixed,
            )
        )
    return out


def bin_correlation(run: Run) -> Correlation:
    """The lag-1 correlation of a run's velocity bins' errors, as ``cosserat calibrate``
    takes it (``calibration.noise``): the sidecar's ``bin_correlation.u`` (measured from the
    run's time blocks), clipped to ``[0, RHO_MAX]``; without it, estimated from the profile's
    second differences (:func:`~cosserat.calibration.noise.estimate_rho`; rho = 0 without the
    bins' errors)."""
    given = run.meta.get("bin_correlation")
    value = given.get("u") if isinstance(given, dict) else None
    if isinstance(value, int | float) and math.isfinite(value):
        rho = min(max(float(value), 0.0), RHO_MAX)
        source = "metadata" if rho == value else f"metadata {float(value):.3g}, clipped"
        return Correlation(rho, source)
    m = run.measured()
    if m.u_err is None:
        return Correlation(0.0, "no errors given")
    order = np.argsort(m.distance_d, kind="stable")
    return estimate_rho(np.asarray(m.u_over_uw)[order], np.asarray(m.u_err)[order])


def _independent_weights(
    run: Run, names: Sequence[str] | None, grid: int, measured: Any, given: dict[str, Any]
) -> dict[str, float]:
    """Akaike weights of the same models fitted with independent bins (rho = 0; the same
    fits, starts, design and fixed values as the correlated ones): what the weights are if
    the bins' correlation is ignored."""
    ranking = rank_models(measured, run.cell_parameters(), names, grid=grid, **given)
    return {m: float(w) for m, w in ranking.weights().items()}


def try_fit_run(
    run: Run,
    models: Sequence[str] | None,
    grid: int,
    stress: StressRatio | None,
    independent_bins: bool = False,
    fix: StressFix | None = None,
) -> tuple[RunFits | None, str]:
    """:func:`fit_run`, or None and the reason in one line."""
    try:
        return fit_run(run, models, grid, stress, independent_bins, fix), ""
    except CosseratError as exc:
        return None, " ".join(str(exc).split())


def _misfit_text(fit: Any, measured: Any, dof: int, rho: float) -> str:
    # the comparison's residuals are data - model; the text says model - data
    model_minus_data = -np.asarray(fit.comparison.residuals, dtype=float)
    z = model_minus_data / np.asarray(measured.u_err, dtype=float)
    u = np.asarray(measured.u_over_uw, dtype=float)
    tail = u < BAND_U
    worst = int(np.argmax(np.abs(z)))
    where = f"in the creep tail (u < {BAND_U:g})" if tail[worst] else "in the band"
    share = ""
    if np.any(tail):
        share = (
            f"; the creep tail (u < {BAND_U:g}, {int(tail.sum())} bins) holds "
            f"{float(np.sum(z[tail] ** 2)) / max(float(np.sum(z**2)), 1e-300):.0%} of the "
            "independent-bin chi^2"
        )
    sig = significance(fit.chi2, dof)
    bins = (
        f", bins correlated with rho = {rho:.2f}, {effective_bins(measured.n, rho):.1f} "
        f"effective bins of {measured.n}"
        if rho > 0.0
        else ""
    )
    return (
        f"misfit: chi^2 = {fit.chi2:.4g} for {dof} degrees of freedom{bins} "
        f"({sig}{' <' if sig.startswith('p = ') else '; p <'} {P_SIGNIFICANT:g}); it misses "
        f"most {where}, "
        f"{measured.distance_d[worst]:.3g} d from the moving wall (model - data = "
        f"{z[worst]:+.3g} se){share}"
    )


FLOWS_ABOVE = {"mui": "mu(I) needs mu >= mu_s to flow"}
"""Why a model's mu_s above the band's measured stress ratio contradicts the run: a local
rheology flows only at a stress ratio of at least mu_s (NGF flows below it through its
nonlocal term, so it has no such clause)."""


def _stress_contradiction(
    key: str,
    value: float,
    what: str,
    ratio: float,
    pinned: bool,
    stress: StressRatio | None,
    model: str = "",
) -> str:
    if stress is None:
        return ""
    diff = abs(ratio - stress.value)
    if diff <= STRESS_SIGMAS * stress.stderr or diff <= STRESS_RELATIVE * stress.value:
        return ""
    how = "pinned" if pinned else "fitted"
    if what == key:  # mu(I)'s and NGF's ratio is mu_s itself (referee 14, point 2 (iii))
        above = ratio > stress.value
        why = FLOWS_ABOVE.get(model, "") if above else ""
        return (
            f"contradicts the measured stress: its {how} {key} = {value:.4g} "
            f"{'exceeds' if above else 'lies below'} the band's measured |shear|/normal stress "
            f"ratio {stress.value:.3g} +- {stress.stderr:.2g} ({stress.bins} bins) by "
            f"{diff / stress.stderr:.1f} errors" + (f", where {why}" if why else "")
        )
    return (
        f"contradicts the measured stress: {key} = {value:.4g} ({how})"
        + (f" gives {what} = {ratio:.3g}" if what != key else "")
        + ", but the run's |shear|/normal stress ratio in the band is "
        f"{stress.value:.3g} +- {stress.stderr:.2g} ({stress.bins} bins), "
        f"{diff / stress.stderr:.1f} errors away"
    )


def _shear_contradiction(fix: StressFix) -> str:
    """The fixed Cosserat model's T against the run's own, measured as the fixed T is (module
    docstring): the run's moving-wall ratio where it gives one (the estimator the angles are
    fixed from, :mod:`~cosserat.studies.validate.stresses`), else its band's T; "" when they
    agree within :data:`STRESS_SIGMAS` errors (the run's and the fixed T's in quadrature) or
    :data:`STRESS_RELATIVE` of the run's T, and "" when the run's T is below the model's at a
    moving wall that holds the material (:attr:`StressFix.holds`: its first bin's slip within
    :data:`HOLDS_SIGMAS` se of 0): ``T = tan delta`` is the condition of a wall where the
    material next to it yields, and a wall that does not slip carries any ``T`` up to ``tan
    delta``. A ``T`` above the model's is flagged whether the wall holds or not."""
    model = fix.tan_delta
    on_wall = math.isfinite(fix.wall)
    t, t_se = (fix.wall, fix.wall_se) if on_wall else (fix.T, fix.T_se)
    se = math.hypot(t_se, fix.model_se)
    diff = abs(model - t)
    if diff <= STRESS_SIGMAS * se or diff <= STRESS_RELATIVE * t:
        return ""
    if t < model and fix.holds:
        return ""
    where = "moving wall's contacts give" if on_wall else "band gives"
    return (
        f"contradicts the measured stress: the fixed angles give T = tan delta = {model:.3g} "
        f"+- {fix.model_se:.2g} (the shear stress over the moving wall's normal stress), but "
        f"the run's {where} T = {t:.3g} +- {t_se:.2g}, {diff / se:.1f} errors away"
    )


# --------------------------------------------------------------------------- gap series
SERIES_STARTS: int | None = None
"""Latin-hypercube starts of a series' joint calibration besides the declared defaults: None,
the engine's default design (``4 k + 4``), so that it is the calibration ``cosserat calibrate
RUNS --models MODEL`` gives. One start is not enough: on the shipped smooth-wall series mu(I)
then ends in a local minimum (chi^2 7851 against 5213)."""
CLAIMED_MODEL = "cosserat"
"""The model the Delta claims are about; the others are its alternatives, which also get a
per-series best fit (:func:`calibrate_best`)."""
BEST_FIELDS = ("u", "wall_ratio")
"""The fields of an alternative's per-series best fit (:func:`calibrate_best`): the velocity,
which Delta is read from (as the per-run u-only fits), and the moving wall's stress ratio T =
|sigma_yx|/N that each run measures from the wall's contacts (``calibration.data``'s
``wall_ratio``, one datum per run with its error), against the model's own T at the moving
wall (its sigma_yx/sigma_yy there: mu(I) at the wall for mu(I), the root NGF's solver finds
so that the wall moves at V). On u alone a fit may put T anywhere the velocity does not see
(on the shipped rough series NGF's mu_s went to 1.2, T >= 1.2 against the measured 0.31): a
fit that contradicts a measured field is not the alternative at its best."""
BEST_STARTS = 100
"""Latin-hypercube starts of a per-series best fit (:func:`calibrate_best`) besides the declared
defaults. The engine's default design (``4 k + 4``) is not enough once T is held: on the
shipped rough series mu(I)'s fit on u and T has two basins, I_0 ~ 0.4 (no band at the bins,
chi^2 957) and a narrow valley along the measured T, mu_s = 0.20, I_0 = 0.0023 (chi^2 590),
which 12 starts missed and 40 and 100 found with either design seed; NGF's and the smooth
series' fits are the same at 12, 40 and 100 starts. A start costs one solve per run."""
EDGE_MARGIN = 2.0
"""How many times above the solver's double-precision edge a per-series best fit starts NGF's
b (:func:`solver_edges`) [-]: at the edge the profile is still good to about 1e-9
(:data:`~cosserat.model.rheologies.ngf.NGF_EXCESS_RTOL`), but a finite-difference step of the
fit's Jacobian or of Delta's error must not cross it."""
CURVE_POINTS = 9
"""Points of each model's Delta curve across the series' gaps (for the figure)."""
CURVE_SPAN = (1.25, 2.0)
"""The curve runs from the smallest gap over the first factor to the largest times the
second [-]."""
REACH_SPAN = 64.0
"""The claims' model's curve is carried on beyond the figure's (``SeriesCalibration.reach``) to
the series' largest gap times this [-]: where its own slope reaches the claimed limits
(referee 13, point 3: on the round-13 corpus the slope over a factor 4 first comes within
0.05 of the rough limit 1/3 at H/d = 55 and of the smoother limit 0 at 271)."""
REACH_POINTS = 16
"""Points of the reach beyond the curve's largest gap (a factor 32 in 15 steps of 1.26) [-]."""


@dataclass
class SeriesCalibration:
    """One model calibrated jointly on the runs of a material (:func:`calibrate_material`),
    and its Delta at one gap series' runs.

    Attributes
    ----------
    model : str
    status, message : str
        ``"ok"``, or ``"failed"`` and why.
    summary : dict
        Parameters (value, stderr, free, reason), chi2, dof, p_value, warnings; ``material``
        (the engine's label), ``runs`` (every run calibrated, of every series of the material)
        and ``wall_kinds`` (wall kind -> its runs).
    predicted : dict of run name to (Delta, se)
        Delta of the calibrated model at each run's gap, bins and rate [d], with its error from
        the calibration's covariance [d].
    curve : (gaps, Delta)
        Delta on a grid of H/d and at the series' runs (their ``predicted`` values, so that
        the curve passes through them) [-], [d]; None where the model gives none.
    why : dict
        Why the model gives no Delta, by run name (``predicted``) and by curve gap (its
        ``f"{gap:.6g}"``): ``_delta``'s reasons.
    resolved_above : dict
        Like ``why``: the distance of the second bin from the moving wall [d] at that run or
        gap; a Delta at or below it is not resolved by the bins (the data's rule,
        ``measures.measured_thickness``): it is set by where the first bins fall.
    """

    model: str
    status: str
    message: str = ""
    summary: dict[str, Any] = field(default_factory=dict)
    predicted: dict[str, tuple[float | None, float | None]] = field(default_factory=dict)
    curve: tuple[tuple[float, ...], tuple[float | None, ...]] = ((), ())
    why: dict[str, str] = field(default_factory=dict)
    resolved_above: dict[str, float] = field(default_factory=dict)
    best: SeriesCalibration | None = None
    """An alternative's per-series best fit (:func:`calibrate_best`), None for the claims'
    model or where it was not made."""
    reach: tuple[tuple[float, ...], tuple[float | None, ...]] = ((), ())
    """The claims' model's Delta beyond the curve (``_series_reach``), as ``curve``; empty for
    the other models."""


def _series_start(model: str, keys: set[str], fits: Sequence[RunFits | None]) -> dict[str, float]:
    """The median of the per-run fits' values of the calibration's parameters (by key)."""
    values: dict[str, list[float]] = {}
    for rf in fits:
        s = None if rf is None else rf.summary(model)
        if s is None or not s.ok:
            continue
        for k, (v, _) in s.parameters.items():
            if k in keys and isinstance(v, int | float) and math.isfinite(v):
                values.setdefault(k, []).append(float(v))
    return {k: float(np.median(v)) for k, v in values.items()}


def _probe(template: Any, name: str, gap_d: float, s: FloatArray, I_w: float | None) -> Any:
    """A run of the calibration frame like ``template`` at gap H/d = ``gap_d`` whose one field
    is ``u`` at the distances ``s`` [d] (values unused)."""
    import dataclasses

    from ...calibration.data import Field

    cell = dict(template.cell_values)
    cell["eps"] = 1.0 / gap_d
    u = Field("u", np.asarray(s, dtype=float), np.zeros(len(s)), np.ones(len(s)))
    return dataclasses.replace(
        template, name=name, gap_d=gap_d, cell_values=cell, I_w=I_w, fields={"u": u}
    )


def _delta(model: Any, probe: Any, values: Any, u0: float, f: float) -> tuple[float | None, str]:
    """The model's Delta at the probe's bins [d], or None and why ("" with a value)."""
    from ...calibration.models import SOLVE_ERRORS
    from .measures import thickness_of

    try:
        u = model.predict(probe, values, ["u"])["u"]
    except SOLVE_ERRORS as exc:
        text = " ".join(str(exc).split())
        if isinstance(exc, ParameterError) and "double precision" in text:
            # the solver refuses a rate whose driving excess it cannot resolve: the model's
            # flow exists (NGF and mu(I) flow at every I_w > 0), the solver cannot compute it
            return None, (
                "not computed: the solver's double-precision limit, not the model's (which "
                "flows at every I_w > 0): " + text
            )
        return None, "no solution: " + text
    if not np.all(np.isfinite(u)):
        return None, "no solution: a non-finite velocity"
    u = np.asarray(u, dtype=float)
    if u[0] == u0:
        return None, (
            "no band at the bins: the velocity is the far wall's at every bin centre (a band, "
            "if any, lies between the wall and the first bin's centre, or the wall slides over "
            "grains at rest)"
        )
    value = thickness_of(probe.fields["u"].s, u, u0, f)
    if value is None:
        return None, f"the band fills the gap: u does not fall to {f:g} of its first bin's value"
    return value, ""


def curve_key(gap_d: float) -> str:
    """The key of a curve gap in a :class:`SeriesCalibration`'s ``why`` and ``resolved_above``."""
    return f"{gap_d:.6g}"


def _rate(runs: Sequence[Any]) -> Callable[[float], float | None]:
    """I_w at a gap: the power law of the runs' I_w against H/d (least squares in log-log; one
    gap: I_w proportional to d/H), None without I_w."""
    pts = [(r.gap_d, r.I_w) for r in runs if r.I_w is not None and r.I_w > 0.0]
    if not pts:
        return lambda g: None
    lg = np.log([g for g, _ in pts])
    li = np.log([i for _, i in pts])
    if np.ptp(lg) < 1e-6:
        c0, c1 = float(np.mean(li + lg)), -1.0
    else:
        c1, c0 = (float(x) for x in np.polyfit(lg, li, 1))
    return lambda g: float(math.exp(c0 + c1 * math.log(g)))


def material_fix(model: str, runs: Sequence[Run]) -> tuple[dict[str, float], str]:
    """What the stresses fix in a material's joint calibration of ``model``, and a note: for
    the Cosserat model on a plane material, phi (sin phi = T of its runs with both walls fully
    rough, pooled with a consistency test) and every wall kind's roughness (1 for the fully
    rough kind, the pooled tan delta over sin phi for a smoother one):
    :func:`~cosserat.studies.validate.stresses.material_angles`, the function the spin scan's
    shared calibration fixes them with (one material, one phi, one delta per wall kind).
    Nothing otherwise, the note saying why where the model is the Cosserat one."""
    fix, note, _ = _material_fix(model, runs)
    return fix, note


def _material_fix(model: str, runs: Sequence[Run]) -> tuple[dict[str, float], str, dict[str, Any]]:
    """:func:`material_fix` and the pooling's numbers (``results.json``)."""
    from .stresses import material_angles

    if model != "cosserat":
        return {}, "", {}
    if runs[0].cell != "plane":
        return {}, (
            f"phi fitted: a {runs[0].cell} material (the relation sin phi = T is plane shear's)"
        ), {}  # fmt: skip
    try:
        fix, note, numbers = material_angles(runs)
    except CosseratError as exc:
        return {}, "phi fitted: " + " ".join(str(exc).split()), {}
    return (
        fix,
        (
            f"fixed from the stresses (not fitted): {note}; their errors are not propagated into "
            "Delta's; the spin scan's shared calibration is this same call (same data, same "
            "angles) on the runs it scans"
        ),
        numbers,
    )


def calibrate_material(
    runs: Sequence[Run],
    models: Sequence[str] | None,
    series: Sequence[tuple[str, Sequence[Run], float]],
    fits: Sequence[RunFits | None] = (),
    curve: bool = True,
    use_fits: bool = False,
    fix_phi: bool = True,
    best: bool = True,
) -> dict[str, list[SeriesCalibration]]:
    """Each model calibrated jointly on every run of one material (``cosserat calibrate``'s
    engine, :func:`cosserat.calibration.joint.calibrate_model`: material parameters shared by
    every run, wall parameters shared per wall kind, what the metadata give fixed, every
    measured field the model predicts; NGF's A free), and, for each of the material's gap
    series, that one calibration's Delta at the series' runs and on a grid of H/d with the
    series' own wall (its first run the template).

    Parameters
    ----------
    runs : sequence of Run
        The material's runs (plane or Couette; every wall kind).
    models : sequence of str, optional
        Registered rheologies (default: every one the calibration knows on the runs' cell).
    series : sequence of (key, runs, f)
        The gap series that read the calibration: a key, its runs (among ``runs``) and the
        fraction defining its Delta [-].
    fits : sequence of RunFits or None
        The runs' own fits, whose median values start the calibration with ``use_fits``
        (default: the declared defaults, as ``cosserat calibrate`` starts).
    curve : bool
        Also compute each series' curve on a grid of H/d (for the figure).
    fix_phi : bool
        Fix what the stresses measure (:func:`material_fix`: the Cosserat model's phi on a
        plane material), as the per-run fits and the spin scan do; False fits it (``cosserat
        validate --fit-angles``).
    best : bool
        Also make each alternative's per-series best fit (:func:`calibrate_best`; every model
        but :data:`CLAIMED_MODEL`), the ``best`` of its calibrations.

    Returns
    -------
    dict
        Series key -> one :class:`SeriesCalibration` per model (a failed calibration fails
        for every series).

    Raises
    ------
    CosseratError
        A run the calibration cannot take (:func:`cosserat.calibration.data.from_run`).
    """
    from ...calibration.joint import calibrate_model
    from ...calibration.models import Model
    from ...calibration.models import models as make_models
    from .spin_scan import material_data

    runs = sorted(runs, key=lambda r: r.name)  # the spin scan's shared calibration's order
    data = material_data(runs)
    by_name = {rd.name: rd for rd in data}
    cell = runs[0].cell
    chosen = [m for m in make_models(None) if cell in m.cells()]
    if models is not None:
        chosen = [m for m in chosen if m.name in models]
    kinds: dict[str, list[str]] = {}
    for r in runs:
        kind = r.wall.get("kind") if isinstance(r.wall, dict) else None
        kinds.setdefault(str(kind or "unknown wall"), []).append(r.name)
    out: dict[str, list[SeriesCalibration]] = {key: [] for key, _, _ in series}
    for m in chosen:
        keys = {p.key for p in m.parameters()}
        start = _series_start(m.name, keys, fits) if use_fits else None
        fix, fix_note, fix_numbers = _material_fix(m.name, runs) if fix_phi else ({}, "", {})
        if start is not None:
            start = {k: v for k, v in start.items() if k not in fix}
        mc = calibrate_model(
            Model(m.name), data, None, fix=fix or None, start=start, starts=SERIES_STARTS
        )
        if not mc.ok:
            for key, _, _ in series:
                out[key].append(SeriesCalibration(m.name, "failed", " ".join(mc.message.split())))
            continue
        s, opt = mc.internal
        theta = opt.theta
        cov = _covariance(mc)
        summary = {
            **_summary(mc),
            "material": data[0].material,
            "runs": [r.name for r in runs],
            "wall_kinds": {k: list(v) for k, v in kinds.items()},
            "fixed": dict(fix),
            "fixed_note": fix_note,
            "stresses": fix_numbers,
        }
        for key, members, f in series:
            rds = [by_name[r.name] for r in members]
            predicted, grid, why, floor = _series_delta(s, theta, cov, members, rds, f, curve)
            cal = SeriesCalibration(m.name, "ok", "", dict(summary), predicted, grid, why, floor)
            if curve and m.name == CLAIMED_MODEL:
                cal.reach = _series_reach(s, theta, members, rds, f, cal.why)
            if best and m.name != CLAIMED_MODEL:
                try:
                    cal.best = calibrate_best(m.name, members, rds, f, curve)
                except CosseratError as exc:
                    cal.best = SeriesCalibration(m.name, "failed", " ".join(str(exc).split()))
            out[key].append(cal)
    return out


def _summary(mc: Any) -> dict[str, Any]:
    """What a calibration gave (:class:`SeriesCalibration`'s ``summary``, without what it was
    made on)."""
    return {
        "parameters": {
            n: {
                "value": e.value,
                "stderr": e.stderr_scaled,
                "free": e.free,
                "derived": e.derived,
                "shared": e.shared,
                "unit": e.unit,
                "reason": e.reason,
                "at_bound": e.at_bound,
                "fit_range": None if e.fit_range is None else list(e.fit_range),
            }
            for n, e in mc.parameters.items()
        },
        "fields": list(mc.fields_used),
        "chi2": mc.chi2,
        "dof": mc.dof,
        "p_value": mc.p_value,
        "log10_p_value": mc.log10_p_value,
        "unidentified": [d.describe() for d in mc.flat],
        "warnings": list(mc.warnings),
    }


def _covariance(mc: Any) -> FloatArray:
    """A calibration's parameter covariance in the fit's coordinates, scaled by sqrt(chi^2/dof)
    where it misfits (zeros without one)."""
    _, opt = mc.internal
    scale = max((e.scale for e in mc.parameters.values()), default=1.0)
    if mc.covariance is None:
        return np.zeros((opt.theta.size, opt.theta.size))
    return np.asarray(mc.covariance, dtype=float) * scale**2


def _ranged_model(name: str, ranges: dict[str, tuple[float, float]]) -> Any:
    """The calibration model ``name`` (:class:`cosserat.calibration.models.Model`) with the
    search ranges of the parameters in ``ranges`` (key -> (lo, hi)) replaced."""
    import dataclasses

    from ...calibration.models import Model

    class Ranged(Model):
        def parameters(self) -> tuple[Any, ...]:
            return tuple(
                dataclasses.replace(
                    p, declared=dataclasses.replace(p.declared, fit_range=ranges[p.key])
                )
                if p.key in ranges
                else p
                for p in super().parameters()
            )

    return Ranged(name)


def solver_edges(
    model: str, data: Sequence[Any], runs: Sequence[Run], curve: bool = True
) -> tuple[dict[str, tuple[float, float]], str, dict[str, Any]]:
    """The search ranges a per-series best fit (:func:`calibrate_best`) takes away from the
    solver's numerical edge, with a note saying why, and the numbers (``results.json``).

    NGF's solver needs the stress level's excess over mu_s to keep
    :data:`~cosserat.model.rheologies.ngf.NGF_EXCESS_RTOL` of mu_s (``I_w >= 1e-7 mu_s/b``):
    at the slowest rate the series needs (its runs' I_w and, with ``curve``, the curve's largest
    gap, ``_rate``) and mu_s at the top of its search range, b's search range starts
    :data:`EDGE_MARGIN` times above that edge. The model itself has a flow at every b > 0; b
    -> 0 is its rate-independent limit (T - mu_s -> 0), which the profile approaches as
    b I_w -> 0 (on the shipped rough runs u moves by at most 0.0025 V from b = 0.0151 to
    0.00151, mu_s = 1.2, A = 1.54). Nothing for mu(I), whose
    edge (``I_w >= 1e-7 mu_s I_0/(mu_2 - mu_s)``) lies outside its search ranges at these rates.
    """
    from ...calibration.models import Model
    from ...model.rheologies.ngf import NGF_EXCESS_RTOL

    if model != "ngf":
        return {}, "", {}
    rates = [float(rd.I_w) for rd in data if rd.I_w is not None and rd.I_w > 0.0]
    if curve and runs:
        top = _rate(data)(float(np.max(curve_gaps(runs))))  # the curve's slowest rate
        if top is not None:
            rates.append(top)
    if not rates:
        return {}, "", {}
    declared = {p.key: p.declared for p in Model(model).parameters()}
    mu_s_range, b_range = declared["mu_s"].fit_range, declared["b"].fit_range
    if mu_s_range is None or b_range is None:  # NGF declares both; a model without them has no edge
        return {}, "", {}
    mu_s_hi = float(mu_s_range[1])
    b_lo, b_hi = (float(x) for x in b_range)
    slowest = min(rates)
    edge = NGF_EXCESS_RTOL * mu_s_hi / slowest
    lo = max(b_lo, EDGE_MARGIN * edge)
    note = (
        f"b's search range starts at {lo:.3g}, {EDGE_MARGIN:g} times the solver's "
        f"double-precision edge {NGF_EXCESS_RTOL:g} mu_s/I_w = {edge:.3g} (mu_s at its search "
        f"range's top, {mu_s_hi:g}; I_w = {slowest:.3g}, the slowest rate of the series' runs "
        "and curve): below the edge the excess T - mu_s that drives the flow has too few "
        "significant digits for the solver; the model itself flows at every b > 0, b -> 0 "
        "being its rate-independent limit, which the profile approaches as b I_w -> 0"
    )
    numbers = {"b_edge": edge, "b_lower": lo, "I_w_slowest": slowest, "mu_s_top": mu_s_hi}
    return {"b": (lo, b_hi)}, note, numbers


def calibrate_best(
    model: str, members: Sequence[Run], data: Sequence[Any], f: float, curve: bool = True
) -> SeriesCalibration:
    """An alternative's per-series best fit: ``model`` calibrated on one gap series' runs
    alone (``members``, their calibration data ``data``), on the velocity and the moving
    wall's measured stress ratio T (:data:`BEST_FIELDS`) with every parameter the calibration
    frees free (mu(I)'s I_0 and mu_s, NGF's mu_s, b and A), NGF's b kept off the solver's edge
    (:func:`solver_edges`), and its Delta at the runs and on the curve (``_series_delta``);
    its T at each run's wall against the measured one, and any contradiction left
    (:func:`wall_stress_check`), in the summary's ``wall_T`` and ``stress_contradiction``.
    The Delta claims judge
    an alternative's rejection at this fit, not at the material's joint calibration, which
    describes every field of both wall kinds and so can be a straw man for one series'
    Delta."""
    from ...calibration.joint import calibrate_model
    from ...calibration.models import Model

    ranges, note, numbers = solver_edges(model, data, members, curve)
    m = _ranged_model(model, ranges) if ranges else Model(model)
    mc = calibrate_model(m, data, BEST_FIELDS, starts=BEST_STARTS)
    if not mc.ok:
        return SeriesCalibration(model, "failed", " ".join(mc.message.split()))
    s, opt = mc.internal
    predicted, grid, why, floor = _series_delta(
        s, opt.theta, _covariance(mc), members, data, f, curve
    )
    wall_T, contradiction = wall_stress_check(mc, [rd.name for rd in data])
    summary = {
        **_summary(mc),
        "material": data[0].material,
        "runs": [r.name for r in members],
        "per_series": True,
        "edge_note": note,
        "edges": numbers,
        "wall_T": wall_T,
        "stress_contradiction": contradiction,
    }
    return SeriesCalibration(model, "ok", "", summary, predicted, grid, why, floor)


def wall_stress_check(mc: Any, runs: Sequence[str]) -> tuple[dict[str, Any], str]:
    """A per-series best fit's T at each run's moving wall against the run's measured one
    (the fit's ``wall_ratio`` field, :data:`BEST_FIELDS`), and what contradicts it in words
    ("" if nothing): the model's T more than :data:`STRESS_SIGMAS` errors and
    :data:`STRESS_RELATIVE` of the measured T away from it (the thresholds of the per-run
    fits' stress contradiction; mu(I) and NGF have no wall friction, so a wall that holds the
    material does not excuse a miss as it does the Cosserat model's ``tan delta``).

    Returns
    -------
    wall_T : dict
        Run -> ``{"model", "measured", "se", "z"}`` ([-], [-], [-], [se]); a run without a
        measured wall ratio -> None (its T is not held by the fit).
    contradiction : str
    """
    got = {f.run: f for f in mc.fields if f.field == "wall_ratio"}
    wall_T: dict[str, Any] = {}
    misses = []
    for run in runs:
        f = got.get(run)
        if f is None:
            wall_T[run] = None
            continue
        model, data, se = float(f.model[0]), float(f.data[0]), float(f.se[0])
        z = (model - data) / se
        wall_T[run] = {"model": model, "measured": data, "se": se, "z": z}
        if abs(model - data) > max(STRESS_SIGMAS * se, STRESS_RELATIVE * data):
            misses.append(f"{run}: T = {model:.3g} against {data:.3g} +- {se:.2g} ({z:+.1f} se)")
    if not misses:
        return wall_T, ""
    return wall_T, (
        "still contradicts the measured stresses with T held to them: the fit's T at the "
        f"moving wall is more than {STRESS_SIGMAS:g} errors and {STRESS_RELATIVE:.0%} from "
        "the measured one (" + "; ".join(misses) + "): the model does not give this series' "
        "velocity and its walls' T together"
    )


def _series_delta(
    s: Any,
    theta: FloatArray,
    cov: FloatArray,
    runs: Sequence[Run],
    data: Sequence[Any],
    f: float,
    curve: bool,
) -> tuple[
    dict[str, tuple[float | None, float | None]],
    tuple[tuple[float, ...], tuple[float | None, ...]],
    dict[str, str],
    dict[str, float],
]:
    """One calibration's Delta at a series' runs, with its error from the covariance ``cov``
    (delta method), and on a grid of H/d with the series' first run as the template (its
    wall; at each gap the bins its analysis would make there, ``forward.analysis_distances``;
    I_w from :func:`_rate` of the series' runs), the runs' own values among the grid's; why
    the model gives none where it does not, and the second bin's distance at each
    (:class:`SeriesCalibration`)."""
    from ...calibration.engine import FD_STEP
    from .forward import analysis_distances
    from .measures import reference_velocity

    model = s.model
    u0 = reference_velocity(runs[0])
    rate = _rate(data)
    lo, hi = s.bounds()
    predicted: dict[str, tuple[float | None, float | None]] = {}
    why: dict[str, str] = {}
    floor: dict[str, float] = {}
    for run, rd in zip(runs, data, strict=True):
        dist = run.measured().distance_d
        probe = _probe(rd, rd.name, rd.gap_d, dist, rd.I_w)
        value, reason = _delta(model, probe, s.run_values(rd, theta), u0, f)
        floor[rd.name] = float(dist[1]) if dist.size > 1 else 0.0
        if reason:
            why[rd.name] = reason
        se = None
        if value is not None and theta.size:
            g = np.zeros(theta.size)
            ok = True
            for j in range(theta.size):
                h = (
                    FD_STEP
                    * (hi[j] - lo[j])
                    * (1.0 if theta[j] + FD_STEP * (hi[j] - lo[j]) <= hi[j] else -1.0)
                )
                moved = theta.copy()
                moved[j] += h
                dj = _delta(model, probe, s.run_values(rd, moved), u0, f)[0]
                if dj is None:
                    ok = False
                    break
                g[j] = (dj - value) / h
            se = math.sqrt(max(float(g @ cov @ g), 0.0)) if ok else None
        predicted[rd.name] = (value, se)
    grid: tuple[tuple[float, ...], tuple[float | None, ...]] = ((), ())
    if curve:
        # each gap measured as the analysis would bin a run there (the series' first run's
        # rule), and the series' runs themselves: the curve passes through their predictions
        gaps = curve_gaps(runs)
        values = s.run_values(data[0], theta)
        points: dict[float, float | None] = {}
        for g in gaps:
            dist = analysis_distances(runs[0], float(g))
            probe = _probe(data[0], f"{data[0].name}@H{g:.4g}", float(g), dist,
                           rate(float(g)))  # fmt: skip
            value, reason = _delta(model, probe, values, u0, f)
            points[float(g)] = value
            floor[curve_key(float(g))] = float(dist[1]) if dist.size > 1 else 0.0
            if reason:
                why[curve_key(float(g))] = reason
        for rd in data:
            points[float(rd.gap_d)] = predicted[rd.name][0]
            floor[curve_key(float(rd.gap_d))] = floor[rd.name]
            if rd.name in why:
                why[curve_key(float(rd.gap_d))] = why[rd.name]
        order = sorted(points)
        grid = (tuple(order), tuple(points[g] for g in order))
    return predicted, grid, why, floor


def curve_gaps(runs: Sequence[Run]) -> FloatArray:
    """The gaps of a series' Delta curve [-]: :data:`CURVE_POINTS` from its smallest gap over
    ``CURVE_SPAN[0]`` to its largest times ``CURVE_SPAN[1]``, :func:`phased_gaps` (one
    first-bin position along the curve; referee 14, point 1), the series' first run the
    binning's template."""
    return phased_gaps(
        runs[0],
        np.geomspace(
            min(r.gap_d for r in runs) / CURVE_SPAN[0],
            max(r.gap_d for r in runs) * CURVE_SPAN[1],
            CURVE_POINTS,
        ),
        max(r.gap_d for r in runs),
    )


def phased_gaps(template: Run, gaps: Any, phase_gap: float) -> FloatArray:
    """``gaps`` [d] moved each by under half a bin so that its remainder over ``template``'s
    bins is ``phase_gap``'s: the analysis (``forward.analysis_distances``) then puts the first
    bin's centre at one distance from the moving wall at every gap, as at ``phase_gap`` (the
    series' largest run). A curve of gaps with other remainders carries the first bin's
    position as a sawtooth: on the round-14 corpus the smoother curve fell by 0.5-4% where
    that centre jumped towards the wall (75 -> 94, 179 -> 222, 1013 -> 1258 d; referee 14,
    point 1), which moves a factor-4 slope by about 0.03. Same number of gaps, so no
    solve is added."""
    from .forward import analysis_distances

    g = np.asarray(gaps, dtype=float)
    dist = analysis_distances(template, float(phase_gap))
    if dist.size < 3:
        return g
    w = float(np.median(np.diff(dist)))
    rest = float(phase_gap) - w * math.floor(float(phase_gap) / w + 1e-9)
    out = w * np.round((g - rest) / w) + rest
    return np.where(out > 0.0, out, g)


def _series_reach(
    s: Any,
    theta: FloatArray,
    runs: Sequence[Run],
    data: Sequence[Any],
    f: float,
    why: dict[str, str],
) -> tuple[tuple[float, ...], tuple[float | None, ...]]:
    """One calibration's Delta beyond its curve, at :data:`REACH_POINTS` gaps from the curve's
    largest (exclusive) to the series' largest gap times :data:`REACH_SPAN`, as the curve is
    made (the series' first run as the template, its bins at each gap, I_w from ``_rate``);
    why it gives none where it does not goes into ``why`` by ``curve_key``."""
    from .measures import reference_velocity

    top = max(r.gap_d for r in runs)
    gaps = phased_gaps(
        runs[0], np.geomspace(top * CURVE_SPAN[1], top * REACH_SPAN, REACH_POINTS + 1)[1:], top
    )
    return _delta_grid(s, theta, runs, data, f, gaps, reference_velocity(runs[0]), why)


def _delta_grid(
    s: Any,
    theta: FloatArray,
    runs: Sequence[Run],
    data: Sequence[Any],
    f: float,
    gaps: FloatArray,
    u0: float,
    why: dict[str, str],
) -> tuple[tuple[float, ...], tuple[float | None, ...]]:
    from .forward import analysis_distances

    rate = _rate(data)
    values = s.run_values(data[0], theta)
    out: list[float | None] = []
    for g in gaps:
        dist = analysis_distances(runs[0], float(g))
        probe = _probe(data[0], f"{data[0].name}@H{g:.4g}", float(g), dist, rate(float(g)))
        value, reason = _delta(s.model, probe, values, u0, f)
        out.append(value)
        if reason:
            why[curve_key(float(g))] = reason
    return tuple(float(g) for g in gaps), tuple(out)


@dataclass(frozen=True)
class MaterialJob:
    """One model's joint calibration of one material's runs, and the gap series that read it
    (:func:`calibrate_material`); made by ``study.series_jobs``, run by :func:`material_job`."""

    material: str
    """The material's key (:class:`~cosserat.studies.validate.grouping.Material`)."""
    runs: tuple[Run, ...]
    model: str
    series: tuple[tuple[str, tuple[Run, ...], float], ...]
    """(series key, its runs, its f [-]) of every series of the material."""
    fix_phi: bool = True
    """:func:`calibrate_material`'s ``fix_phi``."""


def material_job(job: MaterialJob) -> dict[str, SeriesCalibration]:
    """:func:`calibrate_material` of one job, series key -> its calibration, a failure as a
    result for every series (for worker processes)."""
    try:
        out = calibrate_material(job.runs, [job.model], job.series, fix_phi=job.fix_phi)
    except CosseratError as exc:
        why = " ".join(str(exc).split())
        return {key: SeriesCalibration(job.model, "failed", why) for key, _, _ in job.series}
    if not any(out.values()):
        why = f"model {job.model!r} has no {job.runs[0].cell} cell"
        return {key: SeriesCalibration(job.model, "failed", why) for key, _, _ in job.series}
    return {key: cals[0] for key, cals in out.items()}
