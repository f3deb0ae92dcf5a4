"""Misfit diagnostics of a calibration: every one a function of residuals and a Jacobian.

* :func:`chi2_p_value`: the probability of a chi^2 at least this large if the model and the
  error model were right;
* :func:`runs_test`: Wald-Wolfowitz runs test on the signs of the whitened residuals of one
  field of one run (too few sign changes: the model misses a trend);
* :func:`misfit_regions`: stretches of neighbouring bins the model misses on the same side,
  named by where they lie (at the moving wall, in the band, in the creep tail);
* :func:`flat_directions`, :func:`identified_covariance` and :func:`strong_correlations`: the
  one identifiability rule of the package (:data:`UNIDENTIFIED_FRACTION`).
"""

from __future__ import annotations

import functools
import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from scipy import stats

from .._text import chi2_ln_p, p_or_z
from ..model.constitutive import FloatArray

MISFIT_P = 1e-3
"""A chi^2 (or runs test) p-value below this is a misfit, and said in the warnings."""
OVERSTATED_P = 1e-3
"""A chi^2 this improbably SMALL says the errors are overstated (or the bins correlated more
than the error model says): the information criteria are then not calibrated."""
UNIDENTIFIED_FRACTION = 0.5
"""A combination of parameters whose 1-sigma uncertainty exceeds this fraction of its search
range (each parameter measured in units of its fit range) is not identified by the data."""
CORRELATION_LIMIT = 0.95
"""|r| above which two fitted parameters are reported as strongly correlated."""
REGION_Z = 2.0
"""|residual| / se above which a bin counts towards a misfit region."""
REGION_BINS = 3
"""Fewest neighbouring bins, missed on the same side, that make a misfit region."""
TAIL_U = 0.05
"""Measured u below this (the definition of Delta's edge, ``eqn-delta_defn``) is the creep tail."""


def chi2_p_value(chi2: float, dof: int) -> float | None:
    """P(X >= chi2) for X ~ chi^2(dof); None without degrees of freedom."""
    if dof <= 0:
        return None
    return float(stats.chi2.sf(chi2, dof))


def chi2_log10_p(chi2: float, dof: int) -> float:
    """log10 P(X >= chi2) for X ~ chi^2(dof), finite where the p-value itself underflows
    (``cosserat._text.chi2_ln_p``); 0 without degrees of freedom."""
    if dof <= 0:
        return 0.0
    return chi2_ln_p(chi2, dof) / math.log(10.0)


def p_text(log10_p: float) -> str:
    """``p = 0.0012`` or, below ``cosserat._text.SIGNIFICANCE_P``, ``z = 7.3``
    (``cosserat._text.p_or_z``; never ``p = 10^-123``)."""
    return p_or_z(log10_p * math.log(10.0))


def tail_decades(s: FloatArray, data: FloatArray, se: FloatArray, model: FloatArray) -> str | None:
    """Where a velocity profile's creep tail (measured u below :data:`TAIL_U`, yet more than
    2 se above 0) lies a decade or more above the model, say where and by how many decades
    (the smallest and largest over those bins), or that the model is at rest there."""
    s, data, se, model = (np.asarray(x, dtype=float) for x in (s, data, se, model))
    tail = (data < TAIL_U) & (data > 2.0 * se)
    if np.count_nonzero(tail) < REGION_BINS:
        return None
    st, dt, mt = s[tail], data[tail], model[tail]
    at_rest = mt <= 0.0
    if np.count_nonzero(at_rest) >= REGION_BINS:
        return (
            f"in the creep tail (s = {_span(st[at_rest])} d, {np.count_nonzero(at_rest)} bins) "
            f"the model predicts no flow (a rigid plug) where the data creep at u = "
            f"{_span(dt[at_rest], '.2g')}"
        )
    below = ~at_rest & (mt < 0.1 * dt)
    if np.count_nonzero(below) < REGION_BINS:
        return None
    decades = np.log10(dt[below] / mt[below])
    return (
        f"in the creep tail (s = {_span(st[below])} d, {np.count_nonzero(below)} bins where u is "
        f"measured above 2 se) the model lies {decades.min():.1f}-{decades.max():.1f} decades "
        "below the data"
    )


def _span(x: FloatArray, fmt: str = ".3g") -> str:
    """``a-b`` of an array's smallest and largest values, or ``a`` if they are equal."""
    lo, hi = float(np.min(x)), float(np.max(x))
    return f"{lo:{fmt}}" if f"{lo:{fmt}}" == f"{hi:{fmt}}" else f"{lo:{fmt}}-{hi:{fmt}}"


