"""The one result type of every fit, ranking and calibration, and its JSON contract.

``Calibration.to_dict()`` is the ``--format json`` output of ``cosserat calibrate`` (and of
``fit``), documented in ``docs/calibration.md``::

    {"models": [{"model", "status", "message",
                 "parameters": {name: {"value", "stderr", "free", "shared", "unit", ...}},
                 "per_run": {run: {"chi2", "n", "fields": {field: {...}}}},
                 "chi2", "dof", "n", "k", "p_value", "log_likelihood", "aic", "bic",
                 "evidence", "warnings": [...], "assumptions": [...]}],
     "best" (null unless the weights are calibrated), "lowest_aic", "comparison",
     "runs": [...], "posterior": {model: summary} (when sampled)}
"""

from __future__ import annotations

import json
import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from .._atomic import write_text
from ..model.constitutive import FloatArray
from .data import RunData
from .diagnostics import FlatDirection, Region


@dataclass(frozen=True)
class Estimate:
    """One calibrated parameter.

    Attributes
    ----------
    name : str
        Its name in the calibration: the model's key, with the wall kind or run it belongs to
        in brackets where it is not global (``K[glued-grains]``).
    key : str
        The model's name for it (``K``).
    role : str
        ``material``, ``wall``, ``cell``, ``drive`` (``cosserat.model.declare``).
    value : float
        Best-fit (or fixed) value [unit].
    stderr : float or None
        1-sigma error from the Jacobian; None where it is not defined (``reason``).
    free : bool
    shared : bool
        Common to more than one run.
    unit : str
    runs : tuple of str
        The runs it enters.
    at_bound : str or None
        ``"lower"``/``"upper"``: the fit ended on that end of the search range.
    reason : str
        Why ``stderr`` is None (fixed, at a bound, not identified).
    meaning : str
    """

    name: str
    key: str
    role: str
    value: float
    stderr: float | None
    free: bool
    shared: bool
    unit: str
    runs: tuple[str, ...]
    at_bound: str | None = None
    reason: str = ""
    meaning: str = ""
    fit_range: tuple[float, float] | None = None
    derived: bool = False
    scale: float = 1.0
    jackknife: tuple[float, float, float] | None = None
    interval: tuple[float, float] | None = None

    @property
    def stderr_scaled(self) -> float | None:
        """``stderr`` times sqrt(chi^2/dof) where the model misfits (the Birge ratio): the
        spread the parameter would have if the misfit were extra noise [unit]."""
        return None if self.stderr is None else self.stderr * self.scale

    def to_dict(self) -> dict[str, Any]:
        return {
            "value": _num(self.value),
            "stderr": _num(self.stderr),
            "stderr_scaled": _num(self.stderr_scaled),
            "derived": self.derived,
            "leave_one_out": None
            if self.jackknife is None
            else {"min": self.jackknife[0], "max": self.jackknife[1], "se": self.jackknife[2]},
            "free": self.free,
            "shared": self.shared,
            "unit": self.unit,
            "role": self.role,
            "runs": list(self.runs),
            "at_bound": self.at_bound,
            "reason": self.reason or None,
            "meaning": self.meaning,
            "fit_range": list(self.fit_range) if self.fit_range else None,
            "interval": None if self.interval is None else [_num(x) for x in self.interval],
        }


@dataclass(frozen=True)
class FieldFit:
    """One measured field of one run against the model.

    Attributes
    ----------
    run, field : str
    s, data, se, model : ndarray
        Distance from the moving wall [d], measured values, standard errors, model values.
    whitened : ndarray
        Residuals whitened under the error model (``calibration.noise``).
    rho : float
        Lag-1 correlation of the bins used, and ``rho_source`` where it came from.
    chi2 : float
        Sum of squared whitened residuals.
    runs_p : float or None
        Runs test on the whitened residuals' signs (``diagnostics.runs_test``).
    regions : list of Region
        Stretches the model misses (``diagnostics.misfit_regions``).
    """

    run: str
    field: str
    s: FloatArray
    data: FloatArray
    se: FloatArray
    model: FloatArray
    whitened: FloatArray
    rho: float
    rho_source: str
    chi2: float
    runs_p: float | None
    regions: list[Region]

    @property
    def n(self) -> int:
        return int(self.s.size)

    def to_dict(self, arrays: bool = False) -> dict[str, Any]:
        out: dict[str, Any] = {
            "n": self.n,
            "chi2": _num(self.chi2),
            "runs_test_p": _num(self.runs_p),
            "rho": self.rho,
            "rho_source": self.rho_source,
            "misses": [r.describe() for r in self.regions],
        }
        if arrays:
            out.update(
                s=self.s.tolist(),
                data=self.data.tolist(),
                se=self.se.tolist(),
                model=[_num(x) for x in self.model],
                whitened=self.whitened.tolist(),
            )
        return out


