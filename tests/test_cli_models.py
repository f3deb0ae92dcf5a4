"""--model and --param on the command line, read from the rheology registry: every registered
model on every one of its cells, one-line errors for a cell a model lacks, an unknown key or an
option of another model."""

from __future__ import annotations

import json

import pytest

from cosserat import Couette, MuI, Plane, Problem, solve
from cosserat.cli import main, make_parser
from cosserat.cli.params import valid_keys
from cosserat.model import problem_parameters
from cosserat.routes import RHEOLOGIES, cells_for


def run(capsys, *args):
    code = main(list(args))
    out, err = capsys.readouterr()
    return code, out, err


def one_line_error(capsys, *args):
    code, out, err = run(capsys, *args)
    assert code == 2 and out == "", err
    assert len(err.strip().splitlines()) == 1 and "Traceback" not in err
    return err


def test_mui_through_param_is_the_api_problem(capsys):
    code, out, _ = run(
        capsys, "solve", "couette", "--model", "mui", "--eps", "0.01", "--Ri", "2",
        "--param", "I_w=0.05", "--param", "mu_s=0.4", "--format", "json", "--points", "21",
    )  # fmt: skip
    assert code == 0
    record = json.loads(out)
    problem = Problem(Couette(eps=0.01, Ri=2.0, I_w=0.05), MuI(mu_s=0.4))
    assert record["parameters"] == problem.parameters()
    assert record["u"] == solve(problem, points=21).u.tolist()
    assert record["r"][0] == 2.0 and "m" not in record["columns"]


def test_cell_options_map_to_any_model_that_has_them(capsys):
    code, out, _ = run(
        capsys, "solve", "plane", "--model", "mui", "--eps", "0.01", "--B", "2", "--nu", "0.6",
        "--format", "json", "--points", "11",
    )  # fmt: skip
    assert code == 0
    params = json.loads(out)["parameters"]
    assert params == Problem(Plane(eps=0.01, B=2.0, nu=0.6), MuI()).parameters()


def test_cosserat_param_is_the_same_as_its_option(capsys):
    base = ["solve", "plane", "--eps", "0.04", "--format", "json", "--points", "11"]
    by_option = json.loads(run(capsys, *base, "--phi", "30", "--delta", "fully-rough")[1])
    by_param = json.loads(
        run(capsys, *base, "--param", "phi=30", "--param", "delta=fully-rough")[1]
    )
    assert by_option == by_param
    assert "given both as an option and as --param" in one_line_error(
        capsys, *base, "--phi", "30", "--param", "phi=31"
    )


def test_unknown_param_lists_the_valid_keys_with_units(capsys):
    err = one_line_error(
        capsys, "solve", "couette", "--eps", "0.01", "--model", "mui", "--param", "phi=30"
    )
    assert "unknown parameter(s) phi for --model mui on the couette cell" in err
    for key in ("mu_s [-]", "mu_2 [-]", "I_0 [-]", "Ri [-]", "I_w [-]"):
        assert key in err
    err = one_line_error(capsys, "solve", "plane", "--eps", "0.01", "--param", "Ri=2")
    assert "valid: phi [deg], L [-], A [-], delta [deg], K [-]" in err
    assert "--param takes KEY=VALUE" in one_line_error(
        capsys, "solve", "plane", "--eps", "0.01", "--param", "phi"
    )


def test_an_option_of_another_model_is_refused(capsys):
    err = one_line_error(
        capsys, "solve", "couette", "--eps", "0.01", "--model", "mui", "--phi", "30"
    )
    assert "--phi do(es) not apply to --model mui" in err and "mu_s [-]" in err


def test_unknown_and_unavailable_models(capsys):
    err = one_line_error(capsys, "solve", "plane", "--eps", "0.01", "--model", "granular")
    assert f"--model must be one of {', '.join(RHEOLOGIES)}; got 'granular'" in err
    err = one_line_error(capsys, "solve", "plane", "--eps", "0.01", "--model", "kinetic")
    assert "kinetic model of Bocquet et al." in err and "not implemented" in err


