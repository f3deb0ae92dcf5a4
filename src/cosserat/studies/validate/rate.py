"""Rate independence: one cell at two wall speeds, compared bin by bin (issue 18, item 1).

A rate-independent (quasi-static) flow scaled by the wall speed V -- u / V, omega d / V -- and
its stresses over the normal stress do not depend on V. Two runs of the same cell (cell, walls,
gap within :data:`GAP_TOLERANCE`, B within :data:`B_TOLERANCE`) at different wall speeds are
compared: u and omega bin by bin at equal y (:func:`cosserat.dem.checks.rate_independence`:
|z| <= 2 in at least the fraction a normal law puts there less 10 points, 85%), Delta, and the
moving wall's measured stress ratio |shear| / normal from its contacts (the sidecar's
``wall_stress``). Errors are the runs' block errors, the two runs' taken as independent.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from ...dem.checks import RateCheck, rate_independence
from ...errors import InputError
from .measures import slip_inertial_number

GAP_TOLERANCE = 0.02
"""Two runs are one cell when their gaps differ by at most this fraction [-]."""
B_TOLERANCE = 0.05
"""... and their B (eqn-nd_B) by at most this [-]."""
STATIC_I = 1e-4
"""The zone that barely moves: bins whose inertial number is below this in both runs [-]
(referee 11, point 2: no rate effect is plausible there, so a difference beyond the block
errors is scatter between the runs that the block errors do not carry)."""
STATIC_SIGMAS = 3.0
"""A static-zone bin whose two runs differ by more than this many combined se is named."""
STATIC_COLUMNS = ("omega", "nu", "sigma_yy", "sigma_rr")
"""The columns compared in the static zone (:func:`static_misses`)."""


@dataclass(frozen=True)
class StaticMiss:
    """One bin of the zone that barely moves where the two runs differ beyond
    :data:`STATIC_SIGMAS` combined block errors."""

    column: str
    distance_d: float
    """From the faster run's moving wall [d]."""
    z: float
    """(fast - slow) / hypot(se_fast, se_slow) [-]."""
    distance_slow_d: float | None = None
    """The same bin from the slower run's moving wall [d]."""


def static_misses(fast: Any, slow: Any) -> list[StaticMiss]:
    """The bins of :data:`STATIC_COLUMNS` where both runs' inertial number is below
    :data:`STATIC_I` and the two runs differ by more than :data:`STATIC_SIGMAS` combined
    block errors, by column then distance; [] where the runs' bins are not the same ``y``
    (``r``) to 1e-6 d or a run lacks the inertial number."""
    a, b = fast.columns, slow.columns
    coord = "y" if "y" in a else "r"
    if coord not in b or "inertial_number" not in a or "inertial_number" not in b:
        return []
    ya, yb = np.asarray(a[coord], float), np.asarray(b[coord], float)
    if ya.shape != yb.shape:
        return []
    same = np.abs(ya - yb) <= 1e-6
    with np.errstate(invalid="ignore"):
        static = same & (np.asarray(a["inertial_number"], float) < STATIC_I)
        static &= np.asarray(b["inertial_number"], float) < STATIC_I
    dist = np.asarray(fast.distance_d, float)
    dist_slow = np.asarray(slow.distance_d, float)
    out = []
    for column in STATIC_COLUMNS:
        if not all(k in c for c in (a, b) for k in (column, f"{column}_se")):
            continue
        se = np.hypot(np.asarray(a[f"{column}_se"], float), np.asarray(b[f"{column}_se"], float))
        with np.errstate(invalid="ignore", divide="ignore"):
            z = (np.asarray(a[column], float) - np.asarray(b[column], float)) / se
        for row in np.flatnonzero(static & np.isfinite(z) & (np.abs(z) > STATIC_SIGMAS)):
            out.append(
                StaticMiss(
                    column,
                    round(float(dist[row]), 4),
                    float(z[row]),
                    round(float(dist_slow[row]), 4),
                )
            )
    return out


