"""
A parameter sweep
=================

:mod:`cosserat.studies.sweep` runs a grid of cases (the same specification as
``cosserat sweep spec.toml``) and returns one row per case, failures included. Here: Delta over
eps and the wall friction angle, in this process; on a cluster the same call takes a Dask
scheduler address (:doc:`/howto/dask_sweep`).
"""

import matplotlib.pyplot as plt

from cosserat.studies.sweep import parse_spec, run_sweep

spec = parse_spec(
    {
        "geometry": "plane",
        "grid": {
            "eps": {"geomspace": [0.05, 1e-5, 10]},
            "delta": [12.0, 16.0, 20.0, 24.0],
        },
    }
)
rows = run_sweep(spec, workers=1)
print(f"{len(rows)} cases, {sum(r['status'] != 'ok' for r in rows)} failed")

fig, ax = plt.subplots(figsize=(7.5, 4), layout="constrained")
for delta in (12.0, 16.0, 20.0, 24.0):
    sel = [r for r in rows if r["delta"] == delta and r["status"] == "ok"]
    ax.semilogx(
        [r["eps"] for r in sel],
        [r["Delta"] for r in sel],
        "o-",
        ms=3,
        label=f"delta = {delta:g} deg",
    )
ax.set_xlabel(r"$\varepsilon = d/H$")
ax.set_ylabel(r"$\Delta$ [grain diameters]")
fig.legend(loc="outside right upper")
ax.grid(alpha=0.3, which="both")
plt.show()
