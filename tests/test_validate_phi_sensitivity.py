"""spin_model's grid-sign argument at the ends of the plausible phi range (referee 11, point 3):
:func:`~cosserat.studies.validate.spin_scan.phi_ends`, ``phi_sensitivity`` and its sentence."""

from __future__ import annotations

import math
from types import SimpleNamespace

import numpy as np
import pytest

from cosserat.analysis.corpus import read_run
from cosserat.errors import ParameterError
from cosserat.studies.validate import spin_scan as ss
from cosserat.studies.validate import stresses
from cosserat.studies.validate.synthetic import synthetic_run


def _asin_deg(x: float) -> float:
    return math.degrees(math.asin(x))


def test_the_phi_ends_are_the_scaled_pooled_range_and_the_runs_extremes(monkeypatch):
    # 0.30 and 0.34 +- 0.01: mean 0.32, chi^2 = 8 on 1 dof (p = 0.0047 < 0.05), so the error
    # 0.01/sqrt(2) is scaled by sqrt(8): 0.02, and +- 2 se is 0.28 to 0.36
    pooled = stresses.pool([0.30, 0.34], [0.01, 0.01], ["a", "b"])
    assert pooled.stderr == pytest.approx(0.02, rel=1e-12)
    got = stresses.StressPool("sin phi", "wall", pooled, None)
    monkeypatch.setattr(
        stresses, "material_sin_phi", lambda runs, material: SimpleNamespace(sin_phi=got)
    )
    ends = ss.phi_ends([], "m")
    assert [lab for lab, _ in ends] == [
        "pooled sin phi - 2 se", "lowest run's T (a)", "highest run's T (b)",
        "pooled sin phi + 2 se",
    ]  # fmt: skip
    np.testing.assert_allclose(
        [phi for _, phi in ends], [_asin_deg(x) for x in (0.28, 0.30, 0.34, 0.36)], rtol=1e-12
    )


def test_the_cross_checks_extreme_enters_where_it_lies_beyond_the_walls_range(monkeypatch):
    # referee 12, point 5(i): walls 0.30 and 0.34 (range 0.28-0.36 as above); the bands' T
    # 0.29 (inside: left out) and 0.37 (beyond: added as the cross-check's highest)
    walls = stresses.pool([0.30, 0.34], [0.01, 0.01], ["a", "b"])
    bands = stresses.pool([0.29, 0.37], [0.01, 0.01], ["a", "b"])
    got = stresses.StressPool("sin phi", "wall", walls, bands)
    monkeypatch.setattr(
        stresses, "material_sin_phi", lambda runs, material: SimpleNamespace(sin_phi=got)
    )
    ends = ss.phi_ends([], "m")
    assert ends[-1] == (
        "cross-check: highest run's band |sigma_yx|/N (b)",
        pytest.approx(_asin_deg(0.37)),
    )
    assert [lab for lab, _ in ends[:-1]] == [
        "pooled sin phi - 2 se", "lowest run's T (a)", "highest run's T (b)",
        "pooled sin phi + 2 se",
    ]  # fmt: skip
    # the v2 runs' band T 0.331 is 19.3 deg, beyond the walls' 16.6-18.7
    assert _asin_deg(0.3306862716376498) == pytest.approx(19.31, abs=0.005)


def test_the_sentence_gives_the_sign_at_the_cross_checks_phi():
    """From a hand record: the cross-check's row at 19.3 deg keeps the positive sign in one run
    and turns it in the other."""
    top = "cross-check: highest run's band |sigma_yx|/N (a)"
    rows_a = [_row(16.7, 0.0005, 0.2), {**_row(19.3, 0.002, 0.38), "label": top}]
    rows_b = [_row(16.7, 0.004, 0.1), {**_row(19.3, 0.02, 0.25), "label": top}]
    a = _scan("a", (0.001, 0.3), -0.1, rows_a)
    b = _scan("b", (0.01, 0.2), -0.2, rows_b)
    text = ss.phi_sensitivity_text([a, b])
    assert (
        "(the pooled sin phi +- 2 se, the runs' extreme wall ratios and the cross-check's highest "
        f"band |sigma_yx|/N = {math.sin(math.radians(19.3)):.3g} (a); each wall's tan delta held)"
        in text
    )
    assert (
        "spans +0.0005 to +0.38 (+0.002 to +0.38 at the cross-check's phi = 19.3 deg: positive, "
        "the fitted phi's sign in 2 of 2 runs): positive over the grid at phi = 16.7-19.3 deg "
        "in all 2 runs" in text
    )
    rows_b[1] = {**_row(19.3, -0.01, 0.25), "label": top}
    b = _scan("b", (0.01, 0.2), -0.2, rows_b)
    text = ss.phi_sensitivity_text([a, b])
    assert "(-0.01 to +0.38 at the cross-check's phi = 19.3 deg: mixed, the fitted phi's sign " \
        "in 1 of 2 runs)" in text  # fmt: skip
    assert "in b: there the refutation depends on phi" in text


