"""The nonlocal granular fluidity model on its three cells (``docs/derivation_ngf.md``).

An independent discretisation (SciPy's ``solve_bvp`` collocation, written here from the
equations with its own statics, local law and the stress level as an unknown parameter)
against the compiled finite volumes; second-order convergence of the scheme and what
Richardson's extrapolation adds; the creep region's exponential decay over the cooperativity
length (with its WKB correction); the local limit A -> 0 against the mu(I) rheology and its
rate (A eps)^(4/3); the channel's symmetry; the wall conditions; the closed form of uniform
shear; what a profile carries; no solution, bad parameters, pickling.
"""

from __future__ import annotations

import math
import pickle

import numpy as np
import pytest
from scipy.integrate import solve_bvp

from cosserat import (
    Couette,
    NoSolutionError,
    ParameterError,
    Plane,
    Problem,
    VerticalChannel,
    shear_layer_thickness,
    solve,
    wall_slip,
)
from cosserat.cli import main
from cosserat.config import DEFAULT_F, MUI_I0, MUI_MU_2, MUI_MU_S
from cosserat.errors import ConvergenceError, CosseratError, MethodNotAvailableError
from cosserat.model.cells import Cell
from cosserat.model.rheologies import NGF, MuI
from cosserat.model.rheologies.ngf import NGF_EXCESS_RTOL
from cosserat.numerics import ngf as kernel
from cosserat.routes import RHEOLOGIES, cells_for
from cosserat.routes import ngf as ngf_routes
from cosserat.routes.ngf import creep_mask, fluidity, friction_ratio, shear_rate

SATURATING = NGF(mu_s=MUI_MU_S, mu_2=MUI_MU_2, b=(MUI_MU_2 - MUI_MU_S) / MUI_I0)
CASES = {
    "couette": Problem(Couette(eps=0.01, Ri=1.0), NGF()),
    "couette-local-bc": Problem(Couette(eps=0.01, Ri=1.0), NGF(fluidity_bc="local")),
    "couette-saturating": Problem(Couette(eps=0.01, Ri=1.0, I_w=0.05), SATURATING),
    "plane-gravity": Problem(Plane(eps=0.01, B=1.0), NGF()),
    "channel-speed": Problem(VerticalChannel(eps=0.02, I_w=0.01), NGF()),
    "channel-stress": Problem(VerticalChannel(eps=0.02, B=2.4, nu=0.5), NGF()),
}
XS = np.linspace(0.0, 1.0, 401)


