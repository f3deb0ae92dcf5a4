"""Rheologies: the constitutive laws, their parameters declared once, and their equations on
each cell.

A rheology is a frozen dataclass of the law's parameters (declared with
:func:`~cosserat.model.declare.param`: meaning, unit, default, bounds, fit range, role
``material``, ``wall`` or ``option``, source). Put on a cell (:mod:`cosserat.model.cells`) it
makes a :class:`~cosserat.model.problem.Problem`; what is specific to the pair (the Cosserat
plane case selection and slip constants, mu(I)'s stress level, ...) lives in the rheology's
module as an :class:`Equations` helper built for the problem, which reads the cell's statics and
never restates them.

Every rheology class registers itself by its :attr:`Rheology.name` when it is defined
(:data:`RHEOLOGIES`); its solution routes register in :mod:`cosserat.routes` per (rheology,
cell, method). A new rheology is one module here, its routes and, where it needs one, its
compiled kernel (``docs/architecture.md``, "The cell x rheology seam").
"""

from __future__ import annotations

from .base import ANY_CELL, RHEOLOGIES, Equations, Rheology, rheology_class

# The built-in rheologies register themselves on import, in this order.
# isort: off
from .cosserat import Cosserat
from .mui import MuI
from .ngf import NGF
# isort: on

__all__ = [
    "ANY_CELL",
    "NGF",
    "RHEOLOGIES",
    "Cosserat",
    "Equations",
    "MuI",
    "Rheology",
    "rheology_class",
]
