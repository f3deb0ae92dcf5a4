"""What a calibration fits: the measured fields of each run, and what the run's metadata fix.

A run is one measured cell (a corpus run, ``docs/dem.md``, or a profile file,
``docs/measurements.md``). Everything is put in one frame, the same for every cell and every
model (``docs/calibration.md``):

* the coordinate is the distance ``s`` from the moving wall's surface, in grain diameters [d];
* ``u`` is the velocity along the flow over the moving wall's velocity [-] (1: no slip);
* ``omega`` is the grain spin in units of the wall speed over a grain diameter, V/d [-], with
  the sign of a frame in which the moving wall moves along +x and the layer lies below it
  (plane shear: the deck's own frame when the upper wall moves; its mirror image when the
  lower one does). Half the vorticity of such a flow is negative;
* ``stress_ratio`` is ``|sigma_yx| / sigma_yy`` (Couette flow: ``|sigma_rt| / sigma_rr``) [-],
  a ratio of two measured stresses, free of the sign conventions of each, in the shear band
  (:data:`BAND_U`) and at least :data:`WALL_EXCLUSION_D` from the walls.

What a run's metadata give is fixed, never fitted unless the caller frees it: the cell
(``eps = d/H``, ``Ri = R_i/H``, ``B``, ``nu``) and the drive, the wall's inertial number
``I_w = V d / (H sqrt(p_w / rho_s))`` from the wall speed ``V``, the moving wall's measured
normal stress ``p_w``, the grain size and density. Runs are grouped into materials (same grains
and contact law) and their walls into wall kinds (same wall description), which is what the
joint calibration shares parameters over.
"""

from __future__ import annotations

import dataclasses
import functools
import hashlib
import json
import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from ..analysis.bins import bin_edges, distance_from_moving, half_vorticity_method
from ..analysis.corpus import Run, read_corpus, read_run, usable, wall_inertial_number
from ..analysis.measurements import MeasuredProfile, read_profile
from ..errors import InputError, ParameterError
from ..model.constitutive import FloatArray
from .noise import Correlation, estimate_rho

FIELDS: tuple[str, ...] = ("u", "omega", "stress_ratio", "wall_ratio")
"""The measured fields a calibration can use, in this order everywhere."""

FIELD_MEANINGS: dict[str, str] = {
    "u": "velocity along the flow over the moving wall's velocity [-]",
    "omega": "grain spin over V/d, V the moving wall's speed [-]",
    "stress_ratio": "|shear stress| / normal stress on planes parallel to the walls [-]",
    "wall_ratio": "|shear stress| / normal stress on the moving wall, from its contacts [-]",
}

QUASI_STATIC_I = 1e-3
"""Largest local inertial number of slow, quasi-static flow [-], the regime the frictional
Cosserat model is for (``docs/dem.md``)."""
WALL_BINS = 3
"""Bins next to the moving wall whose local inertial number says whether a run is
quasi-static (the criterion of ``docs/dem.md``)."""

BAND_U = 0.05
"""``stress_ratio`` is taken where the measured u is at least this (the shear band, by the
definition of Delta's edge, ``eqn-delta_defn``) [-]. Below, the material barely moves: its
force network is frozen for the whole run, so the time blocks that give the standard errors do
not sample it, and bin-to-bin differences of the stress many times those errors are structure,
not noise (seen in every shipped run deeper than 20 d). The models' stresses there are averages
over such structures."""
BIN_NODES = 24
"""Gauss-Legendre points per bin of a model's bin mean (:meth:`Field.nodes`; the same rule as
``studies.validate.forward.bin_average``, so a model measured either way agrees to rounding)."""


@functools.lru_cache(maxsize=8)
def gauss_legendre(n: int) -> tuple[FloatArray, FloatArray]:
    """``np.polynomial.legendre.leggauss(n)`` (nodes on [-1, 1], weights), made once per ``n``
    and read-only: it costs ~0.8 ms (an eigenvalue problem and Newton steps), and the
    calibrations ask for it at every prediction of every field (``cosserat validate`` asked
    ~47,000 times on the shipped corpus, ~37 s of CPU)."""
    x, w = np.polynomial.legendre.leggauss(n)
    x.flags.writeable = False
    w.flags.writeable = False
    return x, w


