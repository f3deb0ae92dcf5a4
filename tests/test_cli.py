"""The command line: the JSON contract, formats, and one-line errors with exit status 2."""

from __future__ import annotations

import json
import subprocess
import sys

import pytest
from reference import delta_limit_by_hand

from cosserat.cli import main

KEYS = {
    "problem",
    "parameters",
    "y",
    "u",
    "omega",
    "m",
    "sigma_xy",
    "sigma_yx",
    "sigma_yy",
    "thickness",
    "wall_slip",
    "wall_omega",
    "columns",
    "diagnostics",
}
COUETTE_KEYS = (KEYS - {"y", "sigma_xy", "sigma_yx", "sigma_yy"}) | {
    "r",
    "sigma_theta_r",
    "sigma_r_theta",
    "sigma_rr",
}


def run(capsys, *args):
    code = main(list(args))
    out, err = capsys.readouterr()
    return code, out, err


def test_solve_plane_json_contract(capsys):
    code, out, err = run(
        capsys, "solve", "plane", "--eps", "1e-3", "--points", "41", "--format", "json"
    )
    assert code == 0 and err == ""
    record = json.loads(out)
    assert set(record) >= KEYS
    assert record["problem"] == "plane"
    assert record["y"][0] == 0.0 and record["y"][-1] == 1.0  # whole gap, symmetric case too
    assert len(record["y"]) == len(record["u"]) <= 41
    assert record["parameters"]["phi"] == 28.5 and record["parameters"]["upper"]["delta"] == 20.0
    assert record["parameters"]["L"] == 10.0 and record["parameters"]["upper"]["K"] == 0.5
    assert record["thickness"] == pytest.approx(delta_limit_by_hand(), rel=1e-6)
    assert record["wall_omega"] < 0 and record["wall_slip"] > 0
    assert record["diagnostics"]["method"] == "numerical"


def test_solve_plane_csv_and_methods(capsys, tmp_path):
    out_file = tmp_path / "p.csv"
    code, out, _ = run(
        capsys,
        "solve",
        "plane",
        "--eps",
        "0.04",
        "--method",
        "closed-form",
        "--format",
        "csv",
        "--out",
        str(out_file),
    )
    assert code == 0 and out == ""
    lines = out_file.read_text().splitlines()
    assert lines[0].startswith("y,u,omega,m,sigma_xy")
    sidecar = json.loads((tmp_path / "p.json").read_text())
    assert sidecar["method"] == "closed-form" and sidecar["file"] == "p.csv"
    code, out, _ = run(
        capsys,
        "solve",
        "plane",
        "--eps",
        "1e-3",
        "--fully-rough",
        "--B",
        "1",
        "--method",
        "asymptotic",
        "--format",
        "json",
    )
    assert code == 0 and json.loads(out)["diagnostics"]["method"] == "asymptotic"


def test_thickness_json(capsys):
    code, out, _ = run(
        capsys,
        "thickness",
        "plane",
        "--eps",
        "1e-2",
        "1e-4",
        "--delta-lower",
        "25",
        "--format",
        "json",
    )
    assert code == 0
    record = json.loads(out)
    assert record["eps"] == [1e-2, 1e-4]
    assert len(record["Delta"]) == 2
    assert record["Delta_asymptote"] == pytest.approx(delta_limit_by_hand(), rel=1e-12)
    assert record["Delta"][1] == pytest.approx(delta_limit_by_hand(), rel=1e-6)


def test_solve_and_thickness_couette(capsys):
    code, out, _ = run(
        capsys,
        "solve",
        "couette",
        "--eps",
        "1e-3",
        "--Ri",
        "1",
        "--points",
        "31",
        "--format",
        "json",
    )
    record = json.loads(out)
    assert code == 0 and COUETTE_KEYS <= set(record)
    assert record["problem"] == "couette" and record["parameters"]["Ri"] == 1.0
    assert record["r"][0] == 1.0 and record["r"][-1] == 2.0  # r/H from R_i/H to R_i/H + 1
    assert record["u"][0] < -0.9  # the inner cylinder moves at u = -1 (paper's sign)
    code, out, _ = run(
        capsys,
        "thickness",
        "couette",
        "--eps",
        "1e-3",
        "--fully-rough",
        "--method",
        "asymptotic",
        "--format",
        "json",
    )
    record = json.loads(out)
    assert code == 0 and record["Delta_asymptote"] is None
    assert record["Delta"][0] == pytest.approx(record["Delta_asymptotic"][0], rel=1e-9)


