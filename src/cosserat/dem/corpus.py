"""The shipped DEM corpus: which runs it holds, and how one run goes from deck to profile.

``cosserat dem corpus --out DIR`` (or :func:`generate_corpus`) regenerates it; the files shipped
in ``cosserat/data/corpus/`` came from that command (docs/dem.md: what was run, its time).
"""

from __future__ import annotations

import json
import os
import time
from collections.abc import Callable
from dataclasses import replace
from pathlib import Path

from .._atomic import write_text
from ..errors import InputError
from .analyse import DEMProfile, read_samples, steady_profile
from .decks import build_deck, resume_deck
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


QS_SPEED = 0.0025
"""Wall speed of corpus v2 [sqrt(N / rho_s)]: the local inertial number next to the moving wall
stays at or below 5e-4 in the plane runs at H = 10 d (quasi-static, docs/dem.md)."""


def _qs_run(steps: int) -> RunLength:
    """Corpus v2's run length: checkpoints every 200k steps (restartable), a sample every 10k."""
    return RunLength(settle_steps=30_000, steps=steps, dump_every=10_000, restart_every=200_000)


def corpus_v2_cells() -> dict[str, Cell]:
    """Corpus v2's runs by name, as they were run (docs/dem.md, "Corpus v2"): quasi-static
    plane shear under gravity (B = 1) at H = 10 and 20 d for a rough and a smooth wall, the
    layer-position cell (no gravity, a smooth fixed lower wall, a rough moving upper one) and
    the 3-D twin of the rough run at H = 10 d; the half-speed partner of the rough run at
    H = 10 d, and the layer cell with a second seed and at a quarter of the speed; the gap
    series' next runs (both walls at H = 40 d, and a second seed at H = 20 d). A sitting
    rarely finishes one: every run writes checkpoints, and ``cosserat dem corpus --version 2``
    continues each from its last one.

    The rough run at H = 10 d was made as 16M steps and then continued to 20M (the same
    trajectory as 20M in one go: checkpointed runs resume byte for byte)."""
    cells: dict[str, Cell] = {}
    for label, wall, steps in (
        ("rough", ROUGH, {10: 20_000_000, 20: 24_000_000}),
        ("smooth", SMOOTH, {10: 16_000_000, 20: 24_000_000}),
    ):
        for gap in (10, 20):
            # gap a float, as the command line made these runs: the deck's parameter line
            # prints the cell's repr, in which 10 and 10.0 differ
            cells[f"plane_{label}_H{gap}_qs"] = PlaneShearDEM(
                gap=float(gap), width=30.0, B=1.0, wall_speed=QS_SPEED, wall=wall,
                run=_qs_run(steps[gap]),
            )  # fmt: skip
    layer = PlaneShearDEM(
        gap=10.0, width=30.0, B=0.0, wall_speed=QS_SPEED, wall=ROUGH, lower_wall=SMOOTH,
        upper_wall=ROUGH, run=_qs_run(20_000_000),
    )  # fmt: skip
    cells["plane_layer_H10_qs"] = layer
    # issue 18's follow-ups (referee 5): the rate-independence partner of the rough run, at
    # half the wall speed over the same 50 d of wall travel (twice the steps); the layer cell
    # again with another seed, and at a quarter of the wall speed (the same travel)
    rough = cells["plane_rough_H10_qs"]
    assert isinstance(rough, PlaneShearDEM)
    cells["plane_rough_H10_qs_half"] = replace(
        rough, wall_speed=QS_SPEED / 2, run=_qs_run(40_000_000)
    )
    cells["plane_layer_H10_qs_s2"] = replace(layer, seed=2)
    # referee 10, point 2: the wall's stress ratio differs by 2.2 se between V and V/2 (one
    # seed at each); a second seed at both speeds tells rate dependence from run-to-run scatter
    cells["plane_rough_H10_qs_s2"] = replace(rough, seed=2)
    cells["plane_rough_H10_qs_half_s2"] = replace(cells["plane_rough_H10_qs_half"], seed=2)
    cells["plane_layer_H10_qs_quarter"] = replace(
        layer, wall_speed=QS_SPEED / 4, run=_qs_run(80_000_000)
    )
    # the gap series' next runs (docs/dem.md, "Corpus v2: the design"): both walls at H = 40 d
    # (40 d + H = 80 d of travel: 32M steps), and a second seed at H = 20 d, the smallest gap
    # whose band does not fill it, for the run-to-run scatter of Delta the design assumed
    for label, wall in (("rough", ROUGH), ("smooth", SMOOTH)):
        h20 = cells[f"plane_{label}_H20_qs"]
        assert isinstance(h20, PlaneShearDEM)
        cells[f"plane_{label}_H20_qs_s2"] = replace(h20, seed=2)
        cells[f"plane_{label}_H40_qs"] = PlaneShearDEM(
            gap=40.0, width=30.0, B=1.0, wall_speed=QS_SPEED, wall=wall,
            run=_qs_run(32_000_000),
        )  # fmt: skip
    # the 3-D twin: the 2-D wall travel (49.9 d) at the 3-D time step (0.727e-3, 2-D 0.996e-3)
    cells["plane3d_rough_H10_qs"] = PlaneShearDEM(
        gap=10.0, width=15.0, B=1.0, wall_speed=QS_SPEED, wall=ROUGH, dim=3, depth=8.0,
        run=_qs_run(27_400_000),
    )  # fmt: skip
    return cells


