"""The shipped DEM corpus: which runs it holds, and how one run goes from deck to profile.

``cosserat dem corpus --out DIR`` (or :func:`generate_corpus`) regenerates it; the files shipped
in ``cosserat/data/corpus/`` came from that command (docs/dem.md: what was run, its time).
"""

from __future__ import annotations

import json
import time
from collections.abc import Callable
from dataclasses import replace
from pathlib import Path

from .._atomic import write_text
from .analyse import DEMProfile, read_samples, steady_profile
from .decks import build_deck
from .params import Cell, ChannelDEM, CouetteDEM, PlaneShearDEM, RunLength, WallRoughness

ROUGH = WallRoughness("glued-grains", glued_diameter=1.0, glued_spacing=1.0)
SMOOTH = WallRoughness("smooth-frictional")
CORPUS_RUN = RunLength(settle_steps=30_000, steps=400_000, dump_every=1_000)
"""Run length of the corpus's smallest plane cells (H = 20 d): 400 samples of the sheared
state at a 0.996e-3 time step."""
SHORT_RUN = RunLength(settle_steps=30_000, steps=250_000, dump_every=1_000)
"""Run length of the plane cells at H = 40 d, the channel and Couette at H = 10 d."""
LONG_RUN = RunLength(settle_steps=30_000, steps=600_000, dump_every=1_500)
"""Run length of the plane cells at H = 80 d (driven at V = 0.2: 250k steps at V = 0.1 left
them in their transient, the upper 50 d sliding as a block)."""
COUETTE_RUN = RunLength(settle_steps=30_000, steps=200_000, dump_every=1_000)
"""Run length of the largest cell (Couette H = 20 d, 3,837 grains)."""
HALFSPEED_RUN = RunLength(settle_steps=30_000, steps=800_000, dump_every=1_000)
"""Run length of the rate check at half the wall speed (plane, rough, H = 20 d, V = 0.05):
twice the steps of :data:`CORPUS_RUN`, so the same strain; 400k steps left the velocity's
standard error at 0.059 of V in the shear layer, above the 5% target."""
CHANNEL_RUN = RunLength(settle_steps=30_000, steps=1_000_000, dump_every=1_000)
"""Run length of the channel: at rho_s nu g H / (2N) = 0.40 its flow rate settles after about
300k steps and then fluctuates by +-10% on a time of about 100k steps."""


def corpus_cells() -> dict[str, Cell]:
    """The corpus's runs by name: plane shear under gravity (B = 1) at three gaps for a rough
    and a smooth wall, plus one run at half the wall speed (the rate check); annular Couette at
    two gaps; one vertical channel. The run lengths fit the corpus into about an hour on a
    shared 2-core machine (docs/dem.md)."""
    cells: dict[str, Cell] = {}
    for label, wall in (("rough", ROUGH), ("smooth", SMOOTH)):
        for gap in (20, 40, 80):
            run = {20: CORPUS_RUN, 40: SHORT_RUN, 80: LONG_RUN}[gap]
            speed = 0.2 if gap == 80 else 0.1  # H = 80 d: twice the strain per step
            cells[f"plane_{label}_H{gap}"] = PlaneShearDEM(gap=gap, width=30.0, B=1.0,
                                                           wall_speed=speed, wall=wall,
                                                           run=run)  # fmt: skip
    rough_20 = cells["plane_rough_H20"]
    assert isinstance(rough_20, PlaneShearDEM)  # made in the loop above
    cells["plane_rough_H20_halfspeed"] = replace(rough_20, wall_speed=0.05,
                                                 run=HALFSPEED_RUN)  # fmt: skip
    for gap, run in ((10, SHORT_RUN), (20, COUETTE_RUN)):
        cells[f"couette_Ri20_H{gap}"] = CouetteDEM(gap=gap, inner_radius=20.0, wall=ROUGH,
                                                    run=run)  # fmt: skip
    # rho_s nu g H / (2N) = 0.32, 0.38 and 0.39 stay jammed after settling (0.39 for 1M steps);
    # 0.40 and 0.41 reach a steady flow within 1M steps, 0.42 still accelerates (docs/dem.md)
    cells["channel_rough_H20"] = ChannelDEM(gap=20, length=30.0, shear_ratio=0.40, wall=ROUGH,
                                            run=CHANNEL_RUN)  # fmt: skip
    return cells


