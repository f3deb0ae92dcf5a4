"""The first layers of grains at a plane cell's wall, grain by grain (no bins).

A layer is the free grains whose centres lie within one diameter band of a wall's surface:
layer 1 at a distance in [0, 1) d, layer 2 in [1, 2) d. Per sample :func:`layer_sums` keeps,
per wall and layer, the sums of :data:`LAYER_SUMS`; :func:`read_layers` reads them from a
run's ``atoms.dump`` with the walls' velocities; :func:`layer_blocks` makes block means
(ratio estimators over the block's samples, as :func:`cosserat.dem.coarse.block_fields`) and
:func:`layer_measures` turns one set of layer means into the measures of the first layer's
spin against half the vorticity:

* ``omega_1``, ``u_1``, ``u_2``, ``d_1``, ``d_2``: the layers' mass-weighted mean spin, velocity
  along the flow and distance of the centres from the wall's surface; ``u_wall`` the wall's
  mean velocity;
* three layer-scale half vorticities W = -(1/2) du/dy, each a difference across one layer:
  ``W_layers`` between the layers' means, -(s/2) (u_2 - u_1) / (d_2 - d_1) (the grains only,
  the analysis' one-sided stencil at grain scale); ``W_wall_second`` from the wall to layer 2,
  -(s/2) (u_2 - u_wall) / d_2 (centred near layer 1, the 'wall' stencil); ``W_wall_first``
  from the wall to layer 1, -(s/2) (u_1 - u_wall) / d_1 (the 'wall-first' stencil); s = +1 at
  the lower wall (the distance is y), -1 at the upper (the distance is H - y);
* ``omega_roll``: the spin of a layer-1 grain of the layer's mean radius rolling on the wall
  without sliding, s (u_wall - u_1) / r_1, and ``rolling`` = omega_1 / omega_roll;
* ``departure_<W>`` = omega_1 - W for each W.

Spins are counter-clockwise positive in the deck's (x, y) plane, as the run's profiles.
Block errors of a departure come from its per-block values, so the correlation of omega_1
and W (the same grains, the same blocks) is in them.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..errors import InputError, ParameterError
from .coarse import block_ranges
from .decks import Deck, dimension
from .dumps import iter_dump
from .geometry import FREE, LOWER_WALL, UPPER_WALL
from .params import MIN_SAMPLES, PlaneShearDEM

LAYER_SUMS = ("mass", "mom", "spin", "m_dist", "count", "radius")
"""Per wall and layer sums of one sample: mass, mass x velocity along the flow, mass x spin,
mass x distance from the wall's surface, grain count, sum of the radii."""
LAYERS = 2
"""Layers kept per wall."""
WALLS = ("lower", "upper")
WALL_SIGN = {"lower": 1.0, "upper": -1.0}
"""d(distance)/dy at each wall [-]."""
HALF_VORTICITIES = ("W_layers", "W_wall_second", "W_wall_first")


def layer_sums(
    distance: np.ndarray, vt: np.ndarray, omega: np.ndarray, mass: np.ndarray,
    radius: np.ndarray, layers: int = LAYERS,
) -> np.ndarray:  # fmt: skip
    """Sums of :data:`LAYER_SUMS` over the grains in each layer (distance in [k, k + 1) d),
    shape (layers, len(LAYER_SUMS)); grains farther than ``layers`` d are not counted.

    Parameters
    ----------
    distance : ndarray
        Distance of each grain's centre from the wall's surface [d] (inside the gap >= 0).
    vt, omega, mass, radius : ndarray
        Velocity along the flow [velocity], spin [1 / time], mass [rho_s d^2], radius [d].
    layers : int
        Number of layers [-].
    """
    distance = np.asarray(distance, dtype=float)
    k = np.floor(distance).astype(np.int64)
    keep = (distance >= 0.0) & (k < layers)
    k, m = k[keep], np.asarray(mass, dtype=float)[keep]
    cols = (m, m * vt[keep], m * omega[keep], m * distance[keep], np.ones_like(m),
            np.asarray(radius, dtype=float)[keep])  # fmt: skip
    return np.stack([np.bincount(k, weights=c, minlength=layers) for c in cols], axis=1)


