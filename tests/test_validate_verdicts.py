"""The verdict functions of ``validate`` on measured quantities made to be decisive (and too
noisy to decide), the grouping of runs into gap series, and the referee's warnings on fits."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from cosserat.analysis.corpus import read_corpus, read_run, write_run
from cosserat.errors import ParameterError
from cosserat.studies.validate import (
    DeltaPoint,
    DeltaSeries,
    WallSpin,
    delta_law_verdict,
    spin_model_verdict,
    spin_verdict,
    validate,
)
from cosserat.studies.validate.grouping import couette_note, group_runs, wall_label, walls_differ
from cosserat.studies.validate.verdicts import relevant, within_regime

DIST = np.array([0.5, 1.5, 2.5])


def wall(run, departure, se, *, wall="moving", sheared=True, predicted=None):
    """A wall's three near-wall bins with the given departures and standard errors."""
    dep = np.broadcast_to(np.asarray(departure, dtype=float), DIST.shape).copy()
    err = np.broadcast_to(np.asarray(se, dtype=float), DIST.shape).copy()
    pred = {k: np.broadcast_to(np.asarray(v, float), DIST.shape).copy()
            for k, v in (predicted or {}).items()}  # fmt: skip
    return WallSpin(run, wall, sheared, DIST, dep, err, pred)


# --------------------------------------------------------------------------- the spin
def test_a_departing_first_layer_is_supported_and_an_idle_fixed_wall_does_not_dilute_it():
    """Two runs whose first layer departs at 3.9 and 4.2 sigma (the rest at zero), each with
    a fixed wall where nothing shears: tested at the moving wall, the pooled test departs
    (chi^2 = 3.9^2 + 4.2^2 = 32.85 for 6 bins, p ~ 1e-5)."""
    walls = []
    for name, z in (("a", 3.9), ("b", 4.2)):
        walls.append(wall(name, [-0.1 * z, 0.0, 0.0], 0.1))
        walls.append(wall(name, 0.0, 1e-4, wall="fixed", sheared=False))
    v = spin_verdict(walls)
    assert v.verdict == "supported", v.text
    assert v.numbers["pooled_dof"] == 6
    assert v.numbers["pooled_chi2"] == pytest.approx(3.9**2 + 4.2**2)
    assert v.numbers["pooled_p_normal"] == pytest.approx(1.1e-5, rel=0.1)
    assert "not judged (the material does not shear there" in v.evidence
    assert "Method:" in v.evidence and "What would change it" in v.text
    assert v.runs == ("a", "b")


def test_no_departure_where_the_model_predicts_a_visible_one_refutes_the_claim():
    walls = [wall(f"r{i}", [0.001, -0.001, 0.0005], 0.005, predicted={"cosserat": 0.05})
             for i in range(3)]  # fmt: skip
    v = spin_verdict(walls)
    assert v.verdict == "refuted", v.text
    assert v.numbers["p_if_model_departure_were_there"] < 1e-3


def test_a_noisy_spin_cannot_decide_and_says_how_much_better_it_must_be():
    walls = [wall("r", [0.01, 0.0, -0.01], 0.05, predicted={"cosserat": 0.02})]
    v = spin_verdict(walls)
    assert v.verdict == "undecided"
    # the shift the prediction adds is 3 (0.02/0.05)^2 = 0.48; p < 1e-3 at 3 dof needs 13.27
    factor = np.sqrt((16.266 - 3.0) / 0.48)
    assert f"errors smaller by a factor {factor:.2g}" in v.would_change


def test_one_run_of_four_departing_is_mixed():
    walls = [wall("big", [-2.0, -1.0, 0.0], 0.1)] + [wall(f"z{i}", 0.0, 0.1) for i in range(3)]
    assert spin_verdict(walls).verdict == "mixed"


def test_runs_too_noisy_to_show_the_predicted_departure_do_not_make_it_mixed():
    """One run departs; three do not, but the departure the model predicts for them (0.01
    against errors of 0.05: chi^2 shifted by 0.12 on 3 bins, p ~ 0.38) could not have shown:
    they neither support nor contradict the first, so the verdict is not "mixed"."""
    walls = [wall("big", [-2.0, -1.0, 0.0], 0.1, predicted={"cosserat": -1.0})]
    walls += [wall(f"z{i}", 0.0, 0.05, predicted={"cosserat": 0.01}) for i in range(3)]
    v = spin_verdict(walls)
    assert v.verdict == "supported", v.text
    assert v.numbers["runs_too_noisy_to_show_the_model_departure"] == ["z0", "z1", "z2"]
    assert "3 do not and could not have" in v.evidence
    # the same three runs with errors that would have shown it: they contradict the first
    walls = walls[:1] + [wall(f"z{i}", 0.0, 0.002, predicted={"cosserat": 0.01})
                         for i in range(3)]  # fmt: skip
    assert spin_verdict(walls).verdict == "mixed"


