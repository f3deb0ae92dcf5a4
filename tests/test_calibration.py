"""The calibration engine: its error model, its diagnostics, joint recovery of known
parameters from synthetic runs made by each model, misfit warnings on another model's data,
the posterior against least squares where both are exact, and the command line.

The coverage of the 68% intervals over hundreds of noisy replicas is a benchmark
(``benchmarks/bench_calibration.py``), too slow for a test.
"""

from __future__ import annotations

import json
import math
import subprocess
import sys
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from cosserat.analysis.corpus import read_corpus, shipped_corpus
from cosserat.calibration import Calibration, calibrate, calibrate_model, load
from cosserat.calibration import diagnostics as dg
from cosserat.calibration.data import Field, RunData, from_run, with_correlations
from cosserat.calibration.engine import setup
from cosserat.calibration.models import Model, ModelParam
from cosserat.calibration.noise import Correlation, covariance, estimate_rho, whiten
from cosserat.calibration.synthetic import make_runs, template_run, template_runs
from cosserat.errors import InputError, ParameterError
from cosserat.model.declare import Param

TRUTH = {
    "cosserat": {"phi": 20.0, "L": 8.0, "roughness[rough]": 0.8, "K[rough]": 0.6},
    "mui": {"mu_s": 0.3, "I_0": 0.3},
    "ngf": {"mu_s": 0.3, "b": 1.0, "A": 0.5},
}

ROOT = Path(__file__).resolve().parents[1]


# --------------------------------------------------------------------------- error model
def test_whitening_makes_ar1_noise_white(rng):
    n, rho = 30, 0.7
    se = np.linspace(0.5, 2.0, n)
    chol = np.linalg.cholesky(covariance(se, rho))
    w = np.array([whiten(chol @ rng.standard_normal(n), se, rho) for _ in range(4000)])
    c = np.cov(w.T)
    assert np.allclose(np.diag(c), 1.0, atol=0.08)
    off = c[~np.eye(n, dtype=bool)]
    assert np.max(np.abs(off)) < 0.08


@pytest.mark.parametrize("rho", [0.0, 0.4, 0.8])
def test_rho_is_recovered_from_the_data_alone(rng, rho):
    """The second-difference estimate, pooled over ten profiles of a shear band, lands within
    0.1 of the correlation the noise was made with."""
    ys, ss = [], []
    for _ in range(10):
        s = np.arange(0.5, 40.0)
        se = 0.02 * (1.0 + s / 40.0)
        truth = np.exp(-s / 5.0)
        ys.append(truth + np.linalg.cholesky(covariance(se, rho)) @ rng.standard_normal(s.size))
        ss.append(se)
    est = estimate_rho(ys, ss)
    assert est.source == "estimated"
    assert abs(est.rho - rho) < 0.1


def test_rho_needs_enough_bins():
    assert estimate_rho(np.ones(4), np.ones(4)) == Correlation(0.0, "too few bins")


# --------------------------------------------------------------------------- diagnostics
def test_runs_test_flags_a_trend_not_noise(rng):
    assert dg.runs_test(np.r_[np.ones(10), -np.ones(10)]).p_value < 1e-3
    ps = [dg.runs_test(rng.standard_normal(40)).p_value for _ in range(400)]
    assert 0.01 < np.mean(np.array(ps) < 0.05) < 0.09  # close to its nominal 5%


def test_misfit_regions_name_where_the_model_misses():
    s = np.arange(0.5, 20.0)
    z = np.zeros_like(s)
    z[12:16] = -3.0
    u = np.exp(-s / 2.0)
    (region,) = dg.misfit_regions(s, z, u)
    assert region.where == "in the creep tail" and region.bins == 4 and region.sign == -1
    z[:] = 0.0
    z[0:3] = 2.5
    assert dg.misfit_regions(s, z, u)[0].where == "at the moving wall"


def test_flat_direction_is_the_unidentified_combination():
    # residuals depend on a + b only: a - b is not determined
    J = np.column_stack([np.ones(20), np.ones(20)]) * 10.0
    (flat,) = dg.flat_directions(J, ["a", "b"], np.ones(2))
    assert set(flat.components) == {"a", "b"}
    assert flat.components["a"] * flat.components["b"] < 0  # the difference
    assert dg.flat_directions(np.eye(2) * 10.0, ["a", "b"], np.ones(2)) == []


