"""The vertical channel (``docs/derivation_channel.md``): the Cosserat model and local mu(I).

Checks: symmetry about the centre line, the wall and centre conditions, residuals recomputed in
the physical variables (independently of the kernel's mapped form), a second discretisation
(SciPy's solve_bvp on the physical equations written out here) to 1e-6, the small-eps rates
(Delta constant for walls smoother than the material, Delta ~ eps^(-1/3) for fully rough walls)
with fitted slopes, the asymptotic route against the numerical one, errors in words.
"""

from __future__ import annotations

import math
import pickle

import numpy as np
import pytest
from scipy.integrate import solve_bvp
from scipy.optimize import brentq

from cosserat import (
    Channel,
    MethodNotAvailableError,
    NoSolutionError,
    ParameterError,
    shear_layer_thickness,
    solve,
    wall_omega,
    wall_slip,
)
from cosserat.model import build_problem
from cosserat.model.parameters import Material, Wall
from cosserat.routes.airy import xi_hat_at_fraction

MAT = Material()  # phi = 28.5 deg, L = 10, A = 1/3


def smooth(eps: float, **kw) -> Channel:  # type: ignore[no-untyped-def]
    return Channel(material=MAT, wall=Wall(), eps=eps, **kw)


def rough(eps: float) -> Channel:
    return Channel(material=MAT, wall=Wall.fully_rough(), eps=eps)


CASES = {
    "slip": smooth(0.05),
    "no-slip": smooth(0.05, B=0.6),
    "fully-rough": rough(0.05),
}


@pytest.fixture(scope="module", params=list(CASES))
def solved(request):  # type: ignore[no-untyped-def]
    problem = CASES[request.param]
    return problem, solve(problem, rtol=1e-10)


# ----------------------------------------------------------------- statics and conditions
def test_statics_from_the_balances():
    p = smooth(0.01)
    x = np.linspace(0.0, 1.0, 11)
    np.testing.assert_array_equal(p.sigma_c(x), 1.0)
    np.testing.assert_allclose(p.sigma_yx(x), 2.0 * math.tan(math.radians(20.0)) * (x - 0.5))
    # friction fully mobilised by default: B nu = 2 tan(delta), the same group as plane shear
    assert p.B * p.nu == pytest.approx(2.0 * math.tan(math.radians(20.0)), rel=1e-15)
    assert p.slips and not smooth(0.01, B=0.5).slips


def test_symmetry_about_the_centre_line(solved):
    _, prof = solved
    x = np.linspace(0.0, 0.5, 41)
    lo, hi = prof.evaluate(x), prof.evaluate(1.0 - x)
    for even in ("u", "m", "sigma_yy"):
        np.testing.assert_allclose(getattr(lo, even), getattr(hi, even), rtol=0, atol=1e-14)
    for odd in ("omega", "sigma_xy", "sigma_yx", "du_dxi"):
        np.testing.assert_allclose(getattr(lo, odd), -getattr(hi, odd), rtol=0, atol=1e-14)


def test_wall_and_centre_conditions(solved):
    problem, prof = solved
    errors = prof.diagnostics.bc_errors
    assert len(errors) >= 8
    for name, value in errors.items():
        assert abs(value) < 1e-9, name
    ends = prof.evaluate([0.0, 0.5, 1.0])
    assert ends.u[1] == pytest.approx(1.0, abs=1e-12)
    assert ends.m[1] == pytest.approx(-math.sqrt(MAT.c2), abs=1e-14)
    if problem.slips:
        eK = problem.eps * problem.wall.K
        assert ends.u[2] == pytest.approx(eK * ends.omega[2], abs=1e-12)
        assert ends.u[0] == pytest.approx(-eK * ends.omega[0], abs=1e-12)
        assert wall_slip(prof) > 0.0
    else:
        assert wall_slip(prof) < 1e-12
    # the material moves down faster inside than at the walls; spin = half vorticity sign
    assert np.all(np.diff(prof.u[prof.xi >= 0.5]) <= 1e-12)
    assert wall_omega(prof) > 0.0


def test_residuals_of_the_returned_profile(solved):
    _, prof = solved
    for name, value in prof.diagnostics.residuals.items():
        assert value < 1e-7, name


