"""The spin verdict after referee round 14, point 2: the model-free reading with its
independent-error bound beside the block-correlated se, the sheared fixed walls' records
(matched to an exponential that tends to the moving wall's velocity), and the model-free
sentence leading the evidence. Every expected number is worked in closed form."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import quad

from cosserat.dem.first_layer import layer_measures
from cosserat.studies.validate import WallSpin, spin_verdict
from cosserat.studies.validate.measures import JOINT_NULL_SOURCE
from cosserat.studies.validate.verdicts import (
    SpinRun,
    fixed_rows,
    free_lead,
    free_rows,
    free_text,
    matched_exponential,
    matched_ratio_se,
)

DIST = np.array([0.5, 1.5, 2.5])
LN2 = math.log(2.0)


def wall(run, role, dep, se, null=None, no_null=""):
    return WallSpin(run, role, True, DIST, np.asarray(dep, float), np.asarray(se, float),
                    null=None if null is None else np.asarray(null, float), null_model="",
                    null_source=JOINT_NULL_SOURCE if null is not None else "",
                    no_null=no_null, blocks=10)  # fmt: skip


def record(u_1, u_2, omega_1, s, se_o, se_w, se_d, moving=True):
    """A first_layer record with layers 1 d apart: W_layers = -(s/2)(u_2 - u_1)."""
    w = -0.5 * s * (u_2 - u_1)
    return {"moving": moving, "d_1": 0.5, "grains_1": 28.0, "u_1": u_1, "u_1_se": 0.01,
            "u_2": u_2, "u_2_se": 0.01, "omega_1": omega_1, "omega_1_se": se_o,
            "W_layers": w, "W_layers_se": se_w, "departure_W_layers": omega_1 - w,
            "departure_W_layers_se": se_d, "departure_W_wall_second": 0.0,
            "departure_W_wall_second_se": 0.02, "rolling": 0.3,
            "rolling_se": 0.03}  # fmt: skip


def test_the_matched_exponential_tends_to_the_far_walls_velocity():
    """At a lower fixed wall (s = +1) facing a moving one, u_1 = 0.6, u_2 = 0.8: with u_far =
    1, q = 0.2/0.4 = 1/2, l = 1/ln 2, A = -0.4/(l/2) = -0.8 ln 2; its layer means are u_1 and
    u_2, its layer-1 spin (1/2)(u_1 - 1)/l = -0.2 ln 2, W_layers = -(1/2)(0.2) = -0.1, ratio
    2 ln 2, as first_layer's layer_measures gives; with u_far = 0 the velocity rises away from
    the wall and no decaying exponential matches."""
    m = matched_exponential(0.6, 0.8, 1.0, 1.0)
    assert m is not None
    assert m["l"] == pytest.approx(1.0 / LN2, rel=1e-12)
    assert m["A"] == pytest.approx(-0.8 * LN2, rel=1e-12)
    assert m["omega_1"] == pytest.approx(-0.2 * LN2, rel=1e-12)
    assert m["W_layers"] == pytest.approx(-0.1, rel=1e-12)
    assert m["ratio"] == pytest.approx(2.0 * LN2, rel=1e-12)

    def u(d):
        return 1.0 + m["A"] * math.exp(-d / m["l"])

    assert quad(u, 0.0, 1.0)[0] == pytest.approx(0.6, rel=1e-10)
    assert quad(u, 1.0, 2.0)[0] == pytest.approx(0.8, rel=1e-10)
    om = quad(lambda d: -0.5 * -m["A"] / m["l"] * math.exp(-d / m["l"]), 0.0, 1.0)[0]
    assert om == pytest.approx(m["omega_1"], rel=1e-10)
    ref = layer_measures("lower", 0.0, 0.6, 0.8, 0.5, 1.5, om, 0.5)
    assert ref["departure_W_layers"] == pytest.approx(m["departure"], rel=1e-10)
    assert matched_exponential(0.6, 0.8, 1.0) is None


def test_the_matched_ratios_se_is_the_linear_propagation():
    """R = -ln q/(1 - q) with q = (u_2 - u_far)/(u_1 - u_far): matched_ratio_se is |dR/dq| se_q
    with se_q = sqrt(se_2^2 + q^2 se_1^2)/|u_1 - u_far|, and agrees with a central difference
    of matched_exponential's ratio in u_1 and u_2 separately; None where nothing matches."""
    u_1, u_2, far, se_1, se_2 = 0.6, 0.75, 1.0, 0.03, 0.02

    def big_r(a, b):
        m = matched_exponential(a, b, 1.0, far)
        assert m is not None
        return m["ratio"]

    h = 1e-6
    d_1 = (big_r(u_1 + h, u_2) - big_r(u_1 - h, u_2)) / (2 * h)
    d_2 = (big_r(u_1, u_2 + h) - big_r(u_1, u_2 - h)) / (2 * h)
    se = matched_ratio_se(u_1, se_1, u_2, se_2, far)
    assert se == pytest.approx(math.hypot(d_1 * se_1, d_2 * se_2), rel=1e-6)
    assert matched_ratio_se(0.6, 0.01, 0.8, 0.01) is None
    assert matched_ratio_se(0.4, math.nan, 0.2, 0.01) is None


