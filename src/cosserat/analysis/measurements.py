"""Measured velocity profiles: the file format, reading it, and where its points sit in the model.

Minimal format (always accepted): a CSV with the header ``distance_d,u_over_uw`` and an optional
third column ``u_err``::

    distance_d,u_over_uw,u_err
    0.5,0.81,0.02
    1.5,0.52,0.02

* ``distance_d``: distance of the point from the moving wall's surface, in grain diameters [-];
* ``u_over_uw``: grain velocity divided by the moving wall's velocity [-] (1 = no slip);
* ``u_err``: optional 1-sigma uncertainty of ``u_over_uw`` [-].

Richer forms:

* instead of ``distance_d``: ``distance_xi`` (fraction of the gap) or ``distance_m`` (metres, with
  ``d_p`` given); instead of ``u_over_uw``: ``u_m_s`` (m/s, with ``wall_speed`` given), and then
  ``u_err_m_s``;
* a header block of ``# key: value`` lines before the column names, describing the cell:
  ``geometry`` (plane | couette), ``eps``, ``Ri``, ``B``, ``nu``, ``gap`` [m], ``R_i`` [m],
  ``d_p`` [m], ``wall_speed`` [m/s], ``wall`` (where the wall is taken, e.g. "outer edge of the
  glued grain layer"), ``label``, ``synthetic`` (true for made-up data), ``source``.

Malformed input raises :class:`MeasurementError` naming the line and the column; no row is
dropped silently.
"""

from __future__ import annotations

import csv
import io
import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from .._atomic import atomic_open
from .._text import read_text
from ..errors import CosseratError
from ..model.constitutive import FloatArray

DISTANCE_COLUMNS = ("distance_d", "distance_xi", "distance_m")
VELOCITY_COLUMNS = ("u_over_uw", "u_m_s")
ERROR_COLUMNS = {"u_over_uw": "u_err", "u_m_s": "u_err_m_s"}
HEADER_KEYS = {
    "geometry",
    "eps",
    "ri",
    "b",
    "nu",
    "gap",
    "r_i",
    "d_p",
    "wall_speed",
    "wall",
    "label",
    "synthetic",
    "source",
}


class MeasurementError(CosseratError, ValueError):
    """A measured profile could not be read; the message names the line and the column."""


@dataclass(frozen=True)
class MeasuredProfile:
    """A measured velocity profile in the package's variables.

    Attributes
    ----------
    distance_d : ndarray
        Distance from the moving wall in grain diameters [-].
    u_over_uw : ndarray
        Velocity over the moving wall's velocity [-].
    u_err : ndarray or None
        1-sigma uncertainty of ``u_over_uw`` [-].
    meta : dict
        The header block (cell description), keys lower-case.
    """

    distance_d: FloatArray
    u_over_uw: FloatArray
    u_err: FloatArray | None = None
    meta: dict[str, Any] = field(default_factory=dict)

    def __post_init__(self) -> None:
        d = np.asarray(self.distance_d, dtype=float)
        u = np.asarray(self.u_over_uw, dtype=float)
        if d.ndim != 1 or d.shape != u.shape:
            raise MeasurementError("distance and velocity must be 1-D arrays of the same length")
        if d.size == 0:
            raise MeasurementError("no points: a measured profile needs at least one")
        if self.u_err is not None:
            e = np.asarray(self.u_err, dtype=float)
            if e.shape != d.shape:
                raise MeasurementError("u_err must have one value per point")
            if np.any(~np.isfinite(e)) or np.any(e <= 0):
                raise MeasurementError("u_err must be finite and > 0 for every point")
            object.__setattr__(self, "u_err", e)
        if np.any(~np.isfinite(d)) or np.any(~np.isfinite(u)):
            raise MeasurementError("distances and velocities must be finite")
        if np.any(d < 0):
            raise MeasurementError("distances from the moving wall must be >= 0")
        object.__setattr__(self, "distance_d", d)
        object.__setattr__(self, "u_over_uw", u)

    @property
    def label(self) -> str:
        base = str(self.meta.get("label", "measured"))
        return base + " (synthetic)" if self.is_synthetic and "synthetic" not in base else base

    @property
    def is_synthetic(self) -> bool:
        return str(self.meta.get("synthetic", "false")).lower() in ("1", "true", "yes")

    def xi(self, eps: float, moving_wall: float = 0.0) -> FloatArray:
        """Positions in the model's xi for grain size ratio eps; the moving wall at
        ``moving_wall`` (0 for the inner cylinder, 1 for the upper plate) [-]."""
        d = self.distance_d * eps
        if np.any(d > 1.0 + 1e-12):
            raise MeasurementError(
                f"a point lies {self.distance_d.max():g} grain diameters from the wall, beyond "
                f"the gap of {1 / eps:g} grain diameters (eps = {eps:g})"
            )
        return d if moving_wall == 0.0 else 1.0 - d

    @property
    def n(self) -> int:
        return int(self.distance_d.size)


