"""Parameters: validation names the parameter, the bound and the value; objects are frozen."""

from __future__ import annotations

import dataclasses
import math

import pytest

from cosserat import (
    Cosserat,
    Material,
    ParameterError,
    Plane,
    PlaneShearCase,
    Problem,
    Wall,
)

MAT = Material(28.5)


@pytest.mark.parametrize(
    ("kwargs", "pattern"),
    [
        (
            {"phi": 0.0},
            r"phi \(angle of internal friction\) must satisfy 0 < phi < 90 \[deg\]; got 0",
        ),
        ({"phi": 90.0}, r"phi \(.*\) must satisfy 0 < phi < 90"),
        ({"phi": float("nan")}, r"phi \(.*\) must be finite"),
        ({"phi": "x"}, r"phi \(.*\) must be a number"),
        (
            {"phi": 30.0, "A": -1.0},
            r"A \(.*\) must satisfy -1 < A < 1 \(the quadratic form .* must be positive\); got -1",
        ),
        ({"phi": 30.0, "A": 1.0}, r"A \(.*\) must satisfy -1 < A < 1 .*; got 1"),
        ({"phi": 30.0, "L": 0.0}, r"L \(.*\) must satisfy 0.001 <= L <= 10000 .*; got 0"),
        ({"phi": 30.0, "L": -2.0}, r"L \(.*\) must satisfy 0.001 <= L <= 10000 .*; got -2"),
    ],
)
def test_material_bounds(kwargs, pattern):
    with pytest.raises(ParameterError, match=pattern):
        Material(**kwargs)


@pytest.mark.parametrize(
    ("args", "pattern"),
    [
        ((0.0,), r"delta \(.*\) must satisfy 0 < delta < 90 \[deg\]; got 0"),
        ((95.0,), r"delta \(.*\) must satisfy 0 < delta < 90"),
        ((20.0, -0.1), r"K \(.*\) must satisfy 0 <= K; got -0.1"),
        ((20.0, float("inf")), r"K \(.*\) must be finite"),
    ],
)
def test_wall_bounds(args, pattern):
    with pytest.raises(ParameterError, match=pattern):
        Wall(*args)


def test_wall_rougher_than_fully_rough_is_rejected_with_the_bound():
    pattern = r"tan\(delta\) <= sin\(phi\).*25.5086.*got delta = 26"
    with pytest.raises(ParameterError, match=pattern):
        Problem(Plane(eps=0.1), Cosserat(material=MAT, wall=Wall(26.0)))
    with pytest.raises(ParameterError, match=r"delta_lower"):
        Problem(Plane(eps=0.1), Cosserat(material=MAT, wall=Wall(20.0), lower=Wall(30.0)))


@pytest.mark.parametrize(
    ("kwargs", "pattern"),
    [
        (
            {"eps": 0.0},
            r"eps \(grain diameter over gap, d_p/H\) must satisfy 1e-08 <= eps <= 0.5.*got 0",
        ),
        ({"eps": 0.6}, r"eps \(.*\) must satisfy 1e-08 <= eps <= 0.5.*got 0.6"),
        (
            {"eps": 0.1, "B": -1.0},
            r"B \(gravity parameter rho_p g H / N.*\) must satisfy 0 <= B <= 1e\+06.*got -1",
        ),
        ({"eps": 0.1, "B": 1e300}, r"B \(.*\) must satisfy 0 <= B <= 1e\+06.*got 1e\+300"),
        ({"eps": 0.1, "nu": 0.0}, r"nu \(solids fraction.*\) must satisfy 0 < nu <= 1; got 0"),
        ({"eps": 0.1, "nu": 1.5}, r"nu .* got 1.5"),
        ({"eps": float("nan")}, r"eps \(.*\) must be finite"),
    ],
)
def test_plane_bounds(kwargs, pattern):
    with pytest.raises(ParameterError, match=pattern):
        Problem(Plane(**kwargs), Cosserat(material=MAT, wall=Wall(20.0)))


def test_frozen_and_replace_revalidates():
    p = Problem(Plane(eps=0.1), Cosserat(material=MAT, wall=Wall(20.0)))
    with pytest.raises(dataclasses.FrozenInstanceError):
        p.eps = 0.2  # type: ignore[misc]
    assert p.with_values({"eps": 0.2}).eps == 0.2
    assert dataclasses.replace(p, cell=Plane(eps=0.2)).eps == 0.2
    with pytest.raises(ParameterError, match="eps"):
        p.with_values({"eps": 2.0})


