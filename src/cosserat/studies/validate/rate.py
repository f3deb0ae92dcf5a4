"""Rate independence: one cell at two wall speeds, compared bin by bin (issue 18, item 1).

A rate-independent (quasi-static) flow scaled by the wall speed V -- u / V, omega d / V -- and
its stresses over the normal stress do not depend on V. Two runs of the same cell (cell, walls,
gap within :data:`GAP_TOLERANCE`, B within :data:`B_TOLERANCE`) at different wall speeds are
compared: u and omega bin by bin at equal y (:func:`cosserat.dem.checks.rate_independence`:
|z| <= 2 in at least the fraction a normal law puts there less 10 points, 85%), Delta, and the
moving wall's measured stress ratio |shear| / normal from its contacts (the sidecar's
``wall_stress``). Errors are the runs' block errors, the two runs' taken as independent.

**Same-conditions replicates** (referee 12, point 2): two runs of one cell at one wall speed
with two seeds (:func:`twin_pairs`) are compared the same way on every field (u, omega, nu and
the stresses, bins paired by row), and their seed-scatter factor sqrt(sum z^2 / n) -- what the
block errors must be multiplied by to carry the scatter between realisations, overall and in
the static zone -- rescales the static-zone checks beside their block-error z
(:func:`static_rescaled_text`, :func:`balance_rescaled_text`, :func:`misfit_twin_text`).
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ...calibration.data import BAND_U, WALL_EXCLUSION_D
from ...dem.checks import RateCheck, rate_independence
from ...errors import InputError
from .measures import slip_inertial_number, truncated_rows

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
    return ", ".join(f"{m.column} at {m.distance_d:.1f} d (z = {m.z:+.2g})" for m in misses)


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


# ----------------------------------------------------------------- same-conditions replicates
TWIN_COLUMNS = (
    "u",
    "omega",
    "nu",
    "sigma_yy",
    "sigma_xx",
    "sigma_yx",
    "sigma_rr",
    "sigma_tt",
    "sigma_rt",
)
"""The fields two same-conditions replicates are compared on (those both profiles carry with
their ``_se``), in this order."""
SE_FLOOR = 0.01
"""A paired bin enters no seed-scatter factor when either run's block se is below this
fraction of the field's median block se over both runs' paired bins [-] (referee 17, point 5).
Such a se means the ten blocks returned one value (plane_smooth_H20_qs_s2's nu at 0.5 and 4.5
d: 3.7e-17 and 1.7e-17, round-off on zero: no grain crossed the bin over the window), so the
bin has no error estimate rather than a precise one, and its z is the difference over the
other run's se alone (nu: -65). A hundredth keeps the small but measured static-zone se
(seed 1's nu se at 0.5 d, 3.6e-4, is 6% of the median): those are the within-realisation
errors the factor is there to measure."""
TWIN_BIN_D = 0.1
"""Two replicates' bins are one bin (paired by row) when their centres are within this [d]:
the truncated bin at a wall sits a little apart where the two gaps differ slightly."""
TWIN_SIGMAS = 3.0
"""A bin whose two replicates differ by more than this many combined se is named."""
AGREE_FRACTION = 0.9545 - 0.10
"""A field agrees between replicates when at least this fraction of its bins is within 2 se:
the rate check's rule (``cosserat.dem.checks.rate_independence``, a normal law's 95.45% less
10 points) [-]."""
SPEED_TOL = 1e-6
"""Two wall speeds are one when they differ by at most this fraction [-]."""


@dataclass(frozen=True)
class TwinField:
    """One field of two same-conditions replicates compared bin by bin (referee 12, point 2).

    ``z`` is (a - b) / hypot(se_a, se_b) per paired bin, with the bin's distance from the
    fixed wall [d] and whether it is in the static zone (inertial number below
    :data:`STATIC_I` in both runs)."""

    column: str
    z: tuple[float, ...]
    distance_fixed_d: tuple[float, ...]
    static: tuple[bool, ...]
    truncated: tuple[bool, ...] = ()
    """Whether each bin is a truncated wall bin in either run (``measures.truncated_rows``)."""
    rows: tuple[int, ...] = ()
    """Each bin's row in both profiles (bins are paired by row)."""
    floored: tuple[bool, ...] = ()
    """Whether either run's block se of the bin is below :data:`SE_FLOOR` of the field's
    median: listed in :attr:`chi2`, left out of :meth:`factor`."""

    @property
    def n(self) -> int:
        return len(self.z)

    @property
    def chi2(self) -> float:
        """sum z^2 over the paired bins [-]: about n where the block errors are each run's
        whole error."""
        return float(sum(v * v for v in self.z))

    @property
    def beyond(self) -> list[tuple[float, float]]:
        """(distance from the fixed wall [d], z) of the bins beyond :data:`TWIN_SIGMAS`."""
        return [
            (d, v)
            for d, v in zip(self.distance_fixed_d, self.z, strict=True)
            if abs(v) > TWIN_SIGMAS
        ]

    @property
    def within_two(self) -> float:
        """The fraction of the bins within 2 se [-]."""
        return sum(abs(v) <= 2.0 for v in self.z) / self.n

    @property
    def agrees(self) -> bool:
        """The rate check's rule (``cosserat.dem.checks.rate_independence``): at least
        :data:`AGREE_FRACTION` of the bins within 2 se."""
        return self.within_two >= AGREE_FRACTION

    def is_truncated(self, distance_d: float) -> bool:
        """Whether the bin at ``distance_d`` from the fixed wall is a truncated wall bin."""
        return any(
            t and abs(d - distance_d) < 1e-9
            for d, t in zip(self.distance_fixed_d, self.truncated, strict=False)
        )

    @property
    def n_truncated(self) -> int:
        """How many of the paired bins are truncated wall bins (listed in :attr:`chi2`, left
        out of :meth:`factor`)."""
        return sum(self.truncated)

    @property
    def largest(self) -> tuple[float, float]:
        """(distance from the fixed wall [d], z) of the bin with the largest |z|."""
        k = int(np.argmax(np.abs(self.z)))
        return self.distance_fixed_d[k], self.z[k]

    def is_floored(self, distance_d: float) -> bool:
        """Whether the bin at ``distance_d`` from the fixed wall has a run's block se below
        :data:`SE_FLOOR` of the median."""
        return any(
            t and abs(d - distance_d) < 1e-9
            for d, t in zip(self.distance_fixed_d, self.floored, strict=False)
        )

    @property
    def floored_at(self) -> list[float]:
        """The distances from the fixed wall [d] of the bins below the se floor."""
        return [d for d, t in zip(self.distance_fixed_d, self.floored, strict=False) if t]

    def _picked(self, zone: str, without: Sequence[int] = ()) -> list[tuple[float, float]]:
        """(z, distance from the fixed wall [d]) of the bins :meth:`factor` uses."""
        cut = self.truncated or (False,) * self.n
        low = self.floored or (False,) * self.n
        rows = self.rows or (-1,) * self.n
        return [
            (v, d)
            for v, d, s, t, f, r in zip(
                self.z, self.distance_fixed_d, self.static, cut, low, rows, strict=True
            )
            if not t
            and not f
            and r not in without
            and (zone == "all" or (s if zone == "static" else not s))
        ]

    def without_largest(self, zone: str = "all") -> tuple[float, float] | None:
        """(the factor without the bin of largest |z|, that bin's distance from the fixed wall
        [d]) over ``zone``'s bins (referee 17, point 5: a factor one bin drives); None with
        fewer than two bins."""
        pick = self._picked(zone)
        if len(pick) < 2:
            return None
        k = max(range(len(pick)), key=lambda i: abs(pick[i][0]))
        rest = [v for i, (v, _) in enumerate(pick) if i != k]
        return math.sqrt(sum(v * v for v in rest) / len(rest)), pick[k][1]

    def factor(self, zone: str = "all", without: Sequence[int] = ()) -> float | None:
        """The seed-scatter factor sqrt(sum z^2 / n) over ``zone``'s bins ("all", "static"
        or "flowing"), truncated wall bins left out (their values are not bulk values, and a
        truncated bin has a different width in each run: referee 13, point 5), so are bins
        below the se floor (:data:`SE_FLOOR`) and the rows in ``without`` (a miss's own bin,
        when the factor rescales it: referee 17, point 5); None without such a bin there [-].

        If each run's true error is f times its block se, the difference has variance
        f^2 (se_a^2 + se_b^2), so E z^2 = f^2: f is what the block se must be multiplied by
        to carry the scatter between realisations (1 where they already do). From one pair
        it rests on n bins, with neighbouring bins' errors correlated."""
        pick = [v for v, _ in self._picked(zone, without)]
        if not pick:
            return None
        return math.sqrt(sum(v * v for v in pick) / len(pick))

    def to_dict(self) -> dict[str, Any]:
        return {
            "column": self.column,
            "n": self.n,
            "sum_z2": self.chi2,
            "z": list(self.z),
            "distance_fixed_d": list(self.distance_fixed_d),
            "static": list(self.static),
            "truncated": list(self.truncated),
            "beyond": [{"distance_fixed_d": d, "z": v} for d, v in self.beyond],
            "factor": self.factor("all"),
            "factor_static": self.factor("static"),
            "factor_flowing": self.factor("flowing"),
            "factor_excludes_truncated": True,
            "floored": list(self.floored),
            "se_floor": SE_FLOOR,
            "factor_without_largest": _loo(self.without_largest("all")),
            "factor_static_without_largest": _loo(self.without_largest("static")),
        }


