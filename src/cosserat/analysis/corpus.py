"""Read and check a corpus of measured profiles (format ``cosserat-corpus/1``).

A corpus is a folder; each run is two files with the same stem, ``<run>.csv`` and
``<run>.json``. The CSV has one header row and one row per bin across the gap, ordered from
the reference wall outward, in grain units: the coordinate (``y`` for plane and channel, the
distance from the lower/left wall [d]; ``r`` for Couette, the distance from the axis [d]),
``u`` and ``u_se`` (velocity along the flow over the velocity scale, and its standard error),
and optionally ``omega``, ``half_vorticity``, ``nu``, the stresses and ``inertial_number``, each
quantity ``q`` with ``q_se``. The JSON sidecar describes the cell (``cell``, ``gap_d``,
``Ri_d``, ``B``, ``wall``), the grains, the contact law and the run (``docs/dem.md``).

Only the format tag, the cell, ``gap_d`` (and ``Ri_d`` for Couette) and the columns
coordinate, ``u``, ``u_se`` are required: a user's own data is validated with what it has, and
:meth:`Run.missing` says what it lacks. Every malformed file raises
:class:`~cosserat.errors.InputError` naming the file, the line and the column.

The moving wall is the upper one in plane shear (y = gap_d) and the inner cylinder in Couette
flow unless the sidecar says otherwise (``"moving_wall": "lower" | "upper" | "inner" |
"outer"``). Velocities are taken with the sign that makes the moving wall's velocity
positive; spins and vorticities with the same sign change (a mirror image of the flow).
"""

from __future__ import annotations

import csv
import io
import json
import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from importlib import resources
from pathlib import Path
from typing import Any

import numpy as np

from .._atomic import atomic_open, write_text
from .._text import read_text
from ..errors import InputError
from ..model.constitutive import BoolArray, FloatArray
from .measurements import MeasuredProfile

FORMAT = "cosserat-corpus/1"
CELLS = ("plane", "couette", "channel")
COORDINATE = {"plane": "y", "channel": "y", "couette": "r"}
REQUIRED_KEYS = ("format", "cell", "gap_d")
DOCUMENTED_KEYS = (
    "format", "cell", "gap_d", "Ri_d", "gravity", "gravity_note", "B", "wall", "grains",
    "contact", "seed", "lammps_version", "deck_sha256", "steps", "timestep", "steady_window",
    "dropped_steps", "blocks", "wall_speed", "velocity_scale", "stress_scale",
    "inertial_number", "sign_convention", "columns", "source",
)  # fmt: skip
"""Every key the format defines (``docs/dem.md``); only :data:`REQUIRED_KEYS` must be there."""
OPTIONAL_QUANTITIES = (
    "omega", "half_vorticity", "nu", "inertial_number",
    "sigma_xx", "sigma_yy", "sigma_xy", "sigma_yx",
    "sigma_rr", "sigma_tt", "sigma_rt", "sigma_tr",
)  # fmt: skip
EXTRA_KEYS = (
    "moving_wall", "synthetic_model",
    "B_note", "settle_steps", "dump_every", "wall_stress", "moving_wall_speed", "steady_drift",
    "wall_time_s", "wall_inertial_number", "quasi_static", "steadiness", "bin_correlation",
    "bin_correlation_note", "segments", "extended_from_steps", "wall_fixed", "walls",
    "half_vorticity_method",
    "block_autocorrelation", "omega_half_vorticity_correlation", "window_rule", "truncated_bins",
    "first_layer",
)  # fmt: skip
"""Keys this reader also understands: which wall moves; the model a synthetic run came from;
and what ``cosserat.dem`` records of a run (how B was set, the settling and dump intervals,
the moving wall's measured stresses and speed, the drift of the flow over the steady window,
the run's wall time; the fixed wall where it differs from the moving one (``wall_fixed``)
and each wall by position (``walls``); the local inertial number next to the walls and
whether the run is quasi-static, the steadiness test, the bins' error correlation, the
block length against the autocorrelation times of the run's series, the segments of a resumed
run and the steps of its deck if it was continued for longer; how the half_vorticity column
was made, ``np.gradient`` over the binned u by default or ``bin-average``, the bin's mean of
the point value (synthetic runs); the per-bin correlation of omega's and half_vorticity's
errors; the window rule (wall travel discarded before averaging) and the truncated end bins;
the first layers of grains at each sheared wall, grain by grain (``first_layer``,
``cosserat.dem.first_layer``); ``docs/dem.md``)."""
WALL_KINDS = ("glued-grains", "smooth-frictional")
ROUGHNESS = ("fully-rough", "smoother")