@dataclass(frozen=True)
class PosteriorSummary:
    """What a posterior sample says of each parameter.

    Attributes
    ----------
    samples : int
        Retained draws (walkers x steps after burn-in and thinning).
    parameters : dict
        Name -> {"mean", "sd", "q16", "q50", "q84", "ess"}.
    acceptance : float
        Mean acceptance fraction of the walkers.
    autocorrelation : dict
        Name -> integrated autocorrelation time [steps] (None where too short to tell).
    path : str or None
        The InferenceData file written (netCDF).
    seconds : float
        Wall time of the sampling.
    """

    samples: int
    parameters: dict[str, dict[str, float | None]]
    acceptance: float
    autocorrelation: dict[str, float | None]
    burn_in: int
    path: str | None = None
    seconds: float = 0.0

    def to_dict(self) -> dict[str, Any]:
        return {
            "samples": self.samples,
            "burn_in": self.burn_in,
            "acceptance": self.acceptance,
            "autocorrelation": self.autocorrelation,
            "parameters": self.parameters,
            "path": self.path,
            "seconds": round(self.seconds, 2),
        }


@dataclass(frozen=True)
class ModelCalibration:
    """One model calibrated on every run: the parameters, the fit, the diagnostics."""

    model: str
    status: str
    message: str = ""
    parameters: dict[str, Estimate] = field(default_factory=dict)
    fields: list[FieldFit] = field(default_factory=list)
    fields_used: tuple[str, ...] = ()
    chi2: float | None = None
    n: int = 0
    k: int = 0
    log_likelihood: float | None = None
    flat: list[FlatDirection] = field(default_factory=list)
    correlations: list[tuple[str, str, float]] = field(default_factory=list)
    covariance: FloatArray | None = None
    covariance_names: tuple[str, ...] = ()
    warnings: list[str] = field(default_factory=list)
    assumptions: list[str] = field(default_factory=list)
    evidence: tuple[float, float] | None = None
    posterior: PosteriorSummary | None = None
    nfev: int = 0
    seconds: float = 0.0
    held_out: list[FieldFit] = field(default_factory=list)
    internal: Any = field(default=None, repr=False, compare=False)

    @property
    def ok(self) -> bool:
        return self.status == "ok"

    @property
    def dof(self) -> int:
        return self.n - self.k

    @property
    def p_value(self) -> float | None:
        from .diagnostics import chi2_p_value

        return None if self.chi2 is None else chi2_p_value(self.chi2, self.dof)

    @property
    def log10_p_value(self) -> float | None:
        """log10 of ``p_value``, finite where the p-value underflows to 0."""
        from .diagnostics import chi2_log10_p

        return None if self.chi2 is None or self.dof <= 0 else chi2_log10_p(self.chi2, self.dof)

    @property
    def reduced_chi2(self) -> float | None:
        return None if self.chi2 is None or self.dof <= 0 else self.chi2 / self.dof

    @property
    def aic(self) -> float | None:
        """-2 ln L + 2k (the full Gaussian likelihood of the error model)."""
        return None if self.log_likelihood is None else -2.0 * self.log_likelihood + 2 * self.k

    @property
    def bic(self) -> float | None:
        """-2 ln L + k ln n."""
        if self.log_likelihood is None or self.n <= 0:
            return None
        return -2.0 * self.log_likelihood + self.k * math.log(self.n)

    def per_run(self) -> dict[str, dict[str, Any]]:
        out: dict[str, dict[str, Any]] = {}
        for f in self.fields:
            entry = out.setdefault(f.run, {"chi2": 0.0, "n": 0, "fields": {}})
            entry["chi2"] += f.chi2
            entry["n"] += f.n
            entry["fields"][f.field] = f.to_dict()
        for entry in out.values():
            entry["chi2"] = _num(entry["chi2"])
        return out

    def to_dict(self) -> dict[str, Any]:
        return {
            "model": self.model,
            "status": self.status,
            "message": self.message or None,
            "fields": list(self.fields_used),
            "parameters": {n: e.to_dict() for n, e in self.parameters.items()},
            "per_run": self.per_run(),
            "chi2": _num(self.chi2),
            "dof": self.dof if self.ok else None,
            "n": self.n,
            "k": self.k,
            "reduced_chi2": _num(self.reduced_chi2),
            "p_value": _num(self.p_value),
            "log10_p_value": _num(self.log10_p_value),
            "log_likelihood": _num(self.log_likelihood),
            "aic": _num(self.aic),
            "bic": _num(self.bic),
            "evidence": None
            if self.evidence is None
            else {"log_z": _num(self.evidence[0]), "error": _num(self.evidence[1])},
            "unidentified": [d.describe() for d in self.flat],
            "correlations": [{"a": a, "b": b, "r": r} for a, b, r in self.correlations],
            "warnings": list(self.warnings),
            "held_out": {
                f"{f.run}/{f.field}": {**f.to_dict(), "log10_p_value": _log10_p(f.chi2, f.n)}
                for f in self.held_out
            },
            "assumptions": list(self.assumptions),
            "nfev": self.nfev,
            "seconds": round(self.seconds, 3),
        }

    def parameter_rows(self) -> list[dict[str, Any]]:
        return [
            {"model": self.model, "parameter": n, **e.to_dict()} for n, e in self.parameters.items()
        ]

    def to_dataframe(self) -> Any:
        """One row per parameter (pandas), as :meth:`Calibration.to_dataframe` gives them."""
        return _dataframe(self.parameter_rows())

    def to_json(self, path: str | Path | None = None, indent: int | None = 1) -> str:
        """``to_dict()`` as JSON text (no NaN), written to ``path`` if given."""
        text = json.dumps(self.to_dict(), indent=indent, allow_nan=False)
        if path is not None:
            write_text(path, text + "\n")
        return text


