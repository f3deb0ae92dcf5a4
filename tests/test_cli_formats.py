"""The command line's outputs, in process: --format text|json|csv, --plot's one line, thickness
--plot, the dimensional cell, progress bars and --quiet, help texts, and no LaTeX anywhere."""

from __future__ import annotations

import io
import json
import math
import sys

import numpy as np
import pandas as pd
import pytest

from cosserat import (
    Cosserat,
    Couette,
    Material,
    Plane,
    Problem,
    Wall,
    shear_layer_thickness,
    solve,
)
from cosserat.analysis.cell import CouetteCell
from cosserat.cli import main

SYNTHETIC = "src/cosserat/data/synthetic_couette.csv"


def run(capsys, *args):
    code = main(list(args))
    out, err = capsys.readouterr()
    return code, out, err


@pytest.fixture
def synthetic(request):
    return str(request.config.rootpath / SYNTHETIC)


# --------------------------------------------------------------------------- solve
def test_solve_prints_a_readable_summary_by_default(capsys):
    code, out, err = run(capsys, "solve", "plane", "--eps", "0.04", "--points", "51")
    assert code == 0 and err == ""
    prof = solve(Problem(Plane(eps=0.04), Cosserat(material=Material(), wall=Wall())), points=51)
    assert out.startswith(prof.problem.describe())
    assert f"Delta = {shear_layer_thickness(prof):.6g} grain diameters" in out
    assert "wall slip = " in out
    header = [line for line in out.splitlines() if line.split()[:2] == ["y", "u"]]
    assert header, out  # the short table, in the cell's own coordinate
    assert len(out.splitlines()) < 25 and "{" not in out and "$" not in out


def test_solve_plot_writes_the_figure_and_one_line(capsys, tmp_path):
    fig = tmp_path / "p.png"
    code, out, _ = run(capsys, "solve", "couette", "--eps", "0.04", "--plot", str(fig))
    assert code == 0
    assert out.count("\n") == 1 and "Delta = " in out and str(fig) in out
    assert fig.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    data = tmp_path / "p.json"
    code, out, _ = run(
        capsys, "solve", "couette", "--eps", "0.04", "--plot", str(fig), "--format", "json",
        "--out", str(data),
    )  # fmt: skip
    assert code == 0 and out.count("\n") == 1 and str(data) in out
    assert json.loads(data.read_text())["r"][0] == 1.0


def test_solve_csv_to_a_file_reads_with_pandas_and_has_a_sidecar(capsys, tmp_path):
    target = tmp_path / "couette.csv"
    code, out, _ = run(
        capsys, "solve", "couette", "--eps", "0.04", "--Ri", "2", "--format", "csv",
        "--out", str(target),
    )  # fmt: skip
    assert code == 0 and out == ""
    frame = pd.read_csv(target)
    assert list(frame.columns[:7]) == [
        "r", "u", "omega", "m", "sigma_theta_r", "sigma_r_theta", "sigma_rr",
    ]  # fmt: skip
    assert frame["r"].iloc[0] == 2.0 and frame["r"].iloc[-1] == 3.0
    meta = json.loads((tmp_path / "couette.json").read_text())
    assert meta["file"] == "couette.csv" and meta["cell"] == "couette"
    assert meta["parameters"]["Ri"] == 2.0 and list(meta["columns"]) == list(frame.columns)


def test_solve_csv_to_stdout_is_the_csv_alone(capsys):
    code, out, _ = run(capsys, "solve", "plane", "--eps", "0.04", "--format", "csv")
    assert code == 0
    frame = pd.read_csv(io.StringIO(out))
    assert frame.columns[0] == "y" and frame["y"].iloc[-1] == 1.0


# --------------------------------------------------------------------------- thickness
def test_thickness_text_csv_and_plot(capsys, tmp_path):
    eps = ["1e-2", "1e-3", "1e-4"]
    code, out, _ = run(capsys, "thickness", "plane", "--eps", *eps)
    assert code == 0 and "eps -> 0 limit of Delta" in out and "$" not in out
    rows = [line.split() for line in out.splitlines() if line.split()[:1] in (["0.01"],)]
    assert rows and len(rows[0]) == 3
    code, out, _ = run(capsys, "thickness", "plane", "--eps", *eps, "--format", "csv")
    frame = pd.read_csv(io.StringIO(out))
    assert list(frame.columns) == ["eps", "Delta", "Delta_asymptotic"]
    assert frame["Delta"].iloc[-1] == pytest.approx(frame["Delta_asymptotic"].iloc[-1], rel=1e-2)
    fig = tmp_path / "t.png"
    code, out, _ = run(capsys, "thickness", "couette", "--eps", *eps, "--plot", str(fig))
    assert code == 0 and out.count("\n") == 1 and "Delta from" in out
    assert fig.stat().st_size > 10_000


