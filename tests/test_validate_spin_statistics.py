"""The spin verdicts' statistics and figure (referee 8, points 8 and 9).

* The scan figure's hatched band (:func:`cosserat.viz.validation.band_cells`): where the
  model's departure beyond its null, interpolated between the grid's points, comes within 2 se
  of the data's; found even where no grid point lies inside it (the v2 smooth run's band,
  which the figure used to miss).
* The size rule's z read under Student's t with the blocks' dof (``verdicts.t_p``).
* The covariance of omega and half the vorticity: the sidecar's per-bin correlation of their
  block means where it records one (``cosserat.dem.coarse.block_correlation``), "independent
  (bound)" where it does not.
"""

from __future__ import annotations

import dataclasses
import json
import math
import subprocess
import sys

import numpy as np
import pytest
from scipy.stats import t as student_t

from cosserat.analysis.corpus import read_run, write_run
from cosserat.dem.coarse import block_correlation
from cosserat.errors import InputError
from cosserat.studies.validate import measures
from cosserat.studies.validate import spin_scan as ss
from cosserat.studies.validate.synthetic import synthetic_run
from cosserat.studies.validate.verdicts import t_p
from cosserat.viz.validation import band_cells, hatch_cells, refine_grid, spin_scan_figure

PHI = 20.0
ROUGH = math.degrees(math.atan(math.sin(math.radians(PHI))))


@pytest.fixture(scope="module")
def pair(tmp_path_factory):
    folder = tmp_path_factory.mktemp("pair")
    runs = []
    for name, wall, delta, seed in (("rough", "rough", ROUGH, 0), ("smooth", "smooth", 15.0, 1)):
        path = synthetic_run(
            folder, name, "cosserat", "plane", 10.0,
            parameters={"phi": PHI, "L": 3.0, "K": 0.5, "delta": delta}, wall=wall, B=1.0,
            noise=0.005, stress_noise=0.005, seed=seed,
        )  # fmt: skip
        runs.append(read_run(path))
    return tuple(runs)


@pytest.fixture(scope="module")
def scan(pair):
    rough, smooth = pair
    return ss.scan_run(rough, [rough, smooth], points=2)


# --------------------------------------------------------------------------- the hatch
def test_the_band_between_two_grid_points_is_found():
    """values = the column index: [0.4, 0.6] lies between the first two columns, at no grid
    point; refined 4 times, the fine cells [0.25, 0.5] and [0.5, 0.75] reach it, no other."""
    values = np.tile(np.arange(3.0), (2, 1))
    xe, ye, mask = band_cells([0.0, 1.0, 2.0], [0.0, 1.0], values, 0.4, 0.6, refine=4)
    np.testing.assert_allclose(xe, np.linspace(0.0, 2.0, 9))
    np.testing.assert_allclose(ye, np.linspace(0.0, 1.0, 5))
    assert mask.shape == (4, 8)
    expected = np.zeros(8, dtype=bool)
    expected[[1, 2]] = True
    assert (mask == expected).all()
    # the old rule (grid points within the band) finds nothing here
    assert not np.any(np.abs(values - 0.5) <= 0.1)