def _number(text: str, line: int, column: str) -> float:
    try:
        value = float(text)
    except ValueError:
        raise MeasurementError(
            f"line {line}, column {column!r}: {text!r} is not a number"
        ) from None
    if not math.isfinite(value):
        raise MeasurementError(f"line {line}, column {column!r}: {text!r} is not finite")
    return value


def _meta_value(key: str, text: str) -> Any:
    if key in ("geometry", "wall", "label", "source", "synthetic"):
        return text
    try:
        return float(text)
    except ValueError:
        return text


def read_profile(source: str | Path | Any, **meta: Any) -> MeasuredProfile:
    """Read a measured profile from a CSV file, CSV text, or a pandas DataFrame.

    Keyword arguments supply or override header values (e.g. ``d_p=1e-3`` to convert
    ``distance_m``, ``wall_speed=0.01`` to convert ``u_m_s``). A file is read as UTF-8, with or
    without a byte-order mark.

    Raises
    ------
    MeasurementError
        Malformed content (the message names the line and the column), or no data rows.
    InputError
        A file that is not UTF-8 text (the message names the line, column and byte).
    OSError
        A file that cannot be read (no such file, a directory, no permission).
    """
    if hasattr(source, "columns") and hasattr(source, "__getitem__"):
        frame = {str(c).strip().lower(): np.asarray(source[c], dtype=float) for c in source.columns}
        rows_meta: dict[str, Any] = dict(getattr(source, "attrs", {}) or {})
        return _assemble(frame, {**rows_meta, **meta}, first_data_line=1)
    text = read_text(source) if _is_path(source) else str(source).removeprefix("\ufeff")
    header: dict[str, Any] = {}
    lines = text.splitlines()
    i = 0
    while i < len(lines) and (lines[i].startswith("#") or not lines[i].strip()):
        body = lines[i].lstrip("#").strip()
        for sep in (":", "="):
            if sep in body:
                key, value = (s.strip() for s in body.split(sep, 1))
                if key.lower() in HEADER_KEYS:
                    header[key.lower()] = _meta_value(key.lower(), value)
                break
        i += 1
    if i == len(lines):
        raise MeasurementError("no column header found (expected e.g. 'distance_d,u_over_uw')")
    reader = csv.reader(io.StringIO("\n".join(lines[i:])))
    names = [n.strip().lower() for n in next(reader)]
    columns: dict[str, list[float]] = {n: [] for n in names}
    for offset, row in enumerate(reader, start=1):
        line = i + 1 + offset
        if not row or all(not cell.strip() for cell in row):
            raise MeasurementError(f"line {line}: empty row (remove it; nothing is skipped)")
        if len(row) != len(names):
            raise MeasurementError(
                f"line {line}: {len(row)} values for {len(names)} columns ({', '.join(names)})"
            )
        for name, cell in zip(names, row, strict=True):
            columns[name].append(_number(cell.strip(), line, name))
    if not any(columns.values()):
        raise MeasurementError(f"no data rows after the column header (line {i + 1})")
    arrays = {k: np.asarray(v, dtype=float) for k, v in columns.items()}
    return _assemble(arrays, {**header, **meta}, first_data_line=i + 2)