def _loo(got: tuple[float, float] | None) -> dict[str, float] | None:
    return None if got is None else {"factor": got[0], "distance_fixed_d": got[1]}


STRESS_COLUMNS = ("nu", "sigma_yy", "sigma_xx", "sigma_yx", "sigma_rr", "sigma_tt", "sigma_rt")
"""The fields whose seed-scatter factors :meth:`TwinPair.factors_text` gives."""


def _g2(x: float) -> str:
    """Two significant figures, a trailing zero kept (4.0, 0.43, 19)."""
    return f"{x:#.2g}".rstrip(".")


def _z(a: float | None, sa: float | None, b: float | None, sb: float | None) -> float | None:
    if a is None or b is None or sa is None or sb is None or not math.hypot(sa, sb) > 0.0:
        return None
    return (a - b) / math.hypot(sa, sb)


@dataclass(frozen=True)
class TwinPair:
    """Two runs of one cell at one wall speed with different seeds (``a`` the lower seed):
    same-conditions replicates, compared bin by bin with their independent block errors
    (referee 12, point 2)."""

    a: str
    b: str
    speed: float
    seeds: tuple[Any, Any]
    fields: dict[str, TwinField]
    delta: tuple[tuple[float, float] | None, tuple[float, float] | None]
    wall_ratio: tuple[tuple[float, float] | None, tuple[float, float] | None]
    runs: tuple[Any, ...] = field(default=(), compare=False, repr=False)
    """The two corpus runs (``a``'s, ``b``'s), to tell which cell the pair measures."""

    @property
    def delta_z(self) -> float | None:
        """(Delta_a - Delta_b) over the combined block error [-]."""
        (da, db) = self.delta
        return None if da is None or db is None else _z(da[0], da[1], db[0], db[1])

    @property
    def wall_ratio_z(self) -> float | None:
        """(a - b) over the combined error of the moving walls' |shear| / normal [-]."""
        (wa, wb) = self.wall_ratio
        return None if wa is None or wb is None else _z(wa[0], wa[1], wb[0], wb[1])

    @property
    def delta_scatter(self) -> float | None:
        """The per-run relative scatter of Delta the pair shows, |ln(Delta_a / Delta_b)| /
        sqrt(2): the sample standard deviation of ln Delta from two runs (one degree of
        freedom) [-]; None without both Deltas."""
        (da, db) = self.delta
        if da is None or db is None or not (da[0] > 0.0 and db[0] > 0.0):
            return None
        return abs(math.log(da[0] / db[0])) / math.sqrt(2.0)

    def field_text(self, f: TwinField) -> str:
        """One field's clause: sum z^2, the bins beyond :data:`TWIN_SIGMAS` (else the
        largest), truncated wall bins named."""

        def at(d: float, v: float) -> str:
            # one decimal: 11.5 and 12.5 d both read "12 d" at 2 significant figures
            return (
                f"{v:+.2g} at {d:.1f} d"
                + (" (truncated bin)" if f.is_truncated(d) else "")
                + (" (se below the floor)" if f.is_floored(d) else "")
            )

        beyond = ", ".join(at(d, v) for d, v in f.beyond)
        return (
            f"{f.column} sum z^2 = {f.chi2:.3g} on {f.n} bins ("
            + (f"beyond {TWIN_SIGMAS:g} se: {beyond}" if beyond else f"largest {at(*f.largest)}")
            + ")"
        )

    def factors_text(self) -> str:
        """The seed-scatter factors of nu and the stresses, overall and in the static zone,
        each with its value without its largest bin (referee 17, point 5: "4.0 (2.8 without
        the bin at 4.5 d)")."""
        parts = []
        for name in STRESS_COLUMNS:
            f = self.fields.get(name)
            if f is None or (al := f.factor("all")) is None:
                continue
            st, loo, loo_st = f.factor("static"), f.without_largest(), f.without_largest("static")
            inner = [] if loo is None else [f"{_g2(loo[0])} without the bin at {loo[1]:.1f} d"]
            if st is not None:
                inner.append(f"static zone {_g2(st)}")
                if loo_st is not None:
                    same = loo is not None and abs(loo[1] - loo_st[1]) < 1e-9
                    where = "it" if same else f"the bin at {loo_st[1]:.1f} d"
                    inner[-1] += f", {_g2(loo_st[0])} without {where}"
            parts.append(f"{name} {_g2(al)}" + (f" ({'; '.join(inner)})" if inner else ""))
        return ", ".join(parts)

    def cut_text(self) -> str:
        """Which bins the factors leave out: truncated wall bins (counted in each sum z^2) and
        bins below the se floor (:data:`SE_FLOOR`), named ("" where none is)."""
        out = ""
        if any(f.n_truncated for f in self.fields.values()):
            out += (
                "; the truncated wall bins, counted in each sum z^2 above, are left out of every "
                "factor: their values are not bulk values and their width differs between the "
                "runs"
            )
        low = [
            f"{f.column} at " + " and ".join(f"{d:.1f}" for d in f.floored_at) + " d"
            for f in self.fields.values()
            if f.floored_at
        ]
        if low:
            out += (
                f"; left out too, for a block se below {SE_FLOOR:g} of the field's median in "
                f"one run (the blocks returned one value: no error estimate, so no z): "
                + "; ".join(low)
            )
        return out

    def unused_text(self) -> str:
        """Referee 17, point 5: no verdict uses binned nu or the binned stresses outside the
        band, and what the verdicts do use agrees between the seeds (the band's stress ratio,
        the moving walls' contact stress ratio), from this pair's numbers; "" without them."""
        ratio, wz = self.fields.get("stress_ratio"), self.wall_ratio_z
        if ratio is None or wz is None or (rf := ratio.factor()) is None:
            return ""
        agree = ratio.agrees and abs(wz) <= 2.0
        return (
            " No verdict uses binned nu or binned stresses outside the band; the stresses "
            "they use are the band's stress ratio (the joint fits' stress part: factor "
            f"{_g2(rf)} between the seeds) and the walls' contacts (the moving wall's stress "
            f"ratio: z = {wz:+.2g} between the seeds; phi and delta)"
            + (
                ", both agreeing between the seeds. So the factors above undercut no "
                "verdict's errors."
                if agree
                else "; "
                + ("the band's" if not ratio.agrees else "the walls'")
                + " differs between the seeds beyond the block errors."
            )
        )

    def text(self, note: str = "") -> str:
        """One sentence: every field's sum z^2, the bins beyond 3 se, Delta's and the wall
        ratio's z, the seed-scatter factors and what they mean for the checks that use the
        static zone; ``note`` right after "Same-conditions replicates"."""
        parts = [self.field_text(f) for f in self.fields.values()]
        (da, db), dz = self.delta, self.delta_z
        if da is not None and db is not None and dz is not None:
            parts.append(f"Delta {da[0]:.3g} +- {da[1]:.2g} against {db[0]:.3g} +- {db[1]:.2g} d "
                         f"(z = {dz:+.2g})")  # fmt: skip
        (wa, wb), wz = self.wall_ratio, self.wall_ratio_z
        if wa is not None and wb is not None and wz is not None:
            parts.append(
                f"the moving wall's stress ratio {wa[0]:.3g} +- {wa[1]:.2g} against "
                f"{wb[0]:.3g} +- {wb[1]:.2g} (z = {wz:+.2g})"
            )
        text = (
            f"Same-conditions replicates{note}: {self.a} against {self.b} (one cell at V = "
            f"{self.speed:.3g}, seed {self.seeds[0]} against {self.seeds[1]}; bins paired by "
            f"row, distance from the fixed wall, each z over the two runs' independent block "
            f"errors): {'; '.join(parts)}."
        )
        factors = self.factors_text()
        if factors:
            text += (
                " The seed-scatter factor sqrt(sum z^2 / n) (what each run's block se must be "
                "multiplied by to carry the scatter between realisations; static zone: I < "
                f"{STATIC_I:g} in both; beside each, the factor without its largest bin): "
                f"{factors}{self.cut_text()}. In the static zone the "
                "packing is frozen over the window, so the ten time blocks sample one quenched "
                "configuration and their se is a within-realisation error: static-zone misses "
                "of nu and the stresses beyond their block errors are realisation noise at "
                "about these factors, not model or rate effects." + self.unused_text()
            )
        ratio = self.fields.get("stress_ratio")
        if ratio is not None:
            text += (
                f" The joint fits' stress-ratio part (|shear| / normal over the bins with u >= "
                f"{BAND_U:g}, at least {WALL_EXCLUSION_D:g} d from the walls) "
                + (
                    "agrees between the seeds"
                    if ratio.agrees
                    else "differs between the seeds beyond the block errors"
                )
                + f" (sum z^2 = {ratio.chi2:.3g} on {ratio.n} bins, factor "
                f"{ratio.factor():.2g}"
                + (
                    f", {sum(ratio.static)} of them in the static zone"
                    if any(ratio.static)
                    else ", none in the static zone"
                )
                + ")"
                + (
                    ", so its errors are taken as they are."
                    if ratio.agrees
                    else ": its chi^2 is short of the scatter between realisations."
                )
            )
        om = self.fields.get("omega")
        if om is not None:
            text += " " + self.omega_text()
        return text

    def brief(self) -> str:
        """One clause for a verdict that does not use the pair: each field's sum z^2 over its
        bins (truncated wall bins included and marked) and, where measured, its static-zone
        factor without them (the full comparison is :meth:`text`, in the verdicts whose runs
        the pair is)."""
        parts = []
        for f in self.fields.values():
            static = f.factor("static")
            notes = [f"{f.n_truncated} truncated bin"] if f.n_truncated else []
            if static is not None and static > 1:
                notes.append(f"static zone x{static:.2g}" + (" without it" if notes else ""))
            parts.append(
                f"{f.column} {f.chi2:.3g}/{f.n}" + (f" ({'; '.join(notes)})" if notes else "")
            )
        return f"{self.a} against {self.b} (seed {self.seeds[0]} against {self.seeds[1]}): " + (
            ", ".join(parts)
        )

    def omega_text(self) -> str:
        """Whether omega agrees between the seeds (:attr:`TwinField.agrees`), and what that
        means for the spin verdicts; "" without omega."""
        om = self.fields.get("omega")
        if om is None:
            return ""
        _, v = om.largest
        where = f"sum z^2 = {om.chi2:.3g} on {om.n} bins, no bin beyond {abs(v):.2g} se"
        if om.agrees:
            return (
                f"omega agrees between the seeds ({where}), so the spin verdicts' block "
                "errors are not undercut by the seed scatter that nu and the stresses show."
            )
        return (
            f"omega differs between the seeds ({where}; fewer than "
            f"{100 * AGREE_FRACTION:.0f}% of the bins within 2 se): the spin verdicts' block "
            f"errors may be short of the scatter between realisations, by about "
            f"{om.factor():.2g}."
        )

    def to_dict(self) -> dict[str, Any]:
        return {
            "a": self.a,
            "b": self.b,
            "speed": self.speed,
            "seeds": list(self.seeds),
            "fields": {k: f.to_dict() for k, f in self.fields.items()},
            "delta": [None if d is None else list(d) for d in self.delta],
            "delta_z": self.delta_z,
            "delta_scatter": self.delta_scatter,
            "wall_ratio": [None if w is None else list(w) for w in self.wall_ratio],
            "wall_ratio_z": self.wall_ratio_z,
        }


