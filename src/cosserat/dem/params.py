"""Parameters of the DEM cells: frozen, validated records with defaults.

Units are "grain units": lengths in the mean grain diameter d, masses through the grain
density rho_s (mass per area of a disk, 2-D), stresses in the applied normal stress N of the
plane cell (N = 1), so velocities are in sqrt(N / rho_s) and times in d sqrt(rho_s / N).
LAMMPS runs in ``units lj`` with d = rho_s = N = 1.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Literal

from ..errors import ParameterError, shown

ContactModel = Literal["hooke", "hertz"]
WallKind = Literal["glued-grains", "smooth-frictional"]

SMOOTH_SPACING_D = 0.1
"""Centre spacing of the glued disks (diameter 1 d) that make a smooth frictional wall [d]:
bumps 0.0025 d high, about the contact overlap at the wall's normal stress."""


def _check(name: str, value: float, low: float, high: float = math.inf, *, open_low=True) -> None:
    ok = (value > low if open_low else value >= low) and value <= high
    if not (math.isfinite(value) and ok):
        bound = f"{'>' if open_low else '>='} {low:g}" + (
            f" and <= {high:g}" if math.isfinite(high) else ""
        )
        raise ParameterError(f"{name} must be {bound}; got {shown(value)}")


@dataclass(frozen=True)
class Grains:
    """Polydisperse disks: diameters uniform in [1 - p, 1 + p] d (mean 1 d).

    Parameters
    ----------
    polydispersity : float
        Half-width p of the diameter distribution [d]; 0.2 avoids crystallisation in 2-D.
    density : float
        Mass per area of a disk rho_s [mass / d^2].
    """

    polydispersity: float = 0.2
    density: float = 1.0

    def __post_init__(self) -> None:
        _check("polydispersity", self.polydispersity, 0.0, 0.5, open_low=False)
        _check("density", self.density, 0.0)

    @property
    def d_min(self) -> float:
        """Smallest diameter [d]."""
        return 1.0 - self.polydispersity

    @property
    def d_max(self) -> float:
        """Largest diameter [d]."""
        return 1.0 + self.polydispersity

    @property
    def mean_volume(self) -> float:
        """Mean sphere volume pi <D^3> / 6 = pi (1 + p^2) / 6 [d^3] (3-D cells)."""
        return math.pi / 6.0 * (1.0 + self.polydispersity**2)

    @property
    def mean_area(self) -> float:
        """Mean disk area pi <D^2> / 4 [d^2] of the uniform diameter distribution."""
        return math.pi / 4.0 * (1.0 + self.polydispersity**2 / 3.0)

    def describe(self, n: int) -> dict:
        return {
            "n": int(n),
            "polydispersity": f"diameters uniform in [{self.d_min:g}, {self.d_max:g}] d",
            "diameter_range_d": [self.d_min, self.d_max],
            "density": self.density,
        }


