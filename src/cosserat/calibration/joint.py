"""``calibrate``: every model on every run, with its diagnostics and the comparison.

This is the one engine behind ``cosserat calibrate``, ``cosserat fit`` (one run is a
calibration on one run) and the model fits of ``cosserat validate`` (``docs/calibration.md``).
"""

from __future__ import annotations

import dataclasses
import logging
import math
import time
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

import numpy as np
from scipy import stats

from ..errors import ConvergenceError, MethodNotAvailableError, NoSolutionError, ParameterError
from ..model.constitutive import FloatArray
from . import diagnostics as dg
from .checks import all_checks
from .data import BAND_U, RunData, load, with_correlations
from .engine import AT_BOUND, Optimum, Setup, fit, setup
from .models import HELD, LOCAL_SPIN, SOLVE_ERRORS, Model
from .models import models as make_models
from .noise import covariance
from .result import Calibration, Estimate, FieldFit, ModelCalibration

log = logging.getLogger(__name__)

DERIVED_STEP = 1e-6
"""Relative finite-difference step of a derived parameter's gradient (in the fit's coordinates)."""
NO_SOLUTION_EDGE = "at the edge of the region where the model has a solution"
"""The reason of a fitted value the data push onto the edge of the region where the model has
a solution (:attr:`~cosserat.calibration.engine.Optimum.no_solution`): no error is given."""


# --------------------------------------------------------------------------- estimates
def _estimates(
    s: Setup, opt: Optimum
) -> tuple[dict[str, Estimate], list[dg.FlatDirection], list[tuple[str, str, float]], FloatArray]:
    names = s.names
    lo, hi = s.bounds()
    widths = hi - lo
    J = opt.jacobian
    flat = dg.flat_directions(J, names, widths)
    unidentified = {n for d in flat for n in d.components}
    cov = dg.identified_covariance(J, widths) if J.size else np.zeros((0, 0))
    natural = s.natural(opt.theta)
    edges: dict[int, list[str]] = {}
    for j, side in opt.no_solution:
        edges.setdefault(j, []).append(side)
    out: dict[str, Estimate] = {}
    i = 0
    for slot in s.slots:
        decl = slot.param.declared
        shared = len(slot.runs) > 1
        common: dict[str, Any] = dict(
            name=slot.name,
            key=slot.key,
            role=slot.param.role,
            unit=decl.unit,
            shared=shared,
            runs=slot.runs,
            meaning=decl.meaning,
            fit_range=decl.fit_range,
        )
        if not slot.free:
            held = HELD.get(s.model.name, {}).get(slot.key)
            is_default = slot.value == decl.default
            out[slot.name] = Estimate(
                value=slot.value,
                stderr=None,
                free=False,
                reason=held if (held and is_default) else "fixed",
                **common,
            )
            continue
        theta = opt.theta[i]
        at = None
        if theta - lo[i] <= AT_BOUND * widths[i]:
            at = "lower"
        elif hi[i] - theta <= AT_BOUND * widths[i]:
            at = "upper"
        value = natural[slot.name]
        stderr: float | None = None
        reason = ""
        if at is not None:
            reason = f"at the {at} end of its search range {decl.fit_range}"
        elif i in edges:
            where = " and ".join("below" if e == "lower" else "above" for e in edges[i])
            reason = (
                f"{NO_SOLUTION_EDGE} (none {where} it, one finite-difference step away): "
                "not identified by the data"
            )
        elif slot.name in unidentified:
            reason = "not identified by the data (a flat direction of the fit)"
        else:
            se_int = math.sqrt(max(cov[i, i], 0.0))
            stderr = value * math.log(10.0) * se_int if slot.log else se_int
        out[slot.name] = Estimate(
            value=value, stderr=stderr, free=True, at_bound=at, reason=reason, **common
        )
        i += 1
    strong = [c for c in dg.strong_correlations(cov, names) if not {c[0], c[1]} & unidentified]
    return out, flat, strong, cov


