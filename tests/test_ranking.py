"""Ranking the registered rheologies against a measured profile, and Delta against the gap."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from cosserat.analysis.gap import power_law_slope, thickness_vs_gap
from cosserat.analysis.measurements import MeasuredProfile
from cosserat.analysis.ranking import (
    get_parameter,
    information_criteria,
    model_solve,
    model_velocity,
    set_parameters,
)
from cosserat.calibration.single import fit_model, rank_models
from cosserat.errors import MethodNotAvailableError, ParameterError
from cosserat.model import make_problem
from cosserat.routes import RHEOLOGIES, cells_for
from cosserat.routes.laws import asymptotic_thickness, thickness_limit

COUETTE = {"geometry": "couette", "eps": 0.025, "Ri": 2.0}
"""A Couette cell of 40 grain diameters on which the three models' profiles differ."""
TRUTH = {"cosserat": {"delta": 22.0, "K": 0.5}, "mui": {"I_w": 0.05}, "ngf": {"I_w": 0.01}}
NOISE = 0.003


def synthetic(model: str, seed: int, cell: dict = COUETTE) -> tuple[MeasuredProfile, object]:
    """The model's velocity at the centres of one-grain bins, plus Gaussian noise; the header
    states the wall's inertial number where the model has one (what the wall speed fixes)."""
    params = {k: v for k, v in cell.items() if k != "geometry"}
    problem = make_problem(model, cell["geometry"], {**params, **TRUTH.get(model, {})})
    d = np.arange(0.5, 1.0 / cell["eps"], 1.0)
    u = model_velocity(model_solve(problem, points=201), d)
    rng = np.random.default_rng(seed)
    meta = {"i_w": TRUTH[model]["I_w"]} if "I_w" in TRUTH.get(model, {}) else {}
    noisy = u + rng.normal(0.0, NOISE, d.size)
    return MeasuredProfile(d, noisy, np.full(d.size, NOISE), meta), problem


def test_information_criteria_by_hand():
    r = np.array([1.0, 2.0, -1.0])  # chi^2 = RSS = 6, n = 3
    chi2, aic, bic = information_criteria(r, 1, absolute_sigma=True)
    assert (chi2, aic) == (6.0, 8.0) and bic == pytest.approx(6.0 + math.log(3.0), rel=1e-15)
    rss, aic, bic = information_criteria(r, 2, absolute_sigma=False)
    assert rss == 6.0
    assert aic == pytest.approx(3.0 * math.log(2.0) + 4.0, rel=1e-15)
    assert bic == pytest.approx(3.0 * math.log(2.0) + 2.0 * math.log(3.0), rel=1e-15)
    assert information_criteria(np.zeros(4), 1, absolute_sigma=False)[1:] == (None, None)


def test_ranking_table_recomputes_from_its_residuals():
    measured, _ = synthetic("cosserat", 1)
    ranking = rank_models(measured, COUETTE, models=["cosserat"])
    fit = ranking.fits[0]
    chi2 = float(np.sum((fit.comparison.residuals / NOISE) ** 2))
    assert fit.chi2 == pytest.approx(chi2, rel=1e-6)
    assert fit.reduced_chi2 == pytest.approx(fit.chi2 / (measured.n - 2), rel=1e-12)
    # the full Gaussian likelihood: chi2 + 2k plus n ln(2 pi sigma^2), the same for every model
    const = measured.n * math.log(2.0 * math.pi * NOISE**2)
    assert fit.aic == pytest.approx(fit.chi2 + 4.0 + const, rel=1e-12)
    assert fit.bic == pytest.approx(fit.chi2 + 2.0 * math.log(measured.n) + const, rel=1e-12)


@pytest.mark.parametrize("model", [m for m in TRUTH if m in RHEOLOGIES])
@pytest.mark.parametrize("seed", [1, 2])
def test_data_from_a_model_rank_that_model_first(model, seed):
    measured, _ = synthetic(model, seed)
    ranking = rank_models(measured, COUETTE)
    assert {f.model for f in ranking.fits} == {m for m in RHEOLOGIES if "couette" in cells_for(m)}
    assert ranking.best is not None and ranking.best.model == model
    assert ranking.by_bic()[0].model == model
    # the true model describes the data within their noise
    assert ranking.best.reduced_chi2 < 2.0
    assert max(ranking.weights(), key=ranking.weights().get) == model


@pytest.mark.parametrize("model", [m for m in TRUTH if m in RHEOLOGIES])
def test_parameters_recovered_within_their_uncertainties(model):
    measured, problem = synthetic(model, 3)
    start = {
        **dict(list(COUETTE.items())[1:]),
        **{k: v for k, v in TRUTH[model].items() if k == "I_w"},
    }
    fit = fit_model(measured, make_problem(model, "couette", start))
    assert fit.shown()
    for name, est in fit.shown().items():
        truth = float(get_parameter(problem, name))
        assert est.stderr is not None and est.stderr > 0.0, (name, est)
        assert abs(est.value - truth) < 3.0 * est.stderr, (name, est, truth)


