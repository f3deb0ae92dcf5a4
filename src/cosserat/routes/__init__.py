"""Solution routes and the single entry point :func:`solve`."""

from __future__ import annotations

import inspect
from collections.abc import Callable
from dataclasses import replace
from typing import Any

from ..errors import MethodNotAvailableError, ParameterError
from ..model import CouetteFlow, PlaneShear, Problem
from ..results.profile import Profile
from . import asymptotic, closed_form, numerical

_ROUTES: dict[str, dict[type, Callable[..., Profile]]] = {
    "numerical": {PlaneShear: numerical.solve_plane, CouetteFlow: numerical.solve_couette},
    "closed-form": {PlaneShear: closed_form.solve_plane},
    "asymptotic": {PlaneShear: asymptotic.solve_plane, CouetteFlow: asymptotic.solve_couette},
}
METHODS = tuple(_ROUTES)
# routes whose dense evaluator is plain data (it pickles as it is)
_PICKLABLE = {numerical.solve_plane, numerical.solve_couette}


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
        Unknown method or option, or a problem that is neither PlaneShear nor CouetteFlow.
    MethodNotAvailableError
        The route does not exist for this problem (no closed form under gravity or in
        Couette flow; the asymptotics where the layer is not thin), with the route to use.
    NoSolutionError
        The model has no real solution for these parameters.
    ConvergenceError
        The numerical route did not converge (saying where); see ``docs/numerics.md``.
    """
    try:
        routes = _ROUTES[method]
    except KeyError:
        raise ParameterError(
            f"method must be one of {', '.join(repr(m) for m in METHODS)}; got {method!r}"
        ) from None
    if not isinstance(problem, PlaneShear | CouetteFlow):
        raise ParameterError(
            f"cannot solve a {type(problem).__name__}: give a PlaneShear or a CouetteFlow"
        )
    route = routes.get(type(problem))
    if route is None:
        available = [m for m, r in _ROUTES.items() if type(problem) in r]
        raise MethodNotAvailableError(
            f"no {method} route for {type(problem).__name__}: use one of "
            f"{', '.join(repr(m) for m in available)}"
        )
    accepted = [p for p in inspect.signature(route).parameters if p != "problem"]
    unknown = sorted(set(options) - set(accepted))
    if unknown:
        raise ParameterError(
            f"option(s) {', '.join(unknown)} do not apply to method={method!r}; it accepts "
            f"{', '.join(accepted)}"
        )
    profile = route(problem, **options)
    if route not in _PICKLABLE:
        # closures: the profile pickles as its arrays and this recipe (Profile.__getstate__)
        profile = replace(profile, recipe=(route, {k: v for k, v in options.items() if k != "xi"}))
    return profile


__all__ = ["METHODS", "solve"]