def _derived(
    model: Model, s: Setup, opt: Optimum, cov: FloatArray, estimates: Mapping[str, Estimate]
) -> dict[str, Estimate]:
    """Parameters computed from fitted ones (the Cosserat wall angle delta from the wall's
    roughness and phi), with errors by the delta method."""
    if model.name != "cosserat":
        return {}
    out = {}
    material_phi = [sl for sl in s.slots if sl.key == "phi"]
    for slot in s.slots:
        if slot.key != "roughness":
            continue
        label = slot.group
        phi_slot = next((p for p in material_phi if set(slot.runs) & set(p.runs)), material_phi[0])

        def delta(theta: FloatArray, slot: Any = slot, phi_slot: Any = phi_slot) -> float:
            nat = s.natural(theta)
            t = nat[slot.name]
            return math.degrees(math.atan(t * math.sin(math.radians(nat[phi_slot.name]))))

        value = delta(opt.theta)
        free = slot.free or phi_slot.free
        stderr = None
        est = estimates[slot.name]
        reason = "fixed" if not free else ""
        if free and est.stderr is None and slot.free:
            reason = est.reason
        elif free and opt.theta.size:
            g = np.zeros(opt.theta.size)
            for j in range(opt.theta.size):
                h = DERIVED_STEP * max(1.0, abs(opt.theta[j]))
                up = opt.theta.copy()
                up[j] += h
                g[j] = (delta(up) - value) / h
            stderr = math.sqrt(max(float(g @ cov @ g), 0.0))
        fully = est.at_bound == "upper" or (not slot.free and slot.value >= 1.0 - 1e-12)
        out[f"delta[{label}]"] = Estimate(
            derived=True,
            name=f"delta[{label}]",
            key="delta",
            role="wall",
            value=value,
            stderr=stderr,
            free=free,
            shared=len(slot.runs) > 1,
            unit="deg",
            runs=slot.runs,
            at_bound="upper" if fully else None,
            reason=("fully rough: tan(delta) = sin(phi)" if fully else reason),
            meaning="angle of wall friction, atan(roughness sin(phi)) (derived)",
        )
    return out


# --------------------------------------------------------------------------- field fits
def _field_fits(s: Setup, predictions: Mapping[str, Mapping[str, FloatArray]]) -> list[FieldFit]:
    from .noise import whiten

    out = []
    for run in s.runs:
        u = run.fields.get("u")
        for name in s.fields:
            if name not in run.fields:
                continue
            f = run.fields[name]
            model = predictions[run.name][name]
            z = (model - f.value) / f.se
            w = whiten(model - f.value, f.se, f.correlation.rho)
            u_at = None if u is None else np.interp(f.s, u.s, u.value)
            out.append(
                FieldFit(
                    run=run.name,
                    field=name,
                    s=f.s,
                    data=f.value,
                    se=f.se,
                    model=model,
                    whitened=w,
                    rho=f.correlation.rho,
                    rho_source=f.correlation.source,
                    chi2=float(w @ w),
                    runs_p=dg.runs_test(w).p_value,
                    regions=dg.misfit_regions(f.s, z, u_at),
                )
            )
    return out


def _as(source: str) -> str:
    """How the bins' correlation was obtained (:class:`~.noise.Correlation`'s ``source``), as
    the warnings say it: the old wording said "as estimated" for a correlation given too."""
    return {
        "estimated": "as estimated",
        "metadata": "as the run's metadata state",
        "given": "as given",
        "too few bins": "as assumed (too few bins to estimate it)",
    }.get(source, f"as set ({source})")