# ----------------------------------------------------------------- physical equations, again
def physical_rates(problem: Channel, xi, m):  # type: ignore[no-untyped-def]
    """(dm/dxi, F1, F2) of the upper half in the physical variables, written out from the
    balances: sigma_yx = B nu (xi - 1/2) > 0, sigma_c = 1 and the root of eqn-nd_sigxy with
    sigma_xy + A sigma_yx = +sqrt(S) (the mirror image of the paper's root)."""
    A, sp = MAT.A, MAT.sin_phi
    ea = problem.eps * MAT.alpha
    syx = problem.B * problem.nu * (xi - 0.5)
    S = (A * A - 1.0) * syx**2 + 2.0 * (A + 1.0) * sp**2 - 4.0 * (A + 1.0) ** 2 * m**2
    root = np.sqrt(np.maximum(S, 0.0))
    sxy = -A * syx + root
    dm = (syx - sxy) / (2.0 * (A + 1.0)) / ea
    F1 = (A + 1.0) * (sxy + syx) / root
    F2 = 2.0 * (A + 1.0) * m / root
    return dm, F1, F2


def test_physical_equations_hold_on_the_profile(solved):
    """Central differences of the dense profile against the physical equations (not the
    kernel's mapped, cancellation-free form)."""
    problem, prof = solved
    x = np.linspace(0.52, 0.995, 300)
    h = 1e-6
    f, fp, fm = prof.evaluate(x), prof.evaluate(x + h), prof.evaluate(x - h)
    dm, F1, F2 = physical_rates(problem, x, f.m)
    ea = problem.eps * MAT.alpha
    np.testing.assert_allclose((fp.m - fm.m) / (2 * h), dm, rtol=0, atol=1e-6 * np.abs(dm).max())
    du = (fp.u - fm.u) / (2 * h)
    np.testing.assert_allclose(du, -F1 * f.omega, rtol=0, atol=1e-6 * np.abs(du).max())
    dw = (fp.omega - fm.omega) / (2 * h)
    np.testing.assert_allclose(ea * dw, -F2 * f.omega, rtol=0, atol=1e-6 * np.abs(ea * dw).max())
    # and the stresses satisfy the yield condition eqn-nd_yc with m
    A = MAT.A
    yc = (
        f.sigma_xy**2
        + f.sigma_yx**2
        + 2 * A * f.sigma_xy * f.sigma_yx
        + 4 * (A + 1) ** 2 * f.m**2
        - 2 * (A + 1) * MAT.sin_phi**2
    )
    assert np.max(np.abs(yc)) < 1e-13


def centre_series(problem: Channel) -> float:
    """mu of m = -(c - mu s^2): the O(s) balance of the couple-stress equation, solved here by
    root finding on sqrt(2 c mu - beta) = B nu/2 - 2 eps alpha mu (doc section 4)."""
    A, c = MAT.A, math.sqrt(MAT.c2)
    ea = problem.eps * MAT.alpha
    Bn = problem.B * problem.nu
    beta = Bn**2 * (1 - A) / (4 * (1 + A))
    lo, hi = beta / (2 * c), Bn / (4 * ea)
    return brentq(
        lambda mu: math.sqrt(max(2 * c * mu - beta, 0.0)) - Bn / 2 + 2 * ea * mu, lo, hi, xtol=1e-15
    )