CORPORA: dict[int, Callable[[], dict[str, Cell]]] = {1: corpus_cells, 2: corpus_v2_cells}
"""The corpora by version: 1, the shipped one (fast, not quasi-static); 2, the quasi-static one."""


def run_cell(
    cell: Cell, folder: str | Path, *, np: int = 1, keep_dumps: bool = False,
    engine: str = "subprocess", resume: bool = False,
) -> tuple[DEMProfile, float]:  # fmt: skip
    """Write a cell's deck in ``folder``, run it, coarse-grain it; returns the profile and
    the LAMMPS wall time [s] of all its segments. The dumps are deleted afterwards unless
    ``keep_dumps``. With ``resume``, continue a stopped run of the same cell from its last
    checkpoint (:func:`run_segment`)."""
    run_segment(cell, folder, np=np, engine=engine, resume=resume)
    profile = analyse_cell(cell, folder)
    if not keep_dumps:
        for name in ("atoms.dump", "contacts.dump"):
            (Path(folder) / name).unlink(missing_ok=True)
    return profile, float(profile.sidecar["wall_time_s"])


def latest_checkpoint(folder: str | Path) -> int | None:
    """The sheared step of the newest restart file ``restart.<step>.bin`` in ``folder`` (None:
    none). A file of that name is complete: the deck writes it under another name first."""
    steps = []
    for path in Path(folder).glob("restart.*.bin"):
        middle = path.name[len("restart.") : -len(".bin")]
        if middle.isdigit():
            steps.append(int(middle))
    return max(steps) if steps else None


def truncate_dump(path: str | Path, last_step: int) -> int:
    """Cut a LAMMPS text dump after its snapshot of step ``last_step`` (the snapshots a stopped
    run wrote after its last checkpoint are written again when it resumes); returns the
    number of snapshots kept."""
    path = Path(path)
    if not path.is_file():
        return 0
    kept, offset, cut = 0, 0, None
    with path.open("rb") as fh:
        expect_step = False
        for line in fh:
            if expect_step:
                if int(line) > last_step:
                    break
                kept += 1
                expect_step = False
            elif line == b"ITEM: TIMESTEP\n":
                expect_step, cut = True, offset
            offset += len(line)
        else:
            cut = None
    if cut is not None:
        os.truncate(path, cut)
    return kept


def _truncate_walls(path: Path, before_step: int) -> None:
    """Keep the comment lines of ``walls.txt`` and its lines of steps below ``before_step``."""
    if not path.is_file():
        return
    lines = path.read_text().splitlines(keepends=True)
    keep = [
        x for x in lines if x.startswith("#") or (x.split() and int(x.split()[0]) < before_step)
    ]
    write_text(path, "".join(keep))


def _loop_seconds(log: Path) -> float:
    """Sum of the ``Loop time`` of every finished ``run`` in a LAMMPS log [s] (the LAMMPS time
    of a segment that was stopped: its last, unfinished chunk is not counted)."""
    if not log.is_file():
        return 0.0
    total = 0.0
    for line in log.read_text(errors="replace").splitlines():
        if line.startswith("Loop time of "):
            total += float(line.split()[3])
    return total


