"""Verdicts on the paper's claims: small pure functions of measured quantities.

Each takes what was measured (:class:`~cosserat.studies.validate.measures.WallSpin` per run
and wall, :class:`DeltaSeries` per gap series) and returns a :class:`Verdict`: the claim,
"supported", "refuted", "mixed" or "undecided", the evidence (the method, the numbers, the
p-values, the runs used) and what data would change it. The rules:

* **spin departs** (:func:`spin_verdict`): each sheared wall of each run is tested on its own:
  chi^2 of z = (omega - half vorticity - null)/se over its near-wall bins, whitened with the
  bins' AR(1) correlation, the null being what the measurement reports for grains that turn
  with the material (``WallSpin.null``: in the joint u + omega + stress-ratio fit's velocity,
  the one ``spin_model`` judges, with its error in quadrature; an envelope of nulls is an
  interval, :mod:`.nulls`). The first layer's departure beyond the null is formed under every
  difference stencil (:data:`~cosserat.studies.validate.forward.STENCILS`), the null
  forward-modelled under each; a wall where it changes sign between them is tested without
  its first layer; every test is made under each stencil and the verdict taken under the one
  where it is weakest (a run departs when it does under every stencil). A run's test adds its
  sheared walls, the pooled test adds every run's (degrees of freedom added; runs taken as
  independent). A sheared wall whose null is not determined (``WallSpin.no_null``) is
  reported, not judged, with what judging it against the null it carries would change. The
  power is stated against the joint fit's departure beyond the null (``WallSpin.joint``; else
  a usable u-only fit's, never one in ``unfit``) and against a model-free
  :data:`DETECT_SIZE` in the bins beyond the first layers. "supported" when the pooled p <
  :data:`P_SIGNIFICANT` and at least half the runs show a departure at p <
  :data:`P_CONSISTENT` ("mixed" when fewer do: the pooled result rests on a few runs; a run
  that does not depart and whose errors would not have shown the predicted departure at p <
  :data:`P_CONSISTENT` counts neither way, unless its fit supplies no prediction,
  ``unfit``: then it counts as not departing); the evidence names the bins with |z| >=
  :data:`CARRY_Z` the departure rests on (with p under t(blocks - 1), the se coming from the
  blocks) and the walls where none is detected; "refuted" when the pooled p >=
  :data:`P_CONSISTENT` although the predicted departure would have given a pooled p <
  :data:`P_SIGNIFICANT` at these errors; "undecided" otherwise.
* **the model's departure** (:func:`spin_model_verdict`): at each sheared wall, the measured
  departure in the first layer (the bin nearest to the wall, where the departure is largest) m
  +- s against the model's there, p_m, forward-modelled as the data are measured
  (:mod:`~cosserat.studies.validate.forward`). The measured sign is determined where it is the
  same under every stencil (and the model's too) and |m| >= :data:`SIGN_SIGMAS` s under at
  least one. "refuted" where the model departs with the opposite sign at every wall
  of determined sign (however small its departure), or with the right sign but a size the data
  reject (pooled chi^2 of (departure - model)/se, p < :data:`P_SIGNIFICANT`), or predicts none
  (|p_m| <= :data:`NO_DEPARTURE`, a rheology without a spin of its own) where the data depart;
  "supported" when the sign agrees everywhere it is determined and the size is not rejected;
  "mixed" when the sign agrees at some walls and is opposite at others. When no wall has a
  determined sign: "refuted" if the model's departure is rejected all the same (chi^2 of
  data - model over every sheared wall's near-wall bins, p < :data:`P_SIGNIFICANT`: the model
  predicts a departure these errors would see and the data have none), else "undecided".
  Only usable fits predict: walls of runs whose fit contradicts the measured stress ratio or
  holds a wall parameter at a search cut (``unfit``) decide nothing; with no other wall the
  verdict is "undecided", and what they would say is kept (``with_contradicting_fits``).
* **Delta against the gap** (:func:`delta_law_verdict`): in each relevant series, the measured
  Delta(H/d) against each model's Delta from one joint calibration of the series' material
  (every run of its material on its cell, every wall kind; read with the series' own wall:
  :class:`ModelDelta`; :func:`curve_test`: chi^2 with the two errors in quadrature, as it is
  and up to a common factor, which tests the dependence on the gap). "supported" when the
  Cosserat curve's shape has p >= :data:`P_CONSISTENT` and an alternative (another model's
  curve, or the other claim's power law with a free level, :func:`power_law_test`) has p <
  :data:`P_SIGNIFICANT`; "refuted" when the Cosserat curve's shape has p < :data:`P_SIGNIFICANT`,
  "mixed" instead when the claimed law itself (the claimed exponent, free level) has p >=
  :data:`P_CONSISTENT` (the data follow the limit law, not the model's approach to it);
  "undecided" otherwise. The slope s +- se of ln Delta against ln(H/d) (weighted by the errors
  of Delta, at least :data:`MIN_GAPS` gaps) is judged only where the Cosserat curve's own slope
  over the series' gaps is within :data:`EXPONENT_TOL` of the claimed limit (the range allows
  it): a claimed exponent c is then "supported" when |s - c| <= 2 se and the other claimed
  exponent c' is excluded (|s - c'| > 2 se), "refuted" when |s - c| > 2 se. Without a curve, the
  slope rule alone, as before (refuted unless the data agree within 2 se with the slope of
  the Cosserat fits to the same runs). Runs whose band fills its gap are left out (they cannot
  test a law of the gap, either way). Series that disagree make the verdict "mixed".
"""

from __future__ import annotations

import functools
import itertools
import math
import re
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np
from scipy.stats import chi2 as chi2_dist
from scipy.stats import norm
from scipy.stats import t as student_t

from ..._text import significance
from ...analysis.gap import PAPER_SLOPES, SlopeFit, power_law_slope
from ...calibration.noise import whiten
from ...errors import ParameterError
from ...model.constitutive import FloatArray
from .forward import STENCILS
from .measures import (
    FAR_SLIP_SIGMAS,
    FILLS_GAP,
    JOINT_NULL_NAME,
    JOINT_NULL_SOURCE,
    P_SIGNIFICANT,
    WallSpin,
    chi2_p,
)

P_CONSISTENT = 0.05
"""A test with p at or above this shows no departure [-]."""
SIGN_SIGMAS = 3.0
"""The measured departure's sign is determined when |first layer| >= this many standard
errors."""
MIN_GAPS = 3
"""Fewest gaps for a verdict on how Delta scales with the gap."""
NO_DEPARTURE = 1e-9
"""A model's departure below this is none (a rheology without a spin of its own) [-]."""
SAME_GAP = 0.05
"""Gaps within this relative difference are one gap (replicates) [-]."""
EXPONENT_TOL = 0.05
"""The measured exponent is judged only where the Cosserat model's own curve, calibrated on
the series, has a log-log slope within this of the claimed limit over the series' gaps [-]."""
PRECISION_DESIGNS: tuple[tuple[tuple[float, ...], int], ...] = (
    ((1.0, 2.0, 4.0), 1),
    ((1.0, 2.0, 4.0), 3),
)
"""Gap designs (H/d in units of the smallest gap, runs per gap) whose slope error
:func:`precision_needed` gives at the window where the slope rule can judge the exponent
(:func:`slope_window`; :data:`DESIGN_START` where the curve gives none): three gaps a factor 2
apart across that factor-4 window, one and three seeds each (referee 14, point 1: the designs
are sized where the rule judges, not at 20/40/80 d, which test only the finite-H curve)."""
SEED_DESIGNS: tuple[tuple[tuple[float, ...], int], ...] = (
    ((1.0, 2.0, 4.0), 1),
    ((1.0, 2.0, 4.0), 2),
    ((1.0, 2.0, 4.0), 3),
)
"""Gap designs (as :data:`PRECISION_DESIGNS`) whose slope error :func:`precision_needed` also
gives at the run-to-run scatter of Delta the same-conditions replicates show
(:func:`seed_scatter`; referee 12, point 3): one, two and three seeds per gap."""
DESIGN_START = 20.0
"""The smallest gap [d] of the designs where the curve gives no window (20/40/80 d)."""
DEM_GAP_COSTED = 160.0
"""The largest gap [d] the DEM design costs (docs/dem.md, 'Cost': a plane run at H = 160 d,
48.9 CPU-hours): a window of gaps starting beyond it is out of DEM's reach here, so the
exponent there cannot be judged by DEM at feasible gaps (referee 14, point 1)."""

CLAIMS = {
    "spin": "The grain spin departs from half the vorticity near the walls.",
    "smoother": "Delta is independent of the gap H/d for walls smoother than the material.",
    "rough": "Delta grows as (H/d)^(1/3) for fully rough walls (under gravity, or in Couette "
    "flow).",
    "spin_model": "The spin departs from half the vorticity with the sign and size the "
    "Cosserat model predicts (fitted to the same velocities).",
}
"""The claims judged, by key, in the order of the report."""
VERDICTS = ("supported", "refuted", "mixed", "undecided")
SLOW_FLOW_CLAIMS = ("smoother", "rough", "spin_model")
"""Claims about the rate-independent models' predictions, which hold for slow flow only:
data outside that regime neither support nor refute them (:func:`within_regime`)."""


@dataclass(frozen=True)
class Verdict:
    """A verdict on one claim, with its evidence and what would change it."""

    key: str
    verdict: str
    evidence: str
    would_change: str = ""
    runs: tuple[str, ...] = ()
    numbers: Mapping[str, Any] = field(default_factory=dict)
    qualifier: str = ""
    """The condition or scope the verdict holds under, shown beside it wherever the verdict is
    (e.g. spin "supported" *given a velocity smooth on the grain scale*; referee 10, point 3);
    empty when the verdict stands alone."""
    summary: str = ""
    """The headline numbers the evidence leads with, in a few sentences (:mod:`.summaries`),
    set where the verdicts are assembled; empty: none (the report then shows the evidence in
    place)."""

    @property
    def claim(self) -> str:
        return CLAIMS[self.key]

    @property
    def text(self) -> str:
        """The evidence and what would change the verdict, in one paragraph."""
        return self.evidence + (
            f" What would change it: {self.would_change}" if self.would_change else ""
        )

    def to_dict(self) -> dict[str, Any]:
        return {
            "key": self.key,
            "claim": self.claim,
            "verdict": self.verdict,
            "qualifier": self.qualifier,
            "summary": self.summary,
            "evidence": self.evidence,
            "would_change": self.would_change,
            "runs": list(self.runs),
            "numbers": dict(self.numbers),
            "text": self.text,
        }


def _g(x: float | None, spec: str = ".3g") -> str:
    return "-" if x is None else format(x, spec)


P_AS_Z = 1e-6
"""A chi^2 p-value below this is reported as the equivalent normal z and chi^2/dof (a p of
1e-41 means nothing beyond "far out": the error model is not that exact)."""


def log_chi2_sf(chi2: float, dof: int) -> float:
    """ln of chi^2's p-value with ``dof`` degrees of freedom, without underflow: scipy's where
    p is representable, else the asymptotic series of the upper incomplete gamma function
    Q(a, x) ~ x^(a-1) e^(-x) / Gamma(a) (1 + (a-1)/x + (a-1)(a-2)/x^2 + ...) [-]."""
    p = float(chi2_dist.sf(chi2, dof))
    if p > 1e-280:
        return math.log(p)
    a, x = 0.5 * dof, 0.5 * chi2
    term, total = 1.0, 1.0
    for k in range(1, 30):
        term *= (a - k) / x
        if abs(term) < 1e-16:
            break
        total += term
    return (a - 1.0) * math.log(x) - x - math.lgamma(a) + math.log(total)


def equivalent_z(chi2: float, dof: int) -> float:
    """The one-sided standard-normal z of chi^2's p-value with ``dof`` degrees of freedom,
    from the log of p (no underflow) [-]."""
    logp = log_chi2_sf(chi2, dof)
    if logp >= math.log(0.5):
        return float(norm.isf(math.exp(logp)))
    lo, hi = 0.0, 1.0
    while float(norm.logsf(hi)) > logp:
        lo, hi = hi, 2.0 * hi
    for _ in range(100):  # norm.logsf falls with z: bisect
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if float(norm.logsf(mid)) > logp else (lo, mid)
    return 0.5 * (lo + hi)


def p_text(chi2: float | None, dof: int, p: float | None) -> str:
    """ "p = ..." or, below :data:`P_AS_Z`, "z = ..., chi^2/dof = .../..."."""
    if chi2 is None or p is None or dof <= 0:
        return "p = -"
    if p >= P_AS_Z:
        return f"p = {p:.2g}"
    return f"z = {equivalent_z(chi2, dof):.3g}, chi^2/dof = {chi2:.4g}/{dof}"


def _test_text(t: tuple[float | None, int, float | None]) -> str:
    c, n, p = t
    return f"chi^2 = {_g(c, '.4g')} for {n} bins ({p_text(c, n, p)})"


def _stencil_text(w: WallSpin, models: Sequence[str]) -> str:
    """The first layer's departure under each stencil, of the data and each model."""
    if not w.stencils:
        return ""
    values = ", ".join(f"{k} {v[0]:+.3g}" for k, v in w.stencils.items())
    out = (
        f"; first layer by stencil: {values} (sign "
        + ("stencil-dependent" if w.stencil_dependent() else "the same under all")
        + ")"
    )
    for m in models:
        v = w.predicted_stencils.get(m)
        if not v:
            continue
        lo, hi = min(v.values()), max(v.values())
        state = "stencil-dependent" if w.stencil_dependent(m) else "same sign"
        out += f"; {m} as measured {lo:+.3g} to {hi:+.3g} ({state})"
    return out


def _stencils_of(walls: Sequence[WallSpin]) -> list[str]:
    """The stencils the walls' first layers are given under (the analysis' alone without)."""
    return [s for s in STENCILS if any(s in w.stencils for w in walls)] or ["analysis"]


def _decisive(w: WallSpin, stencil: str = "analysis") -> FloatArray:
    """The whitened departures beyond the null a wall's test rests on, the first layer under
    ``stencil``: every near-wall bin, or without the first layer where its departure beyond
    the null changes sign between the stencils (:meth:`WallSpin.beyond_dependent`)."""
    return w.z_under(stencil, rest=w.beyond_dependent())


def _pooled(walls: Sequence[WallSpin], stencil: str) -> tuple[float | None, int, float | None]:
    z = [_decisive(w, stencil) for w in walls]
    return chi2_p(np.concatenate(z) if z else np.zeros(0))


def _weakest(walls: Sequence[WallSpin]) -> str:
    """The stencil under which the walls' pooled test is least significant (the verdict
    holds under every stencil only if it holds under this one)."""
    return min(_stencils_of(walls), key=lambda s: _pooled(walls, s)[0] or 0.0)


def _prediction(w: WallSpin, model: str, unfit: Mapping[str, str]) -> tuple[FloatArray | None, str]:
    """The model's departure beyond the null at a wall's bins and whose it is: the joint
    u + omega + stress-ratio fit's (``WallSpin.joint``, the fit ``spin_model`` judges), else
    the u-only ``model`` fit's where it supplies a prediction (not in ``unfit``), else none
    (referee 8, point 5: never a fit the report rejects) [-]."""
    if w.joint is not None:
        return np.asarray(w.joint, dtype=float), "joint"
    if model in w.predicted and w.run not in unfit:
        null = 0.0 if w.null is None else np.asarray(w.null, dtype=float)
        return np.asarray(w.predicted[model], dtype=float) - null, model
    return None, ""


def _shift(w: WallSpin, model: str, unfit: Mapping[str, str]) -> float:
    """The chi^2 the predicted departure beyond the null (:func:`_prediction`) adds to noise
    over the bins of :func:`_decisive` [-]."""
    pred, _ = _prediction(w, model, unfit)
    if pred is None:
        return 0.0
    order = np.argsort(w.distance_d)[1 if w.beyond_dependent() else 0 :]
    se = np.asarray(w.se_beyond, dtype=float)
    return float(np.sum(whiten(pred[order], se[order], w.rho) ** 2))


DETECT_SIZE = 0.05
"""The model-free departure the spin claim's power is stated against: omega d / V - half
the vorticity of this size, one sign, in every near-wall bin beyond the first layer [-]."""


def _shift_free(w: WallSpin) -> tuple[float, int]:
    """The chi^2 a departure of :data:`DETECT_SIZE` in every near-wall bin beyond the first
    layer adds to noise, and those bins' number [-]."""
    order = np.argsort(w.distance_d)[1:]
    se = np.asarray(w.se_beyond, dtype=float)[order]
    z = whiten(np.full(order.size, DETECT_SIZE), se, w.rho)
    return float(np.sum(z**2)), int(order.size)


def _null_text(w: WallSpin) -> str:
    """The null in the first layer and where it comes from ("" without one)."""
    if w.null is None:
        return ""
    k = w.nearest
    if w.null_range is not None:
        value = (
            f"{float(np.asarray(w.null_range[0])[k]):+.3g} to "
            f"{float(np.asarray(w.null_range[1])[k]):+.3g}"
        )
    else:
        se = 0.0 if w.null_se is None else float(np.asarray(w.null_se)[k])
        value = f"{float(np.asarray(w.null)[k]):+.3g}" + (f" +- {se:.2g}" if se > 0.0 else "")
    source = w.null_source or f"the {w.null_model} fit's velocity"
    return (
        f", of which the binning and the stencil make {value} (grains turning with the "
        f"material in {source})"
    )


def _beyond_text(w: WallSpin) -> str:
    """The first layer's departure beyond the null under each stencil."""
    if w.null is None or not w.stencils:
        return ""
    values = ", ".join(
        f"{s} {b:+.3g} +- {se:.2g}" for s in w.stencils for b, se in [w.beyond_first(s)]
    )
    state = "stencil-dependent" if w.beyond_dependent() else "the same under all"
    return f"; first layer beyond the null by stencil: {values} (sign {state})"


def _walls_text(walls: Sequence[WallSpin], models: Sequence[str] = ()) -> str:
    rows = []
    for w in walls:
        rows.append(
            f"{w.run} ({w.wall} wall, {w.dof} bins within {float(np.max(w.distance_d)):.2g} d, "
            f"rho = {w.rho:.2g}): first layer {_g(w.first, '+.3g')} +- {_g(w.first_se, '.2g')}"
            f"{_null_text(w)}; beyond that {_test_text(chi2_p(w.z))}, without the first layer "
            f"{_test_text(chi2_p(w.z_rest))}"
            + (f"; against 0: {_test_text(chi2_p(w.z_zero))}" if w.null is not None else "")
            + _stencil_text(w, models)
            + _beyond_text(w)
        )
    return "; ".join(rows)


CARRY_Z = 3.0
"""A near-wall bin whose whitened departure beyond the null has |z| at or above this is named
as one the spin verdict rests on [-]."""


def t_p(z: float, blocks: int) -> float | None:
    """Two-sided p of ``z`` read as Student's t with ``blocks - 1`` degrees of freedom (the
    standard error comes from ``blocks`` time blocks; None when not recorded) [-]."""
    if blocks < 2:
        return None
    return float(2.0 * student_t.sf(abs(z), blocks - 1))


T_SAMPLES = 200_000
"""Draws of :func:`pooled_t_p`'s seeded Monte Carlo (its p is good to about 10% at 1e-3)."""


def pooled_t_p(chi2: float | None, dof: int, blocks: int, samples: int = T_SAMPLES) -> float | None:
    """p of a pooled chi^2 of ``dof`` bins with each bin's z read as Student's t with
    ``blocks - 1`` degrees of freedom, as a bin's p is (:func:`t_p`; referee 9, point 1): the
    tail of a sum of ``dof`` independent F(1, blocks - 1) variables (each t^2), by a seeded
    Monte Carlo of ``samples`` draws (the same number every call), floored at one draw
    [-]. None when the blocks are not recorded or there is no test.
    """
    counted = pooled_t_count(chi2, dof, blocks, samples)
    if counted is None:
        return None
    return float((counted[0] + 1) / (counted[1] + 1))


def pooled_t_count(
    chi2: float | None, dof: int, blocks: int, samples: int = T_SAMPLES
) -> tuple[int, int] | None:
    """:func:`pooled_t_p`'s Monte Carlo as (exceedances, draws): the number of draws whose
    sum is at or above ``chi2``, and ``samples``; p = (exceedances + 1) / (draws + 1)
    (referee 12, point 7). None where :func:`pooled_t_p` is."""
    if chi2 is None or blocks < 2 or dof < 1 or not math.isfinite(chi2):
        return None
    sums = _t_sorted(dof, blocks, samples)
    return int(sums.size - np.searchsorted(sums, chi2, side="left")), int(samples)


@functools.lru_cache(maxsize=8)
def _t_sorted(dof: int, blocks: int, samples: int) -> FloatArray:
    """:func:`_t_sums` sorted ascending and read-only (cached: the verdict reads one set of
    draws at several chi^2, :func:`seed_factor_rows`, and :func:`crossing_factor` reads its
    k-th largest) [-]."""
    out = np.sort(_t_sums(dof, blocks, samples))
    out.flags.writeable = False
    return out


def crossing_factor(
    chi2: float | None, dof: int, blocks: int, line: float = P_SIGNIFICANT,
    samples: int = T_SAMPLES,
) -> float | None:  # fmt: skip
    """The factor F on every bin's se at which :func:`pooled_t_p` of the pooled chi^2 reaches
    ``line`` (referee 17, point 2) [-]. Exact over the Monte Carlo's draws, no bisection: F
    divides every whitened z by F and so chi^2 by F^2, and the p at F is the unscaled p at
    chi^2 / F^2 over the same seeded draws; p = (count + 1) / (draws + 1) >= ``line`` once at
    least k = ceil(line (draws + 1) - 1) draws are at or above chi^2 / F^2, i.e. chi^2 / F^2 <=
    s_k, the k-th largest draw: F = sqrt(chi^2 / s_k) (below 1 where the unscaled p is already
    at or above ``line``). None without a test or where ``line`` needs more draws than there
    are."""
    if chi2 is None or blocks < 2 or dof < 1 or not math.isfinite(chi2) or chi2 <= 0.0:
        return None
    k = max(1, math.ceil(line * (samples + 1) - 1.0 - 1e-9))
    if k > samples:
        return None
    sums = _t_sorted(dof, blocks, samples)
    return math.sqrt(chi2 / float(sums[sums.size - k]))


T_SEED = 20261127
"""The seed of :func:`pooled_t_count`'s Monte Carlo."""

_T_KEPT: dict[tuple[int, int, int], tuple[FloatArray, Mapping[str, Any]]] = {}
"""The sums of :func:`_t_sums` last made: (dof, blocks, samples) -> (the sums, read-only; the
generator's state after them)."""
_T_KEEP = 6
"""How many of them are kept (each ``samples`` floats: 1.6 MB at :data:`T_SAMPLES`)."""


def _t_sums(dof: int, blocks: int, samples: int) -> FloatArray:
    """The ``samples`` sums of ``dof`` F(1, blocks - 1) draws of :func:`pooled_t_count`, one
    bin's column at a time from the seeded generator. The first k columns are the same for
    every dof, so a sum over fewer columns made before is carried on from the generator's
    state after it rather than drawn again (a validate asks for 4 sums, two of them the
    others' first columns): the same additions in the same order, so the same floats."""
    key = (dof, blocks, samples)
    if key in _T_KEPT:
        return _T_KEPT[key][0]
    start = max(
        (k for k in _T_KEPT if k[0] <= dof and k[1:] == (blocks, samples)),
        key=lambda k: k[0],
        default=None,
    )
    rng = np.random.default_rng(T_SEED)
    if start is None:
        done, total = 0, np.zeros(samples)
    else:
        done, total = start[0], _T_KEPT[start][0].copy()
        rng.bit_generator.state = _T_KEPT[start][1]
    for _ in range(dof - done):  # one bin at a time: memory stays one column
        total += rng.f(1.0, blocks - 1.0, size=samples)
    total.flags.writeable = False
    if len(_T_KEPT) >= _T_KEEP:
        del _T_KEPT[next(iter(_T_KEPT))]
    _T_KEPT[key] = (total, rng.bit_generator.state)
    return total


def mc_error(count: int, draws: int) -> float:
    """The relative Monte Carlo error of p = (count + 1) / (draws + 1), sqrt((1 - p) / ((count
    + 1))), about 1 / sqrt(count + 1) [-]: the binomial error of the exceedance fraction over
    the fraction."""
    p = (count + 1) / (draws + 1)
    return math.sqrt((1.0 - p) / (count + 1))


def at_the_line(p: float, count: int, draws: int) -> bool:
    """A Monte Carlo p within its own Monte Carlo error of :data:`P_SIGNIFICANT`,
    |p - P_SIGNIFICANT| <= :func:`mc_error` x p (referee 13, point 6): it is neither above
    nor below the line."""
    return abs(p - P_SIGNIFICANT) <= mc_error(count, draws) * p


def mc_p_text(p: float, count: int, draws: int, line: bool = False) -> str:
    """A Monte Carlo p with its exceedances, draws and relative error, e.g. "p = 0.00095 (189
    of 200,000 draws at or above, MC error +-7%)" (referee 12, point 7); with ``line``, a p
    :func:`at_the_line` reads "p ~ 0.001 (0.00099: 197 of 200,000 draws ...)", not below or
    above it (referee 13, point 6)."""
    tail = (
        f"{count:,} of {draws:,} draws at or above, MC error "
        f"+-{100.0 * mc_error(count, draws):.2g}%)"
    )
    if line and at_the_line(p, count, draws):
        return f"p ~ {P_SIGNIFICANT:g} ({p:.2g}: {tail}"
    return f"p = {p:.2g} ({tail}"


