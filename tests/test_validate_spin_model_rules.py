"""spin_model's per-run rules under every stencil and every error model of u, and the scan's
95% region in one definition (referee 10, points 1 and 7), on hand-computable inputs.

The scans here are built by hand (no solve): a 2 x 2 grid whose admissible points and
departures are chosen, a joint fit of chi^2 = dof (scale 1), and u's chi^2 under the three
error models set directly, so every z below is arithmetic.
"""

from __future__ import annotations

import math
from types import SimpleNamespace

import numpy as np
import pytest

from cosserat.errors import ParameterError
from cosserat.studies.validate import spin_scan as ss

PPF = 5.991464547107979  # chi2.ppf(0.95, 2)


def _scan(measured, measured_se, stencils=None, region=None, u=None, departure=(0.05, 0.35)):
    """A scan whose 95% region is the two points (K 0, L 1) and (K 0, L 2) of a 2 x 2 grid,
    with the model's first-layer departure ``departure`` there (best fit: the first), every
    null 0, chi^2 = dof = 10."""
    fit = SimpleNamespace(calibration=SimpleNamespace(dof=10, chi2=10.0, p_value=0.44))
    dep = np.array([[departure[0], departure[1]], [0.9, 0.9]])
    chi2 = 10.0 + np.array([[0.0, 1.0], [100.0, 100.0]])
    sc = ss.Scan(
        "x", fit, np.array([0.0, 1.0]), np.array([1.0, 2.0]), dep, chi2, 10.0, 2,
        departure[0], measured, measured_se, 0.5,
        stencils=dict(stencils or {}), null=np.zeros((2, 2)),
        stencil_region=dict(region or {}),
    )  # fmt: skip
    sc.__dict__["_error_models"] = {} if u is None else {"u": u}
    return sc


SPREAD = 0.3 / (2.0 * math.sqrt(PPF))  # the region's span of the departure as an se


def test_the_hand_scan_has_the_numbers_the_rules_take():
    sc = _scan(-0.1, 0.04)
    assert sc.scale == 1.0 and sc.threshold == pytest.approx(PPF)
    assert sc.beyond_span == (0.05, 0.35)
    assert sc.prediction_se == pytest.approx(SPREAD, rel=1e-12)
    assert sc.measured_beyond_se == pytest.approx(0.04)  # the null has no spread


def test_null_and_sign_rules_at_one_stencil():
    # not excluded (0.1 < 3 x 0.04) and the region 0.15 > 0.12 from it: the null rule
    assert ss.null_sign_rules(-0.1, 0.04, 0.05, 0.35, 3.0) == {"null": True, "sign": False}
    # excluded (0.2 >= 0.18) and no region point negative: the sign rule
    assert ss.null_sign_rules(-0.2, 0.06, 0.05, 0.35, 3.0) == {"null": False, "sign": True}
    # a region point of the data's sign: neither
    assert ss.null_sign_rules(-0.2, 0.06, -0.01, 0.35, 3.0) == {"null": False, "sign": False}
    # not excluded but the region within 3 se: neither
    assert ss.null_sign_rules(-0.05, 0.04, 0.05, 0.35, 3.0) == {"null": False, "sign": False}


def test_the_size_rule_needs_every_stencil_and_every_error_model():
    assert ss.size_holds({"ar1": {"a": 4.0, "b": 5.0}, "diagonal": {"a": 3.5, "b": 3.1}})
    assert not ss.size_holds({"ar1": {"a": 4.0, "b": 5.0}, "diagonal": {"a": 3.5, "b": 2.9}})
    assert not ss.size_holds({"ar1": {"a": 4.0, "b": -5.0}})  # not one sign
    assert ss.size_holds({"ar1": {"a": -4.0}, "common-mode": {"a": -3.01}})
    assert not ss.size_holds({})