def bvp_profile(problem: Channel):  # type: ignore[no-untyped-def]
    """solve_bvp on the physical equations in t = ln(xi - 1/2) (m, l = ln(omega/omega_w), u;
    unknown omega_w), from s_0 = 1e-3 to the wall (the naive radicand of eqn-nd_sigxy used here
    loses ~1e-16/S of relative accuracy near the centre line, where S ~ s^2)."""
    s0 = 1e-3
    c = math.sqrt(MAT.c2)
    m0 = -(c - centre_series(problem) * s0**2)
    ea = problem.eps * MAT.alpha
    eK = problem.eps * problem.wall.K if problem.slips else 0.0

    def rhs(t, y, par):  # type: ignore[no-untyped-def]
        s = np.exp(t)
        dm, F1, F2 = physical_rates(problem, 0.5 + s, y[0])
        return np.vstack([s * dm, -s * F2 / ea, -s * F1 * par[0] * np.exp(y[1])])

    def bc(ya, yb, par):  # type: ignore[no-untyped-def]
        # omega ~ s^p vanishes at the centre (p = 4 here), so u(xi_0) = u(1/2) to ~1e-16
        return np.array([ya[0] - m0, yb[1], yb[2] - eK * par[0], ya[2] - 1.0])

    # the leading-order layer as the first guess (k = 1 stands in at fully rough walls)
    k = problem.slip_constants.k or 1.0
    K = problem.wall.K if problem.slips else 0.0
    t = np.linspace(math.log(s0), math.log(0.5), 400)
    x = 0.5 + np.exp(t)
    decay = np.exp(-k * (1 - x) / problem.eps)
    guess = np.vstack(
        [problem.outer_couple_stress(x), np.log(decay), 1.0 - (2 / k) / (K + 2 / k) * decay]
    )
    w_guess = 1.0 / (problem.eps * (K + 2 / k))
    sol = solve_bvp(rhs, bc, t, guess, p=[w_guess], tol=1e-8, max_nodes=200000)
    assert sol.success, sol.message
    return sol


@pytest.mark.parametrize("name", list(CASES))
def test_second_discretisation_agrees_to_1e_6(name):
    problem = CASES[name]
    prof = solve(problem, rtol=1e-11)
    sol = bvp_profile(problem)
    x = np.linspace(0.5 + 2e-3, 1.0, 200)
    y = sol.sol(np.log(x - 0.5))
    f = prof.evaluate(x)
    omega = sol.p[0] * np.exp(y[1])
    assert np.max(np.abs(f.m - y[0])) < 1e-6
    assert np.max(np.abs(f.u - y[2])) < 1e-6
    assert np.max(np.abs(f.omega - omega)) < 1e-6 * np.max(np.abs(omega))
    # the lower half by symmetry
    g = prof.evaluate(1.0 - x)
    assert np.max(np.abs(g.u - y[2])) < 1e-6


@pytest.mark.parametrize("make", [smooth, rough])
@pytest.mark.parametrize("eps", [1e-2, 1e-4, 1e-6])
def test_error_follows_the_tolerance(make, eps):
    """Against rtol = 1e-12: u, omega (relative to the wall spin) and m within 10 rtol in the
    layer (measured: 0.01-5.4 rtol for rtol = 1e-5 ... 1e-10)."""
    problem = make(eps)
    x = 1.0 - eps * np.linspace(0.0, 60.0, 301)
    x = x[x >= 0.5]
    ref = solve(problem, rtol=1e-12).evaluate(x)
    for rtol in (1e-6, 1e-8, 1e-10):
        f = solve(problem, rtol=rtol).evaluate(x)
        assert np.abs(f.u - ref.u).max() < 10 * rtol
        assert np.abs(f.omega - ref.omega).max() < 10 * rtol * np.abs(ref.omega).max()
        assert np.abs(f.m - ref.m).max() < 10 * rtol


# ----------------------------------------------------------------- eps -> 0
def test_smooth_walls_delta_tends_to_a_constant():
    """Walls smoother than the material: Delta -> -ln f/k = 17.6688 (eqn-delta_soln), with a
    correction linear in eps (the shear stress changes across the layer). Measured: Delta =
    16.115, 17.488, 17.650, 17.667, 17.6686 at eps = 1e-3 ... 1e-7; local slopes of log Delta
    -3.6e-2, -4.0e-3, -4.1e-4, -4.1e-5; (limit - Delta)/eps -> 1848."""
    eps = np.array([1e-3, 1e-4, 1e-5, 1e-6, 1e-7])
    deltas = np.array([shear_layer_thickness(solve(smooth(e), check=False)) for e in eps])
    limit = -math.log(0.05) / smooth(1e-3).slip_constants.k
    assert limit == pytest.approx(17.6688, abs=1e-4)
    slopes = np.diff(np.log(deltas)) / np.diff(np.log(eps))
    assert abs(slopes[-1]) < 1e-4
    np.testing.assert_allclose(slopes[1:] / slopes[:-1], 0.1, rtol=0.15)  # one decade each
    assert deltas[-1] == pytest.approx(limit, rel=2e-5)
    slope_gap = np.polyfit(np.log(eps), np.log(limit - deltas), 1)[0]
    assert slope_gap == pytest.approx(1.0, abs=0.02)


