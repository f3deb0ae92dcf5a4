"""Calibration: one material, many experiments (``docs/calibration.md``).

:func:`calibrate` fits each model jointly to every run it is given (material parameters shared,
wall parameters shared per wall kind, what the metadata give fixed), with every measured field
the model predicts and an error model for correlated bins; it reports chi^2 and its p-value,
runs tests, parameters at bounds, unidentified directions and the regions a model misses, and
compares the models by AIC, BIC and (optionally) the Bayesian evidence; it can sample each
model's posterior.
"""

from __future__ import annotations

from .data import FIELDS, Field, RunData, load
from .joint import calibrate, calibrate_model
from .models import Model
from .result import Calibration, Estimate, FieldFit, ModelCalibration

__all__ = [
    "FIELDS",
    "Calibration",
    "Estimate",
    "Field",
    "FieldFit",
    "Model",
    "ModelCalibration",
    "RunData",
    "calibrate",
    "calibrate_model",
    "load",
]