@dataclass(frozen=True)
class Contact:
    """Contact law of LAMMPS's ``pair_style granular`` between two grains.

    Parameters
    ----------
    model : {"hooke", "hertz"}
        Linear spring with history (``hooke`` + ``linear_history``) or Hertz-Mindlin
        (``hertz`` + ``mindlin``); for ``hertz`` kn is in [N d^-1/2] (force = kn delta^3/2 in 2-D
        force per length units).
    kn : float
        Normal stiffness [N] (force per length per overlap in 2-D: kn / N is the stiffness
        number kappa, 1000 by default).
    kt_ratio : float
        Tangential over normal stiffness [-].
    friction : float
        Coulomb friction coefficient between grains [-].
    restitution : float
        Normal coefficient of restitution [-] (``damping coeff_restitution``).
    rolling_friction : float
        Rolling-resistance coefficient of the ``sds`` rolling model [-]; 0: none.
    """

    model: ContactModel = "hooke"
    kn: float = 1000.0
    kt_ratio: float = 0.5
    friction: float = 0.5
    restitution: float = 0.5
    rolling_friction: float = 0.0

    def __post_init__(self) -> None:
        if self.model not in ("hooke", "hertz"):
            raise ParameterError(f"contact model must be 'hooke' or 'hertz'; got {self.model!r}")
        _check("kn", self.kn, 0.0)
        _check("kt_ratio", self.kt_ratio, 0.0, 1.0)
        _check("friction", self.friction, 0.0, 10.0, open_low=False)
        _check("restitution", self.restitution, 0.0, 1.0)
        _check("rolling_friction", self.rolling_friction, 0.0, 1.0, open_low=False)

    def collision_time(self, grains: Grains, dim: int = 2) -> float:
        """Undamped duration of a contact between two of the smallest grains [time]: disks
        (``dim`` 2, mass rho_s pi d^2 / 4) or spheres (``dim`` 3, mass rho_s pi d^3 / 6)."""
        if dim == 3:
            m = grains.density * math.pi / 6.0 * grains.d_min**3
        else:
            m = grains.density * math.pi / 4.0 * grains.d_min**2
        return math.pi * math.sqrt(0.5 * m / self.kn)

    def describe(self) -> dict:
        return {
            "model": "linear spring-dashpot with history (LAMMPS pair granular hooke, "
            "linear_history)"
            if self.model == "hooke"
            else "Hertz-Mindlin (LAMMPS pair granular hertz, mindlin)",
            "kn": self.kn,
            "kt": self.kn * self.kt_ratio,
            "friction": self.friction,
            "restitution": self.restitution,
            "rolling_friction": self.rolling_friction,
        }


@dataclass(frozen=True)
class WallRoughness:
    """A wall: a row of glued disks, or a smooth frictional line.

    Parameters
    ----------
    kind : {"glued-grains", "smooth-frictional"}
        ``smooth-frictional`` is a row of glued disks of diameter 1 d at spacing
        :data:`SMOOTH_SPACING_D` (geometrically flat to 0.0025 d).
    glued_diameter : float
        Diameter of the glued disks [d].
    glued_spacing : float
        Centre-to-centre spacing of the glued disks [d]; at most their diameter plus 0.7 of the
        smallest free grain so no grain falls through.
    friction : float or None
        Grain-wall friction coefficient [-]; None: the grains' own.
    """

    kind: WallKind = "glued-grains"
    glued_diameter: float = 1.0
    glued_spacing: float = 1.0
    friction: float | None = None

    def __post_init__(self) -> None:
        if self.kind not in ("glued-grains", "smooth-frictional"):
            raise ParameterError(
                f"wall kind must be 'glued-grains' or 'smooth-frictional'; got {self.kind!r}"
            )
        if self.kind == "smooth-frictional":
            object.__setattr__(self, "glued_diameter", 1.0)
            object.__setattr__(self, "glued_spacing", SMOOTH_SPACING_D)
        _check("glued_diameter", self.glued_diameter, 0.0, 5.0)
        _check("glued_spacing", self.glued_spacing, 0.0, 10.0)
        if self.glued_spacing > self.glued_diameter + 0.7 * 0.5:
            raise ParameterError(
                "glued_spacing must be <= glued_diameter + 0.35 d (no grain may pass between "
                f"glued disks); got spacing {self.glued_spacing:g}, diameter "
                f"{self.glued_diameter:g}"
            )
        if self.friction is not None:
            _check("wall friction", self.friction, 0.0, 10.0, open_low=False)

    def wall_friction(self, contact: Contact) -> float:
        return contact.friction if self.friction is None else self.friction

    def describe(self, contact: Contact) -> dict:
        return {
            "kind": self.kind,
            "glued_diameter_d": self.glued_diameter,
            "glued_spacing_d": self.glued_spacing,
            "friction": self.wall_friction(contact),
        }


BLOCKS = 10
"""Number of averaging blocks over a run's steady window (:mod:`cosserat.dem.analyse`)."""
MIN_SAMPLES = 2 * BLOCKS
"""Fewest samples a run may hold: the analysis needs two per block; a run with fewer would be
refused only after LAMMPS has run, so :class:`RunLength` refuses it before."""


