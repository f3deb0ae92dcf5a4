"""Validation of the models against a corpus: the orchestration.

For every run: fit the models to its velocity (:mod:`.fits`), measure Delta, the spin at each
wall, the band's stress ratio and the inertial number at the moving wall (:mod:`.measures`),
and set each model's predicted spin departure beside the measured one. Across runs: the gap
series (:mod:`.grouping`) and the verdicts (:mod:`.verdicts`). Writing is
:mod:`cosserat.studies.validate.report`'s.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping, Sequence
from concurrent.futures import FIRST_COMPLETED, Future, wait
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ...analysis.corpus import Corpus, Run, read_corpus
from ...analysis.gap import SlopeFit, power_law_slope
from ...config import DEFAULT_F
from ...errors import ParameterError
from ...model.constitutive import FloatArray
from .fits import (
    MaterialJob,
    RunFits,
    SeriesCalibration,
    StressFix,
    cosserat_fix,
    material_job,
    try_fit_run,
)
from .forward import STENCILS
from .grouping import couette_note, group_materials, group_runs, material_of, walls_differ
from .layer import LayerPosition, band_inertial_number, layer_verdicts, measure_layer
from .measures import (
    BALANCE_SIGMAS,
    HEXAGONAL_NU,
    INVERSION_SIGMAS,
    MISS_PLACES,
    NEAR_WALL_D,
    NU_STEP,
    P_SIGNIFICANT,
    SENSITIVITY_F,
    TRUNCATED_FRACTION,
    WALL_EXCLUSION_D,
    WINDOW_TRAVEL_D,
    DeltaSensitivity,
    SpinMeasure,
    StressRatio,
    Thickness,
    WallBins,
    WallSpin,
    YBalance,
    autocorrelation_text,
    band_stress_ratio,
    measure_spin,
    measured_thickness,
    miss_place,
    moving_wall_inertial_number,
    reference_velocity,
    thickness_of,
    thickness_sensitivity,
    wall_bins,
    wall_p_source,
    window_travel,
    y_balance,
)
from .nulls import (
    Null,
    envelope,
    joint_null,
    monotone_beyond,
    point_null,
    velocity_null,
    with_null,
)
from .rate import (
    balance_record,
    balance_rescaled_text,
    balance_warning,
    misfit_twin_text,
    replicate_cells,
    slip_text,
    static_rescaled_text,
    twin_names,
    twin_pairs,
)
from .spin_scan import (
    COARSE,
    Scan,
    mark_seed_basins,
    scan_or_skip,
    scan_region,
    scan_verdict,
    shared_fits,
    spin_scans,
)
from .summaries import summary as verdict_summary
from .verdicts import (
    MIN_GAPS,
    SAME_GAP,
    DeltaPoint,
    DeltaSeries,
    ModelDelta,
    SpinRun,
    Verdict,
    delta_law_verdict,
    spin_model_verdict,
    spin_verdict,
    within_regime,
)
from .wall_k import check_scans

QUASI_STATIC_I = 1e-3
"""Largest local inertial number of the slow flow the models are for [-]."""

LAYER_NOTE = (
    "walls of two kinds without gravity: the band sits at the smoother wall (the layer claim), "
    "and Delta, measured from the moving wall, is not defined for it; this run is in no Delta "
    "series"
)

CHANNEL_NOTE = (
    "the vertical channel has no moving wall: the models are compared with velocities over a "
    "wall speed, and Delta is measured from a moving wall, so neither is done for this run "
    "(its spin is compared)"
)


@dataclass
class RunResult:
    """Everything validate found for one run."""

    run: Run
    fits: RunFits | None
    error: str
    spin: SpinMeasure
    thickness: Thickness
    model_delta: dict[str, float | None]
    skipped: list[str]
    stress: StressRatio | None = None
    inertial_number: float | None = None
    figure: str = ""
    layer: LayerPosition | None = None
    sensitivity: DeltaSensitivity | None = None
    joint: dict[str, Any] | None = None
    """The spin scan's joint u + omega + stress-ratio fit for the run's figure
    (``forward.figure_curves``; None where the run was not scanned): the velocity of both
    spin verdicts' null."""
    figure_joint: bool = False
    """True when ``figure`` was drawn with ``joint`` (by :func:`figure_job`), so the
    report need not draw it again."""

    def to_dict(self) -> dict[str, Any]:
        return {
            "run": self.run.name,
            "cell": self.run.cell,
            "gap_d": self.run.gap_d,
            "wall": self.run.wall,
            "roughness": self.run.roughness,
            "source": self.run.meta.get("source"),
            "error": self.error,
            "ranking": None if self.fits is None else self.fits.to_dict(),
            "spin": self.spin.to_dict(),
            "Delta": self.thickness.to_dict(),
            "Delta_sensitivity": None if self.sensitivity is None else self.sensitivity.to_dict(),
            "model_delta": self.model_delta,
            "band_stress_ratio": None if self.stress is None else self.stress.to_dict(),
            "moving_wall_inertial_number": self.inertial_number if self.layer is None else None,
            "band_inertial_number": self.inertial_number if self.layer is not None else None,
            "layer": None if self.layer is None else self.layer.to_dict(),
            "block_autocorrelation": self.run.meta.get("block_autocorrelation"),
            "skipped": self.skipped,
            "notes": list(self.run.notes),
            "figure": self.figure,
        }


@dataclass
class ValidationReport:
    """The result of :func:`validate`: runs, gap series, verdicts."""

    corpus: Path
    models: list[str]
    results: list[RunResult]
    groups: list[DeltaSeries]
    verdicts: list[Verdict]
    f: float
    near_wall_d: float
    notes: list[str] = field(default_factory=list)
    files: dict[str, str] = field(default_factory=dict)

    def verdict(self, key: str) -> Verdict:
        return next(v for v in self.verdicts if v.key == key)

    def to_dict(self) -> dict[str, Any]:
        return {
            "schema": "cosserat-validate/2",
            "corpus": str(self.corpus),
            "models": self.models,
            "f": self.f,
            "near_wall_d": self.near_wall_d,
            "p_significant": P_SIGNIFICANT,
            "min_gaps": MIN_GAPS,
            "verdicts": [v.to_dict() for v in self.verdicts],
            "runs": [r.to_dict() for r in self.results],
            "gap_series": [g.to_dict() for g in self.groups],
            "twins": [p.to_dict() for p in twin_pairs(self.results)],
            "notes": self.notes,
            "files": self.files,
        }

    def to_text(self) -> str:
        lines = [f"Validation against {self.corpus} ({len(self.results)} runs)", ""]
        for v in self.verdicts:
            qualified = f"{v.verdict}, {v.qualifier}" if v.qualifier else v.verdict
            lines += [f"[{qualified}] {v.claim}", f"  {v.text}", ""]
        for r in self.results:
            best = r.fits.best if r.fits and r.fits.best else "-"
            lines.append(
                f"{r.run.name}: {r.run.cell}, H/d = {r.run.gap_d:g}, best by AIC: {best}"
                + (f" ({r.error})" if r.error else "")
            )
        return "\n".join(lines) + "\n"


def _l_region(region: Mapping[str, Any]) -> Any:
    """A scan's 95% region in L for the layer warning (``layer._LRegion``): its (lowest,
    highest) L [d], or each island's interval where it has several (review of stop 29: a
    run's islands are alternatives, and the span between them holds no admissible point)."""
    islands = [tuple(i["L"]) for i in region.get("islands") or () if i.get("L")]
    if len(islands) > 1:
        return [(float(a), float(b)) for a, b in islands]
    return (float(region["L"][0]), float(region["L"][1]))


def _model_slopes(results: Sequence[RunResult]) -> dict[str, SlopeFit | None]:
    out: dict[str, SlopeFit | None] = {}
    for m in sorted({m for r in results for m in r.model_delta}):
        pts = [
            (r.run.gap_d, d) for r in results if (d := r.model_delta.get(m)) is not None and d > 0.0
        ]
        ok = len({g for g, _ in pts}) >= 2
        out[m] = power_law_slope([g for g, _ in pts], [d for _, d in pts]) if ok else None
    return out


def _spin_model_inputs(
    results: Sequence[RunResult], model: str = "cosserat"
) -> tuple[list[WallSpin], str, dict[str, str], list[str]]:
    """The walls ``spin_model`` judges, the model, the runs whose fit of it cannot predict
    (:attr:`~.fits.FitSummary.unfit_reason`) and the walls left out: the fixed wall of a run
    whose walls differ (the fits give it the moving wall's kind, so they predict nothing there)."""
    walls, left_out = [], []
    unfit: dict[str, str] = {}
    for r in results:
        if not r.spin.available:
            continue
        differ = walls_differ(r.run)
        for w in r.spin.walls:
            if differ and w.wall == "fixed":
                if w.sheared:
                    left_out.append(
                        f"{w.run} (fixed wall: its kind differs from the moving wall's, which "
                        "the fits give it, so they predict nothing there)"
                    )
                continue
            walls.append(w)
        s = r.fits.summary(model) if r.fits else None
        if s is not None and s.ok and s.unfit_reason:
            unfit[r.run.name] = s.unfit_reason
    return walls, model, unfit, left_out


