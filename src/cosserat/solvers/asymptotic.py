"""Asymptotic route: leading order in eps -> 0 (Appendix, ``docs/derivation_plane.md``).

Walls that are not fully rough (k > 0): outside O(eps) layers the couple stress sits where the
stress is symmetric, ``m^(0)`` with ``sigma_xy = sigma_yx`` (``eqn-asymp_soln_eta_g0``,
``eqn-asymp_eta_g``), and the velocity decays from the slipping wall as (``eqn-asymp_vels``)::

    u - u_0 = (u_w - u_0) (2/k)/(K + 2/k) exp(-k d/eps),
    omega   = -s (u_w - u_0) / (eps (K + 2/k)) exp(-k d/eps),

d the distance from the slipping wall, u_w its velocity, s its slip sign (+1 upper wall,
-1 lower wall) and k the decay rate there (``eqn-k_def``). This is ``eqn-asymp_soln_vels_g0``
(u_0 = 1/2) and ``eqn-asymp_soln_vels_g0_aw`` (u_0 = 0); for a layer at the lower wall it is
their mirror image.

Fully rough walls without gravity shear uniformly at leading order (u = xi, omega = -1/2, m = 0;
``vel_g0`` as eps -> 0). Fully rough walls under gravity need the Airy-function inner layer
(:mod:`cosserat.solvers.airy`).
"""

from __future__ import annotations

import numpy as np

from ..constitutive import FloatArray, symmetric_couple_stress
from ..problems.couette import CouetteFlow
from ..problems.plane import PlaneShear, PlaneShearCase
from ..profile import Fields, Profile
from .assemble import make_profile


def outer_couple_stress(problem: PlaneShear, xi: FloatArray) -> FloatArray:
    """m^(0): the couple stress at which sigma_xy = sigma_yx, with the case's sign [-].

    ``eqn-asymp_soln_eta_g0`` (m0) without gravity, ``eqn-asymp_eta_g`` (a) with it.
    """
    x = np.asarray(xi, dtype=float)
    mag = np.array(
        [
            symmetric_couple_stress(problem.sigma_yx, float(s), problem.material)
            for s in np.ravel(problem.sigma_c(x))
        ]
    ).reshape(x.shape)
    case = problem.case
    if case is PlaneShearCase.SYMMETRIC:
        return np.where(x >= 0.5, mag, -mag)
    return mag if case is PlaneShearCase.UPPER else -mag


def exponential_layer(
    distance: FloatArray,
    *,
    eps: float,
    k: float,
    K: float,
    u_wall: float,
    u_ref: float,
    slip_sign: float,
) -> tuple[FloatArray, FloatArray]:
    """(u, omega) of ``eqn-asymp_vels`` at a distance from the slipping wall [-]."""
    with np.errstate(under="ignore"):
        decay = np.exp(-k * np.abs(distance) / eps)
    u = u_ref + (u_wall - u_ref) * (2.0 / k) / (K + 2.0 / k) * decay
    omega = -slip_sign * (u_wall - u_ref) / (eps * (K + 2.0 / k)) * decay
    return u, omega


