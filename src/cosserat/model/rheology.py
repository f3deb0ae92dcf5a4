"""The seam between cells and rheologies (``docs/architecture.md``).

A **cell** is a geometry with its statics and wall conditions: plane shear (with or without
gravity), cylindrical Couette flow, and next the vertical channel. A **rheology** is a
constitutive closure: the frictional Cosserat model now, local mu(I) and nonlocal granular
fluidity next. A cell times a rheology is a one-dimensional boundary-value problem, a
*problem class* (``PlaneShear`` and ``CouetteFlow`` are the Cosserat model on the two cells);
a rheology provides, for each cell it supports, the problem class and its solution routes.

Adding a rheology is one model module (its parameter class and problem classes, the 1-D
equations derived in ``docs/``), one compiled kernel on ``cosserat.numerics.radau`` and one
routes module that builds a :class:`Rheology`, listed once in :mod:`cosserat.routes`.
Nothing else changes: :func:`cosserat.solve`, the profile, the analysis and the command line
work on any registered problem class.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import Any, Protocol, runtime_checkable

from numpy.typing import NDArray

from ..errors import ParameterError


@runtime_checkable
class Cell(Protocol):
    """What every problem class states about its cell: the statics and the wall conditions.

    Coordinates: ``xi`` across the gap from 0 (lower wall, inner cylinder) to 1 [-]; velocities
    over the moving wall's speed [-]; stresses over the cell's stress scale [-]
    (``docs/model.md``).
    """

    eps: float
    """Grain diameter over gap, d_p / H [-]."""

    @property
    def slip_wall(self) -> float:
        """xi of the wall where friction is mobilised (the shear layer's wall) [-]."""
        ...

    def sigma_c(self, xi: NDArray[Any]) -> NDArray[Any]:
        """Mean (normal) stress across the gap, from the momentum balances [-]."""
        ...

    def curvature(self, xi: NDArray[Any]) -> NDArray[Any]:
        """1/(Ri + xi) in Couette flow, 0 in plane shear [-]."""
        ...

    @staticmethod
    def wall_velocity(xi_wall: float) -> float:
        """Velocity of the wall at ``xi_wall`` [-]."""
        ...

    def describe(self) -> str:
        """One line: the cell, the rheology and every parameter."""
        ...

    def parameters(self) -> dict[str, Any]:
        """Plain-data record of every parameter (for JSON and tables)."""
        ...


Route = Callable[..., Any]
"""A solution route: ``route(problem, **options) -> Profile``."""


@dataclass(frozen=True)
class Rheology:
    """A rheology as the package sees it: its cells and, for each, its solution routes.

    Parameters
    ----------
    name : str
        Short name used on the command line (``cosserat``, ``mui``, ``ngf``).
    title : str
        Human-readable name.
    reference : str
        The publication the equations come from.
    cells : mapping of str to type
        Cell name (``plane``, ``couette``, ``channel``) to the problem class of this rheology
        on that cell.
    routes : mapping of str to mapping of type to route
        Method name (``numerical``, ``closed-form``, ``asymptotic``) to the route for each
        problem class that has one.
    picklable : frozenset of routes
        Routes whose profiles carry a plain-data evaluator; the others' profiles pickle with a
        recipe that rebuilds it (:class:`~cosserat.results.profile.Profile`).
    """

    name: str
    title: str
    reference: str
    cells: Mapping[str, type]
    routes: Mapping[str, Mapping[type, Route]]
    picklable: frozenset[Route] = field(default_factory=frozenset)

    def __post_init__(self) -> None:
        known = set(self.cells.values())
        for method, table in self.routes.items():
            stray = [t.__name__ for t in table if t not in known]
            if stray:
                raise ParameterError(
                    f"rheology {self.name!r}: method {method!r} has routes for "
                    f"{', '.join(stray)}, which are not among its cells "
                    f"({', '.join(self.cells)})"
                )
