"""Parameter declarations: each parameter's meaning, unit, default, bounds, fit range, role and
source, written once beside the class that holds it.

A parameter class (a cell, a rheology, a material, a wall) declares its fields with
:func:`param`; everything else reads the declaration through :func:`declarations`:
validation (:func:`validate`), the command line's ``--param`` keys and help, ``cosserat
models``, sweeps, fitting and calibration (search ranges, priors, which parameters a run's
metadata fix), and the docs' parameter tables. Nothing restates a unit or a bound.

Roles (:data:`ROLES`) say what a parameter is to a calibration:

* ``material``: a property of the grains, shared by every run of one material;
* ``wall``: a property of a wall, shared by every run with the same kind of wall;
* ``cell``: the geometry or loading of one run (eps, Ri, B, nu), fixed from its metadata;
* ``drive``: how fast the cell is driven (the wall's inertial number), fixed from metadata;
* ``option``: a modelling choice (a boundary condition, a closure), never fitted.

Examples
--------
>>> from dataclasses import dataclass
>>> from cosserat.model.declare import param, declarations, validate
>>> @dataclass(frozen=True)
... class Grain:
...     phi: float = param(28.5, "friction angle", "deg", bounds=(0.0, 90.0),
...                        fit_range=(10.0, 60.0), role="material")
...     def __post_init__(self):
...         validate(self)
>>> declarations(Grain)["phi"].describe()
'phi [deg]: friction angle'
>>> Grain(95.0)
Traceback (most recent call last):
...
cosserat.errors.ParameterError: phi (friction angle) must satisfy 0 < phi < 90 [deg]; got 95
"""

from __future__ import annotations

import dataclasses
import math
import numbers
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import Any, Literal

from ..errors import ParameterError, shown

Role = Literal["material", "wall", "cell", "drive", "option"]
ROLES: tuple[str, ...] = ("material", "wall", "cell", "drive", "option")
"""What a parameter can be to a calibration (the module docstring says what each means)."""
Scale = Literal["linear", "log"]


class _Required:
    """The type of :data:`REQUIRED`."""

    def __repr__(self) -> str:
        return "REQUIRED"


REQUIRED: Any = _Required()
"""The default of a parameter that has none (it must be given)."""


