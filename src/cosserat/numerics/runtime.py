"""Running the compiled kernels: warming numba's cache, and process pools that are safe with it.

numba compiles the kernels on first use and keeps the machine code in its cache (``__pycache__``
beside the sources, or ``NUMBA_CACHE_DIR``; ``docs/numerics.md``), so only the first run on a
machine pays the compilation. Two things follow for parallel work:

* compile once, in the parent, before starting workers (:func:`warm_up`), or every worker
  compiles the same code at the same time;
* start workers with ``spawn``, not ``fork`` (a forked child of a process that has run
  compiled code with threads is not safe), and let each worker run its batches on one thread,
  so that processes and threads do not oversubscribe the cores.

The kernels release the GIL, so batches also run in parallel on threads (:func:`map_batches`).

Workers never outlive their parent, whatever ends it (:func:`process_pool`):

* each worker watches its parent: on Linux the kernel sends it SIGTERM when the parent ends
  (``prctl(PR_SET_PDEATHSIG)``), and on every system a thread waits on the parent's sentinel
  (a pipe that reaches end-of-file when the parent is gone, even after SIGKILL) and ends the
  worker at once; either way the worker first deletes the temporary files it was writing;
* workers ignore SIGINT: Ctrl-C reaches the whole process group, and the parent, which gets it
  too, stops the pool (:func:`stop_pool`, :func:`worker_processes`) instead of every worker
  printing its own traceback. A worker is started with SIGINT blocked (the mask is inherited
  through fork and exec), so a Ctrl-C that arrives while it is still importing, before its
  initializer can ignore SIGINT, does not print a traceback from inside its start-up either;
* an interrupted parent (Ctrl-C, SIGTERM, any exception) cancels what has not started and
  terminates the workers (:func:`worker_processes`), rather than waiting for their running
  tasks to finish as ``ProcessPoolExecutor.shutdown`` would.
"""

from __future__ import annotations

import contextlib
import ctypes
import multiprocessing
import multiprocessing.context
import os
import signal
import sys
import threading
import time
from collections.abc import Iterator
from concurrent.futures import ProcessPoolExecutor, ThreadPoolExecutor
from multiprocessing.connection import wait

import numpy as np

# fewer cases than this per thread are not worth a thread
MIN_CASES_PER_THREAD = 8


def warm_up() -> None:
    """Load (or, on a machine's first run, compile) every kernel entry point."""
    from . import cosserat as kernel

    p = np.zeros(kernel.N_PARAMS)
    p[kernel.P_A], p[kernel.P_SIN_PHI], p[kernel.P_EPS] = 1.0 / 3.0, 0.477, 0.1
    p[kernel.P_ALPHA] = 10.0 / np.sqrt(8.0 / 3.0)
    p[kernel.P_SIGMA_YX], p[kernel.P_M_START] = -0.36, 0.2
    p[kernel.P_GEOMETRY], p[kernel.P_CASE] = kernel.PLANE, kernel.UPPER
    kernel.solve_case(p, 1e-6, 1e-8, 0.05, 100)
    kernel.solve_batch(p[None, :], 1e-6, 1e-8, 0.05, 100)
    from .mui import plane_pieces  # mu(I)'s plane quadrature (validate's fits)

    plane_pieces(np.zeros(1), np.ones(1), 1.0, 0.64, 0.38, 0.28, 0.1, 1e-8, 400)


class _SpawnWithoutInterrupt(multiprocessing.context.SpawnProcess):
    """A spawned process that starts with SIGINT blocked (module docstring); the starting
    thread's own mask is restored at once, so the parent loses no Ctrl-C."""

    def start(self) -> None:
        if not hasattr(signal, "pthread_sigmask"):
            super().start()
            return
        previous = signal.pthread_sigmask(signal.SIG_BLOCK, {signal.SIGINT})
        try:
            super().start()
        finally:
            signal.pthread_sigmask(signal.SIG_SETMASK, previous)


class _SpawnContext(multiprocessing.context.SpawnContext):
    Process = _SpawnWithoutInterrupt


def process_pool(workers: int | None) -> ProcessPoolExecutor:
    """A pool of ``workers`` spawned processes (their batches run on one thread each) that end
    when this process ends, whatever the signal (module docstring). Use it through
    :func:`worker_processes`, which also stops it at once on an interruption."""
    warm_up()
    return ProcessPoolExecutor(
        max_workers=workers,
        mp_context=_SpawnContext(),
        initializer=_worker_start,
        initargs=(os.getpid(),),
    )


