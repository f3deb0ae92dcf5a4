"""Parameter sweeps: a grid or a list of cases from a TOML spec, one tidy row per case.

Spec (``cosserat sweep SPEC.toml``)::

    model = "cosserat"              # any registered rheology (cosserat, mui, ngf, ...);
                                    #   may also vary in [grid] or [[cases]]
    cell = "plane"                  # any registered cell (plane, couette, channel, ...);
                                    #   "geometry" is the same key; may also vary
    rtol = 1e-8                     # tolerance of the Cosserat model's kernels (optional)
    f = 0.05                        # fraction defining Delta (optional)
    output = "sweep.csv"            # .csv, or .parquet if pyarrow is installed (optional)
    max_cases = 1000000             # refuse a spec of more cases (optional; the default)

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

Parameters: the command-line keys of the case's model on its cell
(:func:`cosserat.model.problem_parameters`; ``cosserat models`` lists them): for the Cosserat
model phi, L, A, delta, K ("fully-rough" allowed), delta_lower, K_lower, m_wall (plane); for
mu(I) mu_s, mu_2, I_0; for NGF mu_s, b, A, mu_2, fluidity_bc; and the cell's eps, B, nu
(plane, channel), Ri (Couette), I_w, stress_ratio (the drive of mu(I) and NGF). Absent keys take
their declared defaults, and every case is built by :func:`cosserat.model.make_problem`, as on
the command line; a key the case's model or cell does not have makes that case's row
"invalid". ``rtol`` and ``f`` default to ``config.RTOL`` and ``config.DEFAULT_F``.

The number of cases is counted from the spec before any case is made, and a spec of more than
``max_cases`` (default :data:`MAX_CASES`, one million: about a gigabyte of memory for the cases
and their rows, and hours of work on a few cores) is refused with its count; give a larger
``max_cases`` at the top of the spec to run it anyway.

Every case gives a row: its parameters (the declared defaults filled in), Delta, wall_slip,
wall_omega (empty for a rheology without grain spin), wall_stress, and ``status`` ("ok";
"no-solution": the model has no real solution; "error": the solver could not finish, e.g. a
singular start on the yield bound; "invalid": a parameter out of bounds or of another model)
with the reason in ``message``: failed cases are recorded, never dropped. The Cosserat model on
plane shear and Couette flow runs on the compiled batch kernel, every other case by its
numerical route (:func:`cosserat.routes.walls.wall_quantities`). Cases run in chunks in local
worker processes, or on a Dask cluster (``scheduler="tcp://..."``); the rows are the same either
way, and a chunk whose Dask worker is lost is run again.

:func:`run_sweep_to_table` (``cosserat sweep``) appends each finished chunk of rows to a journal
``<table>.part`` beside the table, flushed at once (synced to disk every second), and writes the
table atomically at the end: an interrupted sweep keeps every finished row, and ``resume=True``
(``--resume``) computes only the cases whose rows are missing (matched by their parameters).
"""

from __future__ import annotations

import csv
import io
import itertools
import math
import os
import time
import tomllib
from collections.abc import Callable, Hashable, Iterable, Sequence
from concurrent.futures import as_completed
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from .. import config
from .._atomic import atomic_open
from .._text import read_text
from ..errors import CosseratError, InputError, ParameterError
from ..model import Problem, make_problem
from ..model.build import problem_parameters
from ..numerics.runtime import worker_processes

DEFAULT_MODEL, DEFAULT_CELL = "cosserat", "plane"
"""The model and cell of a case that names none."""

RESULTS = ("Delta", "wall_slip", "wall_omega", "wall_stress", "status", "message")

MAX_CASES = 1_000_000
"""Most cases a spec may have unless it gives ``max_cases`` (each case and its row take about a
kilobyte in memory, so a grid of 10^12 cases would exhaust any machine before it starts)."""


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


def _count(spec: Any) -> int:
    """How many values a grid entry gives (:func:`_values`), counted without making them; a
    malformed entry counts 1 (then :func:`_values` says what is wrong with it)."""
    if isinstance(spec, list):
        return len(spec)
    if isinstance(spec, dict) and len(spec) == 1:
        ((kind, args),) = spec.items()
        if kind in ("geomspace", "linspace") and isinstance(args, list) and len(args) == 3:
            n = args[2]
            if isinstance(n, int) and not isinstance(n, bool) and n >= 1:
                return n
    return 1


