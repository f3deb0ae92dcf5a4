"""The spin scan behind ``spin_model`` (:mod:`cosserat.studies.validate.spin_scan`).

The relation phi comes from (a fully rough wall's T = |sigma_yx| / N = sin phi, the stress ratio
T / sigma_yy(s) across the band) is checked against a solved profile; the scan on data the
Cosserat model made gives the sign it was made with; data whose first-layer departure is
reversed are refuted; runs without a spin are clean one-line errors.
"""

from __future__ import annotations

import math
import subprocess
import sys

import numpy as np
import pytest
from scipy.stats import chi2 as chi2_dist

from cosserat.analysis.corpus import read_run, write_run
from cosserat.analysis.ranking import model_solve
from cosserat.errors import InputError, ParameterError
from cosserat.model import make_problem
from cosserat.studies.validate import spin_scan as ss
from cosserat.studies.validate.synthetic import synthetic_run

PHI = 20.0
ROUGH = math.degrees(math.atan(math.sin(math.radians(PHI))))  # tan delta = sin phi
SMOOTH = 15.0
COMMON = {"phi": PHI, "L": 3.0, "K": 0.5}


def _run(folder, name, wall, delta, *, seed=0, **options):
    params = {**COMMON, "delta": delta}
    path = synthetic_run(
        folder, name, "cosserat", "plane", 10.0, parameters=params, wall=wall, B=1.0,
        noise=0.005, stress_noise=0.005, seed=seed, **options,
    )  # fmt: skip
    return read_run(path)


@pytest.fixture(scope="module")
def pair(tmp_path_factory):
    folder = tmp_path_factory.mktemp("pair")
    return _run(folder, "rough", "rough", ROUGH), _run(folder, "smooth", "smooth", SMOOTH, seed=1)


def test_the_band_ratio_is_T_over_sigma_yy_on_a_solved_profile(pair):
    """eqn-nd_xmom, eqn-nd_ymom, eqn-nd_bc1, eqn-nd_bc2, eqn-bc_fullyrough: sigma_yx / N is
    uniform, tan delta at the slipping wall (sin phi when it is fully rough), and
    sigma_yy / N = 1 + B nu eps s at s grain diameters from the moving upper plate."""
    rough, _ = pair
    p = rough.cell_parameters()
    problem = make_problem("cosserat", "plane", {**COMMON, "delta": "fully-rough",
                                                 "eps": p["eps"], "B": p["B"]})  # fmt: skip
    s = np.linspace(0.0, rough.gap_d, 23)
    f = model_solve(problem, points=201).evaluate(1.0 - s * p["eps"])
    ratio = np.abs(f.sigma_yx) / f.sigma_yy
    expected = math.sin(math.radians(PHI)) / ss.normal_stress(rough, s)
    np.testing.assert_allclose(ratio, expected, rtol=1e-8)


def test_phi_and_delta_come_back_from_the_runs_stresses(pair):
    rough, smooth = pair
    t = ss.shear_stress(rough)
    assert abs(t.value - math.sin(math.radians(PHI))) <= 3.0 * t.stderr
    assert t.stderr < 0.01
    # the smooth wall slips: its stresses give delta (here from the wall's contacts: the band
    # is too thin for two stress bins), phi comes from the rough run of the same material
    with pytest.raises(InputError, match="run smooth: fewer than two band bins"):
        ss.shear_stress(smooth)
    ang = ss.angles(smooth, [rough, smooth])
    assert abs(ang.phi - PHI) <= 3.0 * ang.phi_se
    assert "pooled over rough (one run, no consistency test)" in ang.phi_source
    assert ang.delta_source["moving"].startswith("tan delta = ")
    source = ang.delta_source["moving"]
    assert "the moving walls' T = |sigma_yx|/N from their contacts, pooled over smooth" in source
    assert abs(ang.delta("moving") - SMOOTH) < 0.3
    assert ss.angles(rough, [rough, smooth]).roughness == {"moving": 1.0}


def test_a_smooth_run_alone_has_no_phi(pair):
    _, smooth = pair
    with pytest.raises(InputError, match="no plane run with both walls fully rough"):
        ss.angles(smooth, [smooth])


