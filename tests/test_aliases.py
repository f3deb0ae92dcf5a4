"""The problem classes of release 0.x, kept for one release: each keeps its signature, warns
with the name of its replacement, and returns the equivalent ``Problem(cell, rheology)``."""

from __future__ import annotations

import re

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
    Wall,
    solve,
)
from cosserat.model import aliases

MAT = Material(phi=30.0)
ALIASES = [
    (
        lambda: aliases.PlaneShear(
            material=MAT, upper=Wall(20.0), lower=Wall(25.0), eps=0.01, B=0.5, nu=0.8
        ),
        Problem(
            Plane(eps=0.01, B=0.5, nu=0.8),
            Cosserat(material=MAT, wall=Wall(20.0), lower=Wall(25.0)),
        ),
        "Problem(Plane(",
    ),
    (
        lambda: aliases.CouetteFlow(material=MAT, wall=Wall(20.0), eps=0.04, Ri=2.0),
        Problem(Couette(eps=0.04, Ri=2.0), Cosserat(material=MAT, wall=Wall(20.0))),
        "Problem(Couette(",
    ),
    (
        lambda: aliases.Channel(material=MAT, wall=Wall(20.0), eps=0.02),
        Problem(VerticalChannel(eps=0.02), Cosserat(material=MAT, wall=Wall(20.0))),
        "Problem(VerticalChannel(",
    ),
    (
        lambda: aliases.MuIPlaneShear(eps=0.01, B=1.0, I_w=0.05),
        Problem(Plane(eps=0.01, B=1.0, I_w=0.05), MuI()),
        "MuI(",
    ),
    (
        lambda: aliases.MuICouetteFlow(rheology=MuI(mu_s=0.4), eps=0.01, Ri=1.0, stress_ratio=0.5),
        Problem(Couette(eps=0.01, Ri=1.0, stress_ratio=0.5), MuI(mu_s=0.4)),
        "Problem(Couette(",
    ),
    (  # its old default B = 1 stays with the alias
        lambda: aliases.MuIChannel(eps=0.01),
        Problem(VerticalChannel(eps=0.01, B=1.0), MuI()),
        "Problem(VerticalChannel(",
    ),
    (
        lambda: aliases.NGFPlaneShear(eps=0.01, fluidity_bc="local"),
        Problem(Plane(eps=0.01), NGF(fluidity_bc="local")),
        "NGF(",
    ),
    (
        lambda: aliases.NGFCouetteFlow(rheology=NGF(A=0.6), eps=0.01, Ri=1.0, I_w=0.02),
        Problem(Couette(eps=0.01, Ri=1.0, I_w=0.02), NGF(A=0.6)),
        "NGF(",
    ),
    (
        lambda: aliases.NGFChannel(eps=0.02, B=2.4, nu=0.5),
        Problem(VerticalChannel(eps=0.02, B=2.4, nu=0.5), NGF()),
        "Problem(VerticalChannel(",
    ),
]


@pytest.mark.parametrize(
    ("make", "expected", "replacement"), ALIASES, ids=[a.__name__ for a in aliases.ALIASES.values()]
)
def test_an_alias_warns_and_returns_the_equivalent_problem(make, expected, replacement):
    with pytest.warns(DeprecationWarning, match=rf"is deprecated .*use .*{re.escape(replacement)}"):
        problem = make()
    assert problem == expected
    assert problem.parameters() == expected.parameters()


def test_the_aliases_are_importable_where_they_were():
    import cosserat
    from cosserat.model import channel, couette, mui, ngf, plane

    assert cosserat.PlaneShear is plane.PlaneShear is aliases.PlaneShear
    assert cosserat.CouetteFlow is couette.CouetteFlow and cosserat.Channel is channel.Channel
    assert mui.MuIPlaneShear is aliases.MuIPlaneShear and mui.MuI is MuI
    assert ngf.NGFChannel is aliases.NGFChannel and ngf.NGF is NGF


def test_an_alias_solves_to_the_same_numbers():
    with pytest.warns(DeprecationWarning):
        old = aliases.PlaneShear(material=MAT, upper=Wall(20.0), eps=0.01)
    new = solve(Problem(Plane(eps=0.01), Cosserat(material=MAT, wall=Wall(20.0))))
    assert (solve(old).u == new.u).all()
