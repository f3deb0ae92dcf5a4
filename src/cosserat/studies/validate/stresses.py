"""The angles a material's measured stresses fix: sin phi, and each smoother wall kind's tan delta.

**T.** In plane shear the model's shear stress is uniform (eqn-nd_xmom) and its normal stress
is 1 at the upper plate (eqn-nd_bc1, stresses in units of N, the normal stress applied to the
upper plate). ``T`` is that uniform shear stress over N: ``T = |sigma_yx| / N``, the ratio of
shear to normal stress **on the moving wall**. Where the material slips on that wall,
friction is fully mobilised there (eqn-nd_bc2, at xi = 1 where sigma_yy = 1): ``T = tan
delta``; a fully rough wall has ``tan delta = sin phi`` (eqn-bc_fullyrough), so a run whose
two walls are fully rough has ``T = sin phi``. A run measures T two ways:

* **the wall's ratio** (:func:`wall_ratio`, the estimator): the moving wall's time-averaged
  shear force over its normal force, from its contacts (the sidecar's ``wall_stress``; its
  error from the steady window's block means). It measures T where eqn-nd_bc2 states it, with
  nothing else assumed.
* **the band's T** (:func:`shear_stress`, the cross-check): the weighted least-squares T of
  ``ratio_i = T / sigma_yy(s_i)`` over the band's stress-ratio bins (u >= 0.05, at least 1 d
  from either wall: ``calibration.data``'s ``stress_ratio``), with the model's normal stress
  ``sigma_yy(s) = 1 + B nu eps s`` (B nu uniform). It is neither the band's mean ratio (which
  gravity lowers below T: 0.257 against 0.33 at H = 10 d, B = 1) nor the wall's ratio: it
  assumes the model's hydrostatic normal stress at the run's mean solids fraction (the DEM band
  is dilated, its sigma_yy lower) and a uniform coarse-grained sigma_yx, whose block errors
  are too small where the force network is frozen (referee 10, point 8).

**Two band readings, two names** (referee 14, point 3). The cross-check is named **the
band's |sigma_yx|/N** (:data:`BAND_T`): the wall's T read in the band, each bin's measured
ratio multiplied back by the model's hydrostatic ``sigma_yy/N``. The other reading of the same
bins, **the band's local |sigma_yx|/sigma_yy** (:data:`BAND_LOCAL`,
``measures.band_stress_ratio``: each bin's measured normal stress, inverse-variance mean), is
the one the mu(I) stress contradiction and the layer warning use. Under gravity sigma_yy grows
with depth under a uniform sigma_yx, so the local ratio lies below T (0.221-0.259 against
0.288-0.331 in the shipped rough runs): those runs' shearing bins creep below local yield,
sin phi, as the layers do (:meth:`MaterialPhi.source` says so with the numbers).

``docs/validation.md`` ("The angles from the stresses") derives both and says why the wall's
ratio is the estimator of sin phi: eqn-nd_bc2 and eqn-bc_fullyrough are statements about the
traction on the wall, which the wall's contacts measure directly.

**Pooling** (:func:`pool`): runs of one material (sin phi: its runs with both walls fully
rough) or of one wall kind (tan delta: the runs whose moving wall is of that kind) are
combined as their inverse-variance weighted mean. Their consistency is tested by chi^2 of the
values about that mean (n - 1 dof); where p < :data:`CONSISTENCY_P` the mean's error is
scaled by ``S = sqrt(chi^2 / (n - 1))``, the Particle Data Group's scale factor (PDG, Review of
Particle Physics, Introduction, "Procedures: averages and fits, unconstrained averaging"; the PDG
scales whenever S > 1, this rule only when the values are inconsistent at 5%), and the value
furthest from the mean in its own errors is named as the outlier.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
from scipy.stats import chi2 as chi2_dist

from ...analysis.corpus import Run
from ...errors import InputError
from ...model.constitutive import FloatArray
from .measures import band_stress_ratio

CONSISTENCY_P = 0.05
"""Pooled values whose chi^2 about their weighted mean has p below this are inconsistent: the
mean's error is scaled by the PDG scale factor sqrt(chi^2/dof) [-]."""