def test_fully_rough_walls_delta_grows_as_eps_to_minus_one_third():
    """Fully rough walls: an Airy layer ~ eps^(2/3) of the width, Delta = 1.2748 eps^(-1/3)
    (L^2/4)^(1/3) (doc section 6). Measured: fitted slope -0.3344 over eps = 1e-4 ... 1e-8
    (local slopes -0.3371, -0.3341, -0.3335, -0.33337), Delta / law = 0.98901 ... 0.99998,
    the gap falling as eps^(2/3)."""
    eps = np.array([1e-4, 1e-5, 1e-6, 1e-7, 1e-8])
    deltas = np.array([shear_layer_thickness(solve(rough(e), check=False)) for e in eps])
    slope = np.polyfit(np.log(eps), np.log(deltas), 1)[0]
    assert slope == pytest.approx(-1.0 / 3.0, abs=0.002)
    local = np.diff(np.log(deltas)) / np.diff(np.log(eps))
    assert local[-1] == pytest.approx(-1.0 / 3.0, abs=1e-4)
    law = xi_hat_at_fraction(0.05) * eps ** (-1.0 / 3.0) * (MAT.L**2 / 4.0) ** (1.0 / 3.0)
    assert deltas[-1] / law[-1] == pytest.approx(1.0, abs=1e-4)
    gap_slope = np.polyfit(np.log(eps), np.log(np.abs(deltas / law - 1.0)), 1)[0]
    assert gap_slope == pytest.approx(2.0 / 3.0, abs=0.02)


@pytest.mark.parametrize("make, eps", [(smooth, 1e-4), (rough, 1e-6)])
def test_asymptotic_route_approaches_the_numerical_one(make, eps):
    problem = make(eps)
    num = solve(problem)
    asy = solve(problem, method="asymptotic")
    assert asy.diagnostics.method == "asymptotic"
    for name, value in asy.diagnostics.bc_errors.items():
        if "yield" in name or "symmetry" in name or "scale" in name:
            assert abs(value) < 1e-12, name
    x = 1.0 - problem.eps * np.linspace(0.0, 40.0, 81)
    du = np.abs(num.evaluate(x).u - asy.evaluate(x).u).max()
    # leading order: errors O(eps Delta) for the exponential layer, O(eps^(1/3)) for Airy
    assert du < (5e-3 if make is smooth else 2e-2)
    assert shear_layer_thickness(asy) == pytest.approx(shear_layer_thickness(num), rel=2e-2)


# ----------------------------------------------------------------- errors in words
def test_no_real_solution_in_a_narrow_channel():
    with pytest.raises(NoSolutionError, match="centre line"):
        solve(smooth(0.5))


def test_weight_beyond_wall_friction_has_no_steady_flow():
    with pytest.raises(NoSolutionError, match="accelerates"):
        smooth(0.01, B=1.0)
    with pytest.raises(ParameterError, match="B"):
        smooth(0.01, B=0.0)


def test_asymptotic_route_refuses_thick_layers():
    with pytest.raises(MethodNotAvailableError, match="thinner"):
        solve(smooth(0.05), method="asymptotic")


def test_build_problem_and_pickle():
    p = build_problem({"geometry": "channel", "eps": 0.02})
    assert isinstance(p, Channel) and p.slips
    assert build_problem({"geometry": "channel", "eps": 0.02, "B": 0.6}).case.value.endswith(
        "not-slip"
    )
    prof = solve(p)
    back = pickle.loads(pickle.dumps(prof))
    np.testing.assert_array_equal(back.evaluate([0.9]).u, prof.evaluate([0.9]).u)
    assert np.all(np.isfinite(np.concatenate(list(prof.columns().values()))))
    assert prof.to_dict()["parameters"]["velocity_scale"].startswith("centre-line")