@dataclass(frozen=True)
class Param:
    """The declaration of one parameter.

    Attributes
    ----------
    name : str
        The field's name (set by :func:`declarations`).
    meaning : str
        One line: what the parameter is, with its symbol.
    unit : str
        Its unit as printed in brackets: ``"deg"``, ``"-"`` for dimensionless.
    default : Any
        The default value, or :data:`REQUIRED`.
    bounds : (float, float)
        The admissible interval [unit]; ``-inf``/``inf`` for none.
    closed : (bool, bool)
        Whether each end of ``bounds`` is admissible (default: both open).
    fit_range : (float, float) or None
        Where a fit or a posterior searches [unit]; None: never fitted (an option, or a
        quantity a run's metadata always give).
    scale : {"linear", "log"}
        How a fit parametrises the range and which prior a posterior puts on it (uniform in
        the value or in its logarithm).
    role : str
        One of :data:`ROLES` (module docstring).
    source : str
        Where the default comes from (a publication, or "the paper").
    reason : str
        Why the bounds are what they are, appended to a validation error.
    choices : tuple of str
        Words accepted besides a number (``"fully-rough"`` for a wall's friction angle).
    optional : bool
        None is a valid value (the default then says what None means).
    key : str
        The name on the command line and in sweep specs when it differs from ``name``.
    numeric : bool
        False for a parameter that takes only one of its ``choices`` (a boundary condition).
    cells : tuple of str
        The cells the parameter applies to (empty: every cell); a wall parameter of the plane
        cell's fixed lower plate, for instance.
    """

    name: str = ""
    meaning: str = ""
    unit: str = "-"
    default: Any = REQUIRED
    bounds: tuple[float, float] = (-math.inf, math.inf)
    closed: tuple[bool, bool] = (False, False)
    fit_range: tuple[float, float] | None = None
    scale: Scale = "linear"
    role: Role = "option"
    source: str = ""
    reason: str = ""
    choices: tuple[str, ...] = ()
    optional: bool = False
    key: str = ""
    numeric: bool = True
    cells: tuple[str, ...] = ()

    def __post_init__(self) -> None:
        if self.role not in ROLES:
            raise ValueError(f"role must be one of {ROLES}; got {self.role!r}")
        lo, hi = self.bounds
        if not lo <= hi:
            raise ValueError(f"{self.name}: bounds {self.bounds} are not ordered")
        if self.fit_range is not None:
            a, b = self.fit_range
            if not (a < b and self.admits(a) and self.admits(b)):
                raise ValueError(
                    f"{self.name}: fit_range {self.fit_range} must be ordered and inside the "
                    f"bounds {self.interval()}"
                )
            if self.scale == "log" and a <= 0.0:
                raise ValueError(f"{self.name}: a log-scaled fit range must be positive")

    @property
    def cli_key(self) -> str:
        """The name on the command line and in sweep specs."""
        return self.key or self.name

    @property
    def has_default(self) -> bool:
        return self.default is not REQUIRED

    @property
    def fittable(self) -> bool:
        return self.fit_range is not None

    def applies_to(self, cell: str) -> bool:
        """True if the parameter applies to the cell named ``cell``."""
        return not self.cells or cell in self.cells

    def admits(self, x: float) -> bool:
        """True if ``x`` lies inside the bounds (ends included where ``closed`` says)."""
        lo, hi = self.bounds
        lo_ok = x >= lo if self.closed[0] else x > lo
        hi_ok = x <= hi if self.closed[1] else x < hi
        return bool(lo_ok and hi_ok)

    def interval(self, name: str | None = None) -> str:
        """The bounds as text, ``0 < eps <= 0.5``; empty if unbounded."""
        n = name or self.cli_key or "x"
        lo, hi = self.bounds
        left = "" if lo == -math.inf else f"{lo:g} {'<=' if self.closed[0] else '<'} "
        right = "" if hi == math.inf else f" {'<=' if self.closed[1] else '<'} {hi:g}"
        return f"{left}{n}{right}" if left or right else ""

    def describe(self) -> str:
        """``key [unit]: meaning`` (one line, for help texts and error lists)."""
        return f"{self.cli_key} [{self.unit}]: {self.meaning}"

    def check(self, value: Any, name: str | None = None) -> Any:
        """``value`` validated: a finite number inside the bounds (returned as a float), one of
        the ``choices``, or None where ``optional``.

        Raises
        ------
        ParameterError
            Naming the parameter, its meaning, the bound and the value received.
        """
        if type(value) is float and self.numeric and math.isfinite(value) and self.admits(value):
            return value  # the common case, without the checks below
        n = name or self.cli_key
        if value is None and self.optional:
            return None
        if isinstance(value, str):
            word = value.strip().lower()
            for choice in self.choices:
                if word == choice or word.replace("_", "-") == choice:
                    return choice
        if not self.numeric:
            raise ParameterError(
                f"{n} ({self.meaning}) must be one of "
                f"{', '.join(repr(c) for c in self.choices)}; got {shown(value)}"
            )
        if isinstance(value, bool) or not isinstance(value, numbers.Real | str):
            raise ParameterError(
                f"{n} ({self.meaning}) must be a number{self._or()}; got {shown(value)}"
            )
        try:
            x = float(value)
        except ValueError:
            raise ParameterError(
                f"{n} ({self.meaning}) must be a number{self._or()}; got {shown(value)}"
            ) from None
        if not math.isfinite(x):
            raise ParameterError(f"{n} ({self.meaning}) must be finite; got {shown(value)}")
        if not self.admits(x):
            unit = f" [{self.unit}]" if self.unit not in ("", "-") else ""
            why = f" ({self.reason})" if self.reason else ""
            raise ParameterError(
                f"{n} ({self.meaning}) must satisfy {self.interval(n)}{unit}{why}; got {x:g}"
            )
        return x

    def _or(self) -> str:
        return "".join(f" or {c!r}" for c in self.choices) + (" or None" if self.optional else "")

    def default_text(self) -> str:
        """The default as help texts show it (``config.text``); "required" if there is none."""
        from ..config import text

        if not self.has_default:
            return "required"
        if isinstance(self.default, bool) or not isinstance(self.default, numbers.Real):
            return str(self.default)
        return text(float(self.default))

    def to_dict(self) -> dict[str, Any]:
        """Plain data (for JSON, ``cosserat models --format json`` and the docs' tables)."""
        return {
            "name": self.cli_key,
            "meaning": self.meaning,
            "unit": self.unit,
            "default": None if not self.has_default else self.default,
            "bounds": self.interval(),
            "reason": self.reason,
            "fit_range": list(self.fit_range) if self.fit_range else None,
            "scale": self.scale,
            "role": self.role,
            "source": self.source,
            "choices": list(self.choices),
            "cells": list(self.cells),
        }


