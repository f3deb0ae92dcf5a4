"""Same-conditions replicates (one cell, one wall speed, two seeds) compared bin by bin, the
seed-scatter factor, what it does to the static-zone checks, and the Delta design at the
replicates' scatter (referee 12, points 2 and 3)."""

from __future__ import annotations

import math
from dataclasses import replace
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest

from cosserat.analysis.corpus import read_run, write_run
from cosserat.studies.validate.measures import miss_place, wall_bins, y_balance
from cosserat.studies.validate.rate import (
    SE_FLOOR,
    RatePair,
    StaticMiss,
    TwinField,
    TwinPair,
    balance_record,
    balance_rescaled,
    balance_rescaled_text,
    balance_warning,
    misfit_twin_text,
    static_rescaled_text,
    twin_factor,
    twin_names,
    twin_pairs,
)
from cosserat.studies.validate.verdicts import (
    DeltaPoint,
    DeltaSeries,
    delta_law_verdict,
    precision_needed,
    precision_text,
    seed_scatter,
    slope_sigma,
)

DATA = Path(__file__).resolve().parents[1] / "data" / "dem_v2"
SE = 0.01
STATIC = np.array([1e-5] * 5 + [1e-3] * 5)  # I: the five bins nearest the fixed wall static


def _plane(tmp_path, name, *, seed=1, speed=0.0025, shift=None, inertial=STATIC, extra=None):
    """A plane run of 10 bins (centres 0.5 ... 9.5 d from the fixed lower wall, the moving wall
    at 10 d), every field's se 0.01; ``shift`` (column -> added values) moves fields."""
    y = np.arange(10) + 0.5
    cols = {"y": y, "u": np.linspace(0.0, 0.9, 10), "omega": np.zeros(10),
            "half_vorticity": np.zeros(10), "nu": np.full(10, 0.8),
            "sigma_yy": np.full(10, 1.0), "sigma_xx": np.full(10, 1.0),
            "sigma_yx": np.full(10, -0.3),
            "inertial_number": np.asarray(inertial, float)}  # fmt: skip
    for k, v in (shift or {}).items():
        cols[k] = cols[k] + np.asarray(v, float)
    for k in list(cols):
        if k != "y":
            cols[f"{k}_se"] = np.full(10, SE)
    meta = {"cell": "plane", "gap_d": 10.0, "B": 1.0, "wall": {"kind": "glued-grains"},
            "wall_speed": speed, "seed": seed, "grains": {"density": 1.0},
            "wall_stress": {"normal": 1.0, "shear": -0.3, "normal_se": 0.001,
                            "shear_se": 0.01}} | (extra or {})  # fmt: skip
    return read_run(write_run(tmp_path, name, meta, cols))


def _result(run, delta=(None, None)):
    return SimpleNamespace(run=run, thickness=SimpleNamespace(value=delta[0], stderr=delta[1]))


def test_equal_replicates_give_zero_and_a_floor_of_one(tmp_path):
    a, b = _plane(tmp_path, "a"), _plane(tmp_path, "b", seed=2)
    (p,) = twin_pairs([_result(b), _result(a)])
    assert (p.a, p.b, p.seeds) == ("a", "b", (1, 2))  # the lower seed first
    assert set(p.fields) == {"u", "omega", "nu", "sigma_yy", "sigma_xx", "sigma_yx",
                             "stress_ratio"}  # fmt: skip
    for f in p.fields.values():
        assert f.chi2 == 0.0 and f.beyond == [] and f.factor() == 0.0 and f.agrees
    assert twin_factor([p], "nu") == 1.0  # never below 1: one pair does not shrink errors
    assert twin_names([a, b]) == (("a", "b"),)


def test_a_shift_of_three_combined_se_gives_nine_per_bin(tmp_path):
    """nu lower by 3 sqrt(2) se in every bin of seed 2: z = +3 per bin, sum z^2 = 90 on 10,
    factor 3 everywhere, no bin beyond 3 (strictly); sigma_yy lower by 5 sqrt(2) se in the
    first bin only: z = +5 at 0.5 d from the fixed wall, sum 25, factor sqrt(25/5) = 2.24
    in the static zone and 0 in the flowing one; the rate check's rule says it agrees (9 of
    10 within 2 se) while nu does not."""
    shift = 3.0 * math.hypot(SE, SE)
    one = np.zeros(10)
    one[0] = -5.0 * math.hypot(SE, SE)
    a = _plane(tmp_path, "a")
    b = _plane(tmp_path, "b", seed=2, shift={"nu": np.full(10, -shift), "sigma_yy": one})
    (p,) = twin_pairs([_result(a), _result(b)])
    nu, syy = p.fields["nu"], p.fields["sigma_yy"]
    assert nu.z == pytest.approx([3.0] * 10) and nu.chi2 == pytest.approx(90.0)
    assert nu.factor() == pytest.approx(3.0) and nu.factor("static") == pytest.approx(3.0)
    assert nu.beyond == [] and not nu.agrees
    assert syy.chi2 == pytest.approx(25.0) and syy.beyond == [(0.5, pytest.approx(5.0))]
    assert syy.factor("static") == pytest.approx(math.sqrt(5.0))
    assert syy.factor("flowing") == pytest.approx(0.0) and syy.agrees
    assert syy.static == (True,) * 5 + (False,) * 5
    text = p.text()
    assert "Same-conditions replicates: a against b (one cell at V = 0.0025, seed 1 against 2" \
        in text  # fmt: skip
    assert "nu sum z^2 = 90 on 10 bins (largest +3 at 0.5 d)" in text
    assert "sigma_yy sum z^2 = 25 on 10 bins (beyond 3 se: +5 at 0.5 d)" in text
    # referee 17, point 5: beside each factor, the factor without its largest bin
    assert "nu 3.0 (3.0 without the bin at 0.5 d; static zone 3.0, 3.0 without it), sigma_yy " \
        "1.6 (0.0 without the bin at 0.5 d; static zone 2.2, 0.0 without it)" in text  # fmt: skip
    assert syy.without_largest("static") == (pytest.approx(0.0), 0.5)
    assert "So the factors above undercut no verdict's errors." in text
    assert "omega agrees between the seeds (sum z^2 = 0 on 10 bins" in text


