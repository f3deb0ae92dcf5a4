"""Benchmarks, side by side in one run: ``python benchmarks/run.py [--quick]``.

Not tests: machines are shared and noisy, so only ratios measured in the same run mean
anything. Prints one table per question:

1. a profile at eps = 1e-3 against the closed-form evaluation (the physical floor);
2. the full plane-shear-under-gravity and Couette systems against a straightforward
   ``scipy.integrate.solve_bvp`` and against LSODA shooting as the paper did it
   (``benchmarks/baselines.py``, independent right-hand sides), with the error of every run
   against the package at rtol = 1e-12, and the speed ratio at equal accuracy;
3. a Delta(eps) curve of 50 values from 1e-1 to 1e-6 for the four problems, with the scalar
   solver (continuation in eps) and the batched engine.
"""

from __future__ import annotations

import argparse
import statistics
import sys
import time
from collections.abc import Callable
from dataclasses import replace
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).parent))

from baselines import (
    bvp_couette,
    bvp_plane_gravity,
    lsoda_shooting_couette,
    lsoda_shooting_plane_gravity,
)

from cosserat import CouetteFlow, Material, PlaneShear, Wall, solve
from cosserat.analysis import thickness_curve
from cosserat.routes.batch import wall_quantities

MAT = Material(28.5)


def median_time(fn: Callable[[], object], repeat: int) -> tuple[float, object]:
    times, out = [], None
    for _ in range(repeat):
        t = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - t)
    return statistics.median(times), out


def profile_error(fields: dict, ref) -> float:  # type: ignore[no-untyped-def]
    """max of |du|, |domega|/max|omega| and |dm| on the reference grid."""
    w = np.max(np.abs(ref.omega))
    return float(
        max(
            np.max(np.abs(fields["u"] - ref.u)),
            np.max(np.abs(fields["omega"] - ref.omega)) / w,
            np.max(np.abs(fields["m"] - ref.m)),
        )
    )


def table(rows: list[list[str]], header: list[str]) -> str:
    widths = [max(len(str(r[i])) for r in [header, *rows]) for i in range(len(header))]
    lines = [
        "| " + " | ".join(h.ljust(w) for h, w in zip(header, widths, strict=True)) + " |",
        "|" + "|".join("-" * (w + 2) for w in widths) + "|",
    ]
    lines += [
        "| " + " | ".join(str(c).ljust(w) for c, w in zip(r, widths, strict=True)) + " |"
        for r in rows
    ]
    return "\n".join(lines)


def closed_form_floor(repeat: int) -> None:
    print("\n## 1. One profile at eps = 1e-3 (201 points, no residual check)\n")
    rows = []
    for name, problem in {
        "plane, rougher lower wall": PlaneShear(
            material=MAT, upper=Wall(20.0), lower=Wall.fully_rough(), eps=1e-3
        ),
        "plane, identical walls": PlaneShear(material=MAT, upper=Wall(20.0), eps=1e-3),
    }.items():
        t_cf, cf = median_time(
            lambda p=problem: solve(p, method="closed-form", check=False), repeat
        )
        for rtol in (1e-6, 1e-8):
            t_num, num = median_time(
                lambda p=problem, r=rtol: solve(p, rtol=r, check=False), repeat
            )
            err = np.max(np.abs(num.u - cf.u))
            rows.append(
                [
                    name,
                    f"{rtol:g}",
                    f"{t_cf * 1e3:.2f}",
                    f"{t_num * 1e3:.2f}",
                    f"{t_num / t_cf:.1f}",
                    f"{err:.1e}",
                ]
            )
    print(
        table(rows, ["problem", "rtol", "closed form [ms]", "numerical [ms]", "ratio", "max |du|"])
    )


