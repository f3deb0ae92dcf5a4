"""Solution routes and the single entry point :func:`solve`."""

from __future__ import annotations

import functools
import inspect
from collections.abc import Callable
from dataclasses import replace
from typing import Any

from ..errors import MethodNotAvailableError, ParameterError
from ..model import Channel, CouetteFlow, PlaneShear, Problem
from ..model.rheology import Rheology
from ..results.profile import Profile
from . import asymptotic, channel, closed_form, numerical
from .mui import MUI
from .ngf import NGF_RHEOLOGY

COSSERAT = Rheology(
    name="cosserat",
    title="frictional Cosserat model",
    reference=(
        "Mohan, Kesava Rao & Nott, A frictional Cosserat model for the slow shearing of "
        "granular materials, J. Fluid Mech. 457 (2002) 377-409"
    ),
    cells={"plane": PlaneShear, "couette": CouetteFlow, "channel": Channel},
    routes={
        "numerical": {
            PlaneShear: numerical.solve_plane,
            CouetteFlow: numerical.solve_couette,
            Channel: channel.solve_numerical,
        },
        "closed-form": {PlaneShear: closed_form.solve_plane},
        "asymptotic": {
            PlaneShear: asymptotic.solve_plane,
            CouetteFlow: asymptotic.solve_couette,
            Channel: channel.solve_asymptotic,
        },
    },
    picklable=frozenset({numerical.solve_plane, numerical.solve_couette, channel.solve_numerical}),
)
"""The frictional Cosserat model on its two cells, through the seam every rheology uses."""

RHEOLOGIES: dict[str, Rheology] = {}
"""The registered rheologies by name (``"cosserat"``, ``"mui"``, ...); see :func:`register`."""
_ROUTES: dict[str, dict[type, Callable[..., Profile]]] = {}
_PICKLABLE: set[Callable[..., Profile]] = set()


def register(rheology: Rheology) -> None:
    """Make ``rheology``'s problem classes solvable by :func:`solve` (``docs/architecture.md``)."""
    if rheology.name in RHEOLOGIES:
        raise ParameterError(f"a rheology named {rheology.name!r} is already registered")
    RHEOLOGIES[rheology.name] = rheology
    for method, table in rheology.routes.items():
        _ROUTES.setdefault(method, {}).update(table)
    _PICKLABLE.update(rheology.picklable)


register(COSSERAT)
register(MUI)
register(NGF_RHEOLOGY)
METHODS = tuple(_ROUTES)


@functools.cache
def _options(route: Callable[..., Profile]) -> list[str]:
    """The keyword options a route accepts (read once per route)."""
    return [p for p in inspect.signature(route).parameters if p != "problem"]


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

    Examples
    --------
    >>> from cosserat import Material, PlaneShear, Wall, shear_layer_thickness, solve
    >>> problem = PlaneShear(material=Material(), upper=Wall(delta=20.0), eps=0.01)
    >>> profile = solve(problem)
    >>> profile.xi.shape
    (201,)
    >>> closed = solve(problem, method="closed-form", xi=profile.xi)
    >>> bool(abs(closed.u - profile.u).max() < 1e-6)
    True
    >>> round(shear_layer_thickness(closed), 2)
    18.35
    """
    try:
        routes = _ROUTES[method]
    except KeyError:
        raise ParameterError(
            f"method must be one of {', '.join(repr(m) for m in METHODS)}; got {method!r}"
        ) from None
    solvable = {t for table in _ROUTES.values() for t in table}
    if type(problem) not in solvable:
        names = ", ".join(sorted(t.__name__ for t in solvable))
        raise ParameterError(f"cannot solve a {type(problem).__name__}: give one of {names}")
    route = routes.get(type(problem))
    if route is None:
        available = [m for m, r in _ROUTES.items() if type(problem) in r]
        raise MethodNotAvailableError(
            f"no {method} route for {type(problem).__name__}: use one of "
            f"{', '.join(repr(m) for m in available)}"
        )
    accepted = _options(route)
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


__all__ = ["COSSERAT", "METHODS", "MUI", "NGF_RHEOLOGY", "RHEOLOGIES", "register", "solve"]