def sample_layers(
    atoms: np.ndarray, info: dict, density: float, layers: int = LAYERS
) -> tuple[np.ndarray, list[float]]:
    """One sample's layer sums at both walls, shape (2 walls (lower, upper), layers,
    len(LAYER_SUMS)), and the walls' mean velocity along the flow [velocity], from the rows
    of a 2-D plane cell's ``atoms.dump`` (:data:`~cosserat.dem.decks.ATOM_COLUMNS`) and its
    layout's ``info`` (the walls' surface offsets) [simulation units]."""
    off = info["surface_offset"]
    top = off + info["upper_offset"] if "upper_offset" in info else 2.0 * off
    kind = atoms[:, 1].astype(int)
    free = kind == FREE
    upper, lower = kind == UPPER_WALL, kind == LOWER_WALL
    rad, y, vx, om = atoms[:, 2], atoms[:, 4], atoms[:, 5], atoms[:, 7]
    gap = y[upper].mean() - top
    s = y[free] - off
    mass = density * math.pi * rad[free] ** 2
    per = [layer_sums(d, vx[free], om[free], mass, rad[free], layers) for d in (s, gap - s)]
    return np.stack(per), [float(vx[lower].mean()) if lower.any() else 0.0,
                           float(vx[upper].mean())]  # fmt: skip


@dataclass(frozen=True)
class LayerSamples:
    """Per-sample layer sums of a run: ``sums`` of shape (samples, 2 walls (lower, upper),
    layers, len(LAYER_SUMS)), the walls' mean velocity along the flow ``u_wall`` (samples, 2)
    [velocity] and the ``steps``."""

    steps: np.ndarray
    sums: np.ndarray
    u_wall: np.ndarray


def read_layers(folder: str | Path, deck: Deck, layers: int = LAYERS) -> LayerSamples:
    """Read the layer sums of every sample of a finished plane run's ``atoms.dump``.

    Raises
    ------
    InputError
        Not a 2-D plane cell, a missing dump, or fewer than MIN_SAMPLES samples.
    """
    cell, info = deck.cell, deck.layout.info
    if not isinstance(cell, PlaneShearDEM) or dimension(cell) != 2:
        raise InputError(f"{folder}: the layer measure is for 2-D plane cells; got {cell.cell}")
    path = Path(folder) / "atoms.dump"
    if not path.is_file():
        raise InputError(f"{path} is missing: did the run keep its dumps?")
    steps, sums, u_wall = [], [], []
    for step, atoms in iter_dump(path):
        one, walls = sample_layers(atoms, info, cell.grains.density, layers)
        steps.append(step)
        sums.append(one)
        u_wall.append(walls)
    if len(steps) < MIN_SAMPLES:
        raise InputError(f"{path}: {len(steps)} samples; at least {MIN_SAMPLES} are needed")
    return LayerSamples(np.array(steps), np.array(sums), np.array(u_wall))


def layer_blocks(layers: LayerSamples, first: int, blocks: int) -> list[dict[str, np.ndarray]]:
    """Per block (contiguous samples from index ``first``): each wall's layer means ``u``,
    ``omega``, ``d`` (distance), ``r`` (mean radius), each of shape (2 walls, layers), and
    ``u_wall`` (2,) [simulation units].

    Raises
    ------
    ParameterError
        Fewer than 2 blocks.
    InputError
        Fewer steady samples than blocks, or a layer with no grain in a block.
    """
    out = []
    for a, b in block_ranges(layers.sums.shape[0], first, blocks):
        t = layers.sums[a:b].sum(axis=0)
        S = {name: t[..., k] for k, name in enumerate(LAYER_SUMS)}
        if np.any(S["count"] == 0):
            raise InputError(f"a layer has no grain in the samples {a}-{b - 1}")
        out.append({"u": S["mom"] / S["mass"], "omega": S["spin"] / S["mass"],
                    "d": S["m_dist"] / S["mass"], "r": S["radius"] / S["count"],
                    "u_wall": layers.u_wall[a:b].mean(axis=0)})  # fmt: skip
    return out


