"""The vertical channel's solve time beside plane shear, and beside a solve_bvp of the same
equations.

    python benchmarks/bench_channel.py [--rounds 7]

Not a test (the machine is shared): each line is the minimum over rounds of the calls timed in
turns. Problems: phi = 28.5 deg, L = 10, A = 1/3, K = 0.5; channel walls delta = 20 deg (B nu =
2 tan delta, friction mobilised) and fully rough; plane shear P1 (identical walls, B = 0) and
P3 (gravity, B = 1). Calls: ``solve(problem, check=False, points=3)`` (the wall quantities),
and ``solve(problem)`` (201 points, residuals and boundary checks). The solve_bvp line runs the
channel's physical equations as ``tests/test_channel.py`` writes them (log-graded mesh, a good
start, tol = 1e-8) against the kernel at rtol = 1e-10, which agrees with it to ~1e-10.
"""

from __future__ import annotations

import argparse
import sys
import time
from collections.abc import Callable
from pathlib import Path

from cosserat import (
    Cosserat,
    Material,
    Plane,
    Problem,
    VerticalChannel,
    Wall,
    solve,
)

ROOT = Path(__file__).resolve().parents[1]


def best(fn: Callable[[], object], rounds: int, inner: int = 5) -> float:
    """Minimum over rounds of the mean time of ``inner`` calls [s]."""
    times = []
    for _ in range(rounds):
        t0 = time.perf_counter()
        for _ in range(inner):
            fn()
        times.append((time.perf_counter() - t0) / inner)
    return min(times)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rounds", type=int, default=7)
    args = parser.parse_args()
    mat = Material()
    problems = {}
    for eps in (1e-2, 1e-4, 1e-6):
        problems[f"channel delta=20 eps={eps:g}"] = Problem(
            VerticalChannel(eps=eps), Cosserat(material=mat, wall=Wall())
        )
        problems[f"channel rough    eps={eps:g}"] = Problem(
            VerticalChannel(eps=eps), Cosserat(material=mat, wall=Wall.fully_rough())
        )
        problems[f"plane P1         eps={eps:g}"] = Problem(
            Plane(eps=eps), Cosserat(material=mat, wall=Wall())
        )
        problems[f"plane P3 (B=1)   eps={eps:g}"] = Problem(
            Plane(eps=eps, B=1.0), Cosserat(material=mat, wall=Wall())
        )
    for p in problems.values():  # compile and warm
        solve(p, check=False, points=3)
    print(f"{'problem':32s} {'wall quantities':>16s} {'full profile':>14s}")
    for name, p in problems.items():
        quick = best(lambda p=p: solve(p, check=False, points=3), args.rounds)
        full = best(lambda p=p: solve(p), args.rounds, inner=1)
        print(f"{name:32s} {quick * 1e3:13.3f} ms {full * 1e3:11.2f} ms")

    sys.path.insert(0, str(ROOT / "tests"))
    from test_channel import CASES, bvp_profile  # the physical equations, written separately

    print()
    for name, p in CASES.items():
        t_bvp = best(lambda p=p: bvp_profile(p), max(2, args.rounds // 3), inner=1)
        t_ker = best(lambda p=p: solve(p, rtol=1e-10, check=False, points=3), args.rounds)
        print(
            f"channel {name:12s} eps=0.05: solve_bvp {t_bvp * 1e3:8.1f} ms, kernel (rtol 1e-10) "
            f"{t_ker * 1e3:6.3f} ms: {t_bvp / t_ker:7.0f}x"
        )


if __name__ == "__main__":
    main()