# --------------------------------------------------------------------------- recovery
@pytest.mark.parametrize("model", ["cosserat", "mui", "ngf"])
def test_joint_calibration_recovers_each_models_parameters(model):
    """Three runs (two plane-shear gaps under gravity, one Couette cell) made by the model,
    with correlated noise: every free parameter comes back within 3.5 standard errors, chi^2
    is consistent with its degrees of freedom, and no misfit is reported."""
    m = Model(model)
    runs = make_runs(m, TRUTH[model], rho={"u": 0.5, "omega": 0.2}, seed=11)
    mc = calibrate_model(m, runs)
    assert mc.ok, mc.message
    for name, value in TRUTH[model].items():
        e = mc.parameters[name]
        assert e.stderr is not None, (name, e.reason)
        assert abs(e.value - value) < 3.5 * e.stderr, (name, e.value, e.stderr)
        assert e.shared and e.free
    assert mc.p_value > 1e-3
    assert not [w for w in mc.warnings if "misfit" in w or "chi^2 =" in w], mc.warnings


def test_data_made_by_another_model_are_flagged():
    runs = make_runs(Model("mui"), TRUTH["mui"], seed=3)
    cos = calibrate_model(Model("cosserat"), runs)
    assert cos.ok and cos.p_value < 1e-3
    assert any(w.startswith("cosserat: misfit") for w in cos.warnings)
    # the warning names the run and the field
    assert any("run plane_H40, u" in w for w in cos.warnings)
    own = calibrate_model(Model("mui"), runs)
    assert own.p_value > 1e-3 and not own.warnings
    cal = Calibration(runs, [cos, own])
    # the Cosserat model misfits, so the weights are not calibrated: the least bad is named,
    # but not as the best
    assert cal.lowest_aic == "mui" and not cal.calibrated_weights and cal.best is None
    assert Calibration(runs, [own]).best == "mui"


def test_material_parameters_are_shared_and_metadata_fixed():
    runs = template_runs()
    s = setup(Model("cosserat"), runs)
    names = {sl.name: sl for sl in s.slots}
    assert names["phi"].runs == ("plane_H20", "plane_H40", "couette_H20")
    assert names["K[rough]"].scope == "wall"
    assert not names["A"].free  # fixed by default
    # a second wall kind gets its own parameters; the material stays one
    other = replace(runs[2], walls={"moving": "smooth", "fixed": "smooth"})
    s2 = setup(Model("cosserat"), [*runs[:2], other])
    assert {"K[rough]", "K[smooth]", "roughness[smooth]"} <= {sl.name for sl in s2.slots}
    # the wall's inertial number is the metadata's, never a fitted parameter
    assert "I_w" not in {sl.key for sl in setup(Model("mui"), runs).slots}
    with pytest.raises(ParameterError, match="needs the wall's inertial number"):
        Model("mui").problem(replace(runs[0], I_w=None), {"mu_s": 0.3})


def test_fixing_and_freeing():
    runs = make_runs(Model("cosserat"), TRUTH["cosserat"], seed=2)
    mc = calibrate_model(Model("cosserat"), runs, fix={"phi": 20.0}, free=["A"])
    assert not mc.parameters["phi"].free and mc.parameters["phi"].value == 20.0
    assert mc.parameters["A"].free
    with pytest.raises(ParameterError, match="not a parameter of cosserat"):
        setup(Model("cosserat"), runs, fix={"mu_s": 0.3})


def test_a_fully_rough_wall_is_a_bound_not_an_error():
    truth = dict(TRUTH["cosserat"], **{"roughness[rough]": 1.0})
    runs = make_runs(Model("cosserat"), truth, seed=5)
    mc = calibrate_model(Model("cosserat"), runs)
    d = mc.parameters["delta[rough]"]
    if mc.parameters["roughness[rough]"].at_bound == "upper":
        assert "fully rough" in d.reason
    assert abs(d.value - math.degrees(math.atan(math.sin(math.radians(20.0))))) < 1.0


