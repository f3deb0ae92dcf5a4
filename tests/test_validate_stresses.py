"""The angles a material's stresses fix (``studies.validate.stresses``, referee 10, points 2
and 6): the pooling with its consistency test and the PDG scale factor, the estimator of sin
phi (the moving walls' ratios, the bands' T as the cross-check), and one tan delta per wall
kind, the same in the per-run fits, the spin scan and the material calibration."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from cosserat.analysis.corpus import read_corpus, write_run
from cosserat.calibration.data import _material_label
from cosserat.errors import InputError
from cosserat.studies.validate.fits import cosserat_fix, material_fix
from cosserat.studies.validate.spin_scan import angles
from cosserat.studies.validate.stresses import (
    material_angles,
    material_sin_phi,
    pool,
    pooled_T,
    shear_stress,
    wall_ratio,
)

GAP = 12.0


def plane_run(folder: Path, name: str, kind: str, T: float, *, wall: float | None = None,
              B: float = 0.0) -> None:  # fmt: skip
    """A plane run whose upper wall moves: u = exp(-s/2), the model's stresses with a uniform
    shear stress ``T`` (sigma_yy = 1 + B eps s, errors 0.003), and (``wall``) the moving
    wall's measured |shear|/normal ``wall`` (shear se 0.005, normal 1 +- 1e-4)."""
    y = np.arange(int(GAP)) + 0.5
    s = GAP - y
    cols = {"y": y, "u": np.exp(-s / 2.0), "u_se": np.full(y.size, 2e-3),
            "sigma_yx": np.full(y.size, -T), "sigma_yx_se": np.full(y.size, 0.003),
            "sigma_yy": 1.0 + B * s / GAP, "sigma_yy_se": np.full(y.size, 0.003)}  # fmt: skip
    meta = {"cell": "plane", "gap_d": GAP, "B": B, "wall": {"kind": kind},
            "grains": {"n": 100, "diameter_range_d": [0.8, 1.2]}}  # fmt: skip
    if wall is not None:
        meta["wall_stress"] = {"normal": 1.0, "shear": -wall, "normal_se": 1e-4,
                               "shear_se": 0.005}  # fmt: skip
    write_run(folder, name, meta, cols)


def test_consistent_values_pool_to_their_weighted_mean_unscaled():
    """1 +- 1 and 3 +- 1: mean 2 +- 1/sqrt(2), chi^2 = 2 for 1 dof, p = 0.157 (>= 0.05)."""
    p = pool([1.0, 3.0], [1.0, 1.0], ["a", "b"])
    assert p.value == pytest.approx(2.0) and p.chi2 == pytest.approx(2.0) and p.dof == 1
    assert p.p_value == pytest.approx(0.1573, abs=1e-4) and p.consistent
    assert p.scale == 1.0 and p.stderr == pytest.approx(1.0 / math.sqrt(2.0))
    assert p.outlier is None
    assert p.consistency_text() == "chi^2 = 2 for 1 dof about the mean (p = 0.16): consistent"
    # weights: 1 +- 1 and 4 +- 2 -> (1 + 4/4) / (1 + 1/4) = 1.6, error 1/sqrt(1.25)
    w = pool([1.0, 4.0], [1.0, 2.0], ["a", "b"])
    assert w.value == pytest.approx(1.6) and w.stderr == pytest.approx(1.0 / math.sqrt(1.25))


def test_inconsistent_values_scale_the_error_by_the_pdg_factor_and_name_the_outlier():
    """0, 0, 6 (+- 1 each): mean 2, chi^2 = 4 + 4 + 16 = 24 for 2 dof (p = 6e-6), S =
    sqrt(12); the error 1/sqrt(3) becomes 2; the outlier is the third (+4 se)."""
    p = pool([0.0, 0.0, 6.0], [1.0, 1.0, 1.0], ["a", "b", "c"])
    assert p.value == pytest.approx(2.0) and p.chi2 == pytest.approx(24.0)
    assert p.p_value == pytest.approx(math.exp(-12.0)) and not p.consistent
    assert p.scale == pytest.approx(math.sqrt(12.0))
    assert p.stderr_raw == pytest.approx(1.0 / math.sqrt(3.0))
    assert p.stderr == pytest.approx(2.0)
    assert p.outlier == "c" and p.pulls() == pytest.approx((-2.0, -2.0, 4.0))
    assert "inconsistent, the error scaled by the PDG scale factor sqrt(chi^2/dof) = 3.46; " \
        "outlier c (+4.0 se)" in p.consistency_text()  # fmt: skip
    d = p.to_dict()
    assert d["scale_factor"] == pytest.approx(math.sqrt(12.0)) and d["outlier"] == "c"
    assert d["stderr"] == pytest.approx(2.0) and d["consistent"] is False


def test_the_referee_10_numbers():
    """The three fully rough v2 runs: the bands' T (0.331 +- 0.0067, 0.288 +- 0.0084, 0.319
    +- 0.0038) are inconsistent (chi^2 16.5/2, as the referee found), the error scaled by 2.88; the
    walls' ratios (0.321 +- 0.0086, 0.286 +- 0.013, 0.312 +- 0.0073) agree (p = 0.079 from
    these rounded values, 0.09 from the runs' own)."""
    names = ["rough_H10", "rough_H10_half", "rough_H20"]
    band = pool([0.331, 0.288, 0.319], [0.0067, 0.0084, 0.0038], names)
    assert band.chi2 == pytest.approx(16.55, abs=0.01) and band.outlier == "rough_H10_half"
    assert band.scale == pytest.approx(math.sqrt(band.chi2 / 2)) and band.scale > 2.87
    walls = pool([0.321, 0.286, 0.312], [0.0086, 0.013, 0.0073], names)
    assert walls.consistent and walls.p_value == pytest.approx(0.0793, abs=1e-4)
    assert walls.value == pytest.approx(0.3112, abs=1e-4) and walls.scale == 1.0


