"""Corpus v2, the design written before running (docs/dem.md): which gaps and how many runs
separate the models' finite-H predictions of the shear-layer thickness Delta at 3 sigma, and
what they cost.

    PYTHONPATH=src python tools/dem_design.py [--bench] [--json OUT]

1. Predictions: Delta(H/d) [d] (``cosserat.shear_layer_thickness``, f = 0.05) of each model
   with the material measured at quasi-static rates (corpus v2, H = 10 d, V = 0.0025):
   phi = 19 deg (sin(phi) = 0.33; the rough moving wall's stress ratio 0.321-0.328) for
   plane shear under gravity at fixed B = 1 (nu = 0.8, the corpus's B nu) for a fully rough
   wall and for the smooth wall's delta = 13.9 deg (tan(delta) = 0.248 +- 0.011 measured);
   Couette at the fixed R_i/H = 1. (v1's faster runs gave phi = 17, delta = 12.8 deg.) mu(I) and
   NGF take mu_s = sin(phi) and the wall inertial number of the design's wall speed,
   I_w = V d / (H sqrt(p_w / rho_s)) with V = 0.0025 sqrt(N/rho_s) and p_w = N; their other
   parameters are the package's defaults (NGF's A = 0.48 is the 3-D glass-bead value: the
   scale-free test below does not depend on it to first order). Every model's L or A is free
   in a calibration, so two tests are reported: ``absolute`` (the curves as they are) and
   ``shape`` (the second model's curve times the best factor: what a calibration that fits
   one amplitude cannot absorb).
2. Errors: the standard error of Delta of one run, from the shipped corpus's plane runs
   (u_se carried through the crossing u = f u_wall), as a fraction of Delta; the run-to-run
   scatter is not yet measured (no replicas), so the design uses twice the median
   within-run fraction and reports what it needs at 4 times the median.
3. Separation: sqrt(sum_H n_H (Delta_a - s Delta_b)^2 / sigma_H^2), s = 1 (absolute) or the
   best factor (shape); 3 means the pair is told apart at 3 sigma by the expected data.
4. Cost: atoms of each cell (walls included), sheared steps for a wall travel of 40 d + H at
   V (the corpus's transients lasted 11-52 d of wall travel), settling 30k steps, and the
   atom-steps per second measured here (``--bench``: 2,000 + 2,000 steps of each size, the
   load average printed; ``--rates FILE`` reads them back from a ``--json``) times
   :data:`PRODUCTION_FACTOR`, or, without them, the 1.7e6 atom-steps/s of the first v2 run
   at a load average of 7.
"""

from __future__ import annotations

import argparse
import csv
import itertools
import json
import math
import os
import tempfile
from importlib import resources
from pathlib import Path

import numpy as np

from cosserat import make_problem, shear_layer_thickness, solve
from cosserat.config import DEFAULT_F

PHI, B, NU = 19.0, 1.0, 0.8
"""phi [deg]: sin(phi) = 0.33, the stress ratio 0.321-0.328 at the rough moving wall of the
quasi-static plane run at H = 10 d (data/dem_v2); B and nu as in the design."""
DELTA_SMOOTH = 13.9
"""The smooth wall's delta [deg]: tan(delta) = 0.248 +- 0.011 at the moving wall of the
quasi-static smooth plane run at H = 10 d (data/dem_v2)."""
V = 0.0025
DT = 0.996e-3
PLANE_GAPS = (10, 20, 40, 80, 160)
COUETTE_GAPS = (10, 20, 40, 80)
RI_OVER_H = 1.0
FALLBACK_RATE = 1.7e6
PRODUCTION_FACTOR = 0.65
"""Production over bench speed: the first v2 run (plane, H = 10 d, dense and sheared) makes
1.6-1.7e6 atom-steps/s where the bench's loose packing of the same cell makes 2.6e6, at the
same load average (6-7); applied to every size's bench rate."""
SCATTER_FACTOR = 2.0
MAX_REPLICAS = 10
DESIGNS = {
    "full": {
        "plane rough": {10: 3, 20: 3, 40: 3, 80: 3, 160: 3},
        "plane smooth": {10: 3, 20: 3, 40: 3, 80: 3, 160: 3},
        "couette Ri/H=1": {10: 3, 20: 3, 40: 3},
    },
    "reduced": {
        "plane rough": {10: 2, 20: 2, 40: 2, 80: 2, 160: 2},
        "plane smooth": {10: 2, 20: 2, 40: 2, 80: 2, 160: 2},
        "couette Ri/H=1": {10: 2, 20: 2},
    },
}
"""The proposed corpus v2 (gap: replicas) before its half-speed partners, and a reduced one."""
LARGE_GAPS = 40
"""Separations are also given from the gaps of at least this many d only: below, the
predictions depend on the material length L (10 d by default) beyond an overall factor."""
HALF_SPEED = (("plane", 20), ("plane", 20), ("couette", 10))
"""Half-speed partners (twice the steps): rough and smooth plane at H = 20 d, Couette H = 10 d."""