OUTSIDE_TOLERANCE_D = 0.5
"""Bin centres this far outside the sidecar's gap [d] are accepted (a coarse-grained wall
position) and taken at the wall; farther out they are an error."""


def usable(values: FloatArray, stderr: FloatArray) -> BoolArray:
    """True where a measured quantity and its standard error can be used (finite, se > 0)."""
    return np.isfinite(values) & np.isfinite(stderr) & (stderr > 0.0)


def shipped_corpus() -> Path:
    """The folder of the corpus shipped with the package, ``cosserat/data/corpus``."""
    return Path(str(resources.files("cosserat") / "data" / "corpus"))


@dataclass(frozen=True)
class Run:
    """One run of a corpus: its sidecar and its columns (as read, grain units)."""

    name: str
    path: Path
    meta: dict[str, Any]
    columns: dict[str, FloatArray]
    notes: tuple[str, ...] = field(default=())

    # ---------------------------------------------------------------- the cell
    @property
    def cell(self) -> str:
        return str(self.meta["cell"])

    @property
    def gap_d(self) -> float:
        """H/d [-]."""
        return float(self.meta["gap_d"])

    @property
    def Ri_d(self) -> float | None:
        """Inner radius over d (Couette) [-]."""
        v = self.meta.get("Ri_d")
        return None if v is None else float(v)

    @property
    def B(self) -> float:
        """Gravity parameter rho_s nu g H / N of plane shear (0 without gravity) [-]."""
        v = self.meta.get("B")
        return 0.0 if v is None else float(v)

    @property
    def wall(self) -> dict[str, Any]:
        w = self.meta.get("wall")
        return dict(w) if isinstance(w, dict) else {}

    @property
    def roughness(self) -> str | None:
        """ "fully-rough" (glued grains) or "smoother" (a smooth frictional wall); the sidecar's
        ``wall.roughness`` overrides; None if the sidecar does not say."""
        w = self.wall
        if w.get("roughness") in ROUGHNESS:
            return str(w["roughness"])
        return {"glued-grains": "fully-rough", "smooth-frictional": "smoother"}.get(
            str(w.get("kind"))
        )

    @property
    def wall_key(self) -> str:
        """Runs with the same cell, wall, gravity (plane, B to one significant digit) and
        (Couette) inner radius form one gap series."""
        w = {k: v for k, v in sorted(self.wall.items())}
        extra = f", Ri_d = {self.Ri_d:g}" if self.cell == "couette" and self.Ri_d else ""
        # B to one significant digit: runs of one design differ by their measured gaps
        grav = f", B = {self.B:.1g}" if self.cell == "plane" else ""
        kind = w.pop("kind", "unknown wall")
        details = ", ".join(f"{k} = {v}" for k, v in w.items())
        return f"{self.cell}, {kind}" + (f" ({details})" if details else "") + grav + extra

    @property
    def moving_wall(self) -> str:
        default = {"plane": "upper", "couette": "inner"}.get(self.cell, "none")
        return str(self.meta.get("moving_wall", default))

    @property
    def eps(self) -> float:
        return 1.0 / self.gap_d

    def cell_parameters(self) -> dict[str, Any]:
        """The model's cell parameters: geometry, eps = d/H, Ri = R_i/H (Couette), B with
        nu = 1 (plane; the sidecar's B already contains the solids fraction) [-]."""
        out: dict[str, Any] = {"geometry": self.cell, "eps": self.eps}
        if self.cell == "couette":
            out["Ri"] = float(self.Ri_d or 0.0) / self.gap_d
        if self.cell == "plane":
            out["B"] = self.B
            out["nu"] = 1.0
        return out

    # ---------------------------------------------------------------- the columns
    def has(self, quantity: str) -> bool:
        """Both ``quantity`` and its standard error are present."""
        return quantity in self.columns and f"{quantity}_se" in self.columns

    def missing(self) -> list[str]:
        """Optional quantities the run does not have (with their standard errors)."""
        skip = ("sigma_rr", "sigma_tt", "sigma_rt", "sigma_tr")
        if self.cell == "couette":
            skip = ("sigma_xx", "sigma_yy", "sigma_xy", "sigma_yx")
        return [q for q in OPTIONAL_QUANTITIES if q not in skip and not self.has(q)]

    @property
    def distance_d(self) -> FloatArray:
        """Distance of each bin from the moving wall [d]."""
        c = self.columns[COORDINATE[self.cell]]
        if self.cell == "couette":
            inner = float(self.Ri_d or 0.0)
            d = c - inner if self.moving_wall == "inner" else inner + self.gap_d - c
        else:
            d = self.gap_d - c if self.moving_wall == "upper" else c.copy()
        return np.clip(d, 0.0, self.gap_d)  # bins a little beyond the gap: at the wall

    @property
    def sign(self) -> float:
        """+1 or -1: the sign making the moving wall's velocity positive (from the bin
        nearest to it)."""
        u = self.columns["u"]
        nearest = int(np.argmin(self.distance_d))
        return -1.0 if u[nearest] < 0.0 else 1.0

    def quantity(self, name: str) -> tuple[FloatArray, FloatArray]:
        """(values, standard errors) of ``u``, ``omega`` or ``half_vorticity`` in the sign of
        :attr:`sign`; other quantities as read."""
        s = self.sign if name in ("u", "omega", "half_vorticity") else 1.0
        return s * self.columns[name], self.columns[f"{name}_se"]

    def measured(self) -> MeasuredProfile:
        """The velocity profile as :mod:`cosserat.analysis.measurements` reads one."""
        u, se = self.quantity("u")
        order = np.argsort(self.distance_d)
        meta: dict[str, Any] = {
            "label": self.name,
            "geometry": self.cell,
            "source": self.meta.get("source", ""),
        }
        I_w = wall_inertial_number(self.meta, self.gap_d)
        if I_w is not None:  # what the wall speed fixes (docs/calibration.md): never fitted
            meta["i_w"] = I_w
        return MeasuredProfile(self.distance_d[order], u[order], se[order], meta)