def static_text(misses: Sequence[StaticMiss]) -> str:
    """The misses as ``"omega at 6.3 d (z = -3.2), nu at 9.3 d (z = +3.3)"``."""
    return ", ".join(f"{m.column} at {m.distance_d:.2g} d (z = {m.z:+.2g})" for m in misses)


@dataclass(frozen=True)
class RatePair:
    """Two runs of one cell at two wall speeds (``fast`` the faster), compared."""

    fast: str
    slow: str
    speeds: tuple[float, float]
    checks: dict[str, RateCheck]
    delta: tuple[tuple[float, float] | None, tuple[float, float] | None]
    wall_ratio: tuple[tuple[float, float] | None, tuple[float, float] | None]
    static: tuple[StaticMiss, ...] = ()
    """:func:`static_misses` of the pair."""

    @property
    def wall_ratio_z(self) -> float | None:
        """(fast - slow) over the combined error of the walls' stress ratios [-]."""
        a, b = self.wall_ratio
        if a is None or b is None or not math.hypot(a[1], b[1]) > 0.0:
            return None
        return (a[0] - b[0]) / math.hypot(a[1], b[1])

    def text(self) -> str:
        """One clause: what agrees and what does not."""
        parts = []
        for name, c in self.checks.items():
            n = c.z.size
            inside = round(c.within * n)
            z2 = c.chi2_per_dof * n
            parts.append(f"{name} within 2 se in {inside} of {n} bins (sum of z^2 = {z2:.3g})")
        d_fast, d_slow = self.delta
        if d_fast is not None and d_slow is not None:
            parts.append(
                f"Delta {d_fast[0]:.3g} +- {d_fast[1]:.2g} against {d_slow[0]:.3g} +- "
                f"{d_slow[1]:.2g} d"
            )
        z = self.wall_ratio_z
        w_fast, w_slow = self.wall_ratio
        if z is not None and w_fast is not None and w_slow is not None:
            parts.append(
                f"the moving wall's stress ratio {w_fast[0]:.3g} +- {w_fast[1]:.2g} against "
                f"{w_slow[0]:.3g} +- {w_slow[1]:.2g} (z = {z:+.2g})"
            )
        agree = [n for n, c in self.checks.items() if c.consistent]
        differ = [n for n, c in self.checks.items() if not c.consistent]
        reading = []
        if agree:
            reading.append(f"{' and '.join(agree)} {'agree' if len(agree) > 1 else 'agrees'}")
        if differ:
            reading.append(
                f"{' and '.join(differ)} {'do' if len(differ) > 1 else 'does'} not (the rule: "
                "at least 85% of the bins within 2 se)"
            )
        if self.static:
            reading.append(
                f"where the material barely moves (I < {STATIC_I:g} in both) they differ "
                f"beyond {STATIC_SIGMAS:g} se at {static_text(self.static)}: scatter between "
                "the runs that the block errors do not carry, no rate effect being plausible "
                "there"
            )
        if z is not None:
            if abs(z) <= 2.0:
                reading.append("the stress level agrees within 2 se")
            elif self.static:
                reading.append(
                    f"the stress level differs by {abs(z):.2g} se, within the scatter these "
                    "static-zone misses show, so it is not read as a rate dependence (a second "
                    "seed at each speed would tell)"
                )
            else:
                reading.append(
                    "the stress level differs beyond 2 se (a rate dependence the "
                    "rate-independent models cannot carry, or run-to-run scatter: one seed at "
                    "each speed)"
                )
        return (
            f"{self.fast} (V = {self.speeds[0]:.3g}) against {self.slow} (V = "
            f"{self.speeds[1]:.3g}): {'; '.join(parts)}: {', '.join(reading)}"
        )


