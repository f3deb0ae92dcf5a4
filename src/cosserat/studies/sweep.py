"""Parameter sweeps: a grid or a list of cases from a TOML spec, one tidy row per case.

Spec (``cosserat sweep SPEC.toml``)::

    geometry = "plane"              # or "couette"; may also vary in [grid] or [[cases]]
    rtol = 1e-8                     # numerical tolerance (optional)
    f = 0.05                        # fraction defining Delta (optional)
    output = "sweep.csv"            # .csv, or .parquet if pyarrow is installed (optional)

    [fixed]                         # parameters common to every case
    phi = 28.5
    K = 0.5

    [grid]                          # Cartesian product
    delta = [10.0, 15.0, 20.0, "fully-rough"]
    eps = { geomspace = [1e-1, 1e-6, 50] }      # or linspace, or a list
    B = [0.0, 1.0]

    [[cases]]                       # and/or an explicit list (each merged over [fixed])
    eps = 0.01
    delta = 22.0

Parameters: phi, L, A [material]; delta, K [the moving wall; "fully-rough" allowed];
delta_lower, K_lower, B, nu, m_wall [plane]; Ri [Couette]; eps. Defaults are the paper's.

Every case gives a row: its parameters, Delta, wall_slip, wall_omega, wall_stress, and
``status`` ("ok"; "no-solution": the model has no real solution; "error": the solver could not
finish, e.g. a singular start on the yield bound; "invalid": a parameter out of bounds) with the
reason in ``message``: failed cases are recorded, never dropped. Cases run in chunks in local
worker processes, or on a Dask cluster (``scheduler="tcp://..."``); the rows are the same either
way.
"""

from __future__ import annotations

import csv
import itertools
import math
import tomllib
from collections.abc import Callable, Iterable, Sequence
from concurrent.futures import as_completed
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from ..errors import CosseratError, ParameterError
from ..model import CouetteFlow, PlaneShear, Problem
from ..model.parameters import FULLY_ROUGH, Material, Wall
from ..numerics.runtime import process_pool

DEFAULTS: dict[str, Any] = {
    "geometry": "plane",
    "phi": 28.5,
    "L": 10.0,
    "A": 1.0 / 3.0,
    "delta": 20.0,
    "K": 0.5,
    "B": 0.0,
    "nu": 1.0,
    "Ri": 1.0,
}
PARAMETERS = (
    "geometry",
    "phi",
    "L",
    "A",
    "delta",
    "K",
    "delta_lower",
    "K_lower",
    "B",
    "nu",
    "m_wall",
    "Ri",
    "eps",
)
RESULTS = ("Delta", "wall_slip", "wall_omega", "wall_stress", "status", "message")


@dataclass
class SweepSpec:
    """A parsed sweep: the cases (parameter dicts) and how to run them."""

    cases: list[dict[str, Any]]
    rtol: float = 1e-8
    f: float = 0.05
    output: str | None = None
    chunk: int = 64
    columns: list[str] = field(default_factory=list)


def _values(name: str, spec: Any) -> list[Any]:
    if isinstance(spec, list):
        return spec
    if isinstance(spec, dict) and len(spec) == 1:
        ((kind, args),) = spec.items()
        if kind in ("geomspace", "linspace") and isinstance(args, list) and len(args) == 3:
            fn = np.geomspace if kind == "geomspace" else np.linspace
            return [float(v) for v in fn(float(args[0]), float(args[1]), int(args[2]))]
    if isinstance(spec, int | float | str):
        return [spec]
    raise ParameterError(
        f"grid entry {name!r} must be a list, a value, or {{geomspace|linspace = [a, b, n]}}; "
        f"got {spec!r}"
    )


def parse_spec(data: dict[str, Any]) -> SweepSpec:
    """Build a :class:`SweepSpec` from the parsed TOML (errors name the offending key)."""
    known = {"geometry", "rtol", "f", "output", "chunk", "fixed", "grid", "cases"}
    unknown = set(data) - known
    if unknown:
        raise ParameterError(f"unknown top-level key(s) in the sweep spec: {sorted(unknown)}")
    fixed = dict(data.get("fixed", {}))
    if "geometry" in data:
        fixed.setdefault("geometry", data["geometry"])
    grid = data.get("grid", {})
    listed = data.get("cases", [])
    for where, table in [("fixed", fixed), ("grid", grid), *[("cases", c) for c in listed]]:
        bad = set(table) - set(PARAMETERS)
        if bad:
            raise ParameterError(
                f"unknown parameter(s) {sorted(bad)} in [{where}]; known: {', '.join(PARAMETERS)}"
            )
    cases: list[dict[str, Any]] = []
    if grid:
        names = list(grid)
        for combo in itertools.product(*(_values(n, grid[n]) for n in names)):
            cases.append({**DEFAULTS, **fixed, **dict(zip(names, combo, strict=True))})
    cases += [{**DEFAULTS, **fixed, **c} for c in listed]
    if not grid and not listed:
        cases.append({**DEFAULTS, **fixed})
    for i, c in enumerate(cases):
        if "eps" not in c:
            raise ParameterError(f"case {i}: no eps (give it in [fixed], [grid] or [[cases]])")
    columns = [p for p in PARAMETERS if any(p in c for c in cases)]
    return SweepSpec(
        cases,
        float(data.get("rtol", 1e-8)),
        float(data.get("f", 0.05)),
        data.get("output"),
        int(data.get("chunk", 64)),
        columns,
    )


