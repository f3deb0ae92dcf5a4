"""Laboratory cells in SI units (cosserat.analysis.cell) for every rheology on plane shear,
Couette flow and the channel: the SI results against hand computations from the
dimensionless solution, closed forms where they exist."""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest

from cosserat import NGF, Cosserat, MuI, Wall, solve
from cosserat.analysis.cell import ChannelCell, CouetteCell, PlaneCell
from cosserat.errors import ParameterError

GRAINS = {"grain_diameter": 1e-3, "density": 2500.0, "gap": 0.02}
COUETTE = {**GRAINS, "inner_radius": 0.02, "fill_depth": 0.1, "rotation_rate": 0.5}


def mu_of(law: MuI, inertial: float) -> float:
    v = law.values()
    return v["mu_s"] + (v["mu_2"] - v["mu_s"]) / (v["I_0"] / inertial + 1.0)


def test_plane_mui_without_gravity_is_the_closed_form_in_si():
    # uniform stress ratio, so uniform I = I_w: u = y/H, tau = N mu(I_w)
    V, N = 0.04, 100.0
    cell = PlaneCell(**GRAINS, normal_stress=N, wall_speed=V, gravity=0.0)
    I_w = V * 1e-3 / (0.02 * math.sqrt(N / 2500.0))
    assert cell.inertial_number() == pytest.approx(I_w, rel=1e-15) and cell.B == 0.0
    law = MuI()
    profile = solve(cell.problem(law))
    assert profile.problem.cell.I_w == pytest.approx(I_w, rel=1e-15)
    assert cell.wall_shear_stress(profile) == pytest.approx(N * mu_of(law, I_w), rel=1e-10)
    np.testing.assert_allclose(cell.velocity(profile), V * profile.xi, atol=1e-12 * V)
    np.testing.assert_allclose(cell.spin(profile), -V / (2 * 0.02), rtol=1e-9)
    np.testing.assert_allclose(cell.position(profile), 0.02 * profile.xi, rtol=0, atol=0)
    assert cell.slip_velocity(profile) == pytest.approx(0.0, abs=1e-12 * V)
    r = cell.results(profile)
    assert r["I_w"] == pytest.approx(I_w, rel=1e-12) and r["stress_scale"] == N


def test_plane_cosserat_without_gravity_carries_tan_delta_and_slips():
    V, N = 0.04, 100.0
    cell = PlaneCell(**GRAINS, normal_stress=N, wall_speed=V, gravity=0.0)
    profile = solve(cell.problem(Cosserat(wall=Wall(delta=20.0))), method="closed-form")
    assert cell.wall_shear_stress(profile) == pytest.approx(N * math.tan(math.radians(20.0)))
    slip = V * (1.0 - float(profile.evaluate([1.0]).u[0]))
    assert cell.slip_velocity(profile) == pytest.approx(slip, rel=1e-12)
    # Delta in metres is Delta in grain diameters times d_p
    r = cell.results(profile)
    assert r["Delta_m"] == pytest.approx(r["Delta"] * 1e-3, rel=1e-15)


def test_plane_gravity_parameter_is_rho_g_h_over_n():
    cell = PlaneCell(**GRAINS, normal_stress=200.0, wall_speed=0.1)
    assert cell.B == pytest.approx(2500 * 9.81 * 0.02 / 200.0, rel=1e-15)
    assert cell.problem(MuI()).cell.B == cell.B


def test_couette_mui_inertial_number_follows_depth_and_torque_is_integrated():
    cell = CouetteCell(**COUETTE)
    V = 0.5 * 0.02
    for z in (0.1, 0.025):
        expected = V * 1e-3 / (0.02 * math.sqrt(9.81 * 0.6 * z))  # p/rho_p = g nu z
        assert cell.inertial_number(z) == pytest.approx(expected, rel=1e-14)
        assert cell.problem(MuI(), depth=z).cell.I_w == pytest.approx(expected, rel=1e-14)
    law = MuI()
    profile = solve(cell.problem(law))
    # no couple stress: the torque per height is 2 pi R_i^2 tau_w
    assert cell.torque_density(profile)[0] == pytest.approx(
        cell.shear_torque_density(profile), rel=1e-12
    )
    # the torque over the fill depth against 20-node quadrature in s = sqrt(z/D) done here
    nodes, weights = np.polynomial.legendre.leggauss(20)
    total = 0.0
    for x, w in zip(nodes, weights, strict=True):
        s = 0.5 * (x + 1.0)
        z = 0.1 * s * s
        p = solve(cell.problem(law, depth=z), points=3)
        total += 0.5 * w * 0.2 * s * 2 * math.pi * 0.02**2 * cell.wall_shear_stress(p, depth=z)
    assert cell.torque(profile) == pytest.approx(total, rel=1e-7)  # TORQUE_NODES
    # the stress ratio lies between mu_s and mu_2 at every depth
    static = 2 * math.pi * 0.02**2 * 2500 * 9.81 * 0.6 * 0.1**2 / 2
    v = law.values()
    assert v["mu_s"] * static < cell.torque(profile) < v["mu_2"] * static