def test_no_spin_near_a_sheared_wall_is_undecided():
    assert spin_verdict([]).verdict == "undecided"
    assert spin_verdict([wall("r", 1.0, 0.01, sheared=False)]).verdict == "undecided"


def test_a_model_departing_with_the_opposite_sign_is_refuted_and_said_so():
    """The measured first layer spins faster than half the vorticity (-0.09 +- 0.02, 4.5
    sigma); the model, fitted to the velocity, departs by +0.03: refuted on the sign."""
    walls = [wall(r, [-0.09, -0.02, 0.0], 0.02, predicted={"cosserat": [0.03, 0.01, 0.0],
                                                          "mui": 0.0})
             for r in ("a", "b")]  # fmt: skip
    v = spin_model_verdict(walls)
    assert v.verdict == "refuted"
    # the scope in the verdict field (referee 10, point 1): the u-only fits
    assert v.qualifier == "with the cosserat model fitted to the velocity alone"
    assert "departs with the opposite sign (2 of 2 walls" in v.evidence
    assert "measured -0.09 +- 0.02, cosserat predicts +0.03" in v.evidence
    assert "other models mui +0" in v.evidence


def test_predictions_from_fits_that_contradict_the_measured_stress_decide_nothing():
    """The same opposite-sign walls, but the fits that supply the +0.03 hold sin phi = 0.477
    against a measured band ratio of 0.2 (made-up numbers): undecided, with why, what would
    decide it, and what the data say on those fits kept as numbers."""
    walls = [wall(r, [-0.09, -0.02, 0.0], 0.02, predicted={"cosserat": [0.03, 0.01, 0.0]})
             for r in ("a", "b")]  # fmt: skip
    why = "the cosserat fit: its sin phi = 0.477 contradicts the measured band stress ratio"
    v = spin_model_verdict(walls, unfit={"a": why, "b": why})
    assert (v.verdict, v.qualifier) == ("undecided", ""), v.text
    assert v.evidence.startswith("Undecided: the cosserat fits that supply the predicted "
                                 f"departure cannot be used (a: {why}; b: {why})")  # fmt: skip
    assert "On these fits the data would read 'refuted'" in v.evidence
    assert "joint calibration of the cosserat model on u and omega together, with phi tied to " \
        "the measured band stress ratio" in v.would_change  # fmt: skip
    said = v.numbers["with_contradicting_fits"]
    assert said["verdict"] == "refuted" and said["opposite_sign"] == ["a:moving", "b:moving"]
    assert v.runs == ("a", "b")
    # one run's fit agrees with its stress ratio: the verdict rests on it alone, the other named
    one = spin_model_verdict(walls, unfit={"b": why})
    assert one.verdict == "refuted" and "(1 of 1 walls" in one.evidence
    assert f"Not used (b: {why}): on those fits the data would read 'refuted'." in one.evidence
    assert one.numbers["with_contradicting_fits"]["opposite_sign"] == ["b:moving"]
    # a wall the caller leaves out is named; without unfit runs the verdict is as before
    out = spin_model_verdict(walls, left_out=["c (fixed wall: its kind differs)"])
    assert out.verdict == "refuted"
    assert out.evidence.endswith(" Left out: c (fixed wall: its kind differs).")
    assert spin_model_verdict(walls).verdict == "refuted"


def test_a_slow_flow_claim_is_not_decided_by_runs_outside_the_slow_regime():
    """The same refutation on runs at I = 0.01-0.07 next to the moving wall (above 1e-3):
    undecided, with what the data say at their rates kept; one quasi-static run, or a run
    whose regime is unknown, leaves the verdict as it was; the spin claim itself (kinematics,
    not a slow-flow prediction) is never gated."""
    walls = [wall(r, [-0.09, -0.02, 0.0], 0.02, predicted={"cosserat": [0.03, 0.01, 0.0]})
             for r in ("a", "b")]  # fmt: skip
    v = spin_model_verdict(walls)
    fast = within_regime(v, [0.012, 0.074], 1e-3)
    assert (fast.verdict, fast.numbers["at_these_rates"]) == ("undecided", "refuted")
    assert fast.qualifier == ""  # an undecided verdict carries no scope
    assert fast.evidence.startswith("Not tested in the model's regime: every run used has "
                                    "I = 0.012-0.074")  # fmt: skip
    assert "At these rates the data would say refuted: Refuted:" in fast.evidence
    assert "runs with I <= 0.001" in fast.would_change
    assert within_regime(v, [4e-4, 0.074], 1e-3) == v
    assert within_regime(v, [None, 0.074], 1e-3) == v
    departs = spin_verdict(walls)
    assert within_regime(departs, [0.012, 0.074], 1e-3) == departs