# ----------------------------------------------------------------- an independent solver
def _bvp(problem, tol=1e-6):
    """u(xi) and the stress level by solve_bvp: y = (F, r F', int w F mu, int sign F mu/r),
    the stress level T a free parameter fixed by the fifth boundary condition."""
    law, cell = problem.rheology, problem.cell
    mu_s, b, mu_2, a = law.mu_s, law.b, law.mu_2, law.A * problem.eps
    name = {"plane": "NGFPlaneShear", "couette": "NGFCouetteFlow", "channel": "NGFChannel"}[
        problem.cell_name
    ]
    Ri = getattr(cell, "Ri", None)
    Bnu = None if getattr(cell, "B", None) is None else cell.B * cell.nu
    I_w = problem.equations.I_w  # the cell's drive, its default included

    def statics(x, T):
        one = np.ones_like(x)
        if name == "NGFPlaneShear":
            s = 1.0 + Bnu * (1.0 - x)
            return T / s, s, one
        if name == "NGFCouetteFlow":
            r = Ri + x
            return T * (Ri / r) ** 2, one, r
        return 2.0 * T * np.abs(x - 0.5), one, one

    def f_loc(mu, s):
        e = np.maximum(mu - mu_s, 0.0)
        i = e / b if mu_2 is None else (mu_2 - mu_s) / b * e / (mu_2 - mu)
        return np.sqrt(s) * i / np.where(mu > 0.0, mu, 1.0)

    def weight(x):
        return Ri / (Ri + x) if name == "NGFCouetteFlow" else np.ones_like(x)

    def sign(x):
        return np.where(x > 0.5, -1.0, 1.0) if name == "NGFChannel" else np.ones_like(x)

    speed = name != "NGFChannel" or I_w is not None
    imposed = None if speed else 0.5 * Bnu
    target = (I_w or 0.0) * (2.0 if name == "NGFChannel" else 1.0)

    def rhs(x, y, p=None):
        T = p[0] if speed else imposed
        mu, s, r = statics(x, T)
        k = np.abs(mu - mu_s) / a**2
        return np.vstack(
            [
                y[1] / r,
                r * k * (y[0] - f_loc(mu, s)),
                weight(x) * y[0] * mu,
                sign(x) * y[0] * mu / r,
            ]
        )

    def bc(ya, yb, p=None):
        T = p[0] if speed else imposed
        if law.fluidity_bc == "local":
            ends = [f_loc(*statics(np.array([w]), T)[:2])[0] for w in (0.0, 1.0)]
            walls = [ya[0] - ends[0], yb[0] - ends[1]]
        else:
            walls = [ya[1], yb[1]]
        last = [yb[2] - target] if speed else []
        return np.array([*walls, ya[2], ya[3], *last])

    x = np.linspace(0.0, 1.0, 101)
    T0 = 1.2 * mu_s if speed else imposed
    y = np.zeros((4, x.size))
    y[0] = f_loc(*statics(x, T0)[:2]) + 1e-3
    sol = solve_bvp(rhs, bc, x, y, p=[T0] if speed else None, tol=tol, max_nodes=100_000)
    assert sol.status == 0, sol.message
    T = sol.p[0] if speed else imposed

    def velocity(xx):
        yy = sol.sol(xx)
        if name == "NGFCouetteFlow":
            return -(Ri + xx) * (sol.sol(1.0)[3] - yy[3]) / I_w
        if name == "NGFChannel":
            return yy[3] / sol.sol(0.5)[3]  # u(1/2) = 1
        return yy[3] / I_w

    return velocity, T


@pytest.mark.parametrize("name", list(CASES))
def test_collocation_agrees_with_the_finite_volumes(name):
    problem = CASES[name]
    velocity, T = _bvp(problem)
    p = solve(problem, xi=XS)
    # the bar is 1e-6; measured 5e-10 to 8e-9 (solve_bvp at tol 1e-6 has its own ~1e-9)
    assert np.max(np.abs(p.u - velocity(XS))) < 3e-8
    assert p.diagnostics.stats["stress_ratio"] == pytest.approx(T, rel=1e-8)
    # the second-order solution alone, with its error estimate
    raw = solve(problem, xi=XS, extrapolate=False)
    estimate = raw.diagnostics.residuals["discretisation (u, second order, Richardson estimate)"]
    err = np.max(np.abs(raw.u - velocity(XS)))
    assert 0.5 * estimate < err < 2.0 * estimate


# ----------------------------------------------------------------- convergence order
NS = np.array([256, 512, 1024, 2048, 4096])


@pytest.mark.parametrize("name", ["couette", "plane-gravity", "channel-speed"])
def test_the_scheme_converges_at_second_order_and_the_extrapolation_beyond(name):
    problem = CASES[name]
    ref = solve(problem, xi=XS, cells=2**16, check=False).u
    raw = [np.max(np.abs(solve(problem, xi=XS, cells=n, extrapolate=False).u - ref)) for n in NS]
    ext = [np.max(np.abs(solve(problem, xi=XS, cells=n).u - ref)) for n in NS]
    order = -np.polyfit(np.log(NS), np.log(raw), 1)[0]
    assert 1.95 < order < 2.05, (order, raw)
    ratios = np.array(raw[:-1]) / np.array(raw[1:])
    assert np.all((ratios > 3.8) & (ratios < 4.2)), ratios  # a regular O(h^2): kinks exact
    assert np.all(np.array(ext) < 0.05 * np.array(raw)), (ext, raw)
    assert ext[-1] < 2e-9


# ----------------------------------------------------------------- the creep region
def _along(f, x, direction, step):
    """Derivative of f along ``direction`` (+1 or -1) by central differences."""
    return direction * (f(x + step) - f(x - step)) / (2 * step)


