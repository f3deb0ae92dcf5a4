"""
Couette flow: the curvature of the cell
=======================================

Between two coaxial cylinders, the inner one turning, the shear stress falls outwards like
``1/r^2``: the shear layer sits at the inner cylinder and narrows as the inner radius shrinks.
``u = -v_theta/V_i`` is -1 at the inner wall (the paper's sign; see :doc:`/cells/couette`).
"""

import matplotlib.pyplot as plt

from cosserat import (
    Cosserat,
    Couette,
    Material,
    Problem,
    Wall,
    shear_layer_thickness,
    solve,
)

fig, ax = plt.subplots(figsize=(6, 4), layout="constrained")
for Ri in (0.5, 1.0, 4.0, 20.0):
    wall = Wall(delta=20.0)
    problem = Problem(Couette(eps=0.04, Ri=Ri), Cosserat(material=Material(), wall=wall))
    profile = solve(problem)
    Delta = shear_layer_thickness(profile)
    label = f"Ri = {Ri:g}: Delta = {Delta:.1f} d"
    ax.plot(-profile.u, profile.xi / problem.eps, label=label)
ax.set_xlabel(r"$-u = v_\theta / V_i$")
ax.set_ylabel("distance from the inner cylinder $(r - R_i)/d$")
ax.legend(loc="upper right")
ax.grid(alpha=0.3)
plt.show()
