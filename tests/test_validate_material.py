"""One material, one calibration: the Delta verdicts' joint calibrations are made per
material (every wall kind), and each gap series reads them with its own wall."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from cosserat.analysis.corpus import read_corpus, synthetic_run, write_run
from cosserat.analysis.ranking import model_solve
from cosserat.model import make_problem
from cosserat.studies.validate.fits import calibrate_material
from cosserat.studies.validate.grouping import group_materials, group_runs, material_of
from cosserat.studies.validate.study import series_jobs
from cosserat.studies.validate.verdicts import ModelDelta, scope_text

GRAINS = {"n": 600, "diameter_range_d": [0.8, 1.2], "density": 1.0}
WALLS = {"rough": {"kind": "glued-grains"}, "smooth": {"kind": "smooth-frictional"}}


def plane_run(folder: Path, name: str, gap: float, wall: str, friction: float, **meta) -> Path:
    """A plane run under gravity with an exponential band at the moving wall; its material
    is its grains and its contact law (``friction``: the grains' friction coefficient)."""
    y = np.arange(int(gap)) + 0.5
    u = np.exp(-(gap - y) / 3.0)
    record = {"cell": "plane", "gap_d": gap, "Ri_d": None, "B": 1.0, "wall": WALLS[wall],
              "grains": dict(GRAINS, n=int(30 * gap)),  # the number is the cell's
              "contact": {"model": "hooke", "friction": friction}} | meta  # fmt: skip
    return write_run(folder, name, record, {"y": y, "u": u, "u_se": np.full(y.size, 0.01)})


def test_one_material_is_one_calibration_over_its_wall_kinds_and_two_materials_two(tmp_path):
    """Material A (contact friction 0.5) at two gaps with each wall kind, and a layer run of
    it (walls of two kinds); material B (friction 0.3), rough walls at two gaps; material C
    (friction 0.7) at one gap: one job per model for A over its four runs and both its series
    (not the layer run), one for B, none for C (no series with two gaps)."""
    for g in (10.0, 20.0):
        for wall in ("rough", "smooth"):
            plane_run(tmp_path, f"A_{wall}_{g:g}", g, wall, 0.5)
        plane_run(tmp_path, f"B_rough_{g:g}", g, "rough", 0.3)
    plane_run(tmp_path, "C_rough_10", 10.0, "rough", 0.7)
    plane_run(tmp_path, "A_layer_10", 10.0, "rough", 0.5, B=0.0,
              wall_fixed=WALLS["smooth"])  # fmt: skip
    runs = read_corpus(tmp_path).runs
    by_name = {r.name: r for r in runs}
    # the number of grains is the cell's, not the material's
    assert material_of(by_name["A_rough_10"]) == material_of(by_name["A_smooth_20"])
    assert material_of(by_name["A_rough_10"]) != material_of(by_name["B_rough_10"])
    materials = group_materials(group_runs(runs))
    assert sorted(len(m.series) for m in materials) == [1, 1, 2]
    jobs = series_jobs(runs, ["cosserat", "ngf"])
    assert len(jobs) == 4  # two materials, two models
    for model in ("cosserat", "ngf"):
        a, b = sorted((j for j in jobs if j.model == model), key=lambda j: -len(j.runs))
        assert sorted(r.name for r in a.runs) == [
            "A_rough_10", "A_rough_20", "A_smooth_10", "A_smooth_20"]  # fmt: skip
        assert len(a.series) == 2 and {len(runs) for _, runs, _ in a.series} == {2}
        assert sorted(r.name for r in b.runs) == ["B_rough_10", "B_rough_20"]
        assert len(b.series) == 1 and a.material != b.material
    # a sidecar that names its material is that material, whatever its grains
    plane_run(tmp_path, "D_rough_10", 10.0, "rough", 0.5, material="sand")
    (named,) = [r for r in read_corpus(tmp_path).runs if r.name == "D_rough_10"]
    assert material_of(named) == "sand"


def test_the_series_of_one_material_share_its_calibration_and_keep_their_walls(tmp_path):
    """Cosserat profiles of one material (phi = 28.5 deg) at H/d = 20 and 40 with fully rough
    walls (delta = 25 deg) and smoother ones (delta = 12 deg): one calibration over the four
    runs (one phi, one roughness per wall kind), read by each series with its own wall: the
    rough series' Delta and curve are its wall's, and larger than the smooth series'."""
    for wall, delta in (("rough", 25.0), ("smooth", 12.0)):
        for i, g in enumerate((20, 40)):
            p = make_problem("cosserat", "plane", {"eps": 1 / g, "B": 1.0, "delta": delta})
            synthetic_run(tmp_path, f"{wall}_{g}", model_solve(p, points=401), noise=0.01,
                          seed=i, wall=WALLS[wall])  # fmt: skip
    runs = read_corpus(tmp_path).runs
    series = group_runs(runs)
    assert len(series) == 2
    parts = [(s.key, s.runs, 0.05) for s in series]
    out = calibrate_material(runs, ["cosserat"], parts)
    by_wall = {s.roughness: out[s.key] for s in series}
    (rough,), (smooth,) = by_wall["fully-rough"], by_wall["smoother"]
    assert rough.status == smooth.status == "ok"
    # one calibration: the same parameters and fit for both series, over all four runs
    assert rough.summary["parameters"] == smooth.summary["parameters"]
    assert rough.summary["chi2"] == smooth.summary["chi2"]
    assert sorted(rough.summary["runs"]) == ["rough_20", "rough_40", "smooth_20", "smooth_40"]
    assert rough.summary["wall_kinds"] == {
        "glued-grains": ["rough_20", "rough_40"],
        "smooth-frictional": ["smooth_20", "smooth_40"],
    }
    params = rough.summary["parameters"]
    assert [n for n in params if n.startswith("phi")] == ["phi"]  # one material
    # without stresses phi is fitted, and the calibration says why
    assert rough.summary["fixed"] == {}
    assert rough.summary["fixed_note"].startswith("phi fitted: material ")
    # one roughness tan(delta)/sin(phi) per wall kind, each its wall's (phi itself is not
    # identified by velocities alone, so delta is not either: the roughness is)
    sin_phi = np.sin(np.radians(28.5))
    for kind, delta in (("glued-grains", 25.0), ("smooth-frictional", 12.0)):
        (name,) = [n for n in params if n.startswith("roughness[") and kind in n]
        assert params[name]["value"] == pytest.approx(np.tan(np.radians(delta)) / sin_phi,
                                                      abs=0.02)  # fmt: skip
    # each series reads it at its own runs ...
    assert set(rough.predicted) == {"rough_20", "rough_40"}
    assert set(smooth.predicted) == {"smooth_20", "smooth_40"}
    # ... and draws its curve with its own wall: through its own predictions (the runs' gaps
    # are among the curve's, with the runs' values: referee 9, point 9), far from the other's
    for cal, other in ((rough, smooth), (smooth, rough)):
        pts = [(g, v) for g, v in zip(*cal.curve, strict=True) if v is not None]
        assert len(pts) >= 9
        lg, lv = np.log([g for g, _ in pts]), np.log([v for _, v in pts])
        for run, (delta, _) in cal.predicted.items():
            wall, g = run.split("_")
            at = float(np.exp(np.interp(np.log(float(g)), lg, lv)))
            assert at == pytest.approx(delta, rel=1e-12)
            # the second bin's distance where the band must be to be resolved
            assert cal.resolved_above[run] == pytest.approx(1.5)
            partner = other.predicted[f"{'smooth' if wall == 'rough' else 'rough'}_{g}"][0]
            assert abs(at - partner) > 0.5 * min(at, partner)
    assert rough.predicted["rough_40"][0] > 1.2 * smooth.predicted["smooth_40"][0]
    # the evidence names the calibration's scope
    text = scope_text(ModelDelta("cosserat", rough.predicted, rough.curve, rough.summary))
    assert text == (
        "one calibration of the material over 4 runs of both wall kinds (glued-grains: 2, "
        "smooth-frictional: 2), this series' 2 among them"
    )
