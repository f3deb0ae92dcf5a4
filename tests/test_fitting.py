"""Compare and fit: recovery of known parameters within their uncertainties over many seeds,
honest failure on data from another law, identifiability warnings, the command line.

A fit is a calibration of one run (``cosserat.calibration.single``): the numbers are checked
against the previous engine's where it was right."""

from __future__ import annotations

import json

import numpy as np
import pytest

from cosserat import (
    NGF,
    Cosserat,
    Couette,
    Material,
    MuI,
    Plane,
    Problem,
    Wall,
)
from cosserat.analysis.fitting import compare, model_at, model_profile
from cosserat.analysis.measurements import MeasuredProfile, write_profile
from cosserat.calibration.single import CellMismatchWarning, fit, fit_model
from cosserat.cli import main

MAT = Material(28.5)
TRUE = {"delta": 20.0, "K": 0.5}
SIGMA = 0.01
D = np.linspace(0.0, 40.0, 25)


def plane(delta=TRUE["delta"], K=TRUE["K"]):
    # gravity-free layer at the upper wall: the closed form makes many fits cheap
    return Problem(
        Plane(eps=0.02), Cosserat(material=MAT, wall=Wall(delta, K), lower=Wall.fully_rough())
    )


def synthetic(seed, problem=None, distance=D, method="closed-form"):
    clean = model_at(model_profile(problem or plane(), method), distance)
    noise = SIGMA * np.random.default_rng(seed).standard_normal(distance.size)
    return MeasuredProfile(distance, clean + noise, np.full(distance.size, SIGMA))


def test_compare_is_exact_on_noise_free_model_data():
    meas = synthetic(0)
    exact = MeasuredProfile(
        meas.distance_d, model_at(model_profile(plane(), "closed-form"), D), meas.u_err
    )
    cmp = compare(plane(), exact, method="closed-form")
    assert cmp.rms < 1e-14 and cmp.chi2 < 1e-20


@pytest.mark.slow
def test_recovery_coverage_over_many_seeds():
    """68% nominal: the true value lies within one standard error in about 68% of fits."""
    n = 120
    inside = {"delta": 0, "K": 0, "delta_interval": 0}
    pulls = []
    for seed in range(n):
        res = fit(synthetic(seed), plane(15.0, 1.0), free=("delta", "K"), method="closed-form")
        for name in ("delta", "K"):
            p = res.parameters[name]
            inside[name] += abs(p.value - TRUE[name]) <= p.stderr
        lo, hi = res.parameters["delta"].interval
        inside["delta_interval"] += lo <= TRUE["delta"] <= hi
        pulls.append(
            (res.parameters["delta"].value - TRUE["delta"]) / res.parameters["delta"].stderr
        )
    coverage = {k: v / n for k, v in inside.items()}
    # binomial 99% band around 0.683 for n = 120: +- 0.11
    for name, c in coverage.items():
        assert 0.57 <= c <= 0.79, (name, coverage)
    assert abs(np.mean(pulls)) < 0.35 and 0.75 < np.std(pulls) < 1.3


def test_data_from_another_law_is_reported_as_a_poor_fit():
    rng = np.random.default_rng(7)
    gauss = np.exp(-((D / 8.0) ** 2)) + SIGMA * rng.standard_normal(D.size)
    res = fit(
        MeasuredProfile(D, gauss, np.full(D.size, SIGMA)), plane(15.0, 1.0), method="closed-form"
    )
    assert res.reduced_chi2 > 10
    assert res.p_value < 1e-100
    assert any(w.startswith("cosserat: misfit: chi^2 = ") for w in res.warnings)
    assert any("runs test" in w and "systematic misfit" in w for w in res.warnings)


def test_K_without_points_near_the_wall_is_flagged():
    far = np.linspace(5.0, 40.0, 20)
    res = fit(synthetic(3, distance=far), plane(15.0, 1.0), method="closed-form")
    assert any("no point within 2 grain diameters" in w for w in res.warnings)