def _scans(results: Sequence[RunResult], points: int) -> tuple[list[Scan], list[str]]:
    """The spin scans of :mod:`.spin_scan` (``points`` per parameter; none at 0) and the runs
    left out, each with why."""
    if points <= 0:
        return [], []
    corpus = [r.run for r in results]
    scans, skipped = spin_scans([r.run for r in results if r.spin.available], corpus, points)
    check_scans(scans, corpus)  # eqn-bc3 against the measured K (referee 8, points 2-3)
    return scans, skipped


def _joint_curves(results: Sequence[RunResult], scans: Sequence[Scan]) -> None:
    """Each scanned run's joint fit for its figure (:attr:`RunResult.joint`)."""
    from ...calibration.models import SOLVE_ERRORS
    from .forward import (
        calibration_profile,
        figure_curves,
        grain_layers,
        model_fields,
        turning_with_the_material,
    )

    by_name = {r.run.name: r for r in results}
    for sc in scans:
        r = by_name.get(sc.run)
        if r is None:
            continue
        try:
            profile = calibration_profile(sc.fit.setup, sc.fit.theta)
            r.joint = {**figure_curves(profile, r.run), "K": sc.fit.value("K"),
                       "L": sc.fit.value("L"),
                       # its region's islands: the fit is one of them (referee 14, point 8)
                       "basins": len((scan_region(sc) or {}).get("islands", ()))}  # fmt: skip
            grains = _moving_grains(r.run)
            if grains is not None and grains.get("r_1"):  # the grain-scale null (referee 12)
                fields = model_fields(profile, r.run)
                r.joint["grain_null"] = grain_layers(
                    turning_with_the_material(fields), r.run, float(grains["r_1"])
                )
                r.joint["grain_model"] = grain_layers(fields, r.run, float(grains["r_1"]))
        except SOLVE_ERRORS:
            r.joint = None


def _wall_grains(run: Run, wall: str | None) -> Mapping[str, Any] | None:
    """The sidecar's grain-by-grain first-layer record (``first_layer``,
    ``cosserat.dem.first_layer``) at a plane run's wall ``wall`` ("upper" or "lower"); None
    where not recorded."""
    record = run.meta.get("first_layer")
    if run.cell != "plane" or not isinstance(record, Mapping) or wall is None:
        return None
    found = (record.get("walls") or {}).get(wall)
    return found if isinstance(found, Mapping) else None


def _moving_grains(run: Run) -> Mapping[str, Any] | None:
    """:func:`_wall_grains` at the run's moving wall."""
    return _wall_grains(run, run.moving_wall)


def _fixed_grains(run: Run) -> Mapping[str, Any] | None:
    """:func:`_wall_grains` at a plane run's fixed wall, which ``cosserat.dem.first_layer``
    records only where that wall shears (layer 1 moves relative to it by at least 0.05 V: the
    layer runs' smooth fixed walls); None where not recorded or marked moving (referee 14,
    point 2: read model-free beside the moving walls')."""
    fixed = {"upper": "lower", "lower": "upper"}.get(run.moving_wall)
    wall = _wall_grains(run, fixed)
    return None if wall is None or wall.get("moving", False) else wall


@dataclass
class ScanOutcome:
    """One run's part of ``_scans``, made alone (:func:`scan_job`, in a worker process
    when there are workers): its scan with its wall check (``Scan.wall_k``) and its joint
    fit's null, or why it is left out."""

    run: str
    scan: Scan | None = None
    skipped: str = ""
    null: Null | None = None


@dataclass
class Scanned:
    """``_scans`` and the joint fits' nulls of ``_joint_nulls``, made before
    :func:`judge` (by :func:`validate`, its runs' scans in parallel)."""

    scans: list[Scan]
    skipped: list[str]
    nulls: dict[str, Null]
    figure_of: bytes | None = None
    """The scans' ``to_dict`` (pickled) from which the spin scan's figure was drawn already,
    in the pool, while the other jobs ran (``_analyse_all``); the report draws it again
    only if the verdict's scans differ (``report.write_figures``). None: not drawn."""


def scan_job(run: Run, corpus: Sequence[Run], points: int) -> ScanOutcome:
    """The scan of one run (:func:`.spin_scan.scan_or_skip`), its wall check
    (:func:`.wall_k.check_scans`) and its joint fit's null (:func:`.nulls.joint_null`): each
    depends on this run's scan alone, so runs can be scanned in parallel; the material's
    shared fit (:func:`.spin_scan.shared_fits`) is made afterwards over every scan
    (:func:`gather_scans`)."""
    got = scan_or_skip(run, corpus, points)
    if not isinstance(got, Scan):
        return ScanOutcome(run.name, skipped=got or "")
    check_scans([got], corpus)
    return ScanOutcome(run.name, got, null=joint_null(got, run))


def figure_job(result: RunResult, scan: Scan | None, out: Path) -> tuple[str, Any]:
    """Draw a run's figure once its scan is made (in a worker process): the scan's joint fit
    (``_joint_curves``, None without a scan) set on ``result`` and drawn with the run's own
    fits; returns (the figure's file name, the joint fit's curves)."""
    from .report import write_run_figure

    if scan is not None:
        _joint_curves([result], [scan])
    return write_run_figure(result, out), result.joint


def shared_job(scans: Sequence[Scan], scanned_runs: Sequence[Run]) -> dict[str, dict[str, Any]]:
    """:func:`.spin_scan.shared_fits` of ``scans`` (in a worker process): run name -> its
    ``Scan.shared``."""
    shared_fits(scans, scanned_runs)
    return {sc.run: sc.shared for sc in scans}


def gather_scans(
    outcomes: Sequence[ScanOutcome],
    scanned_runs: Sequence[Run],
    shared: Mapping[str, dict[str, Any]] | None = None,
) -> Scanned:
    """The scans of :func:`scan_job` in the runs' order, each material's shared fit over them
    (:func:`.spin_scan.shared_fits`, with ``scanned_runs``: the runs with a measured spin, as
    ``_scans`` gives it) as :func:`.spin_scan.spin_scans` makes it; ``shared``: those fits
    already made (:func:`shared_job`), else made here."""
    scans = [o.scan for o in outcomes if o.scan is not None]
    skipped = [o.skipped for o in outcomes if o.scan is None and o.skipped]
    if shared is None:
        shared_fits(scans, scanned_runs)
    else:
        for sc in scans:
            if sc.run in shared:
                sc.shared = shared[sc.run]
    mark_seed_basins(scans)  # the seed pairs' panel notes (referee 17, point 1)
    nulls = {o.run: o.null for o in outcomes if o.null is not None}
    return Scanned(scans, skipped, nulls)


def _joint_nulls(
    results: Sequence[RunResult],
    scans: Sequence[Scan],
    nulls: Mapping[str, Null] | None = None,
) -> str:
    """Put each scanned run's joint-fit null (:func:`.nulls.joint_null`, spin_model's) on its
    walls in ``results`` (one null for both spin verdicts, referee 8, point 4); return one
    sentence with the first layer beyond every null the run has (the joint fit's, the u-only
    fits', the measured velocity's), the systematic a choice of velocity would make ("" without
    a scan). ``nulls``: the joint nulls already made (run name -> null), else made here."""
    by_name = {r.run.name: r for r in results}
    rows = []
    for sc in scans:
        r = by_name.get(sc.run)
        if r is None or not r.spin.available or r.spin.rows is None:
            continue
        joint = nulls[sc.run] if nulls and sc.run in nulls else joint_null(sc, r.run)
        spin = r.spin
        spin_rows = r.spin.rows
        spin.walls = [
            w
            if w.no_null
            else with_null(w, joint, spin_rows[spin.index[w.wall]], spin.wall_rows[w.wall])
            for w in spin.walls
        ]
        env = spin.envelope
        if env is None:
            continue
        every = envelope([joint, env], "every velocity")
        a = "analysis"  # the interval beside the test (bin 2's envelope, referee 10 point 3)
        spin.walls = [
            replace(
                w,
                null_every=(
                    np.asarray(every.lo[a], dtype=float)[spin_rows[spin.index[w.wall]]],
                    np.asarray(every.hi[a], dtype=float)[spin_rows[spin.index[w.wall]]],
                ),
            )
            if w.null is not None and w.wall in spin.index
            else w
            for w in spin.walls
        ]
        for w in spin.walls:
            if not (w.sheared and w.dof and not w.no_null):
                continue
            k = spin.wall_rows[w.wall]
            first = float(w.first or 0.0)
            data = {st: v[0] for st, v in w.stencils.items()} or {"analysis": first}
            an = data.get("analysis", first)
            a_lo, a_hi = an - float(every.hi["analysis"][k]), an - float(every.lo["analysis"][k])
            lo = min(d - float(every.hi[st][k]) for st, d in data.items())
            hi = max(d - float(every.lo[st][k]) for st, d in data.items())
            text = (
                f"{w.run} ({w.wall} wall) {a_lo:+.3g} to {a_hi:+.3g} under the analysis' "
                f"stencil ({lo:+.3g} to {hi:+.3g} under any)"
            )
            bounds = monotone_beyond(r.run)
            if bounds is not None:
                text += (
                    f", and over every monotone velocity with the measured bin means "
                    f"{float(bounds[0][k]):+.3g} to {float(bounds[1][k]):+.3g}"
                )
            rows.append(text)
    if not rows:
        return ""
    return (
        "Systematic: beyond the null of any velocity the run has (the joint fit's, the u-only "
        "fits', the measured velocity's reconstructions), the first-layer departure spans "
        + "; ".join(rows)
        + ". The verdict takes the joint fit's null, "
        "spin_model's (the u-only fits contradict the stress ratio; the reconstructions and "
        "the monotone bound are no model's velocity): the first layer's departure beyond the "
        "null rests on the velocity inside the first bin, which the bins do not resolve."
    )


