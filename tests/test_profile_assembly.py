"""How the numerical route turns a kernel solution into a profile: the compiled screen of the
profile's checks, the boundary errors computed when read, and what is made once per problem
(the parameter vector, the output grid). Speed itself is measured by benchmarks/bench_speed.py,
never here; these tests pin that the shortcuts change no number, no decision and no message."""

from __future__ import annotations

import dataclasses
import pickle

import numpy as np
import pytest

from cosserat import (
    ConvergenceError,
    Cosserat,
    Couette,
    Material,
    ParameterError,
    Plane,
    Problem,
    Wall,
    config,
    solve,
)
from cosserat.model._cached import cached
from cosserat.model.grids import layered_grid
from cosserat.numerics import cosserat as kernel
from cosserat.results.diagnostics import Deferred
from cosserat.results.profile import PENDING, Diagnostics, Fields, Profile
from cosserat.routes import assemble, numerical
from cosserat.routes.numerical import NumericalSolution, parameter_vector, run_kernel

MAT = Material(28.5)
W20 = Wall(20.0, 0.5)
PROBLEMS = {
    "symmetric": Problem(Plane(eps=0.04), Cosserat(material=MAT, wall=W20)),
    "rough lower wall": Problem(
        Plane(eps=0.01), Cosserat(material=MAT, wall=W20, lower=Wall.fully_rough(K=0.5))
    ),
    "gravity": Problem(Plane(eps=1e-3, B=1.0), Cosserat(material=MAT, wall=W20)),
    "couette": Problem(Couette(eps=0.04, Ri=1.0), Cosserat(material=MAT, wall=W20)),
}
FIELDS = ("u", "omega", "m", "sigma_xy", "sigma_yx", "sigma_yy", "du_dxi", "kappa")


def _same_profile(a, b) -> None:  # type: ignore[no-untyped-def]
    assert np.array_equal(a.xi, b.xi)
    for name in FIELDS:
        assert np.array_equal(getattr(a, name), getattr(b, name)), name


@pytest.mark.parametrize("name", list(PROBLEMS))
def test_screen_is_fields_at_and_clears_a_good_profile(name: str) -> None:
    problem = PROBLEMS[name]
    sol = run_kernel(problem, config.RTOL, config.RTOL * config.ATOL_OVER_RTOL)
    grid = np.linspace(0.0, 1.0, 301)
    args = (grid, sol.params, sol.info, *sol.couple, sol.geometry, *sol.spin)
    out, first, finite = kernel.fields_checked(*args, numerical.SCREEN_SLACK)
    assert np.array_equal(out, kernel.fields_at(*args))
    assert first == -1 and finite
    # a slack no radicand satisfies flags the first point
    _, first, _ = kernel.fields_checked(*args, -1.0)
    assert first == 0


@pytest.mark.parametrize("name", list(PROBLEMS))
def test_fields_of_points_in_any_order_and_across_blocks_are_the_same_numbers(name: str) -> None:
    """The field loop works on blocks of kernel.BLOCK points and searches each point's steps
    from the last point's: shuffled points, and points spanning several blocks, give each
    point the same numbers as one point at a time."""
    problem = PROBLEMS[name]
    sol = run_kernel(problem, config.RTOL, config.RTOL * config.ATOL_OVER_RTOL)
    rest = (sol.params, sol.info, *sol.couple, sol.geometry, *sol.spin)
    grid = np.linspace(0.0, 1.0, 3 * kernel.BLOCK + 17)
    order = np.random.default_rng(3).permutation(grid.size)
    sorted_out = kernel.fields_at(grid, *rest)
    assert np.array_equal(kernel.fields_at(grid[order], *rest), sorted_out[:, order])
    for q in (0, kernel.BLOCK - 1, kernel.BLOCK, grid.size - 1):
        single = kernel.fields_at(grid[q : q + 1], *rest)
        assert np.array_equal(single[:, 0], sorted_out[:, q])


def test_a_flagged_profile_is_checked_in_python_and_unchanged(monkeypatch) -> None:  # type: ignore[no-untyped-def]
    problem = PROBLEMS["gravity"]
    plain = solve(problem)
    calls = []
    check = numerical.check_fields

    def spy(*args, **kwargs):  # type: ignore[no-untyped-def]
        calls.append(args[1])
        return check(*args, **kwargs)

    monkeypatch.setattr(numerical, "check_fields", spy)  # the route calls it by that name
    assert solve(problem).u is not None and calls == []  # cleared by the screen
    monkeypatch.setattr(numerical, "SCREEN_SLACK", -1.0)  # flag every profile
    flagged = solve(problem)
    assert calls == ["numerical"]
    _same_profile(flagged, plain)


