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
"""What each column means (all dimensionless; ``docs/model.md``)."""


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
        """The profile as named columns (the export format)."""
        return {
            "xi": self.xi,
            "u": self.u,
            "omega": self.omega,
            "m": self.m,
            "sigma_xy": self.sigma_xy,
            "sigma_yx": self.sigma_yx,
            "sigma_yy": self.sigma_yy,
            "asymmetry": self.asymmetry,
            "spin_minus_half_vorticity": self.spin_minus_half_vorticity,
        }

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready record: parameters, columns, derived wall quantities and diagnostics."""
        out: dict[str, Any] = {
            "problem": self.problem.parameters()["geometry"],
            "parameters": self.problem.parameters(),
        }
        out.update({k: v.tolist() for k, v in self.columns().items()})
        out["thickness"] = shear_layer_thickness(self)
        out["wall_slip"] = wall_slip(self)
        out["wall_omega"] = wall_omega(self)
        out["diagnostics"] = self.diagnostics.to_dict()
        return out

    def to_json(self, path: str | Path | None = None, indent: int | None = None) -> str:
        """JSON text (written to ``path`` if given). Non-finite numbers are an error."""
        text = json.dumps(_finite(self.to_dict()), indent=indent, allow_nan=False)
        if path is not None:
            write_text(path, text + "\n")
        return text

    def to_csv(self, path: str | Path | None = None) -> str:
        """CSV text of :meth:`columns` with a commented header of parameters."""
        buf = io.StringIO()
        params = self.problem.parameters()
        buf.write(f"# cosserat profile, method = {self.method}\n")
        buf.write(f"# parameters = {json.dumps(params)}\n")
        cols = self.columns()
        writer = csv.writer(buf, lineterminator="\n")
        writer.writerow(cols.keys())
        for row in zip(*cols.values(), strict=True):
            writer.writerow([repr(float(v)) for v in row])
        text = buf.getvalue()
        if path is not None:
            write_text(path, text)
        return text

    # ----------------------------------------------------------------- notebooks
    def to_dataframe(self) -> Any:
        """The columns as a :class:`pandas.DataFrame` indexed by position; the parameters,
        method and units (every field is dimensionless, ``docs/model.md``) in ``attrs``."""
        try:
            import pandas as pd
        except ImportError:
            raise ImportError("Profile.to_dataframe needs pandas: pip install pandas") from None
        frame = pd.DataFrame(self.columns())
        frame.attrs.update(self._attrs())
        return frame

    def to_xarray(self) -> Any:
        """The fields as an :class:`xarray.Dataset` on the coordinate ``xi``, with each
        variable's meaning and unit in its attributes."""
        try:
            import xarray as xr
        except ImportError:
            raise ImportError("Profile.to_xarray needs xarray: pip install xarray") from None
        cols = self.columns()
        xi = cols.pop("xi")
        data = {
            name: ("xi", values, {"long_name": FIELD_MEANINGS[name], "units": "1"})
            for name, values in cols.items()
        }
        coords = {"xi": ("xi", xi, {"long_name": FIELD_MEANINGS["xi"], "units": "1"})}
        attrs = {k: json.dumps(v) if isinstance(v, dict) else v for k, v in self._attrs().items()}
        return xr.Dataset(data, coords=coords, attrs=attrs)

    def _attrs(self) -> dict[str, Any]:
        return {
            "description": self.problem.describe(),
            "method": self.method,
            "parameters": self.problem.parameters(),
            "units": "every field is dimensionless; scalings in docs/model.md",
        }

    def _repr_html_(self) -> str:
        """A short HTML summary for notebooks: parameters, Delta, slip, a few rows."""
        rows = np.unique(np.linspace(0, self.xi.size - 1, 7).round().astype(int))
        cols = ["xi", "u", "omega", "m", "asymmetry"]
        table = "".join(
            "<tr>" + "".join(f"<td>{self.columns()[c][i]:.6g}</td>" for c in cols) + "</tr>"
            for i in rows
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