def test_a_parameter_the_profile_does_not_depend_on_has_no_error_and_says_why():
    # mu(I) plane shear without gravity shears uniformly whatever mu_s and I_w: u = xi
    cell = {"geometry": "plane", "eps": 0.05, "B": 0.0}
    measured, _ = synthetic("mui", 4, cell)
    fit = fit_model(measured, make_problem("mui", "plane", {"eps": 0.05, "I_w": 0.05}))
    assert fit.shown()
    for est in fit.shown().values():
        assert est.stderr is None and "not identified by the data" in est.reason
    assert json.dumps(fit.to_dict())  # None, never NaN


def test_a_parameter_at_its_bound_has_no_error():
    measured, _ = synthetic("mui", 1)
    fit = fit_model(measured, make_problem("cosserat", "couette", {"eps": 0.025, "Ri": 2.0}))
    K = fit.parameters["K"]
    assert K.value == pytest.approx(0.0, abs=1e-9)
    assert K.stderr is None and "at the lower end of its search range" in K.reason


def test_ranking_outputs():
    measured, _ = synthetic("cosserat", 1)
    ranking = rank_models(measured, COUETTE, models=["cosserat", "mui"])
    record = json.loads(json.dumps(ranking.to_dict(), allow_nan=False))
    assert record["best"] == "cosserat" and len(record["fits"]) == 2
    text = ranking.to_text()
    assert "AIC = chi2 + 2k" in text and "delta = 22" in text
    assert ranking.plot().axes


def test_models_not_defined_on_a_cell_are_listed_with_the_reason():
    measured = MeasuredProfile(np.arange(0.5, 10.0), np.linspace(1.0, 0.0, 10), None)
    ranking = rank_models(measured, {"geometry": "channel", "eps": 0.1})
    assert ranking.fits and not any(f.ok for f in ranking.fits)
    # no wall moves in the channel: no velocity over a wall speed to compare
    assert any("no wall moves" in f.message for f in ranking.fits)
    assert "not fitted" in ranking.to_text()


def test_model_problem_and_parameters():
    p = make_problem("cosserat", "plane", {"eps": 0.1, "B": 1.0, "delta": "fully-rough"})
    assert p.rheology.wall.is_fully_rough and p.cell.B == 1.0
    q = set_parameters(p, {"delta": 20.0, "K": 0.3, "phi": 30.0})
    assert get_parameter(q, "delta") == pytest.approx(20.0) and q.rheology.wall.K == 0.3
    m = make_problem("mui", "couette", {"eps": 0.1, "Ri": 1.0, "mu_s": 0.4})
    assert m.rheology.mu_s == 0.4
    with pytest.raises(ParameterError, match="model must be one of cosserat, mui, ngf"):
        make_problem("kinetic-theory", "plane", {"eps": 0.1})
    with pytest.raises(ParameterError, match="cell must be one of 'plane', 'couette'"):
        make_problem("mui", "annulus", {"eps": 0.1})
    with pytest.raises(MethodNotAvailableError, match="kinetic model"):
        make_problem("kinetic", "plane", {"eps": 0.1})
    with pytest.raises(ParameterError, match=r"unknown parameter\(s\) delta"):
        set_parameters(m, {"delta": 20.0})
    with pytest.raises(ParameterError, match="eps"):
        make_problem("mui", "plane", {})


# --------------------------------------------------------------------------- Delta vs gap
def test_power_law_slope_exact_and_weighted():
    g = np.array([10.0, 20.0, 40.0, 80.0])
    s = power_law_slope(g, 3.0 * g ** (1 / 3))
    assert s.slope == pytest.approx(1 / 3, abs=1e-12) and s.prefactor == pytest.approx(3.0)
    assert s.stderr == pytest.approx(0.0, abs=1e-12)
    # weighted, two points: the line through them; error from the two errors by hand
    w = power_law_slope([10.0, 40.0], [2.0, 4.0], [0.2, 0.4])
    assert w.slope == pytest.approx(0.5, rel=1e-12)
    assert w.stderr == pytest.approx(math.sqrt(0.1**2 + 0.1**2) / math.log(4.0), rel=1e-12)
    with pytest.raises(ParameterError):
        power_law_slope([10.0], [1.0])