def test_a_flagged_non_finite_field_raises_the_python_message(monkeypatch) -> None:  # type: ignore[no-untyped-def]
    problem = PROBLEMS["couette"]
    screen = kernel.fields_checked

    def poisoned(*args):  # type: ignore[no-untyped-def]
        out, first, _ = screen(*args)
        out = out.copy()
        out[kernel.F_U, 3] = np.nan
        return out, first, False

    monkeypatch.setattr(kernel, "fields_checked", poisoned)
    with pytest.raises(ConvergenceError) as err:
        solve(problem)
    assert str(err.value) == (
        f"the numerical solution produced non-finite u for {problem.describe()}"
    )


@pytest.mark.parametrize("name", list(PROBLEMS))
def test_boundary_errors_are_computed_when_read(name: str) -> None:
    problem = PROBLEMS[name]
    profile = solve(problem)
    bc = profile.diagnostics.bc_errors
    assert isinstance(bc, Deferred)
    expected = problem.equations.boundary_errors(profile.evaluator)
    assert dict(bc) == expected and len(expected) >= 4
    assert max(abs(v) for v in bc.values()) < 1e-8
    # pickled as the dict it stands for; the diagnostics' JSON form has it
    again = pickle.loads(pickle.dumps(profile))
    assert type(again.diagnostics.bc_errors) is dict
    assert again.diagnostics.bc_errors == expected
    assert profile.diagnostics.to_dict()["bc_errors"] == expected
    assert solve(problem, check=False).diagnostics.bc_errors == {}


def test_deferred_computes_once() -> None:
    calls = []

    def compute() -> dict[str, float]:
        calls.append(1)
        return {"a": 1.0, "b": -2.0}

    d = Deferred(compute)
    assert calls == []
    assert d["a"] == 1.0 and list(d) == ["a", "b"] and len(d) == 2 and d == {"a": 1.0, "b": -2.0}
    assert calls == [1]
    assert pickle.loads(pickle.dumps(d)) == {"a": 1.0, "b": -2.0}


def test_parameter_vector_is_a_new_array_each_call() -> None:
    problem = PROBLEMS["couette"]
    first = parameter_vector(problem)
    assert np.isnan(first[kernel.P_MU_GUESS])
    kept = first.copy()
    first[:] = 0.0  # a caller's change reaches no other caller
    guessed = parameter_vector(problem, -0.2)
    assert guessed[kernel.P_MU_GUESS] == -0.2
    plain = parameter_vector(problem)
    assert np.array_equal(plain, kept, equal_nan=True)
    assert np.array_equal(np.delete(guessed, kernel.P_MU_GUESS), np.delete(kept, kernel.P_MU_GUESS))


@pytest.mark.parametrize("name", list(PROBLEMS))
def test_output_grid_is_made_once_and_handed_out_as_a_copy(name: str) -> None:
    eq = PROBLEMS[name].equations
    a = assemble.profile_grid(eq, None, None)
    assert np.array_equal(a, eq.output_grid(config.OUTPUT_POINTS))
    a[:] = -1.0
    b = assemble.profile_grid(eq, None, None)
    assert np.array_equal(b, eq.output_grid(config.OUTPUT_POINTS))
    assert np.array_equal(assemble.profile_grid(eq, 57, None), eq.output_grid(57))
    assert np.array_equal(solve(PROBLEMS[name]).xi, eq.output_grid(config.OUTPUT_POINTS))


def _numpy_layered_grid(n, zones, lo=0.0, hi=1.0):  # type: ignore[no-untyped-def]
    """layered_grid as it was written with np.linspace and np.unique."""
    n = max(int(n), 3)
    zones = [(c, w) for c, w in zones if 0.0 < w < 0.5 * (hi - lo)]
    n_zone = n // (2 + 2 * len(zones)) if zones else 0
    parts = [np.linspace(lo, hi, n - n_zone * len(zones))]
    for centre, width in zones:
        a, b = max(lo, centre - width), min(hi, centre + width)
        parts.append(np.linspace(a, b, n_zone))
    grid = np.unique(np.concatenate(parts))
    return grid[(grid >= lo) & (grid <= hi)]


def test_layered_grid_has_numpys_numbers() -> None:
    rng = np.random.default_rng(17)
    for _ in range(500):
        n = int(rng.integers(1, 3000))
        zones = [
            (float(rng.choice([0.0, 0.5, 1.0, rng.uniform()])), float(10 ** rng.uniform(-7, 0)))
            for _ in range(int(rng.integers(0, 4)))
        ]
        lo, hi = (0.0, 1.0) if rng.uniform() < 0.7 else (rng.uniform(-1, 0), rng.uniform(0.5, 2))
        expected = _numpy_layered_grid(n, zones, lo, hi)
        got = layered_grid(n, zones, lo, hi)
        assert got.shape == expected.shape and np.array_equal(got, expected)