def _spin_model(
    results: Sequence[RunResult],
    points: int,
    scans: Sequence[Scan] | None = None,
    skipped: Sequence[str] = (),
) -> Verdict:
    """``spin_model``: from the joint calibration and scan of :mod:`.spin_scan` where a run can
    be scanned (``scans``, made here when None), the u-only fits' verdict kept in its numbers;
    the u-only verdict alone when ``points`` is 0 or no run can be scanned."""
    u_only = spin_model_verdict(*_spin_model_inputs(results))
    if points <= 0:
        return u_only
    if scans is None:
        scans, skipped = _scans(results, points)
    if not scans:
        if not skipped:
            return u_only
        return replace(u_only, evidence=f"{u_only.evidence} Not scanned: {'; '.join(skipped)}.")
    from .rate import rate_pairs

    v = scan_verdict(scans, u_only, rate_pairs(results))
    if skipped:
        v = replace(v, evidence=f"{v.evidence} Not scanned: {'; '.join(skipped)}.")
    return v


def _null_misfit(spin: SpinMeasure, null: FloatArray, skip_fixed: bool = False) -> float:
    """chi^2 of the measured departure against a null (per row of the run) over the
    near-wall bins of the sheared walls (``skip_fixed``: not the fixed wall), whitened."""
    assert spin.rows is not None and spin.departure is not None and spin.stderr is not None
    total = 0.0
    for w in spin.walls:
        if w.sheared and w.dof and not (w.wall == "fixed" and skip_fixed):
            at = null[spin.rows][spin.index[w.wall]]
            total += float(np.sum(w.white(np.asarray(w.departure) - at) ** 2))
    return total


def _unresolved(run: Run, w: WallSpin, rows: NDArray[np.intp]) -> str:
    """Why a wall no fit describes is not judged against the measured velocity's null
    (referee 8, point 6): that null needs the velocity inside the bins, which they do not
    resolve; the ranges any monotone velocity with the measured bin means allows for the
    departure beyond the null (:func:`.nulls.monotone_beyond`) are given, with how far the
    nearest end of each is from 0 in se."""
    why = (
        "no fit describes the velocity there (its kind differs from the moving wall's, which "
        "the fits give it)"
    )
    bounds = monotone_beyond(run)
    if bounds is None or w.dof == 0:
        return why + ": no null, so not judged"
    lo, hi = (np.asarray(b, dtype=float)[rows] for b in bounds)
    se = np.asarray(w.stderr, dtype=float)
    gap = np.maximum(np.maximum(lo, -hi), 0.0) / se  # 0 where the range holds 0
    order = np.argsort(w.distance_d)
    parts = ", ".join(
        f"{float(w.distance_d[i]):.2g} d: {float(lo[i]):+.3g} to {float(hi[i]):+.3g}" for i in order
    )
    raw = ", ".join(
        f"{float(w.distance_d[i]):.2g} d: {float(w.departure[i]):+.3g} +- {float(se[i]):.2g}"
        + (
            ""
            if w.null is None
            else f" (beyond the reconstructions' null {float(w.beyond[i]):+.3g} +- "
            f"{float(w.se_beyond[i]):.2g})"
        )
        for i in order
    )
    return (
        f"{why}; measured (raw, the analysis' stencil) {raw}; the measured velocity's null "
        "(smooth reconstructions of u, shown) needs the "
        "velocity inside the bins, which the bins do not resolve: a velocity monotone across "
        "the gap with the measured bin means (a layered packing's steps between grain layers "
        "as well as a smooth profile) allows the departure beyond the null to be anywhere in "
        f"{parts} (the nearest to 0 at most {float(np.max(gap)):.2g} se from it), so the null "
        "is not determined and the wall is not judged"
    )


def analyse_run(
    run: Run,
    models: Sequence[str] | None,
    f: float,
    near_wall_d: float,
    grid: int,
    figures_to: Path | None = None,
    independent_bins: bool = False,
    fix: StressFix | None = None,
) -> RunResult:
    """Fit, measure and compare one run (module docstring); with ``figures_to``, also draw
    the run's figure there (in the worker that analysed it, when there are workers; a layer
    run's waits for the layer verdict, :func:`.report.write_figures`);
    ``independent_bins`` and ``fix`` (what the stresses fix in the Cosserat fit):
    :func:`.fits.fit_run`'s."""
    stress = band_stress_ratio(run)
    if run.cell == "channel":
        fits, error = None, CHANNEL_NOTE
    else:
        fits, error = try_fit_run(run, models, grid, stress, independent_bins, fix)
    skipped = [f"{q}: not in this run" for q in run.missing() if q in ("omega", "half_vorticity")]
    spin = measure_spin(run, near_wall_d)
    if not spin.available:
        skipped.append(f"spin comparison skipped: {spin.reason}")
    elif fits is not None and fits.models:
        assert spin.rows is not None
        by_stencil = {m: {st: fits.spin_departure(m, run, st) for st in STENCILS}
                      for m in fits.models}  # fmt: skip
        point = {m: fits.spin_point(m, run) for m in fits.models}
        # the null: grains turning with the material in a velocity, measured so. Here, before
        # the joint fits of judge() (whose null replaces it where a run has one): the envelope
        # of every velocity the run has, the u-only fits' and the measured one's (.nulls)
        fit_nulls = [
            point_null(
                f"the {m} fit's velocity", {st: fits.spin_null(m, run, st) for st in STENCILS}
            )
            for m in fits.models
        ]
        try:
            measured = velocity_null(run)
        except ParameterError:
            measured = None
        env = envelope(
            fit_nulls + ([measured] if measured is not None else []),
            "the envelope of the velocities the run has (its u-only fits' ("
            + ", ".join(fits.models)
            + ")"
            + (", and the measured one, reconstructed" if measured is not None else "")
            + "; no joint fit)",
        )
        # the fits give a fixed wall of another kind the moving wall's: no fit's null there;
        # the measured velocity's is shown, not judged (_unresolved)
        differ = walls_differ(run)
        if differ:
            spin.notes.append(
                "fixed wall: its kind differs from the moving wall's, which the fits give it, "
                "so their velocity there is not the run's: no fit's null; the measured "
                "velocity's is shown but not judged (the spin verdict says why)"
            )
        spin.notes.append(
            "the spin's test is against the departure the analysis reports for grains that "
            "turn with the material (bin averages of u and of omega = half the vorticity, the "
            "difference stencil): what the binning and the stencil make alone; in the joint "
            "u + omega + stress-ratio fit's velocity where the run has one (spin_model's), "
            "else over the envelope of its u-only fits' and its measured velocity's"
        )
        for m in fits.models:
            spin.predicted[m] = by_stencil[m]["analysis"][spin.rows]
        walls = []
        for w in spin.walls:
            w = w.with_predictions(
                {m: p[spin.index[w.wall]] for m, p in spin.predicted.items()},
                {
                    m: {st: float(v[spin.wall_rows[w.wall]]) for st, v in by_stencil[m].items()}
                    for m in fits.models
                },
                {m: float(point[m][spin.wall_rows[w.wall]]) for m in fits.models},
            )
            if differ and w.wall == "fixed":
                if measured is not None:
                    w = with_null(
                        w, measured, spin.rows[spin.index[w.wall]], spin.wall_rows[w.wall]
                    )
                w = replace(w, no_null=_unresolved(run, w, spin.rows[spin.index[w.wall]]))
            else:
                w = with_null(w, env, spin.rows[spin.index[w.wall]], spin.wall_rows[w.wall])
            walls.append(w)
        spin.walls = walls
        spin.envelope = env
    if spin.available and run.meta.get("blocks"):
        spin.walls = [replace(w, blocks=int(run.meta["blocks"])) for w in spin.walls]
    layer = measure_layer(run, fits)
    thickness = (
        Thickness(None, None, CHANNEL_NOTE)
        if run.cell == "channel"
        else Thickness(None, None, LAYER_NOTE, run.gap_d)
        if layer is not None
        else measured_thickness(run, f)
    )
    model_delta: dict[str, float | None] = {}
    if fits is not None and layer is None:
        profile = run.measured()
        for name in fits.models:
            model_delta[name] = thickness_of(
                profile.distance_d,
                fits.curve(name, profile.distance_d),
                reference_velocity(run),
                f,
            )
    result = RunResult(
        run,
        fits,
        error,
        spin,
        thickness,
        model_delta,
        skipped,
        stress,
        moving_wall_inertial_number(run)
        if layer is None
        else band_inertial_number(run.meta, layer.smoother),
        layer=layer,
        sensitivity=None
        if run.cell == "channel" or layer is not None
        else thickness_sensitivity(run, sensitivity_fs(f)),
    )
    # a layer run's figure waits for the layer verdict's profile at the material's L
    # (report.write_figures draws it; referee 15, point 2): drawn once, not twice
    if figures_to is not None and layer is None:
        from .report import write_run_figure

        result.figure = write_run_figure(result, figures_to)
    return result


