"""Small-eps thickness laws along a thickness curve (the laws: :mod:`cosserat.routes.laws`)."""

from __future__ import annotations

from ..config import DEFAULT_F
from ..model import Problem
from ..routes.laws import asymptotic_thickness, thickness_limit


def thickness_curve_asymptote(
    problem: Problem, eps_values: list[float], f: float = DEFAULT_F
) -> list[float]:
    """:func:`asymptotic_thickness` at each eps of ``eps_values``."""
    return [asymptotic_thickness(problem.with_values({"eps": e}), f) for e in eps_values]


__all__ = ["asymptotic_thickness", "thickness_curve_asymptote", "thickness_limit"]
