"""The calibration engine: one model, many runs, every measured field it predicts.

Parameters (``docs/calibration.md``):

* a **material** parameter (role ``material``: phi, L, mu_s, ...) is one number for all runs of
  one material;
* a **wall** parameter (role ``wall``: the Cosserat model's wall roughness and slip
  coefficient) is one number per wall kind;
* what a run's metadata give (eps, Ri, B, nu, the wall's inertial number I_w) is fixed.

The objective is the Gaussian likelihood of the error model of
:mod:`~cosserat.calibration.noise` (AR(1)-correlated bins within a field, fields and runs
independent): the fit minimises the sum of squared whitened residuals with lmfit's
``least_squares`` (SciPy's trust-region reflective method, bounds handled natively), from the
best of a Latin-hypercube set of starts. Parameters with a log scale in their declaration are
fitted in log10.

Uncertainties come from the Jacobian of the whitened residuals at the optimum (central
differences in the fit's coordinates, one-sided at a bound), through one identifiability rule
(:func:`~cosserat.calibration.diagnostics.flat_directions`): a parameter in a direction the data
do not determine, or at an end of its search range, has no standard error and the reason is
given.
"""

from __future__ import annotations

import dataclasses
import math
import time
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from scipy.stats import qmc

from ..errors import ConvergenceError, ParameterError
from ..model.constitutive import FloatArray
from .data import FIELDS, Field, RunData
from .models import SOLVE_ERRORS, Model, ModelParam
from .noise import log_normalisation, whiten

NO_SOLUTION_RESIDUAL = 1e3
"""Whitened residual of every point where the model has no solution for trial parameters."""
FD_STEP = 1e-4
"""Finite-difference step of the Jacobian, as a fraction of each parameter's search range."""
AT_BOUND = 1e-3
"""A fitted value within this fraction of its search range from an end is at that bound."""
_SOLVE_ERRORS = SOLVE_ERRORS


@dataclass(frozen=True)
class Slot:
    """One parameter of a calibration (a column of the Jacobian when free).

    Attributes
    ----------
    name : str
        ``key``, or ``key[group]`` where the parameter belongs to one wall kind, one material
        among several, or one run.
    param : ModelParam
    scope : str
        ``"material"``, ``"wall"`` or ``"run"``.
    group : str
        The material label, wall label or run name it belongs to.
    free : bool
    value : float
        Start value (free) or value (fixed), natural units.
    runs : tuple of str
        The runs it enters.
    """

    name: str
    param: ModelParam
    scope: str
    group: str
    free: bool
    value: float
    runs: tuple[str, ...]

    @property
    def key(self) -> str:
        return self.param.key

    @property
    def log(self) -> bool:
        return self.param.declared.scale == "log"

    def internal(self, x: float) -> float:
        return math.log10(x) if self.log else float(x)

    def natural(self, y: float) -> float:
        return float(10.0**y) if self.log else float(y)

    @property
    def range(self) -> tuple[float, float]:
        """The search range in the fit's coordinate (log10 for log-scaled parameters)."""
        lo, hi = self.param.declared.fit_range or (self.value, self.value)
        return (self.internal(lo), self.internal(hi))


def _ident(i: int) -> str:
    return f"p{i}"


