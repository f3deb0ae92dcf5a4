"""The spin scan's refinement along its 95% region, the joint fit's restart from a lower grid
point and the match zone (referee 12, point 5(ii)-(iii); the per-run joint fit's local optimum
at plane_smooth_H20_qs): :func:`~cosserat.studies.validate.spin_scan.refine_cells`,
``cell_axes``, ``restart_from_grid``, ``match_zone`` and their sentences."""

from __future__ import annotations

import itertools
import math
from types import SimpleNamespace

import numpy as np
import pytest
from scipy.optimize import minimize

from cosserat.errors import ParameterError
from cosserat.studies.validate import spin_scan as ss

K = np.linspace(0.0, 4.0, 9)
L = np.geomspace(0.5, 100.0, 11)
L_EXIST = 20.0  # no solution beyond


def _valley(k, ll):
    """Delta chi^2 0 along K = 1 + ln(L)/2 (a flat valley), rising across it with width 0.1;
    no solution (NaN) beyond L = 20 d."""
    kk, lg = np.meshgrid(k, ll, indexing="ij")
    d = ((kk - 1.0 - 0.5 * np.log(lg)) / 0.1) ** 2
    return np.where(lg > L_EXIST, np.nan, d)


def test_the_refinement_follows_a_flat_valley_to_the_existence_bound():
    d, thr = _valley(K, L), 6.0
    cells = ss.refine_cells(K, L, d, thr)
    inside = np.isfinite(d) & (d <= thr)
    # exactly the cells with a corner inside
    want = [(a, b) for a in range(K.size - 1) for b in range(L.size - 1)
            if inside[a : a + 2, b : b + 2].any()]  # fmt: skip
    assert cells == want
    patches = []
    for a, b in cells:
        kk, ll = ss.cell_axes(K, L, a, b)
        # the cell's corners exactly, K even and L even in log in between
        assert (kk[0], kk[-1], ll[0], ll[-1]) == (K[a], K[a + 1], L[b], L[b + 1])
        assert kk.size == ll.size == ss.REFINE + 1
        np.testing.assert_allclose(np.diff(np.log(ll)), np.log(L[b + 1] / L[b]) / ss.REFINE)
        patches.append((kk, ll, _valley(kk, ll), "refined"))
    coarse = ss.region_extent([(K, L, d, "range")], thr)
    fine = ss.region_extent([(K, L, d, "range"), *patches], thr)
    # the coarse grid stops at its last solved L, 12 d; the refined one at the last solved
    # point of the patch below 20 d, one patch step (in log L) short of the bound
    assert coarse["L"][1] == pytest.approx(L[6]) and coarse["L_bounds"][1] == "existence"
    step = (L[7] / L[6]) ** (1.0 / ss.REFINE)
    assert fine["L"][1] == pytest.approx(L[7] / step, rel=1e-12)
    assert fine["L"][1] < L_EXIST < fine["L"][1] * step
    assert fine["L_bounds"][1] == "existence"
    # the valley's K there, 1 + ln(17.9)/2 = 2.44: the region reaches it
    assert fine["K"][1] >= 1.0 + 0.5 * math.log(fine["L"][1]) - 1e-12
    masks, others, _ = ss.region_pieces([(K, L, d, "range"), *patches], thr, (1.0, 1.0))
    assert others == [] and all(m.any() for m in masks[1:])


def test_a_finer_box_keeps_its_cells_and_a_box_no_finer_is_none():
    d = _valley(K, L)
    all_cells = ss.refine_cells(K, L, d, 6.0)
    box = (0.0, 1.5, 0.5, 1.5)  # K 0-1.5, L 0.5-1.5 d: the cells between L 0.5, 0.85, 1.44
    kept = ss.refine_cells(K, L, d, 6.0, box)
    assert set(all_cells) - set(kept) == {(0, 0), (1, 0), (2, 0), (1, 1), (2, 1)}
    assert all(K[a + 1] <= 1.5 and L[b + 1] <= 1.5 for a, b in set(all_cells) - set(kept))
    with pytest.raises(ParameterError, match=r"Delta chi\^2 must be \(K, L\) = \(9, 11\)"):
        ss.refine_cells(K, L, d[:, :3], 6.0)
    with pytest.raises(ParameterError, match="a cell is refined into >= 1 intervals; got 0"):
        ss.cell_axes(K, L, 0, 0, 0)
    # a finer grid twice as fine in K and in log L covers its box; one as coarse does not
    fine_k, fine_l = np.linspace(1.0, 2.0, 5), np.geomspace(2.0, 4.0, 5)
    assert ss._finer_box(K, L, fine_k, fine_l) == (1.0, 2.0, 2.0, 4.0)
    assert ss._finer_box(K, L, np.linspace(0.0, 3.6, 9), fine_l) is None


