"""cosserat.dem: walls of two kinds in one cell (issue 18 item 4, the layer position): the
decks of one wall kind unchanged, the per-wall rows, frictions, densities and the deck's
``# walls:`` line, the sidecar's ``wall`` / ``wall_fixed`` / ``walls``, and the CLI flags
(through a subprocess). No LAMMPS run."""

from __future__ import annotations

import hashlib
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from cosserat.dem import CouetteDEM, PlaneShearDEM, RunLength, WallRoughness, build_deck
from cosserat.dem.analyse import _walls_meta
from cosserat.dem.decks import resume_deck
from cosserat.dem.geometry import LOWER_WALL, UPPER_WALL
from cosserat.errors import ParameterError

ROUGH = WallRoughness("glued-grains")
SMOOTH = WallRoughness("smooth-frictional")
SRC = str(Path(__file__).resolve().parents[1] / "src")

CORPUS_V1_DECKS = {
    # sha256 prefixes of the shipped corpus's decks before walls of two kinds existed
    "plane_rough_H20": "194de08de516",
    "plane_smooth_H20": "c711d3aea5e6",
    "couette_Ri20_H10": "bf992476b3fc",
    "channel_rough_H20": "0b4a6b0db084",
}


def cosserat(*args: str) -> subprocess.CompletedProcess:
    env = {**os.environ, "PYTHONPATH": SRC}
    return subprocess.run(
        [sys.executable, "-m", "cosserat", *args],
        capture_output=True,
        text=True,
        check=False,
        timeout=120,
        env=env,
    )


@pytest.mark.parametrize("name", sorted(CORPUS_V1_DECKS))
def test_decks_of_one_wall_kind_are_unchanged(name):
    from cosserat.dem.corpus import corpus_cells

    assert build_deck(corpus_cells()[name]).sha256.startswith(CORPUS_V1_DECKS[name])


def test_equal_walls_are_one_kind():
    both = PlaneShearDEM(gap=10, lower_wall=SMOOTH, upper_wall=SMOOTH)
    assert not both.walls_differ
    assert both == PlaneShearDEM(gap=10, wall=SMOOTH)
    assert build_deck(both).sha256 == build_deck(PlaneShearDEM(gap=10, wall=SMOOTH)).sha256
    assert "# walls:" not in build_deck(both).text


def test_walls_that_differ_the_moving_one_is_wall():
    cell = PlaneShearDEM(gap=10, B=0.0, wall=SMOOTH, lower_wall=SMOOTH, upper_wall=ROUGH)
    assert cell.walls_differ
    assert cell.walls == (SMOOTH, ROUGH)
    assert cell.wall == ROUGH  # the moving (upper) wall's kind in the parameter line
    only_lower = PlaneShearDEM(gap=10, B=0.0, lower_wall=SMOOTH)  # upper: wall (rough)
    assert only_lower == cell


def test_plane_deck_with_a_smooth_lower_and_a_rough_upper_wall():
    cell = PlaneShearDEM(gap=10, B=0.0, wall_speed=0.0025, lower_wall=SMOOTH)
    deck = build_deck(cell)
    layout, text = deck.layout, deck.text
    lower = layout.kind == LOWER_WALL
    upper = layout.kind == UPPER_WALL
    # the lower row: 300 disks at 0.1 d over the 30 d period; the upper row: 30 at 1 d
    assert lower.sum() == 300 and upper.sum() == 30
    assert np.allclose(np.diff(np.sort(layout.x[lower])), 0.1)
    assert np.allclose(np.diff(np.sort(layout.x[upper])), 1.0)
    assert layout.info["wall_count"] == 30  # the load is shared by the upper wall's disks
    assert f"fix load upper aveforce NULL {-30.0 / 30:.10g} NULL" in text
    # only the smooth row is lightened to rho_s pi d/4 per length of wall
    assert "set type 2 density/disc 0.1" in text
    assert "set type 3 density" not in text and "set type 2*3" not in text
    walls_line = (
        "# walls: lower WallRoughness(kind='smooth-frictional', glued_diameter=1.0, "
        "glued_spacing=0.1, friction=None), upper WallRoughness(kind='glued-grains', "
        "glued_diameter=1.0, glued_spacing=1.0, friction=None)"
    )
    assert text.splitlines()[2] == walls_line
    assert "fix gravity" not in text  # B = 0
    assert hashlib.sha256(deck.data.encode()).hexdigest() in text
    # a resumed deck names the same walls
    run = RunLength(steps=4000, dump_every=100, restart_every=2000)
    resumed = resume_deck(PlaneShearDEM(gap=10, B=0.0, lower_wall=SMOOTH, run=run), 2000)
    assert walls_line in resumed.splitlines()


