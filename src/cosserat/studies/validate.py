"""Validate the models against a corpus of measured profiles, and judge the paper's claims.

For every run of a corpus (:mod:`cosserat.analysis.corpus`): fit each registered model to the
velocity profile and rank them (:func:`cosserat.calibration.single.rank_models`); compare the
measured spin with half the measured vorticity and with each fitted model's spin; measure the
shear-layer thickness Delta from the data. Across the runs of one cell and wall at several
gaps: the power law of Delta against H/d. Then a verdict on each of the paper's claims, in
words, whichever way it goes:

1. the grain spin departs from half the vorticity near the walls;
2. Delta does not depend on the gap for walls smoother than the material;
3. Delta grows as (H/d)^(1/3) for fully rough walls (under gravity, or in Couette flow).

Each verdict is "supported", "refuted", "undecided" (the data cannot decide: too few gaps,
errors too large, nothing measured) or "mixed" (runs or wall series disagree), with the
numbers it rests on. The decision rules, stated once here and in the report:

* spin: a run departs near a wall when chi^2 of (omega - half vorticity)/se over the bins
  within ``near_wall_d`` of a wall has p < :data:`P_SIGNIFICANT`; "supported" if at least half
  the runs with spin data depart; "refuted" if none does although the departure the fitted
  Cosserat model predicts would have given p < :data:`P_SIGNIFICANT` with these errors;
* Delta: the slope s +- se of ln Delta against ln(H/d) over at least :data:`MIN_GAPS` gaps
  (weighted by the errors of Delta); a claimed exponent c is "supported" when |s - c| <= 2 se
  and the other claimed exponent is excluded (|s - c'| > 2 se), "refuted" when |s - c| > 2 se,
  "undecided" otherwise; also "undecided" when the data miss c but agree with the slope of the
  Cosserat model fitted to the same runs, which itself misses c (the claims are limits
  H/d -> infinity; such gaps are too small to test them).

Delta of the data: the distance from the moving wall's surface at which the velocity (linear
between bins) has fallen to a fraction f of its value in the bin nearest to that wall,
relative to u_0 (1/2 for plane shear without gravity, else 0); its standard error from
:data:`DRAWS` redraws of the velocities within their standard errors. The fitted models' Delta
in the tables is the same estimator applied to the model at the same bins.
"""

from __future__ import annotations

import html
import json
import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
from scipy.stats import chi2 as chi2_dist

from .._atomic import save_figure, write_text
from ..analysis.corpus import Corpus, Run, read_corpus, usable
from ..analysis.gap import PAPER_SLOPES, SlopeFit, power_law_slope
from ..analysis.fitting import moving_wall
from ..calibration.single import Ranking, rank_models
from ..config import DEFAULT_F
from ..errors import CosseratError, ParameterError
from ..model.constitutive import FloatArray

P_SIGNIFICANT = 1e-3
"""p-value below which a departure of the spin from half the vorticity is significant."""
MIN_GAPS = 3
"""Fewest gaps for a verdict on how Delta scales with the gap."""
DRAWS = 400
"""Redraws of a run's velocities for the standard error of its Delta."""
NEAR_WALL_D = 3.0
"""Bins within this many grain diameters of a wall are 'near the wall' [d]."""

CLAIMS = {
    "spin": "The grain spin departs from half the vorticity near the walls.",
    "smoother": "Delta is independent of the gap H/d for walls smoother than the material.",
    "rough": "Delta grows as (H/d)^(1/3) for fully rough walls (under gravity, or in Couette "
    "flow).",
}


# --------------------------------------------------------------------------- per run
@dataclass
class Thickness:
    """Delta of a run's data [d] and its standard error, or why there is none."""

    value: float | None
    stderr: float | None
    reason: str = ""

    def to_dict(self) -> dict[str, Any]:
        return {"value": self.value, "stderr": self.stderr, "reason": self.reason}


def reference_velocity(run: Run) -> float:
    """u_0 of Delta: 1/2 in plane shear without gravity (the symmetric profile), else 0."""
    return 0.5 if run.cell == "plane" and run.B == 0.0 else 0.0


def thickness_of(distance_d: FloatArray, u: FloatArray, u0: float, f: float) -> float | None:
    """Where u (ordered by distance from the moving wall, linear between bins) first falls to
    ``u0 + f (u[0] - u0)``; None if it does not within the bins [d]."""
    target = u0 + f * (u[0] - u0)
    below = np.flatnonzero((u - target) * np.sign(u[0] - u0) <= 0.0)
    if u[0] == u0 or below.size == 0 or below[0] == 0:
        return None
    i = int(below[0])
    d0, d1, u_a, u_b = distance_d[i - 1], distance_d[i], u[i - 1], u[i]
    return float(d0 + (target - u_a) * (d1 - d0) / (u_b - u_a))


