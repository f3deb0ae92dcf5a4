"""One immutable profile type for every solution route.

A :class:`Profile` holds the fields on a grid across the whole gap (xi from 0 to 1), the
parameters that made it, a dense evaluator (``evaluate(xi)`` at any point), and diagnostics:
the ODE residuals recomputed on the returned fields and the boundary-condition errors.
Variables and signs are the paper's (``docs/model.md``).
"""

from __future__ import annotations

import csv
import html
import io
import json
import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any, NamedTuple, TypeVar

import numpy as np
from numpy.typing import ArrayLike

from .._atomic import write_text
from ..config import DEFAULT_F
from ..errors import ConvergenceError, CosseratError, ParameterError
from ..model.cells import Coordinate
from ..model.constitutive import FloatArray
from .wall import shear_layer_thickness, wall_omega, wall_slip

if TYPE_CHECKING:
    from matplotlib.figure import Figure

    from ..model import Problem


class Fields(NamedTuple):
    """Fields at a set of points xi [-] (paper's scalings, ``dimlessvar``); ``omega`` and ``m``
    are None for a rheology without grain spin and couple stress (local mu(I), NGF)."""

    u: FloatArray
    omega: FloatArray | None
    m: FloatArray | None
    sigma_xy: FloatArray
    sigma_yx: FloatArray
    sigma_yy: FloatArray
    du_dxi: FloatArray
    kappa: FloatArray

    def spin(self) -> tuple[FloatArray, FloatArray]:
        """(omega, m), the fields of a law with couple stresses.

        Raises
        ------
        ParameterError
            The law has no grain spin and couple stress (the fields are None).
        """
        if self.omega is None or self.m is None:
            raise ParameterError(
                "these fields have no grain spin and couple stress (the law has none)"
            )
        return self.omega, self.m


Evaluator = Callable[[FloatArray], Fields]


@dataclass(frozen=True)
class Diagnostics:
    """How a profile was obtained and how well it satisfies its equations.

    Attributes
    ----------
    method : str
        "numerical", "closed-form" or "asymptotic".
    rtol, atol : float or None
        Tolerances requested from the numerical solver (None for the other routes).
    residuals : dict
        Largest defect of each ODE, recomputed on the returned profile in integral form over
        the intervals of a layer-resolving check grid
        (:func:`cosserat.results.diagnostics.residuals`):
        "couple_stress" (relative to the stress scale), "spin" (relative to the wall spin),
        "velocity" (relative to the wall speed).
    bc_errors : dict
        Each boundary condition written as ``lhs - rhs`` and evaluated on the profile.
    message : str
        Human-readable summary (e.g. solver status, the asymptotic order).
    stats : dict
        Solver statistics (function evaluations, steps, root-finder iterations).
    """

    method: str
    rtol: float | None
    atol: float | None
    residuals: Mapping[str, float]
    bc_errors: Mapping[str, float]
    message: str = ""
    stats: Mapping[str, Any] = field(default_factory=dict)

    def to_dict(self) -> dict[str, Any]:
        return {
            "method": self.method,
            "rtol": self.rtol,
            "atol": self.atol,
            "residuals": dict(self.residuals),
            "bc_errors": dict(self.bc_errors),
            "message": self.message,
            "stats": dict(self.stats),
        }


_Frozen = TypeVar("_Frozen", "Profile", Diagnostics)


def assembled(cls: type[_Frozen], values: dict[str, Any]) -> _Frozen:
    """``cls(**values)`` for :class:`Profile` or :class:`Diagnostics`, without the generated
    ``__init__``.

    A frozen dataclass's ``__init__`` sets each field through ``object.__setattr__``: 3 us for
    a Profile's 16 fields, a tenth of a plane-shear kernel (``docs/performance.md``). Neither
    class has a ``__post_init__``, so filling the instance's ``__dict__`` makes the same
    object. ``values`` must name every field, those with defaults included (the solve path's
    :func:`~cosserat.routes.assemble.make_profile` does; ``tests/test_profile_assembly.py``
    checks it against the constructor).
    """
    obj = object.__new__(cls)
    obj.__dict__.update(values)
    return obj


