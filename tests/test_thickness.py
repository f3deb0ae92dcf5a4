"""Shear-layer thickness: eqn-delta_defn on profiles, its eps -> 0 laws, wall slip and spin."""

from __future__ import annotations

import itertools
import math

import pytest
from reference import delta_limit_by_hand

from cosserat import (
    Cosserat,
    Material,
    Plane,
    Problem,
    Wall,
    shear_layer_thickness,
    solve,
    wall_omega,
    wall_slip,
)
from cosserat.analysis import asymptotic_thickness, thickness_curve, thickness_limit

MAT = Material(28.5)


def plane(eps, upper, lower=None, B=0.0, nu=1.0):  # type: ignore[no-untyped-def]
    """The Cosserat model in plane shear with the paper's material (MAT)."""
    return Problem(Plane(eps=eps, B=B, nu=nu), Cosserat(material=MAT, wall=upper, lower=lower))


F = 0.05


def test_the_papers_limit_is_17_67():
    assert round(delta_limit_by_hand(), 2) == 17.67
    assert thickness_limit(
        Problem(Plane(eps=0.1), Cosserat(material=MAT, wall=Wall(20.0)))
    ) == pytest.approx(delta_limit_by_hand(), rel=1e-13)


CASES = {
    "no gravity, identical walls": {"upper": Wall(20.0)},
    "no gravity, rougher lower wall": {"upper": Wall(20.0), "lower": Wall(25.0)},
    "gravity, layer at the upper wall": {"upper": Wall(20.0), "B": 1.0},
    "gravity, layer at the lower wall": {"upper": Wall(25.0), "lower": Wall(20.0), "B": 0.2},
}


@pytest.mark.parametrize("name", list(CASES))
def test_delta_approaches_17_67_in_every_plane_case(name):
    problem = plane(1e-2, **CASES[name])
    eps = [1e-2, 1e-3, 1e-4, 1e-5, 1e-6]
    curve = thickness_curve(problem, eps)
    gaps = [abs(d - delta_limit_by_hand()) for d in curve.Delta]
    assert gaps[-1] < 2e-3  # eps = 1e-6
    # from eps = 1e-3 on, each decade brings Delta closer to the limit
    assert all(g1 <= g0 + 1e-6 for g0, g1 in itertools.pairwise(gaps[1:]))


def test_thickness_of_uniform_shear_is_exact():
    """Fully rough identical walls: linear u, so Delta = (1 - u0)(1 - f)/eps with u0 = 1/2."""
    eps = 0.02
    problem = Problem(Plane(eps=eps), Cosserat(material=MAT, wall=Wall.fully_rough()))
    for method in ("closed-form", "numerical"):
        assert shear_layer_thickness(solve(problem, method=method)) == pytest.approx(
            0.5 * (1 - F) / eps, rel=1e-9
        )
    assert asymptotic_thickness(problem) == pytest.approx(0.5 * (1 - F) / eps)


def test_thickness_does_not_depend_on_the_output_grid():
    problem = Problem(Plane(eps=1e-4, B=1.0), Cosserat(material=MAT, wall=Wall(20.0)))
    coarse = solve(problem, points=5)
    fine = solve(problem, points=2001)
    assert shear_layer_thickness(coarse) == pytest.approx(shear_layer_thickness(fine), rel=1e-12)


def test_thickness_definition_holds_on_the_profile():
    problem = Problem(Plane(eps=1e-3), Cosserat(material=MAT, wall=Wall(15.0)))
    prof = solve(problem)
    d = shear_layer_thickness(prof, f=0.1)
    u_w, u_d = prof.evaluate([1.0, 1.0 - problem.eps * d]).u
    assert (u_d - 0.5) == pytest.approx(0.1 * (u_w - 0.5), rel=1e-9)


def test_wall_slip_and_spin_match_the_closed_form():
    eps, K = 1e-3, 0.5
    problem = Problem(Plane(eps=eps), Cosserat(material=MAT, wall=Wall(20.0, K), lower=Wall(25.0)))
    k = problem.equations.slip_constants.k
    omega_1 = -1.0 / eps / (2.0 / k + K - 2.0 * math.exp(-k / eps) / k)  # eqn-omega1_g0aw
    prof = solve(problem)
    assert wall_omega(prof) == pytest.approx(omega_1, rel=1e-7)
    assert wall_slip(prof) == pytest.approx(-eps * K * omega_1, rel=1e-7)  # eqn-nd_bc3u


def test_thickness_curve_records_no_solution_instead_of_failing():
    problem = Problem(Plane(eps=0.01, B=1.0), Cosserat(material=MAT, wall=Wall(20.0)))
    curve = thickness_curve(problem, [0.1, 0.01])
    assert curve.Delta[0] is None and "no real solution" in curve.failures[0.1]
    single = shear_layer_thickness(
        solve(Problem(Plane(eps=0.01, B=1.0), Cosserat(material=MAT, wall=Wall(20.0))))
    )
    assert curve.Delta[1] == pytest.approx(single, rel=1e-12)
