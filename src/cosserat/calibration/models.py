"""A model as a calibration sees it: its parameters by role, and its predictions of the
measured fields of a run (``docs/calibration.md``).

Predictions are in the frame of :mod:`cosserat.calibration.data`: at the bins' distances from
the moving wall, ``u`` over the wall's velocity, ``omega`` in units of V/d, and the stress ratio
``|sigma_yx| / sigma_yy``.

Local rheologies (mu(I), NGF) carry no spin of their own. Where a calibration compares them
with spin data, their grains are taken to turn with the material, at half the vorticity of
their velocity field (:data:`LOCAL_SPIN`): the kinematics of a classical continuum, which is
what the Cosserat model departs from near walls. The assumption is stated in every report that
uses it; ``fields=("u", "stress_ratio")`` leaves spin out.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from .. import config
from ..analysis.ranking import model_solve
from ..errors import ConvergenceError, NoSolutionError, ParameterError
from ..model.build import make_problem, problem_parameters
from ..model.cells import CELLS
from ..model.constitutive import FloatArray
from ..model.declare import Param
from ..model.rheologies import RHEOLOGIES
from ..routes.numerical import predict_many
from .data import FIELDS, RunData

SOLVE_ERRORS = (NoSolutionError, ConvergenceError, ParameterError)
"""What a model raises where it has no solution for trial parameters."""
LEAN_FIELDS = ("u", "omega", "sigma_yx", "sigma_yy")
"""What the Cosserat model's lean prediction returns (``routes.numerical.predict_many``)."""
LOCAL_SPIN = "half-vorticity"
"""How a calibration gives a local rheology a spin: half the vorticity of its velocity."""


@dataclass(frozen=True)
class ModelParam:
    """One parameter of a model in a calibration.

    Attributes
    ----------
    key : str
        The model's name for it (``phi``, ``mu_s``, ``delta``, ...).
    declared : Param
        Its declaration (meaning, unit, bounds, fit range, scale, role).
    default_free : bool
        Fitted unless the caller fixes it.
    """

    key: str
    declared: Param
    default_free: bool = True

    @property
    def role(self) -> str:
        return self.declared.role


HELD: dict[str, dict[str, str]] = {
    "cosserat": {
        "A": "a2/a1 of the yield condition changes the layer's width much as L does: velocity "
        "profiles do not tell the two apart (free it with --free A)",
    },
    "mui": {
        "mu_2": "held at its declared value, tan(32.76 deg) of glass beads (Jop, Forterre & "
        "Pouliquen 2006): at the small inertial numbers of slow flow mu(I) depends on mu_2 and "
        "I_0 only through (mu_2 - mu_s)/I_0, so I_0 is fitted given it (free it with --free "
        "mu_2)",
    },
}
"""Material parameters a calibration holds at their declared defaults unless freed, and why."""

ROUGHNESS = Param(
    name="roughness",
    meaning="the wall's roughness tan(delta)/sin(phi) (1: fully rough, eqn-bc_fullyrough)",
    unit="-",
    default=0.7,
    bounds=(0.0, 1.0),
    closed=(False, True),
    fit_range=(0.05, 1.0),
    role="wall",
    source="the calibration's coordinate for the declared delta: its upper end, fully rough, "
    "is tan(delta) = sin(phi), which moves with phi",
)
"""The Cosserat wall's friction as a calibration fits it (``docs/calibration.md``): the declared
``delta`` through ``tan(delta) = roughness * sin(phi)``, so that "fully rough" is the end of a
fixed range rather than a bound tied to another parameter."""

WALL_KEYS = {"delta": "roughness", "K": "K"}
"""The declared wall keys a calibration fits, by their calibration names; the fixed wall's own
(``delta_lower``, ``K_lower``) are the same parameters of another wall kind."""


def _declared(model: str, cells: Sequence[str]) -> dict[str, Param]:
    out: dict[str, Param] = {}
    for cell in cells:
        for key, p in problem_parameters(model, cell).items():
            out.setdefault(key, p)
    return out