def test_the_scan_of_cosserat_data_gives_the_sign_they_were_made_with(pair):
    rough, smooth = pair
    for run in (rough, smooth):
        sc = ss.scan_run(run, [rough, smooth], points=5)
        assert sc.how.startswith("measured like a synthetic run")
        assert abs(sc.measured) >= 3.0 * sc.measured_se  # a departure of determined sign
        assert sc.best * sc.measured > 0.0
        lo, hi = sc.admissible_span
        assert lo <= sc.best <= hi
        assert ss.wall_call(sc) == "supported", ss._describe(sc)
        assert sc.admissible_count >= 1
        assert sc.departure.shape == (5, 5) and sc.departure_near.shape == (5, 5)
        # the joint fit finds the K and L the data were made with
        assert abs(sc.fit.value("L") - COMMON["L"]) < 1.0
    v = ss.scan_verdict([ss.scan_run(r, [rough, smooth], points=3) for r in (rough, smooth)])
    assert v.verdict == "supported", v.evidence


def test_a_reversed_first_layer_is_refuted(tmp_path, pair):
    """The rough run with its spin mirrored about half the vorticity (omega' = 2 half - omega):
    the first-layer departure changes sign, which no (K, L) of the 95% region gives. The rough
    run is seed 4, whose wall ratio (0.3417 +- 0.0024, which fixes phi) and band T (0.3419 +-
    0.0017) agree, so that its band's stress ratio fits the fixed phi and the joint fit's
    misfit is the spin's alone. (The pair's seed 0 has them 2.1 se apart, 0.3435 against
    0.3375: its two band bins then misfit the wall-fixed phi, and the misfit is read as
    understated errors instead.)"""
    _, smooth = pair
    rough = _run(tmp_path, "agreeing", "rough", ROUGH, seed=4)
    cols = {k: np.asarray(v) for k, v in rough.columns.items()}
    cols["omega"] = 2.0 * cols["half_vorticity"] - cols["omega"]
    write_run(tmp_path, "reversed", dict(rough.meta), cols)
    rev = read_run(tmp_path / "reversed.csv")
    sc = ss.scan_run(rev, [rough, smooth], points=5)
    assert sc.measured < -3.0 * sc.measured_se
    assert sc.admissible_span[0] > 0.0
    assert ss.wall_call(sc) == "refuted"
    v = ss.scan_verdict([sc])
    assert v.verdict == "refuted"
    # refuted by the sign rule, not the size rule: a null enters, so no run is solid
    assert v.evidence.startswith(
        "Refuted at the first layer, as calibrated with the eqn-nd_bc3u wall spin condition. "
        "At reversed the joint fit misfits "
    )
    fields = ss._misfit_fields(sc)
    # the overall p, then each field that misfits (referee 17, point 3(b))
    bad = ss._misfit_parts(sc)
    words = f"misfits (overall p = {sc.fit.calibration.p_value:.2g}; {'; '.join(bad)}"
    if not bad:
        words = "misfits its fields together (overall p = "
    assert f"At reversed the joint fit {words}" in v.evidence
    assert "; sign rule under every stencil. " in v.evidence
    assert " No run is refuted by the size rule, where no null enters" in v.evidence
    # the scope in the verdict field (referee 10, point 1)
    assert v.qualifier == (
        f"where the joint fit misfits (reversed: {fields}), as calibrated with eqn-nd_bc3u"
    )
    assert "Calibrated jointly on u, omega" in v.evidence
    (ratio,) = [f for f in sc.fit.calibration.fields if f.field == "stress_ratio"]
    assert chi2_dist.sf(ratio.chi2, ratio.n) >= ss.FITS_P  # the premise: the stresses fit
    # the mirrored spin misfits the joint fit while the stress ratio fits: the verdict rests
    # on the misfit (inadequacy, referee 8 point 3) and the first layer's sign rule corroborates
    assert v.numbers["reading"] == "inadequacy"
    assert "untested. The misfit at reversed (p < 0.001) is read as the model's inadequacy" in (
        v.evidence
    )
    assert "The held-out first layer: reversed refuted by the sign rule: the data's departure" in (
        v.evidence
    )


