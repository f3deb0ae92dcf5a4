"""LAMMPS input decks for the DEM cells (2-D disks, ``atom_style sphere``, ``dimension 2``).

A deck is two files: ``deck.lmp`` (the commands) and ``grains.data`` (the initial positions,
read by ``read_data``); the deck names the data file's sha256, so the deck's own sha256
(:attr:`Deck.sha256`) identifies both. The same deck runs unchanged with ``lmp -in deck.lmp``
or ``mpirun -np N lmp -in deck.lmp``. It writes, every ``dump_every`` steps of the sheared
stage, ``atoms.dump`` (id, type, radius, position, velocity, spin) and ``contacts.dump`` (the
two atom ids, the normal and tangential contact force on the first, and the vector from the
second's centre to the first's).
"""

from __future__ import annotations

import hashlib
import math
from dataclasses import dataclass
from pathlib import Path

from .._atomic import write_text
from .geometry import FREE, LOWER_WALL, UPPER_WALL, Layout, annular_layout, planar_layout
from .params import Cell, ChannelDEM, CouetteDEM, PlaneShearDEM

ATOM_COLUMNS = ("id", "type", "radius", "x", "y", "vx", "vy", "omegaz")
CONTACT_COLUMNS = ("i", "j", "fnx", "fny", "ftx", "fty", "dx", "dy")
"""Contact dump: ids i, j; normal and tangential force on i [N d]; x_i - x_j [d]."""
SETTLE_DAMPING = 0.1
"""Viscous damping of the free grains while they settle or grow [rho_s d sqrt(N/rho_s)]."""


@dataclass(frozen=True)
class Deck:
    """A deck's text, its data file and what the coarse-graining needs to know."""

    cell: Cell
    text: str
    data: str
    layout: Layout
    timestep: float

    @property
    def sha256(self) -> str:
        """sha256 of the deck text (which holds the data file's sha256) [hex]."""
        return hashlib.sha256(self.text.encode()).hexdigest()

    def write(self, folder: str | Path) -> Path:
        """Write ``deck.lmp``, ``grains.data`` and ``job.sh`` into ``folder``; returns the deck."""
        out = Path(folder)
        out.mkdir(parents=True, exist_ok=True)
        write_text(out / "grains.data", self.data)
        write_text(out / "job.sh", job_script())
        return write_text(out / "deck.lmp", self.text)


def job_script() -> str:
    """A shell job script for a user's own MPI build of LAMMPS (edit NP and LMP)."""
    return (
        "#!/bin/sh\n"
        "# Run this deck with your own LAMMPS build (needs the GRANULAR package):\n"
        "#   NP=64 LMP=lmp_mpi sh job.sh      (or submit it from a batch script)\n"
        'cd "$(dirname "$0")"\n'
        'mpirun -np "${NP:-4}" "${LMP:-lmp}" -in deck.lmp -log log.lammps\n'
    )


def _data_file(layout: Layout, density: float) -> str:
    xlo, xhi, ylo, yhi = layout.box
    lines = [
        "cosserat.dem initial positions",
        "",
        f"{layout.x.size} atoms",
        "3 atom types",
        "",
        f"{xlo:.10g} {xhi:.10g} xlo xhi",
        f"{ylo:.10g} {yhi:.10g} ylo yhi",
        "-0.5 0.5 zlo zhi",
        "",
        "Atoms # sphere",
        "",
    ]
    for k in range(layout.x.size):
        lines.append(
            f"{k + 1} {int(layout.kind[k])} {layout.diameter[k]:.10g} {density:.10g} "
            f"{layout.x[k]:.10g} {layout.y[k]:.10g} 0"
        )
    return "\n".join(lines) + "\n"


def _pair_coeffs(cell: Cell) -> list[str]:
    c = cell.contact
    kt = c.kn * c.kt_ratio
    tangential = "linear_history" if c.model == "hooke" else "mindlin"

    def coeff(mu: float) -> str:
        text = (
            f"{c.model} {c.kn:.10g} {c.restitution:.10g} tangential {tangential} {kt:.10g} 1.0 "
            f"{mu:.10g} damping coeff_restitution"
        )
        if c.rolling_friction > 0:
            text += f" rolling sds {kt:.10g} 0.0 {c.rolling_friction:.10g}"
        return text

    mu_w = cell.wall.wall_friction(c)
    return [
        "pair_style granular",
        f"pair_coeff * * {coeff(c.friction)}",
        f"pair_coeff {FREE} {LOWER_WALL} {coeff(mu_w)}",
        f"pair_coeff {FREE} {UPPER_WALL} {coeff(mu_w)}",
        f"neigh_modify exclude type {LOWER_WALL} {LOWER_WALL}",
        f"neigh_modify exclude type {LOWER_WALL} {UPPER_WALL}",
        f"neigh_modify exclude type {UPPER_WALL} {UPPER_WALL}",
    ]


def _sampling(every: int) -> list[str]:
    pair = "compute cf all pair/local fx fy p1 p2 p10 p11"
    return [
        "compute ids all property/local patom1 patom2",
        pair,
        f"dump atoms all custom {every} atoms.dump {' '.join(ATOM_COLUMNS)}",
        "dump_modify atoms sort id format float %.9g",
        f"dump contacts all local {every} contacts.dump c_ids[1] c_ids[2] c_cf[*]",
        "dump_modify contacts format float %.9g",
    ]


