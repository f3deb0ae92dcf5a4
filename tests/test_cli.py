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
    "xi",
    "u",
    "omega",
    "m",
    "sigma_xy",
    "sigma_yx",
    "sigma_yy",
    "thickness",
    "wall_slip",
    "wall_omega",
    "diagnostics",
}


def run(capsys, *args):
    code = main(list(args))
    out, err = capsys.readouterr()
    return code, out, err


def test_solve_plane_json_contract(capsys):
    code, out, err = run(capsys, "solve", "plane", "--eps", "1e-3", "--points", "41")
    assert code == 0 and err == ""
    record = json.loads(out)
    assert set(record) >= KEYS
    assert record["problem"] == "plane"
    assert record["xi"][0] == 0.0 and record["xi"][-1] == 1.0  # whole gap, symmetric case too
    assert len(record["xi"]) == len(record["u"]) <= 41
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
    assert lines[0].startswith("# cosserat profile, method = closed-form")
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
    code, out, _ = run(capsys, "solve", "couette", "--eps", "1e-3", "--Ri", "1", "--points", "31")
    record = json.loads(out)
    assert code == 0 and KEYS <= set(record)
    assert record["problem"] == "couette" and record["parameters"]["Ri"] == 1.0
    assert record["xi"][0] == 0.0 and record["xi"][-1] == 1.0
    assert record["u"][0] < -0.9  # the inner cylinder moves at u = -1 (paper's sign)
    code, out, _ = run(
        capsys, "thickness", "couette", "--eps", "1e-3", "--fully-rough", "--method", "asymptotic"
    )
    record = json.loads(out)
    assert code == 0 and record["Delta_asymptote"] is None
    assert record["Delta"][0] == pytest.approx(record["Delta_asymptotic"][0], rel=1e-9)


def test_thickness_reports_eps_without_solution(capsys):
    code, out, _ = run(capsys, "thickness", "plane", "--eps", "0.1", "0.01", "--B", "1")
    record = json.loads(out)
    assert code == 0 and record["Delta"][0] is None
    assert "no real solution" in record["failures"]["0.1"]


@pytest.mark.parametrize(
    ("args", "needle"),
    [
        (["solve", "plane", "--eps", "0.7"], "eps = d_p/H must satisfy 0 < eps <= 0.5"),
        (["solve", "plane", "--eps", "0.1", "--delta", "40"], "tan(delta) <= sin(phi)"),
        (["solve", "plane", "--eps", "0.1", "--A", "1.5"], "A must satisfy -1 < A < 1"),
        (["solve", "plane", "--eps", "0.1", "--K", "-1"], "K must satisfy K >= 0"),
        (
            ["solve", "plane", "--eps", "0.1", "--B", "1", "--method", "closed-form"],
            "no closed form",
        ),
        (["solve", "plane", "--eps", "0.1", "--B", "1"], "no real solution"),
        (["solve", "plane", "--eps", "0.1", "--bogus"], "unrecognized arguments"),
        (["solve", "plane"], "required: --eps"),
        (["solve", "plane", "--eps", "abc"], "invalid float value"),
        (["thickness", "plane", "--eps", "0.1", "--f", "2"], "--f must satisfy 0 < f < 1"),
        (["solve", "couette", "--eps", "0.1", "--Ri", "-1"], "Ri = R_i/H must satisfy"),
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