def test_the_band_is_hatched_as_one_patch_covering_exactly_its_cells():
    """hatch_cells: one patch (Agg hatched each of pcolor's cells on its own: 30 s for the
    shipped corpus's figure), one rectangle per run of a row's cells; the centre of every cell
    of the mask is inside it, of every other cell outside, and its area is the cells'."""
    from matplotlib.figure import Figure

    xe = np.array([1.0, 2.0, 4.0, 8.0, 16.0])
    ye = np.array([0.0, 0.5, 1.5, 2.0])
    mask = np.array([[1, 1, 0, 1], [0, 0, 0, 0], [0, 1, 1, 1]], dtype=bool)
    ax = Figure().subplots()
    ax.set_xscale("log")
    hatch_cells(ax, xe, ye, mask, "////", "0.15")
    (patch,) = ax.patches
    assert patch.get_hatch() == "////" and patch.get_facecolor()[3] == 0.0
    path = patch.get_path()
    rectangles = path.vertices.reshape(-1, 5, 2)
    assert len(rectangles) == 3  # (0-1, 3) in row 0, (1-3) in row 2
    area = sum((r[1, 0] - r[0, 0]) * (r[2, 1] - r[1, 1]) for r in rectangles)
    widths, heights = np.diff(xe), np.diff(ye)
    assert area == pytest.approx(float(np.sum(np.outer(heights, widths)[mask])))
    for j, i in np.ndindex(*mask.shape):
        centre = (0.5 * (xe[i] + xe[i + 1]), 0.5 * (ye[j] + ye[j + 1]))
        assert path.contains_point(centre) == mask[j, i]
    hatch_cells(ax, xe, ye, np.zeros_like(mask), "////", "0.15")  # nothing: no patch
    assert len(ax.patches) == 1


def test_a_log_axis_is_refined_geometrically_and_no_solution_is_never_hatched():
    values = np.array([[0.0, 1.0, np.nan], [0.0, 1.0, 2.0]])
    x, y, fine = refine_grid([1.0, 10.0, 100.0], [0.0, 1.0], values, refine=2, log_x=True)
    np.testing.assert_allclose(x, [1.0, math.sqrt(10.0), 10.0, math.sqrt(1000.0), 100.0])
    np.testing.assert_allclose(y, [0.0, 0.5, 1.0])
    assert fine[0, 1] == pytest.approx(0.5) and math.isnan(fine[0, 3])
    assert fine[0, 2] == 1.0  # a grid point keeps its value beside a NaN
    _, _, mask = band_cells([1.0, 10.0, 100.0], [0.0, 1.0], values, 1.4, 1.6, refine=2)
    # the band lies between x = 10 and 100, where every fine cell has a corner in the cell
    # of the point without a solution: none is hatched
    assert not mask.any()
    values[0, 2] = 2.0
    _, _, mask = band_cells([1.0, 10.0, 100.0], [0.0, 1.0], values, 1.4, 1.6, refine=2)
    assert mask[:, 2].all() and mask[:, 3].all() and not mask[:, :2].any()


def test_the_v2_smooth_runs_band_is_hatched():
    """The smooth v2 run's range grid at K = 0, 1.25 (L = 0.5-7.07 d; cosserat validate
    /tmp/v2corp --spin-scan 9): the measured -0.178 +- 0.024 lies between the points, and one
    point only (-0.161) fell within 2 se, which contourf cannot fill: the panel had no hatch."""
    L = [0.5, 0.97, 1.88, 3.65, 7.07]
    K = [0.0, 1.25]
    dep = np.array(
        [[-0.355, -0.265, -0.161, -0.075, 0.008], [-0.100, -0.108, -0.086, -0.047, 0.006]]
    )
    lo, hi = -0.178 - 2 * 0.024, -0.178 + 2 * 0.024
    assert np.count_nonzero((dep >= lo) & (dep <= hi)) == 1
    xe, _, mask = band_cells(L, K, dep, lo, hi, log_x=True)
    assert mask.any()
    # where the K = 0 row crosses -0.178: between L = 0.97 and 1.88 d (the interpolation in
    # ln L puts -0.178 at 0.97 (1.88/0.97)^((0.265-0.178)/(0.265-0.161)))
    cross = 0.97 * (1.88 / 0.97) ** ((0.265 - 0.178) / (0.265 - 0.161))
    centres = np.sqrt(xe[:-1] * xe[1:])
    assert mask[0, int(np.argmin(np.abs(centres - cross)))]
    assert not mask[0, centres < 0.6].any() and not mask[0, centres > 5.0].any()


