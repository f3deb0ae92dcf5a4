"""No worker process outlives the command that started it, whatever ends the command.

For real: ``cosserat sweep`` and ``cosserat reproduce`` run in a separate session, the test
waits until their spawned workers exist (read from ``/proc``), sends SIGINT to the whole
process group (what Ctrl-C at a terminal does), or SIGTERM or SIGKILL to the command alone,
and then polls until every process the command had started is gone.
"""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

pytestmark = pytest.mark.skipif(not Path("/proc/self/stat").exists(), reason="reads /proc (Linux)")

GONE_WITHIN = 10.0
"""Seconds the workers may take to end after their parent (they take well under one)."""


def _stat(pid: int) -> tuple[str, int] | None:
    """(state, parent pid) of a process, or None if it is gone."""
    try:
        text = Path(f"/proc/{pid}/stat").read_text()
    except OSError:
        return None
    fields = text[text.rindex(")") + 2 :].split()
    return fields[0], int(fields[1])


def _alive(pid: int) -> bool:
    stat = _stat(pid)
    return stat is not None and stat[0] not in ("Z", "X")  # a zombie has ended


def _descendants(root: int) -> set[int]:
    parents = {}
    for entry in Path("/proc").iterdir():
        if entry.name.isdigit():
            stat = _stat(int(entry.name))
            if stat is not None:
                parents[int(entry.name)] = stat[1]
    found, frontier = set(), {root}
    while frontier:
        frontier = {pid for pid, ppid in parents.items() if ppid in frontier} - found
        found |= frontier
    return found


def _workers(root: int) -> set[int]:
    """The multiprocessing workers among the descendants of ``root``."""
    out = set()
    for pid in _descendants(root):
        try:
            cmdline = Path(f"/proc/{pid}/cmdline").read_bytes()
        except OSError:
            continue
        if b"spawn_main" in cmdline:
            out.add(pid)
    return out


def _default_sigint() -> None:
    """SIGINT back to its default in the child (a shell without job control starts
    background commands with it ignored, and then Python installs no handler for it)."""
    signal.signal(signal.SIGINT, signal.SIG_DFL)


def _start(*args: str, cwd: Path) -> subprocess.Popen:
    return subprocess.Popen(
        [sys.executable, "-m", "cosserat", *args],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        cwd=cwd,
        start_new_session=True,  # its own process group: the test's Ctrl-C reaches it alone
        preexec_fn=_default_sigint,
    )


def _wait_for(condition, what: str, proc: subprocess.Popen, timeout: float = 240.0) -> None:
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        if condition():
            return
        if proc.poll() is not None:
            _, err = proc.communicate()
            pytest.fail(f"the command ended before {what}: {proc.returncode} {err}")
        time.sleep(0.05)
    pytest.fail(f"timed out waiting for {what}")


def _send(proc: subprocess.Popen, sig: str) -> None:
    if sig == "SIGINT":  # Ctrl-C: the terminal signals the whole foreground process group
        os.killpg(proc.pid, signal.SIGINT)
    else:
        os.kill(proc.pid, getattr(signal, sig))


def _assert_all_gone(started: set[int], proc: subprocess.Popen, sig: str) -> str:
    """Every process in ``started`` ends within :data:`GONE_WITHIN`; returns stderr."""
    try:
        _, err = proc.communicate(timeout=60)
        deadline = time.monotonic() + GONE_WITHIN
        left = {pid for pid in started if _alive(pid)}
        while left and time.monotonic() < deadline:
            time.sleep(0.05)
            left = {pid for pid in left if _alive(pid)}
        assert not left, f"processes left running after {sig} to their parent: {sorted(left)}"
    finally:
        for pid in started:  # never leave a stray process behind a failed test
            if _alive(pid):
                os.kill(pid, signal.SIGKILL)
    if sig == "SIGKILL":
        assert proc.returncode == -signal.SIGKILL
    else:
        assert proc.returncode == 128 + getattr(signal, sig), err
        assert "Traceback" not in err and len(err.strip().splitlines()) == 1, err
        assert "cosserat: interrupted" in err
    return err


SPEC = """
chunk = 4
[fixed]
geometry = "plane"
[grid]
delta = [10.0, 20.0, "fully-rough"]
eps = { geomspace = [1e-1, 1e-6, 4000] }
"""


@pytest.mark.parametrize("sig", ["SIGINT", "SIGTERM", "SIGKILL"])
def test_sweep_workers_end_with_their_parent(tmp_path, sig):
    spec = tmp_path / "s.toml"
    spec.write_text(SPEC)
    journal = tmp_path / "t.csv.part"
    proc = _start("sweep", str(spec), "--out", "t.csv", "--workers", "2", cwd=tmp_path)
    # working: two workers exist and rows are arriving
    _wait_for(lambda: len(_workers(proc.pid)) == 2, "two workers started", proc)
    _wait_for(
        lambda: journal.exists() and journal.read_bytes().count(b"\n") > 8, "rows arrive", proc
    )
    started = _descendants(proc.pid)
    _send(proc, sig)
    err = _assert_all_gone(started, proc, sig)
    if sig != "SIGKILL":
        assert "--resume" in err
    assert not (tmp_path / "t.csv").exists() and journal.exists()


