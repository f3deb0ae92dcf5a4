"""Sweep scaling: one 10^4-case sweep on 1 and 2 local processes and on a 2-worker Dask
LocalCluster, timed side by side: ``python benchmarks/sweep_scaling.py [n_cases]``.

The cases: plane shear over a grid of wall friction, K, gravity and eps (10 x 10 x 4 x 25).
Checks that the three runs give the same table.
"""

from __future__ import annotations

import sys
import time

from cosserat.studies.sweep import parse_spec, run_sweep


def spec(n_eps: int = 25):  # type: ignore[no-untyped-def]
    return parse_spec(
        {
            "geometry": "plane",
            "chunk": 100,
            "fixed": {"phi": 28.5},
            "grid": {
                "delta": {"linspace": [8.0, 25.0, 10]},
                "K": {"linspace": [0.0, 1.0, 10]},
                "B": [0.0, 0.1, 0.5, 1.0],
                "eps": {"geomspace": [0.05, 1e-6, n_eps]},
            },
        }
    )


def main() -> None:
    n_eps = int(sys.argv[1]) // 400 if len(sys.argv) > 1 else 25
    s = spec(n_eps)
    print(f"{len(s.cases)} cases (plane shear), chunks of {s.chunk}")
    rows = {}
    for label, kwargs in (
        ("1 local process", {"workers": 1}),
        ("2 local processes", {"workers": 2}),
    ):
        t = time.perf_counter()
        rows[label] = run_sweep(s, **kwargs)
        print(f"  {label:28s} {time.perf_counter() - t:7.1f} s")
    from distributed import LocalCluster

    with LocalCluster(
        n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None
    ) as cluster:
        t = time.perf_counter()
        rows["dask"] = run_sweep(s, scheduler=cluster.scheduler_address)
        print(f"  {'Dask LocalCluster, 2 workers':28s} {time.perf_counter() - t:7.1f} s")
    first = rows["1 local process"]
    print("same rows in all three runs:", all(r == first for r in rows.values()))
    status = [r["status"] for r in first]
    print({k: status.count(k) for k in set(status)})


if __name__ == "__main__":
    main()