def test_couette_fit_recovers_delta_and_K_within_uncertainties():
    truth = Problem(Couette(eps=0.05, Ri=2.0), Cosserat(material=MAT, wall=Wall(23.0, 0.3)))
    distance = np.geomspace(0.25, 15.0, 30)
    meas = synthetic(11, truth, distance, method="numerical")
    res = fit(
        meas,
        Problem(Couette(eps=0.05, Ri=2.0), Cosserat(material=MAT, wall=Wall(20.0, 1.0))),
        interval_for=(),
    )
    for name, true in (("delta", 23.0), ("K", 0.3)):
        p = res.parameters[name]
        assert abs(p.value - true) < 3 * p.stderr, (name, p)
    assert 0.3 < res.reduced_chi2 < 2.0
    # the calibration's 4k + 4 Latin-hypercube starts, two local searches, the Jacobian
    assert res.n_solves < 120


def test_fit_cli_json_contract(tmp_path, capsys):
    meas = synthetic(5)
    meas = MeasuredProfile(
        meas.distance_d,
        meas.u_over_uw,
        meas.u_err,
        {"geometry": "plane", "eps": 0.02, "synthetic": "true"},
    )
    path = write_profile(meas, tmp_path / "d.csv")
    code = main(
        [
            "fit",
            str(path),
            "--free",
            "delta,K",
            "--delta",
            "15",
            "--K",
            "1",
            "--delta-lower",
            "fully-rough",
            "--method",
            "closed-form",
            "--format",
            "json",
        ]
    )
    out = capsys.readouterr().out
    assert code == 0
    record = json.loads(out)
    assert set(record) >= {"parameters", "rms", "n_points", "n_solves", "warnings"}
    # the calibration's contract (docs/calibration.md) for one model on one run
    assert set(record) >= {"model", "status", "chi2", "dof", "p_value", "aic", "bic", "per_run"}
    delta = record["parameters"]["delta"]
    assert set(delta) >= {"value", "stderr", "interval", "reason", "free", "shared", "unit"}
    assert delta["reason"] is None and delta["unit"] == "deg" and delta["free"]
    assert abs(delta["value"] - 20.0) < 4 * delta["stderr"]
    assert delta["interval"][0] < delta["value"] < delta["interval"][1]
    assert record["n_points"] == 25
    # --plot writes the figure and prints one line
    code = main(
        [
            "fit",
            str(path),
            "--delta",
            "15",
            "--delta-lower",
            "fully-rough",
            "--method",
            "closed-form",
            "--plot",
            str(tmp_path / "fit.png"),
        ]
    )
    out = capsys.readouterr().out
    assert code == 0 and len(out.strip().splitlines()) == 1
    assert (tmp_path / "fit.png").stat().st_size > 0


def test_compare_cli_with_a_preset(tmp_path, capsys):
    from cosserat.studies.experiments import PRESETS

    truth = PRESETS["glass"].problem(delta=23.0)
    meas = synthetic(2, truth, np.linspace(0.5, 10, 12), method="numerical")
    path = write_profile(meas, tmp_path / "glass.csv")
    assert (
        main(["compare", str(path), "--preset", "glass", "--delta", "23", "--format", "json"]) == 0
    )
    record = json.loads(capsys.readouterr().out)
    assert record["rms"] < 3 * SIGMA and record["n_points"] == 12


@pytest.mark.parametrize(
    ("args", "needle"),
    [
        (["--free", "delta,zeta"], "free parameters must be among"),
        ([], "give --geometry"),
    ],
)
def test_fit_cli_errors(tmp_path, capsys, args, needle):
    path = tmp_path / "d.csv"
    path.write_text("distance_d,u_over_uw\n0,1\n1,0.5\n2,0.2\n3,0.1\n")
    extra = [] if "give --geometry" in needle else ["--geometry", "plane", "--eps", "0.05"]
    code = main(["fit", str(path), *extra, *args])
    err = capsys.readouterr().err
    assert code == 2 and needle in err and len(err.strip().splitlines()) == 1