def carrying_bins(w: WallSpin, stencil: str = "analysis") -> list[dict[str, float | None]]:
    """The bins of a wall's test (every near-wall bin, or all but the first layer where its
    departure beyond the null changes sign between stencils), the first layer under
    ``stencil``, with |z| >= :data:`CARRY_Z`: distance from the wall [d], departure beyond the
    null and its se (the null's in quadrature) [-], whitened z [-], p of z under
    t(blocks - 1) (None when the blocks are not recorded), and the bin against its own null
    envelope over every velocity the run has (:func:`bin_null_envelope`, the analysis'
    stencil; referee 11, point 1): ``null_lo``, ``null_hi`` [-] and ``inside_null_envelope``
    (None where the null is one velocity's, without an envelope)."""
    full = np.argsort(w.distance_d)
    order = full
    beyond = np.array(w.beyond, dtype=float)
    se = np.array(w.se_beyond, dtype=float)
    beyond[w.nearest], se[w.nearest] = w.beyond_first(stencil)
    if w.beyond_dependent():
        order = order[1:]
    z = _decisive(w, stencil)
    dist = np.asarray(w.distance_d, dtype=float)[order]
    enveloped = w.null_every is not None or w.null_range is not None
    out = []
    for i in range(z.size):
        if abs(float(z[i])) < CARRY_Z:
            continue
        e = bin_null_envelope(w, int(np.flatnonzero(full == order[i])[0])) if enveloped else None
        out.append(
            {
                "distance_d": float(dist[i]),
                "departure": float(beyond[order][i]),
                "se": float(se[order][i]),
                "z": float(z[i]),
                "p_t": t_p(float(z[i]), w.blocks),
                "null_lo": None if e is None else e["null_lo"],
                "null_hi": None if e is None else e["null_hi"],
                "inside_null_envelope": None if e is None else not e["outside"],
                "data": None if e is None else e["departure"],
            }
        )
    return out


def envelope_text(b: Mapping[str, Any]) -> str:
    """A carrying bin (:func:`carrying_bins`) against its own null envelope, in words: ", which
    lies inside its own null envelope (lo to hi, data d)" or "..., outside ..." ("" without an
    envelope)."""
    if b.get("inside_null_envelope") is None:
        return ""
    where = "inside" if b["inside_null_envelope"] else "outside"
    return (
        f", which lies {where} its own null envelope ({b['null_lo']:+.3g} to "
        f"{b['null_hi']:+.3g}, data {b['data']:+.3g})"
    )


def _carry_text(tested: Sequence[WallSpin], stencil: str = "analysis") -> str:
    """Which walls and bins carry the departure, and where none is detected."""
    parts = []
    for w in tested:
        for b in carrying_bins(w, stencil):
            under_t = (
                f", p = {b['p_t']:.2g} under t({w.blocks - 1})" if b["p_t"] is not None else ""
            )
            parts.append(
                f"{b['distance_d']:.2g} d from {w.run}'s {w.wall} wall ({b['departure']:+.3g} "
                f"+- {b['se']:.2g}, z = {b['z']:.3g}{under_t}){envelope_text(b)}"
            )
    # which se (referee 9, point 8): the first layer's under this stencil, with the null's
    which = (
        "with the sidecar's omega/half-vorticity r where recorded"
        if stencil == "analysis"
        else "omega and this stencil's half vorticity independent"
    )
    p_wall = [chi2_p(_decisive(w, stencil))[2] for w in tested]
    quiet = [w for w, p in zip(tested, p_wall, strict=True) if p is None or p >= P_CONSISTENT]
    n = len(parts)
    out = (
        f"the departure rests on {n} bin{'s' if n != 1 else ''} with |z| >= {CARRY_Z:g} (se "
        f"under the {stencil} stencil: the data's, {which}, and the null's in quadrature): "
        + "; ".join(parts)
        if parts
        else f"no bin departs by |z| >= {CARRY_Z:g}"
    )
    if quiet:
        out += (
            "; none detected at "
            + ", ".join(f"{w.run}'s {w.wall} wall" for w in quiet)
            + f" ({_test_text(chi2_p(np.concatenate([_decisive(w, stencil) for w in quiet])))})"
        )
    return out


SPIN_METHOD = (
    "Method: z = (omega - half vorticity - null)/se in the bins near each wall, the null "
    "being what the analysis reports where the grains turn with the material (omega = half "
    "the vorticity at every point) in a velocity, measured as the data are (bin averages of u "
    "and omega, the difference stencil): the velocity of the joint u + omega + stress-ratio "
    "fit that spin_model judges (one null for both verdicts), with its spread over that fit's "
    "95% region as its error; where a run has no joint fit, the envelope of the nulls it has "
    "(the u-only fits' velocities, the measured velocity's reconstructions) as a systematic "
    "interval (the departure beyond it is the distance to it, 0 inside); for a wall no fit "
    "describes, the measured velocity's (u's bin means reconstructed by several smooth "
    "interpolants of its integral, their envelope the interval). se = sqrt(se_omega^2 "
    "+ se_half^2 - 2 r se_omega se_half + se_null^2) (omega and half the vorticity come from "
    "the same particles and blocks: r is the per-bin correlation of their block means where "
    "the sidecar records it, else 0, 'independent (bound)', each run's notes saying which; "
    "r is recorded for the analysis stencil's half vorticity, so under the other stencils, "
    "which difference the binned u, omega and their half vorticity are taken as independent; "
    "an r from 10 blocks has a sampling sd of (1 - r^2)/3, 0.33 near 0; "
    "the largest error any correlation allows, se_omega + se_half, reported as a bound); "
    "neighbouring bins' errors correlated as an AR(1) sequence with the sidecar's "
    "bin_correlation of omega (else u's), z whitened; chi^2 = sum z^2 against no departure, "
    "one degree of freedom per bin; each sheared wall (the material next to it moves relative "
    "to it: |u(first bin) - u_wall| >= 0.05) tested on its own, a run's test adds its sheared "
    "walls, the pooled test adds the runs. The first layer's half vorticity depends on the "
    f"difference stencil: its departure and the null are given under {len(STENCILS)} "
    f"stencils ({', '.join(STENCILS)}), the null and the models forward-modelled as the data; "
    "the first layer is tested where its departure beyond the null has the same sign under "
    "all of them, else that wall's test rests on its other bins; every test is made under "
    "each stencil and the verdict taken under the one where it is weakest. A sheared wall "
    "that needs a null and has none is reported, not judged. Every se comes from the runs' "
    "time blocks (10 in the shipped runs: 9 degrees of freedom) and z is read as normal: "
    f"under t(9) z = 6.1 is p = {2.0 * float(student_t.sf(6.1, 9)):.2g}, not "
    f"{2.0 * float(norm.sf(6.1)):.2g}; the p of each bin the verdict rests on is given "
    "under t as well."
)

DECIDING_RUNS = (
    "the runs that would decide: more seeds at these conditions (run-to-run scatter), a "
    "second wall speed (rate independence), and a larger gap where the band does not fill it "
    "(a first layer and bins 2-3 away from the band's far edge)"
)
"""What the spin claim's data lack, named in its verdict whatever it is (referee 8, point 5)."""
DECIDING_RUNS_TWO_SPEEDS = (
    "the runs that would decide: more seeds at these conditions (run-to-run scatter; the "
    "runs of one cell at two wall speeds share one seed), and a larger gap where the band does "
    "not fill it (a first layer and bins 2-3 away from the band's far edge)"
)
""":data:`DECIDING_RUNS` where a cell is already run at two wall speeds (referee 10, point 2:
the stale request for a second wall speed dropped)."""
SMOOTH_VELOCITY = "given a velocity smooth on the grain scale"
"""What the spin's support holds under where it needs the first layers (referee 10, point 3;
:func:`needs_first_layers`); the qualifier says it as "(smooth on the grain scale)" after the
null's name (:func:`null_qualifier`)."""
NULL_MISFIT_P = 1e-3
"""The joint fit whose velocity is the null misfits a field (u or omega) whose chi^2 p is
below this (REFEREE.md's warning; ``spin_scan.MISFIT_P``)."""


def null_name(w: WallSpin) -> str:
    """The null a wall is tested against, in the qualifier's words: the joint fit's is "the
    joint Cosserat fit's velocity" (:data:`~.measures.JOINT_NULL_NAME`), any other its
    source."""
    if w.null_source == JOINT_NULL_SOURCE:
        return JOINT_NULL_NAME
    return w.null_source or f"the {w.null_model} fit's velocity"


def null_qualifier(tested: Sequence[WallSpin], smooth: bool) -> str:
    """The spin verdict's qualifier (referee 11, point 1): "beyond the null of" the nulls the
    tested walls used, each named once (:func:`null_name`), with "(smooth on the grain scale)"
    where the support needs the first layers (``smooth``, :func:`needs_first_layers`)."""
    names = sorted({null_name(w) for w in tested if w.null is not None})
    if not names:
        return SMOOTH_VELOCITY if smooth else ""
    return f"beyond the null of {' or '.join(names)}" + (
        " (smooth on the grain scale)" if smooth else ""
    )


def null_misfits(
    tested: Sequence[WallSpin], info: Mapping[str, SpinRun]
) -> dict[str, list[dict[str, Any]]]:
    """Run -> the fields, u or omega, whose chi^2 p is below :data:`NULL_MISFIT_P` in the
    joint fit whose velocity is that run's null (``SpinRun.joint_fit``; referee 11, point 1):
    ``field``, ``chi2``, ``n``, ``p``; runs whose fit describes both, or whose null is not the
    joint fit's, are left out."""
    out: dict[str, list[dict[str, Any]]] = {}
    for r in sorted({w.run for w in tested if w.null_source == JOINT_NULL_SOURCE}):
        bad = []
        for name, chi2, n in info[r].joint_fit if r in info else ():
            if n < 1 or not (name == "omega" or name == "u" or name.startswith("u,")):
                continue
            p = float(chi2_dist.sf(chi2, n))
            if p < NULL_MISFIT_P:
                bad.append({"field": name, "chi2": float(chi2), "n": int(n), "p": p})
        if bad:
            out[r] = bad
    return out


def _null_misfit_text(bad: Mapping[str, Sequence[Mapping[str, Any]]]) -> str:
    """The line on the null's own quality ("" where every joint fit whose velocity is a null
    describes u and omega)."""
    if not bad:
        return ""
    parts = []
    for r, rows in bad.items():
        fields: dict[str, list[str]] = {}  # u's error models grouped under u
        for b in rows:
            name, _, model = b["field"].partition(", ")
            fields.setdefault(name, []).append(
                (f"under {model} " if model else "")
                + f"chi^2 = {b['chi2']:.3g}/{b['n']}, p = {b['p']:.2g}"
            )
        parts.append(
            f"at {r} it misfits " + " and ".join(f"{f} ({'; '.join(t)})" for f, t in fields.items())
        )
    return (
        f" The null's own quality: the joint fit whose velocity is the null misfits "
        f"(p < {NULL_MISFIT_P:g}) at {len(bad)} run{'s' if len(bad) != 1 else ''}: "
        + "; ".join(parts)
        + "; there the departure is measured beyond a velocity that does not describe the "
        "run's own u and omega."
    )


@dataclass(frozen=True)
class SpinRun:
    """What the spin verdict says of a run beyond its walls' tests, from its sidecar.

    Attributes
    ----------
    cell : str
        The run's cell for counting: runs with the same ``cell`` differ only in wall speed
        (same cell, walls, gap and seed: ``rate.replicate_cells``) and are replicates of one
        cell ("" or the run's own name: a cell of its own).
    gap_d : float or None
        H/d [-].
    seed : object
        The sidecar's ``seed`` (None: not recorded).
    wall_speed : float or None
        V in the deck's units [sqrt(N/rho_s)].
    gravity : bool
        Plane shear under gravity (B > 0).
    inertial_number : float or None
        The moving wall's inertial number by the bin gradient [-].
    unsteady : str
        What the sidecar's steadiness test finds not steady ("" where steady or not
        recorded).
    joint_fit : tuple of (str, float, int)
        The joint fit whose velocity is the run's null, by field: (field, chi^2, bins), u
        also under other error models ("u, diagonal errors"); empty where not recorded
        (referee 11, point 1: the null's own quality).
    grains : mapping or None
        The sidecar's grain-by-grain record of the moving wall's first layers
        (``first_layer.walls[<moving wall>]``, ``cosserat.dem.first_layer``): ``u_1``,
        ``omega_1``, ``d_1``, the three ``departure_<W>`` of :data:`GRAIN_MEASURES`, each with
        ``<name>_se``, ``rolling``, ``grains_1`` (None: not recorded).
    grains_null : mapping or None
        The same measures of the joint fit's velocity with grains turning with the material
        (``forward.grain_layers``): the grain-scale null (None: no joint fit or no record).
    u_only : tuple of (str, float, int)
        The u-only fits: (model, chi^2 on u, degrees of freedom).
    u_only_contradiction : tuple of (str, str)
        The u-only fits that contradict the run's measured stresses: (model, the fit's
        sentence saying how, ``FitSummary.contradiction``); such a velocity is no null.
    fixed_grains : mapping or None
        The sidecar's grain-by-grain record at the fixed wall where that wall shears
        (``first_layer.walls[<fixed wall>]``: the layer runs' smooth fixed walls), read
        model-free only (:func:`free_rows`; no joint fit describes it); None: not recorded.
    joint_basins : str
        Where the joint fit whose velocity is the null sits when its 95% region is more than
        one island, in words ("" for one): the pooled p depends on which basin it finds.
    """

    cell: str = ""
    gap_d: float | None = None
    seed: Any = None
    wall_speed: float | None = None
    gravity: bool = False
    inertial_number: float | None = None
    unsteady: str = ""
    joint_fit: tuple[tuple[str, float, int], ...] = ()
    grains: Mapping[str, Any] | None = None
    grains_null: Mapping[str, float] | None = None
    u_only: tuple[tuple[str, float, int], ...] = ()
    u_only_contradiction: tuple[tuple[str, str], ...] = ()
    fixed_grains: Mapping[str, Any] | None = None
    joint_basins: str = ""


def basins_text(runs: Sequence[str], info: Mapping[str, SpinRun]) -> str:
    """The clause saying that the pooled p depends on which basin a joint fit finds, where a
    run's joint fit has a 95% region of more than one island (``SpinRun.joint_basins``;
    referee 14, point 2: the headline p moved with smooth_H20's basin); "" where none has."""
    several = [(r, info[r].joint_basins) for r in runs if r in info and info[r].joint_basins]
    if not several:
        return ""
    return (
        "; the pooled p depends on which basin a joint fit with several finds, its velocity "
        "being the run's null: " + "; ".join(f"{r}'s joint fit is at {b}" for r, b in several)
    )


def needs_first_layers(p_rest: float | None) -> bool:
    """The spin's support needs the first layers (referee 10, point 3): the pooled test
    without them (``p_rest``, read under t(blocks - 1) where the blocks are recorded) is not
    significant by the verdict's rule, p < :data:`P_SIGNIFICANT` (None: no such test)."""
    return p_rest is None or p_rest >= P_SIGNIFICANT


def bin_null_envelope(w: WallSpin, k: int = 1) -> dict[str, Any] | None:
    """The ``k``-th bin from a wall (0: the first layer; 1: bin 2) against the null of every
    velocity the run has (``WallSpin.null_every``, else the null's own interval or value;
    referee 9, point 1; referee 10, point 3): the bin's distance [d], the data's departure
    and se [-], the nulls' smallest and largest value [-], the data beyond that envelope (the
    distance to it, 0 inside) and that distance over the data's se [-], and whether the data
    lie outside. None without a null or without that bin."""
    order = np.argsort(w.distance_d)
    if w.null is None or order.size <= k:
        return None
    i = int(order[k])
    if w.null_every is not None:
        lo, hi = (float(np.asarray(a, dtype=float)[i]) for a in w.null_every)
    elif w.null_range is not None:
        lo, hi = (float(np.asarray(a, dtype=float)[i]) for a in w.null_range)
    else:
        lo = hi = float(np.asarray(w.null, dtype=float)[i])
    d = float(np.asarray(w.departure, dtype=float)[i])
    se = float(np.asarray(w.stderr, dtype=float)[i])
    beyond = d - min(max(d, lo), hi)
    return {
        "distance_d": float(np.asarray(w.distance_d, dtype=float)[i]),
        "departure": d,
        "se": se,
        "null_lo": lo,
        "null_hi": hi,
        "beyond": beyond,
        "z": beyond / se if se > 0.0 else None,
        "outside": beyond != 0.0,
    }


def _bin2_text(tested: Sequence[WallSpin]) -> tuple[str, dict[str, Any]]:
    """The sentence on bin 2's null envelope over every velocity, per wall, and its numbers
    (``bin2_null_envelope``)."""
    rows = {f"{w.run}:{w.wall}": e for w in tested if (e := bin_null_envelope(w)) is not None}
    if not rows:
        return "", {}
    parts = []
    for key, e in rows.items():
        where = (
            f"outside by {e['beyond']:+.3g}"
            + (f" ({e['z']:+.2g} se)" if e["z"] is not None else "")
            if e["outside"]
            else "inside"
        )
        parts.append(
            f"{key.split(':')[0]} {e['null_lo']:+.3g} to {e['null_hi']:+.3g}, data "
            f"{e['departure']:+.3g} +- {e['se']:.2g} ({where})"
        )
    out = [e for e in rows.values() if e["outside"]]
    far = sum(1 for e in out if e["z"] is not None and abs(e["z"]) >= CARRY_Z)
    lo = min(e["distance_d"] for e in rows.values())
    hi = max(e["distance_d"] for e in rows.values())
    text = (
        " Bin 2's null over every velocity each run has (the joint fit's, the u-only fits', "
        "the measured velocity's reconstructions; the second bin from the wall, at "
        + (f"{lo:.2g}" if f"{lo:.2g}" == f"{hi:.2g}" else f"{lo:.2g}-{hi:.2g}")
        + " d): "
        + "; ".join(parts)
        + f"; the data lie outside that envelope at {len(out)} of {len(rows)} walls"
        + (f" ({far} by at least {CARRY_Z:g} se)" if out else "")
        + "."
    )
    return text, rows


GRAIN_MEASURES = {
    "W_wall_second": "the wall-to-layer-2 chord",
    "W_layers": "the layer-1-to-2 chord",
    "W_wall_first": "the wall-to-layer-1 chord",
}
"""The grain-scale half vorticities of ``cosserat.dem.first_layer`` (W = -(1/2) du/dy across
one layer), in words."""
GRAIN_SE = 2.0
"""At the grain scale, a first layer within this many se of its null turns with the material
[-]; beyond it, it departs (the sign of the difference)."""
REPRODUCE_SE = 2.0
"""A velocity reproduces a bin's departure when the two differ by at most this many of the
data's se [-]."""
GRAIN_WOULD_CHANGE = (
    "the grain-scale re-binning is done (the first layer grain by grain, against the joint "
    "fit's null and model-free), and it leaves the first layer's sign to the measure: "
    "what would still decide is a definition of the velocity jump between the wall and its "
    "first layer of grains (the wall-to-grain slip) as vorticity or not, which picks one of "
    "the three grain-scale chords, or a model whose wall condition is stated at layer 1 (its "
    "layer-1 spin then a prediction to compare, not a velocity forward-modelled inside a "
    "first bin); then "
)
"""What would change the spin verdict first where the runs carry the grain-scale record
(referee 12, point 1: named before more seeds)."""


GRAIN_KEYS = ("d_1", "grains_1", "u_1", "u_1_se", "u_2", "u_2_se", "omega_1", "omega_1_se",
              "rolling", "rolling_se", "W_layers", "W_layers_se")  # fmt: skip
"""The layer measures :func:`grain_rows` and :func:`fixed_rows` copy from a sidecar's
``first_layer`` record."""


def grain_rows(tested: Sequence[WallSpin], info: Mapping[str, SpinRun]) -> dict[str, Any]:
    """Per run with the sidecar's grain-scale record at its tested moving wall
    (``SpinRun.grains``): layer 1's ``d_1`` [d], ``grains_1``, ``u_1``, ``u_2`` (layer 2's),
    ``omega_1``, ``rolling`` (each with ``_se``), the null's layer velocities ``null_u``
    ([u_1, u_2]; None: not given) and per measure of :data:`GRAIN_MEASURES` the
    ``departure`` and its ``se``, the ``null`` (the joint fit's velocity turning with the
    material, ``SpinRun.grains_null``; None without one: then the departure is taken against
    0), ``beyond`` = departure - null and ``z`` = beyond / se [-]."""
    rows: dict[str, Any] = {}
    for w in tested:
        i = info.get(w.run)
        if w.wall != "moving" or i is None or not i.grains:
            continue
        g, nul = i.grains, i.grains_null or {}
        per = {}
        for key in GRAIN_MEASURES:
            d, se = g.get(f"departure_{key}"), g.get(f"departure_{key}_se")
            if d is None or se is None:
                continue
            n = nul.get(f"departure_{key}")
            beyond = float(d) - (float(n) if n is not None else 0.0)
            per[key] = {"departure": float(d), "se": float(se), "null": n, "beyond": beyond,
                        "z": beyond / float(se) if se > 0.0 else None}  # fmt: skip
        if per:
            rows[w.run] = {k: g.get(k) for k in GRAIN_KEYS}
            rows[w.run]["wall"] = "moving"
            rows[w.run]["null_u"] = (
                [float(nul["u_1"]), float(nul["u_2"])] if "u_1" in nul and "u_2" in nul else None
            )
            rows[w.run]["measures"] = per
    return rows


def _grain_call(m: Mapping[str, Any]) -> int:
    """-1, 0 or +1: the first layer beyond the null by at least :data:`GRAIN_SE` se below it,
    within it (turning with the material), above it."""
    z = m["z"]
    if z is None or abs(z) < GRAIN_SE:
        return 0
    return 1 if z > 0 else -1


def grain_text(rows: Mapping[str, Any]) -> tuple[str, dict[str, Any]]:
    """The evidence's "against the joint fit's null, measured grain by grain" paragraph
    (referee 12, point 1; named so by referee 13, point 1: the null is a model's) from
    :func:`grain_rows`, and its counts per measure (``turns_with_the_material``,
    ``below``, ``above``, ``walls``; ``smallest_null``: the measure whose null is smallest
    over the walls, mean |null|)."""
    if not rows:
        return "", {}
    parts = []
    for run, r in rows.items():
        ms = []
        for key, m in r["measures"].items():
            null = "no null: against 0" if m["null"] is None else f"null {m['null']:+.3g}"
            z = "" if m["z"] is None else f", {m['z']:+.2g} se"
            ms.append(
                f"{GRAIN_MEASURES[key].removeprefix('the ').removesuffix(' chord')} "
                f"{m['departure']:+.3g} +- {m['se']:.2g} ({null}{z})"
            )
        layer = []
        if r.get("d_1") is not None:
            layer.append(f"layer 1 at {r['d_1']:.2g} d")
        if r.get("grains_1") is not None:
            layer.append(f"{r['grains_1']:.0f} grains")
        for k, label in (("u_1", "u_1"), ("u_2", "u_2"), ("omega_1", "omega_1"),
                         ("rolling", "rolling fraction")):  # fmt: skip
            if r.get(k) is not None and r.get(f"{k}_se") is not None:
                layer.append(f"{label} {r[k]:+.3g} +- {r[f'{k}_se']:.2g}")
        if r.get("null_u") is not None:
            layer.append(f"the null's layers u_1 {r['null_u'][0]:+.3g}, u_2 {r['null_u'][1]:+.3g}")
        parts.append(f"{run} ({', '.join(layer)}): " + "; ".join(ms))
    counts: dict[str, Any] = {}
    for key in GRAIN_MEASURES:
        calls = [_grain_call(r["measures"][key]) for r in rows.values() if key in r["measures"]]
        nulls = [abs(r["measures"][key]["null"]) for r in rows.values()
                 if key in r["measures"] and r["measures"][key]["null"] is not None]  # fmt: skip
        counts[key] = {"walls": len(calls), "turns_with_the_material": calls.count(0),
                       "below": calls.count(-1), "above": calls.count(1),
                       "mean_abs_null": float(np.mean(nulls)) if nulls else None}  # fmt: skip
    with_null = [k for k in counts if counts[k]["mean_abs_null"] is not None]
    order = sorted(with_null, key=lambda k: counts[k]["mean_abs_null"]) + [
        k for k in counts if k not in with_null
    ]
    said = []
    for k in order:
        c = counts[k]
        if not c["walls"]:
            continue
        smallest = " (the measure whose null is smallest)" if with_null and k == order[0] else ""
        off = [f"below it at {c['below']}"] if c["below"] else []
        off += [f"above it at {c['above']}"] if c["above"] else []
        said.append(
            f"against {GRAIN_MEASURES[k]}{smallest} the first layer turns with the material "
            f"(within {GRAIN_SE:g} se of the null) at {c['turns_with_the_material']} of "
            f"{c['walls']} moving walls" + (f", departs {' and '.join(off)}" if off else "")
        )
    by_wall = [[_grain_call(m) for m in r["measures"].values()] for r in rows.values()]
    mixed = sum(1 for c in by_wall if len(set(c) - {0}) > 1)
    one = {k: sum(1 for c in by_wall if set(c) == {k}) for k in (-1, 1)}
    counts = {"per_measure": counts, "smallest_null": order[0] if with_null else None,
              "walls_where_the_sign_follows_the_measure": mixed,
              "walls_one_sign_under_every_measure": {"below": one[-1],
                                                     "above": one[1]}}  # fmt: skip
    if one[-1] or one[1]:
        said.append(
            "the first layer lies "
            + " and ".join(
                f"{'below' if k < 0 else 'above'} the null under all three measures (by at "
                f"least {GRAIN_SE:g} se each) at {one[k]} of {len(rows)} walls"
                for k in (-1, 1)
                if one[k]
            )
        )
    text = (
        " Against the joint fit's null, measured grain by grain (the sidecars' first_layer: the "
        "grains whose centres lie "
        "within 1 d of the moving wall, no bins; omega_1 - W with W = -(1/2) "
        "du/dy across one layer, se from the time blocks; the null is the same measure of the "
        "joint fit's velocity with grains turning with the material, its u and omega averaged "
        "uniformly over [0, 1) and [1, 2) d from the wall, without its error): "
        + "; ".join(parts)
        + ". So "
        + "; ".join(said)
        + (
            f"; at {mixed} of {len(rows)} walls the first layer lies beyond the null with "
            "opposite signs under two measures: its sign at the grain scale is the measure's"
            if mixed
            else ""
        )
        + "."
    )
    return text, counts