def test_only_one_cell_at_one_speed_with_two_seeds_is_a_pair(tmp_path):
    a = _plane(tmp_path, "a")
    same_seed = _plane(tmp_path, "b", seed=1)
    half = _plane(tmp_path, "c", seed=2, speed=0.00125)
    other_gap = _plane(tmp_path, "d", seed=2, extra={"gap_d": 20.0})
    no_seed = replace(_plane(tmp_path, "e", seed=2), meta={**a.meta, "seed": None})
    assert twin_pairs([_result(r) for r in (a, same_seed, half, other_gap, no_seed)]) == []


def test_delta_and_wall_ratio_z_and_the_per_run_scatter(tmp_path):
    """Delta 6.609 +- 0.67 against 5.154 +- 0.53: z = 1.455 / 0.854 = +1.70; per-run scatter
    |ln(6.609 / 5.154)| / sqrt(2) = 0.176."""
    a, b = _plane(tmp_path, "a"), _plane(tmp_path, "b", seed=2)
    (p,) = twin_pairs([_result(a, (6.609, 0.67)), _result(b, (5.154, 0.53))])
    assert p.delta_z == pytest.approx(1.455 / math.hypot(0.67, 0.53))
    assert p.delta_scatter == pytest.approx(math.log(6.609 / 5.154) / math.sqrt(2.0))
    assert p.wall_ratio_z == pytest.approx(0.0)
    assert "Delta 6.61 +- 0.67 against 5.15 +- 0.53 d (z = +1.7)" in p.text()
    d = p.to_dict()
    assert d["delta_z"] == pytest.approx(1.7032, abs=1e-4) and d["fields"]["nu"]["n"] == 10


def test_the_truncated_bin_is_named_and_paired_by_row(tmp_path):
    """The top bins' centres differ by 0.03 d (two slightly different gaps): still one bin,
    named truncated from the sidecar."""
    trunc = {"truncated_bins": {"bins": [{"row": 9, "wall": "upper", "width_d": 0.8}]}}
    shift = np.zeros(10)
    shift[9] = 5.0 * math.hypot(SE, SE)
    a = _plane(tmp_path, "a", extra=trunc)
    b = _plane(tmp_path, "b", seed=2, shift={"sigma_yy": -shift}, extra=trunc)
    cols = dict(b.columns)
    cols["y"] = cols["y"] - np.r_[np.zeros(9), 0.03]
    (p,) = twin_pairs([_result(a), _result(replace(b, columns=cols))])
    assert p.fields["sigma_yy"].truncated[-1]
    assert "(beyond 3 se: +5 at 9.5 d (truncated bin))" in p.text()


def test_the_shipped_twins_give_the_referees_check_e():
    """Referee 12, check (e): plane_rough_H10_qs_s2 against plane_rough_H10_qs, bin by bin."""
    runs = [replace(read_run(DATA / n / "profile.csv"), name=n)
            for n in ("plane_rough_H10_qs", "plane_rough_H10_qs_s2")]  # fmt: skip
    (p,) = twin_pairs([_result(runs[0], (6.609, 0.67)), _result(runs[1], (5.154, 0.53))])
    chi2 = {k: round(f.chi2, 1) for k, f in p.fields.items()}
    assert chi2["u"] == 3.8 and chi2["omega"] == 15.9 and chi2["sigma_yx"] == 19.0
    assert (chi2["nu"], chi2["sigma_yy"], chi2["sigma_xx"]) == (88.5, 92.5, 141.7)
    # seed 1 against seed 2, as the referee quotes them
    assert [(d, round(z, 1)) for d, z in p.fields["nu"].beyond] == [(0.5, -5.7), (1.5, -5.8)]
    xx = [(d, round(z, 1)) for d, z in p.fields["sigma_xx"].beyond]
    assert xx == [(0.5, -10.3), (1.5, -5.2)]
    assert round(p.fields["sigma_yy"].beyond[0][1], 1) == -7.0
    assert round(p.fields["omega"].largest[1], 1) == 2.1
    assert round(p.delta_z, 1) == 1.7 and round(p.wall_ratio_z, 1) == 0.8
    assert p.fields["omega"].agrees and p.fields["stress_ratio"].agrees


def test_static_misses_between_speeds_rescaled_by_the_twins_factor(tmp_path):
    """A rate pair's static misses nu z = -9.9 and sigma_yy z = +4.0 with twins' static
    factors nu 3 and sigma_yy 1 (floored): -3.3 stays beyond 3 se, 4.0 too."""
    shift = 3.0 * math.hypot(SE, SE)
    a, b = _plane(tmp_path, "a"), _plane(tmp_path, "b", seed=2, shift={"nu": np.full(10, shift)})
    twins = twin_pairs([_result(a), _result(b)])
    pair = RatePair("f", "s", (2.0, 1.0), {}, (None, None), (None, None),
                    (StaticMiss("nu", 9.3, -9.9), StaticMiss("sigma_yy", 8.3, 4.0)))  # fmt: skip
    text = static_rescaled_text([pair], twins)
    assert "(a against b: nu 3, sigma_yy 1; from the run's own cell's replicates where" in text
    assert "2 stay beyond 3 se (nu at 9.3 d of f against s (z = -9.9 -> -3.3); sigma_yy at " \
        "8.3 d of f against s (z = +4 -> +4))" in text  # fmt: skip
    small = replace(pair, static=(StaticMiss("nu", 9.3, -6.0),))
    assert "none stays beyond 3 se, so they are realisation noise" in static_rescaled_text(
        [small], twins
    )
    assert static_rescaled_text([pair], []) == ""