ESTIMATORS = ("wall", "band")
"""The two measures of T: the moving wall's ratio (the estimator of sin phi and tan delta)
and the band's T (the cross-check)."""
BAND_T = "the band's |sigma_yx|/N"
"""The cross-check's name in the text (:func:`shear_stress`; module docstring)."""
BAND_T_DEFINED = (
    f"{BAND_T} (a weighted least-squares T over the band's bins, u >= 0.05 at least 1 d from "
    "the walls: each bin's measured |sigma_yx|/sigma_yy = T / (1 + B nu eps s), sigma_yy taken "
    "as the model's hydrostatic normal stress, so the wall's T read in the band)"
)
"""The cross-check's name with its definition, where its values are quoted."""
BANDS_T_SHORT = (
    "the bands' |sigma_yx|/N (their bins' |sigma_yx|/sigma_yy times the model's hydrostatic "
    "sigma_yy/N)"
)
"""The cross-check of several runs, named and defined in brief (the per-run notes)."""
BAND_LOCAL = "the band's local |sigma_yx|/sigma_yy"
"""The other reading of the same bins (``measures.band_stress_ratio``: each bin's measured
normal stress, inverse-variance mean), named apart from :data:`BAND_T`."""


@dataclass(frozen=True)
class ShearStress:
    """The band's T = |sigma_yx| / N [-] (module docstring: the cross-check), fitted to a
    run's band stress-ratio bins, with its error and the fit's chi^2."""

    value: float
    stderr: float
    bins: int
    chi2: float


def normal_stress(run: Run, s: FloatArray) -> FloatArray:
    """The model's sigma_yy / N at distances ``s`` [d] from the moving wall (eqn-nd_ymom,
    eqn-nd_bc1; the model takes B nu uniform) [-]."""
    p = run.cell_parameters()
    bnu = float(p.get("B", 0.0)) * float(p.get("nu", 1.0))
    eps = float(p["eps"])
    s = np.asarray(s, dtype=float)
    if run.moving_wall == "lower":
        return 1.0 + bnu * (1.0 - eps * s)
    return 1.0 + bnu * eps * s


def shear_stress(run: Run) -> ShearStress:
    """The band's T (module docstring): the weighted least-squares T of ``ratio_i = T /
    sigma_yy(s_i)`` over the band's stress-ratio bins (those of
    :func:`cosserat.calibration.data.from_run`: u >= 0.05, at least 1 d from either wall); its
    error scaled up by sqrt(chi^2/dof) where the bins scatter more than their errors.

    Raises
    ------
    InputError
        Not a plane-shear run, or fewer than two usable stress-ratio bins.
    """
    from ...calibration.data import from_run

    if run.cell != "plane":
        raise InputError(
            f"run {run.name}: the spin scan takes plane shear only (a {run.cell} cell's stress "
            "ratio is not T / sigma_yy)"
        )
    f = from_run(run).fields.get("stress_ratio")
    if f is None or f.n < 2:
        raise InputError(
            f"run {run.name}: fewer than two band bins with sigma_yx and sigma_yy, so the "
            "stress ratio cannot fix phi or delta"
        )
    g = 1.0 / normal_stress(run, f.s)
    w = 1.0 / f.se**2
    t = float(np.sum(w * g * f.value) / np.sum(w * g * g))
    chi2 = float(np.sum(w * (f.value - t * g) ** 2))
    se = 1.0 / math.sqrt(float(np.sum(w * g * g)))
    if f.n > 1:
        se *= max(1.0, math.sqrt(chi2 / (f.n - 1)))
    return ShearStress(t, se, f.n, chi2)


def wall_ratio(run: Run) -> tuple[float, float] | None:
    """The moving wall's T (module docstring: the estimator): its measured ``|shear| /
    normal`` from its contacts and the error [-] (``calibration.data``'s ``wall_ratio``
    field: the sidecar's ``wall_stress``, errors of shear and normal in quadrature); None
    where the run does not give it."""
    from ...calibration.data import from_run

    f = from_run(run).fields.get("wall_ratio")
    if f is None:
        return None
    return float(f.value[0]), float(f.se[0])