MATCHED_NULL = (
    "a velocity matched to the measured layer means with no model fit: u = u_far + A "
    "exp(-d/l) in the distance d from the wall, u_far the other wall's velocity (0 for a "
    "moving wall's layers, V for a fixed wall's), l and A set so its uniform averages over "
    "[0, 1) and [1, 2) d are u_1 and u_2 (q = (u_2 - u_far)/(u_1 - u_far), l = -1/ln q, A = "
    "(u_1 - u_far)/(l (1 - q))), its grains turning with it and measured as the joint fit's "
    "null is (layers at 0.5 and 1.5 d): omega_1/W_layers = R = 1/(l (1 - q)); the data beyond "
    "it are omega_1 - R W_layers, its se with the block correlation of omega_1 and W_layers "
    "that the sidecar's departure se implies (R held fixed), and as a bound with the two "
    "independent and R's own error from the se of u_1 and u_2 propagated linearly (u_1 and "
    "u_2 independent)"
)
"""The model-free null of :func:`matched_exponential`, in words (referee 13, point 1; the
far velocity and the independent-error bound: referee 14, point 2)."""


def matched_exponential(
    u_1: float, u_2: float, s: float, u_far: float = 0.0
) -> dict[str, float] | None:
    """The first layer's measures against the layer-1-to-2 chord for the exponential velocity
    matched to the measured layer means (:data:`MATCHED_NULL`), grains turning with it.

    Parameters
    ----------
    u_1, u_2 : float
        Layers 1 and 2's mean velocities along the flow [V].
    s : float
        d(distance)/dy at the wall: +1 at the lower wall, -1 at the upper [-].
    u_far : float
        The velocity the exponential tends to away from the wall [V]: the other wall's (0 at
        a moving wall facing a fixed one, 1 at a fixed wall facing a moving one).

    Returns
    -------
    dict or None
        ``l`` [d], ``A`` [V], ``omega_1`` = (s/2)(u_1 - u_far)/l (layer 1's mean of the spin
        -(s/2) du/dd), ``W_layers`` = -(s/2)(u_2 - u_1) over the layers' 1 d spacing [V/d],
        ``ratio`` = omega_1/W_layers = 1/(l (1 - q)) [-] with q = (u_2 - u_far)/(u_1 -
        u_far) and ``departure`` = omega_1 - W_layers [V/d]. None where no decaying
        exponential matches (q not in (0, 1)).
    """
    if u_1 == u_far or not 0.0 < (u_2 - u_far) / (u_1 - u_far) < 1.0:
        return None
    q = (u_2 - u_far) / (u_1 - u_far)
    ell = -1.0 / math.log(q)
    omega = 0.5 * s * (u_1 - u_far) / ell
    w = -0.5 * s * (u_2 - u_1)
    return {"l": ell, "A": (u_1 - u_far) / (ell * (1.0 - q)), "omega_1": omega,
            "W_layers": w, "ratio": omega / w, "departure": omega - w}  # fmt: skip


P_NOTE = (
    "verdict_p (= pooled_p_headline) is the verdict's p: the pooled departure beyond the joint "
    "fit's null under the weakest stencil, each z read under t(blocks - 1) where the blocks are "
    "recorded; the other pooled_p_* are not: pooled_p_normal and "
    "pooled_p_without_first_layer_normal read each z as normal, pooled_p_every_bin is the "
    "analysis' stencil with every first layer, pooled_p_bound takes se_omega + se_half, "
    "pooled_p_against_zero tests against 0 (no null), pooled_p_t_without_first_layer leaves the "
    "first layers out (pooled_p_t is the headline's t reading), pooled_p_at_seed_factor "
    "multiplies every se by the replicates' seed factors (seed_factor_note)"
)
"""The spin verdict's ``p_note`` in results.json (referee 15, point 6)."""

SEED_FACTOR_NOTE = (
    "pooled_p_at_seed_factor: the verdict's pooled test (same stencil, same bins, same seeded "
    "t(blocks - 1) Monte Carlo) with every bin's se multiplied by a same-conditions replicate "
    "pair's omega seed-scatter factor sqrt(sum z^2 / n) (above 1 only; label: the pair, 'with "
    "its truncated wall bin' where that bin is counted), one row per factor: factor, p "
    "(count of draws at or above, draws; p_reading t or normal), bins_beyond_3 of bins (the "
    "bins the verdict rests on still at |z| >= 3), the same without the first layers "
    "(*_without_first_layer) and verdict (the rule's at that factor); seed_factor_crossing "
    "(_without_first_layer) is the factor at which p reaches 0.001 (exact over the draws: p at "
    "F is the unscaled p at chi^2/F^2); seed_factor_largest and verdict_at_largest_seed_factor "
    "the largest factor's"
)
"""The spin verdict's ``seed_factor_note`` in results.json (referee 17, point 2)."""


def _scaled_p(chi2: float | None, dof: int, blocks: int, factor: float) -> tuple[
    float | None, int | None, int | None
]:  # fmt: skip
    """The pooled p of ``chi2`` over ``dof`` bins with every se times ``factor`` (chi^2 /
    factor^2): :func:`pooled_t_count`'s where the blocks are recorded, else chi^2's; with the
    count and draws (None for chi^2's) [-]."""
    if chi2 is None or dof < 1:
        return None, None, None
    c = pooled_t_count(chi2 / factor**2, dof, blocks)
    if c is None:
        return float(chi2_dist.sf(chi2 / factor**2, dof)), None, None
    return (c[0] + 1) / (c[1] + 1), c[0], c[1]


def seed_factor_rows(
    factors: Sequence[tuple[str, float]],
    pooled: tuple[float | None, int],
    rest: tuple[float | None, int],
    blocks: int,
    carrying: Sequence[tuple[float, bool]],
    rule: Any = None,
) -> list[dict[str, Any]]:
    """The spin verdict's pooled test with every bin's se multiplied by each seed-scatter
    factor above 1 (referee 17, point 2; :data:`SEED_FACTOR_NOTE`), by factor.

    Parameters
    ----------
    factors : sequence of (str, float)
        (the replicate pair it comes from, omega's seed-scatter factor [-]).
    pooled, rest : (float or None, int)
        The pooled chi^2 and its bins, with and without the first layers [-].
    blocks : int
        Time blocks behind each se (the t reading's blocks - 1 degrees of freedom).
    carrying : sequence of (float, bool)
        The whitened z of each bin the verdict rests on and whether it is a first layer [-].
    rule : callable, optional
        factor -> the rule's verdict at that factor (None: not given).
    """
    rows = []
    for label, f in sorted(factors, key=lambda x: x[1]):
        if not (math.isfinite(f) and f > 1.0):
            continue
        p, count, draws = _scaled_p(pooled[0], pooled[1], blocks, f)
        p_r, count_r, draws_r = _scaled_p(rest[0], rest[1], blocks, f)
        rows.append(
            {
                "label": label,
                "factor": float(f),
                "p": p,
                "count": count,
                "draws": draws,
                "p_reading": "normal" if count is None else f"t({blocks - 1})",
                "bins_beyond_3": sum(abs(z) / f >= CARRY_Z for z, _ in carrying),
                "bins": len(carrying),
                "p_without_first_layer": p_r,
                "count_without_first_layer": count_r,
                "draws_without_first_layer": draws_r,
                "bins_beyond_3_without_first_layer": sum(
                    abs(z) / f >= CARRY_Z for z, first in carrying if not first
                ),
                "bins_without_first_layer": sum(1 for _, first in carrying if not first),
                "verdict": None if rule is None else rule(f),
            }
        )
    return rows


MC_QUOTE_COUNT = 30
"""A Monte Carlo p resting on fewer draws at or above its chi^2 than this is quoted with its
relative error (:func:`mc_error`; referee 18, point 4)."""


def seed_factor_text(rows: Sequence[Mapping[str, Any]], crossing: float | None) -> str:
    """The sentence on the pooled p at the replicates' omega seed factors
    (:func:`seed_factor_rows`; referee 17, point 2); "" without a factor above 1."""
    if not rows:
        return ""
    ps = [r["p"] for r in rows if r["p"] is not None]
    if not ps:
        return ""
    named = ", ".join(f"x{r['factor']:.3g} {r['label']}" for r in rows)

    def quoted(r: Mapping[str, Any]) -> str:  # referee 18, point 4: few draws, its MC error
        count, draws = r.get("count"), r.get("draws")
        if count is None or not draws or count >= MC_QUOTE_COUNT:
            return f"{r['p']:.2g}"
        return f"{r['p']:.2g} (+-{100.0 * mc_error(count, draws):.0f}%)"

    text = (
        f" With every bin's se multiplied by the same-conditions replicates' omega seed-scatter "
        f"factors ({named}) the pooled p is "
        f"{', '.join(quoted(r) for r in rows if r['p'] is not None)} under "
        f"{rows[0]['p_reading']} ({', '.join(str(r['bins_beyond_3']) for r in rows)} of the "
        f"{rows[0]['bins']} bins it rests on stay beyond {CARRY_Z:g} se)"
    )
    rest = [r["p_without_first_layer"] for r in rows if r["p_without_first_layer"] is not None]
    if rest:
        text += f"; without the first layers {', '.join(f'{p:.2g}' for p in rest)}"
    if crossing is not None:
        text += (
            f"; it would reach {P_SIGNIFICANT:g} at a factor of {crossing:.3g} (exact over the "
            "Monte Carlo's draws: F divides chi^2 by F^2, and the p at F is the unscaled p at "
            "chi^2/F^2 over the same seeded draws)"
        )
    top = rows[-1]
    if top["verdict"] is not None:
        text += f"; at the largest, x{top['factor']:.3g}, the rule's verdict is '{top['verdict']}'"
    return text + "."


def matched_ratio_se(
    u_1: float, u_1_se: float, u_2: float, u_2_se: float, u_far: float = 0.0
) -> float | None:
    """The se of the matched ratio R = -ln q/(1 - q) = 1/(l (1 - q)) of
    :func:`matched_exponential` from the measured layer means' se (referee 15, point 3(i)),
    by linear propagation with u_1 and u_2 independent: se_q = sqrt(se_2^2 + q^2 se_1^2) /
    abs(u_1 - u_far) and se_R = abs(dR/dq) se_q, dR/dq = (-(1 - q)/q - ln q)/(1 - q)^2.

    Parameters
    ----------
    u_1, u_1_se, u_2, u_2_se : float
        Layers 1 and 2's mean velocities and their se [V].
    u_far : float
        As in :func:`matched_exponential` [V].

    Returns
    -------
    float or None
        se_R [-]; None where no decaying exponential matches (q not in (0, 1)) or an se is
        not finite and non-negative.
    """
    if u_1 == u_far or not 0.0 < (u_2 - u_far) / (u_1 - u_far) < 1.0:
        return None
    if not all(math.isfinite(x) and x >= 0.0 for x in (u_1_se, u_2_se)):
        return None
    q = (u_2 - u_far) / (u_1 - u_far)
    se_q = math.hypot(u_2_se, q * u_1_se) / abs(u_1 - u_far)
    slope = (-(1.0 - q) / q - math.log(q)) / (1.0 - q) ** 2
    return abs(slope) * se_q


def fixed_rows(walls: Sequence[WallSpin], info: Mapping[str, SpinRun]) -> dict[str, Any]:
    """The grain-scale records of the sheared fixed walls (``SpinRun.fixed_grains``: the
    layer runs' smooth fixed walls, referee 14, point 2), keyed ``"<run>:fixed"``, in
    :func:`grain_rows`' form without a null (no joint fit describes them): read model-free
    only, by :func:`free_rows`."""
    rows: dict[str, Any] = {}
    for w in walls:
        i = info.get(w.run)
        if w.wall != "fixed" or not w.sheared or i is None or not i.fixed_grains:
            continue
        g = i.fixed_grains
        per = {}
        for key in GRAIN_MEASURES:
            d, se = g.get(f"departure_{key}"), g.get(f"departure_{key}_se")
            if d is not None and se is not None:
                z = float(d) / float(se) if se > 0 else None
                per[key] = {"departure": float(d), "se": float(se), "null": None,
                            "beyond": float(d), "z": z}  # fmt: skip
        if per:
            rows[f"{w.run}:fixed"] = {k: g.get(k) for k in GRAIN_KEYS}
            rows[f"{w.run}:fixed"].update({"wall": "fixed", "null_u": None, "measures": per})
    return rows


def _wall_name(key: str) -> str:
    """A free row's key in words: "run" (its moving wall) or "run's fixed wall"."""
    run, _, wall = key.partition(":")
    return f"{run}'s fixed wall" if wall == "fixed" else run


def free_rows(rows: Mapping[str, Any]) -> dict[str, Any]:
    """The model-free reading of the grain-scale record (referee 13, point 1), per wall of
    :func:`grain_rows` (keyed by run: the moving wall) and :func:`fixed_rows` (``"<run>:fixed"``)
    with the layer-1-to-2 measure: ``wall``, ``ratio`` = omega_1 / W_layers (W_layers =
    omega_1 - its departure), the raw departure against the wall-to-layer-2 chord and its se
    and z (against 0), ``matched`` (:func:`matched_exponential`, u_far the other wall's
    velocity: 0 at a moving wall, 1 at a fixed one; None: no match), the data ``beyond`` it =
    omega_1 - R W_layers (R the matched ratio) with ``se`` (omega_1 and W_layers correlated as
    the sidecar's departure se implies: ``rho``; without ``W_layers_se`` the departure's se)
    and ``z`` = beyond / se (R held fixed), and ``se_independent`` = sqrt(se_omega^2 + R^2
    se_W^2 + W_layers^2 se_R^2) with ``z_independent`` (the bound, referee 14, point 2; R's
    own se ``matched["ratio_se"]`` from :func:`matched_ratio_se`, referee 15, point 3(i);
    None without the layers' se), and the bound with R held fixed,
    ``se_independent_fixed_R`` and ``z_independent_fixed_R`` [-]."""
    out: dict[str, Any] = {}
    for run, r in rows.items():
        m = r["measures"].get("W_layers")
        if m is None or r.get("omega_1") is None or r.get("u_1") is None or r.get("u_2") is None:
            continue
        om, u_1, u_2 = float(r["omega_1"]), float(r["u_1"]), float(r["u_2"])
        w = om - m["departure"]
        wall = r.get("wall", "moving")
        row: dict[str, Any] = {"wall": wall, "ratio": om / w if w != 0.0 else None,
                               "omega_1": om}  # fmt: skip
        second = r["measures"].get("W_wall_second")
        if second is not None:
            row["wall_second"] = {"departure": second["departure"], "se": second["se"],
                                  "z": second["departure"] / second["se"]
                                  if second["se"] > 0.0 else None}  # fmt: skip
        s = -math.copysign(1.0, w * (u_2 - u_1)) if w * (u_2 - u_1) != 0.0 else None
        far = 1.0 if wall == "fixed" else 0.0
        match = None if s is None else matched_exponential(u_1, u_2, s, far)
        se_1, se_2 = r.get("u_1_se"), r.get("u_2_se")
        se_r = (
            None
            if match is None or se_1 is None or se_2 is None
            else matched_ratio_se(u_1, float(se_1), u_2, float(se_2), far)
        )
        row["matched"] = None if match is None else {**match, "ratio_se": se_r}
        if match is not None:
            ratio = match["ratio"]
            beyond = om - ratio * w
            se_o, se_w = r.get("omega_1_se"), r.get("W_layers_se")
            row["beyond"] = beyond
            row["rho"] = None
            if se_o is not None and se_w is not None and se_o > 0.0 and se_w > 0.0:
                vo, vw = float(se_o) ** 2, float(se_w) ** 2
                rho = (vo + vw - m["se"] ** 2) / (2.0 * math.sqrt(vo * vw))
                rho = min(1.0, max(-1.0, rho))
                cov = rho * math.sqrt(vo * vw)
                se = math.sqrt(max(vo + ratio**2 * vw - 2.0 * ratio * cov, 0.0))
                se_fixed = math.sqrt(vo + ratio**2 * vw)
                se_ind = None if se_r is None else math.sqrt(se_fixed**2 + (w * se_r) ** 2)
                row["rho"] = rho
            else:
                se, se_fixed, se_ind = m["se"], None, None
            row["se"] = se
            row["z"] = beyond / se if se > 0.0 else None
            row["se_independent"] = se_ind
            row["z_independent"] = beyond / se_ind if se_ind else None
            row["se_independent_fixed_R"] = se_fixed
            row["z_independent_fixed_R"] = beyond / se_fixed if se_fixed else None
        out[run] = row
    return out


def _span(values: Sequence[float], spec: str = ".2g") -> str:
    """ "a-b" over ``values`` (one value where they print alike)."""
    lo, hi = f"{min(values):{spec}}", f"{max(values):{spec}}"
    return lo if lo == hi else f"{lo}-{hi}"


def _bound_z(r: Mapping[str, Any]) -> float | None:
    """A free row's z under independent errors where it has one, else its z."""
    z = r.get("z_independent")
    return z if z is not None else r.get("z")


def free_lead(rows: Mapping[str, Any]) -> str:
    """The model-free sentence that leads the spin verdict's evidence (referee 14, "Verdicts I
    would accept", (1), and point 2), from :func:`free_rows`: layer 1's ratio omega_1/W_layers
    at the walls beyond the matched null by at least :data:`GRAIN_SE` se under independent
    errors, the matched ratios, and those walls' z under independent errors; "" without
    rows."""
    zs = {k: z for k, r in rows.items() if r.get("matched") is not None
          and (z := _bound_z(r)) is not None}  # fmt: skip
    ok = {k: rows[k] for k in zs}
    if not ok:
        return ""
    far = {k: r for k, r in ok.items() if abs(zs[k]) >= GRAIN_SE}
    moving = {k: r for k, r in ok.items() if r["wall"] == "moving"}
    fixed = {k: r for k, r in ok.items() if r["wall"] == "fixed"}
    parts = []
    for group, name in ((moving, "moving walls"), (fixed, "sheared fixed walls")):
        if not group:
            continue
        hit = [k for k in group if k in far]
        miss = [k for k in group if k not in far]
        if hit:
            text = (f"{_span([group[k]['ratio'] for k in hit], '.3g')} times the half vorticity "
                    f"between layers 1 and 2 at {len(hit)} of {len(group)} {name}")  # fmt: skip
        else:
            text = f"no faster than the matched velocity at the {len(group)} {name}"
        if miss and hit:
            text += " (" + ", ".join(f"{group[k]['ratio']:.3g} at {_wall_name(k)}"
                                     for k in miss) + ")"  # fmt: skip
        parts.append(text)
    z_hit = [abs(zs[k]) for k in far]
    three = sum(1 for k in ok if abs(zs[k]) >= 3.0)
    # the span above is of the walls beyond GRAIN_SE only: the others' said beside it
    # (referee 16, point 3)
    z_rest = [abs(z) for k, z in zs.items() if k not in far]
    rest = f"; {_span(z_rest, '.2g')} se at the other {len(z_rest)}" if z_rest else ""
    independent = all(r.get("z_independent") is not None for r in ok.values())
    kind = (
        "under independent errors (R's own error from u_1 and u_2 propagated)"
        if independent
        else "in the departure's se"
    )
    return (
        (
            "Model-free, grain by grain: layer 1 turns "
            + "; ".join(parts)
            + f"; a velocity matched to the measured layer means gives R = "
            f"{_span([r['matched']['ratio'] for r in ok.values()], '.3g')}; the data lie beyond "
            f"it by {_span(z_hit, '.2g')} se: beyond {GRAIN_SE:g} se at {len(far)} of "
            f"{len(ok)} sheared walls ({three} by >= 3 se{rest}) {kind}. "
        )
        if far
        else (
            "Model-free, grain by grain: layer 1 turns with the velocity matched to the measured "
            f"layer means within {GRAIN_SE:g} se at the {len(ok)} sheared walls {kind}. "
        )
    )


def free_text(rows: Mapping[str, Any]) -> tuple[str, dict[str, Any]]:
    """The evidence's model-free sentences on the grain-scale record from :func:`free_rows`
    (referee 13, point 1; referee 14, point 2), and their counts over the walls with a
    matched null: those beyond it by at least :data:`GRAIN_SE` and by 3 se, with the
    block-correlated se (``beyond``, ``beyond_3_se``) and under independent errors
    (``beyond_independent``, ``beyond_3_se_independent``), and where the raw wall-to-layer-2
    departure is within :data:`GRAIN_SE` se of 0 (``wall_second_zero``)."""
    if not rows:
        return "", {}
    per = []
    for run, r in rows.items():
        bits = [] if r["ratio"] is None else [f"omega_1/W_layers {r['ratio']:.3g}"]
        if r.get("matched") is not None:
            z = "" if r["z"] is None else f", {r['z']:+.2g} se"
            if r.get("z_independent") is not None:
                z += f" ({r['z_independent']:+.2g} under independent errors)"
            bits.append(f"the matched velocity's {r['matched']['ratio']:.3g} (l = "
                        f"{r['matched']['l']:.2g} d), the data beyond it by "
                        f"{r['beyond']:+.3g}{z}")  # fmt: skip
        if r.get("wall_second") is not None:
            ws = r["wall_second"]
            z = "" if ws["z"] is None else f", {ws['z']:+.2g} se"
            bits.append(f"raw departure against the wall-to-layer-2 chord "
                        f"{ws['departure']:+.3g} +- {ws['se']:.2g}{z}")  # fmt: skip
        per.append(f"{_wall_name(run)} {', '.join(bits)}")

    def count(key: str, at: float) -> list[str]:
        return [k for k, r in rows.items() if r.get(key) is not None and abs(r[key]) >= at]

    beyond = count("z", GRAIN_SE)
    bound = count("z_independent", GRAIN_SE)
    with_bound = [k for k, r in rows.items() if r.get("z_independent") is not None]
    others = [k for k, r in rows.items() if k not in beyond and r["ratio"] is not None]
    seconds = [r["wall_second"] for r in rows.values() if r.get("wall_second") is not None
               and r["wall_second"]["z"] is not None]  # fmt: skip
    zero = [ws for ws in seconds if abs(ws["z"]) < GRAIN_SE]
    matched = [r["matched"]["ratio"] for r in rows.values() if r.get("matched") is not None]
    said = []
    ratios = [rows[k]["ratio"] for k in beyond if rows[k]["ratio"] is not None]
    if ratios:
        said.append(
            f"So layer 1 turns {_span(ratios, '.3g')} times faster than the half vorticity "
            f"between layers 1 and 2 at {len(beyond)} of {len(rows)} sheared walls"
            + (
                " (" + ", ".join(f"{rows[k]['ratio']:.3g} at {_wall_name(k)}" for k in others) + ")"
                if others
                else ""
            )
        )
    if matched:
        said.append(
            f"a velocity matched to the measured layer means gives {_span(matched, '.3g')}, "
            f"and the data lie beyond it by at least {GRAIN_SE:g} se at {len(beyond)} of "
            f"{len(matched)} walls ({len(count('z', 3.0))} by at least 3 se)"
            + (
                f"; with omega_1 and W_layers independent (the bound: their correlation comes "
                f"from the time blocks) and R's own error propagated at {len(bound)} of "
                f"{len(with_bound)} "
                f"({len(count('z_independent', 3.0))} by at least 3 se)"
                if with_bound
                else ""
            )
            + ": only a velocity varying within a fraction of the first "
            "grain layer (a drop of about 2|omega_1| = "
            + _span([2.0 * abs(r["omega_1"]) for r in rows.values()])
            + " V across it) turns this into rotation with the material"
        )
    if seconds:
        said.append(
            f"against the wall-to-layer-2 chord the raw departure is 0 within {GRAIN_SE:g} se at "
            f"{len(zero)} of {len(seconds)} walls (the largest |z| "
            f"{max(abs(ws['z']) for ws in seconds):.2g})"
        )
    text = (
        f" Model-free, grain by grain (the null: {MATCHED_NULL}): "
        + "; ".join(per)
        + ". "
        + "; ".join(said)
        + "."
    )
    counts = {"moving_walls": sum(1 for r in rows.values() if r["wall"] == "moving"),
              "fixed_walls": sum(1 for r in rows.values() if r["wall"] == "fixed"),
              "beyond": len(beyond), "beyond_3_se": len(count("z", 3.0)),
              "beyond_independent": len(bound),
              "beyond_3_se_independent": len(count("z_independent", 3.0)),
              "walls_with_independent_bound": len(with_bound),
              "wall_second_zero": len(zero),
              "wall_second_walls": len(seconds)}  # fmt: skip
    return text, counts