@functools.lru_cache(maxsize=4096)
def stretch_p_value(n: int, rho: float, length: int, sims: int = 4000, seed: int = 0) -> float:
    """P(the longest stretch of same-sign residuals among ``n`` bins is at least ``length``)
    when the residuals are AR(1) noise with lag-1 correlation ``rho`` (Monte Carlo, ``sims``
    draws, seeded: the same answer every time, so each answer is kept: a calibration asks
    again at every fit of the same data, ~30 ms a time)."""
    if length <= 1 or n < length:
        return 1.0 if length <= 1 else 0.0
    rng = np.random.default_rng(seed)
    e = rng.standard_normal((sims, n))
    x = np.empty_like(e)
    x[:, 0] = e[:, 0]
    c = math.sqrt(1.0 - rho * rho)
    for i in range(1, n):
        x[:, i] = rho * x[:, i - 1] + c * e[:, i]
    sign = x > 0.0
    run = np.ones(sims, dtype=int)
    longest = np.ones(sims, dtype=int)
    for i in range(1, n):
        run = np.where(sign[:, i] == sign[:, i - 1], run + 1, 1)
        longest = np.maximum(longest, run)
    return float((np.count_nonzero(longest >= length) + 1) / (sims + 1))


def longest_stretch(s: FloatArray, z: FloatArray) -> tuple[int, float, float, int]:
    """The longest stretch of neighbouring bins whose (not whitened) residuals ``z`` share a
    sign: (bins, first s, last s, sign)."""
    z = np.asarray(z, dtype=float)
    best = (0, 0.0, 0.0, 0)
    i = 0
    while i < z.size:
        j = i
        while j + 1 < z.size and np.sign(z[j + 1]) == np.sign(z[i]) != 0:
            j += 1
        if j - i + 1 > best[0] and z[i] != 0:
            best = (j - i + 1, float(s[i]), float(s[j]), int(np.sign(z[i])))
        i = j + 1
    return best


def chi2_p_low(chi2: float, dof: int) -> float | None:
    """P(X <= chi2) for X ~ chi^2(dof): small when the errors are overstated."""
    if dof <= 0:
        return None
    return float(stats.chi2.cdf(chi2, dof))


@dataclass(frozen=True)
class RunsTest:
    """Wald-Wolfowitz runs test on residual signs.

    Attributes
    ----------
    runs, expected : float
        Observed and expected number of runs of equal signs.
    p_value : float or None
        P(this few runs or fewer) under independent signs (normal approximation with continuity
        correction); None with fewer than 2 of either sign.
    """

    runs: int
    expected: float
    p_value: float | None


def runs_test(residuals: FloatArray) -> RunsTest:
    """The one-sided runs test of ``residuals`` (in bin order; zeros are dropped)."""
    r = np.asarray(residuals, dtype=float)
    signs = np.sign(r[r != 0.0])
    n_pos, n_neg = int(np.sum(signs > 0)), int(np.sum(signs < 0))
    n = n_pos + n_neg
    runs = 1 + int(np.sum(signs[1:] != signs[:-1])) if n else 0
    if n_pos < 2 or n_neg < 2:
        return RunsTest(runs, float("nan") if n == 0 else float(runs), None)
    mu = 2.0 * n_pos * n_neg / n + 1.0
    var = (mu - 1.0) * (mu - 2.0) / (n - 1.0)
    z = (runs - mu + 0.5) / math.sqrt(var)
    return RunsTest(runs, mu, float(stats.norm.cdf(z)))


@dataclass(frozen=True)
class Region:
    """Neighbouring bins a model misses on one side.

    Attributes
    ----------
    start, stop : float
        Distance from the moving wall of the first and the last bin [d].
    bins : int
    sign : int
        +1: the model is above the data; -1: below.
    worst : float
        The largest |residual| / se in the region [-].
    where : str
        "at the moving wall", "in the shear band" or "in the creep tail".
    """

    start: float
    stop: float
    bins: int
    sign: int
    worst: float
    where: str

    def describe(self) -> str:
        side = "above" if self.sign > 0 else "below"
        return (
            f"{self.where} (s = {_span(np.array([self.start, self.stop]))} d, {self.bins} bins), "
            "the model "
            f"{side} the data by up to {self.worst:.1f} se"
        )


def _where(start: float, stop: float, u: FloatArray | None) -> str:
    """Name a stretch of bins by where it lies: at the moving wall (within 2 d), in the shear
    band (measured u at least TAIL_U), in the creep tail (below), or across them."""
    parts = []
    if start < 2.0:
        parts.append("the moving wall")
    if u is None or np.any(u >= TAIL_U):
        parts.append("the shear band")
    if u is not None and np.any(u < TAIL_U):
        parts.append("the creep tail")
    if start < 2.0 and stop < 4.0:
        return "at the moving wall"
    if len(parts) == 1:
        return "in " + parts[0]
    return (
        "from " + " into ".join(parts[:1]) + " into " + parts[-1]
        if len(parts) == 2
        else ("from the moving wall through the shear band into the creep tail")
    )


