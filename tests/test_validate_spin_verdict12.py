"""The spin verdict after referee round 12: the first layer grain by grain (the sidecar's
``first_layer`` record) against the joint fit's null measured the same way, where the u-only
mu(I) velocity alone reproduces the first bins, and every Monte Carlo p with its exceedances
and draws (point 7). Every input is small and every expected number is worked by hand."""

from __future__ import annotations

import math
import re

import numpy as np
import pytest

from cosserat.studies.validate import WallSpin, spin_verdict
from cosserat.studies.validate.measures import JOINT_NULL_SOURCE
from cosserat.studies.validate.verdicts import (
    GRAIN_WOULD_CHANGE,
    T_SAMPLES,
    SpinRun,
    grain_rows,
    grain_text,
    mc_error,
    mc_line,
    mc_p_text,
    pooled_t_count,
    pooled_t_p,
    u_only_reproduces,
    u_only_text,
)

DIST = np.array([0.5, 1.5, 2.5])


def moving(run, dep, se, null, mui=None):
    """A sheared moving wall, departures ``dep`` +- ``se`` against the joint fit's null, the
    u-only mu(I) velocity's departures ``mui`` where given."""
    return WallSpin(run, "moving", True, DIST, np.asarray(dep, float), np.asarray(se, float),
                    predicted={} if mui is None else {"mui": np.asarray(mui, float)},
                    null=np.asarray(null, float), null_model="",
                    null_source=JOINT_NULL_SOURCE, blocks=10)  # fmt: skip


def grains(wall_second, layers, wall_first, se=0.02):
    """A sidecar record at the moving wall: the three departures with one se."""
    out = {"d_1": 0.56, "grains_1": 27.8, "u_1": 0.489, "u_1_se": 0.032, "u_2": 0.301,
           "u_2_se": 0.029, "omega_1": -0.216, "omega_1_se": 0.026, "rolling": 0.206,
           "rolling_se": 0.022}  # fmt: skip
    for key, v in (("W_wall_second", wall_second), ("W_layers", layers),
                   ("W_wall_first", wall_first)):  # fmt: skip
        out[f"departure_{key}"] = v
        out[f"departure_{key}_se"] = se
    return out


NULL = {"departure_W_wall_second": 0.006, "departure_W_layers": -0.059,
        "departure_W_wall_first": 0.136}  # fmt: skip
DEP, SE, BIN_NULL = [-0.30, 0.048, 0.0], [0.03, 0.008, 0.01], [-0.04, 0.008, 0.0]


def test_the_grain_scale_departures_beyond_the_null_and_their_counts():
    """Run a: wall-to-layer-2 +0.016 against +0.006 (beyond +0.010, +0.5 se: turns with the
    material), layers -0.116 against -0.059 (-0.057, -2.85 se: below), wall-to-layer-1 +0.240
    against +0.136 (+0.104, +5.2 se: above): a's sign follows the measure. Run b: +0.056
    (+2.5 se above), -0.049 (+0.5 se), +0.146 (+0.5 se). The wall-to-layer-2 chord has the
    smallest mean |null| (0.006) and comes first."""
    walls = [moving("a", DEP, SE, BIN_NULL), moving("b", DEP, SE, BIN_NULL)]
    info = {"a": SpinRun(grains=grains(0.016, -0.116, 0.240), grains_null=NULL),
            "b": SpinRun(grains=grains(0.056, -0.049, 0.146), grains_null=NULL)}  # fmt: skip
    rows = grain_rows(walls, info)
    a = rows["a"]["measures"]
    assert a["W_wall_second"]["beyond"] == pytest.approx(0.010, abs=1e-12)
    assert a["W_wall_second"]["z"] == pytest.approx(0.5, abs=1e-9)
    assert a["W_layers"]["z"] == pytest.approx(-2.85, abs=1e-9)
    assert a["W_wall_first"]["z"] == pytest.approx(5.2, abs=1e-9)
    text, counts = grain_text(rows)
    assert counts["smallest_null"] == "W_wall_second"
    per = counts["per_measure"]
    assert per["W_wall_second"] == {"walls": 2, "turns_with_the_material": 1, "below": 0,
                                    "above": 1, "mean_abs_null": 0.006}  # fmt: skip
    assert (per["W_layers"]["below"], per["W_layers"]["turns_with_the_material"]) == (1, 1)
    assert counts["walls_where_the_sign_follows_the_measure"] == 1
    assert text.startswith(" Against the joint fit's null, measured grain by grain (the sidecars' "
                           "first_layer")  # fmt: skip
    assert "a (layer 1 at 0.56 d, 28 grains, u_1 +0.489 +- 0.032, u_2 +0.301 +- 0.029" in text
    assert "wall-to-layer-2 +0.016 +- 0.02 (null +0.006, +0.5 se)" in text
    assert (
        "So against the wall-to-layer-2 chord (the measure whose null is smallest) the first "
        "layer turns with the material (within 2 se of the null) at 1 of 2 moving walls, "
        "departs above it at 1; against the layer-1-to-2 chord the first layer turns with the "
        "material (within 2 se of the null) at 1 of 2 moving walls, departs below it at 1"
    ) in text
    assert text.endswith("at 1 of 2 walls the first layer lies beyond the null with opposite "
                         "signs under two measures: its sign at the grain scale is the "
                         "measure's.")  # fmt: skip