@pytest.mark.parametrize("name", list(PROBLEMS))
def test_assembled_profile_is_the_constructors(name: str) -> None:
    """make_profile fills the frozen dataclasses' __dict__ (results.profile.assembled): every
    field is there, and the constructor makes the same object from the same values."""
    profile = solve(PROBLEMS[name])
    fields = {f.name for f in dataclasses.fields(Profile)}
    # the fields' arrays and the diagnostics are made when first read (results.profile.pending)
    pending = {*Fields._fields, "diagnostics"}
    assert set(vars(profile)) == (fields - pending) | {PENDING}
    assert profile.u is vars(profile)["u"] and "diagnostics" not in vars(profile)
    assert profile.diagnostics is vars(profile)["diagnostics"]
    assert set(vars(profile)) == fields
    assert set(vars(profile.diagnostics)) == {f.name for f in dataclasses.fields(Diagnostics)}
    again = Profile(**{k: getattr(profile, k) for k in fields})
    assert vars(again) == vars(profile)
    diag = profile.diagnostics
    assert vars(Diagnostics(**vars(diag))) == vars(diag)
    with pytest.raises(dataclasses.FrozenInstanceError):
        profile.u = profile.u  # type: ignore[misc]
    sol = profile.evaluator
    assert isinstance(sol, NumericalSolution)
    assert set(vars(sol)) == {f.name for f in dataclasses.fields(NumericalSolution)}


def test_plane_normal_stress_of_a_number_has_the_arrays_bits() -> None:
    rng = np.random.default_rng(5)
    for _ in range(300):
        cell = Plane(eps=0.01, B=float(10 ** rng.uniform(-6, 6)), nu=float(rng.uniform(0.3, 1)))
        xs = [0.0, 1.0, 0.5, float(rng.uniform()), 0, 1]
        numbers = [cell.normal_stress(x) for x in xs]
        assert all(isinstance(v, float) for v in numbers)
        assert np.array_equal(numbers, cell.normal_stress(np.array(xs, dtype=float)))


def test_a_given_grid_with_nan_is_refused() -> None:
    with pytest.raises(ParameterError, match="strictly increasing"):
        assemble.given_grid(np.array([0.0, np.nan, 1.0]))
    with pytest.raises(ParameterError, match="strictly increasing"):
        assemble.given_grid(np.array([0.0, 0.5, 0.5, 1.0]))
    grid = np.linspace(0.0, 1.0, 11)
    assert np.array_equal(assemble.given_grid(grid), grid)


def test_cached_property_computes_once_per_instance() -> None:
    calls = []

    class Thing:
        def __init__(self, x: float) -> None:
            self.x = x

        @cached
        def double(self) -> float:
            """Twice x."""
            calls.append(self.x)
            return 2.0 * self.x

    a, b = Thing(1.0), Thing(3.0)
    assert (a.double, a.double, b.double) == (2.0, 2.0, 6.0) and calls == [1.0, 3.0]
    assert isinstance(Thing.double, cached) and Thing.double.__doc__ == "Twice x."
    eq = PROBLEMS["rough lower wall"].equations
    assert eq.case is eq.case and eq.slip_constants is eq.slip_constants


@pytest.mark.parametrize("name", ["symmetric", "couette"])
def test_fields_made_on_first_read_behave_as_given(name: str) -> None:
    """A numerical profile's field arrays and diagnostics wait for their first read
    (results.profile.pending): pickling, copying and dataclasses.replace see them filled, an
    unknown name is still an AttributeError, and reading one group leaves the other pending."""
    problem = PROBLEMS[name]
    fresh = solve(problem)
    plain = solve(problem)
    expected = {k: getattr(plain, k) for k in FIELDS}
    again = pickle.loads(pickle.dumps(fresh))
    assert PENDING not in vars(fresh) and PENDING not in vars(again)
    _same_profile(again, plain)
    assert again.diagnostics.to_dict() == plain.diagnostics.to_dict()
    other = solve(problem)
    with pytest.raises(AttributeError, match="has no attribute 'spin_rate'"):
        other.spin_rate  # type: ignore[attr-defined]  # noqa: B018
    assert not hasattr(other, "nothing") and PENDING in vars(other)
    replaced = dataclasses.replace(other, recipe=None)
    _same_profile(replaced, plain)
    assert all(np.array_equal(getattr(replaced, k), v) for k, v in expected.items())
    third = solve(problem, check=False)
    assert third.m is not None and PENDING in vars(third)
    assert third.diagnostics.residuals == {} and PENDING not in vars(third)