def test_a_model_with_the_measured_sign_and_size_is_supported():
    walls = [wall("a", [-0.09, -0.02, 0.0], 0.02, predicted={"cosserat": [-0.085, -0.025, 0.0]})]
    v = spin_model_verdict(walls)
    assert v.verdict == "supported", v.text
    assert v.numbers["size_p"] > 1e-3


def test_the_right_sign_with_the_wrong_size_is_refuted():
    walls = [wall("a", [-0.09, -0.06, -0.03], 0.005, predicted={"cosserat": [-0.02, -0.01, 0.0]})]
    v = spin_model_verdict(walls)
    assert v.verdict == "refuted" and "the sign agrees but the size does not" in v.evidence


def test_a_model_without_a_spin_of_its_own_is_refuted_where_the_data_depart():
    v = spin_model_verdict([wall("a", [-0.09, 0.0, 0.0], 0.02, predicted={"mui": 0.0})], "mui")
    assert v.verdict == "refuted" and "predicts no departure" in v.evidence


def test_signs_that_disagree_between_walls_are_mixed():
    walls = [wall("a", [-0.09, 0, 0], 0.02, predicted={"cosserat": [-0.05, 0, 0]}),
             wall("b", [-0.09, 0, 0], 0.02, predicted={"cosserat": [0.05, 0, 0]})]  # fmt: skip
    assert spin_model_verdict(walls).verdict == "mixed"


def test_no_departure_where_the_model_predicts_a_visible_one_refutes_the_model():
    """No wall departs at 3 se, but the model predicts +0.03 against errors of 0.005 (chi^2
    of data - model = 3 x 36 over 3 bins): the model's departure is rejected."""
    v = spin_model_verdict([wall("a", 0.0, 0.005, predicted={"cosserat": 0.03})])
    assert v.verdict == "refuted", v.text
    assert v.numbers["size_chi2"] == pytest.approx(108.0)
    assert "predicts one these errors reject" in v.evidence


def test_a_sign_hidden_in_the_noise_cannot_decide_the_model():
    v = spin_model_verdict([wall("a", [0.01, 0.0, 0.0], 0.02, predicted={"cosserat": 0.03})])
    assert v.verdict == "undecided" and "not determined" in v.evidence
    assert spin_model_verdict([wall("a", 0.1, 0.01)]).verdict == "undecided"  # no fit


# --------------------------------------------------------------------------- Delta
def series(exponent, *, gaps=(20.0, 40.0, 80.0, 160.0), rel_err=0.02, rough=False,
           fills=(), values=None, cosserat=None):  # fmt: skip
    vals = values or [3.0 * (g / 20.0) ** exponent for g in gaps]
    reason = "the band fills its gap"
    pts = tuple(
        DeltaPoint(f"H{g:g}", g, v, rel_err * v, g in fills, reason if g in fills else "")
        for g, v in zip(gaps, vals, strict=True)
    )
    from cosserat.analysis.gap import power_law_slope

    slopes = {} if cosserat is None else {"cosserat": power_law_slope(gaps, [
        3.0 * (g / 20.0) ** cosserat for g in gaps])}  # fmt: skip
    return DeltaSeries("plane, glued-grains, B = 1" if rough else "plane, smooth-frictional, "
                       "B = 1", "plane", "fully-rough" if rough else "smoother", True, pts,
                       slopes)  # fmt: skip


def test_delta_laws_decided_by_series_made_for_them():
    assert delta_law_verdict([series(0.0)], "smoother").verdict == "supported"
    assert delta_law_verdict([series(1 / 3)], "smoother").verdict == "refuted"
    assert delta_law_verdict([series(1 / 3, rough=True)], "rough").verdict == "supported"
    v = delta_law_verdict([series(0.0, rough=True)], "rough")
    assert v.verdict == "refuted" and "H20" in v.runs
    # two series that disagree
    both = [series(0.0), series(1 / 3)]
    assert delta_law_verdict(both, "smoother").verdict == "mixed"


