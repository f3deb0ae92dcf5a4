"""The local mu(I) rheology on the two cells (``docs/derivation_mui.md``).

Closed form against the numerical route; an independent trapezoidal discretisation written
here (its own mu(I), its own root-find) and its second-order convergence; the wall
conditions, monotonicity, the friction range and the plug; the quasi-static limit
(u -> -(1 - eta)^2 in Couette, eta^2 in plane shear under gravity, layer ~ sqrt(I_w)); no
solution beyond mu_2; parameter validation; pickling.
"""

from __future__ import annotations

import math
import pickle

import numpy as np
import pytest
from scipy.optimize import brentq

from cosserat import (
    Couette,
    NoSolutionError,
    ParameterError,
    Plane,
    Problem,
    shear_layer_thickness,
    solve,
    wall_slip,
)
from cosserat.config import DEFAULT_F, MUI_I0, MUI_MU_2, MUI_MU_S
from cosserat.errors import MethodNotAvailableError
from cosserat.model.cells import Cell
from cosserat.model.rheologies import MuI
from cosserat.routes import RHEOLOGIES, cells_for
from cosserat.routes.mui import plug_mask

LAW = MuI()
COUETTE = [
    Problem(Couette(eps=0.01, Ri=1.0, I_w=0.01), MuI()),  # plug in the outer part
    Problem(Couette(eps=0.01, Ri=0.2, I_w=0.05), MuI()),
    Problem(Couette(eps=0.02, Ri=5.0, I_w=0.2), MuI()),  # no plug
    Problem(Couette(eps=0.01, Ri=1.0, I_w=0.9), MuI()),  # mu within 1e-8 of mu_2 at the wall
    Problem(Couette(eps=0.01, Ri=1.0, I_w=1e-5), MuI()),  # a thin layer
]
PLANE_G = [
    Problem(Plane(eps=0.01, B=1.0, I_w=0.01), MuI()),
    Problem(Plane(eps=0.01, B=0.3, nu=0.6, I_w=0.1), MuI()),
    Problem(Plane(eps=0.01, B=10.0, I_w=1.0), MuI()),
]


def test_glass_bead_defaults_are_jop_et_al():
    assert LAW.mu_s == pytest.approx(math.tan(math.radians(20.9)), rel=1e-15)
    assert LAW.mu_2 == pytest.approx(math.tan(math.radians(32.76)), rel=1e-15)
    assert LAW.I_0 == 0.279
    assert (LAW.mu_s, LAW.mu_2, LAW.I_0) == (MUI_MU_S, MUI_MU_2, MUI_I0)
    inertial = np.array([1e-3, 0.1, 1.0])
    np.testing.assert_allclose(LAW.inertial_number(LAW.friction(inertial)), inertial, rtol=1e-12)


def test_mui_is_registered_and_its_problems_are_cells():
    assert RHEOLOGIES["mui"] is MuI
    assert cells_for("mui")[:3] == ["plane", "couette", "channel"]
    assert isinstance(COUETTE[0].cell, Cell) and isinstance(PLANE_G[0].cell, Cell)
    with pytest.raises(MethodNotAvailableError, match="method='numerical'"):
        solve(PLANE_G[0], method="closed-form")


# ----------------------------------------------------------------- closed form vs numerical
@pytest.mark.parametrize("problem", COUETTE, ids=lambda p: f"Ri{p.cell.Ri:g}-Iw{p.cell.I_w:g}")
def test_couette_closed_form_agrees_with_numerical(problem):
    closed = solve(problem, method="closed-form")
    num = solve(problem, method="numerical", xi=closed.xi)
    np.testing.assert_allclose(num.u, closed.u, rtol=0, atol=1e-8)
    np.testing.assert_allclose(num.du_dxi, closed.du_dxi, rtol=1e-8, atol=1e-8)
    s_c, s_n = closed.diagnostics.stats, num.diagnostics.stats
    assert s_n["stress_ratio"] == pytest.approx(s_c["stress_ratio"], rel=1e-8)
    assert s_n["gap_to_mu_2"] == pytest.approx(s_c["gap_to_mu_2"], rel=1e-8)
    assert shear_layer_thickness(num) == pytest.approx(shear_layer_thickness(closed), rel=1e-8)
    for p in (closed, num):
        assert p.diagnostics.residuals["velocity"] < 1e-10
        assert p.diagnostics.residuals["law"] < 1e-10