@dataclass(frozen=True)
class Calibration:
    """Every model calibrated on the same runs, compared.

    Attributes
    ----------
    runs : list of RunData
    models : list of ModelCalibration
    comparison : list of str
        The assumptions under which the models are compared.
    skipped : list of str
        Runs of the folders given that could not be calibrated, with the reason.
    data_notes : list of str
        What the data say of themselves, whatever the model (``calibration.checks``): runs
        that are not quasi-static, same cells at two speeds that disagree, error models at
        their limits.
    """

    runs: list[RunData]
    models: list[ModelCalibration]
    comparison: list[str] = field(default_factory=list)
    skipped: list[str] = field(default_factory=list)
    data_notes: list[str] = field(default_factory=list)
    held_out: list[RunData] = field(default_factory=list)

    def __getitem__(self, model: str) -> ModelCalibration:
        for m in self.models:
            if m.model == model:
                return m
        raise KeyError(model)

    @property
    def calibrated_weights(self) -> bool:
        """Information-criterion weights mean something only where every compared model
        describes the data (chi^2 p-value at least ``diagnostics.MISFIT_P``)."""
        from .diagnostics import MISFIT_P, chi2_log10_p

        ok = [m for m in self.models if m.ok and m.chi2 is not None and m.dof > 0]
        return bool(ok) and all(
            chi2_log10_p(m.chi2 or 0.0, m.dof) >= math.log10(MISFIT_P) for m in ok
        )

    @property
    def notes(self) -> list[str]:
        """Misfits every model shares: a field of a run that no model describes (its chi^2
        per bin above 3 in each fitted model, within a factor 1.5 of each other) points at
        the data or their errors (the statics are common to all models), not at one model."""
        out = list(self.data_notes)
        ok = [m for m in self.models if m.ok]
        if len(ok) < 2:
            return out
        for f in ok[0].fields:
            chis = []
            for m in ok:
                match = [g for g in m.fields if g.run == f.run and g.field == f.field]
                if match:
                    chis.append(match[0].chi2 / max(match[0].n, 1))
            if len(chis) == len(ok) and min(chis) > 3.0 and max(chis) < 1.5 * min(chis):
                out.append(
                    f"run {f.run}, {f.field}: every model misses it alike (chi^2 per bin "
                    f"{min(chis):.3g}-{max(chis):.3g}): the scatter of the data exceeds their "
                    "standard errors, or what the models share (their statics; for the spin, its "
                    "kinematics) does not hold there"
                )
        return out

    @property
    def lowest_aic(self) -> str | None:
        """The model with the lowest AIC among those fitted to the same fields, whether or not
        any of them describes the data."""
        ok = [m for m in self.models if m.ok and m.aic is not None]
        if not ok:
            return None
        return min(ok, key=lambda m: m.aic if m.aic is not None else math.inf).model

    @property
    def best(self) -> str | None:
        """The model with the lowest AIC where the weights are calibrated (every compared model
        describes the data); None otherwise: the least bad of models that all misfit is not a
        best model (:attr:`lowest_aic` still names it)."""
        return self.lowest_aic if self.calibrated_weights else None

    def weights(self, criterion: str = "aic") -> dict[str, float]:
        """Akaike (or BIC, or evidence) weights of the fitted models [-]."""
        vals = {}
        for m in self.models:
            if not m.ok:
                continue
            if criterion == "evidence":
                if m.evidence is None:
                    continue
                vals[m.model] = -2.0 * m.evidence[0]
            else:
                v = m.aic if criterion == "aic" else m.bic
                if v is None:
                    continue
                vals[m.model] = v
        if not vals:
            return {}
        lo = min(vals.values())
        w = {k: math.exp(-0.5 * (v - lo)) for k, v in vals.items()}
        total = sum(w.values())
        return {k: v / total for k, v in w.items()}

    def to_dict(self) -> dict[str, Any]:
        """The JSON contract of ``cosserat calibrate --format json`` (module docstring)."""
        out: dict[str, Any] = {
            "format": "cosserat-calibration/1",
            "models": [m.to_dict() for m in self.models],
            "best": self.best,
            "lowest_aic": self.lowest_aic,
            "weights": {
                "aic": self.weights("aic"),
                "bic": self.weights("bic"),
                "evidence": self.weights("evidence"),
                "calibrated": self.calibrated_weights,
            },
            "comparison": list(self.comparison),
            "notes": self.notes,
            "runs": [_run_dict(r) for r in self.runs],
            "held_out": [_run_dict(r) for r in self.held_out],
            "skipped": list(self.skipped),
        }
        posterior = {m.model: m.posterior.to_dict() for m in self.models if m.posterior}
        if posterior:
            out["posterior"] = posterior
        return out

    def to_json(self, path: str | Path | None = None, indent: int | None = 1) -> str:
        text = json.dumps(self.to_dict(), indent=indent, allow_nan=False)
        if path is not None:
            write_text(path, text + "\n")
        return text

    def to_dataframe(self) -> Any:
        """One row per model and parameter (pandas; ``pip install pandas``)."""
        return _dataframe([row for m in self.models for row in m.parameter_rows()])


