"""Initial grain and wall positions of the DEM cells (NumPy only).

Walls are rows of glued disks (type 2: the lower or inner wall, type 3: the upper or outer
wall); the free grains (type 1) start on a triangular lattice, loose enough that no two overlap,
and are compacted by the deck (settling under the wall load, or growing in place).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import ParameterError
from .params import ChannelDEM, CouetteDEM, PlaneShearDEM, WallRoughness

FREE, LOWER_WALL, UPPER_WALL = 1, 2, 3
LATTICE_MARGIN = 1.02
"""Triangular-lattice spacing over the largest diameter at the start [-]."""


@dataclass(frozen=True)
class Layout:
    """Initial positions: ``x``, ``y`` [d], diameters ``diameter`` [d], ``kind`` (1, 2, 3), the
    box, and the geometric facts the deck and the coarse-graining need."""

    x: np.ndarray
    y: np.ndarray
    diameter: np.ndarray
    kind: np.ndarray
    box: tuple[float, float, float, float]
    info: dict
    z: np.ndarray | None = None
    """3-D cells: the coordinate along the periodic depth [d] (``info["depth"]``); None in 2-D."""

    @property
    def n_free(self) -> int:
        return int(np.count_nonzero(self.kind == FREE))


def _diameters(rng: np.random.Generator, n: int, polydispersity: float) -> np.ndarray:
    return rng.uniform(1.0 - polydispersity, 1.0 + polydispersity, n)


def _walls(cell: PlaneShearDEM | ChannelDEM | CouetteDEM) -> tuple[WallRoughness, WallRoughness]:
    """The (lower or inner, upper or outer) walls of a cell (the channel has one kind)."""
    return cell.walls if hasattr(cell, "walls") else (cell.wall, cell.wall)


def _wall_row(length: float, spacing: float) -> tuple[int, float]:
    n = max(3, round(length / spacing))
    return n, length / n


def planar_layout(cell: PlaneShearDEM | ChannelDEM) -> Layout:
    """Walls along x at y = 0 (centres of the lower row) and above; free grains between.

    The lower wall's surface (top of its disks) is at y = dw / 2: the profiles' y = 0.
    """
    rng = np.random.default_rng(cell.seed)
    length = cell.width if isinstance(cell, PlaneShearDEM) else cell.length
    low, up = _walls(cell)
    dw, dwu = low.glued_diameter, up.glued_diameter
    n_wall, s = _wall_row(length, low.glued_spacing)
    n_up, s_up = _wall_row(length, up.glued_spacing)
    n_free = round(cell.nu_nominal * length * cell.gap / cell.grains.mean_area)
    a = cell.grains.d_max * LATTICE_MARGIN
    per_row = math.floor(length / a)
    if per_row < 2:
        raise ParameterError(f"the cell is narrower than two grains ({length:g} d)")
    dx = length / per_row
    rows = math.ceil(n_free / per_row)
    dy = a * math.sqrt(3.0) / 2.0
    y0 = dw / 2.0 + a / 2.0 + 0.02
    sites_y = y0 + dy * np.arange(rows)
    xs, ys = [], []
    for k, yk in enumerate(sites_y):
        xs.append((np.arange(per_row) + 0.5 * (k % 2)) * dx)
        ys.append(np.full(per_row, yk))
    x = np.concatenate(xs)[:n_free]
    y = np.concatenate(ys)[:n_free]
    d = _diameters(rng, n_free, cell.grains.polydispersity)
    y_top = sites_y[-1] + a / 2.0 + dwu / 2.0 + 0.02
    shift = rng.uniform(0.0, s_up)
    wx = np.arange(n_wall) * s
    all_x = np.concatenate([x, wx, (np.arange(n_up) * s_up + shift) % length])
    all_y = np.concatenate([y, np.zeros(n_wall), np.full(n_up, y_top)])
    all_d = np.concatenate([d, np.full(n_wall, dw), np.full(n_up, dwu)])
    kind = np.concatenate(
        [np.full(n_free, FREE), np.full(n_wall, LOWER_WALL), np.full(n_up, UPPER_WALL)]
    )
    box = (0.0, length, -dw, y_top + dwu)
    info = {
        "length": length,
        "wall_count": n_up,
        "wall_spacing": s_up,
        "surface_offset": dw / 2.0,
        # (one wall diameter: the expression of one wall kind, to the last bit)
        "initial_gap": y_top - dw if dw == dwu else y_top - dwu / 2.0 - dw / 2.0,
    }
    if getattr(cell, "walls_differ", False):
        # walls of two kinds: the lower wall's own row, and the upper wall's surface below its
        # centres (a single wall kind has one offset)
        info.update(lower_wall_count=n_wall, lower_wall_spacing=s, upper_offset=dwu / 2.0)
    return Layout(all_x, all_y, all_d, kind, box, info)


def _wall_sheet(width: float, depth: float, spacing: float) -> tuple[np.ndarray, np.ndarray, float]:
    """Centres (x, z) of a triangular sheet of glued spheres filling a periodic width x depth:
    rows along x of spacing about ``spacing``, an even number of rows along z (each shifted by
    half a spacing from the last) about ``spacing`` sqrt(3)/2 apart; returns x, z and the
    spacing along x."""
    nx, sx = _wall_row(width, spacing)
    nz = max(2, 2 * round(depth / (spacing * math.sqrt(3.0))))
    sz = depth / nz
    xs = [(np.arange(nx) + 0.5 * (k % 2)) * sx for k in range(nz)]
    zs = [np.full(nx, k * sz) for k in range(nz)]
    return np.concatenate(xs), np.concatenate(zs), sx


def planar_layout_3d(cell: PlaneShearDEM) -> Layout:
    """Spheres between two sheets of glued spheres (:func:`_wall_sheet`) at y = 0 (centres of
    the lower sheet) and above; periodic along x (``width``) and z (``depth``).

    The free grains start on a loose lattice of square layers (spacing at least 1.02 of the
    largest diameter) stacked with a shift of half a spacing along x and z, as in a face-centred
    cubic packing; the lower wall's surface (top of its spheres) is at y = dw / 2: the
    profiles' y = 0.
    """
    rng = np.random.default_rng(cell.seed)
    width, depth = cell.width, cell.depth
    dw = cell.wall.glued_diameter
    wx, wz, s = _wall_sheet(width, depth, cell.wall.glued_spacing)
    n_wall = wx.size
    n_free = round(cell.nu_nominal * width * depth * cell.gap / cell.grains.mean_volume)
    a = cell.grains.d_max * LATTICE_MARGIN
    nx, nz = math.floor(width / a), math.floor(depth / a)
    if min(nx, nz) < 2:
        raise ParameterError(f"the cell is narrower than two grains ({width:g} d x {depth:g} d)")
    dx, dz = width / nx, depth / nz
    dy = max(math.sqrt(max(a * a - 0.25 * (dx * dx + dz * dz), 0.0)), 0.5 * a)
    layers = math.ceil(n_free / (nx * nz))
    y0 = dw / 2.0 + a / 2.0 + 0.02
    sites_y = y0 + dy * np.arange(layers)
    ii, kk = np.meshgrid(np.arange(nx), np.arange(nz), indexing="ij")
    xs, ys, zs = [], [], []
    for k, yk in enumerate(sites_y):
        xs.append(((ii + 0.5 * (k % 2)) * dx).ravel())
        zs.append(((kk + 0.5 * (k % 2)) * dz).ravel())
        ys.append(np.full(nx * nz, yk))
    x = np.concatenate(xs)[:n_free]
    y = np.concatenate(ys)[:n_free]
    z = np.concatenate(zs)[:n_free]
    d = _diameters(rng, n_free, cell.grains.polydispersity)
    y_top = sites_y[-1] + a / 2.0 + dw / 2.0 + 0.02
    shift_x, shift_z = rng.uniform(0.0, s), rng.uniform(0.0, depth)
    all_x = np.concatenate([x, wx, (wx + shift_x) % width])
    all_y = np.concatenate([y, np.zeros(n_wall), np.full(n_wall, y_top)])
    all_z = np.concatenate([z, wz, (wz + shift_z) % depth])
    all_d = np.concatenate([d, np.full(2 * n_wall, dw)])
    kind = np.concatenate(
        [np.full(n_free, FREE), np.full(n_wall, LOWER_WALL), np.full(n_wall, UPPER_WALL)]
    )
    box = (0.0, width, -dw, y_top + dw)
    info = {
        "length": width,
        "depth": depth,
        "wall_area": width * depth,
        "wall_count": n_wall,
        "wall_spacing": s,
        "surface_offset": dw / 2.0,
        "initial_gap": y_top - dw,
    }
    return Layout(all_x, all_y, all_d, kind, box, info, z=all_z)


def annular_layout(cell: CouetteDEM) -> Layout:
    """Rings centred on the origin; free grains on a lattice inside the annulus, shrunk by the
    factor ``info["shrink"]`` (the deck grows them back to their diameters)."""
    rng = np.random.default_rng(cell.seed)
    walls = _walls(cell)
    dw, dwo = walls[0].glued_diameter, walls[1].glued_diameter
    ri, ro = cell.inner_radius, cell.inner_radius + cell.gap
    area = math.pi * (ro**2 - ri**2)
    n_free = round(cell.nu_fill * area / cell.grains.mean_area)
    rows = []
    for radius, wall_kind, wall in (
        (ri - dw / 2.0, LOWER_WALL, walls[0]),
        (ro + dwo / 2.0, UPPER_WALL, walls[1]),
    ):
        n_wall, _ = _wall_row(2.0 * math.pi * radius, wall.glued_spacing)
        t = 2.0 * math.pi * (np.arange(n_wall) + rng.uniform()) / n_wall
        rows.append((radius * np.cos(t), radius * np.sin(t), np.full(n_wall, wall_kind)))
    # lattice spacing a0 such that the annulus (less a margin) holds 10% more sites than grains
    usable = math.pi * ((ro - 0.5) ** 2 - (ri + 0.5) ** 2)
    a0 = math.sqrt(usable / (1.1 * n_free * math.sqrt(3) / 2))
    shrink = min(1.0, a0 / (cell.grains.d_max * LATTICE_MARGIN))
    half = ro + 1.0
    nx = math.ceil(2 * half / a0) + 1
    ny = math.ceil(2 * half / (a0 * math.sqrt(3) / 2)) + 1
    jj, ii = np.meshgrid(np.arange(ny), np.arange(nx), indexing="ij")
    px = (-half + (ii + 0.5 * (jj % 2)) * a0).ravel()
    py = (-half + jj * a0 * math.sqrt(3) / 2).ravel()
    pr = np.hypot(px, py)
    margin = 0.5 * cell.grains.d_max * shrink + 0.02
    inside = (pr > ri + margin) & (pr < ro - margin)
    px, py = px[inside], py[inside]
    if px.size < n_free:
        raise ParameterError(
            f"nu_fill {cell.nu_fill:g} leaves no room to place {n_free} grains in the annulus"
        )
    pick = np.sort(rng.choice(px.size, n_free, replace=False))
    d = _diameters(rng, n_free, cell.grains.polydispersity)
    x = np.concatenate([px[pick], rows[0][0], rows[1][0]])
    y = np.concatenate([py[pick], rows[0][1], rows[1][1]])
    diam = np.concatenate([d * shrink, np.full(rows[0][0].size, dw), np.full(rows[1][0].size, dwo)])
    kind = np.concatenate([np.full(n_free, FREE), rows[0][2], rows[1][2]])
    edge = ro + dwo + 1.0
    box = (-edge, edge, -edge, edge)
    info = {
        "shrink": shrink,
        "inner_radius": ri,
        "outer_radius": ro,
        "wall_count": [int(rows[0][0].size), int(rows[1][0].size)],
        "surface_offset": dw / 2.0,
    }
    return Layout(x, y, diam, kind, box, info)
