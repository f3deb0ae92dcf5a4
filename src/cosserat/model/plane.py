"""Plane shear between horizontal walls (section "Application to plane shear").

The upper wall (xi = 1) moves at speed V in +x under the normal stress N; the lower wall
(xi = 0) is fixed. Scalings (``dimlessvar``): xi = y/H, u = v_x/V, omega = omega_z H/V,
stresses / N, m = M_yz / (L sqrt(2(A+1)) N d_p); eps = d_p/H, B = rho_p g H / N.

Momentum balances with ``eqn-nd_bc1`` give ``sigma_yy = sigma_c = 1 + B nu (1 - xi)`` and a
constant ``sigma_yx``. Which wall slips is decided by friction, as the paper argues
(section "Results for plane shear"): friction ``-sigma_yx/sigma_yy = tan(delta)``
(``eqn-nd_bc2``) can hold only at the wall where ``tan(delta_wall) * sigma_yy(wall)`` is smaller,
because ``|sigma_yx|`` is the same everywhere. Three cases result:

* ``SYMMETRIC``: no gravity and equal friction angles: both walls slip, the solution is
  symmetric about xi = 1/2 (``eqn-nd_bc6``: m(1/2) = 0);
* ``UPPER``: tan(delta_L)(1 + B nu) >= tan(delta) (rougher lower wall, or gravity): the shear
  layer is at the upper wall, sigma_yx = -tan(delta); the lower wall does not slip
  (``eqn-nd_bc4``, ``eqn-nd_bc5l``);
* ``LOWER``: tan(delta_L)(1 + B nu) < tan(delta): friction is mobilised at the lower wall,
  sigma_yx = -tan(delta_L)(1 + B nu); the upper wall does not slip (``eqn-nd_bc4``,
  ``eqn-nd_bc5u``) and the layer sits at the bottom.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Callable
from dataclasses import dataclass
from enum import StrEnum
from typing import Any, NamedTuple

import numpy as np
from numba import njit

from ..errors import ParameterError
from .constitutive import FloatArray, radicand, symmetric_couple_stress
from .formulation import Formulation
from .grids import layered_grid
from .parameters import Material, Wall, require_finite


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


B_MAX = 1e6  # beyond, stresses of order (B sin phi)^2 leave the range of doubles soon


@njit(cache=True, nogil=True)
def mean_stress(xi: Any, B_nu: float) -> Any:
    """sigma_c = sigma_yy = 1 + B nu (1 - xi): ``eqn-nd_ymom`` with ``eqn-nd_bc1`` [-].

    Compiled: the solver kernels call it on numbers, the problem on arrays.
    """
    return 1.0 + B_nu * (1.0 - xi)


def validate_B(B: float) -> float:
    """The gravity parameter B = rho_p g H / N, checked: 0 <= B <= B_MAX [-]."""
    B = require_finite("B", B)
    if not 0.0 <= B <= B_MAX:
        raise ParameterError(
            f"B = rho_p g H / N must satisfy 0 <= B <= {B_MAX:g} (weight of the layer at most "
            f"{B_MAX:g} times the applied normal stress); got {B:g}"
        )
    return B


def validate_nu(nu: float) -> float:
    """The solids fraction nu, checked: 0 < nu <= 1 [-]."""
    nu = require_finite("nu", nu)
    if not 0.0 < nu <= 1.0:
        raise ParameterError(f"nu (solids fraction) must satisfy 0 < nu <= 1; got {nu:g}")
    return nu


def validate_eps(eps: float) -> float:
    x = require_finite("eps", eps)
    if not 0.0 < x <= 0.5:
        raise ParameterError(
            f"eps = d_p/H must satisfy 0 < eps <= 0.5 (at least two grain diameters across the "
            f"gap); got {x:g}"
        )
    return x


@dataclass(frozen=True, kw_only=True)
class PlaneShear:
    """Plane shear of a granular layer between two walls.

    Parameters
    ----------
    material : Material
    upper : Wall
        The moving upper wall (angle of wall friction delta, slip coefficient K).
    lower : Wall, optional
        The fixed lower wall (delta_L, K_L); defaults to a wall identical to ``upper``.
    eps : float
        Grain diameter over gap, d_p / H, ``0 < eps <= 0.5`` [-].
    B : float
        Gravity parameter rho_p g H / N, ``B >= 0`` [-]; 0 for no gravity.
    nu : float
        Solids fraction, ``0 < nu <= 1`` [-]; only the product B nu enters.
    m_fixed_wall : float, optional
        Couple stress m at the wall that does not slip, replacing ``eqn-nd_bc4``
        (sigma_xy = sigma_yx) there; the paper's sensitivity study (figure 5). Admissible:
        ``0 <= m <= b`` when the layer is at the upper wall, ``-b <= m <= 0`` when at the lower
        wall, where ``b`` makes the radicand of ``eqn-nd_sigxy`` vanish at that wall [-].

    Examples
    --------
    >>> from cosserat import Material, PlaneShear, Wall
    >>> problem = PlaneShear(material=Material(), upper=Wall(delta=20.0), eps=0.01)
    >>> problem.case
    <PlaneShearCase.SYMMETRIC: 'symmetric'>
    >>> PlaneShear(material=Material(), upper=Wall(), eps=0.01, B=1.0).case
    <PlaneShearCase.UPPER: 'layer-at-upper-wall'>
    """

    material: Material
    upper: Wall
    lower: Wall | None = None
    eps: float
    B: float = 0.0
    nu: float = 1.0
    m_fixed_wall: float | None = None

    def __post_init__(self) -> None:
        if not isinstance(self.material, Material):
            raise ParameterError(f"material must be a Material; got {type(self.material).__name__}")
        if not isinstance(self.upper, Wall):
            raise ParameterError(f"upper must be a Wall; got {type(self.upper).__name__}")
        if self.lower is None:
            object.__setattr__(self, "lower", self.upper)
        elif not isinstance(self.lower, Wall):
            raise ParameterError(f"lower must be a Wall; got {type(self.lower).__name__}")
        object.__setattr__(self, "eps", validate_eps(self.eps))
        object.__setattr__(self, "B", validate_B(self.B))
        object.__setattr__(self, "nu", validate_nu(self.nu))
        # tan(delta) <= sin(phi) for both walls (raises with the wall's name).
        self.upper.tan_delta(self.material, "delta")
        self.lower_wall.tan_delta(self.material, "delta_lower")
        if self.m_fixed_wall is not None:
            self._validate_m_fixed_wall(require_finite("m_fixed_wall", self.m_fixed_wall))

    # ----------------------------------------------------------------- walls and friction
    @property
    def lower_wall(self) -> Wall:
        assert self.lower is not None  # set in __post_init__
        return self.lower

    @functools.cached_property
    def tan_delta_upper(self) -> float:
        return self.upper.tan_delta(self.material, "delta")

    @functools.cached_property
    def tan_delta_lower(self) -> float:
        return self.lower_wall.tan_delta(self.material, "delta_lower")

    @functools.cached_property
    def case(self) -> PlaneShearCase:
        """Which wall slips, from the friction angles and gravity (module docstring)."""
        upper_limit = self.tan_delta_upper
        lower_limit = self.tan_delta_lower * (1.0 + self.B * self.nu)
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

    def curvature(self, xi: FloatArray) -> FloatArray:
        """0: plane walls (the Couette cell's is 1/(Ri + xi)) [-]."""
        return np.zeros_like(np.asarray(xi, dtype=float))

    def sigma_c(self, xi: FloatArray) -> FloatArray:
        """Mean stress = sigma_yy (:func:`mean_stress`) [-]."""
        return mean_stress(xi, self.B * self.nu)

    @functools.cached_property
    def sigma_yx(self) -> float:
        """The constant shear stress, -tan(delta) at the slipping wall times sigma_yy there [-]."""
        if self.case is PlaneShearCase.LOWER:
            return -self.tan_delta_lower * (1.0 + self.B * self.nu)
        return -self.tan_delta_upper

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
    @functools.cached_property
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

    def mirrored(self) -> PlaneShear:
        """The same problem seen upside down (walls swapped): only for B = 0.

        Rotating by 180 deg about z and adding V to every velocity maps the layer at the lower
        wall onto a layer at the upper wall: xi -> 1 - xi, u -> 1 - u, omega -> omega,
        m -> -m, stresses unchanged (``docs/derivation_plane.md``).
        """
        if self.B != 0.0:
            raise ParameterError("mirrored(): gravity breaks the up-down symmetry (B > 0)")
        m_fixed = None if self.m_fixed_wall is None else -self.m_fixed_wall
        return PlaneShear(
            material=self.material,
            upper=self.lower_wall,
            lower=self.upper,
            eps=self.eps,
            m_fixed_wall=m_fixed,
        )

    @staticmethod
    def wall_velocity(xi_wall: float) -> float:
        """Velocity of the wall at ``xi_wall``: 1 for the upper wall, 0 for the lower [-]."""
        return 1.0 if xi_wall == 1.0 else 0.0

    @staticmethod
    def slip_sign(xi_wall: float) -> float:
        """s in the slip condition u = u_wall + s eps K omega (``eqn-nd_bc3u``, ``eqn-nd_bc3l``).

        From ``eqn-bc3``, v - v_w = -K d_p n x omega with n the normal into the material:
        n = -e_y at the upper wall gives s = +1, n = +e_y at the lower wall s = -1.
        """
        return 1.0 if xi_wall == 1.0 else -1.0

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
