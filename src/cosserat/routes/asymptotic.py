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
(:mod:`cosserat.routes.airy`).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from ..errors import MethodNotAvailableError, NoSolutionError
from ..model import Problem
from ..model.constitutive import FloatArray, symmetric_couple_stress
from ..model.rheologies.base import equations_of
from ..model.rheologies.cosserat import CosseratCouette, CosseratPlane, PlaneShearCase
from ..results.profile import Fields, Profile
from .airy import airy_layer, inner_couple_stress
from .assemble import make_profile
from .laws import asymptotic_thickness


def plane_outer_couple_stress(eq: CosseratPlane, xi: FloatArray) -> FloatArray:
    """m^(0): the couple stress at which sigma_xy = sigma_yx, with the case's sign [-].

    ``eqn-asymp_soln_eta_g0`` (m0) without gravity, ``eqn-asymp_eta_g`` (a) with it.
    """
    x = np.asarray(xi, dtype=float)
    mag = np.array(
        [
            symmetric_couple_stress(eq.sigma_yx, float(s), eq.material)
            for s in np.ravel(eq.sigma_c(x))
        ]
    ).reshape(x.shape)
    case = eq.case
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


# The expansion needs a layer much thinner than the gap: eps * Delta (where u falls to 5%)
# at most this fraction of the gap.
THIN_LAYER = 0.1
AIRY_BC_TOL = 0.1
"""Largest boundary-condition error the leading-order Airy layer at a fully rough wall may
leave [wall speed, or the stress scale]: its slip condition is missed by about
0.3 K eps^(1/3) (0.016 at eps = 1e-3, K = 1/2; 0.039 at K = 1.2; 0.03 at eps = 1e-4, K = 2),
but by 0.76 at eps = 0.015, Ri = 0.557, L = 0.6, K = 1.2 (measured), where the numerical route
gives a profile that satisfies it to 1e-15. Beyond this the route refuses."""


def require_valid(eq: Any, thickness: float) -> None:
    """Raise :class:`MethodNotAvailableError` unless the small-eps expansion applies.

    Checks that the layer is thin (``thickness`` = eps Delta of the leading-order law at most
    ``THIN_LAYER`` of the gap), that no couple stress is prescribed at a wall (the expansion
    uses eqn-nd_bc4), and that the outer couple stress m^(0) is attainable outside the layer:
    the couple-stress balance can lower m at most at the rate a/(eps alpha) (where
    sqrt(S) = 0), so eps alpha |dm0/dxi + kappa m0| must stay well below a = |sigma_yx|/2
    (``docs/derivation_plane.md`` section 6).
    """
    if getattr(eq, "m_fixed_wall", None) is not None:
        raise MethodNotAvailableError(
            "the asymptotic route assumes sigma_xy = sigma_yx at the fixed wall (eqn-nd_bc4); "
            "with m_fixed_wall use method='numerical'"
        )
    if thickness > THIN_LAYER:
        raise MethodNotAvailableError(
            f"the small-eps asymptotics need a layer much thinner than the gap, but the "
            f"leading-order layer is {thickness:.3g} gap widths thick (> {THIN_LAYER:g}): use "
            f"method='numerical'"
        )
    x = np.linspace(0.0, 1.0, 401)
    layers = [eq.slip_wall]  # and the inner layer at the centre between identical walls
    if eq.problem.cell_name == "plane" and eq.case is PlaneShearCase.SYMMETRIC:
        layers += [0.0, 0.5]
    for centre in layers:
        x = x[np.abs(x - centre) > 3.0 * thickness + 0.01]
    if x.size < 3:
        raise MethodNotAvailableError(
            f"the small-eps asymptotics need an outer region between the layers, but layers "
            f"{thickness:.3g} gap widths thick at xi = "
            f"{', '.join(f'{c:g}' for c in sorted(set(layers)))} fill the gap: use "
            f"method='numerical'"
        )
    m0 = outer_couple_stress(eq, x)
    form = eq.formulation(float(m0[0])) if eq.problem.cell_name == "couette" else (eq.formulation())
    need = eq.eps * eq.material.alpha * np.abs(np.gradient(m0, x) + form.curvature(x) * m0)
    a = 0.5 * np.abs(np.asarray(form.sigma_yx(x, m0), dtype=float))
    if np.any(need > 0.5 * a):
        i = int(np.argmax(need / np.maximum(a, 1e-300)))
        raise MethodNotAvailableError(
            f"the leading-order couple stress changes too fast for the couple-stress balance "
            f"near xi = {x[i]:.3g} (eps alpha |dm0/dxi| = {need[i]:.3g} against a = {a[i]:.3g}): "
            f"the expansion does not apply; method='numerical' says whether a real solution "
            f"exists"
        )


