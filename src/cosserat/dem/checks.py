"""Checks on DEM profiles: is the flow rate-independent (quasi-static)?"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..errors import InputError


@dataclass(frozen=True)
class RateCheck:
    """Two scaled profiles compared bin by bin.

    Attributes
    ----------
    z : ndarray
        (a - b) / sqrt(se_a^2 + se_b^2) per bin (b interpolated onto a's coordinate).
    within : float
        Fraction of bins with |z| <= ``z_limit`` [-].
    chi2_per_dof : float
        mean(z^2) [-]: about 1 when the profiles agree within their errors.
    consistent : bool
        ``within`` at least the fraction a normal law puts inside ``z_limit`` less 10 points.
    """

    column: str
    z: np.ndarray
    within: float
    chi2_per_dof: float
    z_limit: float
    consistent: bool


_NORMAL_INSIDE = {1.0: 0.6827, 2.0: 0.9545, 3.0: 0.9973}


def rate_independence(
    a: dict[str, np.ndarray], b: dict[str, np.ndarray], column: str = "u", z_limit: float = 2.0
) -> RateCheck:
    """Compare the scaled ``column`` of two runs at different wall speeds.

    Parameters
    ----------
    a, b : dict
        Profile columns (corpus format, e.g. :attr:`DEMProfile.columns` or a CSV read into a
        dict); the coordinate is ``y`` or ``r``.
    z_limit : float
        The bins' agreement threshold in combined standard errors (1, 2 or 3).
    """
    if z_limit not in _NORMAL_INSIDE:
        raise InputError(f"z_limit must be 1, 2 or 3; got {z_limit!r}")
    coord = "y" if "y" in a else "r"
    for prof, name in ((a, "a"), (b, "b")):
        for key in (coord, column, f"{column}_se"):
            if key not in prof:
                raise InputError(f"profile {name} has no column {key!r}")
    xa, xb = np.asarray(a[coord], float), np.asarray(b[coord], float)
    inside = (xa >= xb.min()) & (xa <= xb.max())
    va = np.asarray(a[column], float)[inside]
    sa = np.asarray(a[f"{column}_se"], float)[inside]
    vb = np.interp(xa[inside], xb, np.asarray(b[column], float))
    sb = np.interp(xa[inside], xb, np.asarray(b[f"{column}_se"], float))
    se = np.hypot(sa, sb)
    ok = np.isfinite(va) & np.isfinite(vb) & (se > 0)
    if not ok.any():
        raise InputError("the two profiles share no bin with a finite value and error")
    z = (va[ok] - vb[ok]) / se[ok]
    within = float(np.mean(np.abs(z) <= z_limit))
    return RateCheck(
        column,
        z,
        within,
        float(np.mean(z**2)),
        z_limit,
        within >= _NORMAL_INSIDE[z_limit] - 0.10,
    )
