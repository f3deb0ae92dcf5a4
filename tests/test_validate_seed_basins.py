"""The seed pairs' L basins in the spin_model verdict (referee 17, point 1): two seeds of one
cell found among the scans by their metadata, their 95% regions compared in L
(``spin_scan.basin_comparison``), the verdict's sentence and the scan figure's panel note, and
which refuted runs' joint fits fit (``spin_scan.fits_text``). Synthetic region records, no
solves; the shapes are those of ``cosserat validate`` on the nine v2 runs (results.json)."""

from __future__ import annotations

from types import SimpleNamespace

import pytest

from cosserat.studies.validate import spin_scan as ss


def _island(k, l_, dchi2):
    return {"K": list(k), "L": list(l_), "delta_chi2": dchi2}


def _record(run, seed, best, islands, *, threshold=5.99, call="refuted"):
    ks = [v for i in islands for v in i["K"]]
    ls = [v for i in islands for v in i["L"]]
    region = {"K": [min(ks), max(ks)], "L": [min(ls), max(ls)], "islands": islands}
    return {"run": run, "seed": seed, "best_K": best[0], "best_L": best[1],
            "threshold": threshold, "region": region, "call": call, "gap_d": 20.0}  # fmt: skip


# seed 1: the fit in a large-L island, a small-L island that exists only just (5.86 < 5.99);
# seed 2: one region next to the small-L island (overlapping in L, not in K)
TWO = [_island((4.88, 6.29), (12.7, 15.7), 0.0), _island((2.87, 2.87), (3.54, 3.54), 5.86)]
ONE = [_island((1.51, 2.86), (2.03, 4.11), 0.0)]


def test_two_basins_against_one_each_fit_in_its_own_and_the_large_l_one_unreplicated():
    a = _record("cell_s1", 1, (5.54, 14.6), TWO)
    b = _record("cell_s2", 2, (2.11, 2.85), ONE, threshold=12.4)
    cmp = ss.basin_comparison(a, b)
    assert cmp["own_basins"] is True
    assert cmp["unmet"] == {"cell_s1": ["large-L"], "cell_s2": []}
    # islands sorted by L: the small-L one first, and it alone meets seed 2's region
    assert [p["label"] for p in cmp["islands"]["cell_s1"]] == ["small-L", "large-L"]
    assert [p["met"] for p in cmp["islands"]["cell_s1"]] == [[0], []]
    assert [p["fit"] for p in cmp["islands"]["cell_s1"]] == [False, True]
    assert [p["only_just"] for p in cmp["islands"]["cell_s1"]] == [True, False]
    text = ss.basin_text(cmp)
    assert text.startswith(
        "The refutation holds at both seeds of one cell at H = 20 d (cell_s1, seed 1; cell_s2, "
        "seed 2), each fit in its own L basin: cell_s1's fit at K 5.54, L 14.6 d in the large-L "
        "island (K 4.88-6.29, L 12.7-15.7 d) of two; its small-L island (K 2.87, L ~3.5 d) "
        "exists only just (least Delta chi^2 5.86 against the threshold 5.99); cell_s2's fit at "
        "K 2.11, L 2.85 d in its single region (K 1.51-2.86, L 2.03-4.11 d), next to cell_s1's "
        "small-L island: overlapping it in L, not in K (K 2.87, L ~3.5 d)."
    )
    assert text.endswith(
        " So cell_s1's large-L basin is not replicated, and the refutation holds in both basins."
    )
    assert ss.basin_title(cmp, "cell_s1") == "one of two basins; seed 2 finds only the small-L one"
    assert ss.basin_title(cmp, "cell_s2") == ""
    assert ss.basin_title(cmp, "another_run") == ""


def test_regions_overlapping_in_l_share_a_basin():
    a = _record("x", 1, (2.0, 3.0), [_island((1.5, 2.5), (2.0, 4.0), 0.0)])
    b = _record("y", 2, (2.2, 3.6), [_island((1.9, 3.0), (3.5, 6.0), 0.0)])
    cmp = ss.basin_comparison(a, b)
    assert cmp["own_basins"] is False
    assert cmp["unmet"] == {"x": [], "y": []}
    text = ss.basin_text(cmp)
    assert text.startswith("The refutation holds at both seeds of one cell at H = 20 d (x, ")
    assert "own L basin" not in text and "not replicated" not in text
    assert "both basins" not in text
    assert text.endswith(
        "y's fit at K 2.2, L 3.6 d in its single region (K 1.9-3, L 3.5-6 d), overlapping x's "
        "region in L and K."
    )
    b["call"] = a["call"] = "undecided"
    assert ss.basin_text(ss.basin_comparison(a, b)).startswith(
        "Both seeds of one cell at H = 20 d (x, seed 1; y, seed 2) are undecided: x's fit"
    )
    assert ss.basin_title(cmp, "x") == ss.basin_title(cmp, "y") == ""