def _stress_contradictions(model: Model, fits: Sequence[FieldFit]) -> list[str]:
    """Runs whose fitted stress ratio in the band contradicts the measured one (> 3 se)."""
    friction = {"cosserat": "delta (the wall's friction) and phi", "mui": "mu_s", "ngf": "mu_s"}
    by_run: dict[str, dict[str, FieldFit]] = {}
    for f in fits:
        by_run.setdefault(f.run, {})[f.field] = f
    out = []
    for run, fields in by_run.items():
        ratio, u = fields.get("stress_ratio"), fields.get("u")
        if ratio is None or u is None:
            continue
        band = np.interp(ratio.s, u.s, u.data) > dg.TAIL_U
        if np.count_nonzero(band) < 2:
            continue
        m = int(np.count_nonzero(band))
        C = covariance(ratio.se[band], ratio.rho)
        se_mean = math.sqrt(float(np.sum(C))) / m
        data = float(np.mean(ratio.data[band]))
        pred = float(np.mean(ratio.model[band]))
        if abs(pred - data) > 3.0 * se_mean:
            out.append(
                f"{model.name}: run {run}: the fitted parameters give |sigma_yx|/sigma_yy = "
                f"{pred:.3f} in the shear band where the run measures {data:.3f} +- "
                f"{se_mean:.3f} ({(pred - data) / se_mean:+.1f} se): "
                f"{friction.get(model.name, 'the friction parameters')} contradict the "
                "measured stresses"
            )
    return out