def outer_couple_stress(eq: Any, xi: FloatArray) -> FloatArray:
    """m^(0) on either cell: the couple stress at which the stress is symmetric [-]."""
    if eq.problem.cell_name == "couette":
        return eq.outer_couple_stress(xi)
    return plane_outer_couple_stress(eq, xi)


def require_boundary_conditions(eq: Any, profile: Profile) -> Profile:
    """``profile`` if its boundary conditions hold to :data:`AIRY_BC_TOL`, else raise
    :class:`MethodNotAvailableError` naming the worst one (a fully rough wall's Airy layer)."""
    bc = profile.diagnostics.bc_errors or eq.boundary_errors(profile.evaluator)
    if not bc:
        return profile
    key = max(bc, key=lambda k: abs(bc[k]))
    if abs(bc[key]) > AIRY_BC_TOL:
        raise MethodNotAvailableError(
            f"the leading-order Airy layer misses the boundary condition {key} by "
            f"{abs(bc[key]):.3g} (more than {AIRY_BC_TOL:g}; its error grows like K eps^(1/3)): "
            f"{eq.problem.describe()} is outside the small-eps expansion's range, use "
            "method='numerical'"
        )
    return profile


def _profile(eq: Any, form, evaluate, **kw):
    """make_profile, with a composite that leaves the yield surface reported as the
    expansion's failure, not the model's."""
    try:
        return make_profile(eq.problem, form, evaluate, method="asymptotic", **kw)
    except NoSolutionError as exc:
        raise MethodNotAvailableError(
            f"the leading-order asymptotic profile leaves the yield surface ({exc}); eps is "
            f"too large for the expansion: use method='numerical'"
        ) from None


def solve_plane(
    problem: Problem,
    *,
    points: int | None = None,
    xi: FloatArray | None = None,
    check: bool = True,
) -> Profile:
    """The leading-order small-eps profile of the Cosserat model in plane shear."""
    return _solve_plane(equations_of(problem, CosseratPlane), points=points, xi=xi, check=check)


def _solve_plane(
    eq: CosseratPlane, *, points: int | None, xi: FloatArray | None, check: bool
) -> Profile:
    eps = eq.eps
    case = eq.case
    const = eq.slip_constants
    sigma_yx = eq.sigma_yx

    # k = 0 (fully rough slipping wall) happens only between identical fully rough walls
    # without gravity, or at the upper wall under gravity: no wall is rougher than fully rough.
    if const.k == 0.0:
        if eq.B > 0.0:
            return solve_plane_fully_rough(eq, points=points, xi=xi, check=check)
        require_valid(eq, 0.0)

        def uniform(x: FloatArray) -> Fields:
            x = np.asarray(x, dtype=float)
            return _fields(x, np.zeros_like(x), x.copy(), np.full_like(x, -0.5), sigma_yx, eq)

        return _profile(
            eq,
            eq.formulation(),
            uniform,
            points=points,
            xi=xi,
            reference_velocity=0.5,
            check=check,
            message="leading order of vel_g0: uniform shear (fully rough walls, m = 0)",
        )

    k = const.k
    require_valid(eq, eps * asymptotic_thickness(eq.problem))
    if case is PlaneShearCase.SYMMETRIC:
        # both walls slip; omega even, u - u_c odd; the layers each carry 2 omega_1 eps/k of
        # velocity, so u(1) - u(0) = 1 + eps (K_u + K_l) omega_1 gives omega_1, and the sum of
        # the slip conditions u_c (as the closed form's symmetric_wall_constants)
        K_u, K_l = eq.upper.K, eq.lower_wall.K
        omega_1 = -1.0 / (eps * (4.0 / k + K_u + K_l))
        u0 = 0.5 * (1.0 + eps * (K_u - K_l) * omega_1)

        def evaluate(x: FloatArray) -> Fields:
            x = np.asarray(x, dtype=float)
            with np.errstate(under="ignore"):
                up, low = np.exp(-k * (1.0 - x) / eps), np.exp(-k * x / eps)
            u = u0 - 2.0 * omega_1 * (eps / k) * (up - low)
            return _fields(
                x, plane_outer_couple_stress(eq, x), u, omega_1 * (up + low), sigma_yx, eq
            )

        message = f"eqn-asymp_soln_vels_g0 (both walls), k = {k:.6g}, u_c = {u0:.6g}"
    else:
        xs = eq.slip_wall
        u0 = eq.reference_velocity
        layer = {
            "eps": eps,
            "k": k,
            "K": eq.slipping.K,
            "u_wall": eq.wall_velocity(xs),
            "u_ref": u0,
            "slip_sign": eq.slip_sign(xs),
        }

        def evaluate(x: FloatArray) -> Fields:
            x = np.asarray(x, dtype=float)
            u, omega = exponential_layer(xs - x, **layer)
            return _fields(x, plane_outer_couple_stress(eq, x), u, omega, sigma_yx, eq)

        message = f"eqn-asymp_vels at leading order in eps (k = {k:.6g}, u_0 = {u0:g})"
    return _profile(
        eq,
        eq.formulation(),
        evaluate,
        points=points,
        xi=xi,
        reference_velocity=u0,
        check=check,
        message=message,
    )


