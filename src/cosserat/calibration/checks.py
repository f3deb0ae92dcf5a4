"""What the runs say of themselves, whatever the model: checks a calibration reports beside
its fits (``docs/calibration.md``).

* **Regime**: a run whose local inertial number next to the moving wall exceeds
  :data:`~cosserat.calibration.data.QUASI_STATIC_I` is not in the slow, quasi-static regime the
  frictional Cosserat model is for.
* **Rate independence**: two runs of the same cell (cell, walls, material, gap within
  :data:`SAME_GAP`, B within :data:`SAME_B`) at different wall speeds should agree if the
  material is rate-independent there; their difference in each field is tested
  (chi^2 of the difference with both runs' errors, the bins of one interpolated onto the other's
  positions, whitened with the field's pooled rho).
* **The error model's limits**: a field whose estimated bin correlation sits at its cap
  (:data:`~cosserat.calibration.noise.RHO_MAX`) scatters less from bin to bin than its errors
  say; from the profile alone, overstated errors and strong correlation cannot be told apart.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from .data import QUASI_STATIC_I, WALL_BINS, RunData
from .diagnostics import MISFIT_P, chi2_log10_p, p_text
from .noise import RHO_MAX, whiten

SAME_GAP = 0.03
"""Relative difference of H/d within which two runs are the same cell [-]."""
SAME_B = 0.05
"""Absolute difference of B within which two runs are the same cell [-]."""
OTHER_SPEED = 0.2
"""Relative difference of I_w beyond which two runs are at different speeds [-]."""


def regime(runs: Sequence[RunData]) -> list[str]:
    """Runs that are not quasi-static, and runs whose regime is not measured."""
    out = []
    for r in runs:
        if r.local_inertial_number is None and r.meta.get("synthetic"):
            continue
        if r.local_inertial_number is None:
            out.append(
                f"run {r.name}: its local inertial number is not given, so whether it is "
                "quasi-static (the frictional Cosserat model's regime) is not known"
            )
        elif r.local_inertial_number > QUASI_STATIC_I:
            mean = "" if r.I_w is None else f"; I_w, the gap-mean value, is {r.I_w:.2g}"
            out.append(
                f"run {r.name} is not quasi-static: the local inertial number in the "
                f"{WALL_BINS} bins next to the moving wall reaches "
                f"{r.local_inertial_number:.2g} (the frictional Cosserat model is for I <= "
                f"{QUASI_STATIC_I:g}{mean})"
            )
    return out


def _same_cell(a: RunData, b: RunData) -> bool:
    if (a.cell, a.material, a.walls) != (b.cell, b.material, b.walls):
        return False
    if abs(a.gap_d / b.gap_d - 1.0) > SAME_GAP:
        return False
    if a.cell == "couette":
        return abs(a.cell_values.get("Ri", 0.0) - b.cell_values.get("Ri", 0.0)) <= 0.05
    return abs(a.cell_values.get("B", 0.0) - b.cell_values.get("B", 0.0)) <= SAME_B


def rate_pairs(runs: Sequence[RunData]) -> list[str]:
    """Same cells at different speeds, and whether each field agrees (module docstring)."""
    out = []
    for i, a in enumerate(runs):
        for b in runs[i + 1 :]:
            if not _same_cell(a, b) or a.I_w is None or b.I_w is None:
                continue
            if abs(a.I_w / b.I_w - 1.0) <= OTHER_SPEED:
                continue
            parts = []
            worst = 0.0
            for name in ("u", "omega", "stress_ratio"):
                fa, fb = a.fields.get(name), b.fields.get(name)
                if fa is None or fb is None:
                    continue
                inside = (fa.s >= fb.s.min()) & (fa.s <= fb.s.max())
                if np.count_nonzero(inside) < 3:
                    continue
                diff = fa.value[inside] - np.interp(fa.s[inside], fb.s, fb.value)
                se = np.hypot(fa.se[inside], np.interp(fa.s[inside], fb.s, fb.se))
                rho = max(fa.correlation.rho, fb.correlation.rho)
                w = whiten(diff, se, rho)
                chi2 = float(w @ w)
                lp = chi2_log10_p(chi2, w.size)
                worst = min(worst, lp)
                parts.append(f"{name}: chi^2 = {chi2:.1f} on {w.size} bins ({p_text(lp)})")
            if not parts:
                continue
            verdict = (
                "they differ: the material is not rate-independent at these speeds"
                if worst < math.log10(MISFIT_P)
                else "they agree within their errors"
            )
            out.append(
                f"runs {a.name} and {b.name} are one cell at two wall speeds (I_w = "
                f"{a.I_w:.2g} and {b.I_w:.2g}): " + "; ".join(parts) + f"; {verdict}"
            )
    return out


def error_model(runs: Sequence[RunData]) -> list[str]:
    """Fields whose estimated correlation sits at its cap (module docstring)."""
    capped = sorted(
        {
            name
            for r in runs
            for name, f in r.fields.items()
            if f.correlation.source == "estimated" and f.correlation.rho >= RHO_MAX
        }
    )
    return [
        f"the bins of {name} scatter less from one to the next than their standard errors say "
        f"(the estimated correlation is at its cap, rho = {RHO_MAX:g}): the profile alone "
        "cannot tell overstated errors from strongly correlated ones; errors measured from the "
        "runs' time blocks (bin_correlation in the metadata) would"
        for name in capped
    ]


def all_checks(runs: Sequence[RunData]) -> list[str]:
    return regime(runs) + rate_pairs(runs) + error_model(runs)


__all__ = ["OTHER_SPEED", "SAME_B", "SAME_GAP", "all_checks", "error_model", "rate_pairs",
           "regime"]  # fmt: skip
