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
"""

from __future__ import annotations

import multiprocessing
import os
from concurrent.futures import ProcessPoolExecutor, ThreadPoolExecutor

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


def process_pool(workers: int | None) -> ProcessPoolExecutor:
    """A pool of ``workers`` spawned processes (their batches run on one thread each)."""
    warm_up()
    return ProcessPoolExecutor(
        max_workers=workers,
        mp_context=multiprocessing.get_context("spawn"),
        initializer=_single_threaded,
    )


_THREADS = [0]  # 0: as many as cores; set to 1 inside process-pool workers


def _single_threaded() -> None:
    _THREADS[0] = 1


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
        return kernel.solve_batch(params, rtol, atol, f, max_steps)  # type: ignore[no-any-return]
    chunks = np.array_split(np.arange(n), workers)
    with ThreadPoolExecutor(max_workers=workers) as pool:
        parts = list(
            pool.map(lambda idx: kernel.solve_batch(params[idx], rtol, atol, f, max_steps), chunks)
        )
    return np.concatenate([s for s, _ in parts]), np.concatenate([i for _, i in parts])