def _two_minima(x):
    """Two minima: chi^2 0 at x = 1 and -1 at x = 4."""
    return float(min((x - 1.0) ** 2, (x - 4.0) ** 2 - 1.0))


GRID = np.linspace(0.0, 5.0, 11)


def _lowest(x):
    i = int(np.argmin([_two_minima(g) for g in GRID]))
    return {"K": float(GRID[i]), "L": 1.0, "chi2": _two_minima(GRID[i])}


def _local(x0):
    return float(minimize(lambda v: _two_minima(v[0]), [x0], method="Nelder-Mead",
                          options={"xatol": 1e-10, "fatol": 1e-12}).x[0])  # fmt: skip


def test_the_restart_rule_moves_a_local_optimum_to_the_global_one():
    x = _local(0.5)
    assert x == pytest.approx(1.0, abs=1e-6)  # the optimiser's local optimum
    fit, moves = ss.restart_from_grid(
        x, _lowest, lambda f, p: _local(p["K"]), _two_minima, lambda f: (f, 1.0)
    )
    assert fit == pytest.approx(4.0, abs=1e-6) and _two_minima(fit) == pytest.approx(-1.0)
    (m,) = moves  # one restart: from the grid point x = 4, then the grid has nothing lower
    assert (m["K"], m["chi2"], m["kept"]) == (4.0, -1.0, 1.0)
    assert m["K_from"] == pytest.approx(1.0, abs=1e-6) and m["chi2_from"] == pytest.approx(0.0)
    assert m["K_to"] == pytest.approx(4.0, abs=1e-6) and m["chi2_to"] == pytest.approx(-1.0)
    # at the global optimum nothing moves; a refit that does not improve is kept out
    assert ss.restart_from_grid(4.0, _lowest, None, _two_minima, lambda f: (f, 1.0)) == (4.0, [])
    fit, moves = ss.restart_from_grid(x, _lowest, lambda f, p: f, _two_minima, lambda f: (f, 1.0))
    assert fit == x and len(moves) == 1 and moves[0]["kept"] == 0.0
    # a grid point within the tolerance does not restart
    fit, moves = ss.restart_from_grid(
        1.0, lambda f: {"K": 1.2, "L": 1.0, "chi2": -0.005}, None, _two_minima,
        lambda f: (f, 1.0),
    )  # fmt: skip
    assert (fit, moves) == (1.0, [])


def test_the_restart_sentence_names_the_moved_fits():
    moves = [
        {
            "K": 5.25,
            "L": 13.7,
            "chi2": 40.6,
            "K_from": 2.89,
            "L_from": 3.77,
            "chi2_from": 45.77,
            "K_to": 5.32,
            "L_to": 14.1,
            "chi2_to": 40.21,
            "kept": 1.0,
        }
    ]
    text = ss.restarts_text([SimpleNamespace(run="b", restarts=moves),
                             SimpleNamespace(run="a", restarts=[])])  # fmt: skip
    assert text == (
        "The joint fits are global over the scan: where a grid point's chi^2 lay more than 0.01 "
        "below the fit's, the optimiser was restarted from it: b from K = 2.89, L = 3.77 d "
        "(chi^2 = 45.77) via the grid point K = 5.25, L = 13.7 d (chi^2 = 40.6) to K = 5.32, "
        "L = 14.1 d (chi^2 = 40.21, -5.56)."
    )
    assert ss.restarts_text([SimpleNamespace(run="a", restarts=[])]) == ""


def _zone_scan(measured_beyond):
    """A scan whose departure beyond the null is 0.05 ln(L/0.5) + 0.02 (1 - K/10): lowest at
    small L and large K; its 95% region at K 2-3, L 3-6 d."""
    k, ll = np.linspace(0.0, 10.0, 11), np.geomspace(0.5, 100.0, 11)
    kk, lg = np.meshgrid(k, ll, indexing="ij")
    beyond = 0.05 * np.log(lg / 0.5) + 0.02 * (1.0 - kk / 10.0)
    chi2 = np.where((kk >= 2) & (kk <= 3) & (lg >= 3) & (lg <= 6), 10.0, 100.0)
    grid = (k, ll, beyond + 0.01, chi2, np.full(beyond.shape, 0.01), "range")
    return SimpleNamespace(
        run="r", grids=lambda: [grid], measured_beyond=measured_beyond, measured_beyond_se=0.005,
        chi2_min=10.0, threshold=6.0, K=k, L=ll,
    )  # fmt: skip