def _dataframe(rows: list[dict[str, Any]]) -> Any:
    try:
        import pandas as pd
    except ImportError:  # pragma: no cover - pandas is in the notebook and test extras
        from ..errors import MethodNotAvailableError

        raise MethodNotAvailableError(
            "to_dataframe needs pandas: pip install 'cosserat-granular[notebook]'"
        ) from None
    return pd.DataFrame(rows)


def _run_dict(run: RunData) -> dict[str, Any]:
    return {
        "name": run.name,
        "cell": run.cell,
        "gap_d": run.gap_d,
        "local_inertial_number": _num(run.local_inertial_number),
        "quasi_static": run.quasi_static,
        "fixed": {**run.cell_values, "I_w": run.I_w},
        "material": run.material,
        "walls": dict(run.walls),
        "fields": {
            name: {"n": f.n, "rho": f.correlation.rho, "rho_source": f.correlation.source}
            for name, f in run.fields.items()
        },
    }


def _log10_p(chi2: float, n: int) -> float | None:
    from .diagnostics import chi2_log10_p

    return _num(chi2_log10_p(chi2, n)) if n > 0 else None


def _num(x: Any) -> Any:
    """A finite float, or None (JSON has no NaN or infinity)."""
    if x is None:
        return None
    x = float(x)
    return x if math.isfinite(x) else None


def rows_of(models: Sequence[ModelCalibration]) -> list[Mapping[str, Any]]:
    """Comparison rows (model, k, n, chi2, dof, p, AIC, BIC, log Z)."""
    return [
        {
            "model": m.model,
            "status": m.status,
            "k": m.k,
            "n": m.n,
            "chi2": m.chi2,
            "dof": m.dof if m.ok else None,
            "p_value": m.p_value,
            "aic": m.aic,
            "bic": m.bic,
            "log_z": None if m.evidence is None else m.evidence[0],
        }
        for m in models
    ]


__all__ = [
    "Calibration",
    "Estimate",
    "FieldFit",
    "ModelCalibration",
    "PosteriorSummary",
    "rows_of",
]