def test_runs_without_a_spin_are_one_line_errors(tmp_path, pair):
    rough, smooth = pair
    cols = {k: v for k, v in rough.columns.items() if k not in ("omega", "omega_se")}
    meta = {**rough.meta, "columns": {k: v for k, v in rough.meta.get("columns", {}).items()
                                      if k not in ("omega", "omega_se")}}  # fmt: skip
    write_run(tmp_path, "nospin", meta, cols)
    run = read_run(tmp_path / "nospin.csv")
    message = "run nospin: no omega and omega_se columns: the spin scan needs the measured spin"
    with pytest.raises(InputError, match=message):
        ss.scan_run(run, [rough, smooth])
    with pytest.raises(InputError, match="run nospin: no usable omega bins"):
        ss.joint_fit(run, ss.angles(rough, [rough]))
    scans, skipped = ss.spin_scans([run], [rough, smooth])
    assert scans == [] and skipped == []  # no spin: nothing to scan, nothing to say
    sc_fit = ss.joint_fit(rough, ss.angles(rough, [rough]))
    with pytest.raises(ParameterError, match="at least 2 points per parameter; got 1"):
        ss.scan(rough, sc_fit, points=1)
    with pytest.raises(ParameterError, match="unknown spin predictor 'exact'"):
        ss.scan(rough, sc_fit, points=2, predictor="exact")


def test_validate_rejects_a_one_point_scan_in_one_line(tmp_path):
    proc = subprocess.run(
        [sys.executable, "-m", "cosserat", "validate", str(tmp_path), "--out",
         str(tmp_path / "o"), "--spin-scan", "1"],
        capture_output=True, text=True,
    )  # fmt: skip
    assert proc.returncode == 2
    assert "--spin-scan: must be 0 (no scan) or at least 2 points per parameter; got 1" in (
        proc.stderr
    )


def test_the_scan_figure_draws_each_scanned_run(pair, tmp_path):
    import json

    from cosserat.viz.validation import spin_scan_figure

    rough, smooth = pair
    record = ss.scan_run(rough, [rough, smooth], points=3).to_dict()
    record = json.loads(json.dumps(record))  # as results.json holds it (None, no NaN)
    assert set(record["grids"]) == {"range", "near"}
    fig = spin_scan_figure([record])
    panel, bar = fig.axes
    assert panel.get_xscale() == "log" and panel.get_xlabel() == "L [d]"
    assert "rough" in panel.get_title() and "first-layer" in bar.get_ylabel()
    fig.savefig(tmp_path / "scan.png")


def test_one_run_supported_and_one_missed_in_size_is_mixed(pair):
    import dataclasses

    rough, smooth = pair
    good = ss.scan_run(rough, [rough, smooth], points=3)
    assert ss.wall_call(good) == "supported"
    # the same sign, three times the size: the admissible set gives the sign, the best fit
    # misses the size
    far = dataclasses.replace(good, run="far", measured=3.0 * good.measured)
    assert abs(far.best - far.measured) > 2.0 * math.hypot(far.measured_se, far.prediction_se)
    assert ss.wall_call(far) == "undecided"
    v = ss.scan_verdict([good, far])
    assert v.verdict == "mixed", v.evidence
    # the error models are written once, in scans[]; numbers.error_models points there
    assert v.numbers["error_models"] == {
        "rough": "scans[0].error_models",
        "far": "scans[1].error_models",
    }
    assert v.numbers["scans"][1]["run"] == "far" and "u" in v.numbers["scans"][1]["error_models"]
    assert v.evidence.startswith("Mixed: supported at rough; at far the admissible set gives")
    assert v.would_change.startswith("at far: a best fit whose first-layer departure")
    alone = ss.scan_verdict([far])
    assert alone.verdict == "undecided"
    assert "at far the admissible set gives the measured sign but the best fit misses" in (
        alone.evidence
    )


def test_the_forward_scan_reports_the_first_layer_under_every_stencil(pair):
    from cosserat.studies.validate.forward import STENCILS

    rough, smooth = pair
    fit = ss.joint_fit(rough, ss.angles(rough, [rough, smooth]))
    sc = ss.scan(rough, fit, points=2, predictor="forward")
    assert sc.how.startswith("measured like the data")
    assert set(sc.stencils) == set(STENCILS)
    # the analysis' stencil is the run's own half_vorticity column: the scan's measured value
    assert sc.stencils["analysis"]["data"] == pytest.approx(sc.measured, abs=1e-12)
    assert sc.stencils["analysis"]["model"] == pytest.approx(sc.best, abs=1e-12)
    assert "best fit - data under each stencil, in se of the data's se " in ss._describe(sc)
    assert f"in quadrature: analysis {sc.best - sc.measured:+.3g} (" in ss._describe(sc)
    assert ss.scan(rough, fit, points=2, predictor="point").stencils == {}


