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
delta_lower, K_lower, B, nu, m_wall [plane]; Ri [Couette]; eps. Defaults are the paper's
(:data:`cosserat.model.build.DEFAULTS`, from :mod:`cosserat.config`), and every case is built
by :func:`cosserat.model.build_problem`, as on the command line. ``rtol`` and ``f`` default to
``config.RTOL`` and ``config.DEFAULT_F``.

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

from .. import config
from .._atomic import atomic_open
from ..errors import CosseratError, InputError, ParameterError
from ..model import Problem, build_problem
from ..model.build import DEFAULTS, PARAMETERS
from ..numerics.runtime import process_pool

RESULTS = ("Delta", "wall_slip", "wall_omega", "wall_stress", "status", "message")


@dataclass
class SweepSpec:
    """A parsed sweep: the cases (parameter dicts) and how to run them."""

    cases: list[dict[str, Any]]
    rtol: float = config.RTOL
    f: float = config.DEFAULT_F
    output: str | None = None
    chunk: int = 64
    columns: list[str] = field(default_factory=list)


def _values(name: str, spec: Any) -> list[Any]:
    """The values of grid entry ``name``: a list, one value, or {geomspace|linspace = [a, b, n]}."""
    if isinstance(spec, list):
        if not spec:
            raise ParameterError(f"grid entry {name!r} is an empty list: give at least one value")
        return spec
    if isinstance(spec, dict) and len(spec) == 1:
        ((kind, args),) = spec.items()
        if kind in ("geomspace", "linspace") and isinstance(args, list) and len(args) == 3:
            a, b, n = args
            if (
                any(isinstance(v, bool) or not isinstance(v, int | float) for v in (a, b))
                or isinstance(n, bool)
                or not isinstance(n, int)
                or n < 1
            ):
                raise ParameterError(
                    f"grid entry {name!r}: {kind} = [a, b, n] needs numbers a, b and a whole "
                    f"number n >= 1; got {args!r}"
                )
            if kind == "geomspace" and (a == 0 or b == 0 or (a < 0) != (b < 0)):
                raise ParameterError(
                    f"grid entry {name!r}: geomspace needs a and b nonzero and of the same sign; "
                    f"got {args!r}"
                )
            fn = np.geomspace if kind == "geomspace" else np.linspace
            return [float(v) for v in fn(float(a), float(b), n)]
    if isinstance(spec, int | float | str):
        return [spec]
    raise ParameterError(
        f"grid entry {name!r} must be a list, a value, or {{geomspace|linspace = [a, b, n]}}; "
        f"got {spec!r}"
    )


def _table(where: str, value: Any) -> dict[str, Any]:
    if not isinstance(value, dict):
        raise ParameterError(
            f"[{where}] must be a table of parameter = value; got {type(value).__name__} {value!r}"
        )
    return value


def _number(key: str, value: Any, lo: float, hi: float, closed: bool = False) -> float:
    """A top-level number of the spec, ``lo < value < hi`` (``<=`` if ``closed``)."""
    if isinstance(value, bool) or not isinstance(value, int | float):
        raise ParameterError(f"{key} must be a number; got {value!r}")
    x = float(value)
    ok = lo <= x <= hi if closed else lo < x < hi
    if not ok:
        op = "<=" if closed else "<"
        raise ParameterError(f"{key} must satisfy {lo:g} {op} {key} {op} {hi:g}; got {x:g}")
    return x


