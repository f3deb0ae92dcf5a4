"""``validate`` on synthetic corpora whose answers are known (issue 18, "How it is shown").

Each corpus is made by one model (:mod:`cosserat.studies.validate.synthetic`: bins one grain
wide, errors growing with u as the DEM's block errors do, AR(1) noise correlated at rho = 0.4
between neighbouring bins, quasi-static wall speed) and ``validate`` must return, for each
claim, the verdict that follows from the claim's definition (``docs/validation.md``):

* data made by the Cosserat model depart from half the vorticity near the moving wall, with
  the sign and size the model (fitted to the velocity) predicts: ``spin`` supported, and
  ``spin_model`` supported in at least the fraction of independent seeds its own 2-se rule
  predicts (a binomial bound, computed);
* data made by mu(I) or NGF turn with the material (spin = half the vorticity), where the
  Cosserat model fitted to the same velocities predicts a departure these errors would see:
  both refuted;
* the same corpora with errors ten times larger: undecided;
* a mu(I) band thinner than a bin has no measurable Delta, so neither Delta law can be
  decided from it (a bin's width is not a thickness).

Only the Cosserat model is fitted (the spin claims need its predicted departure, and the
other fits cost most of the time): these tests took 30 s together (pytest's durations, at a
load average of 2-7 on two cores), and the 20-seed ``spin_model`` test (marked slow) 32 s
of CPU more (70-100 s at a load of 5-7). The larger version:
``benchmarks/bench_validate_synthetic.py``.
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from cosserat.analysis.corpus import read_run
from cosserat.errors import ParameterError
from cosserat.studies.validate import measured_thickness, validate
from cosserat.studies.validate.synthetic import synthetic_corpus, synthetic_run

ROUGH = {"delta": "fully-rough"}  # tan(delta) = sin(phi), as the corpus reads glued grains
SMOOTH = {"delta": 15.0}  # a wall smoother than the material


def corpus(folder, model, *, noise, seed=0):
    """A plane cell under gravity (B = 1) with each wall, and a Couette cell at R_i/H = 1, all
    at H = 20 d."""
    params = {"rough": ROUGH, "smooth": SMOOTH} if model == "cosserat" else None
    synthetic_corpus(folder, model, plane={"rough": (20.0,), "smooth": (20.0,)},
                     couette=(20.0,), parameters=params, noise=noise, seed=seed)  # fmt: skip
    return folder


def verdicts(report):
    return {v.key: v.verdict for v in report.verdicts}


# --------------------------------------------------------------------------- the generator
def test_a_synthetic_run_reads_back_in_the_corpus_format_with_its_truth(tmp_path):
    path = synthetic_run(tmp_path, "r", "cosserat", "couette", 20.0, parameters=ROUGH,
                         noise=1e-6, rho=0.4, seed=3)  # fmt: skip
    run = read_run(path)
    assert run.notes == ()  # every column described, every sidecar key in the format
    meta = json.loads(path.with_suffix(".json").read_text())
    assert meta["quasi_static"] is True and meta["bin_correlation"]["u"] == 0.4
    assert meta["synthetic_model"]["model"] == "cosserat"
    assert meta["Ri_d"] == 20.0 and run.cell_parameters()["Ri"] == 1.0
    near = meta["wall_inertial_number"]["inner"]["per_bin"]
    assert len(near) == 3 and max(near) <= 1e-3
    u, se = run.quantity("u")
    assert u[0] > 0.3 and np.all(np.diff(u) < 1e-5)  # the inner wall drives the flow
    assert se[0] > 10 * se[-1]  # errors grow with the velocity, as block errors do
    # noise-free: omega - half vorticity is the model's departure, positive at the wall
    omega, _ = run.quantity("omega")
    half, _ = run.quantity("half_vorticity")
    assert half[0] < 0.0 and omega[0] - half[0] > 0.02
    # the sign convention of the corpus: sigma_rt > 0 when the inner cylinder drags +t
    assert np.all(run.columns["sigma_rt"] > 0.0)


def test_the_noise_is_correlated_between_neighbouring_bins_as_the_sidecar_says(tmp_path):
    lags = []
    truth = read_run(synthetic_run(tmp_path, "t", "ngf", "plane", 80.0, noise=1e-6,
                                   stress_noise=1e-9))  # fmt: skip
    for seed in range(20):
        run = read_run(synthetic_run(tmp_path, f"r{seed}", "ngf", "plane", 80.0, noise=0.03,
                                     rho=0.4, seed=seed))  # fmt: skip
        z = (run.columns["sigma_yy"] - truth.columns["sigma_yy"]) / run.columns["sigma_yy_se"]
        lags.append(np.corrcoef(z[:-1], z[1:])[0, 1])
    assert np.mean(lags) == pytest.approx(0.4, abs=0.06)  # 20 x 79 pairs: se of the mean ~0.02


@pytest.mark.parametrize(
    ("kwargs", "message"),
    [
        ({"cell": "channel"}, "cell must be 'plane' or 'couette'"),
        ({"wall": "bumpy"}, "wall must be one of rough, smooth"),
        ({"rho": 1.0}, "rho must lie in [0, 1); got 1"),
        ({"noise": -0.1}, "noise must lie in"),
        ({"model": "kinetic-theory"}, "unknown model 'kinetic-theory'"),
        ({"parameters": {"I_w": 0.01}}, "I_w is set by wall_speed"),
        (
            {"model": "cosserat", "parameters": {"delta": 25.5}},
            "a rough wall (glued grains) is fully rough, tan(delta) = sin(phi) "
            "(eqn-bc_fullyrough); got delta = 25.5 deg, tan(delta)/sin(phi) = 0.999616 at "
            "phi = 28.5 deg",
        ),
    ],
)
def test_bad_inputs_are_one_line_errors(tmp_path, kwargs, message):
    args = {"model": "mui", "cell": "plane"} | kwargs
    with pytest.raises(ParameterError, match=_escape(message)):
        synthetic_run(tmp_path, "r", args.pop("model"), args.pop("cell"), 20.0, **args)


def _escape(text):
    import re

    return re.escape(text)


def test_the_joint_fit_recovers_the_model_that_made_noise_free_data(tmp_path):
    """A model fitted to data it made recovers its parameters (noise and stress noise 1e-6).

    The generator and the calibration solve with one kernel at rtol 1e-8 and measure u and
    omega as the same Gauss-Legendre bin means: at the true parameters they agree to 2e-9
    (measured at noise 2e-9), a thousandth of these errors, so the fit's chi^2 is the noise's
    (chi^2 with dof degrees of freedom, p >= 1e-3) and every parameter lies within 4 of its
    se of the truth, se about 1e-5 of its value. Before: the fit took point values for bin
    means and a rough wall at delta = 25.5 deg (0.04% smoother than fully rough) for fully
    rough (phi 0.012 deg low): chi^2/dof ~ 1400 on the rough run, and the smooth run's
    residuals (over 1e3 se each) read as "no solution at any of 13 starting points"."""
    from cosserat.studies.validate.spin_scan import angles, joint_fit, scan

    synthetic_corpus(tmp_path, "cosserat", plane={"rough": (20.0,), "smooth": (20.0,)},
                     parameters={"rough": ROUGH, "smooth": SMOOTH}, noise=1e-6,
                     stress_noise=1e-6, seed=0)  # fmt: skip
    runs = [read_run(path) for path in sorted(tmp_path.glob("*.csv"))]
    for run in runs:
        truth = run.meta["synthetic_model"]["parameters"]
        ang = angles(run, runs)
        assert abs(ang.phi - truth["phi"]) <= 4.0 * ang.phi_se and ang.phi_se < 1e-4
        if truth["delta"] != "fully-rough":
            # tan delta from the wall's ratio, relative se sqrt(2) 1e-6: 2e-5 deg
            assert abs(ang.delta("moving") - truth["delta"]) <= 4.0 * 2e-5
        fit = joint_fit(run, ang)
        mc = fit.calibration
        assert mc.p_value >= 1e-3, (run.name, mc.chi2, mc.dof)
        for key in ("K", "L"):
            e = mc.parameters[fit._slot(key).name]
            assert e.stderr < 1e-4 * truth[key], (run.name, key, e.stderr)
            assert abs(e.value - truth[key]) <= 4.0 * e.stderr, (run.name, key, e.value)
        # the held-out first layer: the best fit's departure is the data's within their errors
        sc = scan(run, fit, points=2)
        assert abs(sc.best - sc.measured) <= 4.0 * math.hypot(sc.measured_se, sc.prediction_se)


def test_the_calibrations_bin_means_are_the_forward_models(tmp_path):
    """calibration.data.Field.bins: a model's prediction of a binned field is its mean over
    each bin by the rule of validation's forward model (the generator's), to rounding; without
    bins, its value at the bin centre."""
    from cosserat.analysis.ranking import model_solve
    from cosserat.calibration.data import from_run
    from cosserat.calibration.models import Model
    from cosserat.studies.validate.forward import bin_average, bin_edges, model_fields
    from cosserat.studies.validate.spin_scan import bin_means

    run = read_run(synthetic_run(tmp_path, "r", "cosserat", "plane", 20.0, parameters=SMOOTH,
                                 wall="smooth", noise=1e-6, seed=0))  # fmt: skip
    rough = math.tan(math.radians(15.0)) / math.sin(math.radians(28.5))
    values = {"phi": 28.5, "L": 10.0, "A": 1.0 / 3.0, ("K", "moving"): 0.5,
              ("roughness", "moving"): rough}  # fmt: skip
    model = Model("cosserat")
    point = from_run(run)
    binned = bin_means(point, run)
    assert binned.fields["u"].bins is not None and point.fields["u"].bins is None
    fields = model_fields(model_solve(model.problem(binned, values)), run)
    bins = bin_edges(run)
    order = np.argsort(run.distance_d)  # the calibration's order: from the moving wall
    for name, f in (("u", fields.u), ("omega", fields.omega)):
        mean = np.empty(bins.centre.size)
        mean[bins.order] = bin_average(bins, f)
        got = model.predict(binned, values, (name,))[name]
        np.testing.assert_allclose(got, mean[order], rtol=1e-9, atol=1e-12)
        at_centre = model.predict(point, values, (name,))[name]
        y = np.asarray(run.columns["y"], dtype=float)[order]
        np.testing.assert_allclose(at_centre, f(y), rtol=1e-9, atol=1e-12)
        assert np.max(np.abs(at_centre - got)) > 1e-4  # u bends within the first bins


# --------------------------------------------------------------------------- the verdicts
def test_cosserat_data_support_the_spin_claim_and_noisy_ones_cannot_decide(tmp_path):
    """Seed 0, as every other corpus here. ``spin`` is supported: the first layers depart by
    6.5 (rough) and 34 (smooth) se, so the pooled test cannot miss. ``spin_model`` is a 2-se
    window per run and misses honest runs at a rate: its fraction over many seeds is the next
    test's; here only what holds at every seed is asserted (no run refuted: with no stencil
    for synthetic runs the size rule never applies, and the null and sign rules need a first
    layer within 3 se of the null, P < 3e-4 per run). Noisy corpora (errors x 30): the first
    layers are 0.2 and 1.1 se, undecided."""
    report = validate(corpus(tmp_path / "clean", "cosserat", noise=0.01), models=["cosserat"])
    v = verdicts(report)
    assert v["spin"] == "supported", report.verdict("spin").text
    sm = report.verdict("spin_model")
    assert v["spin_model"] in ("supported", "mixed"), sm.text
    # the joint u + omega calibration and scan (spin_scan) decide; the u-only reading is kept
    assert set(sm.numbers["calls"]) == {"cosserat_plane_rough_H20", "cosserat_plane_smooth_H20"}
    assert "refuted" not in sm.numbers["calls"].values(), sm.numbers["calls"]
    assert sm.numbers["u_only_fits"]["opposite_sign"] == []
    # one speed per cell: spin_model, as spin, says rate independence is not shown (referee 8)
    for key in ("spin", "spin_model"):
        text = report.verdict(key).evidence
        assert "Rate independence is not shown" in text or "show rate independence" in text
    noisy = validate(corpus(tmp_path / "noisy", "cosserat", noise=0.3), models=["cosserat"])
    v = verdicts(noisy)
    assert v["spin"] == "undecided", noisy.verdict("spin").text
    assert v["spin_model"] == "undecided", noisy.verdict("spin_model").text
    assert "errors smaller by a factor" in noisy.verdict("spin").would_change


SEEDS = range(0, 60, 3)  # corpus() gives its three runs seeds s, s + 1, s + 2: none shared
CI_SEEDS = range(0, 24, 3)  # the first 8 of them: what CI runs (the 20 are a study)
ALPHA = 1e-3  # the chance that a correct implementation fails the fraction test


@pytest.mark.slow
def test_spin_model_supports_cosserat_data_as_often_as_its_statistics_predict_8_seeds(tmp_path):
    """The study below on its first 8 corpora, with the bound its own statistics give for 8
    (k = 4: P(X < 4) = 2.5e-4 under binomial(8, 0.911)) and the z means within 3 / sqrt(8):
    a weaker test in a third of the time, run in CI."""
    _coverage(tmp_path, CI_SEEDS)


@pytest.mark.study
def test_spin_model_supports_cosserat_data_as_often_as_its_statistics_predict(tmp_path):
    """The 20-corpus study (``pytest -m study``; not in CI: see the cost below)."""
    k = _coverage(tmp_path, SEEDS)
    assert k == 13


def _coverage(tmp_path, seeds) -> int:
    """Over 20 independent clean Cosserat corpora, ``spin_model`` (validate's verdict:
    :func:`scan_verdict` of the plane runs' scans) is "supported" in at least the number its
    own rules predict. A run is supported when its first layer is >= 3 se from the null
    (P = Phi(t/se - 3), t the noise-free departure) and the best fit is within 2 se
    (P(|z| <= 2) = 0.9545 if its se are right and both runs' errors independent); the
    corpus when both runs are: p = 0.911 here. The count is binomial(20, p), and the test
    asks for the largest count k with P(X < k) <= ALPHA (k = 13; P(X < 13) = 1.9e-4).

    Each run's z = (best - data)/se (the se of the 2-se window) has mean 0 over the seeds
    within 3 / sqrt(20) (its sd is at most 1 where the se is right or conservative).

    Measured (this commit): 18 of 20 (per run 19 and 19), z mean -0.08 (sd 0.89) on the rough
    run, -0.10 (sd 0.79) on the smooth one. Before, 15 of 20 and the smooth run's z mean
    +1.03 (+1.18 at the true phi): the joint fit took the model's point values for the bin
    means the data are, and the prediction's se left out the errors of the phi and the smooth
    wall's delta the scan fixes from the stresses (z fell with phi, correlation -0.77). 20
    corpora x 2 joint fits, their refits at phi and delta +- se, and scans: 6 min alone on
    two busy cores (load 8-14), 16 min beside other tests, hence slow."""
    from scipy.stats import binom, norm

    from cosserat.studies.validate.spin_scan import first_bin, scan_verdict, spin_scans

    def runs(folder):
        return [read_run(path) for path in sorted(folder.glob("*.csv"))]

    truth, se0 = {}, {}
    for run in runs(corpus(tmp_path / "truth", "cosserat", noise=1e-6)):
        if run.cell == "plane":
            (omega, _), (half, _) = run.quantity("omega"), run.quantity("half_vorticity")
            truth[run.name] = float(omega[first_bin(run)] - half[first_bin(run)])
    supported, calls, z = 0, [], {r: [] for r in truth}
    for seed in seeds:
        corpus_runs = runs(corpus(tmp_path / f"s{seed}", "cosserat", noise=0.01, seed=seed))
        scans, _ = spin_scans(corpus_runs, corpus_runs)
        assert [sc.run for sc in scans] == list(truth)
        se0 = se0 or {sc.run: sc.measured_beyond_se for sc in scans}
        for sc in scans:
            se = math.hypot(sc.measured_beyond_se, sc.beyond_se)
            z[sc.run].append((sc.beyond_best - sc.measured_beyond) / se)
        verdict = scan_verdict(scans)
        calls.append(verdict.numbers["calls"])
        supported += verdict.verdict == "supported"
    window = 1.0 - 2.0 * norm.sf(2.0)
    p = math.prod(window * norm.cdf(abs(truth[r]) / se0[r] - 3.0) for r in truth)
    n = len(seeds)
    k = next(k for k in range(n, -1, -1) if binom.cdf(k - 1, n, p) <= ALPHA)
    assert p == pytest.approx(0.911, abs=5e-3) and k >= n // 2
    assert supported >= k, calls
    assert all("refuted" not in c.values() for c in calls), calls
    for run, zs in z.items():
        assert abs(np.mean(zs)) <= 3.0 / math.sqrt(n), (run, np.mean(zs), zs)
    return k


@pytest.mark.parametrize("model", ["mui", "ngf"])
def test_data_that_turn_with_the_material_refute_both_spin_claims(tmp_path, model):
    """Data that turn with the material refute spin_model both ways.

    NGF-made data: no first-layer departure, while every (K, L) in the 95% region of the
    Cosserat model's joint u + omega calibration (phi from the runs' stresses) departs by more
    than 3 se: refuted by the scan (spin_scan). The u-only fits' reading is kept: on the plane
    runs phi and delta are fixed from the stresses (fits.cosserat_fix), so those fits agree with
    the band's stress and predict a departure the data reject: refuted too; only the Couette
    run's fit (phi at 28.5 deg: the relations are plane shear's) contradicts its stress.

    mu(I)-made data: the band is thinner than a bin, so no bin measures the band's stress
    ratio, but the moving walls' ratios measure T (referee 10, point 2: the estimator of sin
    phi): phi = 23.4 deg from the rough wall, both plane runs are scanned (only the Couette run
    is not), and the scan refutes at the smooth run by the null rule."""
    report = validate(corpus(tmp_path, model, noise=0.01, seed=7), models=["cosserat"])
    v = verdicts(report)
    assert v["spin"] == "refuted", report.verdict("spin").text
    sm = report.verdict("spin_model")
    assert v["spin_model"] == "refuted", sm.text
    if model == "mui":
        assert sm.numbers["calls"] == {"mui_plane_rough_H20": "undecided",
                                       "mui_plane_smooth_H20": "refuted"}  # fmt: skip
        assert sm.numbers["rules"]["mui_plane_smooth_H20"].startswith("null rule: ")
        assert "mui_couette_rough_H20 (a couette cell: the scan takes plane shear" in sm.evidence
        fixed = {r.run.name: r.fits.summary("cosserat").fixed for r in report.results}
        assert fixed["mui_couette_rough_H20"] == {}
        assert fixed["mui_plane_rough_H20"]["phi"][1].startswith(
            "sin phi = 0.397 +- 0.011: the moving walls' T = |sigma_yx|/N from their contacts, "
            "pooled over mui_plane_rough_H20"
        )
    else:
        assert set(sm.numbers["calls"].values()) == {"refuted"}, sm.numbers["calls"]
        assert "by the null rule: the data do not exclude the null and every admissible" in (
            sm.evidence
        )
        u_only = sm.numbers["u_only_fits"]
        assert u_only["verdict"] == "refuted"
        unfit = {r.run.name: r.fits.summary("cosserat").unfit_reason for r in report.results}
        assert [k for k, why in unfit.items() if why] == ["ngf_couette_rough_H20"], unfit


def test_a_band_thinner_than_a_bin_has_no_delta_and_decides_no_delta_law(tmp_path):
    """mu(I)'s band at I_w = V d / H ~ 1e-4 is a fraction of a grain: the velocity falls from
    its first bin's value to nothing in the next bin, whatever the gap."""
    synthetic_corpus(tmp_path, "mui", plane={"rough": (10.0, 14.0, 20.0),
                                             "smooth": (10.0, 14.0, 20.0)}, noise=0.01)  # fmt: skip
    for path in sorted(tmp_path.glob("*.csv")):
        t = measured_thickness(read_run(path))
        assert t.value is None and "the band is not resolved" in t.reason
    report = validate(tmp_path, models=["cosserat"])
    v = verdicts(report)
    assert (v["smoother"], v["rough"]) == ("undecided", "undecided")
    assert "Delta usable at 0 gap(s)" in report.verdict("rough").evidence