@pytest.mark.parametrize(
    "problem",
    [
        Problem(Couette(eps=0.002, Ri=20.0, I_w=0.01), NGF()),
        Problem(Plane(eps=0.002, B=0.2, I_w=0.01), NGF()),
    ],
    ids=["couette-far", "plane-below-yield"],
)
def test_the_creep_region_decays_over_the_cooperativity_length(problem):
    """Where mu < mu_s, g'' = k g with k = (mu_s - mu)/(A d)^2: g ~ k^(-1/4) exp(-int sqrt k)
    (WKB), so -d ln g/ds = sqrt(k) (1 + w) with w = k_s/(4 k^(3/2)), s the distance from the
    flowing region: g decays as exp(-distance/xi_c) up to the slow variation w of mu, and
    the WKB term removes that to O(w^2). Six lengths from the far wall, its reflection
    (n . grad g = 0 there) is below 2 exp(-12)."""
    p = solve(problem, cells=2**15)
    T = p.diagnostics.stats["stress_ratio"]
    lo, hi = p.diagnostics.stats["creep"]
    law = problem.rheology
    a = law.A * problem.eps
    edge, far = (lo, 1.0) if problem.cell_name == "couette" else (hi, 0.0)
    away = 1.0 if far > edge else -1.0  # the direction away from the flowing region
    x = np.linspace(edge, far, 401)[1:-1]
    k = (law.mu_s - problem.equations.friction_ratio(x, T)) / a**2
    keep = (np.abs(x - edge) * np.sqrt(k) > 5.0) & (np.abs(x - far) * np.sqrt(k) > 6.0)
    x, k = x[keep], k[keep]
    assert x.size > 100
    assert np.all(creep_mask(p, x)) and np.all(fluidity(p, x) > 0.0)
    assert np.all(p.evaluate(x).u != 0.0)  # it moves: creep, not a plug at rest
    rate = -_along(lambda y: np.log(fluidity(p, y)), x, away, 1e-5)
    dk = _along(lambda y: -problem.equations.friction_ratio(y, T) / a**2, x, away, 1e-6)
    w = dk / (4.0 * k**1.5)
    assert np.all((w > 0.0) & (w < 0.06))  # mu close to constant on xi_c
    plain = rate / np.sqrt(k) - 1.0  # exp(-distance / xi_c)
    assert np.all(np.abs(plain - w) < 0.25 * w), np.c_[plain, w]
    wkb = rate / (np.sqrt(k) * (1.0 + w)) - 1.0
    assert np.all(np.abs(wkb) < 4.0 * w**2 + 1e-5), np.c_[wkb, w]


# ----------------------------------------------------------------- the local limit
@pytest.mark.parametrize("cell", ["couette", "plane", "channel"])
def test_ngf_tends_to_local_mu_of_I_as_A_goes_to_zero(cell):
    """The nonlocal correction is largest at the plug edge, where xi_c diverges: an inner
    layer of width (A d)^(2/3) (derivation section 6) makes |u_NGF - u_mu(I)| ~ (A d)^(4/3)."""
    mui = SATURATING.matching_mui()
    assert (mui.mu_s, mui.mu_2) == (MUI_MU_S, MUI_MU_2)
    assert mui.I_0 == pytest.approx(MUI_I0, rel=1e-14)
    As = np.array([0.12, 0.06, 0.03, 0.015])
    errors = []
    for A in As:
        law = NGF(mu_s=SATURATING.mu_s, b=SATURATING.b, mu_2=SATURATING.mu_2, A=A)
        if cell == "couette":
            ngf = Problem(Couette(eps=0.01, Ri=1.0, I_w=0.05), law)
            local = Problem(Couette(eps=0.01, Ri=1.0, I_w=0.05), mui)
        elif cell == "plane":
            ngf = Problem(Plane(eps=0.01, B=1.0, I_w=0.05), law)
            local = Problem(Plane(eps=0.01, B=1.0, I_w=0.05), mui)
        else:  # both driven by gravity, B nu = 1: wall stress ratio 0.5, a plug in the core
            ngf = Problem(VerticalChannel(eps=0.01, B=1.0), law)
            local = Problem(VerticalChannel(eps=0.01, B=1.0), mui)
        p = solve(ngf, xi=XS, check=False)
        errors.append(np.max(np.abs(p.u - solve(local, xi=XS, check=False).u)))
    errors = np.array(errors)
    assert np.all(np.diff(errors) < 0.0), errors
    orders = np.log(errors[:-1] / errors[1:]) / math.log(2.0)
    assert np.all((orders > 1.2) & (orders < 1.5)), orders
    assert errors[-1] < {"couette": 3e-4, "plane": 3e-4, "channel": 1.5e-3}[cell]