def parse_spec(data: dict[str, Any]) -> SweepSpec:
    """Build a :class:`SweepSpec` from the parsed TOML (errors name the offending key).

    Raises
    ------
    ParameterError
        An unknown key or parameter, a table or grid entry of the wrong form, a case without
        eps, or ``rtol`` (within ``config.RTOL_RANGE``), ``f`` (0 < f < 1), ``chunk`` (>= 1) or
        ``output`` (a file name) out of bounds. A parameter *value* out of bounds is not an
        error here: that case gives a row with status "invalid".
    """
    known = {"geometry", "rtol", "f", "output", "chunk", "fixed", "grid", "cases"}
    unknown = set(data) - known
    if unknown:
        raise ParameterError(f"unknown top-level key(s) in the sweep spec: {sorted(unknown)}")
    fixed = dict(_table("fixed", data.get("fixed", {})))
    if "geometry" in data:
        fixed.setdefault("geometry", data["geometry"])
    grid = _table("grid", data.get("grid", {}))
    listed = data.get("cases", [])
    if not isinstance(listed, list):
        raise ParameterError(f"cases must be an array of tables ([[cases]]); got {listed!r}")
    listed = [_table("cases", c) for c in listed]
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
    rtol = _number("rtol", data.get("rtol", config.RTOL), *config.RTOL_RANGE, closed=True)
    f = _number("f", data.get("f", config.DEFAULT_F), 0.0, 1.0)
    chunk = data.get("chunk", 64)
    if isinstance(chunk, bool) or not isinstance(chunk, int) or chunk < 1:
        raise ParameterError(f"chunk must be a whole number >= 1; got {chunk!r}")
    output = data.get("output")
    if output is not None and (not isinstance(output, str) or not output.strip()):
        raise ParameterError(f"output must be a file name (.csv or .parquet); got {output!r}")
    return SweepSpec(cases, rtol, f, output, chunk, columns)


def load_spec(path: str | Path) -> SweepSpec:
    """Read and parse a sweep spec (TOML).

    Raises
    ------
    InputError
        The file cannot be read (missing, a directory, no permission, not text).
    ParameterError
        Not valid TOML, or a spec :func:`parse_spec` rejects.
    """
    try:
        text = Path(path).read_text()
    except OSError as exc:
        raise InputError(f"cannot read the sweep spec {path}: {_reason(exc)}") from None
    except UnicodeDecodeError:
        raise InputError(f"cannot read the sweep spec {path}: not a text (TOML) file") from None
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise ParameterError(f"{path}: not valid TOML: {exc}") from None
    return parse_spec(data)


def _reason(exc: OSError) -> str:
    """The operating system's reason, lower case ("no such file or directory")."""
    reason = exc.strerror or str(exc) or type(exc).__name__
    return reason[:1].lower() + reason[1:]


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
        except CosseratError as exc:  # build_problem raises ParameterError for any bad value
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
        try:
            client = Client(scheduler)
        except (OSError, ValueError, TypeError) as exc:  # includes timeouts and bad addresses
            raise InputError(
                f"cannot connect to the Dask scheduler at {scheduler!r}: {exc}"
            ) from None
        with client:
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


def check_table_format(path: str | Path) -> None:
    """Raise :class:`ParameterError` now if :func:`write_table` could not write this format
    (``.parquet`` without pyarrow), so that a long sweep does not fail at its end."""
    if Path(path).suffix == ".parquet":
        try:
            import pyarrow.parquet  # noqa: F401
        except ImportError:
            raise ParameterError(
                "writing .parquet needs pyarrow (pip install pyarrow); or write .csv"
            ) from None


def write_table(rows: Iterable[dict[str, Any]], path: str | Path, columns: Sequence[str]) -> Path:
    """Tidy table, one row per case: CSV, or Parquet for a ``.parquet`` path (pyarrow).

    Raises
    ------
    ParameterError
        ``.parquet`` without pyarrow installed.
    InputError
        The file cannot be written (no such folder, a directory, permission denied).
    """
    path = Path(path)
    cols = [*columns, *RESULTS]
    rows = list(rows)
    check_table_format(path)
    try:
        if path.suffix == ".parquet":
            import pyarrow as pa
            import pyarrow.parquet as pq

            table = pa.table({c: [r.get(c) for r in rows] for c in cols})
            pq.write_table(table, path)
            return path
        with atomic_open(path, newline="") as fh:
            writer = csv.writer(fh)
            writer.writerow(cols)
            for r in rows:
                writer.writerow(["" if r.get(c) is None else _fmt(r.get(c)) for c in cols])
    except OSError as exc:
        raise InputError(f"cannot write the sweep table {path}: {_reason(exc)}") from None
    return path


def _fmt(value: Any) -> str:
    if isinstance(value, float):
        return repr(value) if math.isfinite(value) else ""
    return str(value)
