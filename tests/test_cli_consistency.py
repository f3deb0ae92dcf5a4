"""One meaning per flag and one shape per output across the commands (issue 19, items 2 and
3): each reproducer through a separate process, as a user meets it."""

from __future__ import annotations

import io
import json
import math
import subprocess
import sys

import pandas as pd
import pytest

from cosserat import MuI


def cosserat(*args, cwd=None):
    return subprocess.run(
        [sys.executable, "-m", "cosserat", *args],
        capture_output=True,
        text=True,
        check=False,
        cwd=cwd,
    )


def one_error_line(proc) -> str:
    assert proc.returncode == 2 and proc.stdout == "", proc.stdout
    assert proc.stderr.count("\n") == 1 and "Traceback" not in proc.stderr, proc.stderr
    assert proc.stderr.startswith("cosserat: error: "), proc.stderr
    assert "np.float64" not in proc.stderr
    return proc.stderr


GRAINS = ["--grain-diameter", "1e-3", "--density", "2500", "--gap", "0.02"]


# --------------------------------------------------------------------------- item 2: cells
def test_cell_plane_mui_is_the_closed_form_in_si():
    proc = cosserat(
        "cell", "plane", "--model", "mui", *GRAINS, "--normal-stress", "100",
        "--wall-speed", "0.04", "--gravity", "0", "--format", "json",
    )  # fmt: skip
    assert proc.returncode == 0, proc.stderr
    rec = json.loads(proc.stdout)
    I_w = 0.04 * 1e-3 / (0.02 * math.sqrt(100 / 2500))
    v = MuI().values()
    mu = v["mu_s"] + (v["mu_2"] - v["mu_s"]) / (v["I_0"] / I_w + 1)
    assert rec["I_w"] == pytest.approx(I_w, rel=1e-12) and rec["B"] == 0.0
    assert rec["wall_shear_stress"] == pytest.approx(100 * mu, rel=1e-10)
    assert rec["velocity"][-1] == pytest.approx(0.04, rel=1e-12)
    assert rec["spin"][0] == pytest.approx(-0.04 / (2 * 0.02), rel=1e-9)
    assert rec["units"]["wall_shear_stress"] == "Pa" and rec["cell"] == "plane"


def test_cell_channel_ngf_carries_the_weight_and_reports_its_speed():
    proc = cosserat(
        "cell", "channel", "--model", "ngf", *GRAINS, "--normal-stress", "300",
        "--format", "json",
    )  # fmt: skip
    assert proc.returncode == 0, proc.stderr
    rec = json.loads(proc.stdout)
    assert rec["wall_shear_stress"] == pytest.approx(2500 * 9.81 * 0.6 * 0.02 / 2, rel=1e-12)
    assert rec["B"] == pytest.approx(2500 * 9.81 * 0.02 / 300, rel=1e-12)
    V_c = rec["I_w"] * 0.02 * math.sqrt(300 / 2500) / 1e-3
    assert rec["velocity_scale"] == pytest.approx(V_c, rel=1e-12)


def test_cell_couette_mui_and_python_share_names_and_values():
    from cosserat import solve
    from cosserat.cell import CouetteCell

    proc = cosserat(
        "cell", "couette", "--model", "mui", *GRAINS, "--inner-radius", "0.02",
        "--fill-depth", "0.1", "--rotation-rate", "0.5", "--format", "json",
    )  # fmt: skip
    assert proc.returncode == 0, proc.stderr
    rec = json.loads(proc.stdout)
    cell = CouetteCell(
        grain_diameter=1e-3, density=2500, gap=0.02, inner_radius=0.02, fill_depth=0.1,
        rotation_rate=0.5,
    )  # fmt: skip
    py = cell.results(solve(cell.problem(MuI())))
    for key in ("I_w", "wall_shear_stress", "torque", "Delta_m", "slip_velocity"):
        assert rec[key] == pytest.approx(py[key], rel=1e-9), key
    assert set(rec["inputs"]) == set(cell.inputs())
    # the inertial number at the bottom: V_i d / (H sqrt(g nu D))
    assert rec["I_w"] == pytest.approx(0.01 * 1e-3 / (0.02 * math.sqrt(9.81 * 0.6 * 0.1)))


def test_cell_csv_has_the_cells_own_columns():
    proc = cosserat(
        "cell", "plane", *GRAINS, "--normal-stress", "100", "--wall-speed", "0.04",
        "--gravity", "0", "--format", "csv",
    )  # fmt: skip
    assert proc.returncode == 0, proc.stderr
    frame = pd.read_csv(io.StringIO(proc.stdout))
    assert list(frame.columns) == ["y", "v_x", "omega"]