@dataclass(frozen=True)
class Constraint:
    """A declared bound that ties two or more fields of one class (``mu_2 - mu_s >= 1e-3``),
    checked by :func:`validate` after every field's own bounds.

    A class declares its constraints in a class attribute ``constraints`` (a tuple of
    :class:`Constraint`); :func:`constraints` reads them, the docs' parameter tables list them.

    Attributes
    ----------
    names : tuple of str
        The fields the constraint reads (the first is the one the message blames); the
        constraint is skipped while any of them is None.
    text : str
        The bound as users read it, in the fields' command-line keys: ``"mu_2 - mu_s >= 1e-3"``.
    holds : callable
        ``holds(*values)`` (in the order of ``names``): True where the values are admissible.
    reason : str
        Why the bound is what it is (one line, quoted by the error).
    """

    names: tuple[str, ...]
    text: str
    holds: Callable[..., bool]
    reason: str

    def check(self, obj: Any) -> None:
        """Raise :class:`~cosserat.errors.ParameterError` unless the constraint holds on
        ``obj`` (or some field it reads is None)."""
        got = [getattr(obj, n) for n in self.names]
        if any(v is None for v in got) or self.holds(*got):
            return
        keys = _declared(obj)
        pairs = zip(self.names, got, strict=True)
        shown_values = ", ".join(f"{keys[n].cli_key if n in keys else n} = {v:g}" for n, v in pairs)
        first = keys.get(self.names[0])
        what = f"{first.cli_key} ({first.meaning})" if first else self.names[0]
        raise ParameterError(f"{what} must satisfy {self.text} ({self.reason}); got {shown_values}")


def constraints(cls: Any) -> tuple[Constraint, ...]:
    """The :class:`Constraint` s declared by the class ``cls`` (or an instance's class)."""
    klass = cls if isinstance(cls, type) else type(cls)
    return tuple(getattr(klass, "constraints", ()))


_SAME: Any = object()


def param(
    default: Any = REQUIRED,
    meaning: str = "",
    unit: str = "-",
    *,
    field_default: Any = _SAME,
    **spec: Any,
) -> Any:
    """A dataclass field declared with its :class:`Param` (``spec``: its other attributes).

    ``field_default``: the field's own default when it differs from the declared one: None for
    a value the class resolves itself (a wall's inertial number takes its declared default
    unless the wall stress is imposed instead).
    """
    declared = Param(meaning=meaning, unit=unit, default=default, **spec)
    value = default if field_default is _SAME else field_default
    if value is REQUIRED:
        return dataclasses.field(metadata={"param": declared})
    return dataclasses.field(default=value, metadata={"param": declared})


_DECLARED: dict[type, dict[str, Param]] = {}


def _declared(cls: Any) -> dict[str, Param]:
    """:func:`declarations` itself, the cached dict (not to be changed)."""
    klass = cls if isinstance(cls, type) else type(cls)
    found = _DECLARED.get(klass)
    if found is None:
        found = {}
        if dataclasses.is_dataclass(klass):
            for f in dataclasses.fields(klass):
                p = f.metadata.get("param")
                if p is not None:
                    found[f.name] = dataclasses.replace(p, name=f.name)
        _DECLARED[klass] = found
    return found


def declarations(cls: Any) -> dict[str, Param]:
    """Every declared field of the dataclass ``cls`` (or of an instance's class), by field name,
    in field order, each :class:`Param` with its ``name`` set (computed once per class)."""
    return dict(_declared(cls))


def validate(obj: Any, skip: tuple[str, ...] = ()) -> None:
    """Check and normalise every declared field of the frozen dataclass ``obj`` in place
    (:meth:`Param.check`); call it first in ``__post_init__``, then check what ties fields
    together; the class's declared :func:`constraints` are checked last (those that read a
    field in ``skip`` are left to the caller)."""
    for name, p in _declared(obj).items():
        if name in skip:
            continue
        object.__setattr__(obj, name, p.check(getattr(obj, name), name))
    for c in constraints(obj):
        if not any(n in skip for n in c.names):
            c.check(obj)


def values(obj: Any) -> dict[str, Any]:
    """Declared field -> value of ``obj`` (its command-line keys)."""
    return {p.cli_key: getattr(obj, name) for name, p in _declared(obj).items()}


def table(params: Mapping[str, Param]) -> list[dict[str, Any]]:
    """Rows of a parameter table (docs, ``cosserat models``)."""
    return [p.to_dict() for p in params.values()]


__all__ = [
    "REQUIRED",
    "ROLES",
    "Constraint",
    "Param",
    "constraints",
    "declarations",
    "param",
    "table",
    "validate",
    "values",
]