@pytest.mark.parametrize("I_w", [1e-4, 0.01, 0.5])
def test_plane_shear_without_gravity_is_uniform_at_mu_of_I_w(I_w):
    problem = Problem(Plane(eps=0.02, I_w=I_w), MuI())
    for method in ("closed-form", "numerical"):
        p = solve(problem, method=method)
        np.testing.assert_allclose(p.u, p.xi, atol=1e-12)
        assert p.diagnostics.stats["stress_ratio"] == pytest.approx(
            float(LAW.friction(I_w)), rel=1e-12
        )
        assert p.diagnostics.stats["plug"] is None
        # Delta with u_0 = 0 at the fixed wall: u = 1 - f at 1 - f of the gap
        assert shear_layer_thickness(p) == pytest.approx((1.0 - DEFAULT_F) / 0.02, rel=1e-10)


# ----------------------------------------------------------------- an independent discretisation
def _trapezoid(problem, n):
    """u on a uniform grid of n points by the trapezoidal rule, with this test's own mu(I)
    and its own root-find on the stress ratio at the moving wall."""
    mu_s, mu_2, I_0, I_w = MUI_MU_S, MUI_MU_2, MUI_I0, problem.equations.I_w
    xi = np.linspace(0.0, 1.0, n)

    def inertial(mu):
        return np.where(mu > mu_s, I_0 * (mu - mu_s) / (mu_2 - mu), 0.0)

    def cumulative(f):  # int_0^xi f
        return np.concatenate([[0.0], np.cumsum(0.5 * (f[1:] + f[:-1]) * np.diff(xi))])

    if problem.cell_name == "couette":
        Ri = problem.cell.Ri

        def velocity(T):
            f = inertial(T * (Ri / (Ri + xi)) ** 2) / (Ri + xi)
            c = cumulative(f)
            return -(Ri + xi) * (c[-1] - c) / I_w

        T = brentq(lambda T: velocity(T)[0] + 1.0, mu_s, mu_2 * (1 - 1e-12), xtol=1e-15)
    else:
        s = 1.0 + problem.cell.B * problem.cell.nu * (1.0 - xi)

        def velocity(T):
            return cumulative(np.sqrt(s) * inertial(T / s)) / I_w

        T = brentq(lambda T: velocity(T)[-1] - 1.0, mu_s, mu_2 * (1 - 1e-12), xtol=1e-15)
    return xi, velocity(T)


def _trapezoid_errors(problem, ns):
    errors = []
    for n in ns:
        xi, u = _trapezoid(problem, n)
        ref = solve(problem, method="numerical", xi=xi, check=False)
        errors.append(np.max(np.abs(u - ref.u)))
    return np.array(errors)


NS = np.array([65, 129, 257, 513, 1025, 2049])


@pytest.mark.parametrize("problem", [COUETTE[2], PLANE_G[1]], ids=["couette", "plane"])
def test_an_independent_discretisation_converges_at_second_order_where_the_rate_is_smooth(
    problem,
):
    assert (
        problem.equations.plug_extent(solve(problem, check=False).diagnostics.stats["gap_to_mu_2"])
        is None
    )
    errors = _trapezoid_errors(problem, NS)
    order = -np.polyfit(np.log(NS - 1.0), np.log(errors), 1)[0]
    assert 1.9 < order < 2.1, (order, errors)
    xi, u = _trapezoid(problem, 4097)
    assert np.max(np.abs(u - solve(problem, xi=xi, check=False).u)) < 1e-6


