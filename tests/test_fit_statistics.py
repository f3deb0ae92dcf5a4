"""validate's fits with correlated bins, and numbers a referee can read (issue 18; referee 5,
requests 4 and 8): the AR(1) error model of the calibration engine in the per-run fits, the
Jacobian at the edge of the region where a model has a solution (NGF's b +- 1.7e-10 on the v2
runs), and significances printed as z and chi^2/dof."""

from __future__ import annotations

import math
import shutil
from pathlib import Path

import numpy as np
import pytest

from cosserat.analysis.corpus import read_run, write_run
from cosserat.calibration.engine import NO_SOLUTION_RESIDUAL, jacobian, jacobian_with_edges
from cosserat.calibration.noise import covariance, effective_bins
from cosserat.errors import InputError
from cosserat.studies.validate.fits import bin_correlation, fit_run
from cosserat.studies.validate.report import parameters_text
from cosserat.studies.validate.verdicts import CurveTest

V2 = Path(__file__).resolve().parents[1] / "data" / "dem_v2"


# --------------------------------------------------------------------------- the Jacobian
class _Cliff:
    """Residuals r_i = x_i (a - 1) + (b - 0.3)^2 on a search range [0, 1]^2, with no solution
    (the engine's penalty residuals) for b < 0.3: the optimum b = 0.3 sits on the edge."""

    x = np.linspace(0.0, 1.0, 6)

    def bounds(self):
        return np.zeros(2), np.ones(2)

    def residuals(self, theta):
        a, b = theta
        if b < 0.3:
            return np.full(self.x.size, NO_SOLUTION_RESIDUAL)
        return self.x * (a - 1.0) + (b - 0.3) ** 2


def test_the_jacobian_does_not_difference_through_a_region_without_solution():
    s = _Cliff()
    theta = np.array([0.5, 0.3])
    J, edges = jacobian_with_edges(s, theta)
    assert edges == ((1, "lower"),)
    # a: central difference, exact for a linear residual
    np.testing.assert_allclose(J[:, 0], s.x, rtol=0, atol=1e-9)
    # b: one-sided from above, d/db (b - 0.3)^2 = h at the step h = 1e-4: not 1e3 / (2h) = 5e6
    np.testing.assert_allclose(J[:, 1], 1e-4, rtol=1e-6)
    np.testing.assert_array_equal(jacobian(s, theta), J)


def test_no_solution_on_both_sides_gives_a_zero_column():
    class Island(_Cliff):
        def residuals(self, theta):
            if abs(theta[1] - 0.3) > 1e-9:
                return np.full(self.x.size, NO_SOLUTION_RESIDUAL)
            return self.x * (theta[0] - 1.0)

    J, edges = jacobian_with_edges(Island(), np.array([0.5, 0.3]))
    assert edges == ((1, "upper"), (1, "lower"))
    assert not np.any(J[:, 1])


@pytest.fixture(scope="module")
def v2_rough(tmp_path_factory):
    """The v2 rough-wall run as a corpus run (profile.csv and .json copied to <run>.csv)."""
    folder = tmp_path_factory.mktemp("v2")
    for ext in ("csv", "json"):
        shutil.copy(V2 / "plane_rough_H10_qs" / f"profile.{ext}", folder / f"rough.{ext}")
    return read_run(folder / "rough.csv")


def test_ngf_b_on_the_v2_rough_run_is_reported_as_not_identified(v2_rough):
    """The v2 report gave b = 1.503e-4 +- 1.7e-10: the model has no solution a step below
    (the fit pushes b onto that edge) and the Jacobian differenced through the penalty. Now b
    has no error and says why; A keeps one from the identified direction."""
    fits = fit_run(v2_rough, ["ngf"], 3, None)
    f = fits.ranking.fits[0]
    b = f.parameters["b"]
    assert b.stderr is None
    assert b.reason.startswith("at the edge of the region where the model has a solution")
    assert "not identified by the data" in b.reason
    assert f.parameters["A"].stderr is not None and f.parameters["A"].stderr > 1e-3
    (s,) = fits.summaries
    assert "b" in s.unidentified and "b" not in {k for k, (_, e) in s.parameters.items() if e}
    assert any("b = 0.0001503 is at the edge of the region" in w for w in s.warnings)
    assert parameters_text(s).startswith("A = 0.")
    assert parameters_text(s).endswith("; b = 0.0001503 (not identified)")


# --------------------------------------------------------------------------- correlated bins
def _run(folder: Path, meta_rho=None, seed=0):
    gap = 20.0
    y = np.arange(int(gap)) + 0.5
    rng = np.random.default_rng(seed)
    se = np.full(y.size, 0.01)
    u = np.exp(-(gap - y) / 3.0) + rng.normal(0.0, 0.01, y.size)
    meta = {"cell": "plane", "gap_d": gap, "B": 1.0, "wall": {"kind": "glued-grains"}}
    if meta_rho is not None:
        meta["bin_correlation"] = {"u": meta_rho, "omega": 0.1}
    return read_run(write_run(folder, f"run{seed}", meta, {"y": y, "u": u, "u_se": se}))