# --------------------------------------------------------------------------- identifiability
def test_parameters_that_trade_off_exactly_are_named_with_no_uncertainty():
    """Gravity-free plane shear: the profile depends on delta and L only through a combination
    (the fit moves along it freely), and not at all on A: the calibration's one rule (a
    direction whose 1-sigma exceeds half the search range) names both."""
    res = fit(synthetic(4), plane(15.0, 1.0), free=("delta", "K", "L", "A"), method="closed-form")
    flat = [w for w in res.warnings if "the data do not determine" in w]
    assert len(flat) == 2, res.warnings
    (a_only,) = [w for w in flat if " A " in w]
    assert "roughness" not in a_only and "L" not in a_only
    (trade,) = [w for w in flat if w is not a_only]
    assert "roughness" in trade and "L" in trade and "of the search range" in trade
    for name in ("delta", "roughness", "L", "A"):
        par = res.parameters[name]
        assert par.stderr is None and par.reason.startswith("not identified by the data")
    assert res.parameters["K"].stderr is not None and np.isfinite(res.parameters["K"].stderr)
    record = json.loads(json.dumps(res.to_dict(), allow_nan=False))  # no NaN anywhere
    assert record["parameters"]["L"]["stderr"] is None
    assert len(record["unidentified"]) == 2


def test_a_strong_correlation_names_the_partner_and_the_value():
    # 10 points between 5 and 20 grain diameters from a slipping wall: delta and K both act
    # through the slip, which the data see only through the layer's level
    problem = plane(15.0, 1.0)
    far = np.linspace(5.0, 20.0, 10)
    res = fit(synthetic(3, problem=problem, distance=far), problem, method="closed-form")
    assert res.covariance_names == ("roughness", "K")
    corr = res.correlation[0, 1]
    assert abs(corr) > 0.95
    (strong,) = [w for w in res.warnings if "strongly correlated" in w]
    assert f"r = {corr:+.3f}" in strong and "roughness and K" in strong
    # the previous engine's optimum (chi^2 24.21557 at delta = 14.25665, K at its bound 0)
    assert res.chi2 == pytest.approx(24.215572, rel=1e-6)
    assert res.parameters["delta"].value == pytest.approx(14.25665, abs=1e-4)
    assert res.parameters["K"].at_bound == "lower" and res.parameters["K"].stderr is None
    assert any("no point within 2 grain diameters" in w for w in res.warnings)
    # the near-wall data of the other tests separate them: no such warning there
    res = fit(synthetic(3, problem=problem), problem, method="closed-form")
    assert abs(res.correlation[0, 1]) < 0.95
    assert not [w for w in res.warnings if "strongly correlated" in w]


def test_well_posed_uncertainties_agree_with_a_parametric_bootstrap():
    """The Jacobian standard errors against the scatter of refits of independent noise."""
    n = 60
    fits = [
        fit(synthetic(100 + s), plane(15.0, 1.0), method="closed-form", interval_for=())
        for s in range(n)
    ]
    for name in ("delta", "K"):
        values = np.array([f.parameters[name].value for f in fits])
        stderr = np.array([f.parameters[name].stderr for f in fits])
        assert all(f.parameters[name].stderr is not None for f in fits)
        # the sample std of 60 draws is within +-25% of the truth with probability > 99%
        assert np.std(values, ddof=1) == pytest.approx(np.median(stderr), rel=0.25), name


def test_fit_progress_reports_improvements_and_a_closing_message():
    seen: list[str] = []
    res = fit(
        synthetic(9),
        plane(15.0, 1.0),
        free=("delta", "K", "L", "phi", "A"),
        method="closed-form",
        progress=seen.append,
    )
    assert seen[0] == "fitting delta, K, L, phi, A to 25 points"
    better = [m for m in seen[1:-1] if "chi-square" in m and " solves, " in m]
    assert better and "delta = " in better[0]
    chi2 = [float(m.split("chi-square ")[1].split(" at")[0]) for m in better]
    assert chi2 == sorted(chi2, reverse=True)  # improvements only
    assert any(m.startswith("profile likelihood for delta") for m in seen[1:-1])
    assert seen[-1].startswith(f"done after {res.n_solves} solves")
    assert "warning(s)" in seen[-1]


