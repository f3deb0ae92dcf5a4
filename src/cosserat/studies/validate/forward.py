"""The forward model of the spin measurement: what a run's analysis would report for a model.

A DEM run reports, per bin, the mean velocity u and the mean grain spin omega over the grains
in that bin, and half the vorticity by a difference stencil over the binned u
(``cosserat._stencil``, the code ``cosserat.dem.analyse`` writes the run's
``half_vorticity`` column with). A model's point value of omega - half vorticity, with analytic
derivatives, is not that: near a wall, where u bends within one bin, the binned spin and the
stencil's half vorticity differ from the point values by as much as the departure itself. So
a model's departure is compared with the data's only after the same measurement:

1. **bins**: the run's own, from its coordinate column (``bin_edges``, defined in
   ``cosserat.analysis.bins`` for the calibration's bin means too): an interior bin spans
   its centre +- w/2 (w the median spacing of the centres); a bin next to a wall spans from
   the wall's surface to twice its centre's distance from it (the analysis puts the end
   bins' centres midway between the wall and the inner edge);
2. **averages**: u and omega averaged over each bin (Gauss-Legendre, :data:`NODES` points per
   bin), weighted by r in Couette flow (the bins are annuli);
3. **stencil**: half the vorticity from the binned u at the bin centres by the analysis'
   stencil (``"analysis"``) or, at the first bin next to each wall, by one of the alternative
   stencils of :data:`STENCILS`. That is how ``cosserat.dem`` measures a run; a run made
   otherwise says so in its sidecar (``half_vorticity_method``: ``bin-average``, the
   synthetic runs, or ``point``, values at the bin centres, the default for a run that is not
   from ``cosserat.dem``) and the model is measured the same way (the alternative stencils
   still replace the first layers).

Every stencil is a linear combination of the wall's velocity and the binned u of the first
three bins (:func:`first_layer_weights`), so the same weights give the data's half vorticity
under that stencil and its standard error from u's (:func:`measured_first_layer`).

All quantities are in the run's units and sign (omega d / V, the moving wall's velocity
positive: :attr:`cosserat.analysis.corpus.Run.sign`).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ..._stencil import half_vorticity
from ...analysis.bins import Bins, bin_edges, half_vorticity_method
from ...analysis.bins import distance_from_moving as _distance_from_moving
from ...analysis.corpus import COORDINATE, Run
from ...analysis.fitting import moving_wall
from ...calibration.data import BIN_NODES, gauss_legendre
from ...errors import ParameterError
from ...model.constitutive import FloatArray

NODES = BIN_NODES
"""Gauss-Legendre points per bin of the bin averages (the calibration's bin means use the same
rule, ``calibration.data.Field.nodes``)."""
WALL_SHIFT_D = 0.5
"""The wall's position in the wall stencils is varied by +- this from its surface [d]."""

STENCILS: dict[str, str] = {
    "analysis": "np.gradient over the bin centres, as the DEM analysis (one-sided between the "
    "first two bins)",
    "wall": "central difference across the first bin, from the wall's velocity at its surface "
    "to the second bin",
    "wall-0.5": "as 'wall', the wall's velocity placed 0.5 d behind its surface",
    "wall+0.5": "as 'wall', the wall's velocity placed 0.5 d inside the gap",
    "wall-first": "one-sided, from the wall's velocity at its surface to the first bin",
    "second-order": "one-sided second order through the first three bins (np.gradient with "
    "edge_order=2)",
}
"""The first layer's half-vorticity stencils, by name: how each differences u at the bin
nearest to a wall (every other bin keeps the analysis' stencil)."""


def _check_stencil(stencil: str) -> None:
    if stencil not in STENCILS:
        raise ParameterError(f"stencil must be one of {', '.join(STENCILS)}; got {stencil!r}")


def bin_average(bins: Bins, f: Callable[[FloatArray], FloatArray]) -> FloatArray:
    """The average of ``f`` (a function of the coordinate [d]) over each bin, weighted by r
    in Couette flow [unit of f]."""
    x, wq = gauss_legendre(NODES)
    half = 0.5 * (bins.hi - bins.lo)
    pts = 0.5 * (bins.hi + bins.lo)[:, None] + half[:, None] * x[None, :]
    weight = wq[None, :] * (pts if bins.polar else np.ones_like(pts))
    values = np.asarray(f(pts.ravel()), dtype=float).reshape(pts.shape)
    return np.sum(weight * values, axis=1) / np.sum(weight, axis=1)


