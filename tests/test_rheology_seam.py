"""The cell x rheology seam: cells and rheologies register by name, a problem is one of each,
routes register per (rheology, cell, method), and every cell states its statics consistently.

The plug-in proof (a toy rheology and a toy cell reaching solve, the CLI, sweeps and fitting
with no edit elsewhere) is ``test_plugins.py``.
"""

from __future__ import annotations

import pickle

import numpy as np
import pytest

from cosserat import (
    NGF,
    Cosserat,
    Couette,
    MethodNotAvailableError,
    MuI,
    ParameterError,
    Plane,
    Problem,
    VerticalChannel,
    solve,
)
from cosserat.model.cells import CELLS, Cell
from cosserat.model.rheologies import RHEOLOGIES, Rheology
from cosserat.routes import cells_for, methods_for
from cosserat.routes.registry import ROUTES, register_route

CELL_CASES = [
    Plane(eps=0.01),
    Plane(eps=0.01, B=2.0, nu=0.6),
    Couette(eps=0.01, Ri=0.3),
    Couette(eps=0.01, Ri=50.0),
    VerticalChannel(eps=0.01, B=1.0),
]


def test_the_built_in_cells_and_rheologies_are_registered_by_name():
    assert list(CELLS)[:3] == ["plane", "couette", "channel"]
    assert (CELLS["plane"], CELLS["couette"], CELLS["channel"]) == (Plane, Couette, VerticalChannel)
    assert list(RHEOLOGIES)[:3] == ["cosserat", "mui", "ngf"]
    assert (RHEOLOGIES["cosserat"], RHEOLOGIES["mui"], RHEOLOGIES["ngf"]) == (Cosserat, MuI, NGF)
    for name in ("cosserat", "mui", "ngf"):
        assert cells_for(name)[:3] == ["plane", "couette", "channel"]
    assert methods_for("cosserat", "plane") == ["numerical", "closed-form", "asymptotic"]
    assert methods_for("mui", "couette") == ["numerical", "closed-form"]
    assert ROUTES[("mui", "*", "numerical")] is ROUTES[("mui", "*", "numerical")]


@pytest.mark.parametrize("cell", CELL_CASES, ids=lambda c: f"{c.name}-{c.describe()}")
def test_every_cell_states_one_statics(cell):
    """|sigma_yx|/sigma_yy from the shear and normal stresses equals T q(t) from the ratio
    shape; q and its complement sum to 1; the inverse distance inverts it; the ratio is
    largest at the peak wall."""
    xi = np.linspace(0.0, 1.0, 41)
    T = 0.47
    ratio = np.abs(cell.shear_stress(xi, T)) / cell.normal_stress(xi)
    np.testing.assert_allclose(ratio, cell.stress_ratio_profile(xi, T), rtol=1e-14, atol=1e-15)
    q, rest = cell.ratio_shape(cell.distance(xi))
    np.testing.assert_allclose(q + rest, 1.0, rtol=1e-15)
    assert float(np.max(ratio)) == pytest.approx(T * float(cell.ratio_shape(0.0)[0]), rel=1e-15)
    assert cell.stress_ratio_profile(np.array([cell.peak_wall]), T)[0] == pytest.approx(
        T, rel=1e-15
    )
    for r in (1.1, 1.7):
        t = cell.distance_of_ratio(r)
        if t < cell.span:
            assert float(cell.ratio_shape(t)[0]) == pytest.approx(1.0 / r, rel=1e-12)
    # the generic inverse (Brent's method on the shape) agrees with the closed form
    t = cell.distance_of_ratio(1.05)
    generic = Cell.distance_of_ratio(cell, 1.05)
    assert generic == (pytest.approx(t, rel=1e-10, abs=1e-14) if t < cell.span else float("inf"))
    h = 1e-6
    slope = float(cell.ratio_shape(np.array([h]))[1][0]) / h
    assert slope == pytest.approx(cell.ratio_slope, rel=1e-5, abs=1e-12)
    # the distance where 1 - q reaches delta, without cancellation however small delta is
    for delta in (1e-300, 1e-12, 0.01):
        t = cell.distance_of_complement(delta)
        if t < cell.span:
            assert float(cell.ratio_shape(np.array([t]))[1][0]) == pytest.approx(delta, rel=1e-9)


def test_a_problem_is_a_cell_and_a_rheology():
    problem = Problem(Couette(eps=0.01, Ri=2.0), Cosserat())
    assert (problem.model, problem.cell_name, problem.eps) == ("cosserat", "couette", 0.01)
    assert problem == Problem(Couette(eps=0.01, Ri=2.0), Cosserat())
    assert hash(problem) == hash(Problem(Couette(eps=0.01, Ri=2.0), Cosserat()))
    assert pickle.loads(pickle.dumps(problem)) == problem
    with pytest.raises(ParameterError, match="cell must be a Cell"):
        Problem("plane", Cosserat())  # type: ignore[arg-type]
    with pytest.raises(ParameterError, match="rheology must be a Rheology"):
        Problem(Plane(eps=0.01), "cosserat")  # type: ignore[arg-type]


