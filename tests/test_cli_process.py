"""The new command-line behaviour as a user meets it: separate processes (a few; each one
imports the package, about a second)."""

from __future__ import annotations

import io
import json
import subprocess
import sys

import pandas as pd


def cosserat(*args, cwd=None):
    return subprocess.run(
        [sys.executable, "-m", "cosserat", *args],
        capture_output=True,
        text=True,
        check=False,
        cwd=cwd,
    )


def test_solve_plot_prints_one_line_and_no_progress_when_piped(tmp_path):
    fig = tmp_path / "profile.png"
    proc = cosserat("solve", "couette", "--eps", "0.04", "--plot", str(fig))
    assert proc.returncode == 0, proc.stderr
    assert proc.stdout.count("\n") == 1 and "Delta = " in proc.stdout and proc.stderr == ""
    assert fig.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_thickness_plot_and_csv_with_sidecar(tmp_path):
    table = tmp_path / "thickness.csv"
    fig = tmp_path / "thickness.png"
    proc = cosserat(
        "thickness", "plane", "--eps", "1e-2", "1e-3", "1e-4", "--format", "csv",
        "--out", str(table), "--plot", str(fig),
    )  # fmt: skip
    assert proc.returncode == 0, proc.stderr
    assert proc.stdout.count("\n") == 1 and proc.stderr == ""  # stderr is a pipe: no bar
    frame = pd.read_csv(table)
    assert list(frame.columns) == ["eps", "Delta", "Delta_asymptotic"] and len(frame) == 3
    meta = json.loads((tmp_path / "thickness.json").read_text())
    assert meta["file"] == "thickness.csv" and meta["columns"]["Delta"]["unit"] == "d_p"
    assert fig.stat().st_size > 10_000


def test_cell_csv_reads_with_pandas():
    proc = cosserat(
        "cell", "--grain-diameter", "2e-3", "--density", "1100", "--inner-radius", "0.1",
        "--gap", "0.05", "--fill-depth", "0.2", "--rotation-rate", "0.5", "--format", "csv",
    )  # fmt: skip
    assert proc.returncode == 0, proc.stderr
    frame = pd.read_csv(io.StringIO(proc.stdout))
    assert list(frame.columns) == ["r", "v_theta", "omega"]
    assert frame["r"].iloc[0] == 0.1 and abs(frame["r"].iloc[-1] - 0.15) < 1e-12
    assert 0.0 < frame["v_theta"].iloc[0] < 0.05  # slower than the wall (0.05 m/s): slip


def test_unknown_param_is_one_line_in_a_process():
    proc = cosserat("solve", "plane", "--eps", "0.01", "--model", "mui", "--param", "x=1")
    assert proc.returncode == 2 and proc.stdout == ""
    assert proc.stderr.count("\n") == 1 and "mu_s [-]" in proc.stderr
