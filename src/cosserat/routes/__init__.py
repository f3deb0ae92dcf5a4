"""Solution routes and the single entry point :func:`solve`.

Routes register per (rheology, cell, method) in :mod:`.registry`: the Cosserat model's in
:mod:`.cosserat`, local mu(I)'s in :mod:`.mui`, NGF's in :mod:`.ngf`. :func:`solve` looks the
problem's up; a rheology registered later (a module calling
:func:`~cosserat.routes.registry.register_route`) is solved the same way.
"""

from __future__ import annotations

import functools
import inspect
from collections.abc import Callable
from dataclasses import replace
from typing import Any

from ..errors import MethodNotAvailableError, ParameterError
from ..model import Problem
from ..model.rheologies import RHEOLOGIES
from ..results.profile import Profile
from . import cosserat as _cosserat  # noqa: F401  (registers the Cosserat model's routes)
from . import mui as _mui  # noqa: F401  (registers mu(I)'s)
from . import ngf as _ngf  # noqa: F401  (registers NGF's)
from .registry import (
    PICKLABLE,
    ROUTES,
    cells_for,
    find,
    methods,
    methods_for,
    models_for,
    register_route,
    register_routes,
)

METHODS = methods()
"""The methods of the built-in routes ("numerical", "closed-form", "asymptotic")."""


@functools.cache
def _options(route: Callable[..., Profile]) -> list[str]:
    """The keyword options a route accepts (read once per route)."""
    return [p for p in inspect.signature(route).parameters if p != "problem"]


def solve(problem: Problem, method: str = "numerical", **options: Any) -> Profile:
    """Solve ``problem`` (any rheology on any of its cells) by the route ``method``.

    Parameters
    ----------
    problem : Problem
        A cell and a rheology, ``Problem(cell, rheology)``: the Cosserat model, local mu(I),
        nonlocal fluidity or a rheology registered later, on plane shear, Couette flow, the
        vertical channel or a cell registered later.
    method : str
        A registered method: "numerical" (every built-in rheology on every cell and eps),
        "closed-form" (the Cosserat model in plane shear without gravity; mu(I) in Couette
        flow, the channel and plane shear without gravity), "asymptotic" (the Cosserat model's
        leading order in eps, the paper's Appendix). A bad name lists the valid ones.
    **options
        Every route takes ``points`` (output grid size, default 201) or ``xi`` (an explicit
        grid) and ``check`` (recompute residuals and boundary errors, default True). The
        numerical routes also take ``rtol`` (Cosserat default 1e-8, mu(I) 1e-12), the
        Cosserat ones ``atol``, NGF's ``cells``, ``resolution`` and ``extrapolate``; an option
        a route does not take is an error that lists the ones it does.

    Returns
    -------
    Profile
        The fields across the gap; ``omega`` and ``m`` are None for a rheology without grain
        spin and couple stress (local mu(I), NGF).

    Raises
    ------
    ParameterError
        Not a problem, an unknown method or option.
    MethodNotAvailableError
        The route does not exist for this rheology on this cell (no closed form under
        gravity, the asymptotics where the layer is not thin), with the routes to use.
    NoSolutionError
        The model has no real solution for these parameters.
    ConvergenceError
        The numerical route did not converge (saying where); see ``docs/numerics.md``.

    Examples
    --------
    >>> from cosserat import Cosserat, Plane, Problem, Wall, shear_layer_thickness, solve
    >>> problem = Problem(Plane(eps=0.01), Cosserat(wall=Wall(delta=20.0)))
    >>> profile = solve(problem)
    >>> profile.xi.shape
    (201,)
    >>> closed = solve(problem, method="closed-form", xi=profile.xi)
    >>> bool(abs(closed.u - profile.u).max() < 1e-6)
    True
    >>> round(shear_layer_thickness(closed), 2)
    18.35
    """
    if not isinstance(problem, Problem):
        raise ParameterError(
            f"cannot solve a {type(problem).__name__}: give a Problem(cell, rheology), e.g. "
            "Problem(Plane(eps=0.01), Cosserat())"
        )
    route = find(problem.model, problem.cell_name, method)
    if route is None:
        known = methods()
        if method not in known:
            raise ParameterError(
                f"method must be one of {', '.join(repr(m) for m in known)}; got {method!r}"
            )
        available = methods_for(problem.model, problem.cell_name)
        if not available:
            raise ParameterError(
                f"no route solves the {problem.model} rheology on the {problem.cell_name} "
                f"cell; it has routes on {', '.join(cells_for(problem.model)) or 'no cell'}"
            )
        raise MethodNotAvailableError(
            f"no {method} route for the {problem.model} rheology on the {problem.cell_name} "
            f"cell: use one of {', '.join(repr(m) for m in available)}"
        )
    accepted = _options(route)
    unknown = sorted(set(options) - set(accepted)) if options else []
    if unknown:
        raise ParameterError(
            f"option(s) {', '.join(unknown)} do not apply to method={method!r}; it accepts "
            f"{', '.join(accepted)}"
        )
    profile = route(problem, **options)
    if route not in PICKLABLE:
        # closures: the profile pickles as its arrays and this recipe (Profile.__getstate__)
        profile = replace(profile, recipe=(route, {k: v for k, v in options.items() if k != "xi"}))
    return profile


__all__ = [
    "METHODS",
    "RHEOLOGIES",
    "ROUTES",
    "cells_for",
    "methods",
    "methods_for",
    "models_for",
    "register_route",
    "register_routes",
    "solve",
]
