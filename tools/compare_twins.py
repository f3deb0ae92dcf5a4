"""Does it carry to 3-D? Two runs of one cell side by side (issue 18 item 3, docs/dem.md).

    PYTHONPATH=src python tools/compare_twins.py RUN_A.csv RUN_B.csv [--json OUT]

Each run is a profile in the corpus format (``<run>.csv`` + ``<run>.json``, e.g. a run
folder's ``profile.csv``), typically the 2-D run and its 3-D twin. Printed, for each: the
dimension, the gap, whether it is quasi-static (the local I in the three bins next to the
moving wall) and steady, the moving wall's stress ratio |shear|/normal (sin phi at a rough
wall) with its block error, the band's stress ratio, Delta (where u falls to 0.05 of its
value next to the moving wall) with its error and whether the band fills the gap, and the
spin's departure from half the vorticity in the first bin at the moving wall (sign and size,
in V/d); then the profiles u and omega compared bin by bin in combined standard errors
(:func:`cosserat.dem.checks.rate_independence`, which compares any two scaled profiles). The
measures are validation's own (:mod:`cosserat.studies.validate.measures`).
"""

from __future__ import annotations

import argparse
import json
import math
from pathlib import Path
from typing import Any

import numpy as np

from cosserat.analysis.corpus import read_run
from cosserat.dem.checks import rate_independence
from cosserat.studies.validate.measures import (
    band_stress_ratio,
    measure_spin,
    measured_thickness,
    moving_wall_inertial_number,
)


def summary(csv: str | Path) -> dict[str, Any]:
    """The measures of one run (module docstring) as a dict of plain numbers."""
    run = read_run(csv)
    meta = run.meta
    wall = meta.get("wall_stress", {})
    normal, shear = wall.get("normal"), wall.get("shear")
    ratio = abs(shear) / normal if normal and shear is not None else None
    ratio_se = None
    if ratio is not None and wall.get("shear_se") is not None:
        ratio_se = ratio * math.hypot(wall["shear_se"] / shear, wall.get("normal_se", 0) / normal)
    delta = measured_thickness(run)
    band = band_stress_ratio(run)
    spin = measure_spin(run)
    moving = next((w for w in spin.walls if w.wall == "moving"), None) if spin.available else None
    return {
        "run": str(csv),
        "dim": meta.get("dim", 2),
        "gap_d": run.gap_d,
        "quasi_static": meta.get("quasi_static"),
        "I_moving_wall": moving_wall_inertial_number(run),
        "steady": meta.get("steadiness", {}).get("steady"),
        "wall_stress_ratio": ratio,
        "wall_stress_ratio_se": ratio_se,
        "band_stress_ratio": None if band is None else band.value,
        "band_stress_ratio_se": None if band is None else band.stderr,
        "delta_d": delta.value,
        "delta_se": delta.stderr,
        "fills_gap": delta.fills_gap,
        "spin_first_bin": None if moving is None else moving.first,
        "spin_first_bin_se": None if moving is None else moving.first_se,
        "nu_mean": float(np.nanmean(run.columns["nu"])) if "nu" in run.columns else None,
    }


def compare(a_csv: str | Path, b_csv: str | Path) -> dict[str, Any]:
    """Both runs' summaries and their u and omega profiles compared bin by bin (within 2 se)."""
    a, b = read_run(a_csv), read_run(b_csv)
    profiles = {}
    for column in ("u", "omega"):
        if a.has(column) and b.has(column):
            check = rate_independence(a.columns, b.columns, column=column)
            profiles[column] = {
                "within_2se": round(check.within, 3),
                "chi2_per_bin": round(check.chi2_per_dof, 3),
                "consistent": check.consistent,
            }
    return {"runs": [summary(a_csv), summary(b_csv)], "profiles": profiles}


def _cell(value: Any, se: Any = None) -> str:
    if value is None:
        return "-"
    if isinstance(value, bool):
        return "yes" if value else "no"
    if isinstance(value, float):
        text = f"{value:.3g}"
        return text if se is None else f"{text} +- {se:.2g}"
    return str(value)


def table(result: dict[str, Any]) -> str:
    """The comparison as a Markdown table (one column per run) and the profiles' lines."""
    rows = [
        ("dimension", "dim", None),
        ("gap [d]", "gap_d", None),
        ("quasi-static (I <= 1e-3 at the moving wall)", "quasi_static", None),
        ("largest I in the 3 bins at the moving wall", "I_moving_wall", None),
        ("steady", "steady", None),
        ("moving wall's stress ratio", "wall_stress_ratio", "wall_stress_ratio_se"),
        ("band's stress ratio", "band_stress_ratio", "band_stress_ratio_se"),
        ("Delta [d]", "delta_d", "delta_se"),
        ("band fills the gap", "fills_gap", None),
        ("omega - W/2, first bin at the moving wall [V/d]", "spin_first_bin", "spin_first_bin_se"),
        ("mean solids fraction", "nu_mean", None),
    ]
    runs = result["runs"]
    out = ["| | " + " | ".join(Path(r["run"]).parent.name or r["run"] for r in runs) + " |"]
    out.append("|---" * (len(runs) + 1) + "|")
    for label, key, se in rows:
        cells = [_cell(r[key], r[se] if se else None) for r in runs]
        out.append(f"| {label} | " + " | ".join(cells) + " |")
    for column, p in result["profiles"].items():
        out.append(
            f"\n{column}: {p['within_2se']:.0%} of the bins within 2 combined se, chi^2 per bin "
            f"{p['chi2_per_bin']:g} ({'consistent' if p['consistent'] else 'not consistent'})"
        )
    return "\n".join(out)


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("a", help="a run's profile CSV (corpus format, with its JSON sidecar)")
    parser.add_argument("b", help="its twin's profile CSV")
    parser.add_argument("--json", default=None, help="also write the numbers to this file")
    args = parser.parse_args(argv)
    result = compare(args.a, args.b)
    print(table(result))
    if args.json:
        Path(args.json).write_text(json.dumps(result, indent=1) + "\n")


if __name__ == "__main__":
    main()
