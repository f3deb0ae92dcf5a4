"""Gap series: the runs of one cell, material and wall at several gaps.

Two runs are in one series when they have the same cell, the same walls (the sidecars'
``wall`` and ``wall_fixed``), the same grains and contact law (``grains`` without the number
of grains, ``contact``), and the cell parameter that a claim holds fixed agrees within a
tolerance: plane shear's B (relative :data:`REL_TOL`, or both below :data:`ZERO_B`: no
gravity), Couette's R_i/H (relative :data:`REL_TOL`; the paper's Couette law holds R_i/H
fixed, so runs at one inner radius R_i/d and several gaps are separate series). The gap
itself is what varies. Several runs at one gap (a rate-check partner at another wall speed)
are replicates, named as such. A plane run whose two walls differ (the sidecar's ``wall_fixed``
or ``walls``, :func:`walls_differ`) is in no smooth-wall or rough-wall series: its
:attr:`Series.roughness` is None, and its walls are named both (:func:`wall_label`).

**One material.** The Delta verdicts' joint calibrations are made per material
(:func:`group_materials`), not per series: the series of one cell whose runs are of one
material (:func:`material_of`: the sidecar's ``material`` where it names one, else its
``grains`` without their number and its ``contact`` law, the label
:mod:`cosserat.calibration.data` gives, so that the engine shares the material parameters over
exactly these runs) form one :class:`Material`, whatever their walls and their held cell
parameter (B, R_i/H: cell parameters the models take from the metadata). Runs that give
neither are one unnamed material, as the engine takes them.
"""

from __future__ import annotations

import json
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

from ...analysis.corpus import Run

REL_TOL = 0.1
"""Relative tolerance on the held cell parameter (B, R_i/H) within one series [-]."""
ZERO_B = 0.05
"""B below this is 'no gravity' [-]."""


ROUGHNESS_OF_KIND = {"glued-grains": "fully-rough", "smooth-frictional": "smoother"}
"""The roughness class of a wall kind."""


def _kind(wall: Any) -> str | None:
    return str(wall.get("kind")) if isinstance(wall, dict) and wall.get("kind") else None


def walls_differ(run: Run) -> bool:
    """Whether the run's two walls are of different kinds (the sidecar's ``wall_fixed``
    against ``wall``, or its ``walls`` by position)."""
    fixed = _kind(run.meta.get("wall_fixed"))
    if fixed is not None and fixed != _kind(run.wall):
        return True
    walls = run.meta.get("walls")
    if isinstance(walls, dict):
        kinds = {_kind(w) for w in walls.values()} - {None}
        return len(kinds) > 1
    return False


def wall_label(run: Run) -> str:
    """The run's wall roughness, both walls named where they differ ("-" if unknown)."""
    if not walls_differ(run):
        return run.roughness or "-"
    moving = run.roughness or _kind(run.wall) or "?"
    fixed_kind = _kind(run.meta.get("wall_fixed"))
    if fixed_kind is None:  # only ``walls`` by position says they differ
        walls = run.meta.get("walls")
        assert isinstance(walls, dict)
        return ", ".join(
            f"{pos} {ROUGHNESS_OF_KIND.get(k, k)}"
            for pos, w in sorted(walls.items())
            if (k := _kind(w)) is not None
        )
    return f"moving {moving}, fixed {ROUGHNESS_OF_KIND.get(fixed_kind, fixed_kind)}"


def held(run: Run) -> tuple[str, float] | None:
    """(name, value) of the cell parameter a series holds fixed: B (plane), R_i/H (Couette)."""
    if run.cell == "plane":
        return "B", run.B
    if run.cell == "couette":
        return "Ri/H", float(run.Ri_d or 0.0) / run.gap_d
    return None


def _close(a: float, b: float, name: str) -> bool:
    if name == "B" and a < ZERO_B and b < ZERO_B:
        return True
    return abs(a - b) <= REL_TOL * max(abs(a), abs(b))


def _material(run: Run) -> str:
    """The walls, grains and contacts of a run, as one comparable string."""
    grains = run.meta.get("grains")
    if isinstance(grains, dict):
        grains = {k: v for k, v in grains.items() if k != "n"}
    record = {
        "wall": run.meta.get("wall"),
        "wall_fixed": run.meta.get("wall_fixed"),
        "grains": grains,
        "contact": run.meta.get("contact"),
        "material": run.meta.get("material"),
        "moving_wall": run.moving_wall,
    }
    return json.dumps(record, sort_keys=True, default=str)


def same_series(a: Run, b: Run) -> bool:
    """Whether two runs belong to one gap series (module docstring)."""
    if a.cell != b.cell or _material(a) != _material(b):
        return False
    ha, hb = held(a), held(b)
    if ha is None or hb is None:
        return ha == hb
    return _close(ha[1], hb[1], ha[0])


