"""``cosserat sweep``: a parameter sweep from a TOML spec."""

from __future__ import annotations

import argparse
from pathlib import Path

from . import files
from .common import positive_int, progress_bar


def cmd_sweep(args: argparse.Namespace) -> None:
    import time

    from ..studies.sweep import check_table_format, load_spec, run_sweep, write_table

    spec = load_spec(args.spec)
    out = args.out or spec.output or str(Path(args.spec).with_suffix(".csv"))
    check_table_format(out)
    files.check_output_file(out, "--out" if args.out else "the sweep table")
    start = time.perf_counter()
    rows = run_sweep(
        spec, workers=args.workers, scheduler=args.scheduler, progress=progress_bar("sweep")
    )
    write_table(rows, out, spec.columns)
    states = ("ok", "no-solution", "error", "invalid")
    counts = {s: sum(r.get("status") == s for r in rows) for s in states}
    print(
        f"{len(rows)} cases in {time.perf_counter() - start:.1f} s -> {out} "
        f"({', '.join(f'{k}: {v}' for k, v in counts.items())})"
    )


def add_parsers(sub: argparse._SubParsersAction) -> None:  # type: ignore[type-arg]
    """Add this module's commands to the ``cosserat`` parser."""
    sw = sub.add_parser("sweep", help="run a parameter sweep from a TOML spec")
    sw.add_argument("spec", help="TOML file (see cosserat.sweep)")
    sw.add_argument("--out", default=None, help="table to write (.csv or .parquet)")
    sw.add_argument(
        "--workers", type=positive_int, default=None, help="local processes (default: cores)"
    )
    sw.add_argument(
        "--scheduler",
        default=None,
        help="Dask scheduler address (tcp://host:port) instead of local processes",
    )
    sw.set_defaults(func=cmd_sweep)
