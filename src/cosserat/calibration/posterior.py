"""Posterior samples of a calibrated model (emcee), written as ArviZ InferenceData.

The posterior is ``p(theta | data) ~ L(theta) prior(theta)`` with the likelihood of the error
model (:mod:`~cosserat.calibration.noise`) and priors from the parameter declarations: uniform
over each free parameter's search range, in log10 where the declaration's scale is log
(log-uniform). Where the model has no solution the likelihood is zero.

Sampling: emcee's affine-invariant ensemble (Goodman & Weare 2010) with ``max(32, 4k)``
walkers started in a small ball around the least-squares optimum; the first
:data:`BURN_IN` steps (or five integrated autocorrelation times, if longer and measurable)
are dropped. Files (``out``): ``posterior_<model>.nc`` (InferenceData: the ``posterior`` group
in natural units, ``sample_stats`` with the log-probability, ``observed_data`` with every
field, ``constant_data`` with each field's positions s [d] and standard errors,
``posterior_predictive``: replicated data, the model at a subsample of draws plus the error
model's noise) and ``corner_<model>.png``.
Needs the extra ``posterior`` (ArviZ, h5netcdf, corner).
"""

from __future__ import annotations

import dataclasses
import logging
import math
import time
from pathlib import Path
from typing import Any

import numpy as np

from .._atomic import atomic_path, save_figure
from ..errors import MethodNotAvailableError
from ..model.constitutive import FloatArray
from .engine import Optimum, Setup
from .models import SOLVE_ERRORS
from .noise import covariance
from .result import ModelCalibration, PosteriorSummary

log = logging.getLogger(__name__)

BURN_IN = 100
"""Steps dropped at the start of every chain (at least)."""
PREDICTIVE_DRAWS = 200
"""Posterior draws on which the posterior predictive is evaluated."""


def _require(module: str) -> Any:
    import importlib
    import warnings

    try:
        with warnings.catch_warnings():
            # ArviZ 0.2x announces its 1.0 refactor with a FutureWarning at import
            warnings.simplefilter("ignore", FutureWarning)
            return importlib.import_module(module)
    except ImportError:
        raise MethodNotAvailableError(
            f"posterior sampling needs {module}: pip install 'cosserat-granular[posterior]'"
        ) from None


def log_prior(s: Setup, theta: FloatArray) -> float:
    """ln prior of ``theta`` (fit coordinates): uniform on the search box, up to a constant."""
    lo, hi = s.bounds()
    return 0.0 if np.all(theta >= lo) and np.all(theta <= hi) else -math.inf


def log_probability(s: Setup, theta: FloatArray) -> float:
    """ln posterior of ``theta`` (fit coordinates) up to a constant: prior plus likelihood."""
    lp = log_prior(s, theta)
    if not math.isfinite(lp):
        return -math.inf
    return lp + s.log_likelihood(theta)


def log_probability_many(s: Setup, thetas: FloatArray) -> FloatArray:
    """:func:`log_probability` of every row of ``thetas`` (the model solved for all at once)."""
    thetas = np.atleast_2d(thetas)
    lo, hi = s.bounds()
    inside = np.all((thetas >= lo) & (thetas <= hi), axis=1)
    out = np.full(len(thetas), -np.inf)
    if np.any(inside):
        out[inside] = s.log_likelihood_many(thetas[inside])
    return out


def _initial(s: Setup, opt: Optimum, cov: FloatArray, walkers: int, rng: Any) -> FloatArray:
    lo, hi = s.bounds()
    k = lo.size
    scale = np.sqrt(np.clip(np.diag(cov), 0.0, None)) if cov.size else np.zeros(k)
    scale = np.minimum(
        np.where(np.isfinite(scale) & (scale > 0), scale, 1e-3 * (hi - lo)), 0.05 * (hi - lo)
    )
    p0 = opt.theta + 0.1 * scale * rng.standard_normal((walkers, k))
    return np.clip(p0, lo + 1e-9 * (hi - lo), hi - 1e-9 * (hi - lo))


