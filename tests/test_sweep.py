"""Sweeps: the spec, the batched engine against single solves, failures recorded, and the same
table from local processes and from a Dask cluster."""

from __future__ import annotations

import csv

import numpy as np
import pytest

from cosserat import CouetteFlow, Material, ParameterError, PlaneShear, Wall, solve
from cosserat.analysis import shear_layer_thickness, wall_omega, wall_slip
from cosserat.cli import main
from cosserat.routes.numerical import wall_quantities
from cosserat.studies.sweep import load_spec, parse_spec, run_sweep

MAT = Material(28.5)
SPEC = """
geometry = "plane"
chunk = 5
[fixed]
phi = 28.5
[grid]
delta = [10.0, 20.0, "fully-rough"]
eps = { geomspace = [1e-1, 1e-5, 4] }
B = [0.0, 1.0]
[[cases]]
geometry = "couette"
eps = 0.01
Ri = 2.0
[[cases]]
eps = 0.9
"""


def test_spec_expansion_and_errors(tmp_path):
    spec = parse_spec(__import__("tomllib").loads(SPEC))
    assert len(spec.cases) == 3 * 4 * 2 + 2
    assert spec.cases[0]["delta"] == 10.0 and spec.cases[0]["eps"] == pytest.approx(0.1)
    with pytest.raises(ParameterError, match=r"unknown parameter\(s\) \['zeta'\] in \[grid\]"):
        parse_spec({"grid": {"zeta": [1]}, "fixed": {"eps": 0.1}})
    with pytest.raises(ParameterError, match="unknown top-level key"):
        parse_spec({"gird": {}})
    with pytest.raises(ParameterError, match="grid entry 'eps' must be"):
        parse_spec({"grid": {"eps": {"logspace": [1, 2, 3]}}})
    with pytest.raises(ParameterError, match="case 0: no eps"):
        parse_spec({"fixed": {"delta": 20.0}})
    bad = tmp_path / "bad.toml"
    bad.write_text("[grid\n")
    with pytest.raises(ParameterError, match="not valid TOML"):
        load_spec(bad)


PROBLEMS = [
    PlaneShear(material=MAT, upper=Wall(20.0), eps=1e-3),
    PlaneShear(material=MAT, upper=Wall(15.0, 0.2), lower=Wall(25.0), eps=0.02),
    PlaneShear(material=MAT, upper=Wall(25.0), lower=Wall(20.0), eps=1e-4, B=0.2),
    PlaneShear(material=MAT, upper=Wall.fully_rough(), eps=1e-5, B=1.0),
    PlaneShear(material=MAT, upper=Wall.fully_rough(), eps=0.04),
    PlaneShear(material=Material(35.0, L=5, A=0.0), upper=Wall(28.0, 1.0), eps=0.01, B=2.0),
    PlaneShear(material=MAT, upper=Wall(20.0), eps=0.1, B=1.0),  # no real solution
    CouetteFlow(material=MAT, wall=Wall(20.0), eps=1e-3, Ri=1.0),
    CouetteFlow(material=MAT, wall=Wall.fully_rough(0.0), eps=0.05, Ri=10.0),
    CouetteFlow(material=MAT, wall=Wall(20.0), eps=0.04, Ri=0.05),  # no real solution
]


def test_batched_wall_quantities_match_single_solves():
    results = wall_quantities(PROBLEMS, rtol=1e-9)
    for problem, res in zip(PROBLEMS, results, strict=True):
        try:
            prof = solve(problem, rtol=1e-11, check=False)
        except Exception as exc:
            assert res.status == "no-solution" and "no real solution" in res.message
            assert "no real solution" in str(exc)
            continue
        assert res.status == "ok"
        assert res.Delta == pytest.approx(shear_layer_thickness(prof), rel=1e-7)
        assert res.wall_omega == pytest.approx(wall_omega(prof), rel=1e-7)
        assert res.wall_slip == pytest.approx(wall_slip(prof), rel=1e-6, abs=1e-12)


def _read(path):
    with open(path) as fh:
        return list(csv.DictReader(fh))


def test_sweep_records_every_case_and_is_the_same_in_one_or_two_processes(tmp_path):
    spec = parse_spec(__import__("tomllib").loads(SPEC))
    one = run_sweep(spec, workers=1)
    two = run_sweep(spec, workers=2)
    assert len(one) == len(spec.cases) == len(two)
    assert one == two
    status = [r["status"] for r in one]
    assert status.count("invalid") == 1 and "eps = d_p/H must satisfy" in one[-1]["message"]
    assert status.count("no-solution") >= 1
    fine = [r for r in one if r["status"] == "ok"]
    assert all(np.isfinite(r["Delta"]) for r in fine)


def test_sweep_on_a_dask_local_cluster_gives_the_same_rows():
    distributed = pytest.importorskip("distributed")
    spec = parse_spec(__import__("tomllib").loads(SPEC))
    local = run_sweep(spec, workers=1)
    with distributed.LocalCluster(
        n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None
    ) as cluster:
        remote = run_sweep(spec, scheduler=cluster.scheduler_address)
    assert remote == local


def test_sweep_cli(tmp_path, capsys):
    spec = tmp_path / "s.toml"
    spec.write_text(SPEC)
    out = tmp_path / "table.csv"
    assert main(["sweep", str(spec), "--out", str(out), "--workers", "1"]) == 0
    rows = _read(out)
    assert len(rows) == 26
    assert set(rows[0]) >= {"delta", "eps", "B", "Delta", "wall_slip", "status", "message"}
    assert "26 cases" in capsys.readouterr().out