def load_spec(path: str | Path) -> SweepSpec:
    try:
        data = tomllib.loads(Path(path).read_text())
    except tomllib.TOMLDecodeError as exc:
        raise ParameterError(f"{path}: not valid TOML: {exc}") from None
    return parse_spec(data)


def build_problem(case: dict[str, Any]) -> Problem:
    """The problem of one case (raises ParameterError naming the bad value)."""
    material = Material(case["phi"], L=case["L"], A=case["A"])
    delta = FULLY_ROUGH if str(case["delta"]).lower() in ("fully-rough", "rough") else case["delta"]
    wall = Wall(delta, case["K"])
    if case["geometry"] == "couette":
        return CouetteFlow(material=material, wall=wall, eps=case["eps"], Ri=case["Ri"])
    if case["geometry"] != "plane":
        raise ParameterError(f"geometry must be 'plane' or 'couette'; got {case['geometry']!r}")
    lower = None
    if case.get("delta_lower") is not None or case.get("K_lower") is not None:
        dl = case.get("delta_lower", case["delta"])
        dl = FULLY_ROUGH if str(dl).lower() in ("fully-rough", "rough") else dl
        lower = Wall(dl, case.get("K_lower", case["K"]))
    return PlaneShear(
        material=material,
        upper=wall,
        lower=lower,
        eps=case["eps"],
        B=case["B"],
        nu=case["nu"],
        m_fixed_wall=case.get("m_wall"),
    )


def run_chunk(cases: Sequence[dict[str, Any]], rtol: float, f: float) -> list[dict[str, Any]]:
    """Solve a chunk of cases with the compiled batch kernel; one row per case, in order."""
    from ..routes.numerical import wall_quantities

    rows: list[dict[str, Any]] = []
    problems: list[Problem] = []
    slots: list[int] = []
    for case in cases:
        row = dict(case)
        try:
            problems.append(build_problem(case))
            slots.append(len(rows))
        except (CosseratError, KeyError, TypeError) as exc:
            row.update(status="invalid", message=" ".join(str(exc).split()))
        rows.append(row)
    for slot, res in zip(slots, wall_quantities(problems, rtol=rtol, f=f), strict=True):
        rows[slot].update(
            Delta=res.Delta,
            wall_slip=res.wall_slip,
            wall_omega=res.wall_omega,
            wall_stress=res.wall_stress,
            status=res.status,
            message=" ".join(res.message.split()),
        )
    return rows


def run_sweep(
    spec: SweepSpec,
    workers: int | None = None,
    scheduler: str | None = None,
    progress: Callable[[int, int], None] | None = None,
) -> list[dict[str, Any]]:
    """Run every case; rows in the spec's order.

    ``workers``: local processes (default: all cores; 1 runs in this process).
    ``scheduler``: address of a Dask ``distributed`` scheduler, used instead of local processes.
    """
    chunks = [spec.cases[i : i + spec.chunk] for i in range(0, len(spec.cases), spec.chunk)]
    results: list[list[dict[str, Any]] | None] = [None] * len(chunks)
    done = 0

    def collect(i: int, rows: list[dict[str, Any]]) -> None:
        nonlocal done
        results[i] = rows
        done += len(rows)
        if progress:
            progress(done, len(spec.cases))

    if scheduler is not None:
        try:
            from distributed import Client
            from distributed import as_completed as dask_completed
        except ImportError:  # pragma: no cover - depends on the installation
            raise ParameterError(
                "--scheduler needs Dask: pip install 'cosserat-granular[dask]'"
            ) from None
        with Client(scheduler) as client:
            futures = [client.submit(run_chunk, c, spec.rtol, spec.f, pure=False) for c in chunks]
            index = {fut.key: i for i, fut in enumerate(futures)}
            for fut in dask_completed(futures):
                collect(index[fut.key], fut.result())
    elif (workers or 0) == 1 or len(chunks) == 1:
        for i, c in enumerate(chunks):
            collect(i, run_chunk(c, spec.rtol, spec.f))
    else:
        with process_pool(workers) as pool:
            futs = {pool.submit(run_chunk, c, spec.rtol, spec.f): i for i, c in enumerate(chunks)}
            for fut in as_completed(futs):
                collect(futs[fut], fut.result())
    return [row for rows in results for row in (rows or [])]


def write_table(rows: Iterable[dict[str, Any]], path: str | Path, columns: Sequence[str]) -> Path:
    """Tidy table, one row per case: CSV, or Parquet for a ``.parquet`` path (pyarrow)."""
    path = Path(path)
    cols = [*columns, *RESULTS]
    rows = list(rows)
    if path.suffix == ".parquet":
        try:
            import pyarrow as pa
            import pyarrow.parquet as pq
        except ImportError:
            raise ParameterError(
                "writing .parquet needs pyarrow (pip install pyarrow); or write .csv"
            ) from None
        table = pa.table({c: [r.get(c) for r in rows] for c in cols})
        pq.write_table(table, path)
        return path
    with path.open("w", newline="") as fh:
        writer = csv.writer(fh)
        writer.writerow(cols)
        for r in rows:
            writer.writerow(["" if r.get(c) is None else _fmt(r.get(c)) for c in cols])
    return path


def _fmt(value: Any) -> str:
    if isinstance(value, float):
        return repr(value) if math.isfinite(value) else ""
    return str(value)