def u_only_reproduces(
    tested: Sequence[WallSpin], info: Mapping[str, SpinRun], model: str = "mui"
) -> dict[str, Any]:
    """Where ``model``'s u-only velocity, its grains turning with the material and measured
    as the data (``WallSpin.predicted``, the analysis' stencil), reproduces the moving wall's
    first-layer departure (within :data:`REPRODUCE_SE` of the data's se), and bin 2's too:
    run -> ``bins`` (1 or 2), ``data`` and ``model`` (the departures of those bins) [-], and
    that fit's ``chi2`` and ``dof`` on u (None: not recorded) and ``contradiction`` (how it
    contradicts the run's measured stresses, ``SpinRun.u_only_contradiction``; "": not)."""
    out: dict[str, Any] = {}
    for w in tested:
        pred = w.predicted.get(model)
        if w.wall != "moving" or pred is None or w.dof < 1:
            continue
        order = np.argsort(w.distance_d)
        d, se, p = (np.asarray(a, dtype=float) for a in (w.departure, w.stderr, pred))
        ok = [abs(d[i] - p[i]) <= REPRODUCE_SE * se[i] for i in order[:2]]
        if not ok[0]:
            continue
        n = 2 if len(ok) > 1 and ok[1] else 1
        fit = next((f for f in (info[w.run].u_only if w.run in info else ()) if f[0] == model),
                   None)  # fmt: skip
        why = next((c[1] for c in (info[w.run].u_only_contradiction if w.run in info else ())
                    if c[0] == model), "")  # fmt: skip
        out[w.run] = {"bins": n, "data": [float(d[i]) for i in order[:n]],
                      "model": [float(p[i]) for i in order[:n]],
                      "chi2": None if fit is None else fit[1],
                      "dof": None if fit is None else fit[2],
                      "contradiction": why}  # fmt: skip
    return out


MODEL_WORDS = {"mui": "mu(I)", "ngf": "nonlocal fluidity", "cosserat": "Cosserat"}


def u_only_text(rows: Mapping[str, Any], walls: int, model: str = "mui") -> str:
    """The referee's first sentence of point 1 ("the u-only mu(I) velocity ... reproduces the
    first-layer departure at ...; that velocity is rejected by u at chi^2 = ... there"), from
    :func:`u_only_reproduces`."""
    name = MODEL_WORDS.get(model, model)
    lead = (
        f" The u-only {name} velocity, its grains turning with the material (the spin equal to "
        "half its vorticity) and measured as the data, "
    )
    if not rows:
        return lead + f"reproduces the first-layer departure at none of the {walls} moving walls."
    one = [f"{r} ({v['data'][0]:+.2g}; the velocity's {v['model'][0]:+.2g})"
           for r, v in rows.items() if v["bins"] == 1]  # fmt: skip
    two = [f"{r} ({v['data'][0]:+.2g}, {v['data'][1]:+.2g}; the velocity's "
           f"{v['model'][0]:+.2g}, {v['model'][1]:+.2g})"
           for r, v in rows.items() if v["bins"] == 2]  # fmt: skip
    said = ([f"the first-layer departure at {', '.join(one)}"] if one else []) + (
        [f"the first two bins at {', '.join(two)}"] if two else []
    )
    fits = []
    absorbed = []
    for r, v in rows.items():
        if v["chi2"] is None:
            continue
        p = float(chi2_dist.sf(v["chi2"], v["dof"])) if v["dof"] > 0 else None
        verdict = ", rejected" if p is not None and p < P_SIGNIFICANT else ""
        fits.append(
            f"chi^2 = {v['chi2']:.3g}/{v['dof']}"
            + (f" (p = {p:.2g}{verdict})" if p is not None else "")
            + f" at {r}"
        )
        if p is not None and p >= P_SIGNIFICANT:  # referee 13, point 1: the consequence
            why = v.get("contradiction") or ""
            absorbed.append(
                f" At {r} the first-layer departure is absorbed by a velocity u accepts "
                f"(p = {p:.2g}); it is not the verdict's null because "
                + (
                    why.removeprefix("contradicts the measured stress: ")
                    if why.startswith("contradicts the measured stress: its ")
                    else "its fit contradicts the measured stress ("
                    + why.removeprefix("contradicts the measured stress: ")
                    + ")"
                    if why
                    else "the verdict's null is the velocity of the joint fit to u, omega and "
                    "the stress ratio together"
                )
                + "."
            )
    return (
        lead
        + f"reproduces (within {REPRODUCE_SE:g} se) "
        + " and ".join(said)
        + (f"; that velocity's fit to u there: {'; '.join(fits)}" if fits else "")
        + "."
        + "".join(absorbed)
    )


def mc_line(p: float | None, counted: tuple[int, int] | None, what: str) -> str:
    """One sentence on a Monte Carlo p against :data:`P_SIGNIFICANT` with its count and
    error (referee 12, point 7): at the line within twice its Monte Carlo error, or
    below / above it."""
    if p is None or counted is None:
        return ""
    err = mc_error(*counted)
    where = (
        f"at the {P_SIGNIFICANT:g} line within twice its Monte Carlo error"
        if abs(p - P_SIGNIFICANT) <= 2.0 * err * p
        else f"{'below' if p < P_SIGNIFICANT else 'above'} the {P_SIGNIFICANT:g} line beyond "
        "twice its Monte Carlo error"
    )
    return f" {what} {mc_p_text(p, *counted, line=True)}, {where}."


def _cells(runs: Sequence[str], info: Mapping[str, SpinRun]) -> dict[str, str]:
    """Run -> its cell's label (the run's own name without a recorded cell)."""
    return {r: (info[r].cell if r in info and info[r].cell else r) for r in runs}


def _replicates_text(runs: Sequence[str], info: Mapping[str, SpinRun]) -> str:
    """ "; a and b are one cell at V = ... and ..." for each cell of several runs ("" when
    every run is a cell of its own)."""
    cells = _cells(runs, info)
    groups: dict[str, list[str]] = {}
    for r in runs:
        groups.setdefault(cells[r], []).append(r)
    parts = []
    for members in groups.values():
        if len(members) < 2:
            continue
        speeds = [v for m in members if m in info and (v := info[m].wall_speed) is not None]
        at = (
            " at V = " + " and ".join(f"{v:.3g}" for v in speeds)
            if len(speeds) == len(members) and len(set(speeds)) == len(speeds)
            else ""
        )
        parts.append(f"{' and '.join(members)} are one cell{at}")
    return "; ".join(parts)


def count_text(
    selected: Sequence[str], runs: Sequence[str], info: Mapping[str, SpinRun], named: bool = True
) -> str:
    """ "n of N runs", or, where some runs are replicates of one cell (``SpinRun.cell``),
    "n of M cells (N runs; a and b are one cell at V = ... and ...)", a cell counted where
    every run of it is in ``selected`` (referee 10, point 3); ``named`` False: without the
    parenthesis (said already)."""
    cells = _cells(runs, info)
    labels = sorted(set(cells.values()))
    if len(labels) == len(runs):
        return f"{len(selected)} of {len(runs)} runs"
    chosen = set(selected)
    n = sum(1 for c in labels if all(r in chosen for r in runs if cells[r] == c))
    if not named:
        return f"{n} of {len(labels)} cells"
    return f"{n} of {len(labels)} cells ({len(runs)} runs; {_replicates_text(runs, info)})"


def _two_speeds(tested: Sequence[WallSpin], info: Mapping[str, SpinRun]) -> list[Any]:
    """One cell's first-layer departure beyond the null at its fastest and slowest wall
    speed (``rate.FirstLayerRate``), for each cell run at two speeds."""
    from .rate import FirstLayerRate

    runs = sorted({w.run for w in tested})
    cells = _cells(runs, info)
    moving = {w.run: w for w in tested if w.wall == "moving"}
    out = []
    for c in sorted(set(cells.values())):
        members = [
            r
            for r in runs
            if cells[r] == c and r in moving and r in info and info[r].wall_speed is not None
        ]
        if len(members) < 2:
            continue
        fast = max(members, key=lambda r: info[r].wall_speed or 0.0)
        slow = min(members, key=lambda r: info[r].wall_speed or 0.0)
        if info[fast].wall_speed == info[slow].wall_speed:
            continue
        out.append(
            FirstLayerRate(
                fast,
                slow,
                (float(info[fast].wall_speed or 0.0), float(info[slow].wall_speed or 0.0)),
                (moving[fast].beyond_first(), moving[slow].beyond_first()),
            )
        )
    return out


def _unsteady_text(carrying: Mapping[str, Sequence[Any]], info: Mapping[str, SpinRun]) -> str:
    """The line that a bin the verdict rests on (|z| >= :data:`CARRY_Z`) sits in a run the
    sidecar's steadiness test finds not steady ("" when none does)."""
    n = sum(len(b) for b in carrying.values())
    bad, k = [], 0
    for key, bins in carrying.items():
        run = key.split(":")[0]
        if bins and run in info and info[run].unsteady:
            bad.append(f"{run} ({info[run].unsteady})")
            k += len(bins)
    if not bad:
        return ""
    return (
        f" {k} of the {n} bins with |z| >= {CARRY_Z:g} "
        + ("sits" if k == 1 else "sit")
        + f" in {'a run' if len(bad) == 1 else 'runs'} that {'is' if len(bad) == 1 else 'are'} "
        "not steady: " + "; ".join(bad) + "."
    )


def _lead(
    tested: Sequence[WallSpin],
    info: Mapping[str, SpinRun],
    weak: str,
    pooled: tuple[float, int, float, float | None],
    rest: tuple[float | None, int, float | None, float | None],
    blocks: int,
    counts: tuple[tuple[int, int] | None, tuple[int, int] | None] = (None, None),
) -> str:
    """The verdict's first sentences, in the form referee 10 accepts ("Verdicts I would
    accept", (1)), every number computed: where the spin departs and in which runs, the
    pooled test, what carries it, and the test without the first layers."""
    runs = sorted({w.run for w in tested})
    sources = sorted({w.null_source or f"the {w.null_model} fit's velocity" for w in tested})
    roles = sorted({w.wall for w in tested})
    reach = max(float(np.max(w.distance_d)) for w in tested)
    gravity = all(r in info and info[r].gravity for r in runs)
    text = (
        f"Beyond the null of {' or '.join(sources)}, the spin departs from half the vorticity "
        f"within {reach:.2g} d of the sheared {' and '.join(roles)} walls of "
        f"{len(runs)} {'gravity ' if gravity else ''}runs"
    )
    cells = _replicates_text(runs, info)
    if cells:
        n_cells = len(set(_cells(runs, info).values()))
        text += f" ({n_cells} cell{'s' if n_cells != 1 else ''}: {cells})"
    facts = []
    gaps = sorted({round(g, 0) for r in runs if r in info and (g := info[r].gap_d) is not None})
    if gaps:
        facts.append("H = " + ", ".join(f"{g:g}" for g in gaps) + " d")
    inertial = [i for r in runs if r in info and (i := info[r].inertial_number) is not None]
    if inertial:
        facts.append(f"I = {min(inertial):.2g}-{max(inertial):.2g} by the bin gradient")
    seeds = {info[r].seed for r in runs if r in info and info[r].seed is not None}
    if len(seeds) == 1:
        facts.append(f"seed {next(iter(seeds))} throughout")
    elif seeds:
        facts.append(f"{len(seeds)} seeds")
    for f in _two_speeds(tested, info):
        (a, sa), (b, sb) = f.departures
        z = f.z
        facts.append(
            f"one cell at V = {f.speeds[0]:.3g} and {f.speeds[1]:.3g} with the first-layer "
            f"departure beyond the null {a:+.3g} +- {sa:.2g} and {b:+.3g} +- {sb:.2g} (z = "
            + ("-" if z is None else f"{z:+.2g}")
            + (", the same within 2 se)" if f.agrees else ", not the same)")
        )
    if facts:
        text += ". These are " + ", ".join(facts)
    chi2, dof, p, p_t = pooled
    reading = (
        (mc_p_text(p_t, *counts[0]) if counts[0] is not None else f"p = {p_t:.2g}")
        + f" with bins read under t({blocks - 1})"
        if p_t is not None
        else p_text(chi2, dof, p)
    )
    carrying = {f"{w.run}:{w.wall}": carrying_bins(w, weak) for w in tested}
    named = []
    first_runs = []
    inside = []
    for w in tested:
        for b in carrying[f"{w.run}:{w.wall}"]:
            first = b["distance_d"] == float(np.min(w.distance_d))
            if first:
                first_runs.append(w)
            where = "first layer" if first else f"bin at {b['distance_d']:.2g} d"
            named.append(f"{w.run}'s {where} (z = {b['z']:+.2g}){envelope_text(b)}")
            if b.get("inside_null_envelope"):
                inside.append(f"{w.run}'s {where}")
    text += (
        f". Pooled chi^2 = {chi2:.3g}/{dof} under the weakest stencil ({weak}), {reading}"
        + (f", carried by {'; '.join(named)}" if named else "")
        + "."
    )
    if inside:  # referee 11, point 1: a carrying bin inside its envelope, said in words
        n_in, n_all = len(inside), len(named)
        text += (
            f" {n_in} of the {n_all} bins the verdict rests on "
            + ("lies" if n_in == 1 else "lie")
            + f" inside {'its' if n_in == 1 else 'their'} own null envelope over every "
            f"velocity the run has ({', '.join(inside)}): "
            + ("its" if n_in == 1 else "their")
            + " departure holds beyond the verdict's null, not beyond every smooth velocity "
            "the run has."
        )
    if first_runs:
        spans = []
        for w in first_runs:
            e = bin_null_envelope(w, 0)
            if e is not None and e["null_hi"] > e["null_lo"]:
                spans.append(
                    f"{e['null_lo']:+.3g} to {e['null_hi']:+.3g} at {w.run} (the verdict's "
                    f"{float(np.asarray(w.null)[w.nearest]):+.3g})"
                )
        text += (
            " A first layer's null is the velocity inside a first bin, which the bins do not "
            "resolve"
            + (
                "; over every velocity the run has (the joint fit's, the u-only fits', the "
                "measured velocity's reconstructions) it spans " + "; ".join(spans)
                if spans
                else ""
            )
            + "."
        )
    c_rest, n_rest, p_rest, p_t_rest = rest
    if n_rest:
        beyond2 = [e for w in tested if (e := bin_null_envelope(w)) is not None]
        signs = [w for w in tested if w.dof > 1]
        pos = [w.run for w in signs if float(w.beyond[int(np.argsort(w.distance_d)[1])]) > 0.0]
        neg = [w.run for w in signs if float(w.beyond[int(np.argsort(w.distance_d)[1])]) < 0.0]
        major, sign = (pos, "positive") if len(pos) >= len(neg) else (neg, "negative")
        reading_rest = (
            (
                mc_p_text(p_t_rest, *counts[1], line=True)
                if counts[1] is not None
                else f"p = {p_t_rest:.2g}"
            )
            + f" under t({blocks - 1})"
            if p_t_rest is not None
            else p_text(c_rest, n_rest, p_rest)
        )
        text += (
            f" Without the first layers, the other near-wall bins give chi^2 = "
            f"{_g(c_rest, '.3g')}/{n_rest}, {reading_rest}"
            + (
                f", with bin 2 beyond the null {sign} in "
                f"{count_text(major, [w.run for w in signs], info)}"
                if beyond2 and len(signs) == len({w.run for w in signs})
                else ""
            )
            + "."
        )
    return text