# ----------------------------------------------------------------- symmetry, walls, closed form
@pytest.mark.parametrize("name", ["channel-speed", "channel-stress"])
def test_the_channel_is_symmetric_about_its_centre_line(name):
    problem = CASES[name]
    p = solve(problem, xi=XS)
    f = p.evaluate(1.0 - XS)
    np.testing.assert_allclose(f.u, p.u, atol=1e-12)
    np.testing.assert_allclose(fluidity(p), fluidity(p, 1.0 - XS), rtol=1e-10, atol=1e-14)
    np.testing.assert_allclose(f.sigma_yx, -p.sigma_yx, atol=1e-15)  # odd shear stress
    np.testing.assert_allclose(f.du_dxi, -p.du_dxi, atol=1e-9)
    assert p.evaluate([0.5]).u[0] == pytest.approx(1.0, abs=1e-14)
    assert abs(p.u[0]) < 1e-14 and abs(p.u[-1]) < 1e-12
    Bn = p.diagnostics.stats["B_nu"]
    np.testing.assert_allclose(p.sigma_yx, Bn * (XS - 0.5), atol=1e-15)
    core = creep_mask(p)
    np.testing.assert_array_equal(core, Bn * np.abs(XS - 0.5) <= problem.rheology.mu_s)
    assert core[200] and not core[0]
    assert np.all(p.u[core] > 0.9)  # the creeping core is sheared, not a plug
    assert np.all(np.abs(p.du_dxi[core & (XS != 0.5)]) > 0.0)
    delta = shear_layer_thickness(p)
    assert p.evaluate([1.0 - delta * problem.eps]).u[0] == pytest.approx(1.0 - DEFAULT_F)


def test_imposed_stress_and_imposed_speed_are_one_solution():
    for by_speed in (CASES["couette"], CASES["plane-gravity"], CASES["channel-speed"]):
        p = solve(by_speed, xi=XS)
        T = p.diagnostics.stats["stress_ratio"]
        if by_speed.cell_name == "channel":
            by_stress = Problem(VerticalChannel(eps=by_speed.eps, B=2.0 * T), NGF())
        else:
            by_stress = by_speed.with_values({"I_w": None, "stress_ratio": T})
        q = solve(by_stress, xi=XS)
        assert q.diagnostics.stats["I_w"] == pytest.approx(by_speed.equations.I_w, rel=1e-9)
        np.testing.assert_allclose(q.u, p.u, atol=1e-9)


@pytest.mark.parametrize("I_w", [1e-3, 0.01, 0.3])
def test_uniform_shear_is_the_local_law_exactly(I_w):
    """Plane shear without gravity: mu uniform, so g = g_loc solves the fluidity equation
    with either wall condition and T = mu_s + b I_w (the linear law), u = xi."""
    for bc in ("neumann", "local"):
        p = solve(Problem(Plane(eps=0.02, I_w=I_w), NGF(fluidity_bc=bc)), xi=XS)
        np.testing.assert_allclose(p.u, XS, atol=1e-13)
        law = NGF()
        assert p.diagnostics.stats["stress_ratio"] == pytest.approx(
            law.mu_s + law.b * I_w, rel=1e-13
        )
        assert p.diagnostics.stats["creep"] is None and not creep_mask(p).any()