def test_fit_cli_text_with_unidentifiable_parameters(tmp_path, capsys):
    meas = synthetic(6)
    meas = MeasuredProfile(
        meas.distance_d, meas.u_over_uw, meas.u_err, {"geometry": "plane", "eps": 0.02}
    )
    path = write_profile(meas, tmp_path / "d.csv")
    code = main(
        [
            "fit",
            str(path),
            "--free",
            "delta,K,A",
            "--delta",
            "15",
            "--K",
            "1",
            "--delta-lower",
            "fully-rough",
            "--method",
            "closed-form",
        ]
    )
    out = capsys.readouterr().out
    assert code == 0
    assert "nan" not in out.lower()
    assert "warning: cosserat: the data do not determine +1.00 A" in out
    assert "\n  A = " in out and "(no uncertainty: " in out and "\n  delta = " in out


def test_the_moving_wall_is_read_from_the_cell_for_every_rheology():
    """Couette flow is driven by the inner cylinder whatever the rheology (mu(I) and NGF too)."""
    from cosserat.analysis.fitting import moving_wall
    from cosserat.errors import MethodNotAvailableError

    assert moving_wall(Problem(Couette(eps=0.01, Ri=1.0), MuI())) == (0.0, -1.0)
    assert moving_wall(Problem(Couette(eps=0.01, Ri=1.0), NGF())) == (0.0, -1.0)
    assert moving_wall(Problem(Plane(eps=0.01), MuI())) == (1.0, 1.0)

    class Still:
        def wall_velocity(self, xi):
            return 0.0

    with pytest.raises(MethodNotAvailableError, match="no wall moves"):
        moving_wall(Still())


# --------------------------------------------------------------------------- one engine
def test_the_data_cell_wins_over_the_problem_with_a_warning():
    """A file of eps 0.05, Ri 2 fitted from a problem of eps 0.02, Ri 5: the header's cell is
    used (the previous engine kept the problem's and found delta = 14.5 instead of 23)."""
    truth = Problem(Couette(eps=0.05, Ri=2.0), Cosserat(material=MAT, wall=Wall(23.0, 0.3)))
    distance = np.geomspace(0.25, 15.0, 30)
    clean = synthetic(11, truth, distance, method="numerical")
    meas = MeasuredProfile(
        clean.distance_d,
        clean.u_over_uw,
        clean.u_err,
        {"geometry": "couette", "eps": 0.05, "ri": 2.0},
    )
    start = Problem(Couette(eps=0.02, Ri=5.0), Cosserat(material=MAT, wall=Wall(20.0, 1.0)))
    with pytest.warns(CellMismatchWarning) as caught:
        res = fit(meas, start, interval_for=())
    said = [str(w.message) for w in caught]
    assert any("eps = 0.05; the problem given has eps = 0.02" in m for m in said)
    assert any("Ri = 2; the problem given has Ri = 5" in m for m in said)
    assert all(any(m in w for w in res.warnings) for m in said)
    assert res.problem.eps == 0.05 and res.problem.cell.Ri == 2.0
    delta = res.parameters["delta"]
    assert abs(delta.value - 23.0) < 3 * delta.stderr
    # a plane problem against a Couette file: the file's cell
    with pytest.warns(CellMismatchWarning, match="geometry couette"):
        res = fit(meas, plane(20.0, 1.0), interval_for=())
    assert res.cell == "couette" and res.problem.cell.Ri == 2.0


def test_without_errors_the_fit_is_the_previous_engines():
    """No u_err: unit weights, errors scaled by the residual variance. The previous engine
    (eigh rule, forward differences) gave delta = 20.09015 +- 0.094594 [19.99559, 20.18372]
    and K = 0.641678 +- 0.101053 on these data."""
    meas = synthetic(5)
    res = fit(MeasuredProfile(meas.distance_d, meas.u_over_uw, None), plane(15.0, 1.0),
              method="closed-form")  # fmt: skip
    assert not res.absolute_sigma and res.p_value is None
    delta, K = res.parameters["delta"], res.parameters["K"]
    assert delta.value == pytest.approx(20.09015, abs=1e-4)
    assert K.value == pytest.approx(0.641678, abs=1e-5)
    assert delta.stderr == pytest.approx(0.094594, rel=1e-3)
    assert K.stderr == pytest.approx(0.101053, rel=1e-3)
    assert delta.interval == pytest.approx((19.99559, 20.18372), abs=2e-3)
    assert res.reduced_chi2 == pytest.approx(res.rss / 23, rel=1e-12)
    # AIC with sigma at its maximum-likelihood value: n ln(RSS/n) + 2k + n (1 + ln 2 pi)
    n = 25
    aic = n * np.log(res.rss / n) + 4 + n * (1 + np.log(2 * np.pi))
    assert res.aic == pytest.approx(aic, rel=1e-10)