# --------------------------------------------------------------------------- spin
def spin_verdict(
    walls: Sequence[WallSpin],
    model: str = "cosserat",
    unfit: Mapping[str, str] | None = None,
    runs_info: Mapping[str, SpinRun] | None = None,
    seed_factors: Sequence[tuple[str, float]] = (),
) -> Verdict:
    """Does the spin depart from half the vorticity near the walls (module docstring)?

    Parameters
    ----------
    walls : sequence of WallSpin
        Every run's near-wall tests; unsheared walls, and sheared walls without the null they
        need (``WallSpin.no_null``), are reported, not judged.
    model : str
        The model whose predicted departure says whether the errors could have seen one,
        where the joint fit's (``WallSpin.joint``) is not given.
    unfit : mapping of run name to str, optional
        Runs whose ``model`` fit supplies no prediction (pinned, or contradicting the measured
        stress ratio), with why: such a run is counted among the runs, never excused as too
        noisy to have shown the model's departure, and its u-only fit's departure is not a
        prediction to state power against.
    runs_info : mapping of run name to SpinRun, optional
        What the sidecars say of the runs (:class:`SpinRun`): runs of one cell that differ
        only in wall speed are counted as one cell (the rule's "half the runs" is half the
        cells, a cell departing where each of its runs does), the evidence names the gaps,
        inertial numbers, seeds and wall speeds, compares one cell's first layer at two
        speeds, and says where a bin it rests on sits in a run that is not steady.
    seed_factors : sequence of (str, float)
        The same-conditions replicates' omega seed-scatter factors (``rate.TwinField.factor``),
        each with the pair it comes from: the pooled test is repeated with every bin's se
        multiplied by each factor above 1 (:func:`seed_factor_rows`; referee 17, point 2),
        and where the rule would not say "supported" at the largest, the qualifier says so.

    Notes
    -----
    "supported" carries the qualifier (``Verdict.qualifier``, :func:`null_qualifier`) naming
    the null it holds beyond, e.g. "beyond the null of the joint Cosserat fit's velocity", with
    "(smooth on the grain scale)" where its support needs the first layers
    (:func:`needs_first_layers`): their null is the velocity inside a first bin, which the
    bins do not resolve. Each bin it rests on is set against its own null envelope over every
    velocity the run has, and a joint fit whose velocity is a null and misfits u or omega
    (p < :data:`NULL_MISFIT_P`, ``SpinRun.joint_fit``) is named (referee 11, point 1).
    """
    unfit = dict(unfit or {})
    info = dict(runs_info or {})
    sheared = [w for w in walls if w.sheared and w.dof > 0]
    no_null = [w for w in sheared if w.no_null]
    tested = [w for w in sheared if not w.no_null]
    untested = [w for w in walls if not w.sheared and w.dof > 0]
    key = "spin"
    unjudged = (
        " Not judged (a test against 0 would count what the binning and the stencil make as a "
        "departure): "
        + "; ".join(f"{_walls_text([w])}; not judged: {w.no_null}" for w in no_null)
        + "."
        if no_null
        else ""
    )
    shown = [w for w in no_null if w.null is not None]
    if shown and any(not w.no_null for w in walls):  # what the walls shown would change
        ids = {id(w) for w in shown}
        would = spin_verdict(
            [replace(w, no_null="") if id(w) in ids else w for w in walls], model, unfit
        )
        wn = would.numbers
        n_dep = len(wn.get("runs_departing_p_0.05", []))
        pooled_would = p_text(
            wn.get("pooled_chi2"), wn.get("pooled_dof", 0), wn.get("pooled_p_normal")
        )
        unjudged += (
            f" Were {', '.join(f'{w.run}:{w.wall}' for w in shown)} judged against the null "
            f"shown, {n_dep} of {len(would.runs)} runs would depart at p < {P_CONSISTENT:g} "
            f"(pooled {pooled_would}) and the verdict would read '{would.verdict}'."
        )
    if not tested:
        return Verdict(
            key,
            "undecided",
            "The data cannot decide: no run has the spin and half the vorticity measured near "
            "a sheared wall with a null to test against." + unjudged,
            "omega and half_vorticity columns with their standard errors in the bins next to "
            "the moving wall, and a velocity a fit describes there.",
            tuple(sorted({w.run for w in no_null})),
            {"walls_without_null": [f"{w.run}:{w.wall}" for w in no_null]},
        )
    runs = sorted({w.run for w in tested})
    names = _stencils_of(tested)
    by_stencil = {s: _pooled(tested, s) for s in names}
    weak = _weakest(tested)
    dependent = [w for w in tested if w.beyond_dependent()]
    per_run: dict[str, tuple[float | None, int, float | None]] = {}
    for r in runs:
        own = [w for w in tested if w.run == r]
        per_run[r] = max((_pooled(own, s) for s in names), key=lambda t: t[2] or 0.0)
    chi2, dof, p = by_stencil[weak]
    assert chi2 is not None and p is not None  # every tested wall has bins (dof > 0)
    every = chi2_p(np.concatenate([w.z for w in tested]))
    rest = chi2_p(np.concatenate([w.z_rest for w in tested]))
    bound = chi2_p(np.concatenate([w.z_bound for w in tested]))
    roles = sorted({w.wall for w in tested})
    by_wall = {role: _pooled([w for w in tested if w.wall == role], weak) for role in roles}
    p_run = {r: 1.0 if v[2] is None else v[2] for r, v in per_run.items()}  # p may be 0.0
    showing = [r for r in runs if p_run[r] < P_CONSISTENT]
    significant = [r for r in runs if p_run[r] < P_SIGNIFICANT]
    cell_of = _cells(runs, info)
    cells = sorted(set(cell_of.values()))

    # a run whose errors could not have shown the departure predicted for it is neither for
    # nor against: it does not make the runs disagree
    def blind_at(show: Sequence[str], scale: float = 1.0) -> list[str]:
        """The runs too noisy to show the predicted departure, every se times
        1/sqrt(``scale``) (the shift scales as 1/se^2)."""
        out = []
        for r in runs:
            own = [w for w in tested if w.run == r]
            if r in show or r in unfit or all(_prediction(w, model, unfit)[0] is None for w in own):
                continue
            n_r = sum(_decisive(w).size for w in own)
            s_r = sum(_shift(w, model, unfit) for w in own)
            if float(chi2_dist.sf(n_r + scale * s_r, n_r)) >= P_CONSISTENT:
                out.append(r)
        return out

    blind = blind_at(showing)
    on = (
        f"without the first layer at the {len(dependent)} walls where its departure beyond "
        f"the null changes sign between the stencils "
        f"({', '.join(f'{w.run}:{w.wall}' for w in dependent)}): {dof} bins"
        if dependent
        else f"every near-wall bin, the first layer included: {dof} bins"
    )
    spread = (
        f" (under the {weak} stencil, where it is weakest; over the {len(names)} stencils "
        f"chi^2 = {min(t[0] or 0.0 for t in by_stencil.values()):.4g} to "
        f"{max(t[0] or 0.0 for t in by_stencil.values()):.4g})"
        if len(names) > 1
        else ""
    )
    pooled = (
        f"pooled over {len(runs)} runs, {on}, the departure beyond the null "
        f"{_test_text((chi2, dof, p))}{spread}"
    )
    pooled += "".join(f"; {role} walls alone: {_test_text(t)}" for role, t in by_wall.items())
    zero = chi2_p(np.concatenate([w.z_zero for w in tested]))
    pooled += (
        f". Under the analysis' stencil, with every first layer: {_test_text(every)}; without "
        f"any first layer: {_test_text(rest)}; with se_omega + se_half (the largest error): "
        f"{_test_text(bound)}; against 0 (no null), every bin: {_test_text(zero)}"
    )
    models = sorted({m for w in tested for m in w.predicted_stencils})
    detail = _walls_text(tested, models)
    if untested:
        detail += (
            "; not judged (the material does not shear there: it moves with the wall, and no "
            "model predicts a departure): " + _walls_text(untested)
        )
    first_layers = {
        f"{w.run}:{w.wall}": {s: w.beyond_first(s) for s in (list(w.stencils) or ["analysis"])}
        for w in tested
    }
    numbers: dict[str, Any] = {
        "pooled_chi2": chi2,
        "pooled_dof": dof,
        # the normal reading's p, named so (referee 14, point 6): the verdict states
        # pooled_p_headline (t(blocks - 1)); no tool should quote this one as the verdict's p
        "pooled_p_normal": p,
        "pooled_stencil": weak,
        "pooled_by_stencil": {
            s: {"chi2": t[0], "dof": t[1], "p": t[2]} for s, t in by_stencil.items()
        },
        "pooled_chi2_every_bin": every[0],
        "pooled_dof_every_bin": every[1],
        "pooled_p_every_bin": every[2],
        "pooled_chi2_without_first_layer": rest[0],
        "pooled_dof_without_first_layer": rest[1],
        "pooled_p_without_first_layer_normal": rest[2],
        "pooled_chi2_bound": bound[0],
        "pooled_p_bound": bound[2],
        "pooled_chi2_against_zero": zero[0],
        "pooled_p_against_zero": zero[2],
        "null_models": {f"{w.run}:{w.wall}": w.null_model for w in tested if w.null is not None},
        "null_sources": {f"{w.run}:{w.wall}": w.null_source for w in tested if w.null is not None},
        "first_layer_beyond_null": {
            k: {s: {"departure": b, "se": e} for s, (b, e) in v.items()}
            for k, v in first_layers.items()
        },
        "stencil_dependent_walls": [f"{w.run}:{w.wall}" for w in dependent],
        "model_first_layer_stencil_dependent": {
            m: [f"{w.run}:{w.wall}" for w in tested if w.stencil_dependent(m)] for m in models
        },
        "by_wall": {k: {"chi2": v[0], "dof": v[1], "p": v[2]} for k, v in by_wall.items()},
        "runs_departing_p_0.05": showing,
        "runs_departing_p_significant": significant,
    }
    shift = sum(_shift(w, model, unfit) for w in tested)
    sources = sorted({s for w in tested if (s := _prediction(w, model, unfit)[1])})
    whose = (
        "the joint u + omega + stress-ratio fits' (spin_model's)"
        if sources == ["joint"]
        else f"the {', '.join(sources)} fits'"
        if sources
        else ""
    )
    numbers["prediction_from"] = sources
    needed = float(chi2_dist.isf(P_SIGNIFICANT, dof)) - dof
    p_seen = float(chi2_dist.sf(dof + shift, dof)) if sources else None
    numbers["p_if_model_departure_were_there"] = p_seen
    free = [_shift_free(w) for w in tested]
    free_shift, free_n = sum(f[0] for f in free), sum(f[1] for f in free)
    p_free = float(chi2_dist.sf(free_n + free_shift, free_n)) if free_n else None
    numbers["p_if_size_were_there"] = p_free
    numbers["detect_size"] = DETECT_SIZE
    numbers["runs_too_noisy_to_show_the_model_departure"] = blind
    too_noisy = (
        f"; {len(blind)} do not and could not have: the departure {whose} predict for them "
        f"would not give p < {P_CONSISTENT:g} at their errors ({', '.join(blind)})"
        if blind
        else ""
    )
    rests = (
        f" The first layer's departure beyond the null changes sign between the stencils at "
        f"{len(dependent)} of {len(tested)} sheared walls: the verdict rests on the other "
        "near-wall bins there."
        if dependent
        else ""
    )
    counted = sorted(r for r in runs if r in unfit and r not in showing)
    counted_text = (
        f"; counted although the {model} u-only fit supplies no prediction there: "
        + "; ".join(f"{r} ({unfit[r]})" for r in counted)
        if counted
        else ""
    )
    numbers["runs_counted_with_unusable_fits"] = counted
    numbers["carrying_bins"] = {
        f"{w.run}:{w.wall}": carrying_bins(w, weak) for w in tested if carrying_bins(w, weak)
    }
    numbers["walls_without_null"] = [f"{w.run}:{w.wall}" for w in no_null]
    need_free = float(chi2_dist.isf(P_SIGNIFICANT, free_n)) - free_n if free_n else 0.0
    smallest = DETECT_SIZE * math.sqrt(need_free / free_shift) if free_shift > 0.0 else None
    numbers["smallest_size_seen"] = smallest
    power = (
        f" Power: {whose} departure beyond the null would give p = {p_seen:.2g} at these errors"
        if p_seen is not None
        else " Power: no usable fit predicts a departure here"
    )
    if p_free is not None and smallest is not None:
        power += (
            f"; model-free, a departure of {DETECT_SIZE:g} V/d (one sign) in each of the "
            f"{free_n} near-wall bins beyond the first layers would give p = {p_free:.2g}, and "
            f"the smallest these errors would show there at p < {P_SIGNIFICANT:g} is "
            f"{smallest:.2g} V/d"
        )
    power += "."
    strong = [st for st, t in by_stencil.items() if t[2] is not None and t[2] < P_SIGNIFICANT]
    if len(names) > 1 and strong and len(strong) < len(names):
        weak_ones = ", ".join(
            f"{st} (p = {t[2]:.2g})"
            for st, t in by_stencil.items()
            if st not in strong and t[2] is not None
        )
        power += (
            f" The pooled test departs at p < {P_SIGNIFICANT:g} under {len(strong)} of "
            f"{len(names)} stencils ({', '.join(strong)}), not under {weak_ones}."
        )
    bin2, bin2_rows = _bin2_text(tested)
    numbers["bin2_null_envelope"] = bin2_rows
    numbers["cells"] = cell_of
    carrying_all = {f"{w.run}:{w.wall}": carrying_bins(w, weak) for w in tested}
    unsteady = _unsteady_text(carrying_all, info)
    numbers["carrying_runs_not_steady"] = sorted(
        {k.split(":")[0] for k, b in carrying_all.items() if b}
        & {r for r, i in info.items() if i.unsteady}
    )
    two = _two_speeds(tested, info)
    numbers["first_layer_at_two_speeds"] = [
        {"fast": f.fast, "slow": f.slow, "speeds": list(f.speeds),
         "departures": [list(d) for d in f.departures], "z": f.z, "agrees": f.agrees}
        for f in two
    ]  # fmt: skip
    deciding = DECIDING_RUNS_TWO_SPEEDS if two else DECIDING_RUNS
    head = (
        f"{_carry_text(tested, weak)}. In detail: {pooled}. "
        f"{count_text(showing, runs, info)} depart at p < {P_CONSISTENT:g} "
        f"({count_text(significant, runs, info, named=False)} at p < {P_SIGNIFICANT:g}) "
        f"under every stencil{too_noisy}{counted_text}.{rests}{power} {detail}.{unjudged} "
        f"{SPIN_METHOD}"
    )
    blocks = min((w.blocks for w in tested), default=0)
    # the fewer bins first: the pooled test's sums then carry on from theirs (_t_sums)
    c_t_rest = pooled_t_count(rest[0], rest[1], blocks)
    c_t = pooled_t_count(chi2, dof, blocks)
    p_t = None if c_t is None else (c_t[0] + 1) / (c_t[1] + 1)
    p_t_rest = None if c_t_rest is None else (c_t_rest[0] + 1) / (c_t_rest[1] + 1)
    numbers["pooled_p_t"] = p_t
    numbers["pooled_p_t_without_first_layer"] = p_t_rest
    # referee 12, point 7: each Monte Carlo p with its exceedances and draws
    for name, c in (("pooled_p_t", c_t), ("pooled_p_t_without_first_layer", c_t_rest)):
        numbers[f"{name}_count"] = None if c is None else c[0]
        numbers[f"{name}_draws"] = None if c is None else c[1]
        numbers[f"{name}_mc_error"] = None if c is None else mc_error(*c)
    numbers["blocks"] = blocks
    # referee 13, point 6: a p within its MC error of the line is "p ~ 0.001", not "< 0.001"
    numbers["pooled_p_t_without_first_layer_text"] = (
        None if c_t_rest is None else mc_p_text(p_t_rest or 0.0, *c_t_rest, line=True)
    )
    # referee 11, point 1: pooled_p_normal reads each z as normal, pooled_p_t under t(blocks - 1);
    # the headline is the one the verdict states (t where the blocks are recorded)
    numbers["pooled_p_headline"] = p_t if p_t is not None else p
    numbers["pooled_p_headline_reading"] = f"t({blocks - 1})" if p_t is not None else "normal"
    numbers["pooled_p_headline_count"] = None if c_t is None else c_t[0]
    numbers["pooled_p_headline_draws"] = None if c_t is None else c_t[1]
    numbers["pooled_p_headline_mc_error"] = None if c_t is None else mc_error(*c_t)
    # referee 15, point 6: the one p the verdict states, and why the other pooled_p_* are not it
    numbers["verdict_p"] = numbers["pooled_p_headline"]
    numbers["p_note"] = P_NOTE
    misfits = null_misfits(tested, info)
    numbers["null_fit_misfits"] = misfits
    misfit_line = _null_misfit_text(misfits)
    # referee 12, point 1: the first layer grain by grain against the joint fit's null, and
    # where the u-only mu(I) velocity alone makes the first bins' departure
    grains = grain_rows(tested, info)
    grain_line, grain_counts = grain_text(grains)
    numbers["grain_scale"] = {"walls": grains, **grain_counts} if grains else None
    # referee 13, point 1: the model-free reading of the same record
    # referee 14, point 2: the sheared fixed walls' records too (the layer runs' smooth walls)
    grain_free = free_rows({**grains, **fixed_rows(walls, info)})
    free_line, free_counts = free_text(grain_free)
    free_first = free_lead(grain_free)
    grain_line += free_line
    numbers["grain_scale_model_free"] = {"walls": grain_free, **free_counts} if grain_free else None
    reproduced = u_only_reproduces(tested, info)
    numbers["u_only_mui_reproduces"] = reproduced
    moving = sum(1 for w in tested if w.wall == "moving" and "mui" in w.predicted)
    grain_line += u_only_text(reproduced, moving) if moving else ""
    grain_line += mc_line(p_t_rest, c_t_rest, "Without the first layers")
    would_first = GRAIN_WOULD_CHANGE if grains else ""
    if p_t is not None and c_t is not None:
        head = (
            f"read with each bin's z under t({blocks - 1}), as the bins' p are (the se come "
            f"from {blocks} time blocks; a seeded Monte Carlo of {T_SAMPLES:,} draws): the "
            f"pooled {mc_p_text(p_t, *c_t)}"
            + (
                f", without any first layer {mc_p_text(p_t_rest, *c_t_rest, line=True)}"
                if p_t_rest is not None and c_t_rest is not None
                else ""
            )
            + basins_text(runs, info)
            + f"; {head}"
        )
    # the first layers' null is the velocity inside the first bin, which the bins do not
    # resolve (a sub-grain wall layer that fits the bins can absorb their departure; referee
    # 9, point 1): where the support needs them, the verdict says it holds given a velocity
    # smooth on the grain scale
    rest_p = p_t_rest if p_t_rest is not None else rest[2]
    needs_first = needs_first_layers(rest_p)
    numbers["supported_given_smooth_velocity"] = needs_first
    # the rule counts cells: runs of one cell at two wall speeds are not independent
    cells_showing = [c for c in cells if all(r in showing for r in runs if cell_of[r] == c)]
    cells_blind = [c for c in cells if all(r in blind for r in runs if cell_of[r] == c)]

    def rule_at(factor: float) -> str:
        """The rule's verdict with every se multiplied by ``factor`` (each chi^2 and the
        predicted shift divided by factor^2), the cells counted as above."""
        scale = 1.0 / factor**2
        p_f = float(chi2_dist.sf(chi2 * scale, dof))
        c_f = pooled_t_count(chi2 * scale, dof, blocks)
        show = [r for r in runs if per_run[r][2] is not None
                and float(chi2_dist.sf((per_run[r][0] or 0.0) * scale, per_run[r][1]))
                < P_CONSISTENT]  # fmt: skip
        blind_f = blind_at(show, scale)
        c_show = [c for c in cells if all(r in show for r in runs if cell_of[r] == c)]
        c_blind = [c for c in cells if all(r in blind_f for r in runs if cell_of[r] == c)]
        if p_f < P_SIGNIFICANT and (c_f is None or (c_f[0] + 1) / (c_f[1] + 1) < P_SIGNIFICANT):
            return "supported" if 2 * len(c_show) >= len(cells) - len(c_blind) else "mixed"
        seen_f = float(chi2_dist.sf(dof + scale * shift, dof)) if sources else None
        if p_f >= P_CONSISTENT and seen_f is not None and seen_f < P_SIGNIFICANT:
            return "refuted"
        return "undecided"

    first_z = [(float(b["z"] or 0.0), b["distance_d"] == float(np.min(w.distance_d)))
               for w in tested for b in carrying_bins(w, weak)]  # fmt: skip
    rows = seed_factor_rows(seed_factors, (chi2, dof), rest[:2], blocks, first_z, rule_at)
    numbers["pooled_p_at_seed_factor"] = rows
    numbers["seed_factor_crossing"] = crossing_factor(chi2, dof, blocks)
    numbers["seed_factor_crossing_without_first_layer"] = crossing_factor(rest[0], rest[1], blocks)
    largest = max(rows, key=lambda r: r["factor"]) if rows else None
    numbers["seed_factor_largest"] = None if largest is None else largest["factor"]
    numbers["verdict_at_largest_seed_factor"] = None if largest is None else largest["verdict"]
    numbers["seed_factor_note"] = SEED_FACTOR_NOTE
    seed_line = seed_factor_text(rows, numbers["seed_factor_crossing"])
    if p < P_SIGNIFICANT and (p_t is None or p_t < P_SIGNIFICANT):
        lead = _lead(
            tested, info, weak, (chi2, dof, p, p_t), (*rest, p_t_rest), blocks, (c_t, c_t_rest)
        )
        lead += f"{bin2}{misfit_line}{unsteady}{grain_line}"
        if 2 * len(cells_showing) >= len(cells) - len(cells_blind):
            given = (
                f" It holds {SMOOTH_VELOCITY}: the support needs the first layers, whose null "
                "is the velocity inside a first bin the bins do not resolve; without them the "
                f"pooled test gives p = {rest_p if rest_p is not None else float('nan'):.2g}"
                + (f" under t({blocks - 1})" if p_t_rest is not None else "")
                + f", not below {P_SIGNIFICANT:g}."
                if needs_first
                else ""
            )
            qualifier = null_qualifier(tested, needs_first)
            if largest is not None and largest["verdict"] not in (None, "supported"):
                # referee 17, point 2: not "supported" at the replicates' seed scatter
                qualifier += (
                    f", at the block errors (at the replicates' omega seed factor "
                    f"x{largest['factor']:.3g}: p = {largest['p']:.2g}, '{largest['verdict']}')"
                )
            numbers["qualifier"] = qualifier
            return Verdict(
                key,
                "supported",
                f"{free_first}{lead}{given}{seed_line} The test: the measured spin departs from "
                f"half the measured vorticity near the sheared walls, beyond what the binning and "
                f"the stencil make of a spin equal to half the vorticity, under every stencil; "
                f"{head}",
                f"{would_first}runs at the same conditions whose near-wall spins agree with half "
                "the vorticity, a null (a velocity inside the first bin) that absorbs the "
                "first-layer departure, or a bin-to-bin correlation of the errors large enough "
                f"to bring the pooled chi^2 below {float(chi2_dist.isf(P_SIGNIFICANT, dof)):.4g}; "
                f"{deciding}.",
                tuple(runs),
                numbers,
                qualifier=qualifier,
            )
        return Verdict(
            key,
            "mixed",
            f"{free_first}Mixed: the pooled test departs, but only {len(cells_showing)} of "
            f"{len(cells) - len(cells_blind)} "
            f"{'runs' if len(cells) == len(runs) else 'cells'} that could show it do; the "
            f"pooled result rests on them. {lead}{misfit_line}{seed_line} {head}",
            f"{would_first}more runs at the conditions of those that do not depart, to tell a "
            f"real difference between runs from scatter; {deciding}.",
            tuple(runs),
            numbers,
        )
    head = f"{head}{bin2}{misfit_line}{unsteady}{grain_line}{seed_line}"
    if p >= P_CONSISTENT and p_seen is not None and p_seen < P_SIGNIFICANT:
        return Verdict(
            key,
            "refuted",
            f"{free_first}Refuted: no departure near the sheared walls, although {whose} departure "
            f"beyond the null would have given p = {p_seen:.2g}; {head}",
            f"{would_first}a departure in runs with smaller errors, or a model whose predicted "
            f"departure these errors could not see; {deciding}.",
            tuple(runs),
            numbers,
        )
    changes = []
    if shift > 0.0:
        factor = math.sqrt(needed / shift)
        changes.append(
            f"errors smaller by a factor {factor:.2g} (runs about {factor**2:.2g} times longer) "
            f"would show {whose} predicted departure at p < {P_SIGNIFICANT:g}"
        )
    if smallest is not None:
        changes.append(
            f"a departure in the bins beyond the first layers: these errors would show one of "
            f"{smallest:.2g} V/d at p < {P_SIGNIFICANT:g}"
        )
    change = "; ".join(changes) or (
        f"errors small enough to see a pooled chi^2 above {needed + dof:.4g}"
    )
    a = by_stencil.get("analysis", (chi2, dof, p))
    lead = (
        f"the departure beyond the null is significant under every stencil with z read as "
        f"normal (under {weak}: {p_text(chi2, dof, p)}), but not with each bin's z under "
        f"t({blocks - 1}) (p = {p_t:.2g})"
        if p < P_SIGNIFICANT and p_t is not None
        else f"the departure beyond the null is significant under {len(strong)} of {len(names)} "
        f"stencils (the analysis' {_test_text(a)}), not under every one (under {weak}: "
        f"{p_text(chi2, dof, p)})"
        if strong
        else f"no significant departure ({p_text(chi2, dof, p)}, under the {weak} stencil)"
        if len(names) > 1
        else f"no significant departure ({p_text(chi2, dof, p)})"
    )
    seen = (
        f"the errors are too large to have seen {whose} departure beyond the null (it would "
        f"give p = {p_seen:.2g})"
        if p_seen is not None
        else "no usable fit predicts a departure to have seen"
    )
    return Verdict(
        key,
        "undecided",
        f"{free_first}The data cannot decide: {lead}, and {seen}; {head}",
        f"{would_first}{change}; {deciding}.",
        tuple(runs),
        numbers,
    )


def spin_model_verdict(
    walls: Sequence[WallSpin],
    model: str = "cosserat",
    unfit: Mapping[str, str] | None = None,
    left_out: Sequence[str] = (),
) -> Verdict:
    """Has the measured departure the sign and size ``model`` predicts (module docstring)?

    Parameters
    ----------
    walls : sequence of WallSpin
        Every run's walls, with each fitted model's departure.
    model : str
        The model whose departure is judged.
    unfit : mapping of run name to str, optional
        Runs whose ``model`` fit cannot supply a prediction (it contradicts the measured
        stress ratio, or a wall parameter sits at a bound), with why: their walls decide
        nothing; what they say is kept in ``numbers["with_contradicting_fits"]``.
    left_out : sequence of str
        Walls left out by the caller, each with why (the fit cannot predict there), named in
        the evidence.
    """
    key = "spin_model"
    unfit = dict(unfit or {})
    tested = [w for w in walls if w.sheared and w.dof > 0 and model in w.predicted]
    flagged = [w for w in tested if w.run in unfit]
    kept = [w for w in tested if w.run not in unfit]
    out = _spin_model_on(kept, model) if kept or not flagged else None
    note = f" Left out: {'; '.join(left_out)}." if left_out else ""
    if out is not None and out.verdict != "undecided":
        # the scope in the verdict field (referee 10, point 1): these are the u-only fits
        out = replace(out, qualifier=f"with the {model} model fitted to the velocity alone")
    if not flagged:
        assert out is not None
        return replace(out, evidence=out.evidence + note)
    on_flagged = _spin_model_on(flagged, model)
    why = "; ".join(f"{r}: {unfit[r]}" for r in sorted({w.run for w in flagged}))
    said = {**on_flagged.numbers, "verdict": on_flagged.verdict}
    decide = (
        f"a joint calibration of the {model} model on u and omega together, with phi tied to "
        "the measured band stress ratio (sin phi = |sigma_yx|/sigma_yy) and the wall "
        "parameters inside their ranges, whose first-layer departure is then compared with "
        "the data's."
    )
    if out is None:
        return Verdict(
            key,
            "undecided",
            f"Undecided: the {model} fits that supply the predicted departure cannot be used "
            f"({why}); a prediction from a calibration that contradicts what the same runs "
            f"measure directly tests the calibration, not the model. On these fits the data "
            f"would read '{on_flagged.verdict}' ({on_flagged.evidence}){note}",
            decide,
            tuple(sorted({w.run for w in flagged})),
            {"with_contradicting_fits": said},
        )
    return replace(
        out,
        evidence=(
            f"{out.evidence} Not used ({why}): on those fits the data would read "
            f"'{on_flagged.verdict}'.{note}"
        ),
        would_change=f"{out.would_change} For the runs not used: {decide}",
        numbers={**out.numbers, "with_contradicting_fits": said},
    )


def _sign_determined(w: WallSpin) -> bool:
    """The first layer's measured sign is determined: |departure| >= :data:`SIGN_SIGMAS` se
    (without stencils: under the analysis' stencil; with them: the same sign under every
    stencil, and that far from 0 under at least one, with its own error)."""
    m, s = w.first, w.first_se
    assert m is not None and s is not None
    if not w.stencils:
        return abs(m) >= SIGN_SIGMAS * s
    if w.stencil_dependent():
        return False
    return any(abs(d) >= SIGN_SIGMAS * math.hypot(sh, so) for d, sh, so in w.stencils.values())


def _model_residual(w: WallSpin, model: str) -> FloatArray:
    """Whitened (departure - the model's)/se of a wall, without the first layer where its sign
    (the data's or the model's) depends on the stencil [-]."""
    r = np.asarray(w.departure) - w.predicted[model]
    return w.white_rest(r) if w.stencil_dependent() or w.stencil_dependent(model) else w.white(r)


def _spin_model_on(tested: Sequence[WallSpin], model: str) -> Verdict:
    """:func:`spin_model_verdict` on the walls ``tested`` (sheared, with spin and a fit)."""
    key = "spin_model"
    if not tested:
        return Verdict(
            key,
            "undecided",
            f"The data cannot decide: no run has both the spin near a sheared wall and a fit "
            f"of the {model} model.",
            f"a run with omega and half_vorticity near the moving wall that the {model} model "
            "can be fitted to.",
        )
    rows, same, opposite, none, undetermined, dependent = [], [], [], [], [], []
    for w in tested:
        m, s, pm = w.first, w.first_se, w.predicted_first(model)
        assert m is not None and s is not None and pm is not None
        others = ", ".join(
            f"{k} {w.predicted_first(k):+.3g}" for k in sorted(w.predicted) if k != model
        )
        point = w.point.get(model)
        at_point = "" if point is None else f", {point:+.3g} as a point value"
        c, n, pp = w.misfit(model)
        cr, nr, pr = w.misfit(model, rest=True)
        shaky = [who for who in ("data", model) if w.stencil_dependent(who)]
        rows.append(
            f"{w.run} ({w.wall} wall, first layer): measured {m:+.3g} +- {s:.2g}, {model} "
            f"predicts {pm:+.3g} as measured{at_point} (chi^2 of data - model over {n} "
            f"near-wall bins = {_g(c, '.4g')}, {p_text(c, n, pp)}; without the first layer "
            f"{_g(cr, '.4g')} for {nr}, {p_text(cr, nr, pr)})"
            + (f"; other models {others}" if others else "")
            + _stencil_text(w, [model])
            + (
                f"; the first layer's sign is stencil-dependent ({' and '.join(shaky)}): not "
                "counted"
                if shaky
                else ""
            )
        )
        if shaky:
            dependent.append(w)
        elif not _sign_determined(w):
            undetermined.append(w)
        elif abs(pm) <= NO_DEPARTURE:
            none.append(w)
        elif pm * m > 0:
            same.append(w)
        else:
            opposite.append(w)
    undetermined += dependent
    detail = "; ".join(rows)
    method = (
        "Method: omega - half vorticity in the first layer of each sheared wall (the bin "
        "nearest to it) against the model's there, the model's measured as the data are (bin "
        "averages of its u and omega, the analysis' difference stencil); the measured sign is "
        f"determined where its sign (and the model's) is the same under all {len(STENCILS)} "
        f"stencils and |departure| >= {SIGN_SIGMAS:g} se under at least one; the size is "
        "tested by chi^2 of the whitened (departure - model)/se over the bins of the walls "
        "with a determined sign (where the first layer is stencil-dependent: over the other "
        "bins)."
    )
    determined = same + opposite + none
    runs = tuple(sorted({w.run for w in tested}))
    numbers: dict[str, Any] = {
        "stencil_dependent": [f"{w.run}:{w.wall}" for w in dependent],
        "same_sign": [f"{w.run}:{w.wall}" for w in same],
        "opposite_sign": [f"{w.run}:{w.wall}" for w in opposite],
        "model_predicts_none": [f"{w.run}:{w.wall}" for w in none],
        "sign_undetermined": [f"{w.run}:{w.wall}" for w in undetermined],
    }
    if not determined:
        c, n, pp = chi2_p(np.concatenate([_model_residual(w, model) for w in tested]))
        numbers.update({"size_chi2": c, "size_dof": n, "size_p": pp})
        if pp is not None and pp < P_SIGNIFICANT:
            return Verdict(
                key,
                "refuted",
                f"Refuted: the data show no departure of determined sign, but the {model} "
                f"model, fitted to the velocity, predicts one these errors reject: chi^2 of "
                f"data - model = {c:.4g} for {n} near-wall bins ({p_text(c, n, pp)}). {detail}. "
                f"{method}",
                "runs with a departure of the size the model predicts, or model parameters "
                "(a joint calibration on the spin) whose departure is smaller.",
                runs,
                numbers,
            )
        best = min(tested, key=lambda w: w.first_se or math.inf)
        return Verdict(
            key,
            "undecided",
            f"The data cannot decide: the measured departure's sign is not determined at any "
            f"wall (in every first layer |departure| < {SIGN_SIGMAS:g} se, or its sign or the "
            f"model's depends on the stencil), and the model's departure is not rejected over "
            f"the other bins ({_test_text((c, n, pp))}). {detail}. {method}",
            f"errors of the first layer's departure below |departure|/{SIGN_SIGMAS:g} (now "
            f"{_g(best.first_se, '.2g')} at best).",
            runs,
            numbers,
        )
    if opposite and same:
        return Verdict(
            key,
            "mixed",
            f"Mixed: the {model} model's departure has the measured sign at "
            f"{len(same)} walls and the opposite sign at {len(opposite)}. {detail}. {method}",
            "more runs at the conditions of each group, to tell whether the sign depends on "
            "the wall or the cell.",
            runs,
            numbers,
        )
    if opposite:
        small = sum(1 for w in opposite if abs(w.predicted_first(model) or 0.0) < (w.first_se or 0))
        return Verdict(
            key,
            "refuted",
            f"Refuted: where the measured sign is determined the {model} model, fitted to the "
            f"velocity, departs with the opposite sign ({len(opposite)} of "
            f"{len(determined)} walls of determined sign; at {small} of them the predicted "
            f"departure is smaller than the measured error). {detail}. {method}",
            "a fit of the model to the spin as well as the velocity (a joint calibration) "
            "that reverses the predicted sign, or runs where the measured sign turns.",
            runs,
            numbers,
        )
    c, n, pp = chi2_p(np.concatenate([_model_residual(w, model) for w in determined]))
    numbers.update({"size_chi2": c, "size_dof": n, "size_p": pp})
    if none:
        return Verdict(
            key,
            "refuted",
            f"Refuted: the data depart where the {model} model predicts no departure "
            f"({len(none)} of {len(determined)} walls). {detail}. {method}",
            "model parameters (a joint calibration on the spin) that make the model depart there.",
            runs,
            numbers,
        )
    if pp is not None and pp < P_SIGNIFICANT:
        return Verdict(
            key,
            "refuted",
            f"Refuted: the sign agrees but the size does not: chi^2 of data - model = {c:.4g} "
            f"for {n} bins ({p_text(c, n, pp)}). {detail}. {method}",
            "a fit that matches the spin's size as well as the velocity.",
            runs,
            numbers,
        )
    return Verdict(
        key,
        "supported",
        f"Supported: the measured departure has the sign the {model} model predicts at every "
        f"wall where it is determined, and its size is not rejected (chi^2 = {_g(c)} for {n} "
        f"bins, {p_text(c, n, pp)}). {detail}. {method}",
        "a run with smaller errors whose departure differs from the model's in size or sign.",
        runs,
        numbers,
    )


