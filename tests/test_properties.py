"""Property-based: over the physical parameter space, every solve gives a finite profile that
satisfies its boundary conditions, or says in words that the model has no real solution."""

from __future__ import annotations

import numpy as np
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from cosserat import Material, NoSolutionError, PlaneShear, Wall, solve

angles = st.floats(min_value=10.0, max_value=50.0)
fractions = st.floats(min_value=0.05, max_value=1.0)


@st.composite
def plane_problems(draw):
    phi = draw(angles)
    mat = Material(phi, L=draw(st.floats(1.0, 40.0)), A=draw(st.floats(-0.9, 0.95)))
    rough = mat.fully_rough_delta

    def wall():
        if draw(st.booleans()) and draw(st.booleans()):
            return Wall.fully_rough(draw(st.floats(0.0, 2.0)))
        return Wall(draw(fractions) * rough, draw(st.floats(0.0, 2.0)))

    return PlaneShear(
        material=mat,
        upper=wall(),
        lower=wall() if draw(st.booleans()) else None,
        eps=10 ** draw(st.floats(-6.0, np.log10(0.5))),
        B=draw(st.sampled_from([0.0, 0.0, 0.1, 1.0, 5.0])),
        nu=draw(st.floats(0.5, 1.0)),
    )


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(problem=plane_problems())
def test_numerical_profiles_are_finite_and_satisfy_their_conditions(problem):
    try:
        prof = solve(problem, points=61)
    except NoSolutionError as exc:
        assert "no real solution" in str(exc)
        assert "xi =" in str(exc)  # says where
        return
    for values in prof.columns().values():
        assert np.all(np.isfinite(values))
    assert max(abs(v) for v in prof.diagnostics.bc_errors.values()) < 1e-7
    assert prof.diagnostics.residuals["velocity"] < 1e-6
    assert np.all(np.diff(prof.u) >= -1e-10)
    assert np.all(prof.omega <= 1e-300)


@settings(max_examples=40, deadline=None)
@given(problem=plane_problems())
def test_closed_form_and_asymptotic_never_return_nan(problem):
    for method in ("closed-form", "asymptotic"):
        try:
            prof = solve(problem, method=method, points=31, check=False)
        except Exception as exc:  # only the package's own, explained errors are allowed
            from cosserat import CosseratError

            assert isinstance(exc, CosseratError), repr(exc)
            continue
        for values in prof.columns().values():
            assert np.all(np.isfinite(values))