WALL_EXCLUSION_D = 1.0
"""Stress bins whose centre is closer than this to a wall are left out of ``stress_ratio`` [d]:
the first layer's stresses are those of a half-filled bin against the wall's grains."""


@dataclass(frozen=True)
class Field:
    """One measured field of one run, in the calibration frame (module docstring).

    Attributes
    ----------
    name : str
        One of :data:`FIELDS`.
    s : ndarray
        Distance of each bin from the moving wall [d], increasing.
    value, se : ndarray
        The field and its standard error, in bin order.
    correlation : Correlation
        The lag-1 correlation of neighbouring bins' errors (``calibration.noise``).
    bins : (ndarray, ndarray) or None
        The bins' edges as distances from the moving wall (near, far) [d], where the values
        are bin means (a coarse-grained u or omega): a model's prediction is then its mean over
        each bin (:data:`BIN_NODES` Gauss-Legendre points, weighted by r in Couette flow), not
        its value at the centre. None (the default): values at the bin centres ``s``.
    """

    name: str
    s: FloatArray
    value: FloatArray
    se: FloatArray
    correlation: Correlation = field(default_factory=lambda: Correlation(0.0, "given"))
    bins: tuple[FloatArray, FloatArray] | None = None

    @property
    def n(self) -> int:
        return int(self.s.size)

    def with_correlation(self, correlation: Correlation) -> Field:
        return dataclasses.replace(self, correlation=correlation)

    def nodes(self) -> tuple[FloatArray, FloatArray]:
        """Where a model is evaluated for this field and with what weight: the bins' Gauss-
        Legendre points row by row (``n x BIN_NODES``, distances [d]) and their weights, or the
        centres ``s`` with weight 1 (one column) where the values are not bin means. Made at
        the first call and kept, read-only (a calibration asks at every prediction: ~10^5
        times in one ``cosserat validate``, ~2 s of CPU)."""
        kept = self.__dict__.get("_nodes")
        if kept is None:
            kept = self._make_nodes()
            for a in kept:
                if a.flags.writeable:
                    a.flags.writeable = False
            object.__setattr__(self, "_nodes", kept)  # frozen: the fields stay as they are
        return kept

    def _make_nodes(self) -> tuple[FloatArray, FloatArray]:
        if self.bins is None:
            return self.s[:, None], np.ones((self.n, 1))
        lo, hi = (np.asarray(b, dtype=float) for b in self.bins)
        x, w = gauss_legendre(BIN_NODES)
        half = 0.5 * (hi - lo)
        pts = 0.5 * (hi + lo)[:, None] + half[:, None] * x[None, :]
        return pts, np.broadcast_to(w[None, :], pts.shape)


@dataclass(frozen=True)
class RunData:
    """One run as a calibration sees it.

    Attributes
    ----------
    name : str
        The run's name (file stem), used in every warning about it.
    cell : str
        ``"plane"`` or ``"couette"``.
    gap_d : float
        H/d [-].
    cell_values : dict
        What the metadata fix about the cell: ``eps``, and ``Ri`` (Couette) or ``B``, ``nu``
        (plane) [-].
    I_w : float or None
        The wall's inertial number from the metadata (module docstring) [-]; None if the
        metadata do not give the wall speed, normal stress and density.
    material : str
        Label of the run's material (runs with equal labels share material parameters).
    walls : dict
        ``{"moving": kind, "fixed": kind}``: labels of the wall kinds (equal labels share wall
        parameters).
    fields : dict of str to Field
        The measured fields the run has, by name.
    meta : dict
        The run's metadata as read.
    local_inertial_number : float or None
        The largest local inertial number in the :data:`WALL_BINS` bins next to the moving wall
        (the sidecar's ``wall_inertial_number``, else the run's ``inertial_number`` column)
        [-]; None where not measured. Above :data:`QUASI_STATIC_I` the run is not quasi-static.
    """

    name: str
    cell: str
    gap_d: float
    cell_values: dict[str, float]
    I_w: float | None
    material: str
    walls: dict[str, str]
    fields: dict[str, Field]
    meta: dict[str, Any] = field(default_factory=dict)
    local_inertial_number: float | None = None

    @property
    def quasi_static(self) -> bool | None:
        """Local I next to the moving wall at most :data:`QUASI_STATIC_I` (None: unknown)."""
        return (
            None
            if self.local_inertial_number is None
            else self.local_inertial_number <= QUASI_STATIC_I
        )

    @property
    def eps(self) -> float:
        return float(self.cell_values["eps"])

    def xi(self, s: FloatArray, moving_wall_xi: float) -> FloatArray:
        """Positions ``s`` [d] as gap fractions of a model whose moving wall is at
        ``moving_wall_xi`` (0 or 1) [-]."""
        d = np.clip(np.asarray(s, dtype=float) * self.eps, 0.0, 1.0)
        return d if moving_wall_xi == 0.0 else 1.0 - d

    def n_points(self, fields: Sequence[str] | None = None) -> int:
        use = (
            self.fields
            if fields is None
            else {k: self.fields[k] for k in fields if k in self.fields}
        )
        return sum(f.n for f in use.values())


