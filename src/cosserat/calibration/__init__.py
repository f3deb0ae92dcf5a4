"""Calibration: one material, many experiments (``docs/calibration.md``).

:func:`calibrate` fits each model jointly to every run it is given (material parameters shared,
wall parameters shared per wall kind, what the metadata give fixed), with every measured field
the model predicts and an error model for correlated bins; it reports chi^2 and its p-value,
runs tests, parameters at bounds, unidentified directions and the regions a model misses, and
compares the models by AIC, BIC and (optionally) the Bayesian evidence; it can sample each
model's posterior.

A fit to one measured profile is a calibration of one run: :func:`fit`, :func:`fit_model` and
:func:`rank_models` (``cosserat.calibration.single``) run the same engine, with the same
identifiability rule and result type, behind ``cosserat fit``, ``fit --models`` and
``cosserat validate``.
"""

from __future__ import annotations

from .data import FIELDS, Field, RunData, load
from .joint import calibrate, calibrate_model
from .models import Model
from .result import Calibration, Estimate, FieldFit, ModelCalibration
from .single import Ranking, SingleFit, fit, fit_model, rank_models

__all__ = [
    "FIELDS",
    "Calibration",
    "Estimate",
    "Field",
    "FieldFit",
    "Model",
    "ModelCalibration",
    "Ranking",
    "RunData",
    "SingleFit",
    "calibrate",
    "calibrate_model",
    "fit",
    "fit_model",
    "load",
    "rank_models",
]