def layer_measures(
    wall: str, u_wall: float, u_1: float, u_2: float, d_1: float, d_2: float, omega_1: float,
    r_1: float,
) -> dict[str, float]:  # fmt: skip
    """The first layer's measures of the module docstring from one set of layer means.

    Parameters
    ----------
    wall : {"lower", "upper"}
        Which wall the distances are from.
    u_wall, u_1, u_2 : float
        The wall's and the layers' velocity along the flow [velocity].
    d_1, d_2 : float
        The layers' mean distance from the wall's surface, 0 < d_1 < d_2 [d].
    omega_1 : float
        Layer 1's mean spin, counter-clockwise positive [velocity / d].
    r_1 : float
        Layer 1's mean radius [d].

    Returns
    -------
    dict
        ``omega_1``, ``u_1``, ``u_2``, ``u_wall``, ``d_1``, ``d_2``, each W of
        :data:`HALF_VORTICITIES`, ``departure_<W>``, ``omega_roll`` and ``rolling``
        [velocity / d, velocity, d, -].

    Raises
    ------
    ParameterError
        An unknown wall, or distances not 0 < d_1 < d_2.
    """
    if wall not in WALL_SIGN:
        raise ParameterError(f"wall must be one of {', '.join(WALLS)}; got {wall!r}")
    if not 0.0 < d_1 < d_2:
        raise ParameterError(f"the layers' distances must satisfy 0 < d_1 < d_2; got {d_1}, {d_2}")
    s = WALL_SIGN[wall]
    out = {"omega_1": omega_1, "u_1": u_1, "u_2": u_2, "u_wall": u_wall, "d_1": d_1, "d_2": d_2}
    out["W_layers"] = -0.5 * s * (u_2 - u_1) / (d_2 - d_1)
    out["W_wall_second"] = -0.5 * s * (u_2 - u_wall) / d_2
    out["W_wall_first"] = -0.5 * s * (u_1 - u_wall) / d_1
    for w in HALF_VORTICITIES:
        out[f"departure_{w}"] = omega_1 - out[w]
    out["omega_roll"] = s * (u_wall - u_1) / r_1
    out["rolling"] = omega_1 / out["omega_roll"] if out["omega_roll"] != 0.0 else math.nan
    return {k: float(v) for k, v in out.items()}


def first_layer(
    layers: LayerSamples, first: int, blocks: int, wall: str, scale: float
) -> dict[str, tuple[float, float]]:
    """The measures of :func:`layer_measures` at ``wall`` as (block mean, standard error
    std(ddof=1) / sqrt(blocks)), velocities over ``scale`` (the cell's V; d = 1): u [-],
    spins and half vorticities [V/d], distances [d], ``rolling`` [-].

    Raises
    ------
    ParameterError
        An unknown wall or a scale that is not positive.
    """
    if wall not in WALL_SIGN:
        raise ParameterError(f"wall must be one of {', '.join(WALLS)}; got {wall!r}")
    if not scale > 0.0:
        raise ParameterError(f"scale (the velocity scale) must be > 0; got {scale}")
    k = WALLS.index(wall)
    per = []
    for b in layer_blocks(layers, first, blocks):
        u, om, d = b["u"][k] / scale, b["omega"][k] / scale, b["d"][k]
        per.append(layer_measures(wall, float(b["u_wall"][k] / scale), u[0], u[1], d[0], d[1],
                                  om[0], float(b["r"][k][0])))  # fmt: skip
    out = {}
    for name in per[0]:
        v = np.array([p[name] for p in per])
        out[name] = (float(v.mean()), float(v.std(ddof=1) / math.sqrt(v.size)))
    return out


