"""``cosserat models`` and ``cosserat validate`` on the command line."""

from __future__ import annotations

import json

import numpy as np
import pytest

from cosserat.analysis.corpus import write_run
from cosserat.cli import main
from cosserat.model import problem_parameters
from cosserat.routes import RHEOLOGIES, cells_for


def test_models_lists_every_registered_rheology_with_units_and_reference(capsys):
    assert main(["models"]) == 0
    text = capsys.readouterr().out
    for name, rheology in RHEOLOGIES.items():
        assert f"{name}: {rheology.title}" in text and rheology.reference in text
        for cell in cells_for(name):
            assert f"cell {cell} (" in text
    assert "phi [deg], default 28.5; 0 < phi < 90; fit 10 to 60; material" in text
    assert "A [-], default 1/3" in text
    assert "I_w [-], default 0.01; 0 < I_w <= 1; fit 1e-06 to 1 (log); drive" in text


def test_models_json_is_the_declarations(capsys):
    """Meaning, unit, default, bounds, fit range, role and source of every parameter, as
    declared: the rheology's own, and per cell the cell's it reads."""
    assert main(["models", "--format", "json"]) == 0
    models = {m["name"]: m for m in json.loads(capsys.readouterr().out)}
    assert set(models) == set(RHEOLOGIES)
    phi = next(r for r in models["cosserat"]["parameters"] if r["name"] == "phi")
    assert phi["unit"] == "deg" and phi["default"] == 28.5 and not phi["required"]
    assert phi["fit_range"] == [10.0, 60.0] and phi["role"] == "material" and phi["source"]
    eps = next(r for r in models["mui"]["cells"]["couette"]["parameters"] if r["name"] == "eps")
    assert eps["required"] and eps["unit"] == "-" and eps["bounds"] == "1e-08 <= eps <= 0.5"
    for name, model in models.items():
        for cell, c in model["cells"].items():
            keys = [r["name"] for r in c["parameters"]] + c["model_parameters"]
            assert sorted(keys) == sorted(problem_parameters(name, cell))
    assert models["mui"]["default_free"] == ["mu_s", "I_w"]
    # the rate-independent Cosserat model reads no drive
    assert "I_w" not in [r["name"] for r in models["cosserat"]["cells"]["plane"]["parameters"]]


def _corpus(folder, gaps=(20.0, 40.0, 80.0)):
    rng = np.random.default_rng(0)
    for g in gaps:
        y = np.arange(int(g)) + 0.5
        u = np.exp(-(g - y) / 3.0)
        write_run(folder, f"run_{g:g}", {"cell": "plane", "gap_d": g, "B": 1.0,
                                          "wall": {"kind": "smooth-frictional"}},
                  {"y": y, "u": u + rng.normal(0, 0.005, y.size),
                   "u_se": np.full(y.size, 0.005)})  # fmt: skip
    return folder


def test_validate_writes_the_report_and_prints_the_verdicts(tmp_path, capsys):
    corpus = _corpus(tmp_path / "corpus")
    out = tmp_path / "out"
    assert main(["validate", str(corpus), "--out", str(out), "--models", "cosserat"]) == 0
    text = capsys.readouterr().out
    # a constant Delta at H/d = 20-80: the claimed law, not the calibrated model's curve
    assert "[mixed] Delta is independent of the gap" in text
    assert "[undecided] The grain spin departs" in text
    assert (out / "report.md").exists() and (out / "index.html").exists()
    assert main(["validate", str(corpus), "--out", str(out), "--models", "cosserat",
                 "--format", "json"]) == 0  # fmt: skip
    record = json.loads(capsys.readouterr().out)
    verdicts = {v["key"]: v["verdict"] for v in record["verdicts"]}
    assert verdicts == {"spin": "undecided", "smoother": "mixed", "rough": "undecided",
                        "spin_model": "undecided"}  # fmt: skip


@pytest.mark.parametrize(
    ("argv", "message"),
    [
        (["validate", "{tmp}/nowhere", "--out", "{tmp}/o"], "not a folder"),
        (["validate", "{tmp}/corpus", "--out", "{tmp}/o", "--models", "nonesuch"],
         "unknown model(s) nonesuch"),
        (["validate", "{tmp}/corpus", "--out", "{tmp}/o", "--f", "2"], "--f must satisfy"),
        (["validate", "{tmp}/corpus", "--out", "{tmp}/o", "--near-wall", "-1"],
         "--near-wall must be > 0"),
        (["validate", "{tmp}/corpus", "--out", "{tmp}/o", "--workers", "0"], "--workers"),
    ],
)  # fmt: skip
def test_validate_bad_input_is_one_line_and_status_2(tmp_path, capsys, argv, message):
    _corpus(tmp_path / "corpus", gaps=(20.0,))
    assert main([a.format(tmp=tmp_path) for a in argv]) == 2
    err = capsys.readouterr().err
    assert message in err and len(err.strip().splitlines()) == 1


def test_validate_without_a_corpus_argument_uses_the_shipped_one(tmp_path, capsys, monkeypatch):
    """No argument: the shipped corpus (here replaced by a small one, since validating the real
    one is a study, not a unit test); an installation without one says so in one line."""
    import cosserat.analysis.corpus as corpus

    shipped = _corpus(tmp_path / "shipped", gaps=(20.0, 40.0))
    monkeypatch.setattr(corpus, "shipped_corpus", lambda: shipped)
    out = tmp_path / "out"
    assert main(["validate", "--out", str(out), "--models", "cosserat"]) == 0
    assert "run_20" in (out / "report.md").read_text()
    monkeypatch.setattr(corpus, "shipped_corpus", lambda: tmp_path / "absent")
    assert main(["validate", "--out", str(tmp_path / "o2")]) == 2
    assert "no corpus is shipped in this installation" in capsys.readouterr().err