def test_the_wall_conditions_on_the_fluidity():
    neumann = solve(CASES["couette"], xi=XS)
    local = solve(CASES["couette-local-bc"], xi=XS)
    for p in (neumann, local):
        assert all(abs(v) < 1e-5 for v in p.diagnostics.bc_errors.values()), p.diagnostics
        assert p.evaluate([0.0]).u[0] == pytest.approx(-1.0, abs=1e-13)
    problem = CASES["couette-local-bc"]
    T = local.diagnostics.stats["stress_ratio"]
    g_wall = fluidity(local, [0.0])[0] * problem.equations.I_w
    # exact for the second-order solution; the extrapolated one to the extrapolation's error
    g_loc = float(problem.equations.local_fluidity(np.array([0.0]), T)[0])
    assert g_wall == pytest.approx(g_loc, rel=1e-10)
    # zero flux: the slope at the wall, times xi_c over max g, from the nodes (fourth order)
    slopes = [v for k, v in neumann.diagnostics.bc_errors.items() if k.startswith("n.grad g")]
    assert len(slopes) == 2 and max(map(abs, slopes)) < 1e-5
    # the two conditions give different profiles
    assert np.max(np.abs(neumann.u - local.u)) > 1e-3


# ----------------------------------------------------------------- what a profile carries
@pytest.mark.parametrize("name", ["couette", "plane-gravity", "channel-stress"])
def test_profile_fields_and_wall_quantities(name):
    problem = CASES[name]
    p = solve(problem)
    assert isinstance(problem.cell, Cell)
    mu = friction_ratio(p)
    np.testing.assert_allclose(mu, np.abs(p.sigma_yx) / p.sigma_yy, rtol=1e-14)
    g = fluidity(p)
    assert np.all(g >= 0.0) and np.all(np.isfinite(g))
    rate = shear_rate(p)
    np.testing.assert_allclose(rate, g * mu, rtol=1e-6, atol=1e-9 * rate.max())  # gamma = g mu
    np.testing.assert_allclose(np.abs(p.du_dxi - p.kappa * p.u), rate, rtol=1e-12, atol=1e-15)
    np.testing.assert_array_equal(creep_mask(p), mu <= problem.rheology.mu_s)
    extent = p.diagnostics.stats["creep"]
    assert extent is not None and "creeping region" in p.diagnostics.message
    # no grain spin or couple stress in this rheology: absent, not zero
    assert p.omega is None and p.m is None
    assert p.spin_minus_half_vorticity is None and p.asymmetry is None
    assert wall_slip(p) == pytest.approx(0.0, abs=1e-12)
    delta = shear_layer_thickness(p)
    assert 1.0 < delta < 0.5 / problem.eps
    assert "nonlocal granular fluidity" in p.diagnostics.message
    assert p.problem.parameters()["rheology"] == "ngf"
    p.to_json()
    back = pickle.loads(pickle.dumps(p))
    np.testing.assert_array_equal(back.evaluate(XS).u, p.evaluate(XS).u)
    np.testing.assert_array_equal(fluidity(back), g)
    assert shear_layer_thickness(back) == delta


@pytest.mark.parametrize("name", ["couette", "couette-saturating", "plane-gravity"])
def test_the_creep_tail_keeps_its_sign_and_order(name):
    """Deep in the creep region u and g are 1e-20 of their peak and below: still of one sign
    and monotone (the velocity is summed from the wall it decays towards, and the
    extrapolation works on the logarithm there), not round-off of O(1) sums."""
    problem = CASES[name]
    p = solve(problem, points=4001)
    g = fluidity(p)
    assert np.all(g > 0.0) and g.min() < 1e-15 * g.max()
    if problem.cell_name == "couette":  # u = -v/V_i: -1 at the inner cylinder, 0 outside
        assert np.all(p.u[:-1] < 0.0)
    else:
        assert np.all(p.u[1:] > 0.0)
    assert np.all(np.diff(p.u) >= 0.0)