def test_thickness_reports_eps_without_solution(capsys):
    code, out, _ = run(
        capsys, "thickness", "plane", "--eps", "0.1", "0.01", "--B", "1", "--format", "json"
    )
    record = json.loads(out)
    assert code == 0 and record["Delta"][0] is None
    assert "no real solution" in record["failures"]["0.1"]


@pytest.mark.parametrize(
    ("args", "needle"),
    [
        (
            ["solve", "plane", "--eps", "0.7"],
            "eps (grain diameter over gap, d_p/H) must satisfy 1e-08 <= eps <= 0.5",
        ),
        (["solve", "plane", "--eps", "0.1", "--delta", "40"], "tan(delta) <= sin(phi)"),
        (
            ["solve", "plane", "--eps", "0.1", "--A", "1.5"],
            "must satisfy -1 < A < 1 (the quadratic form in eqn-yc2 must be positive); got 1.5",
        ),
        (["solve", "plane", "--eps", "0.1", "--K", "-1"], "must satisfy 0 <= K; got -1"),
        (
            ["solve", "plane", "--eps", "0.1", "--B", "1", "--method", "closed-form"],
            "no closed form",
        ),
        (["solve", "plane", "--eps", "0.1", "--B", "1"], "no real solution"),
        (["solve", "plane", "--eps", "0.1", "--bogus"], "unrecognized arguments"),
        (["solve", "plane"], "required: --eps"),
        (["solve", "plane", "--eps", "abc"], "invalid float value"),
        (["thickness", "plane", "--eps", "0.1", "--f", "2"], "--f must satisfy 0 < f < 1"),
        (
            ["solve", "couette", "--eps", "0.1", "--Ri", "-1"],
            "Ri (inner radius over gap, R_i/H) must satisfy",
        ),
        (["solve", "couette", "--eps", "0.04", "--Ri", "0.05"], "no real solution"),
        (["solve", "couette", "--eps", "0.1", "--B", "1"], "unrecognized arguments: --B"),
    ],
)
def test_bad_input_one_line_exit_2(capsys, args, needle):
    code, out, err = run(capsys, *args)
    assert code == 2
    assert out == ""
    assert len(err.strip().splitlines()) == 1
    assert needle in err
    assert "Traceback" not in err


def test_console_script_entry_point_runs_as_a_process():
    proc = subprocess.run(
        [sys.executable, "-m", "cosserat", "solve", "plane", "--eps", "0.9"],
        capture_output=True,
        text=True,
        check=False,
    )
    assert proc.returncode == 2
    assert proc.stderr.count("\n") == 1 and "eps" in proc.stderr


# --------------------------------------------------------------------------- errors contract
def _one_line_exit_2(capsys, *args):
    code, out, err = run(capsys, *args)
    assert code == 2, err
    assert out == ""
    assert len(err.strip().splitlines()) == 1
    assert "Traceback" not in err
    return err


PROFILE = "# geometry: plane\n# eps: 0.05\ndistance_d,u_over_uw\n0.5,0.8\n1.5,0.5\n2.5,0.3\n"


@pytest.mark.parametrize("command", ["compare", "fit"])
def test_a_missing_measured_profile_names_the_file(capsys, tmp_path, command):
    missing = tmp_path / "nope.csv"
    err = _one_line_exit_2(capsys, command, str(missing))
    assert f"cannot read the measured profile {missing}: no such file or directory" in err


@pytest.mark.parametrize("command", ["compare", "fit"])
def test_a_directory_as_measured_profile_names_it(capsys, tmp_path, command):
    err = _one_line_exit_2(capsys, command, str(tmp_path))
    assert f"cannot read the measured profile {tmp_path}: is a directory" in err


def test_figures_data_file_that_does_not_exist(capsys, tmp_path):
    missing = tmp_path / "nope.csv"
    err = _one_line_exit_2(
        capsys, "figures", "--out", str(tmp_path / "f"), "--only", "1", "--data", f"glass={missing}"
    )
    assert f"{missing}: no such file or directory" in err


def test_a_malformed_measured_profile_names_the_file_and_the_line(capsys, tmp_path):
    bad = tmp_path / "bad.csv"
    bad.write_text(PROFILE + "3.5,abc\n")
    err = _one_line_exit_2(capsys, "compare", str(bad))
    assert f"{bad}: line 7, column 'u_over_uw': 'abc' is not a number" in err
    binary = tmp_path / "binary.csv"
    binary.write_bytes(b"\xff\xfe\x00\x81")
    assert f"{binary}: not a text file (it holds NUL bytes" in _one_line_exit_2(
        capsys, "compare", str(binary)
    )


