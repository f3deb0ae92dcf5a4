"""Asymptotic route: against exact solutions, and the error shrinking at the predicted rate."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.integrate import quad
from scipy.optimize import brentq
from scipy.special import airy

from cosserat import (
    Cosserat,
    Couette,
    Material,
    MethodNotAvailableError,
    Plane,
    Problem,
    Wall,
    solve,
)
from cosserat.routes.airy import I_INFINITY, velocity_fraction, xi_hat_at_fraction

MAT = Material(28.5)


def plane(eps, upper, lower=None, B=0.0, nu=1.0):  # type: ignore[no-untyped-def]
    """The Cosserat model in plane shear with the paper's material (MAT)."""
    return Problem(Plane(eps=eps, B=B, nu=nu), Cosserat(material=MAT, wall=upper, lower=lower))


EPS = [1e-3, 1e-4, 1e-5, 1e-6]


def order_of(errors, eps):
    """Slope of log(error) against log(eps): the observed order."""
    return np.polyfit(np.log(eps), np.log(errors), 1)[0]


@pytest.mark.parametrize(
    "lower", [None, Wall(25.0), Wall(10.0), Wall(20.0, K=0.0), Wall(20.0, K=5.0)]
)
def test_zero_gravity_asymptotics_are_exact_up_to_exponentially_small_terms(lower):
    """eqn-asymp_soln_vels_g0 / _g0_aw differ from the exact solution by O(exp(-k/(2 eps)));
    between identical walls with different K the mid-plane velocity is not 1/2."""
    problem = Problem(Plane(eps=1e-3), Cosserat(material=MAT, wall=Wall(20.0), lower=lower))
    exact = solve(problem, method="closed-form")
    asym = solve(problem, method="asymptotic", xi=exact.xi)
    assert np.max(np.abs(asym.u - exact.u)) < 1e-12
    assert np.max(np.abs(asym.omega - exact.omega)) < 1e-12 * np.max(np.abs(exact.omega))


@pytest.mark.parametrize(
    ("kwargs", "order"),
    [
        ({"upper": Wall(20.0), "B": 1.0}, 1.0),  # regular expansion: O(eps)
        ({"upper": Wall(25.0), "lower": Wall(20.0), "B": 0.2}, 1.0),  # layer at the lower wall
        ({"upper": Wall.fully_rough(), "B": 1.0}, 1.0 / 3.0),  # Airy layer: O(eps^1/3)
    ],
)
def test_asymptotic_error_shrinks_at_the_predicted_rate(kwargs, order):
    errors = []
    for eps in EPS:
        problem = plane(eps, **kwargs)
        num = solve(problem)
        asym = solve(problem, method="asymptotic", xi=num.xi)
        errors.append(np.max(np.abs(num.u - asym.u)))
    observed = order_of(errors, EPS)
    assert abs(observed - order) < 0.1, f"observed order {observed:.3f}, expected {order:.3f}"


def test_I_infinity_and_the_airy_fraction_against_quadrature():
    ai0 = airy(0.0)[0]

    def integral_I(x):
        return quad(lambda z: airy(z)[0] ** 2, 0.0, x, epsabs=1e-14, epsrel=1e-13)[0] / ai0**2

    i_inf = quad(lambda z: airy(z)[0] ** 2, 0.0, np.inf, epsabs=1e-14)[0] / ai0**2
    assert pytest.approx(i_inf, rel=1e-10) == I_INFINITY
    for x in (0.3, 1.0, 2.5, 6.0):
        expected = 1 - integral_I(x) / i_inf
        assert float(velocity_fraction(np.array(x))) == pytest.approx(expected, abs=1e-12)
    x_f = brentq(lambda x: 1 - integral_I(x) / i_inf - 0.05, 0.5, 3.0, xtol=1e-13)
    assert xi_hat_at_fraction(0.05) == pytest.approx(x_f, rel=1e-10)
    assert round(xi_hat_at_fraction(0.05), 3) == 1.275  # the paper's number


def test_fully_rough_identical_walls_shear_uniformly_at_leading_order():
    problem = Problem(Plane(eps=1e-3), Cosserat(material=MAT, wall=Wall.fully_rough()))
    uniform = solve(problem, method="asymptotic")
    np.testing.assert_allclose(uniform.u, uniform.xi)
    np.testing.assert_allclose(uniform.omega, -0.5)
    exact = solve(problem, method="closed-form", xi=uniform.xi)
    assert np.max(np.abs(exact.u - uniform.u)) < 2 * problem.eps  # vel_g0: O(eps K) slip


@pytest.mark.parametrize(
    ("problem", "needle"),
    [
        (
            Problem(Plane(eps=1e-3, B=1e-12), Cosserat(material=MAT, wall=Wall.fully_rough())),
            "B nu >> eps",
        ),
        (
            Problem(Couette(eps=0.04, Ri=1e6), Cosserat(material=MAT, wall=Wall.fully_rough())),
            "thinner than",
        ),
        (
            Problem(Plane(eps=1e-3), Cosserat(material=Material(28.5, L=1e3), wall=Wall(20.0))),
            "thinner than",
        ),
        (
            Problem(Plane(eps=1e-3, B=1e6), Cosserat(material=MAT, wall=Wall(20.0))),
            "changes too fast",
        ),
        (
            Problem(Couette(eps=0.04, Ri=1.0), Cosserat(material=MAT, wall=Wall.fully_rough())),
            "thinner than",
        ),
        # identical walls: layers at both walls and the centre leave no outer region
        (Problem(Plane(eps=5e-3), Cosserat(material=MAT, wall=Wall(20.0))), "fill the gap"),
        (
            Problem(
                Plane(eps=1e-3),
                Cosserat(material=MAT, wall=Wall(20.0), lower=Wall(25.0), m_fixed_wall=0.1),
            ),
            "m_fixed_wall",
        ),
    ],
)
def test_the_asymptotic_route_refuses_where_the_expansion_does_not_apply(problem, needle):
    with pytest.raises(MethodNotAvailableError, match=needle):
        solve(problem, method="asymptotic")