def test_fit_and_fit_models_report_the_same_errors(tmp_path):
    """One engine: ``fit`` and ``fit --models cosserat`` give the same Cosserat fit, values and
    standard errors alike (through the command line, in subprocesses)."""
    import subprocess
    import sys

    truth = Problem(Couette(eps=0.05, Ri=2.0), Cosserat(material=MAT, wall=Wall(23.0, 0.3)))
    meas = synthetic(12, truth, np.geomspace(0.25, 15.0, 30), method="numerical")
    meas = MeasuredProfile(meas.distance_d, meas.u_over_uw, meas.u_err,
                           {"geometry": "couette", "eps": 0.05, "ri": 2.0})  # fmt: skip
    path = write_profile(meas, tmp_path / "c.csv")

    def run(*extra):
        out = subprocess.run(
            [sys.executable, "-m", "cosserat", "fit", str(path), "--format", "json", *extra],
            capture_output=True, text=True, check=True,
        )  # fmt: skip
        return json.loads(out.stdout)

    single = run()["parameters"]
    (ranked,) = run("--models", "cosserat")["fits"]
    for name in ("delta", "K"):
        assert ranked["parameters"][name]["value"] == pytest.approx(single[name]["value"], rel=1e-9)
        assert ranked["parameters"][name]["stderr"] == pytest.approx(
            single[name]["stderr"], rel=1e-9
        )
    # and in Python: the same result type and numbers
    py = fit_model(meas, Problem(Couette(eps=0.05, Ri=2.0), Cosserat(material=MAT)))
    assert py.parameters["K"].stderr == pytest.approx(single["K"]["stderr"], rel=1e-9)
    assert py.to_dataframe().set_index("parameter").loc["K", "stderr"] == py.parameters["K"].stderr


def test_the_old_names_are_deprecated_aliases():
    import cosserat.analysis.fitting as fitting
    import cosserat.analysis.ranking as ranking
    from cosserat.calibration import single

    with pytest.warns(DeprecationWarning, match="cosserat.calibration.single.fit"):
        assert fitting.fit is single.fit
    with pytest.warns(DeprecationWarning, match="calibration.single.rank_models"):
        assert ranking.rank_models is single.rank_models
    with pytest.warns(DeprecationWarning, match="calibration.single.Ranking"):
        assert ranking.Ranking is single.Ranking
    with pytest.raises(AttributeError):
        fitting.no_such_name  # noqa: B018


def test_a_corpus_run_fixes_I_w_from_its_wall_speed():
    """validate fits run.measured(): its header carries the I_w the wall speed gives, the same
    as the joint calibration's, and mu(I) is fitted at it (never fitting I_w)."""
    from cosserat.analysis.corpus import read_corpus, shipped_corpus
    from cosserat.calibration.data import from_run
    from cosserat.calibration.single import rank_models

    corpus = shipped_corpus()
    corpus = corpus if hasattr(corpus, "runs") else read_corpus(corpus)
    run = next(r for r in corpus.runs if r.cell == "couette")
    measured = run.measured()
    assert measured.meta["i_w"] == pytest.approx(from_run(run).I_w, rel=1e-15)
    (mui,) = rank_models(measured, run.cell_parameters(), ["mui"]).fits
    assert mui.ok and mui.problem.cell_values()["I_w"] == pytest.approx(measured.meta["i_w"])
    assert "I_w" not in mui.shown() and not any("I_w" in w for w in mui.warnings)
    assert not any("fixed at the problem's value" in a for a in mui.assumptions)
