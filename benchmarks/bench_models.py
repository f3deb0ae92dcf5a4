"""Each registered rheology's solve cost side by side on each cell:
``python benchmarks/bench_models.py [--repeat N] [--json FILE]``.

For every cell of every model in :data:`cosserat.routes.RHEOLOGIES` (so models and cells
registered later appear without an edit), the problem at the paper's eps with the model's
defaults (plane shear without and with gravity B = 1, the paper's Couette cell Ri = 1, the
vertical channel at its defaults), solved by each route the model has for it, ``check=False``
and the default output grid, after one warm-up call (numba's compilation and caches are not
timed). Prints the median time per solve over ``--repeat`` rounds and, for a fitting-sized
workload, the time of ``rank_models``' evaluation (a 3-point solve and the velocity at 40
points) that the fits repeat.
"""

from __future__ import annotations

import argparse
import json
import statistics
import time
from pathlib import Path

import numpy as np

from cosserat import config
from cosserat.analysis.ranking import model_solve, model_velocity
from cosserat.errors import CosseratError
from cosserat.model import make_problem
from cosserat.routes import RHEOLOGIES, cells_for, methods_for, solve

CASES = {
    "plane": {"eps": config.EPS},
    "plane, B = 1": {"eps": config.EPS, "B": 1.0},
    "couette": {"eps": config.EPS, "Ri": config.RI},
    "channel": {"eps": config.EPS},
}


def _cell(case: str) -> str:
    return case.split(",")[0]


def _problem(model: str, case: str):  # type: ignore[no-untyped-def]
    params = CASES[case]
    try:
        return make_problem(model, _cell(case), params)
    except CosseratError:
        return make_problem(model, _cell(case), {**params, "B": 1.0})  # the channel's weight


def _time(fn, repeat: int) -> float:  # type: ignore[no-untyped-def]
    fn()  # warm up
    rounds = []
    for _ in range(repeat):
        n, t0 = 0, time.perf_counter()
        while True:
            fn()
            n += 1
            elapsed = time.perf_counter() - t0
            if elapsed > 0.2 or n >= 200:
                break
        rounds.append(elapsed / n)
    return statistics.median(rounds)


def run(repeat: int) -> list[dict]:
    rows = []
    d = np.arange(0.5, 1.0 / config.EPS, 1.0)
    for case in CASES:
        for model in RHEOLOGIES:
            if _cell(case) not in cells_for(model):
                continue
            try:
                problem = _problem(model, case)
            except CosseratError as exc:
                rows.append({"case": case, "model": model, "error": str(exc)})
                continue
            for method in methods_for(model, _cell(case)):
                try:
                    t = _time(lambda p=problem, m=method: solve(p, method=m, check=False), repeat)
                except CosseratError as exc:
                    rows.append({"case": case, "model": model, "method": method,
                                 "error": " ".join(str(exc).split())[:80]})  # fmt: skip
                    continue
                rows.append({"case": case, "model": model, "method": method, "seconds": t})
            try:
                t_fit = _time(lambda p=problem: model_velocity(model_solve(p), d), repeat)
                rows.append({"case": case, "model": model, "method": "fit evaluation",
                             "seconds": t_fit})  # fmt: skip
            except CosseratError as exc:
                rows.append({"case": case, "model": model, "method": "fit evaluation",
                             "error": " ".join(str(exc).split())[:80]})  # fmt: skip
    return rows


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=5)
    parser.add_argument("--json", type=Path, default=None)
    args = parser.parse_args()
    rows = run(args.repeat)
    print(f"{'cell':<14}{'model':<10}{'method':<16}{'ms per solve':>14}")
    for r in rows:
        value = f"{1e3 * r['seconds']:>14.3f}" if "seconds" in r else f"  {r['error']}"
        print(f"{r['case']:<14}{r['model']:<10}{r.get('method', '-'):<16}{value}")
    if args.json:
        args.json.write_text(json.dumps(rows, indent=1) + "\n")


if __name__ == "__main__":
    main()