def _record(scan_record, dep, null, measured, se):
    K, L = [0.0, 1.25], [0.5, 0.97, 1.88, 3.65, 7.07]
    grid = {
        "K": K,
        "L": L,
        "departure": dep,
        "null": null,
        "delta_chi2": [[50.0] * 5, [40.0] * 5],
    }
    return {
        **scan_record,
        "measured_beyond_null": measured,
        "measured_beyond_null_se": se,
        "grids": {"range": grid, "near": grid},
    }


def test_the_scan_figure_colours_beyond_the_null_and_hatches_the_band(scan, tmp_path):
    """The colours are departure - null (a null of -0.07 shifts every value by +0.07) and the
    band is drawn as one hatched patch per grid (:func:`hatch_cells`)."""
    from matplotlib.collections import QuadMesh

    rec = json.loads(json.dumps(scan.to_dict()))
    assert set(rec["grids"]["range"]) == {"K", "L", "departure", "null", "delta_chi2"}
    dep = [[-0.355, -0.265, -0.161, -0.075, 0.008], [-0.100, -0.108, -0.086, -0.047, 0.006]]
    null = [[-0.07] * 5, [-0.07] * 5]
    fig = spin_scan_figure([_record(rec, dep, null, -0.107, 0.021)])
    panel = fig.axes[0]
    meshes = [c for c in panel.collections if isinstance(c, QuadMesh)]
    assert meshes
    values = np.ma.filled(meshes[0].get_array(), np.nan)
    assert np.nanmax(values) == pytest.approx(0.008 + 0.07, abs=0.01)  # a corner cell's mean
    assert np.nanmin(values) <= -0.355 + 0.07 + 0.05
    hatched = [p for p in panel.patches if p.get_hatch()]
    assert len(hatched) == 2 and all(p.get_hatch() == "////" for p in hatched)
    assert "beyond the null: data -0.107 +- 0.021" in panel.get_title()
    assert "beyond its null" in fig.axes[1].get_ylabel()
    # plain tick labels on the log axis, and the legend text below the panels, off the data
    fig.savefig(tmp_path / "scan.png")
    labels = [t.get_text() for t in panel.get_xticklabels() if t.get_text()]
    assert labels and all("^" not in s and "$" not in s for s in labels)
    (note,) = fig.texts
    assert note.get_position()[1] < 0.1 and "hatched" in note.get_text()


# --------------------------------------------------------------------------- t(9)
def test_the_size_rule_z_is_read_under_t_with_the_blocks_dof(scan):
    stencils = {k: {"data": 0.0, "se": 0.01, "model": 0.05} for k in ("analysis", "wall")}
    ten = dataclasses.replace(scan, stencils=stencils, blocks=10)
    z = ss.size_z(ten)
    p = ss.size_p(ten)
    for k in stencils:
        assert p[k] == t_p(z[k], 10) == pytest.approx(2.0 * student_t.sf(abs(z[k]), 9))
    text = ss._stencil_text(ten)
    assert f"analysis +0.05 ({z['analysis']:+.1f} se, p = {p['analysis']:.2g} under t(9))" in text
    assert ten.to_dict()["size_p_t"] == p and ten.to_dict()["blocks"] == 10
    # 4.3 se under t(9) (referee 8): p = 0.002, not the normal 2e-5
    assert t_p(4.3, 10) == pytest.approx(0.002, abs=5e-5)
    # without recorded blocks there is no t: z alone
    none = dataclasses.replace(ten, blocks=0)
    assert ss.size_p(none) == {"analysis": None, "wall": None}
    assert "under t(" not in ss._stencil_text(none)