def test_registration_and_the_methods_that_do_not_exist():
    assert RHEOLOGIES["ngf"] is NGF
    assert cells_for("ngf")[:3] == ["plane", "couette", "channel"]
    p = solve(Problem(Couette(eps=0.01, Ri=1.0), NGF()))
    assert p.method == "numerical"
    for method, why in (("closed-form", "no closed-form solution"), ("asymptotic", "asymptotics")):
        with pytest.raises(MethodNotAvailableError, match=f"{why}.*method='numerical'"):
            solve(CASES["couette"], method=method)


def test_glass_bead_defaults_are_henann_and_kamrin():
    law = NGF()
    assert (law.mu_s, law.b, law.A, law.mu_2, law.rho_s) == (0.3819, 0.9377, 0.48, None, 2450.0)
    # b is the slope at mu_s of Jop et al.'s law for the same beads, (mu_2 - mu_s)/I_0
    assert law.b == pytest.approx((MUI_MU_2 - MUI_MU_S) / MUI_I0, rel=1e-4)
    assert law.mu_s == pytest.approx(MUI_MU_S, rel=2e-4)
    # both local laws start from mu_s with the slope dI/dmu = 1/b: exactly for the linear law;
    # for the saturating one I = I_0 (mu - mu_s)/(mu_2 - mu), whose forward difference from
    # mu_s over h is exactly I_0/(mu_2 - mu_s - h) = (1/b)/(1 - h/(mu_2 - mu_s)): relative error
    # h/(mu_2 - mu_s - h) = 3.8e-6 at h = 1e-6, plus the rounding of mu_s + h (about 1e-10)
    h = 1e-6
    for ngf in (law, SATURATING):
        ends = ngf.local_inertial_number(np.array([ngf.mu_s, ngf.mu_s + h]))
        assert ends[0] == 0.0
        slope = (ends[1] - ends[0]) / ((ngf.mu_s + h) - ngf.mu_s)
        error = 0.0 if ngf.mu_2 is None else h / (ngf.mu_2 - ngf.mu_s - h)
        assert slope == pytest.approx(1.0 / ngf.b * (1.0 + error), rel=1e-9)
        assert slope == pytest.approx(1.0 / ngf.b, rel=error + 1e-9)
    assert law.wall_inertial_number(V=0.1, H=0.05, d=1e-3, N=2450.0) == pytest.approx(0.002)
    with pytest.raises(ParameterError, match="linear local law"):
        law.matching_mui()
    assert isinstance(SATURATING.matching_mui(), MuI)


# ----------------------------------------------------------------- no solution, bad input
def test_no_solution_is_said_in_words():
    with pytest.raises(NoSolutionError, match=r"<= mu_s .* nothing flows"):
        solve(Problem(Couette(eps=0.01, Ri=1.0, stress_ratio=0.3), NGF()))
    with pytest.raises(NoSolutionError, match="<= mu_s"):
        solve(Problem(VerticalChannel(eps=0.02, B=0.7), NGF()))  # B nu/2 = 0.35 < mu_s
    with pytest.raises(NoSolutionError, match=">= mu_2"):
        solve(Problem(Plane(eps=0.02, stress_ratio=0.7), SATURATING))
    with pytest.raises(NoSolutionError, match="beyond the fastest steady NGF flow"):
        solve(Problem(Couette(eps=0.01, Ri=1.0, I_w=0.9), SATURATING))
    with pytest.raises(ConvergenceError, match="needs 8388608 cells"):  # too thin for the grid
        solve(Problem(Couette(eps=0.001, Ri=1.0), NGF(A=0.001)))