# ----------------------------------------------------------------- local mu(I) on the channel
def mui_velocity_by_hand(problem, x):  # type: ignore[no-untyped-def]
    """u from the rate written out here: I(mu) = I_0 (mu - mu_s)/(mu_2 - mu) with
    mu = B nu t, integrated from the wall by scipy's quad and scaled by the centre line."""
    from scipy.integrate import quad

    law, Bn = problem.rheology, problem.B * problem.nu

    def rate(t):  # type: ignore[no-untyped-def]
        mu = Bn * t
        return law.I_0 * (mu - law.mu_s) / (law.mu_2 - mu) if mu > law.mu_s else 0.0

    t_s = law.mu_s / Bn

    def J(t):  # type: ignore[no-untyped-def]
        lo = max(t, t_s)
        return quad(rate, lo, 0.5, epsabs=0, epsrel=1e-13)[0] if lo < 0.5 else 0.0

    centre = J(0.0)
    return np.array([J(abs(v - 0.5)) for v in x]) / centre, centre


@pytest.mark.parametrize("B", [0.8, 1.0, 1.25])
def test_mui_channel_closed_form(B):
    from cosserat.model.mui import MuIChannel

    problem = MuIChannel(eps=0.01, B=B)
    prof = solve(problem, method="closed-form")
    x = np.linspace(0.0, 1.0, 101)
    u_hand, I_w = mui_velocity_by_hand(problem, x)
    np.testing.assert_allclose(prof.evaluate(x).u, u_hand, rtol=0, atol=1e-12)
    assert prof.diagnostics.stats["I_w"] == pytest.approx(I_w, rel=1e-12)
    # the plug on the centre line: |xi - 1/2| <= mu_s/(B nu), u = 1 exactly there
    t_s = problem.rheology.mu_s / B
    inside = np.abs(x - 0.5) <= t_s
    np.testing.assert_array_equal(prof.evaluate(x[inside]).u, 1.0)
    assert np.all(prof.evaluate(x[~inside]).u < 1.0)
    for name, value in prof.diagnostics.bc_errors.items():
        assert abs(value) < 1e-14, name
    assert prof.diagnostics.residuals["velocity"] < 1e-12
    # the numerical route (quadrature) agrees with the closed form
    num = solve(problem)
    np.testing.assert_allclose(num.evaluate(x).u, prof.evaluate(x).u, rtol=0, atol=1e-12)
    assert shear_layer_thickness(num) == pytest.approx(shear_layer_thickness(prof), rel=1e-10)
    # stresses: symmetric, mu = B nu |xi - 1/2|; spin = half the vorticity
    f = prof.evaluate(x)
    np.testing.assert_allclose(f.sigma_yx, B * (x - 0.5))
    np.testing.assert_array_equal(f.sigma_xy, f.sigma_yx)
    np.testing.assert_allclose(f.omega, -0.5 * f.du_dxi)


def test_mui_channel_without_flow_or_without_steady_rate():
    from cosserat.model.mui import MuIChannel

    with pytest.raises(NoSolutionError, match="plug"):
        MuIChannel(eps=0.01, B=0.7)  # B nu/2 = 0.35 < mu_s = 0.382
    with pytest.raises(NoSolutionError, match="mu_2"):
        MuIChannel(eps=0.01, B=1.4)  # B nu/2 = 0.7 > mu_2 = 0.644


def test_wall_quantities_match_the_profiles():
    from cosserat.routes.channel import wall_quantities

    problems = [smooth(1e-3), rough(1e-4), smooth(0.5)]
    out = wall_quantities(problems, rtol=1e-10)
    assert [r.status for r in out] == ["ok", "ok", "no-solution"]
    for pr, r in zip(problems[:2], out[:2], strict=True):
        prof = solve(pr, rtol=1e-10)
        assert r.Delta == pytest.approx(shear_layer_thickness(prof), rel=1e-12)
        assert r.wall_slip == pytest.approx(wall_slip(prof), rel=1e-9, abs=1e-15)
        assert r.wall_omega == pytest.approx(wall_omega(prof), rel=1e-9)
    assert "centre line" in out[2].message and out[2].Delta is None
