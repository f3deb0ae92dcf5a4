"""``--model NAME`` and ``--param KEY=VALUE``: any registered rheology on any of its cells.

Everything here reads the registries (:data:`cosserat.model.rheologies.RHEOLOGIES`,
:data:`cosserat.model.cells.CELLS`, the routes of :mod:`cosserat.routes.registry`) and the
parameter declarations (:func:`cosserat.model.problem_parameters`: the key, its meaning and unit,
its default), and builds problems with the one builder, :func:`cosserat.model.make_problem`. A
rheology or a cell registered later appears on the command line with no edit here.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

from ..errors import ParameterError
from ..model import Problem, make_problem, problem_parameters
from ..model.build import UNAVAILABLE, check_pair, describe_keys
from ..model.declare import Param
from ..routes import RHEOLOGIES, cells_for, models_for

DEFAULT_MODEL = "cosserat"
"""The model of ``--model`` when it is not given."""


class UsageError(Exception):
    """Bad command-line usage, such as a model, cell or parameter that does not exist
    (reported in one line, exit status 2)."""


def cells() -> dict[str, list[str]]:
    """Every registered cell with a route -> the models solvable on it, in registration order."""
    from ..model.cells import CELLS

    out: dict[str, list[str]] = {}
    for cell in CELLS:
        models = models_for(cell)
        if models:
            out[cell] = models
    return out


def check_model(model: str, cell: str) -> None:
    """Raise :class:`UsageError` unless ``model`` is registered and solvable on ``cell``.

    Raises
    ------
    UsageError
        Unknown model (listing the registered ones), or a model without this cell (listing
        the cells it supports).
    MethodNotAvailableError
        A model the package names but does not implement (the kinetic model: why).
    """
    if model not in RHEOLOGIES and model not in UNAVAILABLE:
        raise UsageError(
            f"--model must be one of {', '.join(RHEOLOGIES)}; got {model!r} "
            "(`cosserat models` lists them)"
        )
    try:
        check_pair(model, cell)
    except ParameterError as exc:
        raise UsageError(str(exc)) from None
    if cell not in cells_for(model):
        raise UsageError(
            f"model {model!r} has no {cell} cell; it supports: {', '.join(cells_for(model))}"
        )


def parameters(model: str, cell: str) -> dict[str, Param]:
    """The declared parameters of ``model`` on ``cell`` by ``--param`` key."""
    check_model(model, cell)
    return problem_parameters(model, cell)


def valid_keys(model: str, cell: str) -> list[str]:
    """``key [unit]`` of every parameter ``--param`` accepts for ``model`` on ``cell``."""
    return describe_keys(parameters(model, cell))


def parse_params(items: Sequence[str] | None) -> dict[str, str]:
    """``KEY=VALUE`` strings -> a mapping (text values; later repeats are an error)."""
    out: dict[str, str] = {}
    for item in items or []:
        key, sep, value = item.partition("=")
        key, value = key.strip(), value.strip()
        if not sep or not key or not value:
            raise UsageError(f"--param takes KEY=VALUE; got {item!r}")
        if key in out:
            raise UsageError(f"--param {key} is given twice")
        out[key] = value
    return out


def convert(text: Any) -> Any:
    """A command-line value as the declarations take it: None, a number, or the text."""
    if not isinstance(text, str):
        return text
    if text.lower() in ("none", "null"):
        return None
    try:
        return float(text)
    except ValueError:
        return text


def check_keys(model: str, cell: str, given: Mapping[str, Any]) -> None:
    """Raise :class:`UsageError` for a key ``model`` on ``cell`` does not have."""
    known = parameters(model, cell)
    unknown = sorted(k for k in given if k not in known)
    if unknown:
        raise UsageError(
            f"unknown parameter(s) {', '.join(unknown)} for --model {model} on the {cell} cell; "
            f"valid: {', '.join(describe_keys(known))}"
        )


def build(model: str, cell: str, values: Mapping[str, Any]) -> Problem:
    """The problem of ``model`` on ``cell`` from ``--param``-style values
    (:func:`cosserat.model.make_problem`: absent keys take the declared defaults; validation
    is the declarations', a :class:`~cosserat.errors.ParameterError` naming the parameter).

    Raises
    ------
    UsageError
        A key the pair does not have, or a required parameter not given.
    """
    known = parameters(model, cell)
    check_keys(model, cell, values)
    missing = [
        f"{k} [{p.unit}]" for k, p in known.items() if not p.has_default and values.get(k) is None
    ]
    if missing:
        raise UsageError(
            f"--model {model} on the {cell} cell needs {', '.join(missing)} (--param KEY=VALUE)"
        )
    return make_problem(model, cell, {k: convert(v) for k, v in values.items()})


__all__ = [
    "DEFAULT_MODEL",
    "UsageError",
    "build",
    "cells",
    "check_keys",
    "check_model",
    "convert",
    "parameters",
    "parse_params",
    "valid_keys",
]
