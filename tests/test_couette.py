"""Cylindrical Couette flow: balances checked independently, the R_i -> infinity limit, the
asymptotics, thickness laws, the conserved torque, and the model's no-solution region."""

from __future__ import annotations

import math

import numpy as np
import pytest
from reference import delta_limit_by_hand

from cosserat import (
    Cosserat,
    Couette,
    Material,
    NoSolutionError,
    ParameterError,
    Plane,
    Problem,
    Wall,
    shear_layer_thickness,
    solve,
)
from cosserat.analysis import asymptotic_thickness
from cosserat.analysis.cell import CouetteCell
from cosserat.routes.airy import xi_hat_at_fraction

MAT = Material(28.5)


def test_parameter_bounds():
    with pytest.raises(
        ParameterError,
        match=r"Ri \(inner radius over gap, R_i/H\) must satisfy 0.001 <= Ri <= 1e\+06; got 0",
    ):
        Problem(Couette(eps=0.1, Ri=0.0), Cosserat(material=MAT, wall=Wall(20.0)))
    with pytest.raises(ParameterError, match="eps"):
        Problem(Couette(eps=0.0, Ri=1.0), Cosserat(material=MAT, wall=Wall(20.0)))
    with pytest.raises(ParameterError, match=r"tan\(delta\) <= sin\(phi\)"):
        Problem(Couette(eps=0.1, Ri=1.0), Cosserat(material=MAT, wall=Wall(30.0)))


def fine_profile(wall: Wall):  # type: ignore[no-untyped-def]
    """(xi, fields, r = Ri + xi) at eps = 0.04, Ri = 1, rtol = 1e-10, on a grid fine enough
    for second-order finite differences."""
    prof = solve(Problem(Couette(eps=0.04, Ri=1.0), Cosserat(material=MAT, wall=wall)), rtol=1e-10)
    x = np.linspace(0.0, 1.0, 40001)
    return x, prof.evaluate(x), 1.0 + x


@pytest.mark.parametrize("wall", [Wall(20.0), Wall.fully_rough()])
def test_balances_hold_by_finite_differences(wall):
    """theta-momentum and the couple-stress balance with the factor 2(A+1) alpha that the
    printed eqn-nd_zangmom_cyl lacks (eqn-nd_shsts_cyl has it)."""
    x, f, r = fine_profile(wall)
    A, alpha, eps = MAT.A, MAT.alpha, 0.04
    theta_mom = np.gradient(f.sigma_yx, x) + (f.sigma_yx + f.sigma_xy) / r
    couple = 2 * (A + 1) * eps * alpha * (np.gradient(f.m, x) + f.m / r)
    imbalance = couple - (f.sigma_yx - f.sigma_xy)
    assert np.max(np.abs(theta_mom[1:-1])) < 1e-6
    assert np.max(np.abs(imbalance[1:-1])) < 1e-6
    # the printed form eps (m' + m/r) = s_rt - s_tr is off by the factor 2(A+1) alpha
    printed = eps * (np.gradient(f.m, x) + f.m / r) - (f.sigma_yx - f.sigma_xy)
    assert np.max(np.abs(printed[1:-1])) > 1e3 * np.max(np.abs(imbalance[1:-1]))


@pytest.mark.parametrize("wall", [Wall(20.0), Wall.fully_rough()])
def test_flow_rule_holds_by_finite_differences(wall):
    """eqn-nd_fr1_cyl and eqn-nd_fr2_cyl as printed (paper's signs), checked on the profile."""
    x, f, r = fine_profile(wall)
    A, alpha, eps = MAT.A, MAT.alpha, 0.04
    srt, str_ = f.sigma_yx, f.sigma_xy
    rel = f.omega + f.u / r
    fr1 = np.gradient(f.u, x) - f.u / r + rel * (A + 1) * (str_ + srt) / (str_ + A * srt)
    fr2 = eps * alpha * np.gradient(f.omega, x) + rel * 2 * (A + 1) * f.m / (str_ + A * srt)
    scale = np.max(np.abs(f.omega))
    assert np.max(np.abs(fr1[1:-1])) < 1e-6 * scale
    assert np.max(np.abs(fr2[1:-1])) < 1e-6 * scale