def _band_ratio(run: Any) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The run's |shear| / normal stress per bin with its se (the two stresses' errors
    independent), and whether the bin is one the joint fits' stress-ratio part takes (u >=
    ``calibration.data.BAND_U``, at least ``WALL_EXCLUSION_D`` from both walls: the rule of
    ``calibration.data``)."""
    c = run.columns
    shear, normal = ("sigma_rt", "sigma_rr") if "r" in c else ("sigma_yx", "sigma_yy")
    n_rows = np.asarray(c["y" if "y" in c else "r"]).size
    if not all(k in c for k in (shear, f"{shear}_se", normal, f"{normal}_se", "u")):
        return np.full(n_rows, np.nan), np.full(n_rows, np.nan), np.zeros(n_rows, bool)
    t, st = np.asarray(c[shear], float), np.asarray(c[f"{shear}_se"], float)
    n, sn = np.asarray(c[normal], float), np.asarray(c[f"{normal}_se"], float)
    u = run.quantity("u")[0]
    s = np.asarray(run.distance_d, float)
    with np.errstate(invalid="ignore", divide="ignore"):
        ratio = np.abs(t) / n
        se = ratio * np.hypot(st / np.abs(t), sn / n)
        band = (n > 0.0) & (u >= BAND_U)
        band &= (s >= WALL_EXCLUSION_D) & (s <= float(run.gap_d) - WALL_EXCLUSION_D)
    return ratio, se, band


def twin_fields(a: Any, b: Any) -> dict[str, TwinField]:
    """:data:`TWIN_COLUMNS` of runs ``a`` and ``b`` (corpus runs) compared bin by bin, and
    ``stress_ratio`` (|shear| / normal) over the bins both runs' joint fits take for their
    stress-ratio part (:func:`_band_ratio`): bins paired by row where both profiles have as
    many rows and their centres are within :data:`TWIN_BIN_D`; {} where the rows differ in
    number or no bin pairs."""
    ca, cb = a.columns, b.columns
    coord = "y" if "y" in ca else "r"
    if coord not in cb:
        return {}
    ya, yb = np.asarray(ca[coord], float), np.asarray(cb[coord], float)
    if ya.shape != yb.shape:
        return {}
    paired = np.abs(ya - yb) <= TWIN_BIN_D
    fixed = float(a.gap_d) - np.asarray(a.distance_d, float)
    static = np.zeros(ya.shape, bool)
    if "inertial_number" in ca and "inertial_number" in cb:
        with np.errstate(invalid="ignore"):
            static = (np.asarray(ca["inertial_number"], float) < STATIC_I) & (
                np.asarray(cb["inertial_number"], float) < STATIC_I
            )
    cut = np.zeros(ya.shape, bool)
    cut[[k for k in (*truncated_rows(a), *truncated_rows(b)) if k < cut.size]] = True
    values = {
        column: (
            np.asarray(ca[column], float),
            np.asarray(ca[f"{column}_se"], float),
            np.asarray(cb[column], float),
            np.asarray(cb[f"{column}_se"], float),
            paired,
        )
        for column in TWIN_COLUMNS
        if all(k in c for c in (ca, cb) for k in (column, f"{column}_se"))
    }
    (ra, sa, band_a), (rb, sb, band_b) = _band_ratio(a), _band_ratio(b)
    values["stress_ratio"] = (ra, sa, rb, sb, paired & band_a & band_b)
    out = {}
    for column, (va, sa_, vb, sb_, use) in values.items():
        se = np.hypot(sa_, sb_)
        with np.errstate(invalid="ignore", divide="ignore"):
            z = (va - vb) / se
        ok = use & np.isfinite(z) & (se > 0.0)
        if not ok.any():
            continue
        rows = np.flatnonzero(ok)
        floor = SE_FLOOR * float(np.median(np.concatenate([sa_[rows], sb_[rows]])))
        low = (sa_ < floor) | (sb_ < floor)
        out[column] = TwinField(
            column,
            tuple(float(z[k]) for k in rows),
            tuple(round(float(fixed[k]), 4) for k in rows),
            tuple(bool(static[k]) for k in rows),
            tuple(bool(cut[k]) for k in rows),
            tuple(int(k) for k in rows),
            tuple(bool(low[k]) for k in rows),
        )
    return out


def _twins(x: Any, y: Any) -> bool:
    """Whether corpus runs ``x`` and ``y`` are same-conditions replicates: one cell
    (:func:`_same_cell`), one wall speed (within :data:`SPEED_TOL`), two different recorded
    seeds."""
    va, vb = x.meta.get("wall_speed"), y.meta.get("wall_speed")
    sa, sb = x.meta.get("seed"), y.meta.get("seed")
    if not (isinstance(va, int | float) and isinstance(vb, int | float)):
        return False
    if abs(va - vb) > SPEED_TOL * max(abs(va), abs(vb)) or sa is None or sb is None:
        return False
    return sa != sb and _same_cell(x, y)


def _lower_seed_first(x: Any, y: Any) -> tuple[Any, Any]:
    return (x, y) if str(x.meta.get("seed")) <= str(y.meta.get("seed")) else (y, x)


def twin_names(runs: Sequence[Any]) -> tuple[tuple[str, str], ...]:
    """(a, b) names of the same-conditions replicates among ``runs`` (corpus runs,
    :func:`_twins`; the lower seed first), without comparing them."""
    return tuple(
        (a.name, b.name)
        for i, x in enumerate(runs)
        for y in runs[i + 1 :]
        if _twins(x, y)
        for a, b in (_lower_seed_first(x, y),)
    )


def twin_pairs(results: Sequence[Any]) -> list[TwinPair]:
    """Every pair of ``results`` (validate's run results: ``run``, ``thickness``) that is
    same-conditions replicates (:func:`_twins`), compared (:class:`TwinPair`; ``a`` the lower
    seed); a pair whose bins do not pair (:func:`twin_fields`) is left out."""
    out: list[TwinPair] = []
    by_run = {id(r.run): r for r in results}
    for i, x in enumerate(results):
        for y in results[i + 1 :]:
            if not _twins(x.run, y.run):
                continue
            ra, rb = _lower_seed_first(x.run, y.run)
            a, b = by_run[id(ra)], by_run[id(rb)]
            fields = twin_fields(a.run, b.run)
            if not fields:
                continue
            out.append(
                TwinPair(
                    a.run.name,
                    b.run.name,
                    float(a.run.meta["wall_speed"]),
                    (a.run.meta.get("seed"), b.run.meta.get("seed")),
                    fields,
                    (_delta(a), _delta(b)),
                    (_wall_ratio(a.run), _wall_ratio(b.run)),
                    (a.run, b.run),
                )
            )
    return out


def _same_walls(a: Any, b: Any) -> bool:
    """One cell kind with the same walls (the sidecars' ``wall`` and ``wall_fixed``), at any
    gap."""
    ma, mb = a.meta, b.meta
    return (
        a.cell == b.cell
        and ma.get("wall") == mb.get("wall")
        and ma.get("wall_fixed", ma.get("wall")) == mb.get("wall_fixed", mb.get("wall"))
    )


def twins_for(run: Any, twins: Sequence[TwinPair]) -> list[TwinPair]:
    """The replicate pairs whose factors apply to ``run``: those of its own cell
    (:func:`_same_cell`), else those with its walls at another gap, else every pair."""
    own = [t for t in twins if t.runs and _same_cell(run, t.runs[0])]
    if own:
        return own
    walls = [t for t in twins if t.runs and _same_walls(run, t.runs[0])]
    return walls or list(twins)


FACTOR_SOURCE = (
    "from the run's own cell's replicates where it has them, else those with its walls at "
    "another gap, else every pair"
)
"""How :func:`twins_for` picks the factor's replicates, in words."""


def twins_text(results: Sequence[Any]) -> str:
    """The regime block's sentence on the same-conditions replicates among ``results``
    (:func:`twin_pairs`; referee 12, point 2); "" without a pair."""
    return " ".join(p.text() for p in twin_pairs(results))


def twin_factor(
    pairs: Sequence[TwinPair],
    column: str,
    zone: str = "static",
    without: tuple[str, int] | None = None,
) -> float | None:
    """The largest seed-scatter factor of ``column`` over ``pairs`` in ``zone``
    (:meth:`TwinField.factor`), never below 1 (a factor under 1 from one pair is not read as
    block errors too large); None where no pair has the column's bins in that zone.
    ``without`` = (run, row): a pair with that run leaves that row out, so a miss is not
    rescaled by a factor its own bin drives (referee 17, point 5)."""

    def rows(p: TwinPair) -> tuple[int, ...]:
        return (without[1],) if without is not None and without[0] in (p.a, p.b) else ()

    got = [
        f
        for p in pairs
        if (tf := p.fields.get(column)) is not None and (f := tf.factor(zone, rows(p))) is not None
    ]
    return max(1.0, *got) if got else None


def static_rescaled_text(
    rate: Sequence[RatePair], twins: Sequence[TwinPair], runs: Mapping[str, Any] | None = None
) -> str:
    """The rate pairs' static-zone misses (:func:`static_misses`) with each z divided by its
    column's static-zone seed-scatter factor (:func:`twin_factor`) from the replicates that
    apply to the pair's cell (:func:`twins_for`, ``runs``: name -> corpus run; every pair
    without it): how many stay beyond :data:`STATIC_SIGMAS` (referee 12, point 2); "" without
    misses or twins."""
    if not twins:
        return ""
    rows = []
    used: dict[str, dict[str, float]] = {}
    for p in rate:
        pick = twins_for(runs[p.fast], twins) if runs and p.fast in runs else list(twins)
        names = "; ".join(f"{t.a} against {t.b}" for t in pick)
        for m in p.static:
            f = twin_factor(pick, m.column)
            if f is not None:
                rows.append((p, m, f))
                used.setdefault(names, {})[m.column] = f
    if not rows:
        return ""
    still = [
        f"{m.column} at {m.distance_d:.1f} d of {p.fast} against {p.slow} "
        f"(z = {m.z:+.2g} -> {m.z / f:+.2g})"
        for p, m, f in rows
        if abs(m.z / f) > STATIC_SIGMAS
    ]
    sources = "; ".join(
        f"{names}: " + ", ".join(f"{c} {f:.2g}" for c, f in fs.items())
        for names, fs in used.items()
    )
    return (
        f" The {len(rows)} static-zone misses between the two speeds, each z divided by its "
        f"field's static-zone seed-scatter factor from the same-conditions replicates "
        f"({sources}; {FACTOR_SOURCE}): "
        + (
            f"{len(still)} stay beyond {STATIC_SIGMAS:g} se ({'; '.join(still)}), more than "
            "the seed scatter the replicates show"
            if still
            else f"none stays beyond {STATIC_SIGMAS:g} se, so they are realisation noise at "
            "the measured factor"
        )
        + "."
    )


def balance_rescaled_text(runs: Sequence[Any], twins: Sequence[TwinPair]) -> str:
    """The momentum-balance misses of ``runs`` outside their truncated bins
    (``measures.wall_bins``), each z divided by the twins' seed-scatter factor of the shear
    stress in the zone its bin is in (static: I < :data:`STATIC_I`): how many stay beyond
    ``measures.BALANCE_SIGMAS`` (referee 12, point 2); "" without misses or twins."""
    from .measures import BALANCE_SIGMAS

    if not twins:
        return ""
    rows = balance_rescaled(runs, twins)
    if not rows:
        return ""
    still = [r for r in rows if abs(r[3]) > BALANCE_SIGMAS]
    names = "; ".join(f"{t.a} against {t.b}" for t in twins)
    listed = "; ".join(
        f"{n} at {d:.1f} d: z = {z:+.2g} -> {zr:+.2g} (factor {_g2(f)})" for n, d, z, zr, f in rows
    )
    return (
        f" The {len(rows)} momentum-balance misses outside the truncated bins, each z divided "
        f"by the shear stress's seed-scatter factor in its zone from the same-conditions "
        f"replicates ({names}; {FACTOR_SOURCE}; without the miss's own bin where the miss is "
        f"in one of the replicates): {listed}: "
        + (
            f"{len(still)} {'stays' if len(still) == 1 else 'stay'} beyond "
            f"{BALANCE_SIGMAS:g} se, so the seed scatter does not explain "
            + ("it." if len(still) == 1 else "them.")
            if still
            else f"none stays beyond {BALANCE_SIGMAS:g} se: realisation noise at the measured "
            "factor."
        )
    )


def balance_rescaled(
    runs: Sequence[Any], twins: Sequence[TwinPair]
) -> list[tuple[str, float, float, float, float]]:
    """:func:`balance_rescaled_text`'s rows: (run, distance from the moving wall [d], z, z over
    the factor, the factor) of each momentum-balance miss outside the truncated bins that has a
    seed-scatter factor; empty without twins."""
    return [(name, d, z, zr, f) for _, name, _, d, z, zr, f in _rescaled(runs, twins)]


def _rescaled(
    runs: Sequence[Any], twins: Sequence[TwinPair]
) -> list[tuple[Any, str, int, float, float, float, float]]:
    """:func:`balance_rescaled`'s rows with the run and the bin's row first; the factor leaves
    out the miss's own bin (:func:`twin_factor`'s ``without``)."""
    from .measures import wall_bins

    rows: list[tuple[Any, str, int, float, float, float, float]] = []
    if not twins:
        return rows
    for run in runs:
        checks = wall_bins(run)
        cut = {row for row, *_ in checks.truncated}
        shear = "sigma_rt" if run.cell == "couette" else "sigma_yx"
        i_col = run.columns.get("inertial_number")
        for row, d, _, z in checks.balance:
            if row in cut:
                continue
            static = i_col is not None and float(i_col[row]) < STATIC_I
            f = twin_factor(
                twins_for(run, twins), shear, "static" if static else "flowing", (run.name, row)
            )
            if f is not None:
                rows.append((run, run.name, row, float(d), float(z), float(z / f), float(f)))
    return rows


def _inertial(run: Any, row: int) -> float | None:
    """The run's inertial number at ``row`` (None without the column)."""
    i_col = run.columns.get("inertial_number")
    return None if i_col is None else float(i_col[row])


def _placed(runs: Sequence[Any], twins: Sequence[TwinPair]) -> list[tuple[Any, ...]]:
    """:func:`balance_rescaled`'s rows, each with its bin's place (``measures.miss_place``)
    and its inertial number last: (run name, distance [d], z, z over the factor, the factor,
    place, I)."""
    from .measures import miss_place, y_balance

    balances = {run.name: y_balance(run) for run in runs}
    return [
        (name, d, z, zr, f, miss_place(run, row, balances[name]), _inertial(run, row))
        for run, name, row, d, z, zr, f in _rescaled(runs, twins)
    ]


def balance_record(runs: Sequence[Any], twins: Sequence[TwinPair]) -> dict[str, Any]:
    """The Delta verdicts' ``numbers["balance_misses"]`` (referee 16, point 1): ``misses``
    (every momentum-balance miss outside the truncated bins with a seed-scatter factor:
    ``run``, ``distance_d``, ``z``, ``z_rescaled``, ``factor``, ``stays`` (beyond
    ``measures.BALANCE_SIGMAS`` after the rescaling) and its place, ``measures.MissPlace``'s
    record), ``y_balance`` (run -> ``measures.YBalance``'s record; plane runs under gravity)
    and the ``thresholds``."""
    from .measures import BALANCE_SIGMAS, HEXAGONAL_NU, INVERSION_SIGMAS, NU_STEP, y_balance

    balances = {run.name: y_balance(run) for run in runs}
    return {
        "misses": [
            {
                "run": name,
                "distance_d": d,
                "z": z,
                "z_rescaled": zr,
                "factor": f,
                "stays": abs(zr) > BALANCE_SIGMAS,
                "inertial_number": i,
                "static_zone": i is not None and i < STATIC_I,
                "factor_without_own_bin": True,
                **place.record(),
            }
            for name, d, z, zr, f, place, i in _placed(runs, twins)
        ],
        "y_balance": {n: b.record() for n, b in balances.items() if b is not None},
        "thresholds": {
            "balance_sigmas": BALANCE_SIGMAS,
            "hexagonal_nu": HEXAGONAL_NU,
            "inversion_sigmas": INVERSION_SIGMAS,
            "nu_step": NU_STEP,
        },
    }


def balance_warning(runs: Sequence[Any], twins: Sequence[TwinPair]) -> str:
    """A warning naming the momentum-balance misses that stay beyond ``BALANCE_SIGMAS`` after
    the seed-scatter rescaling (:func:`balance_rescaled`), by run and distance (referee 14,
    point 7: the Delta series use those runs), by where they sit (``measures.miss_place``;
    referee 16, point 1): in the layered static zone (the bin's nu above the hexagonal packing
    bound ``measures.HEXAGONAL_NU``, 2-D disks), where a centre-binned value is not a bulk
    value; next to it (a neighbour's nu above the bound, or the bin in a sigma_yy inversion or a
    nu step with a neighbour: ``measures.y_balance``); only the others as unexplained; "" where
    none stays."""
    from .measures import BALANCE_SIGMAS, HEXAGONAL_NU, MISS_PLACES, NU_STEP

    still = [r for r in _placed(runs, twins) if abs(r[3]) > BALANCE_SIGMAS]
    if not still:
        return ""

    def named(rows: Sequence[tuple[Any, ...]]) -> str:
        by_run: dict[str, list[tuple[Any, ...]]] = {}
        for name, d, _, zr, f, place, i in rows:
            by_run.setdefault(name, []).append((d, zr, f, place, i))

        def one(d: float, zr: float, f: float, place: Any, i: float | None) -> str:
            why = place.why() if place.place == MISS_PLACES[1] else ""
            if place.place == MISS_PLACES[2] and _static(i):
                why = (
                    f"I = {i:.2g} < {STATIC_I:g}: a static-zone bin (block errors within one "
                    "realisation); Delta, read from u, does not use it"
                )
            return (
                f"{d:.1f} d ("
                + ("" if place.nu is None else f"nu = {place.nu:.3f}; ")
                + f"z = {zr:+.2g} after the rescaling by {_g2(f)}"
                + (f"; {why}" if why else "")
                + ")"
            )

        return "; ".join(
            f"{name} at " + " and ".join(one(*p) for p in sorted(pts, key=lambda p: p[0]))
            for name, pts in by_run.items()
        )

    layered = [r for r in still if r[5].place == MISS_PLACES[0]]
    near = [r for r in still if r[5].place == MISS_PLACES[1]]
    other = [r for r in still if r[5].place == MISS_PLACES[2]]
    # referee 17, point 5: an unexplained miss in the static zone is not one Delta rests on
    flowing = [r for r in other if not _static(r[6])]
    zone = []
    if layered:
        zone.append(f"in it (nu > {HEXAGONAL_NU:.3f}, the hexagonal bound): {named(layered)}")
    if near:
        zone.append(
            f"next to it (beside a bin of nu > {HEXAGONAL_NU:.3f}, in a sigma_yy inversion or a "
            f"nu step of more than {NU_STEP:g}): {named(near)}"
        )
    parts = []
    if zone:
        zoned = layered + near  # review of stop 29: say only what these bins show
        marks = [
            w
            for w, has in (
                ("nu steps between adjacent bins", any(r[5].nu_steps for r in zoned)),
                (
                    "sigma_yy's y-balance broken in the same bins",
                    any(r[5].inversions for r in zoned),
                ),
            )
            if has
        ]
        parts.append(
            "in and next to the layered zone"
            + (f" ({'; '.join(marks)})" if marks else "")
            + ": "
            + "; ".join(zone)
        )
    if other:
        parts.append(f"unexplained: {named(other)}")
    n_runs = len({r[0] for r in still})
    return (
        " Warning: momentum-balance misses "
        + "; ".join(parts)
        + (" stays" if len(still) == 1 else " stay")
        + f" beyond {BALANCE_SIGMAS:g} se of the wall's shear stress with the seed scatter "
        "allowed for (each factor without the miss's own bin); this series' Delta uses "
        + ("that run" if n_runs == 1 else "those runs")
        + (
            ", and nothing here accounts for the unexplained ones."
            if flowing
            else ("'s u, not these bins' stresses" if other else "")
            + (
                "; centre binning of a layered packing is why: a centre-binned layered bin, "
                "and its neighbours, do not test the balance (the stresses are not recomputed "
                "with area-weighted or half-shifted bins in this version)."
                if zone
                else "."
            )
        )
    )


def _static(i: float | None) -> bool:
    """Whether a bin of inertial number ``i`` is in the static zone (I < :data:`STATIC_I`)."""
    return i is not None and i < STATIC_I


def misfit_twin_text(
    twins: Sequence[TwinPair], error_models: dict[str, Any], runs: Sequence[str]
) -> str:
    """For spin_model's misfit reading ("read as understated errors", referee 12, point 2):
    what the same-conditions replicates say of the block errors of u and omega (their
    overall seed-scatter factors, :func:`twin_factor`) and of nu and the static-zone
    stresses, and each misfitting run's AR(1) chi^2 of u and omega (``error_models``: run ->
    field -> ``ar1``, ``n``) divided by that factor squared; "" without twins."""
    from ...calibration import diagnostics as dg

    if not twins:
        return ""
    fu, fo = twin_factor(twins, "u", "all"), twin_factor(twins, "omega", "all")
    parts = []
    for t in twins:
        u, om = t.fields.get("u"), t.fields.get("omega")
        if u is None or om is None:
            continue
        stress = [
            f"{c} {f:.2g}"
            for c in ("nu", "sigma_yy", "sigma_xx")
            if (tf := t.fields.get(c)) is not None and (f := tf.factor("static")) is not None
        ]
        parts.append(
            f"{t.a} against {t.b}: u sum z^2 = {u.chi2:.3g} on {u.n} bins (factor "
            f"{u.factor():.2g}), omega {om.chi2:.3g} on {om.n} (factor {om.factor():.2g}, no bin "
            f"beyond {max(abs(v) for v in om.z):.2g} se)"
            + (f"; static-zone factors {', '.join(stress)}" if stress else "")
        )
    if not parts or fu is None or fo is None:
        return ""
    rescaled = []
    for name in runs:
        em = error_models.get(name) or {}
        for column, f in (("u", fu), ("omega", fo)):
            rec = em.get(column)
            if not isinstance(rec, dict) or not isinstance(rec.get("ar1"), int | float):
                continue
            chi2, n = float(rec["ar1"]) / f**2, int(rec["n"])
            p = dg.chi2_p_value(chi2, n)
            rescaled.append(
                f"{name} {column} {float(rec['ar1']):.3g} -> {chi2:.3g} on {n}"
                + ("" if p is None else f" (p = {p:.2g})")
            )
    return (
        " The same-conditions replicates (one cell, one V, two seeds) measure that error scale: "
        + "; ".join(parts)
        + ". So the block errors of nu and the static-zone stresses are understated by the "
        "static-zone factors (the reading's 'understated errors' holds there), while u's and "
        "omega's carry the scatter between seeds to within their factors, so the spin verdicts "
        "are not undercut; the joint fits' AR(1) chi^2 of u and omega with the errors inflated "
        f"by the replicates' factor (u {fu:.2g}, omega {fo:.2g}; at least 1): "
        + ("; ".join(rescaled) if rescaled else "none recorded")
        + "."
    )