def wall_inertial_number(meta: Mapping[str, Any], gap_d: float) -> float | None:
    """``I_w = V d / (H sqrt(p_w / rho_s))``, the moving wall's inertial number, from a corpus
    sidecar's metadata (``docs/calibration.md``) [-].

    ``V`` is ``wall_speed`` (in the deck's units, sqrt(N/rho_s) with d = 1), ``p_w`` the moving
    wall's measured normal stress ``wall_stress.normal`` [N] (1 if not measured: the applied
    load) and ``rho_s`` the grains' ``density``; None where the speed is not given.
    """
    if "I_w" in meta and meta["I_w"] is not None:
        return float(meta["I_w"])
    speed = meta.get("moving_wall_speed", meta.get("wall_speed"))
    if not isinstance(speed, int | float) or speed <= 0.0:
        return None
    stress = meta.get("wall_stress")
    p = stress.get("normal") if isinstance(stress, Mapping) else None
    p = float(p) if isinstance(p, int | float) and p > 0.0 else 1.0
    grains = meta.get("grains")
    rho = grains.get("density") if isinstance(grains, Mapping) else None
    rho = float(rho) if isinstance(rho, int | float) and rho > 0.0 else 1.0
    return float(speed) / (gap_d * math.sqrt(p / rho))


@dataclass(frozen=True)
class Corpus:
    """Every run of a corpus folder, sorted by name."""

    path: Path
    runs: list[Run]

    def groups(self) -> dict[str, list[Run]]:
        """Runs of the same cell and wall (:attr:`Run.wall_key`), each sorted by gap."""
        out: dict[str, list[Run]] = {}
        for r in self.runs:
            out.setdefault(r.wall_key, []).append(r)
        return {k: sorted(v, key=lambda r: r.gap_d) for k, v in out.items()}


# ---------------------------------------------------------------------- reading
def _reason(exc: OSError) -> str:
    """The operating system's reason, lower case ("permission denied")."""
    text = exc.strerror or str(exc) or type(exc).__name__
    return text[:1].lower() + text[1:]