@dataclass
class Setup:
    """One model on a set of runs: the parameter slots and the objective.

    Build it with :func:`setup`.
    """

    model: Model
    runs: list[RunData]
    fields: tuple[str, ...]
    slots: list[Slot]
    nfev: int = 0
    _run_values: dict[str, list[tuple[Any, int]]] = field(default_factory=dict)

    def __post_init__(self) -> None:
        index = {s.name: i for i, s in enumerate(self.slots)}
        for run in self.runs:
            entries: list[tuple[Any, int]] = []
            for i, s in enumerate(self.slots):
                if run.name not in s.runs:
                    continue
                if s.scope == "wall":
                    for pos, label in run.walls.items():
                        if label == s.group:
                            entries.append(((s.key, pos), i))
                else:
                    entries.append((s.key, i))
            self._run_values[run.name] = entries
        del index

    # ------------------------------------------------------------------ coordinates
    @property
    def free(self) -> list[Slot]:
        return [s for s in self.slots if s.free]

    @property
    def names(self) -> list[str]:
        return [s.name for s in self.free]

    def start(self) -> FloatArray:
        """The free parameters' start values in the fit's coordinates."""
        return np.array([s.internal(s.value) for s in self.free])

    def bounds(self) -> tuple[FloatArray, FloatArray]:
        lo = np.array([s.range[0] for s in self.free])
        hi = np.array([s.range[1] for s in self.free])
        return lo, hi

    def natural(self, theta: FloatArray) -> dict[str, float]:
        """Every slot's natural value (free ones from ``theta``)."""
        out, it = {}, iter(np.asarray(theta, dtype=float))
        for s in self.slots:
            out[s.name] = s.natural(next(it)) if s.free else s.value
        return out

    def run_values(self, run: RunData, theta: FloatArray) -> dict[Any, float]:
        """The values the model's problem for ``run`` takes (``Model.problem``)."""
        nat = self.natural(theta)
        values: dict[Any, float] = {}
        for k, i in self._run_values[run.name]:
            values[k] = nat[self.slots[i].name]
        return values

    # ------------------------------------------------------------------ objective
    def predict(self, theta: FloatArray) -> dict[str, dict[str, FloatArray]]:
        """The model's fields at every run's bins (raises where it has no solution)."""
        self.nfev += 1
        return {
            run.name: self.model.predict(run, self.run_values(run, theta), self._fields(run))
            for run in self.runs
        }

    def curves(self, theta: FloatArray, points: int = 160) -> dict[str, dict[str, tuple]]:
        """The model's fields on a fine grid across each run's gap (for figures):
        ``run -> field -> (s, values)``; a run where the model has no solution is left out."""
        out: dict[str, dict[str, tuple]] = {}
        for run in self.runs:
            s = np.unique(
                np.concatenate(
                    [
                        np.linspace(0.0, run.gap_d, points),
                        np.geomspace(1e-3, run.gap_d, points // 2),
                    ]
                )
            )
            fine = {
                name: Field(name, s, np.zeros_like(s), np.ones_like(s))
                for name in self._fields(run)
            }
            try:
                pred = self.model.predict(
                    dataclasses.replace(run, fields=fine),
                    self.run_values(run, theta),
                    list(fine),
                )
            except _SOLVE_ERRORS:
                continue
            out[run.name] = {name: (s, pred[name]) for name in fine}
        return out

    def _fields(self, run: RunData) -> list[str]:
        return [f for f in self.fields if f in run.fields]

    @property
    def n(self) -> int:
        return sum(run.fields[f].n for run in self.runs for f in self._fields(run))

    def log_likelihood_many(self, thetas: FloatArray) -> FloatArray:
        """:meth:`log_likelihood` of every row of ``thetas``, the model solved for all of them
        at once (what an ensemble sampler's walkers need in one step)."""
        thetas = np.atleast_2d(np.asarray(thetas, dtype=float))
        items = [(run, self.run_values(run, th)) for th in thetas for run in self.runs]
        self.nfev += len(thetas)
        preds = self.model.predict_many(items, self.fields)
        out = np.empty(len(thetas))
        norm = self.log_norm
        k = len(self.runs)
        for i in range(len(thetas)):
            chunk = preds[i * k : (i + 1) * k]
            solved = [p for p in chunk if not isinstance(p, Exception)]
            if len(solved) < len(chunk):
                out[i] = -math.inf
                continue
            w = self.whitened({run.name: p for run, p in zip(self.runs, solved, strict=True)})
            out[i] = -0.5 * float(w @ w) + norm if np.all(np.isfinite(w)) else -math.inf
        return out

    def whitened(self, predictions: Mapping[str, Mapping[str, FloatArray]]) -> FloatArray:
        parts = []
        for run in self.runs:
            for name in self._fields(run):
                f = run.fields[name]
                parts.append(whiten(predictions[run.name][name] - f.value, f.se, f.correlation.rho))
        return np.concatenate(parts) if parts else np.zeros(0)

    def residuals(self, theta: FloatArray) -> FloatArray:
        """Whitened residuals of every field of every run (the least-squares objective)."""
        try:
            w = self.whitened(self.predict(theta))
        except _SOLVE_ERRORS:
            return np.full(self.n, NO_SOLUTION_RESIDUAL)
        if not np.all(np.isfinite(w)):
            return np.full(self.n, NO_SOLUTION_RESIDUAL)
        return w

    @property
    def log_norm(self) -> float:
        """The likelihood's normalisation, the same for every model on the same fields."""
        return sum(
            log_normalisation(run.fields[f].se, run.fields[f].correlation.rho)
            for run in self.runs
            for f in self._fields(run)
        )

    def log_likelihood(self, theta: FloatArray) -> float:
        """ln L of the error model; -inf where the model has no solution."""
        try:
            w = self.whitened(self.predict(theta))
        except _SOLVE_ERRORS:
            return -math.inf
        if not np.all(np.isfinite(w)):
            return -math.inf
        return -0.5 * float(w @ w) + self.log_norm


def setup(
    model: Model,
    runs: Sequence[RunData],
    fields: Sequence[str] | None = None,
    fix: Mapping[str, float] | None = None,
    free: Sequence[str] = (),
    start: Mapping[str, float] | None = None,
) -> Setup:
    """The slots of ``model`` on ``runs`` (module docstring).

    Parameters
    ----------
    model : Model
    runs : sequence of RunData
    fields : sequence of str, optional
        Fields to fit (default: every field the model predicts that some run has).
    fix : mapping, optional
        Parameter name (``phi``, or ``K[glued-grains]``, or a key for all its slots) -> value
        to hold fixed.
    free : sequence of str
        Parameters to fit that are fixed by default (``A``).
    start : mapping, optional
        Parameter name or key -> start value.

    Raises
    ------
    ParameterError
        A name that is not a parameter of the model, a value outside its search range, a run
        on a cell the model lacks, or nothing left to fit.
    """
    runs = list(runs)
    for run in runs:
        if run.cell not in model.cells():
            raise ParameterError(f"run {run.name}: model {model.name!r} has no {run.cell} cell")
    predicted = model.fields()
    use = tuple(f for f in (fields or predicted) if f in predicted)
    if fields is not None:
        unknown = [f for f in fields if f not in FIELDS]
        if unknown:
            raise ParameterError(f"unknown field(s) {', '.join(unknown)}")
    if not any(f in run.fields for run in runs for f in use):
        raise ParameterError(f"no run has any of the fields {', '.join(use)}")
    fix = dict(fix or {})
    start = dict(start or {})
    materials = sorted({r.material for r in runs})
    slots: list[Slot] = []
    for p in model.parameters():
        if p.role == "material":
            for mat in materials:
                members = tuple(r.name for r in runs if r.material == mat)
                name = p.key if len(materials) == 1 else f"{p.key}[{mat}]"
                slots.append(
                    Slot(name, p, "material", mat, p.default_free, p.declared.default, members)
                )
        elif p.role == "wall":
            labels: list[str] = []
            for r in runs:
                positions = ["moving"]
                if r.cell == "plane" and r.walls["fixed"] != r.walls["moving"]:
                    positions.append("fixed")
                for pos in positions:
                    if r.walls[pos] not in labels:
                        labels.append(r.walls[pos])
            for label in labels:
                members = tuple(r.name for r in runs if label in r.walls.values())
                slots.append(
                    Slot(
                        f"{p.key}[{label}]",
                        p,
                        "wall",
                        label,
                        p.default_free,
                        p.declared.default,
                        members,
                    )
                )
    known = {s.name for s in slots} | {s.key for s in slots}
    for name in (*fix, *free, *start):
        if name not in known:
            raise ParameterError(
                f"{name!r} is not a parameter of {model.name}; its parameters here: "
                f"{', '.join(s.name for s in slots)}"
            )
    out = []
    for s in slots:
        value, is_free = s.value, s.free
        if s.key in free or s.name in free:
            is_free = True
        for table in (start, fix):
            for k in (s.key, s.name):
                if k in table:
                    value = float(table[k])
        if s.key in fix or s.name in fix:
            is_free = False
        if is_free:
            lo, hi = s.param.declared.fit_range or (value, value)
            if not lo <= value <= hi:
                value = min(max(value, lo), hi)
        out.append(Slot(s.name, s.param, s.scope, s.group, is_free, value, s.runs))
    if not any(s.free for s in out):
        raise ParameterError(f"{model.name}: every parameter is fixed; nothing to calibrate")
    return Setup(model, runs, use, out)


# --------------------------------------------------------------------------- fitting
@dataclass(frozen=True)
class Optimum:
    """The least-squares optimum and what it took."""

    theta: FloatArray
    residuals: FloatArray
    jacobian: FloatArray
    nfev: int
    message: str
    lmfit_result: Any = None
    no_solution: tuple[tuple[int, str], ...] = ()
    """(index of a free parameter, "lower" or "upper"): the model has no solution one
    finite-difference step to that side of the optimum, which sits on the edge of the region
    where it has one (:func:`jacobian_with_edges`)."""


def _starts(s: Setup, n: int, seed: int) -> FloatArray:
    lo, hi = s.bounds()
    if n <= 0 or lo.size == 0:
        return s.start()[None, :]
    sample = qmc.LatinHypercube(d=lo.size, seed=seed).random(n)
    return np.vstack([s.start(), lo + sample * (hi - lo)])


def jacobian(s: Setup, theta: FloatArray, f0: FloatArray | None = None) -> FloatArray:
    """d(whitened residuals)/d(theta): central differences, one-sided at a bound or where the
    model has no solution on one side (:func:`jacobian_with_edges`)."""
    return jacobian_with_edges(s, theta, f0)[0]


def _solved(r: FloatArray) -> bool:
    """False for the residuals :meth:`Setup.residuals` gives where the model has no solution."""
    return not bool(np.all(r == NO_SOLUTION_RESIDUAL))


def _rank(r: FloatArray) -> tuple[bool, float]:
    """Order of two optima's residuals: a solved one first (a solved point's residuals may
    exceed the penalty where the errors are small), then the smaller chi^2."""
    return (not _solved(r), float(r @ r))


def jacobian_with_edges(
    s: Setup, theta: FloatArray, f0: FloatArray | None = None
) -> tuple[FloatArray, tuple[tuple[int, str], ...]]:
    """:func:`jacobian`, and the sides on which the model has no solution one step away.

    A step into a region where the model has no solution gives the penalty residuals
    :data:`NO_SOLUTION_RESIDUAL`, not a derivative: differencing through it made a column of
    about ``NO_SOLUTION_RESIDUAL / (2 step)`` (1e6 per log10 unit of NGF's b on a v2 run, an
    error of 1.7e-10 on a parameter the data barely constrain). That side is left out (the
    one-sided difference on the other), and both sides failing give a zero column (the
    parameter is then in a flat direction: not identified).

    Returns
    -------
    J : ndarray (n, k)
    edges : tuple of (int, str)
        (parameter index, ``"lower"`` or ``"upper"``) for every side without a solution.
    """
    theta = np.asarray(theta, dtype=float)
    lo, hi = s.bounds()
    f0 = s.residuals(theta) if f0 is None else f0
    J = np.empty((f0.size, theta.size))
    edges: list[tuple[int, str]] = []
    for j in range(theta.size):
        h = FD_STEP * (hi[j] - lo[j])
        r_up = r_down = None
        if theta[j] + h <= hi[j]:
            up = theta.copy()
            up[j] += h
            r_up = s.residuals(up)
            if not _solved(r_up):
                edges.append((j, "upper"))
                r_up = None
        if theta[j] - h >= lo[j]:
            down = theta.copy()
            down[j] -= h
            r_down = s.residuals(down)
            if not _solved(r_down):
                edges.append((j, "lower"))
                r_down = None
        if r_up is not None and r_down is not None:
            J[:, j] = (r_up - r_down) / (2.0 * h)
        elif r_up is not None:
            J[:, j] = (r_up - f0) / h
        elif r_down is not None:
            J[:, j] = (f0 - r_down) / h
        else:
            J[:, j] = 0.0
    return J, tuple(edges)


def fit(s: Setup, starts: int | None = None, seed: int = 0, with_jacobian: bool = True) -> Optimum:
    """Minimise the whitened residuals of ``s`` (module docstring).

    Parameters
    ----------
    s : Setup
    starts : int, optional
        Latin-hypercube starts besides the declared defaults (default ``4 k + 4``).
    seed : int
        Seed of the start design.
    with_jacobian : bool
        Compute the Jacobian at the optimum (False: an empty one, for refits that need only
        the optimum, such as a profile likelihood's).

    Raises
    ------
    ConvergenceError
        The model has no solution at any start.
    """
    import lmfit

    lo, hi = s.bounds()
    k = lo.size
    candidates = _starts(s, 4 * k + 4 if starts is None else starts, seed)
    costs = []
    for theta in candidates:
        r = s.residuals(theta)
        # a start without a solution is marked by its residuals, not their size: with small
        # errors a solved start's residuals can exceed the penalty NO_SOLUTION_RESIDUAL (noise-
        # free synthetic data, se 1e-6: every start's were, and the fit said "no solution")
        costs.append(float(r @ r) if _solved(r) else math.inf)
    order = np.argsort(costs)
    if not math.isfinite(costs[order[0]]):
        raise ConvergenceError(
            f"{s.model.name}: no solution at any of {len(candidates)} starting points in the "
            f"search ranges ({', '.join(s.names)}); the model cannot describe these runs "
            "there"
        )

    def residual(params: Any) -> FloatArray:
        return s.residuals(np.array([params[_ident(i)].value for i in range(k)]))

    best: Optimum | None = None
    for idx in [i for i in order[:2] if math.isfinite(costs[i])]:
        params = lmfit.Parameters()
        for i in range(k):
            params.add(_ident(i), value=float(candidates[idx][i]), min=lo[i], max=hi[i])
        mini = lmfit.Minimizer(residual, params, scale_covar=False)
        # lmfit's own covariance (unused: the errors come from :func:`jacobian`) takes square
        # roots of a singular fit's negative round-off: quiet where the caller made that raise
        with np.errstate(invalid="ignore", divide="ignore"):
            res = mini.least_squares(
                x_scale=hi - lo, diff_step=FD_STEP, max_nfev=200 * (k + 1), xtol=1e-10, ftol=1e-10
            )
        theta = np.array([res.params[_ident(i)].value for i in range(k)])
        r = s.residuals(theta)
        if best is None or _rank(r) < _rank(best.residuals):
            best = Optimum(theta, r, np.zeros((0, 0)), s.nfev, str(res.message), res)
    assert best is not None
    J, edges = (
        jacobian_with_edges(s, best.theta, best.residuals)
        if with_jacobian
        else (np.zeros((0, 0)), ())
    )
    return Optimum(best.theta, best.residuals, J, s.nfev, best.message, best.lmfit_result, edges)


def timed(fn: Callable[[], Any]) -> tuple[Any, float]:
    t0 = time.perf_counter()
    out = fn()
    return out, time.perf_counter() - t0


__all__ = [
    "AT_BOUND",
    "FD_STEP",
    "NO_SOLUTION_RESIDUAL",
    "Optimum",
    "Setup",
    "Slot",
    "fit",
    "jacobian",
    "jacobian_with_edges",
    "setup",
]
