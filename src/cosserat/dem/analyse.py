"""From a finished run's dumps to a profile in the corpus format (CSV + JSON sidecar).

:func:`read_samples` turns every sample of ``atoms.dump`` and ``contacts.dump`` into per-bin
sums in the cell's frame (fine bins of :data:`FINE_BIN` d, merged into bins of about 1 d once
the steady gap is known) and the wall and flow series; :func:`steady_profile` drops the
transient (MSER-5 on the flow rate and on the gap), block-averages the rest and scales it.
"""

from __future__ import annotations

import itertools
import json
import math
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from .._atomic import write_text
from .._stencil import gradient as _gradient
from .._stencil import half_vorticity
from ..errors import InputError, ParameterError
from .checks import block_autocorrelation, profile_autocorrelation
from .coarse import (
    SUMS,
    Grains2D,
    Samples,
    bin_sums,
    block_correlation,
    block_fields,
    inertial_number,
    mean_and_error,
    mser_truncation,
    sample_fields,
)
from .decks import Deck, dimension
from .dumps import iter_frames
from .first_layer import LayerSamples, first_layer_record, sample_layers
from .geometry import FREE, LOWER_WALL, UPPER_WALL
from .params import BLOCKS, MIN_SAMPLES, ChannelDEM, CouetteDEM, PlaneShearDEM

FORMAT = "cosserat-corpus/1"
FINE_BIN = 0.25
"""Width of the fine bins the samples are summed in [d]."""
BIN_WIDTH = 1.0
"""Width of the profile bins [d] (the last bin before the far wall may be narrower)."""
QUASI_STATIC_I = 1e-3
"""Largest local inertial number of a quasi-static run in each of the :data:`WALL_BINS` bins
next to the moving wall [-] (the calibration's ``cosserat.calibration.data.QUASI_STATIC_I``)."""
WALL_BINS = 3
"""Bins next to each wall whose local inertial number the sidecar records."""
STEADY_Z = 3.36
"""A steady observable's second-half mean differs from its first-half mean by at most this
many standard errors of the difference [-]: the two-sided 1% point of Student's t with 8
degrees of freedom (two halves of 5 blocks), so each scalar of a steady window fails by chance
in 1% of runs and the five observables of :func:`steadiness` together in about 6% (2 se, the
first choice, failed half of all steady windows; ``tests/test_dem_sidecar.py``)."""
STEADY_BINS = 0.85
"""A steady profile has at least this fraction of its bins within :data:`STEADY_Z` [-] (the
rate check's 85%)."""
MIN_TRAVEL_D = 20.0
"""Wall travel every window discards before averaging [d]: the default window starts at the
later of MSER-5's truncation and the first sample after the moving wall (plane: the upper
wall; Couette: the inner ring's surface) has travelled this far (referee 9, point 5: one
window rule for every v2 run; v1's transients lasted 11-52 d of travel). A run too short to
keep :data:`~cosserat.dem.params.MIN_SAMPLES` samples after it keeps MSER-5's window, and its
sidecar's ``window_rule`` says the rule is not met."""
TRUNCATED_FRACTION = 0.9
"""An end bin narrower than this fraction of the bin width is *truncated* [-]: the bins are
counted from one wall, so the remainder of the gap at the other is 0.5-1 bin wide (a bin of
0.56-0.84 d with its centre 0.28-0.42 d from the wall in the v2 runs). Centre binning puts a
whole grain's contacts in the bin of its centre, so a truncated bin's stresses and solids
fraction are not bulk values (sigma_yx -0.476 against the wall's -0.307, nu 0.965 above the
hexagonal 0.907 in ``plane_rough_H20_qs``): the sidecar's ``truncated_bins`` names them."""


@dataclass
class RunSamples:
    """Everything read from a run's dumps: fine-bin sums and the per-sample series."""

    samples: Samples
    flow: np.ndarray  # mean velocity of the free grains along the flow [velocity]
    gap: np.ndarray  # gap between the wall surfaces [d]
    wall_normal: np.ndarray  # compressive normal stress on the moving / inner wall [N]
    wall_shear: np.ndarray  # shear stress on that wall (force along the flow / length) [N]
    wall_speed_measured: np.ndarray  # mean flow-direction speed of that wall's disks
    n_free: int
    extra: dict = field(default_factory=dict)


def _per_grain_contacts(atoms: np.ndarray, contacts: np.ndarray, polar: bool, dim: int = 2):
    """Per-atom sums of l_a f_b (4 components, cell frame; 3-D: a fifth, l_z f_z), and the
    (x, y) force on every atom."""
    n = atoms.shape[0]
    radius = atoms[:, 2]
    pos = atoms[:, 3:5]
    lf = np.zeros((n, 4 if dim == 2 else 5))
    force = np.zeros((n, 2))
    where_d = slice(6, 8) if dim == 2 else slice(8, 11)
    # pair/local also lists neighbours within the cutoff that do not touch: their vector
    # (set by the contact model only) is zero
    contacts = contacts[np.any(contacts[:, where_d] != 0.0, axis=1)]
    if contacts.shape[0] == 0:
        return lf, force
    i = contacts[:, 0].astype(np.int64) - 1
    j = contacts[:, 1].astype(np.int64) - 1
    dvec = contacts[:, where_d]
    if dim == 2:
        f = contacts[:, 2:4] + contacts[:, 4:6]
        dist = np.hypot(dvec[:, 0], dvec[:, 1])
    else:
        f = contacts[:, 2:5] + contacts[:, 5:8]
        dist = np.sqrt(np.sum(dvec * dvec, axis=1))
    nhat = dvec / dist[:, None]
    overlap = radius[i] + radius[j] - dist
    l_i = -nhat * (radius[i] - 0.5 * overlap)[:, None]
    l_j = nhat * (radius[j] - 0.5 * overlap)[:, None]
    for who, ell, fo in ((i, l_i, f), (j, l_j, -f)):
        if polar:
            r = np.hypot(pos[who, 0], pos[who, 1])
            er = pos[who] / r[:, None]
            et = np.stack([-er[:, 1], er[:, 0]], axis=1)
            lt, ln = np.sum(ell * et, 1), np.sum(ell * er, 1)
            ft, fn = np.sum(fo * et, 1), np.sum(fo * er, 1)
        else:
            lt, ln, ft, fn = ell[:, 0], ell[:, 1], fo[:, 0], fo[:, 1]
        for k, w in enumerate((lt * ft, ln * fn, ln * ft, lt * fn)):
            lf[:, k] += np.bincount(who, weights=w, minlength=n)
        if dim == 3:
            lf[:, 4] += np.bincount(who, weights=ell[:, 2] * fo[:, 2], minlength=n)
        force[:, 0] += np.bincount(who, weights=fo[:, 0], minlength=n)
        force[:, 1] += np.bincount(who, weights=fo[:, 1], minlength=n)
    return lf, force