def test_a_power_law_that_misfits_its_points_is_said_to():
    """Gaps at 20, 40, 80, 160 d with Delta = 3.0, 4.5, 3.6, 5.4 (2% errors): the slope's
    error is scaled up by sqrt(reduced chi^2), and the evidence says one power law does not
    describe the points (chi^2 in the hundreds on 2 dof), which exact points do not."""
    bad = delta_law_verdict([series(0.0, rough=True, values=[3.0, 4.5, 3.6, 5.4])], "rough")
    assert "one power law does not describe these points (chi^2 = " in bad.evidence
    assert "for 2 degrees of freedom" in bad.evidence
    good = delta_law_verdict([series(1 / 3, rough=True)], "rough")
    assert "one power law does not describe" not in good.evidence


def test_a_band_filling_its_gap_cannot_refute_a_delta_law():
    """Smoother walls: Delta = 12, 8.5, 6 d at H/d = 20, 40, 80. With the H/d = 20 band (12 d
    > H/2) it would refute exponent 0 (slope -0.5); left out, two gaps remain: undecided."""
    made = dict(gaps=(20.0, 40.0, 80.0), values=[12.0, 12.0 / np.sqrt(2.0), 6.0])
    assert delta_law_verdict([series(0, **made)], "smoother").verdict == "refuted"
    v = delta_law_verdict([series(0, fills=(20.0,), **made)], "smoother")
    assert v.verdict == "undecided"
    assert "left out: H20 (the band fills its gap)" in v.evidence


def test_noisy_delta_cannot_decide_and_says_which_gaps_would():
    v = delta_law_verdict([series(1 / 3, rough=True, rel_err=0.3, gaps=(20.0, 30.0, 40.0))],
                          "rough")  # fmt: skip
    assert v.verdict == "undecided" and "cannot tell 0.333 from 0" in v.evidence
    assert "a slope error below 0.083" in v.would_change and "gaps up to H/d" in v.would_change


def test_data_that_follow_the_model_short_of_its_limit_leave_the_law_undecided():
    v = delta_law_verdict([series(0.4, cosserat=0.42, gaps=(20.0, 40.0, 80.0))], "smoother")
    assert v.verdict == "undecided" and "larger gaps are needed" in v.evidence


def test_data_that_follow_the_model_near_its_limit_do_not_refute_the_law():
    """Slope 0.45 +- 0.051 over H/d = 80-320 (5% errors), the model's own 0.41 there: the data
    miss 1/3 by 2.3 se but agree with the model, whose slope is itself within 2 se of 1/3
    (a Couette series made by the Cosserat model at these gaps was refuted so in 2 of 4
    seeds, ``tests/test_validate_synthetic.py``)."""
    s = series(0.45, rough=True, cosserat=0.41, gaps=(80.0, 160.0, 320.0), rel_err=0.05)
    assert abs(s.slope.slope - 1 / 3) > 2 * s.slope.stderr
    assert abs(0.41 - 1 / 3) < 2 * s.slope.stderr
    v = delta_law_verdict([s], "rough")
    assert v.verdict == "undecided" and "larger gaps are needed" in v.evidence
    # the same data where the model's slope is far from them: refuted
    far = series(0.45, rough=True, cosserat=0.2, gaps=(80.0, 160.0, 320.0), rel_err=0.05)
    assert delta_law_verdict([far], "rough").verdict == "refuted"


def test_too_few_gaps_and_no_series_are_undecided_and_a_bad_claim_is_an_error():
    assert delta_law_verdict([series(0.0, gaps=(20.0, 40.0))], "smoother").verdict == "undecided"
    assert delta_law_verdict([], "rough").verdict == "undecided"
    with pytest.raises(ParameterError, match="which must be 'smoother' or 'rough'"):
        delta_law_verdict([], "medium")


# --------------------------------------------------------------------------- series
def _run(folder: Path, name: str, **meta) -> Path:
    y = np.arange(int(meta["gap_d"])) + 0.5
    u = np.exp(-(meta["gap_d"] - y) / 3.0)
    base = {"cell": "plane", "B": 1.0, "wall": {"kind": "glued-grains"}}
    return write_run(folder, name, base | meta, {"y": y, "u": u, "u_se": np.full(y.size, 0.01)})


def test_runs_pair_by_tolerance_on_the_held_parameter_not_by_rounding(tmp_path):
    """B = 0.94 and 1.02 round to 0.9 and 1 at one digit, but agree within 10%: one series;
    B = 0.5 is another; other grains are another material."""
    _run(tmp_path, "a", gap_d=20.0, B=0.94)
    _run(tmp_path, "b", gap_d=40.0, B=1.02)
    _run(tmp_path, "c", gap_d=80.0, B=0.5)
    _run(tmp_path, "d", gap_d=80.0, B=1.0, grains={"diameter_range_d": [0.5, 1.5]})
    groups = group_runs(read_corpus(tmp_path).runs)
    names = sorted(tuple(r.name for r in g.runs) for g in groups)
    assert names == [("a", "b"), ("c",), ("d",)]