def test_one_run_gives_only_the_pooled_ends_and_an_end_beyond_one_is_left_out(monkeypatch):
    pooled = stresses.pool([0.95], [0.03], ["a"])  # 0.95 +- 0.06: 0.89 and 1.01
    got = stresses.StressPool("sin phi", "wall", pooled, None)
    monkeypatch.setattr(
        stresses, "material_sin_phi", lambda runs, material: SimpleNamespace(sin_phi=got)
    )
    ends = ss.phi_ends([], "m")
    assert len(ends) == 1
    assert ends[0][0] == "pooled sin phi - 2 se"
    assert ends[0][1] == pytest.approx(_asin_deg(0.89), rel=1e-12)


def test_a_measured_wall_keeps_its_tan_delta_when_phi_moves_a_rough_one_stays_rough():
    ang = ss.Angles(20.0, 0.5, "", {"moving": 0.5}, {"moving": ""}, {"moving": 0.01})
    values = {"phi": 20.0, "L": 3.0, ("roughness", "moving"): 0.5, ("roughness", "fixed"): 0.5}
    new = ss._values_at_phi(values, ang, 25.0)
    r = 0.5 * math.sin(math.radians(20.0)) / math.sin(math.radians(25.0))
    assert new == {"phi": 25.0, "L": 3.0, ("roughness", "moving"): pytest.approx(r, rel=1e-12),
                   ("roughness", "fixed"): pytest.approx(r, rel=1e-12)}  # fmt: skip
    rough = ss.Angles(20.0, 0.5, "", {"moving": 1.0}, {"moving": ""})
    assert ss._values_at_phi({"phi": 20.0, ("roughness", "moving"): 1.0}, rough, 15.0) == {
        "phi": 15.0, ("roughness", "moving"): 1.0,
    }  # fmt: skip


def _row(phi, lo, hi):
    return {"label": "x", "phi": phi, "lo": lo, "hi": hi, "solved": 1, "points": 1}


def test_the_sign_over_the_phi_rows():
    assert ss._one_sign([_row(16.0, 0.01, 0.3), _row(19.0, 0.002, 0.4)]) == "positive"
    assert ss._one_sign([_row(16.0, -0.3, -0.01), _row(19.0, None, None)]) == "negative"
    assert ss._one_sign([_row(16.0, 0.01, 0.3), _row(19.0, -0.002, 0.4)]) == "mixed"
    assert ss._one_sign([_row(16.0, None, None)]) == "none solved"


def _scan(name, grid, data, rows, seconds=0.5):
    return SimpleNamespace(
        run=name, whole_beyond_span=grid, measured_beyond=data,
        phi_sensitivity={"rows": rows, "sign": ss._one_sign(rows), "seconds": seconds},
    )  # fmt: skip


def test_the_sentence_says_the_refutation_does_not_depend_on_phi():
    a = _scan("a", (0.001, 0.3), -0.1, [_row(16.7, 0.0005, 0.2), _row(19.3, 0.002, 0.38)])
    b = _scan("b", (0.01, 0.2), -0.2, [_row(16.7, 0.004, 0.1), _row(19.3, 0.02, 0.25)])
    # a run whose data share the grid's sign is not part of the argument
    c = _scan("c", (0.01, 0.2), +0.05, [_row(16.7, -0.5, 0.1), _row(19.3, -0.5, 0.1)])
    for sc in (a, b, c):
        sc.phi_sensitivity["grid"] = [6, 6]
    text = ss.phi_sensitivity_text([a, b, c])
    assert "spans +0.0005 to +0.38: positive over the grid at phi = 16.7-19.3 deg in all 2 " in text
    assert text.endswith(
        "the refutation does not depend on phi (a 6 x 6 K-L grid, 2 runs x 2 phi, 1 s)."
    )


