"""tools/dem_design.py: the separation of two Delta(H) curves it designs corpus v2 with."""

from __future__ import annotations

import importlib.util
import math
from pathlib import Path

import pytest

TOOL = Path(__file__).resolve().parents[1] / "tools" / "dem_design.py"


@pytest.fixture(scope="module")
def design():
    spec = importlib.util.spec_from_file_location("dem_design", TOOL)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_separation_absolute_and_up_to_one_amplitude(design):
    a = {10: 4.0, 20: 8.0}
    b = {10: 2.0, 20: 4.0}  # b = a / 2: apart in value, the same shape
    n = {10: 2, 20: 1}
    rel = 0.25  # sigma_H = rel * Delta_a
    # absolute: sqrt(2 (2/1)^2 + 1 (4/2)^2) = sqrt(12)
    assert design.separation(a, b, n, rel, shape=False) == pytest.approx(math.sqrt(12.0))
    assert design.separation(a, b, n, rel, shape=True) == pytest.approx(0.0, abs=1e-12)
    # a gap without runs or without a prediction does not count
    assert design.separation(a, {10: 2.0, 20: math.nan}, n, rel, shape=False) == pytest.approx(
        math.sqrt(8.0)
    )
    assert design.separation(a, b, {10: 0, 20: 0}, rel, shape=False) == 0.0


def test_sheared_steps_give_the_wall_travel_in_whole_checkpoints(design):
    for H in (10, 160):
        steps = design.steps(H)
        assert steps % 200_000 == 0
        travel = steps * design.V * design.DT
        assert 40.0 + H <= travel < 40.0 + H + 200_000 * design.V * design.DT
