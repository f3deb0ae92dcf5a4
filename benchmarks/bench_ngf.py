"""The NGF solve beside the Cosserat solve and beside a plain ``solve_bvp``:
``python benchmarks/bench_ngf.py [--rounds 5]``.

Not a test: timings on a shared machine move by up to 2x, so what means something is a ratio
measured in one run, the sides timed in turns (best of ``--rounds``, timeit's convention).

Problems (glass beads, the defaults of :class:`cosserat.model.ngf.NGF`; I_w = 0.01):

* C: Couette flow, eps = 0.01, Ri = 1 (creep beyond xi ~ 0.16);
* P: plane shear under gravity, eps = 0.01, B = 1 (creep below xi ~ 0.78);
* V: the vertical channel, eps = 0.02, driven by the centre-line I_w (a creeping core).

For each:

1. ``solve(problem)`` (the package's route: finite volumes on n and n/2 cells, Brent on the
   stress level, Richardson's extrapolation, the diagnostics) and ``solve(problem, check=False,
   points=3)`` (the solve alone);
2. a plain ``scipy.integrate.solve_bvp`` of the same problem written here as a user would:
   four first-order equations (F, r F', the wall-speed integral, the velocity integral), the
   stress level a free parameter, a uniform mesh of 101 points, a crude start (F = F_loc at
   1.2 mu_s), SciPy's default tol = 1e-3 and also tol = 1e-6;
3. the package at matched accuracy: the cheapest of ``resolution`` = 2, 4, ..., 64 (cells per
   cooperativity length) whose error is at most the baseline's;
4. the Cosserat model on the same cell (``make_problem`` with the paper's defaults at the same
   eps, Ri, B; check=False, points=3): what a model's solve costs beside it.

Errors: max |u - u_ref| on 401 points, u_ref the package at 2^16 cells (extrapolated).
"""

from __future__ import annotations

import argparse
import time
from collections.abc import Callable

import numpy as np
from scipy.integrate import solve_bvp

from cosserat import NGF, Couette, Plane, Problem, VerticalChannel, solve
from cosserat.model import make_problem

XS = np.linspace(0.0, 1.0, 401)


def plain_bvp(problem, tol: float) -> Callable[[np.ndarray], np.ndarray]:  # type: ignore[no-untyped-def]
    """u(xi) of an NGF problem by solve_bvp, as a user would write it (see the module text)."""
    law, cell = problem.rheology, problem.cell
    mu_s, b, a = law.mu_s, law.b, law.A * problem.eps
    name = {"plane": "NGFPlaneShear", "couette": "NGFCouetteFlow", "channel": "NGFChannel"}[
        problem.cell_name
    ]
    Ri = getattr(cell, "Ri", None)
    I_w = problem.equations.I_w

    def statics(x, T):  # type: ignore[no-untyped-def]
        one = np.ones_like(x)
        if name == "NGFPlaneShear":
            s = 1.0 + cell.B * cell.nu * (1.0 - x)
            return T / s, s, one
        if name == "NGFCouetteFlow":
            r = Ri + x
            return T * (Ri / r) ** 2, one, r
        return 2.0 * T * np.abs(x - 0.5), one, one

    def f_loc(mu, s):  # type: ignore[no-untyped-def]
        return np.sqrt(s) * np.maximum(mu - mu_s, 0.0) / (b * np.where(mu > 0, mu, 1.0))

    weight = (lambda x: Ri / (Ri + x)) if name == "NGFCouetteFlow" else (lambda x: np.ones_like(x))
    sign = (lambda x: np.where(x > 0.5, -1.0, 1.0)) if name == "NGFChannel" else np.ones_like
    target = I_w * (2.0 if name == "NGFChannel" else 1.0)

    def rhs(x, y, p):  # type: ignore[no-untyped-def]
        mu, s, r = statics(x, p[0])
        k = np.abs(mu - mu_s) / a**2
        return np.vstack(
            [
                y[1] / r,
                r * k * (y[0] - f_loc(mu, s)),
                weight(x) * y[0] * mu,
                sign(x) * y[0] * mu / r,
            ]
        )

    def bc(ya, yb, p):  # type: ignore[no-untyped-def]
        return np.array([ya[1], yb[1], ya[2], yb[2] - target, ya[3]])

    x = np.linspace(0.0, 1.0, 101)
    T0 = 1.2 * mu_s
    y = np.zeros((4, x.size))
    y[0] = f_loc(*statics(x, T0)[:2])
    sol = solve_bvp(rhs, bc, x, y, p=[T0], tol=tol)
    if sol.status != 0:
        raise RuntimeError(f"solve_bvp failed: {sol.message}")

    def velocity(xx: np.ndarray) -> np.ndarray:
        yy = sol.sol(xx)
        if name == "NGFCouetteFlow":
            return -(Ri + xx) * (sol.sol(1.0)[3] - yy[3]) / I_w
        if name == "NGFChannel":
            return yy[3] / sol.sol(0.5)[3]
        return yy[3] / I_w

    return velocity