def test_the_bound_beside_the_block_correlated_se():
    """Upper moving wall, u_1 = 0.4, u_2 = 0.2 (R = 2 ln 2), omega_1 = -0.3, W_layers = -0.1:
    beyond = -0.3 + 0.2 ln 2. se_omega 0.02, se_W 0.01 and the departure's se 0.015 imply
    rho = (4e-4 + 1e-4 - 2.25e-4)/(2 x 0.02 x 0.01) = 0.6875; the se of omega_1 - R W is
    sqrt(4e-4 + R^2 1e-4 - 2 R rho 2e-4), the bound's sqrt(4e-4 + R^2 1e-4)."""
    g = record(0.4, 0.2, -0.3, -1.0, 0.02, 0.01, 0.015)
    rows = {"a": {**g, "wall": "moving", "measures": {
        "W_layers": {"departure": g["departure_W_layers"], "se": 0.015}}}}  # fmt: skip
    r = free_rows(rows)["a"]
    big_r = 2.0 * LN2
    beyond = -0.3 + 0.2 * LN2
    assert r["beyond"] == pytest.approx(beyond, rel=1e-12)
    assert r["rho"] == pytest.approx(0.6875, rel=1e-12)
    se = math.sqrt(4e-4 + big_r**2 * 1e-4 - 2.0 * big_r * 0.6875 * 2e-4)
    assert r["se"] == pytest.approx(se, rel=1e-12)
    assert r["z"] == pytest.approx(beyond / se, rel=1e-12)
    fixed_r = math.sqrt(4e-4 + big_r**2 * 1e-4)
    assert r["se_independent_fixed_R"] == pytest.approx(fixed_r, rel=1e-12)
    assert r["z_independent_fixed_R"] == pytest.approx(beyond / fixed_r, rel=1e-12)
    # referee 15, point 3(i): R's own error, u_1_se = u_2_se = 0.01, q = 1/2
    se_big_r = 4.0 * (1.0 - LN2) * math.sqrt(1e-4 + 0.25e-4) / 0.4
    assert r["matched"]["ratio_se"] == pytest.approx(se_big_r, rel=1e-12)
    bound = math.sqrt(fixed_r**2 + (0.1 * se_big_r) ** 2)
    assert r["se_independent"] == pytest.approx(bound, rel=1e-12)
    assert r["z_independent"] == pytest.approx(beyond / bound, rel=1e-12)
    text, counts = free_text(free_rows(rows))
    assert f"the data beyond it by {beyond:+.3g}, {beyond / se:+.2g} se " in text
    assert f"({beyond / bound:+.2g} under independent errors)" in text
    assert counts["beyond_independent"] == 1 and counts["walls_with_independent_bound"] == 1


