"""
Shear-layer thickness against the gap
=====================================

The paper's central result: as the gap H grows (eps = d/H falls), the shear layer at a wall
that is not fully rough tends to a fixed thickness of a few tens of grain diameters,
``Delta -> -ln f / k`` (17.67 d for the paper's parameters), instead of scaling with the gap.
:func:`~cosserat.analysis.thickness.thickness_curve` solves all the gaps in one call of the
compiled kernel.
"""

import matplotlib.pyplot as plt
import numpy as np

from cosserat import Cosserat, Material, Plane, Problem, Wall
from cosserat.analysis import thickness_curve, thickness_limit

eps_values = np.geomspace(0.05, 1e-6, 12)
fig, ax = plt.subplots(figsize=(7.5, 4), layout="constrained")
for delta in (15.0, 20.0, 25.0):
    problem = Problem(Plane(eps=0.01), Cosserat(material=Material(), wall=Wall(delta=delta)))
    curve = thickness_curve(problem, eps_values)
    label = f"delta = {delta:g} deg"
    (line,) = ax.semilogx(curve.eps, curve.Delta, "o-", ms=3, label=label)
    limit = thickness_limit(problem)
    ax.axhline(limit, color=line.get_color(), ls=":", lw=1)
    print(f"delta = {delta:4.1f} deg: Delta(1e-6) = {curve.Delta[-1]:.3f}, limit {limit:.3f}")
ax.set_xlabel(r"$\varepsilon = d/H$")
ax.set_ylabel(r"$\Delta$ [grain diameters]")
fig.legend(title="dotted: eps -> 0 limit", loc="outside right upper")
ax.grid(alpha=0.3, which="both")
plt.show()