def best(fn: Callable[[], object], rounds: int) -> float:
    times = []
    for _ in range(rounds):
        t = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t)
    return min(times)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rounds", type=int, default=5)
    args = parser.parse_args()
    cases = {
        "C": (
            Problem(Couette(eps=0.01, Ri=1.0), NGF()),
            make_problem("cosserat", "couette", {"eps": 0.01, "Ri": 1.0}),
        ),
        "P": (
            Problem(Plane(eps=0.01, B=1.0), NGF()),
            make_problem("cosserat", "plane", {"eps": 0.01, "B": 1.0}),
        ),
        "V": (
            Problem(VerticalChannel(eps=0.02, I_w=0.01), NGF()),
            make_problem("cosserat", "channel", {"eps": 0.02}),
        ),
    }
    for problem, cosserat in cases.values():  # compile and load everything once
        solve(problem)
        if cosserat is not None:
            solve(cosserat, check=False, points=3)
    print(f"NGF solve cost (best of {args.rounds}; errors: max |u - u_ref| on 401 points)\n")
    header = f"{'':3} {'what':44} {'time [ms]':>10} {'error':>9} {'ratio':>8}"
    print(header)
    print("-" * len(header))
    for key, (problem, cosserat) in cases.items():
        ref = solve(problem, xi=XS, cells=2**16, check=False).u
        rows: list[tuple[str, float, float | None]] = []
        t_full = best(lambda p=problem: solve(p), args.rounds)
        t_core = best(lambda p=problem: solve(p, check=False, points=3), args.rounds)
        err = float(np.max(np.abs(solve(problem, xi=XS).u - ref)))
        rows.append(("ngf solve(problem) [default]", t_full, err))
        rows.append(("ngf solve(problem, check=False, points=3)", t_core, err))
        ours: dict[float, tuple[float, float]] = {}
        for res in (2.0, 4.0, 8.0, 16.0, 32.0, 64.0):
            e = float(np.max(np.abs(solve(problem, xi=XS, resolution=res).u - ref)))
            t = best(
                lambda p=problem, r=res: solve(p, check=False, points=3, resolution=r), args.rounds
            )
            ours[res] = (t, e)
        for tol in (1e-3, 1e-6):
            t_bvp = best(lambda p=problem, tl=tol: plain_bvp(p, tl), max(1, args.rounds // 2))
            e_bvp = float(np.max(np.abs(plain_bvp(problem, tol)(XS) - ref)))
            rows.append((f"plain solve_bvp, tol = {tol:g}", t_bvp, e_bvp))
            matched = [(t, e, r) for r, (t, e) in ours.items() if e <= e_bvp]
            if matched:
                t_m, e_m, r_m = min(matched)
                rows.append((f"  ngf at matched accuracy (resolution {r_m:g})", t_m, e_m))
                rows.append((f"  ratio solve_bvp / ngf matched (tol {tol:g})", t_bvp / t_m, None))
            rows.append((f"  ratio solve_bvp / ngf default (tol {tol:g})", t_bvp / t_core, None))
        if cosserat is not None:
            t_cos = best(lambda c=cosserat: solve(c, check=False, points=3), args.rounds)
            rows.append(("cosserat solve(check=False, points=3), same cell", t_cos, None))
            rows.append(("  ratio ngf / cosserat", t_core / t_cos, None))
        for what, t, e in rows:
            if what.strip().startswith("ratio"):
                print(f"{key:3} {what:44} {'':>10} {'':>9} {t:8.1f}")
            else:
                es = "" if e is None else f"{e:9.1e}"
                print(f"{key:3} {what:44} {t * 1e3:10.2f} {es:>9}")
        print()


if __name__ == "__main__":
    main()
