"""The spin verdict after referee round 13, point 1: the grain-scale paragraph named for
what it is (against the joint fit's null), the model-free reading beside it (layer 1's spin
over the layer-1-to-2 chord, and a velocity matched to the measured layer means with no model
fit), the consequence where the u-only mu(I) velocity absorbs the first layer and u accepts
it; point 6: a Monte Carlo p within its error of 0.001 reads "p ~ 0.001". Every expected
number is worked in closed form."""

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
    at_the_line,
    free_rows,
    free_text,
    grain_rows,
    matched_exponential,
    mc_line,
    mc_p_text,
    u_only_reproduces,
    u_only_text,
)

DIST = np.array([0.5, 1.5, 2.5])


def moving(run, dep, se, null, mui=None):
    return WallSpin(run, "moving", True, DIST, np.asarray(dep, float), np.asarray(se, float),
                    predicted={} if mui is None else {"mui": np.asarray(mui, float)},
                    null=np.asarray(null, float), null_model="",
                    null_source=JOINT_NULL_SOURCE, blocks=10)  # fmt: skip


def record(u_1, u_2, omega_1, d_1, d_2, wall_second, se=0.02, s=-1.0):
    """A moving-wall record whose W_layers = -(s/2)(u_2 - u_1)/(d_2 - d_1) sets the
    layer-1-to-2 departure omega_1 - W_layers; the wall-to-layer-2 departure is given."""
    w = -0.5 * s * (u_2 - u_1) / (d_2 - d_1)
    return {"d_1": d_1, "grains_1": 28.0, "u_1": u_1, "u_1_se": 0.03, "u_2": u_2,
            "u_2_se": 0.03, "omega_1": omega_1, "omega_1_se": 0.02, "rolling": 0.2,
            "rolling_se": 0.02, "departure_W_layers": omega_1 - w, "departure_W_layers_se": se,
            "departure_W_wall_second": wall_second,
            "departure_W_wall_second_se": se}  # fmt: skip


def test_the_matched_exponential_is_the_closed_form_and_its_own_layer_means():
    """u_1 = 0.4, u_2 = 0.2 (q = 1/2): l = 1/ln 2, A = u_1/(l/2) = 0.8 ln 2; its uniform
    layer means are u_1 and u_2, its spin -(s/2) du/dd averaged over [0, 1) is (s/2) u_1/l
    = -0.2 ln 2 at the upper wall (s = -1), W_layers = -(s/2)(u_2 - u_1) = -0.1 (layers 1 d
    apart), ratio = 2 ln 2 = 1.386, and cosserat.dem.first_layer's layer_measures at 0.5 and
    1.5 d gives the same departure."""
    m = matched_exponential(0.4, 0.2, -1.0)
    assert m is not None
    ln2 = math.log(2.0)
    assert m["l"] == pytest.approx(1.0 / ln2, rel=1e-12)
    assert m["A"] == pytest.approx(0.8 * ln2, rel=1e-12)
    assert m["omega_1"] == pytest.approx(-0.2 * ln2, rel=1e-12)
    assert m["W_layers"] == pytest.approx(-0.1, rel=1e-12)
    assert m["ratio"] == pytest.approx(2.0 * ln2, rel=1e-12)

    def u(d):
        return m["A"] * math.exp(-d / m["l"])

    assert quad(u, 0.0, 1.0)[0] == pytest.approx(0.4, rel=1e-10)
    assert quad(u, 1.0, 2.0)[0] == pytest.approx(0.2, rel=1e-10)
    om = quad(lambda d: 0.5 * m["A"] / m["l"] * math.exp(-d / m["l"]) * -1.0, 0.0, 1.0)[0]
    assert om == pytest.approx(m["omega_1"], rel=1e-10)
    ref = layer_measures("upper", 1.0, 0.4, 0.2, 0.5, 1.5, om, 0.5)
    assert ref["departure_W_layers"] == pytest.approx(m["departure"], rel=1e-10)
    # the lower wall: the same magnitudes, the spin's sign flipped
    low = matched_exponential(0.4, 0.2, 1.0)
    assert low is not None and low["departure"] == pytest.approx(-m["departure"], rel=1e-12)
    # no decaying exponential matches a velocity rising away from the wall, or u_1 = 0
    assert matched_exponential(0.2, 0.4, -1.0) is None
    assert matched_exponential(0.0, 0.1, -1.0) is None
    assert matched_exponential(0.4, -0.1, -1.0) is None