def measured_thickness(run: Run, f: float = DEFAULT_F, seed: int = 0) -> Thickness:
    """Delta of the run's data with its standard error (module docstring)."""
    m = run.measured()
    u0 = reference_velocity(run)
    value = thickness_of(m.distance_d, m.u_over_uw, u0, f)
    if value is None:
        return Thickness(
            None,
            None,
            f"the measured velocity does not fall to {f:g} of its wall value within the gap",
        )
    rng = np.random.default_rng(seed)
    assert m.u_err is not None
    draws = []
    for _ in range(DRAWS):
        d = thickness_of(m.distance_d, m.u_over_uw + rng.normal(0.0, m.u_err), u0, f)
        if d is not None:
            draws.append(d)
    if len(draws) < 0.9 * DRAWS:
        return Thickness(value, None, "in over 10% of redraws within the errors Delta is undefined")
    return Thickness(value, float(np.std(draws, ddof=1)))


@dataclass
class SpinComparison:
    """The measured spin beside half the measured vorticity and the models' spins."""

    available: bool
    reason: str = ""
    distance_d: FloatArray | None = None
    departure: FloatArray | None = None
    stderr: FloatArray | None = None
    near_wall: FloatArray | None = None
    chi2_near: float | None = None
    dof_near: int = 0
    p_near: float | None = None
    chi2_bulk: float | None = None
    dof_bulk: int = 0
    p_bulk: float | None = None
    predicted: dict[str, FloatArray] = field(default_factory=dict)
    spin_chi2: dict[str, float] = field(default_factory=dict)
    detectable: dict[str, float] = field(default_factory=dict)
    notes: list[str] = field(default_factory=list)

    @property
    def departs(self) -> bool:
        return self.p_near is not None and self.p_near < P_SIGNIFICANT

    def to_dict(self) -> dict[str, Any]:
        if not self.available:
            return {"available": False, "reason": self.reason}
        return {
            "available": True,
            "chi2_near_wall": self.chi2_near,
            "dof_near_wall": self.dof_near,
            "p_near_wall": self.p_near,
            "chi2_bulk": self.chi2_bulk,
            "dof_bulk": self.dof_bulk,
            "p_bulk": self.p_bulk,
            "departs_near_wall": self.departs,
            "model_spin_chi2_per_point": self.spin_chi2,
            "p_if_model_departure_were_there": self.detectable,
            "notes": self.notes,
        }


def _chi2_p(x: FloatArray) -> tuple[float | None, int, float | None]:
    if x.size == 0:
        return None, 0, None
    c = float(np.sum(x * x))
    return c, int(x.size), float(chi2_dist.sf(c, x.size))


def compare_spin(
    run: Run, ranking: Ranking | None, near_wall_d: float = NEAR_WALL_D
) -> SpinComparison:
    """omega - half vorticity of the data, near the walls and in the bulk, and each fitted
    model's prediction of it and of omega at the same bins (in units of V/d)."""
    if not run.has("omega"):
        return SpinComparison(False, "no omega and omega_se columns: the spin was not measured")
    if not run.has("half_vorticity"):
        return SpinComparison(
            False,
            "no half_vorticity and half_vorticity_se columns: nothing to set the spin against",
        )
    omega, s_o = run.quantity("omega")
    half, s_h = run.quantity("half_vorticity")
    ok = usable(omega, s_o) & usable(half, s_h)
    if np.sum(ok) < 3:
        return SpinComparison(False, "fewer than 3 bins with a finite spin and its error")
    omega, s_o, half, s_h = omega[ok], s_o[ok], half[ok], s_h[ok]
    dep = omega - half
    se = np.sqrt(s_o**2 + s_h**2)
    dist = run.distance_d[ok]
    other = run.gap_d - dist
    near = np.minimum(dist, other) <= near_wall_d
    out = SpinComparison(True, distance_d=dist, departure=dep, stderr=se, near_wall=near)
    out.chi2_near, out.dof_near, out.p_near = _chi2_p((dep / se)[near])
    out.chi2_bulk, out.dof_bulk, out.p_bulk = _chi2_p((dep / se)[~near])
    out.notes.append(
        "the standard error of omega - half vorticity is sqrt(se_omega^2 + se_half^2): the "
        "two taken as independent"
    )
    if ranking is None:
        return out
    for fit in ranking.fits:
        if not fit.ok or fit.profile is None:
            continue
        prof = fit.profile
        eps = prof.problem.eps
        xw, _ = moving_wall(prof.problem)
        d = np.clip(dist * eps, 0.0, 1.0)
        xi = d if xw == 0.0 else 1.0 - d
        fields = prof.evaluate(xi)
        model_half = -0.5 * (fields.du_dxi + fields.kappa * fields.u) * eps
        # a rheology without grain spin of its own (omega absent) predicts that the grains
        # turn with the material: spin = half the vorticity, no departure
        model_omega = model_half if fields.omega is None else fields.omega * eps
        # the data's rotation sense against the model's, from the half vorticities
        dot = float(np.sum(model_half * half))
        sign = -1.0 if dot < 0.0 else 1.0
        if dot < 0.0:
            out.notes.append(
                f"{fit.model}: the data's half vorticity has the opposite sign of the model's; "
                "the model's spins are compared with their sign reversed"
            )
        pred = sign * (model_omega - model_half)
        out.predicted[fit.model] = pred
        out.spin_chi2[fit.model] = float(np.mean(((omega - sign * model_omega) / s_o) ** 2))
        if np.any(near):
            shift = float(np.sum((pred / se)[near] ** 2))
            out.detectable[fit.model] = float(chi2_dist.sf(out.dof_near + shift, out.dof_near))
    return out


