"""The checked, typed views of a problem's equations and fields (issue 19, item 5: what the
type checker asked for). A route or analysis that serves one rheology says so in a clean
error when given another, instead of an AttributeError deep inside."""

import re

import numpy as np
import pytest

from cosserat import Cosserat, Couette, MuI, Plane, Problem
from cosserat.analysis import thickness_limit
from cosserat.analysis.fitting import natural_value
from cosserat.errors import MethodNotAvailableError, ParameterError
from cosserat.model.rheologies.base import equations_of
from cosserat.model.rheologies.cosserat import (
    CosseratCouette,
    CosseratPlane,
    cosserat_equations,
)
from cosserat.results.profile import Fields

MUI = Problem(Couette(eps=0.01, Ri=1.0, I_w=0.01), MuI())
PLANE = Problem(Plane(eps=0.01), Cosserat())


def test_equations_of_returns_the_pair_it_names() -> None:
    eq = equations_of(PLANE, CosseratPlane)
    assert eq is PLANE.equations


def test_equations_of_another_pair_is_a_clean_error() -> None:
    msg = f"this route needs the CosseratCouette equations; {PLANE.describe()} has CosseratPlane"
    with pytest.raises(MethodNotAvailableError, match=f"^{re.escape(msg)}$"):
        equations_of(PLANE, CosseratCouette)


def test_cosserat_equations_refuse_another_rheology() -> None:
    msg = f"this route solves the Cosserat model; {MUI.describe()} is another rheology"
    with pytest.raises(MethodNotAvailableError, match=f"^{re.escape(msg)}$"):
        cosserat_equations(MUI)
    assert cosserat_equations(PLANE) is PLANE.equations


def test_thickness_limit_of_a_mui_problem_says_why() -> None:
    """Before: AttributeError ('MuIFlow' has no attribute 'slip_constants')."""
    with pytest.raises(MethodNotAvailableError, match="solves the Cosserat model"):
        thickness_limit(MUI)


def test_fitting_a_mui_problem_says_why() -> None:
    """Before: AttributeError ('MuI' has no attribute 'material')."""
    with pytest.raises(
        MethodNotAvailableError,
        match=r"^fitting delta, K, L, phi or A needs the Cosserat model; got the mui rheology$",
    ):
        natural_value(MUI, "delta")
    assert natural_value(PLANE, "L") == PLANE.rheology.material.L


def test_fields_spin_narrows_or_refuses() -> None:
    x = np.linspace(0.0, 1.0, 3)
    full = Fields(x, -x, 2 * x, x, x, x, x, x)
    omega, m = full.spin()
    assert omega is full.omega and m is full.m
    bare = full._replace(omega=None, m=None)
    with pytest.raises(
        ParameterError,
        match=r"^these fields have no grain spin and couple stress \(the law has none\)$",
    ):
        bare.spin()


def test_message_bar_ticks_with_the_message_and_closes() -> None:
    """The CLI's message bar (was a function with a ``close`` attribute set on it)."""
    from cosserat.cli.common import MessageBar

    calls: list[tuple[object, ...]] = []

    class FakeTqdm:
        def set_postfix_str(self, text: str, refresh: bool) -> None:
            calls.append(("postfix", text, refresh))

        def update(self, n: int) -> None:
            calls.append(("update", n))

        def close(self) -> None:
            calls.append(("close",))

    bar = MessageBar(FakeTqdm())
    bar("solving")
    bar.close()
    assert calls == [("postfix", "solving", False), ("update", 1), ("close",)]