def solve_plane(
    problem: PlaneShear,
    *,
    points: int | None = None,
    xi: FloatArray | None = None,
    check: bool = True,
) -> Profile:
    """The leading-order small-eps profile of a plane-shear problem."""
    eps = problem.eps
    case = problem.case
    const = problem.slip_constants
    sigma_yx = problem.sigma_yx

    # k = 0 (fully rough slipping wall) happens only between identical fully rough walls
    # without gravity, or at the upper wall under gravity: no wall is rougher than fully rough.
    if const.k == 0.0:
        if problem.B > 0.0:
            from .airy import solve_plane_fully_rough

            return solve_plane_fully_rough(problem, points=points, xi=xi, check=check)

        def evaluate(x: FloatArray) -> Fields:
            x = np.asarray(x, dtype=float)
            return _fields(x, np.zeros_like(x), x.copy(), np.full_like(x, -0.5), sigma_yx, problem)

        return make_profile(
            problem,
            problem.formulation(),
            evaluate,
            method="asymptotic",
            points=points,
            xi=xi,
            reference_velocity=0.5,
            check=check,
            message="leading order of vel_g0: uniform shear (fully rough walls, m = 0)",
        )

    xs = problem.slip_wall
    u0 = 0.5 if case is PlaneShearCase.SYMMETRIC else problem.reference_velocity
    layer = {
        "eps": eps,
        "k": const.k,
        "K": problem.slipping.K,
        "u_wall": problem.wall_velocity(xs),
        "u_ref": u0,
        "slip_sign": problem.slip_sign(xs),
    }

    def evaluate(x: FloatArray) -> Fields:
        x = np.asarray(x, dtype=float)
        u, omega = exponential_layer(xs - x, **layer)
        if case is PlaneShearCase.SYMMETRIC:  # the mirror layer at the lower wall
            u_low, omega_low = exponential_layer(x, **layer)
            u, omega = u - (u_low - u0), omega + omega_low
        return _fields(x, outer_couple_stress(problem, x), u, omega, sigma_yx, problem)

    return make_profile(
        problem,
        problem.formulation(),
        evaluate,
        method="asymptotic",
        points=points,
        xi=xi,
        reference_velocity=u0,
        check=check,
        message=f"eqn-asymp_vels at leading order in eps (k = {const.k:.6g}, u_0 = {u0:g})",
    )


def solve_couette(
    problem: CouetteFlow,
    *,
    points: int | None = None,
    xi: FloatArray | None = None,
    check: bool = True,
) -> Profile:
    """Leading-order small-eps Couette profile (Appendix, "Cylindrical Couette flow").

    Not fully rough: the Couette m^(0) outside an O(eps) layer and the velocity of
    ``eqn-asymp_soln_vels_g0_aw`` near the inner cylinder. Fully rough: the Airy inner layer
    (``eqn-asymp_soln_vels_cyl_fr``).
    """
    const = problem.slip_constants
    if const.k == 0.0:
        from .airy import solve_couette_fully_rough

        return solve_couette_fully_rough(problem, points=points, xi=xi, check=check)
    layer = {
        "eps": problem.eps,
        "k": const.k,
        "K": problem.wall.K,
        "u_wall": problem.wall_velocity(0.0),
        "u_ref": 0.0,
        "slip_sign": problem.slip_sign(0.0),
    }
    form = problem.formulation(float(problem.outer_couple_stress(np.array([0.0]))[0]))

    def evaluate(x: FloatArray) -> Fields:
        x = np.asarray(x, dtype=float)
        u, omega = exponential_layer(x, **layer)
        return couette_leading_order_fields(problem, x, problem.outer_couple_stress(x), u, omega)

    return make_profile(
        problem,
        form,
        evaluate,
        method="asymptotic",
        points=points,
        xi=xi,
        reference_velocity=0.0,
        check=check,
        message=f"Couette m^(0) and eqn-asymp_soln_vels_g0_aw at leading order (k = {const.k:.6g})",
    )


def couette_leading_order_fields(
    problem: CouetteFlow, x: FloatArray, m: FloatArray, u: FloatArray, omega: FloatArray
) -> Fields:
    """Leading order: s_rt = s_tr = -tan(delta)/(1 + xi/Ri)^2 and du/dxi = -2 omega."""
    s = -problem.tan_delta / (1.0 + x / problem.Ri) ** 2
    return Fields(
        u=u,
        omega=omega,
        m=m,
        sigma_xy=s,
        sigma_yx=s,
        sigma_yy=np.ones_like(x),
        du_dxi=-2.0 * omega,
        kappa=problem.curvature(x),
    )


def _fields(
    x: FloatArray,
    m: FloatArray,
    u: FloatArray,
    omega: FloatArray,
    sigma_yx: float,
    problem: PlaneShear,
) -> Fields:
    """Leading-order fields: symmetric stress, so du/dxi = -2 omega (``eqn-nd_fr1``)."""
    return Fields(
        u=u,
        omega=omega,
        m=m,
        sigma_xy=np.full_like(x, sigma_yx),
        sigma_yx=np.full_like(x, sigma_yx),
        sigma_yy=problem.sigma_c(x),
        du_dxi=-2.0 * omega,
        kappa=np.zeros_like(x),
    )