def test_a_run_whose_walls_differ_is_in_no_smooth_or_rough_series_and_names_both(tmp_path):
    """A plane run without gravity, rough moving wall and smooth fixed wall (the layer run):
    its series has no roughness, so neither Delta claim takes it; its label names both walls."""
    smooth = {"kind": "smooth-frictional"}
    _run(tmp_path, "layer", gap_d=10.0, B=0.0, wall_fixed=smooth)
    _run(tmp_path, "rough", gap_d=10.0, B=0.0)
    runs = {r.name: r for r in read_corpus(tmp_path).runs}
    assert walls_differ(runs["layer"]) and not walls_differ(runs["rough"])
    assert wall_label(runs["layer"]) == "moving fully-rough, fixed smoother"
    assert wall_label(runs["rough"]) == "fully-rough"
    rough = {s.runs[0].name: s.roughness for s in group_runs(list(runs.values()))}
    assert rough == {"layer": None, "rough": "fully-rough"}
    series = [DeltaSeries("k", "plane", None, False, (DeltaPoint("layer", 10.0, 9.3, 0.1),))]
    assert relevant(series, "smoother") == relevant(series, "rough") == []


def test_couette_runs_at_one_inner_radius_are_not_a_series_and_the_report_says_why(tmp_path):
    for h in (10.0, 20.0):
        r = np.linspace(20.5, 20.0 + h - 0.5, int(h))
        write_run(tmp_path, f"c{h:g}", {"cell": "couette", "gap_d": h, "Ri_d": 20.0,
                                        "wall": {"kind": "glued-grains"}},
                  {"r": r, "u": np.exp(-(r - 20.0) / 2.0),
                   "u_se": np.full(r.size, 0.01)})  # fmt: skip
    groups = group_runs(read_corpus(tmp_path).runs)
    assert len(groups) == 2
    (note,) = couette_note(groups)
    assert "R_i/d = 20" in note and "holds R_i/H fixed" in note


# --------------------------------------------------------------------------- fits
def test_misfit_pinned_and_contradicted_parameters_are_warned_in_every_output(tmp_path):
    """An exponential profile with errors of 1e-3 that the Cosserat model cannot follow
    (misfit), its phi pinned at 28.5 deg (sin phi = 0.477) while the run's band carries a
    stress ratio of 0.27: each said in results.json and in the report. With ``fit_angles``,
    the fits of one profile (by default the stresses fix phi: test_validate_stress_fix)."""
    gap = 20.0
    y = np.arange(int(gap)) + 0.5
    u = np.exp(-(gap - y) / 2.0)
    se = np.full(y.size, 1e-3)
    ratio = np.full(y.size, 0.27)
    write_run(tmp_path / "c", "run", {"cell": "plane", "gap_d": gap, "B": 1.0,
                                       "wall": {"kind": "glued-grains"}},
              {"y": y, "u": u + np.random.default_rng(0).normal(0, 1e-3, y.size), "u_se": se,
               "sigma_yx": -ratio, "sigma_yx_se": np.full(y.size, 0.005),
               "sigma_yy": np.ones(y.size), "sigma_yy_se": np.full(y.size, 0.005)})  # fmt: skip
    report = validate(tmp_path / "c", tmp_path / "out", models=["cosserat"], fit_angles=True)
    (result,) = report.results
    assert result.stress.value == pytest.approx(0.27) and result.stress.bins >= 2
    (fit,) = result.fits.summaries
    assert fit.p_value < 1e-3
    text = " | ".join(fit.warnings)
    assert "misfit: chi^2 = " in text and "(z = " in text and ", chi^2/dof = " in text
    assert "pinned (held at the declared default, not fitted): phi = 28.5" in text
    assert "contradicts the measured stress: phi = 28.5 (pinned) gives sin phi = 0.477" in text
    record = json.loads((tmp_path / "out" / "results.json").read_text())
    (entry,) = record["runs"][0]["ranking"]["fits"]
    assert {"model", "status", "reduced_chi2", "warnings", "p_value", "pinned"} <= set(entry)
    assert any(w.startswith("misfit:") for w in entry["warnings"])
    assert entry["pinned"]["phi"] == 28.5
    md = (tmp_path / "out" / "report.md").read_text()
    assert "contradicts the measured stress" in md and "misfit: chi^2" in md
    html = (tmp_path / "out" / "index.html").read_text()
    assert "contradicts the measured stress" in html
    # two gap series (with and without notes): each a list item of its own line
    from cosserat.studies.validate.report import context
    from cosserat.viz.report import render

    ctx = context(report)
    one = {"key": "a", "points": "H/d = 20: 5", "slope": "no slope", "reason": "",
           "models": "m 0.1", "notes": []}  # fmt: skip
    ctx["series"] = [one, {**one, "key": "b", "notes": ["n"]}, {**one, "key": "c"}]
    gaps = render("validate.md.j2", ctx).split("\n## Delta against the gap\n")[1].split("\n## ")[0]
    lines = [line for line in gaps.splitlines() if line.strip()]
    assert [line[:4] for line in lines] == ["* a:", "* b:", "  * ", "* c:"]


