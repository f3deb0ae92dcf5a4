"""The Cosserat model in plane shear: which wall slips, the slip constants, the conditions
(section "Application to plane shear").

The cell (:class:`~cosserat.model.cells.plane.Plane`) gives the statics: ``sigma_yy = sigma_c``
across the gap and a uniform ``sigma_yx``. Which wall slips is decided by friction, as the paper
argues (section "Results for plane shear"): friction ``-sigma_yx/sigma_yy = tan(delta)``
(``eqn-nd_bc2``) can hold only at the wall where ``tan(delta_wall) * sigma_yy(wall)`` is smaller,
because ``|sigma_yx|`` is the same everywhere. Three cases result:

* ``SYMMETRIC``: no gravity and equal friction angles: both walls slip, the solution is
  symmetric about xi = 1/2 (``eqn-nd_bc6``: m(1/2) = 0);
* ``UPPER``: tan(delta_L) sigma_yy(0) >= tan(delta) (rougher lower wall, or gravity): the shear
  layer is at the upper wall, sigma_yx = -tan(delta); the lower wall does not slip
  (``eqn-nd_bc4``, ``eqn-nd_bc5l``);
* ``LOWER``: tan(delta_L) sigma_yy(0) < tan(delta): friction is mobilised at the lower wall,
  sigma_yx = -tan(delta_L) sigma_yy(0); the upper wall does not slip (``eqn-nd_bc4``,
  ``eqn-nd_bc5u``) and the layer sits at the bottom.

Couple stress scaled as ``m = M_yz / (L sqrt(2(A+1)) N d_p)`` (``dimlessvar``).
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable
from enum import StrEnum
from typing import Any, NamedTuple

import numpy as np

from ....errors import ParameterError
from ..._cached import cached
from ...constitutive import FloatArray, radicand, symmetric_couple_stress
from ...formulation import Formulation
from ...grids import layered_grid
from ...parameters import Material, Wall
from ..base import Equations


class PlaneShearCase(StrEnum):
    """Where friction is mobilised, hence where the shear layer sits."""

    SYMMETRIC = "symmetric"
    UPPER = "layer-at-upper-wall"
    LOWER = "layer-at-lower-wall"


class WallConstants(NamedTuple):
    """Constants of the couple-stress equation at the slipping wall (``eqn-a_b_def``) [-].

    With tau = |sigma_yx| and s = sigma_c at that wall: a = tau/2,
    b^2 = a^2 + (s^2 sin^2 phi - tau^2) / (2(A+1)), m0 = sqrt(b^2 - a^2) and the decay rate of
    the spin k = m0 / (alpha a) (``eqn-k_def``). For no gravity s = 1 and these are the paper's.
    """

    a: float
    b: float
    m0: float
    k: float


def wall_constants(tau: float, sigma_c: float, material: Material) -> WallConstants:
    """:class:`WallConstants` for shear stress magnitude ``tau`` and mean stress ``sigma_c``."""
    a = 0.5 * tau
    m0 = symmetric_couple_stress(-tau, sigma_c, material)
    b = math.sqrt(a * a + m0 * m0)
    return WallConstants(a, b, m0, m0 / (material.alpha * a))


class CosseratPlane(Equations):
    """The Cosserat model on the plane cell (module docstring): ``problem.equations`` of
    ``Problem(Plane(...), Cosserat(...))``.

    Attributes read from the problem: ``material``, ``upper`` (the moving wall), ``lower_wall``,
    ``m_fixed_wall`` (the rheology's); ``eps``, ``B``, ``nu`` (the cell's).

    Examples
    --------
    >>> from cosserat import Cosserat, Plane, Problem, Wall
    >>> Problem(Plane(eps=0.01), Cosserat(wall=Wall(delta=20.0))).equations.case
    <PlaneShearCase.SYMMETRIC: 'symmetric'>
    >>> Problem(Plane(eps=0.01, B=1.0), Cosserat()).equations.case
    <PlaneShearCase.UPPER: 'layer-at-upper-wall'>
    """

    def validate(self) -> None:
        # tan(delta) <= sin(phi) for both walls (raises with the wall's name).
        self.upper.tan_delta(self.material, "delta")
        self.lower_wall.tan_delta(self.material, "delta_lower")
        if self.m_fixed_wall is not None:
            self._validate_m_fixed_wall(float(self.m_fixed_wall))

    # ----------------------------------------------------------------- the parameters
    @property
    def material(self) -> Material:
        return self.law.material

    @property
    def upper(self) -> Wall:
        """The moving upper wall."""
        return self.law.wall

    @property
    def lower_wall(self) -> Wall:
        """The fixed lower wall (the upper one's twin unless given)."""
        return self.law.lower_wall

    @property
    def m_fixed_wall(self) -> float | None:
        return self.law.m_fixed_wall

    @property
    def B(self) -> float:
        return float(self.cell.B)

    @property
    def nu(self) -> float:
        return float(self.cell.nu)

    # ----------------------------------------------------------------- walls and friction
    @cached
    def tan_delta_upper(self) -> float:
        return self.upper.tan_delta(self.material, "delta")

    @cached
    def tan_delta_lower(self) -> float:
        return self.lower_wall.tan_delta(self.material, "delta_lower")

    @cached
    def case(self) -> PlaneShearCase:
        """Which wall slips, from the friction angles and the normal stress (module
        docstring)."""
        upper_limit = self.tan_delta_upper * float(self.sigma_c(1.0))
        lower_limit = self.tan_delta_lower * float(self.sigma_c(0.0))
        if self.B == 0.0 and math.isclose(upper_limit, lower_limit, rel_tol=1e-12):
            return PlaneShearCase.SYMMETRIC
        # Equality with gravity: the paper puts the layer at the upper wall ("if >=").
        if lower_limit >= upper_limit * (1.0 - 1e-12):
            return PlaneShearCase.UPPER
        return PlaneShearCase.LOWER

    @property
    def slip_wall(self) -> float:
        """xi of the wall where friction is mobilised (the upper one when both slip)."""
        return 0.0 if self.case is PlaneShearCase.LOWER else 1.0

    @property
    def fixed_wall(self) -> float | None:
        """xi of the wall that does not slip; None in the symmetric case."""
        case = self.case
        if case is PlaneShearCase.SYMMETRIC:
            return None
        return 1.0 if case is PlaneShearCase.LOWER else 0.0

    @property
    def slipping(self) -> Wall:
        """The wall at which friction is mobilised."""
        return self.lower_wall if self.case is PlaneShearCase.LOWER else self.upper

    @cached
    def sigma_yx(self) -> float:
        """The uniform shear stress: -tan(delta) times sigma_yy at the slipping wall [-]."""
        if self.case is PlaneShearCase.LOWER:
            return -self.tan_delta_lower * float(self.sigma_c(0.0))
        return -self.tan_delta_upper * float(self.sigma_c(1.0))

    def formulation(self) -> Formulation:
        """The ODEs of :mod:`cosserat.model.formulation` for this problem."""
        syx = self.sigma_yx
        return Formulation(
            material=self.material,
            eps=self.eps,
            sigma_yx=lambda xi, m: syx + 0.0 * m,
            sigma_c=self.sigma_c,
        )

    # ----------------------------------------------------------------- wall constants
    @cached
    def slip_constants(self) -> WallConstants:
        """a, b, m0, k at the slipping wall (``eqn-a_b_def``, ``eqn-k_def``)."""
        return wall_constants(-self.sigma_yx, float(self.sigma_c(self.slip_wall)), self.material)

    @property
    def is_fully_rough(self) -> bool:
        """True if friction is fully mobilised at a fully rough slipping wall (m0 = 0 there)."""
        return self.slip_constants.m0 == 0.0

    def couple_stress_bound(self, xi: float) -> float:
        """Largest |m| at xi for which ``eqn-nd_sigxy`` is real [-].

        S is S(m = 0) - 4(A+1)^2 m^2 (``constitutive.radicand``), zero at the bound.
        """
        S0 = float(radicand(self.sigma_yx, float(self.sigma_c(xi)), 0.0, self.material))
        return math.sqrt(max(S0, 0.0)) / (2.0 * (self.material.A + 1.0))

    @property
    def m_at_fixed_wall(self) -> float:
        """m at the non-slipping wall: ``m_fixed_wall`` or the value ``eqn-nd_bc4`` gives [-].

        sigma_xy = sigma_yx there fixes |m| by ``eqn-nd_yc``; the sign is that of the stable
        branch of the couple-stress equation integrated towards the slipping wall: positive
        when the layer is at the upper wall, negative at the lower one.
        """
        fixed = self.fixed_wall
        if fixed is None:
            raise ParameterError("m_at_fixed_wall: both walls slip in the symmetric case")
        if self.m_fixed_wall is not None:
            return float(self.m_fixed_wall)
        m = symmetric_couple_stress(self.sigma_yx, float(self.sigma_c(fixed)), self.material)
        return m if fixed == 0.0 else -m

    def _validate_m_fixed_wall(self, m: float) -> None:
        fixed = self.fixed_wall
        if fixed is None:
            raise ParameterError(
                "m_fixed_wall cannot be set when both walls slip (identical walls, no gravity): "
                "the symmetric solution has m(1/2) = 0 (eqn-nd_bc6)"
            )
        bound = self.couple_stress_bound(fixed)
        sign = 1.0 if fixed == 0.0 else -1.0
        if not 0.0 <= sign * m <= bound * (1.0 + 1e-12):
            lo, hi = (0.0, bound) if sign > 0 else (-bound, 0.0)
            wall = "lower" if fixed == 0.0 else "upper"
            raise ParameterError(
                f"m_fixed_wall must satisfy {lo:.6g} <= m_fixed_wall <= {hi:.6g} at the {wall} "
                f"wall (its sign is that of the couple stress in the layer; beyond b the second "
                f"shear stress eqn-nd_sigxy is complex); got {m:g}"
            )

    # ----------------------------------------------------------------- velocity conditions
    @property
    def reference_velocity(self) -> float:
        """u_0 of ``eqn-delta_defn`` when one wall is fixed (that wall's velocity) [-]."""
        return 1.0 if self.case is PlaneShearCase.LOWER else 0.0

    def mirrored(self) -> Any:
        """The same problem seen upside down (walls swapped): only for B = 0.

        Rotating by 180 deg about z and adding V to every velocity maps the layer at the lower
        wall onto a layer at the upper wall: xi -> 1 - xi, u -> 1 - u, omega -> omega,
        m -> -m, stresses unchanged (``docs/derivation_plane.md``).
        """
        if self.B != 0.0:
            raise ParameterError("mirrored(): gravity breaks the up-down symmetry (B > 0)")
        m_fixed = None if self.m_fixed_wall is None else -self.m_fixed_wall
        law = dataclasses.replace(
            self.law, wall=self.lower_wall, lower=self.upper, m_fixed_wall=m_fixed
        )
        return type(self.problem)(self.cell, law)

    def boundary_errors(self, evaluate: Callable[[FloatArray], Any]) -> dict[str, float]:
        """Every boundary condition of this case as ``lhs - rhs`` on an evaluator [-]."""
        ends = evaluate(np.array([0.0, 1.0]))
        u, om, m = ends.u, ends.omega, ends.m
        errors = {"sigma_yy(1) - 1 [eqn-nd_bc1]": float(ends.sigma_yy[1] - 1.0)}
        walls = {0.0: (0, self.lower_wall, "delta_lower"), 1.0: (1, self.upper, "delta")}
        slipping = [0.0, 1.0] if self.case is PlaneShearCase.SYMMETRIC else [self.slip_wall]
        for xw in slipping:
            i, wall, name = walls[xw]
            tag = "upper" if i else "lower"
            errors[f"-sigma_yx/sigma_yy - tan({name}) at {tag} wall [eqn-nd_bc2]"] = float(
                -ends.sigma_yx[i] / ends.sigma_yy[i] - wall.tan_delta(self.material, name)
            )
            eq = "eqn-nd_bc3u" if i else "eqn-nd_bc3l"
            errors[f"u - u_wall - s eps K omega at {tag} wall [{eq}]"] = float(
                u[i] - self.wall_velocity(xw) - self.slip_sign(xw) * self.eps * wall.K * om[i]
            )
        fixed = self.fixed_wall
        if fixed is None:
            errors["m(1/2) [eqn-nd_bc6]"] = float(evaluate(np.array([0.5])).m[0])
        else:
            i = int(fixed)
            tag = "upper" if i else "lower"
            eq = "eqn-nd_bc5u" if i else "eqn-nd_bc5l"
            errors[f"u - u_wall at {tag} wall [{eq}]"] = float(u[i] - self.wall_velocity(fixed))
            if self.m_fixed_wall is None:
                errors[f"sigma_xy - sigma_yx at {tag} wall [eqn-nd_bc4]"] = float(
                    ends.sigma_xy[i] - ends.sigma_yx[i]
                )
            else:
                errors[f"m - m_fixed_wall at {tag} wall"] = float(m[i] - self.m_fixed_wall)
        return errors

    # ----------------------------------------------------------------- output helpers
    def output_grid(self, n: int) -> FloatArray:
        """About ``n`` points across the gap, resolving the layers (:mod:`cosserat.model.grids`)."""
        w = self.layer_width()
        # where m leaves its start value (centre or fixed wall): ~eps/k near m0, but a rise
        # over ~eps alpha when the wall is nearly frictionless (a << m0)
        w_m = max(w, min(0.5, 10.0 * self.eps * self.material.alpha))
        if self.case is PlaneShearCase.SYMMETRIC:
            zones = [(0.0, w), (0.5, w_m), (1.0, w)]
        else:
            zones = [(self.slip_wall, w), (1.0 - self.slip_wall, w_m)]
        return layered_grid(n, zones)

    def inner_scale(self) -> float:
        """(L^2 / (2 B nu))^(1/3): 1 - xi = eps^(2/3) scale x_hat in the Airy layer of a fully
        rough upper wall under gravity (Appendix, "Plane shear under gravity") [-]."""
        return (self.material.L**2 / (2.0 * self.B * self.nu)) ** (1.0 / 3.0)

    def layer_width(self) -> float:
        """A distance from the slipping wall beyond which u is within ~1e-10 of u_0 [-].

        Used to place output points; ~24/k grain diameters for non-fully-rough walls, a few
        times the Airy scale for fully rough walls under gravity, the whole gap otherwise.
        """
        const = self.slip_constants
        half = 0.5 if self.case is PlaneShearCase.SYMMETRIC else 1.0
        if const.k > 0.0:
            return min(half, 24.0 * self.eps / const.k)
        if self.B > 0.0:
            return min(half, 6.0 * self.eps ** (2.0 / 3.0) * self.inner_scale())
        return half

    def describe(self) -> str:
        return (
            f"plane shear ({self.case.value}): phi = {self.material.phi:g} deg, "
            f"L = {self.material.L:g}, A = {self.material.A:g}, eps = {self.eps:g}, "
            f"B = {self.B:g}, nu = {self.nu:g}; upper wall {self.upper.describe()}; "
            f"lower wall {self.lower_wall.describe()}"
        )

    def parameters(self) -> dict[str, Any]:
        """Plain-data record of every parameter (angles in degrees)."""

        def wall(w: Wall, name: str) -> dict[str, Any]:
            return {
                "delta": w.delta,
                "tan_delta": w.tan_delta(self.material, name),
                "K": w.K,
            }

        return {
            "geometry": "plane",
            "rheology": "cosserat",
            "case": self.case.value,
            "phi": self.material.phi,
            "L": self.material.L,
            "A": self.material.A,
            "eps": self.eps,
            "B": self.B,
            "nu": self.nu,
            "upper": wall(self.upper, "delta"),
            "lower": wall(self.lower_wall, "delta_lower"),
            "m_fixed_wall": self.m_fixed_wall,
        }
