"""
Profiles as tables: pandas and CSV
==================================

A :class:`~cosserat.results.profile.Profile` exports its columns (named in the cell's own
coordinates) to pandas, xarray, CSV and JSON, so it drops into a notebook.
"""

import matplotlib.pyplot as plt

from cosserat import Cosserat, Material, Plane, Problem, Wall, solve

problem = Problem(Plane(eps=0.04), Cosserat(material=Material(), wall=Wall(delta=20.0)))
profile = solve(problem, points=41)
table = profile.to_dataframe()
print(list(table.columns))
print(table.iloc[:5, :4])

ax = table.plot(x=table.columns[1], y=table.columns[0], legend=False, figsize=(5, 4))
ax.set_xlabel(table.columns[1])
ax.set_ylabel(table.columns[0])
ax.grid(alpha=0.3)
plt.show()