def run_sampler(
    s: Setup, opt: Optimum, cov: FloatArray, samples: int, seed: int = 0, progress: bool = False
) -> tuple[Any, int]:
    """emcee's sampler run for about ``samples`` retained draws; returns it and the burn-in."""
    emcee = _require("emcee")
    k = opt.theta.size
    walkers = max(32, 4 * k)
    walkers += walkers % 2
    rng = np.random.default_rng(seed)
    steps = math.ceil(samples / walkers)
    sampler = emcee.EnsembleSampler(
        walkers, k, lambda thetas: log_probability_many(s, thetas), vectorize=True
    )
    sampler.random_state = np.random.RandomState(seed).get_state()
    sampler.run_mcmc(_initial(s, opt, cov, walkers, rng), BURN_IN + steps, progress=progress)
    return sampler, BURN_IN


def sample_posterior(
    mc: ModelCalibration,
    samples: int,
    out: str | Path | None = None,
    seed: int = 0,
    progress: bool = False,
) -> ModelCalibration:
    """``mc`` with :class:`PosteriorSummary` (module docstring); files under ``out``."""
    s, opt = mc.internal
    t0 = time.perf_counter()
    sampler, burn = run_sampler(s, opt, np.asarray(mc.covariance), samples, seed, progress)
    chain = sampler.get_chain(discard=burn)  # (steps, walkers, k), fit coordinates
    lp = sampler.get_log_prob(discard=burn)
    emcee_log = logging.getLogger("emcee.autocorr")
    level = emcee_log.level
    emcee_log.setLevel(logging.ERROR)  # a short chain is said in our own warning, below
    try:
        tau = sampler.get_autocorr_time(discard=burn, quiet=True)
    finally:
        emcee_log.setLevel(level)
    natural = _natural(s, chain)
    flat = {n: v.reshape(-1) for n, v in natural.items()}
    summary = {}
    for i, name in enumerate(s.names):
        x = flat[name]
        q16, q50, q84 = np.percentile(x, [16, 50, 84])
        ess = x.size / max(float(tau[i]), 1.0) if np.isfinite(tau[i]) else None
        summary[name] = {
            "mean": float(np.mean(x)),
            "sd": float(np.std(x, ddof=1)),
            "q16": float(q16),
            "q50": float(q50),
            "q84": float(q84),
            "ess": None if ess is None else float(ess),
        }
    path = None
    if out is not None:
        path = str(write_inference_data(mc, s, natural, lp, Path(out), seed))
        corner_plot(mc, s, natural, opt, Path(out))
    post = PosteriorSummary(
        samples=int(chain.shape[0] * chain.shape[1]),
        parameters=summary,
        acceptance=float(np.mean(sampler.acceptance_fraction)),
        autocorrelation={
            n: (float(t) if np.isfinite(t) else None) for n, t in zip(s.names, tau, strict=True)
        },
        burn_in=burn,
        path=path,
        seconds=time.perf_counter() - t0,
    )
    mc = dataclasses.replace(mc, posterior=post, internal=(s, opt, chain))
    short = [
        n for n, t in zip(s.names, tau, strict=True) if np.isfinite(t) and chain.shape[0] < 50 * t
    ]
    if short:
        mc.warnings.append(
            f"{mc.model}: the posterior chains are shorter than 50 autocorrelation times for "
            f"{', '.join(short)}: draw more samples for reliable tails"
        )
    return mc


def _natural(s: Setup, chain: FloatArray) -> dict[str, FloatArray]:
    """Fit-coordinate chain (steps, walkers, k) -> name: (walkers, steps) natural values."""
    out = {}
    for i, slot in enumerate(s.free):
        x = chain[:, :, i].T
        out[slot.name] = 10.0**x if slot.log else x
    return out


def predictive(
    s: Setup, chain: FloatArray, draws: int = PREDICTIVE_DRAWS, seed: int = 0, noise: bool = True
) -> dict[str, FloatArray]:
    """Replicated data at the data's bins for ``draws`` posterior draws: ``run/field`` ->
    (draws, bins); each draw is the model at a posterior sample plus, with ``noise``, a draw of
    the error model's noise (AR(1) with the field's se and rho): the posterior predictive
    distribution of the data."""
    flat = chain.reshape(-1, chain.shape[-1])
    rng = np.random.default_rng(seed)
    pick = rng.choice(flat.shape[0], size=min(draws, flat.shape[0]), replace=False)
    out: dict[str, list[FloatArray]] = {}
    chol = {
        (run.name, name): np.linalg.cholesky(covariance(f.se, f.correlation.rho))
        for run in s.runs
        for name, f in run.fields.items()
    }
    for theta in flat[pick]:
        try:
            pred = s.predict(theta)
        except SOLVE_ERRORS:
            continue  # a draw without a solution has zero posterior mass
        for run, fields in pred.items():
            for name, values in fields.items():
                if noise:
                    values = values + chol[(run, name)] @ rng.standard_normal(values.size)
                out.setdefault(f"{run}/{name}", []).append(values)
    return {k: np.array(v) for k, v in out.items()}


