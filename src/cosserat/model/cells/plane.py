"""Plane shear between horizontal walls (section "Application to plane shear").

The upper wall (xi = 1) moves at speed V in +x under the normal stress N; the lower wall
(xi = 0) is fixed. Scalings (``dimlessvar``): xi = y/H, u = v_x/V, stresses over N;
eps = d_p/H, B = rho_p g H / N.

Statics: the y-momentum balance with ``eqn-nd_bc1`` gives ``sigma_yy = sigma_c =
1 + B nu (1 - xi)`` (:func:`mean_stress`); the x-momentum balance a uniform shear stress,
``sigma_yx = -T``. The stress ratio ``T/(1 + B nu (1 - xi))`` is largest at the upper wall,
where sigma_yy = 1, so T is the stress ratio there.
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

B_MAX = 1e6
"""Largest B: beyond, stresses of order (B sin phi)^2 leave the range of doubles soon."""


@njit(cache=True, nogil=True)
def mean_stress(xi: Any, B_nu: float) -> Any:
    """sigma_c = sigma_yy = 1 + B nu (1 - xi): ``eqn-nd_ymom`` with ``eqn-nd_bc1`` [-].

    Compiled: the solver kernels call it on numbers, the cell on arrays.
    """
    return 1.0 + B_nu * (1.0 - xi)


def gravity_param(default: Any, meaning: str, lower: float, closed: bool, **spec: Any) -> Any:
    """The declaration of B = rho_p g H / N (plane shear and the channel)."""
    return param(
        default,
        meaning,
        bounds=(lower, B_MAX),
        closed=(closed, True),
        role="cell",
        reason=f"the weight of the layer at most {B_MAX:g} times the normal stress",
        source="the run's loading",
        **spec,
    )


def nu_param() -> Any:
    """The declaration of the solids fraction nu (only B nu enters)."""
    return param(
        config.NU,
        "solids fraction (only B nu enters)",
        bounds=(0.0, 1.0),
        closed=(False, True),
        role="cell",
        source="the run's packing",
    )


def stress_ratio_param(where: str) -> Any:
    """The declaration of an imposed wall stress ratio (instead of I_w)."""
    return param(
        None,
        f"imposed stress ratio |sigma_yx|/sigma_yy at the {where}, instead of I_w (the wall "
        "speed is then an output)",
        bounds=(0.0, float("inf")),
        role="drive",
        optional=True,
    )


@dataclass(frozen=True, kw_only=True)
class Plane(Cell):
    """Plane shear between two horizontal walls; the upper wall (xi = 1) moves.

    Parameters
    ----------
    eps : float
        Grain diameter over gap d_p/H, ``1e-8 <= eps <= 0.5`` [-].
    B : float, default :data:`cosserat.config.B` (0: no gravity)
        Gravity parameter rho_p g H / N, ``0 <= B <= 1e6`` [-].
    nu : float, default :data:`cosserat.config.NU`
        Solids fraction, ``0 < nu <= 1`` [-]; only B nu enters.
    I_w : float, optional
        Inertial number of the upper wall's speed, V d / (H sqrt(N/rho_s)), ``0 < I_w <= 1``
        [-]: the drive of a rate-dependent rheology (default :data:`cosserat.config.MUI_I_W`;
        the rate-independent Cosserat model has none).
    stress_ratio : float, optional
        Instead of I_w: the imposed tau/N at the upper wall [-].

    Examples
    --------
    >>> from cosserat import Plane
    >>> cell = Plane(eps=0.01, B=1.0)
    >>> cell.normal_stress([0.0, 1.0]).tolist()  # 1 + B nu (1 - xi)
    [2.0, 1.0]
    """

    name: ClassVar[str] = "plane"
    title: ClassVar[str] = "plane shear"
    coordinate: ClassVar[Coordinate] = Coordinate(
        "y",
        "height above the fixed lower wall over the gap, y/H (0 to 1)",
        lambda cell, xi: xi,
        {
            "u": ("u", "velocity u_x over the moving upper wall's speed V"),
            "omega": ("omega", "grain spin omega_z H / V"),
            "sigma_xy": ("sigma_xy", "shear stress sigma_xy over the normal stress N"),
            "sigma_yx": ("sigma_yx", "shear stress on wall-parallel planes sigma_yx over N"),
            "sigma_yy": ("sigma_yy", "normal stress sigma_yy over N"),
        },
    )
    peak_wall: ClassVar[float] = 1.0
    moving_wall: ClassVar[float | None] = 1.0
    velocity_scale: ClassVar[tuple[float, float]] = (1.0, 1.0)
    layer_wall: ClassVar[float] = 1.0
    reference_velocity: ClassVar[float] = 0.0
    peak_wall_name: ClassVar[str] = "moving upper wall"

    B: float = gravity_param(config.B, "gravity parameter rho_p g H / N (0: no gravity)", 0.0, True)
    nu: float = nu_param()
    I_w: float | None = wall_inertial_number_param("moving upper wall")
    stress_ratio: float | None = stress_ratio_param("moving upper wall")

    @property
    def B_nu(self) -> float:
        """B nu, the one gravity group of the statics [-]."""
        return self.B * self.nu

    def normal_stress(self, xi: FloatArray) -> FloatArray:
        """sigma_yy = 1 + B nu (1 - xi) (:func:`mean_stress`) [-].

        A number gives a float, computed in Python with :func:`mean_stress`'s operations (the
        same bits): the compiled function's dispatch on a 0-d array cost more than the rest
        of making a new problem's constants (``docs/performance.md``).
        """
        if isinstance(xi, float | int):
            return 1.0 + self.B_nu * (1.0 - xi)
        return mean_stress(np.asarray(xi, dtype=float), self.B_nu)

    def normal_stress_at(self, t: FloatArray) -> FloatArray:
        """1 + B nu t at t = 1 - xi [-]."""
        return 1.0 + self.B_nu * np.asarray(t, dtype=float)

    def shear_stress(self, xi: FloatArray, level: float) -> FloatArray:
        """sigma_yx = -T, uniform (x-momentum) [-]."""
        return np.full_like(np.asarray(xi, dtype=float), -level)

    def ratio_shape(self, t: FloatArray) -> tuple[FloatArray, FloatArray]:
        """q = 1/(1 + B nu t), 1 - q = B nu t/(1 + B nu t) at t = 1 - xi [-]."""
        g = self.B_nu * np.asarray(t, dtype=float)
        return 1.0 / (1.0 + g), g / (1.0 + g)

    def distance_of_ratio(self, r: float) -> float:
        """t = (r - 1)/(B nu) [-]."""
        return (r - 1.0) / self.B_nu if self.B_nu > 0.0 else (0.0 if r == 1.0 else float("inf"))

    @property
    def ratio_slope(self) -> float:
        return self.B_nu