def read_samples(folder: str | Path, deck: Deck) -> RunSamples:
    """Read a finished run's dumps into fine-bin sums and series (see the module doc)."""
    cell, info = deck.cell, deck.layout.info
    if dimension(cell) == 3:
        return _read_samples_3d(folder, deck)
    polar = isinstance(cell, CouetteDEM)
    density = cell.grains.density
    off = info["surface_offset"]
    if polar:
        lo, hi = info["inner_radius"] - 1.0, info["outer_radius"] + 1.0
        length = 2.0 * math.pi * info["inner_radius"]
    else:
        lo, hi = -1.0, info["initial_gap"] + 2.0
        length = info["length"]
    fine = lo + FINE_BIN * np.arange(math.ceil((hi - lo) / FINE_BIN) + 1)
    steps, sums, flow, gap, wn, ws, wv = [], [], [], [], [], [], []
    plane = isinstance(cell, PlaneShearDEM)
    layer_sums, layer_u_wall = [], []  # the first layers, grain by grain (plane cells)
    n_free = 0
    for step, atoms, contacts in iter_frames(folder):
        kind = atoms[:, 1].astype(int)
        free = kind == FREE
        n_free = int(free.sum())
        lf, force = _per_grain_contacts(atoms, contacts, polar)
        x, y, vx, vy = atoms[:, 3], atoms[:, 4], atoms[:, 5], atoms[:, 6]
        rad = atoms[:, 2]
        mass = density * math.pi * rad**2
        if polar:
            r = np.hypot(x, y)
            s = r
            vt = (-y * vx + x * vy) / r
            vn = (x * vx + y * vy) / r
        else:
            s = y - off
            vt, vn = vx, vy
        g = Grains2D(s[free], vt[free], vn[free], atoms[free, 7], mass[free],
                     math.pi * rad[free] ** 2, lf[free])  # fmt: skip
        steps.append(step)
        sums.append(bin_sums(g, fine))
        flow.append(vt[free].mean())
        if polar:
            inner = kind == LOWER_WALL
            fr = (x[inner] * force[inner, 0] + y[inner] * force[inner, 1]) / r[inner]
            torque = x[inner] * force[inner, 1] - y[inner] * force[inner, 0]
            wn.append(-fr.sum() / length)
            ws.append(torque.sum() / (length * info["inner_radius"]))
            wv.append(vt[inner].mean() * info["inner_radius"] / r[inner].mean())
            gap.append(info["outer_radius"] - info["inner_radius"])
        else:
            upper = kind == UPPER_WALL
            top = off + info["upper_offset"] if "upper_offset" in info else 2.0 * off
            gap.append(y[upper].mean() - top)
            wn.append(force[upper, 1].sum() / length)
            ws.append(force[upper, 0].sum() / length)
            wv.append(vx[upper].mean())
            if plane:
                one, walls = sample_layers(atoms, info, density)
                layer_sums.append(one)
                layer_u_wall.append(walls)
    if len(steps) < MIN_SAMPLES:
        raise InputError(f"{folder}: {len(steps)} samples; at least {MIN_SAMPLES} are needed")
    area_fine = math.pi * (fine[1:] ** 2 - fine[:-1] ** 2) if polar else np.diff(fine) * length
    samples = Samples(np.array(steps), np.array(sums), fine, area_fine)
    extra = {"layers": LayerSamples(np.array(steps), np.array(layer_sums),
                                    np.array(layer_u_wall))} if plane else {}  # fmt: skip
    return RunSamples(samples, np.array(flow), np.array(gap), np.array(wn), np.array(ws),
                      np.array(wv), n_free, extra)  # fmt: skip


def _read_samples_3d(folder: str | Path, deck: Deck) -> RunSamples:
    """:func:`read_samples` for a 3-D plane cell: spheres averaged over the periodic x and z.

    The bins are slabs of the whole width x depth; velocity and spin about z (``omegaz``, the
    axis normal to the flow's (x, y) plane) are mass-weighted; the solids fraction is the
    spheres' volume over the slab's; the stresses are the (x, y) components of the 3-D
    kinetic + contact stress over the slab's volume. ``extra["sigma_zz_ratio"]`` holds, per
    sample, the free grains' sigma_zz over (sigma_xx + sigma_yy) / 2 (whole cell)."""
    cell, info = deck.cell, deck.layout.info
    density = cell.grains.density
    off = info["surface_offset"]
    extent = info["length"] * info["depth"]
    lo, hi = -1.0, info["initial_gap"] + 2.0
    fine = lo + FINE_BIN * np.arange(math.ceil((hi - lo) / FINE_BIN) + 1)
    steps, sums, flow, gap, wn, ws, wv, zz = [], [], [], [], [], [], [], []
    n_free = 0
    for step, atoms, contacts in iter_frames(folder):
        if atoms.shape[1] != 12 or (contacts.size and contacts.shape[1] != 11):
            raise InputError(
                f"{folder}: step {step} is not a 3-D dump (atoms need 12 columns, contacts 11; "
                f"got {atoms.shape[1]} and {contacts.shape[1]})"
            )
        kind = atoms[:, 1].astype(int)
        free = kind == FREE
        n_free = int(free.sum())
        lf, force = _per_grain_contacts(atoms, contacts, False, dim=3)
        y, vx, vy, vz = atoms[:, 4], atoms[:, 6], atoms[:, 7], atoms[:, 8]
        rad = atoms[:, 2]
        volume = 4.0 / 3.0 * math.pi * rad**3
        mass = density * volume
        g = Grains2D(y[free] - off, vx[free], vy[free], atoms[free, 11], mass[free],
                     volume[free], lf[free, :4])  # fmt: skip
        steps.append(step)
        sums.append(bin_sums(g, fine))
        flow.append(vx[free].mean())
        upper = kind == UPPER_WALL
        gap.append(y[upper].mean() - 2.0 * off)
        wn.append(force[upper, 1].sum() / extent)
        ws.append(force[upper, 0].sum() / extent)
        wv.append(vx[upper].mean())
        m = mass[free]
        kin = [np.sum(m * (v[free] - np.sum(m * v[free]) / m.sum()) ** 2) for v in (vx, vy, vz)]
        s_xx, s_yy, s_zz = (kin[k] - lf[free, c].sum() for k, c in ((0, 0), (1, 1), (2, 4)))
        zz.append(s_zz / (0.5 * (s_xx + s_yy)) if s_xx + s_yy > 0 else math.nan)
    if len(steps) < MIN_SAMPLES:
        raise InputError(f"{folder}: {len(steps)} samples; at least {MIN_SAMPLES} are needed")
    samples = Samples(np.array(steps), np.array(sums), fine, np.diff(fine) * extent)
    return RunSamples(samples, np.array(flow), np.array(gap), np.array(wn), np.array(ws),
                      np.array(wv), n_free, extra={"sigma_zz_ratio": np.array(zz)})  # fmt: skip