# --------------------------------------------------------------------------- covariance
def test_block_correlation_is_the_correlation_of_the_blocks():
    rng = np.random.default_rng(3)
    a = rng.normal(size=(10, 4))
    b = np.stack([2.0 * a[:, 0] + 1.0, -a[:, 1], np.ones(10), a[:, 3]], axis=1)
    b[4, 3] = np.nan
    r = block_correlation(a, b)
    assert r[0] == 1.0 and r[1] == -1.0 and r[2] is None and r[3] is None
    # an estimate on many blocks of a known correlation
    n = 20000
    e1, e2 = rng.normal(size=(2, n, 1))
    est = block_correlation(e1, 0.3 * e1 + math.sqrt(1 - 0.09) * e2)[0]
    assert est == pytest.approx(0.3, abs=4 * (1 - 0.09) / math.sqrt(n))
    with pytest.raises(InputError, match=r"two \(blocks >= 2, bins\) arrays of one shape"):
        block_correlation(a, b[:, :3])


def _with_correlation(run, folder, per_bin):
    meta = {**run.meta, measures.OMEGA_HALF_KEY: {"per_bin": per_bin, "note": "test"}}
    write_run(folder, run.name, meta, dict(run.columns))
    return read_run(folder / f"{run.name}.csv")


def test_the_departures_error_takes_the_sidecars_covariance(pair, tmp_path):
    rough, _ = pair
    n = rough.distance_d.size
    # without the field: independent, and said so
    r, how = measures.omega_half_correlation(rough)
    assert r is None and how == "independent (bound)"
    plain = measures.measure_spin(rough)
    assert plain.notes[0].startswith("omega / half-vorticity covariance: independent (bound).")
    # with it: se^2 = se_o^2 + se_h^2 - 2 r se_o se_h, bin by bin (null: independent)
    per_bin = [0.5] * n
    per_bin[1] = None
    run = _with_correlation(rough, tmp_path, per_bin)
    assert not any("outside the format" in x for x in run.notes)
    spin = measures.measure_spin(run)
    assert spin.notes[0].startswith("omega / half-vorticity covariance: from the sidecar.")
    _, so = run.quantity("omega")
    _, sh = run.quantity("half_vorticity")
    rr = np.where(np.arange(n) == 1, 0.0, 0.5)[spin.rows]
    so, sh = so[spin.rows], sh[spin.rows]
    np.testing.assert_allclose(spin.stderr, np.sqrt(so**2 + sh**2 - 2 * rr * so * sh), rtol=1e-12)
    assert measures.departure_se(0.3, 0.4) == pytest.approx(0.5)
    assert measures.departure_se(0.3, 0.4, 1.0) == pytest.approx(0.1)
    assert measures.departure_se(0.3, 0.4, math.nan) == pytest.approx(0.5)


def test_the_scan_reads_the_covariance_when_present(pair, scan, tmp_path):
    rough, smooth = pair
    assert math.isnan(scan.omega_half_r)
    assert ss.covariance_text(scan) == "omega / half-vorticity covariance: independent (bound)"
    run = _with_correlation(rough, tmp_path, [-0.4] * rough.distance_d.size)
    sc = ss.scan_run(run, [run, smooth], points=2)
    i0 = ss.first_bin(run)
    _, so = run.quantity("omega")
    _, sh = run.quantity("half_vorticity")
    assert sc.omega_half_r == -0.4
    assert sc.measured_se == pytest.approx(
        math.sqrt(so[i0] ** 2 + sh[i0] ** 2 + 0.8 * so[i0] * sh[i0]), rel=1e-12
    )
    assert sc.measured_se > scan.measured_se
    text = ss._describe(sc)
    # which se uses r, and r's sampling sd from the blocks (referee 9, point 8)
    sd = (
        f" (from {sc.blocks} blocks: sampling sd {0.84 / math.sqrt(sc.blocks - 1):.2g} here, "
        f"{1.0 / math.sqrt(sc.blocks - 1):.2g} near 0)"
        if sc.blocks >= 3
        else ""
    )
    assert (
        f"measured {sc.measured:+.3g} +- {sc.measured_se:.2g} (omega / half-vorticity "
        f"covariance from the sidecar: r = -0.40 in this bin{sd}, in the analysis stencil's se "
        "(the other stencils' se take omega and their half vorticity as independent))"
    ) in text
    assert sc.to_dict()["omega_half_correlation"] == -0.4


