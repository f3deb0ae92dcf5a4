"""The difference stencil of a binned profile: one definition for the DEM analysis, which
writes a run's ``half_vorticity`` and ``gamma_dot`` columns (:mod:`cosserat.dem.analyse`), and
for validation's forward model of that measurement
(:mod:`cosserat.studies.validate.forward`), so that a model is differenced exactly as the data
were.

The stencil is :func:`numpy.gradient` over the bin centres: second-order central differences
between neighbouring bins in the interior, and at each end bin the one-sided difference
between it and its neighbour (first order).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

FloatArray = NDArray[np.float64]


def gradient(s: FloatArray, f: FloatArray) -> FloatArray:
    """df/ds at the bin centres ``s`` by :func:`numpy.gradient` (NaN with fewer than 3 bins)
    [unit of f / unit of s]."""
    s = np.asarray(s, dtype=float)
    f = np.asarray(f, dtype=float)
    return np.gradient(f, s) if s.size > 2 else np.full_like(f, np.nan)


def half_vorticity(s: FloatArray, u: FloatArray, polar: bool = False) -> FloatArray:
    """Half the vorticity of a binned velocity, counter-clockwise positive: plane
    ``-(1/2) du/dy`` (``s`` = y, ``u`` along x); polar ``(1/(2 r)) d(r u)/dr`` (``s`` = r,
    ``u`` azimuthal) [unit of u / unit of s]."""
    s = np.asarray(s, dtype=float)
    u = np.asarray(u, dtype=float)
    if polar:
        return 0.5 * gradient(s, s * u) / s
    return -0.5 * gradient(s, u)