PENDING = "_pending"
"""The key of a profile's ``__dict__`` under which a route leaves fields to fill on first read
(:func:`pending`)."""


class _Pending:
    # A field of Profile that a route may leave to its first read (pending): a non-data
    # descriptor, which the value, once in the instance's __dict__, shadows (as
    # model._cached.cached does); no docstring, so the API docs list the field once, in the
    # class's Attributes. Read on the class, it is absent, as a dataclass field without a
    # default is.
    __slots__ = ("name",)

    def __init__(self, name: str) -> None:
        self.name = name

    def __get__(self, obj: Profile | None, owner: type | None = None) -> Any:
        if obj is None:
            raise AttributeError(self.name)
        return _filled(obj, self.name)


PENDABLE = (*Fields._fields, "diagnostics")
"""The fields of a :class:`Profile` a route may leave to first read (:func:`pending`)."""


def pending(
    cls: type[Profile],
    values: dict[str, Any],
    names: frozenset[str],
    fill: Callable[..., dict[str, Any]],
    *args: Any,
) -> Profile:
    """:func:`assembled`, with the fields ``names`` (some of :data:`PENDABLE`) that
    ``values`` lacks made when first read (then kept, as if they had been given):
    ``fill(name, *args)`` returns ``name`` and any others made with it (``fill(None, *args)``:
    all of them).

    The numerical route's fields are rows of one array its compiled kernel returns, and its
    :class:`Diagnostics` are read by few callers: making the eight rows' views, the
    diagnostics and their statistics cost more than a tenth of a plane-shear kernel
    (``docs/performance.md``). Their numbers are computed, and the profile checked, before
    :func:`cosserat.solve` returns; only the Python objects that hold them wait. A profile
    pickles with them filled. Two threads reading a new profile at once may both call
    ``fill``; the first's objects are kept.
    """
    obj = object.__new__(cls)
    values[PENDING] = (names, fill, args)
    obj.__dict__.update(values)
    return obj


def _filled(profile: Profile, name: str | None) -> Any:
    """``name`` of a profile made by :func:`pending`, filled first if it is pending (None:
    fill every pending field)."""
    state = profile.__dict__
    todo = state.get(PENDING)
    if todo is not None and (name is None or name in todo[0]):
        names, fill, args = todo
        for key, value in fill(name, *args).items():
            state.setdefault(key, value)
        if state.keys() >= names:
            state.pop(PENDING, None)
    if name is None:
        return None
    try:
        return state[name]
    except KeyError:
        raise AttributeError(
            f"{type(profile).__name__!r} object has no attribute {name!r}"
        ) from None


FIELD_MEANINGS = {
    "xi": "distance from the lower wall (inner cylinder) over the gap, y/H or (r - R_i)/H",
    "u": "velocity over the moving wall's speed",
    "omega": "grain spin omega_z H / V",
    "m": "couple stress M_yz / (L sqrt(2(A+1)) sigma d_p)",
    "sigma_xy": "shear stress sigma_xy (Couette: sigma_theta_r) over the normal stress scale",
    "sigma_yx": "shear stress on wall-parallel planes sigma_yx (Couette: sigma_r_theta)",
    "sigma_yy": "normal stress sigma_yy (Couette: sigma_rr) over its scale",
    "asymmetry": "stress asymmetry sigma_yx - sigma_xy",
    "spin_minus_half_vorticity": "grain spin minus half the vorticity",
}
"""What each field of the profile means (all dimensionless; ``docs/model.md``). The exports
(:meth:`Profile.columns` and everything built on it) name them in the cell's own coordinates:
the cell's :attr:`~cosserat.model.cells.base.Cell.coordinate`."""

COSSERAT_ONLY = ("omega", "m", "asymmetry", "spin_minus_half_vorticity")
"""Fields only a rheology with grain spin and couple stress has: a profile of any other
(local mu(I), NGF) has them as None, and its exports leave them out."""


