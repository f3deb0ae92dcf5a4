"""Sweeps: the spec, the batched engine against single solves, failures recorded, and the same
table from local processes and from a Dask cluster."""

from __future__ import annotations

import csv

import numpy as np
import pytest

from cosserat import (
    Cosserat,
    Couette,
    Material,
    ParameterError,
    Plane,
    Problem,
    Wall,
    solve,
)
from cosserat.analysis import shear_layer_thickness, wall_omega, wall_slip
from cosserat.cli import main
from cosserat.errors import NoSolutionError
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
    Problem(Plane(eps=1e-3), Cosserat(material=MAT, wall=Wall(20.0))),
    Problem(Plane(eps=0.02), Cosserat(material=MAT, wall=Wall(15.0, 0.2), lower=Wall(25.0))),
    Problem(Plane(eps=1e-4, B=0.2), Cosserat(material=MAT, wall=Wall(25.0), lower=Wall(20.0))),
    Problem(Plane(eps=1e-5, B=1.0), Cosserat(material=MAT, wall=Wall.fully_rough())),
    Problem(Plane(eps=0.04), Cosserat(material=MAT, wall=Wall.fully_rough())),
    Problem(
        Plane(eps=0.01, B=2.0), Cosserat(material=Material(35.0, L=5, A=0.0), wall=Wall(28.0, 1.0))
    ),
    Problem(Plane(eps=0.1, B=1.0), Cosserat(material=MAT, wall=Wall(20.0))),  # no real solution
    Problem(Couette(eps=1e-3, Ri=1.0), Cosserat(material=MAT, wall=Wall(20.0))),
    Problem(Couette(eps=0.05, Ri=10.0), Cosserat(material=MAT, wall=Wall.fully_rough(0.0))),
    Problem(
        Couette(eps=0.04, Ri=0.05), Cosserat(material=MAT, wall=Wall(20.0))
    ),  # no real solution
]


def test_batched_wall_quantities_match_single_solves():
    results = wall_quantities(PROBLEMS, rtol=1e-9)
    for problem, res in zip(PROBLEMS, results, strict=True):
        try:
            prof = solve(problem, rtol=1e-11, check=False)
        except NoSolutionError as exc:
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
    assert (
        status.count("invalid") == 1
        and "eps (grain diameter over gap, d_p/H) must satisfy" in one[-1]["message"]
    )
    assert status.count("no-solution") >= 1
    fine = [r for r in one if r["status"] == "ok"]
    assert all(np.isfinite(r["Delta"]) for r in fine)


