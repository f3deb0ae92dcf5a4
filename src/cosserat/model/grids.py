"""Output grids that resolve the thin layers of the solutions.

At eps = 1e-6 the shear layer is ~1e-5 of the gap: a uniform grid would step over it. A
layered grid puts a share of the points uniformly inside each layer (where the fields vary on
the scale eps/k or eps^(2/3)) and the rest uniformly across the gap.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from .constitutive import FloatArray


def layered_grid(
    n: int, zones: Sequence[tuple[float, float]], lo: float = 0.0, hi: float = 1.0
) -> FloatArray:
    """Sorted points in [lo, hi] with extra resolution in ``zones``.

    Parameters
    ----------
    n : int
        Total number of points (>= 3); the result has at most ``n`` points, both ends included.
    zones : sequence of (centre, half_width)
        Intervals ``[centre - half_width, centre + half_width]`` (clipped to [lo, hi]) that
        each receive about a quarter of the points; zones wider than the domain are ignored.
    """
    n = max(int(n), 3)
    zones = [(c, w) for c, w in zones if 0.0 < w < 0.5 * (hi - lo)]
    n_zone = n // (2 + 2 * len(zones)) if zones else 0
    parts = [_linspace(lo, hi, n - n_zone * len(zones))]
    for centre, width in zones:
        a, b = max(lo, centre - width), min(hi, centre + width)
        parts.append(_linspace(a, b, n_zone))
    # np.unique's values (sorted, exact duplicates dropped) without its overhead
    grid = np.concatenate(parts)
    grid.sort()
    keep = np.empty(grid.size, dtype=bool)
    keep[:1] = True
    np.not_equal(grid[1:], grid[:-1], out=keep[1:])
    grid = grid[keep]
    return grid[(grid >= lo) & (grid <= hi)]


def _linspace(a: float, b: float, num: int) -> FloatArray:
    """``np.linspace(a, b, num)``, the same numbers (``arange * step + a``, the last set to
    ``b``) at a fraction of its cost for a few hundred points: a solve's output grid is made
    per problem, and NumPy's general version cost more than a plane-shear kernel."""
    if num < 2:
        return np.linspace(a, b, num)
    y = np.arange(num, dtype=float)
    y *= (b - a) / (num - 1)
    y += a
    y[-1] = b
    return y
