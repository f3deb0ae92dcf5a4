"""Where the default ``solve(p)`` of the Cosserat model spends its time, step by step.

    python benchmarks/solve_path_lines.py [P1|P2|P3|C] [--eps 0.04] [--calls 3000]

The numerical route's steps (``cosserat.routes.numerical.solve_plane`` / ``solve_couette``),
written out here with ``time.perf_counter_ns`` between them: the median and the 10th percentile
of each step over many calls (the garbage collector off), then ``solve(p)`` itself for
comparison. Not a test: the machine is shared and the numbers move with its load. If the route
changes, change the copy below with it (it reads the route's private helpers on purpose).
``docs/performance.md`` quotes its output.
"""

from __future__ import annotations

import argparse
import gc
import sys
import time
from pathlib import Path
from typing import Any

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

from run import BASE  # noqa: E402

from cosserat import config, solve  # noqa: E402
from cosserat.numerics import cosserat as kernel  # noqa: E402
from cosserat.results.profile import Profile, pending  # noqa: E402
from cosserat.routes import PICKLABLE, _options, find  # noqa: E402
from cosserat.routes import numerical as route  # noqa: E402

STEPS = [
    "solve(): the route's look-up",
    "tolerances, the problem's inputs, the vector's copy",
    "the kernel",
    "the solution object, the grid's copy",
    "the fields and the screen (fields_checked)",
    "the Profile (pending)",
    "freeing it all",
]


def one_call(problem: Any) -> np.ndarray:
    """The route's steps for the default call, timed [ns]."""
    clock = time.perf_counter_ns
    t = [clock()]
    found = find(problem.model, problem.cell_name, "numerical")
    _options(found)
    t.append(clock())
    rtol, atol = route.tolerances(route.DEFAULT_RTOL, None)
    inputs = route._inputs(problem)
    p = inputs.params.copy()
    t.append(clock())
    entry = kernel.solve_couette_case if inputs.couette else kernel.solve_plane_case
    status, info, couple, spin, geometry = entry(p, rtol, atol, config.DEFAULT_F, config.MAX_STEPS)
    t.append(clock())
    sol = object.__new__(route.NumericalSolution)
    sol.__dict__.update(
        problem=problem, params=p, info=info, couple=couple, spin=spin, geometry=geometry,
        info_f=config.DEFAULT_F,
    )  # fmt: skip
    grid = inputs.output_grid(None, None)
    t.append(clock())
    out, first, finite = kernel.fields_checked(
        grid, p, info, *couple, geometry, *spin, route.SCREEN_SLACK
    )
    t.append(clock())
    profile = pending(
        Profile,
        {
            "problem": problem,
            "xi": grid,
            "slip_wall": inputs.slip_wall,
            "reference_velocity": float(info[kernel.I_U_REF]),
            "evaluator": sol,
            "velocity": sol.velocity,
            "recipe": None,
        },
        route._LEFT,
        route._rest,
        inputs,
        sol,
        out,
        rtol,
        atol,
        True,
    )
    _ = found not in PICKLABLE
    t.append(clock())
    del profile, sol, couple, spin, info, geometry, p, grid, out
    t.append(clock())
    assert status == kernel.OK and first < 0 and finite
    return np.diff(np.array(t))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("case", nargs="?", default="P2", choices=list(BASE))
    parser.add_argument("--eps", type=float, default=0.04)
    parser.add_argument("--calls", type=int, default=3000)
    args = parser.parse_args()
    problem = BASE[args.case].with_values({"eps": args.eps})
    solve(problem)
    warm = args.calls // 6
    gc.disable()
    rows = np.array([one_call(problem) for _ in range(args.calls)])[warm:] / 1e3
    whole = []
    for _ in range(args.calls):
        start = time.perf_counter_ns()
        solve(problem)
        whole.append(time.perf_counter_ns() - start)
    gc.enable()
    n = args.calls - warm
    print(f"{args.case} at eps {args.eps:g}, {n} calls [us]: median, 10th percentile")
    for name, column in zip(STEPS, rows.T, strict=True):
        print(f"  {name:55s} {np.median(column):7.2f} {np.percentile(column, 10):7.2f}")
    total = rows.sum(axis=1)
    print(f"  {'the steps together':55s} {np.median(total):7.2f} {np.percentile(total, 10):7.2f}")
    w = np.array(whole[warm:]) / 1e3
    print(f"  {'solve(p) itself':55s} {np.median(w):7.2f} {np.percentile(w, 10):7.2f}")


if __name__ == "__main__":
    main()