def first_layer_weights(
    bins: Bins, wall: int, stencil: str
) -> tuple[float, FloatArray, NDArray[np.intp]]:
    """The stencil at the bin nearest to wall ``wall`` (0 lower/inner, 1 upper/outer) as a
    linear combination: d g/dx at that bin = ``w_wall g_wall + sum w_k g[bins_k]``, g = u
    (plane) or r u (Couette), x the coordinate [1/d].

    Returns
    -------
    (w_wall, w, bins_k)
        The wall velocity's weight, the bins' weights and the bins' indices (across-gap order).
    """
    _check_stencil(stencil)
    n = bins.centre.size
    idx = np.array([0, 1, 2]) if wall == 0 else np.array([n - 1, n - 2, n - 3])
    x = bins.centre[idx]
    inward = 1.0 if wall == 0 else -1.0
    zero = np.zeros(3)
    if stencil == "analysis":
        w = zero.copy()
        w[0], w[1] = -1.0 / (x[1] - x[0]), 1.0 / (x[1] - x[0])
        return 0.0, w, idx
    if stencil == "second-order":
        h1, h2 = x[1] - x[0], x[2] - x[1]
        # np.gradient's edge_order=2 at the first point (non-uniform spacing)
        a = -(2.0 * h1 + h2) / (h1 * (h1 + h2))
        b = (h1 + h2) / (h1 * h2)
        c = -h1 / (h2 * (h1 + h2))
        return 0.0, np.array([a, b, c]), idx
    xp = _wall_position(bins, wall, stencil)
    k = 0 if stencil == "wall-first" else 1
    if (x[k] - xp) * inward <= 0.0:
        raise ParameterError(
            f"stencil {stencil!r}: the wall position {xp:.4g} d is not between the wall and "
            f"the bin at {x[k]:.4g} d"
        )
    w = zero.copy()
    w[k] = 1.0 / (x[k] - xp)
    return -1.0 / (x[k] - xp), w, idx


def _wall_position(bins: Bins, wall: int, stencil: str) -> float:
    """Where a wall stencil puts the wall's velocity [d]."""
    shift = {"wall-0.5": -WALL_SHIFT_D, "wall+0.5": WALL_SHIFT_D}.get(stencil, 0.0)
    return bins.walls[wall] + (1.0 if wall == 0 else -1.0) * shift


def _wall_g(bins: Bins, u_wall: float, wall: int, stencil: str) -> float:
    """g = u (plane) or r u (Couette) of the wall at a wall stencil's position: the wall
    moves rigidly (a translation; a rotation, u = u_wall r / r_wall) [-]."""
    if not bins.polar:
        return float(u_wall)
    xp = _wall_position(bins, wall, stencil)
    return float(u_wall * xp * xp / bins.walls[wall])


def _half_from(bins: Bins, g_slope: FloatArray | float, at: FloatArray | float) -> Any:
    """Half the vorticity from d g/dx (g = u or r u) at positions ``at`` [d]."""
    return 0.5 * np.asarray(g_slope) / np.asarray(at) if bins.polar else -0.5 * np.asarray(g_slope)


def stencil_half(
    bins: Bins, u: FloatArray, u_walls: tuple[float, float], stencil: str
) -> FloatArray:
    """Half the vorticity of the binned ``u`` (across-gap order) by the analysis' stencil,
    the first bin at each wall by ``stencil`` [unit of u / d]."""
    _check_stencil(stencil)
    half = half_vorticity(bins.centre, u, bins.polar)
    if stencil == "analysis":
        return half
    g = bins.centre * u if bins.polar else np.asarray(u, dtype=float)
    for wall in (0, 1):
        ww, w, idx = first_layer_weights(bins, wall, stencil)
        gw = _wall_g(bins, u_walls[wall], wall, stencil)
        slope = ww * gw + float(np.dot(w, g[idx]))
        half[idx[0]] = _half_from(bins, slope, bins.centre[idx[0]])
    return half


def wall_velocities(run: Run) -> tuple[float, float]:
    """The two walls' velocities in the run's units and sign (lower/inner first): 1 at the
    moving wall, 0 at a fixed one (both 0 in the channel) [-]."""
    if run.cell == "channel":
        return 0.0, 0.0
    if run.cell == "couette":
        return (1.0, 0.0) if run.moving_wall == "inner" else (0.0, 1.0)
    return (0.0, 1.0) if run.moving_wall == "upper" else (1.0, 0.0)