def merge_bins(
    samples: Samples, lo: float, hi: float, width: float = BIN_WIDTH, anchor: str = "lower"
) -> Samples:
    """Merge fine bins into bins of ``width`` spanning [lo, hi] (fine-bin sums outside go to the
    end bins; the bins' areas are those of [lo, hi] only). The bins are counted from the
    ``anchor`` end ("lower": from lo, "upper": from hi); the remainder at the other end is a
    narrower bin, or joins its neighbour if under half a bin."""
    if anchor not in ("lower", "upper"):
        raise ParameterError(f"anchor must be 'lower' or 'upper'; got {anchor!r}")
    fine = samples.edges
    k_lo = int(np.argmin(np.abs(fine - lo)))
    k_hi = int(np.argmin(np.abs(fine - hi)))
    per = max(1, round(width / (fine[1] - fine[0])))
    if anchor == "lower":
        cuts = [*range(k_lo, k_hi, per), k_hi]
        if cuts[-1] - cuts[-2] < per / 2 and len(cuts) > 2:
            cuts.pop(-2)
    else:
        cuts = sorted({k_lo, *range(k_hi, k_lo, -per)})
        if cuts[1] - cuts[0] < per / 2 and len(cuts) > 2:
            cuts.pop(1)
    nb = len(cuts) - 1
    out = np.zeros((samples.sums.shape[0], nb, samples.sums.shape[2]))
    area = np.zeros(nb)
    for b in range(nb):
        a, z = cuts[b], cuts[b + 1]
        if b == 0:
            a = 0
        if b == nb - 1:
            z = samples.sums.shape[1]
        out[:, b] = samples.sums[:, a:z].sum(axis=1)
        area[b] = samples.bin_area[cuts[b] : cuts[b + 1]].sum()
    return Samples(samples.steps, out, fine[cuts], area)


def drift(series: np.ndarray) -> float:
    """Change of a series' mean from the first to the second half of the window [its units]:
    near zero (within the flow's noise) in a steady state, of the sign of the trend if not."""
    half = series.size // 2
    return float(series[half:].mean() - series[:half].mean())


def steady_start(run: RunSamples) -> int:
    """Index of the first steady sample: the largest MSER-5 truncation of the series of the
    flow rate, the gap and the wall's normal and shear stresses."""
    series = (run.flow, run.gap, run.wall_normal, run.wall_shear)
    return max(mser_truncation(x) for x in series)


def window_start(
    run: RunSamples, deck: Deck, first: int | None = None, min_travel_d: float = MIN_TRAVEL_D
) -> tuple[int, dict]:
    """The index of the window's first sample and the sidecar's ``window_rule`` record.

    Parameters
    ----------
    run : RunSamples
        The run's samples and series.
    deck : Deck
        The run's deck (its timestep; the cell's wall speed).
    first : int, optional
        A window start chosen by the caller (the rule is then only recorded, not applied).
    min_travel_d : float
        Wall travel to discard [d] (default :data:`MIN_TRAVEL_D`).

    Returns
    -------
    tuple of (int, dict)
        The first sample's index: by default the later of :func:`steady_start` (MSER-5) and
        the first sample after ``min_travel_d`` of wall travel (a channel has no moving wall:
        MSER-5 alone); the record: ``min_travel_d``, ``mser_start_step``,
        ``travel_at_start_d`` (the moving wall's travel at the window's first step [d];
        None for a channel), ``met`` and ``rule``.
    """
    steps = run.samples.steps
    mser = steady_start(run)
    cell = deck.cell
    speed = None if isinstance(cell, ChannelDEM) else float(cell.wall_speed)
    travel = None if speed is None else steps * deck.timestep * speed
    chosen = first is not None
    if first is None:
        first = mser
        if travel is not None:
            after = np.flatnonzero(travel >= min_travel_d)
            # the rule only where it leaves enough samples; else MSER-5's window, not met
            if after.size and steps.size - max(int(after[0]), mser) >= MIN_SAMPLES:
                first = max(int(after[0]), mser)
    at = None if travel is None else round(float(travel[first]), 3)
    record = {
        "min_travel_d": min_travel_d,
        "mser_start_step": int(steps[mser]),
        "travel_at_start_d": at,
        "met": None if at is None else bool(at >= min_travel_d - 1e-9),
        "rule": (
            f"the window starts at the later of MSER-5's truncation and the first sample after "
            f"{min_travel_d:g} d of the moving wall's travel (steps x timestep x wall speed)"
            + ("; chosen by the caller here" if chosen else "")
            + ("" if travel is not None else "; a channel has no moving wall: MSER-5 alone")
        ),
    }
    return first, record


