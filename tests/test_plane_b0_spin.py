"""Spin against half the vorticity in plane shear without gravity: a model fact, checked
independently (``docs/derivation_plane.md``, "Spin and half the vorticity").

eqn-nd_fr1 and eqn-nd_zangmom give ``omega + du/dxi / 2 = (1 - A)(A + 1) eps alpha omega
(dm/dxi) / sqrt(S)`` on the paper's root (``sigma_xy + A sigma_yx = -sqrt(S)``): the spin
departs from half the vorticity exactly where the couple stress varies. At B = 0 the
couple-stress equation (eqn-eta_g0) is autonomous, and eqn-nd_bc4 at a wall that does not
slip puts m at its fixed point m0 there, so m = m0 across the gap and the departure is zero at
every point: one slipping wall (eqn-eta_soln_aw_g0; the caption of the paper's figure 3,
fig-zero_g_aw, says so) and, since m = 0, identical fully rough walls (vel_g0). It is not
zero between identical walls smoother than the material (m(1/2) = 0, the paper's figure
2(b), fig-zero_g), with a prescribed m(0) != m0 (figure 5, fig-bc) or under gravity.

The reference here is SciPy's solve_bvp on the five balances and the flow rule written out
from the paper's labels (eqn-nd_xmom ... eqn-nd_fr2 with eqn-nd_sigxy's negative root) and the
wall conditions (eqn-nd_bc1 ... eqn-nd_bc5l), none of the package's kernel; its first guess
for m is not m0 (m0 is where Newton's iteration must arrive, not where it starts).
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from scipy.integrate import solve_bvp

from cosserat.model import make_problem
from cosserat.routes import solve

PHI = 28.5
FLOOR = 1e-8  # least radicand of eqn-nd_sigxy the reference evaluates
DATA = Path(__file__).resolve().parents[1] / "data" / "dem_v2"


def _tan(delta: Any, phi: float) -> float:
    if delta == "fully-rough":
        return math.sin(math.radians(phi))
    return math.tan(math.radians(float(delta)))


def bvp_plane(
    *,
    phi: float = PHI,
    L: float = 10.0,
    A: float = 1.0 / 3.0,
    eps: float = 0.04,
    B: float = 0.0,
    nu: float = 1.0,
    delta: Any = 15.0,
    delta_lower: Any = None,
    K: float = 0.5,
    K_lower: float | None = None,
    m_wall: float | None = None,
) -> tuple[str, Any]:
    """Plane shear by solve_bvp on y = (sigma_yx, sigma_yy, m, u, omega); returns the case
    (which wall slips, decided as the paper does in "Shear in the absence of gravity") and
    the solution. Written from the paper, not from the package."""
    tu, tl = _tan(delta, phi), _tan(delta if delta_lower is None else delta_lower, phi)
    k_low = K if K_lower is None else K_lower
    s2 = math.sin(math.radians(phi)) ** 2
    ea = eps * L / math.sqrt(2.0 * (A + 1.0))  # eps alpha
    if B == 0.0 and math.isclose(tu, tl):
        case = "symmetric"
    elif tl * (1.0 + B * nu) >= tu:
        case = "upper"  # friction at the upper wall, eqn-nd_bc4 and no slip at the lower
    else:
        case = "lower"

    def radicand(syx, syy, m):  # type: ignore[no-untyped-def]
        return (A * A - 1.0) * syx**2 + 2.0 * (A + 1.0) * syy**2 * s2 - 4.0 * (A + 1.0) ** 2 * m**2

    def sxy(syx, syy, m):  # type: ignore[no-untyped-def]
        # eqn-nd_sigxy, negative root; sigma_c = sigma_yy (eqn-ns). The floor keeps Newton's
        # trial points finite; the solution itself is checked to stay clear of it.
        return -A * syx - np.sqrt(np.maximum(radicand(syx, syy, m), FLOOR))

    def rhs(x, y):  # type: ignore[no-untyped-def]
        syx, syy, m, _, om = y
        sx = sxy(syx, syy, m)
        return np.vstack(
            [
                0.0 * x,  # eqn-nd_xmom
                -B * nu + 0.0 * x,  # eqn-nd_ymom
                -(sx - syx) / (2.0 * (A + 1.0) * ea),  # eqn-nd_zangmom
                -(A + 1.0) * (sx + syx) * om / (sx + A * syx),  # eqn-nd_fr1
                -2.0 * (A + 1.0) * m * om / (ea * (sx + A * syx)),  # eqn-nd_fr2
            ]
        )

    def bc(ya, yb):  # type: ignore[no-untyped-def]
        r = [yb[1] - 1.0]  # eqn-nd_bc1
        if case in ("symmetric", "upper"):  # eqn-nd_bc2, eqn-nd_bc3u at the upper wall
            r += [-yb[0] / yb[1] - tu, yb[3] - 1.0 - eps * K * yb[4]]
        if case in ("symmetric", "lower"):  # eqn-nd_bc3l at the lower wall
            r += [ya[3] + eps * k_low * ya[4]]
        if case == "symmetric":  # m odd about 1/2 (eqn-nd_bc6)
            r += [ya[2] + yb[2]]
        fixed, other = (ya, yb) if case == "upper" else (yb, ya)
        if case == "lower":  # eqn-nd_bc2 at the lower wall
            r += [-other[0] / other[1] - tl]
        if case != "symmetric":  # eqn-nd_bc5l/u and eqn-nd_bc4 (or m prescribed)
            r += [fixed[3] - (0.0 if case == "upper" else 1.0)]
            r += [fixed[2] - m_wall if m_wall is not None else sxy(*fixed[:3]) - fixed[0]]
        return np.array(r)

    x = np.linspace(0.0, 1.0, 2001)
    d = {"lower": x, "upper": 1.0 - x, "symmetric": np.minimum(x, 1.0 - x)}[case]
    y0 = np.zeros((5, x.size))
    y0[0] = -min(tu, tl)
    y0[1] = 1.0 + B * nu * (1.0 - x)
    y0[2] = {"lower": -0.1 + 0.0 * x, "upper": 0.1 + 0.0 * x, "symmetric": 0.2 * (x - 0.5)}[case]
    y0[3] = {"lower": np.exp(-d / 0.1), "upper": 1.0 - np.exp(-d / 0.1), "symmetric": x}[case]
    y0[4] = -5.0 * np.exp(-d / 0.1)
    sol = solve_bvp(rhs, bc, x, y0, tol=1e-8, max_nodes=200_000)
    assert sol.success, sol.message
    assert np.min(radicand(*sol.y[:3])) > 1e3 * FLOOR
    sol.rates = rhs  # type: ignore[attr-defined]
    return case, sol


def bvp_departure(sol: Any, xi: np.ndarray) -> np.ndarray:
    """omega + du/dxi / 2 of the reference, du/dxi from eqn-nd_fr1 at its solution."""
    y = sol.sol(xi)
    return y[4] + 0.5 * sol.rates(xi, y)[3]


def package(values: dict[str, Any]) -> Any:
    return solve(make_problem("cosserat", "plane", {"phi": PHI, **values}))


# the layer cell (rough moving upper wall, smoother fixed lower one) and its mirror image
ONE_SLIPPING_WALL = {
    "layer cell": {"B": 0.0, "L": 4.0, "eps": 0.05, "delta": "fully-rough", "delta_lower": 15.0},
    "rougher lower wall": {"B": 0.0, "L": 10.0, "eps": 0.04, "delta": 15.0, "delta_lower": 25.0},
    "A = 0.6, K_lower = 1": {
        "B": 0.0,
        "L": 6.0,
        "A": 0.6,
        "eps": 0.1,
        "delta": 24.0,
        "delta_lower": 8.0,
        "K_lower": 1.0,
    },
}
# cases where the model says the spin departs: the largest departure (both solvers) and the
# sign of dm/dxi (m rises from m(1/2) = 0 or from m(0) = 0.02 < m0; falls with the overburden)
DEPARTING = {
    "identical walls": ({"B": 0.0, "L": 10.0, "eps": 0.04, "delta": 15.0}, -0.09417, 1.0),
    "m(0) prescribed": (
        {"B": 0.0, "L": 10.0, "eps": 0.04, "delta": 15.0, "delta_lower": 25.0, "m_wall": 0.02},
        -0.011246,
        1.0,
    ),
    "gravity, B = 1": ({"B": 1.0, "L": 10.0, "eps": 0.04, "delta": 15.0}, 2.7524, -1.0),
}


def _agree(values: dict[str, Any]) -> tuple[Any, Any, np.ndarray]:
    """The package's profile, the reference's departure on its points, after checking that
    the two solve the same problem (u, omega relative to their size, m)."""
    prof = package(values)
    _, sol = bvp_plane(**values)
    xi = np.asarray(prof.xi)
    y = sol.sol(xi)
    assert np.max(np.abs(y[3] - prof.u)) < 1e-7
    assert np.max(np.abs(y[4] - prof.omega)) < 1e-7 * np.max(np.abs(prof.omega))
    assert np.max(np.abs(y[2] - prof.m)) < 1e-7
    return prof, sol, bvp_departure(sol, xi)


@pytest.mark.parametrize("name", list(ONE_SLIPPING_WALL))
def test_one_slipping_wall_at_b0_spin_is_half_the_vorticity_at_every_point(name):
    """eqn-eta_soln_aw_g0: m = m0, sigma_xy = sigma_yx, du/dxi = -2 omega. The reference,
    started at m = +-0.1, arrives at m0 and at a departure of its own tolerance's size;
    the package's is zero to rounding."""
    values = ONE_SLIPPING_WALL[name]
    prof, sol, dep = _agree(values)
    scale = np.max(np.abs(prof.omega))
    assert np.max(np.abs(dep)) < 1e-10 * scale
    assert np.max(np.abs(prof.spin_minus_half_vorticity)) <= 1e-14 * scale
    assert np.ptp(sol.y[2]) < 1e-12 and np.ptp(prof.m) == 0.0  # m constant
    assert np.max(np.abs(prof.asymmetry)) <= 1e-15  # a symmetric stress