def test_the_model_free_reading_of_a_hand_made_record():
    """Run a (upper wall): u_1 = 0.4, u_2 = 0.2 at d = 0.5, 1.5, omega_1 = -0.3: W_layers =
    -0.1, ratio 3; the matched null's departure is -0.2 ln 2 + 0.1 = -0.03863, the data's
    -0.2, beyond it by -0.16137 = -8.07 se (se 0.02); wall-to-layer-2 +0.01 +- 0.02 (+0.5 se).
    Run b: omega_1 = -0.11: ratio 1.1, beyond -0.01 + 0.2 ln 2 - 0.1 = +0.02863 (+1.43 se);
    wall-to-layer-2 -0.05 (-2.5 se)."""
    walls = [moving(r, [-0.3, 0.05, 0.0], [0.03, 0.01, 0.01], [-0.04, 0.0, 0.0]) for r in "ab"]
    info = {"a": SpinRun(grains=record(0.4, 0.2, -0.3, 0.5, 1.5, 0.01)),
            "b": SpinRun(grains=record(0.4, 0.2, -0.11, 0.5, 1.5, -0.05))}  # fmt: skip
    rows = free_rows(grain_rows(walls, info))
    ln2 = math.log(2.0)
    assert rows["a"]["ratio"] == pytest.approx(3.0, rel=1e-12)
    assert rows["a"]["matched"]["ratio"] == pytest.approx(2.0 * ln2, rel=1e-12)
    assert rows["a"]["beyond"] == pytest.approx(-0.2 + 0.2 * ln2 - 0.1, rel=1e-12)
    assert rows["a"]["z"] == pytest.approx((-0.3 + 0.2 * ln2) / 0.02, rel=1e-12)
    assert rows["a"]["wall_second"]["z"] == pytest.approx(0.5, rel=1e-12)
    assert rows["b"]["ratio"] == pytest.approx(1.1, rel=1e-12)
    assert rows["b"]["z"] == pytest.approx((-0.01 + 0.2 * ln2 - 0.1) / 0.02, rel=1e-12)
    assert rows["b"]["beyond"] == pytest.approx(-0.01 - (-0.2 * ln2 + 0.1), rel=1e-12)
    text, counts = free_text(rows)
    assert counts == {"moving_walls": 2, "fixed_walls": 0, "beyond": 1, "beyond_3_se": 1,
                      "beyond_independent": 0, "beyond_3_se_independent": 0,
                      "walls_with_independent_bound": 0, "wall_second_zero": 1,
                      "wall_second_walls": 2}  # fmt: skip
    assert text.startswith(" Model-free, grain by grain (the null: a velocity matched to the "
                           "measured layer means with no model fit")  # fmt: skip
    assert (
        "a omega_1/W_layers 3, the matched velocity's 1.39 (l = 1.4 d), the data beyond "
        "it by -0.161, -8.1 se, raw departure against the wall-to-layer-2 chord +0.01 +- "
        "0.02, +0.5 se"
    ) in text
    assert (
        "So layer 1 turns 3 times faster than the half vorticity between layers 1 and 2 "
        "at 1 of 2 sheared walls (1.1 at b); a velocity matched to the measured layer means "
        "gives 1.39, and the data lie beyond it by at least 2 se at 1 of 2 walls (1 by at "
        "least 3 se): only"
    ) in text
    assert text.endswith("against the wall-to-layer-2 chord the raw departure is 0 within 2 se "
                         "at 1 of 2 walls (the largest |z| 2.5).")  # fmt: skip
    assert free_text({}) == ("", {})


