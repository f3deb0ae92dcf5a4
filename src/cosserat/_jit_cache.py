"""Where numba keeps the compiled kernels, and what happens when it can write nowhere.

numba uses the first writable of: ``NUMBA_CACHE_DIR``, the ``__pycache__`` folders beside the
package's sources, and the user-wide cache folder (``~/.cache/numba``); the kernels compile
once (about 35 s on two cores) and later processes load them (``docs/performance.md``). When
none of these is writable, numba refuses to define a cached compiled function at all ("no
locator available") and the package would not import. This module, run before any compiled
function is defined, then points numba at a fresh temporary folder and warns: the package
works, and pays the compilation in every new process until ``NUMBA_CACHE_DIR`` names a
writable folder.
"""

from __future__ import annotations

import tempfile
import warnings
from pathlib import Path

import numba
from numba.misc.appdirs import AppDirs


def _writable(folder: Path) -> bool:
    try:
        folder.mkdir(parents=True, exist_ok=True)
        with tempfile.TemporaryFile(dir=folder):
            pass
    except OSError:
        return False
    return True


def ensure_cache() -> str | None:
    """The temporary cache folder chosen when no usual one is writable, else None."""
    candidates = [Path(__file__).parent / "numerics" / "__pycache__"]
    # numba.config sets its options (CACHE_DIR among them) at run time from the environment,
    # so the module has no attribute mypy can see
    cache_dir = numba.config.CACHE_DIR  # type: ignore[attr-defined]
    if cache_dir:
        candidates.insert(0, Path(cache_dir))
    candidates.append(Path(AppDirs(appname="numba", appauthor=False).user_cache_dir))
    if any(_writable(folder) for folder in candidates):
        return None
    folder = tempfile.mkdtemp(prefix="cosserat-numba-")
    numba.config.CACHE_DIR = folder  # type: ignore[attr-defined]  # (as above)
    warnings.warn(
        f"no writable folder for numba's cache ({', '.join(map(str, candidates))}): the "
        f"compiled kernels go to {folder} for this process only, and every new process "
        f"compiles them again (about 35 s); set NUMBA_CACHE_DIR to a writable folder",
        RuntimeWarning,
        stacklevel=2,
    )
    return folder


ensure_cache()