@dataclass
class RunResult:
    """Everything validate found for one run."""

    run: Run
    ranking: Ranking | None
    error: str
    spin: SpinComparison
    thickness: Thickness
    model_delta: dict[str, float | None]
    skipped: list[str]
    figure: str = ""

    def to_dict(self) -> dict[str, Any]:
        return {
            "run": self.run.name,
            "cell": self.run.cell,
            "gap_d": self.run.gap_d,
            "wall": self.run.wall,
            "roughness": self.run.roughness,
            "source": self.run.meta.get("source"),
            "error": self.error,
            "ranking": None if self.ranking is None else self.ranking.to_dict(),
            "spin": self.spin.to_dict(),
            "Delta": self.thickness.to_dict(),
            "model_delta": self.model_delta,
            "skipped": self.skipped,
            "notes": list(self.run.notes),
            "figure": self.figure,
        }


# --------------------------------------------------------------------------- across gaps
@dataclass
class GapGroup:
    """The runs of one cell and wall at several gaps, and how Delta scales."""

    key: str
    cell: str
    roughness: str | None
    B: float
    gaps: list[float]
    Delta: list[float | None]
    stderr: list[float | None]
    slope: SlopeFit | None
    reason: str
    model_slopes: dict[str, SlopeFit | None]
    notes: tuple[str, ...] = ()

    def to_dict(self) -> dict[str, Any]:
        return {
            "notes": list(self.notes),
            "key": self.key,
            "cell": self.cell,
            "roughness": self.roughness,
            "gaps": self.gaps,
            "Delta": self.Delta,
            "stderr": self.stderr,
            "slope": None if self.slope is None else self.slope.to_dict(),
            "reason": self.reason,
            "model_slopes": {
                k: None if v is None else v.to_dict() for k, v in self.model_slopes.items()
            },
        }


def _group(key: str, results: list[RunResult]) -> GapGroup:
    runs = [r.run for r in results]
    gaps = [r.gap_d for r in runs]
    deltas = [r.thickness.value for r in results]
    errs = [r.thickness.stderr for r in results]
    usable = [
        (g, d, e)
        for g, d, e in zip(gaps, deltas, errs, strict=True)
        if d is not None and e is not None and d > 0
    ]
    distinct = len({g for g, _, _ in usable})
    slope, reason = None, ""
    if distinct < 2:
        reason = f"Delta measured at {distinct} gap(s): no power law"
    else:
        slope = power_law_slope(
            [u[0] for u in usable], [u[1] for u in usable], [u[2] for u in usable]
        )
        if distinct < MIN_GAPS:
            reason = f"only {distinct} gaps (a verdict needs {MIN_GAPS})"
    models = sorted({m for r in results for m in r.model_delta})
    model_slopes: dict[str, SlopeFit | None] = {}
    for m in models:
        pts = [
            (r.run.gap_d, r.model_delta.get(m))
            for r in results
            if r.model_delta.get(m) is not None and r.model_delta[m] > 0  # type: ignore[operator]
        ]
        model_slopes[m] = (
            power_law_slope([p[0] for p in pts], [p[1] for p in pts])  # type: ignore[misc]
            if len({p[0] for p in pts}) >= 2
            else None
        )
    return GapGroup(
        key, runs[0].cell, runs[0].roughness, runs[0].B, gaps, deltas, errs, slope, reason,
        model_slopes, _replicate_notes(runs),
    )  # fmt: skip


def _replicate_notes(runs: list[Run]) -> tuple[str, ...]:
    """Say where a series holds several runs at one gap (at different wall speeds: a rate
    check): they enter the power law as replicates, which is right only if the flow is
    rate-independent, as the model assumes."""
    notes = []
    for g in sorted({r.gap_d for r in runs}):
        same = [r for r in runs if r.gap_d == g]
        if len(same) > 1:
            speeds = ", ".join(
                f"{r.name} (wall speed {r.meta.get('wall_speed', '?')})" for r in same
            )
            notes.append(
                f"H/d = {g:g} has {len(same)} runs, {speeds}: used as replicates, which assumes "
                "the rate independence the model has (compare their profiles to check it)"
            )
    return tuple(notes)