def test_fully_rough_wall_is_exactly_sin_phi_and_atan_round_trip_snaps():
    rough = Problem(Plane(eps=0.1), Cosserat(material=MAT, wall=Wall.fully_rough()))
    assert rough.equations.tan_delta_upper == MAT.sin_phi
    assert rough.equations.is_fully_rough
    via_angle = Problem(Plane(eps=0.1), Cosserat(material=MAT, wall=Wall(MAT.fully_rough_delta)))
    assert via_angle.equations.tan_delta_upper == MAT.sin_phi
    assert math.isclose(MAT.fully_rough_delta, 25.5086, abs_tol=1e-4)


@pytest.mark.parametrize(
    ("upper", "lower", "B", "case"),
    [
        (20.0, None, 0.0, PlaneShearCase.SYMMETRIC),
        (20.0, 25.0, 0.0, PlaneShearCase.UPPER),
        (20.0, 10.0, 0.0, PlaneShearCase.LOWER),
        (20.0, None, 1.0, PlaneShearCase.UPPER),
        # tan(delta_L) (1 + B nu) < tan(delta): friction is mobilised at the lower wall
        (25.0, 10.0, 1.0, PlaneShearCase.LOWER),
        (25.0, 20.0, 0.2, PlaneShearCase.LOWER),
        (20.0, 20.0, 0.2, PlaneShearCase.UPPER),
    ],
)
def test_the_problem_decides_which_wall_slips(upper, lower, B, case):
    p = Problem(
        Plane(eps=0.1, B=B),
        Cosserat(material=MAT, wall=Wall(upper), lower=None if lower is None else Wall(lower)),
    )
    assert p.equations.case is case
    limit_upper = math.tan(math.radians(upper))
    limit_lower = math.tan(math.radians(lower if lower is not None else upper)) * (1 + B)
    assert abs(p.equations.sigma_yx) == pytest.approx(min(limit_upper, limit_lower), rel=1e-14)


def test_m_fixed_wall_range():
    p = Problem(Plane(eps=0.04), Cosserat(material=MAT, wall=Wall(10.0), lower=Wall(20.0)))
    b = p.equations.slip_constants.b
    assert p.equations.couple_stress_bound(0.0) == pytest.approx(b, rel=1e-14)
    Problem(
        Plane(eps=0.04), Cosserat(material=MAT, wall=Wall(10.0), lower=Wall(20.0), m_fixed_wall=b)
    )
    with pytest.raises(ParameterError, match=r"m_fixed_wall must satisfy 0 <= m_fixed_wall"):
        Problem(
            Plane(eps=0.04),
            Cosserat(material=MAT, wall=Wall(10.0), lower=Wall(20.0), m_fixed_wall=1.01 * b),
        )
    with pytest.raises(ParameterError, match=r"m_fixed_wall must satisfy"):
        Problem(
            Plane(eps=0.04),
            Cosserat(material=MAT, wall=Wall(10.0), lower=Wall(20.0), m_fixed_wall=-0.01),
        )
    with pytest.raises(ParameterError, match=r"both walls slip"):
        Problem(Plane(eps=0.04), Cosserat(material=MAT, wall=Wall(10.0), m_fixed_wall=0.1))


def test_defaults_are_the_papers_from_config():
    from cosserat import config

    assert Material() == Material(config.PHI, config.L, config.A)
    assert (Material().phi, Material().L, Material().A) == (config.PHI, config.L, config.A)
    assert (Wall().delta, Wall().K) == (config.DELTA, config.K)
    assert Wall.fully_rough().K == config.K


def test_positional_use_still_works():
    assert Material(28.5) == Material(phi=28.5)
    assert Material(30.0, 5.0, 0.0) == Material(phi=30.0, L=5.0, A=0.0)
    assert Wall(20.0, 0.5) == Wall(delta=20.0, K=0.5)
    assert Wall(15.0) == Wall(delta=15.0)
    assert Wall("fully-rough") == Wall.fully_rough()
    assert Wall("fully-rough", 0.2) == Wall.fully_rough(0.2)
    assert Wall.fully_rough().is_fully_rough