def test_a_model_without_the_cell_names_the_cells_it_has(capsys, toys):
    err = one_line_error(capsys, "solve", "stratified", "--eps", "0.01", "--model", "ngf")
    assert "model 'ngf' has no stratified cell; it supports: plane, couette, channel" in err


def test_a_newly_registered_cell_appears_without_edits(capsys, toys):
    solve_parser = make_parser()._subparsers._group_actions[0].choices["solve"]
    assert "stratified" in solve_parser._subparsers._group_actions[0].choices
    code, out, _ = run(
        capsys, "solve", "stratified", "--model", "mui", "--eps", "0.01", "--param", "c=3",
        "--format", "json", "--points", "5",
    )  # fmt: skip
    assert code == 0 and json.loads(out)["parameters"]["c"] == 3.0
    err = one_line_error(capsys, "solve", "stratified", "--eps", "0.01")
    assert "model 'cosserat' has no stratified cell; it supports: plane, couette" in err


def test_every_registered_model_and_cell_is_on_the_command_line():
    solve_parser = make_parser()._subparsers._group_actions[0].choices["solve"]
    cells = solve_parser._subparsers._group_actions[0].choices
    for name in RHEOLOGIES:
        for cell in cells_for(name):
            assert cell in cells
            assert valid_keys(name, cell)  # every pair states its parameters
            for key, param in problem_parameters(name, cell).items():
                assert param.cli_key == key and param.meaning and "$" not in param.meaning


def test_thickness_compare_and_fit_take_a_model(capsys, request):
    data = str(request.config.rootpath / "src/cosserat/data/synthetic_couette.csv")
    code, out, _ = run(
        capsys,
        "thickness",
        "couette",
        "--model",
        "mui",
        "--eps",
        "1e-2",
        "1e-3",
        "--format",
        "json",
    )
    record = json.loads(out)
    assert code == 0 and record["model"] == "mui" and record["Delta_asymptote"] is None
    # a local rheology's layer has a fixed width in xi: Delta (in grains) scales as 1/eps
    assert record["Delta"][1] == pytest.approx(10 * record["Delta"][0], rel=1e-6)
    code, out, _ = run(capsys, "compare", data, "--model", "mui", "--format", "json")
    assert code == 0 and json.loads(out)["problem"]["rheology"] == "mui"
    code, out, _ = run(capsys, "fit", data, "--model", "mui", "--free", "mu_s", "--format", "json")
    record = json.loads(out)
    assert code == 0 and record["model"] == "mui"
    # the calibration's contract: every parameter, the fixed ones with free = false
    assert {k for k, v in record["parameters"].items() if v["free"]} == {"mu_s"}
    assert record["parameters"]["I_0"]["reason"] == "fixed"
    assert "phi" in one_line_error(capsys, "fit", data, "--model", "mui", "--free", "phi")


@pytest.mark.parametrize(
    ("model", "cell"),
    [(name, cell) for name in RHEOLOGIES for cell in cells_for(name)],
)
def test_every_model_solves_on_every_cell_from_the_command_line(capsys, model, cell):
    required = [
        key
        for key, p in problem_parameters(model, cell).items()
        if not p.has_default and key != "eps"
    ]
    given = [a for key in required for a in ("--param", f"{key}=1")]  # e.g. a channel's B
    code, out, err = run(
        capsys, "solve", cell, "--model", model, "--eps", "0.02", "--points", "11",
        "--format", "json", *given,
    )  # fmt: skip
    assert code == 0, err
    record = json.loads(out)
    coordinate = "r" if cell == "couette" else "y"
    assert record[coordinate][0] == (
        record["parameters"].get("Ri", 0.0) if cell == "couette" else 0.0
    )
    assert record["parameters"].get("rheology", "cosserat") == model


def test_thickness_on_the_channel(capsys):
    code, out, _ = run(capsys, "thickness", "channel", "--eps", "1e-2", "1e-3", "--format", "json")
    record = json.loads(out)
    assert code == 0 and all(d is not None and d > 0 for d in record["Delta"])