def _read_sidecar(path: Path) -> dict[str, Any]:
    try:
        text = read_text(path)
    except FileNotFoundError:
        raise InputError(
            f"{path.with_suffix('.csv').name}: no sidecar {path.name} beside it (each run is "
            "<run>.csv and <run>.json)"
        ) from None
    except OSError as exc:
        raise InputError(f"cannot read {path}: {_reason(exc)}") from None
    try:
        meta = json.loads(text)
    except json.JSONDecodeError as exc:
        raise InputError(f"{path}: not valid JSON (line {exc.lineno}: {exc.msg})") from None
    if not isinstance(meta, dict):
        raise InputError(f"{path}: the sidecar must be a JSON object")
    missing = [k for k in REQUIRED_KEYS if k not in meta]
    if missing:
        raise InputError(f"{path}: missing key(s) {', '.join(missing)}")
    if meta["format"] != FORMAT:
        raise InputError(f"{path}: format must be {FORMAT!r}; got {meta['format']!r}")
    if meta["cell"] not in CELLS:
        raise InputError(f"{path}: cell must be one of {', '.join(CELLS)}; got {meta['cell']!r}")
    for key in ("gap_d", "Ri_d", "B"):
        value = meta.get(key)
        if value is None and key != "gap_d":
            continue
        if (
            isinstance(value, bool)
            or not isinstance(value, int | float)
            or not math.isfinite(value)
        ):
            raise InputError(f"{path}: {key} must be a finite number; got {value!r}")
    if meta["gap_d"] <= 2.0:
        raise InputError(f"{path}: gap_d = H/d must be > 2; got {meta['gap_d']!r}")
    if meta["cell"] == "couette" and (meta.get("Ri_d") is None or meta["Ri_d"] <= 0):
        raise InputError(f"{path}: a couette run needs Ri_d > 0 (inner radius / d)")
    if meta.get("B") is not None and meta["B"] < 0:
        raise InputError(f"{path}: B must be >= 0; got {meta['B']!r}")
    wall = meta.get("wall")
    if wall is not None and not isinstance(wall, dict):
        raise InputError(f"{path}: wall must be an object like {{'kind': 'glued-grains', ...}}")
    return meta


def _read_columns(path: Path) -> dict[str, FloatArray]:
    try:
        rows = list(csv.reader(io.StringIO(read_text(path), newline="")))
    except FileNotFoundError:
        raise InputError(f"{path}: no such file") from None
    except OSError as exc:
        raise InputError(f"cannot read {path}: {_reason(exc)}") from None
    if not rows:
        raise InputError(f"{path}: empty file")
    if len(rows) == 1:
        raise InputError(f"{path}: no data rows after the column header (line 1)")
    names = [n.strip() for n in rows[0]]
    if len(set(names)) != len(names):
        raise InputError(f"{path}, line 1: repeated column names")
    values: dict[str, list[float]] = {n: [] for n in names}
    for line, row in enumerate(rows[1:], start=2):
        if not row or all(not c.strip() for c in row):
            raise InputError(f"{path}, line {line}: empty row (nothing is skipped; remove it)")
        if len(row) != len(names):
            raise InputError(f"{path}, line {line}: {len(row)} values for {len(names)} columns")
        for name, cell in zip(names, row, strict=True):
            try:
                x = float(cell)
            except ValueError:
                raise InputError(
                    f"{path}, line {line}, column {name!r}: {cell!r} is not a number"
                ) from None
            values[name].append(x)  # nan/inf: checked by read_run (allowed where optional)
    return {k: np.asarray(v, dtype=float) for k, v in values.items()}


