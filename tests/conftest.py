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


@pytest.fixture
def toys():
    """The toy cell (``tests/toy_cell.py``) and the toy rheology (``tests/toy_rheology.py``)
    registered for one test, every registry restored afterwards (no toy left registered)."""
    import importlib
    import sys
    from types import SimpleNamespace

    from cosserat.model.cells import CELLS
    from cosserat.model.rheologies import RHEOLOGIES
    from cosserat.routes.registry import PICKLABLE, ROUTES

    saved = (dict(CELLS), dict(RHEOLOGIES), dict(ROUTES), set(PICKLABLE))
    names = ("toy_cell", "toy_rheology")
    for name in names:
        sys.modules.pop(name, None)
    try:
        yield SimpleNamespace(**{n: importlib.import_module(n) for n in names})
    finally:
        for registry, old in zip((CELLS, RHEOLOGIES, ROUTES, PICKLABLE), saved, strict=True):
            registry.clear()
            registry.update(old)
        for name in names:
            sys.modules.pop(name, None)