_GENERIC = Coordinate("xi", FIELD_MEANINGS["xi"], lambda cell, xi: xi)


def cell_names(problem: Any) -> Coordinate:
    """The export names of ``problem``'s cell (:attr:`~cosserat.model.cells.base.Cell.coordinate`;
    the generic ``xi`` names for an object without a cell)."""
    cell = getattr(problem, "cell", None)
    return getattr(cell, "coordinate", _GENERIC)


def _position(problem: Any, xi: FloatArray) -> FloatArray:
    cell = getattr(problem, "cell", None)
    return np.asarray(cell_names(problem).position(cell, xi), dtype=float)


def is_local(problem: Any) -> bool:
    """True for a rheology without couple stress or independent spin (not the Cosserat one)."""
    law = getattr(problem, "rheology", None)
    return not getattr(law, "couple_stresses", True)


@dataclass(frozen=True, eq=False)
class Profile:
    """Fields across the gap for one problem and one solution route.

    Attributes
    ----------
    problem : Problem
        The cell and rheology that made the profile.
    xi : ndarray
        Wall-normal coordinate, 0 (lower wall / inner cylinder) to 1 [-].
    u : ndarray
        Velocity / V [-].
    omega, m : ndarray or None
        Spin omega_z H / V, scaled couple stress (``dimlessvar``) [-]; None for a rheology
        without grain spin and couple stress (local mu(I), NGF): absent, not zero.
    sigma_xy, sigma_yx, sigma_yy : ndarray
        Shear stresses and the normal stress / N (Couette: sigma_theta_r, sigma_r_theta,
        sigma_rr / sigma_c) [-].
    du_dxi : ndarray
        Velocity gradient from the flow rule [-].
    kappa : ndarray
        Curvature 1/(Ri + xi) (0 in plane shear) [-].
    slip_wall : float
        xi of the wall where friction is mobilised (the layer's wall).
    reference_velocity : float
        u_0 of ``eqn-delta_defn``: the velocity the layer decays to.
    diagnostics : Diagnostics
    """

    problem: Problem
    xi: FloatArray
    u: FloatArray
    omega: FloatArray | None
    m: FloatArray | None
    sigma_xy: FloatArray
    sigma_yx: FloatArray
    sigma_yy: FloatArray
    du_dxi: FloatArray
    kappa: FloatArray
    slip_wall: float
    reference_velocity: float
    diagnostics: Diagnostics
    evaluator: Evaluator = field(repr=False)
    velocity: Callable[[FloatArray], FloatArray] | None = field(default=None, repr=False)
    recipe: tuple[Callable[..., Profile], Mapping[str, Any]] | None = field(
        default=None, repr=False
    )

    # ----------------------------------------------------------------- pickling and display
    def __getstate__(self) -> dict[str, Any]:
        """Everything but a route's dense evaluator when it is a closure: that is rebuilt
        from ``recipe`` (the route function and its options) on first use after unpickling.
        The numerical route's evaluator is plain arrays and travels as it is."""
        if PENDING in self.__dict__:
            _filled(self, None)
        state = dict(self.__dict__)
        if self.recipe is not None:
            state["evaluator"] = None
            state["velocity"] = None
        return state

    def __setstate__(self, state: dict[str, Any]) -> None:
        if state.get("evaluator") is None and state.get("recipe") is not None:
            state["evaluator"] = _Rebuilt(state["problem"], state["recipe"])
        self.__dict__.update(state)

    def __repr__(self) -> str:
        d = self.diagnostics
        n = self.xi.size
        ranges = [
            f"{name} in [{v.min():.6g}, {v.max():.6g}]"
            for name, v in (("u", self.u), ("omega", self.omega), ("m", self.m))
            if v is not None
        ]
        lines = [
            f"<Profile: {self.problem.describe()}",
            f"  {d.method}, {n} points, xi in [{self.xi[0]:g}, {self.xi[-1]:g}]"
            + ("" if d.rtol is None else f", rtol = {d.rtol:g}"),
            f"  {', '.join(ranges)}>",
        ]
        return "\n".join(lines)

    @property
    def method(self) -> str:
        return self.diagnostics.method

    @property
    def has_spin(self) -> bool:
        """True if the rheology has a grain spin and couple stress of its own (omega, m)."""
        return self.omega is not None

    @property
    def asymmetry(self) -> FloatArray | None:
        """sigma_yx - sigma_xy, >= 0 with the paper's root [-]; None for a rheology without
        couple stress (its stress is symmetric by construction)."""
        if self.m is None:
            return None
        return self.sigma_yx - self.sigma_xy

    @property
    def half_vorticity(self) -> FloatArray:
        """-(du/dxi + kappa u)/2: half the vorticity, the material spin of a classical
        continuum (paper's signs) [-]."""
        return -0.5 * (self.du_dxi + self.kappa * self.u)

    @property
    def spin_minus_half_vorticity(self) -> FloatArray | None:
        """omega + (du/dxi + kappa u)/2: spin minus half the vorticity [-]; None without
        grain spin.

        In plane shear this is the paper's ``omega + 1/2 du/dxi``; in Couette flow the
        vorticity has the extra u/r term.
        """
        if self.omega is None:
            return None
        return self.omega + 0.5 * (self.du_dxi + self.kappa * self.u)

    def evaluate(self, xi: ArrayLike) -> Fields:
        """The fields at arbitrary points of [0, 1] (dense output of the route)."""
        x = np.atleast_1d(np.asarray(xi, dtype=float))
        if np.any((x < 0.0) | (x > 1.0)):
            raise ParameterError(f"evaluate: xi must lie in [0, 1]; got [{x.min():g}, {x.max():g}]")
        return self.evaluator(x)

    def velocity_at(self, xi: ArrayLike) -> FloatArray:
        """u only, at arbitrary points (cheaper than :meth:`evaluate` where the route has a
        velocity-only evaluator; used by the thickness root-finder)."""
        x = np.atleast_1d(np.asarray(xi, dtype=float))
        return self.velocity(x) if self.velocity is not None else self.evaluate(x).u

    def columns(self) -> dict[str, FloatArray]:
        """The profile as named columns in the cell's own coordinates (the export format).

        Plane shear: ``y`` (= y/H), ``u``, ``omega``, ``m``, ``sigma_xy``, ``sigma_yx``,
        ``sigma_yy``, ``asymmetry``, ``spin_minus_half_vorticity``; Couette flow: ``r``
        (= r/H), ..., ``sigma_theta_r``, ``sigma_r_theta``, ``sigma_rr``, ... (meanings:
        :meth:`column_meanings`). A rheology without grain spin and couple stress (local
        mu(I), NGF) has no ``omega``, ``m``, ``asymmetry`` or ``spin_minus_half_vorticity``
        column: those fields are absent.
        """
        names = cell_names(self.problem)
        out = {names.name: _position(self.problem, self.xi)}
        for name in FIELD_MEANINGS:
            if name == "xi":
                continue
            values = getattr(self, name)
            if values is None:
                continue
            out[names.fields.get(name, (name, ""))[0]] = values
        return out

    def column_meanings(self) -> dict[str, str]:
        """What each column of :meth:`columns` holds, with its scaling (all dimensionless)."""
        names = cell_names(self.problem)
        out = {names.name: names.meaning}
        for name, meaning in FIELD_MEANINGS.items():
            if name == "xi" or getattr(self, name) is None:
                continue
            export, cell_meaning = names.fields.get(name, (name, meaning))
            out[export] = cell_meaning
        return out

    def summary(self) -> dict[str, Any]:
        """Metadata of an export: cell, rheology, method, parameters, Delta, wall slip and
        spin, what each column means and its unit, and the diagnostics (JSON-ready)."""
        from .._version import __version__

        params = self.problem.parameters()
        out: dict[str, Any] = {
            "description": self.problem.describe(),
            "cell": params.get("geometry"),
            "rheology": params.get("rheology", "cosserat"),
            "method": self.method,
            "parameters": params,
            "coordinate": cell_names(self.problem).name,
            "points": int(self.xi.size),
        }
        try:
            out["Delta"] = shear_layer_thickness(self)
        except CosseratError as exc:
            out["Delta"] = None
            out["Delta_undefined"] = " ".join(str(exc).split())
        out["Delta_unit"] = f"grain diameters (f = {DEFAULT_F:g} in eqn-delta_defn)"
        out["wall_slip"] = wall_slip(self)
        out["wall_omega"] = wall_omega(self)
        out["columns"] = {
            name: {"meaning": meaning, "unit": "1"}
            for name, meaning in self.column_meanings().items()
        }
        out["units"] = "every column is dimensionless (unit 1); scalings in docs/model.md"
        out["diagnostics"] = self.diagnostics.to_dict()
        out["cosserat_version"] = __version__
        return _finite(out)

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready record: parameters, columns (cell's own names), derived wall quantities
        (``Delta``, as in every command's JSON; ``thickness``, its name in 0.1, is kept one
        release), what each column means, and diagnostics."""
        out: dict[str, Any] = {
            "problem": self.problem.parameters()["geometry"],
            "parameters": self.problem.parameters(),
        }
        out.update({k: v.tolist() for k, v in self.columns().items()})
        out["Delta"] = shear_layer_thickness(self)
        out["thickness"] = out["Delta"]  # the key of 0.1, kept one release (CHANGELOG)
        out["wall_slip"] = wall_slip(self)
        out["wall_omega"] = wall_omega(self)
        out["columns"] = self.column_meanings()
        out["diagnostics"] = self.diagnostics.to_dict()
        return out

    def to_json(self, path: str | Path | None = None, indent: int | None = None) -> str:
        """JSON text (written to ``path`` if given). Non-finite numbers are an error."""
        text = json.dumps(_finite(self.to_dict()), indent=indent, allow_nan=False)
        if path is not None:
            write_text(path, text + "\n")
        return text

    def to_csv(self, path: str | Path | None = None) -> str:
        """Plain CSV of :meth:`columns`: one header row of column names, then the values
        (``pandas.read_csv(path)`` reads it with no options).

        With ``path`` (``profile.csv``), the metadata (:meth:`summary`: parameters, method,
        Delta, slip, diagnostics, each column's meaning and unit) go to a JSON sidecar
        beside it with the suffix ``.json`` (``profile.json``); both are written atomically,
        the CSV first. Returns the CSV text.
        """
        buf = io.StringIO()
        cols = self.columns()
        writer = csv.writer(buf, lineterminator="\n")
        writer.writerow(cols.keys())
        for row in zip(*cols.values(), strict=True):
            writer.writerow([repr(float(v)) for v in row])
        text = buf.getvalue()
        if path is not None:
            target = Path(path)
            sidecar = sidecar_path(target)
            meta = json.dumps({"file": target.name, **self.summary()}, indent=1, allow_nan=False)
            write_text(target, text)
            write_text(sidecar, meta + "\n")
        return text

    # ----------------------------------------------------------------- notebooks
    def to_dataframe(self) -> Any:
        """The columns (:meth:`columns`: the cell's own names, ``y`` or ``r`` first) as a
        :class:`pandas.DataFrame` indexed by position; the parameters, method, each column's
        meaning and the units (every field is dimensionless, ``docs/model.md``) in ``attrs``."""
        try:
            import pandas as pd
        except ImportError:
            raise ImportError("Profile.to_dataframe needs pandas: pip install pandas") from None
        frame = pd.DataFrame(self.columns())
        frame.attrs.update(self._attrs())
        return frame

    def to_xarray(self) -> Any:
        """The fields as an :class:`xarray.Dataset` on the cell's coordinate (``y`` in plane
        shear, ``r`` in Couette flow: :meth:`columns`), with each variable's meaning and unit
        in its attributes."""
        try:
            import xarray as xr
        except ImportError:
            raise ImportError("Profile.to_xarray needs xarray: pip install xarray") from None
        cols = self.columns()
        meanings = self.column_meanings()
        coord = cell_names(self.problem).name
        position = cols.pop(coord)
        data = {
            name: (coord, values, {"long_name": meanings[name], "units": "1"})
            for name, values in cols.items()
        }
        coords = {coord: (coord, position, {"long_name": meanings[coord], "units": "1"})}
        attrs = {k: json.dumps(v) if isinstance(v, dict) else v for k, v in self._attrs().items()}
        return xr.Dataset(data, coords=coords, attrs=attrs)

    def _attrs(self) -> dict[str, Any]:
        return {
            "description": self.problem.describe(),
            "method": self.method,
            "parameters": self.problem.parameters(),
            "columns": self.column_meanings(),
            "units": "every field is dimensionless; scalings in docs/model.md",
        }

    def _repr_html_(self) -> str:
        """A short HTML summary for notebooks: parameters, Delta, slip, a few rows."""
        rows = np.unique(np.linspace(0, self.xi.size - 1, 7).round().astype(int))
        columns = self.columns()
        cols = [c for c in columns if c in (*_coordinates(), "u", "omega", "m", "asymmetry")]
        table = "".join(
            "<tr>" + "".join(f"<td>{columns[c][i]:.6g}</td>" for c in cols) + "</tr>" for i in rows
        )
        head = "".join(f"<th>{c}</th>" for c in cols)
        try:
            delta = f"{shear_layer_thickness(self):.6g} grain diameters"
        except CosseratError as exc:
            delta = html.escape(str(exc))
        return (
            f"<div><b>Profile</b> ({html.escape(self.method)}): "
            f"{html.escape(self.problem.describe())}<br>"
            f"Delta = {delta}; wall slip = {wall_slip(self):.6g}; "
            f"{self.xi.size} points"
            f"<table><thead><tr>{head}</tr></thead><tbody>{table}</tbody></table></div>"
        )

    def plot(self, fig: Figure | None = None) -> Figure:
        """A quick four-panel plot (u, omega + du/dxi/2, asymmetry, m against xi)."""
        from ..viz.plotting import quick_profile_plot

        return quick_profile_plot(self, fig)


def _coordinates() -> tuple[str, ...]:
    from ..model.cells import CELLS

    return ("xi", *(c.coordinate.name for c in CELLS.values()))


def sidecar_path(path: str | Path) -> Path:
    """The JSON sidecar of a CSV export: ``profile.csv`` -> ``profile.json`` (a name without
    suffix, or ending in ``.json`` itself, gets ``.json`` appended)."""
    target = Path(path)
    if target.suffix and target.suffix.lower() != ".json":
        return target.with_suffix(".json")
    return target.with_name(target.name + ".json")


def _finite(obj: Any) -> Any:
    """Check recursively that every float is finite (NaN never leaves the package)."""
    if isinstance(obj, float) and not math.isfinite(obj):
        raise ConvergenceError("profile contains a non-finite number")
    if isinstance(obj, dict):
        return {k: _finite(v) for k, v in obj.items()}
    if isinstance(obj, list | tuple):
        return [_finite(v) for v in obj]
    return obj


class _Rebuilt:
    """A dense evaluator rebuilt from its recipe on first use (see :meth:`Profile.__getstate__`)."""

    def __init__(self, problem: Any, recipe: tuple[Callable[..., Profile], Mapping[str, Any]]):
        self._problem, self._recipe = problem, recipe
        self._evaluate: Evaluator | None = None

    def __call__(self, xi: FloatArray) -> Fields:
        if self._evaluate is None:
            route, options = self._recipe
            rebuilt = route(self._problem, **{**options, "check": False, "points": 3})
            self._evaluate = rebuilt.evaluator
        return self._evaluate(xi)

    def __reduce__(self) -> tuple[Any, ...]:
        return (_Rebuilt, (self._problem, self._recipe))


for _name in PENDABLE:  # pending() may leave them to first read
    setattr(Profile, _name, _Pending(_name))