def _is_path(source: Any) -> bool:
    if isinstance(source, Path):
        return True
    return isinstance(source, str) and "\n" not in source and "," not in source


def _assemble(
    columns: dict[str, FloatArray], meta: dict[str, Any], first_data_line: int
) -> MeasuredProfile:
    meta = {k.lower(): v for k, v in meta.items()}
    dist_col = [c for c in DISTANCE_COLUMNS if c in columns]
    vel_col = [c for c in VELOCITY_COLUMNS if c in columns]
    if len(dist_col) != 1 or len(vel_col) != 1:
        raise MeasurementError(
            f"need exactly one distance column ({' | '.join(DISTANCE_COLUMNS)}) and one velocity "
            f"column ({' | '.join(VELOCITY_COLUMNS)}); got columns {', '.join(columns)}"
        )
    allowed = set(DISTANCE_COLUMNS) | set(VELOCITY_COLUMNS) | set(ERROR_COLUMNS.values())
    unknown = [c for c in columns if c not in allowed]
    if unknown:
        raise MeasurementError(f"unknown column(s) {', '.join(unknown)}")
    d_name, v_name = dist_col[0], vel_col[0]
    d, u = columns[d_name], columns[v_name]
    err = columns.get(ERROR_COLUMNS[v_name])
    if d_name == "distance_xi":
        if "eps" not in meta:
            raise MeasurementError("column 'distance_xi' needs 'eps' in the header or arguments")
        d = d / float(meta["eps"])
    elif d_name == "distance_m":
        if "d_p" not in meta:
            raise MeasurementError("column 'distance_m' needs 'd_p' [m] in the header or arguments")
        d = d / float(meta["d_p"])
    if v_name == "u_m_s":
        if "wall_speed" not in meta:
            raise MeasurementError("column 'u_m_s' needs 'wall_speed' [m/s]")
        u = u / float(meta["wall_speed"])
        err = None if err is None else err / abs(float(meta["wall_speed"]))
    for name, values in ((d_name, d), (v_name, u)):
        bad = np.flatnonzero(~np.isfinite(values))
        if bad.size:
            raise MeasurementError(
                f"line {first_data_line + int(bad[0])}, column {name!r}: not a finite number"
            )
    if err is not None:
        bad = np.flatnonzero(~(np.isfinite(err) & (err > 0)))
        if bad.size:
            raise MeasurementError(
                f"line {first_data_line + int(bad[0])}, column {ERROR_COLUMNS[v_name]!r}: "
                f"uncertainties must be finite and > 0; got {float(err[bad[0]]):g}"
            )
    bad = np.flatnonzero(d < 0)
    if bad.size:
        raise MeasurementError(
            f"line {first_data_line + int(bad[0])}, column {d_name!r}: distances from the wall "
            f"must be >= 0; got {float(d[bad[0]]):g}"
        )
    return MeasuredProfile(d, u, err, meta)


def write_profile(profile: MeasuredProfile, path: str | Path) -> Path:
    """Write ``profile`` in the minimal format, with its header block."""
    path = Path(path)
    with atomic_open(path, newline="") as fh:
        for key, value in profile.meta.items():
            fh.write(f"# {key}: {value}\n")
        writer = csv.writer(fh)
        cols = ["distance_d", "u_over_uw"] + (["u_err"] if profile.u_err is not None else [])
        writer.writerow(cols)
        for i in range(profile.n):
            row = [repr(float(profile.distance_d[i])), repr(float(profile.u_over_uw[i]))]
            if profile.u_err is not None:
                row.append(repr(float(profile.u_err[i])))
            writer.writerow(row)
    return path
