"""
Three routes to one profile
===========================

:func:`~cosserat.routes.solve` has three routes: the compiled ``"numerical"`` one (every
problem, every eps), the paper's ``"closed-form"`` solution (plane shear without gravity) and
the leading order in eps of the paper's Appendix (``"asymptotic"``, valid when the layer is much
thinner than the gap). Here they are side by side at eps = 0.002, near the moving upper wall.
"""

import matplotlib.pyplot as plt
import numpy as np

from cosserat import Cosserat, Material, Plane, Problem, Wall, solve

problem = Problem(Plane(eps=0.002), Cosserat(material=Material(), wall=Wall(delta=20.0)))
fig, ax = plt.subplots(figsize=(6, 4), layout="constrained")
for method, style in (("numerical", "-"), ("closed-form", "--"), ("asymptotic", ":")):
    profile = solve(problem, method=method)
    ax.plot(profile.u, (1.0 - profile.xi) / problem.eps, style, lw=2, label=method)
ax.set_ylim(60.0, 0.0)
ax.set_xlabel("velocity $u = v_x/V$")
ax.set_ylabel("distance from the moving wall $(H - y)/d$")
ax.legend(loc="lower left")
ax.grid(alpha=0.3)

numerical = solve(problem)
closed = solve(problem, method="closed-form", xi=numerical.xi)
difference = np.max(np.abs(numerical.u - closed.u))
print(f"max |numerical - closed form| in u: {difference:.2e}")
plt.show()
