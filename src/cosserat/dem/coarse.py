"""Coarse-graining of DEM samples into profiles across the gap, with block-averaged errors.

Every grain is assigned whole to the bin of its centre. A bin's velocity and spin are
mass-weighted means; its solids fraction is the grains' area over the bin's area; its stress is
kinetic plus contact,

    sigma_ij = (1/A) [ sum_p m_p dv_i dv_j  -  sum_p sum_c l_i f_j ],

compressive positive, where dv is a grain's velocity less the bin's mean, l the vector from the
grain's centre to the contact point and f the contact force on the grain: i is the normal of
the plane the force acts across, j the force component. The contact part is not symmetric;
its antisymmetric part is the asymmetry the Cosserat model carries.

Components are in the cell's frame: "t" along the flow (x, or the azimuth), "n" across the gap
(y, or the radius). Sums are kept per sample (:class:`Samples`); time averages and their
standard errors are taken over contiguous blocks of samples (:func:`block_profiles`).
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass

import numpy as np

from ..errors import InputError, ParameterError

SUMS = ("mass", "mom_t", "mom_n", "spin", "area", "mvv_tt", "mvv_nn", "mvv_tn",
        "lf_tt", "lf_nn", "lf_nt", "lf_tn", "count")  # fmt: skip
"""Per-bin sums of one sample (mass, momenta, mass x spin, area, m v v, l f, grain count)."""


@dataclass(frozen=True)
class Grains2D:
    """One sample of the free grains in the cell's frame.

    Attributes
    ----------
    s : ndarray
        Coordinate across the gap (y from the lower wall, or r from the axis) [d].
    vt, vn : ndarray
        Velocity along the flow and across the gap [velocity].
    omega : ndarray
        Spin, counter-clockwise positive [1 / time].
    mass, area : ndarray
        Mass [rho_s d^2] and area [d^2] of each grain (a 3-D cell's spheres: mass
        [rho_s d^3] and volume [d^3], the bins' ``bin_area`` then their volumes [d^3]).
    lf : ndarray, shape (n, 4)
        Per grain, sum over its contacts of l_t f_t, l_n f_n, l_n f_t, l_t f_n [force d].
    """

    s: np.ndarray
    vt: np.ndarray
    vn: np.ndarray
    omega: np.ndarray
    mass: np.ndarray
    area: np.ndarray
    lf: np.ndarray


def bin_sums(grains: Grains2D, edges: np.ndarray) -> np.ndarray:
    """Per-bin sums of one sample, shape (bins, len(SUMS)); grains outside the edges go to the
    end bins."""
    nb = edges.size - 1
    k = np.clip(np.searchsorted(edges, grains.s, side="right") - 1, 0, nb - 1)
    m = grains.mass
    cols = (
        m,
        m * grains.vt,
        m * grains.vn,
        m * grains.omega,
        grains.area,
        m * grains.vt * grains.vt,
        m * grains.vn * grains.vn,
        m * grains.vt * grains.vn,
        grains.lf[:, 0],
        grains.lf[:, 1],
        grains.lf[:, 2],
        grains.lf[:, 3],
        np.ones_like(m),
    )
    return np.stack([np.bincount(k, weights=c, minlength=nb) for c in cols], axis=1)


@dataclass(frozen=True)
class Samples:
    """Per-sample bin sums of a run: ``sums`` of shape (samples, bins, len(SUMS)), the
    ``steps``, the bin ``edges`` [d] and each bin's ``bin_area`` [d^2]."""

    steps: np.ndarray
    sums: np.ndarray
    edges: np.ndarray
    bin_area: np.ndarray

    @property
    def centres(self) -> np.ndarray:
        return 0.5 * (self.edges[1:] + self.edges[:-1])


def _fields(total: np.ndarray, n_samples: int, bin_area: np.ndarray) -> dict[str, np.ndarray]:
    """Velocity, spin, solids fraction and stress (simulation units) from summed sums."""
    S = {name: total[:, k] for k, name in enumerate(SUMS)}
    with np.errstate(invalid="ignore", divide="ignore"):
        ut = S["mom_t"] / S["mass"]
        un = S["mom_n"] / S["mass"]
        omega = S["spin"] / S["mass"]
    area = bin_area * n_samples
    kin_tt = S["mvv_tt"] - S["mass"] * ut * ut
    kin_nn = S["mvv_nn"] - S["mass"] * un * un
    kin_tn = S["mvv_tn"] - S["mass"] * ut * un
    kin_tt, kin_nn, kin_tn = (np.where(S["mass"] > 0, k, 0.0) for k in (kin_tt, kin_nn, kin_tn))
    return {
        "u": ut,
        "v_n": un,
        "omega": omega,
        "nu": S["area"] / area,
        "sigma_tt": (kin_tt - S["lf_tt"]) / area,
        "sigma_nn": (kin_nn - S["lf_nn"]) / area,
        "sigma_nt": (kin_tn - S["lf_nt"]) / area,
        "sigma_tn": (kin_tn - S["lf_tn"]) / area,
    }


def sample_fields(samples: Samples, first: int, names: tuple[str, ...]) -> dict[str, np.ndarray]:
    """Per sample from index ``first``, the fields ``names`` of each bin, as one sample alone
    gives them (:func:`block_fields` with one-sample blocks), shape (samples, bins) [simulation
    units]: the per-sample series whose autocorrelation sets how long a block must be.

    Raises
    ------
    InputError
        A name that is not a field, or ``first`` outside the samples.
    """
    n = samples.sums.shape[0]
    if not 0 <= first < n:
        raise InputError(f"first sample {first} outside the {n} samples")
    rows = [_fields(samples.sums[k], 1, samples.bin_area) for k in range(first, n)]
    unknown = [x for x in names if x not in rows[0]]
    if unknown:
        raise InputError(f"unknown fields {unknown}; known: {sorted(rows[0])}")
    return {x: np.stack([r[x] for r in rows]) for x in names}


def block_ranges(n_samples: int, first: int, blocks: int) -> list[tuple[int, int]]:
    """``blocks`` contiguous sample ranges ``[a, b)`` covering the samples from index
    ``first`` of ``n_samples``, as equal as whole samples allow.

    Raises
    ------
    ParameterError
        Fewer than 2 blocks.
    InputError
        Fewer steady samples than blocks.
    """
    n = n_samples - first
    if blocks < 2:
        raise ParameterError(f"blocks must be >= 2; got {blocks}")
    if n < blocks:
        raise InputError(f"{n} steady samples cannot make {blocks} blocks")
    bounds = first + (np.arange(blocks + 1) * n) // blocks
    return [(int(a), int(b)) for a, b in itertools.pairwise(bounds)]


def block_fields(samples: Samples, first: int, blocks: int) -> list[dict[str, np.ndarray]]:
    """The fields of each of ``blocks`` contiguous blocks of the samples from index ``first``."""
    out = []
    for a, b in block_ranges(samples.sums.shape[0], first, blocks):
        total = samples.sums[a:b].sum(axis=0)
        out.append(_fields(total, b - a, samples.bin_area))
    return out


def mean_and_error(blocks: list[dict[str, np.ndarray]]) -> dict[str, tuple[np.ndarray, np.ndarray]]:
    """Mean over blocks and its standard error std(ddof=1) / sqrt(blocks), per field."""
    nb = len(blocks)
    out = {}
    for name in blocks[0]:
        stack = np.stack([b[name] for b in blocks])
        out[name] = (stack.mean(axis=0), stack.std(axis=0, ddof=1) / np.sqrt(nb))
    return out


def block_correlation(a: np.ndarray, b: np.ndarray) -> list[float | None]:
    """Per bin, the correlation across blocks of two per-block profiles of shape (blocks,
    bins): the correlation of the errors of their block means, so that the covariance of the
    means is ``r se_a se_b`` (``se`` from :func:`mean_and_error`) [-]. None for a bin where
    either profile is not finite in every block or does not vary.

    Raises
    ------
    InputError
        The profiles' shapes differ, or fewer than 2 blocks.
    """
    x, y = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    if x.shape != y.shape or x.ndim != 2 or x.shape[0] < 2:
        raise InputError(
            f"block_correlation needs two (blocks >= 2, bins) arrays of one shape; got "
            f"{x.shape} and {y.shape}"
        )
    out: list[float | None] = []
    for k in range(x.shape[1]):
        u, v = x[:, k], y[:, k]
        if not (np.all(np.isfinite(u)) and np.all(np.isfinite(v))):
            out.append(None)
            continue
        du, dv = u - u.mean(), v - v.mean()
        norm = float(np.sqrt(np.sum(du * du) * np.sum(dv * dv)))
        # a profile constant up to round-off has no correlation to speak of
        if not norm > 1e-24 * max(float(np.max(np.abs(u))) * float(np.max(np.abs(v))), 1e-300):
            out.append(None)
            continue
        out.append(round(float(np.clip(np.sum(du * dv) / norm, -1.0, 1.0)), 4))
    return out


def mser_truncation(series: np.ndarray, batch: int = 5) -> int:
    """Samples to drop from the start of a series as its transient: the Marginal Standard
    Error Rule MSER-5 (White 1997; White, Cobb & Spratt 2000), on batch means of ``batch``
    samples, the truncation restricted to the first half of the series.

    Returns
    -------
    int
        Number of samples to drop (a multiple of ``batch``).
    """
    x = np.asarray(series, dtype=float)
    nb = x.size // batch
    if nb < 4:
        return 0
    z = x[: nb * batch].reshape(nb, batch).mean(axis=1)
    best, best_d = np.inf, 0
    for d in range(nb // 2 + 1):
        tail = z[d:]
        value = np.sum((tail - tail.mean()) ** 2) / tail.size**2
        if value < best:
            best, best_d = value, d
    return best_d * batch


def inertial_number(gamma_dot: np.ndarray, pressure: np.ndarray, density: float) -> np.ndarray:
    """Local inertial number I = |gamma_dot| d / sqrt(p / rho_s) (d = 1); NaN where p <= 0."""
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.where(pressure > 0, np.abs(gamma_dot) / np.sqrt(pressure / density), np.nan)
