"""Problems from names: the one builder the command line, sweeps, fitting and calibration use.

``make_problem(model, cell, values)`` makes the :class:`~cosserat.model.problem.Problem` of the
rheology ``model`` on the cell ``cell`` from ``values`` by command-line key (absent keys and None
take the declared defaults; numbers may be given as numeric strings, as read from a file or the
command line; a wall's delta also as "fully-rough"). ``problem_parameters(model, cell)`` lists
the keys with their declarations (meaning, unit, default, bounds, fit range, role); a problem's
``with_values`` changes some of them.

Examples
--------
>>> from cosserat.model.build import make_problem, problem_parameters
>>> problem = make_problem("mui", "couette", {"eps": 0.01, "I_w": "0.05"})
>>> problem.values()["I_w"], problem.values()["Ri"]
(0.05, 1.0)
>>> [k for k, p in problem_parameters("cosserat", "plane").items() if p.role == "wall"]
['delta', 'K', 'delta_lower', 'K_lower']
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from ..errors import ParameterError
from .cells import CELLS, cell_class
from .declare import Param
from .problem import Problem, pair_parameters
from .rheologies import RHEOLOGIES, rheology_class

UNAVAILABLE = ("kinetic",)
"""Models the package names but does not implement (:mod:`cosserat.model.kinetic` says why)."""


def check_pair(model: str, cell: str) -> None:
    """Raise if ``model`` is not a registered rheology, ``cell`` not a registered cell, or the
    rheology has no equations on that cell.

    Raises
    ------
    ParameterError
        Unknown model or cell (listing the registered ones), or a model without this cell
        (listing the cells it has).
    MethodNotAvailableError
        A model the package names but does not implement (the kinetic model: why).
    """
    if model in UNAVAILABLE and model not in RHEOLOGIES:
        from .kinetic import unavailable

        raise unavailable(cell)
    law = rheology_class(model)
    cell_class(cell)
    if not law.supports(cell):
        raise ParameterError(
            f"model {model!r} has no {cell} cell; it supports: {', '.join(law.cells())}"
        )


def problem_parameters(model: str, cell: str) -> dict[str, Param]:
    """Every parameter of ``model`` on ``cell`` by command-line key, with its declaration:
    the rheology's (those that apply to this cell), then the cell's (its drive only for a
    rate-dependent rheology).

    Raises
    ------
    ParameterError, MethodNotAvailableError
        As :func:`check_pair`.
    """
    check_pair(model, cell)
    return pair_parameters(RHEOLOGIES[model], CELLS[cell])


def make_problem(model: str, cell: str, values: Mapping[str, Any] | None = None) -> Problem:
    """The problem of the rheology ``model`` on the cell ``cell`` with the parameters
    ``values`` by command-line key (module docstring).

    Raises
    ------
    ParameterError
        An unknown model or cell, a key this pair does not have (the message lists those it
        has with their units), a required parameter not given (eps), or a value out of its
        bounds (the message names the parameter).
    MethodNotAvailableError
        A model the package names but does not implement.
    NoSolutionError
        A pair that can have no solution (as :class:`~cosserat.model.problem.Problem`).
    """
    if values is not None and not isinstance(values, Mapping):
        raise ParameterError(
            f"the parameters must be a mapping of name to value; got {type(values).__name__}"
        )
    keys = problem_parameters(model, cell)
    given = {k: v for k, v in (values or {}).items() if v is not None}
    unknown = sorted(str(k) for k in given if k not in keys)
    if unknown:
        raise ParameterError(
            f"unknown parameter(s) {', '.join(unknown)} for model {model!r} on the {cell} "
            f"cell; valid: {', '.join(describe_keys(keys))}"
        )
    missing = [k for k, p in keys.items() if not p.has_default and k not in given]
    if missing:
        raise ParameterError(
            f"{', '.join(f'{k} ({keys[k].meaning})' for k in missing)} must be given; "
            "it has no default"
        )
    geometry = CELLS[cell]
    own = geometry.declared()
    names = {p.cli_key: n for n, p in _declarations(geometry).items()}
    cell_kwargs = {names[k]: v for k, v in given.items() if k in own}
    law = RHEOLOGIES[model].from_values({k: v for k, v in given.items() if k not in own})
    return Problem(geometry(**cell_kwargs), law)


def describe_keys(params: Mapping[str, Param]) -> list[str]:
    """``key [unit]`` for each parameter (as error messages and ``--help`` list them)."""
    return [f"{k} [{p.unit}]" for k, p in params.items()]


def _declarations(cls: Any) -> dict[str, Param]:
    from .declare import declarations

    return declarations(cls)


__all__ = [
    "UNAVAILABLE",
    "check_pair",
    "describe_keys",
    "make_problem",
    "problem_parameters",
]