# --------------------------------------------------------------------------- reading
def _label(obj: Any) -> str:
    """A short stable label of a JSON-able description (for material and wall groups)."""
    text = json.dumps(obj, sort_keys=True, default=str)
    return hashlib.sha256(text.encode()).hexdigest()[:8]


def _material_label(meta: Mapping[str, Any]) -> str:
    if "material" in meta:
        return str(meta["material"])
    grains, contact = meta.get("grains"), meta.get("contact")
    if grains is None and contact is None:
        return "material"
    g = dict(grains or {})
    g.pop("n", None)  # the number of grains is the cell's, not the material's
    return f"material-{_label([g, contact])}"


def _wall_label(wall: Any) -> str:
    if isinstance(wall, str):
        return wall
    if not isinstance(wall, Mapping) or not wall:
        return "wall"
    kind = str(wall.get("kind", "wall"))
    rest = {k: v for k, v in wall.items() if k != "kind"}
    return f"{kind}-{_label(rest)}" if rest else kind


def _ordered(s: FloatArray, *arrays: FloatArray) -> tuple[FloatArray, ...]:
    order = np.argsort(s, kind="stable")
    return tuple(np.asarray(a, dtype=float)[order] for a in (s, *arrays))


def _stress_ratio(run: Run) -> tuple[FloatArray, FloatArray, FloatArray] | None:
    shear, normal = ("sigma_rt", "sigma_rr") if run.cell == "couette" else ("sigma_yx", "sigma_yy")
    if not (run.has(shear) and run.has(normal)):
        return None
    t, st = run.quantity(shear)
    n, sn = run.quantity(normal)
    u, _ = run.quantity("u")
    s = run.distance_d
    ok = usable(t, st) & usable(n, sn) & (n > 0.0)
    ok &= (s >= WALL_EXCLUSION_D) & (s <= run.gap_d - WALL_EXCLUSION_D)
    ok &= u >= BAND_U  # where the material flows: below, the stresses are frozen in
    if np.count_nonzero(ok) < 2:
        return None
    ratio = np.abs(t[ok]) / n[ok]
    # the two stresses' errors taken as independent (their positive correlation would make
    # the ratio's error smaller: this errs on the safe side)
    se = ratio * np.hypot(st[ok] / np.maximum(np.abs(t[ok]), 1e-300), sn[ok] / n[ok])
    return s[ok], ratio, se


BINNED_FIELDS = ("u", "omega")
"""The fields a DEM run reports as bin means (the coarse-graining's mean over the grains in a
bin): a model is compared with them as its mean over each bin (:func:`with_bin_means`)."""