def _warnings(mc: ModelCalibration, fits: Sequence[FieldFit]) -> list[str]:
    """The model's warnings, the worst first (overall misfit, then fields by their excess
    chi^2, then parameters)."""
    name = mc.model
    out = []
    if mc.chi2 is not None and mc.dof > 0:
        lp = dg.chi2_log10_p(mc.chi2, mc.dof)
        if lp < math.log10(dg.MISFIT_P):
            worst = max(fits, key=lambda f: f.chi2 - f.n)
            out.append(
                f"{name}: misfit: chi^2 = {mc.chi2:.1f} on {mc.dof} degrees of freedom "
                f"({dg.p_text(lp)}); the largest excess: run {worst.run}, {worst.field} "
                f"(chi^2 = {worst.chi2:.1f} on {worst.n} bins); errors scaled by "
                f"sqrt(chi^2/dof) = {math.sqrt(mc.chi2 / mc.dof):.2g} are given beside the "
                "statistical ones"
            )
    low = dg.chi2_p_low(mc.chi2 or 0.0, mc.dof)
    if low is not None and low < dg.OVERSTATED_P:
        out.append(
            f"{name}: chi^2 = {mc.chi2:.1f} on {mc.dof} degrees of freedom is improbably small "
            f"(P(chi^2 <= this) = {low:.2g}): the errors are overstated, or the bins are more "
            "correlated than the error model says; the information criteria are not calibrated"
        )
    per_field = []
    for f in sorted(fits, key=lambda f: f.chi2 - f.n, reverse=True):
        lp = dg.chi2_log10_p(f.chi2, f.n)
        where = "; ".join(r.describe() for r in f.regions)
        tail = dg.tail_decades(f.s, f.data, f.se, f.model) if f.field == "u" else None
        if tail is not None:
            where = "; ".join(x for x in (where, tail) if x)
        z = (f.model - f.data) / f.se
        top = int(np.argmax(np.abs(z))) if f.n else 0
        largest = f"largest: s = {f.s[top]:.3g} d, {z[top]:+.1f} se" if f.n else ""
        if lp < math.log10(dg.MISFIT_P):
            per_field.append(
                f"{name}: run {f.run}, {f.field}: chi^2 = {f.chi2:.1f} on {f.n} bins "
                f"({dg.p_text(lp)}; {largest})" + (f": misses {where}" if where else "")
            )
        elif where:
            per_field.append(f"{name}: run {f.run}, {f.field}: misses {where}")
        low_f = dg.chi2_p_low(f.chi2, f.n)
        if f.n >= 5 and low_f is not None and low_f < dg.OVERSTATED_P:
            per_field.append(
                f"{name}: run {f.run}, {f.field}: chi^2 = {f.chi2:.1f} on {f.n} bins is "
                f"improbably small (P(chi^2 <= this) = {low_f:.2g}): the errors are overstated "
                f"or more correlated than rho = {f.rho:.2f} says"
            )
        bins, first, last, sign = dg.longest_stretch(f.s, z)
        if bins >= REGION_STRETCH:
            p_free = dg.stretch_p_value(f.n, 0.0, bins)
            p_rho = dg.stretch_p_value(f.n, f.rho, bins) if f.rho > 0.0 else p_free
            side = "above" if sign > 0 else "below"
            where = (
                f"{bins} neighbouring bins (s = {first:.3g}-{last:.3g} d) all have the model "
                f"{side} the data"
            )
            if p_rho < dg.MISFIT_P:
                per_field.append(
                    f"{name}: run {f.run}, {f.field}: {where}, improbable even for bins "
                    f"correlated {_as(f.rho_source)} (rho = {f.rho:.2f}, p = {p_rho:.2g}): "
                    "a misfit"
                )
            elif p_free < dg.MISFIT_P:
                per_field.append(
                    f"{name}: run {f.run}, {f.field}: {where}; for independent bins that would "
                    f"be a misfit (p = {p_free:.2g}), for bins correlated {_as(f.rho_source)} "
                    f"(rho = {f.rho:.2f}) it is not (p = {p_rho:.2g}): whether it is one rests on "
                    "that correlation (errors from the runs' time blocks would decide)"
                )
        if f.runs_p is not None and f.runs_p < dg.MISFIT_P:
            per_field.append(
                f"{name}: run {f.run}, {f.field}: the signs of the whitened residuals change "
                f"too rarely (runs test p = {f.runs_p:.2g}): a systematic misfit"
            )
    out += per_field
    for e in mc.parameters.values():
        if e.free and e.at_bound is not None and e.key != "roughness" and not e.derived:
            direction = BOUND_MEANING.get((mc.model, e.key, e.at_bound), "")
            out.append(
                f"{name}: {e.name} = {e.value:.4g}{'' if e.unit in ('', '-') else ' ' + e.unit}"
                f" is at the {e.at_bound} end of its search range {e.fit_range}"
                + (f" ({direction})" if direction else "")
                + ": the data push it further; no error is given"
            )
    for e in mc.parameters.values():
        if e.free and e.reason.startswith(NO_SOLUTION_EDGE):
            out.append(
                f"{name}: {e.name} = {e.value:.4g}{'' if e.unit in ('', '-') else ' ' + e.unit} "
                f"is {e.reason}; "
                "the data push it there, so no error is given"
            )
    for d in mc.flat:
        out.append(f"{name}: the data do not determine {d.describe()}")
    for a, b, r in mc.correlations:
        out.append(f"{name}: {a} and {b} are strongly correlated (r = {r:+.3f})")
    return out


REGION_STRETCH = 6
"""Shortest stretch of one-sided residuals that is tested against the error model."""

BOUND_MEANING = {
    ("ngf", "b", "lower"): "b -> 0: the local law loses its rate dependence",
    ("mui", "I_0", "upper"): "I_0 -> infinity: mu stays at mu_s, a rate-independent law",
    ("cosserat", "K", "upper"): "K -> infinity: the wall slips freely",
}
"""What a parameter at an end of its search range means, for the warnings."""