def _analyse_all(
    runs: Sequence[Run],
    models: Sequence[str] | None,
    f: float,
    near_wall_d: float,
    grid: int,
    progress: Callable[[str, int, int], None] | None,
    workers: int | None,
    figures_to: Path | None = None,
    jobs: Sequence[MaterialJob] = (),
    independent_bins: bool = False,
    fixes: Mapping[str, StressFix] | None = None,
    scan_runs: Sequence[Run] = (),
    points: int = COARSE,
    pool: Any = None,
) -> tuple[list[RunResult], dict[str, list[SeriesCalibration]], Scanned | None]:
    """:func:`analyse_run` of every run and :func:`.fits.material_job` of every job, in worker
    processes when worth it (``validate``): (the runs' results, series key -> calibrations,
    one per model, and the spin scans). With workers, the spin scans of ``scan_runs`` (the
    runs with a measured spin; ``points`` per parameter) are made there too (:func:`scan_job`,
    :func:`gather_scans`); in one process (and without ``scan_runs`` or ``points``) they are
    left to :func:`judge` (None). ``pool``: the process pool to use (``workers`` of them,
    :func:`pool_size`), else one is made here and shut down after."""
    workers = pool_size(workers, runs, jobs)
    cals: dict[str, list[SeriesCalibration]] = {}
    # a run that is scanned is drawn once its scan is in (with the joint fit): not by
    # analyse_run, but by a figure job (with workers) or by the report (in one process)
    to_scan = list(scan_runs) if points > 0 else []
    scanned_names = {r.name for r in to_scan}

    def draw_to(run: Run) -> Path | None:
        return None if run.name in scanned_names else figures_to

    if workers <= 1:
        out = []
        for i, run in enumerate(runs):
            out.append(
                analyse_run(
                    run, models, f, near_wall_d, grid, draw_to(run), independent_bins,
                    (fixes or {}).get(run.name),
                )
            )  # fmt: skip
            if progress:
                progress("runs", i + 1, len(runs))
        for job in jobs:
            for key, cal in material_job(job).items():
                cals.setdefault(key, []).append(cal)
        return out, cals, None
    if pool is None:
        from ...numerics.runtime import worker_processes

        with worker_processes(workers) as own:
            return _analyse_all(
                runs, models, f, near_wall_d, grid, progress, workers, figures_to, jobs,
                independent_bins, fixes, scan_runs, points, own,
            )  # fmt: skip
    # the spin scans first (a joint fit, two grids and the refits of each): the material's
    # shared spin fit and then the spin scan's figure (the longest job, ~25 s of drawing)
    # wait for all of them, and go first in the queue once they can; then the longest
    # first, so that the workers end together: mu(I)'s material calibrations, the other
    # calibrations, the runs with the most bins
    order = sorted(range(len(runs)), key=lambda i: -runs[i].measured().n)
    ranked = sorted(range(len(jobs)), key=lambda k: (jobs[k].model != "mui", -len(jobs[k].runs)))
    everyone = list(runs)
    run_of_scan = {j: next(i for i, r in enumerate(runs) if r.name == sc.name)
                   for j, sc in enumerate(to_scan)}  # fmt: skip
    scan_of_run = {i: j for j, i in run_of_scan.items()}
    queue: list[tuple[str, int, Callable[..., Any], tuple[Any, ...]]] = [
        *(
            ("scan", i, scan_job, (to_scan[i], everyone, points))
            for i in sorted(range(len(to_scan)), key=lambda i: -to_scan[i].measured().n)
        ),
        *(("job", k, material_job, (jobs[k],)) for k in ranked if jobs[k].model == "mui"),
        *(("job", k, material_job, (jobs[k],)) for k in ranked if jobs[k].model != "mui"),
        *(
            (
                "run", i, analyse_run,
                (runs[i], models, f, near_wall_d, grid, draw_to(runs[i]), independent_bins,
                 (fixes or {}).get(runs[i].name)),
            )
            for i in order
        ),
    ]  # fmt: skip
    done: dict[int, RunResult] = {}
    got: dict[int, dict[str, SeriesCalibration]] = {}
    outcomes: dict[int, ScanOutcome] = {}
    shared: dict[str, dict[str, Any]] | None = None if to_scan else {}

    early: list[Scanned] = []

    def scan_figure() -> None:
        """Once every scan and the shared fit are in: the scans as judge() will take them,
        and their figure drawn first in the pool (it takes the longest of the figures)."""
        if early or not to_scan or shared is None or len(outcomes) < len(to_scan):
            return
        early.append(gather_scans([outcomes[i] for i in range(len(to_scan))], to_scan, shared))
        if figures_to is not None and early[0].scans:
            import pickle

            from .report import SPIN_SCAN_FIGURE, draw_figure

            dicts = [sc.to_dict() for sc in early[0].scans]
            early[0].figure_of = pickle.dumps(dicts)
            args = ("spin_scan_figure", (dicts,), figures_to / SPIN_SCAN_FIGURE)
            queue.insert(0, ("drawn", 0, draw_figure, args))

    def figure(i: int) -> None:
        """Queue run i's figure, first, once its analysis and its scan are both in."""
        j = scan_of_run.get(i)
        if figures_to is None or j is None or i not in done or j not in outcomes:
            return
        queue.insert(0, ("figure", i, figure_job, (done[i], outcomes[j].scan, figures_to)))

    running: dict[Future[Any], tuple[str, int]] = {}
    while queue or running:
        # at most one job waiting per worker: a job queued later (the shared fit) can
        # still go before the runs not yet handed out
        while queue and len(running) < 2 * workers:
            kind, i, fn, fn_args = queue.pop(0)
            running[pool.submit(fn, *fn_args)] = (kind, i)
        finished, _ = wait(running, return_when=FIRST_COMPLETED)
        for fut in finished:
            kind, i = running.pop(fut)
            if kind == "run":
                done[i] = fut.result()
                if progress:
                    progress("runs", len(done), len(runs))
                figure(i)
            elif kind == "job":
                got[i] = fut.result()
            elif kind == "scan":
                outcomes[i] = fut.result()
                if len(outcomes) == len(to_scan):
                    scans = [o.scan for _, o in sorted(outcomes.items()) if o.scan]
                    queue.insert(0, ("shared", 0, shared_job, (scans, to_scan)))
                figure(run_of_scan[i])
            elif kind == "figure":
                done[i].figure, done[i].joint = fut.result()
                done[i].figure_joint = done[i].joint is not None
            elif kind == "drawn":
                fut.result()
            else:
                shared = fut.result()
                scan_figure()
    for k in range(len(jobs)):  # in the jobs' order, whichever ended first
        for key, cal in got[k].items():
            cals.setdefault(key, []).append(cal)
    scanned = (
        early[0]
        if early
        else gather_scans([outcomes[i] for i in range(len(to_scan))], to_scan, shared)
        if to_scan
        else None
    )
    return [done[i] for i in range(len(runs))], cals, scanned


def pool_size(workers: int | None, runs: Sequence[Run], jobs: Sequence[MaterialJob]) -> int:
    """The worker processes ``_analyse_all`` uses: ``workers`` (None: one), at most one
    per run or job; 1 means no pool."""
    return 1 if workers is None else min(workers, len(runs) + len(jobs))