def with_bin_means(rd: RunData, run: Run) -> RunData:
    """``rd`` with :data:`BINNED_FIELDS` marked as bin means over ``run``'s bins
    (``Field.bins``, the edges of ``cosserat.analysis.bins.bin_edges`` as distances
    from the moving wall), unless the run's values are point values at the bin centres
    (``cosserat.analysis.bins.half_vorticity_method`` ``"point"``: a run not made by
    ``cosserat.dem`` that does not say otherwise).

    A model fitted to bin means at its point values is biased where u bends within a bin, next
    to the moving wall: on synthetic data at noise 1e-6 the point fit's chi^2/dof was 9,500
    (rough run) and 31,000 (smooth), K 7% and 39% low.
    """
    if half_vorticity_method(run) == "point":
        return rd
    bins = bin_edges(run)
    a, b = distance_from_moving(run, bins.lo), distance_from_moving(run, bins.hi)
    near, far = np.minimum(a, b), np.maximum(a, b)
    centre = distance_from_moving(run, bins.centre)
    fields = dict(rd.fields)
    for name in BINNED_FIELDS:
        f = fields.get(name)
        if f is None:
            continue
        j = np.argmin(np.abs(f.s[:, None] - centre[None, :]), axis=1)
        fields[name] = dataclasses.replace(f, bins=(near[j], far[j]))
    return dataclasses.replace(rd, fields=fields)


def from_run(run: Run, bin_means: bool = False) -> RunData:
    """The :class:`RunData` of a corpus run (``cosserat-corpus/1``).

    Parameters
    ----------
    run : Run
    bin_means : bool
        Compare a model with the run's u and omega as its bin means where the run's values are
        bin means (:func:`with_bin_means`; what :func:`load`, hence ``cosserat calibrate``,
        does). False (the default): at the bin centres, as ``cosserat validate``'s single-run
        and Delta fits do.

    Raises
    ------
    InputError
        A cell the calibration does not take (the channel: no wall sets its velocity scale),
        a moving wall the models do not have (the outer cylinder), or no usable velocity bins.
    """
    if run.cell not in ("plane", "couette"):
        raise InputError(
            f"run {run.name}: a {run.cell} cell cannot be calibrated yet: no wall moves, so the "
            "velocity scale is not set by the cell and a rate-independent model predicts only "
            "the profile's shape"
        )
    if run.cell == "couette" and run.moving_wall != "inner":
        raise InputError(
            f"run {run.name}: the models' Couette cell turns the inner cylinder; this run's "
            f"moving wall is the {run.moving_wall} one"
        )
    s_all = run.distance_d
    fields: dict[str, Field] = {}
    u, se = run.quantity("u")
    ok = usable(u, se)
    if np.count_nonzero(ok) < 2:
        raise InputError(f"run {run.name}: fewer than two bins with a usable u and u_se")
    s, v, e = _ordered(s_all[ok], u[ok], se[ok])
    fields["u"] = Field("u", s, v, e)
    if run.has("omega"):
        w, sw = run.quantity("omega")
        ok = usable(w, sw)
        if np.count_nonzero(ok) >= 2:
            mirror = -1.0 if (run.cell == "plane" and run.moving_wall == "lower") else 1.0
            s, v, e = _ordered(s_all[ok], mirror * w[ok], sw[ok])
            fields["omega"] = Field("omega", s, v, e)
    ratio = _stress_ratio(run)
    if ratio is not None:
        s, v, e = _ordered(*ratio)
        fields["stress_ratio"] = Field("stress_ratio", s, v, e)
    meta = dict(run.meta)
    wall = _wall_ratio(run, fields.get("stress_ratio"))
    if wall is not None:
        fields["wall_ratio"] = wall
    correlation = meta.get("bin_correlation")
    if isinstance(correlation, Mapping):
        for name, rho in correlation.items():
            if name in fields and isinstance(rho, int | float) and 0.0 <= rho < 1.0:
                fields[name] = fields[name].with_correlation(Correlation(float(rho), "metadata"))
    wall = meta.get("wall")
    moving = _wall_label(wall)
    fixed = _wall_label(meta.get("wall_fixed", wall))
    rd = RunData(
        name=run.name,
        cell=run.cell,
        gap_d=run.gap_d,
        cell_values={k: v for k, v in run.cell_parameters().items() if k != "geometry"},
        I_w=wall_inertial_number(meta, run.gap_d),
        material=_material_label(meta),
        walls={"moving": moving, "fixed": fixed},
        fields=fields,
        meta=meta,
        local_inertial_number=_local_inertial_number(run),
    )
    return with_bin_means(rd, run) if bin_means else rd


