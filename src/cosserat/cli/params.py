"""``--model NAME`` and ``--param KEY=VALUE``: any registered rheology on any of its cells.

Everything here is read from the registry (:data:`cosserat.routes.RHEOLOGIES`: each rheology's
``cells``, cell name -> problem class) and from the problem classes themselves: their dataclass
fields (nested parameter classes such as ``MuI`` or ``Material`` are flattened into their own
fields) and the numpydoc ``Parameters`` section of their docstrings (meaning, unit in
brackets). A rheology or a cell registered later appears on the command line with no edit here.

The Cosserat model on the cells :func:`cosserat.model.build_problem` knows is built by it, with
its command-line names (``phi``, ``delta``, ``K``, ``delta_lower``, ``m_wall``, ...).
"""

from __future__ import annotations

import dataclasses
import inspect
import re
import typing
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

from ..model.build import GEOMETRIES as BUILD_GEOMETRIES
from ..model.build import PARAMETERS as BUILD_PARAMETERS
from ..routes import RHEOLOGIES

DEFAULT_MODEL = "cosserat"
UNAVAILABLE = {"kinetic"}
"""Models issue 11 names that are not implemented (``cosserat.model.kinetic`` says why)."""


class UsageError(Exception):
    """Bad command-line usage, such as a model, cell or parameter that does not exist
    (reported in one line, exit status 2)."""


@dataclass(frozen=True)
class Param:
    """One parameter of a problem class as ``--param`` takes it.

    Attributes
    ----------
    key : str
        Name on the command line (the field's, or ``field.name`` where two nested classes
        share a name).
    path : tuple of str
        Field names from the problem class down to the value.
    meaning : str
        First sentence of the docstring's description.
    unit : str
        The unit in brackets in the docstring ("-" for dimensionless; "" if none given).
    default : Any
        The default, or :data:`dataclasses.MISSING`.
    """

    key: str
    path: tuple[str, ...]
    meaning: str
    unit: str
    default: Any = dataclasses.MISSING

    def describe(self) -> str:
        """``key [unit]`` as an error message lists it."""
        return f"{self.key} [{self.unit}]" if self.unit else self.key


# Units and meanings of the Cosserat model's command-line names (build_problem's names).
COSSERAT_PARAMS: dict[str, tuple[str, str]] = {
    "phi": ("angle of internal friction", "deg"),
    "L": ("yield-condition constant L (material length over grain diameter)", "-"),
    "A": ("yield-condition ratio A = a2/a1", "-"),
    "delta": ("angle of wall friction of the moving wall, or fully-rough", "deg"),
    "K": ("wall slip coefficient of the moving wall", "-"),
    "delta_lower": ("lower wall's angle of wall friction, or fully-rough (plane)", "deg"),
    "K_lower": ("lower wall's slip coefficient (plane)", "-"),
    "B": ("gravity parameter rho_p g H / N (plane, channel)", "-"),
    "nu": ("solids fraction (plane, channel)", "-"),
    "m_wall": ("couple stress at the non-slipping wall (plane)", "-"),
    "Ri": ("inner radius over gap R_i/H (Couette)", "-"),
    "eps": ("grain diameter over gap d_p/H", "-"),
}


def cells() -> dict[str, list[str]]:
    """Every cell of the registry -> the models that have it, cells in registration order."""
    out: dict[str, list[str]] = {}
    for name, rheology in RHEOLOGIES.items():
        for cell in rheology.cells:
            out.setdefault(cell, []).append(name)
    return out


def problem_class(model: str, cell: str) -> type:
    """The problem class of ``model`` on ``cell``.

    Raises
    ------
    UsageError
        Unknown model (listing the registered ones), or a model without this cell (listing
        the cells it supports).
    MethodNotAvailableError
        A model issue 11 names that is not implemented (the kinetic model: why).
    """
    if model in UNAVAILABLE and model not in RHEOLOGIES:
        from ..model.kinetic import unavailable

        raise unavailable(cell)
    if model not in RHEOLOGIES:
        raise UsageError(
            f"--model must be one of {', '.join(RHEOLOGIES)}; got {model!r} "
            "(`cosserat models` lists them)"
        )
    supported = RHEOLOGIES[model].cells
    if cell not in supported:
        raise UsageError(f"model {model!r} has no {cell} cell; it supports: {', '.join(supported)}")
    return supported[cell]


def uses_build_problem(model: str, cell: str) -> bool:
    """True where :func:`cosserat.model.build_problem` builds the problem (the Cosserat model on
    the cells it knows)."""
    return model == DEFAULT_MODEL and cell in BUILD_GEOMETRIES


def doc_parameters(cls: type) -> dict[str, str]:
    """Name -> description from the numpydoc ``Parameters`` section of ``cls``."""
    lines = (inspect.getdoc(cls) or "").splitlines()
    out: dict[str, str] = {}
    section, names = "", []
    for i, line in enumerate(lines):
        nxt = lines[i + 1].strip() if i + 1 < len(lines) else ""
        if line.strip() and nxt and set(nxt) == {"-"} and not line.startswith(" "):
            section, names = line.strip(), []
            continue
        if section != "Parameters" or (line.strip() and set(line.strip()) == {"-"}):
            continue
        if line and not line.startswith(" "):
            names = [n.strip() for n in line.split(" : ")[0].split(",") if n.strip()]
            for n in names:
                out.setdefault(n, "")
        elif line.strip():
            for n in names:
                out[n] = (out[n] + " " + line.strip()).strip()
    return out