def truncated_bins(edges: np.ndarray, lo: float, hi: float, bin_width: float) -> dict[int, float]:
    """The end bins narrower than :data:`TRUNCATED_FRACTION` of ``bin_width``: index -> width
    [d] (the first bin spans ``lo`` to ``edges[1]``, the last ``edges[-2]`` to ``hi``)."""
    out = {}
    nb = len(edges) - 1
    for k, width in ((0, edges[1] - lo), (nb - 1, hi - edges[-2])):
        if width < TRUNCATED_FRACTION * bin_width:
            out[k] = round(float(width), 4)
    return out


@dataclass(frozen=True)
class DEMProfile:
    """A steady profile in the corpus format: ``columns`` (name -> array) and ``sidecar``."""

    columns: dict[str, np.ndarray]
    sidecar: dict

    def write(self, folder: str | Path, stem: str) -> tuple[Path, Path]:
        """Write ``<stem>.csv`` and ``<stem>.json`` into ``folder``."""
        out = Path(folder)
        out.mkdir(parents=True, exist_ok=True)
        names = list(self.columns)
        rows = [",".join(names)]
        for k in range(len(self.columns[names[0]])):
            rows.append(",".join(_fmt(self.columns[n][k]) for n in names))
        csv = write_text(out / f"{stem}.csv", "\n".join(rows) + "\n")
        side = write_text(out / f"{stem}.json", json.dumps(self.sidecar, indent=1) + "\n")
        return csv, side


def _fmt(v: float) -> str:
    return "" if not np.isfinite(v) else f"{v:.6g}"


def check_bin_width(bin_width: float) -> float:
    """``bin_width`` [d] if it is a whole multiple of :data:`FINE_BIN` (the bins are made of
    fine bins); else ParameterError."""
    per = bin_width / FINE_BIN if isinstance(bin_width, int | float) else math.nan
    if not (math.isfinite(per) and per >= 1.0 - 1e-9 and abs(per - round(per)) < 1e-9):
        raise ParameterError(
            f"bin_width must be a whole multiple of the fine bins' {FINE_BIN:g} d (0.25, 0.5, "
            f"1, ...); got {bin_width!r}"
        )
    return float(bin_width)


def merge_empty_bins(samples: Samples, first: int, blocks: int) -> Samples:
    """Merge each bin that has no grain centre in some block of the steady window into its
    neighbour toward the middle of the gap, until every bin has one in every block (a bin of
    0.25 d next to a wall can hold no centre, the grains' radius being about 0.5 d, nor can
    one between two layers of grains crystallised on a rough wall); the merged bin spans both.

    Raises
    ------
    InputError
        Fewer than 3 bins left.
    """
    n = samples.sums.shape[0] - first
    bounds = first + (np.arange(blocks + 1) * n) // blocks
    mass = SUMS.index("mass")
    sums = [samples.sums[:, k] for k in range(samples.sums.shape[1])]
    area = list(samples.bin_area)
    edges = list(samples.edges)
    while True:
        per_block = np.stack([[x[a:b, mass].sum() for a, b in itertools.pairwise(bounds)]
                              for x in sums])  # fmt: skip
        empty = np.flatnonzero(np.any(per_block <= 0.0, axis=1))
        if empty.size == 0:
            break
        if len(sums) <= 3:
            raise InputError(
                f"{len(sums)} bins left after merging those with no grain in a block of the "
                "steady window; a profile needs 3 that hold grains"
            )
        k = int(empty[0])
        j = k + 1 if k < (len(sums) - 1) / 2 else k - 1
        lo, hi = min(k, j), max(k, j)
        sums[lo] = sums[lo] + sums[hi]
        area[lo] += area[hi]
        del sums[hi], area[hi], edges[hi]
    if len(sums) == samples.sums.shape[1]:
        return samples
    return Samples(samples.steps, np.stack(sums, axis=1), np.array(edges), np.array(area))


