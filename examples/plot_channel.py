"""
Flow down a vertical channel
============================

Grains flowing under gravity between two vertical walls: the weight is carried by wall
friction, the walls slip, and a shear layer forms at each wall around a plug-like core. The
velocity is scaled by its value on the centre line.
"""

import matplotlib.pyplot as plt

from cosserat import (
    Cosserat,
    Material,
    Problem,
    VerticalChannel,
    Wall,
    shear_layer_thickness,
    solve,
)

fig, ax = plt.subplots(figsize=(7.5, 4), layout="constrained")
for delta in (15.0, 20.0, 25.0):
    problem = Problem(
        VerticalChannel(eps=0.02), Cosserat(material=Material(), wall=Wall(delta=delta))
    )
    profile = solve(problem)
    Delta = shear_layer_thickness(profile)
    ax.plot(profile.xi, profile.u, label=f"delta = {delta:g} deg: Delta = {Delta:.1f} d")
ax.set_xlabel(r"$\xi = y/H$ (walls at 0 and 1)")
ax.set_ylabel("downward velocity / centre-line velocity")
ax.set_ylim(0.0, 1.05)
ax.grid(alpha=0.3)
fig.legend(loc="outside right upper")
plt.show()