@pytest.mark.parametrize(
    ("make", "match"),
    [
        (
            lambda: NGF(mu_s=-0.1),
            r"mu_s \(static friction coefficient\) must satisfy 0 < mu_s < 10 .*; got -0.1",
        ),
        (lambda: NGF(b=0.0), r"b \(.*\) must satisfy 0 < b; got 0"),
        (
            lambda: NGF(A=0.0),
            r"A \(.*\) must satisfy 0.0001 <= A \(A -> 0 is local mu\(I\): use the 'mui' "
            "rheology",
        ),
        (
            lambda: NGF(mu_2=0.3),
            r"mu_2 \(.*\) must satisfy mu_2 - mu_s >= 0.0001 \(.*\); got "
            "mu_2 = 0.3, mu_s = 0.3819",
        ),
        (lambda: NGF(rho_s=-1.0), r"rho_s \(.*\) must satisfy 0 < rho_s \[kg/m\^3\]"),
        (lambda: NGF(A=float("nan")), r"A \(.*\) must be finite"),
        (lambda: Problem(Plane(eps=0.01, I_w=0.0), NGF()), r"0 < I_w <= 1 .*; got 0"),
        (lambda: Problem(Plane(eps=0.01, I_w=0.1, stress_ratio=0.5), NGF()), "not both"),
        (lambda: Problem(Plane(eps=0.7), NGF()), r"eps \(.*\) must satisfy 1e-08 <= eps <= 0.5"),
        (lambda: Problem(Plane(eps=0.01, B=-1.0), NGF()), r"B \(.*\) must satisfy 0 <= B"),
        (
            lambda: Problem(Plane(eps=0.01), NGF(fluidity_bc="dirichlet")),
            r"fluidity_bc \(.*\) must be one of 'neumann', 'local'; got 'dirichlet'",
        ),
        (lambda: Problem(Couette(eps=0.01, Ri=0.0), NGF()), r"Ri \(.*\) must satisfy 0.001 <= Ri"),
        (lambda: Problem(Couette(eps=0.01, Ri=1.0), "ngf"), "rheology must be a Rheology"),
        (lambda: Problem(VerticalChannel(eps=0.01, B=1.0, I_w=0.1), NGF()), "not both"),
        (lambda: Problem(VerticalChannel(eps=0.01, B=-1.0), NGF()), r"B \(.*\) must satisfy 0 < B"),
        (
            lambda: Problem(VerticalChannel(eps=0.01, B=1.0, nu=2.0), NGF()),
            "nu .* must satisfy 0 < nu <= 1",
        ),
        (lambda: solve(CASES["couette"], cells=1002), "cells must be a multiple of 4"),
        (lambda: solve(CASES["couette"], resolution=0.1), "resolution must satisfy"),
        (lambda: solve(CASES["couette"], rtol=1e-8), "do not apply"),
    ],
)
def test_parameter_errors_name_the_parameter_and_the_bound(make, match):
    with pytest.raises(ParameterError, match=match):
        make()