@pytest.mark.parametrize(
    ("given", "rho", "source"),
    [(0.6, 0.6, "metadata"), (-0.2, 0.0, "metadata -0.2, clipped"),
     (0.99, 0.95, "metadata 0.99, clipped")],
)  # fmt: skip
def test_the_bin_correlation_is_the_sidecars(tmp_path, given, rho, source):
    c = bin_correlation(_run(tmp_path, given))
    assert (c.rho, c.source) == (rho, source)


def test_without_the_sidecars_it_is_estimated_as_calibrate_does(tmp_path):
    from cosserat.calibration.noise import estimate_rho

    run = _run(tmp_path)
    m = run.measured()
    order = np.argsort(m.distance_d)
    assert bin_correlation(run) == estimate_rho(m.u_over_uw[order], m.u_err[order])


def test_fits_use_the_ar1_covariance_and_report_rho_and_effective_bins(tmp_path):
    """chi^2 of the fit is the generalised r^T C^-1 r with C_ij = se_i se_j rho^|i-j| (the
    engine's whitening is exact for AR(1)); the report line gives rho and n (1-rho)/(1+rho)
    effective bins, and the Akaike weights with and without the correlation."""
    run = _run(tmp_path, 0.6)
    fits = fit_run(run, ["cosserat", "mui"], 0, None, independent_bins=True)
    assert fits.correlation.rho == 0.6
    for f in fits.ranking.fits:
        s_, opt = f.internal
        data = s_.runs[0].fields["u"]
        r = s_.predict(opt.theta)[s_.runs[0].name]["u"] - data.value
        C = covariance(data.se, 0.6)
        assert f.chi2 == pytest.approx(float(r @ np.linalg.solve(C, r)), rel=1e-9)
        summary = fits.summary(f.model)
        assert summary.rho == 0.6 and summary.n_bins == 20
        assert summary.effective_bins == pytest.approx(20 * 0.4 / 1.6)
    assert effective_bins(20, 0.6) == 5.0
    (note,) = fits.weight_notes()
    assert note.startswith(
        "Akaike weights with the bins' correlation (rho = 0.60, metadata; 5.0 effective bins "
        "of 20): "
    )
    assert "; with independent bins (rho = 0, each model fitted again): " in note
    assert set(fits.independent_weights) == {"cosserat", "mui"}
    assert sum(fits.independent_weights.values()) == pytest.approx(1.0)
    record = fits.to_dict()
    assert record["bin_correlation"] == {"rho": 0.6, "source": "metadata", "effective_bins": 5.0}
    assert record["akaike_weights_independent_bins"] == fits.independent_weights


def test_independent_bins_say_nothing_more(tmp_path):
    fits = fit_run(_run(tmp_path, 0.0), ["cosserat"], 0, None, independent_bins=True)
    assert fits.correlation.rho == 0.0
    assert fits.weight_notes() == [] and fits.independent_weights == {}


def test_the_independent_bin_refit_is_asked_for(tmp_path):
    """validate fits each run once, with the bins' correlation; the second fit with
    independent bins (it doubles to triples the cost) only with ``independent_bins``."""
    fits = fit_run(_run(tmp_path, 0.6), ["cosserat", "mui"], 0, None)
    assert fits.correlation.rho == 0.6
    assert fits.weight_notes() == [] and fits.independent_weights == {}


# --------------------------------------------------------------------------- numbers
def test_a_delta_test_far_in_the_tail_prints_z_and_chi2_per_dof():
    from scipy import stats

    t = CurveTest("cosserat", 4, 412.0, 1e-80, 1.3, 8.0, 0.046)
    z = stats.norm.isf(stats.chi2.sf(412.0, 4))  # 19.8
    assert t.text() == (
        f"cosserat: chi^2 = 412 for 4 dof (z = {z:.1f}, chi^2/dof = 412/4); times 1.3: "
        "chi^2 = 8 for 3 dof (p = 0.046)"
    )
    assert "e-" not in t.text()
    assert math.isclose(t.p_shape, 0.046)


# --------------------------------------------------------------------------- blocks
def _ar1(phi: float, n: int, seed: int = 0) -> np.ndarray:
    rng = np.random.default_rng(seed)
    e = rng.normal(size=n)
    x = np.empty(n)
    x[0] = e[0] / math.sqrt(1.0 - phi * phi)
    for i in range(1, n):
        x[i] = phi * x[i - 1] + e[i]
    return x


def test_the_autocorrelation_time_of_ar1_series_is_its_closed_form():
    """tau = (1 + phi)/(1 - phi) for AR(1): 1 for white noise, 9 for phi = 0.8."""
    from cosserat.dem.checks import autocorrelation_time

    tau, reliable = autocorrelation_time(_ar1(0.0, 40000))
    assert reliable and tau == pytest.approx(1.0, abs=0.05)
    tau, reliable = autocorrelation_time(_ar1(0.8, 40000, seed=1))
    assert reliable and tau == pytest.approx(9.0, rel=0.1)
    assert autocorrelation_time(np.ones(100)) is None
    assert autocorrelation_time(np.full(100, 0.1) * (1.0 + 1e-16 * _ar1(0.0, 100))) is None
    assert autocorrelation_time(np.arange(10.0)) is None