def fully_rough(run: Run) -> bool:
    """Both walls of the run are fully rough (the corpus' wall roughness)."""
    from .grouping import walls_differ

    return run.roughness == "fully-rough" and not walls_differ(run)


def moving_wall_kind(run: Run) -> str:
    """The moving wall's kind, as the calibration labels it (its sidecar description)."""
    from ...calibration.data import _wall_label

    return _wall_label(run.meta.get("wall"))


# --------------------------------------------------------------------------- pooling
@dataclass(frozen=True)
class Pooled:
    """Values of several runs pooled as their weighted mean, with the consistency test
    (module docstring, "Pooling").

    Attributes
    ----------
    names : tuple of str
        The runs.
    values, errors : tuple of float
        Each run's value and standard error [-].
    value : float
        The inverse-variance weighted mean [-].
    stderr_raw : float
        Its error from the values' errors alone, ``1/sqrt(sum w)`` [-].
    chi2 : float
        chi^2 of the values about the mean [-].
    dof : int
        ``n - 1``.
    p_value : float or None
        ``chi2.sf(chi2, dof)``; None for one value (no test).
    scale : float
        The PDG scale factor applied to the error: ``sqrt(chi2/dof)`` where p <
        :data:`CONSISTENCY_P`, else 1 [-].
    """

    names: tuple[str, ...]
    values: tuple[float, ...]
    errors: tuple[float, ...]
    value: float
    stderr_raw: float
    chi2: float
    dof: int
    p_value: float | None
    scale: float

    @property
    def stderr(self) -> float:
        """The mean's error, scaled by :attr:`scale` where the values are inconsistent [-]."""
        return self.stderr_raw * self.scale

    @property
    def consistent(self) -> bool:
        """The values agree with one mean (p >= :data:`CONSISTENCY_P`, or one value)."""
        return self.p_value is None or self.p_value >= CONSISTENCY_P

    def pulls(self) -> tuple[float, ...]:
        """Each value's distance from the mean in its own errors [-]."""
        return tuple((v - self.value) / e for v, e in zip(self.values, self.errors, strict=True))

    @property
    def outlier(self) -> str | None:
        """The run furthest from the mean in its own errors, where the values are
        inconsistent (None where they agree)."""
        if self.consistent:
            return None
        pulls = self.pulls()
        return self.names[int(np.argmax(np.abs(pulls)))]

    def consistency_text(self) -> str:
        """One clause: the test, and the scaling and outlier where it fails."""
        if self.p_value is None:
            return "one run, no consistency test"
        from ..._text import significance

        sig = significance(self.chi2, self.dof)
        head = f"chi^2 = {self.chi2:.3g} for {self.dof} dof about the mean ({sig})"
        if self.consistent:
            return f"{head}: consistent"
        k = self.names.index(self.outlier or "")
        return (
            f"{head}: inconsistent, the error scaled by the PDG scale factor sqrt(chi^2/dof) = "
            f"{self.scale:.3g}; outlier {self.names[k]} ({self.pulls()[k]:+.1f} se)"
        )

    def values_text(self) -> str:
        """The runs' values, ``name: v +- e`` each."""
        return ", ".join(
            f"{n}: {v:.3g} +- {e:.2g}"
            for n, v, e in zip(self.names, self.values, self.errors, strict=True)
        )

    def to_dict(self) -> dict[str, Any]:
        """The pooling in plain types (``results.json``)."""
        return {
            "value": self.value,
            "stderr": self.stderr,
            "stderr_unscaled": self.stderr_raw,
            "chi2": self.chi2,
            "dof": self.dof,
            "p_value": self.p_value,
            "consistent": self.consistent,
            "scale_factor": self.scale,
            "outlier": self.outlier,
            "runs": {
                n: {"value": v, "stderr": e}
                for n, v, e in zip(self.names, self.values, self.errors, strict=True)
            },
        }