# --------------------------------------------------------------------------- verdicts
@dataclass(frozen=True)
class Verdict:
    claim: str
    verdict: str
    text: str

    def to_dict(self) -> dict[str, str]:
        return {"claim": self.claim, "verdict": self.verdict, "text": self.text}


def spin_verdict(results: list[RunResult]) -> Verdict:
    """Claim 1 (module docstring: the rule)."""
    claim = CLAIMS["spin"]
    with_spin = [r for r in results if r.spin.available and r.spin.dof_near > 0]
    if not with_spin:
        return Verdict(
            claim,
            "undecided",
            "The data cannot decide: no run has the spin and half the vorticity measured near "
            "a wall.",
        )
    departs = [r for r in with_spin if r.spin.departs]
    detail = "; ".join(
        f"{r.run.name}: chi^2 = {r.spin.chi2_near:.3g} for {r.spin.dof_near} near-wall bins "
        f"(p = {r.spin.p_near:.2g})"
        + (
            f", bulk chi^2 = {r.spin.chi2_bulk:.3g} for {r.spin.dof_bulk} (p = {r.spin.p_bulk:.2g})"
            if r.spin.p_bulk is not None
            else ""
        )
        for r in with_spin
    )
    n, k = len(with_spin), len(departs)
    if 2 * k >= n and k > 0:
        return Verdict(
            claim,
            "supported",
            f"Supported: in {k} of {n} runs the measured spin differs from half the measured "
            f"vorticity near the walls beyond the errors (p < {P_SIGNIFICANT:g}). {detail}.",
        )
    if k == 0:
        seen = [r for r in with_spin if r.spin.detectable.get("cosserat", 1.0) < P_SIGNIFICANT]
        if seen:
            return Verdict(
                claim,
                "refuted",
                f"Refuted: in none of {n} runs does the spin depart from half the vorticity "
                f"near the walls beyond the errors, although in {len(seen)} of them the "
                "departure the Cosserat model predicts (fitted to the same velocities) would "
                f"have shown with p < {P_SIGNIFICANT:g}. {detail}.",
            )
        return Verdict(
            claim,
            "undecided",
            f"The data cannot decide: no run shows a departure, but the errors are too large "
            "to have seen the departure the Cosserat model predicts for these runs (or no "
            f"Cosserat fit). {detail}.",
        )
    return Verdict(
        claim,
        "mixed",
        f"Mixed: {k} of {n} runs show a significant departure near the walls, the others do "
        f"not. {detail}.",
    )


def scaling_verdict(groups: list[GapGroup], which: str) -> Verdict:
    """Claim 2 (``which`` = "smoother", exponent 0) or 3 ("rough", exponent 1/3)."""
    claim = CLAIMS[which]
    target = PAPER_SLOPES["smoother walls" if which == "smoother" else "fully rough walls"]
    other = PAPER_SLOPES["fully rough walls" if which == "smoother" else "smoother walls"]
    if which == "smoother":
        relevant = [g for g in groups if g.roughness == "smoother" and g.cell != "channel"]
    else:
        relevant = [
            g
            for g in groups
            if g.roughness == "fully-rough"
            and (g.cell == "couette" or g.B > 0)
            and g.cell != "channel"
        ]
    kind = "smoother than the material" if which == "smoother" else "fully rough"
    if not relevant:
        return Verdict(
            claim,
            "undecided",
            f"The data cannot decide: no series of runs with walls {kind}"
            + (" under gravity or in Couette flow" if which == "rough" else "")
            + " (the sidecars' wall.kind says which: smooth-frictional or glued-grains).",
        )
    calls = []
    for g in relevant:
        s = g.slope
        head = f"{g.key}: "
        if s is None or g.reason:
            calls.append(("undecided", head + (g.reason or "no slope")))
            continue
        se = s.stderr
        text = (
            head
            + f"slope {s.slope:.3f} +- {se:.2g} over H/d = "
            + ", ".join(f"{x:g}" for x in sorted(set(g.gaps)))
        )
        cos = g.model_slopes.get("cosserat")
        if cos is not None:
            text += f" (the Cosserat fits to these runs give {cos.slope:.3f})"
        text += "".join(f"; note: {n}" for n in g.notes)
        if se is None:
            calls.append(("undecided", text + "; no error on the slope"))
        elif abs(s.slope - target) <= 2 * se and abs(s.slope - other) > 2 * se:
            calls.append(("supported", text))
        elif abs(s.slope - target) > 2 * se:
            if (
                cos is not None
                and abs(cos.slope - target) > 2 * se
                and (abs(s.slope - cos.slope) <= 2 * se)
            ):
                calls.append(
                    (
                        "undecided",
                        text + "; at these gaps the Cosserat model itself does not show the "
                        f"exponent {target:.3g} of the limit H/d -> infinity, and the data agree "
                        "with the model's own slope: larger gaps are needed to test the law",
                    )
                )
            else:
                calls.append(("refuted", text))
        else:
            calls.append(
                ("undecided", text + f"; the errors cannot tell {target:.3g} from {other:.3g}")
            )
    decided = {c for c, _ in calls if c != "undecided"}
    detail = "; ".join(t for _, t in calls)
    want = f"exponent {target:.3g}" if which == "rough" else "exponent 0"
    if not decided:
        return Verdict(claim, "undecided", f"The data cannot decide ({want} claimed): {detail}.")
    if len(decided) > 1:
        return Verdict(claim, "mixed", f"Mixed: the wall series disagree ({want}): {detail}.")
    verdict = decided.pop()
    word = "Supported" if verdict == "supported" else "Refuted"
    return Verdict(
        claim, verdict, f"{word}: the measured Delta against H/d ({want} claimed): {detail}."
    )