def test_the_match_zone_is_the_hatched_zone_and_its_sentence_calls_a_sub_grain_l():
    sc = _zone_scan(0.0)  # matches where beyond <= 0.01: K >= 5 at L = 0.5 d only
    z = ss.match_zone(sc)
    assert z["in_region"] is False and z["L"][0] == 0.5 and z["L_bounds"][0] == "range"
    # |beyond| / 0.01 = 1 between L = 0.5 and 0.85 d at K = 10: 0.05 ln(L/0.5) = 0.01
    assert z["L"][1] == pytest.approx(0.5 * math.exp(0.2), rel=1e-9)
    assert z["K"] == [pytest.approx(5.0), 10.0] and z["K_bounds"] == ["data", "range"]
    assert ss.match_zone_text([sc]) == (
        "Outside the 95% region, where the model's first-layer departure beyond its null comes "
        "within 2 se of the data's (the scan figure's hatched zone, interpolated between grid "
        "points as the region is): r's only match is at a sub-grain L (< 0.61 d), K >= 5."
    )
    assert ss.match_zone(_zone_scan(-1.0)) is None  # nowhere within 2 se
    inside = _zone_scan(0.05 * math.log(8.0) + 0.02 * 0.75)  # the region's point (2.5, 4)
    assert ss.match_zone(inside)["in_region"] is True
    assert ss.match_zone_text([inside]) == ""


def _two_basins(k, ll):
    """Two basins of Delta chi^2: 0 at (K 5.3, L 14 d) and 5.56 at (K 2.9, L 3.8 d), each
    rising as a paraboloid of width 0.3 in K and 0.1 in ln L; a ridge between them."""
    kk, lg = np.meshgrid(k, ll, indexing="ij")
    a = ((kk - 5.3) / 0.3) ** 2 + (np.log(lg / 14.0) / 0.1) ** 2
    b = 5.56 + ((kk - 2.9) / 0.3) ** 2 + (np.log(lg / 3.8) / 0.1) ** 2
    return np.minimum(a, b)


def _basin_scan(extra):
    k, ll = np.linspace(0.0, 10.0, 11), np.geomspace(0.5, 100.0, 11)
    kn, ln = np.linspace(4.5, 6.0, 11), np.geomspace(11.0, 17.0, 11)
    return SimpleNamespace(
        run="r", fit=None, K=k, L=ll, chi2=40.0 + _two_basins(k, ll), chi2_min=40.0,
        K_near=kn, L_near=ln, chi2_near=40.0 + _two_basins(kn, ln), patches=[], extra=extra,
        threshold=6.02,
    )  # fmt: skip


def test_a_solved_point_in_a_second_basin_makes_the_region_two_islands():
    # the grid alone: the second basin's grid point (K 3, L 4.2 d) is above the threshold
    # (the referee's 6.14), so the region is one island
    alone = ss.scan_region(_basin_scan([]))
    assert [len(alone["islands"])] == [1] and alone["L"][0] > 10.0
    assert not ss.islands_disjoint_in_l(alone)
    assert "islands" not in ss.region_text(alone)
    # a restart's start at the old optimum, Delta chi^2 5.56 < 6.02, is a point of the region
    start = {"K": 2.9, "L": 3.8, "chi2": 45.56, "source": "the first fit (a restart's start)"}
    reg = ss.scan_region(_basin_scan([start]))
    assert len(reg["islands"]) == 2 and ss.islands_disjoint_in_l(reg)
    low = min(reg["islands"], key=lambda i: i["L"][0])
    assert low["K"] == [2.9, 2.9] and low["L"] == [3.8, 3.8] and low["points"] == 1
    assert low["delta_chi2"] == pytest.approx(5.56)
    assert reg["L"][0] == 3.8 and reg["L"][1] == alone["L"][1] and reg["K"][0] == 2.9
    text = ss.region_text(reg)
    assert text.startswith("two islands: K 2.9, L ~3.8 d and K ")
    assert f"; L unidentified: 3.8-{alone['L'][1]:.3g} d, two basins" in text
    # the cell refined around it (refine_around's patch) joins it: still two islands
    kk, ll = ss.cell_axes(np.linspace(0.0, 10.0, 11), np.geomspace(0.5, 100.0, 11), 2, 3)
    sc = _basin_scan([start])
    sc.patches = [SimpleNamespace(K=kk, L=ll, chi2=40.0 + _two_basins(kk, ll))]
    two = ss.scan_region(sc)
    assert len(two["islands"]) == 2
    low = min(two["islands"], key=lambda i: i["L"][0])
    inside = int(np.count_nonzero(_two_basins(kk, ll) <= 6.02))
    assert inside >= 1 and low["points"] == 1 + inside
    assert low["K"][1] == 3.0 and low["L"][0] < 3.8
    # outside the threshold the point is no island
    far = ss.scan_region(_basin_scan([{**start, "chi2": 46.1}]))
    assert len(far["islands"]) == 1 and far["L"] == alone["L"]