def _utc() -> str:
    return time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime())


def run_segment(
    cell: Cell, folder: str | Path, *, np: int = 1, engine: str = "subprocess",
    resume: bool = False, stop_at: int | None = None,
) -> int:  # fmt: skip
    """Run (or, with ``resume``, continue) a cell in ``folder``; returns the sheared step
    reached.

    A fresh run writes the deck and starts from the beginning. A resumed run checks that
    ``deck.lmp`` is this cell's deck, finds the newest restart file (:func:`latest_checkpoint`),
    cuts the dumps after that step and ``walls.txt`` before it, writes
    ``resume.<step>.lmp`` (:func:`~cosserat.dem.decks.resume_deck`) and runs it with the log
    ``log.<step>.lammps``; without a restart file (stopped while settling) it starts again.
    ``run.json`` records every segment (deck, log, steps from and to, LAMMPS seconds, start
    time, status); a segment that was stopped is closed at its last checkpoint, its time the
    sum of its log's finished ``run`` loops. ``stop_at`` stops the segment at the first
    checkpoint at or after that step (LAMMPS's ``-var stop_at``; for tests and sittings).

    Raises
    ------
    InputError
        ``resume`` where no deck of this cell was run, or a cell without checkpoints.
    """
    from .runner import lammps_version, run_deck  # LAMMPS only on demand

    folder = Path(folder)
    deck = build_deck(cell)
    steps = cell.run.steps
    record_path = folder / "run.json"
    record: dict = {}
    start_step = 0
    if resume:
        if not (folder / "deck.lmp").is_file():
            raise InputError(f"nothing to resume: {folder / 'deck.lmp'} does not exist")
        if not cell.run.restart_every:
            if (folder / "deck.lmp").read_text() != deck.text:
                raise InputError(
                    f"cannot resume: {folder / 'deck.lmp'} is not the deck of this cell"
                )
            raise InputError("cannot resume a run without checkpoints (restart_every = 0)")
        base = deck_cell(cell, folder)  # this cell, or it with fewer steps: an extension
        record = json.loads(record_path.read_text()) if record_path.is_file() else {}
        start_step = latest_checkpoint(folder) or 0
        for seg in record.get("segments", []):
            if seg.get("status") == "running":  # stopped: closed at the checkpoint it reached
                seg.update(status="stopped", to_step=start_step,
                           seconds=round(_loop_seconds(folder / seg["log"]), 1))  # fmt: skip
        if start_step >= steps:
            _write_record(record_path, record)
            return steps
    if not resume or latest_checkpoint(folder) is None:
        for pattern in ("restart.*", "resume.*.lmp", "log.*.lammps"):  # an older run's
            for old in folder.glob(pattern):
                old.unlink()
        deck.write(folder)
        name, log, start_step = "deck.lmp", "log.lammps", 0
        record = {"segments": []} if not resume else record
    else:
        for dump in ("atoms.dump", "contacts.dump"):
            truncate_dump(folder / dump, start_step)
        _truncate_walls(folder / "walls.txt", start_step)
        name, log = f"resume.{start_step}.lmp", f"log.{start_step}.lammps"
        write_text(folder / name, resume_deck(cell, start_step, build_deck(base).sha256))
    variables = {} if stop_at is None else {"stop_at": str(stop_at)}
    segment = {"deck": name, "log": log, "from_step": start_step, "to_step": None,
               "seconds": None, "started_utc": _utc(), "status": "running"}  # fmt: skip
    record.setdefault("segments", []).append(segment)
    record["lammps_version"] = lammps_version()
    _write_record(record_path, record)
    done = run_deck(folder, np=np, engine=engine, deck=name, log=log, variables=variables)
    reached = latest_checkpoint(folder) if cell.run.restart_every else steps
    segment.update(status="finished" if reached == steps else "stopped", to_step=reached,
                   seconds=round(done.seconds, 1), command=done.command)  # fmt: skip
    _write_record(record_path, record)
    return int(reached if reached is not None else 0)