@dataclass(frozen=True)
class ModelFields:
    """A model's u and omega as functions of a run's coordinate [d], in the run's units and
    sign (u / V with the moving wall's velocity +1, omega d / V); omega None for a rheology
    whose grains turn with the material (its point omega is half the vorticity)."""

    u: Callable[[FloatArray], FloatArray]
    omega: Callable[[FloatArray], FloatArray]
    point_departure: Callable[[FloatArray], FloatArray]


def model_fields(profile: Any, run: Run) -> ModelFields:
    """A cosserat :class:`~cosserat.results.profile.Profile` (fitted to ``run``) in the run's
    coordinate, units and sign.

    The rotation sense: the model's half vorticity ``-(du/dxi + kappa u)/2`` and the analysis'
    half vorticity of the model's u in the run's coordinate agree up to a sign fixed by the
    two frames (which wall is at xi = 0, the sign of the wall's velocity); that sign turns the
    model's omega into the run's frame (a spin turns with the vorticity under a reflection).
    """
    eps = float(profile.problem.eps)
    xw, uw = moving_wall(profile.problem)

    def xi_of(x: FloatArray) -> FloatArray:
        d = np.clip(_distance_from_moving(run, np.asarray(x, dtype=float)) * eps, 0.0, 1.0)
        return d if xw == 0.0 else 1.0 - d

    polar = run.cell == "couette"
    lower = float(run.Ri_d or 0.0) if polar else 0.0
    probe = np.linspace(lower, lower + run.gap_d, 401)
    f = profile.evaluate(xi_of(probe))
    u_run = np.asarray(f.u, dtype=float) / uw
    model_half = -0.5 * (f.du_dxi + f.kappa * f.u) * eps
    sense = float(np.sum(half_vorticity(probe, u_run, polar) * model_half))
    k = -1.0 if sense < 0.0 else 1.0

    def u(x: FloatArray) -> FloatArray:
        return np.asarray(profile.evaluate(xi_of(x)).u, dtype=float) / uw

    def spin(x: FloatArray) -> FloatArray:
        g = profile.evaluate(xi_of(x))
        half = -0.5 * (g.du_dxi + g.kappa * g.u) * eps
        return k * (half if g.omega is None else np.asarray(g.omega) * eps)

    def point(x: FloatArray) -> FloatArray:
        g = profile.evaluate(xi_of(x))
        half = -0.5 * (g.du_dxi + g.kappa * g.u) * eps
        return k * ((half if g.omega is None else np.asarray(g.omega) * eps) - half)

    return ModelFields(u, spin, point)


def turning_with_the_material(fields: ModelFields) -> ModelFields:
    """The same velocity with grains that turn with the material: omega = the point half
    vorticity of u everywhere (no departure at any point). Measured like the data
    (:func:`forward_fields`), it shows the departure that the binning and the stencil alone
    make: the null of the spin claim."""

    def spin(x: FloatArray) -> FloatArray:
        return np.asarray(fields.omega(x), dtype=float) - np.asarray(
            fields.point_departure(x), dtype=float
        )

    return ModelFields(fields.u, spin, lambda x: np.zeros_like(np.asarray(x, dtype=float)))


def forward_fields(
    fields: ModelFields, run: Run, stencil: str = "analysis"
) -> dict[str, FloatArray]:
    """What the run's analysis would report for the model ``fields``: ``u``, ``omega``,
    ``half_vorticity`` and ``departure`` (omega - half vorticity) per bin, in the run's row
    order [-]; and ``point`` (the model's point departure at the bin centres) [-]."""
    bins = _kept_bins(run)
    method = half_vorticity_method(run)

    def point_half(x: FloatArray) -> FloatArray:
        return np.asarray(fields.omega(x), dtype=float) - np.asarray(
            fields.point_departure(x), dtype=float
        )

    if method == "point":
        u = np.asarray(fields.u(bins.centre), dtype=float)
        omega = np.asarray(fields.omega(bins.centre), dtype=float)
    else:
        u = bin_average(bins, fields.u)
        omega = bin_average(bins, fields.omega)
    half = stencil_half(bins, u, wall_velocities(run), stencil)
    if method != "np.gradient":
        # the run's half vorticity is the bin's mean of the point value, or the point value
        # at its centre; the alternative stencils still replace the first layers
        exact = (
            bin_average(bins, point_half)
            if method == "bin-average"
            else np.asarray(point_half(bins.centre), dtype=float)
        )
        keep = np.ones(half.size, dtype=bool)
        if stencil != "analysis":
            keep[[0, -1]] = False
        half = np.where(keep, exact, half)
    out: dict[str, FloatArray] = {}
    for name, v in (
        ("u", u),
        ("omega", omega),
        ("half_vorticity", half),
        ("departure", omega - half),
        ("point", np.asarray(fields.point_departure(bins.centre), dtype=float)),
    ):
        row = np.empty_like(v)
        row[bins.order] = v
        out[name] = row
    return out


