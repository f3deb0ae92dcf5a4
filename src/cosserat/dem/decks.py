"""LAMMPS input decks for the DEM cells (2-D disks, ``atom_style sphere``, ``dimension 2``; the
plane cell also in 3-D, spheres, ``dimension 3``).

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
from .geometry import (
    FREE,
    LOWER_WALL,
    UPPER_WALL,
    Layout,
    annular_layout,
    planar_layout,
    planar_layout_3d,
)
from .params import Cell, ChannelDEM, CouetteDEM, PlaneShearDEM, RunLength, WallRoughness

ATOM_COLUMNS = ("id", "type", "radius", "x", "y", "vx", "vy", "omegaz")
CONTACT_COLUMNS = ("i", "j", "fnx", "fny", "ftx", "fty", "dx", "dy")
"""Contact dump: ids i, j; normal and tangential force on i [N d]; x_i - x_j [d]."""
ATOM_COLUMNS_3D = ("id", "type", "radius", "x", "y", "z", "vx", "vy", "vz",
                   "omegax", "omegay", "omegaz")  # fmt: skip
"""Atom dump of a 3-D (sphere) cell."""
CONTACT_COLUMNS_3D = ("i", "j", "fnx", "fny", "fnz", "ftx", "fty", "ftz", "dx", "dy", "dz")
"""Contact dump of a 3-D cell: ids i, j; normal and tangential force on i [N d^2]; x_i - x_j
[d]."""
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


def dimension(cell: Cell) -> int:
    """2 (disks) or 3 (spheres: a plane cell with ``dim=3``)."""
    return int(getattr(cell, "dim", 2))


def _data_file(layout: Layout, density: float) -> str:
    """LAMMPS's data file of the initial positions: disks in a slab of unit thickness, or
    spheres (``layout.z`` given) in a box periodic along z over the layout's depth."""
    xlo, xhi, ylo, yhi = layout.box
    z = layout.z
    lines = [
        "cosserat.dem initial positions" + ("" if z is None else " (3-D)"),
        "",
        f"{layout.x.size} atoms",
        "3 atom types",
        "",
        f"{xlo:.10g} {xhi:.10g} xlo xhi",
        f"{ylo:.10g} {yhi:.10g} ylo yhi",
        "-0.5 0.5 zlo zhi" if z is None else f"0 {layout.info['depth']:.10g} zlo zhi",
        "",
        "Atoms # sphere",
        "",
    ]
    for k in range(layout.x.size):
        lines.append(
            f"{k + 1} {int(layout.kind[k])} {layout.diameter[k]:.10g} {density:.10g} "
            f"{layout.x[k]:.10g} {layout.y[k]:.10g} {'0' if z is None else f'{z[k]:.10g}'}"
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

    lower, upper = _walls(cell)
    return [
        "pair_style granular",
        f"pair_coeff * * {coeff(c.friction)}",
        f"pair_coeff {FREE} {LOWER_WALL} {coeff(lower.wall_friction(c))}",
        f"pair_coeff {FREE} {UPPER_WALL} {coeff(upper.wall_friction(c))}",
        f"neigh_modify exclude type {LOWER_WALL} {LOWER_WALL}",
        f"neigh_modify exclude type {LOWER_WALL} {UPPER_WALL}",
        f"neigh_modify exclude type {UPPER_WALL} {UPPER_WALL}",
    ]


def _sampling(every: int, resume: int | None = None, dim: int = 2) -> list[str]:
    """Computes and dumps of the sheared stage; resumed from step ``resume``: appended, and
    the first sample after it (the one at ``resume`` is in the dumps already, taken before the
    next chunk's setup re-evaluated the forces)."""
    columns: tuple[str, ...]
    if dim == 3:
        pair = "compute cf all pair/local fx fy fz p1 p2 p3 p10 p11 p12"
        columns = ATOM_COLUMNS_3D
    else:
        pair = "compute cf all pair/local fx fy p1 p2 p10 p11"
        columns = ATOM_COLUMNS
    more = "" if resume is None else f" append yes delay {resume + 1}"
    return [
        "compute ids all property/local patom1 patom2",
        pair,
        f"dump atoms all custom {every} atoms.dump {' '.join(columns)}",
        f"dump_modify atoms sort id format float %.9g{more}",
        f"dump contacts all local {every} contacts.dump c_ids[1] c_ids[2] c_cf[*]",
        f"dump_modify contacts format float %.9g{more}",
    ]


def restart_name(step: int) -> str:
    """The restart file a checkpointed deck writes at sheared step ``step``."""
    return f"restart.{step}.bin"


def _sheared(run: RunLength, first_chunk: int = 1) -> list[str]:
    """The sheared stage from chunk ``first_chunk``: one ``run`` without checkpoints, else
    chunks of ``restart_every`` steps, each followed by a restart file (written under a
    temporary name and renamed, so a ``restart.<step>.bin`` is always complete; the previous
    one is then removed). ``-var stop_at STEP`` on LAMMPS's command line stops the stage after
    the chunk that reaches STEP."""
    if not run.restart_every:
        return [f"run {run.steps}"]
    every = run.restart_every
    lines = []
    if first_chunk == 1:  # the state at the start of the sheared stage is a checkpoint too
        lines += ["write_restart restart.new", f"shell mv restart.new {restart_name(0)}"]
    lines += [
        f"variable stop_at index {run.steps}",
        f"variable chunk loop {first_chunk} {run.chunks}",
        "label shear",
        f"run {every}",
        "write_restart restart.new",
        "shell mv restart.new restart.$(step).bin",
        f"shell rm -f restart.$(step-{every}).bin",
        'if "$(step) >= ${stop_at}" then "jump SELF sheared"',
        "next chunk",
        "jump SELF shear",
        "label sheared",
    ]
    return lines


def _wall_density(cell: Cell) -> list[str]:
    """Glued disks get the density that gives a wall the mass per length of one row of touching
    unit disks, rho_s pi d / 4, whatever their size and spacing (a smooth wall of many
    overlapping disks would otherwise be heavy and bounce on the grains)."""
    lower, upper = _walls(cell)
    if dimension(cell) == 3:  # spheres: a triangular sheet of touching unit spheres' mass/area
        # (3-D cells take one wall kind, glued grains: PlaneShearDEM refuses others)
        density = cell.grains.density * upper.glued_spacing**2 / upper.glued_diameter**3
        if density == cell.grains.density:
            return []
        return [f"set type {LOWER_WALL}*{UPPER_WALL} density {density:.10g}"]
    rho = [cell.grains.density * w.glued_spacing / w.glued_diameter**2 for w in (lower, upper)]
    if rho[0] == rho[1]:
        if rho[0] == cell.grains.density:
            return []
        return [f"set type {LOWER_WALL}*{UPPER_WALL} density/disc {rho[0]:.10g}"]
    return [
        f"set type {kind} density/disc {value:.10g}"
        for kind, value in zip((LOWER_WALL, UPPER_WALL), rho, strict=True)
        if value != cell.grains.density
    ]


def _walls(cell: Cell) -> tuple[WallRoughness, WallRoughness]:
    """The (lower or inner, upper or outer) walls (the channel's are of one kind)."""
    return cell.walls if hasattr(cell, "walls") else (cell.wall, cell.wall)


def _walls_line(cell: Cell) -> list[str]:
    """A comment naming both walls when they differ (the parameter line shows ``wall``, the
    moving one, only); none otherwise, so a deck of one wall kind is unchanged."""
    if not getattr(cell, "walls_differ", False):
        return []
    names = ("lower", "upper") if isinstance(cell, PlaneShearDEM) else ("inner", "outer")
    text = ", ".join(f"{n} {w!r}" for n, w in zip(names, _walls(cell), strict=True))
    return [f"# walls: {text}"]


def _header(cell: Cell, data_sha: str, layout: Layout, dt: float, boundary: str) -> list[str]:
    three = dimension(cell) == 3
    lines = [
        f"# cosserat.dem deck: {cell.cell} cell",
        f"# parameters: {cell!r}",
        *_walls_line(cell),
    ]
    if three:
        lines.append(
            f"# 3-D: spheres, periodic depth {layout.info['depth']:g} d, walls of "
            f"{layout.info['wall_count']} glued spheres each"
        )
    lines += [
        f"# grains.data sha256 {data_sha}",
        "units lj",
        f"dimension {3 if three else 2}",
        f"boundary {boundary}",
        "atom_style sphere",
        "comm_modify vel yes",
        "newton off",
        "read_data grains.data",
        *_no_sort(cell),
        f"set type * {'density' if three else 'density/disc'} {cell.grains.density:.10g}",
        *_wall_density(cell),
        f"group free type {FREE}",
        f"group lower type {LOWER_WALL}",
        f"group upper type {UPPER_WALL}",
        f"neighbor {0.25 * cell.grains.d_max:.6g} bin",
        "neigh_modify delay 0 every 1 check yes",
        f"timestep {dt:.10g}",
    ]
    if not three:
        lines.append("fix twod all enforce2d")
    return lines


def _no_sort(cell: Cell) -> list[str]:
    """3-D: no spatial sorting of the atoms in memory. LAMMPS sorts them every 1,000 steps
    counted from the start of a run, so a run resumed from a checkpoint would sum the forces
    in another order and leave the uninterrupted trajectory by round-off (1e-11 d 1,000 steps
    after the checkpoint, growing tenfold every 400 steps in a small slab); unsorted, the
    resumed run is the same trajectory, byte for byte, as in 2-D."""
    return ["atom_modify sort 0 0.0"] if dimension(cell) == 3 else []


def _integrator(cell: Cell) -> str:
    """``fix nve/sphere`` of the free grains: disks (``disc``, I = m D^2 / 8) in 2-D, spheres
    (I = m D^2 / 10) in 3-D."""
    return "fix move free nve/sphere" + ("" if dimension(cell) == 3 else " disc")


def _planar(cell: PlaneShearDEM | ChannelDEM, layout: Layout, dt: float, data_sha: str) -> str:
    load = _planar_load(layout)  # N = 1 over the wall's length, shared by its disks
    plane = isinstance(cell, PlaneShearDEM)
    g = cell.gravity
    lines = _header(cell, data_sha, layout, dt, "p fm p")
    lines += _pair_coeffs(cell)
    lines += [
        "velocity all set 0 0 0",
        _integrator(cell),
        "fix wall upper nve",
        f"fix settle free viscous {SETTLE_DAMPING}",
        f"fix load upper aveforce NULL {load:.10g} NULL",
        "fix slide upper setforce 0.0 NULL 0.0",
    ]
    if plane and g > 0:
        lines.append(f"fix gravity free gravity {g:.10g} vector 0 -1 0")
    lines += [
        *_planar_thermo(),
        f"run {cell.run.settle_steps}",
        "unfix settle",
    ]
    if plane:
        lines.append(f"velocity upper set {cell.wall_speed:.10g} NULL NULL")
    else:
        lines.append(f"fix gravity free gravity {g:.10g} vector 1 0 0")
    lines += ["reset_timestep 0", _planar_walls(cell)]
    lines += _sampling(cell.run.dump_every, dim=dimension(cell))
    lines += [*_sheared(cell.run), ""]
    return "\n".join(lines)


def _planar_load(layout: Layout) -> float:
    """Force per upper-wall disk (sphere) along y that makes the normal stress N = 1 over the
    wall's length (3-D: its area) [N d (N d^2)]."""
    extent = layout.info.get("wall_area", layout.info["length"])
    return -1.0 * extent / layout.info["wall_count"]


def _planar_thermo() -> list[str]:
    return [
        "variable gap equal xcm(upper,y)",
        "thermo_style custom step ke v_gap f_slide[1] f_load[2]",
        "thermo 5000",
        "thermo_modify norm no",
    ]


def _planar_walls(cell: PlaneShearDEM | ChannelDEM, resume: int | None = None) -> str:
    every = cell.run.dump_every
    # resumed: the line of step ``resume`` is written again at the setup (a driver that
    # resumes drops it from the file first, see cosserat.dem.corpus.run_segment)
    where = "file walls.txt" if resume is None else "append walls.txt"
    return f"fix walls all ave/time {every} 1 {every} v_gap f_slide[1] f_load[2] {where}"


def _planar_sheared_fixes(cell: PlaneShearDEM | ChannelDEM, layout: Layout) -> list[str]:
    """The fixes of the planar sheared stage, in the order the full deck leaves them."""
    lines = [
        _integrator(cell),
        "fix wall upper nve",
        f"fix load upper aveforce NULL {_planar_load(layout):.10g} NULL",
        "fix slide upper setforce 0.0 NULL 0.0",
    ]
    g = cell.gravity
    if isinstance(cell, PlaneShearDEM):
        if g > 0:
            lines.append(f"fix gravity free gravity {g:.10g} vector 0 -1 0")
    else:
        lines.append(f"fix gravity free gravity {g:.10g} vector 1 0 0")
    return lines


def _annular(cell: CouetteDEM, layout: Layout, dt: float, data_sha: str) -> str:
    grow_loops = 20
    factor = (1.0 / layout.info["shrink"]) ** (1.0 / grow_loops)
    per_loop = max(1, cell.run.settle_steps // (grow_loops + 1))
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
        _turn(cell),
    ]
    lines += _sampling(cell.run.dump_every)
    lines += [*_sheared(cell.run), ""]
    return "\n".join(lines)


def _turn(cell: CouetteDEM) -> str:
    period = 2.0 * math.pi * cell.inner_radius / cell.wall_speed
    return f"fix turn lower move rotate 0 0 0 0 0 1 {period:.10g}"


def timestep(cell: Cell) -> float:
    """The time step: ``dt_fraction`` of the smallest grains' collision time [time]."""
    return cell.run.dt_fraction * cell.contact.collision_time(cell.grains, dimension(cell))


def resume_deck(cell: Cell, step: int, deck_sha256: str | None = None) -> str:
    """The deck that continues a checkpointed run of ``cell`` from its restart file at sheared
    step ``step`` (:func:`restart_name`): it reads the restart file, sets again what a restart
    file does not hold (neighbour settings, fixes in the full deck's order, the sampling,
    appending to the dumps and ``walls.txt``) and runs the remaining chunks. Run from the
    checkpoint, it gives the same trajectory as the full deck (the chunks are separate
    ``run`` commands in both, so each starts from the same state).

    ``deck_sha256`` names the deck that ran first (default: this cell's): a run continued for
    more steps than its deck's is this cell with the larger ``steps``.

    Raises
    ------
    InputError
        The cell has no checkpoints, or ``step`` is not one of its chunk boundaries.
    """
    from ..errors import InputError

    run = cell.run
    if not run.restart_every:
        raise InputError("the cell's run has no checkpoints (restart_every = 0): cannot resume")
    if step % run.restart_every or not 0 <= step < run.steps:
        raise InputError(
            f"step must be a checkpoint, a multiple of restart_every ({run.restart_every}) "
            f"below steps ({run.steps}); got {step}"
        )
    full = build_deck(cell)
    layout = full.layout
    lines = [
        f"# cosserat.dem deck: resume the {cell.cell} cell from sheared step {step}",
        f"# parameters: {cell!r}, restart_every={run.restart_every}",
        *_walls_line(cell),
        f"# deck.lmp sha256 {deck_sha256 or full.sha256}",
        f"read_restart {restart_name(step)}",
        *_no_sort(cell),
        "comm_modify vel yes",
        "newton off",
        *_pair_coeffs(cell),  # the restart file's pair settings lose the size-based cutoff
        f"neighbor {0.25 * cell.grains.d_max:.6g} bin",
        "neigh_modify delay 0 every 1 check yes",
    ]
    if dimension(cell) == 2:
        lines.append("fix twod all enforce2d")
    if isinstance(cell, CouetteDEM):
        lines += [
            "fix move free nve/sphere disc",
            "thermo_style custom step ke press",
            "thermo 5000",
            "thermo_modify norm no",
            _turn(cell),
        ]
    else:
        lines += [
            *_planar_sheared_fixes(cell, layout),
            *_planar_thermo(),
            _planar_walls(cell, resume=step),
        ]
    lines += _sampling(run.dump_every, resume=step, dim=dimension(cell))
    lines += [*_sheared(run, first_chunk=step // run.restart_every + 1), ""]
    return "\n".join(lines)


def build_deck(cell: Cell) -> Deck:
    """The deck of a cell (text and data file, not written)."""
    dt = timestep(cell)
    if isinstance(cell, CouetteDEM):
        layout = annular_layout(cell)
    elif dimension(cell) == 3:
        assert isinstance(cell, PlaneShearDEM)  # the only cell with dim 3
        layout = planar_layout_3d(cell)
    else:
        layout = planar_layout(cell)
    data = _data_file(layout, cell.grains.density)
    data_sha = hashlib.sha256(data.encode()).hexdigest()
    if isinstance(cell, CouetteDEM):
        text = _annular(cell, layout, dt, data_sha)
    else:
        text = _planar(cell, layout, dt, data_sha)
    return Deck(cell, text, data, layout, dt)


__all__ = [
    "ATOM_COLUMNS",
    "ATOM_COLUMNS_3D",
    "CONTACT_COLUMNS",
    "CONTACT_COLUMNS_3D",
    "Deck",
    "build_deck",
    "dimension",
    "job_script",
    "restart_name",
    "resume_deck",
    "timestep",
]
