"""A problem is a cell and a rheology: ``Problem(cell, rheology)``.

Composed at the call, as scikit-fem's ``CellBasis(mesh, element)``: the cell
(:mod:`cosserat.model.cells`) states the geometry, statics and wall kinematics, the rheology
(:mod:`cosserat.model.rheologies`) the law; the pair's own equations (which wall slips, the
stress level, ...) are the rheology's :class:`~cosserat.model.rheologies.Equations` helper,
``problem.equations``, built and validated once when the problem is made.

Examples
--------
>>> from cosserat import Cosserat, Couette, MuI, Plane, Problem, Wall, solve
>>> problem = Problem(Plane(eps=0.01), Cosserat(wall=Wall(delta=20.0)))
>>> problem.equations.case
<PlaneShearCase.SYMMETRIC: 'symmetric'>
>>> problem.with_values({"eps": 0.02, "delta": 25.0}).values()["delta"]
25.0
>>> Problem(Couette(eps=0.01, Ri=2.0, I_w=0.05), MuI()).describe()[:24]
'Couette flow, mu(I): mu_'
"""

from __future__ import annotations

import functools
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

from ..errors import ParameterError
from .cells import Cell
from .declare import Param, declarations
from .rheologies import Equations, Rheology


@dataclass(frozen=True)
class Problem:
    """One rheology on one cell: the one problem type every route, analysis and front end
    takes.

    Parameters
    ----------
    cell : Cell
        The experiment's geometry, statics and wall kinematics
        (:class:`~cosserat.model.cells.plane.Plane`, ...).
    rheology : Rheology
        The constitutive law and its parameters
        (:class:`~cosserat.model.rheologies.cosserat.Cosserat`, ...).

    Raises
    ------
    ParameterError
        Not a cell and a rheology, a law without equations on this cell, a parameter that
        does not apply to this pair (the drive of a rate-independent law, a plane-only wall on
        another cell), or a bound that ties the two (the message names the parameter).
    NoSolutionError
        A pair that can have no solution (a channel whose wall friction cannot carry the
        weight).
    """

    cell: Cell
    rheology: Rheology

    def __post_init__(self) -> None:
        if not isinstance(self.cell, Cell):
            raise ParameterError(
                f"cell must be a Cell (Plane, Couette, VerticalChannel, ...); got "
                f"{type(self.cell).__name__}"
            )
        if not isinstance(self.rheology, Rheology):
            raise ParameterError(
                f"rheology must be a Rheology (Cosserat, MuI, NGF, ...); got "
                f"{type(self.rheology).__name__}"
            )
        cell, law = self.cell, self.rheology
        if not law.rate_dependent:
            # type[...] ignores below: mypy checks a class object against Hashable with the
            # instances' __hash__ (a false positive; classes hash by identity)
            for name, p in _drives(type(cell)):  # type: ignore[arg-type]
                if getattr(cell, name) is not None:
                    raise ParameterError(
                        f"{p.cli_key} ({p.meaning.split(';')[0]}) does not apply to the "
                        f"{law.name} rheology, which is rate-independent: it has no drive"
                    )
        elsewhere = _elsewhere(type(law), cell.name)  # type: ignore[arg-type]
        if elsewhere:
            given = law.values()
            for key, p in elsewhere.items():
                if given[key] is not None:
                    raise ParameterError(
                        f"{key} applies to the {' and '.join(p.cells)} cell only; got {key} = "
                        f"{given[key]!r} on the {cell.name} cell"
                    )
        self.equations.validate()

    def __getstate__(self) -> dict[str, Any]:
        """The cell and the rheology (the equations helper is rebuilt on first use)."""
        return {k: v for k, v in self.__dict__.items() if k != "_equations"}

    def __setstate__(self, state: dict[str, Any]) -> None:
        self.__dict__.update(state)

    @property
    def equations(self) -> Equations:
        """The pair's equations (the rheology's helper for this cell), built once."""
        eq = self.__dict__.get("_equations")
        if eq is None:
            eq = self.rheology.equations_for(self)
            object.__setattr__(self, "_equations", eq)
        return eq

    # ----------------------------------------------------------------- names and values
    @property
    def model(self) -> str:
        """The rheology's name (``"cosserat"``, ``"mui"``, ...)."""
        return self.rheology.name

    @property
    def cell_name(self) -> str:
        """The cell's name (``"plane"``, ``"couette"``, ``"channel"``, ...)."""
        return self.cell.name

    @property
    def eps(self) -> float:
        """Grain diameter over gap, d_p/H [-]."""
        return float(self.cell.eps)

    def declared(self) -> dict[str, Param]:
        """Every parameter of this problem by its command-line key, with its declaration
        (:func:`pair_parameters`)."""
        return pair_parameters(type(self.rheology), type(self.cell))

    def cell_values(self) -> dict[str, Any]:
        """The cell's parameters this rheology reads, by key (I_w resolved to its default
        when it drives the flow)."""
        keys = self.declared()
        out = {k: v for k, v in self.cell.values().items() if k in keys}
        if "I_w" in out:
            out["I_w"] = self.cell.wall_inertial_number
        return out

    def values(self) -> dict[str, Any]:
        """Every parameter by its command-line key: the rheology's, then the cell's."""
        keys = self.declared()
        out = {k: v for k, v in self.rheology.values().items() if k in keys}
        out.update({k: v for k, v in self.cell.values().items() if k in keys})
        return out

    def with_values(self, values: Mapping[str, Any]) -> Problem:
        """A copy with the parameters ``values`` (by command-line key) replaced, validated
        again.

        Raises
        ------
        ParameterError
            A key this problem does not have (the message lists those it has), or a value out
            of its bounds.
        """
        keys = self.declared()
        unknown = sorted(k for k in values if k not in keys)
        if unknown:
            raise ParameterError(
                f"unknown parameter(s) {', '.join(unknown)} for the {self.model} rheology on "
                f"the {self.cell_name} cell; it has {', '.join(keys)}"
            )
        cell_keys = set(self.cell.declared())
        own = {k: v for k, v in values.items() if k in cell_keys}
        law = {k: v for k, v in values.items() if k not in cell_keys}
        cell = self.cell
        if own:
            names = {p.cli_key: n for n, p in _fields(cell).items()}
            cell = type(cell)(**{**_init_values(cell), **{names[k]: v for k, v in own.items()}})
        rheology = self.rheology.with_values(law) if law else self.rheology
        return Problem(cell, rheology)

    # ----------------------------------------------------------------- what the routes read
    @property
    def slip_wall(self) -> float:
        """xi of the wall the shear layer is measured from [-]."""
        return self.equations.slip_wall

    @property
    def reference_velocity(self) -> float:
        """u_0 of ``eqn-delta_defn`` [-]."""
        return self.equations.reference_velocity

    def wall_velocity(self, xi_wall: float) -> float:
        """Velocity of the wall at ``xi_wall`` [-]."""
        return self.equations.wall_velocity(xi_wall)

    def describe(self) -> str:
        """One line: the cell, the rheology and every parameter."""
        return self.equations.describe()

    def parameters(self) -> dict[str, Any]:
        """Plain-data record of every parameter (for JSON and tables): ``geometry``,
        ``rheology`` and the values, with what the pair derives (a case, tan delta)."""
        return self.equations.parameters()


