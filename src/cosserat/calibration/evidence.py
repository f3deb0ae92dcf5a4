"""The Bayesian evidence of a calibrated model, by nested sampling (dynesty).

``Z = integral L(theta) prior(theta) d theta`` with the likelihood of the error model
(:mod:`~cosserat.calibration.noise`) and the priors of :mod:`~cosserat.calibration.posterior`:
uniform over each free parameter's declared search range, in log10 where its scale is log.
Z depends on those ranges (a wider range lowers Z by its volume where the likelihood is
negligible); they are stated with the parameters in every output. The ratio of two models'
evidences on the same data (the Bayes factor) is the comparison; ``ln Z`` is given with
dynesty's estimate of its error.

Static nested sampling (Skilling 2006; Speagle 2020), :data:`LIVE_POINTS_PER_DIMENSION` live
points per free parameter (at least :data:`MIN_LIVE_POINTS`), stopping when the remaining
evidence is below ``dlogz = 0.1``.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from ..errors import MethodNotAvailableError
from ..model.constitutive import FloatArray
from .result import ModelCalibration

LIVE_POINTS_PER_DIMENSION = 25
"""Live points of the nested sampler per free parameter."""
MIN_LIVE_POINTS = 75
"""Fewest live points of the nested sampler."""
DLOGZ = 0.1
"""The nested sampler stops when the evidence left in the live points is below this (in ln Z)."""


def nested_evidence(mc: ModelCalibration, seed: int = 0) -> ModelCalibration:
    """``mc`` with ``evidence = (ln Z, error)`` (module docstring)."""
    try:
        import dynesty
    except ImportError:
        raise MethodNotAvailableError(
            "the evidence needs dynesty: pip install 'cosserat-granular[posterior]'"
        ) from None
    s = mc.internal[0]
    lo, hi = s.bounds()
    k = lo.size
    floor = -1e300  # dynesty needs finite values: no solution is (practically) zero likelihood

    def loglike(theta: FloatArray) -> float:
        v = s.log_likelihood(theta)
        return v if math.isfinite(v) else floor

    def transform(u: FloatArray) -> FloatArray:
        return lo + u * (hi - lo)

    sampler = dynesty.NestedSampler(
        loglike,
        transform,
        k,
        nlive=max(MIN_LIVE_POINTS, LIVE_POINTS_PER_DIMENSION * k),
        rstate=np.random.default_rng(seed),
        bound="multi",
        sample="rwalk",
    )
    sampler.run_nested(dlogz=DLOGZ, print_progress=False)
    res = sampler.results
    # dynesty's prior is uniform on the unit cube: Z over the box of the fit's coordinates,
    # which is the prior of the module docstring (uniform / log-uniform on the search ranges)
    logz, err = float(res.logz[-1]), float(res.logzerr[-1])
    return dataclasses.replace(mc, evidence=(logz, err))


__all__ = ["DLOGZ", "LIVE_POINTS_PER_DIMENSION", "MIN_LIVE_POINTS", "nested_evidence"]