def plain_text(description: str) -> str:
    """A docstring description without reStructuredText markup (``x``, :role:`x`), for a
    terminal."""
    text = re.sub(r"``([^`]*)``", r"\1", description)
    return re.sub(r":\w+:`~?([^`]*)`", r"\1", text)


def _meaning_and_unit(description: str) -> tuple[str, str]:
    units = re.findall(r"\[([^\[\]]*)\]", description)
    unit = units[-1] if units else ""
    text = plain_text(description)
    first = re.split(r"(?<=[a-z0-9)])[.;] |, ``|\[", text + " ")[0].strip().rstrip(",.")
    return first, unit


def nested_class(hint: Any) -> type | None:
    """The dataclass among the types of a field's hint (``Wall | None`` -> ``Wall``)."""
    candidates = typing.get_args(hint) or (hint,)
    for c in candidates:
        if isinstance(c, type) and dataclasses.is_dataclass(c):
            return c
    return None


def parameters_of(cls: type) -> dict[str, Param]:
    """Every settable parameter of the problem class ``cls``, by its ``--param`` key.

    Nested dataclass fields (the rheology's constants, a material, a wall) are flattened into
    their own fields; a name that occurs twice is qualified by its field (``upper.delta``).
    """
    leaves: list[Param] = []

    def walk(c: type, prefix: tuple[str, ...]) -> None:
        hints = typing.get_type_hints(c)
        docs = doc_parameters(c)
        for f in dataclasses.fields(c):
            if not f.init:
                continue
            nested = nested_class(hints.get(f.name))
            if nested is not None:
                walk(nested, (*prefix, f.name))
                continue
            meaning, unit = _meaning_and_unit(docs.get(f.name, ""))
            default = f.default
            if default is dataclasses.MISSING and f.default_factory is not dataclasses.MISSING:
                default = f.default_factory()
            leaves.append(Param(f.name, (*prefix, f.name), meaning, unit, default))

    walk(cls, ())
    counts: dict[str, int] = {}
    for p in leaves:
        counts[p.key] = counts.get(p.key, 0) + 1
    out: dict[str, Param] = {}
    for p in leaves:
        key = p.key if counts[p.key] == 1 else ".".join(p.path[-2:])
        out[key] = dataclasses.replace(p, key=key)
    return out


def valid_keys(model: str, cell: str) -> list[str]:
    """``key [unit]`` of every parameter ``--param`` accepts for ``model`` on ``cell``."""
    if uses_build_problem(model, cell):
        from ..model import build

        also = getattr(build, "ALSO_APPLIES_TO", {})
        names = [
            n
            for n in BUILD_PARAMETERS
            if n in COSSERAT_PARAMS
            and (build.APPLIES_TO.get(n, cell) == cell or cell in also.get(n, ()))
        ]
        return [f"{n} [{COSSERAT_PARAMS[n][1]}]" for n in names]
    return [p.describe() for p in parameters_of(problem_class(model, cell)).values()]


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
    """A command-line value as the parameter classes take it: None, a number, or the text."""
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
    valid = valid_keys(model, cell)
    names = {v.split(" [")[0] for v in valid}
    unknown = sorted(k for k in given if k not in names)
    if unknown:
        raise UsageError(
            f"unknown parameter(s) {', '.join(unknown)} for --model {model} on the {cell} cell; "
            f"valid: {', '.join(valid)}"
        )


def build(model: str, cell: str, values: Mapping[str, Any]) -> Any:
    """The problem of ``model`` on ``cell`` from ``--param``-style values (generic path).

    Values not given take the class defaults; nested parameter classes are built from their
    own fields. Validation is the classes' own (a :class:`~cosserat.errors.ParameterError`
    naming the parameter).
    """
    cls = problem_class(model, cell)
    params = parameters_of(cls)
    check_keys(model, cell, values)

    def make(c: type, prefix: tuple[str, ...]) -> Any:
        hints = typing.get_type_hints(c)
        kwargs: dict[str, Any] = {}
        for f in dataclasses.fields(c):
            if not f.init:
                continue
            path = (*prefix, f.name)
            nested = nested_class(hints.get(f.name))
            if nested is not None:
                inner = [p for p in params.values() if p.path[: len(path)] == path]
                if any(p.key in values for p in inner) or f.default is dataclasses.MISSING:
                    kwargs[f.name] = make(nested, path)
                continue
            key = next(p.key for p in params.values() if p.path == path)
            if key in values:
                kwargs[f.name] = convert(values[key])
        return c(**kwargs)

    try:
        return make(cls, ())
    except TypeError:  # a required field without a value
        missing = [
            p.describe()
            for p in params.values()
            if p.default is dataclasses.MISSING and p.key not in values
        ]
        if not missing:
            raise
        raise UsageError(
            f"--model {model} on the {cell} cell needs {', '.join(missing)} (--param KEY=VALUE)"
        ) from None
