"""Parameter sensitivity: where a solution stops existing (section "Parameter sensitivity")."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from .. import config
from ..errors import NoSolutionError
from ..model import Problem


@dataclass(frozen=True)
class Bound:
    """An existence bound found by bisection: solutions exist on one side of ``value``."""

    value: float
    tolerance: float
    parameter: str
    solves: int


def has_solution(problem: Problem, **options: Any) -> bool:
    """True if the numerical route finds a real solution (no :class:`NoSolutionError`).

    Examples
    --------
    >>> from cosserat import Cosserat, Couette, Problem, Wall
    >>> from cosserat.analysis.sensitivity import has_solution
    >>> has_solution(Problem(Couette(eps=0.04, Ri=1.0), Cosserat(wall=Wall(delta=20.0))))
    True
    >>> has_solution(Problem(Couette(eps=0.04, Ri=1.0), Cosserat(wall=Wall(delta=5.0))))
    False
    """
    from ..routes import solve

    try:
        solve(problem, check=False, points=3, **options)
    except NoSolutionError:
        return False
    return True


def existence_bound_A(
    problem: Problem, lo: float = -0.999, hi: float = 0.99, tol: float = config.EXISTENCE_BOUND_TOL
) -> Bound:
    """The smallest A (yield-condition a2/a1) with a real solution, by bisection to ``tol``
    (default :data:`cosserat.config.EXISTENCE_BOUND_TOL`) [-].

    The paper: "the shear stress sigma_xy assumes complex values when A < -0.57" (plane shear
    under gravity, fully rough walls, B = 1). Solutions are assumed to exist at ``hi`` and the
    set of admissible A to be an interval reaching ``hi``; if a solution exists at ``lo`` the
    bound is reported as ``lo`` (none found in the range).
    """

    def with_A(a: float) -> Problem:
        return problem.with_values({"A": a})

    solves = 0
    if not has_solution(with_A(hi)):
        raise NoSolutionError(f"no real solution even at A = {hi:g}: no bound to bracket")
    solves += 1
    if has_solution(with_A(lo)):
        return Bound(lo, 0.0, "A", solves + 1)
    solves += 1
    while hi - lo > tol:
        mid = 0.5 * (lo + hi)
        solves += 1
        if has_solution(with_A(mid)):
            hi = mid
        else:
            lo = mid
    return Bound(0.5 * (lo + hi), 0.5 * (hi - lo), "A", solves)