def test_the_sentence_names_the_run_where_the_sign_turns():
    a = _scan("a", (0.001, 0.3), -0.1, [_row(16.7, -0.0005, 0.2), _row(19.3, 0.002, 0.38)])
    b = _scan("b", (0.01, 0.2), -0.2, [_row(16.7, 0.004, 0.1), _row(19.3, 0.02, 0.25)])
    text = ss.phi_sensitivity_text([a, b])
    assert "it is not positive over the whole grid at some phi of 16.7-19.3 deg in a: " in text
    assert "there the refutation depends on phi" in text
    assert ss.phi_sensitivity_text([_scan("c", (0.01, 0.2), 0.05, [_row(16.7, 0.1, 0.2)])]) == ""


@pytest.fixture(scope="module")
def pair(tmp_path_factory):
    folder = tmp_path_factory.mktemp("phisens")
    phi = 20.0
    rough = math.degrees(math.atan(math.sin(math.radians(phi))))

    def run(name, wall, delta, seed):
        return read_run(synthetic_run(
            folder, name, "cosserat", "plane", 10.0,
            parameters={"phi": phi, "L": 3.0, "K": 0.5, "delta": delta}, wall=wall, B=1.0,
            noise=0.005, stress_noise=0.005, seed=seed,
        ))  # fmt: skip

    return run("rough", "rough", rough, 0), run("smooth", "smooth", 15.0, 1)


def test_at_the_fitted_phi_the_rows_are_the_scans_own_range_grid(pair):
    """phi_sensitivity at the joint fit's own phi recomputes the range grid: its min and max
    beyond the null are the scan's, to the last digit; and scan_run fills it at the ends."""
    rough, smooth = pair
    sc = ss.scan_run(smooth, [rough, smooth], points=4)
    got = ss.phi_sensitivity(sc, smooth, [("fitted", sc.fit.angles.phi)], stride=1)
    diff = sc.departure - sc.null
    fin = diff[np.isfinite(diff)]
    (row,) = got["rows"]
    assert row["solved"] == fin.size and row["points"] == 16 and got["grid"] == [4, 4]
    assert row["lo"] == float(fin.min()) and row["hi"] == float(fin.max())
    assert got["seconds"] > 0.0
    # the default takes every other K and L: the grid's points (0, 2) x (0, 2)
    half = ss.phi_sensitivity(sc, smooth, [("fitted", sc.fit.angles.phi)])
    sub = diff[::2, ::2][np.isfinite(diff[::2, ::2])]
    assert half["grid"] == [2, 2] and half["rows"][0]["solved"] == sub.size
    assert half["rows"][0]["lo"] == float(sub.min()) and half["rows"][0]["hi"] == float(sub.max())
    with pytest.raises(ParameterError, match="the phi sensitivity's stride must be >= 1; got 0"):
        ss.phi_sensitivity(sc, smooth, [], stride=0)
    ends = sc.phi_sensitivity["rows"]
    own = [r for r in ends if not r["label"].startswith(ss.CROSS_CHECK_END)]
    assert [r["label"] for r in own] == ["pooled sin phi - 2 se", "pooled sin phi + 2 se"]
    # the band's T (the cross-check) enters only beyond the walls' range
    for r in ends:
        if r not in own:
            assert not own[0]["phi"] <= r["phi"] <= own[1]["phi"]
    assert sc.to_dict()["phi_sensitivity"]["sign"] in ("positive", "negative", "mixed")
    # the joint fit is the grid's minimum (or a restart from a lower point is recorded), and
    # every refined cell is a range-grid cell with a corner inside the 95% region
    assert ss.below_optimum(sc) is None or any(m["kept"] == 0.0 for m in sc.restarts)
    d = sc.chi2 - sc.chi2_min
    for p in sc.patches:
        a, b = int(np.flatnonzero(sc.K == p.K[0])[0]), int(np.flatnonzero(sc.L == p.L[0])[0])
        assert (p.K[-1], p.L[-1]) == (sc.K[a + 1], sc.L[b + 1])
        assert (d[a : a + 2, b : b + 2] <= sc.threshold).any()
    record = sc.to_dict()
    assert len(record["refined"]) == len(sc.patches) and record["restarts"] == sc.restarts