_PAIRS: dict[tuple[type, type], dict[str, Param]] = {}


@functools.cache
def _drives(cell: type[Cell]) -> tuple[tuple[str, Param], ...]:
    """(field name, declaration) of the cell class's drive parameters."""
    return tuple((n, p) for n, p in declarations(cell).items() if p.role == "drive")


@functools.cache
def _elsewhere(law: type[Rheology], cell: str) -> dict[str, Param]:
    """The law's parameters that do not apply to the cell named ``cell``."""
    return {k: p for k, p in law.declared().items() if not p.applies_to(cell)}


def pair_parameters(law: type[Rheology], cell: type[Cell]) -> dict[str, Param]:
    """The parameters of the rheology ``law`` on the cell ``cell`` by command-line key, with
    their declarations: the law's (those that apply to this cell), then the cell's (its drive
    only for a rate-dependent law). Computed once per pair of classes."""
    found = _PAIRS.get((law, cell))
    if found is None:
        found = dict(law.declared(cell.name))
        for key, p in cell.declared().items():
            if p.role == "drive" and not law.rate_dependent:
                continue
            found[key] = p
        _PAIRS[(law, cell)] = found
    return dict(found)


def _fields(obj: Any) -> dict[str, Any]:
    from .declare import declarations

    return declarations(obj)


def _init_values(obj: Any) -> dict[str, Any]:
    import dataclasses

    return {f.name: getattr(obj, f.name) for f in dataclasses.fields(obj) if f.init}


__all__ = ["Problem", "pair_parameters"]
