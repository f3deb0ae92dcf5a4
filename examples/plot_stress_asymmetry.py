"""
What makes it Cosserat: asymmetric stress and grain spin
========================================================

In a Cosserat continuum the stress need not be symmetric: the difference
``sigma_yx - sigma_xy`` is balanced by the gradient of the couple stress, and the grains spin
at a rate that differs from half the vorticity inside the shear layer. Both vanish in the
core of the gap.
"""

import matplotlib.pyplot as plt

from cosserat import Material, PlaneShear, Wall, solve

problem = PlaneShear(material=Material(), upper=Wall(delta=20.0), eps=0.02)
profile = solve(problem)
y_d = profile.xi / problem.eps

fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(8, 3.8), sharey=True, layout="constrained")
ax1.plot(profile.asymmetry, y_d)
ax1.set_xlabel(r"stress asymmetry $\bar\sigma_{yx} - \bar\sigma_{xy}$")
ax2.plot(profile.spin_minus_half_vorticity, y_d)
ax2.set_xlabel(r"$\omega - \frac{1}{2}$ vorticity  (scaled)")
ax1.set_ylabel("$y/d$")
for ax in (ax1, ax2):
    ax.grid(alpha=0.3)
plt.show()