def delta(model: str, cell: str, values: dict) -> float:
    try:
        return float(shear_layer_thickness(solve(make_problem(model, cell, values))))
    except Exception as exc:  # a pair without a solution at that gap: said in the table
        print(f"  {model} {cell} {values}: {type(exc).__name__}")
        return math.nan


def predictions() -> dict[str, dict[str, dict[int, float]]]:
    mu_s = math.sin(math.radians(PHI))
    out: dict[str, dict[str, dict[int, float]]] = {}
    for case, wall in (("plane rough", "fully-rough"), ("plane smooth", DELTA_SMOOTH)):
        out[case] = {
            "cosserat": {H: delta("cosserat", "plane", {"phi": PHI, "delta": wall,
                                                         "eps": 1 / H, "B": B, "nu": NU})
                         for H in PLANE_GAPS},
            **{m: {H: delta(m, "plane", {"mu_s": mu_s, "eps": 1 / H, "B": B, "nu": NU,
                                          "I_w": V / H}) for H in PLANE_GAPS}
               for m in ("ngf", "mui")},
        }  # fmt: skip
    out["couette Ri/H=1"] = {
        "cosserat": {H: delta("cosserat", "couette", {"phi": PHI, "delta": "fully-rough",
                                                       "eps": 1 / H, "Ri": RI_OVER_H})
                     for H in COUETTE_GAPS},
        **{m: {H: delta(m, "couette", {"mu_s": mu_s, "eps": 1 / H, "Ri": RI_OVER_H,
                                        "I_w": V / H}) for H in COUETTE_GAPS}
           for m in ("ngf", "mui")},
    }  # fmt: skip
    return out


def measured_delta(name: str) -> tuple[float, float]:
    """Delta [d] of a shipped plane run and its standard error from u_se."""
    path = resources.files("cosserat") / "data" / "corpus" / f"{name}.csv"
    with path.open() as fh:
        rows = list(csv.DictReader(fh))
    y = np.array([float(r["y"]) for r in rows])
    u = np.array([float(r["u"]) for r in rows])
    se = np.array([float(r["u_se"]) for r in rows])
    target = DEFAULT_F * u[-1]
    k = len(u) - 1
    while k > 0 and u[k - 1] > target:
        k -= 1
    a, b = k - 1, k  # the crossing lies between bins a and b
    slope = (u[b] - u[a]) / (y[b] - y[a])
    y_cross = y[a] + (target - u[a]) / slope
    err = math.hypot(float(np.interp(y_cross, y, se)), DEFAULT_F * se[-1]) / abs(slope)
    wall = y[-1] + 0.5 * (y[-1] - y[-2])  # the moving wall's surface, near enough
    return float(wall - y_cross), float(err)


def separation(a: dict[int, float], b: dict[int, float], n: dict[int, int], rel: float,
               shape: bool) -> float:  # fmt: skip
    gaps = [H for H in n if n[H] and math.isfinite(a[H]) and math.isfinite(b[H])]
    if not gaps:
        return 0.0
    da = np.array([a[H] for H in gaps])
    db = np.array([b[H] for H in gaps])
    w = np.array([n[H] for H in gaps]) / (rel * da) ** 2
    s = float(np.sum(w * da * db) / np.sum(w * db * db)) if shape else 1.0
    return float(math.sqrt(np.sum(w * (da - s * db) ** 2)))