# ---------------------------------------------------------------- referee 7, points 5-8, 10
def test_the_first_layer_omega_is_held_out_of_the_joint_fit(pair):
    rough, smooth = pair
    fit = ss.joint_fit(rough, ss.angles(rough, [rough, smooth]))
    i0 = ss.first_bin(rough)
    assert fit.held_out_s == pytest.approx(float(np.asarray(rough.distance_d)[i0]), abs=1e-9)
    (omega,) = [f for f in fit.calibration.fields if f.field == "omega"]
    w, sw = rough.quantity("omega")
    assert omega.n == int(np.count_nonzero(np.isfinite(w) & (sw > 0))) - 1
    assert np.all(omega.s > fit.held_out_s)


def test_a_stencil_free_scan_has_no_null_and_the_forward_one_has_its_own(pair):
    rough, smooth = pair
    fit = ss.joint_fit(rough, ss.angles(rough, [rough, smooth]))
    binned = ss.scan(rough, fit, points=2, predictor="binned")
    assert binned.null_best == 0.0 and np.all(binned.null[np.isfinite(binned.null)] == 0.0)
    assert binned.measured_beyond == binned.measured
    forward = ss.scan(rough, fit, points=2, predictor="forward")
    from cosserat.studies.validate.forward import null_departure

    prof = ss._profile(fit.setup.model, fit.setup.runs[0], fit.setup.run_values(
        fit.setup.runs[0], fit.theta))  # fmt: skip
    i0 = ss.first_bin(rough)
    assert forward.null_best == pytest.approx(float(null_departure(prof, rough)[i0]), abs=1e-12)
    assert forward.beyond_best == pytest.approx(forward.best - forward.null_best, abs=1e-15)
    lo, hi = forward.beyond_span
    assert lo <= forward.beyond_best <= hi
    # the first-layer omega the fitted K implies, measured like the data, and the measured one
    w, sw = rough.quantity("omega")
    assert forward.omega_measured == w[i0] and forward.omega_measured_se == sw[i0]
    assert math.isfinite(forward.omega_model)
    assert "implies a first-layer omega d / V = " in ss._describe(forward)


def test_a_profiles_departure_and_null_share_its_fields_to_the_last_bit(pair):
    """forward_departure and null_departure of one profile evaluate it once per point set
    (forward._kept_fields: 5 evaluations for both, not 8) and give, under every stencil, the
    very floats of forward_fields on a fresh model_fields."""
    from cosserat.studies.validate import forward as fw

    rough, smooth = pair
    fit = ss.joint_fit(rough, ss.angles(rough, [rough, smooth]))
    prof = ss._profile(fit.setup.model, fit.setup.runs[0], fit.setup.run_values(
        fit.setup.runs[0], fit.theta))  # fmt: skip

    class Counting:
        def __init__(self, profile):
            self.problem, self.calls, self._p = profile.problem, 0, profile

        def evaluate(self, xi):
            self.calls += 1
            return self._p.evaluate(xi)

    counted = Counting(prof)
    first = fw.forward_departure(counted, rough), fw.null_departure(counted, rough)
    assert counted.calls == 5  # the sign's probe, u, omega, the point departure at two sets
    for stencil in fw.STENCILS:
        fresh = fw.model_fields(prof, rough)
        want = fw.forward_fields(fresh, rough, stencil)["departure"]
        want_null = fw.forward_fields(fw.turning_with_the_material(fresh), rough, stencil)
        for p in (prof, counted):
            assert np.array_equal(fw.forward_departure(p, rough, stencil), want, equal_nan=True)
            assert np.array_equal(
                fw.null_departure(p, rough, stencil), want_null["departure"], equal_nan=True
            )
    assert np.array_equal(first[0], fw.forward_departure(prof, rough), equal_nan=True)
    assert counted.calls == 5  # the other stencils bin and difference the same values


def test_data_that_do_not_exclude_the_null_are_never_supported(pair):
    import dataclasses

    rough, smooth = pair
    good = ss.scan_run(rough, [rough, smooth], points=3)
    assert ss.wall_call(good) == "supported"
    # the data's departure at the null: the model's own departure would match within 2 se
    # of a wide error, but the null is not excluded
    at_null = dataclasses.replace(
        good, measured=good.null_best + 0.5 * good.best, measured_se=abs(good.best)
    )
    call, rule = ss.wall_rule(at_null)
    assert call == "undecided"
    assert rule.startswith("the data do not exclude the null")