def test_momentum_balance_misses_rescaled_by_the_shear_factor(tmp_path):
    """sigma_yx lower by 2 sqrt(2) se in every static bin of seed 2: static factor 2. A run
    whose static bin at 1.5 d from the fixed wall (8.5 d from the moving one) is off the
    wall's shear by 5 se (z = -5 against se hypot(0.01, 0.01)) stays beyond 3 se at -2.5?
    no: -5 / 2 = -2.5, within."""
    step = np.r_[np.full(5, -2.0 * math.hypot(SE, SE)), np.zeros(5)]
    b = _plane(tmp_path, "b", seed=2, shift={"sigma_yx": step})
    twins = twin_pairs([_result(_plane(tmp_path, "a")), _result(b)])
    assert twins[0].fields["sigma_yx"].factor("static") == pytest.approx(2.0)
    off = np.zeros(10)
    off[1] = -5.0 * math.hypot(SE, 0.01)
    run = _plane(tmp_path, "c", shift={"sigma_yx": off})
    text = balance_rescaled_text([run], twins)
    assert "c at 8.5 d: z = -5 -> -2.5 (factor 2.0): none stays beyond 3 se" in text
    assert balance_rescaled_text([run], []) == ""
    assert balance_warning([run], twins) == ""  # within 3 se after the rescaling


def test_a_balance_miss_beyond_the_seed_scatter_is_named_unexplained(tmp_path):
    """Referee 14, point 7: the same static factor 2, a miss of -8 se at 8.5 d stays at -4 se:
    the Delta verdicts' warning names it, by run and distance, as unexplained: an isolated
    miss, nu smooth (0.8 everywhere) and sigma_yy without an inversion (referee 16, point 1)."""
    step = np.r_[np.full(5, -2.0 * math.hypot(SE, SE)), np.zeros(5)]
    b = _plane(tmp_path, "b", seed=2, shift={"sigma_yx": step})
    twins = twin_pairs([_result(_plane(tmp_path, "a")), _result(b)])
    off = np.zeros(10)
    off[1] = -8.0 * math.hypot(SE, 0.01)
    run = _plane(tmp_path, "c", shift={"sigma_yx": off})
    ((name, d, z, zr, f),) = balance_rescaled(run_list := [run], twins)
    assert (name, d, f) == ("c", 8.5, pytest.approx(2.0)) and zr == pytest.approx(z / 2.0)
    assert balance_warning(run_list, twins) == (
        " Warning: momentum-balance misses unexplained: c at 8.5 d (nu = 0.800; z = -4 after "
        "the rescaling by 2.0; I = 1e-05 < 0.0001: a static-zone bin (block errors within one "
        "realisation); Delta, read from u, does not use it) stays beyond 3 se of the wall's "
        "shear stress with the seed scatter allowed for (each factor without the miss's own "
        "bin); this series' Delta uses that run's u, not these bins' stresses."
    )
    assert balance_warning(run_list, []) == ""
    assert miss_place(run, 1).place == "unexplained"
    (rec,) = balance_record(run_list, twins)["misses"]
    assert (rec["place"], rec["stays"], rec["distance_d"]) == ("unexplained", True, 8.5)
    assert rec["static_zone"] and rec["inertial_number"] == pytest.approx(1e-5)
    # referee 17, point 5: in the flowing zone (I = 1e-3; the flowing factor is 1) the same
    # miss is one Delta's run carries unexplained
    moving = _plane(tmp_path, "m", shift={"sigma_yx": off}, inertial=np.full(10, 1e-3))
    assert balance_warning([moving], twins) == (
        " Warning: momentum-balance misses unexplained: m at 8.5 d (nu = 0.800; z = -8 after "
        "the rescaling by 1.0) stays beyond 3 se of the wall's shear stress with the seed scatter "
        "allowed for (each factor without the miss's own bin); this series' Delta uses that "
        "run, and nothing here accounts for the unexplained ones."
    )


def test_a_balance_miss_where_nu_exceeds_the_hexagonal_bound_is_in_the_layered_zone(tmp_path):
    """Referee 15, point 5 and 16, point 1: the same -8 se miss at 8.5 d (-4 se after the
    rescaling), its bin at nu = 0.949 > pi / (2 sqrt 3) = 0.907, is in the layered static
    zone; a second miss at 7.5 d, its bin at nu = 0.8 beside the 0.949 bin, is next to it (the
    two bins' nu differ by 0.149 > 0.07: a nu step too), not unexplained."""
    step = np.r_[np.full(5, -2.0 * math.hypot(SE, SE)), np.zeros(5)]
    b = _plane(tmp_path, "b", seed=2, shift={"sigma_yx": step})
    twins = twin_pairs([_result(_plane(tmp_path, "a")), _result(b)])
    off, dense = np.zeros(10), np.zeros(10)
    off[1] = off[2] = -8.0 * math.hypot(SE, 0.01)
    dense[1] = 0.949 - 0.8
    run = _plane(tmp_path, "c", shift={"sigma_yx": off, "nu": dense})
    assert balance_warning([run], twins) == (
        " Warning: momentum-balance misses in and next to the layered zone (nu steps between "
        "adjacent bins): in it (nu > 0.907, the "
        "hexagonal bound): c at 8.5 d (nu = 0.949; z = -4 after the rescaling by 2.0); next "
        "to it "
        "(beside a bin "
        "of nu > 0.907, in a sigma_yy inversion or a nu step of more than 0.07): c at 7.5 d "
        "(nu = 0.800; z = -4 after the rescaling by 2.0; beside nu = 0.949 at 8.5 d, nu step "
        "y = 1.5/2.5 (0.95/0.80)) stay beyond 3 se of the wall's shear stress with the seed "
        "scatter allowed for (each factor without the miss's own bin); this series' Delta "
        "uses that run; centre binning of a layered "
        "packing is why: a centre-binned layered bin, and its neighbours, do not test the "
        "balance (the stresses are not recomputed with area-weighted or half-shifted bins in "
        "this version)."
    )
    assert "unexplained" not in balance_warning([run], twins)
    # no sigma_yy inversion in these bins: the warning does not say the y-balance is broken
    # (review of stop 29); the real runs' text, with inversions, says both (test below)
    assert "y-balance broken" not in balance_warning([run], twins)
    assert [m["place"] for m in balance_record([run], twins)["misses"]] == [
        "layered",  # row 1, 8.5 d
        "next to the layered zone",  # row 2, 7.5 d
    ]