def atoms(cell: str, H: int) -> int:
    from cosserat.dem import CouetteDEM, PlaneShearDEM, build_deck

    c = PlaneShearDEM(gap=H, width=30.0) if cell == "plane" else CouetteDEM(
        gap=H, inner_radius=RI_OVER_H * H)  # fmt: skip
    return int(build_deck(c).layout.x.size)


def steps(H: int) -> int:
    return int(math.ceil((40.0 + H) / (V * DT) / 200_000) * 200_000)


def bench(sizes: list[tuple[str, int]]) -> dict[str, float]:
    """Atom-steps per second of LAMMPS (one process) for each cell size, from the loop time
    of 2,000 sheared steps after 2,000 settling steps (a loose packing: an upper bound)."""
    from cosserat.dem import CouetteDEM, PlaneShearDEM, RunLength, build_deck
    from cosserat.dem.runner import run_deck

    run = RunLength(settle_steps=2_000, steps=2_000, dump_every=200)
    out = {}
    for cell, H in sizes:
        c = PlaneShearDEM(gap=H, width=30.0, wall_speed=V, run=run) if cell == "plane" else (
            CouetteDEM(gap=H, inner_radius=RI_OVER_H * H, wall_speed=V, run=run))  # fmt: skip
        deck = build_deck(c)
        with tempfile.TemporaryDirectory() as tmp:
            deck.write(tmp)
            run_deck(tmp)
            loops = [float(x.split()[3]) for x in Path(tmp, "log.lammps").read_text()
                     .splitlines() if x.startswith("Loop time of ")]  # fmt: skip
        rate = deck.layout.x.size * run.steps / loops[-1]
        out[f"{cell} H={H}"] = rate
        print(f"  {cell} H = {H} d: {deck.layout.x.size} atoms, {rate:.3g} atom-steps/s, "
              f"{run.steps / loops[-1]:.0f} steps/s (load {os.getloadavg()[0]:.1f})")  # fmt: skip
    return out


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--bench", action="store_true", help="measure LAMMPS's speed here")
    parser.add_argument("--json", default=None, help="write the numbers to this file")
    parser.add_argument("--rates", default=None, help="atom-steps/s per size from a --json")
    args = parser.parse_args()
    report: dict = {}
    print("## Predictions Delta(H) [d]")
    pred = predictions()
    for case, models in pred.items():
        for m, curve in models.items():
            print(f"{case:16s} {m:9s} " + "  ".join(f"H={H}: {v:6.2f}" for H, v in curve.items()))
    report["predictions"] = {c: {m: {str(H): v for H, v in cur.items()} for m, cur in ms.items()}
                             for c, ms in pred.items()}  # fmt: skip
    print("## Measured Delta and its within-run standard error (shipped corpus, V = 0.1-0.2)")
    rels = []
    for name in ("plane_rough_H20", "plane_rough_H40", "plane_rough_H80", "plane_smooth_H20",
                 "plane_smooth_H40", "plane_smooth_H80"):  # fmt: skip
        d, e = measured_delta(name)
        rels.append(e / d)
        print(f"{name:18s} Delta = {d:5.2f} +- {e:4.2f} d ({100 * e / d:.1f}%)")
    rel = SCATTER_FACTOR * float(np.median(rels))
    report["within_run_relative_se"] = rels
    report["design_relative_sigma"] = rel
    print(f"design: sigma_Delta / Delta = {rel:.3f} per run ({SCATTER_FACTOR:g} x the median)")
    print("## Smallest designs separating each pair at 3 sigma (n runs per gap)")
    designs = []
    for case, models in pred.items():
        gaps = PLANE_GAPS if case.startswith("plane") else COUETTE_GAPS
        pairs = [("cosserat", "ngf"), ("cosserat", "mui"), ("ngf", "mui")]
        if case == "plane rough":
            pairs.append(("cosserat smooth", "cosserat"))
        for a_name, b_name in pairs:
            a = pred["plane smooth"]["cosserat"] if a_name == "cosserat smooth" else models[a_name]
            b = models[b_name]
            for shape in (False, True):
                for scale in (1.0, 2.0):
                    best = None
                    for k in range(2, len(gaps) + 1):
                        for sub in itertools.combinations(gaps, k):
                            for reps in range(1, MAX_REPLICAS + 1):
                                n = {H: reps for H in sub}
                                sep = separation(a, b, n, scale * rel, shape)
                                if sep >= 3.0:
                                    cost = sum(reps * atoms(case.split()[0], H) * steps(H)
                                               for H in sub)  # fmt: skip
                                    if best is None or cost < best[0]:
                                        best = (cost, sub, reps, sep)
                                    break
                    row = {"case": case, "pair": f"{a_name} vs {b_name}",
                           "test": "shape" if shape else "absolute",
                           "sigma": round(scale * rel, 3),
                           "design": None if best is None else {
                               "gaps": list(best[1]), "replicas": best[2],
                               "atom_steps": best[0], "separation": round(best[3], 1)}}  # fmt: skip
                    designs.append(row)
                    text = (
                        f"none within {MAX_REPLICAS} replicas at these gaps" if best is None
                        else f"gaps {list(best[1])} x {best[2]}: {best[0]:.3g} atom-steps, "
                        f"{best[3]:.1f} sigma"
                    )  # fmt: skip
                    print(f"{case:15s} {a_name:15s} vs {b_name:9s} {row['test']:8s} "
                          f"sigma {scale * rel:.3f}: {text}")  # fmt: skip
    report["designs"] = designs
    sizes = [("plane", H) for H in PLANE_GAPS] + [("couette", H) for H in COUETTE_GAPS]
    print("## Cost per run")
    rates = bench(sizes) if args.bench else {}
    if args.rates:
        rates = json.loads(Path(args.rates).read_text())["rates"]
    report["rates"] = rates
    costs = {}
    for cell, H in sizes:
        n_atoms, n_steps = atoms(cell, H), steps(H)
        rate = PRODUCTION_FACTOR * rates[f"{cell} H={H}"] if rates else FALLBACK_RATE
        hours = n_atoms * (n_steps + 30_000) / rate / 3600
        costs[f"{cell} H={H}"] = {"atoms": n_atoms, "steps": n_steps, "cpu_hours": hours}
        print(f"{cell:8s} H = {H:3d} d: {n_atoms:6d} atoms, {n_steps / 1e6:5.1f}M steps, "
              f"{rate:.3g} atom-steps/s -> {hours:7.1f} CPU-hours")  # fmt: skip
    report["costs"] = costs
    for label, design in DESIGNS.items():
        print(f"## The {label} design: separations [sigma] (absolute / shape; shape from "
              f"H >= {LARGE_GAPS} d only) and cost")  # fmt: skip
        total = 0.0
        for case, n in design.items():
            cell = case.split()[0]
            hours = sum(reps * costs[f"{cell} H={H}"]["cpu_hours"] for H, reps in n.items())
            total += hours
            models = pred[case]
            large = {H: r for H, r in n.items() if H >= LARGE_GAPS}
            pairs = {
                f"{a} vs {b}": (models[a], models[b])
                for a, b in (("cosserat", "ngf"), ("cosserat", "mui"), ("ngf", "mui"))
            }
            if case == "plane rough":
                pairs["cosserat smooth vs rough"] = (pred["plane smooth"]["cosserat"],
                                                     models["cosserat"])  # fmt: skip
            seps = {
                k: (
                    separation(a, b, n, rel, False),
                    separation(a, b, n, rel, True),
                    separation(a, b, large, rel, True),
                )
                for k, (a, b) in pairs.items()
            }
            print(
                f"{case}: {sum(n.values())} runs at {dict(n)}, {hours:.0f} CPU-hours; "
                + "; ".join(f"{k} {a:.1f} / {b:.1f} ({c:.1f})" for k, (a, b, c) in seps.items())
            )
            report.setdefault(label, {})[case] = {
                "replicas": {str(H): r for H, r in n.items()}, "cpu_hours": hours,
                "separation_absolute_shape_shapelarge": seps}  # fmt: skip
        partners = sum(2 * costs[f"{c} H={H}"]["cpu_hours"] for c, H in HALF_SPEED)
        total += partners
        print(f"half-speed partners {HALF_SPEED}: {partners:.0f} CPU-hours; the {label} design: "
              f"{total:.0f} CPU-hours, {total / 2 / 24:.1f} days on 2 cores")  # fmt: skip
        report.setdefault(label, {})["total_cpu_hours"] = total
    if args.json:
        Path(args.json).write_text(json.dumps(report, indent=1) + "\n")


if __name__ == "__main__":
    main()
