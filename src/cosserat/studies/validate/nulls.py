"""The spin claim's null: what the analysis reports for grains that turn with the material.

A spin equal to half the vorticity at every point, measured as a run was (bin averages of u
and omega, a difference stencil over the binned u: :mod:`.forward`), still departs from the
stencil's half vorticity where u bends within a bin: most in the first layer, where it depends
on how the velocity varies inside that bin, which the bins do not resolve. The spin claim is
tested beyond that null (``verdicts.spin_verdict``), and the model's departure is too
(``spin_scan``, behind ``spin_model``): one null serves both (referee 8, point 4). Where it
comes from, in order (:class:`Null`):

1. **the joint fit** (:func:`joint_null`): the velocity of the run's joint u + omega +
   stress-ratio calibration, the one ``spin_model`` judges (:mod:`.spin_scan`), under every
   stencil of :data:`~.forward.STENCILS` at every bin; its standard error from its spread
   over that calibration's 95% region, as ``spin_scan.Scan.null_se`` (the first layer under
   the analysis' stencil is exactly ``spin_model``'s null and error);
2. **the envelope** (:func:`envelope`) of the other nulls a run has (the u-only fits'
   velocities, and the measured velocity's, item 3) where it has no joint fit: the interval
   between the smallest and the largest null at each bin and stencil, carried as a
   systematic error (the departure beyond it is the distance from the data to the interval,
   0 inside it);
3. **the measured velocity** (:func:`velocity_null`): no fit, the binned u itself, for a wall
   no fit describes (the layer run's fixed wall, whose kind the fits do not have). A velocity
   whose bin means are the measured ones: the cumulative integral of u is known exactly at
   the bin edges (the sum of the bin means times the widths), and u is the derivative of a
   smooth interpolant of it; :data:`RECONSTRUCTIONS` interpolants (monotone cubic, two cubic
   splines, Akima) give the envelope, a systematic error. They agree where u varies over
   several bins and differ in the first layer, where the sub-bin velocity (the wall's slip)
   is unresolved: there the null is an interval as wide as the reconstructions disagree.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, replace
from typing import Any

import numpy as np
from numpy.typing import NDArray
from scipy.interpolate import Akima1DInterpolator, CubicSpline, PchipInterpolator

from ...analysis.corpus import Run
from ...errors import ParameterError
from ...model.constitutive import FloatArray
from .forward import (
    STENCILS,
    ModelFields,
    bin_edges,
    forward_fields,
    null_departure,
    wall_velocities,
)
from .measures import JOINT_NULL_SOURCE, WallSpin

RECONSTRUCTIONS = ("pchip", "spline", "natural", "akima")
"""The interpolants of u's cumulative integral behind :func:`velocity_null`."""
TILE_TOL = 0.01
"""Neighbouring bins tile the gap when their shared edge differs by at most this fraction of
the bins' width (the centres in a run's file are rounded) [-]."""


@dataclass(frozen=True)
class Null:
    """A run's null at every row under every stencil.

    Attributes
    ----------
    source : str
        Where it comes from, in words.
    value : mapping of stencil to array
        The null per row of the run, under each stencil of :data:`~.forward.STENCILS` [-].
    se : mapping of stencil to array
        Its standard error per row (0: none) [-].
    lo, hi : mapping of stencil to array
        Its systematic interval per row (equal to ``value`` where it has none) [-].
    joint : mapping of stencil to array, optional
        The joint fit's own departure beyond this null per row (only from
        :func:`joint_null`) [-].
    """

    source: str
    value: Mapping[str, FloatArray]
    se: Mapping[str, FloatArray]
    lo: Mapping[str, FloatArray]
    hi: Mapping[str, FloatArray]
    joint: Mapping[str, FloatArray] | None = None

    @property
    def systematic(self) -> bool:
        """The null is an interval somewhere (an envelope), not a point with an error."""
        return any(
            bool(np.any(np.asarray(self.hi[s]) > np.asarray(self.lo[s]))) for s in self.value
        )


def point_null(
    source: str, value: Mapping[str, FloatArray], se: Mapping[str, FloatArray] | None = None
) -> Null:
    """A null without a systematic interval: ``value`` (per stencil, per row) with its
    standard error ``se`` (0 without)."""
    v = {s: np.asarray(a, dtype=float) for s, a in value.items()}
    e = {
        s: np.zeros_like(a) if se is None else np.asarray(se[s], dtype=float) for s, a in v.items()
    }
    return Null(source, v, e, v, v)