def test_results_json_has_the_documented_schema(tmp_path):
    """``runs[].ranking.fits[]`` (model, status, reduced_chi2, warnings), ``runs[].spin``
    (p_near_wall, departs_near_wall), ``verdicts[]`` (claim, verdict, evidence)."""
    y = np.arange(20) + 0.5
    dist = 20.0 - y
    u = np.exp(-dist / 3.0)
    half = 0.5 * u / 3.0
    se = np.full(20, 0.01)
    write_run(tmp_path / "c", "r", {"cell": "plane", "gap_d": 20.0, "B": 1.0,
                                     "wall": {"kind": "glued-grains"}},
              {"y": y, "u": u, "u_se": se, "omega": half - 0.1 * np.exp(-dist),
               "omega_se": se, "half_vorticity": half, "half_vorticity_se": se})  # fmt: skip
    validate(tmp_path / "c", tmp_path / "out", models=["cosserat"])
    record = json.loads((tmp_path / "out" / "results.json").read_text())
    run = record["runs"][0]
    for fit in run["ranking"]["fits"]:
        assert {"model", "status", "reduced_chi2", "warnings"} <= set(fit)
    assert {"p_near_wall", "departs_near_wall", "walls"} <= set(run["spin"])
    assert run["spin"]["departs_near_wall"] is True
    moving = next(w for w in run["spin"]["walls"] if w["wall"] == "moving")
    assert moving["first_layer_departure"] == pytest.approx(-0.1 * np.exp(-0.5), abs=1e-9)
    assert [v["key"] for v in record["verdicts"]] == ["spin", "smoother", "rough", "spin_model"]
    for v in record["verdicts"]:
        assert {"claim", "verdict", "evidence", "would_change", "runs"} <= set(v)
    assert read_run(tmp_path / "c" / "r.csv").name == "r"


def test_worker_processes_give_the_same_report_as_one_process(tmp_path):
    for g in (20.0, 40.0, 80.0):
        _run(tmp_path, f"r{g:g}", gap_d=g, B=1.0)
    seen: list[tuple[int, int]] = []
    one = validate(tmp_path, models=["cosserat"], workers=1)
    two = validate(tmp_path, models=["cosserat"], workers=2,
                   progress=lambda stage, i, n: seen.append((i, n)))  # fmt: skip
    assert [v.to_dict() for v in one.verdicts] == [v.to_dict() for v in two.verdicts]
    assert [r.run.name for r in two.results] == ["r20", "r40", "r80"]

    def chi2(report):
        return [[s.chi2 for s in r.fits.summaries] for r in report.results]

    assert chi2(one) == chi2(two)
    assert sorted(seen) == [(1, 3), (2, 3), (3, 3)]


def test_a_departure_so_large_that_its_p_underflows_to_zero_still_counts():
    walls = [wall(r, [-50.0, -20.0, -5.0], 0.01) for r in ("a", "b")]
    v = spin_verdict(walls)
    assert v.numbers["pooled_p_normal"] == 0.0
    assert v.verdict == "supported" and v.numbers["runs_departing_p_significant"] == ["a", "b"]


# --------------------------------------------------------------------------- Delta curves
def test_a_curve_test_has_its_closed_form():
    """Exact agreement: chi^2 0; data twice the prediction: chi^2 = sum (P/se)^2 as it is, 0
    times the factor 2; the two errors add in quadrature (3 and 4 give 5)."""
    from cosserat.studies.validate.verdicts import curve_test

    same = curve_test("m", [(10.0, 1.0), (12.0, 1.0), (14.0, 1.0)],
                      [(10.0, 0.0), (12.0, 0.0), (14.0, 0.0)])  # fmt: skip
    assert same.chi2 == pytest.approx(0.0) and same.p == pytest.approx(1.0)
    assert same.scale == pytest.approx(1.0) and (same.dof, same.dof_shape) == (3, 2)
    double = curve_test("m", [(2.0, 1.0), (4.0, 1.0)], [(1.0, 0.0), (2.0, 0.0)])
    assert double.chi2 == pytest.approx(1.0 + 4.0) and double.scale == pytest.approx(2.0)
    assert double.chi2_shape == pytest.approx(0.0, abs=1e-12)
    quad = curve_test("m", [(10.0, 3.0)], [(14.0, 4.0)])
    assert quad.chi2 == pytest.approx(16.0 / 25.0) and quad.p_shape is None
    assert curve_test("m", [], []) is None
    with pytest.raises(ParameterError, match="2 measured points but 1 predictions"):
        curve_test("m", [(1.0, 1.0), (2.0, 1.0)], [(1.0, 0.0)])
    with pytest.raises(ParameterError, match="a finite value and a positive error"):
        curve_test("m", [(1.0, 0.0)], [(1.0, 0.0)])


