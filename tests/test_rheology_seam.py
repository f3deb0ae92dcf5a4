"""The cell x rheology seam: a rheology plugs in by registering its problem classes and routes.

A toy rheology (a Newtonian fluid in plane Couette flow: u = xi, no slip) goes through the
same door the Cosserat model does, and the package's entry point, wall quantities and pickling
work on it unchanged.
"""

from __future__ import annotations

import pickle
from dataclasses import dataclass
from typing import Any

import numpy as np
import pytest

from cosserat import Material, ParameterError, Wall, shear_layer_thickness, solve, wall_slip
from cosserat.errors import MethodNotAvailableError
from cosserat.model import Channel, CouetteFlow, PlaneShear
from cosserat.model.mui import MuIChannel, MuIPlaneShear
from cosserat.model.ngf import NGFPlaneShear
from cosserat.model.rheology import Cell, Rheology
from cosserat.results.profile import Diagnostics, Fields, Profile
from cosserat.routes import COSSERAT, RHEOLOGIES, register


@dataclass(frozen=True)
class NewtonianPlane:
    eps: float = 0.01
    slip_wall = 1.0

    def sigma_c(self, xi):
        return np.ones_like(np.asarray(xi, dtype=float))

    def curvature(self, xi):
        return np.zeros_like(np.asarray(xi, dtype=float))

    @staticmethod
    def wall_velocity(xi_wall: float) -> float:
        return 1.0 if xi_wall == 1.0 else 0.0

    def describe(self) -> str:
        return f"toy Newtonian plane Couette flow, eps = {self.eps:g}"

    def parameters(self) -> dict[str, Any]:
        return {"geometry": "plane", "eps": self.eps}


def _linear(xi) -> Fields:
    x = np.asarray(xi, dtype=float)
    one, zero = np.ones_like(x), np.zeros_like(x)
    return Fields(
        u=x, omega=-0.5 * one, m=zero, sigma_xy=-one, sigma_yx=-one, sigma_yy=one,
        du_dxi=one, kappa=zero,
    )  # fmt: skip


def solve_newtonian(problem: NewtonianPlane, *, points: int = 11, check: bool = True) -> Profile:
    xi = np.linspace(0.0, 1.0, points)
    f = _linear(xi)
    return Profile(
        problem=problem,  # type: ignore[arg-type]
        xi=xi,
        **{k: v for k, v in f._asdict().items()},
        slip_wall=1.0,
        reference_velocity=0.0,
        diagnostics=Diagnostics("closed-form", None, None, {}, {}, "u = xi"),
        evaluator=_linear,
    )


TOY = Rheology(
    name="toy-newtonian",
    title="Newtonian fluid (a test of the seam)",
    reference="none",
    cells={"plane": NewtonianPlane},
    routes={"closed-form": {NewtonianPlane: solve_newtonian}},
)


@pytest.fixture(scope="module", autouse=True)
def registered():
    register(TOY)
    yield
    del RHEOLOGIES[TOY.name]


def test_the_cosserat_model_comes_through_the_seam():
    assert RHEOLOGIES["cosserat"] is COSSERAT
    assert COSSERAT.cells == {"plane": PlaneShear, "couette": CouetteFlow, "channel": Channel}
    for cls in COSSERAT.cells.values():
        assert {"sigma_c", "curvature", "wall_velocity", "describe", "parameters"} <= set(dir(cls))


def test_a_registered_rheology_is_solved_by_the_entry_point():
    problem = NewtonianPlane(eps=0.01)
    assert isinstance(problem, Cell)
    profile = solve(problem, method="closed-form")
    np.testing.assert_allclose(profile.u, profile.xi)
    # Delta: u - 0 = 0.05 (1 - 0) at 0.95 of the gap from the moving wall = 95 grains
    assert shear_layer_thickness(profile) == pytest.approx(95.0, rel=1e-10)
    assert wall_slip(profile) == 0.0
    back = pickle.loads(pickle.dumps(profile))
    np.testing.assert_array_equal(back.evaluate([0.3]).u, [0.3])


def test_a_method_the_rheology_lacks_is_refused_with_the_alternatives():
    with pytest.raises(MethodNotAvailableError, match="use one of 'closed-form'"):
        solve(NewtonianPlane(), method="numerical")


def test_a_rheology_cannot_route_a_cell_it_does_not_have():
    with pytest.raises(ParameterError, match="not among its cells"):
        Rheology("bad", "bad", "none", {"plane": PlaneShear}, {"numerical": {CouetteFlow: print}})


def test_names_are_unique():
    with pytest.raises(ParameterError, match="already registered"):
        register(TOY)


@pytest.mark.parametrize(
    ("problem", "method"),
    [
        (PlaneShear(material=Material(), upper=Wall(), eps=0.05), "numerical"),
        (MuIPlaneShear(eps=0.05), "numerical"),
        (MuIChannel(eps=0.05, B=1.0), "closed-form"),
        (NGFPlaneShear(eps=0.05), "numerical"),
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
