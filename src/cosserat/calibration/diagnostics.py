"""Misfit diagnostics of a calibration: every one a function of residuals and a Jacobian.

* :func:`chi2_p_value`: the probability of a chi^2 at least this large if the model and the
  error model were right;
* :func:`runs_test`: Wald-Wolfowitz runs test on the signs of the whitened residuals of one
  field of one run (too few sign changes: the model misses a trend);
* :func:`misfit_regions`: stretches of neighbouring bins the model misses on the same side,
  named by where they lie (at the moving wall, in the band, in the creep tail);
* :func:`flat_directions` and :func:`strong_correlations`: the one identifiability rule of the
  package (:data:`UNIDENTIFIED_FRACTION`).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from scipy import stats

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
    """log10 P(X >= chi2) for X ~ chi^2(dof), finite where the p-value itself underflows."""
    if dof <= 0:
        return 0.0
    ln_p = float(stats.chi2.logsf(chi2, dof))
    if not math.isfinite(ln_p):  # far in the tail: the leading term of Q(k/2, x/2)
        a, x = 0.5 * dof, 0.5 * chi2
        ln_p = -x + (a - 1.0) * math.log(x) - math.lgamma(a)
    return ln_p / math.log(10.0)


def p_text(log10_p: float) -> str:
    """``p = 0.0012`` or, below the range of doubles' comfort, ``p = 10^-123``."""
    if log10_p > -4.0:
        return f"p = {10.0**log10_p:.2g}"
    return f"p = 10^{log10_p:.0f}"


def tail_decades(s: FloatArray, data: FloatArray, se: FloatArray, model: FloatArray) -> str | None:
    """Where a velocity profile's creep tail (measured u below :data:`TAIL_U`, yet more than
    2 se above 0) lies a decade or more above the model, say by how many decades."""
    s, data, se, model = (np.asarray(x, dtype=float) for x in (s, data, se, model))
    tail = (data < TAIL_U) & (data > 2.0 * se)
    if np.count_nonzero(tail) < REGION_BINS:
        return None
    at_rest = model[tail] <= 0.0
    if np.count_nonzero(at_rest) >= REGION_BINS:
        return (
            f"in the creep tail (s = {s[tail][at_rest].min():.3g}-{s[tail][at_rest].max():.3g} "
            f"d, {np.count_nonzero(at_rest)} bins) the model is at rest (a rigid plug) where "
            f"the data creep at u = {data[tail][at_rest].min():.2g}-"
            f"{data[tail][at_rest].max():.2g}"
        )
    ratio = np.log10(np.maximum(model[tail], 1e-300) / data[tail])
    if np.median(ratio) > -1.0:
        return None
    lo, hi = np.percentile(-ratio, [10, 90])
    return (
        f"in the creep tail (s = {s[tail].min():.3g}-{s[tail].max():.3g} d, "
        f"{np.count_nonzero(tail)} bins where u is measured above 2 se) the model lies "
        f"{max(lo, 0):.1f}-{hi:.1f} decades below the data"
    )


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
            f"{self.where} (s = {self.start:.3g}-{self.stop:.3g} d, {self.bins} bins), the model "
            f"{side} the data by up to {self.worst:.1f} se"
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
            if s[i] < 2.0:
                where = "at the moving wall"
            elif u_measured is not None and np.all(np.asarray(u_measured)[i : j + 1] < TAIL_U):
                where = "in the creep tail"
            else:
                where = "in the shear band"
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
    "misfit_regions",
    "p_text",
    "runs_test",
    "strong_correlations",
    "tail_decades",
]