def run_cell(
    cell: Cell, folder: str | Path, *, np: int = 1, keep_dumps: bool = False,
    engine: str = "subprocess",
) -> tuple[DEMProfile, float]:  # fmt: skip
    """Write a cell's deck in ``folder``, run it, coarse-grain it; returns the profile and
    the LAMMPS wall time [s]. The dumps are deleted afterwards unless ``keep_dumps``."""
    from .runner import run_deck  # LAMMPS only on demand

    build_deck(cell).write(folder)
    record = run_deck(folder, np=np, engine=engine)
    write_text(Path(folder) / "run.json", json.dumps(
        {"seconds": round(record.seconds, 1), "lammps_version": record.lammps_version,
         "command": record.command}, indent=1) + "\n")  # fmt: skip
    profile = analyse_cell(cell, folder)
    if not keep_dumps:
        for name in ("atoms.dump", "contacts.dump"):
            (Path(folder) / name).unlink(missing_ok=True)
    return profile, record.seconds


def analyse_cell(cell: Cell, folder: str | Path) -> DEMProfile:
    """Coarse-grain a finished run of ``cell`` in ``folder`` (its dumps and ``run.json``)."""
    deck = build_deck(cell)
    folder = Path(folder)
    written = (folder / "deck.lmp").read_text()
    if written != deck.text:
        from ..errors import InputError

        raise InputError(f"{folder / 'deck.lmp'} is not the deck of this cell")
    record = _run_record(folder)
    samples = read_samples(folder, deck)
    profile = steady_profile(samples, deck, lammps_version=record["lammps_version"])
    profile.sidecar["wall_time_s"] = record["seconds"]
    return profile


def _run_record(folder: Path) -> dict:
    """``run.json``, or (a run made elsewhere, or whose driver was stopped) the wall time from
    LAMMPS's log and the installed LAMMPS version."""
    if (folder / "run.json").is_file():
        return json.loads((folder / "run.json").read_text())
    from .runner import lammps_version

    seconds = float("nan")
    log = folder / "log.lammps"
    if log.is_file():
        for line in log.read_text().splitlines():
            if line.startswith("Total wall time:"):
                h, m, sec = (int(x) for x in line.split()[-1].split(":"))
                seconds = 3600.0 * h + 60.0 * m + sec
    return {"seconds": seconds, "lammps_version": lammps_version()}


def generate_corpus(
    out: str | Path, work: str | Path, *, names: list[str] | None = None, np: int = 1,
    log: Callable[[str], None] = print, reanalyse: bool = False,
) -> dict[str, float]:  # fmt: skip
    """Run the corpus's cells (or ``names`` of them) and write ``<name>.csv/.json`` into
    ``out``; the decks, LAMMPS logs and dumps stay in ``work/<name>``. With ``reanalyse``,
    only coarse-grain the runs already in ``work`` again. Returns the LAMMPS wall times [s]."""
    cells = corpus_cells()
    chosen = list(cells) if names is None else names
    unknown = [n for n in chosen if n not in cells]
    if unknown:
        from ..errors import InputError

        raise InputError(f"unknown corpus runs {unknown}; known: {sorted(cells)}")
    out, work = Path(out), Path(work)
    out.mkdir(parents=True, exist_ok=True)
    times: dict[str, float] = {}
    start = time.perf_counter()
    for name in chosen:
        if reanalyse:
            profile = analyse_cell(cells[name], work / name)
            seconds = profile.sidecar["wall_time_s"]
        else:
            log(f"{name}: running in {work / name}")
            profile, seconds = run_cell(cells[name], work / name, np=np, keep_dumps=True)
        profile.write(out, name)
        times[name] = seconds
        log(f"{name}: {seconds:.0f} s of LAMMPS, {time.perf_counter() - start:.0f} s so far")
    write_text(out / "timing.json", json.dumps(
        {"runs_s": times, "total_s": round(time.perf_counter() - start, 1), "np": np}, indent=1
    ) + "\n")  # fmt: skip
    return times


__all__ = [
    "CHANNEL_RUN",
    "CORPUS_RUN",
    "HALFSPEED_RUN",
    "corpus_cells",
    "generate_corpus",
    "run_cell",
]