@dataclass(frozen=True)
class RunLength:
    """How long a cell runs and how often it is sampled.

    Parameters
    ----------
    settle_steps : int
        Steps of preparation (settling under load, or growing the grains) before shearing.
    steps : int
        Steps of shear after the preparation (the transient and the steady state).
    dump_every : int
        Steps between two samples of the grains and contacts.
    dt_fraction : float
        Time step as a fraction of the smallest grains' collision time [-].
    restart_every : int
        Steps between two checkpoints (LAMMPS restart files) of the sheared stage; 0: none (the
        shipped corpus's decks). A multiple of ``dump_every`` that divides ``steps``: the
        sheared stage then runs in chunks of this many steps, each followed by a restart file,
        so a stopped run continues from its last chunk (``cosserat dem run --resume``) exactly
        as if it had not stopped. Not in the deck's parameter line (the chunked stage shows it),
        so the decks without checkpoints stay those of the shipped corpus.
    """

    settle_steps: int = 20_000
    steps: int = 200_000
    dump_every: int = 1_000
    dt_fraction: float = 0.02
    restart_every: int = field(default=0, repr=False)

    def __post_init__(self) -> None:
        for name in ("settle_steps", "steps", "dump_every"):
            value = getattr(self, name)
            if not isinstance(value, int) or value < (0 if name == "settle_steps" else 1):
                raise ParameterError(f"{name} must be a whole number >= 1; got {shown(value)}")
        if self.steps < MIN_SAMPLES * self.dump_every:
            raise ParameterError(
                f"steps ({self.steps}) must hold at least {MIN_SAMPLES} samples of dump_every "
                f"({self.dump_every}): the analysis averages {BLOCKS} blocks of at least two"
            )
        _check("dt_fraction", self.dt_fraction, 0.0, 0.1)
        every = self.restart_every
        if not isinstance(every, int) or every < 0:
            raise ParameterError(f"restart_every must be a whole number >= 0; got {shown(every)}")
        if every and (every % self.dump_every or self.steps % every):
            raise ParameterError(
                f"restart_every ({every}) must be a multiple of dump_every ({self.dump_every}) "
                f"that divides steps ({self.steps}), so checkpoints fall on samples"
            )

    @property
    def chunks(self) -> int:
        """Number of checkpointed chunks of the sheared stage (1 without checkpoints)."""
        return self.steps // self.restart_every if self.restart_every else 1


NU_NOMINAL = {2: 0.8, 3: 0.6}
"""Nominal solids fraction of the plane cell's B by dimension [-]: disks near 0.8, spheres near
0.6 (random loose to random close packing is 0.55-0.64)."""


def _own_walls(cell) -> None:
    """Resolve a cell's per-wall kinds: both equal (or unset) leave the one ``wall`` and no
    override (the deck is then that of a cell with one wall kind); otherwise ``wall`` is the
    moving wall's (upper, inner) and the fixed one keeps its own."""
    lower = cell.lower_wall or cell.wall
    upper = cell.upper_wall or cell.wall
    for name, w in (("lower_wall", lower), ("upper_wall", upper)):
        if not isinstance(w, WallRoughness):
            raise ParameterError(f"{name} must be a WallRoughness; got {type(w).__name__}")
    if lower == upper:
        object.__setattr__(cell, "wall", lower)
        object.__setattr__(cell, "lower_wall", None)
        object.__setattr__(cell, "upper_wall", None)
    else:
        object.__setattr__(cell, "wall", upper)
        object.__setattr__(cell, "lower_wall", lower)
        object.__setattr__(cell, "upper_wall", upper)


class _TwoWalls:
    """Per-wall kinds of a cell whose walls are types 2 (lower or inner) and 3 (upper or
    outer)."""

    wall: WallRoughness
    lower_wall: WallRoughness | None
    upper_wall: WallRoughness | None

    @property
    def walls(self) -> tuple[WallRoughness, WallRoughness]:
        """The (lower or inner, upper or outer) walls."""
        return (self.lower_wall or self.wall, self.upper_wall or self.wall)

    @property
    def walls_differ(self) -> bool:
        """True when the two walls are of different kinds."""
        return self.lower_wall is not None


