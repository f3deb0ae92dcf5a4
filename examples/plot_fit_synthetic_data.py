"""
Fit the wall parameters to a measured profile
=============================================

A velocity profile measured in a Couette cell fixes the wall friction angle delta and the slip
coefficient K of the turning wall. The package ships a *synthetic* profile (the model at
delta = 23 deg, K = 0.3 plus noise of 0.01) to try it on; for your own data, see
:doc:`/howto/fit_your_data`.
"""

from importlib.resources import files

import matplotlib.pyplot as plt
import numpy as np

from cosserat import Cosserat, Couette, Material, Problem, Wall
from cosserat.analysis.measurements import read_profile
from cosserat.calibration import fit

measured = read_profile(files("cosserat") / "data" / "synthetic_couette.csv")
start_wall = Wall(delta=15.0, K=1.0)  # the starting values of the fit
start = Problem(Couette(eps=0.05, Ri=2.0), Cosserat(material=Material(), wall=start_wall))
result = fit(measured, start, free=("delta", "K"))
for name, p in result.shown().items():  # the free parameters
    print(f"{name} = {p.value:.3f} +- {p.stderr:.3f}")
print(f"rms residual = {result.rms:.4f}")

d = np.linspace(0.0, measured.distance_d.max(), 200)
fig, ax = plt.subplots(figsize=(6, 4), layout="constrained")
ax.errorbar(
    measured.distance_d,
    measured.u_over_uw,
    yerr=measured.u_err,
    fmt="o",
    ms=3,
    label="synthetic data",
)
ax.plot(d, result.comparison.model_curve(d), label="fitted model")
ax.set_xlabel("distance from the turning wall [grain diameters]")
ax.set_ylabel("$u / u_w$")
ax.legend(loc="upper right")
ax.grid(alpha=0.3)
plt.show()