_KEEP_PROFILES = 256
"""How many profiles' :func:`model_fields` (and runs' bins) :func:`_kept_fields` (and
:func:`_kept_bins`) keep: more than a scan's 95% region has (~10-150 profiles, each ~25 kB
kept), whose nulls are asked stencil by stencil over all of them (``nulls.joint_null``), so
that the next stencil finds each profile still kept."""
_KEEP_POINTS = 8
"""How many point sets each of their functions keeps the values at."""
_KEPT: dict[tuple[int, int], tuple[Any, Run, ModelFields]] = {}
_KEPT_BINS: dict[int, tuple[Run, Any, Bins]] = {}


def _kept_bins(run: Run) -> Bins:
    """:func:`~cosserat.analysis.bins.bin_edges` of ``run``, made once for the last
    :data:`_KEEP_PROFILES` runs asked (read-only; made again if the run's coordinate column is
    replaced): :func:`forward_fields` is asked ~10^4 times in one validate."""
    column = run.columns.get(COORDINATE[run.cell])
    kept = _KEPT_BINS.get(id(run))  # the run kept alive below, so its id is not reused
    if kept is not None and kept[0] is run and kept[1] is column:
        return kept[2]
    bins = bin_edges(run)
    for a in (bins.centre, bins.lo, bins.hi, bins.order):
        a.flags.writeable = False
    if len(_KEPT_BINS) >= _KEEP_PROFILES:
        del _KEPT_BINS[next(iter(_KEPT_BINS))]
    _KEPT_BINS[id(run)] = (run, column, bins)
    return bins


def forward_departure(profile: Any, run: Run, stencil: str = "analysis") -> FloatArray:
    """A model's omega - half vorticity as the run's analysis would report it, per bin in the
    run's row order (the run's units and sign) [-].

    Parameters
    ----------
    profile : Profile
        The model's solution (a fit to ``run``; :mod:`cosserat.results.profile`).
    run : Run
        The run whose bins, stencil and frame the model is measured with.
    stencil : str
        The first layer's stencil at each wall (:data:`STENCILS`); every other bin keeps the
        analysis' np.gradient.

    Raises
    ------
    ParameterError
        An unknown stencil, or a run with fewer than 3 bins.
    """
    _check_stencil(stencil)
    return forward_fields(_kept_fields(profile, run), run, stencil)["departure"]


def null_departure(profile: Any, run: Run, stencil: str = "analysis") -> FloatArray:
    """:func:`forward_departure` of the model's velocity with grains that turn with the
    material (:func:`turning_with_the_material`): what the run's analysis reports for a spin
    equal to half the vorticity everywhere, per row [-]."""
    _check_stencil(stencil)
    fields = turning_with_the_material(_kept_fields(profile, run))
    return forward_fields(fields, run, stencil)["departure"]


def _kept_fields(profile: Any, run: Run) -> ModelFields:
    """:func:`model_fields` of ``profile`` in ``run``, made once for the last
    :data:`_KEEP_PROFILES` (profile, run) pairs asked, each function giving again the values it
    gave at the same points (:func:`_remembering`). A profile's departure and its null
    (:func:`forward_departure`, :func:`null_departure`) are asked together at every point of
    a scan, and under every stencil: they share the velocity, the spin and their bin means
    (the same floats, evaluated once rather than up to 8 times)."""
    key = (id(profile), id(run))  # both kept alive below, so neither id is reused meanwhile
    kept = _KEPT.get(key)
    if kept is not None and kept[0] is profile and kept[1] is run:
        return kept[2]
    fields = _remembering(model_fields(profile, run))
    if len(_KEPT) >= _KEEP_PROFILES:
        del _KEPT[next(iter(_KEPT))]
    _KEPT[key] = (profile, run, fields)
    return fields