def sensitivity_fs(f: float) -> tuple[float, ...]:
    """The f at which Delta's sensitivity is measured: :data:`~.measures.SENSITIVITY_F` and
    validate's own ``f``."""
    return tuple(sorted({round(x, 12) for x in (f, *SENSITIVITY_F)}))


def series_f(runs: Sequence[Run], f: float) -> dict[str, tuple[float, str]]:
    """Each gap series' f and why (:func:`~.measures.thickness_sensitivity`): validate's ``f``
    unless a run of the series is ill-conditioned there; then the smallest f of
    :func:`sensitivity_fs` above it at which every such run is well conditioned (the series'
    measured Delta and its joint calibrations both use it)."""
    out: dict[str, tuple[float, str]] = {}
    for s in group_runs([r for r in runs if not walls_differ(r)]):
        if s.cell == "channel":
            continue
        chosen, why = f, []
        for r in s.runs:
            sens = thickness_sensitivity(r, sensitivity_fs(f))
            if f not in sens.ill:
                continue
            good = sens.conditioned_f(f)
            j = sens.f.index(f)
            z = sens.shift[j]
            text = (
                f"{r.name} is ill-conditioned at f = {f:g} (its decay length (Delta - s_1)/ln(1/f) "
                f"moves by {z:+.2g} se to the next f"
            )
            if good is None:
                why.append(text + "; no f is well conditioned)")
                continue
            why.append(text + f"; well conditioned at f = {good:g})")
            chosen = max(chosen, good)
        note = ""
        if why:
            note = "; ".join(why) + (
                f": the series' Delta and its calibrations use f = {chosen:g}"
                if chosen != f
                else f": the series keeps f = {f:g}"
            )
        out[s.key] = (chosen, note)
    return out


def series_jobs(
    runs: Sequence[Run], models: Sequence[str] | None, f: float = DEFAULT_F
) -> list[MaterialJob]:
    """The joint calibrations behind the Delta verdicts that validate makes: one per material
    (:func:`.grouping.group_materials`: one cell, one material, every wall kind; runs whose
    walls differ are in none) and model the calibration has on its cell (``models`` only, if
    given), over every run of the material's gap series, made when at least one of its series
    is of plane or Couette runs at two or more distinct gaps; each series reads it at its own
    f (:func:`series_f`)."""
    from ...calibration.models import models as make_models

    chosen = series_f(runs, f)
    out = []
    for mat in group_materials(group_runs([r for r in runs if not walls_differ(r)])):
        if mat.cell not in ("plane", "couette"):
            continue
        if max(_distinct_gaps(s.runs) for s in mat.series) < 2:
            continue
        parts = tuple((s.key, s.runs, chosen.get(s.key, (f, ""))[0]) for s in mat.series)
        for m in make_models(None):
            if mat.cell in m.cells() and (models is None or m.name in models):
                out.append(MaterialJob(mat.key, mat.runs, m.name, parts))
    return out


def _distinct_gaps(runs: Sequence[Run]) -> int:
    gaps: list[float] = []
    for r in runs:
        if not any(abs(r.gap_d - g) <= SAME_GAP * g for g in gaps):
            gaps.append(r.gap_d)
    return len(gaps)


def _curve(c: SeriesCalibration) -> ModelDelta:
    return ModelDelta(
        c.model,
        c.predicted,
        c.curve,  # type: ignore[arg-type]
        c.summary,
        c.status,
        c.message,
        c.why,
        c.resolved_above,
        None if c.best is None else _curve(c.best),
        c.reach,
    )


def _curves(cals: Sequence[SeriesCalibration]) -> dict[str, ModelDelta]:
    return {c.model: _curve(c) for c in cals}


def judge(
    results: Sequence[RunResult],
    models: Sequence[str] | None = None,
    f: float = DEFAULT_F,
    calibrate: bool = True,
    calibrations: Mapping[str, Sequence[SeriesCalibration]] | None = None,
    spin_scan: int = COARSE,
    scanned: Scanned | None = None,
) -> tuple[list[DeltaSeries], list[Verdict], list[str]]:
    """The gap series and the verdicts on every claim, from the runs' results. Each series'
    joint calibrations (one per model over every run of its material, :func:`series_jobs`)
    are ``calibrations`` (series key -> one per model), or else made here unless
    ``calibrate`` is False. ``spin_scan``: points per
    parameter of the spin scan behind ``spin_model`` (:mod:`.spin_scan`; 0: the u-only fits
    alone); ``scanned``: those scans and their nulls already made (:func:`gather_scans`, at
    ``spin_scan`` points), else made here."""
    by_name = {r.run.name: r for r in results}
    if calibrations is None:
        made: dict[str, list[SeriesCalibration]] = {}
        if calibrate:
            for job in series_jobs([r.run for r in results], models, f):
                for key, cal in material_job(job).items():
                    made.setdefault(key, []).append(cal)
        calibrations = made
    chosen = series_f([r.run for r in results], f)
    series = []
    # a run whose walls differ is in no gap series (no smooth- or rough-wall Delta law is
    # about it; the layer run's band is at its fixed wall)
    for s in group_runs([r.run for r in results if not walls_differ(r.run)]):
        members = [by_name[r.name] for r in s.runs]
        curves = _curves(calibrations.get(s.key, []))
        f_s, f_note = chosen.get(s.key, (f, ""))
        # Delta at the series' f (validate's unless a run is ill-conditioned there)
        thick = {
            r.run.name: r.thickness if f_s == f else measured_thickness(r.run, f_s) for r in members
        }
        points = tuple(
            DeltaPoint(
                r.run.name,
                r.run.gap_d,
                thick[r.run.name].value,
                thick[r.run.name].stderr,
                thick[r.run.name].fills_gap,
                thick[r.run.name].reason,
                thick[r.run.name].far_text(),
            )
            for r in members
        )
        series.append(
            DeltaSeries(
                s.key,
                s.cell,
                s.roughness,
                s.gravity,
                points,
                _model_slopes(members),
                (f_note,) if f_note else (),
                curves,
                {r.run.name: r.run.meta.get("wall_speed") for r in members},
                twins=twin_names([r.run for r in members]),
            )
        )
    if scanned is None or spin_scan <= 0:
        scans, skipped = _scans(results, spin_scan)
        systematic = _joint_nulls(results, scans)
    else:
        scans, skipped = scanned.scans, scanned.skipped
        systematic = _joint_nulls(results, scans, scanned.nulls)
    _joint_curves(results, scans)
    walls = [w for r in results if r.spin.available for w in r.spin.walls]
    twins = twin_pairs(results)
    spin = spin_verdict(
        walls,
        unfit=_spin_model_inputs(results)[2],
        runs_info=spin_runs(results, scans),
        seed_factors=omega_seed_factors(twins),
    )
    if systematic:
        spin = replace(
            spin,
            evidence=f"{spin.evidence} {systematic}",
            numbers={**spin.numbers, "systematic_envelope": systematic},
        )
    verdicts = [
        spin,
        delta_law_verdict(series, "smoother"),
        delta_law_verdict(series, "rough"),
        _spin_model(results, spin_scan, scans, skipped),
        # the layer's position, judged only on runs whose walls differ (.layer)
        *layer_verdicts(
            [r.run for r in results],
            {r.run.name: r.fits for r in results},
            {r.run.name: r.layer for r in results if r.layer is not None},
            material_length(series, [r.run for r in results if r.layer is not None]),
            material_phi(series, [r.run for r in results if r.layer is not None]),
            {sc.run: _l_region(reg) for sc in scans if (reg := scan_region(sc))},
        ),
    ]
    verdicts = [
        within_regime(
            v, [by_name[n].inertial_number for n in v.runs if n in by_name], QUASI_STATIC_I
        )
        for v in verdicts
    ]
    spin_keys = ("spin", "spin_model")  # the first layers' own rate, the blocks' tau
    verdicts = [
        replace(
            v,
            evidence=(
                f"{v.evidence} "
                + regime(
                    [by_name[n] for n in v.runs],
                    slip_text([by_name[n] for n in v.runs], QUASI_STATIC_I)
                    if v.key in spin_keys
                    else "",
                )
                + f" {steadiness_text([by_name[n] for n in v.runs])}"
            ).rstrip(),
        )
        for v in verdicts
    ]
    verdicts = [
        replace(v, evidence=f"{v.evidence} {rate_text([by_name[n] for n in v.runs])}")
        if v.key in ("spin", "spin_model") and v.runs
        else v
        for v in verdicts
    ]
    verdicts = [
        replace(
            v,
            evidence=(f"{v.evidence} {twins_text(twins, [by_name[n] for n in v.runs])}").rstrip(),
        )
        for v in verdicts
    ]
    verdicts = [_misfit_twins(v, twins) if v.key == "spin_model" else v for v in verdicts]
    verdicts = [  # the Delta series' runs' balance misses and where they sit (referee 14,
        # point 7; referee 16, point 1)
        replace(
            v,
            evidence=v.evidence + balance_warning(rs := [by_name[n].run for n in v.runs], twins),
            numbers={**v.numbers, "balance_misses": balance_record(rs, twins)},
        )
        if v.key in ("smoother", "rough")
        else v
        for v in verdicts
    ]
    verdicts = [  # the headline numbers, read from each verdict's numbers (.summaries)
        replace(v, summary=verdict_summary(v.key, v.verdict, v.qualifier, v.numbers))
        for v in verdicts
    ]
    return series, verdicts, couette_note(group_runs([r.run for r in results]))


