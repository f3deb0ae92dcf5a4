"""
Local mu(I) beside the Cosserat model
=====================================

The same Couette cell with two rheologies: the local mu(I) law (GDR MiDi 2004; Jop, Forterre &
Pouliquen 2006; glass beads) and the frictional Cosserat model. Each is a
:class:`~cosserat.Problem` of the cell and the rheology, solved by the same
:func:`~cosserat.solve`; both profiles are :class:`~cosserat.results.profile.Profile` objects,
so the same analysis applies.
"""

import matplotlib.pyplot as plt

from cosserat import Cosserat, Couette, MuI, Problem, shear_layer_thickness, solve

cell = Couette(eps=0.04, Ri=1.0, I_w=0.01)  # I_w drives mu(I); the Cosserat model has no drive
mui = solve(Problem(cell, MuI()), method="closed-form")
cosserat = solve(Problem(Couette(eps=0.04, Ri=1.0), Cosserat()))

fig, ax = plt.subplots(figsize=(6, 4), layout="constrained")
for name, profile in (("mu(I), I_w = 0.01", mui), ("Cosserat", cosserat)):
    Delta = shear_layer_thickness(profile)
    label = f"{name}: Delta = {Delta:.2f} d"
    ax.plot(-profile.u, profile.xi / cell.eps, label=label)
ax.set_xlabel(r"$v_\theta / V_i$")
ax.set_ylabel("distance from the inner cylinder $(r - R_i)/d$")
ax.legend(loc="upper right")
ax.grid(alpha=0.3)
plt.show()