# --------------------------------------------------------------------------- Delta
@dataclass(frozen=True)
class DeltaPoint:
    """Delta of one run's data [d] at its gap H/d, with its error and whether it fills it."""

    run: str
    gap_d: float
    value: float | None
    stderr: float | None
    fills_gap: bool = False
    reason: str = ""
    far: str = ""
    """Where the fixed far wall slips: its velocity and both Deltas
    (``measures.Thickness.far_text``), "" where it does not."""

    @property
    def usable(self) -> bool:
        return (
            self.value is not None
            and self.value > 0.0
            and self.stderr is not None
            and self.stderr > 0.0
            and not self.fills_gap
        )


@dataclass(frozen=True)
class ModelDelta:
    """One model's Delta at a gap series from one joint calibration of its material (every
    run of the material on the cell, every wall kind; the series' own wall).

    Attributes
    ----------
    model : str
        The rheology.
    predicted : mapping of run name to (Delta, se)
        The calibrated model's Delta at each run's gap, bins and rate [d], and its standard
        error from the calibration's parameter covariance [d] (None where it has none).
    curve : (gaps, Delta)
        The model's Delta on a grid of H/d (for the figure) [-], [d].
    calibration : mapping
        What the calibration gave (parameters, chi2, dof, p_value, warnings; ``runs`` and
        ``wall_kinds``: what it was made on, :func:`scope_text`), for the report.
    status, message : str
        ``"ok"``, or ``"failed"`` and why.
    why : mapping of str to str
        Why the model gives no Delta, by run name and by curve gap (``fits.curve_key``).
    resolved_above : mapping of str to float
        The second bin's distance from the moving wall at each run and curve gap [d]: a Delta
        at or below it is not resolved by the bins (:meth:`resolved`).
    best : ModelDelta or None
        An alternative's per-series best fit (``fits.calibrate_best``: the series' runs alone,
        the velocity and the moving wall's measured T, every parameter free, NGF's b off the
        solver's edge), at which the
        claims judge its rejection; None for the claims' model or where it was not made.
    """

    model: str
    predicted: Mapping[str, tuple[float | None, float | None]] = field(default_factory=dict)
    curve: tuple[tuple[float, ...], tuple[float, ...]] = ((), ())
    calibration: Mapping[str, Any] = field(default_factory=dict)
    status: str = "ok"
    message: str = ""
    why: Mapping[str, str] = field(default_factory=dict)
    resolved_above: Mapping[str, float] = field(default_factory=dict)
    best: ModelDelta | None = None
    reach: tuple[tuple[float, ...], tuple[float | None, ...]] = ((), ())
    """The claims' model's Delta beyond ``curve`` (``fits.REACH_SPAN``; referee 13, point 3),
    as ``curve``: where its own slope reaches the claimed limits (``full_curve``)."""

    def full_curve(self) -> tuple[tuple[float, ...], tuple[float | None, ...]]:
        """``curve`` and ``reach`` together, by gap."""
        gaps, values = (*self.curve[0], *self.reach[0]), (*self.curve[1], *self.reach[1])
        pts = sorted(zip(gaps, values, strict=True), key=lambda p: p[0])
        return tuple(g for g, _ in pts), tuple(v for _, v in pts)

    def resolved(self, key: str, value: float | None) -> bool:
        """Whether ``value`` (the model's Delta at run or curve gap ``key``) is above the second
        bin there, as the data's Delta must be to be used (True where that is not recorded)."""
        floor = self.resolved_above.get(key)
        return value is not None and (floor is None or value > floor)

    @property
    def ok(self) -> bool:
        return self.status == "ok"

    def slope_between(self, g0: float, g1: float) -> float | None:
        """The curve's own log-log slope between H/d = g0 and g1 (interpolated in log-log),
        None without a curve spanning them (``reach`` included)."""
        gaps, values = self.full_curve()
        pts = [(g, v) for g, v in zip(gaps, values, strict=True) if v is not None and v > 0.0]
        if len(pts) < 2 or g1 <= g0 or pts[0][0] > g0 * (1 + 1e-9) or pts[-1][0] < g1 * (1 - 1e-9):
            return None
        lg = np.log([g for g, _ in pts])
        lv = np.log([v for _, v in pts])
        v0, v1 = np.interp(math.log(g0), lg, lv), np.interp(math.log(g1), lg, lv)
        return float((v1 - v0) / (math.log(g1) - math.log(g0)))


@dataclass(frozen=True)
class CurveTest:
    """Measured Delta against one prediction at the series' gaps.

    ``chi2``/``dof``/``p``: the prediction as it is (dof = points: nothing fitted to Delta);
    ``scale``, ``chi2_shape``/``dof_shape``/``p_shape``: the prediction times the best common
    factor (dof = points - 1), which tests the dependence on the gap apart from the level.
    """

    label: str
    n: int
    chi2: float
    p: float
    scale: float
    chi2_shape: float
    p_shape: float | None
    level_free: bool = False
    """A law with no level of its own (a power law, :func:`power_law_test`): its "as it is"
    chi^2 is against an arbitrary level (Delta = 1 d at H/d = 1) and tests nothing, so only
    the shape test is reported; with one point there is none."""

    @property
    def dof(self) -> int:
        return self.n

    @property
    def dof_shape(self) -> int:
        return self.n - 1

    @property
    def sig(self) -> str:
        """The prediction as it is: p, or z and chi^2/dof below 1e-6
        (``cosserat._text.significance``)."""
        return significance(self.chi2, self.dof)

    @property
    def sig_shape(self) -> str:
        """The shape test's p, or z and chi^2/dof below 1e-6 ("-" without one)."""
        return "-" if self.p_shape is None else significance(self.chi2_shape, self.dof_shape)

    def text(self) -> str:
        shape = (
            f"times {self.scale:.3g}: chi^2 = {self.chi2_shape:.3g} for {self.dof_shape} dof "
            f"({self.sig_shape})"
            if self.p_shape is not None
            else "no shape test (one point)"
        )
        if self.level_free:
            if self.p_shape is None:
                return f"{self.label}: not tested (its level is free, so one gap tests nothing)"
            return f"{self.label} with a free level, {shape}"
        return f"{self.label}: chi^2 = {self.chi2:.3g} for {self.dof} dof ({self.sig}); " + shape

    def to_dict(self) -> dict[str, Any]:
        return {
            "label": self.label,
            "chi2": self.chi2,
            "dof": self.dof,
            "p": self.p,
            "scale": self.scale,
            "chi2_shape": self.chi2_shape,
            "dof_shape": self.dof_shape,
            "p_shape": self.p_shape,
            "level_free": self.level_free,
        }


def curve_test(
    label: str,
    measured: Sequence[tuple[float, float]],
    predicted: Sequence[tuple[float, float]],
) -> CurveTest | None:
    """chi^2 of measured Delta +- se against predicted Delta +- se at the same points (the two
    errors added in quadrature), as it is and times its best common factor (:class:`CurveTest`);
    None without a point.

    Parameters
    ----------
    label : str
        What is tested (a model's name, a power law).
    measured, predicted : sequences of (value, se)
        One pair per point, in the same order [d]; se > 0 for the measured ones.
    """
    if len(measured) != len(predicted):
        raise ParameterError(
            f"curve_test: {len(measured)} measured points but {len(predicted)} predictions"
        )
    if not measured:
        return None
    d = np.array([m for m, _ in measured], dtype=float)
    e = np.array([s for _, s in measured], dtype=float)
    p = np.array([m for m, _ in predicted], dtype=float)
    pe = np.array([s for _, s in predicted], dtype=float)
    if np.any(e <= 0.0) or not np.all(np.isfinite(np.concatenate([d, e, p, pe]))):
        raise ParameterError("curve_test: every point needs a finite value and a positive error")
    w = 1.0 / (e**2 + pe**2)
    chi2 = float(np.sum(w * (d - p) ** 2))
    scale = float(np.sum(w * d * p) / np.sum(w * p * p)) if np.any(p != 0.0) else 1.0
    # the predicted errors scale with the prediction
    ws = 1.0 / (e**2 + (scale * pe) ** 2)
    chi2_shape = float(np.sum(ws * (d - scale * p) ** 2))
    n = int(d.size)
    return CurveTest(
        label,
        n,
        chi2,
        float(chi2_dist.sf(chi2, n)),
        scale,
        chi2_shape,
        float(chi2_dist.sf(chi2_shape, n - 1)) if n > 1 else None,
    )


def power_law_test(
    exponent: float, points: Sequence[tuple[float, float, float]]
) -> CurveTest | None:
    """:func:`curve_test` of Delta proportional to (H/d)^exponent, points (H/d, Delta, se):
    only its shape test means something (its level is the free factor: ``level_free``)."""
    t = curve_test(
        f"Delta ~ (H/d)^{exponent:.3g}",
        [(v, s) for _, v, s in points],
        [(g**exponent, 0.0) for g, _, _ in points],
    )
    return None if t is None else replace(t, level_free=True)


@dataclass(frozen=True)
class DeltaSeries:
    """Delta against H/d for one gap series, the fitted models' slopes there, and each model's
    Delta from one joint calibration of the series' material (``curves``)."""

    key: str
    cell: str
    roughness: str | None
    gravity: bool
    points: tuple[DeltaPoint, ...]
    model_slopes: Mapping[str, SlopeFit | None] = field(default_factory=dict)
    notes: tuple[str, ...] = ()
    curves: Mapping[str, ModelDelta] = field(default_factory=dict)
    speeds: Mapping[str, float | None] = field(default_factory=dict)
    twins: tuple[tuple[str, str], ...] = ()
    """(a, b) run names of same-conditions replicates (one cell, one wall speed, two seeds:
    ``rate.twin_names``) among the points: the run-to-run scatter of Delta
    (:func:`seed_scatter`)."""

    def tests(self, best: bool = False) -> dict[str, CurveTest]:
        """Each calibrated model's :func:`curve_test` over the usable points it predicts; with
        ``best``, each alternative's per-series best fit's (``ModelDelta.best``; models
        without one left out)."""
        out = {}
        for name, cal in self.curves.items():
            c = cal.best if best else cal
            if c is None or not c.ok:
                continue
            pairs = [
                ((p.value, p.stderr), (c.predicted[p.run][0], c.predicted[p.run][1] or 0.0))
                for p in self.points
                if p.usable
                and p.value is not None
                and p.stderr is not None
                and c.predicted.get(p.run, (None, None))[0] is not None
            ]
            t = curve_test(name, [a for a, _ in pairs], [b for _, b in pairs])  # type: ignore[misc]
            if t is not None:
                out[name] = t
        return out

    def replicates(self) -> list[str]:
        """Runs at one gap (within :data:`SAME_GAP`), their Delta and wall speeds, and by how
        many errors they differ: they are not pooled silently (module docstring)."""
        out = []
        done: list[float] = []
        for p in self.points:
            if any(abs(p.gap_d - g) <= SAME_GAP * g for g in done):
                continue
            done.append(p.gap_d)
            same = [q for q in self.points if abs(q.gap_d - p.gap_d) <= SAME_GAP * p.gap_d]
            usable = [q for q in same if q.usable]
            if len(same) < 2:
                continue
            rows = ", ".join(
                f"{q.run} (wall speed {_g(self.speeds.get(q.run))}: Delta = {_g(q.value, '.3g')} "
                f"+- {_g(q.stderr, '.2g')} d)"
                for q in same
            )
            text = f"H/d = {p.gap_d:.3g} has {len(same)} runs, {rows}"
            if len(usable) >= 2:
                a, b = usable[0], usable[-1]
                assert a.value is not None and b.value is not None
                assert a.stderr is not None and b.stderr is not None
                z = abs(a.value - b.value) / math.hypot(a.stderr, b.stderr)
                text += f"; they differ by {z:.2g} se"
                speeds = {self.speeds.get(q.run) for q in same}
                if len(speeds) > 1:
                    text += " at different wall speeds"
                    if z > 2:
                        text += " (beyond 2 se: rate dependence, or run-to-run scatter)"
            text += (
                ". In the curve tests each run is its own point, against each model at its own "
                "rate (I_w); the power law's slope pools them as replicates"
            )
            out.append(text)
        return out

    @property
    def gaps(self) -> list[float]:
        return [p.gap_d for p in self.points]

    @property
    def Delta(self) -> list[float | None]:
        return [p.value for p in self.points]

    @property
    def stderr(self) -> list[float | None]:
        return [p.stderr for p in self.points]

    @property
    def distinct_gaps(self) -> int:
        gaps: list[float] = []
        for p in self.points:
            if p.usable and not any(abs(p.gap_d - g) <= SAME_GAP * g for g in gaps):
                gaps.append(p.gap_d)
        return len(gaps)

    @property
    def left_out(self) -> list[DeltaPoint]:
        return [p for p in self.points if p.fills_gap]

    @property
    def slope(self) -> SlopeFit | None:
        """ln Delta against ln(H/d) over the usable points (two distinct gaps at least)."""
        # usable points have a value and an error (DeltaPoint.usable)
        pts = [
            (p.gap_d, p.value, p.stderr)
            for p in self.points
            if p.usable and p.value is not None and p.stderr is not None
        ]
        if self.distinct_gaps < 2:
            return None
        try:
            return power_law_slope(
                [g for g, _, _ in pts], [v for _, v, _ in pts], [e for _, _, e in pts]
            )
        except ParameterError:
            return None

    @property
    def reason(self) -> str:
        n = self.distinct_gaps
        out = ""
        if n < 2:
            out = f"Delta usable at {n} gap(s): no power law"
        elif n < MIN_GAPS:
            out = f"only {n} gaps (a verdict needs {MIN_GAPS})"
        if self.left_out:
            out += (
                ("; " if out else "")
                + "left out: "
                + ", ".join(
                    f"{p.run} ({p.reason}" + (f"; {p.far}" if p.far else "") + ")"
                    for p in self.left_out
                )
            )
        return out

    def to_dict(self) -> dict[str, Any]:
        s = self.slope
        tests = self.tests()
        best = self.tests(best=True)
        return {
            "key": self.key,
            "cell": self.cell,
            "roughness": self.roughness,
            "runs": [p.run for p in self.points],
            "gaps": self.gaps,
            "Delta": self.Delta,
            "stderr": self.stderr,
            "fills_gap": [p.fills_gap for p in self.points],
            "far_wall": [p.far for p in self.points],
            "slope": None if s is None else s.to_dict(),
            "reason": self.reason,
            "model_slopes": {
                k: None if v is None else v.to_dict() for k, v in self.model_slopes.items()
            },
            "notes": list(self.notes),
            "replicates": self.replicates(),
            "calibration": [
                {
                    "model": c.model,
                    "status": c.status,
                    "message": c.message,
                    **dict(c.calibration),
                    "Delta": {
                        run: {"value": v, "stderr": e} for run, (v, e) in c.predicted.items()
                    },
                    "curve": {"gaps": list(c.curve[0]), "Delta": list(c.curve[1])},
                    "reach": {"gaps": list(c.reach[0]), "Delta": list(c.reach[1])},
                    "why": dict(c.why),
                    "resolved_above": dict(c.resolved_above),
                    "test": None if (t := tests.get(c.model)) is None else t.to_dict(),
                    "best": None if c.best is None else _best_dict(c.best, best.get(c.model)),
                }
                for c in self.curves.values()
            ],
        }


def _best_dict(c: ModelDelta, test: CurveTest | None) -> dict[str, Any]:
    """An alternative's per-series best fit in ``results.json``."""
    return {
        "status": c.status,
        "message": c.message,
        **dict(c.calibration),
        "Delta": {run: {"value": v, "stderr": e} for run, (v, e) in c.predicted.items()},
        "curve": {"gaps": list(c.curve[0]), "Delta": list(c.curve[1])},
        "why": dict(c.why),
        "resolved_above": dict(c.resolved_above),
        "test": None if test is None else test.to_dict(),
    }


def short(key: str) -> str:
    """A series key without its parenthesised wall details."""
    return re.sub(r" \(.*?\)", "", key)


def relevant(series: Sequence[DeltaSeries], which: str) -> list[DeltaSeries]:
    """The series a Delta claim is about: smoother walls (plane or Couette), or fully rough
    walls under gravity or in Couette flow."""
    if which == "smoother":
        return [s for s in series if s.roughness == "smoother" and s.cell != "channel"]
    return [
        s for s in series if s.roughness == "fully-rough" and (s.cell == "couette" or s.gravity)
    ]


def _gaps_needed(s: DeltaSeries, se: float, target: float, other: float) -> str:
    """What slope error would tell the two exponents apart, and the gaps that would give it."""
    want = abs(target - other) / 4.0  # 2 se each side
    pts = [p.gap_d for p in s.points if p.usable]
    g0, g1 = min(pts), max(pts)
    if se <= want or g1 <= g0:
        return ""
    g_max = g0 * (g1 / g0) ** (se / want)
    return (
        f"a slope error below {want:.2g} (now {se:.2g}): gaps up to H/d ~ {g_max:.3g} at the "
        f"same errors of Delta, or errors of Delta {se / want:.2g} times smaller over "
        f"H/d = {g0:g}-{g1:g}"
    )


def slope_sigma(rel_se: float, gaps: Sequence[float], seeds: int = 1) -> float:
    """The standard error of the least-squares slope of ln Delta on ln(H/d) when every run's
    Delta has the relative error ``rel_se`` (the error of ln Delta) and each gap has ``seeds``
    runs: ``rel_se / sqrt(seeds sum_i (x_i - mean x)^2)``, x = ln(H/d) [-]."""
    x = np.log(np.asarray(gaps, dtype=float))
    if rel_se <= 0.0 or seeds < 1 or x.size < 2 or np.ptp(x) == 0.0:
        raise ParameterError(
            f"slope_sigma needs rel_se > 0, seeds >= 1 and two distinct gaps; got {rel_se}, "
            f"{seeds}, {list(gaps)}"
        )
    return float(rel_se / math.sqrt(seeds * float(np.sum((x - x.mean()) ** 2))))


def seeds_needed(rel_se: float, gaps: Sequence[float], sigma: float) -> int:
    """The fewest runs per gap at which :func:`slope_sigma` is at most ``sigma``: the smallest
    whole number at or above ``(rel_se / sigma)^2 / sum_i (x_i - mean x)^2``, x = ln(H/d)
    (referee 13, point 3: at 18% per run, 20/40/80 d and sigma <= 0.0833 it is 5) [-]."""
    x = np.log(np.asarray(gaps, dtype=float))
    if rel_se <= 0.0 or sigma <= 0.0 or x.size < 2 or np.ptp(x) == 0.0:
        raise ParameterError(
            f"seeds_needed needs rel_se > 0, sigma > 0 and two distinct gaps; got {rel_se}, "
            f"{sigma}, {list(gaps)}"
        )
    exact = (rel_se / sigma) ** 2 / float(np.sum((x - x.mean()) ** 2))
    return max(1, math.ceil(exact - 1e-9))


def slope_window(
    curve: tuple[Sequence[float], Sequence[float | None]],
    target: float,
    tol: float = EXPONENT_TOL,
    span: float = 4.0,
) -> dict[str, Any]:
    """Where a Delta curve's own log-log slope over a window of gaps a factor ``span`` wide
    (H/d = g to span g; 4 is the 20/40/80 d designs' span) comes within ``tol`` of ``target``,
    the exponent a claim gives for H/d -> infinity (referee 13, point 3): the slope rule
    (:data:`EXPONENT_TOL`) judges a measured exponent only there.

    The slope is the curve's, interpolated linearly in log-log between its points (from its
    first gap with a value up to the next gap without one: the curve stops there). Returns ``start``
    (the smallest g whose window qualifies [-], exact for the interpolated curve;
    None when no window up to the curve's last gap does), ``end`` (span start), ``last`` (the
    largest gap computed [-]), ``last_slope`` (the slope over the last window, ending at
    ``last``; None when the curve spans less than ``span``) and ``stops`` (the first gap
    without a value, None when the curve has a value at each of its gaps)."""
    if span <= 1.0 or tol <= 0.0:
        raise ParameterError(f"slope_window needs span > 1 and tol > 0; got {span}, {tol}")
    gaps, values = curve
    pts: list[tuple[float, float]] = []
    stops = None
    for g, v in sorted(zip(gaps, values, strict=True)):
        if v is None or not v > 0.0:
            if pts:  # leading gaps without a value (no band yet) are skipped
                stops = float(g)
                break
            continue
        pts.append((float(g), float(v)))
    out: dict[str, Any] = {
        "start": None,
        "end": None,
        "last": pts[-1][0] if pts else None,
        "last_slope": None,
        "stops": stops,
        "span": span,
        "tol": tol,
    }
    if len(pts) < 2 or pts[-1][0] < span * pts[0][0] * (1 - 1e-12):
        return out
    lg = np.log([g for g, _ in pts])
    lv = np.log([v for _, v in pts])
    w = math.log(span)
    top = float(lg[-1]) - w

    def slope(x0: float) -> float:
        return float(np.interp(x0 + w, lg, lv) - np.interp(x0, lg, lv)) / w

    out["last_slope"] = slope(top)
    # between these starts neither end of the window crosses a curve point, so the slope is
    # linear in ln g there: its first entry into the band is found exactly
    knots = sorted(
        {float(x) for x in lg if x <= top} | {float(x) - w for x in lg if x - w >= lg[0]}
    )
    lo, hi = target - tol, target + tol
    for a, b in zip(knots, [*knots[1:], knots[-1]], strict=True):
        sa, sb = slope(a), slope(b)
        if lo <= sa <= hi:
            found = a
        elif b > a and min(sa, sb) <= hi and max(sa, sb) >= lo:
            edge = lo if sa < lo else hi
            found = a + (edge - sa) / (sb - sa) * (b - a)
        else:
            continue
        out["start"] = math.exp(found)
        out["end"] = span * math.exp(found)
        break
    return out


def seed_scatter(s: DeltaSeries) -> dict[str, Any] | None:
    """The run-to-run relative scatter of Delta from the series' same-conditions replicates
    (``s.twins``; referee 12, point 3); None without a pair whose two runs both have a Delta
    and an error.

    Each pair gives the sample variance of ln Delta with one degree of freedom,
    (ln Delta_a - ln Delta_b)^2 / 2; pairs are pooled by the mean of those variances
    (``relative`` = its square root, ``dof`` = pairs). It carries the block errors and the
    scatter between realisations together. ``interval``: its 95% range from the chi^2 law of
    the variance with ``dof`` degrees of freedom (one pair: 0.45x to 32x)."""
    by = {p.run: p for p in s.points}
    rows: list[dict[str, Any]] = []
    for a, b in s.twins:
        pa, pb = by.get(a), by.get(b)
        if pa is None or pb is None or pa.value is None or pb.value is None:
            continue
        if not (pa.value > 0.0 and pb.value > 0.0 and pa.stderr and pb.stderr):
            continue
        z = (pa.value - pb.value) / math.hypot(pa.stderr, pb.stderr)
        rows.append(
            {
                "a": a,
                "b": b,
                "Delta": [pa.value, pb.value],
                "stderr": [pa.stderr, pb.stderr],
                "difference": pa.value - pb.value,
                "z": z,
                "relative": abs(math.log(pa.value / pb.value)) / math.sqrt(2.0),
            }
        )
    if not rows:
        return None
    n = len(rows)
    rel = math.sqrt(sum(r["relative"] ** 2 for r in rows) / n)
    lo = rel * math.sqrt(n / float(chi2_dist.ppf(0.975, n)))
    hi = rel * math.sqrt(n / float(chi2_dist.ppf(0.025, n)))
    return {"pairs": rows, "relative": rel, "dof": n, "interval": [lo, hi]}


def design_gaps(
    designs: Sequence[tuple[Sequence[float], int]], start: float
) -> list[tuple[list[float], int]]:
    """``designs`` (gaps in units of the smallest) at the smallest gap ``start`` [d]."""
    return [([float(start) * float(g) for g in gaps], int(seeds)) for gaps, seeds in designs]


