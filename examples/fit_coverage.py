"""Coverage of the fit's uncertainties: fit many synthetic profiles with known parameters.

Plane shear without gravity, layer at the upper wall (phi = 28.5 deg, eps = 0.02, lower wall
fully rough), true delta = 20 deg and K = 0.5, 25 points from 0 to 40 grain diameters, Gaussian
noise sigma = 0.01; the closed-form route keeps each fit cheap. Writes coverage.png and prints
the fraction of fits whose 1-sigma error bar (and profile-likelihood interval) holds the truth.

Run: python examples/fit_coverage.py [n_seeds] [out.png]
"""

from __future__ import annotations

import sys
import time

import numpy as np

from cosserat import Cosserat, Material, Plane, Problem, Wall
from cosserat.analysis.fitting import model_at, model_profile
from cosserat.analysis.measurements import MeasuredProfile
from cosserat.calibration import fit
from cosserat.viz.plotting import new_figure, style

TRUE = {"delta": 20.0, "K": 0.5}
SIGMA = 0.01


def main(n: int = 300, out: str = "coverage.png") -> dict[str, float]:
    mat = Material(28.5)
    truth = Problem(
        Plane(eps=0.02), Cosserat(material=mat, wall=Wall(20.0, 0.5), lower=Wall.fully_rough())
    )
    start = Problem(
        Plane(eps=0.02), Cosserat(material=mat, wall=Wall(15.0, 1.0), lower=Wall.fully_rough())
    )
    d = np.linspace(0.0, 40.0, 25)
    clean = model_at(model_profile(truth, "closed-form"), d)
    pulls: dict[str, list[float]] = {"delta": [], "K": []}
    inside_interval = 0
    t0 = time.perf_counter()
    for seed in range(n):
        noisy = clean + SIGMA * np.random.default_rng(seed).standard_normal(d.size)
        res = fit(MeasuredProfile(d, noisy, np.full(d.size, SIGMA)), start, method="closed-form")
        for name in pulls:
            p = res.parameters[name]
            pulls[name].append((p.value - TRUE[name]) / p.stderr)
        lo, hi = res.parameters["delta"].interval
        inside_interval += lo <= TRUE["delta"] <= hi
    summary = {f"coverage_{k}": float(np.mean(np.abs(v) <= 1.0)) for k, v in pulls.items()}
    summary["coverage_delta_interval"] = inside_interval / n
    summary["seconds_per_fit"] = (time.perf_counter() - t0) / n
    fig, axes = new_figure(1, 2, width=6.6, height=2.8)
    z = np.linspace(-4, 4, 200)
    with style():
        for ax, (name, v) in zip(axes[0], pulls.items(), strict=True):
            ax.hist(v, bins=25, range=(-4, 4), density=True, color="0.75", label=f"{n} fits")
            ax.plot(z, np.exp(-z * z / 2) / np.sqrt(2 * np.pi), "k-", label="N(0, 1)")
            ax.set_xlabel(
                rf"pull $(\hat{{{name}}} - {name}_{{true}})/\sigma$".replace("delta", r"\delta")
            )
            ax.set_title(
                f"within 1 sigma: {np.mean(np.abs(v) <= 1):.3f} (nominal 0.683)", loc="left"
            )
            ax.legend()
        fig.tight_layout()
        fig.savefig(out)
    return summary


if __name__ == "__main__":
    n = int(sys.argv[1]) if len(sys.argv) > 1 else 300
    print(main(n, sys.argv[2] if len(sys.argv) > 2 else "coverage.png"))