@pytest.mark.parametrize("problem", [COUETTE[0], PLANE_G[0]], ids=["couette", "plane"])
def test_an_independent_discretisation_agrees_across_a_plug_edge(problem):
    """The rate has a kink at the plug edge: the trapezoidal rule stays second order, but its
    constant depends on where the edge falls in its cell (between 0 and h^2/4 times the
    jump), so the errors are bounded by an O(h^2) envelope rather than on a straight line."""
    errors = _trapezoid_errors(problem, NS)
    scaled = errors * (NS - 1.0) ** 2
    assert np.max(scaled) < 10.0 * scaled[0], scaled
    order = -np.polyfit(np.log(NS - 1.0), np.log(errors), 1)[0]
    assert 1.5 < order < 2.5, (order, errors)
    xi, u = _trapezoid(problem, 16385)
    assert np.max(np.abs(u - solve(problem, xi=xi, check=False).u)) < 1e-6


# ----------------------------------------------------------------- invariants
@pytest.mark.parametrize("problem", COUETTE + PLANE_G, ids=lambda p: p.describe()[:40])
def test_walls_monotone_friction_range_and_plug(problem):
    p = solve(problem, method="numerical")
    mw = problem.cell.moving_wall
    fw = 1.0 - mw
    ends = p.evaluate([mw, fw])
    assert ends.u[0] == pytest.approx(problem.wall_velocity(mw), abs=1e-12)
    assert ends.u[1] == 0.0
    assert wall_slip(p) == pytest.approx(0.0, abs=1e-12)
    assert np.all(np.diff(p.u) >= -1e-15)  # u rises from the inner cylinder / lower wall
    mu = np.abs(p.sigma_yx) / p.sigma_yy
    plug = plug_mask(p)
    np.testing.assert_array_equal(plug, mu <= LAW.mu_s)
    # mu_2 - mu from the statics (|sigma_yx|/sigma_yy rounds to mu_2 when the wall is within
    # round-off of saturation, B = 10 and I_w = 1 here)
    gap = problem.equations.saturation_gap(p.xi, p.diagnostics.stats["gap_to_mu_2"])
    assert np.all((mu[~plug] > LAW.mu_s) & (gap[~plug] > 0.0))
    assert np.all(p.u[plug] == 0.0) and np.all(p.du_dxi[plug] == 0.0)
    extent = p.diagnostics.stats["plug"]
    if extent is None:
        assert not plug.any() and "no plug" in p.diagnostics.message
    else:
        assert plug.any() and "plug at rest" in p.diagnostics.message
        assert fw in extent  # the plug sits at the fixed wall
    # what a local rheology does not have: absent, not zero, and stated
    assert p.m is None and p.omega is None and p.asymmetry is None
    assert p.spin_minus_half_vorticity is None
    assert "no omega or m" in p.diagnostics.message
    assert all(abs(v) < 1e-12 for v in p.diagnostics.bc_errors.values())


def test_an_imposed_stress_gives_back_the_wall_speed():
    for problem in (COUETTE[0], PLANE_G[0]):
        by_speed = solve(problem, method="numerical")
        T = by_speed.diagnostics.stats["stress_ratio"]
        by_stress = problem.with_values({"I_w": None, "stress_ratio": T})
        by_stress = solve(by_stress, method="numerical", xi=by_speed.xi)
        assert by_stress.diagnostics.stats["I_w"] == pytest.approx(problem.equations.I_w, rel=1e-9)
        np.testing.assert_allclose(by_stress.u, by_speed.u, atol=1e-9)


# ----------------------------------------------------------------- the quasi-static limit
def test_quasi_static_limit_couette_is_a_parabolic_layer_of_width_sqrt_I_w():
    Ri = 1.0
    scale = math.sqrt(Ri * (MUI_MU_2 - MUI_MU_S) / (MUI_I0 * MUI_MU_S))
    eta = np.linspace(0.0, 1.0, 41)
    I_ws = np.array([1e-4, 1e-5, 1e-6, 1e-7])
    shape_err, width_err = [], []
    for I_w in I_ws:
        problem = Problem(Couette(eps=1e-3, Ri=Ri, I_w=I_w), MuI())
        p = solve(problem, method="closed-form", check=False)
        xi_c = p.diagnostics.stats["plug"][0]
        width_err.append(abs(xi_c / (scale * math.sqrt(I_w)) - 1.0))
        shape_err.append(np.max(np.abs(p.evaluate(eta * xi_c).u + (1.0 - eta) ** 2)))
        delta = shear_layer_thickness(p) * problem.eps
        assert delta / xi_c == pytest.approx(1.0 - math.sqrt(DEFAULT_F), rel=20 * xi_c)
    for err in (shape_err, width_err):
        slope = np.polyfit(np.log(I_ws), np.log(err), 1)[0]
        assert 0.4 < slope < 0.6, (slope, err)  # both errors O(xi_c) = O(sqrt(I_w))