def precision_needed(
    s: DeltaSeries,
    target: float,
    other: float,
    designs: Sequence[tuple[Sequence[float], int]] = PRECISION_DESIGNS,
    seed_designs: Sequence[tuple[Sequence[float], int]] = SEED_DESIGNS,
    window: tuple[float, float] | None = None,
) -> dict[str, Any] | None:
    """The slope error each gap design would give at the series' measured precision of Delta,
    and whether it tells ``target`` from ``other`` (referee 11, point 5); None without a run
    with a Delta and an error.

    The designs (gaps in units of the smallest) are placed at ``window``, the factor-4 window
    where the slope rule can judge the exponent (:func:`slope_window`'s start and end; referee
    14, point 1), or from :data:`DESIGN_START` where there is none (``window_found`` False).
    Three gaps a factor 2 apart give sum (ln H - mean)^2 = 2 ln^2 2 = 0.961 wherever they sit,
    so the slope errors and the seed counts do not depend on the window, only its gaps do.

    The relative error of Delta is the largest of the series' runs' se/Delta (those left out
    for filling their gap included: their errors come from the same redraws); it is the block
    error, which run-to-run scatter may exceed. The slope rule's margin (a slope at ``target``
    within 2 se of it and more than 2 se from ``other``) needs sigma <= |target - other| / 4
    (``sigma_margin``); 2 se between the exponents, sigma <= |target - other| / 2
    (``sigma_two_se``, ``two_se``), is kept in results.json only, not in the text. A design's
    smallest gap clears the fills-its-gap cut when its H/2 exceeds the largest measured Delta
    (bands no thicker than the measured).

    Where the series holds same-conditions replicates (:func:`seed_scatter`), ``seeds`` gives
    the run-to-run scatter and ``seed_designs[]`` the slope error of ``seed_designs`` at the
    larger of it and the block error (the scatter of one pair may fall below the block error
    by chance; the design is not made better than the block errors allow).

    ``seeds_for_margin``: :func:`seeds_needed` at the window's three gaps for the margin, at
    the replicates' level where there are replicates, else at the block error (``exact``: the
    closed form before rounding up; ``runs``: seeds x gaps; ``replicated``: whether the level
    is the replicates'; referee 13, point 3)."""
    rel = [
        p.stderr / p.value
        for p in s.points
        if p.value is not None and p.value > 0.0 and p.stderr is not None and p.stderr > 0.0
    ]
    if not rel:
        return None
    worst = max(rel)
    biggest = max(p.value for p in s.points if p.value is not None)
    two, four = abs(target - other) / 2.0, abs(target - other) / 4.0
    start = DESIGN_START if window is None else float(window[0])
    placed, seed_placed = design_gaps(designs, start), design_gaps(seed_designs, start)

    def rows_at(level: float, which: Sequence[tuple[Sequence[float], int]]) -> list[dict]:
        out = []
        for gaps, seeds in which:
            sigma = slope_sigma(level, gaps, seeds)
            out.append(
                {
                    "gaps": [float(g) for g in gaps],
                    "seeds": int(seeds),
                    "sigma": sigma,
                    "two_se": sigma <= two,  # results.json only: not the rule's criterion
                    "margin": sigma <= four,
                    "clears_cut": FILLS_GAP * min(gaps) > biggest,
                }
            )
        return out

    scatter = seed_scatter(s)
    level = worst if scatter is None else max(scatter["relative"], worst)
    base = seed_placed[0][0] if seed_placed else [start, 2.0 * start, 4.0 * start]
    x = np.log(base)
    n = seeds_needed(level, base, four)
    return {
        "rule": "margin",
        "window": None if window is None else [float(window[0]), float(window[1])],
        "window_found": window is not None,
        "seeds_for_margin": {
            "gaps": base,
            "level": level,
            "replicated": scatter is not None,
            "exact": (level / four) ** 2 / float(np.sum((x - x.mean()) ** 2)),
            "seeds": n,
            "runs": n * len(base),
        },
        "relative_se": worst,
        "relative_se_range": [min(rel), worst],
        "sigma_two_se": two,
        "sigma_margin": four,
        "largest_Delta": biggest,
        "designs": rows_at(worst, placed),
        "seeds": scatter,
        "seed_level": None if scatter is None else max(scatter["relative"], worst),
        "seed_designs": [] if scatter is None else rows_at(level, seed_placed),
    }


def _design_text(row: Mapping[str, Any]) -> str:
    gaps = "/".join(f"{g:.4g}" for g in row["gaps"])
    seeds = "one seed" if row["seeds"] == 1 else f"{row['seeds']} seeds each"
    return f"{gaps} d with {seeds}: sigma = {row['sigma']:.2g}"


def _designs_text(rows: Sequence[Mapping[str, Any]], margin: float) -> str:
    ok = [_design_text(r) for r in rows if r["margin"]]
    short_ = [_design_text(r) for r in rows if not r["margin"]]
    seeds = sorted({int(r["seeds"]) for r in rows})
    span = f"{seeds[0]}" if len(seeds) == 1 else f"{seeds[0]}-{seeds[-1]}"
    return (
        f"sigma <= {margin:.3g} is "
        + (
            "reached by " + "; ".join(ok)
            if ok
            # referee 17, point 7: the seed counts the text calls for are not "listed" designs
            else f"reached by none of the {span}-seed designs listed"
        )
        + ("" if not short_ else "; not by " + "; ".join(short_))
    )


def precision_text(
    s: DeltaSeries,
    target: float,
    other: float,
    window: tuple[float, float] | None = None,
    curve: ModelDelta | None = None,
) -> str:
    """:func:`precision_needed` in words ("" without a measured Delta), at the window where
    the slope rule can judge the exponent: the rule's criterion (the margin), the slope error
    of the designs there, the seeds per gap and runs it needs at the replicates' scatter (or
    at the block error where the walls have no replicates), and whether that window is within
    the gaps the DEM design costs (:data:`DEM_GAP_COSTED`; referee 14, point 1). Where the
    walls have replicates the design at their scatter leads, and the designs at the block error
    follow, labelled as holding only if the block error were the scatter (referee 15, point 1).
    ``curve``: the series' calibrated curve, for the slope over the window and over the largest
    costed factor-4 window where the window ends beyond the costed gaps."""
    need = precision_needed(s, target, other, window=window)
    if need is None:
        return ""
    lo, hi = need["relative_se_range"]
    rows = need["designs"]
    cut = [r for r in rows if not r["clears_cut"]]
    scatter = need["seeds"]
    n = need["seeds_for_margin"]
    gaps = "/".join(f"{g:.4g}" for g in n["gaps"])
    x = np.log(n["gaps"])
    where = (
        f"at the window where the slope rule could judge the exponent ({gaps} d)"
        if need["window_found"]
        else f"at {gaps} d (the curve gives no window where the slope rule could judge the "
        "exponent)"
    )
    text = (
        f"the precision needed in {short(s.key)} {where}: the slope rule supports the exponent "
        f"{target:.3g} when the slope is within 2 se of it and more than 2 se from {other:.3g}, "
        f"so it needs sigma <= |{target:.3g} - {other:.3g}|/4 = {need['sigma_margin']:.3g}. "
        "The slope's error is rel/sqrt(seeds sum (ln H - mean)^2), rel the per-run error of "
        f"Delta, with sum (ln H - mean)^2 = {float(np.sum((x - x.mean()) ** 2)):.3g} for any "
        "three gaps a factor 2 apart"
    )
    block = (
        f"the runs' Delta errors ({100 * lo:.0f}-{100 * hi:.0f}% of Delta; the largest, "
        f"{100 * hi:.0f}%, taken for every run; block errors"
    )
    if scatter is None:
        text += f". At {block}, which a second seed would check): " + _designs_text(
            rows, need["sigma_margin"]
        )
    else:  # the replicates' scatter leads (referee 15, point 1)
        text += (
            _seed_text(need)
            + f". If the block error were the scatter ({block}): "
            + _designs_text(rows, need["sigma_margin"])
        )
    if cut:
        text += (
            "; the smallest gap of "
            + ", ".join("/".join(f"{g:.4g}" for g in r["gaps"]) for r in cut)
            + f" is not above {1 / FILLS_GAP:g} x the largest measured Delta "
            f"({need['largest_Delta']:.3g} d)"
        )
    else:
        text += (
            f"; every design's smallest gap is above {1 / FILLS_GAP:g} x the largest measured "
            f"Delta ({need['largest_Delta']:.3g} d), so bands like the measured would not fill it"
        )
    if scatter is None:
        text += (
            f". No same-conditions replicates of these walls, so no measured seed scatter: at "
            f"the block error, {100 * n['level']:.0f}% per run, the slope rule's sigma <= "
            f"{need['sigma_margin']:.3g} needs {n['seeds']} seeds per gap at {gaps} d "
            f"(({100 * n['level']:.1f}%/{need['sigma_margin']:.3g})^2 / "
            f"{float(np.sum((x - x.mean()) ** 2)):.3g} = {n['exact']:.2g}, rounded up): "
            f"{n['runs']} runs, more if the seed scatter exceeds the block error"
        )
    return text + _reach_of_dem(need, target, curve)


def _reach_of_dem(need: Mapping[str, Any], target: float, curve: ModelDelta | None = None) -> str:
    """Whether the window's gaps are within :data:`DEM_GAP_COSTED` ("" without a window).
    Where the window ends beyond it, with ``curve``: the curve's slope over the window (at the
    rule's edge, the window being the first to qualify), over the largest costed factor-4
    window, and the runs the window's design puts beyond the costed gaps (referee 15,
    point 1)."""
    w = need.get("window")
    if not w:
        return ""
    if w[0] > DEM_GAP_COSTED:
        what = "the H-independence exponent" if target == 0.0 else f"the exponent {target:.3g}"
        return (
            f". That window starts beyond {DEM_GAP_COSTED:g} d, the largest gap the DEM design "
            f"costs (docs/dem.md): {what} cannot be judged by DEM at feasible gaps; only the "
            "finite-H curve can"
        )
    if w[1] > DEM_GAP_COSTED:
        text = (
            f". That window ends beyond {DEM_GAP_COSTED:g} d, the largest gap the DEM design "
            f"costs (docs/dem.md)"
        )
        at = None if curve is None else curve.slope_between(w[0], w[1])
        lo = DEM_GAP_COSTED / 4.0
        costed = None if curve is None else curve.slope_between(lo, DEM_GAP_COSTED)
        if at is not None:
            text += (
                f", and sits at the rule's edge (the first window to qualify: the curve's slope "
                f"over it {at:.3f} against {target:.3g} +- {EXPONENT_TOL:g})"
            )
        if costed is not None and abs(costed - target) > EXPONENT_TOL:
            text += (
                f": the exponent {target:.3g} is not judgeable at costed gaps either; the "
                f"largest costed factor-4 window, {lo:.4g}-{DEM_GAP_COSTED:g} d, has the "
                f"curve's slope {costed:.3f} (|{costed:.3f} - {target:.3g}| = "
                f"{abs(costed - target):.3f} > {EXPONENT_TOL:g}), so no costed design judges "
                "the exponent"
            )
        n = need["seeds_for_margin"]
        beyond = [g for g in n["gaps"] if g > DEM_GAP_COSTED]
        gaps = "/".join(f"{g:.4g}" for g in n["gaps"])
        return text + (
            f"; at the rule's edge, {gaps} d, the margin needs {n['seeds']} seeds per gap "
            f"({n['runs']} runs), {n['seeds'] * len(beyond)} of them at "
            + ("a gap" if len(beyond) == 1 else f"{len(beyond)} gaps")
            + f" beyond {DEM_GAP_COSTED:g} d"
        )
    return ""


def _seed_text(need: Mapping[str, Any]) -> str:
    """:func:`precision_needed`'s design at the replicates' scatter in words ("" without
    replicates): the seeds per gap and the runs the slope rule's margin needs, then the
    designs."""
    scatter = need.get("seeds")
    if not scatter:
        return ""
    pairs = "; ".join(
        f"{r['a']} and {r['b']}: {r['Delta'][0]:.3g} +- {r['stderr'][0]:.2g} against "
        f"{r['Delta'][1]:.3g} +- {r['stderr'][1]:.2g} d, {abs(r['difference']):.3g} d apart "
        f"(z = {r['z']:+.2g})"
        for r in scatter["pairs"]
    )
    rows = need["seed_designs"]
    lo, hi = scatter["interval"]
    level = need["seed_level"]
    n = need["seeds_for_margin"]
    gaps = "/".join(f"{g:.4g}" for g in n["gaps"])
    x = np.log(n["gaps"])
    return (
        f". At the seed scatter: the {100 * need['relative_se']:.0f}% block error is questioned "
        f"by a second seed: the same-conditions replicates (one cell, one wall speed, two seeds; "
        f"{pairs}) give a per-run scatter of Delta of |ln(Delta_a / Delta_b)| / sqrt(2) = "
        f"{100 * scatter['relative']:.0f}% from {scatter['dof']} pair(s) ({scatter['dof']} "
        f"degree(s) of freedom: 95% range {100 * lo:.0f}-{100 * hi:.0f}%, so "
        + ("one pair barely bounds it" if scatter["dof"] == 1 else "a rough estimate")
        + "). At "
        f"{100 * level:.0f}% per run"
        + (
            " (the block error: the replicates' scatter is below it)"
            if level > scatter["relative"]
            else ""
        )
        + f", the slope rule's sigma <= {need['sigma_margin']:.3g} needs {n['seeds']} seeds per "
        f"gap at {gaps} d (({100 * level:.1f}%/{need['sigma_margin']:.3g})^2 / "
        f"{float(np.sum((x - x.mean()) ** 2)):.3g} = {n['exact']:.2g}, rounded up): "
        f"{n['runs']} runs; "
        + _designs_text(rows, need["sigma_margin"])
        + f". The {100 * scatter['relative']:.0f}% rests on {scatter['dof']} pair(s) (95% range "
        f"{100 * lo:.0f}-{100 * hi:.0f}%), so the {n['seeds']} seeds per gap are a floor: a "
        "larger scatter, which the replicates do not exclude, needs more"
    )


def _monotone_text(curve: tuple[Sequence[float], Sequence[float | None]]) -> str:
    """Whether a Delta curve rises at every step of its grid, or where it falls and by how much
    (a fall is the bins' or the solver's, not the model's; referee 14, point 1)."""
    pts = [(g, v) for g, v in zip(*curve, strict=True) if v is not None and v > 0.0]
    falls = [(g0, g1, 1.0 - v1 / v0) for (g0, v0), (g1, v1) in itertools.pairwise(pts) if v1 < v0]
    if len(pts) < 2:
        return ""
    if not falls:
        return f" (rising at each of its {len(pts) - 1} steps)"
    worst = max(falls, key=lambda f: f[2])
    return (
        f" (falling at {len(falls)} of its {len(pts) - 1} steps, by up to "
        f"{100 * worst[2]:.1f}% at H/d = {worst[0]:.4g} -> {worst[1]:.4g})"
    )


def _window_level(c: ModelDelta, w: Mapping[str, Any], target: float) -> str:
    """The curve's Delta over the slope window [d] and in units of the calibration's L ("" for
    a rising claim or without values): where the claim is H-independence, the level the curve
    saturates at, a statement that does not hang on the window's edges (referee 14, point 1)."""
    if target != 0.0:
        return ""
    gaps, values = c.full_curve()
    inside = [
        float(v)
        for g, v in zip(gaps, values, strict=True)
        if v is not None and w["start"] * (1 - 1e-9) <= g <= w["end"] * (1 + 1e-9)
    ]
    if not inside:
        return ""
    par = (c.calibration.get("parameters") or {}).get("L")
    length = par.get("value") if isinstance(par, Mapping) else None
    in_l = (
        f" = {min(inside) / length:.2g}-{max(inside) / length:.2g} L (L = {length:.3g} d, the "
        "calibration's)"
        if isinstance(length, int | float) and length > 0.0
        else ""
    )
    return f"; there the curve saturates at Delta = {min(inside):.3g}-{max(inside):.3g} d{in_l}"


def reach_text(
    s: DeltaSeries, target: float, model: str = "cosserat", other: float | None = None
) -> str:
    """Where ``model``'s one-calibration curve, carried on beyond the figure's
    (``ModelDelta.full_curve``), has a slope within :data:`EXPONENT_TOL` of ``target`` over a
    factor-4 window like 20/40/80 d (:func:`slope_window`), in words: the gaps at which the
    slope rule could judge the exponent, or that they lie beyond the largest gap computed; and
    what DEM at 20/40/80 d tests, with the curve's slope there (referee 13, point 3); whether
    the curve rises at every step; for H-independence the level it saturates at over the
    window; and where the curve's slope at 20-80 d is within :data:`EXPONENT_TOL` of ``other``
    (the other claim's exponent), that a series there with that slope would agree with the
    model (referee 14, point 1). "" without a curve."""
    c = s.curves.get(model)
    if c is None or not c.ok:
        return ""
    w = slope_window(c.full_curve(), target)
    if w["last"] is None:
        return ""
    if w["stops"] is not None:
        reason = c.why.get(f"{w['stops']:.6g}", "")  # fits.curve_key
        stop = f", where it stops: no value at H/d = {w['stops']:.3g}" + (
            f" ({reason.split(':')[0]})" if reason else ""
        )
    else:
        stop = ", with a Delta at every gap"
    head = (
        f"where the slope rule could judge the exponent: the {model} curve's own slope over a "
        f"factor-{w['span']:g} window of gaps (as 20/40/80 d) must be within {w['tol']:g} of "
        f"{target:.3g}; the curve is computed to H/d = {w['last']:.4g}{stop}"
    )
    head += _monotone_text(c.full_curve())
    design = c.slope_between(20.0, 80.0)
    feasible = (
        f"at 20/40/80 d (the curve's slope there {design:.2f}) DEM tests the finite-H curve "
        "(the shape test with a common factor)"
        if design is not None
        else "at the gaps proposed DEM tests the finite-H curve (the shape test with a common "
        "factor)"
    )
    agree = ""
    if design is not None and other is not None and abs(design - other) <= EXPONENT_TOL:
        # referee 14, point 1: at feasible gaps the model's own curve has the other claim's
        # slope, so a series with that slope agrees with the model and refutes nothing
        agree = (
            f"; at 20/40/80 d the curve's slope is within {EXPONENT_TOL:g} of the other "
            f"claim's {other:.3g}, so a DEM series of these walls there with a slope near "
            f"{other:.3g} would agree with the model and would not refute the claim; only the "
            "ratio of the two wall kinds' Delta at equal H separates them there"
        )
    if w["start"] is not None:
        return (
            head + f", and its slope first comes within {w['tol']:g} of {target:.3g} over "
            f"H/d = {w['start']:.4g}-{w['end']:.4g}: gaps from there could judge the exponent"
            + _window_level(c, w, target)
            + (
                f"; {feasible}, not the claimed H/d -> infinity exponent{agree}"
                if w["start"] > 20.0
                else ""
            )
        )
    last = (
        f"; its slope over H/d = {w['last'] / w['span']:.4g}-{w['last']:.4g} is "
        f"{w['last_slope']:.2f}"
        if w["last_slope"] is not None
        else ""
    )
    return (
        head + f"{last}, so that window lies beyond H/d = {w['last']:.4g}, the largest gap "
        f"computed: {feasible}, not the claimed H/d -> infinity exponent {target:.3g}{agree}"
    )


RATIO_GAPS: tuple[float, ...] = (20.0, 40.0, 80.0, 160.0)
"""The gaps [d] at which the two wall kinds' calibrated Delta curves give the ratio DEM can test
at costed gaps (:func:`ratio_test`; referee 15, point 1): 20/40/80 d and the largest costed
factor-4 window, 40/80/160 d."""


def curve_at(c: ModelDelta, gap: float) -> float | None:
    """``c``'s Delta at H/d = ``gap`` [d], interpolated in log-log on its full curve; None
    outside the curve's valued gaps."""
    gaps, values = c.full_curve()
    pts = [(g, v) for g, v in zip(gaps, values, strict=True) if v is not None and v > 0.0]
    if not pts or gap < pts[0][0] * (1 - 1e-9) or gap > pts[-1][0] * (1 + 1e-9):
        return None
    lg = np.log([g for g, _ in pts])
    lv = np.log([v for _, v in pts])
    return float(np.exp(np.interp(math.log(gap), lg, lv)))


def ratio_test(
    rough: ModelDelta,
    smoother: ModelDelta,
    rough_level: float,
    smoother_level: float,
    gaps: Sequence[float] = RATIO_GAPS,
) -> dict[str, Any] | None:
    """The costed test of the finite-H curves (referee 15, point 1): the calibrated ratio
    Delta_rough / Delta_smoother at ``gaps`` [d], its log-log slope over each factor-4 window of
    three of them a factor 2 apart (20/40/80 and 40/80/160 d: for three evenly spaced ln H the
    least-squares slope is the end points' slope), and the seeds per gap per wall kind that tell
    that slope from 0 at 2 se at the combined per-run scatter of ln ratio,
    ``hypot(rough_level, smoother_level)`` (:func:`seeds_needed` with sigma = |slope|/2, the
    closed form of the series' seed counts). None without both curves' values at ``gaps``."""
    vals = [(curve_at(rough, g), curve_at(smoother, g)) for g in gaps]
    if any(a is None or b is None or not b > 0.0 for a, b in vals):
        return None
    ratio = [float(a) / float(b) for a, b in vals]  # type: ignore[arg-type]
    level = math.hypot(rough_level, smoother_level)
    by = dict(zip(gaps, ratio, strict=True))
    windows = []
    for g0 in gaps:
        three = [g0, 2.0 * g0, 4.0 * g0]
        if not all(g in by for g in three):
            continue
        slope = math.log(by[three[2]] / by[g0]) / math.log(4.0)
        x = np.log(three)
        sxx = float(np.sum((x - x.mean()) ** 2))
        sigma = abs(slope) / 2.0
        windows.append(
            {
                "gaps": three,
                "slope": slope,
                "sigma_two_se": sigma,
                "exact": (level / sigma) ** 2 / sxx if sigma > 0.0 else None,
                "seeds": seeds_needed(level, three, sigma) if sigma > 0.0 else None,
            }
        )
    return {
        "gaps": [float(g) for g in gaps],
        "ratio": ratio,
        "level": level,
        "levels": [rough_level, smoother_level],
        "windows": windows,
    }


def ratio_text(t: Mapping[str, Any], model: str = "cosserat") -> str:
    """:func:`ratio_test` in words."""
    gaps = ", ".join(f"{g:g}" for g in t["gaps"])
    ratios = ", ".join(f"{r:.2f}" for r in t["ratio"])
    slopes = " and ".join(
        f"{w['slope']:.2f} over {w['gaps'][0]:g}-{w['gaps'][-1]:g} d" for w in t["windows"]
    )
    sxx = 2.0 * math.log(2.0) ** 2
    seeds = "; ".join(
        f"{w['seeds']} seeds at {'/'.join(f'{g:g}' for g in w['gaps'])} d "
        f"(({100 * t['level']:.1f}%/{w['sigma_two_se']:.3g})^2 / {sxx:.3g} = {w['exact']:.3g}, "
        f"rounded up: {2 * len(w['gaps']) * w['seeds']} runs over both wall kinds)"
        for w in t["windows"]
        if w["seeds"] is not None
    )
    rough, smooth = t["levels"]
    return (
        f"the costed test of the finite-H curves: the calibrated {model} curves give "
        f"Delta_rough / Delta_smoother = {ratios} at H/d = {gaps}; its log-slope is {slopes}; "
        f"at the combined per-run scatter of the ratio, {100 * t['level']:.0f}% "
        f"({100 * rough:.1f}% rough and {100 * smooth:.1f}% smoother, the series' levels "
        "above, in quadrature), telling that slope from 0 at 2 se (sigma <= |slope|/2) needs, "
        f"per gap per wall kind, {seeds}"
    )


def level_miss(s: DeltaSeries, model: str = "cosserat") -> dict[str, Any] | None:
    """Where ``model``'s one-calibration Delta is below (or above) the measured Delta in every
    run of the series that has both (those left out for filling their gap included): the
    ratios model / measured and the runs; None where it is not on one side at every run, or
    fewer than one run has both."""
    c = s.curves.get(model)
    if c is None or not c.ok:
        return None
    pairs = [
        (p.run, float(v) / p.value, p.usable)
        for p in s.points
        if p.value is not None
        and p.value > 0.0
        and (v := c.predicted.get(p.run, (None, None))[0]) is not None
    ]
    if not pairs:
        return None
    ratios = [r for _, r, _ in pairs]
    if all(r < 1.0 for r in ratios):
        side = "below"
    elif all(r > 1.0 for r in ratios):
        side = "above"
    else:
        return None
    return {
        "side": side,
        "ratio_min": min(ratios),
        "ratio_max": max(ratios),
        "runs": {run: r for run, r, _ in pairs},
        "left_out": [run for run, _, ok in pairs if not ok],
    }


