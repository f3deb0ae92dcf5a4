"""Issue 19's reproducers of files and inputs that failed with a traceback or did the wrong
thing: each now ends in one line on stderr and exit status 2, before any work where the
problem is known before it. The command-line ones run the command in a separate process."""

from __future__ import annotations

import os
import subprocess
import sys

import pytest

PROFILE = "# geometry: plane\n# eps: 0.05\ndistance_d,u_over_uw\n0.5,0.8\n1.5,0.5\n2.5,0.3\n"


def cosserat(*args, cwd=None, timeout=120, env=None):
    return subprocess.run(
        [sys.executable, "-m", "cosserat", *args],
        capture_output=True,
        text=True,
        check=False,
        cwd=cwd,
        timeout=timeout,
        env=None if env is None else {**os.environ, **env},
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
    a_file = tmp_path / "a_file"
    a_file.write_text("")  # a missing folder is created; one through a file cannot be
    for plot in ("fig", str(a_file / "such" / "fig.png"), str(tmp_path / "f.xyz")):
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
    # no scheduler listens on port 1: the sweep fails before any row (within 2 s, not Dask's
    # default 30 s of retries)
    failed = cosserat(
        "sweep", str(spec), "--out", str(out), "--scheduler", "tcp://127.0.0.1:1",
        env={"DASK_DISTRIBUTED__COMM__TIMEOUTS__CONNECT": "2s"},
    )  # fmt: skip
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


# ---------------------------------------------------------------------------- input files
@pytest.fixture
def corpus(tmp_path):
    """A copy of the shipped corpus to damage."""
    import shutil

    from cosserat.analysis.corpus import shipped_corpus

    folder = tmp_path / "corpus"
    shutil.copytree(shipped_corpus(), folder)
    return folder


def test_a_header_only_profile_says_it_has_no_data_rows(tmp_path):
    empty = tmp_path / "empty.csv"
    empty.write_text("# geometry: plane\n# eps: 0.05\ndistance_d,u_over_uw\n")
    err = one_line_exit_2(cosserat("compare", str(empty)))
    assert f"{empty}: no data rows after the column header (line 3)" in err
    assert "1-D arrays" not in err


def test_a_utf8_profile_with_a_byte_order_mark_is_read(tmp_path):
    from cosserat.analysis.measurements import read_profile

    plain = tmp_path / "plain.csv"
    plain.write_text(PROFILE, encoding="utf-8")
    bom = tmp_path / "bom.csv"
    bom.write_text(PROFILE.replace("# geometry", "distance_d,u_over_uw\n", 0), encoding="utf-8-sig")
    assert bom.read_bytes()[:3] == b"\xef\xbb\xbf"
    a, b = read_profile(plain), read_profile(bom)
    assert a.meta == b.meta and list(a.distance_d) == list(b.distance_d)
    assert read_profile("\ufeff" + PROFILE).n == 3  # text with the mark, as a string
    proc = cosserat("compare", str(bom), "--format", "json")
    assert proc.returncode == 0, proc.stderr


def test_a_latin1_profile_says_which_encoding_and_where(tmp_path):
    latin = tmp_path / "latin.csv"
    latin.write_bytes(("# label: caf\u00e9 au lait\n" + PROFILE).encode("latin-1"))
    err = one_line_exit_2(cosserat("compare", str(latin)))
    assert f"{latin}: not UTF-8 text: byte 0xe9 at line 1, column 13 is not valid UTF-8" in err
    assert "save the file as UTF-8" in err


def test_profile_messages_print_plain_numbers(tmp_path):
    import numpy as np

    from cosserat import Material
    from cosserat.analysis.measurements import MeasurementError, read_profile
    from cosserat.errors import ParameterError, shown

    with pytest.raises(MeasurementError, match=r"must be >= 0; got -1$"):
        read_profile("distance_d,u_over_uw\n-1.0,0.5\n1.0,0.2\n")
    with pytest.raises(MeasurementError, match=r"finite and > 0; got -0.5$"):
        read_profile("distance_d,u_over_uw,u_err\n1.0,0.5,-0.5\n")
    with pytest.raises(
        ParameterError, match=r"phi \(angle of internal friction\) must be finite; got nan$"
    ):
        Material(phi=np.float64(np.nan))
    assert shown(np.float64(-1.0)) == "-1.0" and shown(np.int64(3)) == "3"
    assert shown("abc") == "'abc'" and shown(True) == "True" and shown(2.5) == "2.5"


def test_no_numpy_repr_in_the_package_messages():
    """The source has no message that would print np.float64(...): every ``got {x!r}`` is of
    a value that is never a NumPy scalar, or goes through errors.shown."""
    import re
    from pathlib import Path

    import cosserat

    numeric = re.compile(r"got \{[^}]*(value|rtol|atol|cells|seed|bound|\bT\b|mu_s)[^}]*!r\}")
    hits = [
        f"{path.name}:{i}: {line.strip()}"
        for path in Path(cosserat.__file__).parent.rglob("*.py")
        for i, line in enumerate(path.read_text().splitlines(), start=1)
        if numeric.search(line) and "np." not in line
    ]
    # TOML and JSON values (Python numbers only); an angle that is a string or a bool
    allowed = ("sweep.py", "corpus.py")
    assert [h for h in hits if not h.startswith(allowed) and "or 'fully-rough'" not in h] == []


def test_corpus_files_in_utf8_with_a_mark_are_read_and_latin1_is_named(corpus, tmp_path):
    from cosserat.analysis.corpus import read_run

    run = corpus / "plane_rough_H20.csv"
    sidecar = run.with_suffix(".json")
    for path in (run, sidecar):
        path.write_bytes(b"\xef\xbb\xbf" + path.read_bytes())
    assert read_run(run).columns["u"].size > 3
    sidecar.write_bytes(
        sidecar.read_bytes()[3:].replace(b'"format"', b'"note": "caf\xe9", "format"', 1)
    )
    err = one_line_exit_2(cosserat("validate", str(corpus), "--out", str(tmp_path / "report")))
    assert f"{sidecar}: not UTF-8 text: byte 0xe9 at line 2, column" in err


def test_a_header_only_corpus_run_says_it_has_no_data_rows(corpus, tmp_path):
    run = corpus / "plane_rough_H20.csv"
    run.write_text(run.read_text().splitlines()[0] + "\n")
    err = one_line_exit_2(cosserat("validate", str(corpus), "--out", str(tmp_path / "report")))
    assert f"{run}: no data rows after the column header (line 1)" in err


# ---------------------------------------------------------------------------- a full disk
@pytest.fixture
def one_run(tmp_path):
    """A corpus of one shipped run (validate with --models mui takes a few seconds)."""
    import shutil

    from cosserat.analysis.corpus import shipped_corpus

    folder = tmp_path / "one"
    folder.mkdir()
    for path in shipped_corpus().glob("plane_rough_H20.*"):
        shutil.copy(path, folder)
    return folder


def test_validate_onto_a_full_disk_is_one_line(one_run, tmp_path, monkeypatch, capsys):
    """The writer fails as a full disk makes it fail (ENOSPC): one line, exit 2, and nothing
    half-written or temporary left in the report folder."""
    import errno

    from cosserat import _atomic
    from cosserat.cli import main

    class FullDisk:
        """The os module as _atomic sees it, with a replace that fails as on a full disk. Only
        _atomic's writes fail: patching os.replace itself also failed numba's cache writes
        when the kernels compiled in this test (a fresh cache), before any report file."""

        def __getattr__(self, name):
            return getattr(os, name)

        @staticmethod
        def replace(src, dst):
            raise OSError(errno.ENOSPC, "No space left on device")

    monkeypatch.setattr(_atomic, "os", FullDisk())
    out = tmp_path / "report"
    assert main(["validate", str(one_run), "--out", str(out), "--models", "mui"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "Traceback" not in err
    assert err.startswith(f"cosserat: error: cannot write {out}/run_plane_rough_H20.png: no space")
    assert list(out.iterdir()) == []


@pytest.mark.slow
def test_validate_onto_a_real_full_file_system(one_run, tmp_path):
    """The same on a 64 kB tmpfs mounted in a private mount namespace (where the system
    allows one: unshare -rm)."""
    import shutil

    if shutil.which("unshare") is None or sys.platform != "linux":
        pytest.skip("needs unshare (util-linux) on Linux")
    tiny = tmp_path / "tiny"
    tiny.mkdir()
    probe = subprocess.run(
        ["unshare", "-rm", "sh", "-c", f"mount -t tmpfs -o size=64k tmpfs {tiny}"],
        capture_output=True,
        check=False,
    )
    if probe.returncode != 0:
        pytest.skip(f"cannot mount a tmpfs in a user namespace here: {probe.stderr!r}")
    script = (
        f"mount -t tmpfs -o size=64k tmpfs {tiny} && "
        f"{sys.executable} -m cosserat validate {one_run} --out {tiny}/report --models mui; "
        f"echo status=$?; ls -A {tiny}/report"
    )
    proc = subprocess.run(
        ["unshare", "-rm", "sh", "-c", script],
        capture_output=True,
        text=True,
        check=False,
        timeout=600,
        env={**os.environ, "PYTHONPATH": os.pathsep.join(sys.path)},
    )
    assert "status=2" in proc.stdout, proc.stderr
    assert proc.stderr.count("\n") == 1 and "Traceback" not in proc.stderr
    assert (
        f"cannot write {tiny}/report/" in proc.stderr and "no space left on device" in proc.stderr
    )
    left = proc.stdout.split("status=2", 1)[1].split()
    assert not [name for name in left if name.startswith(".")], "temporary files left"