def misfit_regions(
    s: FloatArray, z: FloatArray, u_measured: FloatArray | None = None
) -> list[Region]:
    """Stretches of at least :data:`REGION_BINS` bins with ``|z| > REGION_Z`` of one sign.

    Parameters
    ----------
    s : ndarray
        Distance of the bins from the moving wall [d], increasing.
    z : ndarray
        (model - data) / se of each bin [-].
    u_measured : ndarray, optional
        The measured u at the same bins, to name a region in the creep tail (u < ``TAIL_U``).
    """
    s, z = np.asarray(s, dtype=float), np.asarray(z, dtype=float)
    flag = np.where(np.abs(z) > REGION_Z, np.sign(z), 0.0)
    out: list[Region] = []
    i = 0
    while i < z.size:
        if flag[i] == 0.0:
            i += 1
            continue
        j = i
        while j + 1 < z.size and flag[j + 1] == flag[i]:
            j += 1
        if j - i + 1 >= REGION_BINS:
            u = None if u_measured is None else np.asarray(u_measured)[i : j + 1]
            where = _where(float(s[i]), float(s[j]), u)
            out.append(
                Region(
                    float(s[i]),
                    float(s[j]),
                    j - i + 1,
                    int(flag[i]),
                    float(np.max(np.abs(z[i : j + 1]))),
                    where,
                )
            )
        i = j + 1
    return out


@dataclass(frozen=True)
class FlatDirection:
    """A combination of parameters the data do not determine.

    Attributes
    ----------
    components : dict of str to float
        Parameter name -> component of the unit direction (parameters in units of their fit
        range), only those with |component| >= 0.1.
    sigma : float
        1-sigma uncertainty along it, as a fraction of the fit ranges [-].
    """

    components: dict[str, float]
    sigma: float

    def describe(self) -> str:
        terms = " ".join(f"{c:+.2f} {n}" for n, c in self.components.items())
        return f"{terms} (1-sigma {self.sigma:.2g} of the search range)"


def flat_directions(
    jacobian: FloatArray, names: Sequence[str], widths: FloatArray
) -> list[FlatDirection]:
    """The package's identifiability rule: the SVD of the whitened Jacobian with every
    parameter in units of its fit range (``widths``); a singular direction whose 1-sigma
    uncertainty ``1/s`` exceeds :data:`UNIDENTIFIED_FRACTION` is not identified.
    """
    J = np.asarray(jacobian, dtype=float) * np.asarray(widths, dtype=float)[None, :]
    if J.size == 0:
        return []
    _, sv, vt = np.linalg.svd(J, full_matrices=False)
    out = []
    for s, v in zip(sv, vt, strict=True):
        sigma = math.inf if s <= 0.0 else 1.0 / s
        if sigma > UNIDENTIFIED_FRACTION:
            v = v * (1.0 if v[np.argmax(np.abs(v))] > 0 else -1.0)
            comps = {n: float(c) for n, c in zip(names, v, strict=True) if abs(c) >= 0.1}
            out.append(FlatDirection(comps, sigma))
    return out


def identified_covariance(jacobian: FloatArray, widths: FloatArray) -> FloatArray:
    """The covariance of the fit's coordinates from the whitened Jacobian, with the directions
    :func:`flat_directions` names left out (a pseudo-inverse on the identified subspace): the
    errors of the identified parameters hold the unidentified combinations at their best-fit
    values instead of carrying their arbitrary size. Parameters of a flat direction get no
    error anyway."""
    w = np.asarray(widths, dtype=float)
    J = np.asarray(jacobian, dtype=float) * w[None, :]
    if J.size == 0:
        return np.zeros((w.size, w.size))
    _, sv, vt = np.linalg.svd(J, full_matrices=False)
    with np.errstate(divide="ignore"):
        sigma = np.where(sv > 0.0, 1.0 / np.where(sv > 0.0, sv, 1.0), np.inf)
    keep = sigma <= UNIDENTIFIED_FRACTION
    v = vt[keep]
    cov_scaled = (v.T * (sigma[keep] ** 2)) @ v
    return cov_scaled * np.outer(w, w)


def strong_correlations(
    covariance: FloatArray, names: Sequence[str]
) -> list[tuple[str, str, float]]:
    """Pairs of parameters with |r| > :data:`CORRELATION_LIMIT`."""
    c = np.asarray(covariance, dtype=float)
    d = np.sqrt(np.clip(np.diag(c), 0.0, None))
    out = []
    for i in range(len(names)):
        for j in range(i + 1, len(names)):
            if d[i] > 0 and d[j] > 0:
                r = c[i, j] / (d[i] * d[j])
                if abs(r) > CORRELATION_LIMIT:
                    out.append((names[i], names[j], float(r)))
    return out


__all__ = [
    "CORRELATION_LIMIT",
    "MISFIT_P",
    "OVERSTATED_P",
    "REGION_BINS",
    "REGION_Z",
    "TAIL_U",
    "UNIDENTIFIED_FRACTION",
    "FlatDirection",
    "Region",
    "RunsTest",
    "chi2_log10_p",
    "chi2_p_low",
    "chi2_p_value",
    "flat_directions",
    "identified_covariance",
    "longest_stretch",
    "misfit_regions",
    "p_text",
    "runs_test",
    "stretch_p_value",
    "strong_correlations",
    "tail_decades",
]