# --------------------------------------------------------------------------- point 4
def _fitted(fields, u_p=None):
    sc = SimpleNamespace(
        fit=SimpleNamespace(calibration=SimpleNamespace(
            fields=[SimpleNamespace(field=n, chi2=c, n=k) for n, c, k in fields]
        )),
    )  # fmt: skip
    sc._error_models = {} if u_p is None else {"u": {"p": u_p}}
    return sc


def test_the_missed_fields_are_the_calibrations_and_us_under_the_other_error_models():
    from scipy.stats import chi2 as chi2_dist

    # omega 40 on 10 bins: p = 1.7e-5 < 1e-3; u 12 on 10 (p = 0.28) fits under AR(1) but not
    # under the diagonal and common-mode models given; the stress ratio fits
    sc = _fitted([("u", 12.0, 10), ("omega", 40.0, 10), ("stress_ratio", 5.0, 8)],
                 {"ar1": 0.28, "diagonal": 2.0e-11, "common-mode": 5.0e-4})  # fmt: skip
    p = chi2_dist.sf(40.0, 10)
    assert ss.missed_fields(sc) == [
        f"omega (p = {p:.2g})", "u (diagonal p = 2e-11; common-mode p = 0.0005)",
    ]  # fmt: skip
    fine = _fitted([("u", 12.0, 10), ("omega", 9.0, 10)], {"diagonal": 0.01, "common-mode": None})
    assert ss.missed_fields(fine) == []


def _grid_scan(wall_k):
    # departures over K x L; the measured -0.1 +- 0.01: within 2 se are -0.12..-0.08
    dep = np.array([[-0.10, -0.09, 0.05], [-0.30, 0.02, 0.20]])
    return SimpleNamespace(
        K=np.array([0.2, 2.0]), L=np.array([0.5, 0.8, 5.0]), departure=dep,
        K_near=np.array([1.0]), L_near=np.array([0.7, 3.0]),
        departure_near=np.array([[-0.11, 0.1]]),
        measured=-0.1, measured_se=0.01, wall_k=wall_k,
    )  # fmt: skip


def test_the_physical_reading_is_the_largest_matching_L_and_the_ks():
    wall_k = {
        "matching_point": {"matched": True, "L": 0.5, "K": 0.2, "delta_chi2": 58.64},
        "model": {"K": 6.59}, "fitted_K": 2.67,
    }  # fmt: skip
    text = ss.matching_reading(_grid_scan(wall_k))
    assert text == (
        "the model reaches the measured first layer (within 2 se) only with L <= 0.8 d "
        "(K = 0.2-1 at the scan's points); its best first-layer-matching point, L = 0.5 d and "
        "K = 0.2, costs Delta chi^2 = +58.6 on the rest of the profile. Measured like the data "
        "the joint fit's K is 6.59 against the fitted 2.67, so its first-bin spin lies about "
        "2.5 times below its wall spin: the miss lies in a spin boundary layer thinner than a "
        "grain, where the continuum is at its limit"
    )
    far = _grid_scan({})
    far.measured = 0.5
    assert ss.matching_reading(far) == ""


def test_the_reading_band_is_wall_ks_match_band():
    from cosserat.studies.validate import wall_k

    assert wall_k.MATCH_SIGMAS == 2.0  # matching_reading's default sigmas


# --------------------------------------------------------------------------- point 7
def _ridge():
    """Delta chi^2 10 on K = 0..4, ln L = 0..4 except a diagonal ridge (1, 1) 0, (2, 2) 1 and
    an isolated point (4, 4) 1: threshold 3."""
    K, L = np.arange(5.0), np.exp(np.arange(5.0))
    d = np.full((5, 5), 10.0)
    d[1, 1], d[2, 2], d[4, 4] = 0.0, 1.0, 1.0
    return K, L, d


