"""The ``cosserat`` command line: a thin layer over the API (no physics here).

Bad input (a :class:`~cosserat.errors.CosseratError`, or a usage error) exits with status 2 and
one line on stderr, ``cosserat: error: ...``, saying what is wrong (every command, every kind
of bad input: one prefix); anything else is a bug and shows as one (a traceback,
exit status 1). Ctrl-C and SIGTERM stop the command as cleanly (worker processes stopped,
temporary files removed, finished outputs kept) and exit with one line and the shell's status,
130 (128 + SIGINT) or 143 (128 + SIGTERM), also from inside a long compiled kernel, where
Python cannot run a signal handler (:mod:`cosserat.cli.watchdog`). A full disk (or quota, or
read-only file system) is reported in one line too, exit status 2 (:data:`FULL`). Defaults
are the paper's, from :mod:`cosserat.config`, filled in by
:func:`cosserat.model.build_problem` (the same as for sweeps).

Each command lives in its own module with an ``add_parsers(sub)`` function; :data:`COMMANDS`
lists them in the order ``cosserat --help`` shows them.
"""

from __future__ import annotations

import argparse
import errno
import signal
import sys
from collections.abc import Sequence

from .._atomic import destination_of
from .._version import __version__
from ..errors import CosseratError
from . import calibrate, cell, data, dem, models, paper, solve, sweep
from .common import (
    Parser,
    Terminated,
    UsageError,
    add_quiet,
    interrupt_hint,
    interrupted,
    problem_from_args,
    set_interrupt_hint,
    set_quiet,
)
from .watchdog import ending_inside_kernels

COMMANDS = (solve, cell, paper, data, calibrate, sweep, dem, models)
"""The command modules, each with ``add_parsers(sub)``."""

__all__ = ["COMMANDS", "UsageError", "main", "make_parser", "problem_from_args"]


def make_parser() -> argparse.ArgumentParser:
    """The ``cosserat`` argument parser with every command of :data:`COMMANDS`."""
    parser = Parser(prog="cosserat", description=__doc__.splitlines()[0].replace("``", ""))
    parser.add_argument("--version", action="version", version=f"cosserat {__version__}")
    add_quiet(parser)
    sub = parser.add_subparsers(
        dest="command", required=False, parser_class=Parser, metavar="COMMAND"
    )
    for module in COMMANDS:
        module.add_parsers(sub)
    return parser


INTERRUPTED = 128 + signal.SIGINT
"""Exit status after Ctrl-C (128 + SIGINT, the shell's convention)."""
TERMINATED = 128 + signal.SIGTERM
"""Exit status after SIGTERM (128 + SIGTERM)."""


def main(argv: Sequence[str] | None = None) -> int:
    """Run the command line; returns the exit status (0; 2 for bad input; 130 or 143 when
    interrupted by Ctrl-C or SIGTERM)."""
    parser = make_parser()
    # SIGTERM raises Terminated (a KeyboardInterrupt), so that a terminated command cleans up
    # as after Ctrl-C (Python's default for SIGTERM ends at once, skipping it); both also end
    # a command stuck inside a compiled kernel (cli/watchdog.py)
    with ending_inside_kernels(_raise_terminated):
        set_interrupt_hint(None)
        try:
            args = parser.parse_args(argv)
            if getattr(args, "command", None) is None:  # bare `cosserat`: the command list
                parser.print_help()
                return 0
            set_quiet(getattr(args, "quiet", False))
            if getattr(args, "f", None) is not None and not 0.0 < args.f < 1.0:
                raise UsageError(f"--f must satisfy 0 < f < 1; got {args.f:g}")
            args.func(args)
        except UsageError as exc:
            print(f"cosserat: error: {' '.join(str(exc).split())}", file=sys.stderr)
            return 2
        except CosseratError as exc:  # a model or input problem; anything else is a bug
            message = " ".join(str(exc).split()) or type(exc).__name__
            print(f"cosserat: error: {message}", file=sys.stderr)
            return 2
        except OSError as exc:
            if exc.errno not in FULL:  # anything else is a bug, or a CosseratError already
                raise
            print(f"cosserat: error: {_full_message(exc)}", file=sys.stderr)
            return 2
        except (KeyboardInterrupt, SystemError) as exc:
            if not interrupted(exc):
                raise
            hint = interrupt_hint()
            newline = "\n" if sys.stderr.isatty() else ""  # off the terminal's "^C"
            print(f"{newline}cosserat: interrupted{'; ' + hint if hint else ''}", file=sys.stderr)
            return TERMINATED if interrupted(exc, Terminated) else INTERRUPTED
    return 0


FULL = {getattr(errno, e) for e in ("ENOSPC", "EDQUOT", "EFBIG", "EROFS") if hasattr(errno, e)}
"""Errors of a write the command line reports in one line (exit 2) wherever they arise: a full
disk, a quota, a file too large, a read-only file system. They are never bugs, and every
output is written whole or not at all (:mod:`cosserat._atomic`), so nothing half-written is
left behind."""


def _full_message(exc: OSError) -> str:
    reason = exc.strerror or str(exc)
    if not exc.filename:
        return f"cannot write the output: {reason[:1].lower() + reason[1:]}"
    name = destination_of(exc.filename)
    return f"cannot write {name}: {reason[:1].lower() + reason[1:]}"


def _raise_terminated(signum: int, frame: object) -> None:
    raise Terminated


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