@dataclass(frozen=True)
class PlaneShearDEM(_TwoWalls):
    """Plane shear between two walls, periodic along x; the upper wall is driven at speed
    ``wall_speed`` along +x under the normal stress N = 1, the lower one is fixed.

    Parameters
    ----------
    gap : float
        Nominal gap H between the walls' glued-disk surfaces [d] (the settled gap is measured
        and reported).
    width : float
        Periodic length along the flow [d].
    B : float
        Gravity parameter rho_s nu g H / N [-] with nu = ``nu_nominal``; gravity along -y; 0: none.
    wall_speed : float
        Upper-wall speed V [sqrt(N / rho_s)].
    nu_nominal : float or None
        Nominal solids fraction in B [-]; None: :data:`NU_NOMINAL` of the dimension (0.8 for
        disks, 0.6 for spheres).
    dim : {2, 3}
        2: disks (the corpus); 3: spheres in a slab periodic along x and z, of depth ``depth``,
        between walls of glued spheres on a triangular lattice (``docs/dem.md``, "Does it carry
        to 3-D?"). Not in the deck's parameter line (the 3-D deck says it on its own line), so
        the 2-D decks stay those of the corpus.
    depth : float
        3-D: periodic depth along z [d]; 0 in 2-D.
    wall : WallRoughness
        Both walls, or (with ``lower_wall`` or ``upper_wall`` of another kind) the moving
        upper one.
    lower_wall, upper_wall : WallRoughness or None
        A wall of its own kind (None: ``wall``). Walls that differ add a comment line
        ``# walls: lower ..., upper ...`` to the deck; equal ones leave it that of one kind.
    """

    gap: float = 20.0
    width: float = 30.0
    B: float = 1.0
    wall_speed: float = 0.1
    wall: WallRoughness = field(default_factory=WallRoughness)
    grains: Grains = field(default_factory=Grains)
    contact: Contact = field(default_factory=Contact)
    run: RunLength = field(default_factory=RunLength)
    seed: int = 1
    nu_nominal: float = None  # type: ignore[assignment]  # set in __post_init__ from dim
    dim: int = field(default=2, repr=False)
    depth: float = field(default=0.0, repr=False)
    lower_wall: WallRoughness | None = field(default=None, repr=False)
    upper_wall: WallRoughness | None = field(default=None, repr=False)

    cell = "plane"

    def __post_init__(self) -> None:
        if self.dim not in (2, 3):
            raise ParameterError(f"dim must be 2 or 3; got {shown(self.dim)}")
        if self.nu_nominal is None:
            object.__setattr__(self, "nu_nominal", NU_NOMINAL[self.dim])
        if self.dim == 3:
            _check("depth", self.depth, 4.0, 5000.0, open_low=False)
            kinds = {(w or self.wall).kind for w in (self.lower_wall, self.upper_wall)}
            if kinds != {"glued-grains"}:
                raise ParameterError(
                    "a 3-D plane cell takes glued-grains walls only (a smooth-frictional wall "
                    f"of spheres at {SMOOTH_SPACING_D:g} d spacing would hold about "
                    f"{round(1 / SMOOTH_SPACING_D**2 / 0.866):,} spheres per d^2); got "
                    f"{sorted(kinds)}"
                )
        elif self.depth != 0.0:
            raise ParameterError(f"depth is for dim 3 only; got depth {shown(self.depth)} in 2-D")
        _check("gap", self.gap, 2.0, 2000.0)
        _check("width", self.width, 4.0, 5000.0)
        _check("B", self.B, 0.0, 100.0, open_low=False)
        _check("wall_speed", self.wall_speed, 0.0, 10.0)
        _check("nu_nominal", self.nu_nominal, 0.3, 0.91)
        if not isinstance(self.seed, int) or self.seed < 1:
            raise ParameterError(f"seed must be a whole number >= 1; got {shown(self.seed)}")
        _own_walls(self)

    @property
    def gravity(self) -> float:
        """g [N / (rho_s d)] from B = rho_s nu g H / N."""
        return self.B / (self.grains.density * self.nu_nominal * self.gap)