def read_run(csv_path: str | Path) -> Run:
    """Read one run (``<run>.csv`` and the sidecar ``<run>.json``) and check it.

    Raises
    ------
    InputError
        A missing or malformed file, a required key or column missing, a standard error that
        is not positive, bins not ordered or outside the gap (the message says where).
    """
    path = Path(csv_path)
    meta = _read_sidecar(path.with_suffix(".json"))
    columns = _read_columns(path)
    cell = meta["cell"]
    coord = COORDINATE[cell]
    need = [coord, "u", "u_se"]
    absent = [c for c in need if c not in columns]
    if absent:
        raise InputError(
            f"{path}: missing column(s) {', '.join(absent)} (a {cell} run needs {', '.join(need)})"
        )
    for name in need:
        bad = np.flatnonzero(~np.isfinite(columns[name]))
        if bad.size:
            i = int(bad[0])
            raise InputError(
                f"{path}, line {i + 2}, column {name!r}: {columns[name][i]} is not finite"
            )
    n = columns[coord].size
    if n < 3:
        raise InputError(f"{path}: {n} bins; a profile needs at least 3")
    c = columns[coord]
    step = np.diff(c)
    if not (np.all(step > 0) or np.all(step < 0)):
        line = int(np.flatnonzero(step * np.sign(step[0]) <= 0)[0]) + 3
        raise InputError(
            f"{path}, line {line}, column {coord!r}: bins must be ordered across the gap "
            "(strictly monotone)"
        )
    lo = float(meta.get("Ri_d") or 0.0) if cell == "couette" else 0.0
    hi = lo + float(meta["gap_d"])
    outside = np.flatnonzero((c < lo - OUTSIDE_TOLERANCE_D) | (c > hi + OUTSIDE_TOLERANCE_D))
    if outside.size:
        i = int(outside[0])
        raise InputError(
            f"{path}, line {i + 2}, column {coord!r}: {c[i]:g} lies outside the gap "
            f"[{lo:g}, {hi:g}] given by the sidecar"
        )
    notes = []
    if np.any((c < lo) | (c > hi)):
        notes.append(
            f"bins up to {OUTSIDE_TOLERANCE_D:g} d beyond the sidecar's gap [{lo:g}, {hi:g}] "
            "are taken at the wall"
        )
    bad = np.flatnonzero(columns["u_se"] <= 0.0)
    if bad.size:
        i = int(bad[0])
        raise InputError(
            f"{path}, line {i + 2}, column 'u_se': a standard error must be > 0; got "
            f"{columns['u_se'][i]:g}"
        )
    for name in list(columns):
        if name.endswith("_se") and name[:-3] not in columns:
            notes.append(f"column {name} without {name[:-3]}")
    for q in OPTIONAL_QUANTITIES:
        if q in columns and f"{q}_se" in columns:
            unusable = ~usable(columns[q], columns[f"{q}_se"])
            if np.any(unusable):
                notes.append(
                    f"{q}: {int(np.sum(unusable))} bin(s) not finite or with {q}_se <= 0 are "
                    "left out of the comparisons"
                )
    for q in OPTIONAL_QUANTITIES:
        if q in columns and f"{q}_se" not in columns:
            notes.append(f"column {q} has no {q}_se: it is not used")
    documented = meta.get("columns")
    if isinstance(documented, dict):
        undocumented = [k for k in columns if k not in documented]
        if undocumented:
            notes.append(f"columns not described in the sidecar: {', '.join(undocumented)}")
        absent_doc = [k for k in documented if k not in columns]
        if absent_doc:
            raise InputError(
                f"{path}: the sidecar describes column(s) {', '.join(absent_doc)} that the CSV "
                "does not have"
            )
    unknown = [k for k in meta if k not in DOCUMENTED_KEYS and k not in EXTRA_KEYS]
    if unknown:
        notes.append(f"sidecar keys outside the format: {', '.join(unknown)}")
    return Run(path.stem, path, meta, columns, tuple(notes))


def _is_sidecar(path: Path) -> bool:
    """A JSON file that says it is a run's sidecar (other JSON files in a corpus folder, such
    as a run log, are not runs)."""
    try:
        meta = json.loads(read_text(path))
    except (OSError, ValueError):  # InputError (not UTF-8) is a ValueError
        return True  # unreadable: report it rather than skip it
    return isinstance(meta, dict) and meta.get("format") == FORMAT


def read_corpus(folder: str | Path | None = None) -> Corpus:
    """Every run in ``folder`` (default :func:`shipped_corpus`), sorted by name.

    Raises
    ------
    InputError
        The folder does not exist or holds no run, a CSV without its sidecar or a sidecar
        without its CSV, or any run that :func:`read_run` rejects.
    """
    path = shipped_corpus() if folder is None else Path(folder)
    if not path.is_dir() or (folder is None and not any(path.glob("*.csv"))):
        if folder is None:
            raise InputError(
                f"no corpus is shipped in this installation ({path} does not exist); give a "
                "folder of runs in the corpus format"
            )
        raise InputError(f"{path}: not a folder (give a folder of <run>.csv + <run>.json)")
    csvs = sorted(path.glob("*.csv"))
    jsons = {p.stem for p in path.glob("*.json")}
    orphans = sorted(s for s in jsons - {p.stem for p in csvs} if _is_sidecar(path / f"{s}.json"))
    if orphans:
        names = ", ".join(o + ".json" for o in orphans)
        raise InputError(f"{path}: sidecar(s) without a CSV: {names}")
    if not csvs:
        raise InputError(f"{path}: no runs (<run>.csv with <run>.json) in this folder")
    return Corpus(path, [read_run(p) for p in csvs])