# --------------------------------------------------------------------------- posterior
class Line(Model):
    """y = a + b s on a plane cell: a linear-Gaussian model, posterior known exactly."""

    def __init__(self) -> None:
        self.name = "line"
        self.local_spin = False

    def fields(self):  # type: ignore[override]
        return ("u",)

    def cells(self):  # type: ignore[override]
        return ("plane",)

    def parameters(self):  # type: ignore[override]
        def p(key: str) -> ModelParam:
            return ModelParam(
                key,
                Param(name=key, meaning=key, default=0.0, fit_range=(-50.0, 50.0), role="material"),
            )

        return (p("a"), p("b"))

    def predict(self, run, values, fields):  # type: ignore[override]
        return {"u": values["a"] + values["b"] * run.fields["u"].s}


def test_posterior_of_a_linear_gaussian_model_matches_least_squares():
    pytest.importorskip("emcee")
    from cosserat.calibration.posterior import sample_posterior

    s = np.linspace(0.0, 10.0, 25)
    se = np.full_like(s, 0.3)
    y = 1.0 + 0.5 * s + np.random.default_rng(4).normal(0.0, 0.3, s.size)
    run = RunData(
        "line",
        "plane",
        10.0,
        {"eps": 0.1},
        None,
        "m",
        {"moving": "w", "fixed": "w"},
        {"u": Field("u", s, y, se, Correlation(0.0, "given"))},
    )
    mc = calibrate_model(Line(), [run])
    X = np.column_stack([np.ones_like(s), s]) / 0.3
    cov = np.linalg.inv(X.T @ X)
    beta = cov @ X.T @ (y / 0.3)
    assert np.allclose([mc.parameters["a"].value, mc.parameters["b"].value], beta, rtol=1e-6)
    assert np.allclose(
        [mc.parameters["a"].stderr, mc.parameters["b"].stderr], np.sqrt(np.diag(cov)), rtol=1e-4
    )
    post = sample_posterior(mc, 20000, seed=1).posterior
    for i, name in enumerate(("a", "b")):
        sd = math.sqrt(cov[i, i])
        assert abs(post.parameters[name]["mean"] - beta[i]) < 0.1 * sd
        assert abs(post.parameters[name]["sd"] / sd - 1.0) < 0.1


# --------------------------------------------------------------------------- data
def test_the_shipped_corpus_loads_in_the_calibration_frame():
    skipped: list[str] = []
    runs = with_correlations(load([shipped_corpus()], skipped))
    assert len(skipped) == 1 and "channel_rough_H20" in skipped[0]
    plane = next(r for r in runs if r.name == "plane_rough_H40")
    assert set(plane.fields) == {"u", "omega", "stress_ratio", "wall_ratio"}
    u = plane.fields["u"]
    assert np.all(np.diff(u.s) > 0) and u.value[0] > 0.8  # the moving wall first
    # spin and half the vorticity turn the same way near the moving wall
    assert plane.fields["omega"].value[0] < 0
    ratio = plane.fields["stress_ratio"]
    assert 0.2 < ratio.value[0] < 0.35 and ratio.s[0] >= 1.0
    assert 5e-4 < plane.I_w < 1e-2
    assert u.correlation.source == "estimated"
    (channel,) = [r for r in read_corpus(shipped_corpus()).runs if r.cell == "channel"]
    with pytest.raises(InputError, match="cannot be calibrated yet"):
        from_run(channel)  # refused in words, not by a traceback


def test_json_contract_and_dataframe():
    runs = make_runs(Model("cosserat"), TRUTH["cosserat"], runs=template_runs()[:1], seed=1)
    cal = calibrate(runs, models=["cosserat", "mui"])
    d = json.loads(cal.to_json())
    assert d["lowest_aic"] in ("cosserat", "mui")
    assert d["best"] == (d["lowest_aic"] if d["weights"]["calibrated"] else None)
    m = d["models"][0]
    for key in (
        "model",
        "status",
        "parameters",
        "per_run",
        "chi2",
        "dof",
        "p_value",
        "aic",
        "bic",
        "warnings",
    ):
        assert key in m
    assert set(m["parameters"]["phi"]) >= {"value", "stderr", "free", "shared", "unit"}
    assert m["per_run"]["plane_H20"]["fields"]["u"]["n"] == 20
    assert [r["name"] for r in d["runs"]] == ["plane_H20"]
    df = cal.to_dataframe()
    assert {"model", "parameter", "value", "stderr"} <= set(df.columns)