def test_quasi_static_limit_plane_shear_under_gravity_is_a_parabolic_surface_layer():
    B = 1.0
    scale = math.sqrt(2.0 * (MUI_MU_2 - MUI_MU_S) / (MUI_I0 * MUI_MU_S * B))
    eta = np.linspace(0.0, 1.0, 41)
    I_ws = np.array([1e-4, 1e-5, 1e-6, 1e-7])
    errs = []
    for I_w in I_ws:
        p = solve(Problem(Plane(eps=1e-3, B=B, I_w=I_w), MuI()), method="numerical", check=False)
        h = 1.0 - p.diagnostics.stats["plug"][1]
        assert h / (scale * math.sqrt(I_w)) == pytest.approx(1.0, rel=10 * h)
        errs.append(np.max(np.abs(p.evaluate(1.0 - h + eta * h).u - eta**2)))
    slope = np.polyfit(np.log(I_ws), np.log(errs), 1)[0]
    assert 0.4 < slope < 0.6, (slope, errs)


# ----------------------------------------------------------------- no solution, bad parameters
@pytest.mark.parametrize("method", ["closed-form", "numerical"])
def test_a_stress_ratio_at_or_above_mu_2_has_no_steady_solution(method):
    for problem, where in (
        (Problem(Couette(eps=0.01, Ri=1.0, stress_ratio=0.7), MuI()), "inner cylinder"),
        (Problem(Plane(eps=0.01, stress_ratio=MUI_MU_2), MuI()), "upper wall"),
    ):
        with pytest.raises(NoSolutionError, match=rf">= mu_2 = 0.643468 at the .*{where}"):
            solve(problem, method=method)
    with pytest.raises(NoSolutionError, match="whole gap is a plug"):
        solve(Problem(Couette(eps=0.01, Ri=1.0, stress_ratio=0.3), MuI()), method=method)
    with pytest.raises(NoSolutionError, match="no steady shear rate"):
        LAW.inertial_number(np.array([0.5, 0.65]))


@pytest.mark.parametrize(
    ("make", "match"),
    [
        (
            lambda: MuI(mu_s=-0.1),
            r"mu_s \(static friction coefficient\) must satisfy 0 < mu_s < 10 .*; got -0.1",
        ),
        (
            lambda: MuI(mu_2=0.3),
            r"mu_2 \(.*\) must satisfy mu_2 - mu_s >= 0.0001 \(.*\); got "
            "mu_2 = 0.3, mu_s = 0.381863",
        ),
        (lambda: MuI(I_0=0.0), r"I_0 \(.*\) must satisfy 0 < I_0; got 0"),
        (lambda: MuI(I_0=float("nan")), r"I_0 \(.*\) must be finite"),
        (
            lambda: Problem(Plane(eps=0.01, I_w=0.0), MuI()),
            r"I_w .* must satisfy 0 < I_w <= 1 .*; got 0",
        ),
        (lambda: Problem(Plane(eps=0.01, I_w=2.0), MuI()), r"0 < I_w <= 1 .*; got 2"),
        (lambda: Problem(Plane(eps=0.01, I_w=0.1, stress_ratio=0.5), MuI()), "not both"),
        (lambda: Problem(Plane(eps=0.7), MuI()), r"eps \(.*\) must satisfy 1e-08 <= eps <= 0.5"),
        (lambda: Problem(Plane(eps=0.01, B=-1.0), MuI()), r"B \(.*\) must satisfy 0 <= B"),
        (lambda: Problem(Plane(eps=0.01, nu=0.0), MuI()), "nu .* must satisfy 0 < nu <= 1"),
        (lambda: Problem(Couette(eps=0.01, Ri=0.0), MuI()), r"Ri \(.*\) must satisfy 0.001 <= Ri"),
        (lambda: Problem(Couette(eps=0.01, Ri=1.0), 1), "rheology must be a Rheology"),
    ],
)
def test_parameter_errors_name_the_parameter_and_the_bound(make, match):
    with pytest.raises(ParameterError, match=match):
        make()