STOP_GRACE = 2.0
"""Seconds :func:`stop_pool` gives terminated workers to end before it kills them (a worker
inside a compiled kernel handles SIGTERM only when the kernel returns)."""


def stop_pool(pool: ProcessPoolExecutor, grace: float = STOP_GRACE) -> None:
    """End ``pool`` now: cancel the tasks not started, terminate the workers (SIGTERM: each
    deletes its temporary files and exits), and kill those still running after ``grace``
    seconds."""
    processes = list((getattr(pool, "_processes", None) or {}).values())  # CPython's record
    pool.shutdown(wait=False, cancel_futures=True)
    for process in processes:
        with contextlib.suppress(OSError, ValueError):
            process.terminate()
    deadline = time.monotonic() + grace
    for process in processes:
        with contextlib.suppress(OSError, ValueError, AssertionError):
            process.join(max(0.0, deadline - time.monotonic()))
            if process.is_alive():
                process.kill()
                process.join(1.0)


@contextlib.contextmanager
def worker_processes(workers: int | None) -> Iterator[ProcessPoolExecutor]:
    """:func:`process_pool` as a context: shut down normally after the block, stopped at once
    (:func:`stop_pool`) when the block ends by an exception, Ctrl-C or SIGTERM included."""
    pool = process_pool(workers)
    try:
        yield pool
    except BaseException:
        stop_pool(pool)
        raise
    pool.shutdown()


_THREADS = [0]  # 0: as many as cores; set to 1 inside process-pool workers

PR_SET_PDEATHSIG = 1
"""Linux ``prctl`` option: the signal this process gets when its parent ends."""

PARENT_POLL = 0.5
"""Seconds between a worker's checks that its parent still runs (beside the sentinel)."""


def _worker_start(parent: int) -> None:
    """Initializer of a pool worker: one thread for batches, SIGINT left to the parent, and
    an end with the parent (:func:`_end_with_parent`)."""
    _THREADS[0] = 1
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    signal.signal(signal.SIGTERM, _end_now)
    _end_with_parent(parent)


def _end_with_parent(parent: int) -> None:
    """End this process when the process ``parent`` ends: SIGTERM from the kernel on Linux,
    and a thread that waits for the parent's sentinel (or polls the parent's id) elsewhere
    and as a second line."""
    if sys.platform.startswith("linux"):
        with contextlib.suppress(OSError, AttributeError):
            libc = ctypes.CDLL(None, use_errno=True)
            libc.prctl(PR_SET_PDEATHSIG, int(signal.SIGTERM), 0, 0, 0)
    process = multiprocessing.parent_process()
    sentinel = None if process is None else process.sentinel
    watcher = threading.Thread(
        target=_watch_parent, args=(parent, sentinel), name="cosserat-parent-watch", daemon=True
    )
    watcher.start()
    if os.getppid() != parent:  # the parent ended before the watch began
        _end_now()


def _watch_parent(parent: int, sentinel: int | None) -> None:
    while True:
        if sentinel is not None:
            with contextlib.suppress(OSError, ValueError):
                if wait([sentinel], timeout=PARENT_POLL):
                    break
        else:
            time.sleep(PARENT_POLL)
        if os.getppid() != parent:
            break
    _end_now()


def _end_now(signum: int = signal.SIGTERM, frame: object = None) -> None:
    """Delete this worker's temporary files and end it at once (no cleanup can hang)."""
    from .._atomic import remove_own_temporaries

    remove_own_temporaries()
    os._exit(128 + int(signum))


def map_batches(
    params: np.ndarray, rtol: float, atol: float, f: float, max_steps: int, threads: int = 0
) -> tuple[np.ndarray, np.ndarray]:
    """``solve_batch`` over the rows of ``params``, split over threads (the kernel releases the
    GIL). ``threads`` 0: the process default (the cores, or 1 in a pool worker)."""
    from . import cosserat as kernel

    n = params.shape[0]
    workers = threads or _THREADS[0] or os.cpu_count() or 1
    workers = max(1, min(workers, n // MIN_CASES_PER_THREAD))
    if workers == 1:
        return kernel.solve_batch(params, rtol, atol, f, max_steps)
    chunks = np.array_split(np.arange(n), workers)
    with ThreadPoolExecutor(max_workers=workers) as pool:
        parts = list(
            pool.map(lambda idx: kernel.solve_batch(params[idx], rtol, atol, f, max_steps), chunks)
        )
    return np.concatenate([s for s, _ in parts]), np.concatenate([i for _, i in parts])
