"""The ``cosserat`` command line: a thin layer over the API (no physics here).

Bad input (a :class:`~cosserat.errors.CosseratError`, or a usage error) exits with status 2 and
one line on stderr saying what is wrong; anything else is a bug and shows as one (a traceback,
exit status 1). Defaults are the paper's, from :mod:`cosserat.config`, filled in by
:func:`cosserat.model.build_problem` (the same as for sweeps).

Each command lives in its own module with an ``add_parsers(sub)`` function; :data:`COMMANDS`
lists them in the order ``cosserat --help`` shows them.
"""

from __future__ import annotations

import argparse
import sys
from collections.abc import Sequence

from .._version import __version__
from ..errors import CosseratError
from . import calibrate, cell, data, dem, models, paper, solve, sweep
from .common import Parser, UsageError, add_quiet, problem_from_args, set_quiet

COMMANDS = (solve, cell, paper, data, calibrate, sweep, dem, models)
"""The command modules, each with ``add_parsers(sub)``."""

__all__ = ["COMMANDS", "UsageError", "main", "make_parser", "problem_from_args"]


def make_parser() -> argparse.ArgumentParser:
    """The ``cosserat`` argument parser with every command of :data:`COMMANDS`."""
    parser = Parser(prog="cosserat", description=__doc__.splitlines()[0].replace("``", ""))
    parser.add_argument("--version", action="version", version=f"cosserat {__version__}")
    add_quiet(parser)
    sub = parser.add_subparsers(dest="command", required=True, parser_class=Parser)
    for module in COMMANDS:
        module.add_parsers(sub)
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    """Run the command line; returns the exit status (0, or 2 for bad input)."""
    parser = make_parser()
    try:
        args = parser.parse_args(argv)
        set_quiet(getattr(args, "quiet", False))
        if getattr(args, "f", None) is not None and not 0.0 < args.f < 1.0:
            raise UsageError(f"--f must satisfy 0 < f < 1; got {args.f:g}")
        args.func(args)
    except UsageError as exc:
        print(" ".join(str(exc).split()), file=sys.stderr)
        return 2
    except CosseratError as exc:  # a model or input problem; anything else is a bug
        message = " ".join(str(exc).split()) or type(exc).__name__
        print(f"cosserat: error: {message}", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
