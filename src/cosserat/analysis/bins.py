"""A corpus run's bins, and how its binned columns were made.

A DEM run (``cosserat.dem``) reports u and omega as means over the grains in each bin, and
half the vorticity by a difference stencil over the binned u. A model compared with such values
must be measured the same way: averaged over each bin (``calibration.data.Field.nodes``,
``studies.validate.forward``). This module says where a run's bins are (:func:`bin_edges`),
how far each coordinate is from the moving wall (:func:`distance_from_moving`) and how the
run's ``half_vorticity`` column was made (:func:`half_vorticity_method`), once, for both.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from ..errors import ParameterError
from ..model.constitutive import FloatArray
from .corpus import COORDINATE, Run


@dataclass(frozen=True)
class Bins:
    """A run's bins in its own coordinate (y or r) [d], ordered across the gap.

    Attributes
    ----------
    centre, lo, hi : ndarray
        Bin centres and edges [d].
    order : ndarray of int
        ``order[k]`` is the run's row of the k-th bin across the gap.
    walls : (float, float)
        The coordinates of the two walls' surfaces [d] (lower/inner first).
    polar : bool
        Couette bins (annuli).
    """

    centre: FloatArray
    lo: FloatArray
    hi: FloatArray
    order: NDArray[np.intp]
    walls: tuple[float, float]
    polar: bool


def bin_edges(run: Run) -> Bins:
    """The run's bins: an interior bin spans its centre +- w/2 (w the median spacing of the
    centres); a bin next to a wall spans from the wall's surface to twice its centre's distance
    from it (the DEM analysis puts the end bins' centres midway between the wall and the inner
    edge).

    Raises
    ------
    ParameterError
        Fewer than 3 bins, or two bins at one position.
    """
    c = np.asarray(run.columns[COORDINATE[run.cell]], dtype=float)
    order = np.argsort(c)
    s = c[order]
    if s.size < 3 or np.any(np.diff(s) <= 0.0):
        raise ParameterError(
            f"run {run.name}: binned fields need at least 3 bins at distinct positions; "
            f"got {s.size}"
        )
    lower = float(run.Ri_d or 0.0) if run.cell == "couette" else 0.0
    upper = lower + run.gap_d
    w = float(np.median(np.diff(s)))
    lo, hi = s - 0.5 * w, s + 0.5 * w
    lo[0], hi[0] = lower, max(2.0 * s[0] - lower, lower + 1e-9 * w)
    lo[-1], hi[-1] = min(2.0 * s[-1] - upper, upper - 1e-9 * w), upper
    lo, hi = np.clip(lo, lower, upper), np.clip(hi, lower, upper)
    return Bins(s, lo, hi, order, (lower, upper), run.cell == "couette")


HALF_VORTICITY_METHODS = ("np.gradient", "bin-average", "point")
"""How a run's ``half_vorticity`` column can have been made (:func:`half_vorticity_method`)."""


def half_vorticity_method(run: Run) -> str:
    """How the run's ``half_vorticity`` column was made: the sidecar's
    ``half_vorticity_method``, else ``"np.gradient"`` for a run of ``cosserat.dem`` (its
    sidecar names the LAMMPS version: the analysis' stencil over the binned u) and ``"point"``
    for any other (u, omega and half the vorticity are values at the bin centres);
    ``"bin-average"``: the bins' means of u, omega and the point half vorticity (synthetic
    runs).

    Raises
    ------
    ParameterError
        A method not in :data:`HALF_VORTICITY_METHODS`.
    """
    default = "np.gradient" if "lammps_version" in run.meta else "point"
    method = run.meta.get("half_vorticity_method", default)
    if method not in HALF_VORTICITY_METHODS:
        raise ParameterError(
            f"run {run.name}: half_vorticity_method must be one of "
            f"{', '.join(HALF_VORTICITY_METHODS)}; got {method!r}"
        )
    return str(method)


def distance_from_moving(run: Run, x: FloatArray) -> FloatArray:
    """Distance from the moving wall's surface of coordinates ``x`` [d]."""
    if run.cell == "couette":
        inner = float(run.Ri_d or 0.0)
        return x - inner if run.moving_wall == "inner" else inner + run.gap_d - x
    return run.gap_d - x if run.moving_wall == "upper" else np.asarray(x, dtype=float)
