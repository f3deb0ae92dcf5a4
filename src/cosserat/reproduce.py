"""Reproduce the paper's stated numbers into a folder (the README's main job)."""

from __future__ import annotations

import csv
import json
import logging
from collections.abc import Callable
from dataclasses import dataclass, replace
from pathlib import Path

from .analysis import asymptotic_thickness, thickness_curve, thickness_limit
from .parameters import Material, Wall
from .problems import PlaneShear, Problem
from .solvers.airy import xi_hat_at_fraction

log = logging.getLogger(__name__)

PAPER_MATERIAL = Material(phi=28.5, L=10.0, A=1.0 / 3.0)
EPS_CURVE = [1e-1, 3e-2, 1e-2, 3e-3, 1e-3, 1e-4, 1e-5, 1e-6]


@dataclass(frozen=True)
class Claim:
    """A number the paper states beside the one the package computes."""

    quantity: str
    stated: str
    computed: float
    source: str
    how: str


def thickness_problems(fully_rough: bool) -> dict[str, Problem]:
    """The problems of figure 14 (panel a: delta = 20 deg; panel b: fully rough)."""
    wall = Wall.fully_rough(0.5) if fully_rough else Wall(20.0, 0.5)
    mat = PAPER_MATERIAL
    problems: dict[str, Problem] = {
        "plane, no gravity, identical walls": PlaneShear(material=mat, upper=wall, eps=1e-3),
        "plane, no gravity, rougher lower wall": PlaneShear(
            material=mat, upper=wall, lower=Wall.fully_rough(0.5), eps=1e-3
        ),
        "plane, gravity B = 1": PlaneShear(material=mat, upper=wall, eps=1e-3, B=1.0),
    }
    if fully_rough:  # identical fully rough walls without gravity shear uniformly; not in 14b
        problems.pop("plane, no gravity, identical walls")
        problems.pop("plane, no gravity, rougher lower wall")
    return problems


def reproduce(out: str | Path, progress: Callable[[str, int, int], None] | None = None) -> Path:
    """Write the stated-versus-computed table and the thickness curves into ``out``."""
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    claims: list[Claim] = []
    rows: list[dict[str, object]] = []
    jobs = [(name, p, False) for name, p in thickness_problems(False).items()]
    jobs += [(name + " (fully rough)", p, True) for name, p in thickness_problems(True).items()]
    for i, (name, problem, _rough) in enumerate(jobs):
        deltas = thickness_curve(problem, EPS_CURVE).Delta
        for eps, d in zip(EPS_CURVE, deltas, strict=True):
            asym = asymptotic_thickness(replace(problem, eps=eps))
            rows.append({"problem": name, "eps": eps, "Delta": d, "Delta_asymptotic": asym})
        limit = thickness_limit(problem)
        if limit is not None and deltas[-1] is not None:
            claims.append(
                Claim(
                    f"Delta as eps -> 0, {name}",
                    "17.67",
                    deltas[-1],
                    "eqn-delta_soln, fig. 14a",
                    f"numerical at eps = {EPS_CURVE[-1]:g}",
                )
            )
        if progress:
            progress("thickness curves", i + 1, len(jobs))
    claims.append(
        Claim(
            "x_hat where u = 0.05 (Airy inner layer)",
            "1.275",
            xi_hat_at_fraction(0.05),
            "eqn-delta_soln_fr",
            "Brent root of 1 - I/I(inf)",
        )
    )
    claims.append(
        Claim(
            "fully rough delta = atan(sin phi) [deg]",
            "25.5",
            PAPER_MATERIAL.fully_rough_delta,
            "fig. 14 caption",
            "atan(sin 28.5 deg)",
        )
    )

    with (out / "thickness.csv").open("w", newline="") as fh:
        writer = csv.DictWriter(fh, fieldnames=["problem", "eps", "Delta", "Delta_asymptotic"])
        writer.writeheader()
        writer.writerows(rows)
    (out / "claims.json").write_text(json.dumps([c.__dict__ for c in claims], indent=1))
    lines = [
        "# Reproduction of Mohan, Kesava Rao & Nott: stated versus computed",
        "",
        "| quantity | paper | computed | where | how |",
        "|---|---|---|---|---|",
    ]
    lines += [
        f"| {c.quantity} | {c.stated} | {c.computed:.5g} | {c.source} | {c.how} |" for c in claims
    ]
    lines += ["", "Thickness curves: `thickness.csv`."]
    (out / "report.md").write_text("\n".join(lines) + "\n")
    log.info("wrote %s", out)
    return out