def test_a_miss_beside_a_dense_bin_is_next_to_the_layered_zone(tmp_path):
    """The classifier alone: a miss in row 4 (nu = 0.8) whose neighbour row 5 has nu = 0.95
    is next to the layered zone (no nu step: nu 0.86 there, 0.8 -> 0.86 is 0.06 < 0.07; the
    dense neighbour alone places it); the same miss with every nu 0.8 is unexplained."""
    nu = np.full(10, 0.8)
    nu[5] = 0.95
    nu[4] = 0.86  # the miss's own bin: a step of 0.06 from row 3, 0.09 to row 5
    run = _plane(tmp_path, "c", shift={"nu": nu - 0.8})
    m = miss_place(run, 4)
    assert m.place == "next to the layered zone"
    assert m.dense_neighbours == ((4.5, 0.95),)  # row 5: 4.5 d from the moving wall
    assert [(p.deep, p.shallow) for p in m.nu_steps] == [(4, 5)]  # 0.09 > 0.07
    assert miss_place(_plane(tmp_path, "d"), 4).place == "unexplained"
    lone = np.zeros(10)
    lone[4] = 0.06  # a lone bump below NU_STEP, no dense neighbour: still unexplained
    assert miss_place(_plane(tmp_path, "e", shift={"nu": lone}), 4).place == "unexplained"


def test_a_miss_in_a_sigma_yy_inversion_is_next_to_the_layered_zone(tmp_path):
    """sigma_yy rising with depth at gravity's rate (B = 1, H = 10 d, nu uniform: 0.1 per d)
    but for row 6 (y = 6.5), 0.2 below the line: it falls with depth from y = 7.5 to 6.5 by
    0.1 (z = -0.1 / hypot(0.01, 0.01) = -7.1) while rising to y = 5.5 (+0.3); a miss there is
    next to the layered zone, one in row 2 is not."""
    y = np.arange(10) + 0.5
    line = 1.0 + 0.1 * (10.0 - y) - 1.0  # the shift from the uniform 1.0
    line[6] -= 0.2
    run = _plane(tmp_path, "g", shift={"sigma_yy": line})
    yb = y_balance(run)
    assert yb is not None and yb.rate == pytest.approx(0.1) and yb.nu_mean == pytest.approx(0.8)
    ((p,),) = (yb.inversions,)
    assert (p.y_deep, p.y_shallow) == (6.5, 7.5)
    assert p.z == pytest.approx(-0.1 / math.hypot(SE, SE))
    assert p.expected == pytest.approx(0.1) and p.z_balance == pytest.approx(
        -0.2 / math.hypot(SE, SE)
    )
    assert yb.nu_steps == ()
    assert miss_place(run, 6, yb).place == "next to the layered zone"
    assert miss_place(run, 7, yb).place == "next to the layered zone"  # the pair's other bin
    assert miss_place(run, 2, yb).place == "unexplained"
    assert y_balance(_plane(tmp_path, "h", extra={"B": 0.0})) is None  # no gravity: no check


def test_the_y_balance_reproduces_the_referees_inversions():
    """Referee 16, point 1, on the two H = 20 d runs: sigma_yy falls with depth beyond 3 se at
    y = 0.5, 1.5, 5.5, 11.5, 18.5 (-22, -13, -7.8, -5.3, -8.5 se; rough) and 0.5, 1.5, 3.5,
    11.5, 18.5 (-8.3, -25, -3.3, -6.8, -29 se; smooth); the bulk misses at 14 d (rough) and
    16, 18 d (smooth) are next to the layered zone, the one at 17 d (nu 0.949) in it."""
    expect = {
        "plane_rough_H20_qs": ([0.5, 1.5, 5.5, 11.5, 18.5], [-22, -13, -7.8, -5.3, -8.5]),
        "plane_smooth_H20_qs": ([0.5, 1.5, 3.5, 11.5, 18.5], [-8.3, -25, -3.3, -6.8, -29]),
    }
    places = {}
    for name, (ys, zs) in expect.items():
        run = replace(read_run(DATA / name / "profile.csv"), name=name)
        yb = y_balance(run)
        assert yb is not None
        assert [p.y_deep for p in yb.inversions] == ys
        assert [float(f"{p.z:.2g}") for p in yb.inversions] == zs
        assert yb.rate == pytest.approx(run.B / run.gap_d)
        checks = wall_bins(run)
        cut = {row for row, *_ in checks.truncated}
        places[name] = {
            round(d): miss_place(run, row, yb).place
            for row, d, _, _ in checks.balance
            if row not in cut
        }
    assert places == {
        "plane_rough_H20_qs": {17: "layered", 14: "next to the layered zone",
                               1: "next to the layered zone"},
        "plane_smooth_H20_qs": {18: "next to the layered zone",
                                16: "next to the layered zone"},
    }  # fmt: skip