def test_boundary_conditions_and_signs():
    problem = Problem(Couette(eps=0.04, Ri=1.0), Cosserat(material=MAT, wall=Wall(20.0, 0.5)))
    prof = solve(problem)
    assert max(abs(v) for v in prof.diagnostics.bc_errors.values()) < 1e-9
    assert prof.sigma_yx[0] == pytest.approx(-problem.equations.tan_delta)
    assert prof.u[0] == pytest.approx(-1 - problem.eps * 0.5 * prof.omega[0])
    assert np.all(prof.m <= 0.0)  # the paper's "couple stress is negative"
    assert np.all(np.diff(prof.u) >= 0.0)  # |u| falls away from the inner cylinder
    assert prof.diagnostics.stats["m_inner"] == pytest.approx(prof.m[0], abs=1e-9)


def test_large_radius_limit_is_plane_shear_with_a_rougher_fixed_wall_not_the_symmetric_case():
    """With s_rt = s_tr and no slip at the outer cylinder, Ri -> inf gives the plane layer at a
    slipping wall facing a non-slipping one (eqn-soln_aw_vels, mirrored: xi -> 1 - xi, u -> -u,
    m -> -m), not the symmetric gravity-free case the paper names."""
    eps = 0.04
    plane = Problem(
        Plane(eps=eps), Cosserat(material=MAT, wall=Wall(20.0), lower=Wall.fully_rough())
    )
    symmetric = Problem(Plane(eps=eps), Cosserat(material=MAT, wall=Wall(20.0)))
    gaps, m_gaps = [], []
    for Ri in (1e2, 1e3, 1e4):
        cou = solve(Problem(Couette(eps=eps, Ri=Ri), Cosserat(material=MAT, wall=Wall(20.0))))
        ref = solve(plane, method="closed-form", xi=1.0 - cou.xi[::-1])
        sym = solve(symmetric, method="closed-form", xi=1.0 - cou.xi[::-1])
        gaps.append(np.max(np.abs(cou.u + ref.u[::-1])))
        m_gaps.append(np.max(np.abs(cou.m + ref.m[::-1])))
        assert np.max(np.abs(cou.u + sym.u[::-1])) > 0.3
    # converges like 1/Ri, in u and in m
    assert m_gaps[0] / m_gaps[1] == pytest.approx(10, rel=0.2)
    assert m_gaps[1] / m_gaps[2] == pytest.approx(10, rel=0.2)
    assert gaps[0] / gaps[1] == pytest.approx(10, rel=0.2)
    assert gaps[1] / gaps[2] == pytest.approx(10, rel=0.2)
    assert gaps[2] < 2e-4


@pytest.mark.parametrize(("wall", "order"), [(Wall(20.0), 1.0), (Wall.fully_rough(), 1 / 3)])
def test_asymptotic_error_shrinks_at_the_predicted_rate(wall, order):
    eps_values = [1e-4, 1e-5, 1e-6]
    errors = []
    for eps in eps_values:
        problem = Problem(Couette(eps=eps, Ri=1.0), Cosserat(material=MAT, wall=wall))
        num = solve(problem, check=False)
        asym = solve(problem, method="asymptotic", xi=num.xi, check=False)
        errors.append(np.max(np.abs(num.u - asym.u)))
    observed = np.polyfit(np.log(eps_values), np.log(errors), 1)[0]
    assert abs(observed - order) < 0.1


def test_thickness_laws():
    rough = Problem(Couette(eps=1e-6, Ri=1.0), Cosserat(material=MAT, wall=Wall.fully_rough()))
    law = xi_hat_at_fraction(0.05) * 1e-6 ** (-1 / 3) * (MAT.L**2 * 1.0 / 4) ** (1 / 3)
    assert asymptotic_thickness(rough) == pytest.approx(law, rel=1e-12)  # eqn-delta_soln_fr b
    assert shear_layer_thickness(solve(rough, check=False)) / law == pytest.approx(1.0, abs=2e-3)
    # not fully rough: Delta -> -ln f / k = 17.6688 (eqn-delta_soln), the gap closing like eps
    gaps = [
        abs(
            shear_layer_thickness(
                solve(
                    Problem(Couette(eps=eps, Ri=1.0), Cosserat(material=MAT, wall=Wall(20.0))),
                    check=False,
                )
            )
            - delta_limit_by_hand()
        )
        for eps in (1e-4, 1e-5, 1e-6)
    ]
    assert gaps[2] < 5e-3
    assert gaps[0] / gaps[1] == pytest.approx(10, rel=0.1)
    assert gaps[1] / gaps[2] == pytest.approx(10, rel=0.1)