# ---------------------------------------------------------------------- writing
def write_run(
    folder: str | Path, name: str, meta: dict[str, Any], columns: dict[str, FloatArray]
) -> Path:
    """Write ``<folder>/<name>.csv`` and its sidecar ``<name>.json`` (each atomically).

    ``meta`` gets ``format`` if it lacks it; the columns are written in the order given.
    Returns the CSV's path; :func:`read_run` reads it back.
    """
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    names = list(columns)
    n = {np.asarray(v).size for v in columns.values()}
    if len(n) != 1:
        raise InputError(f"run {name}: the columns have different lengths {sorted(n)}")
    with atomic_open(folder / f"{name}.csv", newline="") as fh:
        w = csv.writer(fh, lineterminator="\n")
        w.writerow(names)
        for row in zip(*(np.asarray(columns[k], dtype=float) for k in names), strict=True):
            w.writerow([repr(float(x)) for x in row])
    write_text(folder / f"{name}.json", json.dumps({"format": FORMAT, **meta}, indent=1) + "\n")
    return folder / f"{name}.csv"


def synthetic_run(
    folder: str | Path,
    name: str,
    profile: Any,
    *,
    noise: float = 0.01,
    spin_noise: float | None = None,
    seed: int = 0,
    wall: dict[str, Any] | None = None,
    bins: int | None = None,
) -> Path:
    """Write a model profile as a corpus run with Gaussian noise: a test of the validation.

    Bins of one grain diameter (or ``bins`` across the gap); ``u`` is the profile's velocity
    over the moving wall's, ``omega`` and ``half_vorticity`` the model's spin and half its
    vorticity in units of V/d (the model's times eps), each with standard error ``noise``
    (``spin_noise`` for the spins, default ``noise * eps``) and noise of that size added.
    ``source`` is "synthetic" and the sidecar says which model made it.
    """
    from .ranking import moving_wall, rheology_and_cell

    problem = profile.problem
    model, cell = rheology_and_cell(problem)
    eps = float(problem.eps)
    gap = 1.0 / eps
    n = int(bins or max(round(gap), 3))
    xi = (np.arange(n) + 0.5) / n
    _, uw = moving_wall(problem)
    f = profile.evaluate(xi)
    half = -0.5 * (f.du_dxi + f.kappa * f.u)
    # a rheology without grain spin of its own: the grains turn with the material
    spin = half if f.omega is None else f.omega
    rng = np.random.default_rng(seed)
    s_spin = noise * eps if spin_noise is None else spin_noise
    params = problem.parameters()
    Ri_d = float(params["Ri"]) * gap if cell == "couette" else None
    coord = xi * gap + (Ri_d or 0.0)
    columns = {
        COORDINATE[cell]: coord,
        "u": f.u / uw + rng.normal(0.0, noise, n),
        "u_se": np.full(n, noise),
        "omega": eps * spin + rng.normal(0.0, s_spin, n),
        "omega_se": np.full(n, s_spin),
        "half_vorticity": eps * half + rng.normal(0.0, s_spin, n),
        "half_vorticity_se": np.full(n, s_spin),
    }
    meta = {
        "cell": cell,
        "gap_d": gap,
        "Ri_d": Ri_d,
        "B": float(params.get("B") or 0.0) * float(params.get("nu") or 1.0),
        "wall": wall or {"kind": "glued-grains"},
        "seed": seed,
        "source": "synthetic",
        "synthetic_model": {"model": model, "problem": problem.parameters(), "noise": noise},
        "columns": {k: "synthetic" for k in columns},
    }
    return write_run(folder, name, meta, columns)


def check_corpus(folder: str | Path | None = None) -> list[str]:
    """Read every run (raising on the first bad one) and list the notes on each."""
    corpus = read_corpus(folder)
    return [f"{r.name}: {note}" for r in corpus.runs for note in r.notes]


__all__ = [
    "CELLS",
    "FORMAT",
    "Corpus",
    "Run",
    "check_corpus",
    "read_corpus",
    "read_run",
    "shipped_corpus",
    "synthetic_run",
    "usable",
    "wall_inertial_number",
    "write_run",
]
