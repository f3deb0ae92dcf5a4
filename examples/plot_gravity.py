"""
Plane shear under gravity
=========================

With gravity (``B = rho_p g H / N > 0``) the normal stress grows downwards, so friction is
mobilised first at the upper wall: the layer sits there and the lower wall does not slip. The
larger B, the thinner the layer; beyond B of about 2 (here) the couple stress reaches the yield
bound and the model has no solution (:class:`~cosserat.errors.NoSolutionError`).
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
)

fig, ax = plt.subplots(figsize=(8, 4), layout="constrained")
for B in (0.0, 0.5, 1.0, 2.0):
    problem = Problem(Plane(eps=0.04, B=B), Cosserat(material=Material(), wall=Wall(delta=20.0)))
    profile = solve(problem)
    Delta = shear_layer_thickness(profile)
    label = f"B = {B:g} ({problem.equations.case.value}):\nDelta = {Delta:.1f} d"
    ax.plot(profile.u, profile.xi, label=label)
ax.set_xlabel("velocity $u = v_x/V$")
ax.set_ylabel(r"$\xi = y/H$")
fig.legend(loc="outside right upper")
ax.grid(alpha=0.3)
plt.show()
