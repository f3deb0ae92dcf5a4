"""Issue 19, item 1: extreme inputs are refused at a declared bound (with the bound and why), and
answers at the bounds are verified; nothing is silently wrong. The command-line reproducers run
in a separate process; the bounds' numbers are in their declarations' docstrings."""

from __future__ import annotations

import subprocess
import sys
from dataclasses import dataclass
from typing import ClassVar

import numpy as np
import pytest

from cosserat import (
    NGF,
    Cosserat,
    Couette,
    Material,
    MuI,
    Plane,
    Problem,
    VerticalChannel,
    make_problem,
    shear_layer_thickness,
    solve,
)
from cosserat.errors import MethodNotAvailableError, ParameterError
from cosserat.model.cells.base import EPS_MIN
from cosserat.model.cells.channel import B_NU_MIN
from cosserat.model.declare import Constraint, constraints, param, validate
from cosserat.model.rheologies.mui import SPREAD_MIN
from cosserat.routes.asymptotic import AIRY_BC_TOL


def cosserat(*args: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [sys.executable, "-m", "cosserat", *args],
        capture_output=True,
        text=True,
        check=False,
        timeout=300,
    )


# ----------------------------------------------------------------- the declared constraint
@dataclass(frozen=True)
class Span:
    constraints: ClassVar[tuple[Constraint, ...]] = (
        Constraint(("hi", "lo"), "hi - lo >= 1", lambda hi, lo: hi - lo >= 1.0, "room"),
    )
    lo: float = param(0.0, "lower end")
    hi: float | None = param(2.0, "upper end", optional=True)

    def __post_init__(self) -> None:
        validate(self)


def test_the_declarations_say_why_a_bound_is_there():
    eps = Plane.declared()["eps"].to_dict()
    assert eps["bounds"] == "1e-08 <= eps <= 0.5" and "not verified" in eps["reason"]
    assert [c.text for c in constraints(VerticalChannel)] == ["B nu >= 0.0001"]
    assert [c.text for c in constraints(MuI)] == [c.text for c in constraints(NGF)]


def test_a_constraint_ties_two_fields_and_names_the_first():
    assert constraints(Span) == Span.constraints and Span(0.0, 1.0).hi == 1.0
    with pytest.raises(ParameterError) as info:
        Span(0.5, 1.0)
    expected = "hi (upper end) must satisfy hi - lo >= 1 (room); got hi = 1, lo = 0.5"
    assert str(info.value) == expected
    assert Span(5.0, None).hi is None  # a constraint on a None field is not checked
    validate(Span(0.0, 3.0), skip=("hi",))


# ----------------------------------------------------------------- the command line
REFUSED = [
    (["solve", "channel", "--eps", "1e-3", "--B", "1e-200"], "B nu >= 0.0001"),
    (["solve", "channel", "--eps", "1e-3", "--B", "5e-324"], "B nu >= 0.0001"),
    (
        ["solve", "plane", "--eps", "1e-3", "--model", "ngf", "--param", "mu_2=0.38191"],
        "mu_2 - mu_s >= 0.0001",
    ),
    (
        ["solve", "plane", "--eps", "0.04", "--L", "1e200", "--fully-rough", "--B", "0.03"],
        "0.001 <= L <= 10000",
    ),
    (
        ["solve", "plane", "--eps", "1e-3", "--model", "mui", "--param", "I_w=1e-20"],
        "I_w must satisfy I_w >= 1e-07 mu_s I_0/(mu_2 - mu_s) = 4.07e-08",
    ),
    (["solve", "couette", "--eps", "1e-16", "--Ri", "1"], "1e-08 <= eps <= 0.5"),
]


@pytest.mark.parametrize(("args", "needle"), REFUSED)
def test_extreme_inputs_exit_2_with_the_bound(args, needle):
    proc = cosserat(*args)
    assert proc.returncode == 2, proc.stderr
    assert proc.stdout == "" and "Traceback" not in proc.stderr
    assert len(proc.stderr.strip().splitlines()) == 1, proc.stderr
    assert needle in proc.stderr


# ----------------------------------------------------------------- the Python API
@pytest.mark.parametrize(
    ("make", "needle"),
    [
        (lambda: Plane(eps=1e-300), "1e-08 <= eps <= 0.5"),
        (lambda: Material(L=1e-300), "0.001 <= L <= 10000"),
        (lambda: Material(L=1e200), "L = 1e200 overflows"),
        (lambda: NGF(A=1e-300), "0.0001 <= A"),
        (lambda: NGF(mu_2=0.3819 + 1e-5), "mu_2 - mu_s >= 0.0001"),
        (lambda: MuI(mu_2=1e300), "0 < mu_2 < 10 (a friction angle below 84 deg)"),
        (lambda: MuI(mu_2=MuI().mu_s + 1e-5), "mu_2 - mu_s >= 0.0001"),
        (lambda: VerticalChannel(eps=1e-3, B=1e-4, nu=0.5), "B nu >= 0.0001"),
        (lambda: Problem(Plane(eps=1e-3), MuI(I_0=1e9)), "I_w must satisfy I_w >= 1e-07"),
        (lambda: Problem(Plane(eps=1e-3, I_w=1e-15), MuI()), "got 1e-15"),
        (
            lambda: Problem(Plane(eps=1e-3, stress_ratio=MuI().mu_s * (1 + 1e-9)), MuI()),
            "within 1e-07 mu_s of mu_s",
        ),
    ],
)
def test_extreme_values_are_refused_in_python(make, needle):
    with pytest.raises(ParameterError) as info:
        make()
    assert needle in str(info.value)