def joint_null(scan: Any, run: Run) -> Null:
    """The null of a run's joint fit (``spin_scan.Scan``; module docstring, item 1), with its
    standard error from the spread over the 95% region, and the joint fit's departure beyond
    it (the prediction the spin claim's power is stated against). Sets the scan's per-bin
    sign-and-size table from the same profiles (``spin_scan.attach_near_bins``)."""
    from .forward import forward_departure
    from .spin_scan import attach_near_bins, region_profiles

    profiles = region_profiles(scan)
    attach_near_bins(scan, run, profiles)
    best = profiles[0]
    width = 2.0 * math.sqrt(scan.threshold / scan.scale)
    value, se, joint = {}, {}, {}
    for s in STENCILS:
        each = np.array([null_departure(p, run, s) for p in profiles])
        value[s] = each[0]
        se[s] = (np.max(each, axis=0) - np.min(each, axis=0)) / width
        joint[s] = forward_departure(best, run, s) - each[0]
    out = point_null(JOINT_NULL_SOURCE, value, se)
    return replace(out, joint=joint)


def envelope(nulls: Sequence[Null], source: str) -> Null:
    """The interval between the nulls at every row and stencil (module docstring, item 2),
    its midpoint as the value and the largest of their standard errors.

    Raises
    ------
    ParameterError
        No null.
    """
    if not nulls:
        raise ParameterError("the envelope of the nulls needs at least one null; got none")
    lo = {s: np.min([n.lo[s] for n in nulls], axis=0) for s in STENCILS}
    hi = {s: np.max([n.hi[s] for n in nulls], axis=0) for s in STENCILS}
    value = {s: 0.5 * (lo[s] + hi[s]) for s in STENCILS}
    se = {s: np.max([n.se[s] for n in nulls], axis=0) for s in STENCILS}
    return Null(source, value, se, lo, hi)


def _reconstruct(x: FloatArray, cum: FloatArray, how: str) -> Callable[[FloatArray], FloatArray]:
    """The derivative of an interpolant ``how`` of the cumulative integral ``cum`` at the
    bin edges ``x``."""
    if how == "pchip":
        f: Any = PchipInterpolator(x, cum)
    elif how == "spline":
        f = CubicSpline(x, cum, bc_type="not-a-knot")
    elif how == "natural":
        f = CubicSpline(x, cum, bc_type="natural")
    elif how == "akima":
        f = Akima1DInterpolator(x, cum)
    else:
        raise ParameterError(f"reconstruction must be one of {', '.join(RECONSTRUCTIONS)}")
    d = f.derivative()
    lo, hi = float(x[0]), float(x[-1])
    return lambda s: np.asarray(d(np.clip(np.asarray(s, dtype=float), lo, hi)), dtype=float)


def velocity_null(run: Run) -> Null:
    """The null of the measured velocity itself (module docstring, item 3): the envelope of
    :data:`RECONSTRUCTIONS`.

    Raises
    ------
    ParameterError
        Bins that do not tile the gap (an edge of one is not the next one's), or fewer
        than 3.
    """
    bins = bin_edges(run)
    u = np.asarray(run.quantity("u")[0], dtype=float)[bins.order]
    width = float(np.median(bins.hi - bins.lo))
    if np.any(np.abs(bins.hi[:-1] - bins.lo[1:]) > TILE_TOL * width):
        raise ParameterError(
            f"run {run.name}: the bins do not tile the gap (an edge differs from the next "
            f"bin's by more than {TILE_TOL:g} of their width), so the measured velocity's "
            "integral is not known at their edges"
        )
    # the edges, each shared by two bins (their centres may be rounded in the run's file)
    x = np.concatenate([[bins.lo[0]], 0.5 * (bins.hi[:-1] + bins.lo[1:]), [bins.hi[-1]]])
    # the bins' means are of u (plane) or, weighted by r, of u over annuli: the integral of
    # u (or of r u) up to each edge
    w = 0.5 * (x[1:] ** 2 - x[:-1] ** 2) if bins.polar else np.diff(x)
    cum = np.concatenate([[0.0], np.cumsum(u * w)])
    polar = bins.polar
    nulls = []
    for how in RECONSTRUCTIONS:
        g = _reconstruct(x, cum, how)

        def vel(s: FloatArray, g: Callable[[FloatArray], FloatArray] = g) -> FloatArray:
            s = np.asarray(s, dtype=float)
            return g(s) / s if polar else g(s)

        def half(s: FloatArray, vel: Callable[[FloatArray], FloatArray] = vel) -> FloatArray:
            s = np.asarray(s, dtype=float)
            h = 1e-4 * width
            if polar:  # (1/(2 r)) d(r u)/dr, centred
                return 0.5 * ((s + h) * vel(s + h) - (s - h) * vel(s - h)) / (2.0 * h * s)
            return -0.5 * (vel(s + h) - vel(s - h)) / (2.0 * h)

        fields = ModelFields(vel, half, lambda s: np.zeros_like(np.asarray(s, dtype=float)))
        value = {s: forward_fields(fields, run, s)["departure"] for s in STENCILS}
        nulls.append(point_null(how, value, {s: np.zeros_like(v) for s, v in value.items()}))
    return envelope(
        nulls,
        "the measured velocity (u's bin means, reconstructed by "
        + ", ".join(RECONSTRUCTIONS)
        + " interpolants of its integral)",
    )