def _wall_density(cell: Cell) -> list[str]:
    """Glued disks get the density that gives a wall the mass per length of one row of touching
    unit disks, rho_s pi d / 4, whatever their size and spacing (a smooth wall of many
    overlapping disks would otherwise be heavy and bounce on the grains)."""
    w = cell.wall
    density = cell.grains.density * w.glued_spacing / w.glued_diameter**2
    if density == cell.grains.density:
        return []
    return [f"set type {LOWER_WALL}*{UPPER_WALL} density/disc {density:.10g}"]


def _header(cell: Cell, data_sha: str, layout: Layout, dt: float, boundary: str) -> list[str]:
    return [
        f"# cosserat.dem deck: {cell.cell} cell",
        f"# parameters: {cell!r}",
        f"# grains.data sha256 {data_sha}",
        "units lj",
        "dimension 2",
        f"boundary {boundary}",
        "atom_style sphere",
        "comm_modify vel yes",
        "newton off",
        "read_data grains.data",
        f"set type * density/disc {cell.grains.density:.10g}",
        *_wall_density(cell),
        f"group free type {FREE}",
        f"group lower type {LOWER_WALL}",
        f"group upper type {UPPER_WALL}",
        f"neighbor {0.25 * cell.grains.d_max:.6g} bin",
        "neigh_modify delay 0 every 1 check yes",
        f"timestep {dt:.10g}",
        "fix twod all enforce2d",
    ]


def _planar(cell: PlaneShearDEM | ChannelDEM, layout: Layout, dt: float, data_sha: str) -> str:
    length = layout.info["length"]
    n_wall = layout.info["wall_count"]
    load = -1.0 * length / n_wall  # N = 1 over the wall's length, shared by its disks
    plane = isinstance(cell, PlaneShearDEM)
    g = cell.gravity
    lines = _header(cell, data_sha, layout, dt, "p fm p")
    lines += _pair_coeffs(cell)
    lines += [
        "velocity all set 0 0 0",
        "fix move free nve/sphere disc",
        "fix wall upper nve",
        f"fix settle free viscous {SETTLE_DAMPING}",
        f"fix load upper aveforce NULL {load:.10g} NULL",
        "fix slide upper setforce 0.0 NULL 0.0",
    ]
    if plane and g > 0:
        lines.append(f"fix gravity free gravity {g:.10g} vector 0 -1 0")
    lines += [
        "variable gap equal xcm(upper,y)",
        "thermo_style custom step ke v_gap f_slide[1] f_load[2]",
        "thermo 5000",
        "thermo_modify norm no",
        f"run {cell.run.settle_steps}",
        "unfix settle",
    ]
    if plane:
        lines.append(f"velocity upper set {cell.wall_speed:.10g} NULL NULL")
    else:
        lines.append(f"fix gravity free gravity {g:.10g} vector 1 0 0")
    lines += [
        "reset_timestep 0",
        "fix walls all ave/time "
        f"{cell.run.dump_every} 1 {cell.run.dump_every} v_gap f_slide[1] f_load[2] "
        "file walls.txt",
    ]
    lines += _sampling(cell.run.dump_every)
    lines += [f"run {cell.run.steps}", ""]
    return "\n".join(lines)


def _annular(cell: CouetteDEM, layout: Layout, dt: float, data_sha: str) -> str:
    grow_loops = 20
    factor = (1.0 / layout.info["shrink"]) ** (1.0 / grow_loops)
    per_loop = max(1, cell.run.settle_steps // (grow_loops + 1))
    period = 2.0 * math.pi * cell.inner_radius / cell.wall_speed
    lines = _header(cell, data_sha, layout, dt, "f f p")
    lines += _pair_coeffs(cell)
    lines += [
        "velocity all set 0 0 0",
        "fix move free nve/sphere disc",
        f"fix settle free viscous {SETTLE_DAMPING}",
        "thermo_style custom step ke press",
        "thermo 5000",
        "thermo_modify norm no",
        f"variable grown atom 2.0*radius*{factor:.15g}",
        f"variable k loop {grow_loops}",
        "label grow",
        "set group free diameter v_grown",
        f"set group free density/disc {cell.grains.density:.10g}",
        f"run {per_loop}",
        "next k",
        "jump SELF grow",
        f"run {per_loop}",
        "unfix settle",
        "reset_timestep 0",
        f"fix turn lower move rotate 0 0 0 0 0 1 {period:.10g}",
    ]
    lines += _sampling(cell.run.dump_every)
    lines += [f"run {cell.run.steps}", ""]
    return "\n".join(lines)


def timestep(cell: Cell) -> float:
    """The time step: ``dt_fraction`` of the smallest grains' collision time [time]."""
    return cell.run.dt_fraction * cell.contact.collision_time(cell.grains)


def build_deck(cell: Cell) -> Deck:
    """The deck of a cell (text and data file, not written)."""
    dt = timestep(cell)
    layout = annular_layout(cell) if isinstance(cell, CouetteDEM) else planar_layout(cell)
    data = _data_file(layout, cell.grains.density)
    data_sha = hashlib.sha256(data.encode()).hexdigest()
    if isinstance(cell, CouetteDEM):
        text = _annular(cell, layout, dt, data_sha)
    else:
        text = _planar(cell, layout, dt, data_sha)
    return Deck(cell, text, data, layout, dt)


__all__ = ["ATOM_COLUMNS", "CONTACT_COLUMNS", "Deck", "build_deck", "job_script", "timestep"]