def test_the_grey_is_where_no_grid_has_a_solution():
    from cosserat.viz.validation import no_solution_cells, region_short

    # the range grid solves to L[6] = 12 d; a refined patch of the cell L[6]-L[7] solves to
    # 17.9 d at K 4-5 (the referee's smooth_H20)
    d = _valley(K, L)
    kk, ll = ss.cell_axes(K, L, 4, 6)
    none, bound = no_solution_cells(K, L, d, [(kk, ll, _valley(kk, ll))])
    assert none.shape == bound.shape == (K.size - 1, L.size - 1)
    # cells with every corner beyond 20 d: no grid has a solution
    assert none[:, 7:].all() and not none[:, :7].any()
    # the cell column 12-20 d holds the existence bound: some corners solve, some do not,
    # the patch's solutions inside one of them; no cell is both
    assert bound[:, 6].all() and not bound[:, :6].any() and not (none & bound).any()
    # a cell whose range-grid corners all fail but a finer grid solves inside is not grey
    d2 = d.copy()
    d2[4:6, 6] = np.nan
    none2, _ = no_solution_cells(K, L, d2, [(kk, ll, _valley(kk, ll))])
    assert not none2[4, 6]
    assert none_solved_only_by_range(K, L, d2)[4, 6]
    # the title names the islands
    reg = {
        "K": [2.9, 6.0],
        "L": [3.8, 15.3],
        "K_bounds": ["point", "data"],
        "L_bounds": ["point", "data"],
        "islands": [{"K": [4.7, 6.0], "L": [11.9, 15.3]}, {"K": [2.9, 2.9], "L": [3.8, 3.8]}],
    }
    assert region_short({"region": reg}) == "95% region: 2 islands, L ~3.8 and 11.9-15.3 d"


def none_solved_only_by_range(k, ll, d):
    from cosserat.viz.validation import no_solution_cells

    return no_solution_cells(k, ll, d)[0]


def _pass_grid(middle):
    """Two islands on one row of a 3 x 5 grid, Delta chi^2 0 at (K 0, L 1) and 5.5 at (K 0,
    L 16), the row between them 9, 20, 9; ``middle``: the second row's centre (a bypass)."""
    k, ll = np.array([0.0, 1.0, 2.0]), np.geomspace(1.0, 16.0, 5)
    d = np.full((3, 5), 50.0)
    d[0] = [0.0, 9.0, 20.0, 9.0, 5.5]
    d[1, 2] = middle
    return k, ll, d


def test_the_saddle_is_the_lowest_level_that_joins_the_islands():
    for middle, want in ((50.0, 20.0), (8.0, 9.0)):  # over the ridge, or round it at 9
        k, ll, d = _pass_grid(middle)
        grids = [(k, ll, d, "refined")]
        others = ss.region_pieces(grids, 6.0, (0.0, 1.0))[1]
        assert len(others) == 1 and others[0]["L"] == [16.0, 16.0]
        assert ss.island_saddle(grids, 6.0, (0.0, 1.0), others[0]["masks"]) == (want, "refined")
    # the declared ranges' grid is used only where the finer ones do not join the islands
    k, ll, d = _pass_grid(50.0)
    grids = [(k, ll, d, "range")]
    piece = ss.region_pieces(grids, 6.0, (0.0, 1.0))[1][0]["masks"]
    assert ss.island_saddle(grids, 6.0, (0.0, 1.0), piece) == (20.0, "all")
    # finer grids holding none of the optimum's island (a cell refined around the other
    # island alone) do not set the saddle: the grids do
    cell = (np.array([0.0, 0.5]), np.array([11.0, 16.0]), np.array([[5.8, 5.5], [7.0, 7.0]]),
            "refined")  # fmt: skip
    both = [(k, ll, d, "range"), cell]
    main, others, _ = ss.region_pieces(both, 6.0, (0.0, 1.0))
    assert main[0][0, 0] and not main[1].any() and len(others) == 1
    assert ss.island_saddle(both, 6.0, (0.0, 1.0), others[0]["masks"], main) == (20.0, "all")
    # no finite level joins islands separated by points without a solution
    d2 = d.copy()
    d2[:, 2] = np.nan
    piece = ss.region_pieces([(k, ll, d2, "range")], 6.0, (0.0, 1.0))[1][0]["masks"]
    assert ss.island_saddle([(k, ll, d2, "range")], 6.0, (0.0, 1.0), piece) is None