def test_disjoint_single_regions_and_calls_that_differ():
    a = _record("x", 1, (5.0, 14.0), [_island((4.0, 6.0), (12.0, 16.0), 0.0)])
    b = _record("y", 2, (2.0, 3.0), ONE, call="undecided")
    cmp = ss.basin_comparison(a, b)
    assert cmp["own_basins"] is True
    text = ss.basin_text(cmp)
    assert text.startswith(
        "The call differs between the seeds of one cell at H = 20 d (x refuted; y undecided), "
        "each fit in its own L basin"
    )
    assert "both basins" not in text  # the refutation holds at one seed only
    # a single region the other seed misses is not a "basin not replicated" (no second one)
    assert "not replicated" not in text


def test_a_fit_between_grid_points_sits_in_the_island_of_least_delta_chi2():
    a = _record("x", 1, (3.5, 9.0), TWO)  # (3.5, 9.0) lies in neither island's box
    b = _record("y", 2, (2.11, 2.85), ONE)
    cmp = ss.basin_comparison(a, b)
    assert [p["fit"] for p in cmp["islands"]["x"]] == [False, True]
    assert cmp["own_basins"] is True


def _fake_scan(name, seed, p, fields):
    run = SimpleNamespace(
        name=name, cell="plane", gap_d=20.0,
        meta={"wall": "smooth", "wall_speed": 0.0025, "seed": seed, "B": 1.0},
    )  # fmt: skip
    values = {"K": 5.54 if seed == 1 else 2.11, "L": 14.6 if seed == 1 else 2.85}
    cal = SimpleNamespace(
        p_value=p, fields=[SimpleNamespace(field=f, chi2=c, n=n) for f, c, n in fields]
    )
    fit = SimpleNamespace(setup=SimpleNamespace(runs=[run]), calibration=cal,
                          value=values.__getitem__)  # fmt: skip
    return SimpleNamespace(run=name, fit=fit, threshold=5.99 if seed == 1 else 12.4, basins="")


@pytest.fixture
def seed_scans(monkeypatch):
    """Two seeds of one cell (names that say nothing of it) and a run of another gap."""
    s1 = _fake_scan("alpha", 1, 0.49, [("u", 10.3, 20), ("omega", 27.6, 19)])
    s2 = _fake_scan("beta", 2, 9.5e-05, [("u", 22.2, 20), ("omega", 54.0, 19)])
    other = _fake_scan("gamma", 1, 0.0009, [("u", 16.0, 10), ("omega", 27.3, 9)])
    other.fit.setup.runs[0].gap_d = 10.0
    regions = {"alpha": {"islands": TWO}, "beta": {"islands": ONE}, "gamma": {"islands": ONE}}
    for r in regions.values():
        r["K"] = [min(v for i in r["islands"] for v in i["K"])] * 2
        r["L"] = [min(v for i in r["islands"] for v in i["L"])] * 2
    monkeypatch.setattr(ss, "scan_region", lambda sc: regions[sc.run])
    monkeypatch.setattr(ss, "wall_call", lambda sc: "refuted")
    u_models = {"gamma": {"u": {"n": 10, "diagonal": 71.6, "common-mode": 40.6,
                                "p": {"diagonal": 2.1e-11, "common-mode": 1.3e-05}}}}  # fmt: skip
    monkeypatch.setattr(ss, "error_models", lambda sc: u_models.get(sc.run, {}))
    return [other, s1, s2]


def test_the_seed_pair_is_found_from_the_runs_metadata_and_marks_its_panel(seed_scans):
    pairs = ss.seed_pairs(seed_scans)
    assert [c["runs"] for c in pairs] == [["alpha", "beta"]]
    ss.mark_seed_basins(seed_scans)
    assert [sc.basins for sc in seed_scans] == [
        "",
        "one of two basins; seed 2 finds only the small-L one",
        "",
    ]


