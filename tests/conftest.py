"""Strict test fixtures: headless Matplotlib, NumPy errors raise, a seeded RNG."""

from __future__ import annotations

import os

import numpy as np
import pytest

os.environ.setdefault("MPLBACKEND", "Agg")

from cosserat import Material, Wall

PAPER = Material(phi=28.5, L=10.0, A=1.0 / 3.0)


@pytest.fixture(autouse=True)
def numpy_errors():
    """Division by zero, overflow and invalid operations are bugs; underflow to 0 is not."""
    with np.errstate(divide="raise", over="raise", invalid="raise", under="ignore"):
        yield


@pytest.fixture
def rng() -> np.random.Generator:
    return np.random.default_rng(20261121)


@pytest.fixture
def paper_material() -> Material:
    return PAPER


def wall(delta, K=0.5) -> Wall:
    return Wall(delta, K)