class Model:
    """One registered rheology, as a calibration uses it.

    Parameters
    ----------
    name : str
        A registered rheology (``cosserat``, ``mui``, ``ngf``).
    local_spin : bool
        For a rheology without spin of its own: predict ``omega`` as half the vorticity
        (:data:`LOCAL_SPIN`). Ignored for the Cosserat model.
    """

    def __init__(self, name: str, local_spin: bool = True):
        if name not in RHEOLOGIES:
            raise ParameterError(f"unknown model {name!r}: registered are {', '.join(RHEOLOGIES)}")
        self.name = name
        self.local_spin = local_spin
        self._guess: dict[str, float] = {}  # Couette m(0) of the last solve of each run
        self._points: dict[tuple, tuple[RunData, FloatArray]] = {}  # bins as gap fractions

    @property
    def has_spin(self) -> bool:
        """The rheology's own spin field (the Cosserat model's: ``couple_stresses``)."""
        return bool(RHEOLOGIES[self.name].couple_stresses)

    @property
    def rate_dependent(self) -> bool:
        """Needs the wall's inertial number I_w (mu(I), NGF: the rheology's
        ``rate_dependent``)."""
        return bool(RHEOLOGIES[self.name].rate_dependent)

    def fields(self) -> tuple[str, ...]:
        """The measured fields this model predicts (:data:`~cosserat.calibration.data.FIELDS`)."""
        if self.has_spin or self.local_spin:
            return FIELDS
        return tuple(f for f in FIELDS if f != "omega")

    def parameters(self) -> tuple[ModelParam, ...]:
        """The model's material and wall parameters with a declared fit range, from the
        declarations (``cosserat.model.build.problem_parameters``); the Cosserat wall's delta
        as its :data:`ROUGHNESS`."""
        declared = _declared(self.name, [c for c in ("plane", "couette") if c in self.cells()])
        held = HELD.get(self.name, {})
        out = []
        for key, p in declared.items():
            if p.fit_range is None or p.role not in ("material", "wall"):
                continue
            if p.default is None:
                continue  # a form of the law chosen by its absence (NGF's linear local law)
            if p.role == "wall":
                if key not in WALL_KEYS:
                    continue  # the fixed wall's keys: the same parameters, another wall kind
                if key == "delta" and self.name == "cosserat":
                    out.append(ModelParam("roughness", ROUGHNESS, True))
                    continue
            if self.name == "mui" and key == "mu_s":
                mu_2 = declared["mu_2"].default
                lo, hi = p.fit_range
                p = dataclasses.replace(p, fit_range=(lo, min(hi, 0.98 * mu_2)))
            out.append(ModelParam(key, dataclasses.replace(p, name=key), key not in held))
        return tuple(out)

    def cells(self) -> tuple[str, ...]:
        return tuple(c for c in CELLS if RHEOLOGIES[self.name].supports(c))

    # ------------------------------------------------------------------ problems
    def problem(self, run: RunData, values: Mapping[Any, Any]) -> Any:
        """The model's problem for ``run`` with parameter ``values``.

        ``values`` holds the material parameters by key and the wall parameters as
        ``(key, "moving" | "fixed")`` tuples.
        """
        if run.cell not in self.cells():
            raise ParameterError(f"model {self.name!r} has no {run.cell} cell")
        params: dict[str, Any] = dict(run.cell_values)
        material = {k: v for k, v in values.items() if isinstance(k, str)}
        if self.name == "cosserat":
            params.update(material)
            phi = float(material.get("phi", config.PHI))
            s = math.sin(math.radians(phi))

            def angle(t: float) -> Any:
                return "fully-rough" if t >= 1.0 - 1e-12 else math.degrees(math.atan(t * s))

            params["delta"] = angle(float(values[("roughness", "moving")]))
            params["K"] = float(values[("K", "moving")])
            if run.cell == "plane" and run.walls["fixed"] != run.walls["moving"]:
                params["delta_lower"] = angle(float(values[("roughness", "fixed")]))
                params["K_lower"] = float(values[("K", "fixed")])
            return make_problem("cosserat", run.cell, params)
        if not self.rate_dependent:
            params.update(material)
            return make_problem(self.name, run.cell, params)
        if run.I_w is None:
            raise ParameterError(
                f"run {run.name}: {self.name} needs the wall's inertial number I_w, and the "
                "run's metadata do not give the wall speed (wall_speed) to compute it"
            )
        params.update(material)
        params["I_w"] = run.I_w
        return make_problem(self.name, run.cell, params)

    def predict(
        self, run: RunData, values: Mapping[Any, Any], fields: Sequence[str]
    ) -> dict[str, FloatArray]:
        """The model's values of ``fields`` at the bins of ``run`` (module docstring).

        Raises
        ------
        NoSolutionError, ConvergenceError, ParameterError
            The model has no solution or could not be solved for these values.
        """
        if self.name == "cosserat":
            (out,) = self._lean([(run, values)], fields)
            if isinstance(out, Exception):
                raise out
            return out
        use = [f for f in fields if f in run.fields]
        positions = [_nodes(run, name)[0] for name in use]
        problem = self.problem(run, values)
        xw, xi = self._where(run, problem, use, positions)
        ev = model_solve(problem).evaluate(xi)._asdict()
        return self._fields(run, use, positions, ev, float(problem.wall_velocity(xw)))

    def predict_many(
        self, items: Sequence[tuple[RunData, Mapping[Any, Any]]], fields: Sequence[str]
    ) -> list[dict[str, FloatArray] | Exception]:
        """:meth:`predict` for many (run, values) pairs; a pair without a solution gives the
        exception :meth:`predict` would raise, in its place. The Cosserat model solves them
        all in one compiled call (``routes.numerical.predict_many``)."""
        if self.name == "cosserat":
            return self._lean(items, fields)
        out: list[dict[str, FloatArray] | Exception] = []
        for run, values in items:
            try:
                out.append(self.predict(run, values, fields))
            except SOLVE_ERRORS as exc:
                out.append(exc)
        return out

    def _where(
        self, run: RunData, problem: Any, use: Sequence[str], positions: Sequence[FloatArray]
    ) -> tuple[float, FloatArray]:
        """(the moving wall's xi, the bins of ``use`` as gap fractions), cached per run."""
        xw = 1.0 if float(problem.wall_velocity(1.0)) != 0.0 else 0.0
        key = (id(run), xw, tuple(use))
        if key not in self._points:  # the same bins at every call of a calibration
            xi = run.xi(np.concatenate(positions), xw) if positions else np.zeros(0)
            self._points[key] = (run, xi)
        return xw, self._points[key][1]

    def _lean(
        self, items: Sequence[tuple[RunData, Mapping[Any, Any]]], fields: Sequence[str]
    ) -> list[dict[str, FloatArray] | Exception]:
        """The Cosserat model's predictions of many pairs in one compiled call."""
        plans: list[tuple[Any, ...]] = []
        for run, values in items:
            use = [f for f in fields if f in run.fields]
            positions = [_nodes(run, name)[0] for name in use]
            try:
                problem = self.problem(run, values)
            except ParameterError as exc:
                plans.append((run, use, positions, None, 0.0, exc))
                continue
            xw, xi = self._where(run, problem, use, positions)
            plans.append((run, use, positions, problem, xw, xi))
        todo = [p for p in plans if p[3] is not None]
        preds = iter(
            predict_many(
                [p[3] for p in todo], [p[5] for p in todo], LEAN_FIELDS,
                m_inner_guesses=[self._guess.get(p[0].name) for p in todo],
            )
        )  # fmt: skip
        out: list[dict[str, FloatArray] | Exception] = []
        for run, use, positions, problem, xw, extra in plans:
            if problem is None:
                out.append(extra)
                continue
            pr = next(preds)
            if pr.status != "ok" or pr.values is None:
                kind = NoSolutionError if pr.status == "no-solution" else ConvergenceError
                out.append(kind(pr.message))
                continue
            if pr.m_inner is not None:
                self._guess[run.name] = pr.m_inner
            out.append(self._fields(run, use, positions, pr.values,
                                    float(problem.wall_velocity(xw))))  # fmt: skip
        return out

    def _fields(self, run: RunData, use: Sequence[str], positions: Sequence[FloatArray],
                ev: Mapping[str, FloatArray], uw: float) -> dict[str, FloatArray]:  # fmt: skip
        sizes = np.cumsum([0] + [p.size for p in positions])
        out: dict[str, FloatArray] = {}
        for i, name in enumerate(use):
            part = slice(sizes[i], sizes[i + 1])
            weight = _nodes(run, name)[1]

            def mean(v: FloatArray, weight: FloatArray = weight) -> FloatArray:
                """Values at a field's nodes to one per bin (the bin mean, or the value)."""
                v = np.asarray(v, dtype=float).reshape(weight.shape)
                return np.asarray(np.sum(weight * v, axis=1) / np.sum(weight, axis=1))

            def at(key: str, part: slice = part) -> FloatArray:
                return np.asarray(ev[key])[part]

            if name == "u":
                out[name] = mean(at("u")) / uw
            elif name == "omega":
                if self.has_spin:
                    spin = mean(at("omega"))
                else:  # half the vorticity of the velocity field (LOCAL_SPIN)
                    spin = -0.5 * mean(at("du_dxi") + at("kappa") * at("u"))
                # model: omega_z H / V; data: omega_z d / V. Both in a frame where the wall
                # moves along +x above the layer (plane) or turns counter-clockwise (Couette:
                # the model's x is -e_theta, so its z is e_z): the same sense, no sign change
                out[name] = spin * run.eps / abs(uw)
            elif name in ("stress_ratio", "wall_ratio"):
                out[name] = np.abs(mean(at("sigma_yx"))) / mean(at("sigma_yy"))
            else:  # pragma: no cover - FIELDS is closed
                raise ParameterError(f"unknown field {name!r}")
        return out