def steady_profile(
    run: RunSamples, deck: Deck, *, lammps_version: str, first: int | None = None,
    blocks: int = BLOCKS, bin_width: float = BIN_WIDTH, anchor: str = "lower",
) -> DEMProfile:  # fmt: skip
    """Drop the transient, block-average the steady samples and scale them (corpus format).

    Parameters
    ----------
    run : RunSamples
        The run's fine-bin sums and series (:func:`read_samples`).
    deck : Deck
        The run's deck.
    lammps_version : str
        The LAMMPS version the sidecar names.
    first : int, optional
        Index of the first steady sample (default: :func:`window_start`, the later of MSER-5's
        truncation and :data:`MIN_TRAVEL_D` of wall travel).
    blocks : int
        Blocks of the averages' standard errors [-].
    bin_width : float
        Width of the profile's bins [d], a whole multiple of :data:`FINE_BIN` (default
        :data:`BIN_WIDTH`): the fine bins are merged (:func:`merge_bins`), a bin with no
        grain centre in a block of the window into its neighbour toward the middle of the gap
        (:func:`merge_empty_bins`; such bins are wider). The end bins' centres are midway
        between the wall and their inner edge, the stencil that of :mod:`cosserat._stencil`
        at every width; a width other than the default is recorded in
        the sidecar's ``bin_width_d``.
    anchor : {"lower", "upper"}
        The wall the bins are counted from (:func:`merge_bins`; plane and channel: lower or
        upper; Couette: inner or outer): the bins next to it are whole, the remainder of the
        gap is at the other wall. A non-default anchor is recorded in the sidecar's
        ``bins_from``.

    Raises
    ------
    ParameterError
        A bin width that is not a whole multiple of :data:`FINE_BIN`.
    InputError
        Too few steady samples for the blocks, or fewer than 3 bins that hold grains in
        every block.
    """
    bin_width = check_bin_width(bin_width)
    cell, info = deck.cell, deck.layout.info
    polar = isinstance(cell, CouetteDEM)
    three = dimension(cell) == 3
    first, window_rule = window_start(run, deck, first)
    gap_mean = float(run.gap[first:].mean())
    if polar:
        lo, hi = info["inner_radius"], info["outer_radius"]
    else:
        lo, hi = 0.0, gap_mean
    samples = merge_empty_bins(merge_bins(run.samples, lo, hi, bin_width, anchor), first, blocks)
    s = samples.centres
    s[0] = 0.5 * (lo + samples.edges[1])
    s[-1] = 0.5 * (samples.edges[-2] + hi)
    per_block = block_fields(samples, first, blocks)
    density = cell.grains.density
    truncated = truncated_bins(samples.edges, lo, hi, bin_width)
    moving_bin = {"plane": len(s) - 1, "couette": 0}.get(cell.cell)
    wall_p = block_series(run.wall_normal, first, blocks)  # the moving wall's normal stress
    # scales
    if isinstance(cell, CouetteDEM):
        V, stress = cell.wall_speed, float(run.wall_normal[first:].mean())
        if not stress > 0:
            raise InputError(
                "the grains do not press on the inner ring in the steady window (mean radial "
                f"stress {stress:g}): the Couette stress scale is undefined"
            )
    elif isinstance(cell, ChannelDEM):
        V, stress = cell.wall_speed, 1.0
    else:
        V, stress = cell.wall_speed, 1.0
    for b, f in enumerate(per_block):
        u = f["u"]
        if polar:
            f["half_vorticity"] = half_vorticity(s, u, polar=True)
            f["gamma_dot"] = s * _gradient(s, u / s)
        else:
            f["half_vorticity"] = half_vorticity(s, u)
            f["gamma_dot"] = _gradient(s, u)
        p = 0.5 * (f["sigma_tt"] + f["sigma_nn"])
        f["inertial_number"] = inertial_number(f["gamma_dot"], p, density)
        # the regime's I: a truncated bin's p is not a bulk value (TRUNCATED_FRACTION); at the
        # moving wall the wall's measured normal stress stands in, elsewhere the next bin's p
        p_regime = p.copy()
        for k in truncated:
            p_regime[k] = wall_p[b] if k == moving_bin else p[k + 1 if k == 0 else k - 1]
        f["inertial_number_regime"] = inertial_number(f["gamma_dot"], p_regime, density)
    stats = mean_and_error(per_block)
    coord = "r" if polar else "y"
    t, n = ("t", "r") if polar else ("x", "y")
    columns: dict[str, np.ndarray] = {coord: s}
    desc: dict[str, str] = {}
    vel_text = {
        "plane": "x-velocity / V (V the upper wall's speed)",
        "couette": "azimuthal velocity / V (V = Omega_i R_i, the inner ring's surface speed)",
        "channel": "downward velocity / sqrt(g d)",
    }[cell.cell]
    desc[coord] = (
        "distance from the axis [d]" if polar else "distance from the lower wall's surface [d]"
    )
    for name, key, scale, text in (
        ("u", "u", V, vel_text),
        ("omega", "omega", V, "grain spin x d / velocity scale, counter-clockwise positive"),
        ("half_vorticity", "half_vorticity", V, "half the vorticity of u, d / velocity scale"),
        ("nu", "nu", 1.0, f"solids ({'volume' if three else 'area'}) fraction"),
        (f"sigma_{t}{t}", "sigma_tt", stress, "stress along the flow / stress scale"),
        (f"sigma_{n}{n}", "sigma_nn", stress, "stress across the gap / stress scale"),
        (f"sigma_{n}{t}", "sigma_nt", stress, "flow-direction force across the gap's planes"),
        (f"sigma_{t}{n}", "sigma_tn", stress, "gap-direction force across flow-normal planes"),
        ("inertial_number", "inertial_number", 1.0, "local I = gamma_dot d / sqrt(p / rho_s)"),
    ):
        mean, se = stats[key]
        columns[name] = mean / scale
        columns[f"{name}_se"] = se / scale
        unit = "[-]" if scale == 1.0 or name.startswith("sigma") else "[velocity scale]"
        desc[name] = f"{text} {unit}"
        desc[f"{name}_se"] = f"standard error of {name} from {blocks} blocks {unit}"
    finite_I = columns["inertial_number"][np.isfinite(columns["inertial_number"])]
    I_mean = float(finite_I.mean()) if finite_I.size else None
    steps = samples.steps
    every = int(steps[1] - steps[0])
    nu_mean = float(np.average(columns["nu"], weights=samples.bin_area))
    sidecar = _sidecar(cell, deck, run, gap_mean, V, stress, I_mean, desc, lammps_version,
                       steps, first, every, blocks, nu_mean)  # fmt: skip
    regime_i = stats["inertial_number_regime"]
    extra = _regime_and_steadiness(cell, run, per_block, columns, coord, lo, hi, first, blocks,
                                   regime_i, truncated, moving_bin)  # fmt: skip
    ws = extra.pop("wall_stress_se")
    sidecar["wall_stress"].update(ws)
    sidecar.update(extra)
    sidecar["window_rule"] = window_rule
    sidecar["truncated_bins"] = _truncated_record(cell, truncated, columns, coord, lo, hi)
    series = {
        "mean_velocity": run.flow,
        "wall_shear": run.wall_shear,
        "wall_normal" if polar else "gap": run.wall_normal if polar else run.gap,
    }
    moving = {"plane": -1, "couette": 0}.get(cell.cell)
    if moving is not None:  # the spin the spin verdicts rest on: the moving wall's first bin
        series["moving_wall_spin"] = moving_bin_spin(samples, moving)
    sidecar["block_autocorrelation"] = block_autocorrelation(series, first, blocks, every)
    # the per-bin times of the stresses (referee 10, point 8) and of the spin, velocity and
    # solids fraction (referee 11, point 2: where the material barely moves, their block errors
    # may understate the scatter between runs)
    fields = sample_fields(samples, first, ("sigma_nt", "sigma_nn", "omega", "u", "nu"))
    sidecar["block_autocorrelation"]["profiles"] = profile_autocorrelation(
        {
            f"sigma_{n}{t}": fields["sigma_nt"],
            f"sigma_{n}{n}": fields["sigma_nn"],
            "omega": fields["omega"],
            "u": fields["u"],
            "nu": fields["nu"],
        },
        0,
        blocks,
    )
    sidecar["omega_half_vorticity_correlation"] = {
        "per_bin": block_correlation(
            np.stack([f["omega"] for f in per_block]),
            np.stack([f["half_vorticity"] for f in per_block]),
        ),
        "note": (
            f"per bin (the profile's rows), the correlation across the {blocks} blocks of the "
            "block means of omega and of half_vorticity: the covariance of the two columns' "
            "errors is r omega_se half_vorticity_se, so omega - half_vorticity has the variance "
            "omega_se^2 + half_vorticity_se^2 - 2 r omega_se half_vorticity_se; null where a "
            "bin's blocks do not vary"
        ),
    }
    if three:
        sidecar.update(_three_d(cell, info, run, first, blocks))
    layers = run.extra.get("layers")
    if isinstance(cell, PlaneShearDEM) and not three and isinstance(layers, LayerSamples):
        # the first layers grain by grain over the same window (referee 12, point 1)
        sidecar["first_layer"] = first_layer_record(layers, first, blocks, V)
    if bin_width != BIN_WIDTH:
        sidecar["bin_width_d"] = bin_width
    if anchor != "lower":
        sidecar["bins_from"] = anchor
    return DEMProfile(columns, sidecar)