def pool(values: Sequence[float], errors: Sequence[float], names: Sequence[str]) -> Pooled:
    """The weighted mean of ``values`` with errors ``errors`` [-], its chi^2 consistency test,
    and its error scaled by the PDG factor where they are inconsistent (module docstring).

    Raises
    ------
    InputError
        No values, lengths that differ, or an error that is not positive and finite.
    """
    x = np.asarray(values, dtype=float)
    e = np.asarray(errors, dtype=float)
    if x.size == 0 or x.shape != e.shape or len(names) != x.size:
        raise InputError(
            f"pooling needs one error and one name per value: got {x.size} values, {e.size} "
            f"errors, {len(names)} names"
        )
    if not (np.all(np.isfinite(x)) and np.all(np.isfinite(e)) and np.all(e > 0.0)):
        raise InputError("pooling needs finite values and positive, finite errors")
    w = 1.0 / e**2
    mean = float(np.sum(w * x) / np.sum(w))
    chi2 = float(np.sum(w * (x - mean) ** 2))
    dof = int(x.size - 1)
    p = float(chi2_dist.sf(chi2, dof)) if dof > 0 else None
    scale = math.sqrt(chi2 / dof) if p is not None and p < CONSISTENCY_P else 1.0
    return Pooled(
        tuple(str(n) for n in names), tuple(float(v) for v in x), tuple(float(v) for v in e),
        mean, 1.0 / math.sqrt(float(np.sum(w))), chi2, dof, p, scale,
    )  # fmt: skip


def _measures(runs: Sequence[Run]) -> dict[str, list[tuple[str, float, float]]]:
    """Each estimator's (run, T, se) over ``runs`` (plane runs only; a run that does not give
    an estimator is left out of it)."""
    out: dict[str, list[tuple[str, float, float]]] = {k: [] for k in ESTIMATORS}
    for r in runs:
        if r.cell != "plane":
            continue
        w = wall_ratio(r)
        if w is not None:
            out["wall"].append((r.name, w[0], w[1]))
        try:
            t = shear_stress(r)
        except InputError:
            continue
        out["band"].append((r.name, t.value, t.stderr))
    return out


@dataclass(frozen=True)
class StressPool:
    """T of a set of runs by the estimator and by the cross-check (:func:`pooled_T`)."""

    what: str
    """What the pooled T is ("sin phi", "tan delta")."""
    estimator: str
    """``"wall"`` (the walls' ratios) or ``"band"`` (the band's T, where no run gives its
    wall's ratio)."""
    pooled: Pooled
    cross_check: Pooled | None
    """The other estimator over the same runs where they give it (None where none does)."""

    def text(self) -> str:
        """One sentence: the value, how it is measured and pooled, and the cross-check."""
        how = (
            "T = |sigma_yx|/N on the moving wall from its contacts"
            if self.estimator == "wall"
            else f"{BAND_T_DEFINED} (the walls' ratios are not given)"
        )
        out = (
            f"{self.what} = {self.pooled.value:.3g} +- {self.pooled.stderr:.2g}, the weighted "
            f"mean of {how} ({self.pooled.values_text()}; {self.pooled.consistency_text()})"
        )
        if self.cross_check is not None:
            c = self.cross_check
            other = BAND_T_DEFINED if self.estimator == "wall" else "the walls' ratios"
            out += (
                f"; cross-check, {other}: {c.value:.3g} +- {c.stderr:.2g} "
                f"({c.values_text()}; {c.consistency_text()})"
            )
        return out

    def short(self) -> str:
        """:meth:`text` without the runs' values (for the per-run notes)."""
        p = self.pooled
        how = (
            "the moving walls' T = |sigma_yx|/N from their contacts"
            if self.estimator == "wall"
            else BANDS_T_SHORT
        )
        out = (
            f"{self.what} = {p.value:.3g} +- {p.stderr:.2g}: {how}, pooled over "
            f"{', '.join(p.names)} ({p.consistency_text()})"
        )
        if self.cross_check is not None:
            c = self.cross_check
            other = BANDS_T_SHORT if self.estimator == "wall" else "the walls' ratios"
            verdict = "consistent" if c.consistent else f"inconsistent, outlier {c.outlier}"
            out += f"; cross-check, {other}: {c.value:.3g} +- {c.stderr:.2g} ({verdict})"
        return out

    def to_dict(self) -> dict[str, Any]:
        return {
            "what": self.what,
            "estimator": self.estimator,
            "pooled": self.pooled.to_dict(),
            "cross_check": None if self.cross_check is None else self.cross_check.to_dict(),
        }


