"""Predictions for likelihoods (:func:`cosserat.routes.numerical.predict`, ``predict_many``).

They must be the numbers of ``solve(problem).evaluate(xi)``: the same kernel and the same
compiled field evaluation, without the profile around them.
"""

from __future__ import annotations

import numpy as np
import pytest

from cosserat import (
    ConvergenceError,
    Cosserat,
    Couette,
    Material,
    NoSolutionError,
    ParameterError,
    Plane,
    Problem,
    VerticalChannel,
    Wall,
    solve,
)
from cosserat.routes.numerical import (
    FIELDS,
    PREDICT_FIELDS,
    Prediction,
    predict,
    predict_many,
)


def plane_problem(*, material, upper, lower=None, eps, B=0.0, nu=1.0):  # type: ignore[no-untyped-def]
    """The Cosserat model in plane shear (what plane_problem(...) was)."""
    return Problem(Plane(eps=eps, B=B, nu=nu), Cosserat(material=material, wall=upper, lower=lower))


def couette_problem(*, material, wall, eps, Ri):  # type: ignore[no-untyped-def]
    """The Cosserat model in Couette flow (what couette_problem(...) was)."""
    return Problem(Couette(eps=eps, Ri=Ri), Cosserat(material=material, wall=wall))


MAT = Material(phi=28.5)
W20 = Wall(delta=20.0, K=0.5)
PROBLEMS = [
    plane_problem(material=MAT, upper=W20, lower=W20, eps=0.025),
    plane_problem(material=MAT, upper=W20, lower=Wall.fully_rough(K=0.5), eps=1e-3),
    plane_problem(material=MAT, upper=W20, lower=W20, eps=0.01, B=1.0, nu=1.0),
    plane_problem(material=MAT, upper=Wall.fully_rough(), lower=Wall(15.0), eps=0.05),
    couette_problem(material=MAT, wall=W20, eps=0.04, Ri=1.0),
    couette_problem(material=MAT, wall=Wall(12.0, K=1.0), eps=1e-4, Ri=20.0),
]
NO_SOLUTION = plane_problem(material=MAT, upper=W20, eps=0.1, B=1.0)
RNG = np.random.default_rng(17)


def test_predictions_are_the_profiles_numbers():
    xi = np.concatenate([RNG.uniform(0.0, 1.0, 33), [0.0, 1.0, 0.5]])  # unsorted, walls, centre
    results = predict_many(PROBLEMS, xi, FIELDS)
    assert len(results) == len(PROBLEMS)
    for problem, result in zip(PROBLEMS, results, strict=True):
        assert result.status == "ok" and result.message == ""
        assert list(result.values) == list(FIELDS)
        expected = solve(problem).evaluate(xi)
        for name in FIELDS:
            np.testing.assert_array_equal(result.values[name], getattr(expected, name), name)
        if problem.cell_name == "couette":
            assert result.m_inner == solve(problem).diagnostics.stats["m_inner"]
        else:
            assert result.m_inner is None


def test_one_set_of_points_per_problem_and_the_default_fields():
    sets = [np.sort(RNG.uniform(0.0, 1.0, k)) for k in (20, 1, 40, 7, 25, 30)]
    results = predict_many(PROBLEMS, sets)
    for problem, x, result in zip(PROBLEMS, sets, results, strict=True):
        assert tuple(result.values) == PREDICT_FIELDS
        expected = solve(problem).evaluate(x)
        for name in PREDICT_FIELDS:
            np.testing.assert_array_equal(result.values[name], getattr(expected, name))
    one = predict(PROBLEMS[4], sets[4], ("omega", "u"))
    assert list(one) == ["omega", "u"]
    np.testing.assert_array_equal(one["u"], results[4].values["u"])
    # a plain list of points is one set shared by every problem
    shared = predict_many(PROBLEMS[:2], [0.1, 0.9], "u")
    np.testing.assert_array_equal(shared[1].values["u"], solve(PROBLEMS[1]).evaluate([0.1, 0.9]).u)


def test_a_problem_without_a_solution_says_why_and_has_no_values():
    results = predict_many([PROBLEMS[0], NO_SOLUTION, PROBLEMS[4]], np.linspace(0.0, 1.0, 9))
    assert [r.status for r in results] == ["ok", "no-solution", "ok"]
    bad = results[1]
    assert bad.values is None and bad.m_inner is None
    with pytest.raises(NoSolutionError) as excinfo:
        solve(NO_SOLUTION)
    assert bad.message == str(excinfo.value)
    with pytest.raises(NoSolutionError, match="no real solution"):
        predict(NO_SOLUTION, [0.5])
    edge = plane_problem(material=MAT, upper=Wall(1e-5), eps=1e-3)  # undecidable: an error
    assert predict_many([edge], [0.5])[0].status == "error"
    with pytest.raises(ConvergenceError):
        predict(edge, [0.5])


def test_a_guess_of_the_inner_couple_stress_gives_the_same_prediction():
    problem = PROBLEMS[4]
    xi = np.linspace(0.0, 1.0, 21)
    first = predict_many([problem], xi)[0]
    nearby = couette_problem(material=MAT, wall=Wall(20.5, K=0.5), eps=0.04, Ri=1.0)
    cold = predict_many([nearby], xi)[0]
    warm = predict_many([nearby], xi, m_inner_guesses=[first.m_inner])[0]
    assert abs(warm.m_inner - cold.m_inner) < 1e-8 * abs(cold.m_inner)
    for name in PREDICT_FIELDS:
        scale = np.max(np.abs(cold.values[name]))
        assert np.max(np.abs(warm.values[name] - cold.values[name])) < 1e-7 * scale


@pytest.mark.parametrize(
    "call, match",
    [
        (lambda: predict(PROBLEMS[0], [0.5], ("u", "speed")), "fields must name"),
        (lambda: predict(PROBLEMS[0], [0.5], ()), "fields must name"),
        (lambda: predict(PROBLEMS[0], [0.5, 1.5]), r"in \[0, 1\]"),
        (lambda: predict(PROBLEMS[0], [[0.5, 0.2]]), "1-D"),
        (lambda: predict(PROBLEMS[0], [np.nan]), "finite"),
        (lambda: predict_many(PROBLEMS[:2], [[0.5], [0.2], [0.1]]), "one per problem"),
        (lambda: predict(PROBLEMS[4], [0.5], m_inner_guess=np.inf), "finite"),
        (lambda: predict(PROBLEMS[0], [0.5], rtol=1.0), "rtol"),
        (
            lambda: predict(
                Problem(VerticalChannel(eps=0.02), Cosserat(material=MAT, wall=W20)), [0.5]
            ),
            "solve",
        ),
    ],
)
def test_bad_input_is_a_parameter_error_that_says_what(call, match):
    with pytest.raises(ParameterError, match=match):
        call()


def test_no_problems_no_predictions():
    assert predict_many([], [0.5]) == []
    assert isinstance(predict_many([PROBLEMS[0]], [0.5])[0], Prediction)