def material_length(
    series: Sequence[DeltaSeries], layer_runs: Sequence[Run]
) -> tuple[float, float] | None:
    """The layer runs' material's L and its error [d], from the one Cosserat calibration of
    that material's gap series (every series of a material reads the same one), for the
    layer runs' shape at it (``layer.material_length``); None without layer runs, with
    layer runs of several materials, or without a calibration of theirs."""
    cal = _layer_material_calibration(series, layer_runs)
    e = (cal or {}).get("parameters", {}).get("L", {})
    return _value_and_error(e.get("value"), e.get("stderr"))


def material_phi(
    series: Sequence[DeltaSeries], layer_runs: Sequence[Run]
) -> tuple[float, float] | None:
    """The layer runs' material's phi and its error [deg], fixed from the stresses in the one
    Cosserat calibration of that material (as :func:`material_length`), for the warning that
    the layers flow below it (``layer.below_yield``; referee 13, point 4); None as
    :func:`material_length`, or where the calibration did not fix phi from the stresses."""
    cal = _layer_material_calibration(series, layer_runs)
    e = ((cal or {}).get("stresses") or {}).get("phi") or {}
    return _value_and_error(e.get("phi"), e.get("phi_se"))


def _layer_material_calibration(
    series: Sequence[DeltaSeries], layer_runs: Sequence[Run]
) -> Mapping[str, Any] | None:
    """The one Cosserat calibration (its record) of the layer runs' material, read from the
    first gap series of that material that has it; None without layer runs, with layer runs of
    several materials, or without a calibration of theirs."""
    wanted = {material_of(r) for r in layer_runs}
    if len(wanted) != 1:
        return None
    for s in series:
        c = s.curves.get("cosserat")
        if c is not None and c.ok and c.calibration.get("material") in wanted:
            return c.calibration
    return None


def _value_and_error(v: Any, se: Any) -> tuple[float, float] | None:
    """(value, error) where both are numbers and the value is finite, else None."""
    if isinstance(v, int | float) and isinstance(se, int | float) and math.isfinite(v):
        return float(v), float(se)
    return None


def omega_seed_factors(twins: Sequence[Any]) -> list[tuple[str, float]]:
    """Each same-conditions replicate pair's omega seed-scatter factor (``rate.TwinPair``'s
    omega ``TwinField.factor``, truncated wall bins left out) and, where the pair has a
    truncated wall bin, sqrt(sum z^2 / n) with it counted (referee 17, point 2: 1.26 for the
    rough H = 10 d pair), labelled by the pair, for the spin verdict's pooled p at the seed
    scatter [-]."""
    out = []
    for t in twins:
        om = t.fields.get("omega")
        if om is None:
            continue
        pair = f"{t.a}/{t.b}"
        f = om.factor()
        if f is not None:
            out.append((pair, float(f)))
        if om.n_truncated:
            out.append((f"{pair} with its truncated wall bin", math.sqrt(om.chi2 / om.n)))
    return out


def twins_text(twins: Sequence[Any], results: Sequence[RunResult]) -> str:
    """The regime block's sentences on the corpus's same-conditions replicates (one cell, one
    wall speed, two seeds: ``rate.twin_pairs``; referee 12, point 2), every verdict's: each
    pair compared bin by bin, and the momentum-balance misses of the verdict's runs rescaled
    by the replicates' seed-scatter factor (``rate.balance_rescaled_text``); where none: that
    no run is replicated at the same conditions. Empty without runs."""
    if not results:
        return ""
    if not twins:
        return (
            "Same-conditions replicates: none (no cell run twice at one wall speed with two "
            "seeds), so the block errors are not checked against the scatter between "
            "realisations."
        )
    used = {r.run.name for r in results}
    own = [p for p in twins if {p.a, p.b} <= used]  # the verdict's own pairs first
    others = [p.brief() for p in twins if p not in own]  # in full where their runs are judged
    text = " ".join(
        [p.text() for p in own]
        + (
            [
                "Same-conditions replicates elsewhere in the corpus (sum z^2 per field over its "
                "bins; in full in the verdicts that use them and in results.json twins[]): "
                + "; ".join(others)
                + "."
            ]
            if others
            else []
        )
    )
    return text + balance_rescaled_text([r.run for r in results], twins)


def _misfit_twins(v: Verdict, twins: Sequence[Any]) -> Verdict:
    """spin_model's verdict with the replicates' word on its misfit reading
    (``rate.misfit_twin_text``) right after it (:data:`MISFIT_ANCHORS`), where the joint fits
    misfit."""
    runs = v.numbers.get("misfit_runs") or []
    if not twins or not runs or not v.numbers.get("reading"):
        return v
    own = [t for t in twins if {t.a, t.b} <= set(v.runs)]
    twins = own or twins  # the verdict's own replicates where it has them
    # numbers.error_models points to scans[i].error_models (one record per scan, not repeated)
    models = {
        rec["run"]: rec.get("error_models") or {}
        for rec in v.numbers.get("scans") or []
        if isinstance(rec, dict) and "run" in rec
    }
    extra = misfit_twin_text(twins, models, runs)
    if not extra:
        return v
    for anchor in MISFIT_ANCHORS:  # right after the reading's sentence, where it is found
        at = v.evidence.find(anchor)
        if at >= 0:
            cut = at + len(anchor)
            return replace(v, evidence=f"{v.evidence[:cut]}{extra}{v.evidence[cut:]}")
    return replace(v, evidence=f"{v.evidence}{extra}")


MISFIT_ANCHORS = (
    "a second seed would settle the error scale.",
    "and the 95% region is scaled alike.",
)
"""The ends of spin_model's misfit-reading sentence (``spin_scan.misfit_reading``), after
which the replicates' word on it goes (at the end of the evidence where neither is found)."""


def rate_text(results: Sequence[RunResult]) -> str:
    """One sentence for the spin and spin_model verdicts (referee 8, point 7): the runs' wall
    speeds (the sidecar's ``wall_speed``), and, for one cell run at two speeds, what its
    scaled profiles, Delta and wall stress ratio say (``rate.rate_pairs``; referee 10,
    point 2); with one speed, that rate independence is not shown."""
    from .rate import rate_pairs

    speeds = sorted({float(v) for r in results if (v := r.run.meta.get("wall_speed")) is not None})
    named = ", ".join(f"{v:.3g}" for v in speeds) or "not recorded"
    if len(speeds) <= 1:
        return f"Rate independence is not shown (one wall speed: V = {named})."
    pairs = rate_pairs(results)
    if not pairs:
        return (
            f"The runs span {len(speeds)} wall speeds (V = {named}); the spin's test does not "
            "compare one cell at two speeds, so it does not show rate independence."
        )
    return (
        f"The runs span {len(speeds)} wall speeds (V = {named}); one cell at two speeds "
        "(bins compared at equal y, block errors, the two runs independent): "
        + "; ".join(p.text() for p in pairs)
        + "."
        + static_rescaled_text(pairs, twin_pairs(results), {r.run.name: r.run for r in results})
    )


def regime(results: Sequence[RunResult], first_layer: str = "") -> str:
    """One sentence: the runs' inertial number at the moving wall against the quasi-static
    bound :data:`QUASI_STATIC_I` of the models (empty without runs); ``first_layer``, said
    right after it (the spin verdicts': the first layer's own I from the wall slip,
    ``rate.slip_text``; referee 10, point 5)."""
    if not results:
        return ""
    known = [(r.run.name, r.inertial_number) for r in results if r.inertial_number is not None]
    if not known:
        return (
            "Regime: no run used gives its local inertial number (an inertial_number column), "
            f"so whether it is quasi-static (I <= {QUASI_STATIC_I:g}) is not shown."
        )
    values = [i for _, i in known]
    above = [n for n, i in known if i > QUASI_STATIC_I]
    layers = sum(r.layer is not None for r in results)
    where = (
        "in the band (next to the smoother wall)"
        if layers == len(results)
        else "next to the moving wall"
        + (" (in the band, next to the smoother wall, for a layer run)" if layers else "")
    )
    text = (
        f"Regime: the local inertial number {where} is "
        f"{min(values):.2g}-{max(values):.2g} in the {len(known)} runs that give it"
    )
    if above:
        text += (
            f"; {len(above)} of them are above the quasi-static bound I <= "
            f"{QUASI_STATIC_I:g} of the rate-independent models, so this verdict holds at "
            "their rates only."
        )
    else:
        text += f", within the quasi-static bound I <= {QUASI_STATIC_I:g}."
    return f"{text}{first_layer}{_p_source_text(results)}{wall_bins_text(results)}"