@pytest.mark.parametrize(
    ("args", "needle"),
    [
        (["channel", "--model", "mui", *GRAINS], "--normal-stress [Pa] is needed"),
        (["channel", *GRAINS, "--normal-stress", "300", "--model", "mui", "--centre-speed",
          "1"], "--centre-speed does not apply to a rate-dependent law"),
        (["plane", *GRAINS, "--wall-speed", "1", "--normal-stress", "1", "--fill-depth", "1"],
         "--fill-depth do(es) not apply to the plane cell"),
        (["plane", *GRAINS, "--wall-speed", "1"], "the plane cell needs --normal-stress"),
        (["plane", *GRAINS, "--normal-stress", "-1", "--wall-speed", "1"],
         "--normal-stress must be > 0 Pa; got -1"),
        (["plane", "--model", "mui", *GRAINS, "--normal-stress", "1", "--wall-speed", "100"],
         "the cell's inertial number I_w = V d_p / (H sqrt(p / rho_p)) = 250 is out of"),
        (["plane", "--model", "mui", *GRAINS, "--normal-stress", "1", "--wall-speed", "1",
          "--param", "I_w=0.1"], "--param I_w: computed from the cell in SI units here"),
        (["couette", *GRAINS, "--inner-radius", "0.02", "--fill-depth", "0.1",
          "--rotation-rate", "1", "--depth", "1"], "--depth must satisfy 0 < depth <= fill"),
    ],
)  # fmt: skip
def test_cell_bad_input_is_one_line(args, needle):
    proc = cosserat("cell", *args)
    assert needle in one_error_line(proc)


# --------------------------------------------------------------------------- item 3: flags
def test_dem_lengths_in_grain_diameters_have_their_own_flags(tmp_path):
    new = cosserat("dem", "deck", "couette", "--out", str(tmp_path / "a"), "--gap-d", "8",
                   "--Ri-d", "10")  # fmt: skip
    assert new.returncode == 0 and new.stderr == "", new.stderr
    old = cosserat("dem", "deck", "couette", "--out", str(tmp_path / "b"), "--gap", "8",
                   "--Ri", "10")  # fmt: skip
    assert old.returncode == 0
    warnings = old.stderr.strip().splitlines()
    assert warnings == [
        "cosserat: warning: dem --Ri is deprecated (it is in grain diameters here, a ratio or "
        "metres elsewhere); use --Ri-d",
        "cosserat: warning: dem --gap is deprecated (it is in grain diameters here, a ratio or "
        "metres elsewhere); use --gap-d",
    ]
    # the same deck either way
    assert (tmp_path / "a" / "deck.lmp").read_text() == (tmp_path / "b" / "deck.lmp").read_text()


def test_dem_run_checks_its_sample_count_before_running(tmp_path):
    proc = cosserat("dem", "run", "plane", "--out", str(tmp_path), "--steps", "15000",
                    "--dump-every", "1000")  # fmt: skip
    err = one_error_line(proc)
    assert "--steps / --dump-every must give at least 20 samples" in err
    assert "got 15000 / 1000 = 15, checked before running LAMMPS" in err
    assert not any(tmp_path.iterdir())


def test_bare_cosserat_and_bare_dem_list_their_commands():
    bare = cosserat()
    assert bare.returncode == 0 and bare.stderr == ""
    for command in ("solve", "cell", "fit", "sweep", "dem", "models", "validate"):
        assert f"\n    {command} " in bare.stdout
    dem = cosserat("dem")
    assert dem.returncode == 0 and "{deck,run,corpus}" in dem.stdout
    assert "need LAMMPS" in " ".join(dem.stdout.split())


def test_delta_has_one_json_key_everywhere():
    solve = json.loads(cosserat("solve", "plane", "--eps", "0.01", "--format", "json").stdout)
    assert solve["Delta"] == solve["thickness"]  # the key of 0.1, kept one release
    thick = json.loads(cosserat("thickness", "plane", "--eps", "0.01", "--format", "json").stdout)
    assert thick["Delta"][0] == pytest.approx(solve["Delta"], rel=1e-9)


@pytest.mark.parametrize(
    "args",
    [
        ["solve", "plane", "--eps"],  # argparse
        ["solve", "plane", "--eps", "0.01", "--points", "1"],  # a usage check
        ["solve", "plane", "--eps", "-1"],  # a model bound
        ["bogus"],
    ],
)
def test_every_error_has_one_prefix(args):
    one_error_line(cosserat(*args))


