"""The error model of a measured profile: correlated bins (``docs/calibration.md``).

A profile's bins are not independent. In a DEM run the time blocks that give each bin its
standard error are the same blocks for every bin, and a force chain or a layer that slips for a
while moves several neighbouring bins together; in an experiment the imaging window does the
same. Treating bins as independent overweights a field by the number of bins a fluctuation
spans, and makes chi^2, its p-value, the information criteria and the posterior overconfident.

The model used here: within one field of one run, the errors are Gaussian with standard errors
``se_i`` (as measured) and an AR(1) correlation between bins, ``corr(e_i, e_j) = rho^|i-j|``
for bins ordered across the gap; different fields and different runs are independent (a block
diagonal covariance). Its precision matrix is tridiagonal, so the whitened residual is

    w_1 = z_1,    w_i = (z_i - rho z_{i-1}) / sqrt(1 - rho^2),    z_i = r_i / se_i,

and ``-2 ln L = sum w_i^2 + sum 2 ln se_i + (n - 1) ln(1 - rho^2) + n ln 2 pi``.

Where ``rho`` comes from, in order:

1. the run's metadata, ``bin_correlation: {field: rho}`` (measured from the run's own time
   blocks by ``cosserat.dem``, or stated by the user);
2. otherwise estimated from the data themselves, without any model: for three neighbouring bins
   of a smooth profile the second difference ``y_{i-1} - 2 y_i + y_{i+1}`` is nearly pure noise,
   whose variance under AR(1) is ``se^2 (6 - 8 rho + 2 rho^2)`` (equal ``se``; the general form
   is used), so each squared second difference over that variance is chi^2 with one degree of
   freedom. ``rho`` is the value that puts the median of these ratios at the median of chi^2_1
   (0.4549): a median, so the few triples where the profile bends sharply (a shear band's
   edges, which would push rho down) do not decide it. It is clipped to ``[0, RHO_MAX]``.
   It is the same for every model, so likelihoods of different models stay comparable;
3. a field with fewer than :data:`MIN_BINS_FOR_RHO` usable bins takes ``rho = 0``.

The estimate is checked on synthetic profiles with known rho in ``tests/calibration``.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from ..model.constitutive import FloatArray

RHO_MAX = 0.95
"""Largest lag-1 correlation used [-]: beyond it the whitening divides by sqrt(1 - rho^2) < 0.31
and a single bin pair dominates the fit."""
CHI2_1_MEDIAN = 0.454936423119572
"""Median of a chi^2 variable with one degree of freedom."""
MIN_BINS_FOR_RHO = 6
"""Fewest bins from which rho is estimated (fewer: rho = 0, said in the report)."""


@dataclass(frozen=True)
class Correlation:
    """The lag-1 correlation of one field's bins and where it came from.

    Attributes
    ----------
    rho : float
        Lag-1 correlation of neighbouring bins' errors, ``0 <= rho <= RHO_MAX`` [-].
    source : str
        ``"metadata"``, ``"estimated"`` (second differences of the data), ``"too few bins"``
        or ``"given"``.
    """

    rho: float
    source: str


def estimate_rho(
    values: FloatArray | Sequence[FloatArray], se: FloatArray | Sequence[FloatArray]
) -> Correlation:
    """The lag-1 correlation of profiles' errors from their second differences (module doc).

    Parameters
    ----------
    values, se : ndarray, or sequences of ndarrays
        A field across the gap in bin order and its standard errors (> 0); or several
        (one field of several runs measured the same way), pooled into one estimate.

    Returns
    -------
    Correlation
        ``rho`` in ``[0, RHO_MAX]`` and ``source = "estimated"``; ``rho = 0`` with
        ``source = "too few bins"`` below :data:`MIN_BINS_FOR_RHO` bins in all.
    """
    ys = [values] if isinstance(values, np.ndarray) else list(values)
    ss = [se] if isinstance(se, np.ndarray) else list(se)
    parts = [
        (np.asarray(y, dtype=float), np.asarray(s, dtype=float))
        for y, s in zip(ys, ss, strict=True)
    ]
    parts = [(y, s) for y, s in parts if y.size >= 3]
    if sum(y.size for y, _ in parts) < MIN_BINS_FOR_RHO:
        return Correlation(0.0, "too few bins")
    a = np.concatenate([s[:-2] for _, s in parts])
    b = np.concatenate([s[1:-1] for _, s in parts])
    c = np.concatenate([s[2:] for _, s in parts])
    d2 = np.concatenate([(y[:-2] - 2.0 * y[1:-1] + y[2:]) ** 2 for y, _ in parts])

    def excess(rho: float) -> float:
        # each d2 over its AR(1) variance is chi^2 with one degree of freedom: match medians
        var = a * a + 4.0 * b * b + c * c - 4.0 * rho * (a * b + b * c) + 2.0 * rho**2 * a * c
        return float(np.median(d2 / var)) - CHI2_1_MEDIAN

    lo, hi = 0.0, RHO_MAX
    if excess(lo) >= 0.0:
        return Correlation(0.0, "estimated")
    if excess(hi) <= 0.0:
        return Correlation(RHO_MAX, "estimated")
    for _ in range(60):  # the variance falls as rho grows, so excess rises: bisect
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if excess(mid) < 0.0 else (lo, mid)
    rho = 0.5 * (lo + hi)
    return Correlation(rho, "estimated")


def whiten(residual: FloatArray, se: FloatArray, rho: float) -> FloatArray:
    """Residuals ``r`` of one field (bin order) whitened under the AR(1) error model [-]."""
    z = np.asarray(residual, dtype=float) / np.asarray(se, dtype=float)
    if rho == 0.0 or z.size < 2:
        return z
    w = np.empty_like(z)
    w[..., 0] = z[..., 0]
    w[..., 1:] = (z[..., 1:] - rho * z[..., :-1]) / math.sqrt(1.0 - rho * rho)
    return w


def log_normalisation(se: FloatArray, rho: float) -> float:
    """``-(1/2) ln det(2 pi C)`` of one field's AR(1) covariance ``C`` (module doc)."""
    s = np.asarray(se, dtype=float)
    n = s.size
    logdet = 2.0 * float(np.sum(np.log(s))) + (n - 1) * math.log(1.0 - rho * rho)
    return -0.5 * (logdet + n * math.log(2.0 * math.pi))


def covariance(se: FloatArray, rho: float) -> FloatArray:
    """The AR(1) covariance ``se_i se_j rho^|i-j|`` of one field (for tests and plots)."""
    s = np.asarray(se, dtype=float)
    i = np.arange(s.size)
    return np.outer(s, s) * rho ** np.abs(i[:, None] - i[None, :])


def effective_bins(n: int, rho: float) -> float:
    """Bins' worth of independent information in ``n`` AR(1)-correlated bins,
    ``n (1 - rho) / (1 + rho)`` (for reports) [-]."""
    return n * (1.0 - rho) / (1.0 + rho)


__all__ = [
    "MIN_BINS_FOR_RHO",
    "RHO_MAX",
    "Correlation",
    "covariance",
    "effective_bins",
    "estimate_rho",
    "log_normalisation",
    "whiten",
]
