"""``cosserat reproduce`` and ``cosserat figures``: the paper's results."""

from __future__ import annotations

import argparse
from collections.abc import Callable

from . import files
from .common import (
    PRESETS,
    UsageError,
    add_quiet,
    positive_int,
    progress_bar,
    set_interrupt_hint,
)


def _stage_bar() -> Callable[[str, int, int], None] | None:
    """``progress(stage, i, n)`` for :func:`cosserat.paper.reproduce`: one tqdm bar per stage
    (None when silent: stderr not a terminal, or --quiet)."""
    bars: dict[str, Callable[[int, int], None] | None] = {}
    if progress_bar("reproduce") is None:
        return None

    def progress(stage: str, i: int, n: int) -> None:
        bar = bars.get(stage)
        if bar is None:
            bar = bars[stage] = progress_bar(f"reproduce: {stage}")
        if bar is not None:
            bar(i, n)

    return progress


def cmd_reproduce(args: argparse.Namespace) -> None:
    from ..paper.reproduce import reproduce

    files.output_folder(args.out)
    set_interrupt_hint(
        f"the figures finished so far are in {args.out}; run the same command again to finish "
        "(the report is written at the end)"
    )
    out = reproduce(args.out, figures=args.only, workers=args.workers, progress=_stage_bar())
    print(f"wrote {out}/index.html and {out}/report.md")


def cmd_figures(args: argparse.Namespace) -> None:
    from ..paper.figures import FIGURES, make_figure

    data = {}
    for item in args.data or []:
        key, sep, path = item.partition("=")
        if not sep or key not in PRESETS:
            raise UsageError(f"--data takes mustard=FILE, poppy=FILE or glass=FILE; got {item!r}")
        data[key] = files.read_measured(path)
    files.output_folder(args.out)
    numbers = args.only or list(FIGURES)
    bar = progress_bar("figures")
    for i, n in enumerate(numbers):
        make_figure(n, out=args.out, data=data)
        if bar is not None:
            bar(i + 1, len(numbers))
    print(f"wrote {len(numbers)} figures to {args.out}")


def add_parsers(sub: argparse._SubParsersAction) -> None:
    """Add this module's commands to the ``cosserat`` parser."""
    rp = sub.add_parser("reproduce", help="reproduce the paper's results into a folder")
    rp.add_argument(
        "--out",
        required=True,
        help="output folder (created if needed; index.html, report.md, the figures' PNG/PDF/CSV)",
    )
    rp.add_argument(
        "--only",
        type=int,
        nargs="+",
        choices=range(1, 16),
        metavar="N",
        help="only these figures (1-14; 15: the rheologies side by side); the report keeps "
        "the others from earlier runs",
    )
    rp.add_argument(
        "--workers", type=positive_int, default=None, help="worker processes (default: cores)"
    )
    add_quiet(rp)
    rp.set_defaults(func=cmd_reproduce)

    fp = sub.add_parser("figures", help="write every paper figure (PNG, PDF, CSV)")
    fp.add_argument("--out", required=True, help="output folder")
    fp.add_argument(
        "--only",
        type=int,
        nargs="+",
        choices=range(1, 16),
        metavar="N",
        help="only these figures (1-14; 15: the rheologies side by side; default: all)",
    )
    fp.add_argument(
        "--data",
        nargs="+",
        metavar="KEY=FILE",
        help="overlay measured profiles on figures 10-11 (mustard, poppy, glass)",
    )
    add_quiet(fp)
    fp.set_defaults(func=cmd_figures)
