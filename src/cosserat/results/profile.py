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
from typing import TYPE_CHECKING, Any, NamedTuple

import numpy as np
from numpy.typing import ArrayLike

from .._atomic import write_text
from ..config import DEFAULT_F
from ..errors import ConvergenceError, CosseratError, ParameterError
from ..model.constitutive import FloatArray
from .wall import shear_layer_thickness, wall_omega, wall_slip

if TYPE_CHECKING:
    from matplotlib.figure import Figure

    from ..model import Problem


class Fields(NamedTuple):
    """Fields at a set of points xi [-] (paper's scalings, ``dimlessvar``)."""

    u: FloatArray
    omega: FloatArray
    m: FloatArray
    sigma_xy: FloatArray
    sigma_yx: FloatArray
    sigma_yy: FloatArray
    du_dxi: FloatArray
    kappa: FloatArray


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
        the intervals of a layer-resolving check grid (:func:`cosserat.diagnostics.residuals`):
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
:data:`CELL_NAMES`."""

COSSERAT_ONLY = ("m", "asymmetry", "spin_minus_half_vorticity")
"""Fields a local rheology (no couple stress, symmetric stress) has identically zero: its
profiles do not export them."""


@dataclass(frozen=True)
class CellNames:
    """The names and meanings an export uses for one cell.

    Attributes
    ----------
    coordinate : str
        Name of the wall-normal coordinate column.
    coordinate_meaning : str
        What it holds, with its scaling.
    position : callable
        ``position(problem, xi)``: the coordinate at the gap fractions ``xi`` [-].
    fields : mapping of str to (str, str)
        Profile field -> (export name, meaning) where the cell renames it.
    """

    coordinate: str
    coordinate_meaning: str
    position: Callable[[Any, FloatArray], FloatArray]
    fields: Mapping[str, tuple[str, str]] = field(default_factory=dict)


CELL_NAMES: dict[str, CellNames] = {
    "plane": CellNames(
        "y",
        "height above the fixed lower wall over the gap, y/H (0 to 1)",
        lambda problem, xi: xi,
        {
            "u": ("u", "velocity u_x over the moving upper wall's speed V"),
            "omega": ("omega", "grain spin omega_z H / V"),
            "sigma_xy": ("sigma_xy", "shear stress sigma_xy over the normal stress N"),
            "sigma_yx": ("sigma_yx", "shear stress on wall-parallel planes sigma_yx over N"),
            "sigma_yy": ("sigma_yy", "normal stress sigma_yy over N"),
        },
    ),
    "couette": CellNames(
        "r",
        "radius over the gap, r/H (inner cylinder at r/H = R_i/H, outer at R_i/H + 1)",
        lambda problem, xi: problem.Ri + xi,
        {
            "u": ("u", "velocity -v_theta over the inner cylinder's speed V_i (-1 at it)"),
            "omega": ("omega", "grain spin omega_z H / V_i"),
            "m": ("m", "couple stress M_rz / (L sqrt(2(A+1)) sigma_c d_p)"),
            "sigma_xy": ("sigma_theta_r", "shear stress sigma_theta_r over the mean stress"),
            "sigma_yx": (
                "sigma_r_theta",
                "shear stress on cylinders sigma_r_theta over the mean stress",
            ),
            "sigma_yy": ("sigma_rr", "radial normal stress sigma_rr over the mean stress"),
            "asymmetry": ("asymmetry", "stress asymmetry sigma_r_theta - sigma_theta_r"),
        },
    ),
    "channel": CellNames(
        "y",
        "distance across the channel over its width, y/H (walls at 0 and 1)",
        lambda problem, xi: xi,
        {
            "u": ("u", "downward velocity over its centre-line value"),
            "omega": ("omega", "grain spin omega_z H / u_centre"),
            "sigma_xy": ("sigma_xy", "shear stress sigma_xy over the wall normal stress N"),
            "sigma_yx": ("sigma_yx", "shear stress on wall-parallel planes sigma_yx over N"),
            "sigma_yy": ("sigma_yy", "normal stress sigma_yy over N"),
        },
    ),
}
"""Export names by cell (the ``geometry`` of ``problem.parameters()``). A cell not listed
here exports ``xi`` and the plane names: add it here with its own coordinate."""


def cell_names(problem: Any) -> CellNames:
    """The :class:`CellNames` of ``problem``'s cell (the generic ``xi`` names if unknown)."""
    geometry = problem.parameters().get("geometry")
    return CELL_NAMES.get(geometry, CellNames("xi", FIELD_MEANINGS["xi"], lambda problem, xi: xi))