@dataclass(frozen=True)
class CouetteDEM(_TwoWalls):
    """Annular Couette flow: a rough inner ring of radius R_i turning at tangential speed V
    (counter-clockwise), a fixed rough outer ring at R_i + H; no gravity; the grains fill the
    annulus at the solids fraction ``nu_fill`` (volume control: the stress is measured).

    Parameters
    ----------
    gap : float
        Gap H between the rings' glued-disk surfaces [d].
    inner_radius : float
        R_i, radius of the inner ring's surface [d].
    nu_fill : float
        Area of the grains over the area of the annulus between the ring surfaces [-].
    wall_speed : float
        Tangential speed of the inner ring's surface V = Omega_i R_i [sqrt(N / rho_s)].
    wall : WallRoughness
        Both rings, or (with ``lower_wall`` or ``upper_wall`` of another kind) the moving
        inner one.
    lower_wall, upper_wall : WallRoughness or None
        The inner (``lower_wall``) or outer (``upper_wall``) ring of its own kind (None:
        ``wall``), as in :class:`PlaneShearDEM`.
    """

    gap: float = 20.0
    inner_radius: float = 20.0
    nu_fill: float = 0.81
    wall_speed: float = 0.2
    wall: WallRoughness = field(default_factory=WallRoughness)
    grains: Grains = field(default_factory=Grains)
    contact: Contact = field(default_factory=Contact)
    run: RunLength = field(default_factory=RunLength)
    seed: int = 1
    lower_wall: WallRoughness | None = field(default=None, repr=False)
    upper_wall: WallRoughness | None = field(default=None, repr=False)

    cell = "couette"

    def __post_init__(self) -> None:
        _check("gap", self.gap, 2.0, 2000.0)
        _check("inner_radius", self.inner_radius, 2.0, 5000.0)
        _check("nu_fill", self.nu_fill, 0.3, 0.88)
        _check("wall_speed", self.wall_speed, 0.0, 10.0)
        if not isinstance(self.seed, int) or self.seed < 1:
            raise ParameterError(f"seed must be a whole number >= 1; got {shown(self.seed)}")
        _own_walls(self)


@dataclass(frozen=True)
class ChannelDEM:
    """Vertical channel: gravity along +x (the deck's "down"), periodic along x, two rough walls
    at y = 0 (fixed) and y = H (free to move along y only, under the normal stress N = 1, so
    the grains' dilation is free).

    Parameters
    ----------
    gap : float
        Nominal gap between the walls' glued-disk surfaces [d].
    length : float
        Periodic length along the flow [d].
    shear_ratio : float
        Wall shear stress over wall normal stress if the weight were carried by the walls,
        rho_s nu g H / (2 N) with nu = ``nu_nominal`` [-]: the driving parameter. With the
        default grains and rough walls, 0.32 to 0.39 leave the settled packing jammed, 0.40
        (the default, the corpus's channel) flows steadily at wall inertial numbers of about
        0.24, and 0.42 keeps accelerating over a million steps (docs/dem.md).
    """

    gap: float = 20.0
    length: float = 30.0
    shear_ratio: float = 0.40
    wall: WallRoughness = field(default_factory=WallRoughness)
    grains: Grains = field(default_factory=Grains)
    contact: Contact = field(default_factory=Contact)
    run: RunLength = field(default_factory=RunLength)
    seed: int = 1
    nu_nominal: float = 0.8

    cell = "channel"

    def __post_init__(self) -> None:
        _check("gap", self.gap, 2.0, 2000.0)
        _check("length", self.length, 4.0, 5000.0)
        _check("shear_ratio", self.shear_ratio, 0.0, 5.0)
        _check("nu_nominal", self.nu_nominal, 0.3, 0.91)
        if not isinstance(self.seed, int) or self.seed < 1:
            raise ParameterError(f"seed must be a whole number >= 1; got {shown(self.seed)}")

    @property
    def gravity(self) -> float:
        """g [N / (rho_s d)] from shear_ratio = rho_s nu g H / (2 N)."""
        return 2.0 * self.shear_ratio / (self.grains.density * self.nu_nominal * self.gap)

    @property
    def wall_speed(self) -> float:
        """The velocity scale sqrt(g d) [sqrt(N / rho_s)]."""
        return math.sqrt(self.gravity)


Cell = PlaneShearDEM | CouetteDEM | ChannelDEM
