"""
Plane shear: velocity, spin and couple stress
=============================================

The basic problem of the paper: a layer of grains between two parallel walls, the upper wall
moving at speed V, the lower at rest, both with the paper's wall friction angle
delta = 20 deg. Without gravity the solution is symmetric: a shear layer of a few tens of grain
diameters at each wall, and slip at both walls.
"""

import matplotlib.pyplot as plt

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

wall = Wall(delta=20.0, K=0.5)  # angle of wall friction [deg], slip coefficient
problem = Problem(Plane(eps=0.01), Cosserat(material=Material(phi=28.5), wall=wall))
profile = solve(problem)
print(f"Delta = {shear_layer_thickness(profile):.2f} grain diameters")
print(f"slip at the moving wall = {wall_slip(profile):.4f} V")

# %%
# ``profile`` holds every field on a grid across the gap, ``xi = y/H`` from 0 (lower wall) to
# 1 (upper wall). Distances in grain diameters are ``y/d = xi/eps``.

y_d = profile.xi / problem.eps
fig, axes = plt.subplots(1, 3, figsize=(9, 3.6), sharey=True, layout="constrained")
axes[0].plot(profile.u, y_d)
axes[0].set_xlabel("velocity $u = v_x/V$")
axes[1].plot(profile.omega, y_d)
axes[1].set_xlabel(r"spin $\omega H/V$")
axes[2].plot(profile.m, y_d)
axes[2].set_xlabel("couple stress $m$")
axes[0].set_ylabel("distance from the lower wall $y/d$")
for ax in axes:
    ax.grid(alpha=0.3)
plt.show()