def test_defaults_and_options():
    problem = Problem(Couette(eps=0.01, Ri=1.0), MuI())
    assert problem.cell.I_w is None and problem.equations.I_w == 0.01  # the declared default
    assert problem.parameters()["I_w"] == 0.01
    with pytest.raises(ParameterError, match="rtol must satisfy"):
        solve(COUETTE[0], method="numerical", rtol=1.0)
    with pytest.raises(ParameterError, match="do not apply"):
        solve(COUETTE[0], method="closed-form", rtol=1e-8)
    p = solve(COUETTE[0], method="closed-form", points=11)
    assert 11 <= p.xi.size <= 14 and p.xi[0] == 0.0 and p.xi[-1] == 1.0
    assert "mu(I)" in p.problem.describe() and p.problem.parameters()["rheology"] == "mui"
    p.to_json()  # finite, exportable


@pytest.mark.parametrize("method", ["closed-form", "numerical"])
def test_profiles_pickle_with_their_evaluator(method):
    for problem in (COUETTE[0], Problem(Plane(eps=0.05), MuI())):
        p = solve(problem, method=method, points=21)
        back = pickle.loads(pickle.dumps(p))
        np.testing.assert_array_equal(back.u, p.u)
        x = [0.05, 0.3, 0.9]
        np.testing.assert_array_equal(back.evaluate(x).u, p.evaluate(x).u)
        assert shear_layer_thickness(back) == shear_layer_thickness(p)
        np.testing.assert_array_equal(plug_mask(back), plug_mask(p))


def test_compiled_plane_quadrature_is_quad_vec_to_the_last_bit():
    """The plane cell's velocity quadrature is compiled (``numerics.mui.plane_pieces``): the
    same algorithm as SciPy's ``quad_vec``, so the integrals are equal bit for bit, over
    stress levels from near mu_2 to near mu_s, gravity from weak to strong, plugs and
    tolerances."""
    from scipy.integrate import quad_vec

    from cosserat.model.rheologies.base import equations_of
    from cosserat.model.rheologies.mui import MuIFlow
    from cosserat.routes import mui as route

    rng = np.random.default_rng(18)
    for trial in range(120):
        law = MuI(mu_s=rng.uniform(0.1, 0.55), I_0=10 ** rng.uniform(-2, 0))
        eq = equations_of(Problem(Plane(eps=0.025, B=10 ** rng.uniform(-3, 1.5), I_w=0.01), law),
                          MuIFlow)  # fmt: skip
        gap = (law.mu_2 - law.mu_s) * 10 ** rng.uniform(-12, -1e-4)
        rtol = (1e-8, 1e-12, 1e-6)[trial % 3]
        t = eq.cell.distance(np.sort(rng.uniform(0.0, 1.0, rng.integers(1, 60))))
        nodes = np.unique(np.concatenate([route._breakpoints(eq, gap), t, [0.0]]))
        got = route._quad_intervals(eq, gap, nodes, rtol)
        a, b = nodes[:-1], nodes[1:]
        live = b > a
        t_plug = route._plug_distance(eq, gap)
        if t_plug is not None:
            live &= a < t_plug
        want = np.zeros(nodes.size - 1)
        if np.any(live):
            lo, width = a[live], (b - a)[live]
            value, _, info = quad_vec(
                lambda s, lo=lo, w=width, eq=eq, g=gap: eq.integrand_at(lo + s * w, g) * w,
                0.0, 1.0, epsabs=np.finfo(float).tiny, epsrel=rtol, norm="max", limit=400,
                full_output=True,
            )  # fmt: skip
            assert info.success
            want[live] = value
        assert np.array_equal(got, want), (trial, gap, rtol)