def test_the_small_islands_ends_and_saddle_are_told():
    # the referee's smooth_H20 (round 14, point 5): a restart's fit is the small island's
    # end; the refined points next beyond it, outside, bound it, else it is unresolved; the
    # path between the islands climbs over the two basins' ridge
    start = {"K": 2.9, "L": 3.8, "chi2": 45.56, "source": "the first fit (a restart's start)"}
    kk, ll = ss.cell_axes(np.linspace(0.0, 10.0, 11), np.geomspace(0.5, 100.0, 11), 2, 3)
    sc = _basin_scan([start])
    sc.patches = [SimpleNamespace(K=kk, L=ll, chi2=40.0 + _two_basins(kk, ll))]
    reg = ss.scan_region(sc)
    low = min(reg["islands"], key=lambda i: i["L"][0])
    ends = {(e["name"], e["end"]): e for e in low["point_ends"]}
    assert set(ends) == {("K", "upper"), ("L", "upper")}
    # L's upper end is the fit (3.8 d); the patch's last L, 4.16 d, is next beyond it
    assert ends["L", "upper"]["fit"] and ends["L", "upper"]["at"] == 3.8
    assert ends["L", "upper"]["next"] == ll[-1]
    assert ends["L", "upper"]["delta_chi2"] == pytest.approx(np.min(_two_basins(kk, ll[-1:])))
    assert ends["L", "upper"]["delta_chi2"] > 6.02
    # K's upper end is the patch's own last K (inside): nothing refined beyond it
    assert not ends["K", "upper"]["fit"] and ends["K", "upper"]["next"] is None
    saddle = low["saddle"]
    assert saddle["threshold"] == 6.02
    # 3 sigma for k = 2, scaled as the 95% threshold is: 6.02 x ppf(0.9973) / ppf(0.95)
    assert saddle["threshold_3sigma"] == pytest.approx(6.02 * 11.829 / 5.9915, rel=1e-3)
    # the refined grids alone (the patch and the finer box) do not join: the grids do
    assert saddle["grids"] == "all" and saddle["delta_chi2"] > saddle["threshold_3sigma"]
    text = ss.region_text(reg)
    assert (
        f"; the island at {ss._piece_text(low)} ends at a solved point in K (upper) and L "
        f"(upper) (the refined points next beyond it, L {ll[-1]:.3g} d, are outside: Delta "
        f"chi^2 >= {ends['L', 'upper']['delta_chi2']:.3g}), no refined point beyond it in K "
        "(upper): unresolved there; the path between the islands climbs to Delta chi^2 "
        f"~{sum(saddle['range']) / 2:.2g} ({saddle['range'][0]:.3g}-{saddle['delta_chi2']:.3g} "
        "on the grid points: the pass and its lowest neighbours towards each island) (the "
        "saddle on the grids, at their resolution): separate basins at 95% (threshold 6.02) "
        f"and at 3 sigma ({saddle['threshold_3sigma']:.3g}) at the pass's point only (its "
        "range reaches below), at grid resolution; the island at "
        f"{ss._piece_text(low)} exists only just: its least Delta chi^2 5.56 against the "
        "threshold 6.02"
    ) in text
    # on the declared ranges' grid the pass is one step from the small island's own point
    assert saddle["range"][0] == pytest.approx(low["delta_chi2"])
    assert saddle["delta_chi2"] == pytest.approx(float(np.min(
        _two_basins(np.array([saddle["pass"]["K"]]), np.array([saddle["pass"]["L"]]))
    )))  # fmt: skip
    # the fit alone: each of its ends unresolved
    alone = min(ss.scan_region(_basin_scan([start]))["islands"], key=lambda i: i["L"][0])
    assert ss._point_ends_text(alone) == (
        "; the island at K 2.9, L ~3.8 d ends at a restart's fit in K (lower, upper) and L "
        "(lower, upper), no refined point beyond it in K (lower, upper) and L (lower, upper): "
        "unresolved there"
    )
    # below the 3-sigma threshold the text says so
    one = {**low, "saddle": {**saddle, "delta_chi2": 10.0}}
    assert ", not at 3 sigma (11.9); the island at" in ss._saddle_text(one, True)
    assert ss._beyond_all(3.0, np.array([1.0, 2.0])) == 1
    assert ss._beyond_all(0.5, np.array([1.0, 2.0])) == -1
    assert ss._beyond_all(1.5, np.array([1.0, 2.0])) == 0 == ss._beyond_all(1.0, np.zeros(0))