def monotone_beyond(run: Run) -> tuple[FloatArray, FloatArray] | None:
    """Bounds of omega - the bin's mean point half vorticity (the departure beyond the null of
    grains turning with the material, whatever the stencil) per row, over every velocity that
    is monotone across the gap and has the measured bin means: the velocity at an edge
    between two bins lies between their means, at a wall's surface between the wall's
    velocity and the first bin's mean. A plane run only (None otherwise) [-]."""
    if run.cell != "plane":
        return None
    bins = bin_edges(run)
    u = np.asarray(run.quantity("u")[0], dtype=float)[bins.order]
    omega = np.asarray(run.quantity("omega")[0], dtype=float)[bins.order]
    uw = wall_velocities(run)
    x = np.concatenate([[bins.lo[0]], 0.5 * (bins.hi[:-1] + bins.lo[1:]), [bins.hi[-1]]])
    left = np.concatenate([[uw[0]], u])
    right = np.concatenate([u, [uw[1]]])
    e_lo, e_hi = np.minimum(left, right), np.maximum(left, right)
    w = np.diff(x)
    # mean half vorticity of bin i: -(u(x_i+1) - u(x_i)) / (2 w_i)
    h_lo = -(e_hi[1:] - e_lo[:-1]) / (2.0 * w)
    h_hi = -(e_lo[1:] - e_hi[:-1]) / (2.0 * w)
    lo, hi = np.empty_like(u), np.empty_like(u)
    lo[bins.order], hi[bins.order] = omega - h_hi, omega - h_lo
    return lo, hi


def with_null(
    w: WallSpin, null: Null, rows: NDArray[np.intp], wall_row: int, model: str = ""
) -> WallSpin:
    """``w`` tested against ``null``: its value, error and interval at the wall's bins (the
    run's ``rows``, in ``w``'s order) and in its first layer (the run's ``wall_row``) under
    every stencil; ``model`` names the fit (``WallSpin.null_model``)."""
    idx = np.asarray(rows, dtype=int)
    a = "analysis"
    return replace(
        w,
        null=np.asarray(null.value[a], dtype=float)[idx],
        null_model=model or null.source,
        null_stencils={s: float(null.value[s][wall_row]) for s in STENCILS},
        null_se=np.asarray(null.se[a], dtype=float)[idx],
        null_range=(
            (np.asarray(null.lo[a], dtype=float)[idx], np.asarray(null.hi[a], dtype=float)[idx])
            if null.systematic
            else None
        ),
        null_stencils_se={s: float(null.se[s][wall_row]) for s in STENCILS},
        null_stencils_range=(
            {s: (float(null.lo[s][wall_row]), float(null.hi[s][wall_row])) for s in STENCILS}
            if null.systematic
            else {}
        ),
        null_source=null.source,
        joint=None if null.joint is None else np.asarray(null.joint[a], dtype=float)[idx],
    )


__all__ = [
    "RECONSTRUCTIONS",
    "Null",
    "envelope",
    "joint_null",
    "monotone_beyond",
    "point_null",
    "velocity_null",
    "with_null",
]