def _var(name: str) -> str:
    """A netCDF-safe variable name."""
    return name.replace("[", "__").replace("]", "").replace("/", "__")


def write_inference_data(
    mc: ModelCalibration,
    s: Setup,
    natural: dict[str, FloatArray],
    lp: FloatArray,
    out: Path,
    seed: int,
) -> Path:
    """``posterior_<model>.nc``: an ArviZ InferenceData (module docstring)."""
    az = _require("arviz")
    _require("h5netcdf")
    chain = mc.internal[2] if len(mc.internal) > 2 else None
    post = {_var(n): v for n, v in natural.items()}
    observed: dict[str, FloatArray] = {}
    constant: dict[str, FloatArray] = {}
    for run in s.runs:
        for name in s.fields:
            if name in run.fields:
                observed[_var(f"{run.name}/{name}")] = run.fields[name].value
                constant[_var(f"{run.name}/{name}/s")] = run.fields[name].s
                constant[_var(f"{run.name}/{name}/se")] = run.fields[name].se
    steps_chain = np.stack([natural[n].T for n in s.names], axis=-1)  # (steps, walkers, k)
    del chain
    pp = predictive(s, _to_internal(s, steps_chain), seed=seed)
    idata = az.from_dict(
        posterior=post,
        sample_stats={"lp": lp.T},
        observed_data=observed,
        constant_data=constant,
        posterior_predictive={_var(k): v[None, ...] for k, v in pp.items()},
        attrs={
            "model": mc.model,
            "package": "cosserat-granular",
            "assumptions": " | ".join(mc.assumptions),
            "priors": "; ".join(
                f"{sl.name}: {'log-uniform' if sl.log else 'uniform'} on "
                f"{sl.param.declared.fit_range} [{sl.param.declared.unit}]"
                for sl in s.free
            ),
        },
    )
    out.mkdir(parents=True, exist_ok=True)
    path = out / f"posterior_{mc.model}.nc"
    with atomic_path(path) as tmp:
        idata.to_netcdf(str(tmp), engine="h5netcdf")
    return path


def _to_internal(s: Setup, chain_natural: FloatArray) -> FloatArray:
    out = chain_natural.copy()
    for i, slot in enumerate(s.free):
        if slot.log:
            out[..., i] = np.log10(out[..., i])
    return out


def corner_plot(
    mc: ModelCalibration, s: Setup, natural: dict[str, FloatArray], opt: Optimum, out: Path
) -> Path:
    """``corner_<model>.png``: the posterior's pairs, least-squares optimum marked."""
    corner = _require("corner")
    import matplotlib

    matplotlib.use("Agg", force=False)
    import matplotlib.pyplot as plt

    names = s.names
    data = np.column_stack([natural[n].reshape(-1) for n in names])
    units = [s.free[i].param.declared.unit for i in range(len(names))]
    labels = [f"{n} [{u}]" for n, u in zip(names, units, strict=True)]
    truths = [s.natural(opt.theta)[n] for n in names]
    fig = corner.corner(
        data,
        labels=labels,
        truths=truths,
        quantiles=[0.16, 0.5, 0.84],
        show_titles=True,
        title_fmt=".3g",
        label_kwargs={"fontsize": 9},
        title_kwargs={"fontsize": 8},
    )
    fig.suptitle(f"{mc.model}: posterior ({data.shape[0]} draws); lines: least squares", fontsize=9)
    out.mkdir(parents=True, exist_ok=True)
    path = save_figure(fig, out / f"corner_{mc.model}.png", dpi=110)
    plt.close(fig)
    return path


__all__ = [
    "BURN_IN",
    "corner_plot",
    "log_prior",
    "log_probability",
    "predictive",
    "run_sampler",
    "sample_posterior",
    "write_inference_data",
]
