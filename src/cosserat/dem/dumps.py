"""Readers of the LAMMPS text dumps the decks write (``dump custom`` and ``dump local``)."""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path

import numpy as np

from ..errors import InputError


def iter_dump(path: str | Path) -> Iterator[tuple[int, np.ndarray]]:
    """Yield ``(step, rows)`` for every snapshot of a LAMMPS text dump.

    ``rows`` is a float array of shape (n, columns); a snapshot with no entries has shape
    (0, columns).
    """
    path = Path(path)
    with path.open() as fh:
        while True:
            line = fh.readline()
            if not line:
                return
            if not line.startswith("ITEM: TIMESTEP"):
                raise InputError(f"{path}: expected 'ITEM: TIMESTEP', got {line.strip()!r}")
            step = int(fh.readline())
            head = fh.readline()
            if not head.startswith("ITEM: NUMBER OF"):
                raise InputError(f"{path}: expected 'ITEM: NUMBER OF ...' at step {step}")
            n = int(fh.readline())
            line = fh.readline()
            if line.startswith("ITEM: BOX BOUNDS"):
                for _ in range(3):
                    fh.readline()
                line = fh.readline()
            if not (line.startswith("ITEM: ATOMS") or line.startswith("ITEM: ENTRIES")):
                raise InputError(f"{path}: expected the column header at step {step}")
            ncol = len(line.split()) - 2
            text = "".join(fh.readline() for _ in range(n))
            values = np.array(text.split(), dtype=float)
            if values.size != n * ncol:
                raise InputError(f"{path}: snapshot at step {step} is truncated")
            yield step, values.reshape(n, ncol)


def iter_frames(folder: str | Path) -> Iterator[tuple[int, np.ndarray, np.ndarray]]:
    """Yield ``(step, atoms, contacts)`` from a run folder's ``atoms.dump`` and
    ``contacts.dump`` (the columns of :data:`~cosserat.dem.decks.ATOM_COLUMNS` and
    :data:`~cosserat.dem.decks.CONTACT_COLUMNS`)."""
    folder = Path(folder)
    for name in ("atoms.dump", "contacts.dump"):
        if not (folder / name).is_file():
            raise InputError(f"{folder / name} is missing: did the run finish?")
    contacts = iter_dump(folder / "contacts.dump")
    for step, atoms in iter_dump(folder / "atoms.dump"):
        try:
            c_step, c_rows = next(contacts)
        except StopIteration:
            return
        if c_step != step:
            raise InputError(f"{folder}: atoms at step {step} but contacts at step {c_step}")
        yield step, atoms, c_rows