def test_u_error_models_scale_the_size_rule():
    """chi^2 = 10 on 10 dof with u's 5 (AR(1)) replaced by 25 (diagonal) and 15 (common-
    mode): scales 1, 3, 2. A best fit 0.06 above data 0.1 +- 0.01 (a one-point region: no
    prediction spread) is 6, 6/sqrt(3), 6/sqrt(2) se."""
    u = {"ar1": 5.0, "diagonal": 25.0, "common-mode": 15.0, "n": 10}

    def scan(model):
        st = {k: {"data": 0.1, "se": 0.01, "model": model} for k in ("analysis", "wall")}
        reg = {"wall": {"null": 0.0, "null_se": 0.0, "best": model, "lo": model, "hi": model}}
        return _scan(0.1, 0.01, st, reg, u=u, departure=(model, model))

    sc = scan(0.16)
    assert ss.error_model_scales(sc) == pytest.approx({"ar1": 1.0, "diagonal": 3.0,
                                                       "common-mode": 2.0})  # fmt: skip
    z = ss.size_z_by_model(sc)
    assert z["ar1"] == pytest.approx({"analysis": 6.0, "wall": 6.0})
    assert z["diagonal"]["wall"] == pytest.approx(6.0 / math.sqrt(3.0))
    assert z["common-mode"]["analysis"] == pytest.approx(6.0 / math.sqrt(2.0))
    call, rule = ss.wall_rule(sc)
    assert call == "refuted"
    assert rule == (
        "size rule: best fit - data beyond 3 se, one sign, under every stencil and every "
        "error model of u (AR(1), diagonal, common-mode)"
    )
    # 0.05 above: 5 se under AR(1), 2.89 under diagonal: the size rule does not refute
    sc5 = scan(0.15)
    call, rule = ss.wall_rule(sc5)
    assert call == "undecided"
    assert rule == (
        "depends on the stencil or u's error model: best fit - data is beyond 3 se under 4 of "
        "6 stencils and error models, not all"
    )
    line = ss.rules_line(sc5)
    assert line == (
        "x: undecided; null rule 0/2, sign rule 0/2; size z AR(1) +5.0 (2/2), diagonal +2.9 "
        "(0/2), common-mode +3.5 (2/2)"
    )
    assert ss.rules_summary(sc5) == "size 4/6, null 0/2, sign 0/2"


def _wall(data, se=0.04, null_se=0.0):
    return {"data": data, "se": se, "model": 0.05}, {
        "null": 0.0, "null_se": null_se, "best": 0.05, "lo": 0.05, "hi": 0.35,
    }  # fmt: skip


def test_the_null_rule_refutes_only_under_every_stencil():
    """Data -0.1 +- 0.04 beyond the null, the region 0.05 to 0.35: the null rule holds (0.15
    > 0.12); the size rule does not (0.15 / hypot(0.04, SPREAD) = 2.05 se)."""
    an = {"data": -0.1, "se": 0.04, "model": 0.05}
    wall, reg = _wall(-0.1)
    sc = _scan(-0.1, 0.04, {"analysis": an, "wall": wall}, {"wall": reg})
    z = ss.size_z_by_model(sc)["ar1"]
    assert z["analysis"] == pytest.approx(0.15 / math.hypot(0.04, SPREAD))
    table = ss.stencil_rules(sc)
    assert table["wall"]["null"] and table["analysis"]["null"]
    call, rule = ss.wall_rule(sc)
    assert (call, rule.split(":")[0]) == ("refuted", "null rule")
    assert rule.endswith("under every stencil")
    # under the wall stencil the data sit 0.10 from the region (< 0.12): undecided, named
    wall, reg = _wall(-0.05)
    sc = _scan(-0.1, 0.04, {"analysis": an, "wall": wall}, {"wall": reg})
    assert ss.wall_rule(sc) == (
        "undecided",
        "depends on the stencil or u's error model: the null rule holds under analysis but "
        "not wall",
    )


def test_the_sign_rule_refutes_only_under_every_stencil():
    """Data -0.2 +- 0.06: excluded (>= 0.18), no region point negative: the sign rule; under
    a stencil where the data read -0.15 (not excluded) it is the null rule there instead,
    and no rule holds under both."""
    an = {"data": -0.2, "se": 0.06, "model": 0.05}
    wall, reg = _wall(-0.2, se=0.06)
    sc = _scan(-0.2, 0.06, {"analysis": an, "wall": wall}, {"wall": reg})
    call, rule = ss.wall_rule(sc)
    assert (call, rule.split(":")[0]) == ("refuted", "sign rule")
    wall, reg = _wall(-0.15, se=0.06)
    sc = _scan(-0.2, 0.06, {"analysis": an, "wall": wall}, {"wall": reg})
    assert ss.wall_rule(sc) == (
        "undecided",
        "depends on the stencil or u's error model: the null rule holds under wall but not "
        "analysis; the sign rule holds under analysis but not wall",
    )


def test_a_stencil_without_its_null_is_named():
    an = {"data": -0.1, "se": 0.04, "model": 0.05}
    sc = _scan(-0.1, 0.04, {"analysis": an, "wall": _wall(-0.1)[0]})  # no region for 'wall'
    call, rule = ss.wall_rule(sc)
    assert call == "refuted"
    assert rule.endswith("under every stencil (judged under the analysis' stencil alone)")
    assert ss.rules_line(sc).endswith("; not judged under wall (no null)")


# ------------------------------------------------------------------- the 95% region
def _bowl():
    """Delta chi^2 = 2 (K - 2)^2 + 2 (ln L - 2)^2 on K = 0..4, ln L = 0..4."""
    K = np.arange(5.0)
    lnL = np.arange(5.0)
    return K, np.exp(lnL), 2.0 * (K[:, None] - 2.0) ** 2 + 2.0 * (lnL[None, :] - 2.0) ** 2


