"""Laboratory cells in SI units: dimensional inputs in, dimensional profiles, stresses, slip,
shear-layer thickness and torque out, for every rheology on plane shear, Couette flow and the
vertical channel.

A laboratory cell (:class:`PlaneCell`, :class:`CouetteCell`, :class:`ChannelCell`) states the
experiment in SI units and makes the dimensionless problem with :meth:`LabCell.problem`, the
one ``Problem(cell, rheology)`` every route solves. The groups it computes, never fits:

- ``eps = d_p / H`` (grain diameter over gap),
- the inertial number of the drive ``I_w = V d_p / (H sqrt(p / rho_p))`` with V the velocity
  scale (the moving wall's speed, the inner cylinder's surface speed) and p the stress scale
  (the wall normal stress, or the mean stress at the depth of the profile in a Couette cell):
  the drive of a rate-dependent rheology (mu(I), NGF), unused by the rate-independent
  Cosserat model,
- ``B = rho_p g H / N`` for plane shear and the channel, ``Ri = R_i / H`` for Couette flow.

The results use one vocabulary in Python and on the command line (``cosserat cell``):
``grain_diameter`` (``--grain-diameter``), ``density`` (``--density``), ``gap``,
``solids_fraction``, ``gravity``, ... The paper's symbols ``d_p``, ``rho_p``, ``R_i``, ``nu``
and ``g`` are accepted as deprecated keyword aliases for one release. ``density`` is the
intrinsic density of the grains, the paper's rho_p and the rho_s of the mu(I) and NGF
literature (``I = gamma_dot d / sqrt(p / rho_s)``): one quantity, one name here.

Couette torque. In a Cosserat medium the torque per unit height carried across the cylinder
of radius r is not the shear stress alone: with the traction and the couple per unit area on
that surface, ``T(r) = 2 pi r (r sigma_(r theta) + M_rz)`` (literal signs). theta-momentum,
``d sigma_rt/dr + (sigma_rt + sigma_tr)/r = 0``, and the couple-stress balance,
``(1/r) d(r M_rz)/dr + sigma_rt - sigma_tr = 0``, give ``dT/dr = 0``: T is the same across the
gap (``docs/derivation_couette.md``). In the paper's variables (u and shear stresses along
-e_theta)::

    T = 2 pi sigma_c H^2 [ -(Ri + xi)^2 s_rt(xi) + 2(A+1) eps alpha (Ri + xi) m(xi) ],

and at the inner cylinder, where s_rt = -tan(delta), it is the torque that drives the cylinder
(without couple stress, mu(I) and NGF, the second term is absent). The stresses grow with depth
z as ``sigma_c = rho_p g nu z``; for a rate-independent law the profile does not depend on
depth and the torque over the fill depth D is ``T'(D) D / 2``; for a rate-dependent law the
inertial number, hence the profile, changes with depth, and the torque is integrated over depth
(Gauss-Legendre quadrature, one solve per node).
"""

from __future__ import annotations

import dataclasses
import math
import warnings
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any, ClassVar

import numpy as np

from ..errors import ParameterError
from ..model import Cosserat, Problem
from ..model.constitutive import FloatArray
from ..model.parameters import Material, Wall, require_finite
from ..model.rheologies import Rheology
from ..model.rheologies.base import equations_of
from ..model.rheologies.cosserat import CosseratCouette
from ..results.profile import Profile
from ..results.wall import shear_layer_thickness, wall_slip

ALIASES: dict[str, str] = {
    "d_p": "grain_diameter",
    "rho_p": "density",
    "R_i": "inner_radius",
    "nu": "solids_fraction",
    "g": "gravity",
}
"""Deprecated keyword -> its name now (kept for one release, with a DeprecationWarning)."""