BAD = {
    "not a list": lambda n: "x",
    "one short": lambda n: [0.1] * (n - 1),
    "beyond 1": lambda n: [2.0] + [0.0] * (n - 1),
    "a string": lambda n: ["0.1"] + [0.0] * (n - 1),
}


@pytest.mark.parametrize("bad", sorted(BAD))
def test_a_malformed_correlation_is_one_line(pair, tmp_path, bad):
    rough, _ = pair
    n = rough.distance_d.size
    run = _with_correlation(rough, tmp_path, BAD[bad](n))
    with pytest.raises(InputError) as err:
        measures.omega_half_correlation(run)
    assert str(err.value) == (
        "run rough: the sidecar's omega_half_vorticity_correlation.per_bin must hold one "
        f"correlation in [-1, 1] (or null) per row of the profile ({n} rows)"
    )


def test_validate_refuses_a_malformed_correlation_in_one_line(pair, tmp_path):
    rough, _ = pair
    _with_correlation(rough, tmp_path / "corpus", [3.0] * rough.distance_d.size)
    proc = subprocess.run(
        [sys.executable, "-m", "cosserat", "validate", str(tmp_path / "corpus"), "--out",
         str(tmp_path / "o"), "--spin-scan", "0", "--models", "mui"],
        capture_output=True, text=True,
    )  # fmt: skip
    assert proc.returncode == 2
    lines = proc.stderr.strip().splitlines()
    assert lines == [
        "cosserat: error: run rough: the sidecar's omega_half_vorticity_correlation.per_bin "
        f"must hold one correlation in [-1, 1] (or null) per row of the profile "
        f"({rough.distance_d.size} rows)"
    ]


# --------------------------------------------------------------------------- the report
def test_the_scan_figure_is_embedded_with_its_caption(scan):
    from types import SimpleNamespace

    from cosserat.studies.validate import report as rp
    from cosserat.viz.report import render

    rec = json.loads(json.dumps(scan.to_dict()))
    verdict = SimpleNamespace(key="spin_model", numbers={"scans": [rec]})
    fake = SimpleNamespace(files={"claim_spin_scan": "claim_spin_scan.png"}, verdicts=[verdict])
    (extra,) = rp.extra_figures(fake, "spin_model")
    assert extra["file"] == "claim_spin_scan.png"
    caption = extra["caption"]
    assert "Coloured: the departure beyond the null, omega - half vorticity - null" in caption
    assert "Hatched: where the model comes within 2 se of the data's departure beyond" in caption
    assert (
        f"rough: data {rec['measured_beyond_null']:+.3g} +- "
        f"{rec['measured_beyond_null_se']:.2g}, best fit {rec['best_beyond_null']:+.3g}"
    ) in caption
    assert rp.extra_figures(fake, "spin") == []
    assert rp.extra_figures(SimpleNamespace(files={}, verdicts=[verdict]), "spin_model") == []
    ctx = {
        "title": "t", "corpus": "c", "n_runs": 1, "models": "cosserat", "f": "0.1",
        "near_wall_d": "3", "rules": "r", "runs": [], "series": [], "notes": [],
        "verdicts": [{"key": "spin_model", "claim": "claim", "verdict": "refuted",
                      "evidence": "e", "would_change": "", "figure": "claim_spin_model.png",
                      "extra_figures": [extra]}],
    }  # fmt: skip
    md = render("validate.md.j2", ctx)
    assert "![spin_model scan](claim_spin_scan.png)\n\n*claim_spin_scan.png*: The " in md
    page = render("validate.html.j2", ctx)
    assert "<img src='claim_spin_scan.png' alt='spin_model scan'><figcaption>" in page
