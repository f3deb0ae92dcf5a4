"""
Calibrate one material from several experiments
===============================================

Two of the shipped DEM runs of one material (plane shear under gravity at H = 40 d, and a
Couette cell at H = 20 d, both with glued-grain walls) are fitted *jointly*: the material's
parameters are shared by both runs, the wall's by both cells, and what each run's metadata give
(the gap, gravity, the wall's inertial number) is fixed. The velocity, the spin and the stress
ratio in the band all enter the likelihood, with correlated bins (:doc:`/calibration`).

These runs are not quasi-static (the local inertial number at the moving wall is 1e-2 to
7e-2), so no model is expected to describe them: the calibration says where each one misses.
The walk-through is :doc:`/howto/calibrate`.
"""

import matplotlib.pyplot as plt

from cosserat.analysis.corpus import shipped_corpus
from cosserat.calibration import calibrate
from cosserat.calibration.report import figure_data, text
from cosserat.viz.calibration import run_figure

corpus = shipped_corpus()
cal = calibrate(
    [corpus / "plane_rough_H40.csv", corpus / "couette_Ri20_H20.csv"],
    models=["cosserat", "ngf"],
)
print(text(cal))

(plane,) = [entry for entry in figure_data(cal) if entry["name"] == "plane_rough_H40"]
fig = run_figure(plane)
plt.show()