def _same_cell(a: Any, b: Any) -> bool:
    ma, mb = a.meta, b.meta
    if a.cell != b.cell or ma.get("wall") != mb.get("wall"):
        return False
    if ma.get("wall_fixed", ma.get("wall")) != mb.get("wall_fixed", mb.get("wall")):
        return False
    if abs(a.gap_d - b.gap_d) > GAP_TOLERANCE * max(a.gap_d, b.gap_d):
        return False
    ba, bb = ma.get("B"), mb.get("B")
    if isinstance(ba, int | float) and isinstance(bb, int | float):
        return abs(ba - bb) <= B_TOLERANCE
    return ba == bb


def _wall_ratio(run: Any) -> tuple[float, float] | None:
    ws = run.meta.get("wall_stress")
    if not isinstance(ws, dict):
        return None
    values = [
        v
        for k in ("shear", "normal", "shear_se", "normal_se")
        if isinstance(v := ws.get(k), int | float)
    ]
    if len(values) < 4:
        return None
    shear, normal, s_se, n_se = (float(v) for v in values)
    if not normal > 0.0 or shear == 0.0:
        return None
    ratio = abs(shear) / normal
    return ratio, ratio * math.hypot(s_se / abs(shear), n_se / normal)


def _delta(result: Any) -> tuple[float, float] | None:
    t = result.thickness
    if t is None or t.value is None or t.stderr is None:
        return None
    return float(t.value), float(t.stderr)


def replicate_cells(runs: Sequence[Any]) -> dict[str, str]:
    """Each run's cell for counting (referee 10, point 3): runs of one cell (cell, walls, gap
    within :data:`GAP_TOLERANCE`, B within :data:`B_TOLERANCE`) with the same ``seed`` in
    their sidecars differ only in wall speed, and are replicates of one cell, not independent
    runs. Run name -> the cell's label (the name of its first run by name); a run without a
    recorded seed is a cell of its own."""
    ordered = sorted(runs, key=lambda r: r.name)
    label: dict[str, str] = {}
    for i, a in enumerate(ordered):
        if a.name in label:
            continue
        label[a.name] = a.name
        seed = a.meta.get("seed")
        if seed is None:
            continue
        for b in ordered[i + 1 :]:
            if b.name not in label and b.meta.get("seed") == seed and _same_cell(a, b):
                label[b.name] = a.name
    return label


AGREE_SIGMAS = 2.0
"""Two departures agree when they differ by at most this many standard errors of the
difference (the rate check's bin rule) [-]."""


@dataclass(frozen=True)
class FirstLayerRate:
    """One cell's first-layer departure beyond the null at two wall speeds (referee 10,
    point 5): ``fast`` and ``slow`` run names, each departure and its se [-]."""

    fast: str
    slow: str
    speeds: tuple[float, float]
    departures: tuple[tuple[float, float], tuple[float, float]]

    @property
    def z(self) -> float | None:
        """(fast - slow) over the combined error (the two runs independent) [-]."""
        (a, sa), (b, sb) = self.departures
        se = math.hypot(sa, sb)
        return (a - b) / se if se > 0.0 else None

    @property
    def agrees(self) -> bool:
        """The two departures agree within :data:`AGREE_SIGMAS`."""
        z = self.z
        return z is not None and abs(z) <= AGREE_SIGMAS


def first_layers_at_two_speeds(
    pairs: Sequence[RatePair], walls: Sequence[Any]
) -> list[FirstLayerRate]:
    """For each pair of :func:`rate_pairs`, the moving walls' first-layer departure beyond the
    null under the analysis' stencil (``WallSpin.beyond_first``) at both speeds; a pair
    whose runs lack a moving wall with a null is left out."""
    moving = {w.run: w for w in walls if w.wall == "moving" and w.null is not None and w.dof}
    out = []
    for p in pairs:
        a, b = moving.get(p.fast), moving.get(p.slow)
        if a is None or b is None:
            continue
        out.append(FirstLayerRate(p.fast, p.slow, p.speeds, (a.beyond_first(), b.beyond_first())))
    return out


