"""
What makes it Cosserat: asymmetric stress and grain spin
========================================================

In a Cosserat continuum the stress need not be symmetric: the asymmetry is the gradient of the
couple stress, ``2(A+1) eps alpha dm/dxi = sigma_yx - sigma_xy``. Between identical walls the
couple stress runs from its value at one wall to minus it at the other, so the asymmetry is
largest at the centre, where m changes sign; as the gap widens (eps falls) it concentrates
there. The grains spin at a rate that differs from half the vorticity by an amount that
vanishes quickly as the gap widens.
"""

import matplotlib.pyplot as plt
from matplotlib.ticker import MaxNLocator

from cosserat import Cosserat, Material, Plane, Problem, Wall, solve

fig, axes = plt.subplots(1, 3, figsize=(10, 3.8), sharex=True, layout="constrained")
for eps in (0.05, 0.02, 0.01):
    profile = solve(Problem(Plane(eps=eps), Cosserat(material=Material(), wall=Wall(delta=20.0))))
    label = f"eps = {eps:g}"
    axes[0].plot(profile.xi, profile.m, label=label)
    axes[1].plot(profile.xi, profile.asymmetry, label=label)
    axes[2].plot(profile.xi, profile.spin_minus_half_vorticity, label=label)
axes[0].set_ylabel("couple stress $m$")
axes[1].set_ylabel(r"asymmetry $\bar\sigma_{yx} - \bar\sigma_{xy}$")
axes[2].set_ylabel(r"$\omega + \frac{1}{2}\,du/d\xi$ (spin $-$ half the vorticity)")
for ax in axes:
    ax.set_xlabel(r"$\xi = y/H$")
    ax.yaxis.set_major_locator(MaxNLocator(5))
    ax.grid(alpha=0.3)
fig.legend(*axes[0].get_legend_handles_labels(), loc="outside upper center", ncols=3)
plt.show()