def pooled_T(runs: Sequence[Run], what: str) -> StressPool | None:
    """T of ``runs`` pooled (module docstring): the walls' ratios where at least one run gives
    its wall's ratio, else the band's T; the other estimator as the cross-check. None where no
    run gives either."""
    got = _measures(runs)
    main = "wall" if got["wall"] else "band"
    if not got[main]:
        return None
    other = "band" if main == "wall" else "wall"

    def pooled(rows: list[tuple[str, float, float]]) -> Pooled:
        names, vals, errs = zip(*rows, strict=True)
        return pool(vals, errs, names)

    return StressPool(what, main, pooled(got[main]), pooled(got[other]) if got[other] else None)


@dataclass(frozen=True)
class MaterialPhi:
    """phi of a material from its fully rough runs' T (:func:`material_sin_phi`)."""

    phi: float
    """Angle of internal friction [deg]."""
    phi_se: float
    """Its error [deg] (from the pooled sin phi's, scaled where the runs disagree)."""
    sin_phi: StressPool
    local: tuple[tuple[str, float, float], ...] = ()
    """The same runs' :data:`BAND_LOCAL` (name, value, error) [-] (referee 14, point 3)."""

    def source(self, full: bool = False) -> str:
        """Where phi comes from, in words (``full``: with every run's T, and the same runs'
        :data:`BAND_LOCAL` against sin phi)."""
        out = (
            f"{self.sin_phi.text() if full else self.sin_phi.short()}; at a fully rough wall "
            "T = sin phi (eqn-nd_bc2, eqn-bc_fullyrough)"
        )
        if full and self.local:
            sp = self.sin_phi.pooled.value
            pct = [100.0 * (1.0 - v / sp) for _, v, _ in self.local]
            out += (
                f". Not {BAND_T}: by {BAND_LOCAL} (each bin's measured normal stress, the "
                "same bins, inverse-variance mean; the measure of the mu(I) stress "
                "contradiction and of the layer warning) the same runs' shearing bins sit at "
                + ", ".join(f"{n} {v:.3f} +- {e:.2g}" for n, v, e in self.local)
                + f", {min(pct):.0f}-{max(pct):.0f}% below sin phi = {sp:.3f} (under gravity "
                "sigma_yy grows with depth under a uniform sigma_yx): creep below local yield, "
                "as the layer warning finds in the layer runs; the Cosserat creep tail describes it"
            )
        return out

    def to_dict(self) -> dict[str, Any]:
        return {
            "phi": self.phi,
            "phi_se": self.phi_se,
            **self.sin_phi.to_dict(),
            "band_local": [{"run": n, "value": v, "stderr": e} for n, v, e in self.local],
        }


def material_sin_phi(runs: Sequence[Run], material: str) -> MaterialPhi:
    """phi of ``material``: sin phi = T of its plane runs with both walls fully rough, pooled
    (:func:`pooled_T`: the walls' ratios, the band's T as the cross-check).

    Raises
    ------
    InputError
        No run of the material has both walls fully rough and a measured T, or the pooled
        sin phi is not in (0, 1).
    """
    from ...calibration.data import _material_label

    mine = [
        r for r in runs
        if r.cell == "plane" and fully_rough(r) and _material_label(r.meta) == material
    ]  # fmt: skip
    got = pooled_T(mine, "sin phi")
    if got is None:
        raise InputError(
            f"material {material}: no plane run with both walls fully rough and a measured "
            "stress ratio, so phi (sin phi = |sigma_yx|/N at a fully rough wall) is not measured"
        )
    sin_phi, se = got.pooled.value, got.pooled.stderr
    if not 0.0 < sin_phi < 1.0:
        raise InputError(f"material {material}: sin phi = {sin_phi:.3g} from the stresses")
    phi = math.degrees(math.asin(sin_phi))
    phi_se = math.degrees(se / math.sqrt(1.0 - sin_phi**2))
    local = tuple(
        (r.name, b.value, b.stderr) for r in mine if (b := band_stress_ratio(r)) is not None
    )
    return MaterialPhi(phi, phi_se, got, local)


