"""``cosserat sweep``: a parameter sweep from a TOML spec, resumable after an interruption."""

from __future__ import annotations

import argparse
from pathlib import Path

from . import files
from .common import add_quiet, positive_int, progress_bar, set_interrupt_hint


def cmd_sweep(args: argparse.Namespace) -> None:
    import time

    from ..studies.sweep import check_table_format, journal_path, load_spec, run_sweep_to_table

    spec = load_spec(args.spec)
    out = args.out or spec.output or str(Path(args.spec).with_suffix(".csv"))
    check_table_format(out)
    files.check_output_file(out, "--out" if args.out else "the sweep table")
    files.make_folder_of(out, "--out" if args.out else "the sweep table")
    start = time.perf_counter()
    set_interrupt_hint(
        f"the finished rows are in {journal_path(out)}; run the same command with --resume to "
        "finish the sweep"
    )
    run = run_sweep_to_table(
        spec,
        out,
        resume=args.resume,
        workers=args.workers,
        scheduler=args.scheduler,
        progress=progress_bar("sweep"),
    )
    set_interrupt_hint(None)
    rows = run.rows
    states = ("ok", "no-solution", "error", "invalid")
    counts = {s: sum(r.get("status") == s for r in rows) for s in states}
    reused = f", {run.reused} reused from an earlier run" if run.reused else ""
    if args.format == "json":
        import json

        summary = {
            "cases": len(rows),
            "seconds": round(time.perf_counter() - start, 3),
            "out": out,
            "status": counts,
            "reused": run.reused,
        }
        print(json.dumps(summary))
        return
    print(
        f"{len(rows)} cases in {time.perf_counter() - start:.1f} s -> {out} "
        f"({', '.join(f'{k}: {v}' for k, v in counts.items())}{reused})"
    )


def add_parsers(sub: argparse._SubParsersAction) -> None:
    """Add this module's commands to the ``cosserat`` parser."""
    sw = sub.add_parser(
        "sweep",
        help="run a parameter sweep from a TOML spec",
        description=(
            "Run a parameter sweep. Finished rows are appended to OUT.part as they come, so an "
            "interrupted sweep (Ctrl-C, a killed process) keeps them; --resume finishes it."
        ),
    )
    sw.add_argument("spec", help="TOML file (see cosserat.studies.sweep)")
    sw.add_argument(
        "--out",
        default=None,
        help="table to write (.csv or .parquet; default: the spec's output, else SPEC.csv)",
    )
    sw.add_argument(
        "--resume",
        action="store_true",
        help=(
            "reuse the rows of an interrupted run (OUT.part) and of an existing CSV table OUT, "
            "matched by their case parameters, and compute only the missing cases"
        ),
    )
    sw.add_argument(
        "--workers", type=positive_int, default=None, help="local processes (default: cores)"
    )
    sw.add_argument(
        "--scheduler",
        default=None,
        help="Dask scheduler address (tcp://host:port) instead of local processes",
    )
    sw.add_argument(
        "--format",
        choices=("text", "json"),
        default="text",
        help=(
            "the summary on stdout: text, one line (default), or json (cases, seconds, out, "
            "status counts, reused); the table's format is --out's suffix"
        ),
    )
    add_quiet(sw)
    sw.set_defaults(func=cmd_sweep)