UNITS: dict[str, str] = {
    "grain_diameter": "m",
    "density": "kg/m^3",
    "gap": "m",
    "solids_fraction": "1",
    "gravity": "m/s^2",
    "normal_stress": "Pa",
    "wall_speed": "m/s",
    "inner_radius": "m",
    "fill_depth": "m",
    "rotation_rate": "rad/s",
    "centre_speed": "m/s",
    "depth": "m",
    "eps": "1",
    "Ri": "1",
    "B": "1",
    "I_w": "1",
    "froude": "1",
    "velocity_scale": "m/s",
    "stress_scale": "Pa",
    "wall_shear_stress": "Pa",
    "slip_velocity": "m/s",
    "Delta": "grain diameters",
    "Delta_m": "m",
    "torque": "N m",
    "torque_per_height": "N m/m",
    "torque_per_height_shear": "N m/m",
    "mean_stress": "Pa",
    "position": "m",
    "velocity": "m/s",
    "spin": "rad/s",
}
"""Unit of every input and result, by the name Python and the command line share."""

TORQUE_NODES = 8
"""Gauss-Legendre nodes of the torque over depth for a rate-dependent rheology in a Couette
cell (one solve per node; in s = sqrt(z/D) the integrand is smooth: for mu(I) the torque is
within 2e-8 of adaptive quadrature, ``tests/test_lab_cells.py``)."""

_MISSING = dataclasses.MISSING


