"""Cost of the 3-D twin of the quasi-static rough plane run (issue 18 item 3):
``python benchmarks/dem_3d_cost.py`` (needs the ``dem`` extra).

Runs the decks of the 3-D twin (spheres, H = 10 d, slab 15 d x 8 d) and of its 2-D twin
(disks, H = 10 d, width 30 d), each 30,000 settling + 2,000 sheared steps, one process, and
reads LAMMPS's log: the sheared stage's CPU time per step (its loop time less the dumps'
output time, times LAMMPS's "% CPU use", so a loaded machine's share of the core is taken
out), then the CPU-hours of the quasi-static runs: 27.4M sheared steps in 3-D, 20M in 2-D (the
same 49.9 d of wall travel at the two time steps). ``uptime`` is printed beside them.
"""

from __future__ import annotations

import os
import tempfile
from pathlib import Path

from cosserat.dem import PlaneShearDEM, RunLength, build_deck
from cosserat.dem.runner import run_deck

BENCH = RunLength(settle_steps=30_000, steps=2_000, dump_every=200)
QS_STEPS = {2: 20_000_000, 3: 27_400_000}
"""Sheared steps of the quasi-static runs (2-D: data/dem_v2/plane_rough_H10_qs)."""


def sheared_cpu_per_step(log: Path) -> tuple[float, int]:
    """CPU seconds per step of the last ``run`` in a LAMMPS log (loop time less output time,
    times the CPU share) and the number of atoms."""
    lines = log.read_text().splitlines()
    k = max(i for i, x in enumerate(lines) if x.startswith("Loop time of "))
    words = lines[k].split()
    loop, steps, atoms = float(words[3]), int(words[8]), int(words[11])
    share = float(next(x for x in lines[k:] if "% CPU use" in x).split("%")[0]) / 100.0
    output = float(next(x for x in lines[k:] if x.startswith("Output ")).split("|")[2])
    return (loop - output) * share / steps, atoms


def main() -> None:
    twin = {"gap": 10.0, "B": 1.0, "wall_speed": 0.0025, "run": BENCH}
    cells = {
        3: PlaneShearDEM(width=15.0, dim=3, depth=8.0, **twin),
        2: PlaneShearDEM(width=30.0, **twin),
    }
    print(f"load average before: {os.getloadavg()}")
    for dim, cell in cells.items():
        deck = build_deck(cell)
        with tempfile.TemporaryDirectory() as tmp:
            deck.write(tmp)
            run_deck(tmp, np=1)
            per_step, atoms = sheared_cpu_per_step(Path(tmp) / "log.lammps")
        hours = per_step * QS_STEPS[dim] / 3600.0
        print(
            f"{dim}-D: {atoms} atoms, dt {deck.timestep:.4g}: {per_step * 1e3:.3f} ms of CPU per "
            f"sheared step ({atoms / per_step:.3g} atom-steps per CPU second); "
            f"{QS_STEPS[dim] / 1e6:g}M steps: {hours:.1f} CPU-hours"
        )
    print(f"load average after: {os.getloadavg()}")


if __name__ == "__main__":
    main()
