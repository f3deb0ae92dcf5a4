"""The base of every rheology (:class:`Rheology`), the registry it fills (:data:`RHEOLOGIES`)
and the per-pair helper (:class:`Equations`); the package docstring
(:mod:`cosserat.model.rheologies`) says what a rheology states."""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, ClassVar, TypeVar

from ...errors import MethodNotAvailableError, ParameterError
from ..constitutive import FloatArray
from ..declare import Param, declarations

if TYPE_CHECKING:
    from ..cells import Cell
    from ..problem import Problem

RHEOLOGIES: dict[str, type[Rheology]] = {}
"""Every rheology class by its name (``"cosserat"``, ``"mui"``, ``"ngf"``, ...), in the order
they were defined; a subclass of :class:`Rheology` with a ``name`` adds itself when it is
defined."""

ANY_CELL = "*"
"""Key of :attr:`Rheology.equations` for a helper that works on every cell's statics."""


class Equations:
    """The equations of one rheology on one cell: the per-pair helper a problem carries
    (``problem.equations``). It reads the cell's statics (``self.cell``) and the law's
    parameters (``self.law``); subclasses add what the pair needs and validate the pair in
    :meth:`validate` (called once, when the problem is made).
    """

    def __init__(self, problem: Problem) -> None:
        self.problem = problem
        self.cell: Any = problem.cell
        self.law: Any = problem.rheology

    def validate(self) -> None:
        """Check what ties the cell and the law together (raise ParameterError or
        NoSolutionError); the default checks nothing."""

    # ----------------------------------------------------------------- what every pair has
    @property
    def eps(self) -> float:
        return float(self.cell.eps)

    @property
    def slip_wall(self) -> float:
        """xi of the wall the shear layer is measured from [-]."""
        return float(self.cell.layer_wall)

    @property
    def reference_velocity(self) -> float:
        """u_0 of ``eqn-delta_defn`` [-]."""
        return float(self.cell.reference_velocity)

    def wall_velocity(self, xi_wall: float) -> float:
        return self.cell.wall_velocity(xi_wall)

    def slip_sign(self, xi_wall: float) -> float:
        return self.cell.slip_sign(xi_wall)

    def sigma_c(self, xi: FloatArray | float) -> FloatArray:
        """The normal stress across the gap (the cell's statics) [-]."""
        return self.cell.normal_stress(xi)

    def curvature(self, xi: FloatArray) -> FloatArray:
        return self.cell.curvature(xi)

    def describe(self) -> str:
        return f"{self.cell.title}, {self.law.name}: {self.law.describe()}; {self.cell.describe()}"

    def parameters(self) -> dict[str, Any]:
        out: dict[str, Any] = {"geometry": self.cell.name, "rheology": self.law.name}
        out.update(self.law.values())
        out.update(self.problem.cell_values())
        return out