def material_phi(runs: Sequence[Run], material: str) -> tuple[float, float, str]:
    """:func:`material_sin_phi` as (phi [deg], its error [deg], its source in words)."""
    m = material_sin_phi(runs, material)
    return m.phi, m.phi_se, m.source()


def wall_tan_delta(runs: Sequence[Run], run: Run) -> StressPool | None:
    """tan delta of ``run``'s moving wall kind: T of the plane runs of ``runs`` (and ``run``)
    of the same material whose moving wall is of that kind and not fully rough, pooled
    (:func:`pooled_T`); None where none gives a T."""
    from ...calibration.data import _material_label

    kind, material = moving_wall_kind(run), _material_label(run.meta)
    mine = {
        r.name: r for r in [*runs, run]
        if r.cell == "plane" and r.roughness != "fully-rough"
        and moving_wall_kind(r) == kind and _material_label(r.meta) == material
    }  # fmt: skip
    return pooled_T(list(mine.values()), "tan delta")


def material_angles(runs: Sequence[Run]) -> tuple[dict[str, float], str, dict[str, Any]]:
    """What the stresses fix in one Cosserat calibration of a material's ``runs`` (every one
    of the same material): phi (:func:`material_sin_phi`) and the roughness tan(delta)/sin(phi)
    of every wall kind they measure, keyed as the calibration's parameters (``phi``,
    ``roughness[KIND]``): a fully rough kind 1, a smoother moving wall's kind its pooled tan
    delta (:func:`wall_tan_delta`) over sin phi. One function for the Delta calibration
    (``fits.calibrate_material``) and the spin scan's shared calibration, so that both fix the
    same angles. Returns (fix, note, numbers); the note says what is fixed and from what.

    Raises
    ------
    InputError
        phi is not measured, or a wall kind's pooled tan delta exceeds sin phi by more than
        3 errors (the fully rough limit, eqn-bc_fullyrough).
    """
    from ...calibration.data import _material_label, _wall_label

    m = material_sin_phi(runs, _material_label(runs[0].meta))
    sin_phi = math.sin(math.radians(m.phi))
    fix: dict[str, float] = {"phi": m.phi}
    notes = [f"phi = {m.phi:.4g} +- {m.phi_se:.2g} deg ({m.source(full=True)})"]
    numbers: dict[str, Any] = {"phi": m.to_dict(), "walls": {}}
    for r in runs:
        wall = r.meta.get("wall")
        kinds = {_wall_label(wall), _wall_label(r.meta.get("wall_fixed", wall))}
        if fully_rough(r):
            for k in kinds:
                fix.setdefault(f"roughness[{k}]", 1.0)
                numbers["walls"].setdefault(k, "fully rough")
            continue
        kind = moving_wall_kind(r)
        key = f"roughness[{kind}]"
        if key in fix or r.roughness == "fully-rough":
            continue
        got = wall_tan_delta(runs, r)
        if got is None:
            continue
        t, se = got.pooled.value, got.pooled.stderr
        if t > sin_phi + 3.0 * math.hypot(se, m.sin_phi.pooled.stderr):
            raise InputError(
                f"wall kind {kind}: tan delta = {t:.3g} exceeds sin phi = {sin_phi:.3g} (the "
                "fully rough limit, eqn-bc_fullyrough)"
            )
        fix[key] = min(1.0, t / sin_phi)
        delta = math.degrees(math.atan(t))
        notes.append(f"{kind}: delta = {delta:.4g} deg ({got.text()})")
        numbers["walls"][kind] = {"delta": delta, **got.to_dict()}
    return fix, "; ".join(notes), numbers


__all__ = [
    "BANDS_T_SHORT",
    "BAND_LOCAL",
    "BAND_T",
    "BAND_T_DEFINED",
    "CONSISTENCY_P",
    "ESTIMATORS",
    "MaterialPhi",
    "Pooled",
    "ShearStress",
    "StressPool",
    "fully_rough",
    "material_angles",
    "material_phi",
    "material_sin_phi",
    "moving_wall_kind",
    "normal_stress",
    "pool",
    "pooled_T",
    "shear_stress",
    "wall_ratio",
    "wall_tan_delta",
]