def test_the_size_rule_refutes_a_fit_that_misses_under_every_stencil(pair):
    import dataclasses

    rough, smooth = pair
    good = ss.scan_run(rough, [rough, smooth], points=3)
    stencils = {k: {"data": 0.0, "se": 0.01, "model": 0.05} for k in ("analysis", "wall")}
    missed = dataclasses.replace(good, stencils=stencils)
    models = ", ".join(ss.ERROR_MODEL_NAMES[m] for m in ss.error_model_scales(missed))
    assert ss.wall_rule(missed) == (
        "refuted",
        "size rule: best fit - data beyond 3 se, one sign, under every stencil and every error "
        f"model of u ({models})",
    )
    # one stencil within 3 se: the size rule does not fire, and the run is not supported
    # either: under the analysis' stencil the best fit misses by more than 3 se (referee 10,
    # point 1: a call holds only under every stencil)
    near = {**stencils, "wall": {"data": 0.0, "se": 0.01, "model": 0.02}}
    call, rule = ss.wall_rule(dataclasses.replace(good, stencils=near))
    assert call == "undecided"
    assert rule.startswith("depends on the stencil or u's error model: best fit - data is ")
    v = ss.scan_verdict([missed])
    assert v.verdict == "refuted"
    # the refutation is scoped to the calibration and its wall spin condition (referee 8)
    # where it is refuted (referee 9, point 2; referee 10, point 1: the runs, in the verdict
    # field) in the verdict line, and what it rests on
    assert v.qualifier == "at the first layer of rough, as calibrated with eqn-nd_bc3u"
    assert v.numbers["firm_runs"] == ["rough"]
    assert v.evidence.startswith(
        "Refuted at the first layer of rough, as calibrated with eqn-nd_bc3u. At rough the "
        "joint fit describes u, omega and the stress ratio (p = "
    )
    assert (
        " It rests on one run, rough, and one seed: the only run refuted by the size rule, "
        "where no null enters, with no refit in the scan's reach matching the first layer at "
        "p >= 0.001 (over chi^2/dof). Calibrated jointly on u, omega (the first layer's held "
        "out) and the stress ratio, phi and delta from the stresses; rough"
    ) in v.evidence
    assert v.numbers["solid_runs"] == ["rough"]
    # an unsteady run does not make the verdict firm on its own (referee 10, point 1)
    shaky = dataclasses.replace(missed, steadiness="not steady", unsteady=["dilation z = -5.77"])
    u = ss.scan_verdict([shaky])
    assert (u.verdict, u.qualifier) == ("undecided", "")
    assert u.evidence.startswith(
        "Undecided: refuted at the first layer of rough only, which fails the steadiness test "
        "(rough: dilation z = -5.77): an unsteady run does not make the verdict firm on its own."
    )
    spin = missed.omega_model - missed.omega_measured
    assert (
        f"first-layer omega d / V {missed.omega_model:+.3g} (model) against "
        f"{missed.omega_measured:+.3g} +- {missed.omega_measured_se:.2g} (measured), "
        f"{spin:+.3g} of the best fit - data {missed.best - missed.measured:+.3g}"
    ) in v.evidence
    assert (
        "Other wall spin conditions (omega_w = 0, half the vorticity, couple-stress free), "
        "gaps, seeds and wall speeds are untested. Refuted at rough by the size rule: best fit "
        "- data beyond 3 se"
    ) in v.evidence