def _flow_below_yield(model: Model, mc: ModelCalibration, fits: Sequence[FieldFit]) -> list[str]:
    """mu(I) flows only where |tau|/p > mu_s: bins that flow (measured u >= BAND_U) at a
    measured stress ratio more than 2 se below the fitted mu_s contradict the local law."""
    if model.name != "mui" or "mu_s" not in mc.parameters:
        return []
    mu_s = mc.parameters["mu_s"].value
    out = []
    for f in fits:
        if f.field != "stress_ratio":
            continue
        u = next((g for g in fits if g.run == f.run and g.field == "u"), None)
        if u is None:
            continue
        flowing = np.interp(f.s, u.s, u.data) >= BAND_U
        below = flowing & (f.data < mu_s - 2.0 * f.se)
        if np.any(below):
            out.append(
                f"{model.name}: run {f.run}: the material flows (u >= {BAND_U:g}) at s = "
                f"{f.s[below].min():.3g}-{f.s[below].max():.3g} d where the measured "
                f"|sigma_yx|/sigma_yy ({f.data[below].min():.3f}-{f.data[below].max():.3f}) is "
                f"below the fitted mu_s = {mu_s:.3f}: flow below yield, which the local law "
                "does not allow"
            )
    return out


def _assumptions(s: Setup) -> list[str]:
    rhos = []
    for run in s.runs:
        for name in s.fields:
            if name in run.fields:
                c = run.fields[name].correlation
                rhos.append(f"{run.name}/{name} {c.rho:.2f} ({c.source})")
    out = [
        "error model: Gaussian; the bins of one field of one run AR(1)-correlated with lag-1 "
        "correlation rho (per run/field: " + ", ".join(rhos) + "); fields and runs independent",
        "fixed from each run's metadata (I_w, the wall's inertial number, enters the "
        "rate-dependent models only): "
        + "; ".join(
            f"{r.name}: "
            + ", ".join(
                f"{k} = {v:.4g}" if isinstance(v, int | float) else f"{k} = {v}"
                for k, v in r.cell_values.items()
            )
            + (f", I_w = {r.I_w:.3g}" if r.I_w is not None else "")
            for r in s.runs
        ),
        "fields fitted: " + ", ".join(s.fields),
    ]
    if "omega" in s.fields and not s.model.has_spin:
        out.append(
            f"{s.model.name} has no spin of its own: its grains are taken to turn at "
            f"{LOCAL_SPIN.replace('-', ' ')} (a classical continuum's kinematics)"
        )
    return out


# --------------------------------------------------------------------------- one model
def calibrate_model(
    model: Model,
    runs: Sequence[RunData],
    fields: Sequence[str] | None = None,
    fix: Mapping[str, float] | None = None,
    free: Sequence[str] = (),
    start: Mapping[str, float] | None = None,
    starts: int | None = None,
    seed: int = 0,
) -> ModelCalibration:
    """Calibrate ``model`` on ``runs`` (module docstring); a failure is a result with the
    reason, not an exception, so that a ranking lists it."""
    t0 = time.perf_counter()
    try:
        s = setup(model, runs, fields, fix, free, start)
        opt = fit(s, starts=starts, seed=seed)
    except (ParameterError, ConvergenceError, NoSolutionError, MethodNotAvailableError) as exc:
        return ModelCalibration(
            model=model.name, status="failed", message=str(exc), seconds=time.perf_counter() - t0
        )
    return assemble(s, opt, t0)


def assemble(s: Setup, opt: Optimum, t0: float | None = None) -> ModelCalibration:
    """The :class:`~cosserat.calibration.result.ModelCalibration` of the optimum ``opt`` of
    ``s``: the estimates and their errors by the one identifiability rule, the field fits, the
    warnings (what :func:`calibrate_model` returns; ``cosserat.calibration.single`` calls it on
    a prepared setup). ``t0``: the ``time.perf_counter()`` at the start, for ``seconds``."""
    model = s.model
    t0 = time.perf_counter() if t0 is None else t0
    estimates, flat, corr, cov = _estimates(s, opt)
    estimates.update(_derived(model, s, opt, cov, estimates))
    predictions = s.predict(opt.theta)
    fits = _field_fits(s, predictions)
    chi2 = float(opt.residuals @ opt.residuals)
    mc = ModelCalibration(
        model=model.name,
        status="ok",
        parameters=estimates,
        fields=fits,
        fields_used=s.fields,
        chi2=chi2,
        n=s.n,
        k=len(s.free),
        log_likelihood=-0.5 * chi2 + s.log_norm,
        flat=flat,
        correlations=corr,
        covariance=cov,
        covariance_names=tuple(s.names),
        assumptions=_assumptions(s),
        nfev=s.nfev,
        seconds=time.perf_counter() - t0,
        internal=(s, opt),
    )
    if mc.dof > 0 and dg.chi2_log10_p(chi2, mc.dof) < math.log10(dg.MISFIT_P):
        birge = math.sqrt(chi2 / mc.dof)
        mc = dataclasses.replace(
            mc, parameters={n: dataclasses.replace(e, scale=birge) for n, e in estimates.items()}
        )
    mc.warnings.extend(_warnings(mc, fits))
    mc.warnings.extend(_stress_contradictions(model, fits))
    mc.warnings.extend(_flow_below_yield(model, mc, fits))
    return mc