def test_couette_profile_at_another_depth_is_refused_for_a_rate_dependent_law():
    cell = CouetteCell(**COUETTE)
    profile = solve(cell.problem(MuI()))
    with pytest.raises(ParameterError, match=r"the profile is not at depth 0\.05 m"):
        cell.wall_shear_stress(profile, depth=0.05)


@pytest.mark.parametrize("depth", [1.0, -0.1, 0.0, math.nan])
def test_couette_depth_is_checked_in_the_api(depth):
    cell = CouetteCell(**COUETTE)
    profile = solve(cell.problem())
    with pytest.raises(ParameterError, match=r"depth must satisfy 0 < depth <= fill depth = 0\.1"):
        cell.wall_shear_stress(profile, depth=depth)


def test_channel_mui_wall_stress_is_the_weight_and_speed_comes_from_i_w():
    N = 300.0
    cell = ChannelCell(**GRAINS, normal_stress=N)
    profile = solve(cell.problem(MuI()))
    assert cell.wall_shear_stress(profile) == pytest.approx(2500 * 9.81 * 0.6 * 0.02 / 2)
    I_w = profile.diagnostics.stats["I_w"]
    V_c = I_w * 0.02 * math.sqrt(N / 2500.0) / 1e-3
    assert cell.velocity_scale(profile) == pytest.approx(V_c, rel=1e-15)
    assert cell.velocity(profile)[profile.xi.size // 2] == pytest.approx(V_c, rel=1e-9)


def test_channel_cosserat_needs_the_centre_speed_and_gives_the_normal_stress():
    with pytest.raises(ParameterError, match="centre_speed"):
        ChannelCell(**GRAINS).problem()
    with pytest.raises(ParameterError, match="normal_stress"):
        ChannelCell(**GRAINS, centre_speed=0.1).problem(NGF())
    cell = ChannelCell(**GRAINS, centre_speed=0.1)
    profile = solve(cell.problem())
    r = cell.results(profile)
    # fully mobilised wall friction: B nu = 2 tan(delta), N = rho_p g H / B
    B = 2 * math.tan(math.radians(20.0)) / 0.6
    assert r["B"] == pytest.approx(B, rel=1e-12)
    assert r["normal_stress"] == pytest.approx(2500 * 9.81 * 0.02 / B, rel=1e-12)
    assert r["wall_shear_stress"] == pytest.approx(2500 * 9.81 * 0.6 * 0.02 / 2, rel=1e-12)


def test_old_names_are_deprecated_aliases():
    with pytest.warns(DeprecationWarning, match=r"d_p=\.\.\. is deprecated; use grain_diameter="):
        old = CouetteCell(
            d_p=1e-3, rho_p=2500.0, gap=0.02, R_i=0.02, fill_depth=0.1, rotation_rate=0.5
        )
    assert old == CouetteCell(**COUETTE)
    with pytest.warns(DeprecationWarning, match=r"\.R_i is deprecated; use \.inner_radius"):
        assert old.R_i == 0.02
    with (
        pytest.raises(ParameterError, match="give grain_diameter or its deprecated alias d_p"),
        warnings.catch_warnings(),
    ):
        warnings.simplefilter("ignore", DeprecationWarning)
        CouetteCell(**COUETTE, d_p=1e-3)


@pytest.mark.parametrize(
    ("kwargs", "needle"),
    [
        ({**COUETTE, "gap": -0.02}, "gap must be > 0 m; got -0.02"),
        ({**COUETTE, "solids_fraction": 1.5}, "solids_fraction must satisfy 0 < solids_frac"),
        ({**COUETTE, "grain_diameter": 0.02}, "grain_diameter must be at most half the gap"),
        ({**GRAINS, "inner_radius": 0.02}, "CouetteCell needs fill_depth [m]"),
        ({**COUETTE, "speed": 1.0}, "unknown argument(s) speed of CouetteCell"),
    ],
)
def test_bad_cells_are_one_clean_error(kwargs, needle):
    with pytest.raises(ParameterError) as info:
        CouetteCell(**kwargs)
    assert needle in str(info.value) and "np.float64" not in str(info.value)