def moving_bin_spin(samples: Samples, index: int) -> np.ndarray:
    """Per sample, the mean spin of the grains in bin ``index`` (the moving wall's first bin),
    NaN for a sample with no grain there [1 / time]."""
    k = SUMS.index("spin")
    m = samples.sums[:, index, SUMS.index("mass")]
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.where(m > 0, samples.sums[:, index, k] / m, np.nan)


def _three_d(cell, info: dict, run: RunSamples, first: int, blocks: int) -> dict:
    """Sidecar entries of a 3-D run: its dimension, depth, the walls' sheets and the
    out-of-plane stress (sigma_zz over the in-plane mean, block mean and error)."""
    ratio = block_series(run.extra["sigma_zz_ratio"], first, blocks)
    return {
        "dim": 3,
        "depth_d": info["depth"],
        "wall_sheet": (
            f"{info['wall_count']} glued spheres per wall on a triangular lattice (rows along x "
            f"at {info['wall_spacing']:.4g} d)"
        ),
        "out_of_plane_stress": {
            "sigma_zz_over_in_plane": _finite(ratio.mean()),
            "se": _finite(ratio.std(ddof=1) / math.sqrt(blocks)),
            "note": "sigma_zz / ((sigma_xx + sigma_yy) / 2) of the free grains over the whole "
            "cell (contact + kinetic about the cell's mean velocity), block mean over the "
            "steady window; the profiles' p (and so I) is the in-plane mean, as in 2-D: "
            "trace / 3 is p times (2 + this ratio) / 3",
        },
        "dimension_note": (
            "spheres in a slab periodic along x (width) and z (depth), averaged over x and z; "
            "omega is the spin about z, nu a volume fraction, stresses over the slab's "
            "volume, in units of N (force per area)"
        ),
    }


def block_series(series: np.ndarray, first: int, blocks: int) -> np.ndarray:
    """Means of a per-sample series over the ``blocks`` blocks of :func:`block_fields`."""
    n = series.size - first
    bounds = first + (np.arange(blocks + 1) * n) // blocks
    return np.array([series[a:b].mean() for a, b in itertools.pairwise(bounds)])