def test_identical_fully_rough_walls_at_b0_have_no_departure():
    """vel_g0: m = 0, omega = omega1 uniform, u linear."""
    prof, _, dep = _agree({"B": 0.0, "L": 10.0, "eps": 0.04, "delta": "fully-rough"})
    assert np.max(np.abs(dep)) < 1e-14
    assert np.max(np.abs(prof.spin_minus_half_vorticity)) < 1e-14


@pytest.mark.parametrize("name", list(DEPARTING))
def test_where_the_couple_stress_varies_the_spin_departs_in_both_solvers(name):
    """The identical-wall case departs, most at the midplane (figure 2(b): omega + du/dxi/2
    != 0), a prescribed m(0) near the fixed wall (figure 5), gravity everywhere: the package and the
    reference give the same departure, so the zero above is not a solver's blind spot."""
    values, largest, dm_sign = DEPARTING[name]
    prof, _, dep = _agree(values)
    ours = prof.spin_minus_half_vorticity
    assert ours[np.argmax(np.abs(ours))] == pytest.approx(largest, rel=1e-4)
    assert np.max(np.abs(dep - ours)) < 1e-6 * np.max(np.abs(ours))
    # omega < 0 and A < 1: the departure has the sign of -dm/dxi (the identity below)
    assert np.all(dm_sign * np.diff(prof.m) >= 0.0)
    assert np.all(-dm_sign * ours >= -1e-15)