SHEARED_SLIP = 0.05
"""A fixed wall shears (its record is kept) where layer 1 moves relative to it by at least
this fraction of the moving wall's speed, |u_1 - u_wall| >= 0.05 V [-]: the spin verdict's
rule for a sheared wall (its first bin against the wall), at grain scale."""
RECORD_NOTE = (
    "the first layers of grains at each wall that shears (the moving wall, and a fixed wall "
    "where layer 1 moves relative to it by |u_1 - u_wall| >= 0.05 V), grain by grain, no bins "
    "(cosserat.dem.first_layer): layer 1 the free grains whose centres lie within [0, 1) d of "
    "the wall's surface, layer 2 within [1, 2) d; over the profile's steady window and blocks, "
    "each measure the mean of its per-block values with '<name>_se' = std(ddof=1)/sqrt(blocks) "
    "(so omega_1 and W's correlation is in a departure's se): u_wall, u_1, u_2 velocities "
    "along the flow / V; d_1, d_2 the layers' mass-weighted mean distance of the centres from "
    "the wall's surface [d]; omega_1 layer 1's mass-weighted mean spin [V/d], "
    "counter-clockwise positive as the profile's omega; three half vorticities W = -(1/2) "
    "du/dy across one layer: W_layers = -(s/2)(u_2 - u_1)/(d_2 - d_1), W_wall_second = "
    "-(s/2)(u_2 - u_wall)/d_2 (the wall-to-layer-2 chord, centred near layer 1), W_wall_first "
    "= -(s/2)(u_1 - u_wall)/d_1, s = +1 at the lower wall, -1 at the upper; departure_<W> = "
    "omega_1 - W; omega_roll = s (u_wall - u_1)/r_1 (a layer-1 grain rolling on the wall "
    "without sliding) and rolling = omega_1/omega_roll; r_1 layer 1's mean radius over the "
    "window [d]; grains_1, grains_2 the mean number of grains in each layer per sample"
)
"""The sidecar's ``first_layer.note``."""


def first_layer_record(
    layers: LayerSamples, first: int, blocks: int, scale: float, moving: str = "upper"
) -> dict:
    """The sidecar's ``first_layer`` record (:data:`RECORD_NOTE`): per wall that shears, the
    measures of :func:`first_layer` over the samples from ``first`` in ``blocks`` blocks,
    velocities over ``scale`` (V), each as ``<name>`` and ``<name>_se``, with ``moving``,
    ``r_1`` [d], ``grains_1`` and ``grains_2`` [-].

    Raises
    ------
    ParameterError
        An unknown ``moving`` wall (see also :func:`first_layer`).
    """
    if moving not in WALL_SIGN:
        raise ParameterError(f"moving must be one of {', '.join(WALLS)}; got {moving!r}")
    count, radius = LAYER_SUMS.index("count"), LAYER_SUMS.index("radius")
    walls = {}
    for k, wall in enumerate(WALLS):
        m = first_layer(layers, first, blocks, wall, scale)
        if wall != moving and abs(m["u_1"][0] - m["u_wall"][0]) < SHEARED_SLIP:
            continue
        kept = layers.sums[first:, k]
        row: dict = {"moving": wall == moving}
        for name, (v, se) in m.items():
            row[name] = _finite(v)
            row[f"{name}_se"] = _finite(se)
        row["r_1"] = float(kept[:, 0, radius].sum() / kept[:, 0, count].sum())
        row["grains_1"] = float(kept[:, 0, count].mean())
        row["grains_2"] = float(kept[:, 1, count].mean())
        walls[wall] = row
    return {"walls": walls, "blocks": int(blocks), "note": RECORD_NOTE}


def _finite(x: float) -> float | None:
    """``x``, or None where it is not finite (JSON has no NaN)."""
    return float(x) if math.isfinite(x) else None


__all__ = [
    "LAYER_SUMS",
    "SHEARED_SLIP",
    "LayerSamples",
    "first_layer",
    "first_layer_record",
    "layer_blocks",
    "layer_measures",
    "layer_sums",
    "read_layers",
    "sample_layers",
]  # fmt: skip
