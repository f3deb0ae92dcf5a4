"""DEM throughput: LAMMPS atom-steps per second on a plane-shear deck, and the coarse-graining's
samples per second: ``python benchmarks/dem_throughput.py [gap]`` (needs the ``dem`` extra).

Writes the deck of a plane cell (gravity B = 1, rough walls, width 30 d) into a temporary
folder, runs 2,000 settling + 20,000 sheared steps with the wheel's ``lmp`` (serial, and with
``mpirun -np 2`` when mpirun is found), then coarse-grains the 20 samples. On a shared machine
the numbers depend on the load: ``uptime`` is printed beside them.
"""

from __future__ import annotations

import os
import shutil
import sys
import tempfile
import time
from pathlib import Path

from cosserat.dem import PlaneShearDEM, RunLength, build_deck
from cosserat.dem.analyse import read_samples, steady_profile
from cosserat.dem.runner import run_deck


def main() -> None:
    gap = float(sys.argv[1]) if len(sys.argv) > 1 else 20.0
    run = RunLength(settle_steps=2_000, steps=20_000, dump_every=1_000)
    cell = PlaneShearDEM(gap=gap, width=30.0, run=run)
    deck = build_deck(cell)
    atoms = deck.layout.x.size
    print(f"plane cell H = {gap:g} d: {atoms} atoms, {run.settle_steps + run.steps} steps")
    print(f"load average: {os.getloadavg()}")
    for np_ in (1, 2) if shutil.which("mpirun") else (1,):
        with tempfile.TemporaryDirectory() as tmp:
            deck.write(tmp)
            record = run_deck(tmp, np=np_)
            rate = atoms * (run.settle_steps + run.steps) / record.seconds
            print(f"  np={np_}: {record.seconds:.1f} s, {rate:.3g} atom-steps/s")
            if np_ == 1:
                start = time.perf_counter()
                samples = read_samples(Path(tmp), deck)
                steady_profile(samples, deck, lammps_version=record.lammps_version)
                seconds = time.perf_counter() - start
                n = samples.samples.steps.size
                print(f"  coarse-graining: {n} samples in {seconds:.2f} s ({n / seconds:.0f}/s)")


if __name__ == "__main__":
    main()
