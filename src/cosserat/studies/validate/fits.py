"""The models fitted to one run's velocity: the only module of validation that fits.

Every call to the fitting machinery (:func:`cosserat.calibration.single.rank_models`,
:class:`~cosserat.calibration.single.Ranking`, :func:`~cosserat.analysis.fitting.moving_wall`)
is here, so that moving validation onto another fitting engine changes this module only. The
rest of validation sees :class:`RunFits` and :class:`FitSummary`: plain numbers, the fitted
velocity and spin at given bins, and the warnings a referee asks for:

* **misfit**: with the data's standard errors, a fit with p(chi^2, n - k) < :data:`P_SIGNIFICANT`
  misses the data; the warning says by how much and where it misses most (in the creep tail
  where the measured u < :data:`~cosserat.studies.validate.measures.BAND_U`, or in the band);
* **pinned**: every material or wall parameter with a fit range that the fit held at its
  declared default, named with its value;
* **contradicts the measured stress ratio**: the band's |shear|/normal stress ratio of the run
  (:func:`~cosserat.studies.validate.measures.band_stress_ratio`) against the model's own
  (sin phi for the Cosserat model, mu_s for mu(I) and nonlocal fluidity), whether fitted or
  pinned: flagged when they differ by more than :data:`STRESS_SIGMAS` errors of the measured
  ratio and more than :data:`STRESS_RELATIVE` of it (the model's ratio in the band is only
  about its yield value: the relative margin allows for that).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from scipy.stats import chi2 as chi2_dist

from ...analysis.corpus import Run
from ...analysis.fitting import moving_wall
from ...calibration.single import Ranking, rank_models
from ...errors import CosseratError
from ...model.constitutive import FloatArray
from .measures import BAND_U, P_SIGNIFICANT, StressRatio

STRESS_SIGMAS = 3.0
"""A model's band stress ratio contradicts the measured one beyond this many errors [-] ..."""
STRESS_RELATIVE = 0.1
"""... and beyond this fraction of the measured ratio [-]."""

BAND_RATIO: dict[str, tuple[str, str, Callable[[float], float]]] = {
    "cosserat": ("phi", "sin phi", lambda phi: math.sin(math.radians(phi))),
    "mui": ("mu_s", "mu_s", lambda mu: mu),
    "ngf": ("mu_s", "mu_s", lambda mu: mu),
}
"""Each rheology's stress ratio in a slowly shearing band: (parameter, what, its value)."""


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

    def to_dict(self) -> dict[str, Any]:
        return {
            "model": self.model,
            "p_value": self.p_value,
            "pinned": self.pinned,
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

    def spin_departure(
        self, model: str, distance_d: FloatArray, half_measured: FloatArray
    ) -> FloatArray:
        """The fitted model's omega - half vorticity at distances from the moving wall [d], in
        the run's units (omega d / V) and its rotation sense (the data's half vorticity
        ``half_measured`` at the same bins fixes it). A rheology without a grain spin of its
        own turns with the material: no departure."""
        fit = self._fit(model)
        prof = fit.profile
        eps = prof.problem.eps
        xw, _ = moving_wall(prof.problem)
        d = np.clip(np.asarray(distance_d, dtype=float) * eps, 0.0, 1.0)
        xi = d if xw == 0.0 else 1.0 - d
        fields = prof.evaluate(xi)
        model_half = -0.5 * (fields.du_dxi + fields.kappa * fields.u) * eps
        model_omega = model_half if fields.omega is None else fields.omega * eps
        sign = -1.0 if float(np.sum(model_half * half_measured)) < 0.0 else 1.0
        return sign * (model_omega - model_half)

    def to_dict(self) -> dict[str, Any]:
        """The fitting engine's record, each fit with its p-value, pinned parameters, band
        stress ratio and every warning of :func:`fit_run`."""
        out = self.ranking.to_dict()
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
    run: Run, models: Sequence[str] | None, grid: int, stress: StressRatio | None
) -> RunFits:
    """Fit ``models`` (default: every one defined on the run's cell) to the run's velocity.

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
    ranking = rank_models(measured, run.cell_parameters(), names, grid=grid)
    out = RunFits(ranking)
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
            warnings.append(_misfit_text(f, measured, p, dof))
        values = f.problem.values()
        free = {k for k, e in f.parameters.items() if e.free}
        declared = f.problem.declared()
        pinned = {
            k: float(v)
            for k, v in values.items()
            if k in declared
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
        band = None
        if f.model in BAND_RATIO and BAND_RATIO[f.model][0] in values:
            key, what, ratio = BAND_RATIO[f.model]
            band = (what, float(ratio(float(values[key]))), key in pinned)
            text = _stress_contradiction(
                key, float(values[key]), what, band[1], key in pinned, stress
            )
            if text:
                warnings.append(text)
        params = {k: (e.value, e.stderr) for k, e in f.parameters.items() if e.free}
        out.summaries.append(
            FitSummary(
                f.model, True, "", f.chi2, dof, f.reduced_chi2, p, params, pinned, band, warnings
            )
        )
    return out


def try_fit_run(
    run: Run, models: Sequence[str] | None, grid: int, stress: StressRatio | None
) -> tuple[RunFits | None, str]:
    """:func:`fit_run`, or None and the reason in one line."""
    try:
        return fit_run(run, models, grid, stress), ""
    except CosseratError as exc:
        return None, " ".join(str(exc).split())


def _misfit_text(fit: Any, measured: Any, p: float, dof: int) -> str:
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
            f"{float(np.sum(z[tail] ** 2)) / max(float(np.sum(z**2)), 1e-300):.0%} of chi^2"
        )
    return (
        f"misfit: chi^2 = {fit.chi2:.4g} for {dof} degrees of freedom, p = {p:.2g} < "
        f"{P_SIGNIFICANT:g}; it misses most {where}, {measured.distance_d[worst]:.3g} d from "
        f"the moving wall (model - data = {z[worst]:+.3g} se){share}"
    )


def _stress_contradiction(
    key: str, value: float, what: str, ratio: float, pinned: bool, stress: StressRatio | None
) -> str:
    if stress is None:
        return ""
    diff = abs(ratio - stress.value)
    if diff <= STRESS_SIGMAS * stress.stderr or diff <= STRESS_RELATIVE * stress.value:
        return ""
    how = "pinned" if pinned else "fitted"
    return (
        f"contradicts the measured stress: {key} = {value:.4g} ({how}) gives {what} = "
        f"{ratio:.3g}, but the run's |shear|/normal stress ratio in the band is "
        f"{stress.value:.3g} +- {stress.stderr:.2g} ({stress.bins} bins), "
        f"{diff / stress.stderr:.1f} errors away"
    )