def test_the_misfit_reading_cites_the_replicates(tmp_path):
    """omega differing by 2 sqrt(2) se in two bins: sum z^2 = 8 on 10, factor sqrt(0.8) ->
    floored at 1; a joint fit's omega chi^2 34.9 on 9 is unchanged, u's too."""
    two = np.r_[np.full(2, 2.0 * math.hypot(SE, SE)), np.zeros(8)]
    twins = twin_pairs([_result(_plane(tmp_path, "a")),
                        _result(_plane(tmp_path, "b", seed=2, shift={"omega": two}))])  # fmt: skip
    em = {"r": {"u": {"ar1": 36.1, "n": 10}, "omega": {"ar1": 34.9, "n": 9}}}
    text = misfit_twin_text(twins, em, ["r"])
    assert "omega 8 on 10 (factor 0.89, no bin beyond 2 se)" in text
    assert "(u 1, omega 1; at least 1): r u 36.1 -> 36.1 on 10" in text
    assert "r omega 34.9 -> 34.9 on 9" in text
    assert misfit_twin_text([], em, ["r"]) == ""


# ------------------------------------------------------------------ the Delta design (point 3)
def _rough(points, twins=()):
    return DeltaSeries("plane, glued-grains, B = 1", "plane", "fully-rough", True,
                       tuple(points), twins=tuple(twins))  # fmt: skip


def test_the_seed_scatter_of_delta_from_one_pair():
    """6.609 and 5.154: per-run scatter ln(6.609 / 5.154) / sqrt(2) = 0.1759 (one dof: 95%
    range 0.1759 x [1/sqrt(5.024), 1/sqrt(0.000982)] = 0.0785-5.61)."""
    pts = [DeltaPoint("a", 9.84, 6.609, 0.67), DeltaPoint("b", 9.78, 5.154, 0.53)]
    sc = seed_scatter(_rough(pts, [("a", "b")]))
    rel = math.log(6.609 / 5.154) / math.sqrt(2.0)
    assert sc["relative"] == pytest.approx(rel) and sc["dof"] == 1
    assert sc["interval"] == pytest.approx([rel / math.sqrt(5.0239), rel / math.sqrt(0.000982)],
                                           rel=1e-3)  # fmt: skip
    assert sc["pairs"][0]["z"] == pytest.approx(1.455 / math.hypot(0.67, 0.53))
    assert seed_scatter(_rough(pts)) is None


def test_the_design_at_the_seed_scatter_from_the_closed_form():
    """At 17.6% per run, three gaps a factor 2 apart give sigma = 0.176 / sqrt(s 2 (ln 2)^2):
    0.179 with one seed (not 2 se: 1/6), 0.127 with two, 0.104 with three (2 se; none the
    margin 1/12); the block error (13%) design stays beside it."""
    pts = [DeltaPoint("a", 9.84, 6.609, 0.67), DeltaPoint("b", 9.78, 5.154, 0.53),
           DeltaPoint("c", 19.56, 7.954, 1.1)]  # fmt: skip
    s = _rough(pts, [("a", "b")])
    need = precision_needed(s, 1 / 3, 0.0)
    rel = math.log(6.609 / 5.154) / math.sqrt(2.0)
    assert need["seed_level"] == pytest.approx(rel)
    want = [rel / math.sqrt(k * 2.0 * math.log(2.0) ** 2) for k in (1, 2, 3)]
    assert [r["sigma"] for r in need["seed_designs"]] == pytest.approx(want)
    assert [r["sigma"] for r in need["seed_designs"]] == pytest.approx([0.179, 0.127, 0.104],
                                                                       abs=5e-4)  # fmt: skip
    assert [r["two_se"] for r in need["seed_designs"]] == [False, True, True]
    assert not any(r["margin"] for r in need["seed_designs"])
    assert need["designs"][0]["sigma"] == pytest.approx(slope_sigma(1.1 / 7.954, (20, 40, 80)))
    text = precision_text(s, 1 / 3, 0.0)
    # referee 15, point 1: the seed-scatter design leads; the block-error designs follow,
    # labelled as holding only if the block error were the scatter
    lead, block = text.split(". If the block error were the scatter (the runs' Delta errors ")
    assert "with 3 seeds each: sigma = 0.081" in block and "0.081" not in lead
    assert "block errors, which a second seed" not in text
    assert "At the seed scatter: the 14% block error is questioned by a second seed: the same-" \
        "conditions replicates (one cell, one wall speed, two seeds; a and b: 6.61 +- 0.67 " \
        "against 5.15 +- 0.53 d, 1.46 d apart (z = +1.7)) give a per-run scatter of Delta of " \
        "|ln(Delta_a / Delta_b)| / sqrt(2) = 18% from 1 pair(s) (1 degree(s) of freedom: " \
        "95% range 8-561%, so one pair barely bounds it)" in text  # fmt: skip
    # the rule's margin (1/12) needs ceil(0.176^2 x 144 / (2 ln^2 2)) = 5 seeds per gap
    exact = (rel * 12.0) ** 2 / (2.0 * math.log(2.0) ** 2)
    assert need["seeds_for_margin"]["exact"] == pytest.approx(exact)
    assert 4 < exact < 5 and need["seeds_for_margin"]["seeds"] == 5
    assert "At 18% per run, the slope rule's sigma <= 0.0833 needs 5 seeds per gap at " \
        "20/40/80 d ((17.6%/0.0833)^2 / 0.961 = 4.6, rounded up): 15 runs; sigma <= 0.0833 " \
        "is reached by none of the 1-3-seed designs listed; not by 20/40/80 d with one seed: " \
        "sigma = 0.18; " \
        "20/40/80 d with 2 seeds each: sigma = 0.13; 20/40/80 d with 3 seeds each: sigma = " \
        "0.1. The 18% rests on 1 pair(s) (95% range 8-561%), so the 5 seeds per gap are a " \
        "floor: a larger scatter, which the replicates do not exclude, needs " \
        "more" in lead  # fmt: skip
    assert "as context" not in text  # referee 14, point 1: the rule's criterion alone
    # at the window where the rule judges (referee 14, point 1): the same count, its gaps
    at = precision_text(s, 1 / 3, 0.0, (55.13, 220.5))
    assert "needs 5 seeds per gap at 55.13/110.3/220.5 d" in at and ": 15 runs;" in at
    v = delta_law_verdict([s], "rough")
    assert "is questioned by a second seed" in v.would_change
    assert v.numbers[s.key]["precision_needed"]["seeds"]["dof"] == 1