def test_which_refuted_runs_joint_fits_fit_and_which_misfit(seed_scans):
    assert ss.fits_text(seed_scans) == (
        "Of the refuted runs, only alpha (p = 0.49) has a joint calibration that fits; the "
        "other 2 are refuted against calibrations that misfit: gamma (overall p = 0.0009; u "
        "71.6/10 under diagonal errors, p = 2.1e-11; u 40.6/10 under common-mode errors, p = "
        "1.3e-05), beta (overall p = 9.5e-05; omega 54/19, p = 3.3e-05)."
    )


def test_the_scan_panel_says_which_basins_the_other_seed_finds_on_its_own_title_line():
    import matplotlib.pyplot as plt
    import numpy as np

    from cosserat.viz.validation import spin_scan_figure

    k, ll = np.linspace(0.0, 10.0, 5), np.geomspace(0.5, 100.0, 5)
    d = np.add.outer((k - 5.0) ** 2, np.log(ll / 14.0) ** 2)

    def grid():
        return {"K": list(k), "L": list(ll), "departure": (0.01 + 0.0 * d).tolist(),
                "null": (0.0 * d).tolist(), "delta_chi2": d.tolist()}  # fmt: skip

    rec = {
        "run": "r", "measured": -0.3, "measured_beyond_null": -0.28,
        "measured_beyond_null_se": 0.03, "best_K": 5.0, "best_L": 14.0,
        "best_beyond_null": 0.09, "threshold": 5.99, "phi": 18.1, "delta": {"moving": 13.5},
        "grids": {"range": grid(), "near": grid()},
        "region": {"K": [2.87, 6.29], "L": [3.54, 15.7], "K_bounds": ["data", "data"],
                   "L_bounds": ["data", "data"], "islands": TWO},
        "basins": "one of two basins; seed 2 finds only the small-L one",
    }  # fmt: skip
    fig = spin_scan_figure([rec, {**rec, "run": "s", "basins": ""}])
    lines = fig.axes[0].get_title().splitlines()
    at = lines.index("95% region: 2 islands, L ~3.5 and 12.7-15.7 d")
    assert lines[at + 1] == "one of two basins; seed 2 finds only the small-L one"
    assert "seed 2" not in fig.axes[1].get_title()  # no note: no line
    assert len(fig.axes[1].get_title().splitlines()) == len(lines) - 1
    plt.close(fig)


def test_the_scan_caption_gives_the_basin_note_beside_the_runs_region():
    from cosserat.studies.validate.report import spin_scan_caption

    rec = {"run": "r", "region_text": "two islands: K 2.87, L ~3.5 d and K 4.88-6.29, L "
           "12.7-15.7 d", "measured_beyond_null": -0.28, "measured_beyond_null_se": 0.03,
           "best_beyond_null": 0.09}  # fmt: skip
    note = "one of two basins; seed 2 finds only the small-L one"
    text = spin_scan_caption([{**rec, "basins": note}, {**rec, "run": "s", "basins": ""}])
    assert f"r: two islands: K 2.87, L ~3.5 d and K 4.88-6.29, L 12.7-15.7 d ({note}); s: " in text
    assert text.count(note) == 1


def test_the_refutations_runs_say_which_are_seeds_of_one_cell(monkeypatch):
    """The spin_model evidence's "It rests on n runs": "one seed each" only where no two of
    them are seeds of one cell (rate.twin_names); else how many cells and which pair."""
    from types import SimpleNamespace

    from cosserat.studies.validate import rate, spin_scan

    def scan(name):
        return SimpleNamespace(run=name, fit=SimpleNamespace(setup=SimpleNamespace(
            runs=[SimpleNamespace(name=name)])))  # fmt: skip

    scans = [scan("a"), scan("b"), scan("b_s2")]
    solid = ["a", "b", "b_s2"]
    monkeypatch.setattr(rate, "twin_names", lambda runs: (("b", "b_s2"),))
    assert spin_scan._seeds_note(scans, solid) == (
        " of 2 cells (a, b, b_s2; b and b_s2 two seeds of one cell)"
    )
    monkeypatch.setattr(rate, "twin_names", lambda runs: ())
    assert spin_scan._seeds_note(scans, solid) == ", one seed each (a, b, b_s2)"
    # a pair one of whose runs is not among the refuting ones is not counted
    monkeypatch.setattr(rate, "twin_names", lambda runs: (("b", "c"),))
    assert spin_scan._seeds_note(scans, solid) == ", one seed each (a, b, b_s2)"