def test_a_first_layer_below_the_null_under_every_measure():
    """Run c: -0.10, -0.20, 0.00 against the nulls +0.006, -0.059, +0.136: beyond them by
    -0.106, -0.141, -0.136 (-5.3, -7.05, -6.8 se), below under all three; the null's layer
    velocities are named."""
    walls = [moving("c", DEP, SE, BIN_NULL)]
    null = {**NULL, "u_1": 0.64, "u_2": 0.31}
    rows = grain_rows(walls, {"c": SpinRun(grains=grains(-0.10, -0.20, 0.0), grains_null=null)})
    assert rows["c"]["null_u"] == [0.64, 0.31]
    text, counts = grain_text(rows)
    assert counts["walls_one_sign_under_every_measure"] == {"below": 1, "above": 0}
    assert counts["walls_where_the_sign_follows_the_measure"] == 0
    assert "rolling fraction +0.206 +- 0.022, the null's layers u_1 +0.64, u_2 +0.31)" in text
    assert text.endswith("; the first layer lies below the null under all three measures (by "
                         "at least 2 se each) at 1 of 1 walls.")  # fmt: skip


def test_without_a_record_or_a_null():
    """A run without the record gives no row; one without a joint fit is taken against 0 and
    says so; no rows, no paragraph."""
    walls = [moving("a", DEP, SE, BIN_NULL), moving("b", DEP, SE, BIN_NULL)]
    rows = grain_rows(walls, {"a": SpinRun(grains=grains(0.016, -0.116, 0.24)), "b": SpinRun()})
    assert list(rows) == ["a"] and rows["a"]["measures"]["W_layers"]["null"] is None
    assert rows["a"]["measures"]["W_layers"]["z"] == pytest.approx(-5.8)
    text, counts = grain_text(rows)
    assert "layer-1-to-2 -0.116 +- 0.02 (no null: against 0, -5.8 se)" in text
    assert counts["smallest_null"] is None
    assert grain_text({}) == ("", {})


def test_where_the_u_only_mui_velocity_reproduces_the_first_bins():
    """Run a: first layer -0.26 +- 0.045 against mu(I)'s -0.261 (within 2 se), bin 2 +0.087
    +- 0.026 against -0.01 (3.7 se: not): the first layer only. Run b: -0.329 +- 0.034 against
    -0.30 and +0.084 +- 0.021 against +0.06: both bins. Run c: -0.2 against +0.1: none. Its u
    misfit chi^2 = 176/18 at b: p = 1.1e-27 (chi2.sf(176, 18)), rejected."""
    from scipy.stats import chi2

    walls = [moving("a", [-0.26, 0.087, 0.0], [0.045, 0.026, 0.01], BIN_NULL,
                    mui=[-0.261, -0.01, 0.0]),
             moving("b", [-0.329, 0.084, 0.0], [0.034, 0.021, 0.01], BIN_NULL,
                    mui=[-0.30, 0.06, 0.0]),
             moving("c", [-0.2, 0.0, 0.0], [0.02, 0.01, 0.01], BIN_NULL,
                    mui=[0.1, 0.0, 0.0])]  # fmt: skip
    info = {"a": SpinRun(u_only=(("mui", 16.0, 8),)), "b": SpinRun(u_only=(("mui", 176.0, 18),))}
    rows = u_only_reproduces(walls, info)
    assert set(rows) == {"a", "b"}
    assert rows["a"]["bins"] == 1 and rows["b"]["bins"] == 2
    assert rows["b"]["model"] == [-0.30, 0.06] and rows["b"]["chi2"] == 176.0
    text = u_only_text(rows, 3)
    p_b = float(chi2.sf(176.0, 18))
    assert text == (
        " The u-only mu(I) velocity, its grains turning with the material (the spin equal to "
        "half its vorticity) and measured as the data, reproduces (within 2 se) the "
        "first-layer departure at a (-0.26; the velocity's -0.26) and the first two bins at b "
        "(-0.33, +0.084; the velocity's -0.3, +0.06); that velocity's fit to u there: chi^2 = "
        f"16/8 (p = {float(chi2.sf(16.0, 8)):.2g}) at a; chi^2 = 176/18 (p = {p_b:.2g}, "
        "rejected) at b. At a the first-layer departure is absorbed by a velocity u accepts "
        f"(p = {float(chi2.sf(16.0, 8)):.2g}); it is not the verdict's null because the "
        "verdict's null is the velocity of the joint fit to u, omega and the stress ratio "
        "together."
    )
    assert u_only_text({}, 3).endswith("reproduces the first-layer departure at none of the 3 "
                                       "moving walls.")  # fmt: skip