def _nodes(run: RunData, name: str) -> tuple[FloatArray, FloatArray]:
    """(the points [d] at which a model is evaluated for field ``name`` of ``run``, flattened;
    their weights, one row per bin): the bin centres, or each bin's Gauss-Legendre points
    where the field's values are bin means (``Field.nodes``), weighted by r in Couette flow
    (a bin is an annulus; the inner cylinder moves, so r = R_i + s)."""
    pts, weight = run.fields[name].nodes()
    if run.cell == "couette" and run.fields[name].bins is not None:
        weight = weight * (float(run.cell_values["Ri"]) * run.gap_d + pts)
    return pts.ravel(), weight


def models(names: Sequence[str] | None, local_spin: bool = True) -> list[Model]:
    """:class:`Model` objects for ``names`` (default: every model with declared parameters).

    Raises
    ------
    ParameterError
        An unknown name, or a name given twice.
    """
    chosen = (
        [n for n, law in RHEOLOGIES.items() if law.supports("plane") or law.supports("couette")]
        if names is None
        else list(names)
    )
    twice = sorted({n for n in chosen if chosen.count(n) > 1})
    if twice:
        raise ParameterError(f"model(s) named twice: {', '.join(twice)}")
    return [Model(n, local_spin) for n in chosen]


__all__ = ["LOCAL_SPIN", "Model", "ModelParam", "models"]