def _p_source_text(results: Sequence[RunResult]) -> str:
    """Where the wall inertial number takes p in a truncated bin at the moving wall (referee
    9, point 7): the wall's measured normal stress, or (older sidecars) the bin's own."""
    source = {
        r.run.name: wall_p_source(r.run)
        for r in results
        if r.inertial_number is not None and r.layer is None
    }
    wall = sorted(n for n, v in source.items() if v == "wall")
    own = sorted(n for n, v in source.items() if v == "bin")
    text = ""
    if wall:
        text += (
            f" In the truncated bin next to the moving wall ({', '.join(wall)}) p is the "
            "wall's measured normal stress, not the bin's (a truncated bin's stresses are not "
            "bulk values)."
        )
    if own:
        text += (
            f" In {', '.join(own)} the truncated bin next to the moving wall gives I with its "
            "own p, which is not a bulk value (the sidecar predates the rule that uses the "
            "wall's measured normal stress there)."
        )
    return text


MAX_LISTED = 3
"""Bins a run's wall-bin sentence names before counting the rest."""


def _balance_run(c: WallBins, run: Run) -> str:
    """One run's bins beyond the momentum balance: the truncated ones named, the others'
    count, largest |z| and where they sit (:func:`~.measures.miss_place`)."""
    truncated = {row for row, *_ in c.truncated}
    named = [b for b in c.balance if b[0] in truncated]
    others = [b for b in c.balance if b[0] not in truncated]
    parts = [f"the truncated bin at {d:.2g} d: {t:.3g}, z = {z:+.1f}" for _, d, t, z in named]
    if others:
        worst = max(others, key=lambda b: abs(b[3]))
        yb = y_balance(run)
        places = [miss_place(run, b[0], yb).place for b in others]
        counts = ", ".join(
            f"{places.count(p)} {'in the layered zone' if p == MISS_PLACES[0] else p}"
            for p in MISS_PLACES
            if p in places
        )
        parts.append(
            f"{len(others)} of its other {c.tested - len(named)} bins, largest "
            f"z = {worst[3]:+.1f} at {worst[1]:.1f} d ({counts})"
        )
    return f"{c.run} (wall {c.wall_shear:.3g}; {', '.join(parts)})"


def y_balance_text(runs: Sequence[Run]) -> str:
    """The sentence on sigma_yy's own y-balance (referee 16, point 1;
    :func:`~.measures.y_balance`) in ``runs`` (those whose shear stress misses the momentum
    balance): the inversions (sigma_yy falling with depth beyond ``INVERSION_SIGMAS`` se
    between adjacent bins) and the nu steps, and why the misses are read as layering artefacts;
    "" where no run is plane shear under gravity."""
    checks = [b for r in runs if (b := y_balance(r)) is not None]
    if not checks:
        return ""

    def one(b: YBalance) -> str:
        inv = ", ".join(f"{p.y_deep:.3g}/{p.y_shallow:.3g} ({p.z:+.2g} se)" for p in b.inversions)
        steps = ", ".join(
            f"{p.y_deep:.3g}/{p.y_shallow:.3g} ({p.nu_deep:.2f}/{p.nu_shallow:.2f})"
            for p in b.nu_steps
        )
        return (
            f"{b.run} (rise {b.rate:.2g} N/d): "
            + (f"inversions at y = {inv}" if inv else "no inversion")
            + (f"; nu steps at y = {steps}" if steps else "; no nu step")
        )

    return (
        " sigma_yy's own y-balance in those runs (under gravity along -y, compressive positive, "
        "sigma_yy rises with depth from the upper wall's load by rho_s nu g = B nu / (nu_mean H) "
        "per d; from the profile, no solve): adjacent bins where it falls with depth by more "
        f"than {INVERSION_SIGMAS:g} se of their difference (inversions; y from the lower wall, "
        f"the deeper bin first) and whose nu differ by more than {NU_STEP:g} (nu steps): "
        + "; ".join(one(b) for b in checks)
        + ". A miss is in the layered zone where its bin's nu exceeds the hexagonal bound, next "
        "to it where a neighbour's does or the bin is in an inversion or a nu step, unexplained "
        "otherwise: centre binning of a layered packing puts such bins' stresses off their bulk "
        "values (the stresses are not recomputed with area-weighted or half-shifted bins in "
        "this version)."
    )


def wall_bins_text(results: Sequence[RunResult]) -> str:
    """Sentences on the runs' wall bins (referee 9, point 7; :func:`~.measures.wall_bins`):
    the truncated end bins, whose stresses and nu are not bulk values and which no stress fit
    uses; the bins whose shear stress breaks the momentum balance beyond 3 se of the wall's;
    the bins with nu above the hexagonal bound. Empty where nothing is flagged."""
    checks = [wall_bins(r.run) for r in results]
    by_name = {r.run.name: r.run for r in results}
    text = ""
    truncated = [
        f"{c.run} at {d:.2g} d ({w:.2g} d wide)" for c in checks for _, d, w in c.truncated
    ]
    if truncated:
        text += (
            f" Truncated wall bins (under {TRUNCATED_FRACTION:g} of a bin wide, centre "
            f"distance from their wall): {'; '.join(truncated)}; centre binning makes their "
            "stresses and nu not physical bulk values, and no stress fit uses them (the "
            f"stress-ratio fits keep bins at least {WALL_EXCLUSION_D:g} d from the walls)."
        )
    tested = [c for c in checks if c.tested]
    if tested:
        n_bad = sum(len(c.balance) for c in tested)
        n_all = sum(c.tested for c in tested)
        text += (
            " Momentum balance (plane: sigma_yx uniform and equal to the moving wall's shear "
            "stress; Couette: r^2 sigma_rt uniform): "
            + (
                f"{n_bad} of {n_all} bins beyond {BALANCE_SIGMAS:g} se of the wall's: "
                + "; ".join(_balance_run(c, by_name[c.run]) for c in tested if c.balance)
                if n_bad
                else f"every one of {n_all} bins within {BALANCE_SIGMAS:g} se of the wall's"
            )
            + "."
            + y_balance_text([by_name[c.run] for c in tested if c.balance])
        )
    dense = [c for c in checks if c.dense]
    if dense:
        text += (
            f" Solids fraction above the hexagonal bound {HEXAGONAL_NU:.3f} (centre binning in "
            "a layered packing; not a bulk value): "
            + "; ".join(
                f"{c.run} "
                + ", ".join(f"{nu:.3f} at {d:.2g} d" for _, d, nu in c.dense[:MAX_LISTED])
                + (f" and {len(c.dense) - MAX_LISTED} more" if len(c.dense) > MAX_LISTED else "")
                for c in dense
            )
            + " (distance from the moving wall)."
        )
    return text


def _unsteady(record: Mapping[str, Any]) -> list[str]:
    """The observables a sidecar's steadiness test finds not steady, each with its numbers
    (their autocorrelation times: :func:`~.measures.autocorrelation_text`)."""
    out = []
    for name, o in (record.get("observables") or {}).items():
        if not isinstance(o, Mapping) or o.get("steady", True):
            continue
        if "first_half" in o and "z" in o:
            out.append(
                f"{name}: halves {float(o['first_half']):.4g} / {float(o['second_half']):.4g}, "
                f"z = {float(o['z']):+.3g}"
            )
        elif "bins_within" in o:
            out.append(
                f"{name}: {100.0 * float(o['bins_within']):.0f}% of bins within the bound "
                f"(max |z| = {float(o.get('max_abs_z', float('nan'))):.3g})"
            )
        else:
            out.append(name)
    return out


def steadiness_text(results: Sequence[RunResult]) -> str:
    """One sentence: which runs the DEM analysis found steady on every observable it tests
    (the sidecar's ``steadiness``: the second half of the time blocks against the first), and
    what is not steady where a run is not (referee 9, point 5); empty without runs."""
    if not results:
        return ""
    records = {r.run.name: r.run.meta.get("steadiness") for r in results}
    known = {n: s for n, s in records.items() if isinstance(s, Mapping)}
    missing = sorted(n for n in records if n not in known)
    bad = {n: _unsteady(s) for n, s in known.items()}
    bad = {
        n: v or ["the run's overall test"]
        for n, v in bad.items()
        if v or not known[n].get("steady", True)
    }
    text = ""
    if known:
        names = sorted({k for s in known.values() for k in (s.get("observables") or {})})
        test = next((s.get("test") for s in known.values() if s.get("test")), "")
        text = (
            f"Steady state ({', '.join(names)}; {test}): shown in "
            f"{len(known) - len(bad)} of {len(known)} runs"
        )
        if bad:
            text += "; NOT shown in " + "; ".join(
                f"{n} ({', '.join(v)})" for n, v in sorted(bad.items())
            )
    if missing:
        text += ("; " if text else "Steady state: ") + (f"not recorded for {', '.join(missing)}")
    return (
        (text + "." if text else "")
        + autocorrelation_text([r.run for r in results])
        + _window_text(results)
    )