@dataclass(frozen=True, init=False, kw_only=True)
class LabCell:
    """Base of the laboratory cells: grains, gap and gravity in SI units.

    Subclasses add their drive and geometry, and say which dimensionless cell they make
    (:meth:`cell`). Keyword arguments only; the deprecated aliases of :data:`ALIASES` are
    accepted with a DeprecationWarning.
    """

    name: ClassVar[str] = ""
    """The dimensionless cell's name (``"plane"``, ``"couette"``, ``"channel"``)."""
    coordinate: ClassVar[str] = "y"
    """Name of the wall-normal coordinate of the exported profile."""

    grain_diameter: float
    density: float
    gap: float
    solids_fraction: float = 0.6
    gravity: float = 9.81

    def __init__(self, **kwargs: Any) -> None:
        cls = type(self)
        used = [old for old in ALIASES if old in kwargs]
        for old in used:
            new = ALIASES[old]
            if new in kwargs:
                raise ParameterError(f"give {new} or its deprecated alias {old}, not both")
            kwargs[new] = kwargs.pop(old)
        if used:
            said = ", ".join(f"{old}=... is deprecated; use {ALIASES[old]}=..." for old in used)
            warnings.warn(
                f"{cls.__name__}({said} (the names `cosserat cell` uses)",
                DeprecationWarning,
                stacklevel=2,
            )
        fields = dataclasses.fields(self)
        names = [f.name for f in fields]
        unknown = sorted(k for k in kwargs if k not in names)
        if unknown:
            raise ParameterError(
                f"unknown argument(s) {', '.join(unknown)} of {cls.__name__}; it takes "
                f"{', '.join(names)}"
            )
        for f in fields:
            if f.name in kwargs:
                value = kwargs[f.name]
            elif f.default is not _MISSING:
                value = f.default
            else:
                raise ParameterError(f"{cls.__name__} needs {f.name} [{UNITS[f.name]}]")
            object.__setattr__(self, f.name, value)
        self.__post_init__()

    def __post_init__(self) -> None:
        for f in dataclasses.fields(self):
            value = getattr(self, f.name)
            if value is None:
                continue
            value = require_finite(f.name, value)
            lower_ok = f.name == "gravity" and self._gravity_may_vanish
            if value < 0.0 or (value == 0.0 and not lower_ok):
                bound = ">= 0" if lower_ok else "> 0"
                raise ParameterError(
                    f"{f.name} must be {bound} {UNITS[f.name]}; got {_num(value)}".replace(
                        " 1;", ";"
                    )
                )
            object.__setattr__(self, f.name, value)
        if not self.solids_fraction <= 1.0:
            raise ParameterError(
                f"solids_fraction must satisfy 0 < solids_fraction <= 1; got "
                f"{_num(self.solids_fraction)}"
            )
        if self.grain_diameter > 0.5 * self.gap:
            raise ParameterError(
                f"grain_diameter must be at most half the gap (eps = d_p/H <= 0.5); got "
                f"grain_diameter = {_num(self.grain_diameter)} m, gap = {_num(self.gap)} m"
            )

    _gravity_may_vanish: ClassVar[bool] = False

    # ----------------------------------------------------------------- deprecated names
    def _old(self, old: str) -> float:
        new = ALIASES[old]
        warnings.warn(
            f"{type(self).__name__}.{old} is deprecated; use .{new}",
            DeprecationWarning,
            stacklevel=3,
        )
        return float(getattr(self, new))

    @property
    def d_p(self) -> float:
        """Deprecated: ``grain_diameter`` [m]."""
        return self._old("d_p")

    @property
    def rho_p(self) -> float:
        """Deprecated: ``density`` [kg/m^3]."""
        return self._old("rho_p")

    @property
    def nu(self) -> float:
        """Deprecated: ``solids_fraction`` [-]."""
        return self._old("nu")

    @property
    def g(self) -> float:
        """Deprecated: ``gravity`` [m/s^2]."""
        return self._old("g")

    # ----------------------------------------------------------------- groups
    @property
    def eps(self) -> float:
        """d_p / H [-]."""
        return self.grain_diameter / self.gap

    def velocity_scale(self, profile: Profile | None = None) -> float:
        """The speed velocities are scaled by, V [m/s] (abstract)."""
        raise NotImplementedError

    def stress_scale(self, depth: float | None = None) -> float:
        """The stress the dimensionless stresses are scaled by [Pa] (abstract)."""
        raise NotImplementedError

    def inertial_number(self, depth: float | None = None) -> float:
        """I_w = V d_p / (H sqrt(p / rho_p)) of the drive [-]: computed from the cell's speed,
        stress, grain size and density (the drive of a rate-dependent rheology)."""
        p = self.stress_scale(depth)
        return (
            self.velocity_scale() * self.grain_diameter / (self.gap * math.sqrt(p / self.density))
        )

    def values(self, rate_dependent: bool, depth: float | None = None) -> dict[str, float]:
        """The dimensionless cell's parameters by command-line key (abstract)."""
        raise NotImplementedError

    def cell(self, rate_dependent: bool = False, depth: float | None = None) -> Any:
        """The dimensionless cell (:class:`~cosserat.model.cells.plane.Plane`, ...) for a
        rate-dependent rheology (with its drive I_w) or a rate-independent one (without)."""
        from ..model.cells import CELLS

        return CELLS[self.name](
            **_field_names(CELLS[self.name], self.values(rate_dependent, depth))
        )

    def problem(
        self,
        rheology: Rheology | Material | None = None,
        wall: Wall | None = None,
        *,
        depth: float | None = None,
    ) -> Problem:
        """The dimensionless problem ``Problem(cell, rheology)`` of this cell.

        Parameters
        ----------
        rheology : Rheology, optional
            The law (default: the Cosserat model with the paper's material and wall). A
            :class:`~cosserat.model.parameters.Material` (with ``wall``) is read as the
            Cosserat model's, as before.
        wall : Wall, optional
            The Cosserat model's wall, with a Material.
        depth : float, optional
            Couette cell only: the depth z below the free surface [m] at which a
            rate-dependent law's inertial number is taken (default: the fill depth).
        """
        if rheology is None or isinstance(rheology, Material):
            law: Rheology = Cosserat(
                material=rheology if rheology is not None else Material(),
                wall=wall if wall is not None else Wall(),
            )
        elif isinstance(rheology, Rheology):
            if wall is not None:
                raise ParameterError("wall goes with a Material; a Rheology carries its own")
            law = rheology
        else:
            raise ParameterError(
                f"rheology must be a Rheology (Cosserat, MuI, NGF, ...) or a Material; got "
                f"{type(rheology).__name__}"
            )
        return Problem(self.cell(law.rate_dependent, depth), law)

    # ----------------------------------------------------------------- profiles in SI
    def _check(self, profile: Profile) -> Problem:
        problem = profile.problem
        if not (isinstance(problem, Problem) and problem.cell_name == self.name):
            raise ParameterError(
                f"a {type(self).__name__} needs a profile of the {self.name} cell; got "
                f"{getattr(problem, 'cell_name', type(problem).__name__)}"
            )
        return problem

    def position(self, profile: Profile) -> FloatArray:
        """The wall-normal coordinate at the profile's points [m]."""
        self._check(profile)
        return profile.xi * self.gap

    def velocity(self, profile: Profile) -> FloatArray:
        """Velocity along the flow at the profile's points [m/s] (``u`` times the scale)."""
        self._check(profile)
        return profile.u * self.velocity_scale(profile) + 0.0

    def spin(self, profile: Profile) -> FloatArray:
        """Grain spin about the axis normal to the flow plane [rad/s]: omega V / H (the
        material spin, half the vorticity, for a rheology without grain spin of its own)."""
        self._check(profile)
        omega = profile.omega if profile.omega is not None else profile.half_vorticity
        return omega * self.velocity_scale(profile) / self.gap

    def slip_velocity(self, profile: Profile) -> float:
        """Speed of the slipping wall relative to the grains next to it [m/s] (0 without
        slip)."""
        self._check(profile)
        return float(wall_slip(profile) * self.velocity_scale(profile))

    def wall_shear_stress(self, profile: Profile, depth: float | None = None) -> float:
        """Shear stress on the wall where the stress ratio is largest (the moving wall, the
        inner cylinder, the channel's walls) [Pa]: |sigma_yx| there times the stress scale."""
        problem = self._check(profile)
        s = float(profile.evaluate([problem.cell.peak_wall]).sigma_yx[0])
        return abs(s) * self.stress_scale(depth)

    def thickness(self, profile: Profile) -> float:
        """Shear-layer thickness Delta (``eqn-delta_defn``) [m]."""
        self._check(profile)
        return shear_layer_thickness(profile) * self.grain_diameter

    def inputs(self) -> dict[str, float | None]:
        """The cell's inputs by name (SI units, :data:`UNITS`)."""
        return {f.name: getattr(self, f.name) for f in dataclasses.fields(self)}

    def results(self, profile: Profile, depth: float | None = None) -> dict[str, Any]:
        """Every SI result of ``profile`` by the names ``cosserat cell --format json`` uses:
        ``eps``, ``I_w``, ``velocity_scale``, ``stress_scale``, ``wall_shear_stress``,
        ``slip_velocity``, ``Delta`` (grain diameters), ``Delta_m`` and the profile's
        ``position``, ``velocity``, ``spin`` (units: :data:`UNITS`)."""
        problem = self._check(profile)
        delta = shear_layer_thickness(profile)
        stats = profile.diagnostics.stats
        I_w = stats.get("I_w") if problem.rheology.rate_dependent else None
        out: dict[str, Any] = {
            "eps": self.eps,
            **{
                k: v
                for k, v in problem.cell_values().items()
                if k not in ("eps", "I_w") and v is not None
            },
            "I_w": float(I_w) if I_w is not None else self._inertial_or_none(depth),
            "velocity_scale": self.velocity_scale(profile),
            "stress_scale": self._stress_of(profile, depth),
            "wall_shear_stress": self.wall_shear_stress(profile, depth),
            "slip_velocity": self.slip_velocity(profile),
            "Delta": delta,
            "Delta_m": delta * self.grain_diameter,
            "position": self.position(profile).tolist(),
            "velocity": self.velocity(profile).tolist(),
            "spin": self.spin(profile).tolist(),
        }
        return out

    def _stress_of(self, profile: Profile, depth: float | None) -> float:
        return self.stress_scale(depth)

    def _inertial_or_none(self, depth: float | None) -> float | None:
        try:
            return self.inertial_number(depth)
        except ParameterError:
            return None


