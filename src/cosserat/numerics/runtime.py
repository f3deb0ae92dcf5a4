"""Running the compiled kernels: warming numba's cache, and process pools that are safe with it.

numba compiles the kernels on first use and keeps the machine code in its cache (``__pycache__``
beside the sources, or ``NUMBA_CACHE_DIR``; ``docs/numerics.md``), so only the first run on a
machine pays the compilation. Two things follow for parallel work:

* compile once, in the parent, before starting workers (:func:`warm_up`), or every worker
  compiles the same code at the same time;
* start workers with ``spawn``, not ``fork``: numba's parallel threads (OpenMP) do not survive a
  ``fork``, and each worker runs the kernels on one thread, so that processes and threads do
  not oversubscribe the cores.
"""

from __future__ import annotations

import multiprocessing
from concurrent.futures import ProcessPoolExecutor

import numpy as np


def warm_up() -> None:
    """Load (or, on a machine's first run, compile) every kernel entry point."""
    from . import cosserat as kernel

    p = np.zeros(kernel.N_PARAMS)
    p[kernel.P_A], p[kernel.P_SIN_PHI], p[kernel.P_EPS] = 1.0 / 3.0, 0.477, 0.1
    p[kernel.P_ALPHA] = 10.0 / np.sqrt(8.0 / 3.0)
    p[kernel.P_SIGMA_YX], p[kernel.P_M_START] = -0.36, 0.2
    p[kernel.P_GEOMETRY], p[kernel.P_CASE] = kernel.PLANE, kernel.UPPER
    kernel.solve_one(p, 1e-6, 1e-8, 0.05, 100)
    kernel.solve_batch(p[None, :], 1e-6, 1e-8, 0.05, 100)


def _single_threaded() -> None:
    import numba

    numba.set_num_threads(1)


def process_pool(workers: int | None) -> ProcessPoolExecutor:
    """A pool of ``workers`` spawned processes, each running the kernels on one thread."""
    warm_up()
    return ProcessPoolExecutor(
        max_workers=workers,
        mp_context=multiprocessing.get_context("spawn"),
        initializer=_single_threaded,
    )