def test_the_region_extends_to_the_interpolated_threshold():
    """Threshold 3: inside are (2, 2) and its four neighbours (Delta chi^2 2); the next points
    out have 8, so the crossing is 1/6 of a step beyond: K 5/6 to 19/6, ln L the same."""
    K, L, d = _bowl()
    ext = ss.region_extent([(K, L, d, "range")], 3.0)
    assert ext["points"] == 5
    assert ext["K"] == pytest.approx([5.0 / 6.0, 19.0 / 6.0])
    assert ext["L"] == pytest.approx([math.exp(5.0 / 6.0), math.exp(19.0 / 6.0)])
    assert ext["K_bounds"] == ["data", "data"] and ext["L_bounds"] == ["data", "data"]
    assert ss.region_text(ext) == "K 0.833-3.17, L 2.3-23.7 d"


def test_where_the_model_has_no_solution_the_limit_is_its_existence():
    K, L, d = _bowl()
    d[3:, :] = np.inf  # no solution at K >= 3
    ext = ss.region_extent([(K, L, d, "range")], 3.0)
    assert ext["K"] == pytest.approx([5.0 / 6.0, 2.0])
    assert ext["K_bounds"] == ["data", "existence"]
    assert ss.region_text(ext) == (
        "K 0.833-2, L 2.3-23.7 d (K's upper limit is the model's existence bound (no solution "
        "beyond it on the grid), not the data's)"
    )
    # a region on the grid's edge: that edge limits it
    ext = ss.region_extent([(K, L, d, "range")], 9.0)
    assert ext["K"][0] == 0.0 and ext["K_bounds"][0] == "range"
    assert "K's lower limit is the declared range's bound" in ss.region_text(ext)


def test_the_region_rejects_bad_grids_in_one_line():
    K, L, d = _bowl()
    assert ss.region_extent([(K, L, d, "range")], 1.0) is not None
    assert ss.region_extent([(K, L, d + 10.0, "range")], 1.0) is None
    assert ss.region_text(None) == "no grid point inside"
    with pytest.raises(ParameterError, match=r"must be \(K, L\) = \(5, 4\); got \(5, 5\)"):
        ss.region_extent([(K, L[:4], d, "range")], 3.0)
    with pytest.raises(ParameterError, match="threshold must be finite and > 0; got nan"):
        ss.region_extent([(K, L, d, "range")], math.nan)
    with pytest.raises(ParameterError, match="the grid's L must be > 0"):
        ss.region_extent([(K, -L, d, "range")], 3.0)


def test_the_hand_scan_region_is_its_admissible_points_and_crossings():
    """The hand scan's region: (K 0, L 1) and (K 0, L 2) inside (Delta chi^2 0 and 1); K 1 has
    100, so K's upper end is 0 + (PPF - 0)/(100 - 0) = 0.0599 at L 1; the grid's K 0 is the
    declared range's edge."""
    sc = _scan(-0.1, 0.04)
    ext = ss.scan_region(sc)
    assert ext["K"] == pytest.approx([0.0, PPF / 100.0])
    assert ext["K_bounds"] == ["range", "data"]
    assert ext["L_bounds"] == ["range", "range"]


def test_a_grid_point_below_the_optimum_is_warned():
    """The hand scan's grid with (K 1, L 2) at chi^2 2 below the joint fit's: the optimum is a
    local one, which the evidence says; a point 0.005 below (round-off) is not reported."""
    sc = _scan(-0.1, 0.04)
    assert ss.below_optimum(sc) is None
    sc.chi2[1, 1] = sc.chi2_min - 2.0
    assert ss.below_optimum(sc) == {"K": 1.0, "L": 2.0, "delta_chi2": -2.0}
    assert ss._below_text(sc) == (
        "; WARNING: the grid point K = 1, L = 2 d has chi^2 2 below the joint fit's optimum, "
        "which is a local one"
    )
    sc.chi2[1, 1] = sc.chi2_min - 0.005
    assert ss.below_optimum(sc) is None


def test_what_the_refutation_rests_on_names_an_unsteady_run(monkeypatch):
    monkeypatch.setattr(ss, "wall_rule", lambda sc: ("refuted", "size rule: best fit - data"))
    steady = SimpleNamespace(run="a", wall_k={}, steadiness="steady")
    shaky = SimpleNamespace(run="b", wall_k={}, steadiness="not steady")
    assert ss._rests_on([steady, shaky]).endswith(
        "(over chi^2/dof); b fails the steadiness test, which does not make the verdict firm on "
        "its own."
    )