def test_thickness_figure_is_on_log_axes_with_the_asymptote():
    from cosserat.cli.solve import thickness_figure

    record = {
        "eps": [1e-2, 1e-3, 1e-4],
        "Delta": [10.0, None, 17.0],
        "Delta_asymptotic": [12.0, 15.0, 17.1],
        "Delta_asymptote": 17.6,
        "description": "plane shear: eps = 0.01, B = 0",
    }
    fig = thickness_figure(record)
    ax = fig.axes[0]
    assert ax.get_xscale() == "log" and ax.get_yscale() == "log"
    labels = [t.get_text() for t in ax.get_legend().get_texts()]
    assert labels == ["model", "small-eps asymptote", "eps -> 0 limit"]
    model_line = ax.get_lines()[0]
    assert list(model_line.get_xdata()) == [1e-2, 1e-4]  # the eps without a solution is left out


# --------------------------------------------------------------------------- compare and fit
def test_compare_formats(capsys, synthetic, tmp_path):
    code, out, _ = run(capsys, "compare", synthetic)
    assert code == 0 and "rms(data - model)" in out and "$" not in out
    code, out, _ = run(
        capsys, "compare", synthetic, "--format", "csv", "--out", str(tmp_path / "c.csv")
    )
    frame = pd.read_csv(tmp_path / "c.csv")
    assert list(frame.columns) == ["distance_d", "u_over_uw", "u_err", "model", "residual"]
    np.testing.assert_allclose(frame["residual"], frame["u_over_uw"] - frame["model"], atol=1e-15)
    meta = json.loads((tmp_path / "c.json").read_text())
    assert meta["rms"] == pytest.approx(float(np.sqrt(np.mean(frame["residual"] ** 2))))


def test_fit_csv_is_a_parameter_table_with_units(capsys, synthetic):
    code, out, _ = run(capsys, "fit", synthetic, "--free", "delta,K", "--format", "csv")
    assert code == 0
    frame = pd.read_csv(io.StringIO(out))
    assert list(frame["parameter"]) == ["delta", "K"]
    assert list(frame["unit"]) == ["deg", "-"]
    # the synthetic profile was made with delta = 23 deg, K = 0.3 plus noise
    assert frame["value"].iloc[0] == pytest.approx(23.0, abs=3 * frame["stderr"].iloc[0] + 0.1)


# --------------------------------------------------------------------------- the cell
CELL = [
    "cell", "--grain-diameter", "1e-3", "--density", "2500", "--inner-radius", "0.05",
    "--gap", "0.02", "--fill-depth", "0.1",
]  # fmt: skip


def test_cell_gives_torque_stress_slip_and_velocity_in_si(capsys):
    code, out, err = run(capsys, *CELL, "--rotation-rate", "1", "--format", "json")
    assert code == 0 and err == ""
    rec = json.loads(out)
    cell = CouetteCell(
        density=2500,
        grain_diameter=1e-3,
        gap=0.02,
        inner_radius=0.05,
        fill_depth=0.1,
        rotation_rate=1,
    )
    prof = solve(Problem(Couette(eps=0.05, Ri=2.5), Cosserat(material=Material(), wall=Wall())))
    assert rec["eps"] == 0.05 and rec["Ri"] == 2.5
    assert rec["torque"] == pytest.approx(cell.torque(prof), rel=1e-9)
    # the total torque is the per-height torque at the bottom times D/2 (stress linear in depth)
    assert rec["torque"] == pytest.approx(rec["torque_per_height"] * 0.1 / 2, rel=1e-12)
    # a slipping inner wall carries tan(delta) times the mean stress rho_p g nu z
    sigma_c = 2500 * 9.81 * 0.6 * 0.1
    assert rec["mean_stress"] == pytest.approx(sigma_c, rel=1e-12)
    assert rec["wall_shear_stress"] == pytest.approx(math.tan(math.radians(20)) * sigma_c, 1e-6)
    assert rec["slip_velocity"] == pytest.approx(0.05 - rec["v_theta"][0], rel=1e-9)
    assert rec["r"][0] == 0.05 and rec["r"][-1] == pytest.approx(0.07)
    assert rec["Delta_m"] == pytest.approx(shear_layer_thickness(prof) * 1e-3, rel=1e-9)
    assert rec["units"]["torque"] == "N m" and rec["units"]["v_theta"] == "m/s"
    # the shear stress's share of the torque; the rest is the wall couple stress, and the total
    # is the same on every cylinder across the gap (torque balance, analysis.cell)
    shear = 2 * math.pi * 0.05**2 * rec["wall_shear_stress"]
    assert rec["torque_per_height_shear"] == pytest.approx(shear, rel=1e-12)
    across = cell.torque_density(prof, 0.1)
    np.testing.assert_allclose(across, rec["torque_per_height"], rtol=1e-9)


