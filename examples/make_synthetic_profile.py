"""Make the synthetic Couette profile shipped as package data (clearly labelled synthetic).

The model at known parameters (phi = 28.5 deg, eps = 0.05, Ri = 2, delta = 23 deg, K = 0.3,
L = 10, A = 1/3), sampled at 30 distances from the inner cylinder, plus Gaussian noise of
standard deviation 0.01 (seed 2026). Run: python examples/make_synthetic_profile.py
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from cosserat import Cosserat, Couette, Material, Problem, Wall
from cosserat.analysis.fitting import model_at, model_profile
from cosserat.analysis.measurements import MeasuredProfile, write_profile

TRUE = {"delta": 23.0, "K": 0.3}
SIGMA = 0.01


def make(seed: int = 2026, n: int = 30) -> MeasuredProfile:
    problem = Problem(
        Couette(eps=0.05, Ri=2.0),
        Cosserat(material=Material(28.5), wall=Wall(TRUE["delta"], TRUE["K"])),
    )
    distance = np.round(np.geomspace(0.25, 15.0, n), 4)
    clean = model_at(model_profile(problem, rtol=1e-10), distance)
    noisy = clean + SIGMA * np.random.default_rng(seed).standard_normal(n)
    meta = {
        "label": "synthetic Couette profile",
        "synthetic": "true",
        "source": f"cosserat model, delta = {TRUE['delta']} deg, K = {TRUE['K']}, plus "
        f"N(0, {SIGMA}^2) noise, seed {seed} (examples/make_synthetic_profile.py)",
        "geometry": "couette",
        "eps": 0.05,
        "Ri": 2.0,
        "wall": "surface of the inner cylinder",
    }
    return MeasuredProfile(distance, np.round(noisy, 6), np.full(n, SIGMA), meta)


if __name__ == "__main__":
    out = Path(__file__).resolve().parents[1] / "src" / "cosserat" / "data"
    print(write_profile(make(), out / "synthetic_couette.csv"))