def test_cosserat_data_at_large_gaps_support_the_rough_wall_law(tmp_path):
    """Fully rough walls at H/d = 80, 160, 320, plane shear under gravity and Couette at
    R_i/H = 1: the model's own slopes there are 0.39 and 0.41, on their way to the limit 1/3.
    Neither series may refute the law its own model predicts (before the verdict compared the
    data with the model's slope wherever they missed 1/3, the Couette series of this seed
    was refuted and the verdict mixed)."""
    synthetic_corpus(tmp_path, "cosserat", plane={"rough": (80.0, 160.0, 320.0)},
                     couette=(80.0, 160.0, 320.0), parameters={"rough": ROUGH}, noise=0.04,
                     seed=0)  # fmt: skip
    report = validate(tmp_path, models=["cosserat"])
    v = report.verdict("rough")
    assert v.verdict == "supported", v.text
    plane = next(g for g in report.groups if g.cell == "plane")
    assert abs(plane.slope.slope - 1 / 3) <= 2 * plane.slope.stderr
    assert plane.slope.slope > 4 * plane.slope.stderr  # 0 is far outside


def test_ngf_data_labelled_smooth_are_not_data_of_a_smoother_wall(tmp_path):
    """NGF has no wall friction: its Delta grows at walls labelled smooth as at rough ones
    (5.3, 7.1, 8.9 d at H/d = 20, 40, 80: slope 0.39 +- 0.05). The smoother-wall law is about
    walls smoother than the material, and these walls are not: the series' joint calibration
    finds them fully rough within its error (tan delta / sin phi = 0.98 +- 0.02) and its curve
    follows the data, so the claim is untested here: undecided, not refuted. (With per-run
    refits this case came out undecided for a wrong reason, and the test expected refuted.)"""
    synthetic_corpus(tmp_path, "ngf", plane={"smooth": (20.0, 40.0, 80.0)}, noise=0.03)
    report = validate(tmp_path, models=["cosserat"])
    (series,) = report.groups
    assert series.slope.slope > 5 * series.slope.stderr
    verdict = report.verdict("smoother")
    assert verdict.verdict == "undecided", verdict.text
    fit = series.curves["cosserat"].calibration["parameters"]
    (roughness,) = [v for k, v in fit.items() if k.startswith("roughness[")]
    assert abs(roughness["value"] - 1.0) < 3 * roughness["stderr"]