def _remembering(fields: ModelFields) -> ModelFields:
    """``fields`` whose functions keep their values at the last :data:`_KEEP_POINTS` point
    sets (by value) and give a copy of them when asked at the same points again."""

    def keep(f: Callable[[FloatArray], FloatArray]) -> Callable[[FloatArray], FloatArray]:
        values: dict[tuple[Any, ...], Any] = {}

        def g(x: FloatArray) -> FloatArray:
            a = np.asarray(x)
            key = (a.dtype.str, a.shape, a.tobytes())
            if key not in values:
                if len(values) >= _KEEP_POINTS:
                    del values[next(iter(values))]
                values[key] = f(x)
            return np.array(values[key], copy=True)

        return g

    return ModelFields(keep(fields.u), keep(fields.omega), keep(fields.point_departure))


def first_layer_half_se(
    bins: Bins, u_se: FloatArray, rho_u: float, wall: int, stencil: str
) -> float:
    """Standard error of a stencil's first-layer half vorticity from u's standard errors
    (across-gap order) with lag-1 correlation ``rho_u`` between neighbouring bins (AR(1),
    :func:`cosserat.calibration.noise.covariance`); the wall's velocity is exact [-]."""
    from ...calibration.noise import covariance

    _, w, idx = first_layer_weights(bins, wall, stencil)
    scale = bins.centre[idx] if bins.polar else np.ones(3)
    cov = covariance(np.asarray(u_se, dtype=float)[idx] * scale, rho_u)
    var = float(w @ cov @ w)
    factor = 0.5 / bins.centre[idx[0]] if bins.polar else 0.5
    return factor * math.sqrt(max(var, 0.0))


def measured_first_layer(
    run: Run, wall: int, stencil: str, rho_u: float
) -> tuple[float, float, float]:
    """The data's first-layer omega - half vorticity at wall ``wall`` (0 lower/inner, 1
    upper/outer) under ``stencil``, with the standard error of its half vorticity and of
    omega, in the run's units and sign: ``(departure, se_half, se_omega)`` [-].

    The analysis' stencil takes the run's ``half_vorticity`` column as reported; the others
    difference the run's u, with u's standard errors correlated between neighbouring bins by
    ``rho_u`` (:func:`first_layer_half_se`).
    """
    bins = bin_edges(run)
    u, u_se = (np.asarray(a, dtype=float)[bins.order] for a in run.quantity("u"))
    omega, omega_se = (np.asarray(a, dtype=float)[bins.order] for a in run.quantity("omega"))
    k = 0 if wall == 0 else bins.centre.size - 1
    if stencil == "analysis":
        half, half_se = (
            np.asarray(a, dtype=float)[bins.order] for a in run.quantity("half_vorticity")
        )
        return float(omega[k] - half[k]), float(half_se[k]), float(omega_se[k])
    half = stencil_half(bins, u, wall_velocities(run), stencil)
    se = first_layer_half_se(bins, u_se, rho_u, wall, stencil)
    return float(omega[k] - half[k]), se, float(omega_se[k])


def _counted_centres(gap_d: float, w: float) -> FloatArray:
    """Bin centres [d] from the wall the bins are counted from, at a gap ``gap_d``, as the DEM
    analysis cuts them (``cosserat.dem.analyse.merge_bins``): bins of ``w`` from that wall,
    the remainder at the other end a narrower bin, or joined to its neighbour if under half a
    bin. The analysis decides that on its fine bins (``FINE_BIN``, the gap's end rounded to
    the nearest), and a remainder that rounds to none widens the last bin."""
    from ...dem.analyse import FINE_BIN

    n = math.floor(gap_d / w + 1e-9)
    edges = [k * w for k in range(n + 1)]
    rest = gap_d - edges[-1]
    if rest > 1e-9 * w:
        if round(rest / FINE_BIN) * FINE_BIN < 0.5 * w and len(edges) > 2:
            edges[-1] = gap_d
        else:
            edges.append(gap_d)
    e = np.asarray(edges, dtype=float)
    return 0.5 * (e[:-1] + e[1:])


def analysis_distances(run: Run, gap_d: float) -> FloatArray:
    """Distances from the moving wall [d] of the bin centres that ``run``'s analysis would
    make in the same cell at gap ``gap_d``, in increasing order: a model's Delta measured at
    them is measured as the data's would be (a band thinner than a bin is placed by where the
    first bin's centre falls, which the remainder of the gap over the bins sets).

    The rule is read off the run: bins of its median spacing w counted from the wall its
    interior centres sit at (k + 1/2) w from, the remainder at the other wall a narrower bin,
    or joined to its neighbour if under half a bin (``cosserat.dem.analyse.merge_bins``).
    Where that rule does not give the run's own centres at its own gap (another analysis;
    bins merged for want of grains), the run's first centre and spacing are kept: centres at
    ``s_0 + k w`` from the moving wall."""
    bins = bin_edges(run)
    own = np.sort(_distance_from_moving(run, bins.centre))
    w = float(np.median(np.diff(bins.centre)))
    lower, upper = bins.walls
    size = upper - lower
    for counted_from_lower in (True, False):
        c = _counted_centres(size, w)
        x = lower + c if counted_from_lower else upper - c
        if c.size == own.size and np.allclose(
            np.sort(_distance_from_moving(run, x)), own, atol=1e-3 * w
        ):
            c = _counted_centres(float(gap_d), w)
            x = lower + c if counted_from_lower else lower + float(gap_d) - c
            return _distances_at(run, x, lower, float(gap_d))
    return np.arange(float(own[0]), float(gap_d), w)