def test_pooling_refuses_what_it_cannot_weigh():
    with pytest.raises(InputError, match="one error and one name per value: got 2 values, 1"):
        pool([1.0, 2.0], [1.0], ["a", "b"])
    with pytest.raises(InputError, match="positive, finite errors"):
        pool([1.0, 2.0], [1.0, 0.0], ["a", "b"])


def test_sin_phi_is_the_walls_ratio_and_the_band_is_the_cross_check(tmp_path):
    """Two fully rough runs whose walls give 0.30 and 0.32 (+- 0.005) while their bands'
    uniform shear stress is 0.35: sin phi = 0.31 from the walls, the bands' 0.35 beside it."""
    plane_run(tmp_path, "a", "glued-grains", 0.35, wall=0.30)
    plane_run(tmp_path, "b", "glued-grains", 0.35, wall=0.32)
    runs = read_corpus(tmp_path).runs
    assert wall_ratio(runs[0]) == pytest.approx((0.30, 0.005), rel=1e-3)
    assert shear_stress(runs[0]).value == pytest.approx(0.35, rel=1e-9)
    m = material_sin_phi(runs, _material_label(runs[0].meta))
    got = m.sin_phi
    assert got.estimator == "wall" and got.pooled.value == pytest.approx(0.31, rel=1e-6)
    assert got.pooled.chi2 == pytest.approx(8.0, rel=1e-3)  # (0.01/0.005)^2 * 2
    assert not got.pooled.consistent and got.pooled.scale == pytest.approx(math.sqrt(8.0), 1e-3)
    assert got.cross_check is not None and got.cross_check.value == pytest.approx(0.35)
    assert m.phi == pytest.approx(math.degrees(math.asin(0.31)), rel=1e-6)
    # phi's error: the scaled sin phi error through d(phi) = d(sin phi) / cos(phi)
    se = got.pooled.stderr_raw * math.sqrt(8.0)
    assert m.phi_se == pytest.approx(math.degrees(se / math.sqrt(1 - 0.31**2)), rel=1e-3)


def test_a_run_without_its_walls_ratio_leaves_the_band_as_the_estimator(tmp_path):
    plane_run(tmp_path, "a", "glued-grains", 0.3)
    got = pooled_T(read_corpus(tmp_path).runs, "sin phi")
    assert got is not None and got.estimator == "band" and got.cross_check is None
    assert got.pooled.value == pytest.approx(0.3) and got.pooled.p_value is None


def test_one_tan_delta_per_wall_kind_in_every_fit_and_calibration(tmp_path):
    """Two smooth runs measure 0.24 and 0.26 on their walls (+- 0.005, chi^2 = 8 for 1 dof,
    inconsistent: the error scaled by sqrt(8)); both runs' fits, their scans' angles and the
    material calibration fix the one pooled tan delta = 0.25, and the rough kind fully rough."""
    plane_run(tmp_path, "rough", "glued-grains", 0.3, wall=0.3)
    plane_run(tmp_path, "s1", "smooth-frictional", 0.25, wall=0.24)
    plane_run(tmp_path, "s2", "smooth-frictional", 0.25, wall=0.26)
    runs = read_corpus(tmp_path).runs
    delta = math.degrees(math.atan(0.25))
    for r in runs:
        if r.name.startswith("s"):
            assert cosserat_fix(r, runs).delta == pytest.approx(delta, rel=1e-6)
            a = angles(r, runs)
            assert a.delta("moving") == pytest.approx(delta, rel=1e-6)
            assert a.tan_delta_se["moving"] == pytest.approx(0.005 / math.sqrt(2) * math.sqrt(8),
                                                             rel=1e-3)  # fmt: skip
    fix, note, numbers = material_angles(runs)
    assert fix["phi"] == pytest.approx(math.degrees(math.asin(0.3)), rel=1e-6)
    assert fix["roughness[glued-grains]"] == 1.0
    assert fix["roughness[smooth-frictional]"] == pytest.approx(0.25 / 0.3, rel=1e-6)
    assert "smooth-frictional: delta = 14.04 deg (tan delta = 0.25 +- 0.01" in note
    assert numbers["walls"]["smooth-frictional"]["pooled"]["outlier"] in ("s1", "s2")
    assert material_fix("cosserat", runs)[0] == fix
    assert material_fix("mui", runs) == ({}, "")


def test_a_wall_kind_rougher_than_fully_rough_is_refused(tmp_path):
    plane_run(tmp_path, "rough", "glued-grains", 0.3, wall=0.3)
    plane_run(tmp_path, "s1", "smooth-frictional", 0.4, wall=0.4)
    with pytest.raises(InputError, match=r"wall kind smooth-frictional: tan delta = 0.4 "
                       r"exceeds sin phi = 0.3 \(the fully rough limit"):  # fmt: skip
        material_angles(read_corpus(tmp_path).runs)