@dataclass(frozen=True, init=False, kw_only=True)
class PlaneCell(LabCell):
    """Plane shear between horizontal walls in SI units: the upper wall moves at ``wall_speed``
    under the normal stress ``normal_stress``; the lower one is fixed.

    Parameters
    ----------
    grain_diameter : float
        Mean grain diameter d_p [m].
    density : float
        Intrinsic density of the grains rho_p [kg/m^3].
    gap : float
        Distance H between the walls [m].
    normal_stress : float
        Normal stress N on the upper wall [Pa].
    wall_speed : float
        Speed V of the upper wall [m/s].
    solids_fraction : float
        Solids fraction nu [-] (default 0.6).
    gravity : float
        Gravitational acceleration [m/s^2] (default 9.81; 0: no gravity, B = 0).

    Examples
    --------
    >>> from cosserat import MuI, solve
    >>> from cosserat.analysis.cell import PlaneCell
    >>> cell = PlaneCell(grain_diameter=1e-3, density=2500, gap=0.02, normal_stress=100.0,
    ...                  wall_speed=0.04, gravity=0.0)
    >>> round(cell.inertial_number(), 6)  # V d / (H sqrt(N / rho_p))
    0.01
    >>> profile = solve(cell.problem(MuI()))
    >>> round(cell.wall_shear_stress(profile), 4)  # N mu(I_w) [Pa]
    39.0915
    """

    name: ClassVar[str] = "plane"
    _gravity_may_vanish: ClassVar[bool] = True

    normal_stress: float
    wall_speed: float

    @property
    def B(self) -> float:
        """rho_p g H / N [-]."""
        return self.density * self.gravity * self.gap / self.normal_stress

    def velocity_scale(self, profile: Profile | None = None) -> float:
        """The upper wall's speed V [m/s]."""
        return self.wall_speed

    def stress_scale(self, depth: float | None = None) -> float:
        """The normal stress N on the upper wall [Pa]."""
        if depth is not None:
            raise ParameterError("depth applies to a Couette cell only")
        return self.normal_stress

    def values(self, rate_dependent: bool, depth: float | None = None) -> dict[str, float]:
        out = {"eps": self.eps, "B": self.B, "nu": self.solids_fraction}
        if rate_dependent:
            out["I_w"] = self.inertial_number(depth)
        return out