def _restart_record():
    """A scan record with a cell refined around a restart's fit (the referee's smooth_H20,
    round 14, point 5), and the cell's K and L axes."""
    k, ll = np.linspace(0.0, 10.0, 11), np.geomspace(0.5, 100.0, 11)
    kk, lc = ss.cell_axes(k, ll, 2, 3)
    zeros = np.zeros((11, 11))

    def grid(K, L, d):
        return {"K": list(K), "L": list(L), "departure": (0.01 + 0.0 * d).tolist(),
                "null": (0.0 * d).tolist(), "delta_chi2": d.tolist()}  # fmt: skip

    cell = {**grid(kk, lc, _two_basins(kk, lc)), "base": "the fit at K = 2.9, L = 3.8 d"}
    island = {"K": [2.75, 2.9], "L": [3.65, 3.8]}
    rec = {
        "run": "r", "measured": -0.3, "measured_beyond_null": -0.28,
        "measured_beyond_null_se": 0.03, "best_K": 5.3, "best_L": 14.0,
        "best_beyond_null": 0.09, "threshold": 6.02, "phi": 18.1, "delta": {"moving": 13.2},
        "grids": {"range": grid(k, ll, _two_basins(k, ll) + zeros), "near": grid(k, ll, zeros)},
        "refined": [cell],
        "extra": [{"K": 2.9, "L": 3.8, "delta_chi2": 5.56}],
        "region": {"K": [2.75, 6.0], "L": [3.65, 15.0], "K_bounds": ["data", "data"],
                   "L_bounds": ["data", "data"],
                   "islands": [{"K": [4.7, 6.0], "L": [11.9, 15.0]}, island]},
    }  # fmt: skip
    return rec, kk, lc


def test_the_scan_figure_zooms_on_the_cells_refined_around_a_restarts_fit():
    """The cell refined around a restart's fit is drawn (dashed outline, its points) and
    zoomed in an inset with the island's extent, and the key below the panels is >= 8 pt and
    inside the figure (referee 14, points 5 and 8)."""
    import matplotlib.pyplot as plt

    from cosserat.viz.validation import KEY_POINTS, spin_scan_figure

    rec, kk, lc = _restart_record()
    fig = spin_scan_figure([rec])
    panel = fig.axes[0]
    (inset,) = panel.child_axes
    assert inset.get_xlim() == pytest.approx((lc[0], lc[-1]))
    assert inset.get_ylim() == pytest.approx((kk[0], kk[-1]))
    assert "refined around" in inset.get_title()
    # the island's extent as a box, its corners the region's
    boxes = [ln.get_xydata() for ln in inset.get_lines() if len(ln.get_xdata()) == 5]
    assert any(np.allclose(b[:4], [[3.65, 2.75], [3.8, 2.75], [3.8, 2.9], [3.65, 2.9]])
               for b in boxes)  # fmt: skip
    # the cell's outline in the panel (dashed) and its points
    dashed = [ln for ln in panel.get_lines() if ln.get_linestyle() == "--"
              and len(ln.get_xdata()) == 5]  # fmt: skip
    assert any(np.allclose(ln.get_xdata()[:2], [lc[0], lc[-1]]) for ln in dashed)
    (note,) = fig.texts
    assert note.get_fontsize() == KEY_POINTS >= 8.0
    fig.canvas.draw()
    box = note.get_window_extent()
    assert box.x0 >= 0.0 and box.y0 >= 0.0 and box.x1 <= fig.bbox.width
    assert box.y1 < panel.get_window_extent().y0  # below the panels, clear of the x label
    plt.close(fig)


def test_the_scan_insets_caption_hides_no_tick_label():
    """Referee 16, point 6: in six panels (the shipped corpus's figure) as saved (the
    package's style, at the saved dpi), the inset's caption box stays inside its panel and
    clear of the panel's K tick labels (it hid K = 8)."""
    import io

    import matplotlib.pyplot as plt

    from cosserat.viz.plotting import style
    from cosserat.viz.validation import spin_scan_figure

    rec = _restart_record()[0]
    seen = []

    def check(event):
        renderer = event.renderer
        for panel in event.canvas.figure.axes:
            for inset in panel.child_axes:
                title = inset.title  # its white box: the text and the box's pad (0.3 em)
                pad = 0.3 * title.get_fontsize() * renderer.points_to_pixels(1.0)
                caption = title.get_window_extent(renderer).padded(pad)
                ticks = [t for t in panel.get_yticklabels() if t.get_visible() and t.get_text()]
                seen.append(
                    (
                        caption.x0 > panel.get_window_extent(renderer).x0,
                        len(ticks),
                        [t.get_text() for t in ticks
                         if caption.overlaps(t.get_window_extent(renderer))],
                    )
                )  # fmt: skip

    with style():
        fig = spin_scan_figure([{**rec, "run": f"r{i}"} for i in range(6)])
        fig.canvas.mpl_connect("draw_event", check)
        fig.savefig(io.BytesIO(), format="png")
    plt.close(fig)
    assert seen and len(seen) % 6 == 0  # each panel at each draw (a tight bbox draws twice)
    assert all(inside and n >= 5 and not hidden for inside, n, hidden in seen), seen


