"""Ctrl-C and SIGTERM end the command even inside a compiled kernel.

Python runs a signal handler only between two bytecodes of the main thread. A compiled (numba)
kernel that runs for long never returns to the interpreter, so Ctrl-C and SIGTERM used to wait
for it to end; ``timeout`` could not stop such a command, only SIGKILL could. The kernels run
without the GIL (``nogil=True``), so another thread can still act: at each of these signals the
interpreter's C-level handler writes a byte to a pipe (:func:`signal.set_wakeup_fd`), which a
daemon thread reads. If the main thread has not begun to handle the signal (its Python handler
has not run) :data:`GRACE` seconds later, the thread removes this process's temporary files
(:func:`cosserat._atomic.remove_own_temporaries`: outputs are written whole or not at all),
says so in one line and ends the process with the shell's status (130 or 143). Worker
processes end with their parent (:mod:`cosserat.numerics.runtime`). Where the main thread does
handle the signal in time, nothing changes: the command stops as cleanly as before.
"""

from __future__ import annotations

import contextlib
import os
import signal
import sys
import threading
from collections.abc import Callable, Iterator
from typing import Any

from .._atomic import remove_own_temporaries

GRACE = 3.0
"""Seconds the main thread has to begin handling Ctrl-C or SIGTERM before the process ends
without it [s]; the interpreter takes microseconds when it is not inside a compiled kernel."""

_WATCHED = {int(signal.SIGINT): "interrupted", int(signal.SIGTERM): "terminated"}
_WATCHING: list[int] = []
"""The write end of the pipe while a watchdog runs (empty otherwise)."""


def _forget_in_child() -> None:
    """A forked child (without exec) must not write its signals into its parent's pipe: the
    parent's watchdog would take a worker's SIGTERM for its own. (The package's workers are
    spawned, and LAMMPS runs through exec with its descriptors closed; this guards the rest.)"""
    if _WATCHING:
        with contextlib.suppress(ValueError, OSError):
            signal.set_wakeup_fd(-1)


os.register_at_fork(after_in_child=_forget_in_child)


@contextlib.contextmanager
def ending_inside_kernels(
    on_sigterm: Callable[[int, Any], None], grace: float = GRACE
) -> Iterator[None]:
    """Install ``on_sigterm`` for SIGTERM (and a SIGINT handler that raises
    KeyboardInterrupt as Python's does) and watch that the main thread gets to run them.

    Parameters
    ----------
    on_sigterm : callable
        The Python handler of SIGTERM (it raises, so that the command cleans up).
    grace : float
        Seconds before a process whose main thread is inside compiled code ends anyway [s].

    Only in the main thread (where Python runs signal handlers); elsewhere it does nothing.
    The previous handlers and wakeup descriptor come back on exit.
    """
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    handled = threading.Event()
    stop = threading.Event()

    def term(signum: int, frame: Any) -> None:
        handled.set()
        on_sigterm(signum, frame)

    def interrupt(signum: int, frame: Any) -> None:
        handled.set()
        raise KeyboardInterrupt

    read_end, write_end = os.pipe()
    os.set_blocking(write_end, False)
    # a command started with Ctrl-C ignored (a background job of a script) keeps ignoring it
    ignored = signal.getsignal(signal.SIGINT) == signal.SIG_IGN
    previous_int = signal.signal(signal.SIGINT, signal.SIG_IGN if ignored else interrupt)
    previous_term = signal.signal(signal.SIGTERM, term)
    previous_fd = signal.set_wakeup_fd(write_end, warn_on_full_buffer=False)
    _WATCHING.append(write_end)

    def watch() -> None:
        while True:
            try:
                byte = os.read(read_end, 1)
            except OSError:
                return
            if stop.is_set() or not byte:
                return
            kind = _WATCHED.get(byte[0])
            if kind is None or handled.wait(grace) or stop.is_set():
                continue
            remove_own_temporaries()
            print(
                f"\ncosserat: {kind}; the process ends inside a compiled computation that did "
                f"not return within {grace:g} s (no output of it written)",
                file=sys.stderr,
                flush=True,
            )
            os._exit(128 + (signal.SIGINT if kind == "interrupted" else signal.SIGTERM))

    thread = threading.Thread(target=watch, name="cosserat-signal-watchdog", daemon=True)
    thread.start()
    try:
        yield
    finally:
        stop.set()
        _WATCHING.remove(write_end)
        signal.set_wakeup_fd(previous_fd)
        signal.signal(signal.SIGINT, previous_int)
        signal.signal(signal.SIGTERM, previous_term)
        with contextlib.suppress(OSError):
            os.write(write_end, b"\0")  # wakes the thread, which sees stop and returns
        thread.join(timeout=1.0)
        for fd in (read_end, write_end):
            with contextlib.suppress(OSError):
                os.close(fd)