def predict_held_out(mc: ModelCalibration, runs: Sequence[RunData]) -> ModelCalibration:
    """``mc`` with its predictions of ``runs``, which the fit did not see: every parameter at
    its fitted value, each field's chi^2 and p-value, a warning where a prediction fails.

    A run whose material or wall kind the fit did not see cannot be predicted (said in the
    warnings)."""
    if not mc.ok or not runs:
        return mc
    s, opt = mc.internal[0], mc.internal[1]
    natural = s.natural(opt.theta)
    slots = []
    for sl in s.slots:
        members = tuple(
            r.name
            for r in runs
            if (sl.scope == "material" and r.material == sl.group)
            or (sl.scope == "wall" and sl.group in r.walls.values())
        )
        slots.append(dataclasses.replace(sl, free=False, value=natural[sl.name], runs=members))
    usable, notes = [], []
    for r in runs:
        labels = {sl.group for sl in slots if r.name in sl.runs}
        missing = [w for w in {r.material, *r.walls.values()} if w not in labels]
        if missing:
            notes.append(
                f"{mc.model}: held-out run {r.name} cannot be predicted: the fit saw no run "
                f"with its {', '.join(missing)}"
            )
        else:
            usable.append(r)
    held: list[FieldFit] = []
    if usable:
        hs = Setup(s.model, usable, s.fields, slots)
        try:
            held = _field_fits(hs, hs.predict(np.zeros(0)))
        except SOLVE_ERRORS as exc:
            notes.append(f"{mc.model}: no prediction of the held-out runs: {exc}")
    for f in held:
        lp = dg.chi2_log10_p(f.chi2, f.n)
        if lp < math.log10(dg.MISFIT_P):
            notes.append(
                f"{mc.model}: held-out run {f.run}, {f.field}: predicted with chi^2 = "
                f"{f.chi2:.1f} on {f.n} bins ({dg.p_text(lp)}): the calibration does not carry "
                "to this run"
            )
    return dataclasses.replace(mc, held_out=held, warnings=[*mc.warnings, *notes])


