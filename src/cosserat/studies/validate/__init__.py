"""Validate the models against a corpus of measured profiles, and judge the paper's claims.

For every run of a corpus (:mod:`cosserat.analysis.corpus`): fit each registered model to the
velocity profile (:mod:`.fits`, the only module that fits); measure the shear-layer thickness
Delta, the spin's departure from half the vorticity at each wall, the band's stress ratio and
the inertial number at the moving wall (:mod:`.measures`); set each fitted model's predicted
spin departure beside the measured one. Across the runs of one cell, material and wall at
several gaps (:mod:`.grouping`, by tolerance on the held cell parameter): Delta against H/d,
and each model's Delta there from one joint calibration of the series (:mod:`.fits`).
Then a verdict on each of the paper's claims (:mod:`.verdicts`, each a small pure function of
measured quantities), whichever way it goes:

1. the grain spin departs from half the vorticity near the walls;
2. Delta does not depend on the gap for walls smoother than the material;
3. Delta grows as (H/d)^(1/3) for fully rough walls (under gravity, or in Couette flow);
4. the departure of the spin has the sign and size the Cosserat model predicts.

Each verdict is "supported", "refuted", "mixed" or "undecided", with its evidence (method,
numbers, p-values, runs) and what would change it, and a short summary of its headline
numbers (:mod:`.summaries`). The orchestration is :mod:`.study`; the
writers (figures in ``cosserat.viz.validation``, Markdown and HTML from templates through
``cosserat.viz.report``, ``results.json``) are :mod:`.report`. The rules and the schema of
``results.json``: ``docs/validation.md``.
"""

from __future__ import annotations

from .measures import (
    NEAR_WALL_D,
    P_SIGNIFICANT,
    SpinMeasure,
    StressRatio,
    Thickness,
    WallSpin,
    band_stress_ratio,
    measure_spin,
    measured_thickness,
    reference_velocity,
    thickness_of,
)
from .study import CHANNEL_NOTE, RunResult, ValidationReport, validate
from .verdicts import (
    CLAIMS,
    MIN_GAPS,
    CurveTest,
    DeltaPoint,
    DeltaSeries,
    ModelDelta,
    Verdict,
    curve_test,
    delta_law_verdict,
    power_law_test,
    spin_model_verdict,
    spin_verdict,
)


def write_report(report: ValidationReport, out: str) -> dict[str, str]:
    """Write the report of ``report`` into ``out`` (:func:`.report.write_report`)."""
    from .report import write_report as _write

    return _write(report, out)


__all__ = [
    "CHANNEL_NOTE",
    "CLAIMS",
    "MIN_GAPS",
    "NEAR_WALL_D",
    "P_SIGNIFICANT",
    "CurveTest",
    "DeltaPoint",
    "DeltaSeries",
    "ModelDelta",
    "RunResult",
    "SpinMeasure",
    "StressRatio",
    "Thickness",
    "ValidationReport",
    "Verdict",
    "WallSpin",
    "band_stress_ratio",
    "curve_test",
    "delta_law_verdict",
    "measure_spin",
    "measured_thickness",
    "power_law_test",
    "reference_velocity",
    "spin_model_verdict",
    "spin_verdict",
    "thickness_of",
    "validate",
    "write_report",
]
