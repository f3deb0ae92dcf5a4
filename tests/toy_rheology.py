"""A toy rheology for the plug-in tests: a power-law fluid, on any cell.

One module, no edit anywhere else: the law (flow index n, declared), its equations on any cell
(they read only the cell's statics: the shear stress, the radius, the wall kinematics) and its
numerical route, registered for every cell. The shear rate is ``r d(u/r)/dxi = -sign(tau)
|tau|^(1/n)`` up to a constant that the velocity scale removes, so the velocity over the
velocity scale is independent of the stress level; it has closed forms (u = xi in plane shear,
``u = 1 - |1 - 2 xi|^(1 + 1/n)`` in the channel, a power of the radius in Couette flow) that the
tests check. Imported only by the ``toys`` fixture of ``conftest.py``, which removes it again.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, ClassVar

import numpy as np
from scipy.integrate import quad

from cosserat.model.constitutive import FloatArray
from cosserat.model.declare import param, validate
from cosserat.model.rheologies import ANY_CELL, Equations, Rheology
from cosserat.results.profile import Diagnostics, Fields, Profile
from cosserat.routes.assemble import given_grid
from cosserat.routes.registry import register_route


class PowerLawFlow(Equations):
    """The power law on any cell: ``|d(u/r)/dxi| = |tau|^(1/n)/r`` from the cell's statics."""

    def integrand(self, x: float) -> float:
        """|d(u/r)/dxi| (up to the scale) at xi = x [-]."""
        tau = float(self.cell.shear_stress(np.array([x]), 1.0)[0])
        return abs(tau) ** (1.0 / self.law.n) / float(self.cell.radius(np.array([x]))[0])

    def describe(self) -> str:
        return f"{self.cell.title}, power law: n = {self.law.n:g}, {self.cell.describe()}"


@dataclass(frozen=True)
class PowerLaw(Rheology):
    """A power-law fluid, tau ~ gamma_dot^n (a toy rheology of the tests).

    Parameters
    ----------
    n : float
        Flow index [-] (1: Newtonian; < 1 shear-thinning).
    """

    name: ClassVar[str] = "powerlaw"
    title: ClassVar[str] = "power-law fluid (a test of the seam)"
    reference: ClassVar[str] = "none (a toy)"
    rate_dependent: ClassVar[bool] = False  # u over its scale does not depend on the drive
    default_free: ClassVar[tuple[str, ...]] = ("n",)
    equations: ClassVar[dict[str, type[Equations]]] = {ANY_CELL: PowerLawFlow}

    n: float = param(
        0.5, "flow index", bounds=(0.0, math.inf), fit_range=(0.1, 3.0), role="material",
        source="a toy",
    )  # fmt: skip

    def __post_init__(self) -> None:
        validate(self)


class _Evaluator:
    """u by quadrature of the rate from a wall at rest, scaled at the cell's scale point."""

    def __init__(self, eq: PowerLawFlow) -> None:
        self.eq = eq
        cell = eq.cell
        self.rest = 0.0 if cell.wall_velocity(0.0) == 0.0 else 1.0
        self.xs, self.us = cell.velocity_scale
        self.scale = self._phi(self.xs)

    def _phi(self, x: float) -> float:
        """r(x) int_rest^x |d(u/r)/dxi| dxi (signed by the direction of integration)."""
        cell = self.eq.cell
        value, _ = quad(self.eq.integrand, self.rest, x, epsabs=0.0, epsrel=1e-12, limit=200)
        return float(cell.radius(np.array([x]))[0]) * value

    def velocity(self, x: FloatArray) -> FloatArray:
        x = np.atleast_1d(np.asarray(x, dtype=float))
        if self.eq.cell.symmetric:  # integrate over the half at the peak wall, mirror the rest
            x = np.where(x > 0.5, 1.0 - x, x)
        return np.array([self.us * self._phi(v) / self.scale for v in x])

    def __call__(self, x: FloatArray) -> Fields:
        x = np.atleast_1d(np.asarray(x, dtype=float))
        cell = self.eq.cell
        u = self.velocity(x)
        tau = cell.shear_stress(x, 1.0)
        kappa = cell.curvature(x)
        # r d(u/r)/dxi has the sign of -tau; |u_s/scale| turns the rate into the velocity scale
        rate = -np.sign(tau) * np.abs(tau) ** (1.0 / self.eq.law.n) * abs(self.us / self.scale)
        return Fields(
            u=u, omega=None, m=None, sigma_xy=tau, sigma_yx=tau.copy(),
            sigma_yy=cell.normal_stress(x), du_dxi=rate + kappa * u, kappa=kappa,
        )  # fmt: skip


@register_route("powerlaw", ANY_CELL, "numerical")
def solve_power_law(
    problem: Any, *, points: int | None = None, xi: FloatArray | None = None, check: bool = True
) -> Profile:
    """The power-law profile on any cell (module docstring)."""
    ev = _Evaluator(problem.equations)
    grid = np.linspace(0.0, 1.0, points or 101) if xi is None else given_grid(xi)
    f = ev(grid)
    bc = {}
    if check:
        ends = ev.velocity(np.array([0.0, 1.0]))
        bc = {f"u - u_wall at {w:g}": float(ends[i] - problem.wall_velocity(w)) for i, w in
              enumerate((0.0, 1.0))}  # fmt: skip
    return Profile(
        problem=problem,
        xi=grid,
        **f._asdict(),
        slip_wall=problem.slip_wall,
        reference_velocity=problem.reference_velocity,
        diagnostics=Diagnostics("numerical", None, None, {}, bc, "power law by quadrature"),
        evaluator=ev,
        velocity=ev.velocity,
    )
