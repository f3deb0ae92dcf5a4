"""Where the shear band forms when one wall is smoother than the other (issue 18, item 4).

The claim (the paper's section on plane shear without gravity between walls of different
roughness, ``eqn-soln_aw_vels`` and ``eqn-asymp_soln_vels_g0_aw``): without gravity the shear
stress ratio is uniform, friction is mobilised at the wall that can carry the least,
``tan(delta) sigma_yy``, and the shear localises there: ``u - u_0 ~ exp(-k (1 - xi)/eps)``
decays away from the **smoother** wall, ``u_0`` being the velocity of the rougher wall, so the
bulk moves with the rougher wall. The problem is symmetric under swapping the walls, so this
holds whichever wall moves (a Galilean change of frame without gravity; not tested by a run
with the other wall moving); the decisive cell is the one where the rougher wall moves and the
smoother one is fixed (the band then sits away from the moving wall). mu(I) and NGF as the
package states them (no wall friction, uniform stress) shear such a gap uniformly: no side is
preferred.

The measure (:func:`jump_fractions`): the fraction of the walls' velocity difference taken up
within ``within_d`` grain diameters of each wall, slip at the wall included,
``f_fixed = u(within_d from the fixed wall)`` and ``f_moving = 1 - u(within_d from the moving
wall)`` with ``u`` over the moving wall's speed; their standard errors from ``u_se``
interpolated with the same weights (exact for fully correlated neighbouring bins, larger than
the truth otherwise). The asymmetry ``a = f_smoother - f_rougher`` is 0 for a uniformly
sheared gap (a local rheology with no-slip walls) and near 1 for a block sliding with the
rougher wall. Its standard error (:func:`jump_covariance`) takes the bins' errors as a
stationary AR(1) sequence, ``corr(i, j) = rho^|i - j|`` over bin index, with the lag-1
correlation ``rho`` the sidecar records (``bin_correlation.u``, read by
:func:`~cosserat.studies.validate.measures.velocity_correlation`; 0 when it gives none), the
model ``validate``'s error draws use: ``a = u_f + u_m - 1`` adds the two walls' errors, so
the correlation widens it.

What the side alone does not tell: a local rheology with a Coulomb wall at the smoother wall's
measured friction also puts the band there (the block slides on that wall, a -> 1). What would
tell the Cosserat model from wall friction is the shear rate decaying away from the smoother
wall under uniform stress, so the verdict's numbers carry the measured du/dy per bin
(``shear_rate``, from the smoother wall).

The verdict (:func:`layer_position_verdict`): the inverse-variance mean of the runs'
asymmetries, ``a +- se``; "supported" (the band at the smoother wall) when ``a >=``
:data:`SIGMAS` ``se``, "refuted" when ``a <= -SIGMAS se`` (the band at the rougher wall), or when
``|a| < SIGMAS se`` although the Cosserat model fitted to the same runs predicts an asymmetry at
least ``SIGMAS se`` above the measured one; "mixed" when runs are each determined with opposite
signs; "undecided" otherwise. Runs whose walls' bins are all above the slow-flow bound
(:data:`QUASI_STATIC_I`) leave the claim "undecided" (what they say is kept in the evidence).
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np
from scipy.stats import chi2 as chi2_dist

from ...errors import ParameterError
from .layer_alternatives import REFERENCES, LayerAlternative, LayerData, layer_alternatives
from .measures import P_SIGNIFICANT, band_stress_ratio, velocity_correlation
from .verdicts import Verdict

if TYPE_CHECKING:
    from ...analysis.corpus import Run
    from .fits import RunFits

WITHIN_D = 3.0
"""Distance from each wall within which the velocity jump is counted [d]."""
SIGMAS = 3.0
"""Standard errors an asymmetry must reach to place the band [-]."""
QUASI_STATIC_I = 1e-3
"""Largest local inertial number of the slow flow the models are for [-] (as ``validate``)."""
NO_GRAVITY_B = 0.01
"""Plane runs with B at most this are without gravity [-] (the claim is for B = 0)."""
ROUGHNESS_RANK = {"smooth-frictional": 0, "glued-grains": 1}
"""Wall kinds from smoother to rougher (``cosserat.dem``'s; the smooth wall's measured delta
is 13.9 deg against the material's phi of 19 deg, docs/dem.md)."""
LAYER_CLAIM = (
    "Without gravity, between a wall smoother than the material and a rougher one, the shear "
    "band forms at the smoother wall and the bulk moves with the rougher wall."
)
"""The claim judged (the paper's; issue 18's "rougher wall" is the opposite, docs/dem.md)."""
LAYER_KEY = "layer"
"""The claim's key in ``validate``'s verdicts."""


@dataclass(frozen=True)
class LayerVerdict(Verdict):
    """A :class:`~cosserat.studies.validate.verdicts.Verdict` on :data:`LAYER_CLAIM` (kept
    out of ``verdicts.CLAIMS``: the claim is judged only when a corpus has such runs)."""

    @property
    def claim(self) -> str:
        return LAYER_CLAIM


@dataclass(frozen=True)
class LayerPosition:
    """The velocity jump next to each wall of one run (module docstring).

    Parameters
    ----------
    run : str
        The run's name.
    fixed, fixed_se : float
        Fraction of the velocity jump within ``within_d`` of the fixed wall, and its standard
        error [-].
    moving, moving_se : float
        The same at the moving wall [-].
    smoother : {"fixed", "moving"}
        Which wall is the smoother.
    within_d : float
        The distance counted [d].
    wall_inertial_number : float or None
        The largest local inertial number in the bins next to either wall [-] (None: unknown).
    predicted : mapping
        Each fitted model's asymmetry ``f_smoother - f_rougher`` on this run [-].
    u_correlation : float
        Correlation of the errors of ``u`` at the two walls' points (:func:`jump_covariance`)
        [-]; ``a = u_f + u_m - 1`` so it adds to the asymmetry's variance.
    bin_correlation : float
        The lag-1 correlation of neighbouring bins' errors used [-].
    shear_rate : tuple of float
        ``du/dy`` between neighbouring bins from the smoother wall to the rougher one, in the
        sense of the shear [V/d].
    alternatives : tuple of LayerAlternative
        The alternatives of :mod:`~cosserat.studies.validate.layer_alternatives` (local mu(I)
        with a Coulomb wall, NGF with a wall fluidity, the Cosserat layer profile) against the
        run's velocities, with their chi^2 (empty without a stress ratio).
    stress_ratio : float or None
        The run's |shear|/normal stress ratio used by the alternatives [-].
    alternatives_note : str
        Which alternatives were left out and why ("" when none was).
    """

    run: str
    fixed: float
    fixed_se: float
    moving: float
    moving_se: float
    smoother: str
    within_d: float = WITHIN_D
    wall_inertial_number: float | None = None
    predicted: Mapping[str, float] = field(default_factory=dict)
    u_correlation: float = 0.0
    bin_correlation: float = 0.0
    shear_rate: tuple[float, ...] = ()
    alternatives: tuple[LayerAlternative, ...] = ()
    stress_ratio: float | None = None
    alternatives_note: str = ""

    def __post_init__(self) -> None:
        for name in ("u_correlation", "bin_correlation"):
            value = getattr(self, name)
            if not (math.isfinite(value) and -1.0 <= value <= 1.0):
                raise ParameterError(
                    f"{name} of run {self.run} must be in [-1, 1] (a correlation); got {value}"
                )
        if self.smoother not in ("fixed", "moving"):
            raise ParameterError(f"smoother must be 'fixed' or 'moving'; got {self.smoother!r}")
        for name in ("fixed", "fixed_se", "moving", "moving_se", "within_d"):
            value = getattr(self, name)
            if not math.isfinite(value):
                raise ParameterError(f"{name} of run {self.run} must be finite; got {value}")
        for name in ("fixed_se", "moving_se"):
            if getattr(self, name) <= 0.0:
                raise ParameterError(
                    f"{name} of run {self.run} must be > 0 (a standard error); got "
                    f"{getattr(self, name)}"
                )

    @property
    def asymmetry(self) -> float:
        """``f_smoother - f_rougher`` [-]: > 0 with the band at the smoother wall."""
        return self.fixed - self.moving if self.smoother == "fixed" else self.moving - self.fixed

    @property
    def asymmetry_se(self) -> float:
        """Its standard error [-]: ``sqrt(s_f^2 + s_m^2 + 2 r s_f s_m)`` with ``r`` the
        errors' correlation ``u_correlation`` (0: the two walls independent)."""
        var = (
            self.fixed_se**2
            + self.moving_se**2
            + 2.0 * self.u_correlation * self.fixed_se * self.moving_se
        )
        return math.sqrt(max(var, 0.0))

    def to_dict(self) -> dict[str, Any]:
        return {
            "run": self.run,
            "within_d": self.within_d,
            "fixed": self.fixed,
            "fixed_se": self.fixed_se,
            "moving": self.moving,
            "moving_se": self.moving_se,
            "smoother": self.smoother,
            "asymmetry": self.asymmetry,
            "asymmetry_se": self.asymmetry_se,
            "wall_inertial_number": self.wall_inertial_number,
            "predicted": dict(self.predicted),
            "u_correlation": self.u_correlation,
            "bin_correlation": self.bin_correlation,
            "shear_rate": list(self.shear_rate),
            "stress_ratio": self.stress_ratio,
            "alternatives": [x.to_dict() for x in self.alternatives],
            "alternatives_note": self.alternatives_note,
        }


def jump_fractions(
    distance_d: np.ndarray,
    u: np.ndarray,
    u_se: np.ndarray,
    gap_d: float,
    within_d: float = WITHIN_D,
) -> tuple[float, float, float, float]:
    """The fractions of the velocity jump within ``within_d`` of the fixed and of the moving
    wall, with their standard errors: ``(fixed, fixed_se, moving, moving_se)`` [-].

    Parameters
    ----------
    distance_d : array
        Bin centres' distances from the moving wall [d].
    u, u_se : array
        Velocity over the moving wall's speed (the fixed wall at 0, the moving one at 1) and
        its standard error [-].
    gap_d : float
        The gap H/d [-].
    within_d : float
        Distance from each wall counted [d]; less than half the gap.

    Raises
    ------
    ParameterError
        ``within_d`` is not in (0, gap_d/2), or the arrays are not finite and of one length
        with at least two bins.
    """
    s = np.asarray(distance_d, dtype=float)
    u = np.asarray(u, dtype=float)
    se = np.asarray(u_se, dtype=float)
    if not (s.shape == u.shape == se.shape and s.ndim == 1 and s.size >= 2):
        raise ParameterError(
            f"distance_d, u and u_se must be 1-D arrays of one length >= 2; got shapes "
            f"{s.shape}, {u.shape}, {se.shape}"
        )
    if not (np.all(np.isfinite(s)) and np.all(np.isfinite(u)) and np.all(np.isfinite(se))):
        raise ParameterError("distance_d, u and u_se must be finite")
    if not (math.isfinite(gap_d) and 0.0 < within_d < 0.5 * gap_d):
        raise ParameterError(
            f"within_d must be > 0 and < half the gap ({0.5 * gap_d:g} d); got {within_d:g}"
        )
    order = np.argsort(s)
    s, u, se = s[order], u[order], se[order]

    def at(x: float) -> tuple[float, float]:
        k = int(np.clip(np.searchsorted(s, x), 1, s.size - 1))
        w = float(np.clip((x - s[k - 1]) / (s[k] - s[k - 1]), 0.0, 1.0))
        return (1 - w) * u[k - 1] + w * u[k], (1 - w) * se[k - 1] + w * se[k]

    u_m, se_m = at(within_d)
    u_f, se_f = at(gap_d - within_d)
    return float(u_f), float(se_f), float(1.0 - u_m), float(se_m)


def _interpolation_weights(s: np.ndarray, x: float) -> np.ndarray:
    """The weights over the (sorted) bins of linear interpolation at ``x`` (clamped)."""
    k = int(np.clip(np.searchsorted(s, x), 1, s.size - 1))
    w = float(np.clip((x - s[k - 1]) / (s[k] - s[k - 1]), 0.0, 1.0))
    c = np.zeros(s.size)
    c[k - 1], c[k] = 1.0 - w, w
    return c


def jump_covariance(
    distance_d: np.ndarray,
    u_se: np.ndarray,
    gap_d: float,
    rho: float,
    within_d: float = WITHIN_D,
) -> tuple[float, float, float]:
    """The standard errors of ``u`` interpolated ``within_d`` from the fixed and from the
    moving wall, and the correlation of the two, with the bins' errors a stationary AR(1)
    sequence: ``cov(i, j) = se_i se_j rho^|i - j|`` over bin index (ordered by distance):
    ``(fixed_se, moving_se, correlation)``.

    Parameters
    ----------
    distance_d : array
        Bin centres' distances from the moving wall [d].
    u_se : array
        Standard errors of u over the moving wall's speed [-].
    gap_d : float
        The gap H/d [-].
    rho : float
        Lag-1 correlation of neighbouring bins' errors, in [0, 1] [-].
    within_d : float
        Distance from each wall [d]; less than half the gap.

    Raises
    ------
    ParameterError
        ``rho`` is not in [0, 1], or as :func:`jump_fractions`.
    """
    if not (math.isfinite(rho) and 0.0 <= rho <= 1.0):
        raise ParameterError(f"rho must be in [0, 1] (a bin correlation); got {rho}")
    s = np.asarray(distance_d, dtype=float)
    se = np.asarray(u_se, dtype=float)
    jump_fractions(s, np.zeros(s.shape), se, gap_d, within_d)  # the same checks
    order = np.argsort(s)
    s, se = s[order], se[order]
    idx = np.arange(s.size)
    cov = np.outer(se, se) * rho ** np.abs(idx[:, None] - idx[None, :])
    c_f = _interpolation_weights(s, gap_d - within_d)
    c_m = _interpolation_weights(s, within_d)
    var_f, var_m = float(c_f @ cov @ c_f), float(c_m @ cov @ c_m)
    sf, sm = math.sqrt(var_f), math.sqrt(var_m)
    return sf, sm, float(np.clip(float(c_f @ cov @ c_m) / (sf * sm), -1.0, 1.0))


def shear_rates(distance_d: np.ndarray, u: np.ndarray, smoother: str) -> tuple[float, ...]:
    """``-du/ds`` between neighbouring bins (``s`` from the moving wall; positive in the sense
    of the shear), ordered from the ``smoother`` wall ("fixed" or "moving") [V/d]."""
    s = np.asarray(distance_d, dtype=float)
    order = np.argsort(s)
    s, u = s[order], np.asarray(u, dtype=float)[order]
    rate = -np.diff(u) / np.diff(s)
    return tuple(float(r) for r in (rate[::-1] if smoother == "fixed" else rate))


def smoother_wall(meta: Mapping[str, Any]) -> str | None:
    """Which wall of a run is the smoother, "fixed" or "moving", from its sidecar's ``wall``
    (the moving wall) and ``wall_fixed``; None when they are not of two ranked kinds
    (:data:`ROUGHNESS_RANK`)."""
    moving, fixed = meta.get("wall"), meta.get("wall_fixed")
    if not (isinstance(moving, Mapping) and isinstance(fixed, Mapping)):
        return None
    rm, rf = ROUGHNESS_RANK.get(str(moving.get("kind"))), ROUGHNESS_RANK.get(str(fixed.get("kind")))
    if rm is None or rf is None or rm == rf:
        return None
    return "fixed" if rf < rm else "moving"


def _walls_inertial_number(meta: Mapping[str, Any]) -> float | None:
    """The largest local inertial number in the sidecar's bins next to either wall."""
    walls = meta.get("wall_inertial_number")
    if not isinstance(walls, Mapping):
        return None
    values = [
        float(v)
        for w in walls.values()
        if isinstance(w, Mapping)
        for v in w.get("per_bin", [])
        if isinstance(v, int | float) and math.isfinite(v)
    ]
    return max(values) if values else None


def layer_stress_ratio(run: Run) -> float | None:
    """The run's |shear|/normal stress ratio: the moving wall's (the sidecar's ``wall_stress``,
    from its contacts), else the band's (:func:`~.measures.band_stress_ratio`); None when
    neither is given [-]. Without gravity it is the same across the gap."""
    ws = run.meta.get("wall_stress")
    if isinstance(ws, Mapping):
        shear, normal = ws.get("shear"), ws.get("normal")
        if (
            isinstance(shear, int | float)
            and isinstance(normal, int | float)
            and math.isfinite(shear)
            and math.isfinite(normal)
            and normal > 0.0
            and shear != 0.0
        ):
            return abs(float(shear)) / float(normal)
    band = band_stress_ratio(run)
    return None if band is None else band.value


def band_inertial_number(meta: Mapping[str, Any], smoother: str) -> float | None:
    """The largest local inertial number in the sidecar's bins next to the ``smoother`` wall
    ("fixed" or "moving"), where the band is (None when the sidecar does not give it) [-]."""
    walls = meta.get("wall_inertial_number")
    if not isinstance(walls, Mapping) or walls.get("moving") not in ("upper", "lower"):
        return None
    moving = str(walls["moving"])
    side = moving if smoother == "moving" else ("lower" if moving == "upper" else "upper")
    record = walls.get(side)
    values = [
        float(v)
        for v in (record.get("per_bin", []) if isinstance(record, Mapping) else [])
        if isinstance(v, int | float) and math.isfinite(v)
    ]
    return max(values) if values else None


def measure_layer(
    run: Run, fits: RunFits | None = None, alternatives: bool = True
) -> LayerPosition | None:
    """The :class:`LayerPosition` of a plane run without gravity whose walls differ (None for
    any other run), with each fitted model's predicted asymmetry when ``fits`` are given and
    the alternatives' fits (:func:`~.layer_alternatives.layer_alternatives`) unless
    ``alternatives`` is False or the run gives no stress ratio."""
    smoother = smoother_wall(run.meta)
    if run.cell != "plane" or smoother is None or run.B > NO_GRAVITY_B:
        return None
    u, se = run.quantity("u")
    ok = np.isfinite(u) & np.isfinite(se) & (se > 0.0)
    d = run.distance_d[ok]
    fixed, _, moving, _ = jump_fractions(d, u[ok], se[ok], run.gap_d)
    rho = velocity_correlation(run)
    fixed_se, moving_se, r = jump_covariance(d, se[ok], run.gap_d, rho)
    predicted: dict[str, float] = {}
    if fits is not None:
        for m in fits.models:
            try:
                c = fits.curve(m, np.array([WITHIN_D, run.gap_d - WITHIN_D]))
            except Exception:  # a model that failed to fit predicts nothing here
                continue
            f_moving, f_fixed = 1.0 - float(c[0]), float(c[1])
            if math.isfinite(f_moving) and math.isfinite(f_fixed):
                predicted[m] = f_fixed - f_moving if smoother == "fixed" else f_moving - f_fixed
    ratio = layer_stress_ratio(run)
    alts: tuple[LayerAlternative, ...] = ()
    note = ""
    if alternatives and ratio is not None and rho < 1.0:
        data = LayerData.from_run(d, u[ok], se[ok], run.gap_d, smoother, rho, ratio)
        alts, note = layer_alternatives(data)
    elif alternatives:
        note = "no alternatives: the run gives no stress ratio (wall_stress or sigma columns)"
    return LayerPosition(
        run.name,
        fixed,
        fixed_se,
        moving,
        moving_se,
        smoother,
        WITHIN_D,
        _walls_inertial_number(run.meta),
        predicted,
        r,
        rho,
        shear_rates(d, u[ok], smoother),
        alts,
        ratio,
        note,
    )


def _run_text(p: LayerPosition) -> str:
    return (
        f"{p.run} ({p.smoother} wall smoother): f_fixed = {p.fixed:.3f} +- {p.fixed_se:.2g}, "
        f"f_moving = {p.moving:.3f} +- {p.moving_se:.2g}, a = {p.asymmetry:+.3f} +- "
        f"{p.asymmetry_se:.2g} (bin correlation {p.bin_correlation:.2g}, the walls' errors "
        f"correlated at {p.u_correlation:.2f})"
        + (
            ""
            if not p.shear_rate
            else "; du/dy [V/d] bin to bin from the smoother wall: "
            + ", ".join(f"{g:.3f}" for g in p.shear_rate)
        )
    )


FAMILIES = {
    "mui": "local mu(I) with a Coulomb wall",
    "ngf": "NGF with a wall fluidity",
    "cosserat": "the Cosserat layer profile",
}
"""The alternatives' families, by the prefix of their keys."""


def _best(alts: Sequence[LayerAlternative], family: str) -> LayerAlternative | None:
    """The family's alternative with the smallest chi^2 per dof."""
    own = [x for x in alts if x.key.split("-")[0] == family]
    return min(own, key=lambda x: x.chi2 / max(x.dof, 1)) if own else None


def _alternatives_text(p: LayerPosition) -> str:
    """One run's alternatives and what the shear rate's decay tells (module docstring)."""
    if not p.alternatives:
        return f" {p.run}: {p.alternatives_note}." if p.alternatives_note else ""
    n = p.alternatives[0].dof + len(p.alternatives[0].fitted)
    rows = "; ".join(x.text for x in p.alternatives)
    best = {f: b for f in FAMILIES if (b := _best(p.alternatives, f)) is not None}
    fits = [
        f"{FAMILIES[f]} chi^2 = {b.chi2:.1f}/{b.dof}" + ("" if b.decays else " (no decay)")
        for f, b in best.items()
    ]
    within = [b for b in best.values() if chi2_dist.sf(b.chi2, b.dof) >= P_SIGNIFICANT]
    decay = [FAMILIES[f] for f, b in best.items() if b.decays]
    local = [b for f, b in best.items() if not b.decays]
    return (
        f" {p.run}, the alternatives against all {n} bins (chi^2 with the bins' AR(1) "
        f"covariance, rho = {p.bin_correlation:.2g}; dof = bins - fitted parameters; the stress "
        f"ratio {p.stress_ratio:.3g} uniform): {rows}. The discriminating observation is the "
        "shear rate decaying away from the smoother wall under the uniform stress (du/dy "
        "above): a local rheology shears uniformly under uniform stress whatever its mu_s "
        "(unmeasured here), so it gives a linear profile or a rigid block"
        + (
            f" and misses the decay (best chi^2 = {min(b.chi2 for b in local):.1f})"
            if local
            else ""
        )
        + "; "
        + (" and ".join(decay) + " reproduce it" if decay else "no alternative here reproduces it")
        + ", so it tells a nonlocal model from a local one, not the Cosserat model from NGF. "
        + "Best of each: "
        + ", ".join(fits)
        + "; "
        + (
            "consistent with the errors (p >= "
            f"{P_SIGNIFICANT:g}): " + ", ".join(f"{x.label}" for x in within)
            if within
            else f"none within the errors (each p < {P_SIGNIFICANT:g})"
        )
        + (f"; {p.alternatives_note}" if p.alternatives_note else "")
        + ". References: "
        + "; ".join(f"{k}: {v}" for k, v in REFERENCES.items())
        + "."
    )


def layer_position_verdict(positions: Sequence[LayerPosition]) -> LayerVerdict:
    """The verdict on :data:`LAYER_CLAIM` from the runs' :class:`LayerPosition` (module
    docstring: the rule)."""
    runs = tuple(p.run for p in positions)
    if not positions:
        return LayerVerdict(
            LAYER_KEY,
            "undecided",
            "No plane run without gravity whose walls differ.",
            "a plane run with B = 0 between a smooth and a rough wall (docs/dem.md).",
        )
    w = np.array([1.0 / p.asymmetry_se**2 for p in positions])
    a_runs = np.array([p.asymmetry for p in positions])
    a = float(np.sum(w * a_runs) / np.sum(w))
    se = float(1.0 / math.sqrt(np.sum(w)))
    z = a / se
    models = sorted({m for p in positions for m in p.predicted})
    predicted = {
        m: float(np.mean([p.predicted[m] for p in positions if m in p.predicted])) for m in models
    }
    signs = {
        int(np.sign(p.asymmetry)) for p in positions if abs(p.asymmetry) >= SIGMAS * p.asymmetry_se
    }
    method = (
        f"Method: the fraction of the walls' velocity difference within {positions[0].within_d:g} "
        "d of each wall (slip included), a = f_smoother - f_rougher per run, the inverse-variance "
        f"mean over runs; the band is placed at |a| >= {SIGMAS:g} se. Error model: the bins' u "
        "errors an AR(1) sequence, corr = rho^|i - j| over bin index, rho the sidecar's "
        "bin_correlation.u (0 where none), propagated through the interpolation weights; "
        "runs independent."
    )
    pred_text = (
        " validate's single-run fits (not predictions of the layer: they give the fixed wall the "
        "moving wall's kind): " + ", ".join(f"{m} a = {v:+.3f}" for m, v in predicted.items()) + "."
        if predicted
        else ""
    )
    sliding = (1.0 - abs(a)) / se
    reading = (
        " a = 0 is uniform shear (mu(I) or NGF with no-slip walls and no wall fluidity), "
        f"{abs(z):.1f} se away; rigid sliding on the smoother wall (a = 1), which a local "
        "rheology with a Coulomb wall at that wall's measured friction gives when it is below "
        f"mu_s, is {sliding:.1f} se away. The side of the band alone does not tell the "
        "Cosserat model from wall friction." + "".join(_alternatives_text(p) for p in positions)
    )
    walls_i = [p.wall_inertial_number for p in positions if p.wall_inertial_number is not None]
    regime_text = (
        f" Regime: the local inertial number next to either wall (the band's side included) is "
        f"at most {max(walls_i):.2g} (quasi-static bound I <= {QUASI_STATIC_I:g})."
        if len(walls_i) == len(positions)
        else " Regime: not every run gives its inertial number next to both walls."
    )
    evidence = (
        f"a = {a:+.3f} +- {se:.2g} ({z:+.1f} se) over {len(positions)} run(s): "
        + "; ".join(_run_text(p) for p in positions)
        + "."
        + reading
        + pred_text
        + " "
        + method
        + regime_text
    )
    cosserat = predicted.get("cosserat")
    if len(signs) > 1:
        verdict, change = "mixed", "more runs: the runs place the band at opposite walls."
    elif z >= SIGMAS:
        verdict = "supported"
        change = (
            f"runs at larger gaps or other seeds with a < {SIGMAS:g} se (one seed at one gap "
            "here). The band's side is the claim; its shape (the alternatives above) does not "
            "tell the Cosserat model from NGF with a wall fluidity."
        )
    elif z <= -SIGMAS:
        verdict, change = "refuted", "runs placing the band at the smoother wall."
    elif cosserat is not None and cosserat - a >= SIGMAS * se:
        verdict = "refuted"
        change = (
            f"the Cosserat model fitted to the same runs predicts a = {cosserat:+.3f}, "
            f"{(cosserat - a) / se:.1f} se above the measured; a calibration giving a smaller "
            "asymmetry, or runs showing one."
        )
    else:
        verdict = "undecided"
        change = f"errors small enough to place the band (|a| >= {SIGMAS:g} se)."
    numbers = {
        "asymmetry": a,
        "asymmetry_se": se,
        "z": z,
        "predicted": predicted,
        "runs": [p.to_dict() for p in positions],
    }
    known = [p.wall_inertial_number for p in positions if p.wall_inertial_number is not None]
    if verdict != "undecided" and len(known) == len(positions) and min(known) > QUASI_STATIC_I:
        return LayerVerdict(
            LAYER_KEY,
            "undecided",
            f"Not tested in the model's regime: every run used has I up to {min(known):.2g}-"
            f"{max(known):.2g} next to its walls, above the slow-flow bound I <= "
            f"{QUASI_STATIC_I:g}. At these rates the data would say {verdict}: {evidence}",
            f"runs with I <= {QUASI_STATIC_I:g} next to both walls; then: {change}",
            runs,
            {**numbers, "at_these_rates": verdict},
        )
    return LayerVerdict(LAYER_KEY, verdict, evidence, change, runs, numbers)


def layer_verdicts(
    runs: Sequence[Run],
    fits: Mapping[str, RunFits | None] | None = None,
    measured: Mapping[str, LayerPosition] | None = None,
) -> list[Verdict]:
    """``[layer_position_verdict(...)]`` on the runs :func:`measure_layer` measures (or the
    positions ``measured`` already, by run name), or ``[]`` when a corpus has none (the
    claim is then not judged)."""
    fits, measured = fits or {}, measured or {}
    positions = [
        p
        for r in runs
        if (p := measured.get(r.name) or measure_layer(r, fits.get(r.name))) is not None
    ]
    return [layer_position_verdict(positions)] if positions else []


__all__ = [
    "LAYER_CLAIM",
    "LAYER_KEY",
    "NO_GRAVITY_B",
    "QUASI_STATIC_I",
    "ROUGHNESS_RANK",
    "SIGMAS",
    "WITHIN_D",
    "LayerPosition",
    "LayerVerdict",
    "band_inertial_number",
    "jump_covariance",
    "jump_fractions",
    "layer_position_verdict",
    "layer_stress_ratio",
    "layer_verdicts",
    "measure_layer",
    "shear_rates",
    "smoother_wall",
]