def test_a_parameter_that_does_not_apply_to_the_pair_is_refused():
    with pytest.raises(ParameterError, match=r"I_w .* does not apply to the cosserat rheology"):
        Problem(Plane(eps=0.01, I_w=0.1), Cosserat())
    with pytest.raises(ParameterError, match="m_wall applies to the plane cell only"):
        Problem(Couette(eps=0.01), Cosserat(m_fixed_wall=0.1))
    with pytest.raises(ParameterError, match=r"has no equations on the .* cell"):

        class Nowhere(Rheology):  # not registered: no name
            pass

        Problem(Plane(eps=0.01), Nowhere())


def test_with_values_and_values_by_key():
    problem = Problem(Plane(eps=0.01), Cosserat())
    values = problem.values()
    assert list(values)[:5] == ["phi", "L", "A", "delta", "K"]
    moved = problem.with_values({"eps": 0.02, "delta": 25.0, "B": 1.0})
    assert (moved.cell.eps, moved.cell.B, moved.rheology.wall.delta) == (0.02, 1.0, 25.0)
    assert moved.rheology.lower is None  # the lower wall still follows the moving one
    with pytest.raises(ParameterError, match=r"unknown parameter\(s\) Ri .* it has phi"):
        problem.with_values({"Ri": 2.0})
    with pytest.raises(ParameterError, match=r"eps \(.*\) must satisfy"):
        problem.with_values({"eps": 2.0})
    mui = Problem(Couette(eps=0.01), MuI())
    assert mui.values()["I_w"] is None and mui.cell_values()["I_w"] == 0.01  # the one default
    assert mui.with_values({"I_w": 0.05, "mu_s": 0.4}).parameters()["I_w"] == 0.05


def test_names_are_unique():
    with pytest.raises(ParameterError, match="already registered"):

        class Again(Plane):
            name = "plane"

    with pytest.raises(ParameterError, match="already registered"):
        register_route("cosserat", "plane", "numerical")(lambda problem: None)


def test_solve_refuses_what_is_not_a_problem_and_lists_the_methods():
    with pytest.raises(ParameterError, match=r"give a Problem\(cell, rheology\)"):
        solve(Plane(eps=0.01))  # type: ignore[arg-type]
    with pytest.raises(ParameterError, match="method must be one of 'numerical'"):
        solve(Problem(Plane(eps=0.01), Cosserat()), method="spectral")
    with pytest.raises(MethodNotAvailableError, match="use one of 'numerical', 'asymptotic'"):
        solve(Problem(Couette(eps=0.01), Cosserat()), method="closed-form")


@pytest.mark.parametrize(
    ("problem", "method"),
    [
        (Problem(Plane(eps=0.05), Cosserat()), "numerical"),
        (Problem(Plane(eps=0.05), MuI()), "numerical"),
        (Problem(VerticalChannel(eps=0.05, B=1.0), MuI()), "closed-form"),
        (Problem(Plane(eps=0.05), NGF()), "numerical"),
    ],
)
def test_every_route_checks_a_given_grid_the_same_way(problem, method):
    """One check of a caller's xi (routes.assemble.given_grid) for every rheology and cell."""
    with pytest.raises(ParameterError, match="strictly increasing"):
        solve(problem, method=method, xi=np.array([0.0, 0.5, 0.4]))
    with pytest.raises(ParameterError, match=r"must lie in \[0, 1\]"):
        solve(problem, method=method, xi=np.array([0.0, 0.5, 1.5]))
    profile = solve(problem, method=method, xi=np.array([0.0, 0.25, 1.0]))
    np.testing.assert_array_equal(profile.xi, [0.0, 0.25, 1.0])


@pytest.mark.parametrize("cell", ["plane", "couette", "channel"])
def test_a_local_rheology_has_no_spin_or_couple_stress(cell):
    """Absent, not zero: omega and m are None, and the exports leave them out."""
    values = {"plane": Plane(eps=0.05), "couette": Couette(eps=0.05), "channel":
              VerticalChannel(eps=0.05)}  # fmt: skip
    for law in (MuI(), NGF()):
        profile = solve(Problem(values[cell], law), points=11)
        assert profile.omega is None and profile.m is None
        assert profile.asymmetry is None and profile.spin_minus_half_vorticity is None
        assert profile.evaluate([0.5]).omega is None
        columns = profile.columns()
        assert not {"omega", "m", "asymmetry", "spin_minus_half_vorticity"} & set(columns)
        assert profile.summary()["wall_omega"] is None
        np.testing.assert_array_equal(profile.sigma_xy, profile.sigma_yx)
    cosserat = solve(Problem(values[cell], Cosserat()), points=11)
    assert {"omega", "m"} <= set(cosserat.columns())