@pytest.mark.slow
def test_sweep_on_a_dask_local_cluster_gives_the_same_rows():
    distributed = pytest.importorskip("distributed")
    spec = parse_spec(__import__("tomllib").loads(SPEC))
    local = run_sweep(spec, workers=1)
    with distributed.LocalCluster(
        n_workers=2, threads_per_worker=1, processes=True, dashboard_address=":0"
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


# --------------------------------------------------------------------------- one builder
SAME = [
    {"geometry": "plane", "eps": 0.01},
    {"geometry": "plane", "eps": 0.02, "phi": 30.0, "L": 5.0, "A": 0.0, "delta": 15.0, "K": 0.2},
    {"geometry": "plane", "eps": 0.04, "delta": "fully-rough", "B": 1.0, "nu": 0.6},
    {"geometry": "plane", "eps": 0.04, "delta": 10.0, "delta_lower": "fully-rough"},
    {"geometry": "plane", "eps": 0.04, "delta": 20.0, "delta_lower": 25.0, "K_lower": 0.1},
    {"geometry": "plane", "eps": 0.04, "delta": 10.0, "delta_lower": 20.0, "m_wall": 0.1},
    {"geometry": "couette", "eps": 0.05, "Ri": 2.0, "delta": "fully-rough", "K": 0.0},
]
OPTION = {"delta_lower": "--delta-lower", "K_lower": "--K-lower", "m_wall": "--m-wall"}


def _cli_problem(params):
    from cosserat.cli import make_parser, problem_from_args

    argv = ["solve", params["geometry"]]
    for key, value in params.items():
        if key != "geometry":
            argv += [OPTION.get(key, f"--{key}"), str(value)]
    args = make_parser().parse_args(argv)
    return problem_from_args(args, args.eps)


@pytest.mark.parametrize("params", SAME)
def test_the_cli_and_the_sweep_build_the_same_problem(params):
    from cosserat.model import make_problem
    from cosserat.studies.sweep import case_problem

    from_cli = _cli_problem(params)
    (case,) = parse_spec({"fixed": dict(params)}).cases
    from_sweep = case_problem(case)
    values = {k: v for k, v in params.items() if k != "geometry"}
    assert from_cli == from_sweep == make_problem("cosserat", params["geometry"], values)
    assert from_cli.parameters() == from_sweep.parameters()


def test_there_is_one_builder():
    import cosserat.analysis.gap as gap
    import cosserat.calibration.models as calibration_models
    import cosserat.calibration.single as single
    import cosserat.cli.params as cli
    import cosserat.studies.sweep as sweep
    from cosserat.model import make_problem
    from cosserat.model.build import make_problem as built

    assert sweep.make_problem is cli.make_problem is make_problem is built
    assert single.make_problem is calibration_models.make_problem is gap.make_problem is built


def test_the_defaults_are_the_declared_ones():
    from cosserat.model import make_problem

    assert make_problem("cosserat", "plane", {"eps": 0.1}) == Problem(
        Plane(eps=0.1), Cosserat(material=Material(), wall=Wall())
    )
    assert make_problem("cosserat", "couette", {"eps": 0.1}) == Problem(
        Couette(eps=0.1, Ri=1.0), Cosserat(material=Material(), wall=Wall())
    )
    assert make_problem("cosserat", "plane", {"eps": 0.1, "phi": None, "K_lower": None}) == (
        make_problem("cosserat", "plane", {"eps": 0.1})
    )


@pytest.mark.parametrize(
    ("params", "pattern"),
    [
        (
            {"geometry": "annulus", "eps": 0.1},
            r"cell must be one of 'plane', 'couette'(, '\w+')*; got 'annulus'",
        ),
        (
            {"eps": 0.1, "zeta": 1.0},
            r"unknown parameter\(s\) zeta for model 'cosserat' on the plane cell; "
            r"valid: phi \[deg\]",
        ),
        ({"eps": 0.1, "Phi": 30.0}, r"unknown parameter\(s\) Phi"),
        ({"phi": 30.0}, r"eps \(grain diameter over gap, d_p/H\) must be given"),
        (
            {"eps": 0.1, "delta": "smooth"},
            r"delta \(angle of wall friction.*\) must be a number or 'fully-rough'; got 'smooth'",
        ),
        (
            {"eps": 0.1, "delta_lower": "x"},
            r"lower wall \(delta_lower, K_lower\): delta \(.*\) must be a number",
        ),
        ({"eps": 0.1, "phi": True}, r"phi \(.*\) must be a number; got True"),
        ({"eps": 0.1, "phi": "abc"}, r"phi \(.*\) must be a number; got 'abc'"),
        ({"eps": 0.1, "K_lower": -1.0}, r"lower wall .*K \(.*\) must satisfy 0 <= K; got -1"),
        (
            {"eps": 0.1, "geometry": "couette", "B": 1.0},
            r"unknown parameter\(s\) B for model 'cosserat' on the couette cell",
        ),
        (
            {"eps": 0.1, "geometry": "couette", "delta_lower": 10.0},
            r"unknown parameter\(s\) delta_lower .* couette cell",
        ),
        ({"eps": 0.1, "Ri": 2.0}, r"unknown parameter\(s\) Ri for model 'cosserat' on the plane"),
    ],
)
def test_make_problem_errors_name_the_key(params, pattern):
    from cosserat.model import make_problem

    values = {k: v for k, v in params.items() if k != "geometry"}
    with pytest.raises(ParameterError, match=pattern):
        make_problem("cosserat", params.get("geometry", "plane"), values)


def test_a_bad_case_is_an_invalid_row_naming_the_key():
    spec = parse_spec({"fixed": {"eps": 0.1}, "cases": [{"geometry": "annulus"}, {"phi": "x"}]})
    rows = run_sweep(spec, workers=1)
    assert [r["status"] for r in rows] == ["invalid", "invalid"]
    assert "cell must be one of 'plane', 'couette'" in rows[0]["message"]
    assert "phi (angle of internal friction) must be a number" in rows[1]["message"]


@pytest.mark.parametrize(
    ("data", "pattern"),
    [
        ({"fixed": 3}, r"\[fixed\] must be a table"),
        ({"grid": [1]}, r"\[grid\] must be a table"),
        ({"cases": [1]}, r"\[cases\] must be a table"),
        ({"cases": "x"}, r"cases must be an array of tables"),
        ({"fixed": {"eps": 0.1}, "grid": {"delta": []}}, r"grid entry 'delta' is an empty list"),
        ({"grid": {"eps": {"geomspace": [0, 1, 3]}}}, r"geomspace needs a and b nonzero"),
        ({"grid": {"eps": {"linspace": [0, 1, "a"]}}}, r"linspace = \[a, b, n\] needs numbers"),
        ({"fixed": {"eps": 0.1}, "rtol": "x"}, r"rtol must be a number; got 'x'"),
        ({"fixed": {"eps": 0.1}, "rtol": 1.0}, r"rtol must satisfy 1e-13 <= rtol <= 0.01"),
        ({"fixed": {"eps": 0.1}, "f": 1.5}, r"f must satisfy 0 < f < 1"),
        ({"fixed": {"eps": 0.1}, "chunk": 0}, r"chunk must be a whole number >= 1; got 0"),
        ({"fixed": {"eps": 0.1}, "output": 3}, r"output must be a file name"),
    ],
)
def test_malformed_specs_raise_parameter_error_naming_the_key(data, pattern):
    with pytest.raises(ParameterError, match=pattern):
        parse_spec(data)


def test_spec_files_that_cannot_be_read(tmp_path):
    from cosserat.errors import InputError

    with pytest.raises(InputError, match=r"cannot read the sweep spec .*nope.toml: no such file"):
        load_spec(tmp_path / "nope.toml")
    with pytest.raises(InputError, match=r"cannot read the sweep spec .*: is a directory"):
        load_spec(tmp_path)
    binary = tmp_path / "b.toml"
    binary.write_bytes(b"\xff\xfe\x00\x81")
    with pytest.raises(InputError, match=r"b.toml: not a text file \(it holds NUL bytes"):
        load_spec(binary)


# --------------------------------------------------------------------------- interruptions
LONG = """
geometry = "plane"
chunk = 1
[fixed]
phi = 28.5
[grid]
delta = [10.0, 20.0, "fully-rough"]
eps = { geomspace = [1e-1, 1e-5, 2000] }
B = [0.0, 1.0]
"""


def _default_sigint() -> None:
    """In the child, before exec: SIGINT back to its default. A shell without job control
    starts background commands with SIGINT ignored, and an ignored SIGINT stays ignored
    across exec (Python then installs no KeyboardInterrupt handler): under such a CI runner
    the test's Ctrl-C would never reach the sweep, as it does at a terminal."""
    import signal

    signal.signal(signal.SIGINT, signal.SIG_DFL)


def _cosserat(*args, **kw):
    import subprocess
    import sys

    return subprocess.Popen(
        [sys.executable, "-m", "cosserat.cli", *args],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        preexec_fn=_default_sigint,
        **kw,
    )


def _interrupt_after(proc, journal, rows, sig):
    """Send ``sig`` to ``proc`` once ``journal`` holds ``rows`` finished rows."""
    import time

    deadline = time.monotonic() + 300
    while time.monotonic() < deadline and proc.poll() is None:
        if journal.exists() and journal.read_bytes().count(b"\n") > rows:
            proc.send_signal(sig)
            break
        time.sleep(0.005)
    return proc.communicate(timeout=300)


@pytest.mark.slow
@pytest.mark.parametrize("sig", ["SIGINT", "SIGKILL"])
def test_an_interrupted_sweep_keeps_its_rows_and_resume_computes_only_the_rest(tmp_path, sig):
    import signal

    from cosserat.studies.sweep import journal_path

    spec = tmp_path / "s.toml"
    spec.write_text(LONG)
    reference = tmp_path / "reference.csv"
    assert main(["sweep", str(spec), "--out", str(reference), "--workers", "1"]) == 0
    full = reference.read_text().splitlines()
    out = tmp_path / "table.csv"
    journal = journal_path(out)
    proc = _cosserat("sweep", str(spec), "--out", str(out), "--workers", "1")
    _, err = _interrupt_after(proc, journal, 50, getattr(signal, sig))
    assert not out.exists(), "an interrupted sweep must not write a partial table"
    kept = journal.read_text().splitlines()
    assert 50 <= len(kept) - 1 < len(full) - 1, "interrupted too late: make LONG longer"
    if sig == "SIGINT":
        assert proc.returncode == 130 and "--resume" in err and "Traceback" not in err
    else:
        assert proc.returncode == -signal.SIGKILL
        with journal.open("a") as fh:  # a row cut in the middle by the kill
            fh.write("plane,28.5,10.0,0.33")
    # every kept row is the uninterrupted run's row for that case (chunk = 1: in spec order)
    assert kept[1:] == full[1 : len(kept)]
    again = _cosserat("sweep", str(spec), "--out", str(out))  # refuses: rows would be lost
    _, err = again.communicate(timeout=300)
    assert again.returncode == 2 and "--resume" in err and len(err.strip().splitlines()) == 1
    resumed = _cosserat("sweep", str(spec), "--out", str(out), "--workers", "1", "--resume")
    stdout, err = resumed.communicate(timeout=300)
    assert resumed.returncode == 0, err
    assert f"{len(kept) - 1} reused from an earlier run" in stdout
    assert out.read_text() == reference.read_text()
    assert not journal.exists()


def test_resume_reuses_a_finished_table_and_recomputes_nothing(tmp_path):
    from cosserat.studies.sweep import run_sweep_to_table

    spec = parse_spec(__import__("tomllib").loads(SPEC))
    first = run_sweep_to_table(spec, tmp_path / "t.csv", workers=1)
    text = (tmp_path / "t.csv").read_text()
    assert (first.reused, first.computed) == (0, len(spec.cases))
    again = run_sweep_to_table(spec, tmp_path / "t.csv", resume=True, workers=1)
    assert (again.reused, again.computed) == (len(spec.cases), 0)
    assert (tmp_path / "t.csv").read_text() == text
    # a spec with more cases computes only the new ones
    more = parse_spec(__import__("tomllib").loads(SPEC + "[[cases]]\neps = 0.03\n"))
    grown = run_sweep_to_table(more, tmp_path / "t.csv", resume=True, workers=1)
    assert (grown.reused, grown.computed) == (len(spec.cases), 1)
    assert (tmp_path / "t.csv").read_text().startswith(text.rstrip("\r\n"))


def test_resume_refuses_a_journal_of_another_spec(tmp_path):
    from cosserat.errors import InputError
    from cosserat.studies.sweep import journal_path, run_sweep_to_table

    spec = parse_spec(__import__("tomllib").loads(SPEC))
    journal_path(tmp_path / "t.csv").write_text("eps,Delta\n0.1,3.0\n")
    with pytest.raises(InputError, match=r"its columns \(eps, Delta\) are not this sweep's"):
        run_sweep_to_table(spec, tmp_path / "t.csv", resume=True, workers=1)


@pytest.mark.slow
@pytest.mark.parametrize("allowed_failures", [3, 0])
def test_a_dask_worker_killed_mid_sweep_loses_no_row(allowed_failures):
    """A worker process is killed (SIGKILL) while it holds tasks. With Dask's default retries
    the scheduler reruns them; with none (allowed-failures = 0) the sweep resubmits the chunks
    Dask gives up on. Either way every chunk arrives exactly once and the rows are a local
    run's."""
    import os
    import signal

    dask = pytest.importorskip("dask")
    distributed = pytest.importorskip("distributed")
    from cosserat.studies.sweep import _chunks, run_chunks

    spec = parse_spec(__import__("tomllib").loads(LONG.replace("chunk = 1", "chunk = 12")))
    chunks = _chunks(spec.cases, spec.chunk)
    local = run_sweep(spec, workers=1)
    arrived: list[int] = []
    rows: dict[int, list] = {}
    killed: dict[str, object] = {}
    with (
        dask.config.set({"distributed.scheduler.allowed-failures": allowed_failures}),
        distributed.LocalCluster(
            n_workers=2, threads_per_worker=1, processes=True, dashboard_address=":0"
        ) as cluster,
        distributed.Client(cluster) as client,
    ):

        def on_rows(i, chunk_rows):
            arrived.append(i)
            rows[i] = chunk_rows
            if len(arrived) == 5:  # kill a worker that holds tasks now
                busy = {w: t for w, t in client.processing().items() if t}
                victim = next(iter(busy))
                pid = client.run(os.getpid, workers=[victim])[victim]
                killed.update(worker=victim, tasks=len(busy[victim]))
                os.kill(pid, signal.SIGKILL)

        run_chunks(chunks, spec.rtol, spec.f, on_rows, scheduler=cluster.scheduler_address)
    assert killed["tasks"] >= 1
    assert sorted(arrived) == list(range(len(chunks)))  # each chunk exactly once
    assert [r for i in range(len(chunks)) for r in rows[i]] == local


def test_ctrl_c_inside_a_compiled_kernel_counts_as_an_interruption():
    """numba reports a KeyboardInterrupt raised during a kernel call as a SystemError caused by
    it: the command line must still say 'interrupted' (exit 130), not print a traceback."""
    from cosserat.cli.common import interrupted as _interrupted

    try:
        try:
            raise KeyboardInterrupt
        except KeyboardInterrupt as inner:
            raise SystemError("returned a result with an exception set") from inner
    except SystemError as exc:
        assert _interrupted(exc)
    assert not _interrupted(SystemError("another failure"))