def _check_size(grid: dict[str, Any], listed: int, limit: Any) -> None:
    """Refuse a spec of more than ``limit`` cases, counted before any case is made."""
    if isinstance(limit, bool) or not isinstance(limit, int) or limit < 1:
        raise ParameterError(f"max_cases must be a whole number >= 1; got {limit!r}")
    counts = {name: _count(spec) for name, spec in grid.items()}
    total = (math.prod(counts.values()) if grid else 0) + listed
    if total > limit:
        product = " x ".join(f"{n} {name}" for name, n in counts.items())
        parts = ([product] if grid else []) + ([f"{listed} [[cases]]"] if listed else [])
        raise ParameterError(
            f"the sweep spec has {total:,} cases ({' + '.join(parts)}), more than max_cases = "
            f"{limit:,}: each case takes about a kilobyte of memory and some milliseconds of "
            f"work; make the grid smaller, or put max_cases = {total} at the top of the spec "
            "to run it anyway"
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
        An unknown key or parameter, a table or grid entry of the wrong form, more cases than
        ``max_cases`` (default :data:`MAX_CASES`), a case without eps, or ``rtol`` (within
        ``config.RTOL_RANGE``), ``f`` (0 < f < 1), ``chunk`` (>= 1) or ``output`` (a file
        name) out of bounds. A parameter *value* out of bounds is not an
        error here: that case gives a row with status "invalid".
    """
    known = {
        "model",
        "cell",
        "geometry",
        "rtol",
        "f",
        "output",
        "chunk",
        "max_cases",
        "fixed",
        "grid",
        "cases",
    }
    unknown = set(data) - known
    if unknown:
        raise ParameterError(f"unknown top-level key(s) in the sweep spec: {sorted(unknown)}")
    fixed = _named(dict(_table("fixed", data.get("fixed", {}))), "fixed")
    top = _named({k: data[k] for k in ("model", "cell", "geometry") if k in data}, "the spec")
    for key, value in top.items():
        fixed.setdefault(key, value)
    grid = _named(dict(_table("grid", data.get("grid", {}))), "grid")
    listed = data.get("cases", [])
    if not isinstance(listed, list):
        raise ParameterError(f"cases must be an array of tables ([[cases]]); got {listed!r}")
    listed = [_named(dict(_table("cases", c)), "cases") for c in listed]
    allowed = parameter_keys()
    for where, table in [("fixed", fixed), ("grid", grid), *[("cases", c) for c in listed]]:
        bad = set(table) - set(allowed)
        if bad:
            raise ParameterError(
                f"unknown parameter(s) {sorted(bad)} in [{where}]; known: {', '.join(allowed)}"
            )
    _check_size(grid, len(listed), data.get("max_cases", MAX_CASES))
    cases: list[dict[str, Any]] = []
    if grid:
        names = list(grid)
        for combo in itertools.product(*(_values(n, grid[n]) for n in names)):
            cases.append({**fixed, **dict(zip(names, combo, strict=True))})
    cases += [{**fixed, **c} for c in listed]
    if not grid and not listed:
        cases.append(dict(fixed))
    cases = [_with_defaults(c) for c in cases]
    for i, c in enumerate(cases):
        if "eps" not in c:
            raise ParameterError(f"case {i}: no eps (give it in [fixed], [grid] or [[cases]])")
    columns = [p for p in allowed if any(p in c for c in cases)]
    rtol = _number("rtol", data.get("rtol", config.RTOL), *config.RTOL_RANGE, closed=True)
    f = _number("f", data.get("f", config.DEFAULT_F), 0.0, 1.0)
    chunk = data.get("chunk", 64)
    if isinstance(chunk, bool) or not isinstance(chunk, int) or chunk < 1:
        raise ParameterError(f"chunk must be a whole number >= 1; got {chunk!r}")
    output = data.get("output")
    if output is not None and (not isinstance(output, str) or not output.strip()):
        raise ParameterError(f"output must be a file name (.csv or .parquet); got {output!r}")
    return SweepSpec(cases, rtol, f, output, chunk, columns)


def parameter_keys() -> list[str]:
    """Every key a case may have: ``model``, ``geometry`` and the command-line keys of every
    registered model on every cell it has (:func:`cosserat.model.problem_parameters`), in the
    order of the registries."""
    from ..routes import RHEOLOGIES, cells_for

    keys = ["model", "geometry"]
    for model in RHEOLOGIES:
        for cell in cells_for(model):
            keys += list(problem_parameters(model, cell))
    return list(dict.fromkeys(keys))


def _named(table: dict[str, Any], where: str) -> dict[str, Any]:
    """``cell`` is another name of ``geometry`` (not both)."""
    if "cell" in table:
        if "geometry" in table:
            raise ParameterError(f"give cell or geometry in [{where}], not both")
        table["geometry"] = table.pop("cell")
    return table


def _with_defaults(case: dict[str, Any]) -> dict[str, Any]:
    """``case`` with its model, cell and the declared defaults of their parameters filled in
    (the row shows the values the case ran with); a case naming an unknown model or cell is
    left as it is (its row says why it is invalid)."""
    out = {"model": DEFAULT_MODEL, "geometry": DEFAULT_CELL, **case}
    try:
        declared = problem_parameters(str(out["model"]), str(out["geometry"]))
    except CosseratError:
        return out
    for key, p in declared.items():
        if key not in out and p.has_default and p.default is not None:
            out[key] = p.default
    return out


def case_problem(case: dict[str, Any]) -> Problem:
    """The problem of one case (:func:`cosserat.model.make_problem`).

    Raises
    ------
    ParameterError
        An unknown model or cell, a key the case's model or cell does not have, a value out of
        its bounds.
    """
    values = {k: v for k, v in case.items() if k not in ("model", "geometry")}
    return make_problem(
        str(case.get("model", DEFAULT_MODEL)), str(case.get("geometry", DEFAULT_CELL)), values
    )


def load_spec(path: str | Path) -> SweepSpec:
    """Read and parse a sweep spec (TOML).

    Raises
    ------
    InputError
        The file cannot be read (missing, a directory, no permission, not UTF-8 text).
    ParameterError
        Not valid TOML, or a spec :func:`parse_spec` rejects.
    """
    try:
        text = read_text(path, f"cannot read the sweep spec {path}")  # UTF-8, as TOML is
    except OSError as exc:
        raise InputError(f"cannot read the sweep spec {path}: {_reason(exc)}") from None
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
    """Solve a chunk of cases (:func:`cosserat.routes.walls.wall_quantities`: the compiled
    batch kernel where it applies); one row per case, in order."""
    from ..routes.walls import wall_quantities

    rows: list[dict[str, Any]] = []
    problems: list[Problem] = []
    slots: list[int] = []
    for case in cases:
        row = dict(case)
        try:
            problems.append(case_problem(case))
            slots.append(len(rows))
        except CosseratError as exc:  # make_problem raises ParameterError for any bad value
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


def _chunks(cases: Sequence[dict[str, Any]], size: int) -> list[list[dict[str, Any]]]:
    return [list(cases[i : i + size]) for i in range(0, len(cases), size)]


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
    chunks = _chunks(spec.cases, spec.chunk)
    results: list[list[dict[str, Any]] | None] = [None] * len(chunks)

    def keep(i: int, rows: list[dict[str, Any]]) -> None:
        results[i] = rows

    run_chunks(chunks, spec.rtol, spec.f, keep, workers, scheduler, progress)
    return [row for rows in results for row in (rows or [])]


MAX_RESUBMITS = 3
"""How often a chunk whose Dask worker was lost is submitted again (beyond Dask's own retries)."""


def run_chunks(
    chunks: Sequence[Sequence[dict[str, Any]]],
    rtol: float,
    f: float,
    on_rows: Callable[[int, list[dict[str, Any]]], None],
    workers: int | None = None,
    scheduler: str | None = None,
    progress: Callable[[int, int], None] | None = None,
) -> None:
    """Solve ``chunks`` of cases, calling ``on_rows(i, rows)`` in this process as chunk ``i``
    finishes (in completion order, exactly once per chunk).

    On a Dask cluster a chunk whose worker dies is run again: Dask reschedules the tasks of a
    lost worker itself, and a chunk that Dask gives up on (``KilledWorker``) is resubmitted up to
    :data:`MAX_RESUBMITS` times. Local processes are stopped at once on an interruption (Ctrl-C,
    SIGTERM; :func:`cosserat.numerics.runtime.worker_processes`) and end by themselves if this
    process is killed: the chunks already passed to ``on_rows`` are all that is kept.
    """
    total = sum(len(c) for c in chunks)
    done = 0

    def collect(i: int, rows: list[dict[str, Any]]) -> None:
        nonlocal done
        on_rows(i, rows)
        done += len(rows)
        if progress:
            progress(done, total)

    if not chunks:
        return
    if scheduler is not None:
        _run_on_dask(chunks, rtol, f, collect, scheduler)
    elif (workers or 0) == 1 or len(chunks) == 1:
        for i, c in enumerate(chunks):
            collect(i, run_chunk(c, rtol, f))
    else:
        with worker_processes(workers) as pool:  # stopped at once on an interruption
            futs = {pool.submit(run_chunk, c, rtol, f): i for i, c in enumerate(chunks)}
            for fut in as_completed(futs):
                collect(futs[fut], fut.result())


def _run_on_dask(
    chunks: Sequence[Sequence[dict[str, Any]]],
    rtol: float,
    f: float,
    collect: Callable[[int, list[dict[str, Any]]], None],
    scheduler: str,
) -> None:
    try:
        from distributed import Client, KilledWorker
        from distributed import as_completed as dask_completed
    except ImportError:  # pragma: no cover - depends on the installation
        raise ParameterError(
            "--scheduler needs Dask: pip install 'cosserat-granular[dask]'"
        ) from None
    try:
        client = Client(scheduler)
    except (OSError, ValueError, TypeError) as exc:  # includes timeouts and bad addresses
        raise InputError(f"cannot connect to the Dask scheduler at {scheduler!r}: {exc}") from None
    with client:
        index: dict[Hashable, int] = {}  # a dask key: str, int, float or a tuple of them
        tries = [0] * len(chunks)

        def submit(i: int) -> Any:
            fut = client.submit(run_chunk, list(chunks[i]), rtol, f, pure=False)
            index[fut.key] = i
            return fut

        pending = dask_completed([submit(i) for i in range(len(chunks))])
        for fut in pending:
            i = index.pop(fut.key)
            try:
                rows = fut.result()
            except KilledWorker:
                tries[i] += 1
                if tries[i] > MAX_RESUBMITS:
                    raise
                pending.add(submit(i))
                continue
            collect(i, rows)


# --------------------------------------------------------------------------- resumable tables
def journal_path(path: str | Path) -> Path:
    """The journal of an unfinished sweep writing ``path``: ``<path>.part`` beside it."""
    path = Path(path)
    return path.with_name(path.name + ".part")


def _cell(value: Any) -> str:
    """A value as the sweep table writes it (the empty string for None, NaN or inf)."""
    return "" if value is None else _fmt(value)


def case_key(case: dict[str, Any], columns: Sequence[str]) -> tuple[str, ...]:
    """What identifies a case's row: its parameter cells as written in the table."""
    return tuple(_cell(case.get(c)) for c in columns)


def _complete_rows(path: Path, header: list[str]) -> tuple[list[list[str]], int]:
    """The complete rows of a table or journal (a last line without its newline, cut by a
    killed process, is left out) and the byte length they span.

    Raises
    ------
    InputError
        The file cannot be read, or its header is not ``header`` (another spec's table).
    """
    try:
        data = path.read_bytes()
    except OSError as exc:
        raise InputError(f"cannot read {path}: {_reason(exc)}") from None
    end = data.rfind(b"\n") + 1
    try:
        text = data[:end].decode("utf-8")
    except UnicodeDecodeError:
        raise InputError(f"cannot resume from {path}: not a text (CSV) file") from None
    lines = list(csv.reader(io.StringIO(text, newline="")))
    if not lines:
        return [], 0
    if lines[0] != header:
        raise InputError(
            f"cannot resume from {path}: its columns ({', '.join(lines[0])}) are not this "
            f"sweep's ({', '.join(header)}); delete it or write to another --out"
        )
    return [row for row in lines[1:] if len(row) == len(header)], end


JOURNAL_SYNC = 1.0
"""Seconds between the journal's syncs to disk (each chunk is flushed to the operating system at
once, which is all a killed process needs; the sync bounds what a crash of the machine loses)."""


@dataclass
class SweepRun:
    """The outcome of :func:`run_sweep_to_table`."""

    rows: list[dict[str, Any]]
    path: Path
    reused: int
    computed: int


def run_sweep_to_table(
    spec: SweepSpec,
    path: str | Path,
    *,
    resume: bool = False,
    workers: int | None = None,
    scheduler: str | None = None,
    progress: Callable[[int, int], None] | None = None,
) -> SweepRun:
    """Run a sweep into the table ``path`` so that an interruption loses no finished row.

    Every finished chunk of rows is appended to the journal :func:`journal_path` (``<path>.part``,
    a CSV with the table's columns) and flushed at once (synced to disk every
    :data:`JOURNAL_SYNC` seconds); when all cases are done the
    table is written atomically in the spec's order and the journal removed. An interrupted run
    (Ctrl-C, a killed process or machine) thus leaves every finished row in the journal, and
    ``resume=True`` reuses the rows found in the journal and in an existing CSV table at
    ``path``, keyed by their case parameters (:func:`case_key`), and computes only the rest.
    The finished table is the same as an uninterrupted run's.

    Raises
    ------
    InputError
        A journal with rows exists and ``resume`` is False (the rows of an unfinished run; a
        journal with its header alone holds nothing and is replaced), a
        journal or table to resume from belongs to a sweep with other columns, or a file
        cannot be read or written.
    """
    path = Path(path)
    check_table_format(path)
    journal = journal_path(path)
    header = [*spec.columns, *RESULTS]
    if not resume and _holds_rows(journal):
        raise InputError(
            f"{journal} holds the finished rows of an interrupted sweep: run again with "
            f"--resume to finish it, or delete it to start again"
        )
    found: list[list[str]] = []
    length = 0
    if resume:
        if path.suffix == ".csv" and path.is_file():
            found += _complete_rows(path, header)[0]
        if journal.is_file():
            journal_rows, length = _complete_rows(journal, header)
            found += journal_rows
    stored: dict[tuple[str, ...], list[dict[str, Any]]] = {}
    for cells in found:
        row = {c: (None if v == "" else v) for c, v in zip(header, cells, strict=True)}
        if path.suffix == ".parquet":
            row = {c: _typed(v) for c, v in row.items()}
        stored.setdefault(tuple(cells[: len(spec.columns)]), []).append(row)
    slots: list[dict[str, Any] | None] = []
    pending: list[int] = []
    for i, case in enumerate(spec.cases):
        same = stored.get(case_key(case, spec.columns))
        slots.append(same.pop(0) if same else None)
        if slots[-1] is None:
            pending.append(i)
    reused = len(spec.cases) - len(pending)
    try:
        with journal.open("r+b" if length else "wb") as fh:
            fh.truncate(length)  # a line cut by a kill goes; the finished rows stay
            fh.seek(length)
            if not length:
                fh.write(_csv_lines([header]))
            chunks = [pending[i : i + spec.chunk] for i in range(0, len(pending), spec.chunk)]

            synced = [time.monotonic()]

            def keep(k: int, rows: list[dict[str, Any]]) -> None:
                fh.write(_csv_lines([[_cell(r.get(c)) for c in header] for r in rows]))
                fh.flush()  # in the operating system now: a killed process loses nothing
                if time.monotonic() - synced[0] > JOURNAL_SYNC:  # and on disk, every second
                    os.fsync(fh.fileno())
                    synced[0] = time.monotonic()
                for slot, row in zip(chunks[k], rows, strict=True):
                    slots[slot] = row

            run_chunks(
                [[spec.cases[i] for i in c] for c in chunks],
                spec.rtol,
                spec.f,
                keep,
                workers,
                scheduler,
                None if progress is None else lambda i, n: progress(reused + i, reused + n),
            )
    except OSError as exc:
        _drop_if_empty(journal, length)
        raise InputError(f"cannot write the sweep journal {journal}: {_reason(exc)}") from None
    except BaseException:
        _drop_if_empty(journal, length)  # a sweep that failed before any row keeps nothing
        raise
    rows = [r for r in slots if r is not None]
    write_table(rows, path, spec.columns)
    journal.unlink(missing_ok=True)
    return SweepRun(rows, path, reused, len(pending))


def _holds_rows(journal: Path) -> bool:
    """True if ``journal`` exists and holds anything beyond its header line (rows to keep)."""
    try:
        data = journal.read_bytes()
    except FileNotFoundError:
        return False
    except OSError:
        return True  # cannot tell: let the caller refuse rather than lose rows
    first = data.find(b"\n")
    return first >= 0 and bool(data[first + 1 :].strip())


def _drop_if_empty(journal: Path, length: int) -> None:
    """Delete the journal this run started (``length`` 0) if it holds no row."""
    if not length and not _holds_rows(journal):
        journal.unlink(missing_ok=True)


def _csv_lines(rows: Iterable[Sequence[str]]) -> bytes:
    buf = io.StringIO(newline="")
    csv.writer(buf, lineterminator="\n").writerows(rows)
    return buf.getvalue().encode("utf-8")


def _typed(value: str | None) -> Any:
    """A stored cell back as a number where it is one (for Parquet tables)."""
    if value is None:
        return None
    try:
        return float(value)
    except ValueError:
        return value


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
    if isinstance(value, float):  # a NumPy float too: written as a plain number
        return repr(float(value)) if math.isfinite(value) else ""
    return str(value)