# --------------------------------------------------------------------------- command line
def test_cli_calibrate_on_the_shipped_corpus(tmp_path):
    corpus = shipped_corpus()
    out = tmp_path / "cal"
    proc = subprocess.run(
        [
            sys.executable,
            "-m",
            "cosserat",
            "calibrate",
            str(corpus / "plane_rough_H20.csv"),
            str(corpus / "couette_Ri20_H10.csv"),
            "--models",
            "cosserat,ngf",
            "--format",
            "json",
            "--out",
            str(out),
            "-q",
        ],
        capture_output=True,
        text=True,
        timeout=600,
    )
    assert proc.returncode == 0, proc.stderr
    d = json.loads(proc.stdout)
    assert [m["model"] for m in d["models"]] == ["cosserat", "ngf"]
    assert (out / "calibration.json").is_file() and (out / "report.md").is_file()
    assert (out / "fit_plane_rough_H20.png").is_file()
    # the shipped runs are not what the models describe: the misfit is said, naming the run
    assert any(
        "couette_Ri20_H10" in w or "plane_rough_H20" in w for w in d["models"][0]["warnings"]
    )


def test_cli_calibrate_refuses_bad_input_in_one_line(tmp_path):
    corpus = shipped_corpus()
    for args, words in [
        (["--models", "cosserat,cosserat"], "named twice"),
        (["--fix", "mu_s=abc"], "must be a number"),
        (["--fix", "nothing=1"], "no model has a parameter"),
        (["--fields", "u,pressure"], "unknown field"),
        (["--posterior", "10"], "give --out"),
    ]:
        proc = subprocess.run(
            [
                sys.executable,
                "-m",
                "cosserat",
                "calibrate",
                str(corpus / "plane_rough_H20.csv"),
                *args,
            ],
            capture_output=True,
            text=True,
            timeout=300,
        )
        assert proc.returncode == 2, (args, proc.stderr)
        assert words in proc.stderr and len(proc.stderr.strip().splitlines()) == 1
    proc = subprocess.run(
        [sys.executable, "-m", "cosserat", "calibrate", str(tmp_path / "missing.csv")],
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert proc.returncode == 2 and "no such file" in proc.stderr


def test_template_runs_carry_their_cells():
    r = template_run("c", "couette", 10.0, Ri_d=20.0)
    assert r.cell_values == {"eps": 0.1, "Ri": 2.0}
    assert isinstance(r.fields["u"], Field)


# --------------------------------------------------------------------------- data checks
def test_regime_rate_pairs_and_the_error_models_cap():
    from cosserat.calibration import checks

    runs = load([shipped_corpus()], [])
    by = {r.name: r for r in runs}
    notes = checks.regime(runs)
    # every shipped run is faster than quasi-static next to its moving wall
    assert len(notes) == len(runs) and all("not quasi-static" in n for n in notes)
    assert 1e-3 < by["plane_rough_H40"].local_inertial_number < 0.1
    pairs = checks.rate_pairs(runs)
    (pair,) = pairs  # the one cell shipped at two speeds
    assert "plane_rough_H20 and plane_rough_H20_halfspeed" in pair
    # a run against itself at a fake other speed agrees exactly
    twin = replace(by["plane_rough_H40"], name="twin", I_w=2 * by["plane_rough_H40"].I_w)
    (same,) = checks.rate_pairs([by["plane_rough_H40"], twin])
    assert "chi^2 = 0.0" in same and "they agree" in same
    capped = with_correlations(runs)
    assert any("bins of u" in n for n in checks.error_model(capped))


def test_the_moving_walls_stress_ratio_is_a_datum():
    run = next(r for r in load([shipped_corpus()], []) if r.name == "plane_smooth_H40")
    wall = run.fields["wall_ratio"]
    assert wall.n == 1 and wall.s[0] == 0.0
    sidecar = json.loads((shipped_corpus() / "plane_smooth_H40.json").read_text())
    ws = sidecar["wall_stress"]
    assert wall.value[0] == pytest.approx(abs(ws["shear"]) / ws["normal"])
    # the Cosserat model predicts tan(delta) there
    pred = Model("cosserat").predict(
        run, {"phi": 20.0, "L": 8.0, ("roughness", "moving"): 0.5, ("K", "moving"): 0.5},
        ["wall_ratio"],
    )["wall_ratio"]  # fmt: skip
    assert pred[0] == pytest.approx(0.5 * math.sin(math.radians(20.0)), rel=1e-6)


def test_held_out_runs_are_predicted_not_fitted():
    truth = TRUTH["cosserat"]
    runs = make_runs(Model("cosserat"), truth, seed=8)
    cal = calibrate(runs, models=["cosserat"], holdout=["plane_H40"])
    m = cal["cosserat"]
    assert [r.name for r in cal.runs] == ["plane_H20", "couette_H20"]
    assert {f.run for f in m.held_out} == {"plane_H40"}
    # made by the model: the prediction holds (chi^2 near its bins)
    for f in m.held_out:
        assert dg.chi2_log10_p(f.chi2, f.n) > -3, (f.field, f.chi2, f.n)
    with pytest.raises(ParameterError, match="not among the runs"):
        calibrate(runs, models=["cosserat"], holdout=["nope"])


def test_weights_are_not_calibrated_when_every_model_misfits():
    runs = make_runs(Model("mui"), TRUTH["mui"], seed=3)
    both = calibrate(runs, models=["cosserat", "mui"])
    assert not both.calibrated_weights  # the Cosserat model misfits these data
    assert calibrate(runs, models=["mui"]).calibrated_weights
    assert (
        both["cosserat"].parameters["phi"].stderr_scaled > both["cosserat"].parameters["phi"].stderr
    )


def test_p_values_past_underflow():
    assert dg.chi2_log10_p(10.0, 10) == pytest.approx(math.log10(0.4404932850652124))
    from scipy import stats

    # past underflow the leading term of the incomplete gamma function takes over; where both
    # exist they agree to 0.1 in log10 p (here 1200 on 170)
    assert math.isinf(stats.chi2.logsf(4000.0, 170))
    assert -750 < dg.chi2_log10_p(4000.0, 170) < -690
    a, x = 85.0, 600.0
    lead = (-x + (a - 1.0) * math.log(x) - math.lgamma(a)) / math.log(10.0)
    assert abs(lead - stats.chi2.logsf(1200.0, 170) / math.log(10.0)) < 0.1
    assert dg.p_text(-123.4) == "z = 23.7"  # never "p = 10^-123" (referee 5, request 8)


def test_leave_one_out_agrees_on_data_made_by_the_model():
    runs = make_runs(Model("cosserat"), TRUTH["cosserat"], seed=12)
    cal = calibrate(runs, models=["cosserat"], leave_one_out=True)
    m = cal["cosserat"]
    phi = m.parameters["phi"]
    lo, hi, se = phi.jackknife
    assert lo <= phi.value <= hi or abs(phi.value - lo) < 3 * phi.stderr
    # one material made the runs: no warning that they disagree
    assert not [w for w in m.warnings if "do not agree" in w]
    assert m.to_dict()["parameters"]["phi"]["leave_one_out"]["se"] == pytest.approx(se)


def test_a_long_one_sided_stretch_is_said_where_correlation_hides_it():
    s = np.arange(0.5, 30.0)
    z = np.r_[np.ones(5), -np.ones(25)] * 1.5
    assert dg.longest_stretch(s, z)[:1] == (25,)
    runs = make_runs(Model("ngf"), TRUTH["ngf"], rho={"u": 0.9}, seed=4)
    m = calibrate_model(Model("cosserat"), runs)
    # a long stretch on one side is tested against the error model, both ways, and the
    # warning says where the correlation came from (given here, not estimated)
    stretches = [w for w in m.warnings if "neighbouring bins" in w]
    assert stretches
    for w in stretches:
        assert "rests on that correlation" in w or "improbable even" in w
        assert "correlated as given (rho = " in w and "as estimated" not in w
    # the test itself: 25 of 30 on one side is rare for independent bins, common at rho 0.95
    assert dg.stretch_p_value(30, 0.0, 25) < 1e-3 < dg.stretch_p_value(30, 0.95, 25)
    assert 0.2 < dg.stretch_p_value(20, 0.0, 5) < 0.8


def test_the_posterior_predictive_carries_the_noise():
    pytest.importorskip("emcee")
    from cosserat.calibration.posterior import predictive, sample_posterior

    s = np.linspace(0.0, 10.0, 25)
    y = 1.0 + 0.5 * s
    se = np.full_like(s, 0.3)
    field = Field("u", s, y, se, Correlation(0.0, "given"))
    run = RunData("line", "plane", 10.0, {"eps": 0.1}, None, "m", {"moving": "w", "fixed": "w"},
                  {"u": field})  # fmt: skip
    mc = sample_posterior(calibrate_model(Line(), [run]), 2000, seed=2)
    setup_, _, chain = mc.internal
    rep = predictive(setup_, chain, draws=400, seed=3)["line/u"]
    bare = predictive(setup_, chain, draws=400, seed=3, noise=False)["line/u"]
    # replicated data scatter by the noise (0.3) on top of the parameters' spread
    assert np.std(rep - bare) == pytest.approx(0.3, rel=0.1)


def test_leave_one_out_names_the_run_of_another_material():
    """Two runs made with phi = 20 deg and one with phi = 26 deg, calibrated as one material:
    leaving the odd run out moves phi more than the errors allow, and the warning names it."""
    made = TRUTH["cosserat"]
    runs = template_runs()
    same = make_runs(Model("cosserat"), made, runs=runs[:2], seed=5)
    odd = make_runs(Model("cosserat"), {**made, "phi": 26.0}, runs=runs[2:], seed=6)
    cal = calibrate([*same, *odd], models=["cosserat"], leave_one_out=True)
    notes = [w for w in cal["cosserat"].warnings if "do not agree" in w and "phi" in w]
    assert notes and odd[0].name in notes[0]


def test_load_compares_a_dem_runs_binned_fields_as_bin_means():
    """cosserat calibrate (calibration.data.load) marks a cosserat.dem run's u and omega as bin
    means over the run's own bins: contiguous, the first from the moving wall's surface, each
    holding its centre; from_run alone keeps the centres, and a run whose sidecar says its
    values are point values is left at the centres."""
    from cosserat.analysis.corpus import read_run

    path = ROOT / "data" / "dem_v2" / "plane_rough_H20_qs" / "profile.csv"
    (binned,) = load([path])
    (at_centres,) = load([path], bin_means=False)
    run = read_run(path)
    assert from_run(run).fields["u"].bins is None and at_centres.fields["u"].bins is None
    for name in ("u", "omega"):
        f = binned.fields[name]
        near, far = f.bins
        assert near[0] == 0.0  # the moving wall's surface
        # contiguous, in order, to the 4 decimals of the CSV's centres (the end bin's far edge is
        # twice its centre's distance)
        np.testing.assert_allclose(near[1:], far[:-1], atol=2e-4)
        assert np.all((near < f.s) & (f.s < far))
        np.testing.assert_allclose(far[1:-1] - near[1:-1], 1.0, rtol=1e-9)  # 1 d bins inside
    assert binned.fields["stress_ratio"].bins is None  # stresses stay at the centres
    point = replace(run, meta={**run.meta, "half_vorticity_method": "point"})
    assert from_run(point, bin_means=True).fields["u"].bins is None


def test_a_bin_mean_uses_the_gauss_legendre_rule_made_once():
    """Field.nodes' Gauss-Legendre rule is numpy's leggauss to the last bit, made once per
    number of points (it cost ~0.8 ms at every prediction) and read-only, so no caller can
    change it for the next."""
    from cosserat.calibration.data import BIN_NODES, gauss_legendre

    x, w = gauss_legendre(BIN_NODES)
    want_x, want_w = np.polynomial.legendre.leggauss(BIN_NODES)
    assert np.array_equal(x, want_x) and np.array_equal(w, want_w)
    assert gauss_legendre(BIN_NODES)[0] is x
    with pytest.raises(ValueError, match="read-only"):
        x[0] = 0.0
    lo, hi = np.array([0.0, 1.0]), np.array([1.0, 3.0])
    field = Field("u", 0.5 * (lo + hi), np.zeros(2), np.ones(2), bins=(lo, hi))
    pts, weights = field.nodes()
    assert np.array_equal(pts[1], 2.0 + want_x) and np.array_equal(weights[0], want_w)
    # the nodes themselves are made once per field (asked at every prediction) and read-only
    assert field.nodes()[0] is pts and field.nodes()[1] is weights
    with pytest.raises(ValueError, match="read-only"):
        pts[0, 0] = 0.0
    centres = Field("u", np.array([0.5, 2.0]), np.zeros(2), np.ones(2))
    at, one = centres.nodes()
    assert np.array_equal(at[:, 0], [0.5, 2.0]) and np.array_equal(one, np.ones((2, 1)))
    assert centres.nodes()[0] is at and centres.s.flags.writeable  # s itself left writable