def test_a_pair_closer_than_the_block_error_does_not_improve_the_design():
    pts = [DeltaPoint("a", 9.84, 6.0, 1.2), DeltaPoint("b", 9.78, 6.01, 1.2)]
    need = precision_needed(_rough(pts, [("a", "b")]), 1 / 3, 0.0)
    assert need["seed_level"] == pytest.approx(0.2)  # the block error, 1.2 / 6.0
    assert "(the block error: the replicates' scatter is below it)" in precision_text(
        _rough(pts, [("a", "b")]), 1 / 3, 0.0
    )


def test_twin_field_factor_zones():
    f = TwinField("nu", (3.0, 1.0), (0.5, 5.5), (True, False))
    assert f.factor("static") == 3.0 and f.factor("flowing") == 1.0
    assert f.factor() == pytest.approx(math.sqrt(5.0))
    assert TwinField("nu", (1.0,), (0.5,), (False,)).factor("static") is None


def test_the_replicates_word_follows_the_misfit_reading(tmp_path):
    """spin_model's evidence gets the replicates' sentence right after "a second seed would
    settle the error scale.", not at its end; without a misfit, nothing."""
    from cosserat.studies.validate.study import _misfit_twins
    from cosserat.studies.validate.verdicts import Verdict

    twins = twin_pairs([_result(_plane(tmp_path, "a")), _result(_plane(tmp_path, "b", seed=2))])
    em = {"r": {"u": {"ar1": 20.0, "n": 10}, "omega": {"ar1": 18.0, "n": 9}}}
    v = Verdict("spin_model", "refuted", "Read as understated errors; a second seed would "
                "settle the error scale. Refuted at x.", "", ("r",),
                {"misfit_runs": ["r"], "reading": "errors",
                 "error_models": {"r": "scans[0].error_models"},
                 "scans": [{"run": "r", "error_models": em["r"]}]})  # fmt: skip
    got = _misfit_twins(v, twins).evidence
    # the joint fit's AR(1) chi^2 read from scans[0] (numbers.error_models is a pointer)
    assert "r u 20 -> 20 on 10" in got and "r omega 18 -> 18 on 9" in got
    assert got.startswith("Read as understated errors; a second seed would settle the error "
                          "scale. The same-conditions replicates (one cell, one V, two seeds) "
                          "measure that error scale: a against b: u sum z^2 = 0")  # fmt: skip
    assert got.endswith(" Refuted at x.")
    assert _misfit_twins(replace(v, numbers={"misfit_runs": []}), twins) == replace(
        v, numbers={"misfit_runs": []}
    )


def test_a_runs_factor_comes_from_its_own_cell_first(tmp_path):
    """Two pairs: the rough cell's (nu factor 3) and a layer cell's (other fixed wall, nu
    factor 5). A rough run at another gap takes the rough pair's (its walls); a rough run at
    the pair's gap too; a run of walls no pair has takes both."""
    from cosserat.studies.validate.rate import twins_for

    def nu(k):
        return {"nu": np.full(10, k * math.hypot(SE, SE))}

    smooth = {"wall_fixed": {"kind": "smooth-frictional"}}
    rough = twin_pairs([_result(_plane(tmp_path, "a")),
                        _result(_plane(tmp_path, "b", seed=2, shift=nu(3)))])  # fmt: skip
    d = _plane(tmp_path, "d", seed=2, shift=nu(5), extra=smooth)
    layer = twin_pairs([_result(_plane(tmp_path, "c", extra=smooth)), _result(d)])
    both = rough + layer
    assert twins_for(_plane(tmp_path, "e", seed=3), both) == rough
    wide = _plane(tmp_path, "f", extra={"gap_d": 20.0})
    assert twins_for(wide, both) == rough
    assert twin_factor(twins_for(wide, both), "nu") == pytest.approx(3.0)
    other = _plane(tmp_path, "g", extra={"wall": {"kind": "smooth-frictional"}})
    assert twins_for(other, both) == both
    pair = RatePair("e", "s", (2.0, 1.0), {}, (None, None), (None, None),
                    (StaticMiss("nu", 9.3, -12.0),))  # fmt: skip
    text = static_rescaled_text([pair], both, {"e": _plane(tmp_path, "e", seed=3)})
    assert "(a against b: nu 3; from" in text and "z = -12 -> -4" in text


def test_every_regime_block_names_the_replicates_own_first(tmp_path):
    """The verdict's own pair first, the corpus's other pair marked; none: said so."""
    from cosserat.studies.validate.study import twins_text

    smooth = {"wall_fixed": {"kind": "smooth-frictional"}}
    cells = (("a", 1, None), ("b", 2, None), ("c", 1, smooth), ("d", 2, smooth))
    rs = [_result(_plane(tmp_path, n, seed=k, extra=e)) for n, k, e in cells]
    twins = twin_pairs(rs)
    assert [(t.a, t.b) for t in twins] == [("a", "b"), ("c", "d")]
    text = twins_text(twins, rs[2:])
    assert text.startswith("Same-conditions replicates: c against d (")
    # the other pair in one clause: each field's sum z^2 over its bins, not the full comparison
    other = text.split("Same-conditions replicates elsewhere in the corpus")[1]
    assert "a against b (seed 1 against 2): u 0/10" in other
    assert "bins paired by row" not in other and "seed-scatter factor sqrt" not in other
    assert twins_text([], rs).startswith("Same-conditions replicates: none (no cell run twice")
    assert twins_text(twins, []) == ""