@pytest.mark.parametrize(
    "values", [ONE_SLIPPING_WALL["layer cell"], *(v[0] for v in DEPARTING.values())]
)
def test_the_departure_is_the_couple_stress_gradient(values):
    """omega + du/dxi/2 = (1 - A)(A + 1) eps alpha omega (dm/dxi) / sqrt(S), with dm/dxi from
    eqn-nd_zangmom and sigma_xy + A sigma_yx = -sqrt(S), on the package's own fields."""
    prof = package(values)
    A = values.get("A", 1.0 / 3.0)
    ea = values["eps"] * values["L"] / math.sqrt(2.0 * (A + 1.0))
    dm = (prof.sigma_yx - prof.sigma_xy) / (2.0 * (A + 1.0) * ea)
    sqrt_s = -(prof.sigma_xy + A * prof.sigma_yx)
    identity = (1.0 - A) * (A + 1.0) * ea * prof.omega * dm / sqrt_s
    scale = np.max(np.abs(prof.omega))
    assert np.max(np.abs(prof.spin_minus_half_vorticity - identity)) < 1e-12 * scale


def test_the_layer_runs_cosserat_spin_is_the_binning_of_a_material_spin():
    """On the DEM layer run the Cosserat layer profiles (L = 4, 5 d and the fitted L) report a
    first-bin departure (-0.046, -0.033, -0.095) only through the bins and the stencil: it is
    what the analysis reports for grains turning with the same velocity (null_departure),
    exactly. The model predicts no departure of its own here (docs/validation.md)."""
    from cosserat.analysis.corpus import read_run
    from cosserat.studies.validate.forward import forward_departure, null_departure
    from cosserat.studies.validate.layer import layer_position_verdict, measure_layer
    from cosserat.studies.validate.layer_alternatives import LayerData, cosserat_profile

    run = read_run(DATA / "plane_layer_H10_qs" / "profile.csv")
    pos = measure_layer(run)
    assert pos is not None and pos.stress_ratio is not None
    u, se = run.quantity("u")
    ok = np.isfinite(u) & np.isfinite(se) & (se > 0.0)
    data = LayerData.from_run(
        run.distance_d[ok], u[ok], se[ok], run.gap_d, pos.smoother, pos.bin_correlation,
        pos.stress_ratio,
    )  # fmt: skip
    first = [s.departure[0] for s in pos.spin]
    assert first == pytest.approx([-0.0460, -0.0331, -0.0950], abs=5e-4)
    for s in pos.spin:
        prof = cosserat_profile(data, s.L_d)
        assert prof.problem.equations.case.value == "layer-at-lower-wall"
        # zero up to round-off: 2 ulp of the spin at the run's tan delta (it was exactly 0.0
        # at the stress ratio of the window from 2.7 d of travel)
        scale = np.max(np.abs(prof.omega))
        assert np.max(np.abs(prof.spin_minus_half_vorticity)) <= 4 * np.finfo(float).eps * scale
        forward, null = forward_departure(prof, run), null_departure(prof, run)
        np.testing.assert_allclose(forward, null, rtol=0, atol=4 * np.finfo(float).eps * scale)
        assert 0.0 <= s.own_departure <= 4 * np.finfo(float).eps and s.turns_with_the_material
    text = layer_position_verdict([pos]).evidence
    assert "Cosserat layer profiles' own spin is half their vorticity at every point" in text
    assert "The spin, the one observable that can tell" not in text
