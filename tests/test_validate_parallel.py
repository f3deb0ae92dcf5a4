"""validate's spin scans made one run at a time (``study.scan_job``, as the worker pool makes
them) give what the scans made together in the parent give (issue 18, item 8: the speed-up
must not change a number)."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from cosserat.analysis.corpus import read_run
from cosserat.studies.validate import spin_scan as ss
from cosserat.studies.validate import study
from cosserat.studies.validate.nulls import joint_null
from cosserat.studies.validate.synthetic import synthetic_run
from cosserat.studies.validate.wall_k import check_scans

PHI = 20.0
ROUGH = math.degrees(math.atan(math.sin(math.radians(PHI))))  # tan delta = sin phi
COMMON = {"phi": PHI, "L": 3.0, "K": 0.5}


def _run(folder, name, wall, delta, seed):
    path = synthetic_run(
        folder, name, "cosserat", "plane", 10.0, parameters={**COMMON, "delta": delta},
        wall=wall, B=1.0, noise=0.005, stress_noise=0.005, seed=seed,
    )  # fmt: skip
    return read_run(path)


@pytest.fixture(scope="module")
def pair(tmp_path_factory):
    folder = tmp_path_factory.mktemp("pair")
    return _run(folder, "rough", "rough", ROUGH, 0), _run(folder, "smooth", "smooth", 15.0, 1)


def _plain(x):
    """JSON's view of a record (NaN and None compare equal to themselves), without its timing
    fields (``seconds``: the phi-sensitivity check's cost, which no two runs share)."""

    def timeless(y):
        if isinstance(y, dict):
            return {k: timeless(v) for k, v in y.items() if k != "seconds"}
        if isinstance(y, list):
            return [timeless(v) for v in y]
        return y

    return timeless(json.loads(json.dumps(x, default=str)))


def test_scans_made_one_run_at_a_time_equal_the_scans_made_together(pair):
    runs = list(pair)
    # the parent's way before: every scan, the shared fit, the wall checks, the nulls
    together, skipped = ss.spin_scans(runs, runs, points=2)
    check_scans(together, runs)
    nulls = {sc.run: joint_null(sc, r) for sc, r in zip(together, runs, strict=True)}
    # the pool's way: one job per run, then the shared fit as its own job
    outcomes = [study.scan_job(r, runs, 2) for r in runs]
    shared = study.shared_job([o.scan for o in outcomes if o.scan is not None], runs)
    apart = study.gather_scans(outcomes, runs, shared)
    assert skipped == apart.skipped == []
    assert [sc.run for sc in apart.scans] == ["rough", "smooth"]
    for a, b in zip(together, apart.scans, strict=True):
        assert _plain(a.to_dict()) == _plain(b.to_dict())
        assert b.shared["runs"] == ["rough", "smooth"]  # the shared fit reached every scan
        assert "held" in b.wall_k or "failed" in b.wall_k
    for name, null in nulls.items():
        other = apart.nulls[name]
        for stencil, value in null.value.items():
            assert list(value) == list(other.value[stencil])
            assert list(null.se[stencil]) == list(other.se[stencil])


def test_a_run_without_a_spin_is_dropped_and_a_run_left_out_keeps_why():
    none = study.gather_scans([study.ScanOutcome("x")], [])
    assert none.scans == [] and none.skipped == [] and none.nulls == {}
    left = study.gather_scans([study.ScanOutcome("y", skipped="y (its walls differ)")], [])
    assert left.skipped == ["y (its walls differ)"]


def test_a_scanned_runs_figure_drawn_by_its_job_is_the_one_the_report_drew(pair, tmp_path):
    """A scanned run's figure is drawn once, by ``study.figure_job`` once its scan is in (in
    a worker), where the worker drew it before the joint fit and the report drew it again:
    the same joint fit and the same PNG, byte for byte."""
    import copy

    from cosserat.studies.validate.measures import NEAR_WALL_D
    from cosserat.studies.validate.report import write_run_figure

    run = pair[0]
    result = study.analyse_run(run, ["cosserat"], 0.05, NEAR_WALL_D, 2)
    scan = study.scan_job(run, list(pair), 2).scan
    assert scan is not None
    before = copy.deepcopy(result)
    study._joint_curves([before], [scan])  # judge's way, then the report's drawing
    (tmp_path / "parent").mkdir()
    (tmp_path / "job").mkdir()
    old = write_run_figure(before, tmp_path / "parent")
    name, joint = study.figure_job(result, scan, tmp_path / "job")
    assert name == old == f"run_{run.name}.png"
    assert before.joint is not None and joint is not None and set(joint) == set(before.joint)
    for key, value in before.joint.items():
        assert list(map(float, np.ravel(joint[key]))) == list(map(float, np.ravel(value)))
    assert (tmp_path / "job" / name).read_bytes() == (tmp_path / "parent" / name).read_bytes()


@pytest.mark.slow
def test_two_workers_write_the_report_one_process_writes(pair, tmp_path):
    """validate with a pool (the runs, the scans, each scanned run's figure job, the spin
    scan's figure drawn as soon as the scans are in, the claim figures drawn in the pool)
    writes the files one process writes, byte for byte (results.json but for the fits'
    seconds)."""
    from cosserat.analysis.corpus import read_corpus
    from cosserat.studies.validate import validate

    corpus = read_corpus(pair[0].path.parent)
    one, two = tmp_path / "one", tmp_path / "two"
    validate(corpus, one, models=["cosserat"], workers=1, spin_scan=2)
    validate(corpus, two, models=["cosserat"], workers=2, spin_scan=2)

    def timeless(x):
        if isinstance(x, dict):
            return {k: timeless(v) for k, v in x.items() if k != "seconds"}
        return [timeless(v) for v in x] if isinstance(x, list) else x

    names = sorted(p.name for p in one.iterdir())
    assert names == sorted(p.name for p in two.iterdir())
    assert {"claim_spin_scan.png", "run_rough.png", "run_smooth.png"} <= set(names)
    for name in names:
        a, b = (one / name).read_bytes(), (two / name).read_bytes()
        if name == "results.json":
            assert timeless(json.loads(a)) == timeless(json.loads(b))
        else:
            assert a == b, name