@dataclass(frozen=True)
class Rheology:
    """Base of every rheology (module docstring).

    Class attributes say what the package needs to know besides the parameters: the name,
    title and reference, whether the law reads the cell's drive (:attr:`rate_dependent`),
    whether it has a grain spin and couple stress of its own (:attr:`couple_stresses`), the
    parameters a fit frees by default (:attr:`default_free`), and its :class:`Equations`
    helper for each cell (:attr:`equations`, :data:`ANY_CELL` for one that reads any cell's
    statics).
    """

    name: ClassVar[str] = ""
    """The rheology's name on the command line and in the registry."""
    title: ClassVar[str] = ""
    reference: ClassVar[str] = ""
    rate_dependent: ClassVar[bool] = True
    """True if the law reads the cell's drive (I_w or an imposed stress); a rate-independent
    law refuses a cell with a drive given."""
    couple_stresses: ClassVar[bool] = False
    """True if the law has a grain spin and couple stress of its own (profiles carry omega and
    m); False: they are absent (None)."""
    default_free: ClassVar[tuple[str, ...]] = ()
    """The parameters a fit frees by default."""
    equations: ClassVar[Mapping[str, type[Equations]]] = {}
    """Cell name (or :data:`ANY_CELL`) -> the pair's :class:`Equations` helper."""

    def __init_subclass__(cls, **kwargs: Any) -> None:
        super().__init_subclass__(**kwargs)
        name = cls.__dict__.get("name", "")
        if not name:
            return
        known = RHEOLOGIES.get(name)
        if known is not None and known.__qualname__ != cls.__qualname__:
            raise ParameterError(
                f"a rheology named {name!r} is already registered ({known.__module__}."
                f"{known.__qualname__})"
            )
        RHEOLOGIES[name] = cls

    # ----------------------------------------------------------------- declarations
    @classmethod
    def declared(cls, cell: str | None = None) -> dict[str, Param]:
        """Every declared parameter by its command-line key (those that apply to the cell
        named ``cell``, if given)."""
        out = {p.cli_key: p for p in declarations(cls).values()}
        return {k: p for k, p in out.items() if cell is None or p.applies_to(cell)}

    def values(self) -> dict[str, Any]:
        """Declared key -> value."""
        return {p.cli_key: getattr(self, n) for n, p in declarations(self).items()}

    @classmethod
    def from_values(cls, values: Mapping[str, Any]) -> Rheology:
        """The rheology with the parameters ``values`` (by key; absent or None: declared
        defaults), validated."""
        by_key = {p.cli_key: n for n, p in declarations(cls).items()}
        unknown = sorted(k for k in values if k not in by_key)
        if unknown:
            raise ParameterError(
                f"unknown parameter(s) {', '.join(unknown)} of the {cls.name} rheology; it has "
                f"{', '.join(by_key)}"
            )
        return cls(**{by_key[k]: v for k, v in values.items() if v is not None})

    def with_values(self, values: Mapping[str, Any]) -> Rheology:
        """A copy with the parameters ``values`` replaced (by key), validated again."""
        by_key = {p.cli_key: n for n, p in declarations(self).items()}
        unknown = sorted(k for k in values if k not in by_key)
        if unknown:
            raise ParameterError(
                f"unknown parameter(s) {', '.join(unknown)} of the {self.name} rheology; it "
                f"has {', '.join(by_key)}"
            )
        return dataclasses.replace(self, **{by_key[k]: v for k, v in values.items()})

    # ----------------------------------------------------------------- cells
    @classmethod
    def supports(cls, cell: str) -> bool:
        """True if the law has equations on the cell named ``cell``."""
        return ANY_CELL in cls.equations or cell in cls.equations

    @classmethod
    def cells(cls) -> list[str]:
        """The registered cells the law has equations on, in registration order."""
        from ..cells import CELLS

        return [c for c in CELLS if cls.supports(c)]

    def equations_for(self, problem: Problem) -> Equations:
        """The :class:`Equations` helper of this law on ``problem``'s cell.

        Raises
        ------
        ParameterError
            The law has no equations on this cell (the message lists the cells it has).
        """
        cell: Cell = problem.cell
        helper = self.equations.get(cell.name) or self.equations.get(ANY_CELL)
        if helper is None:
            raise ParameterError(
                f"the {self.name} rheology has no equations on the {cell.name} cell; it has "
                f"{', '.join(self.cells()) or 'none'}"
            )
        return helper(problem)

    def describe(self) -> str:
        """The law's parameters in one line."""
        return ", ".join(f"{k} = {_text(v)}" for k, v in self.values().items() if v is not None)


def _text(value: Any) -> str:
    return f"{value:.6g}" if isinstance(value, float) else str(value)


_E = TypeVar("_E", bound="Equations")


def equations_of(problem: Problem, kind: type[_E]) -> _E:
    """``problem.equations``, checked to be a ``kind`` (the typed view of them a route that
    serves one rheology on one cell needs).

    Raises
    ------
    MethodNotAvailableError
        The problem's equations are another pair's (the message names both).
    """
    eq = problem.equations
    if not isinstance(eq, kind):
        raise MethodNotAvailableError(
            f"this route needs the {kind.__name__} equations; {problem.describe()} has "
            f"{type(eq).__name__}"
        )
    return eq


def rheology_class(name: str) -> type[Rheology]:
    """The registered rheology class called ``name``.

    Raises
    ------
    ParameterError
        No such rheology (the message lists the registered ones).
    """
    try:
        return RHEOLOGIES[name]
    except (KeyError, TypeError):
        raise ParameterError(
            f"model must be one of {', '.join(RHEOLOGIES)}; got {name!r}"
        ) from None
