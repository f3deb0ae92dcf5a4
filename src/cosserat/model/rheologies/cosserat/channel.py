"""The Cosserat model in the vertical channel (``docs/derivation_channel.md``).

The frictional Cosserat model on the vertical channel of Mohan, Nott & Kesava Rao, "A frictional
Cosserat model for the flow of granular materials through a vertical channel", Acta Mechanica
138 (1999). The cell (:class:`~cosserat.model.cells.channel.VerticalChannel`) gives the statics:
``sigma_yy = 1`` and ``sigma_yx = B nu (xi - 1/2)``. Friction at a slipping wall then fixes
``B nu / 2 = tan(delta)``: the wall normal stress of fully developed flow,
N = rho g H/(2 tan delta) (Janssen's limit). A cell without B takes that value; a smaller B means
the walls hold the material with friction not fully mobilised, and they do not slip. The flow is
symmetric about the centre line: u and m even, omega, sigma_yx and sigma_xy odd. At the centre
sigma_xy = sigma_yx = 0, so the yield condition puts all of the yield into the couple stress,
``m(1/2) = -c``, ``c^2 = sin^2(phi)/(2(A+1))``.

The rate-independent model fixes only the shape of the velocity: it is scaled by the centre-line
velocity, ``u(1/2) = 1``.

The solvers work on the upper half in *mapped* variables, the mirror image x -> -x, in which
every equation is the plane-shear one: ``m_hat = -m = c - y``, ``omega_hat = -omega``,
``u_hat = 1 - u``, shear stresses of opposite sign, so that ``sigma_hat_yx = -tau(xi)`` with
``tau = B nu (xi - 1/2) >= 0`` and the paper's root of ``eqn-nd_sigxy`` applies. The compiled
functions below state the constitutive law in the variable ``y = c - m_hat`` (the couple
stress's deficit from its centre value), free of the cancellation that ``c^2 - m^2`` suffers near
the centre, where the radicand S of ``eqn-nd_sigxy`` vanishes.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Callable
from enum import StrEnum
from typing import Any

import numpy as np
from numba import njit

from ....errors import NoSolutionError
from ...cells.channel import shear_stress
from ...constitutive import FloatArray
from ...formulation import Formulation
from ...grids import layered_grid
from ...parameters import Material, Wall
from ..base import Equations
from .plane import WallConstants, wall_constants

FRICTION_MATCH_RTOL = 1e-12
"""B nu / 2 within this relative distance of tan(delta) is friction fully mobilised [-]."""


class ChannelCase(StrEnum):
    """Whether wall friction is fully mobilised (the walls slip) or not."""

    SLIP = "walls-slip"
    NO_SLIP = "walls-do-not-slip"


# ----------------------------------------------------------------- compiled law in y = c - m_hat
@njit(cache=True, nogil=True)
def k_torque_numerator(
    tau: float, wall_gap: float, d: float, B_nu: float, y: float, c: float, A: float, sp: float
) -> float:
    """(sin phi - tau)(sin phi + tau) - 2(A+1) m^2 with m = c - y, without cancellation [-].

    Two equal forms (doc section 3): ``2(A+1) y (2c - y) - tau^2`` near the centre (y small),
    ``(sin phi - tau)(sin phi + tau) - 2(A+1) m^2`` elsewhere, with
    ``sin phi - tau = wall_gap + B nu d`` from the distance d = 1 - xi to the wall and
    ``wall_gap = sin phi - B nu/2 >= 0``.
    """
    if y <= 0.5 * c:
        return 2.0 * (A + 1.0) * y * (2.0 * c - y) - tau * tau
    m = c - y
    return (wall_gap + B_nu * d) * (sp + tau) - 2.0 * (A + 1.0) * m * m


@njit(cache=True, nogil=True)
def k_channel_radicand(tau: float, numerator: float, A: float) -> float:
    """S of ``eqn-nd_sigxy`` = (1+A)^2 tau^2 + 2(A+1) * numerator (doc section 3) [-]."""
    return (1.0 + A) ** 2 * tau * tau + 2.0 * (A + 1.0) * numerator


class CosseratChannel(Equations):
    """The Cosserat model on the vertical channel (module docstring): ``problem.equations`` of
    ``Problem(VerticalChannel(...), Cosserat(...))``; both walls are the rheology's ``wall``.

    Raises
    ------
    NoSolutionError
        ``B nu / 2 > tan(delta)``: wall friction cannot carry the weight; there is no steady
        fully developed flow.

    Examples
    --------
    >>> from cosserat import Cosserat, Problem, VerticalChannel, Wall
    >>> problem = Problem(VerticalChannel(eps=0.02), Cosserat(wall=Wall(delta=20.0)))
    >>> round(problem.equations.B, 4)  # B nu = 2 tan(delta): friction fully mobilised
    0.7279
    """

    def validate(self) -> None:
        tan_delta = self.tan_delta
        if self.cell.B is None:
            return
        B = float(self.cell.B)
        if 0.5 * B * self.nu > tan_delta * (1.0 + FRICTION_MATCH_RTOL):
            raise NoSolutionError(
                f"no steady fully developed flow: the wall shear stress B nu/2 = "
                f"{0.5 * B * self.nu:.6g} (times N) exceeds what wall friction can carry, "
                f"tan(delta) = {tan_delta:.6g}; the material accelerates. Fully developed flow "
                f"with slipping walls has B nu = 2 tan(delta) = {2.0 * tan_delta:.6g} (B=None)"
            )

    @property
    def material(self) -> Material:
        return self.law.material

    @property
    def wall(self) -> Wall:
        return self.law.wall

    @property
    def nu(self) -> float:
        return float(self.cell.nu)

    @functools.cached_property
    def B(self) -> float:
        """rho_p g H / N: the cell's, or B nu = 2 tan(delta) when it has none (Janssen) [-]."""
        if self.cell.B is None:
            return 2.0 * self.tan_delta / self.nu
        return float(self.cell.B)

    # ----------------------------------------------------------------- statics
    @functools.cached_property
    def tan_delta(self) -> float:
        return self.wall.tan_delta(self.material, "delta")

    @functools.cached_property
    def case(self) -> ChannelCase:
        """SLIP if B nu/2 = tan(delta) (friction fully mobilised), else NO_SLIP."""
        B_nu = self.B * self.nu
        if 0.5 * B_nu >= self.tan_delta * (1.0 - FRICTION_MATCH_RTOL):
            return ChannelCase.SLIP
        return ChannelCase.NO_SLIP

    @functools.cached_property
    def wall_stress(self) -> float:
        """tau_w = |sigma_yx| at the walls over N: tan(delta) exactly when the walls slip [-]."""
        if self.case is ChannelCase.SLIP:
            return self.tan_delta
        return 0.5 * self.B * self.nu

    @property
    def B_nu(self) -> float:
        """The slope of the shear stress, 2 tau_w (= B nu) [-]."""
        return 2.0 * self.wall_stress

    @property
    def slips(self) -> bool:
        return self.case is ChannelCase.SLIP

    @functools.cached_property
    def wall_gap(self) -> float:
        """sin(phi) - tau_w >= 0: how far the wall stress is from fully rough [-]."""
        if self.wall_stress == self.material.sin_phi:
            return 0.0
        return self.material.sin_phi - self.wall_stress

    slip_wall = 1.0
    """The solved half ends at the upper wall (both walls are alike)."""
    reference_velocity = 1.0
    """u_0 of ``eqn-delta_defn``: the centre-line velocity, which scales u."""

    def sigma_yx(self, xi: FloatArray) -> FloatArray:
        """sigma_yx = B nu (xi - 1/2) (the cell's statics at the stress level tau_w) [-]."""
        return shear_stress(np.asarray(xi, dtype=float), self.B_nu)

    @functools.cached_property
    def c(self) -> float:
        """|m| at the centre line, sqrt(sin^2 phi/(2(A+1))) (doc section 2) [-]."""
        return math.sqrt(self.material.c2)

    def mapped_formulation(self) -> Formulation:
        """The ODEs of the upper half in the mapped variables (module docstring): plane shear
        with ``sigma_yx = -tau(xi)``, ``sigma_c = 1``; for residuals on xi in [1/2, 1]."""
        B_nu = self.B_nu
        return Formulation(
            material=self.material,
            eps=self.eps,
            sigma_yx=lambda xi, m: -shear_stress(np.asarray(xi, dtype=float), B_nu) + 0.0 * m,
            sigma_c=lambda xi: 1.0 + 0.0 * xi,
        )

    # ----------------------------------------------------------------- the centre line
    def centre_expansion(self) -> float:
        """mu of ``m_hat = c - mu s^2 + O(s^4)``, s = xi - 1/2 (doc section 4) [-].

        The regular solution through the singular point m_hat = c, S = 0 at the centre: the
        smaller root of ``4 (eps alpha)^2 mu^2 - 2 (B nu eps alpha + c) mu + (B nu)^2/4 +
        beta = 0``, beta = (B nu)^2 (1-A)/(4(1+A)), with ``sqrt(2 c mu - beta) = B nu/2 -
        2 eps alpha mu >= 0``.

        Raises
        ------
        NoSolutionError
            No real regular solution leaves the centre line:
            ``eps alpha B nu (1 - A) > 2 c (1 + A)``.
        """
        A, c = self.material.A, self.c
        ea = self.eps * self.material.alpha
        Bn = self.B_nu
        beta = Bn * Bn * (1.0 - A) / (4.0 * (1.0 + A))
        if ea * Bn * (1.0 - A) > 2.0 * c * (1.0 + A):
            raise NoSolutionError(
                f"no real solution for {self.describe()}: at the centre line the couple stress "
                f"holds all of the yield (m = -c, sigma_xy = sigma_yx = 0), and it cannot fall "
                f"fast enough to stay inside the yield surface as the shear stress grows: that "
                f"needs eps alpha B nu (1 - A) <= 2 c (1 + A), here "
                f"{ea * Bn * (1.0 - A):.6g} > {2.0 * c * (1.0 + A):.6g} "
                f"(docs/derivation_channel.md, section 4); a wider channel (smaller eps) has one"
            )
        # smaller root, written without cancellation: mu = q / (p/2 + sqrt(p^2/4 - r q))
        p = 2.0 * (Bn * ea + c)
        q = Bn * Bn / 4.0 + beta
        r = 4.0 * ea * ea
        disc = 0.25 * p * p - r * q
        return q / (0.5 * p + math.sqrt(max(disc, 0.0)))

    @property
    def deficit_scale(self) -> float:
        """Scale of the couple stress's deficit y = c - |m| over the half channel, in units of
        the yield scale: ``min(1, (tau_w / sin phi)^2)`` (doc section 4) [-].

        On the outer solution ``y ~ tau^2 / (4 c (1+A))``, so y is O(tau_w^2) across the whole
        channel when the wall stress is small; the kernel's absolute tolerance on y is measured
        in this unit, else it would exceed y itself (and the width of the band between y and
        the yield bound) when B nu is small.
        """
        return min(1.0, (self.wall_stress / self.material.sin_phi) ** 2)

    # ----------------------------------------------------------------- wall constants
    @functools.cached_property
    def slip_constants(self) -> WallConstants:
        """a, b, m0, k at the walls for tau_w (``eqn-a_b_def``, ``eqn-k_def``) [-]."""
        return wall_constants(self.wall_stress, 1.0, self.material)

    @property
    def is_fully_rough(self) -> bool:
        """True if the wall stress is fully rough, tau_w = sin(phi) (m0 = 0 at the walls)."""
        return self.wall_gap == 0.0

    def inner_scale(self) -> float:
        """(L^2/4)^(1/3): distance from a fully rough wall = eps^(2/3) scale x_hat in the Airy
        layer (doc section 6) [-]."""
        return (self.material.L**2 / 4.0) ** (1.0 / 3.0)

    def outer_couple_stress(self, xi: FloatArray) -> FloatArray:
        """m^(0): the couple stress at which the stress is symmetric, even about 1/2 [-].

        ``m^(0) = -sqrt((sin^2 phi - tau^2)/(2(A+1)))``; -c at the centre (doc section 5).
        """
        tau = np.abs(shear_stress(np.asarray(xi, dtype=float), self.B_nu))
        sp = self.material.sin_phi
        gap = self.wall_gap + self.B_nu * (0.5 - np.abs(np.asarray(xi, dtype=float) - 0.5))
        return -np.sqrt(np.maximum(gap * (sp + tau), 0.0) / (2.0 * (self.material.A + 1.0)))

    # ----------------------------------------------------------------- checks and output
    def boundary_errors(self, evaluate: Callable[[FloatArray], Any]) -> dict[str, float]:
        """Every wall, symmetry and normalisation condition as ``lhs - rhs`` [-]."""
        pts = evaluate(np.array([0.0, 0.5, 1.0]))
        eK = self.eps * self.wall.K
        errors: dict[str, float] = {
            "sigma_yy - 1 at the walls [wall normal stress N]": float(
                max(abs(pts.sigma_yy[0] - 1.0), abs(pts.sigma_yy[2] - 1.0))
            ),
            "u(1/2) - 1 [centre-line velocity scale]": float(pts.u[1] - 1.0),
            "omega(1/2) [symmetry]": float(pts.omega[1]),
            "du/dxi(1/2) [symmetry]": float(pts.du_dxi[1]),
            "sigma_xy(1/2) [symmetry]": float(pts.sigma_xy[1]),
            "m(1/2) + c [yield at the centre line]": float(pts.m[1] + self.c),
        }
        for i, xw in ((0, 0.0), (2, 1.0)):
            tag = "upper" if xw else "lower"
            s = self.slip_sign(xw)
            if self.slips:
                errors[f"|sigma_yx|/sigma_yy - tan(delta) at the {tag} wall [eqn-nd_bc2]"] = float(
                    abs(pts.sigma_yx[i]) / pts.sigma_yy[i] - self.tan_delta
                )
                errors[f"u - s eps K omega at the {tag} wall [eqn-bc3]"] = float(
                    pts.u[i] - s * eK * pts.omega[i]
                )
            else:
                errors[f"u at the {tag} wall [no slip]"] = float(pts.u[i])
        return errors

    def layer_width(self) -> float:
        """A distance from a wall beyond which u is within ~1e-10 of u(1/2) [-]."""
        k = self.slip_constants.k
        if k > 0.0:
            return min(0.5, 24.0 * self.eps / k)
        return min(0.5, 6.0 * self.eps ** (2.0 / 3.0) * self.inner_scale())

    def output_grid(self, n: int) -> FloatArray:
        """About ``n`` points across the channel, resolving both wall layers."""
        w = self.layer_width()
        return layered_grid(n, [(0.0, w), (1.0, w)])

    def describe(self) -> str:
        return (
            f"vertical channel ({self.case.value}): phi = {self.material.phi:g} deg, "
            f"L = {self.material.L:g}, A = {self.material.A:g}, eps = {self.eps:g}, "
            f"B = {self.B:g}, nu = {self.nu:g}; walls {self.wall.describe()}"
        )

    def parameters(self) -> dict[str, Any]:
        """Plain-data record of every parameter (angles in degrees)."""
        return {
            "geometry": "channel",
            "rheology": "cosserat",
            "case": self.case.value,
            "phi": self.material.phi,
            "L": self.material.L,
            "A": self.material.A,
            "eps": self.eps,
            "B": self.B,
            "nu": self.nu,
            "delta": self.wall.delta,
            "tan_delta": self.tan_delta,
            "K": self.wall.K,
            "velocity_scale": "centre-line velocity, u(1/2) = 1",
        }


__all__ = [
    "FRICTION_MATCH_RTOL",
    "ChannelCase",
    "CosseratChannel",
    "k_channel_radicand",
    "k_torque_numerator",
]