def is_local(problem: Any) -> bool:
    """True for a rheology without couple stress or independent spin (not the Cosserat one)."""
    return problem.parameters().get("rheology", "cosserat") != "cosserat"


@dataclass(frozen=True, eq=False)
class Profile:
    """Fields across the gap for one problem and one solution route.

    Attributes
    ----------
    problem : PlaneShear or CouetteFlow
        The parameters that made the profile.
    xi : ndarray
        Wall-normal coordinate, 0 (lower wall / inner cylinder) to 1 [-].
    u, omega, m : ndarray
        Velocity / V, spin omega_z H / V, scaled couple stress (``dimlessvar``) [-].
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
    omega: FloatArray
    m: FloatArray
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
        lines = [
            f"<Profile: {self.problem.describe()}",
            f"  {d.method}, {n} points, xi in [{self.xi[0]:g}, {self.xi[-1]:g}]"
            + ("" if d.rtol is None else f", rtol = {d.rtol:g}"),
            f"  u in [{self.u.min():.6g}, {self.u.max():.6g}], "
            f"omega in [{self.omega.min():.6g}, {self.omega.max():.6g}], "
            f"m in [{self.m.min():.6g}, {self.m.max():.6g}]>",
        ]
        return "\n".join(lines)

    @property
    def method(self) -> str:
        return self.diagnostics.method

    @property
    def asymmetry(self) -> FloatArray:
        """sigma_yx - sigma_xy, >= 0 with the paper's root [-]."""
        return self.sigma_yx - self.sigma_xy

    @property
    def spin_minus_half_vorticity(self) -> FloatArray:
        """omega + (du/dxi + kappa u)/2: spin minus half the vorticity [-].

        In plane shear this is the paper's ``omega + 1/2 du/dxi``; in Couette flow the
        vorticity has the extra u/r term.
        """
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
        :meth:`column_meanings`). A local rheology has no ``m``, ``asymmetry`` or
        ``spin_minus_half_vorticity`` (identically zero), and its ``omega`` is half the
        vorticity.
        """
        names = cell_names(self.problem)
        out = {names.coordinate: np.asarray(names.position(self.problem, self.xi), dtype=float)}
        for name in FIELD_MEANINGS:
            if name == "xi" or (name in COSSERAT_ONLY and is_local(self.problem)):
                continue
            out[names.fields.get(name, (name, ""))[0]] = getattr(self, name)
        return out

    def column_meanings(self) -> dict[str, str]:
        """What each column of :meth:`columns` holds, with its scaling (all dimensionless)."""
        names = cell_names(self.problem)
        out = {names.coordinate: names.coordinate_meaning}
        for name, meaning in FIELD_MEANINGS.items():
            if name == "xi" or (name in COSSERAT_ONLY and is_local(self.problem)):
                continue
            export, cell_meaning = names.fields.get(name, (name, meaning))
            if name == "omega" and is_local(self.problem):
                cell_meaning = "material spin, half the vorticity (no independent grain spin)"
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
            "coordinate": cell_names(self.problem).coordinate,
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
        """JSON-ready record: parameters, columns (cell's own names), derived wall quantities,
        what each column means, and diagnostics."""
        out: dict[str, Any] = {
            "problem": self.problem.parameters()["geometry"],
            "parameters": self.problem.parameters(),
        }
        out.update({k: v.tolist() for k, v in self.columns().items()})
        out["thickness"] = shear_layer_thickness(self)
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
        coord = cell_names(self.problem).coordinate
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
        cols = [c for c in columns if c in (*CELL_COORDINATES, "u", "omega", "m", "asymmetry")]
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


CELL_COORDINATES = ("xi", *(names.coordinate for names in CELL_NAMES.values()))


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