def test_missing_output_folders_are_created_by_every_command(tmp_path):
    out = tmp_path / "new" / "deeper" / "p.csv"
    fig = tmp_path / "figs" / "p.png"
    proc = cosserat("solve", "plane", "--eps", "0.05", "--format", "csv", "--out", str(out),
                    "--plot", str(fig))  # fmt: skip
    assert proc.returncode == 0, proc.stderr
    assert out.is_file() and out.with_suffix(".json").is_file() and fig.is_file()
    # a path through a regular file is refused before the work
    blocker = tmp_path / "a_file"
    blocker.write_text("")
    err = one_error_line(cosserat("solve", "plane", "--eps", "0.05", "--out",
                                  str(blocker / "x.json")))  # fmt: skip
    assert f"{blocker} is not a folder" in err


def test_sweep_takes_format_and_quiet(tmp_path):
    spec = tmp_path / "s.toml"
    spec.write_text("[fixed]\neps = 0.1\n[grid]\ndelta = [15.0, 20.0]\n")
    out = tmp_path / "tables" / "t.csv"
    proc = cosserat("sweep", str(spec), "--out", str(out), "--workers", "1", "--format",
                    "json", "-q")  # fmt: skip
    assert proc.returncode == 0, proc.stderr
    summary = json.loads(proc.stdout)
    assert summary["cases"] == 2 and summary["status"]["ok"] == 2 and out.is_file()


def test_compare_names_its_columns_alike_in_text_and_csv(tmp_path):
    data = tmp_path / "d.csv"
    data.write_text("# geometry: plane\n# eps: 0.05\ndistance_d,u_over_uw\n0,0.9\n2,0.5\n5,0.1\n")
    text = cosserat("compare", str(data))
    csv = cosserat("compare", str(data), "--format", "csv")
    assert text.returncode == 0 and csv.returncode == 0, text.stderr + csv.stderr
    header = csv.stdout.splitlines()[0].split(",")
    assert header == ["distance_d", "u_over_uw", "model", "residual"]
    table_head = next(line for line in text.stdout.splitlines() if "u_over_uw" in line)
    assert table_head.split() == ["distance_d", "[d_p]", "u_over_uw", "model", "residual"]


def test_compare_says_where_the_command_line_overrides_the_header(tmp_path):
    data = tmp_path / "d.csv"
    data.write_text("# geometry: plane\n# eps: 0.05\ndistance_d,u_over_uw\n0,0.9\n2,0.5\n5,0.1\n")
    agree = cosserat("compare", str(data), "--eps", "0.05", "-q")
    assert agree.returncode == 0 and agree.stderr == "", agree.stderr
    differ = cosserat("compare", str(data), "--eps", "0.02", "--format", "json")
    assert differ.returncode == 0, differ.stderr
    assert differ.stderr == (
        "cosserat: warning: --eps 0.02 differs from the file's header (eps: 0.05); "
        "the model is solved with the command line's eps = 0.02\n"
    )
    assert "eps = 0.02" in json.loads(differ.stdout)["description"]


def test_solve_models_overlays_every_model(tmp_path):
    fig = tmp_path / "models.png"
    proc = cosserat("solve", "couette", "--eps", "0.05", "--models", "cosserat,mui",
                    "--plot", str(fig))  # fmt: skip
    assert proc.returncode == 0, proc.stderr
    assert proc.stdout.count("\n") == 1 and "(cosserat," in proc.stdout and "(mui," in proc.stdout
    assert fig.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    csv = cosserat("solve", "plane", "--eps", "0.05", "--models", "cosserat,mui", "--format",
                   "csv", "--phi", "30")  # fmt: skip
    frame = pd.read_csv(io.StringIO(csv.stdout))
    assert list(frame.columns) == ["model", "y", "u"]
    assert set(frame["model"]) == {"cosserat", "mui"}
    err = one_error_line(cosserat("solve", "plane", "--eps", "0.05", "--models", "mui,ngf",
                                  "--phi", "30"))  # fmt: skip
    assert "--phi: none of --models mui,ngf takes it" in err


def test_models_and_help_state_the_defaults_the_commands_use():
    models = cosserat("models", "--format", "json")
    assert models.returncode == 0, models.stderr
    assert '"I_w"' in models.stdout and "0.01" in models.stdout
    channel = cosserat("solve", "channel", "--help").stdout
    assert "moving wall" not in channel


@pytest.mark.parametrize(
    ("body", "needle"),
    [
        ("distance_d,u_over_uw\n", "no data rows after the column header (line 1)"),
        ("distance_d,u_over_uw\n-1,0.5\n",
         "line 2, column 'distance_d': distances from the wall must be >= 0; got -1"),
    ],
)  # fmt: skip
def test_csv_errors_say_what_is_wrong_with_plain_numbers(tmp_path, body, needle):
    data = tmp_path / "d.csv"
    data.write_text(body)
    err = one_error_line(cosserat("compare", str(data), "--geometry", "plane", "--eps", "0.05"))
    assert needle in err and "1-D arrays" not in err
