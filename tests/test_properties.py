"""Property-based: over the physical parameter space, every solve gives a finite profile that
satisfies its boundary conditions, or says in words why not (no NaN, no unexplained error)."""

from __future__ import annotations

import numpy as np
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from cosserat import (
    ConvergenceError,
    Cosserat,
    Couette,
    Material,
    MethodNotAvailableError,
    NoSolutionError,
    Plane,
    Problem,
    Wall,
    solve,
)
from cosserat.routes.numerical import DEFAULT_RTOL

fractions = st.floats(min_value=0.01, max_value=1.0)
log_eps = st.floats(-6.0, float(np.log10(0.5)))


@st.composite
def materials(draw):
    return Material(
        draw(st.floats(5.0, 60.0)), L=draw(st.floats(0.5, 100.0)), A=draw(st.floats(-0.99, 0.99))
    )


@st.composite
def walls(draw, mat):
    K = draw(st.floats(0.0, 5.0))
    if draw(st.integers(0, 3)) == 0:
        return Wall.fully_rough(K)
    return Wall(draw(fractions) * mat.fully_rough_delta, K)


@st.composite
def plane_problems(draw):
    mat = draw(materials())
    return Problem(
        Plane(
            eps=10 ** draw(log_eps),
            B=draw(st.sampled_from([0.0, 0.0, 0.1, 1.0, 5.0, 100.0])),
            nu=draw(st.floats(0.5, 1.0)),
        ),
        Cosserat(
            material=mat,
            wall=draw(walls(mat)),
            lower=draw(walls(mat)) if draw(st.booleans()) else None,
        ),
    )


@st.composite
def couette_problems(draw):
    mat = draw(materials())
    return Problem(
        Couette(eps=10 ** draw(log_eps), Ri=10 ** draw(st.floats(-3.0, 6.0))),
        Cosserat(material=mat, wall=draw(walls(mat))),
    )


def explained(exc: Exception) -> bool:
    """The two ways a valid problem may legitimately fail, each saying why in words."""
    if isinstance(exc, NoSolutionError):
        return "no real solution" in str(exc)
    if isinstance(exc, ConvergenceError):
        return "yield bound" in str(exc)  # a singular start on the yield bound (edge of domain)
    return False


def numerical_or_explained(problem, **options):  # type: ignore[no-untyped-def]
    """The numerical profile, or None when the solver said in words why there is none."""
    try:
        return solve(problem, **options)
    except (NoSolutionError, ConvergenceError) as exc:
        assert explained(exc), repr(exc)
        return None


def check_profile(prof) -> None:  # type: ignore[no-untyped-def]
    for values in prof.columns().values():
        assert np.all(np.isfinite(values))
    assert max(abs(v) for v in prof.diagnostics.bc_errors.values()) < 1e-7
    assert prof.diagnostics.residuals["velocity"] < 1e-6
    assert np.all(np.abs(np.diff(prof.u)) <= np.abs(prof.u[-1] - prof.u[0]) + 1e-12)
    # Velocity is monotone across the gap; the solver integrates to DEFAULT_RTOL, so a wiggle
    # in the decayed tail may be as large as the integration error and no larger.
    assert np.all(np.diff(prof.u) >= -DEFAULT_RTOL * np.abs(prof.u[-1] - prof.u[0]))


@settings(max_examples=30, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(problem=plane_problems())
def test_plane_numerical_profiles_are_finite_and_satisfy_their_conditions(problem):
    prof = numerical_or_explained(problem, points=61)
    if prof is not None:
        check_profile(prof)


@settings(max_examples=20, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(problem=plane_problems())
def test_closed_form_agrees_with_numerical_and_asymptotic_never_returns_nan(problem):
    rtol = 1e-8
    num = numerical_or_explained(problem, points=41, check=False, rtol=rtol)
    try:
        cf = solve(problem, method="closed-form", points=41, check=False)
    except MethodNotAvailableError:
        assert problem.equations.B > 0 or problem.equations.m_fixed_wall is not None
    else:
        for values in cf.columns().values():
            assert np.all(np.isfinite(values))
        if num is not None:
            ref = cf.evaluate(num.xi)
            assert np.max(np.abs(num.u - ref.u)) < 10 * rtol + 1e-12
    try:
        asym = solve(problem, method="asymptotic", points=41, check=False)
    except MethodNotAvailableError as exc:
        assert "numerical" in str(exc)  # says what to do instead
    else:
        for values in asym.columns().values():
            assert np.all(np.isfinite(values))


@settings(max_examples=15, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(problem=couette_problems())
def test_couette_profiles_are_finite_and_satisfy_their_conditions(problem):
    prof = numerical_or_explained(problem, points=61)
    if prof is not None:
        check_profile(prof)