@dataclass(frozen=True, init=False, kw_only=True)
class CouetteCell(LabCell):
    """A Couette cell in SI units (inner cylinder turning, outer fixed, stresses growing with
    depth below the free surface).

    Parameters
    ----------
    grain_diameter : float
        Mean grain diameter d_p [m] (deprecated alias ``d_p``).
    density : float
        Intrinsic density of the grains rho_p [kg/m^3] (deprecated alias ``rho_p``).
    gap : float
        Radial gap H between the cylinders [m] (measured between glued grain layers if the
        walls are coated, as the paper does).
    inner_radius : float
        Inner-cylinder radius R_i [m] (deprecated alias ``R_i``).
    fill_depth : float
        Depth D of granular material [m].
    rotation_rate : float
        Angular velocity of the inner cylinder Omega [rad/s].
    solids_fraction : float
        Solids fraction nu [-] (default 0.6; deprecated alias ``nu``).
    gravity : float
        Gravitational acceleration [m/s^2] (default 9.81; deprecated alias ``g``).

    Examples
    --------
    >>> from cosserat import solve
    >>> from cosserat.cell import CouetteCell
    >>> cell = CouetteCell(grain_diameter=1e-3, density=2500, gap=0.02, inner_radius=0.02,
    ...                    fill_depth=0.1, rotation_rate=0.5)
    >>> cell.eps, cell.Ri
    (0.05, 1.0)
    >>> profile = solve(cell.problem())
    >>> round(cell.torque(profile), 5)  # [N m]
    0.02931
    >>> round(cell.wall_shear_stress(profile, depth=0.1), 1)  # [Pa]
    535.6
    """

    name: ClassVar[str] = "couette"
    coordinate: ClassVar[str] = "r"

    inner_radius: float
    fill_depth: float
    rotation_rate: float

    def __post_init__(self) -> None:
        super().__post_init__()
        if self.froude > 0.1:
            warnings.warn(
                f"Froude number C = Omega^2 R_i / g = {self.froude:.3g} is not small: the model "
                f"is the leading order in C (section 'Cylindrical Couette flow')",
                stacklevel=3,
            )

    @property
    def R_i(self) -> float:
        """Deprecated: ``inner_radius`` [m]."""
        return self._old("R_i")

    @property
    def Ri(self) -> float:
        """R_i / H [-]."""
        return self.inner_radius / self.gap

    @property
    def wall_speed(self) -> float:
        """V_i = Omega R_i [m/s]."""
        return self.rotation_rate * self.inner_radius

    @property
    def froude(self) -> float:
        """C = V_i^2 / (R_i g) [-]."""
        return self.wall_speed**2 / (self.inner_radius * self.gravity)

    def check_depth(self, depth: float | None) -> float:
        """``depth`` (default: the fill depth), checked: ``0 < depth <= fill_depth`` [m]."""
        if depth is None:
            return self.fill_depth
        z = float(depth)
        if not 0.0 < z <= self.fill_depth:
            raise ParameterError(
                f"depth must satisfy 0 < depth <= fill depth = {_num(self.fill_depth)} m (the "
                f"stresses grow with depth below the free surface); got {_num(z)}"
            )
        return z

    def velocity_scale(self, profile: Profile | None = None) -> float:
        """The inner cylinder's surface speed V_i [m/s]."""
        return self.wall_speed

    def stress_scale(self, depth: float | None = None) -> float:
        """The mean stress sigma_c = rho_p g nu z at depth z (default: the fill depth) [Pa]."""
        return float(self.mean_stress(self.check_depth(depth)))

    def values(self, rate_dependent: bool, depth: float | None = None) -> dict[str, float]:
        out = {"eps": self.eps, "Ri": self.Ri}
        if rate_dependent:
            out["I_w"] = self.inertial_number(depth)
        return out

    def mean_stress(self, depth: float | FloatArray) -> FloatArray:
        """sigma_c = rho_p g nu z at depth z below the free surface [Pa]."""
        z = np.asarray(depth, dtype=float)
        if np.any(~np.isfinite(z)) or np.any(z < 0.0) or np.any(z > self.fill_depth):
            raise ParameterError(
                f"depth must satisfy 0 <= depth <= fill depth = {_num(self.fill_depth)} m"
            )
        return self.density * self.gravity * self.solids_fraction * z

    def radius(self, profile: Profile) -> FloatArray:
        """r = R_i + xi H at the profile's points [m]."""
        self._check(profile)
        return self.inner_radius + profile.xi * self.gap

    def position(self, profile: Profile) -> FloatArray:
        """The radius r at the profile's points [m]."""
        return self.radius(profile)

    def velocity(self, profile: Profile) -> FloatArray:
        """Azimuthal velocity v_theta (anticlockwise positive) [m/s]: v = -u V_i."""
        self._check(profile)
        return -profile.u * self.wall_speed + 0.0

    def spin(self, profile: Profile) -> FloatArray:
        """Grain spin omega_z about the upward axis [rad/s]: omega V_i / H (the material spin,
        half the vorticity, for a rheology without grain spin of its own)."""
        return super().spin(profile)

    def slip_velocity(self, profile: Profile) -> float:
        """V_i - v_theta at the inner cylinder [m/s] (>= 0: the grains lag the wall)."""
        self._check(profile)
        return float((1.0 + profile.evaluate([0.0]).u[0]) * self.wall_speed)

    def _depth_of(self, profile: Profile, depth: float | None) -> float:
        """``depth`` checked, and for a rate-dependent law checked against the profile's
        inertial number (the profile holds at one depth only)."""
        z = self.check_depth(depth)
        problem = profile.problem
        if problem.rheology.rate_dependent:
            I_p = problem.cell_values().get("I_w")
            I_z = self.inertial_number(z)
            if I_p is None or not math.isclose(float(I_p), I_z, rel_tol=1e-9):
                raise ParameterError(
                    f"the profile is not at depth {_num(z)} m: its I_w = {_num(I_p)}, the cell's "
                    f"at that depth {_num(I_z)} (a rate-dependent law's profile changes with "
                    f"depth; solve cell.problem(rheology, depth={_num(z)}))"
                )
        return z

    def wall_shear_stress(self, profile: Profile, depth: float | None = None) -> float:
        """Shear stress on the inner cylinder at depth z [Pa]: sigma_c tan(delta) there
        (``0 < depth <= fill_depth``; default the fill depth)."""
        z = self._depth_of(profile, depth)
        return float(-profile.evaluate([0.0]).sigma_yx[0] * self.mean_stress(z))

    def torque_density(self, profile: Profile, depth: float | None = None) -> FloatArray:
        """T(r) per unit height at depth z across each cylinder r of the profile [N m / m].

        The same at every r (module docstring); at r = R_i it is the driving torque.
        """
        z = self._depth_of(profile, depth)
        return self._torque_density(profile, z)

    def _torque_density(self, profile: Profile, z: float) -> FloatArray:
        problem = self._check(profile)
        r = self.Ri + profile.xi
        bracket = -(r**2) * profile.sigma_yx
        if profile.m is not None:
            couple = equations_of(problem, CosseratCouette).couple_factor  # m: a couple stress law
            bracket = bracket + couple * r * profile.m
        return 2.0 * math.pi * self.mean_stress(z) * self.gap**2 * bracket

    def shear_torque_density(self, profile: Profile, depth: float | None = None) -> float:
        """The wall shear stress's share of the torque per unit height at depth z,
        2 pi R_i^2 tau_w [N m / m]; the rest of :meth:`torque_density` at r = R_i is the wall
        couple stress's share."""
        return 2.0 * math.pi * self.inner_radius**2 * self.wall_shear_stress(profile, depth)

    def torque(self, profile: Profile, **options: Any) -> float:
        """Torque on the inner cylinder over the fill depth D [N m].

        Rate-independent law: T per unit height grows linearly with depth (sigma_c = rho_p g
        nu z), so the total is T'(D) D / 2. Rate-dependent law: the inertial number changes
        with depth, so the torque per unit height is integrated over depth by
        :data:`TORQUE_NODES`-point Gauss-Legendre quadrature in s = sqrt(z/D) (where the
        integrand is smooth), one solve per node by the profile's method (``options``:
        further solve options).
        """
        problem = self._check(profile)
        D = self.fill_depth
        if not problem.rheology.rate_dependent:
            return 0.5 * float(self._torque_density(profile, D)[0]) * D
        from ..routes import solve

        # z = D s^2: the inertial number goes as 1/s, the integrand is smooth in s
        nodes, weights = np.polynomial.legendre.leggauss(TORQUE_NODES)
        total = 0.0
        for x, w in zip(nodes, weights, strict=True):
            s = 0.5 * (x + 1.0)
            z = D * s * s
            at = problem.with_values({"I_w": self.inertial_number(z)})
            p = solve(at, method=profile.method, points=3, **options)
            total += 0.5 * float(w) * 2.0 * D * s * float(self._torque_density(p, z)[0])
        return float(total)

    def results(self, profile: Profile, depth: float | None = None) -> dict[str, Any]:
        """:meth:`LabCell.results` plus the torque (``torque``, ``torque_per_height``,
        ``torque_per_height_shear``), ``mean_stress``, ``depth`` and ``froude``."""
        z = self._depth_of(profile, depth)
        out = super().results(profile, z)
        out.update(
            {
                "froude": self.froude,
                "depth": z,
                "mean_stress": float(self.mean_stress(z)),
                "torque": self.torque(profile),
                "torque_per_height": float(self._torque_density(profile, z)[0]),
                "torque_per_height_shear": self.shear_torque_density(profile, z),
            }
        )
        return out


