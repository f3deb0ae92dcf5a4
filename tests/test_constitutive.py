"""The constitutive law: yield condition, root choice, flow-rule ratios, no-solution errors."""

from __future__ import annotations

import numpy as np
import pytest

from cosserat import Cosserat, Material, NoSolutionError, Plane, Problem, Wall
from cosserat.model.constitutive import (
    second_shear_stress,
    spin_ratio,
    symmetric_couple_stress,
    velocity_ratio,
)
from cosserat.model.constitutive import torque as cancellation_free_torque

MAT = Material(28.5)


def yield_residual(sxy, syx, sc, m, mat):
    """eqn-nd_yc written out independently."""
    A = mat.A
    return (
        sxy**2
        + syx**2
        + 2 * A * sxy * syx
        + 4 * (A + 1) ** 2 * m**2
        - 2 * (A + 1) * (sc * mat.sin_phi) ** 2
    )


@pytest.mark.parametrize("A", [-0.5, 0.0, 1 / 3, 0.9])
def test_second_shear_stress_satisfies_the_yield_condition_with_the_papers_root(A, rng):
    mat = Material(28.5, A=A)
    syx = -rng.uniform(0.05, 0.47, 200)
    sc = rng.uniform(1.0, 2.0, 200)
    bound = np.sqrt(
        np.maximum(
            (2 * (A + 1) * (sc * mat.sin_phi) ** 2 + (A * A - 1) * syx**2) / (4 * (A + 1) ** 2), 0
        )
    )
    m = rng.uniform(-1, 1, 200) * bound
    sxy = second_shear_stress(syx, sc, m, mat)
    assert np.max(np.abs(yield_residual(sxy, syx, sc, m, mat))) < 1e-14
    # The paper's root (negative sign in eqn-nd_sigxy): sxy + A syx <= 0, and syx - sxy >= 0
    # wherever |m| is below the value that makes the stress symmetric (as on every solution).
    assert np.all(sxy + A * syx <= 0)
    m_sym = np.sqrt(((sc * mat.sin_phi) ** 2 - syx**2) / (2 * (A + 1)))
    below = np.abs(m) <= m_sym
    assert below.sum() > 20
    assert np.all((syx - sxy)[below] >= -1e-15)
    assert np.all((syx - sxy)[~below] < 0)


def test_no_real_root_says_where_and_why():
    with pytest.raises(NoSolutionError, match=r"no real solution at xi = 0.3.*exceeds its yield"):
        second_shear_stress(-0.3, 1.0, 0.5, MAT, xi=0.3)


def test_flow_ratios_for_a_symmetric_stress():
    syx = -0.36
    m = symmetric_couple_stress(syx, 1.0, MAT)
    sxy = second_shear_stress(syx, 1.0, m, MAT)
    assert sxy == pytest.approx(syx, abs=1e-15)  # eqn-nd_bc4 reached
    assert velocity_ratio(sxy, syx, MAT) == pytest.approx(2.0)  # du/dxi = -2 omega
    # eps alpha omega' = -F2 omega with F2 = 2(A+1)m/((1+A)syx) = 2m/syx, so k = m/(alpha a)
    assert spin_ratio(sxy, syx, m, MAT) == pytest.approx(2 * m / syx)


def test_symmetric_couple_stress_is_the_papers_m0():
    tan_d = np.tan(np.radians(20.0))
    a = tan_d / 2
    b = np.sqrt(a * a + (MAT.sin_phi**2 - tan_d**2) / (2 * (MAT.A + 1)))  # eqn-a_b_def
    assert symmetric_couple_stress(-tan_d, 1.0, MAT) == pytest.approx(np.sqrt(b * b - a * a))
    with pytest.raises(NoSolutionError, match="eqn-nd_bc4"):
        symmetric_couple_stress(-0.6, 1.0, MAT)


def test_cancellation_free_torque_matches_the_direct_form_away_from_cancellation(rng):
    form = Problem(
        Plane(eps=0.1, B=1.0), Cosserat(material=MAT, wall=Wall(15.0))
    ).equations.formulation()
    xi = rng.uniform(0, 1, 100)
    m = rng.uniform(0, 0.2, 100)
    st = form.stresses(xi, m)
    direct = (st.sigma_yx - (-MAT.A * st.sigma_yx - np.sqrt(st.radicand))) / (2 * (MAT.A + 1))
    torque = cancellation_free_torque(st.sigma_yx, st.sigma_c, m, MAT)
    np.testing.assert_allclose(torque, direct, rtol=1e-12, atol=1e-15)


def test_fully_rough_torque_vanishes_exactly_at_m_zero():
    form = Problem(
        Plane(eps=1e-6), Cosserat(material=MAT, wall=Wall.fully_rough())
    ).equations.formulation()
    assert form.dm_dxi(np.array([0.7]), np.array([0.0]))[0] == 0.0
