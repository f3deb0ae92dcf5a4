"""
Three rheologies on one Couette cell
====================================

The frictional Cosserat model, the local mu(I) law and the nonlocal granular fluidity (NGF)
model on the same cell (eps = d/H = 0.04, R_i/H = 1): one :class:`~cosserat.Couette` cell, three
rheologies, each :class:`~cosserat.Problem` solved by :func:`~cosserat.solve`. mu(I) and NGF are
rate-dependent and are driven at the inertial number of the wall speed, the cell's I_w (its
default, 0.01); the Cosserat model is rate-independent and does not read it. Outside its shear
layer mu(I) stops dead (a plug), while NGF creeps: its fluidity diffuses into the region below
the yield stress ratio.
"""

import matplotlib.pyplot as plt

from cosserat import NGF, Cosserat, Couette, MuI, Problem, shear_layer_thickness, solve

cell = Couette(eps=0.04, Ri=1.0)
profiles = {
    "Cosserat": solve(Problem(cell, Cosserat())),
    "mu(I)": solve(Problem(cell, MuI()), method="closed-form"),
    "NGF": solve(Problem(cell, NGF())),
}

fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(10, 4), layout="constrained")
for name, profile in profiles.items():
    Delta = shear_layer_thickness(profile)
    label = f"{name}: Delta = {Delta:.2f} d"
    distance = profile.xi / cell.eps
    ax1.plot(distance, -profile.u, label=label)
    ax2.semilogy(distance, abs(profile.u), label=label)
ax1.set_ylabel(r"$v_\theta / V_i$")
ax2.set_ylabel(r"$|v_\theta| / V_i$ (log)")
ax2.set_ylim(1e-12, 2.0)
for ax in (ax1, ax2):
    ax.set_xlabel("distance from the inner cylinder $(r - R_i)/d$")
    ax.grid(alpha=0.3)
fig.legend(*ax1.get_legend_handles_labels(), loc="outside upper center", ncols=3)
plt.show()