def test_a_power_law_test_frees_the_level_only():
    """Delta = 1 and 2 (se 0.1) at H/d = 1 and 8: exactly (H/d)^(1/3) up to its level; a
    constant gives the mean 1.5 and chi^2 = 2 (0.5/0.1)^2 = 50 on 1 dof."""
    from cosserat.studies.validate.verdicts import power_law_test

    pts = [(1.0, 1.0, 0.1), (8.0, 2.0, 0.1)]
    assert power_law_test(1 / 3, pts).chi2_shape == pytest.approx(0.0, abs=1e-12)
    flat = power_law_test(0.0, pts)
    assert flat.scale == pytest.approx(1.5) and flat.chi2_shape == pytest.approx(50.0)
    assert flat.dof_shape == 1


def _curved(values, curves, gaps=(20.0, 40.0, 80.0), rel_err=0.03, rough=True, speeds=None):
    """A series with Delta ``values`` at ``gaps`` and, per model, a curve function of H/d
    whose values at the runs are its predictions (no error)."""
    from cosserat.studies.validate.verdicts import ModelDelta

    base = series(0.0, rough=rough, gaps=gaps, values=list(values), rel_err=rel_err)
    grid = tuple(float(g) for g in np.geomspace(min(gaps) / 1.25, max(gaps) * 2.0, 9))
    md = {m: ModelDelta(m, {p.run: (fn(p.gap_d), None) for p in base.points},
                        (grid, tuple(fn(g) for g in grid)),
                        {"parameters": {"phi": {"value": 17.0, "stderr": 0.3, "free": True}},
                         "chi2": 100.0, "dof": 90, "p_value": 0.2})
          for m, fn in curves.items()}  # fmt: skip
    import dataclasses

    # an alternative's curve stands for its per-series best fit too (the rule judges there)
    md = {m: c if m == "cosserat" else dataclasses.replace(c, best=c) for m, c in md.items()}
    return dataclasses.replace(base, curves=md, speeds=speeds or {})


def test_a_curve_slope_is_read_between_two_gaps():
    s = _curved([1, 1, 1], {"cosserat": lambda g: 3.0 * (g / 20.0) ** 0.5})
    assert s.curves["cosserat"].slope_between(20.0, 80.0) == pytest.approx(0.5, abs=1e-9)
    assert s.curves["cosserat"].slope_between(5.0, 80.0) is None  # beyond the curve


def test_delta_follows_the_cosserat_curve_and_rejects_another_model():
    """Rough walls: Delta = the Cosserat curve 9.2 (H/20)^0.53 exactly (3% errors), mu(I)'s
    growing as H/d: supported, mu(I) rejected; the exponent is reported, not judged (the
    curve's own slope 0.53 is not its limit 1/3); swapped, the data refute the claim."""
    cos = lambda g: 9.2 * (g / 20.0) ** 0.53  # noqa: E731
    mui = lambda g: 9.2 * (g / 20.0)  # noqa: E731
    gaps = (20.0, 40.0, 80.0)
    v = delta_law_verdict([_curved([cos(g) for g in gaps], {"cosserat": cos, "mui": mui})],
                          "rough")  # fmt: skip
    assert v.verdict == "supported"
    assert "reject mui (per-series best fit)" in v.evidence
    assert "reported, not judged" in v.evidence
    assert "one joint calibration" in v.evidence
    bad = delta_law_verdict([_curved([mui(g) for g in gaps], {"cosserat": cos, "mui": mui})],
                            "rough")  # fmt: skip
    assert bad.verdict == "refuted" and "does not follow the measured Delta" in bad.evidence
    entry = bad.numbers[next(iter(bad.numbers))]
    (c, _) = entry["calibration"]
    assert c["model"] == "cosserat" and c["test"]["dof"] == 3 and c["test"]["p"] < 1e-3
    assert c["Delta"]["H20"]["value"] == pytest.approx(9.2)