def test_the_scan_inset_is_opaque_above_the_dots_and_its_labels_clear():
    """Referee 18, point 3: the panel's grid dots sat on the inset's K ticks 2.2 and 2.8 and
    the L label's box hid half of its tick "3". As saved (the package's style), the inset is
    white, above the panel's dots and outlines, its white backing under every tick and axis
    label, and its L label clear of its L tick labels."""
    import io

    import matplotlib.pyplot as plt
    from matplotlib.colors import to_rgba
    from matplotlib.patches import Rectangle

    from cosserat.viz.plotting import style
    from cosserat.viz.validation import INSET_ZORDER, spin_scan_figure

    rec = _restart_record()[0]
    seen = []

    def check(event):
        renderer = event.renderer
        (panel,) = [a for a in event.canvas.figure.axes if a.child_axes]
        (inset,) = panel.child_axes
        (back,) = [p for p in inset.patches if isinstance(p, Rectangle)
                   and p.get_data_transform() == inset.transAxes]  # fmt: skip
        white = back.get_window_extent(renderer)
        ticks = [t for t in inset.get_xticklabels() + inset.get_yticklabels() if t.get_text()]
        labels = [*ticks, inset.xaxis.label, inset.yaxis.label]
        inside = [white.x0 <= b.x0 and b.x1 <= white.x1 and white.y0 <= b.y0 and b.y1 <= white.y1
                  for b in (t.get_window_extent(renderer) for t in labels)]  # fmt: skip
        em = 0.3 * inset.xaxis.label.get_fontsize() * renderer.points_to_pixels(1.0)
        lab = inset.xaxis.label.get_window_extent(renderer).padded(em)  # as if it had a box
        hit = [t.get_text() for t in inset.get_xticklabels()  # below them all, not only beside
               if t.get_text() and lab.y1 >= t.get_window_extent(renderer).y0]  # fmt: skip
        seen.append((len(ticks), all(inside), hit, to_rgba(back.get_facecolor())))

    with style():
        fig = spin_scan_figure([rec])
        panel = fig.axes[0]
        (inset,) = panel.child_axes
        assert to_rgba(inset.get_facecolor()) == to_rgba("white")
        assert inset.get_zorder() == INSET_ZORDER
        under = [ln.get_zorder() for ln in panel.get_lines() if ln.get_marker() == "."]
        under += [ln.get_zorder() for ln in panel.get_lines() if ln.get_linestyle() == "--"]
        assert under and INSET_ZORDER > max(under)
        fig.canvas.mpl_connect("draw_event", check)
        fig.savefig(io.BytesIO(), format="png")
    plt.close(fig)
    assert seen
    assert all(n >= 4 and ok and not hit and rgba == to_rgba("white")
               for n, ok, hit, rgba in seen), seen  # fmt: skip