def spin_runs(results: Sequence[RunResult], scans: Sequence[Scan] = ()) -> dict[str, SpinRun]:
    """What the spin verdict says of each run beyond its walls (``verdicts.SpinRun``): its
    cell for counting (runs differing only in wall speed are one cell,
    ``rate.replicate_cells``), gap, seed, wall speed, gravity, the moving wall's inertial
    number, what its sidecar's steadiness test finds not steady, and, where the run is
    scanned (``scans``), its joint fit's chi^2 by field, u also under diagonal and
    common-mode errors (the null's own quality, referee 11, point 1)."""
    cells = replicate_cells([r.run for r in results])
    fits = {sc.run: _joint_fit_chi2(sc) for sc in scans}
    basins = {sc.run: _joint_basins(sc) for sc in scans}
    out = {}
    for r in results:
        meta = r.run.meta
        record = meta.get("steadiness")
        bad = _unsteady(record) if isinstance(record, Mapping) else []
        speed = meta.get("wall_speed")
        joint = getattr(r, "joint", None) or {}
        fitted = getattr(r, "fits", None)
        u_only = tuple(
            (m, float(f.chi2), int(f.dof))
            for m in ("mui", "ngf", "cosserat")
            if fitted is not None and (f := fitted.summary(m)) is not None and f.ok
            and f.chi2 is not None
        )  # fmt: skip
        contradiction = tuple(
            (m, f.contradiction)
            for m in ("mui", "ngf", "cosserat")
            if fitted is not None and (f := fitted.summary(m)) is not None and f.contradiction
        )
        out[r.run.name] = SpinRun(
            cells.get(r.run.name, r.run.name),
            r.run.gap_d,
            meta.get("seed"),
            float(speed) if isinstance(speed, int | float) else None,
            r.run.cell == "plane" and r.run.B > 0.0,
            r.inertial_number if r.layer is None else None,
            "; ".join(bad),
            fits.get(r.run.name, ()),
            _moving_grains(r.run),
            joint.get("grain_null"),
            u_only,
            contradiction,
            _fixed_grains(r.run),
            basins.get(r.run.name, ""),
        )
    return out


def _joint_basins(sc: Scan) -> str:
    """Where the joint fit whose velocity is a run's null sits when its 95% region is more
    than one island (``spin_scan.scan_region``; referee 14, point 2: the headline p depends
    on which basin the fit finds), in words, e.g. "K 5.32, L 14.1 d, in one of the islands
    of its 95% region (two islands: ...)"; "" for one island or none. Reads the scan's
    cached region: no solve."""
    from .spin_scan import region_text, scan_region

    region = scan_region(sc)
    if not region or len(region.get("islands") or []) < 2:
        return ""
    return (
        f"K {sc.fit.value('K'):.3g}, L {sc.fit.value('L'):.3g} d, in one of the islands of its "
        f"95% region ({region_text(region)})"
    )


def _joint_fit_chi2(sc: Scan) -> tuple[tuple[str, float, int], ...]:
    """A scan's joint fit by field: (field, chi^2, bins), then u under diagonal and
    common-mode errors where :func:`.spin_scan.error_models` gives them."""
    from .spin_scan import error_models

    out = [(f.field, float(f.chi2), int(f.n)) for f in sc.fit.calibration.fields]
    u = error_models(sc).get("u")
    if u is not None:
        for em in ("diagonal", "common-mode"):
            if u.get(em) is not None:
                out.append((f"u, {em} errors", float(u[em]), int(u["n"])))
    return tuple(out)


def _window_text(results: Sequence[RunResult]) -> str:
    """One sentence on the window rule (referee 9, point 5): each run's averaging window
    starts after at least :data:`~.measures.WINDOW_TRAVEL_D` of the moving wall's travel, or
    which runs' windows start earlier (:func:`~.measures.window_travel`)."""
    travel = {r.run.name: window_travel(r.run) for r in results}
    known = {n: t for n, t in travel.items() if t is not None}
    if not known:
        return ""
    early = {n: t for n, t in known.items() if t < WINDOW_TRAVEL_D - 1e-6}
    text = (
        f" Window rule (at least {WINDOW_TRAVEL_D:g} d of wall travel discarded before "
        f"averaging): met in {len(known) - len(early)} of {len(known)} runs"
    )
    if early:
        text += "; NOT met in " + "; ".join(
            f"{n} (window from {t:.3g} d)" for n, t in sorted(early.items())
        )
    return text + "."


def validate(
    corpus: str | Path | Corpus | None = None,
    out: str | Path | None = None,
    models: Sequence[str] | None = None,
    *,
    f: float = DEFAULT_F,
    near_wall_d: float = NEAR_WALL_D,
    grid: int = 3,
    progress: Callable[[str, int, int], None] | None = None,
    workers: int | None = None,
    spin_scan: int = COARSE,
    independent_bins: bool = False,
    fit_angles: bool = False,
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
    progress : callable, optional
        Called as ``progress("runs", done, total)`` after each run.
    workers : int, optional
        Processes that analyse runs (and draw their figures), make the spin scans and
        calibrate the gap series in parallel; None: one. Timings: ``docs/validation.md``,
        Speed.
    spin_scan : int
        Points per parameter (K, L) of the spin scan behind ``spin_model``
        (:mod:`.spin_scan`; 0: the u-only fits' verdict alone).
    independent_bins : bool
        Also fit each run's models with independent bins, and give both sets of Akaike
        weights in the run's notes (off by default: it doubles to triples the fits' cost).
    fit_angles : bool
        Fit each run's Cosserat model as one profile alone is fitted (phi at its declared
        default, the moving wall's delta and K fitted) rather than with phi and delta fixed from
        the stresses (:func:`.fits.cosserat_fix`; the default).

    Raises
    ------
    InputError
        A malformed corpus (:func:`cosserat.analysis.corpus.read_corpus`).
    ParameterError
        f outside (0, 1), near_wall_d not positive, or an unknown model name.
    """
    if not 0.0 < f < 1.0:
        raise ParameterError(f"f must satisfy 0 < f < 1; got {f:g}")
    if not near_wall_d > 0.0:
        raise ParameterError(f"near_wall_d must be > 0 grain diameters; got {near_wall_d:g}")
    if spin_scan == 1 or spin_scan < 0:
        raise ParameterError(
            f"spin_scan must be 0 (no scan) or at least 2 points per parameter; got {spin_scan}"
        )
    from ...routes import RHEOLOGIES

    if models is not None:
        bad = [m for m in models if m not in RHEOLOGIES]
        if bad:
            raise ParameterError(
                f"unknown model(s) {', '.join(bad)}: registered are {', '.join(RHEOLOGIES)}"
            )
    data = corpus if isinstance(corpus, Corpus) else read_corpus(corpus)
    folder = None if out is None else Path(out)
    if folder is not None:
        folder.mkdir(parents=True, exist_ok=True)
    jobs = series_jobs(data.runs, models, f)
    if fit_angles:  # the Delta calibrations fit phi too
        jobs = [replace(j, fix_phi=False) for j in jobs]
    fixes = None if fit_angles else {r.name: cosserat_fix(r, data.runs) for r in data.runs}
    # the runs with a measured spin, which the spin scans take (as judge's _scans)
    spin_runs = [r for r in data.runs if measure_spin(r, near_wall_d).available]
    from contextlib import nullcontext

    from ...numerics.runtime import worker_processes

    size = pool_size(workers, data.runs, jobs)
    # one pool for the runs, scans and calibrations and then for the report's figures
    with worker_processes(size) if size > 1 else nullcontext() as pool:
        results, cals, scanned = _analyse_all(
            data.runs, models, f, near_wall_d, grid, progress, workers, folder, jobs,
            independent_bins, fixes, spin_runs, spin_scan, pool,
        )  # fmt: skip
        series, verdicts, notes = judge(
            results, models, f, calibrations=cals, spin_scan=spin_scan, scanned=scanned
        )
        used = sorted({m for r in results if r.fits for m in r.fits.models})
        report = ValidationReport(data.path, used, results, series, verdicts, f, near_wall_d, notes)
        if out is not None:
            from .report import write_report

            write_report(report, out, pool, None if scanned is None else scanned.figure_of)
    return report