def test_each_wall_has_its_own_friction():
    cell = PlaneShearDEM(gap=10, B=0.0, lower_wall=WallRoughness("smooth-frictional", friction=0.1))
    lines = build_deck(cell).text.splitlines()
    lower = next(ln for ln in lines if ln.startswith("pair_coeff 1 2 "))
    upper = next(ln for ln in lines if ln.startswith("pair_coeff 1 3 "))
    assert " 1.0 0.1 damping" in lower and " 1.0 0.5 damping" in upper


def test_couette_inner_and_outer_rings_of_two_kinds():
    cell = CouetteDEM(gap=10, inner_radius=10, lower_wall=SMOOTH)
    layout = build_deck(cell).layout
    inner = layout.kind == LOWER_WALL
    outer = layout.kind == UPPER_WALL
    r_in = np.hypot(layout.x[inner], layout.y[inner])
    assert np.allclose(r_in, 9.5)
    assert inner.sum() == round(2 * np.pi * 9.5 / 0.1)
    assert outer.sum() == round(2 * np.pi * 20.5 / 1.0)
    assert "# walls: inner WallRoughness(kind='smooth-frictional'" in build_deck(cell).text


def test_sidecar_names_the_moving_and_the_fixed_wall():
    plane = PlaneShearDEM(gap=10, B=0.0, lower_wall=SMOOTH)
    meta = _walls_meta(plane)
    assert meta["wall"]["kind"] == "glued-grains"  # the moving (upper) wall
    assert meta["wall_fixed"]["kind"] == "smooth-frictional"
    assert meta["walls"]["lower"]["glued_spacing_d"] == 0.1
    assert meta["walls"]["upper"]["glued_spacing_d"] == 1.0
    couette = CouetteDEM(gap=10, inner_radius=10, upper_wall=SMOOTH)  # smooth fixed outer ring
    meta = _walls_meta(couette)
    assert meta["wall"]["kind"] == "glued-grains" and meta["wall_fixed"]["kind"] == (
        "smooth-frictional"
    )
    assert set(meta["walls"]) == {"inner", "outer"}
    assert set(_walls_meta(PlaneShearDEM(gap=10))) == {"wall"}  # one kind: as before


def test_a_wall_that_is_not_a_wall_is_refused():
    with pytest.raises(ParameterError, match="lower_wall must be a WallRoughness; got str"):
        PlaneShearDEM(gap=10, lower_wall="smooth-frictional")


def test_cli_deck_with_walls_of_two_kinds(tmp_path):
    out = tmp_path / "layer"
    proc = cosserat(
        "dem", "deck", "plane", "--out", str(out), "--gap-d", "10", "--B", "0",
        "--wall-lower", "smooth-frictional", "--speed", "0.0025",
    )  # fmt: skip
    assert proc.returncode == 0, proc.stderr
    text = (out / "deck.lmp").read_text()
    assert "# walls: lower WallRoughness(kind='smooth-frictional'" in text
    cell = PlaneShearDEM(gap=10.0, B=0.0, wall_speed=0.0025, lower_wall=SMOOTH)
    assert text == build_deck(cell).text


@pytest.mark.parametrize(
    ("argv", "message"),
    [
        (
            ["channel", "--wall-lower", "smooth-frictional"],
            "cosserat: error: --wall-lower is for the plane cell; the channel cell's walls are "
            "set by --wall",
        ),
        (
            ["plane", "--wall-inner", "smooth-frictional"],
            "cosserat: error: --wall-inner is for the couette cell; the plane cell's walls are "
            "set by --wall and its own flags",
        ),
    ],
)
def test_cli_refuses_another_cells_wall_flags(argv, message, tmp_path):
    proc = cosserat("dem", "deck", *argv, "--out", str(tmp_path / "d"))
    assert proc.returncode == 2
    assert proc.stderr.strip().splitlines() == [message]
