"""Solution routes and the single entry point :func:`solve`."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from ..errors import ParameterError
from ..problems import CouetteFlow, PlaneShear, Problem
from ..profile import Profile
from . import asymptotic, closed_form, numerical

_ROUTES: dict[str, dict[type, Callable[..., Profile]]] = {
    "numerical": {PlaneShear: numerical.solve_plane, CouetteFlow: numerical.solve_couette},
    "closed-form": {PlaneShear: closed_form.solve_plane},
    "asymptotic": {PlaneShear: asymptotic.solve_plane, CouetteFlow: asymptotic.solve_couette},
}
METHODS = tuple(_ROUTES)


def solve(problem: Problem, method: str = "numerical", **options: Any) -> Profile:
    """Solve ``problem`` by the route ``method``.

    Parameters
    ----------
    problem : PlaneShear or CouetteFlow
    method : {"numerical", "closed-form", "asymptotic"}
        "numerical" works for every problem and eps; "closed-form" exists for plane shear
        without gravity; "asymptotic" is the leading order in eps of the paper's Appendix.
    **options
        ``points`` (output grid size, default 201) or ``xi`` (explicit grid); ``check``
        (compute residuals and boundary errors, default True); for "numerical" also ``rtol``
        (default 1e-8) and ``atol``.

    Returns
    -------
    Profile

    Raises
    ------
    ParameterError
        Unknown method.
    MethodNotAvailableError
        The route does not exist for this problem (e.g. no closed form under gravity).
    NoSolutionError
        The model has no real solution for these parameters.
    """
    try:
        routes = _ROUTES[method]
    except KeyError:
        raise ParameterError(
            f"method must be one of {', '.join(repr(m) for m in METHODS)}; got {method!r}"
        ) from None
    route = routes.get(type(problem))
    if route is None:
        raise ParameterError(f"cannot solve a {type(problem).__name__}")
    return route(problem, **options)


__all__ = ["METHODS", "solve"]
