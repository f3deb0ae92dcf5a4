"""
Wall friction: thickness and slip
=================================

The rougher the wall (the larger delta, up to the fully rough ``tan(delta) = sin(phi)``), the
wider the shear layer and the smaller the slip. The fully rough wall is the limit where the
layer spreads over the whole gap.
"""

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.ticker import NullFormatter

from cosserat import (
    Cosserat,
    Material,
    Plane,
    Problem,
    Wall,
    shear_layer_thickness,
    solve,
    wall_slip,
)

material = Material()
deltas = np.linspace(8.0, 0.999 * material.fully_rough_delta, 14)
Delta, slip = [], []
for delta in deltas:
    problem = Problem(Plane(eps=0.01), Cosserat(material=material, wall=Wall(delta=delta)))
    profile = solve(problem)
    Delta.append(shear_layer_thickness(profile))
    slip.append(wall_slip(profile))

fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(8, 3.6), layout="constrained")
ax1.plot(deltas, Delta, "o-", ms=3)
ax1.set_xlabel(r"wall friction angle $\delta$ [deg]")
ax1.set_ylabel(r"$\Delta$ [grain diameters]")
ax2.semilogy(deltas, slip, "o-", ms=3)
ax2.yaxis.set_minor_formatter(NullFormatter())
ax2.set_xlabel(r"wall friction angle $\delta$ [deg]")
ax2.set_ylabel("slip velocity / V")
for ax in (ax1, ax2):
    ax.axvline(material.fully_rough_delta, color="grey", ls=":", lw=1)
    ax.grid(alpha=0.3)
print(f"fully rough: delta = {material.fully_rough_delta:.3f} deg (dotted)")
plt.show()