# --------------------------------------------------------------------------- the study
@dataclass
class ValidationReport:
    corpus: Path
    models: list[str]
    results: list[RunResult]
    groups: list[GapGroup]
    verdicts: list[Verdict]
    f: float
    near_wall_d: float
    files: dict[str, str] = field(default_factory=dict)

    def to_dict(self) -> dict[str, Any]:
        return {
            "corpus": str(self.corpus),
            "models": self.models,
            "f": self.f,
            "near_wall_d": self.near_wall_d,
            "p_significant": P_SIGNIFICANT,
            "min_gaps": MIN_GAPS,
            "verdicts": [v.to_dict() for v in self.verdicts],
            "runs": [r.to_dict() for r in self.results],
            "gap_series": [g.to_dict() for g in self.groups],
        }

    def to_text(self) -> str:
        lines = [f"Validation against {self.corpus} ({len(self.results)} runs)", ""]
        for v in self.verdicts:
            lines += [f"[{v.verdict}] {v.claim}", f"  {v.text}", ""]
        for r in self.results:
            best = r.ranking.best.model if r.ranking and r.ranking.best else "-"
            lines.append(
                f"{r.run.name}: {r.run.cell}, H/d = {r.run.gap_d:g}, best by AIC: {best}"
                + (f" ({r.error})" if r.error else "")
            )
        return "\n".join(lines) + "\n"


CHANNEL_NOTE = (
    "the vertical channel has no moving wall: the models are compared with velocities over a "
    "wall speed, and Delta is measured from a moving wall, so neither is done for this run "
    "(its spin is compared)"
)


def _fit_run(run: Run, models: Sequence[str] | None, grid: int) -> tuple[Ranking | None, str]:
    if run.cell == "channel":
        return None, CHANNEL_NOTE
    try:
        names = models
        if names is not None:
            from ..routes import cells_for

            names = [m for m in names if run.cell in cells_for(m)]
        ranking = rank_models(run.measured(), run.cell_parameters(), names, grid=grid)
    except CosseratError as exc:
        return None, " ".join(str(exc).split())
    return ranking, ""


def validate(
    corpus: str | Path | Corpus | None = None,
    out: str | Path | None = None,
    models: Sequence[str] | None = None,
    *,
    f: float = DEFAULT_F,
    near_wall_d: float = NEAR_WALL_D,
    grid: int = 3,
    progress: Callable[[str, int, int], None] | None = None,
) -> ValidationReport:
    """Fit, compare and judge every run of ``corpus``; write the report into ``out``.

    Parameters
    ----------
    corpus : folder, Corpus or None
        A folder of runs in the corpus format; None: the corpus shipped with the package.
    out : folder, optional
        Where to write ``report.md``, ``index.html``, ``results.json`` and the figures (each
        file atomically); nothing is written without it.
    models : sequence of str, optional
        Registered rheologies to fit (default: every one defined on a run's cell).
    f : float
        Fraction defining Delta (default 0.05) [-].
    near_wall_d : float
        Bins within this distance of a wall count as near it [d].
    grid : int
        Start-grid points per free parameter of each fit.

    Raises
    ------
    InputError
        A malformed corpus (:func:`cosserat.analysis.corpus.read_corpus`).
    ParameterError
        f outside (0, 1) or an unknown model name.
    """
    if not 0.0 < f < 1.0:
        raise ParameterError(f"f must satisfy 0 < f < 1; got {f:g}")
    from ..routes import RHEOLOGIES

    if models is not None:
        bad = [m for m in models if m not in RHEOLOGIES]
        if bad:
            raise ParameterError(
                f"unknown model(s) {', '.join(bad)}: registered are {', '.join(RHEOLOGIES)}"
            )
    data = corpus if isinstance(corpus, Corpus) else read_corpus(corpus)
    results: list[RunResult] = []
    for i, run in enumerate(data.runs):
        ranking, error = _fit_run(run, models, grid)
        skipped = [
            f"{q}: not in this run" for q in run.missing() if q in ("omega", "half_vorticity")
        ]
        spin = compare_spin(run, ranking, near_wall_d)
        if not spin.available:
            skipped.append(f"spin comparison skipped: {spin.reason}")
        thickness = (
            Thickness(None, None, CHANNEL_NOTE)
            if run.cell == "channel"
            else measured_thickness(run, f)
        )
        model_delta: dict[str, float | None] = {}
        if ranking is not None:
            m = run.measured()
            for fit in ranking.fits:
                if fit.ok:
                    model_delta[fit.model] = thickness_of(
                        m.distance_d, fit.curve(m.distance_d), reference_velocity(run), f
                    )
        results.append(RunResult(run, ranking, error, spin, thickness, model_delta, skipped))
        if progress:
            progress("runs", i + 1, len(data.runs))
    groups_by_key: dict[str, list[RunResult]] = {}
    for r in results:
        groups_by_key.setdefault(r.run.wall_key, []).append(r)
    groups = [
        _group(k, sorted(v, key=lambda r: r.run.gap_d)) for k, v in sorted(groups_by_key.items())
    ]
    verdicts = [
        spin_verdict(results),
        scaling_verdict(groups, "smoother"),
        scaling_verdict(groups, "rough"),
    ]
    used = sorted({fit.model for r in results if r.ranking for fit in r.ranking.fits})
    report = ValidationReport(data.path, used, results, groups, verdicts, f, near_wall_d)
    if out is not None:
        write_report(report, out)
    return report


