"""
A real Couette cell, in SI units
================================

:class:`~cosserat.analysis.cell.CouetteCell` takes a laboratory cell (grain size and density,
radii, fill depth, rotation rate) and turns the dimensionless profile into metres per second,
pascals and newton metres. The model is rate-independent: the velocity scales with the rotation
rate, the torque does not.
"""

import matplotlib.pyplot as plt

from cosserat import Material, Wall, solve
from cosserat.cell import CouetteCell

cell = CouetteCell(
    density=2500,  # grain density [kg/m^3]
    grain_diameter=1e-3,  # grain diameter [m]
    gap=0.02,  # [m]
    inner_radius=0.02,  # inner radius [m]
    fill_depth=0.1,  # [m]
    rotation_rate=0.5,  # inner cylinder [rad/s]
)
profile = solve(cell.problem(Material(phi=28.5), Wall(delta=20.0, K=0.5)))

print(f"eps = d/H = {cell.eps:g}, Ri = R_i/H = {cell.Ri:g}, Froude {cell.froude:.2g}")
print(f"torque on the inner cylinder: {cell.torque(profile):.4g} N m")
stress = cell.wall_shear_stress(profile, depth=0.1)
print(f"wall shear stress at the bottom: {stress:.4g} Pa")
print(f"slip velocity: {1e3 * cell.slip_velocity(profile):.3g} mm/s")

fig, ax = plt.subplots(figsize=(6, 4), layout="constrained")
ax.plot(1e3 * cell.radius(profile), 1e3 * cell.velocity(profile))
ax.set_xlabel("radius $r$ [mm]")
ax.set_ylabel(r"azimuthal velocity $v_\theta$ [mm/s]")
ax.grid(alpha=0.3)
plt.show()
