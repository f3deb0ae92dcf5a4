"""`cosserat fit --models` and `cosserat thickness --vs-gap`: the models side by side."""

from __future__ import annotations

import json
from pathlib import Path

import pandas as pd
import pytest

from cosserat import Cosserat, Couette, Problem
from cosserat.cli import main

DATA = Path(__file__).resolve().parents[1] / "src" / "cosserat" / "data" / "synthetic_couette.csv"


def test_fit_models_ranks_the_generating_model_first(capsys):
    """The synthetic profile was made by the Cosserat model (delta = 23, K = 0.3, noise 0.01):
    it must rank first by AIC, and its fitted delta must come back within 3 standard errors."""
    assert main(["fit", str(DATA), "--models", "cosserat,mui", "--format", "json"]) == 0
    record = json.loads(capsys.readouterr().out)
    assert record["best"] == "cosserat"
    fits = {f["model"]: f for f in record["fits"]}
    assert set(fits) == {"cosserat", "mui"}
    assert fits["cosserat"]["aic"] < fits["mui"]["aic"]
    delta = fits["cosserat"]["parameters"]["delta"]
    assert abs(delta["value"] - 23.0) < 3 * delta["stderr"]


def test_fit_models_csv_is_a_plain_table(tmp_path, capsys):
    out = tmp_path / "ranking.csv"
    assert (
        main(["fit", str(DATA), "--models", "cosserat,mui", "--format", "csv", "--out", str(out)])
        == 0
    )
    table = pd.read_csv(out)
    assert list(table.columns[:3]) == ["rank", "model", "k"]
    assert table.loc[0, "model"] == "cosserat" and table.loc[0, "rank"] == 1
    assert (table["AIC"].diff().dropna() >= 0).all()  # ranked by AIC
    assert json.loads(out.with_suffix(".json").read_text())["cell"] == "couette"


def test_fit_models_rejects_unknown_and_repeated_names(capsys):
    assert main(["fit", str(DATA), "--models", "cosserat,nonsense"]) == 2
    err = capsys.readouterr().err
    assert "unknown model(s) nonsense" in err and "cosserat" in err
    assert main(["fit", str(DATA), "--models", "mui,mui"]) == 2
    assert "mui more than once" in capsys.readouterr().err


def test_thickness_vs_gap_reports_each_model_and_the_paper_law(capsys):
    assert main(["thickness", "couette", "--vs-gap", "20", "40", "80", "--format", "json"]) == 0
    record = json.loads(capsys.readouterr().out)
    labels = [s["label"] for s in record["series"]]
    assert "cosserat, fully rough" in labels and "mui" in labels
    assert record["paper_slopes"]["fully rough walls"] == pytest.approx(1 / 3)
    for s in record["series"]:
        assert s["gaps"] == [20.0, 40.0, 80.0]
        assert all(d is not None and d > 0 for d in s["Delta"])
    # each Delta is the one a direct solve of that cell at eps = d/H gives
    from cosserat import Material, Wall, shear_layer_thickness, solve

    rough = next(s for s in record["series"] if s["label"] == "cosserat, fully rough")
    for g, d in zip(rough["gaps"], rough["Delta"], strict=True):
        problem = Problem(
            Couette(eps=1 / g, Ri=1.0), Cosserat(material=Material(), wall=Wall.fully_rough())
        )
        assert d == pytest.approx(shear_layer_thickness(solve(problem)), rel=1e-6)


def test_thickness_vs_gap_takes_the_cosserat_options_and_params(capsys):
    """--delta/--K set the Cosserat series (one series, not the default two); --param with
    --model sets that model's parameters; a parameter for a model left out is an error."""
    argv = ["thickness", "plane", "--vs-gap", "20", "40", "--format", "json"]
    assert main([*argv, "--models", "cosserat", "--delta", "15", "--K", "0.2"]) == 0
    (series,) = json.loads(capsys.readouterr().out)["series"]
    assert series["parameters"]["delta"] == 15.0 and series["parameters"]["K"] == 0.2
    assert main([*argv, "--models", "mui", "--model", "mui", "--param", "mu_s=0.4"]) == 0
    (series,) = json.loads(capsys.readouterr().out)["series"]
    assert series["parameters"]["mu_s"] == 0.4
    assert main([*argv, "--models", "cosserat", "--model", "mui", "--param", "mu_s=0.4"]) == 2
    assert "which --models leaves out" in capsys.readouterr().err


def test_thickness_vs_gap_on_the_channel_gives_every_model_a_row(capsys):
    """No single B makes every model flow in the channel (the Cosserat channel needs
    B nu <= 2 tan(delta), local mu(I) B nu / 2 > mu_s): mu(I) gets its own B, and a model that
    cannot be set up is a row with the reason, never the end of the study."""
    assert main(["thickness", "channel", "--vs-gap", "10", "20", "--format", "json"]) == 0
    series = {s["label"]: s for s in json.loads(capsys.readouterr().out)["series"]}
    assert series["mui"]["Delta"][0] > 0  # driven by the one default I_w (no B given)
    assert all(any(d is not None for d in s["Delta"]) for s in series.values())
    assert main(["thickness", "channel", "--vs-gap", "10", "--B", "0.1", "--format", "json"]) == 0
    rows = {s["model"]: s for s in json.loads(capsys.readouterr().out)["series"]}
    assert rows["mui"]["Delta"] == [None] and rows["mui"]["failures"]


def test_thickness_vs_gap_usage_errors(capsys):
    assert main(["thickness", "plane", "--vs-gap", "1.5"]) == 2
    assert "must exceed 2" in capsys.readouterr().err
    assert main(["thickness", "plane", "--vs-gap", "20", "--eps", "0.1"]) == 2
    assert "not --eps" in capsys.readouterr().err
    assert main(["thickness", "plane"]) == 2
    assert "--vs-gap" in capsys.readouterr().err