def test_a_sheared_fixed_wall_is_read_model_free_and_the_sentence_leads():
    """Runs a, b: a moving wall against the joint fit's null and a record (omega_1 = -0.3 ->
    ratio 3, beyond -0.3 + 0.2 ln 2 = -0.161); run c: a layer run's lower fixed wall, not
    judged (no fit describes it), whose record (u_1 0.6, u_2 0.8, omega_1 = -0.25: ratio 2.5,
    R = 2 ln 2, beyond -0.25 + 0.2 ln 2 = -0.111) is read model-free. The evidence opens with
    the model-free sentence over the three sheared walls."""
    walls = [wall(r, "moving", [-0.30, 0.048, 0.0], [0.03, 0.008, 0.01], [-0.04, 0.008, 0.0])
             for r in "ab"]  # fmt: skip
    walls.append(wall("c", "fixed", [-0.2, 0.05, 0.0], [0.04, 0.02, 0.01],
                      no_null="no fit describes it"))  # fmt: skip
    info = {r: SpinRun(grains=record(0.4, 0.2, -0.3, -1.0, 0.02, 0.01, 0.015)) for r in "ab"}
    info["c"] = SpinRun(fixed_grains=record(0.6, 0.8, -0.25, 1.0, 0.02, 0.01, 0.015, False))
    fixed = fixed_rows(walls, info)
    assert set(fixed) == {"c:fixed"} and fixed["c:fixed"]["wall"] == "fixed"
    assert fixed_rows(walls[:2], info) == {}
    v = spin_verdict(walls, runs_info=info)
    free = v.numbers["grain_scale_model_free"]
    assert set(free["walls"]) == {"a", "b", "c:fixed"}
    c = free["walls"]["c:fixed"]
    assert c["ratio"] == pytest.approx(2.5, rel=1e-12)
    assert c["matched"]["ratio"] == pytest.approx(2.0 * LN2, rel=1e-12)
    assert c["beyond"] == pytest.approx(-0.25 + 0.2 * LN2, rel=1e-12)
    assert free["moving_walls"] == 2 and free["fixed_walls"] == 1
    se_q = math.sqrt(1e-4 + 0.25e-4) / 0.4  # q = 1/2 at both walls (u_far 0 and 1)
    bound = math.sqrt(4e-4 + (2.0 * LN2) ** 2 * 1e-4 + (0.1 * 4.0 * (1.0 - LN2) * se_q) ** 2)
    za, zc = (0.2 * LN2 - 0.3) / bound, (0.2 * LN2 - 0.25) / bound
    lead = free_lead(free["walls"])
    assert v.evidence.startswith(lead)
    assert lead == (
        "Model-free, grain by grain: layer 1 turns 3 times the half vorticity between layers "
        "1 and 2 at 2 of 2 moving walls; 2.5 times the half vorticity between layers 1 and 2 "
        "at 1 of 1 sheared fixed walls; a velocity matched to the measured layer means gives "
        f"R = 1.39; the data lie beyond it by {abs(zc):.2g}-{abs(za):.2g} se: beyond 2 se at 3 "
        "of 3 sheared walls (3 by >= 3 se) under independent errors (R's own error from u_1 "
        "and u_2 propagated). "
    )
    assert "plane" not in lead and "c's fixed wall omega_1/W_layers 2.5" in v.evidence
    # a wall within 2 se: the span is of the walls beyond, the other's z said beside it
    # (referee 16, point 3)
    rows = {k: dict(r) for k, r in free["walls"].items()}
    rows["c:fixed"]["z_independent"] = -1.23
    assert (
        f"the data lie beyond it by {abs(za):.2g} se: beyond 2 se at 2 of 3 sheared walls "
        "(2 by >= 3 se; 1.2 se at the other 1) under independent errors"
    ) in free_lead(rows)
    # without records, nothing leads
    assert free_lead({}) == "" and spin_verdict(walls).evidence.startswith("Beyond the null")


def test_the_headline_p_says_it_depends_on_the_joint_fits_basin():
    """Where a run's joint fit has a 95% region of more than one island, the test's pooled p
    carries one clause saying it depends on which basin the fit finds (SpinRun.joint_basins,
    in words from the study); none where no run's has."""
    from cosserat.studies.validate.verdicts import basins_text

    walls = [wall(r, "moving", [-0.30, 0.048, 0.0], [0.03, 0.008, 0.01], [-0.04, 0.008, 0.0])
             for r in "ab"]  # fmt: skip
    where = "K 5.32, L 14.1 d, in one of its 95% region's two islands: K 2.74-2.89, L 3.61-3.77 d"
    info = {"a": SpinRun(), "b": SpinRun(joint_basins=where)}
    clause = (
        "; the pooled p depends on which basin a joint fit with several finds, its velocity "
        f"being the run's null: b's joint fit is at {where}"
    )
    assert basins_text(["a", "b"], info) == clause
    assert clause + ";" in spin_verdict(walls, runs_info=info).evidence
    assert basins_text(["a"], info) == ""
    assert "depends on which basin" not in spin_verdict(walls, runs_info={"a": SpinRun()}).evidence