@dataclass(frozen=True, init=False, kw_only=True)
class ChannelCell(LabCell):
    """Gravity flow between two vertical walls at rest, in SI units.

    The wall normal stress N sets the wall stress ratio ``B nu / 2`` (``B = rho_p g H / N``).
    For a rate-dependent law (mu(I), NGF) the flow then follows: the centre-line speed is an
    output. For the rate-independent Cosserat model fully developed flow needs fully
    mobilised wall friction (B nu = 2 tan delta): give ``centre_speed`` to scale the
    velocities and leave N out (it is an output); a given N that does not match has no steady
    flow (the error says which B would).

    Parameters
    ----------
    grain_diameter, density, gap, solids_fraction, gravity
        As :class:`LabCell` (the gap is the channel's width H [m]).
    normal_stress : float, optional
        Normal stress N on the walls [Pa] (required for a rate-dependent law).
    centre_speed : float, optional
        Centre-line speed V_c [m/s] (the Cosserat model only: its velocity scale).
    """

    name: ClassVar[str] = "channel"

    normal_stress: float | None = None
    centre_speed: float | None = None

    @property
    def B(self) -> float | None:
        """rho_p g H / N [-] (None without N)."""
        if self.normal_stress is None:
            return None
        return self.density * self.gravity * self.gap / self.normal_stress

    def velocity_scale(self, profile: Profile | None = None) -> float:
        """The centre-line speed V_c [m/s]: given, or for a rate-dependent law from the
        profile's inertial number, V_c = I_w H sqrt(N / rho_p) / d_p."""
        if self.centre_speed is not None:
            return self.centre_speed
        if profile is None or not profile.problem.rheology.rate_dependent:
            raise ParameterError(
                "centre_speed [m/s] is needed: the Cosserat model is rate-independent, its "
                "velocity scale is not set by the stresses"
            )
        I_w = float(profile.diagnostics.stats["I_w"])
        return (
            I_w
            * self.gap
            * math.sqrt(self.stress_scale(profile=profile) / self.density)
            / (self.grain_diameter)
        )

    def stress_scale(self, depth: float | None = None, profile: Profile | None = None) -> float:
        """The wall normal stress N [Pa]: given, or (the Cosserat model) rho_p g H / B with B
        the fully mobilised value of the profile."""
        if depth is not None:
            raise ParameterError("depth applies to a Couette cell only")
        if self.normal_stress is not None:
            return self.normal_stress
        if profile is not None:
            B = profile.problem.parameters().get("B")
            if B:
                return self.density * self.gravity * self.gap / float(B)
        raise ParameterError("normal_stress [Pa] is needed (the wall normal stress N)")

    def inertial_number(self, depth: float | None = None) -> float:
        """I_w of the given centre-line speed and wall normal stress [-] (both needed)."""
        if self.centre_speed is None:
            raise ParameterError("centre_speed [m/s] is needed for the inertial number")
        return super().inertial_number(depth)

    def values(self, rate_dependent: bool, depth: float | None = None) -> dict[str, float]:
        if rate_dependent:
            if self.normal_stress is None:
                raise ParameterError(
                    "normal_stress [Pa] is needed for a rate-dependent law in the channel: "
                    "the wall normal stress sets the flow (the centre-line speed is an output)"
                )
            if self.centre_speed is not None:
                raise ParameterError(
                    "centre_speed does not apply to a rate-dependent law in the channel: the "
                    "wall normal stress sets the flow and the centre-line speed is an output"
                )
        elif self.centre_speed is None:
            raise ParameterError(
                "centre_speed [m/s] is needed for the Cosserat model in the channel: it is "
                "rate-independent, the speed only scales the velocities"
            )
        out: dict[str, float] = {"eps": self.eps, "nu": self.solids_fraction}
        if self.B is not None:
            out["B"] = self.B
        return out

    def wall_shear_stress(self, profile: Profile, depth: float | None = None) -> float:
        """Shear stress on the walls [Pa]: N B nu / 2 = rho_p g nu H / 2 (the weight)."""
        problem = self._check(profile)
        s = float(profile.evaluate([problem.cell.peak_wall]).sigma_yx[0])
        return abs(s) * self.stress_scale(depth, profile)

    def results(self, profile: Profile, depth: float | None = None) -> dict[str, Any]:
        """:meth:`LabCell.results` with the wall normal stress and B the flow has."""
        out = super().results(profile, depth)
        out["normal_stress"] = self.stress_scale(depth, profile)
        out["B"] = float(profile.problem.parameters()["B"])
        return out

    def _inertial_or_none(self, depth: float | None) -> float | None:
        return None

    def _stress_of(self, profile: Profile, depth: float | None) -> float:
        return self.stress_scale(depth, profile)


def _field_names(cls: type, values: Mapping[str, float]) -> dict[str, float]:
    """Command-line keys -> the cell class's field names."""
    from ..model.declare import declarations

    names = {p.cli_key: n for n, p in declarations(cls).items()}
    return {names[k]: v for k, v in values.items()}


def _num(value: Any) -> str:
    """A number as messages print it (``-1``, ``0.5``, ``1e-20``), never ``np.float64(...)``."""
    if value is None:
        return "None"
    try:
        return f"{float(value):g}"
    except (TypeError, ValueError):
        return str(value)


LAB_CELLS: dict[str, type[LabCell]] = {
    "plane": PlaneCell,
    "couette": CouetteCell,
    "channel": ChannelCell,
}
"""The laboratory cell of each dimensionless cell, by the cell's name."""

__all__ = ["ALIASES", "LAB_CELLS", "UNITS", "ChannelCell", "CouetteCell", "LabCell", "PlaneCell"]