def test_the_scan_figure_draws_the_saddles_cells_and_pass_and_names_the_insets_axes():
    """Referee 15, point 4: a refined cell with no point inside the region (the saddle's,
    K 4-5 x L 7.07-12 d in smooth_H20) is outlined and its points drawn, the pass marked (X),
    the star above every dot; the inset's axes are named, its L tick labels apart, and its
    white (not refined) said."""
    import matplotlib.pyplot as plt

    from cosserat.viz.validation import SCAN_KEY, inset_ticks, spin_scan_figure

    k, ll = np.linspace(0.0, 10.0, 11), np.geomspace(0.5, 100.0, 11)
    kk, lc = ss.cell_axes(k, ll, 2, 3)
    ks, ls = ss.cell_axes(k, ll, 4, 5)  # K 4-5, L 7.07-12 d

    def grid(K, L, d):
        return {"K": list(K), "L": list(L), "departure": (0.01 + 0.0 * d).tolist(),
                "null": (0.0 * d).tolist(), "delta_chi2": d.tolist()}  # fmt: skip

    saddle_cell = grid(ks, ls, 12.0 + 0.0 * _two_basins(ks, ls))
    pass_at = {"K": float(ks[2]), "L": float(ls[1])}
    rec = {
        "run": "r", "measured": -0.3, "measured_beyond_null": -0.28,
        "measured_beyond_null_se": 0.03, "best_K": 5.3, "best_L": 14.0,
        "best_beyond_null": 0.09, "threshold": 6.02, "phi": 18.1, "delta": {"moving": 13.2},
        "grids": {"range": grid(k, ll, _two_basins(k, ll)),
                  "near": grid(k, ll, np.zeros((11, 11)))},
        "refined": [saddle_cell, {**grid(kk, lc, _two_basins(kk, lc)), "base": "the fit"}],
        "extra": [{"K": 2.9, "L": 3.8, "delta_chi2": 5.56}],
        "region": {"K": [2.75, 6.0], "L": [3.65, 15.0], "K_bounds": ["data", "data"],
                   "L_bounds": ["data", "data"],
                   "islands": [{"K": [4.7, 6.0], "L": [11.9, 15.0]},
                               {"K": [2.75, 2.9], "L": [3.65, 3.8],
                                "saddle": {"pass": pass_at}}]},
    }  # fmt: skip
    fig = spin_scan_figure([rec])
    panel = fig.axes[0]
    solid = [ln for ln in panel.get_lines() if ln.get_linestyle() == "-"
             and len(ln.get_xdata()) == 5]  # fmt: skip
    assert any(np.allclose(ln.get_xdata()[:2], [ls[0], ls[-1]])
               and np.allclose(ln.get_ydata()[1:3], [ks[0], ks[-1]]) for ln in solid)  # fmt: skip
    # its 25 points, all outside the region, drawn
    assert any(len(ln.get_xdata()) == 25 and np.allclose(sorted(set(ln.get_xdata())), ls)
               for ln in panel.get_lines())  # fmt: skip
    (mark,) = [ln for ln in panel.get_lines() if ln.get_marker() == "X"]
    assert (mark.get_xdata()[0], mark.get_ydata()[0]) == (pass_at["L"], pass_at["K"])
    (star,) = [ln for ln in panel.get_lines() if ln.get_marker() == "*"]
    assert star.get_zorder() > max(ln.get_zorder() for ln in panel.get_lines()
                                   if ln.get_marker() == ".")  # fmt: skip
    (inset,) = panel.child_axes
    assert (inset.get_xlabel(), inset.get_ylabel()) == ("L [d]", "K [-]")
    assert "white: not refined" in inset.get_title() and "white: not refined" in SCAN_KEY
    fig.canvas.draw()
    boxes = [t.get_window_extent() for t in inset.get_xticklabels() if t.get_text()]
    assert len(boxes) >= 2
    assert all(a.x1 < b.x0 for a, b in itertools.pairwise(boxes))
    plt.close(fig)
    # ticks a quarter of the span apart in log L: "3.5" and "5" overlapped over 2.45-7.07 d
    assert inset_ticks(2.45, 7.07) == [3.0, 4.0, 7.0]
    assert inset_ticks(12.0, 20.4) == [15.0, 20.0]


def test_the_saddle_is_told_as_a_range_at_grid_resolution():
    # referee 15, point 4: the pass (20, over the ridge) steps down to 9 towards each island,
    # so the saddle is ~14 (9-20); a pass of two points (round the ridge at 9 by 8) has none
    k, ll, d = _pass_grid(50.0)
    grids = [(k, ll, d, "refined")]
    main, others, _ = ss.region_pieces(grids, 6.0, (0.0, 1.0))
    got = ss.island_saddle(grids, 6.0, (0.0, 1.0), others[0]["masks"], main)
    assert got == (20.0, "refined")
    assert ss.saddle_pass(grids, got, (0.0, 1.0), others[0]["masks"]) == (9.0, 0.0, 4.0)
    k, ll, d8 = _pass_grid(8.0)
    piece = ss.region_pieces([(k, ll, d8, "refined")], 6.0, (0.0, 1.0))[1][0]["masks"]
    assert ss.saddle_pass([(k, ll, d8, "refined")], (9.0, "refined"), (0.0, 1.0), piece) is None
    island = {"K": [0.0, 0.0], "L": [16.0, 16.0], "delta_chi2": 5.5,
              "saddle": {"delta_chi2": 20.0, "grids": "refined", "range": [9.0, 20.0],
                         "threshold": 6.0, "threshold_3sigma": 11.8}}  # fmt: skip
    assert ss._saddle_text(island, True) == (
        "; the path between the islands climbs to Delta chi^2 ~14 (9-20 on the refined "
        "points: the pass and its lowest neighbours towards each island) (the saddle on the "
        "refined grids, at their resolution): separate basins at 95% (threshold 6) and at 3 "
        "sigma (11.8) at the pass's point only (its range reaches below), at grid resolution; "
        "the island at K 0, L ~16 d exists only just: its "
        "least Delta chi^2 5.5 against the threshold 6"
    )
    # the low end above the 3-sigma threshold: the margin, from the range's middle
    far = {**island, "delta_chi2": 1.0,
           "saddle": {**island["saddle"], "range": [12.7, 13.6], "delta_chi2": 13.6,
                      "threshold": 6.02, "threshold_3sigma": 11.9}}  # fmt: skip
    assert ss._saddle_text(far, True).endswith(
        "~13 (12.7-13.6 on the refined points: the pass and its lowest neighbours towards "
        "each island) (the saddle on the refined grids, at their resolution): separate basins "
        "at 95% (threshold 6.02) and at 3 sigma (11.9) by a margin of ~1, at grid resolution"
    )