def test_the_monte_carlo_p_carries_its_count_and_draws():
    """p = (count + 1) / (draws + 1) is pooled_t_p's value; the relative MC error is
    sqrt((1 - p) / (count + 1)): 189 exceedances in 200,000 give p = 190/200,001 = 0.00095
    and an error of 7.3%, within twice of which 0.001 lies (|0.00095 - 0.001| = 5e-5 < 2 x
    7.3% x 0.00095 = 1.4e-4)."""
    count, draws = pooled_t_count(20.0, 6, 10)
    assert draws == T_SAMPLES
    assert pooled_t_p(20.0, 6, 10) == (count + 1) / (draws + 1)
    assert pooled_t_count(None, 6, 10) is None and pooled_t_count(20.0, 6, 1) is None
    p = 190 / 200_001
    assert mc_error(189, 200_000) == pytest.approx(math.sqrt((1 - p) / 190), rel=1e-12)
    assert mc_p_text(p, 189, 200_000) == (
        "p = 0.00095 (189 of 200,000 draws at or above, MC error +-7.3%)"
    )
    assert mc_line(p, (189, 200_000), "Without the first layers") == (
        " Without the first layers p ~ 0.001 (0.00095: 189 of 200,000 draws at or above, MC "
        "error +-7.3%), at the 0.001 line within twice its Monte Carlo error."
    )
    assert "below the 0.001 line beyond twice" in mc_line(1e-4, (19, 200_000), "X")
    assert mc_line(None, None, "X") == ""


def test_the_monte_carlo_sums_carried_on_are_those_drawn_afresh():
    """Sums over fewer bins are carried on to more bins from the generator's state
    (verdicts._t_sums): in any order of asking, each sum equals the one drawn afresh from the
    seed, column by column, to the last bit, and so does every count."""
    from cosserat.studies.validate import verdicts

    def fresh(dof, blocks, samples):
        rng = np.random.default_rng(verdicts.T_SEED)
        total = np.zeros(samples)
        for _ in range(dof):
            total += rng.f(1.0, blocks - 1.0, size=samples)
        return total

    verdicts._T_KEPT.clear()
    for dof, blocks in [(3, 10), (7, 10), (5, 10), (7, 10), (2, 4), (9, 4), (12, 10), (1, 10)]:
        got = verdicts._t_sums(dof, blocks, 5000)
        assert np.array_equal(got, fresh(dof, blocks, 5000)), (dof, blocks)
        assert not got.flags.writeable
        want = int(np.count_nonzero(fresh(dof, blocks, 5000) >= 1.5 * dof))
        assert pooled_t_count(1.5 * dof, dof, blocks, 5000) == (want, 5000)
    assert len(verdicts._T_KEPT) <= verdicts._T_KEEP
    verdicts._T_KEPT.clear()


def test_the_verdict_states_the_grain_scale_evidence_and_the_mc_counts():
    """Two runs with records: the evidence carries the paragraph and the u-only sentence,
    results.json's numbers the grain rows, the counts and every MC count and draws beside
    its p, and "What would change it" names the grain-scale reading before more seeds."""
    walls = [moving(r, DEP, SE, BIN_NULL, mui=[-0.30, 0.1, 0.0]) for r in "ab"]
    info = {r: SpinRun(grains=grains(0.016, -0.116, 0.240), grains_null=NULL,
                       u_only=(("mui", 176.0, 18),)) for r in "ab"}  # fmt: skip
    v = spin_verdict(walls, runs_info=info)
    n = v.numbers
    assert n["pooled_p_headline"] == (n["pooled_p_headline_count"] + 1) / (
        n["pooled_p_headline_draws"] + 1
    )
    assert n["pooled_p_headline_draws"] == T_SAMPLES
    c, d = n["pooled_p_t_without_first_layer_count"], n["pooled_p_t_without_first_layer_draws"]
    assert n["pooled_p_t_without_first_layer"] == (c + 1) / (d + 1)
    assert n["pooled_p_headline_mc_error"] == pytest.approx(
        mc_error(n["pooled_p_headline_count"], T_SAMPLES)
    )
    assert set(n["grain_scale"]["walls"]) == {"a", "b"}
    assert n["grain_scale"]["per_measure"]["W_wall_second"]["turns_with_the_material"] == 2
    assert set(n["u_only_mui_reproduces"]) == {"a", "b"}
    assert "Against the joint fit's null, measured grain by grain" in v.evidence
    assert "The u-only mu(I) velocity" in v.evidence
    assert re.search(
        r"p = \S+ \(\d+ of 200,000 draws at or above, MC error \+-\S+%\) with bins read "
        r"under t\(9\)",
        v.evidence,
    )
    assert v.would_change.startswith(GRAIN_WOULD_CHANGE)
    assert v.would_change.index("grain-scale") < v.would_change.index("more seeds")
    # without records: no paragraph, and "What would change it" as before
    bare = spin_verdict(walls)
    assert "Against the joint fit's null, measured grain by grain" not in bare.evidence
    assert bare.numbers["grain_scale"] is None
    assert not bare.would_change.startswith("the grain-scale")