def test_cosserat_delta_against_gap_tends_to_the_papers_laws():
    gaps = [1e3, 1e4, 1e5]
    study = thickness_vs_gap("plane", ["cosserat"], gaps, cell_parameters={"B": 1.0})
    smooth, rough = study.series
    assert "fully rough" in rough.label
    # smoother wall: Delta -> -ln f / k, independent of the gap (eqn-delta_soln)
    limit = thickness_limit(make_problem("cosserat", "plane", {"eps": 1e-5, "B": 1.0}))
    assert smooth.Delta[-1] == pytest.approx(limit, rel=2e-3)
    assert abs(smooth.slope_large_gap) < 0.01
    # fully rough wall under gravity: Delta ~ (H/d)^(1/3) (eqn-delta_soln_fr)
    assert rough.slope_large_gap == pytest.approx(1 / 3, abs=0.01)
    for g, d in zip(gaps, rough.Delta, strict=True):
        p = make_problem("cosserat", "plane", {"eps": 1 / g, "B": 1.0, "delta": "fully-rough"})
        assert d == pytest.approx(asymptotic_thickness(p), rel=0.05)
    assert "slope" in study.to_text() and json.dumps(study.to_dict(), allow_nan=False)


def test_local_mui_delta_is_proportional_to_the_gap_at_fixed_dimensionless_numbers():
    # the mu(I) profile in xi does not depend on eps, so Delta in grains ~ H/d exactly
    study = thickness_vs_gap("couette", ["mui"], [10.0, 20.0, 40.0])
    s = study.series[0]
    assert s.slope.slope == pytest.approx(1.0, abs=1e-9)
    # ...and with R_i and the wall speed fixed in grain units, Delta does not change
    fixed = thickness_vs_gap("couette", ["mui"], [10.0, 20.0, 40.0],
                             scale_with_gap={"Ri": -1.0, "I_w": -1.0})  # fmt: skip
    d = fixed.series[0].Delta
    assert max(d) - min(d) < 1e-9 * max(d)


def test_gap_study_plot_and_failures():
    study = thickness_vs_gap("plane", ["cosserat"], [10.0, 20.0])
    assert study.series[0].Delta[0] is None and 10.0 in study.series[0].failures
    assert study.plot().axes
    with pytest.raises(ParameterError, match="gaps"):
        thickness_vs_gap("plane", ["cosserat"], [1.0])


def test_models_figure_overlays_every_registered_model():
    from cosserat.paper.figures.models import CELLS, compute_models

    data = compute_models()
    assert len(data.panels) == 3 * len(CELLS)
    for i, cell in enumerate(CELLS):
        models = [m for m in RHEOLOGIES if cell in cells_for(m)]
        labels = [c.label for c in data.panels[2 * i].curves]
        assert [label.split(",")[0] for label in labels] == models
        # only the Cosserat model has a spin of its own
        spin = [c.label for c in data.panels[2 * i + 1].curves]
        assert spin == ["cosserat, fully rough"]
    studies = data.extra["gap_studies"]
    for cell in CELLS:
        by_label = {s["label"]: s for s in studies[cell]["series"]}
        assert (
            by_label["cosserat, delta = 20 deg"]["slope_large_gap"]
            < (by_label["cosserat, fully rough"]["slope_large_gap"])
        )


def test_measured_cell_reads_the_header_and_lets_arguments_override():
    from cosserat.analysis.measurements import read_profile
    from cosserat.analysis.ranking import measured_cell

    m = read_profile("# geometry: couette\n# eps: 0.05\n# Ri: 2\ndistance_d,u_over_uw\n0.5,0.9\n")
    assert measured_cell(m) == {"geometry": "couette", "eps": 0.05, "Ri": 2.0}
    assert measured_cell(m, Ri=None, eps=0.1)["eps"] == 0.1
    with pytest.raises(ParameterError, match="geometry"):
        measured_cell(read_profile("distance_d,u_over_uw\n0.5,0.9\n"), eps=0.1)


@pytest.mark.parametrize("model", ["cosserat", "mui"])
def test_a_fitted_model_compares_as_compare_does(model):
    """SingleFit.comparison is analysis.fitting.compare of the fitted problem: the same model
    curve, residuals (data minus model) and rms, for any rheology."""
    from cosserat.analysis.fitting import compare

    measured, problem = synthetic(model, 5)
    fitted = fit_model(measured, problem)
    mine = fitted.comparison
    theirs = compare(fitted.problem, measured)
    np.testing.assert_allclose(mine.model, theirs.model, rtol=1e-6, atol=1e-9)
    np.testing.assert_allclose(mine.residuals, theirs.residuals, rtol=1e-6, atol=1e-9)
    assert mine.rms == pytest.approx(theirs.rms, rel=1e-5)
    np.testing.assert_allclose(mine.residuals, measured.u_over_uw - mine.model)
