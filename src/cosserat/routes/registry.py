"""The table of solution routes, per (rheology, cell, method).

Each rheology's routes module registers its routes here (SciPy's ``METHODS`` table and py-pde's
solver registry are the models): ``register_route("mui", "plane", "closed-form")`` as a
decorator, or :func:`register_routes` with a table. A route registered for the cell
:data:`~cosserat.model.rheologies.ANY_CELL` (``"*"``) solves the rheology on every cell (it reads
only the cell's statics). :func:`cosserat.routes.solve` looks routes up here; a bad method lists
the valid ones.

A route is ``route(problem, **options) -> Profile``. Its profile pickles with its evaluator when
that is plain data (``picklable=True``, the default); otherwise with a recipe that rebuilds it
(:class:`~cosserat.results.profile.Profile`).
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Mapping
from typing import Any

from ..errors import ParameterError
from ..model.cells import CELLS
from ..model.rheologies import ANY_CELL, RHEOLOGIES

Route = Callable[..., Any]
"""A solution route: ``route(problem, **options) -> Profile``."""

ROUTES: dict[tuple[str, str, str], Route] = {}
"""(rheology name, cell name or ``"*"``, method) -> route."""
PICKLABLE: set[Route] = set()
"""Routes whose profiles carry a plain-data evaluator."""


def register_route(
    rheology: str, cells: str | Iterable[str], method: str, *, picklable: bool = True
) -> Callable[[Route], Route]:
    """A decorator registering a route of ``rheology`` on ``cells`` (a name, ``"*"`` for every
    cell, or several names) for ``method``.

    Raises
    ------
    ParameterError
        A route is already registered for one of these (rheology, cell, method).
    """
    names = (cells,) if isinstance(cells, str) else tuple(cells)

    def add(route: Route) -> Route:
        for cell in names:
            key = (rheology, cell, method)
            if key in ROUTES and ROUTES[key] is not route:
                raise ParameterError(
                    f"a {method} route of the {rheology} rheology on the {cell} cell is already "
                    f"registered ({ROUTES[key].__module__}.{ROUTES[key].__qualname__})"
                )
            ROUTES[key] = route
        if picklable:
            PICKLABLE.add(route)
        return route

    return add


def register_routes(
    rheology: str, table: Mapping[tuple[str, str], Route], picklable: Iterable[Route] = ()
) -> None:
    """Register a table (cell, method) -> route of ``rheology``; the routes in ``picklable``
    keep plain-data evaluators."""
    keep = set(picklable)
    for (cell, method), route in table.items():
        register_route(rheology, cell, method, picklable=route in keep)(route)


def methods() -> tuple[str, ...]:
    """Every method some route is registered for, in registration order."""
    return tuple(dict.fromkeys(m for _, _, m in ROUTES))


def find(model: str, cell: str, method: str) -> Route | None:
    """The route of ``model`` on ``cell`` for ``method`` (one registered for the cell, else
    one for every cell), or None."""
    return ROUTES.get((model, cell, method)) or ROUTES.get((model, ANY_CELL, method))


def methods_for(model: str, cell: str) -> list[str]:
    """The methods with a route for ``model`` on ``cell``."""
    return [m for m in methods() if find(model, cell, m) is not None]


def cells_for(model: str) -> list[str]:
    """The registered cells with at least one route for ``model`` (and equations for it), in
    registration order."""
    law = RHEOLOGIES.get(model)
    return [
        c
        for c in CELLS
        if (law is None or law.supports(c)) and any(find(model, c, m) for m in methods())
    ]


def models_for(cell: str) -> list[str]:
    """The registered rheologies with a route on ``cell``."""
    return [m for m in RHEOLOGIES if cell in cells_for(m)]


__all__ = [
    "PICKLABLE",
    "ROUTES",
    "Route",
    "cells_for",
    "find",
    "methods",
    "methods_for",
    "models_for",
    "register_route",
    "register_routes",
]