def test_the_shipped_sidecars_carry_the_grain_record_the_verdict_reads():
    """study.spin_runs on the stored sidecars: each plane run's moving (upper) wall record
    is its SpinRun.grains, read without a "keys outside the format" note; the rough H10 run's
    numbers are those of docs/dem.md's grain table (wall to layer 2 +0.016 +- 0.021)."""
    from dataclasses import replace
    from pathlib import Path
    from types import SimpleNamespace

    from cosserat.analysis.corpus import read_run
    from cosserat.studies.validate.study import spin_runs

    data = Path(__file__).resolve().parents[1] / "data" / "dem_v2"
    names = ["plane_rough_H10_qs", "plane_smooth_H20_qs", "plane_layer_H10_qs"]
    runs = [replace(read_run(data / n / "profile.csv"), name=n) for n in names]
    assert not any("outside the format" in note for r in runs for note in r.notes)
    info = spin_runs([SimpleNamespace(run=r, inertial_number=4e-4, layer=None) for r in runs])
    for r in runs:
        assert info[r.name].grains == r.meta["first_layer"]["walls"]["upper"]
        assert info[r.name].grains_null is None and info[r.name].u_only == ()
    g = info["plane_rough_H10_qs"].grains
    assert g["departure_W_wall_second"] == pytest.approx(0.0165, abs=5e-5)
    assert g["departure_W_wall_second_se"] == pytest.approx(0.0208, abs=5e-5)
    # the layer run's smooth fixed wall shears (layer 1 at 0.45 V): it is recorded too, and
    # is the run's SpinRun.fixed_grains (read model-free, referee 14, point 2); the gravity
    # runs' fixed walls do not shear and have none
    assert set(runs[2].meta["first_layer"]["walls"]) == {"lower", "upper"}
    assert info["plane_layer_H10_qs"].fixed_grains == runs[2].meta["first_layer"]["walls"]["lower"]
    assert info["plane_layer_H10_qs"].fixed_grains["u_1"] == pytest.approx(0.45, abs=0.005)
    assert info["plane_rough_H10_qs"].fixed_grains is None
    assert info["plane_smooth_H20_qs"].joint_basins == ""  # not scanned here


def test_the_grain_scale_null_of_a_model_velocity():
    """forward.grain_layers: u = 1 - g d from the moving upper wall (y = H - d), grains
    turning with it (omega = -(1/2) du/dy = -g/2): the layer averages are u(0.5), u(1.5), so
    every W is -g/2 and every departure 0; a wall slipping by D = 0.2 (u = 0.8 - g d) adds
    +D/(2 x 1.5) and +D/(2 x 0.5) to the wall measures and nothing to W_layers; a Couette
    run has none."""
    from types import SimpleNamespace

    from cosserat.studies.validate.forward import ModelFields, grain_layers

    g, H = 0.1, 10.0
    run = SimpleNamespace(cell="plane", moving_wall="upper", gap_d=H)

    def fields(slip):
        return ModelFields(lambda y: 1.0 - slip - g * (H - np.asarray(y)),
                           lambda y: np.full_like(np.asarray(y, float), -0.5 * g),
                           lambda y: np.zeros_like(np.asarray(y, float)))  # fmt: skip

    m = grain_layers(fields(0.0), run, 0.5)
    assert (m["u_1"], m["u_2"]) == pytest.approx((1.0 - 0.05, 1.0 - 0.15), abs=1e-12)
    for w in ("W_layers", "W_wall_second", "W_wall_first"):
        assert m[w] == pytest.approx(-0.5 * g, abs=1e-12)
        assert m[f"departure_{w}"] == pytest.approx(0.0, abs=1e-12)
    s = grain_layers(fields(0.2), run, 0.5)
    assert s["departure_W_layers"] == pytest.approx(0.0, abs=1e-12)
    assert s["departure_W_wall_second"] == pytest.approx(0.2 / 3.0, abs=1e-12)
    assert s["departure_W_wall_first"] == pytest.approx(0.2, abs=1e-12)
    assert grain_layers(fields(0.0), SimpleNamespace(cell="couette"), 0.5) is None