def test_blocks_shorter_than_two_autocorrelation_times_are_flagged():
    from cosserat.dem.checks import block_autocorrelation, block_length_text

    x = _ar1(0.8, 40000, seed=2)  # tau about 9 samples
    long = block_autocorrelation({"mean_velocity": x}, 0, 10, 1000)
    v = long["observables"]["mean_velocity"]
    assert long["block_samples"] == 4000 and long["block_steps"] == 4_000_000
    assert v["tau_steps"] == round(v["tau_samples"] * 1000)
    assert v["blocks_per_tau"] == pytest.approx(4000 / v["tau_samples"], rel=1e-3)
    assert not v["short"] and not long["short"]
    # 4000 blocks of 10 samples: shorter than 2 tau
    short = block_autocorrelation({"mean_velocity": x}, 0, 4000, 1000)
    assert short["short"] and short["observables"]["mean_velocity"]["short"]
    text = block_length_text(short)
    assert text.startswith("blocks of 10,000 steps against the integrated autocorrelation time")
    assert " SHORT" in text and text.endswith("their standard errors are too small")
    assert block_length_text(long).endswith("at least 2 autocorrelation times long")
    with pytest.raises(InputError, match=r"^blocks and steps between samples must be >= 1"):
        block_autocorrelation({"x": x}, 0, 0, 1000)


def test_a_stored_run_without_the_record_says_what_it_lacks(v2_rough, tmp_path):
    """A run analysed before cosserat.dem recorded the block autocorrelation (the v2 rough
    run's sidecar without the record it now carries) says what it lacks; the stored run,
    analysed again from its dumps, gives its blocks against the times."""
    import json

    from cosserat.studies.validate.report import block_notes

    meta = json.loads((V2 / "plane_rough_H10_qs" / "profile.json").read_text())
    assert "block_autocorrelation" in meta and "block_autocorrelation" in v2_rough.meta
    del meta["block_autocorrelation"]
    shutil.copy(V2 / "plane_rough_H10_qs" / "profile.csv", tmp_path / "old.csv")
    (tmp_path / "old.json").write_text(json.dumps(meta))
    old = read_run(tmp_path / "old.csv")
    (note,) = block_notes(old)
    assert note == (
        "block length against the autocorrelation time: not recorded (blocks of 1,100,000 "
        "steps); the run was analysed before cosserat.dem recorded it, and its per-sample "
        "series are not kept with the profile, so it needs the run's dumps analysed again"
    )
    assert not any("block_autocorrelation" in n for n in old.notes)  # a key it knows
    (stored,) = block_notes(v2_rough)
    assert "not recorded" not in stored


# --------------------------------------------------------------------------- the figure
def test_the_spin_model_figure_keeps_markers_in_their_rows_and_shows_the_status():
    import matplotlib

    matplotlib.use("Agg")
    from cosserat.viz.validation import spin_model_figure

    rows = [
        {"label": "a: moving", "first": -0.15, "se": 0.02,
         "predicted": {"cosserat": 0.19, "mui": 0.0, "ngf": 0.0},
         "status": {"cosserat": "ps", "mui": "pbs", "ngf": ""},
         "usable": {"cosserat": False, "mui": False, "ngf": True}},
        {"label": "b: moving", "first": -0.18, "se": 0.02,
         "predicted": {"cosserat": 0.13, "mui": 0.0, "ngf": 0.0},
         "status": {}, "usable": {}},
    ]  # fmt: skip
    fig = spin_model_figure(rows, ["cosserat", "mui", "ngf"], ["mui", "ngf"], "t")
    ax = fig.axes[0]
    centres = {"a: moving": 1.0, "b: moving": 0.0}
    assert [t.get_text() for t in ax.get_yticklabels()] == ["a: moving", "b: moving"]
    markers = [ln for ln in ax.get_lines() if ln.get_marker() not in ("None", None, "")]
    assert markers
    for ln in markers:
        for y in np.atleast_1d(ln.get_ydata()):
            assert min(abs(y - c) for c in centres.values()) <= 0.36 + 1e-9
    crosses = [ln for ln in markers if ln.get_marker() == "x"]
    assert len(crosses) == 4 and all(float(ln.get_xdata()[0]) == 0.0 for ln in crosses)
    diamonds = [ln for ln in markers if ln.get_marker() == "d"]
    assert diamonds[0].get_markerfacecolor() in ("white", (1.0, 1.0, 1.0, 1.0))
    texts = [t.get_text() for t in ax.get_legend().get_texts()]
    assert "mui: no grain spin of its own, predicts 0" in texts
    assert "ngf: no grain spin of its own, predicts 0" in texts
    assert "open: that fit cannot predict" in texts
    assert {"p: parameters pinned at their defaults",
            "s: its stress ratio contradicts the measured one"} <= set(texts)  # fmt: skip
    assert sorted(a.get_text() for a in ax.texts) == ["pbs", "ps"]