def test_a_truncated_outlier_bin_is_listed_but_left_out_of_the_factor(tmp_path):
    """Referee 13, point 5: every bin static, nu of seed 2 higher by 2 sqrt(2) se in the nine
    bulk bins (z = -2) and by 21 sqrt(2) se in the truncated top bin (z = -21): sum z^2 =
    36 + 441 = 477 on 10 lists it, the factor is sqrt(36 / 9) = 2 without it (6.9 with it),
    and a static miss z = -9 is rescaled by 2, not 6.9."""
    trunc = {"truncated_bins": {"bins": [{"row": 9, "wall": "upper", "width_d": 0.8}]}}
    shift = np.r_[np.full(9, 2.0), 21.0] * math.hypot(SE, SE)
    static = np.full(10, 1e-5)
    a = _plane(tmp_path, "a", inertial=static, extra=trunc)
    b = _plane(tmp_path, "b", seed=2, inertial=static, shift={"nu": shift}, extra=trunc)
    (p,) = twin_pairs([_result(a), _result(b)])
    nu = p.fields["nu"]
    assert nu.chi2 == pytest.approx(477.0) and nu.n == 10 and nu.n_truncated == 1
    assert nu.factor("static") == pytest.approx(2.0) and nu.factor() == pytest.approx(2.0)
    assert twin_factor([p], "nu") == pytest.approx(2.0)
    assert "nu 477/10 (1 truncated bin; static zone x2 without it)" in p.brief()
    assert "(beyond 3 se: -21 at 9.5 d (truncated bin))" in p.text()
    assert "the truncated wall bins, counted in each sum z^2 above, are left out of every " \
        "factor" in p.text()  # fmt: skip
    pair = RatePair("f", "s", (2.0, 1.0), {}, (None, None), (None, None),
                    (StaticMiss("nu", 5.0, -9.0),))  # fmt: skip
    assert "(z = -9 -> -4.5)" in static_rescaled_text([pair], [p])  # every pair: still 2


def test_the_shipped_layer_twins_factors_without_the_truncated_bin():
    """Referee 13, check (d): the layer twins' sum z^2 nu 538, sigma_yy 565 (the truncated
    top bin at 9.49 d included, z = -21 and -23). Without it the factors over the nine other
    bins are the referee's 3.3 and 1.4; over the four static ones 3.9 and 1.8 (10 and 11 with
    it)."""
    runs = [replace(read_run(DATA / n / "profile.csv"), name=n)
            for n in ("plane_layer_H10_qs", "plane_layer_H10_qs_s2")]  # fmt: skip
    (p,) = twin_pairs([_result(r) for r in runs])
    nu, syy = p.fields["nu"], p.fields["sigma_yy"]
    assert (round(nu.chi2), round(syy.chi2)) == (538, 565)
    assert nu.truncated[-1] and round(nu.z[-1]) == -21 and round(syy.z[-1]) == -23
    assert round(nu.factor(), 1) == 3.3 and round(syy.factor(), 1) == 1.4
    assert round(nu.factor("static"), 1) == 3.9 and round(syy.factor("static"), 1) == 1.8


def test_the_runs_text_places_the_misses_and_lists_the_y_balance():
    """The regime block's momentum-balance sentence (``study.wall_bins_text``) counts where the
    bulk misses sit and adds sigma_yy's y-balance of the runs with misses (referee 16,
    point 1), with the reason: centre binning of a layered packing."""
    from cosserat.studies.validate.study import wall_bins_text

    runs = [
        SimpleNamespace(run=replace(read_run(DATA / n / "profile.csv"), name=n))
        for n in ("plane_rough_H20_qs", "plane_smooth_H20_qs")
    ]
    text = wall_bins_text(runs)
    assert (
        "3 of its other 19 bins, largest z = +5.8 at 14.1 d (1 in the layered zone, 2 next to "
        "the layered zone))" in text
    )
    assert (
        "2 of its other 20 bins, largest z = -4.0 at 16.2 d (2 next to the layered zone))" in text
    )
    assert (
        "plane_rough_H20_qs (rise 0.051 N/d): inversions at y = 0.5/1.5 (-22 se), 1.5/2.5 "
        "(-13 se), 5.5/6.5 (-7.8 se), 11.5/12.5 (-5.3 se), 18.5/19.3 (-8.5 se); nu steps at "
        "y = 0.5/1.5 (0.69/0.91)" in text
    )
    assert "centre binning of a layered packing puts such bins' stresses off" in text
    assert "unexplained otherwise" in text and "(0 unexplained" not in text