def test_cell_by_wall_speed_text_csv_and_depth(capsys, tmp_path):
    _, by_rate, _ = run(capsys, *CELL, "--rotation-rate", "2", "--format", "json")
    _, by_speed, _ = run(capsys, *CELL, "--wall-speed", "0.1", "--format", "json")
    assert json.loads(by_rate)["torque"] == json.loads(by_speed)["torque"]
    code, out, _ = run(capsys, *CELL, "--wall-speed", "0.1")
    assert code == 0 and "$" not in out
    for unit in (" N m", " Pa", " m/s", "r [m]", "v_theta [m/s]"):
        assert unit in out
    target = tmp_path / "cell.csv"
    run(capsys, *CELL, "--wall-speed", "0.1", "--format", "csv", "--out", str(target))
    frame = pd.read_csv(target)
    assert list(frame.columns) == ["r", "v_theta", "omega"]
    meta = json.loads((tmp_path / "cell.json").read_text())
    assert meta["columns"]["v_theta"]["unit"] == "m/s" and meta["units"]["torque"] == "N m"
    code, half, _ = run(capsys, *CELL, "--wall-speed", "0.1", "--depth", "0.05", "--format", "json")
    full = json.loads(by_speed)
    assert json.loads(half)["wall_shear_stress"] == pytest.approx(
        full["wall_shear_stress"] / 2, rel=1e-12
    )


@pytest.mark.parametrize(
    ("extra", "needle"),
    [
        (["--rotation-rate", "1", "--depth", "0.2"], "--depth must satisfy 0 < depth <= fill"),
        (
            ["--rotation-rate", "1", "--wall-speed", "1"],
            "give --rotation-rate or --wall-speed, not",
        ),
        ([], "the couette cell needs --rotation-rate (or --wall-speed)"),
        (["--wall-speed", "-1"], "--wall-speed must be > 0 m/s"),
    ],
)
def test_cell_bad_input_one_line(capsys, extra, needle):
    code, out, err = run(capsys, *CELL, *extra)
    assert code == 2 and out == "" and len(err.strip().splitlines()) == 1 and needle in err


def test_cell_warns_of_a_large_froude_number_in_one_line(capsys):
    code, _, err = run(capsys, *CELL, "--rotation-rate", "30", "--format", "json")
    assert code == 0
    assert err.startswith("cosserat: warning: Froude number") and err.count("\n") == 1


# --------------------------------------------------------------------------- progress
@pytest.fixture
def terminal(monkeypatch):
    """Make stderr look like a terminal (patched when the test runs: capsys swaps sys.stderr
    only then)."""
    return lambda: monkeypatch.setattr(sys.stderr, "isatty", lambda: True)


def test_progress_bar_on_a_terminal_and_quiet(capsys, terminal):
    terminal()
    args = ["thickness", "plane", "--eps", "1e-3", "1e-4", "1e-5", "--method", "asymptotic"]
    code, _, err = run(capsys, *args)
    assert code == 0 and "thickness" in err and "3/3" in err
    assert run(capsys, *args, "--quiet")[2] == ""
    assert run(capsys, "--quiet", *args)[2] == ""
    assert run(capsys, "-q", *args)[2] == ""


def test_no_progress_bar_when_stderr_is_not_a_terminal(capsys, monkeypatch):
    monkeypatch.setattr(sys.stderr, "isatty", lambda: False)
    code, _, err = run(
        capsys, "thickness", "plane", "--eps", "1e-3", "1e-4", "--method", "asymptotic"
    )
    assert code == 0 and err == ""


def test_reproduce_progress_has_one_bar_per_stage(capsys, terminal):
    terminal()
    from cosserat.cli import common
    from cosserat.cli.paper import _stage_bar

    common.set_quiet(False)
    progress = _stage_bar()
    for i in range(1, 4):
        progress("figures", i, 3)
    err = capsys.readouterr().err
    assert "reproduce: figures" in err and "3/3" in err
    common.set_quiet(True)
    assert _stage_bar() is None
    common.set_quiet(False)


def test_progress_bar_keeps_the_call_signature_sweep_uses(capsys, terminal):
    terminal()
    from cosserat.cli.common import progress_bar, set_quiet

    set_quiet(False)
    update = progress_bar("sweep")
    for i in range(1, 6):
        update(i, 5)
    assert "sweep" in capsys.readouterr().err


# --------------------------------------------------------------------------- help texts
@pytest.mark.parametrize(
    "command",
    [
        ["solve", "plane"],
        ["solve", "couette"],
        ["thickness", "plane"],
        ["fit"],
        ["compare"],
        ["cell"],
    ],
)
def test_help_says_meaning_unit_and_default(capsys, command):
    with pytest.raises(SystemExit) as exc:
        main([*command, "--help"])
    assert exc.value.code == 0
    text = " ".join(capsys.readouterr().out.split())
    assert "[deg]" in text and "(default:" in text and "$" not in text
    assert "--format {text,json,csv}" in text and "text: a readable summary (default)" in text
    assert "--quiet" in text