def test_the_optimums_piece_follows_a_diagonal_ridge_and_leaves_an_isolated_point_out():
    K, L, d = _ridge()
    masks, others, joined = ss.region_pieces([(K, L, d, "range")], 3.0, (1.0, math.e))
    assert np.argwhere(masks[0]).tolist() == [[1, 1], [2, 2]]
    # each other piece carries its masks (per grid), here the one range point (4, 4)
    assert [{k: v for k, v in o.items() if k != "masks"} for o in others] == [
        {"K": [4.0, 4.0], "L": [L[4], L[4]], "points": 1, "delta_chi2": 1.0}
    ]
    assert [np.argwhere(m).tolist() for m in others[0]["masks"]] == [[[4, 4]]]
    assert joined == 0
    # the region is reported as its islands (referee 13, point 2), the other piece one of them
    main = {"K": [0.7, 2.2], "L": [2.0, 9.0], "points": 2, "delta_chi2": 0.0}
    ext = {"K": [0.7, 4.0], "L": [2.0, L[4]], "K_bounds": ["data", "data"],
           "L_bounds": ["data", "box"], "islands": [main, others[0]], "joined": 0}  # fmt: skip
    assert ss.region_text(ext) == (
        "two islands: K 0.7-2.2, L 2-9 d and K 4, L ~55 d; L unidentified: 2-54.6 d, two "
        "basins (L's upper limit is the finer grid's edge)"
    )


def test_a_path_along_the_valley_joins_the_pieces():
    K, L, d = _ridge()
    seen = []

    def inside(k, ll):
        seen.append((k, np.log(ll)))
        return np.ones(k.size, bool)

    masks, others, joined = ss.region_pieces([(K, L, d, "range")], 3.0, (1.0, math.e), inside)
    assert others == [] and joined == 1 and masks[0].sum() == 3
    # slices of the segment from (4, 4) to the nearest point of the optimum's piece, (2, 2),
    # in K and ln L; each slice K = the line's +- 2 (the segment's K extent) on 19 points,
    # clipped to the grid's K 0..4
    k, lnl = seen[0]
    t = np.linspace(0.0, 1.0, ss.PATH_POINTS + 2)[1:-1]
    np.testing.assert_allclose(np.unique(np.round(lnl, 12)), np.sort(4.0 - 2.0 * t))
    line = 4.0 - 2.0 * t[0]
    want = np.clip(line + np.linspace(-2.0, 2.0, 2 * ss.PATH_POINTS + 1), 0.0, 4.0)
    np.testing.assert_allclose(k[: want.size], want)
    # a valley 1.5 below the straight line in K joins them; a barrier across ln L = 3 does not
    _, others, joined = ss.region_pieces(
        [(K, L, d, "range")], 3.0, (1.0, math.e),
        lambda k, ll: np.abs(k - (np.log(ll) - 1.5)) < 0.3,
    )  # fmt: skip
    assert joined == 1 and others == []
    _, others, joined = ss.region_pieces(
        [(K, L, d, "range")], 3.0, (1.0, math.e),
        lambda k, ll: np.abs(np.log(ll) - 3.0) > 0.1,
    )  # fmt: skip
    assert joined == 0 and len(others) == 1


def test_a_range_point_inside_the_finer_box_joins_the_finer_grids_piece():
    K, L, d = _ridge()
    d[2, 2] = 10.0  # the range grid: (1, 1) and (4, 4) apart
    Kf, Lf = np.array([3.0, 3.5, 4.0]), np.exp(np.array([3.0, 3.5, 4.0]))
    df = np.zeros((3, 3))  # the finer box around (4, 4) is all inside
    grids = [(K, L, d, "range"), (Kf, Lf, df, "box")]
    masks, others, _ = ss.region_pieces(grids, 3.0, (3.5, math.exp(3.5)))
    assert np.argwhere(masks[0]).tolist() == [[4, 4]] and masks[1].all()
    assert [{k: v for k, v in o.items() if k != "masks"} for o in others] == [
        {"K": [1.0, 1.0], "L": [L[1], L[1]], "points": 1, "delta_chi2": 0.0}
    ]
    assert [np.argwhere(m).tolist() for m in others[0]["masks"]] == [[[1, 1]], []]