@pytest.mark.parametrize("sig", ["SIGINT", "SIGTERM", "SIGKILL"])
def test_reproduce_workers_end_with_their_parent_and_leave_no_temporary(tmp_path, sig):
    out = tmp_path / "out"
    proc = _start("reproduce", "--out", str(out), "--workers", "2", cwd=tmp_path)
    _wait_for(lambda: len(_workers(proc.pid)) == 2, "two workers started", proc)
    workers = _workers(proc.pid)

    def computing() -> bool:  # each worker has used a second of CPU: past its imports
        ticks = []
        for pid in workers:
            try:
                fields = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()
            except OSError:
                return False
            ticks.append(int(fields[11]) + int(fields[12]))
        return min(ticks) > os.sysconf("SC_CLK_TCK")

    _wait_for(computing, "the workers computing", proc)
    started = _descendants(proc.pid)
    before = set(out.iterdir())
    _send(proc, sig)
    _assert_all_gone(started, proc, sig)
    after = set(out.iterdir())
    assert not [p.name for p in after if p.name.startswith(".")], "temporary files left"
    time.sleep(0.5)  # nothing goes on writing figures once the workers are gone
    assert set(out.iterdir()) == after
    assert after >= {p for p in before if not p.name.startswith(".")}


def test_reproduce_removes_the_temporaries_of_a_killed_run(tmp_path):
    """A run killed while it wrote (SIGKILL: nothing can clean up) leaves hidden temporary
    files; the next run into the folder removes them, and leaves those of a running process."""
    dead = subprocess.run([sys.executable, "-c", "import os; print(os.getpid())"],
                          capture_output=True, text=True, check=True)  # fmt: skip
    dead_pid = int(dead.stdout)
    assert not _alive(dead_pid)
    out = tmp_path / "out"
    out.mkdir()
    stale = out / f".fig14_slt.png.{dead_pid}.k2j3h4l5.tmp.png"
    stale.write_bytes(b"half a figure")
    running = out / f".fig01_x.png.{os.getpid()}.abcdefgh.tmp.png"  # this process: running
    running.write_bytes(b"being written")
    proc = subprocess.run(
        [sys.executable, "-m", "cosserat", "reproduce", "--out", str(out), "--only", "1"],
        capture_output=True,
        text=True,
        check=False,
        timeout=600,
    )
    assert proc.returncode == 0, proc.stderr
    assert not stale.exists() and running.exists()
    assert (out / "index.html").exists()


STUCK = """
import argparse, sys
import numba
from cosserat import cli

@numba.njit(nogil=True, cache=False)
def spin(n):
    x = 0.0
    for i in range(n):
        x += (i % 7) * 1e-9
    return x

spin(10)  # compiled now, not after the signal

def make_parser():
    parser = argparse.ArgumentParser(prog="cosserat")
    sub = parser.add_subparsers(dest="command")
    p = sub.add_parser("stuck")
    p.set_defaults(func=lambda args: (print("inside", flush=True), spin(10**15)))
    return parser

cli.make_parser = make_parser
sys.exit(cli.main(["stuck"]))
"""


@pytest.mark.parametrize("sig, status", [("SIGTERM", 143), ("SIGINT", 130)])
def test_a_signal_ends_a_command_stuck_in_a_compiled_kernel(sig, status):
    """Python runs signal handlers between bytecodes only, so a long compiled kernel used to
    hold Ctrl-C and SIGTERM until it ended (``timeout`` could not stop the command); the
    watchdog (cli/watchdog.py) ends the process after its grace time, in one line."""
    from cosserat.cli.watchdog import GRACE

    proc = subprocess.Popen(
        [sys.executable, "-c", STUCK],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        # a shell starts a background job with Ctrl-C ignored, and the child would inherit it
        # (the watchdog rightly keeps ignoring it then): the test needs an interactive SIGINT
        preexec_fn=_default_sigint,
    )
    assert proc.stdout is not None and proc.stdout.readline() == "inside\n"
    time.sleep(0.2)  # inside the kernel by now
    sent = time.monotonic()
    proc.send_signal(getattr(signal, sig))
    try:
        _, err = proc.communicate(timeout=GRACE + GONE_WITHIN)
    except subprocess.TimeoutExpired:
        proc.kill()
        proc.communicate()  # reaped, so no other test sees its unclosed pipes
        pytest.fail(f"{sig} did not end a command stuck in a compiled kernel")
    took = time.monotonic() - sent
    assert proc.returncode == status, err
    kind = "terminated" if sig == "SIGTERM" else "interrupted"
    assert err.strip() == (
        f"cosserat: {kind}; the process ends inside a compiled computation that did not "
        f"return within {GRACE:g} s (no output of it written)"
    )
    assert took >= GRACE  # the main thread had its chance first


def test_a_forked_child_does_not_signal_through_its_parents_watchdog():
    """A worker forked (not spawned) while the watchdog runs and then sent SIGTERM must not
    make the parent end as if it had been terminated."""
    script = """
import os, signal, sys, time
from cosserat.cli.watchdog import ending_inside_kernels

def term(signum, frame):
    raise SystemExit("parent terminated")

with ending_inside_kernels(term, grace=0.5):
    pid = os.fork()
    if pid == 0:
        signal.signal(signal.SIGTERM, lambda s, f: os._exit(0))  # a Python handler
        time.sleep(30)
        os._exit(0)
    time.sleep(0.3)
    os.kill(pid, signal.SIGTERM)
    os.waitpid(pid, 0)
    time.sleep(1.5)  # three grace times
print("parent ran to the end")
"""
    proc = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True,
                          timeout=60, check=False)  # fmt: skip
    assert proc.returncode == 0 and proc.stdout == "parent ran to the end\n", proc.stderr
