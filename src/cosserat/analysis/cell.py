"""A real Couette cell: dimensional inputs in, dimensional profiles, stresses and torque out.

The dimensionless Couette profile (:class:`~cosserat.model.cells.couette.Couette` with the
:class:`~cosserat.model.rheologies.cosserat.Cosserat` model) does not
depend on depth at leading order in the Froude number: stresses scale with the local mean
stress ``sigma_c = rho_p g nu z`` at depth z below the free surface (``eqn-nd_zmom_cyl``), and the
velocity with the inner cylinder's surface speed ``V_i = Omega R_i``.

Torque. In a Cosserat medium the torque per unit height carried across the cylinder of radius r
is not the shear stress alone: with the traction and the couple per unit area on that surface,
``T(r) = 2 pi r (r sigma_(r theta) + M_rz)`` (literal signs). theta-momentum,
``d sigma_rt/dr + (sigma_rt + sigma_tr)/r = 0``, and the couple-stress balance,
``(1/r) d(r M_rz)/dr + sigma_rt - sigma_tr = 0``, give ``dT/dr = 0``: T is the same across the
gap (``docs/derivation_couette.md``). In the paper's variables (u and shear stresses along
-e_theta)::

    T = 2 pi sigma_c H^2 [ -(Ri + xi)^2 s_rt(xi) + 2(A+1) eps alpha (Ri + xi) m(xi) ],

and at the inner cylinder, where s_rt = -tan(delta), it is the torque that drives the cylinder.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass

import numpy as np

from ..errors import ParameterError
from ..model import Cosserat, Couette, Problem
from ..model.constitutive import FloatArray
from ..model.parameters import Material, Wall, require_finite
from ..model.rheologies.cosserat import CosseratCouette
from ..results.profile import Profile


@dataclass(frozen=True, kw_only=True)
class CouetteCell:
    """A Couette cell in SI units (inner cylinder turning, outer fixed).

    Parameters
    ----------
    rho_p : float
        Intrinsic density of the grains [kg/m^3].
    d_p : float
        Mean grain diameter [m].
    gap : float
        Radial gap H between the cylinders [m] (measured between glued grain layers if the
        walls are coated, as the paper does).
    R_i : float
        Inner-cylinder radius [m].
    fill_depth : float
        Depth of granular material [m].
    rotation_rate : float
        Angular velocity of the inner cylinder Omega [rad/s].
    nu : float
        Solids fraction [-] (default 0.6).
    g : float
        Gravitational acceleration [m/s^2] (default 9.81).

    Examples
    --------
    >>> from cosserat import Material, Wall, solve
    >>> from cosserat.cell import CouetteCell
    >>> cell = CouetteCell(
    ...     rho_p=2500, d_p=1e-3, gap=0.02, R_i=0.02, fill_depth=0.1, rotation_rate=0.5
    ... )
    >>> cell.eps, cell.Ri
    (0.05, 1.0)
    >>> profile = solve(cell.problem(Material(), Wall()))
    >>> round(cell.torque(profile), 5)  # [N m]
    0.02931
    >>> round(cell.wall_shear_stress(profile, depth=0.1), 1)  # [Pa]
    535.6
    """

    rho_p: float
    d_p: float
    gap: float
    R_i: float
    fill_depth: float
    rotation_rate: float
    nu: float = 0.6
    g: float = 9.81

    def __post_init__(self) -> None:
        for name in ("rho_p", "d_p", "gap", "R_i", "fill_depth", "rotation_rate", "g"):
            value = require_finite(name, getattr(self, name))
            if value <= 0.0:
                raise ParameterError(f"{name} must be > 0; got {value:g}")
            object.__setattr__(self, name, value)
        nu = require_finite("nu", self.nu)
        if not 0.0 < nu <= 1.0:
            raise ParameterError(f"nu (solids fraction) must satisfy 0 < nu <= 1; got {nu:g}")
        if self.d_p > 0.5 * self.gap:
            raise ParameterError(
                f"d_p must be at most half the gap (eps = d_p/gap <= 0.5); got "
                f"d_p = {self.d_p:g} m, gap = {self.gap:g} m"
            )
        if self.froude > 0.1:
            warnings.warn(
                f"Froude number C = Omega^2 R_i / g = {self.froude:.3g} is not small: the model is "
                f"the leading order in C (section 'Cylindrical Couette flow')",
                stacklevel=2,
            )

    @property
    def eps(self) -> float:
        """d_p / H [-]."""
        return self.d_p / self.gap

    @property
    def Ri(self) -> float:
        """R_i / H [-]."""
        return self.R_i / self.gap

    @property
    def wall_speed(self) -> float:
        """V_i = Omega R_i [m/s]."""
        return self.rotation_rate * self.R_i

    @property
    def froude(self) -> float:
        """C = V_i^2 / (R_i g) [-]."""
        return self.wall_speed**2 / (self.R_i * self.g)

    def problem(self, material: Material, wall: Wall) -> Problem:
        """The dimensionless problem of this cell: the Cosserat model on the Couette cell."""
        return Problem(Couette(eps=self.eps, Ri=self.Ri), Cosserat(material=material, wall=wall))

    def mean_stress(self, depth: float | FloatArray) -> FloatArray:
        """sigma_c = rho_p g nu z at depth z below the free surface [Pa]."""
        return self.rho_p * self.g * self.nu * np.asarray(depth, dtype=float)

    def radius(self, profile: Profile) -> FloatArray:
        """r = R_i + xi H at the profile's points [m]."""
        return self.R_i + profile.xi * self.gap

    def velocity(self, profile: Profile) -> FloatArray:
        """Azimuthal velocity v_theta (anticlockwise positive) [m/s]: v = -u V_i."""
        return -profile.u * self.wall_speed

    def spin(self, profile: Profile) -> FloatArray:
        """Grain spin omega_z about the upward axis [rad/s]: omega V_i / H (the material spin,
        half the vorticity, for a rheology without grain spin of its own)."""
        omega = profile.omega if profile.omega is not None else profile.half_vorticity
        return omega * self.wall_speed / self.gap

    def slip_velocity(self, profile: Profile) -> float:
        """V_i - v_theta at the inner cylinder [m/s] (>= 0: the grains lag the wall)."""
        return float((1.0 + profile.evaluate([0.0]).u[0]) * self.wall_speed)

    def wall_shear_stress(self, profile: Profile, depth: float) -> float:
        """Shear stress on the inner cylinder at depth z [Pa]: sigma_c tan(delta) there."""
        return float(-profile.evaluate([0.0]).sigma_yx[0] * self.mean_stress(depth))

    def torque_density(self, profile: Profile, depth: float) -> FloatArray:
        """T(r) per unit height at depth z across each cylinder r of the profile [N m / m].

        The same at every r (module docstring); at r = R_i it is the driving torque.
        """
        p = _couette(profile)
        r = p.Ri + profile.xi
        bracket = -(r**2) * profile.sigma_yx + p.couple_factor * r * profile.m
        return 2.0 * math.pi * self.mean_stress(depth) * self.gap**2 * bracket

    def shear_torque_density(self, profile: Profile, depth: float) -> float:
        """The wall shear stress's share of the torque per unit height at depth z,
        2 pi R_i^2 tau_w [N m / m]; the rest of :meth:`torque_density` at r = R_i is the wall
        couple stress's share."""
        return 2.0 * math.pi * self.R_i**2 * self.wall_shear_stress(profile, depth)

    def torque(self, profile: Profile) -> float:
        """Torque on the inner cylinder over the fill depth D [N m].

        T per unit height grows linearly with depth (sigma_c = rho_p g nu z), so the total is
        T'(D) D / 2.
        """
        per_height = float(self.torque_density(profile, self.fill_depth)[0])
        return 0.5 * per_height * self.fill_depth


def _couette(profile: Profile) -> CosseratCouette:
    problem = profile.problem
    if not (
        isinstance(problem, Problem)
        and problem.cell_name == "couette"
        and problem.model == "cosserat"
    ):
        raise ParameterError("a CouetteCell needs a Couette profile of the Cosserat model")
    return problem.equations  # type: ignore[return-value]