def jackknife(mc: ModelCalibration, seed: int = 0) -> ModelCalibration:
    """``mc`` with each shared parameter's spread when one run at a time is left out.

    Reported: the range over the leave-one-out fits and the jackknife standard error
    ``sqrt((n-1)/n sum (x_i - mean)^2)`` (descriptive: the runs carry unequal information,
    so it overstates the error when one run dominates a parameter). The test of agreement
    holds the all-run estimate against each leave-one-out fit's own error: leaving run i out
    moves the estimate by ``d_i``, and ``z_i = d_i / se_{-i}`` (errors scaled for the misfit).
    For a linear model with Gaussian errors ``d_i`` has variance ``se_{-i}^2 - se^2``, so this
    ``z_i`` errs on the side of agreement; the sharper ``d_i / sqrt(se_{-i}^2 - se^2)`` was
    tried and rejects data made by the model itself (3.6 sigma on a Cosserat fit whose
    parameters are strongly correlated: the linear formula does not hold there). A warning
    names the runs whose ``|z_i|`` is improbable at ``p < MISFIT_P / n`` (Bonferroni over the
    runs): they do not agree on one value."""
    if not mc.ok:
        return mc
    s, opt = mc.internal[0], mc.internal[1]
    if len(s.runs) < 3:
        return mc
    start = {k: v for k, v in s.natural(opt.theta).items()}
    fixed = {sl.name: sl.value for sl in s.slots if not sl.free}
    values: dict[str, list[float]] = {}
    moves: dict[str, list[tuple[str, float, float | None]]] = {}
    for left in s.runs:
        rest = [r for r in s.runs if r is not left]
        names = {sl.name for sl in s.slots if set(sl.runs) & {r.name for r in rest}}
        sub = calibrate_model(
            s.model, rest, s.fields,
            fix={k: v for k, v in fixed.items() if k in names},
            start={k: v for k, v in start.items() if k in names and k not in fixed},
            starts=0, seed=seed,
        )  # fmt: skip
        if not sub.ok:
            continue
        for name, e in sub.parameters.items():
            if e.free or e.derived:
                values.setdefault(name, []).append(e.value)
                moves.setdefault(name, []).append((left.name, e.value, e.stderr_scaled))
    params = dict(mc.parameters)
    notes = []
    for name, xs in values.items():
        full = params.get(name)
        if full is None or len(xs) < 2:
            continue
        x = np.asarray(xs)
        n = x.size
        se = float(np.sqrt((n - 1) / n * np.sum((x - x.mean()) ** 2)))
        params[name] = dataclasses.replace(full, jackknife=(float(x.min()), float(x.max()), se))
        own = full.stderr_scaled
        if own is None:
            continue
        cut = dg.MISFIT_P / n
        odd = []
        for left, value, sub_se in moves[name]:
            if not sub_se:
                continue
            z = (value - full.value) / sub_se
            if 2.0 * stats.norm.sf(abs(z)) < cut:
                odd.append(f"{left} (moves it to {value:.4g}, {z:+.1f} sigma)")
        if odd:
            notes.append(
                f"{mc.model}: {name} = {full.value:.4g} +- {own:.2g}: leaving out "
                f"{', '.join(odd)} moves it more than the errors allow (p < {cut:.2g} each; "
                f"range {x.min():.4g}-{x.max():.4g} over the {n} runs): the runs do not agree "
                "on one value, so it is not one material's constant under this model"
            )
    return dataclasses.replace(mc, parameters=params, warnings=[*mc.warnings, *notes])


COMPARISON = [
    "AIC = -2 ln L + 2k and BIC = -2 ln L + k ln n use the full Gaussian likelihood of the "
    "error model; they rank models fitted to the same fields of the same runs, and their "
    "weights mean something only where each model's reduced chi^2 is near 1",
    "the Bayesian evidence Z (nested sampling, dynesty) puts priors uniform over each free "
    "parameter's declared search range (log-uniform where the declaration's scale is log); it "
    "depends on those ranges, which are stated with the parameters",
]