# ----------------------------------------------------------------- a flow not told from rest
@pytest.mark.parametrize(
    ("args", "match"),
    [
        (
            ["plane", "--eps", "0.01", "--param", "I_w=1e-16"],
            "I_w must satisfy I_w >= 1e-07 mu_s/b",
        ),
        (["plane", "--eps", "0.01", "--param", "stress_ratio=0.38190000000000007"], "stress_ratio"),
        (["couette", "--eps", "0.01", "--param", "Ri=1", "--param", "I_w=1e-100"], "I_w must"),
        (["channel", "--eps", "0.01", "--param", "I_w=1e-100"], "I_w must satisfy"),
    ],
)
def test_a_flow_indistinguishable_from_rest_is_refused_in_one_line(args, match, capsys):
    """These crashed with ZeroDivisionError in the tridiagonal solve (the first two) or gave
    only 'root-find did not converge' (the last two)."""
    assert main(["solve", *args[:1], "--model", "ngf", *args[1:]]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and err.startswith("cosserat: error: "), err
    assert match in err and "cannot be told from rest" in err


def test_the_bounds_on_the_wall_speed_and_the_stress_level():
    law = NGF()
    assert law.I_w_min == NGF_EXCESS_RTOL * law.mu_s / law.b
    bound = law.mu_s * (1.0 + NGF_EXCESS_RTOL)
    for make in (
        lambda: Problem(Plane(eps=0.01, I_w=1e-16), NGF()),
        lambda: Problem(Couette(eps=0.01, Ri=1.0, I_w=0.99 * law.I_w_min), NGF()),
        lambda: Problem(VerticalChannel(eps=0.01, I_w=1e-100), NGF()),
        lambda: Problem(Plane(eps=0.01, stress_ratio=np.nextafter(law.mu_s, 1.0)), NGF()),
        lambda: Problem(Couette(eps=0.01, Ri=1.0, stress_ratio=law.mu_s * (1.0 + 0.5e-7)), NGF()),
        lambda: Problem(VerticalChannel(eps=0.01, B=2.0 * law.mu_s * (1.0 + 0.5e-7)), NGF()),
    ):
        with pytest.raises(ParameterError, match="cannot be told from rest") as info:
            make()
        assert isinstance(info.value, CosseratError)
    # at the bounds: uniform shear is still u = xi, T = mu_s + b I_w (measured 1.1e-10: the
    # excess T - mu_s = 3.8e-8 resolved to Brent's 1e-15 and mu_s's rounding)
    for eps in (0.01, 0.5):
        p = solve(Problem(Plane(eps=eps, I_w=law.I_w_min), NGF()), xi=XS)
        np.testing.assert_allclose(p.u, XS, atol=1e-9)
        T = p.diagnostics.stats["stress_ratio"]
        assert T - law.mu_s == pytest.approx(law.b * law.I_w_min, rel=1e-7)
    for p in (
        Problem(Plane(eps=0.01, stress_ratio=bound), NGF()),
        Problem(VerticalChannel(eps=0.01, B=2.0 * bound), NGF()),
    ):
        assert solve(p).diagnostics.stats["I_w"] > 0.0
    # a stress level at or below mu_s stays "nothing flows"
    with pytest.raises(NoSolutionError, match="nothing flows"):
        solve(Problem(Plane(eps=0.01, stress_ratio=law.mu_s), NGF()))


@pytest.mark.parametrize("n", [256, 2**16])
@pytest.mark.parametrize("excess", [5.6e-17, 1e-12, 1e-7, 0.3])
def test_the_tridiagonal_solve_keeps_a_small_k_with_zero_flux_walls(n, excess):
    """Uniform shear: F = F_loc whatever k. With zero-flux walls and k h^2 below the rounding
    of the O(1/h) fluxes the plain Thomas algorithm lost k and divided by zero; the form
    without cancellation keeps it to the rounding of n positive terms (measured <= 2.4e-12 at
    n = 2^16, down to a stress level 1 ulp above mu_s)."""
    mu_s, b = NGF().mu_s, NGF().b
    T = max(mu_s * (1.0 + excess), np.nextafter(mu_s, 1.0))
    F_loc = kernel.local_fluidity(T, 1.0, mu_s, b, 0.0)
    for a_eps in (0.48 * 0.01, 0.48 * 0.5):
        for dirichlet in (False, True):
            F = np.empty(n + 1)
            G, status = kernel.fluidity(kernel.PLANE, 0.0, T, n, a_eps, mu_s, b, 0.0, dirichlet, F)
            assert status == kernel.SOLVED
            np.testing.assert_allclose(F, F_loc, rtol=n * np.finfo(float).eps)
            assert G == pytest.approx(T * F_loc, rel=n * np.finfo(float).eps)


def test_a_singular_fluidity_solve_is_a_status_and_then_an_error_in_words():
    """k = 0 in double precision (T = mu_s) with zero-flux walls: F is not determined. The
    kernel says so (status SINGULAR, NaN) instead of dividing by zero, the root-find passes
    it on, and the route raises ConvergenceError."""
    law = NGF()
    F = np.empty(257)
    args = (kernel.PLANE, 0.0)
    G, status = kernel.fluidity(*args, law.mu_s, 256, 0.0048, law.mu_s, law.b, 0.0, False, F)
    assert status == kernel.SINGULAR and math.isnan(G) and np.all(np.isnan(F))
    found = kernel.stress_level(
        *args,
        256,
        0.0048,
        law.mu_s,
        law.b,
        0.0,
        False,
        1e-300,
        law.mu_s,
        2 * law.mu_s,
        1e-15,
        200,
        F,
    )
    assert found[1] == kernel.SINGULAR
    problem = Problem(Plane(eps=0.01), NGF())
    with pytest.raises(ConvergenceError, match=r"singular in double precision.*told from rest"):
        ngf_routes._fluidity(problem.equations, law.mu_s, 256, F)