def _wall_ratio(run: Run, band: Field | None) -> Field | None:
    """The moving wall's measured stress ratio ``|shear| / normal`` from its contacts (the
    sidecar's ``wall_stress``), one datum at s = 0; its error from ``wall_stress.shear_se`` and
    ``normal_se`` where given, else the error of the band's first stress-ratio bin (a bin
    averages fewer contacts than the wall, so this errs on the safe side)."""
    ws = run.meta.get("wall_stress")
    if not isinstance(ws, Mapping):
        return None
    shear, normal = ws.get("shear"), ws.get("normal")
    if not (isinstance(shear, int | float) and isinstance(normal, int | float) and normal > 0):
        return None
    ratio = abs(float(shear)) / float(normal)
    s_se, n_se = ws.get("shear_se"), ws.get("normal_se")
    if isinstance(s_se, int | float) and isinstance(n_se, int | float) and s_se > 0:
        se = ratio * math.hypot(s_se / max(abs(float(shear)), 1e-300), n_se / float(normal))
    elif band is not None and band.n:
        se = float(band.se[0])
    else:
        return None
    return Field("wall_ratio", np.zeros(1), np.array([ratio]), np.array([se]))


def _local_inertial_number(run: Run) -> float | None:
    """Largest local I in the :data:`WALL_BINS` bins next to the moving wall (RunData)."""
    rec = run.meta.get("wall_inertial_number")
    if isinstance(rec, Mapping):
        moving = rec.get(str(rec.get("moving")))
        if isinstance(moving, Mapping) and moving.get("per_bin"):
            return float(max(moving["per_bin"]))
    if "inertial_number" not in run.columns:
        return None
    values = np.asarray(run.columns["inertial_number"], dtype=float)
    order = np.argsort(run.distance_d)
    near = values[order][:WALL_BINS]
    near = near[np.isfinite(near)]
    return float(np.max(near)) if near.size else None


def from_profile(profile: MeasuredProfile, name: str | None = None) -> RunData:
    """The :class:`RunData` of a measured velocity profile (``docs/measurements.md``): its
    header must give the cell (``geometry``, ``eps``; ``Ri`` for Couette; ``B``, ``nu``
    optional) and its points an error ``u_err``.

    Raises
    ------
    InputError
        No geometry, no eps, or no errors (a calibration needs them).
    """
    meta = dict(profile.meta)
    label = name or str(meta.get("label") or "profile")
    cell = meta.get("geometry")
    if cell not in ("plane", "couette"):
        raise InputError(
            f"{label}: the header must say '# geometry: plane' or '# geometry: couette' "
            f"(got {cell!r})"
        )
    if meta.get("eps") is None:
        raise InputError(f"{label}: the header must give '# eps: d/H'")
    if profile.u_err is None:
        raise InputError(
            f"{label}: a calibration needs the points' errors: add a u_err column (1-sigma)"
        )
    eps = float(meta["eps"])
    values: dict[str, float] = {"eps": eps}
    if cell == "couette":
        if meta.get("ri") is None:
            raise InputError(f"{label}: a Couette profile's header must give '# Ri: R_i/H'")
        values["Ri"] = float(meta["ri"])
    else:
        values["B"] = float(meta.get("b") or 0.0)
        values["nu"] = float(meta.get("nu") or 1.0)
    s, v, e = _ordered(profile.distance_d, profile.u_over_uw, profile.u_err)
    return RunData(
        name=label,
        cell=str(cell),
        gap_d=1.0 / eps,
        cell_values=values,
        I_w=float(meta["i_w"]) if meta.get("i_w") is not None else None,
        material=str(meta.get("material", "material")),
        walls={"moving": str(meta.get("wall") or "wall"), "fixed": str(meta.get("wall") or "wall")},
        fields={"u": Field("u", s, v, e)},
        meta=meta,
    )