def calibrate(
    data: Sequence[str | Path | RunData],
    models: Sequence[str] | None = ("cosserat", "mui", "ngf"),
    fields: Sequence[str] | None = None,
    fix: Mapping[str, Mapping[str, float]] | None = None,
    free: Mapping[str, Sequence[str]] | None = None,
    start: Mapping[str, Mapping[str, float]] | None = None,
    bin_correlation: Mapping[str, float] | None = None,
    local_spin: bool = True,
    evidence: bool = False,
    posterior: int = 0,
    out: str | Path | None = None,
    seed: int = 0,
    progress: Any = None,
    holdout: Sequence[str] = (),
    leave_one_out: bool = False,
) -> Calibration:
    """Calibrate each model jointly on every run, and compare them.

    Parameters
    ----------
    data : sequence
        Corpus folders, corpus run files (``.csv`` with a ``.json`` sidecar), profile files
        (``docs/measurements.md``), or :class:`~cosserat.calibration.data.RunData`.
    models : sequence of str, optional
        Registered rheologies (default the three: ``cosserat``, ``mui``, ``ngf``).
    fields : sequence of str, optional
        Measured fields to use (``u``, ``omega``, ``stress_ratio``); default every field a
        model predicts.
    fix, free, start : mapping of model name to ..., optional
        Per model: parameters to hold at a value, to fit although fixed by default, and start
        values (names as in the result: ``phi``, ``K[glued-grains]``, or a key for all).
    bin_correlation : mapping of field to float, optional
        Lag-1 correlation of neighbouring bins' errors, overriding the metadata and the
        estimate (``calibration.noise``).
    local_spin : bool
        Compare local rheologies with spin data through half the vorticity (``models``).
    evidence : bool
        Also compute each model's Bayesian evidence (nested sampling; ~1e4 model solves).
    posterior : int
        Posterior samples to draw per model (0: none), written under ``out``.
    out : path, optional
        Folder for the posterior files (InferenceData netCDF, corner plots).
    seed : int
        Seed of the start design, the sampler and the nested sampler.
    progress : callable, optional
        ``progress(message)`` per model (the command line's progress line).
    holdout : sequence of str
        Runs left out of the fit and predicted with the fitted parameters (a test of whether
        the calibration carries to another gap or cell).
    leave_one_out : bool
        Refit each model with each run left out in turn and report every shared parameter's
        spread (:func:`jackknife`): whether the runs agree on one material.

    Returns
    -------
    Calibration
    """
    runs = [r for r in data if isinstance(r, RunData)]
    paths = [p for p in data if not isinstance(p, RunData)]
    skipped: list[str] = []
    if paths:
        runs += load(paths, skipped)
    runs = with_correlations(runs, bin_correlation)
    unknown = sorted(set(holdout) - {r.name for r in runs})
    if unknown:
        raise ParameterError(f"held-out run(s) {', '.join(unknown)} are not among the runs")
    held = [r for r in runs if r.name in holdout]
    runs = [r for r in runs if r.name not in holdout]
    if not runs:
        raise ParameterError("every run is held out: nothing is left to calibrate on")
    chosen = make_models(models, local_spin)
    results = []
    for m in chosen:
        if progress is not None:
            progress(f"calibrating {m.name} on {len(runs)} run(s)")
        mc = calibrate_model(
            m,
            runs,
            fields,
            fix=(fix or {}).get(m.name),
            free=(free or {}).get(m.name, ()),
            start=(start or {}).get(m.name),
            seed=seed,
        )
        mc = predict_held_out(mc, held)
        if mc.ok and leave_one_out:
            if progress is not None:
                progress(f"{m.name}: leaving each run out in turn")
            mc = jackknife(mc, seed=seed)
        if mc.ok and evidence:
            from .evidence import nested_evidence

            if progress is not None:
                progress(f"evidence of {m.name} (nested sampling)")
            mc = nested_evidence(mc, seed=seed)
        if mc.ok and posterior > 0:
            from .posterior import sample_posterior

            if progress is not None:
                progress(f"posterior of {m.name}: {posterior} samples")
            mc = sample_posterior(mc, posterior, out=out, seed=seed)
        results.append(mc)
    comparison = list(COMPARISON)
    used = {m.fields_used for m in results if m.ok}
    if len(used) > 1:
        comparison.append(
            "the models were fitted to different fields ("
            + "; ".join(f"{m.model}: {', '.join(m.fields_used)}" for m in results if m.ok)
            + "): their information criteria are not comparable"
        )
    return Calibration(
        runs, results, comparison, skipped, data_notes=all_checks([*runs, *held]), held_out=held
    )


__all__ = ["COMPARISON", "assemble", "calibrate", "calibrate_model"]
