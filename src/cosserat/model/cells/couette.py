"""Cylindrical Couette flow at leading order in the Froude number (section "Cylindrical Couette
flow"; ``docs/derivation_couette.md``).

The inner cylinder (radius R_i, xi = 0) turns, the outer one (R_i + H, xi = 1) is fixed.
Variables: ``xi = (r - R_i)/H``, ``Ri = R_i/H``, stresses over the local mean stress (uniform
across the gap at leading order in C = V_i^2/(R_i g), so profiles do not depend on depth). Signs
are the paper's: the inner cylinder turns anticlockwise about +z at surface speed V_i and
``u = -v_theta/V_i`` (so u = -1 at the inner wall), ``sigma_r_theta = -sigma_(r theta)/sigma_c``.

Statics: the radial balance gives a uniform normal stress, the torque balance a shear stress
falling like r^-2, ``sigma_r_theta = -T (Ri/(Ri + xi))^2`` (:func:`torque_decay`) with T the stress
ratio at the inner cylinder, where it is largest. (The Cosserat model adds its couple-stress
terms to this, ``eqn-nd_shsts_cyl``: that part belongs to the Cosserat rheology.)
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, ClassVar

import numpy as np
from numba import njit

from ... import config
from ..constitutive import FloatArray
from ..declare import param
from .base import Cell, Coordinate, wall_inertial_number_param
from .plane import stress_ratio_param

RI_MIN, RI_MAX = 1e-3, 1e6


@njit(cache=True, nogil=True)
def torque_decay(xi: Any, Ri: float) -> Any:
    """(Ri/(Ri + xi))^2: the shear stress over its inner-wall value (torque balance) [-].

    Compiled: the solver kernels call it on numbers, the cell on arrays.
    """
    return (Ri / (Ri + xi)) ** 2


@dataclass(frozen=True, kw_only=True)
class Couette(Cell):
    """Cylindrical Couette flow between coaxial cylinders, the inner one (xi = 0) turning.

    Parameters
    ----------
    eps : float
        Grain diameter over gap d_p/H, ``1e-8 <= eps <= 0.5`` [-].
    Ri : float, default :data:`cosserat.config.RI`
        Inner radius over gap R_i/H, ``1e-3 <= Ri <= 1e6`` [-].
    I_w : float, optional
        Inertial number of the inner wall's speed, V_i d / (H sqrt(p/rho_s)) at the depth of
        the profile, ``0 < I_w <= 1`` [-]: the drive of a rate-dependent rheology (default
        :data:`cosserat.config.MUI_I_W`).
    stress_ratio : float, optional
        Instead of I_w: the imposed tau_i/p at the inner cylinder (the torque) [-].

    Examples
    --------
    >>> from cosserat import Couette
    >>> Couette(eps=0.04).Ri
    1.0
    """

    name: ClassVar[str] = "couette"
    title: ClassVar[str] = "Couette flow"
    coordinate: ClassVar[Coordinate] = Coordinate(
        "r",
        "radius over the gap, r/H (inner cylinder at r/H = R_i/H, outer at R_i/H + 1)",
        lambda cell, xi: cell.Ri + xi,
        {
            "u": ("u", "velocity -v_theta over the inner cylinder's speed V_i (-1 at it)"),
            "omega": ("omega", "grain spin omega_z H / V_i"),
            "m": ("m", "couple stress M_rz / (L sqrt(2(A+1)) sigma_c d_p)"),
            "sigma_xy": ("sigma_theta_r", "shear stress sigma_theta_r over the mean stress"),
            "sigma_yx": (
                "sigma_r_theta",
                "shear stress on cylinders sigma_r_theta over the mean stress",
            ),
            "sigma_yy": ("sigma_rr", "radial normal stress sigma_rr over the mean stress"),
            "asymmetry": ("asymmetry", "stress asymmetry sigma_r_theta - sigma_theta_r"),
        },
    )
    peak_wall: ClassVar[float] = 0.0
    straight: ClassVar[bool] = False
    moving_wall: ClassVar[float | None] = 0.0
    velocity_scale: ClassVar[tuple[float, float]] = (0.0, -1.0)
    layer_wall: ClassVar[float] = 0.0
    reference_velocity: ClassVar[float] = 0.0
    peak_wall_name: ClassVar[str] = "turning inner cylinder"

    Ri: float = param(
        config.RI,
        "inner radius over gap, R_i/H",
        bounds=(RI_MIN, RI_MAX),
        closed=(True, True),
        role="cell",
        source="the run's geometry",
    )
    I_w: float | None = wall_inertial_number_param("turning inner cylinder")
    stress_ratio: float | None = stress_ratio_param("turning inner cylinder")

    def wall_velocity(self, xi_wall: float) -> float:
        """u of the wall: -1 at the turning inner cylinder, 0 at the outer one [-]."""
        return -1.0 if xi_wall == 0.0 else 0.0

    def normal_stress(self, xi: FloatArray) -> FloatArray:
        """sigma_rr over the local mean stress: 1 [-]."""
        return np.ones_like(np.asarray(xi, dtype=float))

    def shear_stress(self, xi: FloatArray, level: float) -> FloatArray:
        """sigma_r_theta = -T (Ri/(Ri + xi))^2 (:func:`torque_decay`) [-]."""
        return -level * torque_decay(np.asarray(xi, dtype=float), self.Ri)

    def ratio_shape(self, t: FloatArray) -> tuple[FloatArray, FloatArray]:
        """q = (Ri/(Ri + t))^2, 1 - q = t (2 Ri + t)/(Ri + t)^2 at t = xi [-]."""
        x = np.asarray(t, dtype=float)
        r2 = (self.Ri + x) ** 2
        return torque_decay(x, self.Ri), x * (2.0 * self.Ri + x) / r2

    def distance_of_ratio(self, r: float) -> float:
        """t = Ri (sqrt(r) - 1) [-]."""
        return self.Ri * (float(np.sqrt(r)) - 1.0)

    @property
    def ratio_slope(self) -> float:
        return 2.0 / self.Ri

    def curvature(self, xi: FloatArray) -> FloatArray:
        """1/(Ri + xi) [-]."""
        return 1.0 / (self.Ri + np.asarray(xi, dtype=float))

    def radius(self, xi: FloatArray) -> FloatArray:
        """r/H = Ri + xi [-]."""
        return self.Ri + np.asarray(xi, dtype=float)

    def radius_at(self, t: FloatArray) -> FloatArray:
        """Ri + t: the distance t from the inner cylinder is xi [-]."""
        return self.Ri + np.asarray(t, dtype=float)