def _half_difference(values: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """First- and second-half means of per-block values (axis 0) and the difference's standard
    error from the spread within each half."""
    half = values.shape[0] // 2
    a, b = values[:half], values[half:]
    se = np.sqrt(a.var(axis=0, ddof=1) / a.shape[0] + b.var(axis=0, ddof=1) / b.shape[0])
    return a.mean(axis=0), b.mean(axis=0), b.mean(axis=0) - a.mean(axis=0), se


def _finite(x: float | np.ndarray) -> float | None:
    """A scalar (a float, or a 0-d mean of per-block values) as a float; None if not finite."""
    return float(x) if np.isfinite(x) else None


def steadiness(scalars: dict[str, np.ndarray], profiles: dict[str, np.ndarray]) -> dict:
    """Is the kept window steady? For each observable, the mean of the second half of the
    blocks against that of the first half, in standard errors of the difference (from the
    spread of the blocks within each half).

    Parameters
    ----------
    scalars : dict
        Per-block values of scalar observables, each of shape (blocks,).
    profiles : dict
        Per-block profiles, each of shape (blocks, bins).

    Returns
    -------
    dict
        ``observables``: per scalar ``first_half``, ``second_half``, ``z``, ``steady``
        (|z| <= :data:`STEADY_Z`); per profile ``bins_within`` (fraction of bins with
        |z| <= :data:`STEADY_Z`), ``max_abs_z``, ``steady`` (``bins_within`` >=
        :data:`STEADY_BINS`); ``steady``: every observable steady; ``test``: the rule.
    """
    out: dict[str, dict] = {}
    for name, values in scalars.items():
        a, b, diff, se = _half_difference(np.asarray(values, dtype=float))
        z = float(diff / se) if se > 0 else (0.0 if diff == 0 else math.inf)
        out[name] = {"first_half": _finite(a), "second_half": _finite(b),
                     "z": _finite(round(z, 3)), "steady": bool(abs(z) <= STEADY_Z)}  # fmt: skip
    for name, values in profiles.items():
        _, _, diff, se = _half_difference(np.asarray(values, dtype=float))
        ok = np.isfinite(diff) & np.isfinite(se) & (se > 0)
        z = diff[ok] / se[ok]
        within = float(np.mean(np.abs(z) <= STEADY_Z)) if z.size else math.nan
        out[name] = {"bins_within": _finite(round(within, 3)),
                     "max_abs_z": _finite(round(float(np.max(np.abs(z))), 3)) if z.size else None,
                     "steady": bool(within >= STEADY_BINS)}  # fmt: skip
    return {
        "test": (
            f"second half of the blocks against the first: |mean difference| <= {STEADY_Z:g} "
            "standard errors of the difference (from the blocks' spread within each half) "
            f"for a scalar, in at least {STEADY_BINS:.0%} of the bins for a profile"
        ),
        "observables": out,
        "steady": all(v["steady"] for v in out.values()),
    }


def bin_correlation(values: np.ndarray) -> float | None:
    """Lag-1 correlation of neighbouring bins' errors from per-block profiles (blocks, bins):
    the correlation across blocks of each pair of neighbouring bins' deviations from their
    means, averaged over the pairs [-]; None with fewer than two usable pairs."""
    x = np.asarray(values, dtype=float)
    dev = x - x.mean(axis=0)
    sd = x.std(axis=0, ddof=1)
    ok = np.all(np.isfinite(x), axis=0) & (sd > 0)
    pairs = ok[:-1] & ok[1:]
    if np.count_nonzero(pairs) < 2:
        return None
    z = dev / np.where(ok, sd, 1.0)
    r = np.sum(z[:, :-1] * z[:, 1:], axis=0) / (x.shape[0] - 1)
    return round(float(np.clip(np.mean(r[pairs]), -1.0, 1.0)), 4)


def _wall_names(cell) -> tuple[tuple[str, str], str | None]:
    """The walls' names (lower/upper or inner/outer, in the bins' order) and the moving one."""
    names = {"plane": ("lower", "upper"), "channel": ("lower", "upper"),
             "couette": ("inner", "outer")}[cell.cell]  # fmt: skip
    moving = {"plane": "upper", "couette": "inner", "channel": None}[cell.cell]
    return names, moving


def _wall_bins(cell, columns: dict[str, np.ndarray], coord: str, lo: float, hi: float,
               regime: tuple[np.ndarray, np.ndarray], truncated: dict[int, float],
               moving_bin: int | None) -> dict:  # fmt: skip
    """The local inertial number in the :data:`WALL_BINS` bins next to each wall (nearest
    first), their distances from the wall's surface, which wall moves, and where each bin's
    p comes from (a truncated bin's own p is not a bulk value)."""
    s = columns[coord]
    nb = len(s)
    inertial, se = regime
    k = WALL_BINS
    names, moving = _wall_names(cell)
    rec: dict = {"moving": moving, "bins": k, "limit": QUASI_STATIC_I}
    for name, where, wall in ((names[0], slice(0, k), lo), (names[1], slice(-1, -k - 1, -1), hi)):
        values = inertial[where]
        index = list(range(nb))[where]
        rec[name] = {
            "per_bin": [float(v) for v in values] if np.all(np.isfinite(values)) else [],
            "se": [_finite(v) for v in se[where]],
            "distance_d": [round(float(abs(c - wall)), 4) for c in s[where]],
            "p_source": [
                "bin"
                if j not in truncated
                else ("wall normal stress" if j == moving_bin else "next bin")
                for j in index
            ],
        }
        if any(j in truncated for j in index):
            rec[name]["per_bin_own_p"] = [_finite(v) for v in columns["inertial_number"][where]]
    rec["note"] = (
        f"local I = |gamma_dot| d / sqrt(p / rho_s) in the {k} bins next to each wall, nearest "
        "first (distance_d: bin centre from the wall's surface); p is the bin's "
        "(sigma_xx + sigma_yy) / 2 (p_source 'bin'), except in a truncated bin (truncated_bins), "
        "whose own p is not a bulk value: there p is the moving wall's measured normal stress "
        "(p_source 'wall normal stress'; per block) or, at a wall whose stress is not measured, "
        "the next bin's p ('next bin'); per_bin_own_p: the profile's inertial_number column "
        "(the bin's own p); the sidecar's quasi_static: all of the moving wall's per_bin at "
        "most limit"
    )
    return rec


def _truncated_record(cell, truncated: dict[int, float], columns: dict[str, np.ndarray],
                      coord: str, lo: float, hi: float) -> dict:  # fmt: skip
    """The sidecar's ``truncated_bins``: which end bins are narrower than
    :data:`TRUNCATED_FRACTION` of a bin, and what that means for their columns."""
    names, _ = _wall_names(cell)
    s = columns[coord]
    bins = []
    for k, width in sorted(truncated.items()):
        wall = names[0] if k == 0 else names[1]
        bins.append({
            "row": k, "wall": wall, coord: round(float(s[k]), 4), "width_d": width,
            "distance_d": round(float(abs(s[k] - (lo if k == 0 else hi))), 4),
            "nu": _finite(columns["nu"][k]),
        })  # fmt: skip
    return {
        "bins": bins,
        "fraction": TRUNCATED_FRACTION,
        "note": (
            f"end bins narrower than {TRUNCATED_FRACTION:g} of a bin (the remainder of the gap "
            "at the wall the bins are not counted from); row: the profile's row (0-based). "
            "Centre binning puts a grain's whole contact stress and area in the bin of its "
            "centre, so a truncated bin's stresses and nu are not physical bulk values (its "
            "sigma_yx breaks the momentum balance, its nu can exceed the hexagonal 0.907): "
            "the stress-ratio fits leave them out (bins within 1 d of a wall), and the "
            "regime's wall inertial number does not use their p (wall_inertial_number)"
        ),
    }


def _regime_and_steadiness(cell, run, per_block, columns, coord, lo, hi, first, blocks, regime,
                           truncated, moving_bin) -> dict:  # fmt: skip
    """Sidecar entries: ``wall_inertial_number``, ``quasi_static``, ``steadiness``,
    ``bin_correlation`` and the wall stresses' block errors."""
    walls = _wall_bins(cell, columns, coord, lo, hi, regime, truncated, moving_bin)
    moving = walls["moving"]
    near = walls[moving]["per_bin"] if moving else []
    quasi = bool(max(near) <= QUASI_STATIC_I) if near else None
    scalars = {
        "wall_shear": block_series(run.wall_shear, first, blocks),
        "wall_normal" if isinstance(cell, CouetteDEM) else "dilation": block_series(
            run.wall_normal if isinstance(cell, CouetteDEM) else run.gap, first, blocks
        ),
        "mean_velocity": block_series(run.flow, first, blocks),
    }
    stack = {k: np.stack([b[k] for b in per_block]) for k in per_block[0]}
    with np.errstate(invalid="ignore", divide="ignore"):
        stack["stress_ratio"] = np.abs(stack["sigma_nt"]) / stack["sigma_nn"]
    steady = steadiness(scalars, {"u_profile": stack["u"], "spin_profile": stack["omega"]})
    t, n = ("t", "r") if isinstance(cell, CouetteDEM) else ("x", "y")
    names = {"u": "u", "omega": "omega", "nu": "nu", "stress_ratio": "stress_ratio",
             "sigma_tt": f"sigma_{t}{t}", "sigma_nn": f"sigma_{n}{n}",
             "sigma_nt": f"sigma_{n}{t}", "sigma_tn": f"sigma_{t}{n}"}  # fmt: skip
    correlation = {out: bin_correlation(stack[key]) for key, out in names.items()}
    sqrt_b = math.sqrt(blocks)
    return {
        "wall_inertial_number": walls,
        "quasi_static": quasi,
        "steadiness": steady,
        "bin_correlation": {k: v for k, v in correlation.items() if v is not None},
        "bin_correlation_note": (
            "lag-1 correlation of neighbouring bins' errors, from the blocks' deviations "
            "(correlation across blocks of each neighbouring pair, averaged over the pairs); "
            "stress_ratio is |sigma_yx| / sigma_yy (couette |sigma_rt| / sigma_rr) per block"
        ),
        "wall_stress_se": {
            "normal_se": float(block_series(run.wall_normal, first, blocks).std(ddof=1) / sqrt_b),
            "shear_se": float(scalars["wall_shear"].std(ddof=1) / sqrt_b),
        },
    }


def _sidecar(cell, deck, run, gap_mean, V, stress, I_mean, desc, version, steps, first, every,
             blocks, nu_mean) -> dict:  # fmt: skip
    plane = isinstance(cell, PlaneShearDEM)
    channel = isinstance(cell, ChannelDEM)
    nu_bulk = cell.nu_nominal if not isinstance(cell, CouetteDEM) else cell.nu_fill
    if plane:
        gravity = cell.gravity / V**2
        gnote = (
            f"g d / V^2 with g = {cell.gravity:.6g} N/(rho_s d) along -y; B = rho_s nu g H / N "
            f"with the nominal nu = {nu_bulk:g} and the nominal H = {cell.gap:g} d"
        )
    elif channel:
        gravity = cell.shear_ratio
        gnote = (
            f"rho_s nu g H / (2 N) with the nominal nu = {nu_bulk:g} and H = {cell.gap:g} d; "
            f"g = {cell.gravity:.6g} N/(rho_s d) along +x (the deck's downward direction)"
        )
    else:
        gravity, gnote = 0.0, "no gravity (a horizontal annulus)"
    scale_v = {
        "plane": f"V = {V:.6g} sqrt(N/rho_s), the upper wall's speed",
        "couette": f"V = Omega_i R_i = {V:.6g} sqrt(N/rho_s), the inner ring's surface speed",
        "channel": f"sqrt(g d) = {V:.6g} sqrt(N/rho_s)",
    }[cell.cell]
    scale_s = {
        "plane": "N, the normal stress applied on the upper wall (N = 1 in the deck)",
        "couette": f"the mean radial stress on the inner ring, {stress:.6g} N",
        "channel": "N, the normal stress applied on the wall at y = H (N = 1 in the deck)",
    }[cell.cell]
    return {
        "format": FORMAT,
        "cell": cell.cell,
        "gap_d": round(gap_mean, 4),
        "Ri_d": cell.inner_radius if isinstance(cell, CouetteDEM) else None,
        "gravity": gravity,
        "gravity_note": gnote,
        "B": (cell.grains.density * nu_mean * cell.gravity * gap_mean) if plane else 0.0,
        "B_note": "rho_s nu g H / N with the measured mean solids fraction and gap; the deck "
        f"set g from the nominal B = {cell.B:g} (nu = {nu_bulk:g}, H = {cell.gap:g} d)"
        if plane
        else "no gravity across the gap",
        **_walls_meta(cell),
        "grains": cell.grains.describe(run.n_free),
        "contact": cell.contact.describe(),
        "seed": cell.seed,
        "lammps_version": version,
        "deck_sha256": deck.sha256,
        "steps": int(steps[-1]),
        "settle_steps": cell.run.settle_steps,
        "timestep": deck.timestep,
        "dump_every": every,
        "steady_window": [int(steps[first]), int(steps[-1])],
        "dropped_steps": int(steps[first] - steps[0]),
        "blocks": blocks,
        "wall_speed": V,
        "velocity_scale": scale_v,
        "stress_scale": scale_s,
        "inertial_number": I_mean,
        "wall_stress": {
            "normal": float(run.wall_normal[first:].mean()),
            "shear": float(run.wall_shear[first:].mean()),
            "note": "on the moving (plane), inner (couette) or free (channel) wall, from its "
            "contacts, in units of N; shear: force along the flow on the wall / length",
        },
        "moving_wall_speed": float(run.wall_speed_measured[first:].mean()),
        "steady_drift": drift(run.flow[first:]) / (V if V else 1.0),
        "sign_convention": (
            "x (or the azimuth t) along the flow, y (or r) across the gap; spin and "
            "vorticity counter-clockwise positive in the deck's (x, y) plane; stresses "
            "compressive positive, sigma_ij = (1/A)[sum m dv_i dv_j - sum_c l_i f_j], i the "
            "normal of the plane (the direction from a grain's centre to its contact), j the "
            "force component: the shear stress carried across the gap is sigma_yx (sigma_rt); "
            "it is negative when the upper wall drags the grains along +x (plane) and positive "
            "when the inner ring drags them along +t (couette)"
        ),
        "columns": desc,
        "source": "DEM",
    }


def _walls_meta(cell) -> dict:
    """``wall``: the moving wall (plane: upper; Couette: inner) or both; walls of two kinds add
    ``wall_fixed`` (the calibration's and validate's key for the fixed wall) and ``walls``
    (each wall by its position)."""
    out = {"wall": cell.wall.describe(cell.contact)}
    if getattr(cell, "walls_differ", False):
        lower, upper = cell.walls
        names = ("lower", "upper") if isinstance(cell, PlaneShearDEM) else ("inner", "outer")
        moving, fixed = (upper, lower) if isinstance(cell, PlaneShearDEM) else (lower, upper)
        out["wall"] = moving.describe(cell.contact)
        out["wall_fixed"] = fixed.describe(cell.contact)
        out["walls"] = {
            names[0]: lower.describe(cell.contact),
            names[1]: upper.describe(cell.contact),
        }
    return out


__all__ = ["FORMAT", "MIN_TRAVEL_D", "SUMS", "TRUNCATED_FRACTION", "DEMProfile",
           "check_bin_width", "merge_empty_bins", "read_samples", "steady_profile",
           "truncated_bins", "window_start"]  # fmt: skip