def solve_couette(
    problem: Problem,
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
    return _solve_couette(equations_of(problem, CosseratCouette), points=points, xi=xi, check=check)


def _solve_couette(
    eq: CosseratCouette, *, points: int | None, xi: FloatArray | None, check: bool
) -> Profile:
    const = eq.slip_constants
    if const.k == 0.0:
        return solve_couette_fully_rough(eq, points=points, xi=xi, check=check)
    require_valid(eq, eq.eps * asymptotic_thickness(eq.problem))
    layer = {
        "eps": eq.eps,
        "k": const.k,
        "K": eq.wall.K,
        "u_wall": eq.wall_velocity(0.0),
        "u_ref": 0.0,
        "slip_sign": eq.slip_sign(0.0),
    }
    form = eq.formulation(float(eq.outer_couple_stress(np.array([0.0]))[0]))

    def evaluate(x: FloatArray) -> Fields:
        x = np.asarray(x, dtype=float)
        u, omega = exponential_layer(x, **layer)
        return couette_leading_order_fields(eq, x, eq.outer_couple_stress(x), u, omega)

    return _profile(
        eq,
        form,
        evaluate,
        points=points,
        xi=xi,
        reference_velocity=0.0,
        check=check,
        message=f"Couette m^(0) and eqn-asymp_soln_vels_g0_aw at leading order (k = {const.k:.6g})",
    )


def couette_leading_order_fields(
    eq: CosseratCouette, x: FloatArray, m: FloatArray, u: FloatArray, omega: FloatArray
) -> Fields:
    """Leading order: s_rt = s_tr = -tan(delta)/(1 + xi/Ri)^2 and du/dxi = -2 omega."""
    s = -eq.tan_delta / (1.0 + x / eq.Ri) ** 2
    return Fields(
        u=u,
        omega=omega,
        m=m,
        sigma_xy=s,
        sigma_yx=s,
        sigma_yy=np.ones_like(x),
        du_dxi=-2.0 * omega,
        kappa=eq.curvature(x),
    )


def _fields(
    x: FloatArray,
    m: FloatArray,
    u: FloatArray,
    omega: FloatArray,
    sigma_yx: float,
    eq: CosseratPlane,
) -> Fields:
    """Leading-order fields: symmetric stress, so du/dxi = -2 omega (``eqn-nd_fr1``)."""
    return Fields(
        u=u,
        omega=omega,
        m=m,
        sigma_xy=np.full_like(x, sigma_yx),
        sigma_yx=np.full_like(x, sigma_yx),
        sigma_yy=eq.sigma_c(x),
        du_dxi=-2.0 * omega,
        kappa=np.zeros_like(x),
    )


# ----------------------------------------------------------------- fully rough walls: Airy layer
def solve_plane_fully_rough(
    eq: CosseratPlane, *, points: int | None, xi: FloatArray | None, check: bool
) -> Profile:
    """Plane shear under gravity, fully rough upper wall (``eqn-eta_g_unif``,
    ``eqn-asymp_soln_vels_g_fr``, ``eqn-asymp_soln_vels_g__fr_consts``, ``eqn-vel_g_unif``)."""
    eps, mat = eq.eps, eq.material
    B_nu = eq.B * eq.nu
    if B_nu < 10.0 * eps:
        raise MethodNotAvailableError(
            f"the Airy inner layer needs B nu >> eps (the paper: not valid when B nu ~ eps); "
            f"got B nu = {B_nu:g}, eps = {eps:g}: use method='numerical'"
        )
    require_valid(eq, eps * asymptotic_thickness(eq.problem))
    a = 0.5 * eq.tan_delta_upper
    scale = eq.inner_scale()
    inner_amp = (4.0 * a * mat.alpha * B_nu * mat.c2) ** (1.0 / 3.0) * eps ** (1.0 / 3.0)
    sigma_yx = eq.sigma_yx

    def evaluate(x: FloatArray) -> Fields:
        x = np.asarray(x, dtype=float)
        depth = 1.0 - x
        xh = depth * eps ** (-2.0 / 3.0) / scale
        sc = eq.sigma_c(x)
        outer = math.sqrt(mat.c2) * np.sqrt(np.maximum(sc**2 - 1.0, 0.0))
        common = np.sqrt(2.0 * B_nu * mat.c2 * depth)
        m = outer + inner_amp * inner_couple_stress(xh) - common
        u, omega = airy_layer(xh, eps=eps, scale=scale, u_wall=1.0, slip_sign=1.0)
        return Fields(
            u=u,
            omega=omega,
            m=m,
            sigma_xy=np.full_like(x, sigma_yx),
            sigma_yx=np.full_like(x, sigma_yx),
            sigma_yy=sc,
            du_dxi=-2.0 * omega,
            kappa=np.zeros_like(x),
        )

    profile = _profile(
        eq,
        eq.formulation(),
        evaluate,
        points=points,
        xi=xi,
        reference_velocity=0.0,
        check=check,
        message="Airy inner layer (eqn-eta_g_unif, eqn-vel_g_unif) at leading order in eps",
    )
    return require_boundary_conditions(eq, profile)


def solve_couette_fully_rough(
    eq: CosseratCouette, *, points: int | None, xi: FloatArray | None, check: bool
) -> Profile:
    """Couette flow, fully rough cylinders: the Airy inner layer at the inner cylinder with
    x_hat = xi eps^(-2/3) (L^2 Ri/4)^(-1/3) and the composite couple stress of the Appendix."""
    require_valid(eq, eq.eps * asymptotic_thickness(eq.problem))
    eps, Ri = eq.eps, eq.Ri
    scale = eq.inner_scale()
    d = eq.tan_delta / math.sqrt(2.0 * (eq.material.A + 1.0))
    inner_amp = eps ** (1.0 / 3.0) * d * (4.0 * eq.material.L / Ri) ** (1.0 / 3.0)

    def evaluate(x: FloatArray) -> Fields:
        x = np.asarray(x, dtype=float)
        xh = x * eps ** (-2.0 / 3.0) / scale
        # composite: outer + inner - common; the inner m_hat = Ai'/Ai solves dm/dx + m^2 = x
        m = (
            eq.outer_couple_stress(x)
            - inner_amp * inner_couple_stress(xh)
            + d * np.sqrt(4.0 * x / Ri)
        )
        u, omega = airy_layer(xh, eps=eps, scale=scale, u_wall=-1.0, slip_sign=-1.0)
        return couette_leading_order_fields(eq, x, m, u, omega)

    form = eq.formulation(float(evaluate(np.array([0.0])).spin()[1][0]))
    profile = _profile(
        eq,
        form,
        evaluate,
        points=points,
        xi=xi,
        reference_velocity=0.0,
        check=check,
        message="Airy inner layer at the inner cylinder (eqn-asymp_soln_vels_cyl_fr)",
    )
    return require_boundary_conditions(eq, profile)