def test_the_size_rule_scales_the_data_se_as_the_region_is(pair):
    """One error model (referee 8, point 1): where chi^2/dof = s > 1 scales the region's Delta
    chi^2, the size rule's se is the data's times sqrt(s) with the prediction's spread in
    quadrature; a 5 se miss in the data's bare se is not refuted at s = 4."""
    import dataclasses

    rough, smooth = pair
    good = ss.scan_run(rough, [rough, smooth], points=3)
    stencils = {k: {"data": 0.0, "se": 0.01, "model": 0.05} for k in ("analysis", "wall")}
    mc = good.fit.calibration
    bad = dataclasses.replace(
        good,
        fit=dataclasses.replace(good.fit, calibration=dataclasses.replace(mc, chi2=4.0 * mc.dof)),
        chi2_min=4.0 * mc.dof,
        stencils=stencils,
    )
    assert bad.scale == pytest.approx(4.0)
    se = math.hypot(0.02, bad.prediction_se)
    assert ss.size_se(bad, 0.01) == pytest.approx(se, rel=1e-12)
    assert ss.size_z(bad) == pytest.approx({"analysis": 0.05 / se, "wall": 0.05 / se})
    assert ss.wall_rule(bad)[0] != "refuted"
    # the sign and null rules read the data beyond the null in the same error model
    assert bad.measured_beyond_se == pytest.approx(
        math.hypot(2.0 * bad.measured_se, bad.null_se), rel=1e-12
    )
    assert "in se of the data's se times sqrt(chi^2/dof) = 2, as the 95% region is scaled" in (
        ss._stencil_text(bad)
    )
    # a miss of 3.5 such se under both stencils: refuted by the size rule
    far = {k: {**v, "model": 3.5 * se} for k, v in stencils.items()}
    assert ss.wall_rule(dataclasses.replace(bad, stencils=far))[1].startswith("size rule")


def test_a_misfit_scales_the_region_and_is_warned(pair):
    import dataclasses

    rough, smooth = pair
    good = ss.scan_run(rough, [rough, smooth], points=3)
    mc = good.fit.calibration
    base = float(ss.chi2_dist.ppf(ss.LEVEL, good.k))
    assert good.scale == max(1.0, good.chi2_min / mc.dof)
    bad_mc = dataclasses.replace(mc, chi2=5.0 * mc.dof)
    bad = dataclasses.replace(
        good, fit=dataclasses.replace(good.fit, calibration=bad_mc), chi2_min=5.0 * mc.dof
    )
    assert bad.scale == pytest.approx(5.0) and bad.threshold == pytest.approx(5.0 * base)
    text = ss._misfit_text(bad)
    assert text.startswith("chi^2 by field: u chi^2 = ")
    assert "stress_ratio chi^2 = " in text and "omega chi^2 = " in text
    assert "(WARNING: p < 0.001, the joint fit misfits; the largest excess is " in text
    assert "Delta chi^2 is scaled by chi^2/dof = 5" in text
    assert "first layer's omega (s = " in text
    if good.scale == 1.0:
        assert "WARNING" not in ss._misfit_text(good)


def test_two_runs_of_one_material_say_their_L_differ(pair):
    rough, smooth = pair
    scans = [ss.scan_run(r, [rough, smooth], points=3) for r in (rough, smooth)]
    text = ss._material_text(scans)
    assert "calibrated run by run: rough L = " in text
    assert "one calibration over these runs with phi and L shared and K per wall kind" in text
    assert "no grain-level rolling fraction or slip" in text


def test_claim_spin_model_draws_the_joint_fits(pair, tmp_path):
    import json

    from cosserat.viz.validation import spin_model_joint_figure

    rough, smooth = pair
    records = [
        json.loads(json.dumps(ss.scan_run(r, [rough, smooth], points=3).to_dict()))
        for r in (rough, smooth)
    ]
    assert records[0]["call"] == "supported"
    fig = spin_model_joint_figure(records, "t")
    (ax,) = fig.axes
    assert [t.get_text() for t in ax.get_yticklabels()] == ["rough", "smooth"]
    assert "beyond its null" in ax.get_xlabel()
    fig.savefig(tmp_path / "joint.png")


def test_two_runs_of_one_material_get_one_calibration_with_L_shared(pair):
    rough, smooth = pair
    scans, skipped = ss.spin_scans([rough, smooth], [rough, smooth], points=2)
    assert skipped == [] and [sc.run for sc in scans] == ["rough", "smooth"]
    a, b = (sc.shared for sc in scans)
    assert a["runs"] == b["runs"] == ["rough", "smooth"]
    assert a["L"] == b["L"] and a["chi2"] == b["chi2"]
    assert abs(a["L"] - COMMON["L"]) < 1.0  # the L the data were made with
    # the shared fit of Cosserat-made data gives each run's first layer within 2 se
    for sc in scans:
        assert abs(sc.shared["beyond"] - sc.measured_beyond) <= 2.0 * sc.measured_beyond_se
    text = ss._material_text(scans)
    assert (
        "that calibration (the material's one Cosserat calibration, which the Delta curves read "
        "too: first layers held out, phi and each wall kind's delta fixed from the walls' "
        "stresses): L = "
    ) in text