def load(
    paths: Sequence[str | Path], skipped: list[str] | None = None, bin_means: bool = True
) -> list[RunData]:
    """Runs from corpus folders, corpus run files (``.csv`` with a ``.json`` sidecar) and
    profile files, in the order given (a folder's runs sorted by name).

    Parameters
    ----------
    paths : sequence of path
    skipped : list, optional
        Where to note the runs of a folder that cannot be calibrated (a channel), with the
        reason, instead of raising; a run named on its own always raises.
    bin_means : bool
        A corpus run's binned u and omega are compared with a model's bin means (the default;
        :func:`from_run`), else with its values at the bin centres.

    Raises
    ------
    InputError
        A path that does not exist or cannot be read, a run that cannot be calibrated, or two
        runs with the same name.
    """
    runs: list[RunData] = []
    for p in paths:
        path = Path(p)
        if path.is_dir():
            for r in read_corpus(path).runs:
                try:
                    runs.append(from_run(r, bin_means))
                except InputError as exc:
                    if skipped is None:
                        raise
                    skipped.append(str(exc))
        elif path.suffix.lower() == ".csv" and path.with_suffix(".json").is_file():
            runs.append(from_run(read_run(path), bin_means))
        elif path.is_file():
            runs.append(from_profile(read_profile(path), name=path.stem))
        else:
            raise InputError(f"{path}: no such file or folder")
    runs = short_labels(runs)
    names = [r.name for r in runs]
    twice = sorted({n for n in names if names.count(n) > 1})
    if twice:
        raise InputError(f"runs given twice (or two runs with one name): {', '.join(twice)}")
    if not runs:
        raise InputError("no runs to calibrate on")
    return runs


def short_labels(runs: Sequence[RunData]) -> list[RunData]:
    """Runs with their wall labels cut to the wall's kind (``glued-grains``) and their material
    label to ``material`` where that leaves no two different descriptions with one label."""
    walls = {label for r in runs for label in r.walls.values()}
    kinds: dict[str, set[str]] = {}
    for label in walls:
        kinds.setdefault(label.rsplit("-", 1)[0] if _hashed(label) else label, set()).add(label)
    wall_map = {
        label: (kind if len(labels) == 1 else label)
        for kind, labels in kinds.items()
        for label in labels
    }
    materials = {r.material for r in runs}
    single = len(materials) == 1 and all(m.startswith("material") for m in materials)
    return [
        dataclasses.replace(
            r,
            walls={pos: wall_map[label] for pos, label in r.walls.items()},
            material="material" if single else r.material,
        )
        for r in runs
    ]


def _hashed(label: str) -> bool:
    tail = label.rsplit("-", 1)[-1]
    return "-" in label and len(tail) == 8 and all(c in "0123456789abcdef" for c in tail)


def with_correlations(
    runs: Sequence[RunData], rho: Mapping[str, float] | None = None, pool: bool = True
) -> list[RunData]:
    """Runs with every field's bin correlation set (``calibration.noise``).

    Parameters
    ----------
    runs : sequence of RunData
    rho : mapping of field name to float, optional
        Given correlations (``source = "given"``), overriding the metadata's and the estimate.
    pool : bool
        Estimate one rho per field from all runs whose metadata do not give it (the runs of one
        corpus are coarse-grained alike), rather than one per run.
    """
    given = dict(rho or {})
    for name, r in given.items():
        if name not in FIELDS:
            raise ParameterError(f"bin correlation for unknown field {name!r}: fields are {FIELDS}")
        if not 0.0 <= r < 1.0:
            raise ParameterError(f"bin correlation of {name} must satisfy 0 <= rho < 1; got {r:g}")
    pooled: dict[str, Correlation] = {}
    if pool:
        for name in FIELDS:
            todo = [
                r.fields[name]
                for r in runs
                if name in r.fields and r.fields[name].correlation.source != "metadata"
            ]
            if todo:
                pooled[name] = estimate_rho([f.value for f in todo], [f.se for f in todo])
    out = []
    for run in runs:
        fields = {}
        for name, f in run.fields.items():
            if name in given:
                f = f.with_correlation(Correlation(given[name], "given"))
            elif f.correlation.source != "metadata":
                f = f.with_correlation(pooled[name] if pool else estimate_rho(f.value, f.se))
            fields[name] = f
        out.append(dataclasses.replace(run, fields=fields))
    return out


__all__ = [
    "FIELDS",
    "FIELD_MEANINGS",
    "Field",
    "RunData",
    "from_profile",
    "from_run",
    "load",
    "wall_inertial_number",
    "with_correlations",
]