def test_a_level_missed_by_a_common_factor_is_said_and_does_not_refute_the_dependence():
    cos = lambda g: 3.0 * (g / 20.0) ** 0.1  # noqa: E731
    gaps = (20.0, 40.0, 80.0)
    v = delta_law_verdict([_curved([2.4 * cos(g) for g in gaps], {"cosserat": cos},
                                   rough=False)], "smoother")  # fmt: skip
    assert "the level is missed: the data are 2.4 times the cosserat curve" in v.evidence
    # nothing rejected besides: the constant's rival (H/d)^(1/3) is far, so supported
    assert v.verdict == "supported" and "Delta ~ (H/d)^0.333" in v.evidence


def test_noisy_delta_on_the_curve_rejects_nothing_and_is_undecided():
    cos = lambda g: 9.2 * (g / 20.0) ** 0.4  # noqa: E731
    gaps = (20.0, 30.0, 40.0)
    v = delta_law_verdict([_curved([cos(g) for g in gaps], {"cosserat": cos}, gaps=gaps,
                                   rel_err=0.3)], "rough")  # fmt: skip
    assert v.verdict == "undecided" and "reject no alternative" in v.evidence


def test_the_exponent_is_judged_only_where_the_curve_has_reached_its_limit():
    """The Cosserat curve (H/d)^(1/3) itself: its own slope is the limit, so the measured
    exponent is judged (and supported: the data follow it, 1/3 is 6 se from 0)."""
    cos = lambda g: 5.0 * (g / 20.0) ** (1 / 3)  # noqa: E731
    gaps = (20.0, 80.0, 320.0)
    v = delta_law_verdict([_curved([cos(g) for g in gaps], {"cosserat": cos}, gaps=gaps,
                                   rel_err=0.01)], "rough")  # fmt: skip
    assert "judged, since the cosserat curve's own slope" in v.evidence
    assert v.verdict == "supported"


def test_replicates_at_two_wall_speeds_are_named_with_their_difference():
    from cosserat.studies.validate.verdicts import DeltaPoint, DeltaSeries

    pts = (DeltaPoint("a", 20.0, 5.7, 0.63), DeltaPoint("b", 20.5, 8.35, 0.82),
           DeltaPoint("c", 40.0, 11.5, 0.5))  # fmt: skip
    s = DeltaSeries("k", "plane", "fully-rough", True, pts, speeds={"a": 0.1, "b": 0.05})
    (text,) = s.replicates()
    z = (8.35 - 5.7) / np.hypot(0.63, 0.82)
    assert f"they differ by {z:.2g} se at different wall speeds (beyond 2 se" in text
    assert "a (wall speed 0.1: Delta = 5.7 +- 0.63 d)" in text
    assert s.to_dict()["replicates"] == [text]


def test_a_verdicts_qualifier_stands_beside_it_in_every_output():
    """Referee 10, point 3: the condition a verdict holds under is in the verdict field of
    report.md, index.html, results.json and the terminal text, not only in the evidence."""
    from types import SimpleNamespace

    from cosserat.studies.validate.study import ValidationReport
    from cosserat.studies.validate.verdicts import Verdict
    from cosserat.viz.report import render

    v = Verdict("spin", "supported", "e", qualifier="given a velocity smooth on the grain scale")
    assert v.to_dict()["qualifier"] == "given a velocity smooth on the grain scale"
    assert Verdict("spin", "undecided", "e").to_dict()["qualifier"] == ""
    ctx = {
        "title": "t", "corpus": "c", "n_runs": 1, "models": "cosserat", "f": "0.1",
        "near_wall_d": "3", "rules": "r", "runs": [], "series": [], "notes": [],
        "verdicts": [{"key": "spin", "claim": "claim", "verdict": "supported",
                      "qualifier": v.qualifier, "evidence": "e", "would_change": "",
                      "figure": "claim_spin.png", "extra_figures": []}],
    }  # fmt: skip
    md = render("validate.md.j2", ctx)
    assert "Verdict: **supported**, given a velocity smooth on the grain scale." in md
    page = render("validate.html.j2", ctx)
    assert "<b>supported</b>, given a velocity smooth on the grain scale.</p>" in page
    fake = SimpleNamespace(corpus="c", results=[], verdicts=[v])
    text = ValidationReport.to_text(fake)  # type: ignore[arg-type]
    assert "[supported, given a velocity smooth on the grain scale] " in text
    ctx["verdicts"][0].pop("qualifier")
    assert "Verdict: **supported**.\n" in render("validate.md.j2", ctx)