def test_the_outside_note_compares_departures_beyond_their_nulls(pair):
    """ "Some (K, L) outside the 95% region gives the measured sign" is about the departure
    beyond each point's null, as every rule compares (fig9's finding: the raw departure can
    have the data's sign through its null alone)."""
    import dataclasses

    rough, smooth = pair
    good = ss.scan_run(rough, [rough, smooth], points=3)
    stencils = {k: {"data": 0.0, "se": 0.01, "model": 0.05} for k in ("analysis", "wall")}
    missed = dataclasses.replace(good, stencils=stencils)
    assert ss.scan_verdict([missed]).verdict == "refuted"
    size = 2.0 * abs(missed.measured_beyond) + 0.01
    sign = 1.0 if missed.measured_beyond > 0.0 else -1.0
    # each raw departure has the data's sign, and each null twice it: beyond the null every
    # point has the other sign
    raw = dataclasses.replace(
        missed,
        best=missed.null_best - missed.measured_beyond,  # the best fit beyond its null: -data
        departure=np.full(good.departure.shape, sign * size),
        null=np.full(good.departure.shape, 2.0 * sign * size),
        departure_near=np.full(good.departure_near.shape, sign * size),
        null_near=np.full(good.departure_near.shape, 2.0 * sign * size),
    )
    lo, hi = raw.whole_beyond_span
    assert sign * hi < 0.0 if sign > 0.0 else sign * lo < 0.0  # none has the data's sign
    assert not ss._sign_given(raw.whole_beyond_span, raw.measured_beyond)
    assert ss._sign_given(raw.whole_span, raw.measured)  # raw, every point has it
    text = ss.scan_verdict([raw]).evidence
    assert "outside the 95% region gives the sign" not in text
    # no null, and the data's sign only outside the 95% region: the note names the run
    far = np.where(good.admissible, -sign * size, sign * size)
    assert (~good.admissible & np.isfinite(good.departure)).any()
    bare = dataclasses.replace(
        raw,
        departure=far,
        null=np.zeros(good.departure.shape),
        departure_near=np.full(good.departure_near.shape, -sign * size),
        null_near=np.zeros(good.departure_near.shape),
    )
    assert ss._sign_given(bare.whole_beyond_span, bare.measured_beyond)
    assert ss.scan_verdict([bare]).verdict == "refuted"
    assert (
        "At rough some (K, L) of the declared ranges outside the 95% region gives the sign of "
        "the measured departure beyond the null."
    ) in ss.scan_verdict([bare]).evidence


def test_the_shared_calibration_is_the_material_calibration_the_delta_curves_read(pair):
    """Referee 10, point 6: one Cosserat calibration of a material. The spin scan's shared
    calibration and the Delta verdicts' material calibration are one call on the same data
    (spin_scan.material_data) with the same angles (stresses.material_angles): the same L,
    chi^2 and dof to the last digit, phi and each wall kind's roughness fixed, not fitted."""
    from cosserat.studies.validate.fits import calibrate_material
    from cosserat.studies.validate.stresses import material_angles

    rough, smooth = pair
    scans, _ = ss.spin_scans([rough, smooth], [rough, smooth], points=2)
    out = calibrate_material([smooth, rough], ["cosserat"], [("all", [rough, smooth], 0.05)],
                             curve=False)  # fmt: skip
    (cal,) = out["all"]
    assert cal.status == "ok"
    shared = scans[0].shared
    assert shared["L"] == cal.summary["parameters"]["L"]["value"]
    assert shared["chi2"] == cal.summary["chi2"] and shared["dof"] == cal.summary["dof"]
    fix, _, _ = material_angles([rough, smooth])
    assert cal.summary["fixed"] == fix and len(fix) == 3
    (glued,) = [k for k in fix if k.startswith("roughness[glued-grains")]
    (smooth_kind,) = [k for k in fix if k.startswith("roughness[smooth-frictional")]
    assert fix[glued] == 1.0 and 0.0 < fix[smooth_kind] < 1.0
    # the calibration holds out each run's first-layer omega and compares u, omega as bin means
    for rd in ss.material_data([rough, smooth]):
        run = rough if rd.name == "rough" else smooth
        first = float(np.asarray(run.distance_d)[ss.first_bin(run)])
        assert first not in rd.fields["omega"].s
        assert rd.fields["u"].bins is not None and rd.fields["omega"].bins is not None
