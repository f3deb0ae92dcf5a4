"""Issue 19's reproducers of files and inputs that failed with a traceback or did the wrong
thing: each now ends in one line on stderr and exit status 2, before any work where the
problem is known before it. The command-line ones run the command in a separate process."""

from __future__ import annotations

import os
import subprocess
import sys

import pytest

PROFILE = "# geometry: plane\n# eps: 0.05\ndistance_d,u_over_uw\n0.5,0.8\n1.5,0.5\n2.5,0.3\n"


def cosserat(*args, cwd=None, timeout=120):
    return subprocess.run(
        [sys.executable, "-m", "cosserat", *args],
        capture_output=True,
        text=True,
        check=False,
        cwd=cwd,
        timeout=timeout,
    )


def one_line_exit_2(proc) -> str:
    assert proc.returncode == 2, proc.stderr
    assert proc.stdout == ""
    assert "Traceback" not in proc.stderr
    assert len(proc.stderr.strip().splitlines()) == 1, proc.stderr
    return proc.stderr


COMMANDS = {
    "solve": ["solve", "plane", "--eps", "1e-3"],
    "thickness": ["thickness", "plane", "--eps", "1e-2", "1e-3"],
    "cell": [
        "cell",
        "--grain-diameter",
        "2e-3",
        "--density",
        "1100",
        "--inner-radius",
        "0.1",
        "--gap",
        "0.05",
        "--fill-depth",
        "0.2",
        "--rotation-rate",
        "0.5",
    ],
    "fit": ["fit", "{profile}"],
    "compare": ["compare", "{profile}"],
}


@pytest.mark.parametrize("command", list(COMMANDS))
def test_a_plot_without_suffix_is_refused_before_the_work(tmp_path, command):
    profile = tmp_path / "p.csv"
    profile.write_text(PROFILE)
    argv = [a.format(profile=profile) for a in COMMANDS[command]]
    err = one_line_exit_2(cosserat(*argv, "--plot", "fig", cwd=tmp_path))
    assert "cannot write --plot fig: no suffix to tell the image format" in err
    assert "png" in err and not (tmp_path / "fig").exists()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["p.csv"]  # no temporary either


def test_plot_checks_run_before_the_work(tmp_path, monkeypatch, capsys):
    """The same refusal without solving anything (the solver would fail the test)."""
    from cosserat.cli import main
    from cosserat.cli import solve as solve_command

    def no_work(*args, **kwargs):
        raise AssertionError("the work started before --plot was checked")

    monkeypatch.setattr(solve_command, "solve", no_work)
    for plot in ("fig", str(tmp_path / "no" / "such" / "fig.png"), str(tmp_path / "f.xyz")):
        assert main(["solve", "plane", "--eps", "1e-3", "--plot", plot]) == 2
        err = capsys.readouterr().err
        assert err.startswith("cosserat: error: cannot write --plot") and err.count("\n") == 1


def test_plot_onto_the_out_file_is_refused(tmp_path):
    out = tmp_path / "result.png"
    err = one_line_exit_2(
        cosserat("solve", "plane", "--eps", "0.1", "--out", str(out), "--plot", str(out))
    )
    assert "it is the same file as --out" in err and not out.exists()
    link = tmp_path / "link.png"
    link.symlink_to(out)
    err = one_line_exit_2(
        cosserat("solve", "plane", "--eps", "0.1", "--out", str(out), "--plot", str(link))
    )
    assert "it is the same file as --out" in err


# ---------------------------------------------------------------------------- --out targets
def test_out_through_a_symlink_writes_its_target(tmp_path):
    real = tmp_path / "data" / "profile.json"
    real.parent.mkdir()
    real.write_text("old\n")
    link = tmp_path / "latest.json"
    link.symlink_to(real)
    proc = cosserat("solve", "plane", "--eps", "0.1", "--format", "json", "--out", str(link))
    assert proc.returncode == 0, proc.stderr
    assert link.is_symlink() and link.resolve() == real.resolve()
    assert real.read_text().startswith("{")
    assert sorted(p.name for p in real.parent.iterdir()) == ["profile.json"]
    assert sorted(p.name for p in tmp_path.iterdir()) == ["data", "latest.json"]


def test_out_through_a_dangling_symlink_creates_its_target(tmp_path):
    from cosserat._atomic import write_text

    link = tmp_path / "link.txt"
    link.symlink_to(tmp_path / "target.txt")
    write_text(link, "x\n")
    assert link.is_symlink() and (tmp_path / "target.txt").read_text() == "x\n"


@pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="no FIFOs on this system")
def test_out_onto_a_fifo_is_refused_and_left_alone(tmp_path):
    fifo = tmp_path / "pipe"
    os.mkfifo(fifo)
    err = one_line_exit_2(cosserat("solve", "plane", "--eps", "0.1", "--out", str(fifo)))
    assert f"cannot write --out {fifo}: it is a FIFO (named pipe)" in err
    assert fifo.is_fifo()
    link = tmp_path / "to_pipe"
    link.symlink_to(fifo)
    err = one_line_exit_2(cosserat("solve", "plane", "--eps", "0.1", "--out", str(link)))
    assert "it is a FIFO (named pipe) (the target" in err and link.is_symlink()


def test_out_onto_a_device_is_refused_and_left_alone():
    if not os.path.exists("/dev/null"):
        pytest.skip("no /dev/null on this system")
    err = one_line_exit_2(cosserat("solve", "plane", "--eps", "0.1", "--out", "/dev/null"))
    assert "cannot write --out /dev/null: it is a device" in err


def test_the_writer_refuses_what_is_not_a_regular_file(tmp_path):
    """The same rule one layer down, for every writer of the package."""
    from cosserat._atomic import save_figure, write_text
    from cosserat.errors import InputError

    with pytest.raises(InputError, match="it is a directory"):
        write_text(tmp_path, "x")
    if hasattr(os, "mkfifo"):
        os.mkfifo(tmp_path / "p")
        with pytest.raises(InputError, match="it is a FIFO"):
            write_text(tmp_path / "p", "x")
        assert (tmp_path / "p").is_fifo()
    with pytest.raises(InputError, match="no suffix"):
        save_figure(object(), tmp_path / "figure")


# ---------------------------------------------------------------------------- sweeps
def test_a_sweep_that_fails_at_start_leaves_no_journal_and_the_next_run_starts(tmp_path):
    spec = tmp_path / "s.toml"
    spec.write_text("[fixed]\ngeometry = 'plane'\n[grid]\neps = [0.1, 0.05]\n")
    out = tmp_path / "t.csv"
    # no scheduler listens on port 1: the sweep fails before any row
    failed = cosserat("sweep", str(spec), "--out", str(out), "--scheduler", "tcp://127.0.0.1:1")
    assert "cannot connect to the Dask scheduler" in one_line_exit_2(failed)
    assert not (tmp_path / "t.csv.part").exists() and not out.exists()
    # a journal with its header and no row (left by an older version, or a crash) holds
    # nothing to lose: the next run starts instead of asking for --resume
    (tmp_path / "t.csv.part").write_text("geometry,eps,Delta\n")
    again = cosserat("sweep", str(spec), "--out", str(out), "--workers", "1")
    assert again.returncode == 0, again.stderr
    assert len(out.read_text().splitlines()) == 3 and not (tmp_path / "t.csv.part").exists()


def test_a_sweep_of_a_trillion_cases_is_refused_before_it_is_made(tmp_path):
    spec = tmp_path / "huge.toml"
    spec.write_text(
        "[fixed]\ngeometry = 'plane'\n[grid]\n"
        "eps = { geomspace = [1e-1, 1e-6, 1000000] }\ndelta = { linspace = [5, 25, 1000000] }\n"
    )
    err = one_line_exit_2(cosserat("sweep", str(spec), "--workers", "1", timeout=60))
    assert "the sweep spec has 1,000,000,000,000 cases (1000000 eps x 1000000 delta)" in err
    assert "max_cases = 1,000,000" in err and "put max_cases = 1000000000000 at the top" in err
    assert not list(tmp_path.glob("huge.csv*"))


def test_max_cases_counts_grid_and_listed_cases():
    import tomllib

    from cosserat.errors import ParameterError
    from cosserat.studies.sweep import MAX_CASES, parse_spec

    text = "[grid]\neps = [0.1, 0.05]\ndelta = [10.0, 20.0]\n[[cases]]\neps = 0.02\n"
    assert len(parse_spec(tomllib.loads("max_cases = 5\n" + text)).cases) == 5
    with pytest.raises(ParameterError, match=r"has 5 cases \(2 eps x 2 delta \+ 1 \[\[cases\]\]\)"):
        parse_spec(tomllib.loads("max_cases = 4\n" + text))
    for bad in ("0", "2.5", "true", "'many'"):
        with pytest.raises(ParameterError, match="max_cases must be a whole number >= 1"):
            parse_spec(tomllib.loads(f"max_cases = {bad}\n" + text))
    with pytest.raises(ParameterError, match=f"more than max_cases = {MAX_CASES:,}"):
        parse_spec(tomllib.loads("[grid]\neps = { linspace = [0.01, 0.1, 1000001] }\n"))