def test_couette_at_the_smallest_eps_has_the_limiting_thickness():
    """Delta -> 17.6688 as eps -> 0 (the paper); at eps = 1e-16 it was 16.875."""
    profile = solve(make_problem("cosserat", "couette", {"eps": EPS_MIN, "Ri": 1.0}))
    assert shear_layer_thickness(profile) == pytest.approx(17.6688, abs=3e-4)
    assert max(profile.diagnostics.residuals.values()) < 1e-7


def test_the_channel_at_its_smallest_stress_ratio_is_resolved():
    """B = 1e-8 gave residuals of 1e140, B = 1e-200 ran for minutes."""
    profile = solve(Problem(VerticalChannel(eps=1e-3, B=B_NU_MIN, nu=1.0), Cosserat()))
    assert max(profile.diagnostics.residuals.values()) < 1e-7


def test_mui_at_the_slowest_wall_is_still_uniform_shear():
    """Plane shear without gravity: u = xi exactly. At I_w = 1e-15 it was 1.006 at the wall."""
    law = MuI()
    profile = solve(Problem(Plane(eps=1e-3, I_w=law.I_w_min), law))
    assert np.max(np.abs(profile.u - profile.xi)) < 1e-8


def test_ngf_at_the_narrowest_friction_span_solves():
    profile = solve(Problem(Plane(eps=1e-3), NGF(mu_2=NGF().mu_s + SPREAD_MIN)))
    assert max(abs(v) for v in profile.diagnostics.bc_errors.values()) < 1e-9
    assert np.max(np.abs(profile.u - profile.xi)) < 1e-8


def test_the_airy_layer_refuses_where_it_misses_its_slip_condition():
    values = {"eps": 0.015, "Ri": 0.557, "L": 0.6, "K": 1.2, "delta": "fully-rough"}
    problem = make_problem("cosserat", "couette", values)
    with pytest.raises(MethodNotAvailableError) as info:
        solve(problem, method="asymptotic")
    assert "misses the boundary condition u(0) + 1 + eps K omega(0)" in str(info.value)
    assert "by 0.755" in str(info.value) and "method='numerical'" in str(info.value)
    numerical = solve(problem, method="numerical")
    assert max(abs(v) for v in numerical.diagnostics.bc_errors.values()) < 1e-12
    # inside its range the route still answers, its slip error below the tolerance
    fine = solve(
        make_problem("cosserat", "couette", {"eps": 1e-3, "Ri": 1.0, "delta": "fully-rough"}),
        method="asymptotic",
    )
    assert 0.0 < max(abs(v) for v in fine.diagnostics.bc_errors.values()) < AIRY_BC_TOL


def test_the_channel_airy_layer_refuses_where_it_misses_its_slip_condition():
    values = {"eps": 0.015, "L": 0.6, "K": 1.2, "delta": "fully-rough"}
    problem = make_problem("cosserat", "channel", values)
    with pytest.raises(MethodNotAvailableError, match="misses the boundary condition"):
        solve(problem, method="asymptotic")
    fine = solve(
        make_problem("cosserat", "channel", {"eps": 1e-3, "delta": "fully-rough"}),
        method="asymptotic",
    )
    assert 0.0 < max(abs(v) for v in fine.diagnostics.bc_errors.values()) < AIRY_BC_TOL


def test_the_quick_plot_draws_round_off_as_zero():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    rough = solve(make_problem("cosserat", "plane", {"eps": 1e-2, "delta": "fully-rough"}))
    spin = rough.spin_minus_half_vorticity
    assert 0.0 < np.max(np.abs(spin)) < 1e-14  # round-off of an identically zero field
    fig = rough.plot()
    ax = fig.axes[1]
    assert np.all(ax.lines[0].get_xdata() == 0.0)
    assert any("zero to round-off" in t.get_text() for t in ax.texts)
    plt.close(fig)
    real = solve(make_problem("cosserat", "plane", {"eps": 1e-2}))
    fig = real.plot()
    np.testing.assert_array_equal(fig.axes[1].lines[0].get_xdata(), real.spin_minus_half_vorticity)
    assert not fig.axes[1].texts
    plt.close(fig)


def test_couette_cell_still_accepts_the_paper_range():
    Couette(eps=0.5, Ri=1.0)
    Plane(eps=EPS_MIN)
    MuI(mu_2=MuI().mu_s + SPREAD_MIN)
