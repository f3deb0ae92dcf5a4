"""``cosserat validate`` on the shipped corpus: wall time with one process and with two, side by
side in one run (issue 18, item 8: under 60 s on two cores).

Run: ``python benchmarks/bench_validate.py [--repeat N] [--corpus DIR] [--workers 1,2]``
(``--corpus``: another corpus folder, e.g. the five quasi-static v2 runs; default the shipped
one, what ``.ci/run``'s release check validates). The kernels are compiled (or loaded from
numba's cache) by a first call that is not timed; each timed call writes its report into a
fresh temporary folder. Prints one JSON object: the wall seconds and the CPU seconds (this
process and its workers) of every call, and the machine's load before and after.
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import tempfile
import time
from pathlib import Path


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=2, help="timed calls per setting")
    parser.add_argument("--corpus", default=None, help="corpus folder (default: the shipped one)")
    parser.add_argument("--workers", default="1,2", help="worker counts to time, comma-separated")
    args = parser.parse_args()
    settings = [int(w) for w in args.workers.split(",") if w.strip()]

    from cosserat.studies.validate import validate

    load_before = os.getloadavg()
    with tempfile.TemporaryDirectory() as tmp:
        validate(args.corpus, Path(tmp) / "warm", workers=1)  # compile or load, not timed
        seconds: dict[str, list[float]] = {f"workers={w}": [] for w in settings}
        cpu: dict[str, list[float]] = {f"workers={w}": [] for w in settings}
        for k in range(args.repeat):
            for workers in settings:  # interleaved: every setting sees the same machine
                before = _cpu()
                start = time.perf_counter()
                validate(args.corpus, Path(tmp) / f"w{workers}_{k}", workers=workers)
                seconds[f"workers={workers}"].append(round(time.perf_counter() - start, 2))
                cpu[f"workers={workers}"].append(round(_cpu() - before, 2))
    print(
        json.dumps(
            {
                "corpus": args.corpus or "shipped",
                "seconds": seconds,
                "cpu_seconds": cpu,
                "load_average_before": load_before,
                "load_average_after": os.getloadavg(),
            },
            indent=1,
        )
    )


def _cpu() -> float:
    """CPU seconds of this process and its ended children (the pool's workers) [s]: on a
    busy machine the wall time overstates what validate costs, this does not."""
    own = resource.getrusage(resource.RUSAGE_SELF)
    kids = resource.getrusage(resource.RUSAGE_CHILDREN)
    return own.ru_utime + own.ru_stime + kids.ru_utime + kids.ru_stime


if __name__ == "__main__":
    main()