# --------------------------------------------------------------------------- figures
def _model_style(model: str) -> dict[str, Any]:
    """One colour and line style per registered model, the same in every panel."""
    from ..routes import RHEOLOGIES

    i = list(RHEOLOGIES).index(model) if model in RHEOLOGIES else len(RHEOLOGIES)
    return {"color": f"C{i % 10}", "linestyle": ["-", "--", "-.", ":"][i % 4]}


def run_figure(result: RunResult):  # type: ignore[no-untyped-def]
    """Velocity with error bands and the fitted models; spin minus half vorticity."""
    from ..viz.plotting import new_figure, style

    m = result.run.measured()
    spin = result.spin
    ncols = 2 if spin.available else 1
    fig, axes = new_figure(1, ncols, width=3.4 * ncols, height=3.0)
    with style():
        ax = axes[0, 0]
        assert m.u_err is not None
        ax.fill_between(
            m.distance_d, m.u_over_uw - m.u_err, m.u_over_uw + m.u_err, color="0.8", linewidth=0
        )
        ax.plot(m.distance_d, m.u_over_uw, "o", color="k", markerfacecolor="none", label="data")
        if result.ranking is not None:
            d = np.linspace(0.0, float(m.distance_d.max()), 200)
            for fit in result.ranking.ranked:
                if fit.ok:
                    ax.plot(d, fit.curve(d), label=fit.model, **_model_style(fit.model))
        ax.set_xlabel(r"distance from the moving wall [$d$]")
        ax.set_ylabel(r"$u/V$")
        ax.legend(fontsize=7)
        if spin.available:
            ax = axes[0, 1]
            assert spin.distance_d is not None and spin.departure is not None
            assert spin.stderr is not None
            order = np.argsort(spin.distance_d)
            x, y, e = spin.distance_d[order], spin.departure[order], spin.stderr[order]
            ax.fill_between(x, y - e, y + e, color="0.8", linewidth=0)
            ax.plot(x, y, "o", color="k", markerfacecolor="none", label="data")
            for name, pred in spin.predicted.items():
                ax.plot(x, pred[order], label=name, **_model_style(name))
            ax.axhline(0.0, color="0.5", linewidth=0.6)
            ax.set_xlabel(r"distance from the moving wall [$d$]")
            ax.set_ylabel(r"$(\omega - \frac{1}{2}\,\mathrm{vorticity})\,d/V$")
            ax.legend(fontsize=7)
        fig.suptitle(
            f"{result.run.name}: {result.run.cell}, H/d = {result.run.gap_d:g}", fontsize=8
        )
        fig.tight_layout()
    return fig