@pytest.mark.parametrize(
    "argv",
    [
        ["solve", "plane", "--eps", "0.1"],
        ["thickness", "plane", "--eps", "0.1"],
        ["compare", "{profile}"],
        ["fit", "{profile}"],
    ],
)
@pytest.mark.parametrize("where", ["below-a-file", "directory"])
def test_an_unwritable_out_is_reported_before_any_work(capsys, tmp_path, argv, where):
    profile = tmp_path / "p.csv"
    profile.write_text(PROFILE)
    out = profile / "such" / "x.json" if where == "below-a-file" else tmp_path
    args = [a.format(profile=profile) for a in argv] + ["--out", str(out)]
    err = _one_line_exit_2(capsys, *args)
    assert f"cannot write --out {out}" in err
    assert (f"{profile} is not a folder" if where == "below-a-file" else "it is a directory") in err


def test_an_unwritable_plot_or_unknown_format(capsys, tmp_path):
    err = _one_line_exit_2(capsys, "solve", "plane", "--eps", "0.1", "--plot", str(tmp_path))
    assert f"cannot write --plot {tmp_path}: it is a directory" in err
    bad = tmp_path / "p.xyz"
    err = _one_line_exit_2(capsys, "solve", "plane", "--eps", "0.1", "--plot", str(bad))
    assert "unknown image format 'xyz'" in err and not bad.exists()


def test_an_out_folder_that_is_a_file(capsys, tmp_path):
    a_file = tmp_path / "f"
    a_file.write_text("")
    for command in ("figures", "reproduce"):
        err = _one_line_exit_2(capsys, command, "--out", str(a_file), "--only", "1")
        assert f"cannot use --out {a_file} as the output folder: it is a file" in err


def test_sweep_spec_and_table_that_cannot_be_used(capsys, tmp_path):
    err = _one_line_exit_2(capsys, "sweep", str(tmp_path / "nope.toml"))
    assert "cannot read the sweep spec" in err and "no such file or directory" in err
    err = _one_line_exit_2(capsys, "sweep", str(tmp_path))
    assert "is a directory" in err
    spec = tmp_path / "s.toml"
    spec.write_text("[fixed]\neps = 0.1\n")
    out = spec / "t.csv"
    err = _one_line_exit_2(capsys, "sweep", str(spec), "--out", str(out), "--workers", "1")
    assert f"cannot write --out {out}: {spec} is not a folder" in err
    spec.write_text("chunk = 'x'\n[fixed]\neps = 0.1\n")
    assert "chunk must be a whole number" in _one_line_exit_2(capsys, "sweep", str(spec))
    spec.write_text("fixed = 3\n")
    assert "[fixed] must be a table" in _one_line_exit_2(capsys, "sweep", str(spec))
    assert "--workers: must be at least 1" in _one_line_exit_2(
        capsys, "sweep", str(spec), "--workers", "0"
    )


def test_a_model_error_from_a_file_header_names_the_parameter(capsys, tmp_path):
    bad = tmp_path / "h.csv"
    bad.write_text(PROFILE.replace("# eps: 0.05", "# eps: abc"))
    assert "eps (grain diameter over gap, d_p/H) must be a number; got 'abc'" in _one_line_exit_2(
        capsys, "compare", str(bad)
    )
    assert "--B do(es) not apply to --model cosserat on the couette cell" in _one_line_exit_2(
        capsys, "compare", str(bad), "--preset", "glass", "--geometry", "couette", "--B", "1"
    )


@pytest.mark.parametrize("error", [RuntimeError, ValueError, ZeroDivisionError, KeyError, OSError])
def test_a_programming_error_is_not_swallowed(monkeypatch, capsys, error):
    """Only CosseratError (and usage errors) become exit status 2; a bug propagates."""
    import cosserat.cli.solve as cli

    def broken(*args, **kwargs):
        raise error("a bug")

    monkeypatch.setattr(cli, "solve", broken)
    with pytest.raises(error, match="a bug"):
        main(["solve", "plane", "--eps", "0.1"])
    assert capsys.readouterr().err == ""


def test_a_bug_in_a_command_shows_as_a_traceback_in_a_process(tmp_path):
    script = (
        "import sys, cosserat.cli as c, cosserat.cli.solve as s\n"
        "def broken(args):\n    raise RuntimeError('a bug')\n"
        "s.cmd_solve = broken\n"
        "sys.exit(c.main(['solve', 'plane', '--eps', '0.1']))\n"
    )
    proc = subprocess.run(
        [sys.executable, "-c", script], capture_output=True, text=True, check=False
    )
    assert proc.returncode == 1
    assert "Traceback" in proc.stderr and "RuntimeError: a bug" in proc.stderr