def test_a_bin_whose_block_se_is_zero_enters_no_factor(tmp_path):
    """Referee 17, point 5: seed 2's nu se is 3.7e-17 in the first bin (the blocks returned one
    value) and its nu 0.05 lower there: z = 0.05 / 0.01 = +5, over seed 1's se alone. Below
    SE_FLOOR (0.01) of nu's median se (0.01), the bin is listed in sum z^2, marked, and left
    out of every factor (so nu's factor is 0, not sqrt(25 / 10))."""
    a = _plane(tmp_path, "a")
    b = _plane(tmp_path, "b", seed=2, shift={"nu": np.r_[-0.05, np.zeros(9)]})
    cols = {k: np.array(v, float) for k, v in b.columns.items()}
    cols["nu_se"][0] = 3.7e-17
    b = replace(b, columns=cols)
    (p,) = twin_pairs([_result(a), _result(b)])
    nu = p.fields["nu"]
    assert SE_FLOOR == 0.01 and nu.floored == (True,) + (False,) * 9
    assert nu.z[0] == pytest.approx(5.0) and nu.chi2 == pytest.approx(25.0)
    assert nu.factor() == 0.0 and nu.factor("static") == 0.0 and nu.floored_at == [0.5]
    assert p.fields["u"].floored == (False,) * 10
    text = p.text()
    assert "nu sum z^2 = 25 on 10 bins (beyond 3 se: +5 at 0.5 d (se below the floor))" in text
    assert "left out too, for a block se below 0.01 of the field's median in one run (the " \
        "blocks returned one value: no error estimate, so no z): nu at 0.5 d." in text  # fmt: skip
    assert nu.to_dict()["floored"][0] and nu.to_dict()["se_floor"] == 0.01


def test_a_miss_is_not_rescaled_by_a_factor_its_own_bin_drives(tmp_path):
    """Referee 17, point 5: seed 2's sigma_yx is 2 sqrt 2 se low in the static bins but 8
    sqrt 2 se low at 1.5 d from the fixed wall, a momentum-balance miss of z = -8 in seed 2
    itself. The pair's static factor is sqrt((4 x 4 + 64) / 5) = 4 with that bin, 2 without
    it: the miss is rescaled by 2 (-4, beyond 3 se), not by 4 (-2, within)."""
    step = np.full(5, -2.0 * math.hypot(SE, SE))
    step[1] = -8.0 * math.hypot(SE, SE)
    b = _plane(tmp_path, "b", seed=2, shift={"sigma_yx": np.r_[step, np.zeros(5)]})
    twins = twin_pairs([_result(_plane(tmp_path, "a")), _result(b)])
    tf = twins[0].fields["sigma_yx"]
    assert tf.factor("static") == pytest.approx(4.0)
    assert tf.factor("static", (1,)) == pytest.approx(2.0) and tf.rows == tuple(range(10))
    assert twin_factor(twins, "sigma_yx", "static", ("b", 1)) == pytest.approx(2.0)
    assert twin_factor(twins, "sigma_yx", "static", ("c", 1)) == pytest.approx(4.0)
    ((name, d, z, zr, f),) = balance_rescaled([b], twins)
    assert (name, d) == ("b", 8.5) and z == pytest.approx(-8.0) and f == pytest.approx(2.0)
    assert zr == pytest.approx(-4.0)
    assert "b at 8.5 d: z = -8 -> -4 (factor 2.0): 1 stays beyond 3 se, so the seed scatter " \
        "does not explain it." in balance_rescaled_text([b], twins)  # fmt: skip
    (rec,) = balance_record([b], twins)["misses"]
    assert rec["factor"] == pytest.approx(2.0) and rec["factor_without_own_bin"]


def test_distances_print_with_one_decimal():
    """Referee 17, point 5: 11.5 and 12.5 d both read "12 d" at two significant figures."""
    p = TwinPair("a", "b", 1.0, (1, 2), {}, (None, None), (None, None))
    f = TwinField("nu", (-24.0, 26.0, 1.0), (10.5, 11.5, 12.5), (True, True, True))
    assert p.field_text(f) == (
        "nu sum z^2 = 1.25e+03 on 3 bins (beyond 3 se: -24 at 10.5 d, +26 at 11.5 d)"
    )
    assert f.without_largest() == (pytest.approx(math.sqrt((24.0**2 + 1.0) / 2.0)), 11.5)
    assert TwinField("u", (1.0,), (0.5,), (True,)).without_largest() is None


def test_the_unused_stresses_sentence_follows_the_pairs_numbers(tmp_path):
    """Referee 17, point 5: "no verdict uses binned nu or stresses outside the band" says
    whether the band's stress ratio and the walls' contact stress ratio agree, from the pair;
    a moving wall's ratio 3 combined se apart is said to differ."""
    a = _plane(tmp_path, "a")
    b = _plane(tmp_path, "b", seed=2)
    (p,) = twin_pairs([_result(a), _result(b)])
    assert p.unused_text().endswith("both agreeing between the seeds. So the factors above "
                                    "undercut no verdict's errors.")  # fmt: skip
    far = replace(p, wall_ratio=((0.30, 0.01), (0.30 - 3 * math.hypot(0.01, 0.01), 0.01)))
    assert far.unused_text().endswith(
        "(the moving wall's stress ratio: z = +3 between the seeds; phi and delta); the walls' "
        "differs between the seeds beyond the block errors."
    )
    assert replace(p, wall_ratio=(None, None)).unused_text() == ""


def test_the_shipped_warning_names_the_y_balance_only_where_it_breaks():
    """plane_rough_H20_qs's misses (rescaled by the rough H = 10 d seed pair's factor, as
    validate does) sit in the layered zone (17 d) and next to it at 14 d, in a sigma_yy
    inversion (y = 5.5/6.5, -7.8 se) and a nu step: the warning names both (and only then:
    the synthetic case above has no inversion and does not say it)."""
    pair = [
        replace(read_run(DATA / n / "profile.csv"), name=n)
        for n in ("plane_rough_H10_qs", "plane_rough_H10_qs_s2")
    ]
    run = replace(read_run(DATA / "plane_rough_H20_qs" / "profile.csv"), name="plane_rough_H20_qs")
    warn = balance_warning([run], twin_pairs([_result(r) for r in pair]))
    assert warn.startswith(
        " Warning: momentum-balance misses in and next to the layered zone (nu steps between "
        "adjacent bins; sigma_yy's y-balance broken in the same bins): "
    )