@pytest.mark.parametrize(("eps", "Ri"), [(0.5, 1e4), (1e-6, 1e4), (1e-6, 0.05), (1e-3, 0.05)])
def test_robust_corners_of_the_parameter_range(eps, Ri):
    prof = solve(Problem(Couette(eps=eps, Ri=Ri), Cosserat(material=MAT, wall=Wall(20.0))))
    for values in prof.columns().values():
        assert np.all(np.isfinite(values))
    assert max(abs(v) for v in prof.diagnostics.bc_errors.values()) < 1e-8


def test_large_radius_velocity_is_accurate_to_the_requested_tolerance():
    # u = (Ri + xi)(u_s/Ri - w_s P): at Ri = 1e5 an absolute tolerance on P that ignores the
    # velocity weight 1/(Ri + xi) once cost u three orders of magnitude (found by Hypothesis)
    problem = Problem(
        Couette(eps=1e-4, Ri=1e5), Cosserat(material=Material(5.0, L=1.0), wall=Wall(2.49))
    )
    ref = solve(problem, points=401, rtol=1e-12, check=False)
    for rtol in (1e-6, 1e-8):
        prof = solve(problem, points=401, rtol=rtol)
        assert np.max(np.abs(prof.u - ref.evaluate(prof.xi).u)) < rtol
        assert prof.diagnostics.residuals["velocity"] < rtol


def test_root_above_the_leading_order_guess_is_bracketed_below_the_real_domain_edge():
    # for this strongly curved, coarse-grained case trials of m(0) above the root soon leave
    # the real domain; the bracket must close in on the root instead of giving up
    mat = Material(5.0, L=0.5)
    for Ri in (0.2288, 0.2371):
        prof = solve(
            Problem(Couette(eps=0.3162, Ri=Ri), Cosserat(material=mat, wall=Wall.fully_rough(0.0)))
        )
        assert max(abs(v) for v in prof.diagnostics.bc_errors.values()) < 1e-8
        assert max(prof.diagnostics.residuals.values()) < 1e-6


def test_small_radius_and_wide_grains_has_no_real_solution_and_says_so():
    with pytest.raises(NoSolutionError, match=r"for no couple stress m\(0\) at the inner"):
        solve(Problem(Couette(eps=0.04, Ri=0.05), Cosserat(material=MAT, wall=Wall(20.0))))


def test_torque_is_the_same_on_every_cylinder_and_includes_the_couple_stress():
    cell = CouetteCell(
        density=2500.0,
        grain_diameter=1e-3,
        gap=0.02,
        inner_radius=0.02,
        fill_depth=0.1,
        rotation_rate=0.5,
        solids_fraction=0.6,
    )
    problem = cell.problem(MAT, Wall(20.0))
    prof = solve(problem, rtol=1e-10)
    T = cell.torque_density(prof, depth=0.1)
    assert np.max(np.abs(T - T[0])) < 1e-8 * abs(T[0])
    # the drive torque differs from the classical 2 pi R_i^2 sigma_c tan(delta) by the couple
    classical = (
        2 * math.pi * cell.inner_radius**2 * cell.mean_stress(0.1) * problem.equations.tan_delta
    )
    couple_part = (
        2
        * math.pi
        * cell.inner_radius
        * cell.mean_stress(0.1)
        * (2 * (MAT.A + 1) * MAT.alpha * cell.grain_diameter * prof.m[0])
    )
    assert T[0] == pytest.approx(classical + couple_part, rel=1e-12)
    assert abs(couple_part) > 1e-3 * classical
    assert cell.torque(prof) == pytest.approx(0.5 * T[0] * 0.1)
    assert cell.wall_shear_stress(prof, 0.1) == pytest.approx(
        2500 * 9.81 * 0.6 * 0.1 * problem.equations.tan_delta
    )
    assert cell.slip_velocity(prof) > 0
    np.testing.assert_allclose(cell.velocity(prof)[0], cell.wall_speed - cell.slip_velocity(prof))