def slip_text(results: Sequence[Any], bound: float) -> str:
    """One sentence for the spin verdicts' regime line (referee 10, point 5): the first
    layer's inertial number from the moving wall's slip
    (:func:`~.measures.slip_inertial_number`) against the quasi-static ``bound``, and whether
    one cell's first-layer departure agrees at two wall speeds (:func:`first_layers_at_two_speeds`),
    the evidence that a slip layer's I above the bound does not matter. Empty without a run
    that gives it. ``results``: validate's run results (``run``, ``spin.walls``)."""
    slips = [s for r in results if (s := slip_inertial_number(r.run)) is not None]
    if not slips:
        return ""
    lo, hi = min(slips, key=lambda s: s.value), max(slips, key=lambda s: s.value)
    above = [s for s in slips if s.value > bound]
    text = (
        f" The first layers lie in the moving wall's slip, where the shear rate (1 - u_1)/s_1 "
        f"(s_1 the first bin's distance from the wall) gives I = {lo.value:.2g} ({lo.run}) "
        f"to {hi.value:.2g} ({hi.run}) in the same units"
        + (
            f": {len(above)} of {len(slips)} runs above the bound I <= {bound:g}, which the "
            "bin gradient does not show"
            if above
            else f", within the bound I <= {bound:g}"
        )
    )
    walls = [w for r in results for w in getattr(r.spin, "walls", [])]
    agree = first_layers_at_two_speeds(rate_pairs(results), walls)
    if not above:
        return text + "."
    if not agree:
        return text + (
            "; no cell's first layer is measured at two wall speeds, so whether the slip "
            "layer's rate matters is not shown."
        )
    by_run = {s.run: s.value for s in slips}
    parts = []
    for f in agree:
        (a, sa), (b, sb) = f.departures
        i_fast, i_slow = by_run.get(f.fast), by_run.get(f.slow)
        slip_i = (
            f", slip I {i_fast:.2g} against {i_slow:.2g}"
            if i_fast is not None and i_slow is not None
            else ""
        )
        z = f.z
        parts.append(
            f"{f.fast} at V = {f.speeds[0]:.3g} and {f.slow} at V = {f.speeds[1]:.3g}: "
            f"{a:+.3g} +- {sa:.2g} against {b:+.3g} +- {sb:.2g}, z = "
            + ("-" if z is None else f"{z:+.2g}")
            + slip_i
        )
    good = [f for f in agree if f.agrees]
    if len(good) == len(agree):
        tail = (
            f"; the first layer's departure beyond the null agrees within {AGREE_SIGMAS:g} se "
            f"where one cell is run at two speeds ({'; '.join(parts)}): that is the evidence "
            "that the slip layer's rate does not matter"
        )
    else:
        tail = (
            f"; the first layer's departure beyond the null differs by more than "
            f"{AGREE_SIGMAS:g} se where one cell is run at two speeds ({'; '.join(parts)}): "
            "it depends on the rate, so the slip layer's I above the bound matters"
        )
    return text + tail + "."


def rate_pairs(results: Sequence[Any]) -> list[RatePair]:
    """Every pair of ``results`` (validate's run results: ``run``, ``thickness``) that is one
    cell at two wall speeds (the sidecars' ``wall_speed``), compared (module docstring)."""
    out: list[RatePair] = []
    for i, a in enumerate(results):
        for b in results[i + 1 :]:
            va, vb = a.run.meta.get("wall_speed"), b.run.meta.get("wall_speed")
            if not (isinstance(va, int | float) and isinstance(vb, int | float)) or va == vb:
                continue
            if not _same_cell(a.run, b.run):
                continue
            fast, slow = (a, b) if va > vb else (b, a)
            checks = {}
            for column in ("u", "omega"):
                try:
                    checks[column] = rate_independence(fast.run.columns, slow.run.columns, column)
                except InputError:
                    continue
            out.append(
                RatePair(
                    fast.run.name,
                    slow.run.name,
                    (float(max(va, vb)), float(min(va, vb))),
                    checks,
                    (_delta(fast), _delta(slow)),
                    (_wall_ratio(fast.run), _wall_ratio(slow.run)),
                    tuple(static_misses(fast.run, slow.run)),
                )
            )
    return out