def level_text(s: DeltaSeries, model: str = "cosserat") -> str:
    """:func:`level_miss` in words ("" where there is none)."""
    miss = level_miss(s, model)
    if miss is None:
        return ""
    n = len(miss["runs"])
    out = miss["left_out"]
    left = (
        ""
        if not out
        else f" ({out[0]} left out for filling its gap)"
        if len(out) == 1
        else f" ({', '.join(out)} left out for filling their gaps)"
    )
    what = "a level miss of the creep tail" if miss["side"] == "below" else "a level miss"
    return (
        f"the one-calibration {model} Delta is {miss['side']} the measured in "
        + ("the one run" if n == 1 else f"all {n} runs")
        + f" of this series{left}: {model} / measured = "
        + (
            f"{miss['ratio_min']:.2g}"
            if n == 1
            else f"{miss['ratio_min']:.2g}-{miss['ratio_max']:.2g}"
        )
        + f" ({what})"
    )


def _exponent_call(s: DeltaSeries, target: float, other: float) -> tuple[str, str, str]:
    """The slope rule on one series (module docstring): (call, evidence, what would change
    it)."""
    head = f"{s.key}: "
    slope = s.slope
    if slope is None or s.distinct_gaps < MIN_GAPS:
        change = f"Delta at {MIN_GAPS} or more gaps (not filling them) in {short(s.key)}"
        return ("undecided", head + (s.reason or "no slope"), change)
    calls: list[tuple[str, str, str]] = []
    se = slope.stderr
    gaps = sorted({p.gap_d for p in s.points if p.usable})
    text = (
        head
        + f"slope {slope.slope:.3f} +- {_g(se, '.2g')} over H/d = "
        + ", ".join(f"{x:g}" for x in gaps)
    )
    text += "".join(
        f" ({p.run}: Delta = {_g(p.value, '.3g')} +- {_g(p.stderr, '.2g')} d"
        + (f"; {p.far}" if p.far else "")
        + ")"
        for p in s.points
        if p.usable
    )
    text += _power_law_misfit(slope)
    cos = s.model_slopes.get("cosserat")
    if cos is not None:
        text += f"; the Cosserat fits to these runs give {cos.slope:.3f}"
    if s.left_out:
        text += f"; {s.reason}"
    if se is None:
        calls.append(("undecided", text + "; no error on the slope", "replicates"))
    elif abs(slope.slope - target) <= 2 * se and abs(slope.slope - other) > 2 * se:
        calls.append(
            ("supported", text, f"a slope more than 2 se from {target:.3g} at larger gaps")
        )
    elif abs(slope.slope - target) > 2 * se:
        # the claimed exponent is the model's limit H/d -> infinity; data that agree with the
        # model's own slope at these gaps do not refute it, even where that slope is itself
        # within 2 se of the limit (data made by the model were refuted so)
        if cos is not None and abs(slope.slope - cos.slope) <= 2 * se:
            calls.append(
                (
                    "undecided",
                    text + f"; the data agree with the Cosserat model's own slope at these "
                    f"gaps ({cos.slope:.3f}), whose exponent {target:.3g} is a limit H/d -> "
                    "infinity: larger gaps are needed to test the law",
                    "gaps large enough that the model's own slope reaches the limit",
                )
            )
        else:
            calls.append(
                (
                    "refuted",
                    text,
                    f"larger gaps where the slope turns to {target:.3g}, within the errors",
                )
            )
    else:
        calls.append(
            (
                "undecided",
                text + f"; the errors cannot tell {target:.3g} from {other:.3g}",
                _gaps_needed(s, se, target, other) or "smaller errors of Delta",
            )
        )
    return calls[0]


def _exponent_text(s: DeltaSeries) -> str:
    slope = s.slope
    if slope is None:
        return s.reason or "no slope"
    gaps = sorted({p.gap_d for p in s.points if p.usable})
    return (
        f"measured exponent {slope.slope:.3f} +- {_g(slope.stderr, '.2g')} over H/d = "
        + ", ".join(f"{x:.3g}" for x in gaps)
        + _power_law_misfit(slope)
    )


def scope_text(c: ModelDelta) -> str:
    """What one calibration was made on: "one calibration of the material over N runs of
    both wall kinds (kind: n, ...), this series' n among them", or "calibrated on n runs"
    (the series' runs) where it does not say
    (``calibration``'s ``runs`` and ``wall_kinds``, :func:`.fits.calibrate_material`)."""
    runs = c.calibration.get("runs")
    kinds = c.calibration.get("wall_kinds") or {}
    if not runs:
        return f"calibrated on {len(c.predicted)} runs"
    which = (
        "one wall kind"
        if len(kinds) <= 1
        else "both wall kinds"
        if len(kinds) == 2
        else f"{len(kinds)} wall kinds"
    )
    counts = ", ".join(f"{k}: {len(v)}" for k, v in sorted(kinds.items()))
    return (
        f"one calibration of the material over {len(runs)} runs of {which}"
        + (f" ({counts})" if counts else "")
        + f", this series' {len(c.predicted)} among them"
    )


def calibration_text(c: ModelDelta) -> str:
    params = c.calibration.get("parameters", {})
    rows = []
    for name, e in params.items():
        if not e.get("free") and not e.get("derived"):
            continue
        v, se = e.get("value"), e.get("stderr")
        text = f"{name} = {_g(v, '.4g')}" + ("" if se is None else f" +- {se:.2g}")
        at, rng = e.get("at_bound"), e.get("fit_range")
        if se is None and at and rng:  # the bound said with its value, to 3 digits
            text += f" (at the {at} end of its search range {rng[0]:.3g}-{rng[1]:.3g})"
        elif se is None and e.get("reason"):
            text += f" ({e['reason']})"
        rows.append(text)
    chi2, dof, p = (c.calibration.get(k) for k in ("chi2", "dof", "p_value"))
    sig = significance(chi2, dof) if chi2 is not None and dof and dof > 0 else f"p = {_g(p)}"
    fit = f"chi^2 = {_g(chi2, '.4g')} for {dof} dof, {sig}" if chi2 is not None else ""
    # what the stresses fixed (fits.material_fix), or why they did not; a per-series best
    # fit's search range kept off the solver's edge (fits.solver_edges)
    notes = (c.calibration.get("fixed_note", ""), c.calibration.get("edge_note", ""))
    return "; ".join(x for x in (fit, ", ".join(rows), *notes) if x)


def best_text(s: DeltaSeries, model: str) -> str:
    """The alternatives' per-series best fits in words: each one's fit (chi^2, parameters, any
    at a bound with the bound or at the solver's edge), its Delta at the series' usable runs
    and its test against the measured Delta ("" without an alternative)."""
    tests = s.tests(best=True)
    rows = []
    for m, cal in s.curves.items():
        if m == model or not cal.ok:
            continue
        c = cal.best
        if c is None:
            rows.append(f"{m}: none made (its rejection is not counted)")
            continue
        if not c.ok:
            rows.append(f"{m}: failed ({c.message}; its rejection is not counted)")
            continue
        preds = ", ".join(
            f"{p.run} " + _predicted_text("", c, p.run).strip() for p in s.points if p.usable
        )
        t = tests.get(m)
        rows.append(
            f"{m}: {calibration_text(c)}; {wall_T_text(c)}; Delta at the runs: "
            f"{preds or 'none'}; "
            + (
                replace(t, label="against the measured Delta").text()
                if t is not None
                else "no Delta at a usable run: no test"
            )
        )
    if not rows:
        return ""
    return (
        "each alternative at its per-series best fit (this series' runs alone, the velocity u "
        "and the moving wall's measured T = |sigma_yx|/N, every parameter free; the rule "
        "judges its rejection here): " + "; ".join(rows)
    )


def wall_T_text(c: ModelDelta) -> str:
    """A per-series best fit's T at each run's moving wall against the measured T
    (``fits.wall_stress_check``: the summary's ``wall_T`` and ``stress_contradiction``), or
    that the fit did not hold T (a fit made before it did, or runs without a wall ratio)."""
    wall = c.calibration.get("wall_T")
    if not isinstance(wall, Mapping):
        return "T at the moving wall not held to the measured T (fitted on u alone)"
    contradiction = str(c.calibration.get("stress_contradiction") or "")
    rows = [
        f"{run} {e['model']:.3g} against {e['measured']:.3g} +- {e['se']:.2g} ({e['z']:+.1f} se)"
        if isinstance(e, Mapping)
        else f"{run} not held (no measured wall ratio)"
        for run, e in wall.items()
        if f"{run}: T = " not in contradiction  # the contradiction gives its runs' numbers
    ]
    if not contradiction:
        return (
            f"the fit's T at the moving wall against the measured: {', '.join(rows)}: agrees "
            "with the measured stresses"
        )
    return contradiction + (f"; the other runs: {', '.join(rows)}" if rows else "")


def _predicted_text(model: str, c: ModelDelta, run: str) -> str:
    """A model's Delta at a run for the evidence: the value +- its error, said to be below the
    bins' resolution where it is (a band thinner than the first bin, placed by the bins), or
    why there is none."""
    value, se = c.predicted.get(run, (None, None))
    if value is None:
        why = c.why.get(run)
        return f"{model} none" + (f" ({why})" if why else "")
    if not c.resolved(run, value):
        # no error: the calibration's covariance moves such a Delta by how the interpolation
        # between two fixed bins moves (printed as +- 0 or +- 4e-14), not by the band's width
        return f"{model} {value:.3g}" + (
            f" (at or below the second bin, {c.resolved_above[run]:.3g} d: a band thinner than "
            "the bins resolve, its value set by where they fall, so no error is given)"
        )
    return f"{model} {value:.3g}" + ("" if se is None else f" +- {se:.2g}")


def _curve_call(
    s: DeltaSeries, target: float, other: float, model: str
) -> tuple[str, str, str] | None:
    """The curve rule on one series (module docstring), None without ``model``'s curve."""
    tests = s.tests()
    t = tests.get(model)
    if t is None:
        return None
    pts = [
        (p.gap_d, p.value, p.stderr)
        for p in s.points
        if p.usable and p.value is not None and p.stderr is not None
    ]
    rival = power_law_test(other, pts)
    claimed = power_law_test(target, pts)
    others = [tt for m, tt in tests.items() if m != model] + ([rival] if rival else [])
    # an alternative's rejection is judged at its per-series best fit, not at the material's
    # joint calibration (a straw man for one series' Delta: referee 11, point 6)
    best = s.tests(best=True)
    judged = [replace(tt, label=f"{m} (per-series best fit)") for m, tt in best.items()]
    judged += [rival] if rival else []
    rows = []
    for p in s.points:
        if not p.usable:
            continue
        preds = ", ".join(_predicted_text(m, c, p.run) for m, c in s.curves.items() if c.ok)
        rows.append(
            f"{p.run} (H/d = {p.gap_d:.3g}): measured {_g(p.value, '.3g')} +- "
            f"{_g(p.stderr, '.2g')} d" + (f" ({p.far})" if p.far else "") + f"; {preds}"
        )
    calib = "; ".join(
        f"{m}: {scope_text(c)}: {calibration_text(c)}" for m, c in s.curves.items() if c.ok
    )
    failed = "; ".join(f"{m}: {c.message}" for m, c in s.curves.items() if not c.ok)
    alts = [m for m, c in s.curves.items() if m != model and c.ok]
    bests = best_text(s, model)
    text = (
        f"{s.key}: Delta against each model's curve from one calibration of the material "
        f"(this series' wall) ({'; '.join(rows)}); {t.text()}; "
        + "; ".join(tt.text() for tt in others)
        + (
            f" ({', '.join(alts)} as calibrated on the whole material, every field of both "
            "wall kinds: the joint material story, not the alternatives' best description of "
            "this series, so their rejections here do not count for the verdict)"
            if alts
            else ""
        )
        + (f"; {bests}" if bests else "")
        + f". Calibrations: {calib}"
        + (f"; failed: {failed}" if failed else "")
    )
    if t.p < P_SIGNIFICANT:
        text += (
            f"; the level is missed: the data are {t.scale:.3g} times the {model} curve "
            f"({t.sig} as it is), so the calibration predicts at most the dependence on the "
            "gap, not Delta itself"
        )
    if t.p_shape is None:
        return (
            "undecided",
            text + "; one usable gap: no test of the dependence on H/d",
            f"Delta at {MIN_GAPS} or more gaps (not filling them) in {short(s.key)}",
        )
    rejected = [tt.label for tt in judged if tt.p_shape is not None and tt.p_shape < P_SIGNIFICANT]
    consistent = [
        tt.label for tt in judged if tt.p_shape is not None and tt.p_shape >= P_CONSISTENT
    ]
    if (
        t.p_shape < P_SIGNIFICANT
        and claimed is not None
        and claimed.p_shape is not None
        and claimed.p_shape >= P_CONSISTENT
    ):
        return (
            "mixed",
            text + f"; the data follow the claimed limit law itself already at these gaps "
            f"({claimed.text()}), but not the {model} model's finite-H approach to it (its "
            f"curve's shape: {t.sig_shape}, p < {P_SIGNIFICANT:g})",
            f"runs at larger gaps, where the {model} curve nears its limit, or a calibration "
            "whose curve follows the data",
        )
    if t.p_shape < P_SIGNIFICANT:
        return (
            "refuted",
            text + f"; the {model} curve does not follow the measured Delta(H/d) even up to a "
            f"common factor ({t.sig_shape}, p < {P_SIGNIFICANT:g})",
            f"a calibration of the {model} model whose curve follows Delta(H/d), or errors of "
            "Delta that are larger than stated (run-to-run scatter from replicas)",
        )
    if t.p_shape >= P_CONSISTENT and rejected:
        return (
            "supported",
            text
            + f"; the data follow the {model} curve (p = {t.p_shape:.2g}) and reject "
            + ", ".join(rejected)
            + f" (p < {P_SIGNIFICANT:g})",
            f"runs at further gaps where Delta leaves the {model} curve",
        )
    if t.p_shape >= P_CONSISTENT:
        return (
            "undecided",
            text + f"; the data follow the {model} curve (p = {t.p_shape:.2g}) but reject no "
            f"alternative at p < {P_SIGNIFICANT:g} (consistent too: "
            + (", ".join(consistent) or "none")
            + ")",
            f"errors of Delta small enough, or gaps far enough apart, to reject the "
            f"alternatives where they leave the {model} curve (the figure's curves show where)",
        )
    return (
        "undecided",
        text + f"; the {model} curve is in tension with the data (p = {t.p_shape:.2g}, between "
        f"{P_SIGNIFICANT:g} and {P_CONSISTENT:g})",
        "replicas at the same gaps (run-to-run scatter) to tell a misfit from chance",
    )


def _ratio_for(series: Sequence[DeltaSeries], model: str) -> dict[str, Any] | None:
    """:func:`ratio_test` for the first rough and the first smoother series with a calibrated
    ``model`` curve each, at their seed-count levels (:func:`precision_needed`); None unless
    both exist."""
    got: list[tuple[ModelDelta, float]] = []
    for which in ("rough", "smoother"):
        target = PAPER_SLOPES["smoother walls" if which == "smoother" else "fully rough walls"]
        other = PAPER_SLOPES["fully rough walls" if which == "smoother" else "smoother walls"]
        for s in relevant(series, which):
            c = s.curves.get(model)
            need = precision_needed(s, target, other)
            if c is not None and c.ok and need is not None:
                got.append((c, float(need["seeds_for_margin"]["level"])))
                break
    if len(got) < 2:
        return None
    return ratio_test(got[0][0], got[1][0], got[0][1], got[1][1])


def delta_law_verdict(
    series: Sequence[DeltaSeries], which: str, model: str = "cosserat"
) -> Verdict:
    """Claim ``which`` = "smoother" (exponent 0) or "rough" (exponent 1/3) against the gap
    series (module docstring): the measured Delta(H/d) against ``model``'s finite-H curve from
    one joint calibration of each series' material (and the other models' curves, and the
    other claim's power law, as alternatives), the measured exponent judged only where
    ``model``'s own curve has reached the claimed limit over the series' gaps (within
    :data:`EXPONENT_TOL`)."""
    if which not in ("smoother", "rough"):
        raise ParameterError(f"which must be 'smoother' or 'rough'; got {which!r}")
    target = PAPER_SLOPES["smoother walls" if which == "smoother" else "fully rough walls"]
    other = PAPER_SLOPES["fully rough walls" if which == "smoother" else "smoother walls"]
    want = f"exponent {target:.3g} claimed for H/d -> infinity"
    kind = "smoother than the material" if which == "smoother" else "fully rough"
    rel = relevant(series, which)
    method = (
        f"Method: one joint calibration per model of every run of the material on this cell, "
        f"every wall kind (one set of material parameters, wall parameters shared per wall "
        f"kind, what the metadata give fixed); each series reads it with its own wall: each "
        f"model's Delta at each run's gap, bins and rate (I_w), with its error from the "
        f"calibration's "
        f"covariance (scaled by sqrt(chi^2/dof) where the calibration misfits); chi^2 of the "
        f"measured Delta against it (errors in quadrature; dof = points, nothing is fitted to "
        f"Delta) and times its best common factor (dof = points - 1: the dependence on H/d "
        f"apart from the level, which is what the claim is about). Supported when the {model} "
        f"curve's shape is consistent (p >= {P_CONSISTENT:g}) and an alternative (another "
        f"model's curve at its per-series best fit: the series' runs alone, the velocity and the "
        f"moving wall's measured T (the model's own T at the wall held to it: a fit on u alone "
        f"put T wherever the velocity does not see it), every parameter free, NGF's b kept off "
        f"the solver's double-precision edge; or "
        f"Delta ~ (H/d)^{other:.3g} with a free level) is rejected (p < "
        f"{P_SIGNIFICANT:g}); the alternatives' material-level curves are tested too, but a "
        "calibration made for every field of both wall kinds can be a straw man for one "
        "series' Delta, so their rejections do not count; "
        f"refuted when the {model} curve's shape is rejected (p < {P_SIGNIFICANT:g}), mixed "
        f"when it is but the claimed law Delta ~ (H/d)^{target:.3g} with a free level is not "
        f"(p >= {P_CONSISTENT:g}: the law without the model's approach to it). The "
        f"exponent (weighted least squares of ln Delta on ln(H/d), error scaled by "
        f"sqrt(reduced chi^2) when above 1, at least {MIN_GAPS} gaps) is judged only where "
        f"the {model} curve's own slope over the series' gaps is within {EXPONENT_TOL:g} of "
        f"the limit {target:.3g}: supported within 2 se when {other:.3g} is outside 2 se. "
        "Runs whose band fills its gap are left out. Delta is measured relative to the fixed "
        "wall's velocity 0, as the models' is; where that wall slips (its nearest bin moves by "
        f"more than {FAR_SLIP_SIGMAS:g} se), Delta relative to the far bin's velocity is given "
        "beside it, with whether the fills-its-gap call would change, but not used: a one-bin "
        "test at 2 se passes a still wall in about 5% of runs by chance and then moves Delta "
        "by as much as that noise."
    )
    if not rel:
        return Verdict(
            which,
            "undecided",
            f"The data cannot decide: no series of runs with walls {kind}"
            + (" under gravity or in Couette flow" if which == "rough" else "")
            + " (the sidecars' wall.kind says which: smooth-frictional or glued-grains).",
            f"runs with walls {kind} at {MIN_GAPS} or more gaps.",
        )
    calls: list[tuple[str, str, str]] = []
    runs: list[str] = []
    numbers: dict[str, Any] = {}
    precision: list[tuple[int, str]] = []
    for s in rel:
        runs += [p.run for p in s.points]
        numbers[s.key] = s.to_dict()
        numbers[s.key]["level_miss"] = level_miss(s, model)
        level = level_text(s, model)
        notes = "".join(f"; note: {n}" for n in (*s.notes, *s.replicates()))
        notes = (f"; {level}" if level else "") + notes
        sw = (
            slope_window(s.curves[model].full_curve(), target)
            if model in s.curves and s.curves[model].ok
            else None
        )
        numbers[s.key]["slope_window"] = sw
        window = (sw["start"], sw["end"]) if sw is not None and sw["start"] is not None else None
        numbers[s.key]["precision_needed"] = precision_needed(s, target, other, window=window)
        reach = reach_text(s, target, model, other)
        need = precision_text(
            s, target, other, window, s.curves.get(model) if model in s.curves else None
        )
        precision.append((len(calls), "; ".join(t for t in (reach, need) if t)))
        curve = _curve_call(s, target, other, model)
        cos = s.curves.get(model)
        usable = sorted({p.gap_d for p in s.points if p.usable})
        own = (
            cos.slope_between(usable[0], usable[-1])
            if cos is not None and cos.ok and len(usable) >= 2
            else None
        )
        if curve is None:  # no calibrated curve: the exponent alone, as before
            call, text, change = _exponent_call(s, target, other)
            text += f"; no {model} curve from a joint calibration"
            calls.append((call, text + notes, change))
            continue
        call, text, change = curve
        if own is not None and abs(own - target) <= EXPONENT_TOL:
            e_call, e_text, e_change = _exponent_call(s, target, other)
            calls.append((call, text + notes, change))
            calls.append(
                (
                    e_call,
                    f"{e_text}; judged, since the {model} curve's own slope over H/d = "
                    f"{usable[0]:.3g}-{usable[-1]:.3g} is {own:.3f}, within {EXPONENT_TOL:g} of "
                    f"the limit {target:.3g}",
                    e_change,
                )
            )
            continue
        why = (
            f"the {model} curve's own slope over H/d = {usable[0]:.3g}-{usable[-1]:.3g} is "
            f"{own:.3f}, not yet its limit {target:.3g} (within {EXPONENT_TOL:g})"
            if own is not None
            else "the gaps do not span a range"
        )
        calls.append(
            (
                call,
                text + f"; {_exponent_text(s)}: reported, not judged ({why}), so the gaps do "
                "not reach the regime of the claimed exponent" + notes,
                change,
            )
        )

    # after the series (the first key stays a series): the claim's exponent, the largest
    # costed gap and the curve's model, which the summary (.summaries) reads
    numbers.update(claimed_exponent=target, costed_gap_d=DEM_GAP_COSTED, curve_model=model)
    ratio = _ratio_for(series, model)  # both wall kinds' curves (referee 15, point 1)
    if ratio is not None:
        numbers["ratio_test"] = ratio
        precision = [(i, f"{t}; {ratio_text(ratio, model)}" if t else t) for i, t in precision]
    for i, need in precision:  # the precision needed, with the series' first call's change
        if need and i < len(calls):
            c, t, ch = calls[i]
            calls[i] = (c, t, f"{ch}; {need}" if ch else need)
    decided = {c for c, _, _ in calls if c != "undecided"}
    detail = "; ".join(t for _, t, _ in calls)
    change = "; ".join(f"{c}" for _, _, c in calls if c)
    runs_t = tuple(runs)
    if not decided:
        return Verdict(
            which,
            "undecided",
            f"The data cannot decide ({want}): {detail}. {method}",
            change + ".",
            runs_t,
            numbers,
        )
    if len(decided) > 1 or decided == {"mixed"}:
        how = "the wall series disagree" if len(decided) > 1 else "the claimed law and the model"
        return Verdict(
            which,
            "mixed",
            f"Mixed: {how} ({want}): {detail}. {method}",
            change + ".",
            runs_t,
            numbers,
        )
    verdict = decided.pop()
    word = "Supported" if verdict == "supported" else "Refuted"
    return Verdict(
        which,
        verdict,
        f"{word}: the measured Delta against H/d ({want}): {detail}. {method}",
        change + ".",
        runs_t,
        numbers,
    )


def within_regime(v: Verdict, inertial_numbers: Sequence[float | None], bound: float) -> Verdict:
    """``v``, unless it judges a slow-flow claim (:data:`SLOW_FLOW_CLAIMS`) as "supported",
    "refuted" or "mixed" on runs that are all outside the slow-flow regime: then "undecided",
    with what the data say at their rates kept in the evidence and in ``numbers``
    (``at_these_rates``). A prediction for I -> 0 is not tested by runs at I above ``bound``
    (the local inertial number next to the moving wall); runs that do not give their inertial
    number leave the verdict as it is (the evidence says the regime is not shown)."""
    known = [i for i in inertial_numbers if i is not None]
    if (
        v.key not in SLOW_FLOW_CLAIMS
        or v.verdict == "undecided"
        or not known
        or len(known) < len(inertial_numbers)
        or min(known) <= bound
    ):
        return v
    return replace(
        v,
        verdict="undecided",
        evidence=(
            f"Not tested in the model's regime: every run used has I = {min(known):.2g}-"
            f"{max(known):.2g} next to the moving wall, above the slow-flow bound I <= "
            f"{bound:g}. At these rates the data would say {v.verdict}: {v.evidence}"
        ),
        would_change=(
            f"runs with I <= {bound:g} next to the moving wall; then, as at these rates: "
            f"{v.would_change}"
        ),
        numbers={**dict(v.numbers), "at_these_rates": v.verdict},
        qualifier="",
    )


def _power_law_misfit(slope: SlopeFit) -> str:
    """A clause saying that one power law does not describe the points (its chi^2 improbable
    at p < :data:`P_SIGNIFICANT`), so the scaled-up slope error hides a misfit; empty
    otherwise."""
    if slope.reduced_chi2 is None or slope.n <= 2:
        return ""
    dof = slope.n - 2
    c = slope.reduced_chi2 * dof
    p = float(chi2_dist.sf(c, dof))
    if p >= P_SIGNIFICANT:
        return ""
    return (
        f"; one power law does not describe these points (chi^2 = {c:.3g} for {dof} degrees "
        f"of freedom, {significance(c, dof)}: replicates or neighbouring gaps disagree beyond "
        "their errors), "
        "so the slope's error is scaled up by sqrt(reduced chi^2) and a verdict on the "
        "exponent rests on that"
    )