def deck_cell(cell: Cell, folder: str | Path) -> Cell:
    """The cell whose deck is ``folder/deck.lmp``: ``cell`` itself, or, for a checkpointed
    run continued for longer (``cell`` with more ``steps``, an extension), ``cell`` with the
    deck's own steps (read from its chunk loop).

    Raises
    ------
    InputError
        ``deck.lmp`` is neither.
    """
    path = Path(folder) / "deck.lmp"
    text = path.read_text()
    if text == build_deck(cell).text:
        return cell
    run = cell.run
    prefix = "variable chunk loop 1 "
    loops = [x[len(prefix) :] for x in text.splitlines() if x.startswith(prefix)]
    if run.restart_every and len(loops) == 1 and loops[0].isdigit():
        steps = int(loops[0]) * run.restart_every
        if steps < run.steps:
            base = replace(cell, run=replace(run, steps=steps))
            if text == build_deck(base).text:
                return base
    raise InputError(f"cannot resume: {path} is not the deck of this cell")


def _write_record(path: Path, record: dict) -> None:
    """``run.json``: the segments, their total LAMMPS time (``seconds``) and the version."""
    record["seconds"] = round(sum(s.get("seconds") or 0.0 for s in record.get("segments", [])), 1)
    if record.get("segments"):
        record["command"] = record["segments"][0].get("command")
    write_text(path, json.dumps(record, indent=1) + "\n")


def analyse_cell(cell: Cell, folder: str | Path) -> DEMProfile:
    """Coarse-grain a finished run of ``cell`` in ``folder`` (its dumps and ``run.json``)."""
    deck = build_deck(cell)
    folder = Path(folder)
    written = (folder / "deck.lmp").read_text()
    base = cell
    if written != deck.text:
        try:
            base = deck_cell(cell, folder)  # a checkpointed run continued for longer
        except InputError:
            raise InputError(f"{folder / 'deck.lmp'} is not the deck of this cell") from None
    record = _run_record(folder)
    samples = read_samples(folder, deck)
    profile = steady_profile(samples, deck, lammps_version=record["lammps_version"])
    profile.sidecar["wall_time_s"] = record["seconds"]
    if base is not cell:  # the sidecar names the deck that ran first, and its length
        profile.sidecar["deck_sha256"] = build_deck(base).sha256
        profile.sidecar["extended_from_steps"] = base.run.steps
    if len(record.get("segments") or []) > 1:
        profile.sidecar["segments"] = [
            {k: seg.get(k) for k in ("deck", "from_step", "to_step", "seconds", "status")}
            for seg in record["segments"]
        ]
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
    log: Callable[[str], None] = print, reanalyse: bool = False, version: int = 1,
) -> dict[str, float]:  # fmt: skip
    """Run the corpus's cells (or ``names`` of them) and write ``<name>.csv/.json`` into
    ``out``; the decks, LAMMPS logs and dumps stay in ``work/<name>``. With ``reanalyse``,
    only coarse-grain the runs already in ``work`` again. ``version`` 2 is corpus v2
    (:func:`corpus_v2_cells`): a run whose deck is in ``work/<name>`` already continues from
    its last checkpoint, so a stopped regeneration is taken up by running it again. Returns
    the LAMMPS wall times [s]."""
    if version not in CORPORA:
        raise InputError(f"corpus version must be one of {sorted(CORPORA)}; got {version!r}")
    cells = CORPORA[version]()
    chosen = list(cells) if names is None else names
    unknown = [n for n in chosen if n not in cells]
    if unknown:
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
            resume = version == 2 and (work / name / "deck.lmp").is_file()
            log(f"{name}: {'continuing' if resume else 'running'} in {work / name}")
            profile, seconds = run_cell(
                cells[name], work / name, np=np, keep_dumps=True, resume=resume
            )
        profile.write(out, name)
        times[name] = seconds
        log(f"{name}: {seconds:.0f} s of LAMMPS, {time.perf_counter() - start:.0f} s so far")
    write_text(out / "timing.json", json.dumps(
        {"runs_s": times, "total_s": round(time.perf_counter() - start, 1), "np": np}, indent=1
    ) + "\n")  # fmt: skip
    return times


__all__ = [
    "CHANNEL_RUN",
    "CORPORA",
    "CORPUS_RUN",
    "HALFSPEED_RUN",
    "QS_SPEED",
    "corpus_cells",
    "corpus_v2_cells",
    "deck_cell",
    "generate_corpus",
    "latest_checkpoint",
    "run_cell",
    "run_segment",
    "truncate_dump",
]
