"""Fully developed gravity flow between two vertical walls (``docs/derivation_channel.md``).

Conventions: x downward along gravity, y across the channel, ``xi = y/H`` in [0, 1] with the
walls (at rest) at 0 and 1 and the centre line at 1/2; the velocity u >= 0 is downward and
scaled by its centre-line value, ``u(1/2) = 1``; stresses are compressive-positive and scaled
by the wall normal stress N.

Statics (doc section 1): the y-momentum balance gives a uniform normal stress ``sigma_yy = 1``;
the x-momentum balance a shear stress linear in xi, ``sigma_yx = B nu (xi - 1/2)``
(:func:`shear_stress`) with ``B = rho_p g H / N``. The stress ratio is largest at the walls,
``T = B nu / 2``; the flow is symmetric about the centre line.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, ClassVar

import numpy as np
from numba import njit

from ..constitutive import FloatArray
from ..declare import Constraint
from .base import Cell, Coordinate, wall_inertial_number_param
from .plane import gravity_param, nu_param

B_NU_MIN = 1e-4
"""Smallest B nu, twice the wall stress ratio [-]. The Cosserat channel's layer thins like B
(Delta = 1.6e-3 grain diameters at B = 1e-4) and its residuals grow as B falls: at eps = 1e-3,
nu = 0.6 the velocity residual is 1.7e-8 at B = 1e-4, 1.8e-7 at 1e-5, 8e-6 at 1e-6, 3.7e140 at
1e-8; B = 1e-200 ran past 60 s and 5e-324 divided by zero (measured)."""


@njit(cache=True, nogil=True)
def shear_stress(xi: Any, B_nu: float) -> Any:
    """sigma_yx = B nu (xi - 1/2): x-momentum with symmetry (doc section 1); its magnitude
    tau on the upper half, where the kernels work [-]."""
    return B_nu * (xi - 0.5)


@dataclass(frozen=True, kw_only=True)
class VerticalChannel(Cell):
    """Fully developed gravity flow between two vertical walls at rest.

    Parameters
    ----------
    eps : float
        Grain diameter over the channel width d_p/H, ``1e-8 <= eps <= 0.5`` [-].
    B : float, optional
        rho_p g H / N with N the wall normal stress, ``0 < B <= 1e6`` and ``B nu >= 1e-4``
        (:data:`B_NU_MIN`) [-]: the wall stress
        ratio is B nu / 2 (the stress level). None: set by the drive, I_w for a
        rate-dependent rheology, fully mobilised wall friction (B nu = 2 tan delta) for the
        Cosserat model.
    nu : float, default :data:`cosserat.config.NU`
        Solids fraction, ``0 < nu <= 1`` [-]; only B nu enters.
    I_w : float, optional
        Instead of B: the inertial number of the centre-line speed, V_c d/(H sqrt(N/rho_s)),
        ``0 < I_w <= 1`` [-] (default :data:`cosserat.config.MUI_I_W` when B is not given,
        for a rate-dependent rheology); B is then an output.

    Examples
    --------
    >>> from cosserat import VerticalChannel
    >>> VerticalChannel(eps=0.02, B=1.0).imposed_level()  # the wall stress ratio B nu / 2
    0.5
    """

    name: ClassVar[str] = "channel"
    title: ClassVar[str] = "vertical channel"
    coordinate: ClassVar[Coordinate] = Coordinate(
        "y",
        "distance across the channel over its width, y/H (walls at 0 and 1)",
        lambda cell, xi: xi,
        {
            "u": ("u", "downward velocity over its centre-line value"),
            "omega": ("omega", "grain spin omega_z H / u_centre"),
            "sigma_xy": ("sigma_xy", "shear stress sigma_xy over the wall normal stress N"),
            "sigma_yx": ("sigma_yx", "shear stress on wall-parallel planes sigma_yx over N"),
            "sigma_yy": ("sigma_yy", "normal stress sigma_yy over N"),
        },
    )
    peak_wall: ClassVar[float] = 1.0
    symmetric: ClassVar[bool] = True
    moving_wall: ClassVar[float | None] = None
    velocity_scale: ClassVar[tuple[float, float]] = (0.5, 1.0)
    layer_wall: ClassVar[float] = 1.0
    reference_velocity: ClassVar[float] = 1.0
    level_name: ClassVar[str] = "B"
    peak_wall_name: ClassVar[str] = "walls"
    constraints: ClassVar[tuple[Constraint, ...]] = (
        Constraint(
            ("B", "nu"),
            f"B nu >= {B_NU_MIN:g}",
            lambda B, nu: B * nu >= B_NU_MIN,
            "a wall stress ratio B nu/2 below 5e-5 thins the shear layer below 1e-3 grain "
            "diameters, where the solver's residuals exceed its tolerance",
        ),
    )

    B: float | None = gravity_param(
        None,
        "rho_p g H / N with N the wall normal stress (the wall stress ratio is B nu/2); None: "
        "set by the drive",
        0.0,
        False,
        optional=True,
    )
    nu: float = nu_param()
    I_w: float | None = wall_inertial_number_param("centre line")

    def imposed_level(self) -> float | None:
        """The wall stress ratio B nu / 2 when B is given, else None [-]."""
        return None if self.B is None else 0.5 * float(self.B) * self.nu

    def normal_stress(self, xi: FloatArray) -> FloatArray:
        """sigma_yy = 1 across the channel (y-momentum) [-]."""
        return np.ones_like(np.asarray(xi, dtype=float))

    def shear_stress(self, xi: FloatArray, level: float) -> FloatArray:
        """sigma_yx = 2 T (xi - 1/2) = B nu (xi - 1/2) (:func:`shear_stress`) [-]."""
        return shear_stress(np.asarray(xi, dtype=float), 2.0 * level)

    def ratio_shape(self, t: FloatArray) -> tuple[FloatArray, FloatArray]:
        """q = 1 - 2t, 1 - q = 2t at the distance t from a wall [-]."""
        tt = np.asarray(t, dtype=float)
        return 1.0 - 2.0 * tt, 2.0 * tt

    def distance_of_ratio(self, r: float) -> float:
        """t = (1 - 1/r)/2 [-]."""
        return 0.5 * (1.0 - 1.0 / r)

    @property
    def ratio_slope(self) -> float:
        return 2.0