def baselines(eps_values: list[float], repeat: int) -> None:
    print("\n## 2. Full systems against solve_bvp and LSODA shooting\n")
    problems = {
        "plane, gravity B = 1": lambda e: PlaneShear(material=MAT, upper=Wall(20.0), eps=e, B=1.0),
        "Couette, Ri = 1": lambda e: CouetteFlow(material=MAT, wall=Wall(20.0), eps=e, Ri=1.0),
    }
    rows, ratios = [], []
    for name, make in problems.items():
        bvp, lsoda = (
            (bvp_plane_gravity, lsoda_shooting_plane_gravity)
            if "plane" in name
            else (bvp_couette, lsoda_shooting_couette)
        )
        for eps in eps_values:
            problem = make(eps)
            ref_prof = solve(problem, rtol=1e-12, points=2001, check=False)
            xi = ref_prof.xi
            ours = []
            for rtol in (1e-6, 1e-8, 1e-10):
                t, prof = median_time(
                    lambda r=rtol, p=problem, x=xi: solve(p, rtol=r, xi=x, check=False), repeat
                )
                err = profile_error(prof.evaluate(xi)._asdict(), ref_prof)
                ours.append((t, err))
                rows.append(
                    [
                        name,
                        f"{eps:g}",
                        "cosserat (numerical)",
                        f"{rtol:g}",
                        "yes",
                        f"{t * 1e3:.1f}",
                        f"{err:.1e}",
                    ]
                )
            methods = [("solve_bvp", bvp), ("LSODA shooting", lsoda)]
            if "plane" in name:
                methods.insert(
                    1,
                    (
                        "solve_bvp, naive guess",
                        lambda p, tl, xi: bvp_plane_gravity(p, tl, xi=xi, naive=True),
                    ),
                )
            for label, fn in methods:
                for tol in (1e-6, 1e-8):
                    t, res = median_time(
                        lambda f=fn, tl=tol, p=problem, x=xi: f(p, tl, xi=x), repeat
                    )
                    ok = bool(res["success"])
                    err = profile_error(res, ref_prof) if ok else float("nan")
                    rows.append(
                        [
                            name,
                            f"{eps:g}",
                            label,
                            f"{tol:g}",
                            "yes" if ok else "NO",
                            f"{t * 1e3:.1f}",
                            f"{err:.1e}" if ok else res["message"][:40],
                        ]
                    )
                    if ok:
                        # our cheapest run at least as accurate
                        candidates = [tt for tt, ee in ours if ee <= err] or [ours[-1][0]]
                        ratios.append(
                            [
                                name,
                                f"{eps:g}",
                                f"{label} tol {tol:g}",
                                f"{err:.1e}",
                                f"{t / min(candidates):.1f}",
                            ]
                        )
    print(
        table(
            rows,
            ["problem", "eps", "method", "tol", "ok", "median [ms]", "max error vs rtol=1e-12"],
        )
    )
    print(
        "\nSpeed ratio at equal accuracy (baseline time / time of our cheapest run that is at "
        "least as accurate):\n"
    )
    print(table(ratios, ["problem", "eps", "baseline", "its error", "ratio"]))


def curves(repeat: int) -> None:
    print("\n## 3. Delta(eps): 50 values from 1e-1 to 1e-6, four problems, one core\n")
    eps = list(np.geomspace(1e-1, 1e-6, 50))
    base = {
        "plane, identical walls": PlaneShear(material=MAT, upper=Wall(20.0), eps=0.1),
        "plane, rougher lower": PlaneShear(
            material=MAT, upper=Wall(20.0), lower=Wall.fully_rough(), eps=0.1
        ),
        "plane, gravity B = 1": PlaneShear(material=MAT, upper=Wall(20.0), eps=0.1, B=1.0),
        "Couette, Ri = 1": CouetteFlow(material=MAT, wall=Wall(20.0), eps=0.1, Ri=1.0),
    }
    rows = []
    for rtol in (1e-8, 1e-6):
        t_scalar, _ = median_time(
            lambda r=rtol: [thickness_curve(p, eps, rtol=r) for p in base.values()], repeat
        )
        everything = [replace(p, eps=e) for p in base.values() for e in eps]
        t_batch, res = median_time(
            lambda r=rtol, ps=everything: wall_quantities(ps, rtol=r), repeat
        )
        n_ok = sum(r.status == "ok" for r in res)
        rows.append([f"{rtol:g}", f"{t_scalar:.2f}", f"{t_batch:.2f}", f"{n_ok}/200"])
    print(table(rows, ["rtol", "scalar, continuation [s]", "batched [s]", "solved"]))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="fewer repeats and eps values")
    args = parser.parse_args()
    repeat = 1 if args.quick else 3
    print(f"# cosserat benchmarks ({time.strftime('%Y-%m-%d %H:%M')}; median of {repeat})")
    closed_form_floor(repeat)
    baselines([0.04, 1e-3] if args.quick else [0.04, 1e-2, 1e-3, 1e-4], repeat)
    curves(repeat)


if __name__ == "__main__":
    main()