def gap_figure(groups: list[GapGroup]):  # type: ignore[no-untyped-def]
    """Measured Delta against H/d on log axes, one series per cell and wall, slope 1/3."""
    from ..viz.plotting import new_figure, style

    fig, axes = new_figure(1, 1, width=5.0, height=3.6)
    ax = axes[0, 0]
    markers = ["o", "s", "D", "^", "v", "*"]
    with style():
        all_g, all_d = [], []
        for i, g in enumerate(groups):
            pts = [
                (x, d, e)
                for x, d, e in zip(g.gaps, g.Delta, g.stderr, strict=True)
                if d is not None and d > 0
            ]
            if not pts:
                continue
            x = np.array([p[0] for p in pts])
            y = np.array([p[1] for p in pts])
            e = np.array([p[2] if p[2] is not None else 0.0 for p in pts])
            label = g.key + ("" if g.slope is None else f": slope {g.slope.text()}")
            ax.errorbar(x, y, yerr=e, marker=markers[i % 6], capsize=2, label=label)
            all_g += list(x)
            all_d += list(y)
        if all_g:
            g0, g1 = min(all_g) / 1.2, max(all_g) * 1.2
            gg = np.geomspace(g0, g1, 20)
            d0 = float(np.exp(np.mean(np.log(all_d))))
            gm = math.sqrt(g0 * g1)
            ax.plot(gg, d0 * (gg / gm) ** (1 / 3), "k:", linewidth=0.8, label="slope 1/3")
            ax.plot(gg, np.full_like(gg, d0), color="0.6", linestyle="--", linewidth=0.8,
                    label="slope 0")  # fmt: skip
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel(r"$H/d$")
        ax.set_ylabel(r"$\Delta$ [$d$]")
        if all_g:
            ax.legend(fontsize=6)
        else:
            ax.text(0.5, 0.5, "no Delta measured", ha="center", transform=ax.transAxes)
        fig.tight_layout()
    return fig


# --------------------------------------------------------------------------- the report
def _fmt(x: float | None, spec: str = ".4g") -> str:
    return "-" if x is None else format(x, spec)


def write_report(report: ValidationReport, out: str | Path) -> dict[str, str]:
    """Write the figures, ``report.md``, ``index.html`` and ``results.json`` into ``out``."""
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    from ..viz.plotting import style

    files: dict[str, str] = {}
    for r in report.results:
        fig = run_figure(r)
        name = f"run_{r.run.name}.png"
        with style():
            save_figure(fig, out / name)
        r.figure = name
        files[r.run.name] = name
    fig = gap_figure(report.groups)
    with style():
        save_figure(fig, out / "delta_vs_gap.png")
    files["delta_vs_gap"] = "delta_vs_gap.png"
    report.files = files
    md, body = _markdown(report), _html(report)
    write_text(out / "report.md", md)
    write_text(out / "index.html", body)
    write_text(out / "results.json", json.dumps(_finite(report.to_dict()), indent=1) + "\n")
    return files


def _finite(obj: Any) -> Any:
    if isinstance(obj, float) and not math.isfinite(obj):
        return None
    if isinstance(obj, dict):
        return {k: _finite(v) for k, v in obj.items()}
    if isinstance(obj, list | tuple):
        return [_finite(v) for v in obj]
    if isinstance(obj, np.ndarray):
        return _finite(obj.tolist())
    if isinstance(obj, np.floating | np.integer | np.bool_):
        return _finite(obj.item())
    return obj


def _rules() -> str:
    return (
        f"Rules: a run's spin departs near a wall when chi^2 of (omega - half vorticity)/se "
        f"over its bins within the near-wall distance has p < {P_SIGNIFICANT:g}; a slope of "
        f"ln Delta against ln(H/d) (at least {MIN_GAPS} gaps, weighted by the errors of Delta) "
        "supports a claimed exponent when within 2 standard errors of it and more than 2 "
        "from the other claimed exponent (0 or 1/3), and refutes it when more than 2 standard "
        "errors away, unless the Cosserat model fitted to the same runs misses the exponent "
        "too and the data agree with the model's slope (the claims are limits H/d -> infinity: "
        "undecided, larger gaps needed). Delta of the data: where the velocity falls to f of "
        "its value in the bin nearest the moving wall (u_0 = 1/2 for plane shear without "
        "gravity, else 0)."
    )


def _run_rows(report: ValidationReport) -> list[list[str]]:
    rows = []
    for r in report.results:
        fits = {f.model: f for f in r.ranking.fits} if r.ranking else {}
        best = r.ranking.best.model if r.ranking and r.ranking.best else "-"
        per_model = "; ".join(
            f"{m}: red. chi2 {_fmt(f.reduced_chi2, '.3g')}, AIC {_fmt(f.aic, '.4g')}"
            if f.ok
            else f"{m}: {f.message}"
            for m, f in fits.items()
        )
        rows.append(
            [
                r.run.name,
                r.run.cell,
                f"{r.run.gap_d:g}",
                str(r.run.roughness or "-"),
                best,
                per_model or r.error,
                _delta_text(r),
            ]
        )  # fmt: skip
    return rows


def _delta_text(r: RunResult) -> str:
    """The data's Delta with its error, then each fitted model's by the same estimator."""
    t = r.thickness
    data = "-" if t.value is None else f"{t.value:.4g}"
    data += "" if t.stderr is None else f" +- {t.stderr:.2g}"
    models = "; ".join(f"{m} {_fmt(d)}" for m, d in r.model_delta.items())
    return f"data {data}" + (f"; {models}" if models else "")


