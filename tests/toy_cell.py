"""A toy cell for the plug-in tests: plane shear under a quadratic overburden.

One module, no edit anywhere else: the class registers itself by its name, declares its one
parameter besides eps, and states its statics (a normal stress ``1 + c (1 - xi)^2`` growing
quadratically with depth below the moving upper wall, a uniform shear stress). Any rheology
whose equations read only a cell's statics (local mu(I), the toy power law) solves on it.
Imported only by the ``toys`` fixture of ``conftest.py``, which removes it again.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import ClassVar

import numpy as np

from cosserat.model.cells import Cell, Coordinate, wall_inertial_number_param
from cosserat.model.declare import param


@dataclass(frozen=True, kw_only=True)
class StratifiedPlane(Cell):
    """Plane shear under a quadratic overburden (a toy cell of the tests).

    Parameters
    ----------
    eps : float
        Grain diameter over gap [-].
    c : float
        Overburden coefficient: sigma_yy = 1 + c (1 - xi)^2 [-].
    I_w : float, optional
        Inertial number of the upper wall's speed [-].
    stress_ratio : float, optional
        Instead of I_w: the imposed tau/N at the upper wall [-].
    """

    name: ClassVar[str] = "stratified"
    title: ClassVar[str] = "stratified plane shear"
    coordinate: ClassVar[Coordinate] = Coordinate(
        "y", "height above the fixed lower wall over the gap", lambda cell, xi: xi
    )
    peak_wall: ClassVar[float] = 1.0
    moving_wall: ClassVar[float | None] = 1.0
    velocity_scale: ClassVar[tuple[float, float]] = (1.0, 1.0)
    peak_wall_name: ClassVar[str] = "moving upper wall"

    c: float = param(
        1.0, "overburden coefficient, sigma_yy = 1 + c (1 - xi)^2", bounds=(0.0, 100.0),
        closed=(True, True), role="cell",
    )  # fmt: skip
    I_w: float | None = wall_inertial_number_param("moving upper wall")
    stress_ratio: float | None = param(
        None, "imposed stress ratio at the upper wall", bounds=(0.0, math.inf), role="drive",
        optional=True,
    )  # fmt: skip

    def normal_stress(self, xi):  # type: ignore[no-untyped-def]
        return 1.0 + self.c * (1.0 - np.asarray(xi, dtype=float)) ** 2

    def shear_stress(self, xi, level):  # type: ignore[no-untyped-def]
        return np.full_like(np.asarray(xi, dtype=float), -level)

    def ratio_shape(self, t):  # type: ignore[no-untyped-def]
        g = self.c * np.asarray(t, dtype=float) ** 2
        return 1.0 / (1.0 + g), g / (1.0 + g)