def test_the_verdict_carries_the_model_free_reading():
    """The evidence names the joint-null paragraph for what it is and adds the model-free
    one; results.json's numbers carry its rows and counts."""
    walls = [moving(r, [-0.30, 0.048, 0.0], [0.03, 0.008, 0.01], [-0.04, 0.008, 0.0])
             for r in "ab"]  # fmt: skip
    info = {r: SpinRun(grains=record(0.4, 0.2, -0.3, 0.5, 1.5, 0.01)) for r in "ab"}
    v = spin_verdict(walls, runs_info=info)
    assert "Against the joint fit's null, measured grain by grain" in v.evidence
    assert "Model-free at the grain scale" not in v.evidence
    assert " Model-free, grain by grain (the null: a velocity matched" in v.evidence
    free = v.numbers["grain_scale_model_free"]
    assert free["beyond"] == 2 and set(free["walls"]) == {"a", "b"}
    assert spin_verdict(walls).numbers["grain_scale_model_free"] is None


def test_a_u_only_velocity_that_absorbs_the_first_layer_and_u_accepts():
    """mu(I)'s velocity reproduces the first layer at a; its fit to u is chi^2 = 16/8, p =
    0.042 >= 0.001: the first-layer departure is absorbed by a velocity u accepts, and the
    fit's own stress contradiction is why it is not the null. At b u rejects it (176/18)."""
    from scipy.stats import chi2

    walls = [moving(r, [-0.26, 0.087, 0.0], [0.045, 0.026, 0.01], [-0.04, 0.0, 0.0],
                    mui=[-0.261, -0.01, 0.0]) for r in "ab"]  # fmt: skip
    why = ("contradicts the measured stress: its fitted mu_s = 0.314 exceeds the band's "
           "measured |shear|/normal stress ratio 0.244 +- 0.015 (4 bins) by 4.8 errors, "
           "where mu(I) needs mu >= mu_s to flow")  # fmt: skip
    info = {"a": SpinRun(u_only=(("mui", 16.0, 8),), u_only_contradiction=(("mui", why),)),
            "b": SpinRun(u_only=(("mui", 176.0, 18),))}  # fmt: skip
    rows = u_only_reproduces(walls, info)
    assert rows["a"]["contradiction"] == why and rows["b"]["contradiction"] == ""
    text = u_only_text(rows, 2)
    p = float(chi2.sf(16.0, 8))
    assert text.endswith(
        f" At a the first-layer departure is absorbed by a velocity u accepts (p = {p:.2g}); it "
        "is not the verdict's null because its fitted mu_s = 0.314 exceeds the band's "
        "measured |shear|/normal stress ratio 0.244 +- 0.015 (4 bins) by 4.8 errors, where "
        "mu(I) needs mu >= mu_s to flow."
    )
    assert "At b the first-layer departure is absorbed" not in text


def test_a_monte_carlo_p_at_the_line_reads_about_0_001():
    """197 of 200,000: p = 198/200,001 = 0.00099, MC error sqrt((1 - p)/198) = 7.1%;
    |p - 0.001| = 1e-5 <= 7.1% x 0.00099 = 7e-5: "p ~ 0.001". 14 of 200,000 (p = 7.5e-5) is
    far below it and keeps "p = 7.5e-05"; 300 of 200,000 (p = 0.0015, error 5.8%) is above."""
    p = 198 / 200_001
    assert at_the_line(p, 197, 200_000)
    assert mc_p_text(p, 197, 200_000, line=True) == (
        "p ~ 0.001 (0.00099: 197 of 200,000 draws at or above, MC error +-7.1%)"
    )
    assert mc_p_text(p, 197, 200_000) == (
        "p = 0.00099 (197 of 200,000 draws at or above, MC error +-7.1%)"
    )
    assert not at_the_line(15 / 200_001, 14, 200_000)
    assert mc_p_text(15 / 200_001, 14, 200_000, line=True).startswith("p = 7.5e-05 (14 of")
    assert not at_the_line(301 / 200_001, 300, 200_000)
    assert mc_line(p, (197, 200_000), "Without the first layers").startswith(
        " Without the first layers p ~ 0.001 (0.00099: 197 of"
    )