RUN_HEADER = ["run", "cell", "H/d", "wall", "best (AIC)", "fits", "Delta [d]"]


def _markdown(report: ValidationReport) -> str:
    md = [
        "# Validation of the models against measured profiles",
        "",
        f"Corpus: `{report.corpus}` ({len(report.results)} runs); models fitted: "
        f"{', '.join(report.models) or 'none'}; Delta with f = {report.f:g}; near the wall: "
        f"within {report.near_wall_d:g} d.",
        "",
        "## Verdicts on the paper's claims",
        "",
    ]
    for v in report.verdicts:
        md += [f"**{v.claim}** Verdict: *{v.verdict}*. {v.text}", ""]
    md += [_rules(), "", "## Runs", ""]
    md += ["| " + " | ".join(RUN_HEADER) + " |", "|" + "---|" * len(RUN_HEADER)]
    md += ["| " + " | ".join(row) + " |" for row in _run_rows(report)]
    md += ["", "## Delta against the gap", "", "![Delta against H/d](delta_vs_gap.png)", ""]
    for g in report.groups:
        pts = ", ".join(
            f"H/d = {x:g}: {_fmt(d)}" + ("" if e is None else f" +- {e:.2g}")
            for x, d, e in zip(g.gaps, g.Delta, g.stderr, strict=True)
        )
        slope = "no slope" if g.slope is None else f"slope {g.slope.text()}"
        models = ", ".join(f"{m} {s.slope:.3f}" for m, s in g.model_slopes.items() if s)
        md.append(
            f"* {g.key}: {pts}; {slope}" + (f" ({g.reason})" if g.reason else "")
            + (f"; fitted models' slopes: {models}" if models else "")
        )  # fmt: skip
    md += ["", "## Each run", ""]
    for r in report.results:
        md += [f"### {r.run.name}", "", f"![{r.run.name}]({r.figure})", ""]
        if r.ranking is not None:
            md += ["```", r.ranking.to_text().rstrip(), "```", ""]
        if r.error:
            md += [f"Not fitted: {r.error}", ""]
        md += [f"* {s}" for s in r.skipped + list(r.run.notes) + r.spin.notes]
        md.append("")
    return "\n".join(md) + "\n"


def _html(report: ValidationReport) -> str:
    e = html.escape
    parts = [
        "<!doctype html><html><head><meta charset='utf-8'><title>cosserat validate</title>"
        "<style>body{font-family:serif;max-width:64em;margin:auto}img{max-width:100%}"
        "td,th{border:1px solid #ccc;padding:3px;font-size:90%}table{border-collapse:collapse}"
        "pre{font-size:80%}</style></head><body>",
        "<h1>Validation of the models against measured profiles</h1>",
        f"<p>Corpus: <code>{e(str(report.corpus))}</code> ({len(report.results)} runs); "
        f"models fitted: {e(', '.join(report.models) or 'none')}; Delta with f = {report.f:g}."
        "</p><h2>Verdicts on the paper's claims</h2>",
    ]
    for v in report.verdicts:
        parts.append(f"<p><b>{e(v.claim)}</b> Verdict: <i>{e(v.verdict)}</i>. {e(v.text)}</p>")
    parts.append(f"<p><small>{e(_rules())}</small></p><h2>Runs</h2><table><tr>")
    parts.append("".join(f"<th>{e(h)}</th>" for h in RUN_HEADER) + "</tr>")
    for row in _run_rows(report):
        parts.append("<tr>" + "".join(f"<td>{e(c)}</td>" for c in row) + "</tr>")
    parts.append(
        "</table><h2>Delta against the gap</h2><img src='delta_vs_gap.png' alt='Delta vs H/d'>"
    )
    parts.append("<h2>Each run</h2>")
    for r in report.results:
        parts.append(f"<h3>{e(r.run.name)}</h3><img src='{e(r.figure)}' alt='{e(r.run.name)}'>")
        if r.ranking is not None:
            parts.append(f"<pre>{e(r.ranking.to_text())}</pre>")
        notes = r.skipped + list(r.run.notes) + r.spin.notes + ([r.error] if r.error else [])
        if notes:
            parts.append("<ul>" + "".join(f"<li>{e(n)}</li>" for n in notes) + "</ul>")
    parts.append("</body></html>\n")
    return "".join(parts)


__all__ = [
    "CLAIMS",
    "GapGroup",
    "RunResult",
    "SpinComparison",
    "Thickness",
    "ValidationReport",
    "Verdict",
    "compare_spin",
    "measured_thickness",
    "scaling_verdict",
    "spin_verdict",
    "thickness_of",
    "validate",
    "write_report",
]