def _distances_at(run: Run, x: FloatArray, lower: float, gap_d: float) -> FloatArray:
    """Distances from the moving wall of coordinates ``x`` in a cell like ``run``'s whose gap
    is ``gap_d`` (the lower/inner wall at ``lower``) [d], sorted."""
    x = np.asarray(x, dtype=float)
    if run.cell == "couette":
        d = x - lower if run.moving_wall == "inner" else lower + gap_d - x
    else:
        d = lower + gap_d - x if run.moving_wall == "upper" else x - lower
    return np.sort(d)


def calibration_profile(setup: Any, theta: FloatArray) -> Any:
    """The profile of a one-run calibration (``calibration.engine.Setup``) at ``theta``: the
    spin scan's joint fit at its optimum (``spin_scan.JointFit``)."""
    from ...analysis.ranking import model_solve

    rd = setup.runs[0]
    return model_solve(setup.model.problem(rd, setup.run_values(rd, theta)))


def figure_curves(profile: Any, run: Run, points: int = 300) -> dict[str, FloatArray]:
    """A fitted profile for the run's figure: ``d`` (distances from the moving wall [d]) and
    ``u`` there (the run's units and sign) [-]; per row of the run, its departure as the run's
    analysis would report it (``departure``, the analysis' stencil) and the null of its
    velocity (``null``: grains turning with the material, :func:`turning_with_the_material`)
    [-]."""
    fields = model_fields(profile, run)
    d = np.linspace(0.0, run.gap_d, points)
    lower = float(run.Ri_d or 0.0) if run.cell == "couette" else 0.0
    if run.cell != "couette":  # the run's coordinate of each distance
        x = run.gap_d - d if run.moving_wall == "upper" else d
    elif run.moving_wall == "inner":
        x = lower + d
    else:
        x = lower + run.gap_d - d
    return {
        "d": d,
        "u": np.asarray(fields.u(x), dtype=float),
        "departure": forward_fields(fields, run)["departure"],
        "null": forward_fields(turning_with_the_material(fields), run)["departure"],
    }


GRAIN_LAYER_NODES = 24
"""Gauss-Legendre points of :func:`grain_layers`' layer averages."""


def grain_layers(fields: ModelFields, run: Run, r_1: float) -> dict[str, float] | None:
    """A model's first-layer measures at a plane run's moving wall, as the grain-by-grain
    measure of ``cosserat.dem.first_layer`` takes them from the grains: u and omega averaged
    uniformly over [0, 1) and [1, 2) d from the wall (layer 1 and 2), at their mid-distances
    0.5 and 1.5 d, through ``cosserat.dem.first_layer.layer_measures`` (the three half
    vorticities W, ``departure_<W>`` = omega_1 - W, the rolling fraction with the layer's
    measured mean radius ``r_1`` [d]) [-]. Made on the velocity turning with the material
    (:func:`turning_with_the_material`) it is that measure's null. None for a cell that is
    not plane shear."""
    from ...dem.first_layer import layer_measures

    if run.cell != "plane":
        return None
    upper = run.moving_wall == "upper"
    t, w = gauss_legendre(GRAIN_LAYER_NODES)

    def layer(f: Callable[[FloatArray], FloatArray], k: int) -> float:
        d = k + 0.5 * (np.asarray(t, dtype=float) + 1.0)
        x = run.gap_d - d if upper else d
        return float(np.sum(w * np.asarray(f(x), dtype=float)) / np.sum(w))

    u_1, u_2 = layer(fields.u, 0), layer(fields.u, 1)
    om_1 = layer(fields.omega, 0)
    u_wall = wall_velocities(run)[1 if upper else 0]
    wall = "upper" if upper else "lower"
    return layer_measures(wall, u_wall, u_1, u_2, 0.5, 1.5, om_1, r_1)
