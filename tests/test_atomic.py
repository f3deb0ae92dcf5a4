"""Outputs appear whole or not at all (interrupted runs leave the old file)."""

from __future__ import annotations

import os
import stat

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import pytest

from cosserat import Cosserat, Material, Plane, Problem, Wall, solve
from cosserat._atomic import atomic_open, save_figure, write_text


def test_write_replaces_the_file_and_leaves_no_temporary(tmp_path):
    target = tmp_path / "out.txt"
    target.write_text("old\n")
    write_text(target, "new\n")
    assert target.read_text() == "new\n"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["out.txt"]


def test_an_interrupted_write_leaves_the_old_file(tmp_path):
    target = tmp_path / "table.csv"
    target.write_text("old\n")
    with pytest.raises(KeyboardInterrupt), atomic_open(target) as fh:
        fh.write("half of a new table")
        raise KeyboardInterrupt
    assert target.read_text() == "old\n"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["table.csv"]


def test_permissions_follow_the_umask_not_mkstemp(tmp_path):
    target = tmp_path / "out.txt"
    write_text(target, "x")
    mask = os.umask(0)
    os.umask(mask)
    assert stat.S_IMODE(target.stat().st_mode) == 0o666 & ~mask


def test_figures_keep_their_format(tmp_path):
    fig, ax = plt.subplots()
    ax.plot([0, 1], [0, 1])
    png = save_figure(fig, tmp_path / "f.png")
    pdf = save_figure(fig, tmp_path / "f.pdf")
    plt.close(fig)
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert pdf.read_bytes()[:5] == b"%PDF-"


def test_a_profile_export_is_atomic(tmp_path, monkeypatch):
    profile = solve(Problem(Plane(eps=0.04), Cosserat(material=Material(), wall=Wall())))
    target = tmp_path / "profile.csv"
    profile.to_csv(target)
    before = target.read_text()

    def fail(*args, **kwargs):
        raise OSError("disk full")

    monkeypatch.setattr(os, "replace", fail)
    with pytest.raises(OSError, match="disk full"):
        solve(Problem(Plane(eps=0.01), Cosserat(material=Material(), wall=Wall()))).to_csv(target)
    assert target.read_text() == before
    assert sorted(p.name for p in tmp_path.iterdir()) == ["profile.csv", "profile.json"]