@dataclass(frozen=True)
class Series:
    """Runs of one gap series, by gap; ``key`` names the cell, wall and held parameter."""

    key: str
    runs: tuple[Run, ...]

    @property
    def cell(self) -> str:
        return self.runs[0].cell

    @property
    def roughness(self) -> str | None:
        """The walls' roughness; None where the two walls differ (no smooth or rough series)."""
        return None if walls_differ(self.runs[0]) else self.runs[0].roughness

    @property
    def gravity(self) -> bool:
        return self.cell == "plane" and self.runs[0].B >= ZERO_B

    def replicate_notes(self) -> tuple[str, ...]:
        """Where a series holds several runs at one gap (at different wall speeds: a rate
        check): they enter the power law as replicates, which is right only if the flow is
        rate-independent, as the model assumes."""
        notes = []
        gaps = [r.gap_d for r in self.runs]
        done: list[float] = []
        for g in gaps:
            if any(abs(g - x) <= 0.05 * g for x in done):
                continue
            done.append(g)
            same = [r for r in self.runs if abs(r.gap_d - g) <= 0.05 * g]
            if len(same) > 1:
                speeds = ", ".join(
                    f"{r.name} (wall speed {r.meta.get('wall_speed', '?')})" for r in same
                )
                notes.append(
                    f"H/d = {g:g} has {len(same)} runs, {speeds}: used as replicates, which "
                    "assumes the rate independence the model has (compare their profiles to "
                    "check it)"
                )
        return tuple(notes)


def series_key(runs: Sequence[Run]) -> str:
    r = runs[0]
    w = dict(r.wall)
    kind = w.pop("kind", "unknown wall")
    details = ", ".join(f"{k} = {v}" for k, v in sorted(w.items()))
    text = f"{r.cell}, {kind}" + (f" ({details})" if details else "")
    h = held(r)
    if h is not None:
        values = [hx[1] for x in runs if (hx := held(x)) is not None]  # a series shares h[0]
        lo, hi = min(values), max(values)
        text += f", {h[0]} = {lo:.3g}" + (f"-{hi:.3g}" if hi - lo > 1e-3 * max(hi, 1e-9) else "")
    return text


def group_runs(runs: Sequence[Run]) -> list[Series]:
    """The gap series of ``runs`` (module docstring), each sorted by gap; a run joins the
    first series whose first run it matches."""
    groups: list[list[Run]] = []
    for run in runs:
        for g in groups:
            if same_series(g[0], run):
                g.append(run)
                break
        else:
            groups.append([run])
    out = []
    for g in groups:
        g.sort(key=lambda r: r.gap_d)
        out.append(Series(series_key(g), tuple(g)))
    keys: dict[str, int] = {}
    for i, s in enumerate(out):  # two series the key cannot tell apart: number them
        if s.key in keys:
            out[i] = Series(f"{s.key} [{sum(1 for x in out[:i] if x.key == s.key) + 1}]", s.runs)
        keys[s.key] = i
    return sorted(out, key=lambda s: s.key)


def material_of(run: Run) -> str:
    """The label of a run's material (module docstring): the calibration engine's
    (:mod:`cosserat.calibration.data`), so that runs with one label share one set of material
    parameters there."""
    from ...calibration.data import _material_label

    return _material_label(run.meta)


@dataclass(frozen=True)
class Material:
    """The gap series of one cell and one material (module docstring); ``key`` names both."""

    key: str
    label: str
    series: tuple[Series, ...]

    @property
    def cell(self) -> str:
        return self.series[0].cell

    @property
    def runs(self) -> tuple[Run, ...]:
        """Every run of the material's series, series by series."""
        return tuple(r for s in self.series for r in s.runs)

    def wall_kinds(self) -> dict[str, list[str]]:
        """Wall kind (the sidecar's ``wall.kind``, "unknown wall" without one) -> its runs."""
        out: dict[str, list[str]] = {}
        for r in self.runs:
            out.setdefault(_kind(r.wall) or "unknown wall", []).append(r.name)
        return out


def group_materials(series: Sequence[Series]) -> list[Material]:
    """The materials of ``series`` (module docstring), each with its series in their order;
    series whose walls differ (:attr:`Series.roughness` None) are in none."""
    groups: dict[tuple[str, str], list[Series]] = {}
    for s in series:
        if walls_differ(s.runs[0]):
            continue
        groups.setdefault((s.cell, material_of(s.runs[0])), []).append(s)
    return [
        Material(f"{cell}, {label}", label, tuple(members))
        for (cell, label), members in sorted(groups.items())
    ]


def couette_note(series: Sequence[Series]) -> list[str]:
    """Couette series at one gap each whose runs share R_i/d: say why they are not paired."""
    singles = [s for s in series if s.cell == "couette" and len({r.gap_d for r in s.runs}) == 1]
    by_ri: dict[Any, list[Run]] = {}
    for s in singles:
        by_ri.setdefault(s.runs[0].Ri_d, []).extend(s.runs)
    notes = []
    for ri, runs in by_ri.items():
        if len({r.gap_d for r in runs}) > 1:
            names = ", ".join(f"{r.name} (R_i/H = {float(ri or 0) / r.gap_d:.3g})" for r in runs)
            notes.append(
                f"Couette runs at one inner radius R_i/d = {ri:g} and several gaps ({names}) "
                "are not a series: the paper's Couette law holds R_i/H fixed, and at fixed "
                "R_i/d the model's Delta hardly changes with the gap, so such a series tests "
                "nothing"
            )
    return notes
