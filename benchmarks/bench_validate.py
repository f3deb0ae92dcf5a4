"""``cosserat validate`` on the shipped corpus: wall time with one process and with two, side by
side in one run (issue 18, item 8: under 60 s on two cores).

Run: ``python benchmarks/bench_validate.py [--repeat N]``. The kernels are compiled (or loaded
from numba's cache) by a first call that is not timed; each timed call writes its report into a
fresh temporary folder. Prints one JSON object: the wall seconds and the CPU seconds (this
process and its workers) of every call, and the machine's load.
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
    args = parser.parse_args()

    from cosserat.studies.validate import validate

    with tempfile.TemporaryDirectory() as tmp:
        validate(None, Path(tmp) / "warm")  # compile or load the kernels, not timed
        seconds: dict[str, list[float]] = {"workers=1": [], "workers=2": []}
        cpu: dict[str, list[float]] = {"workers=1": [], "workers=2": []}
        for k in range(args.repeat):
            for workers in (1, 2):  # interleaved: both settings see the same machine
                before = _cpu()
                start = time.perf_counter()
                validate(None, Path(tmp) / f"w{workers}_{k}", workers=workers)
                seconds[f"workers={workers}"].append(round(time.perf_counter() - start, 2))
                cpu[f"workers={workers}"].append(round(_cpu() - before, 2))
    print(
        json.dumps(
            {"seconds": seconds, "cpu_seconds": cpu, "load_average": os.getloadavg()}, indent=1
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
