"""Where numba keeps the compiled kernels, and what it does when it cannot write there.

    python benchmarks/numba_cache_probe.py [--fast]

Copies the installed ``cosserat`` package into a temporary folder, makes folders read-only and
runs, in a fresh process each, ``from cosserat.numerics.runtime import warm_up; warm_up()``,
printing whether it worked, how long it took and where numba put (or found) the cache:

A. the package's folder read-only, HOME writable and empty;
B. the package's folder and HOME read-only, no NUMBA_CACHE_DIR;
C. NUMBA_CACHE_DIR set to a read-only folder, HOME writable;
D. the package's ``__pycache__`` folders filled by a compilation first, then made read-only;
E. the package's folder and HOME read-only, NUMBA_CACHE_DIR writable.

Root ignores permission bits, so as root each run is started through ``setpriv`` without the
capabilities that let it (CAP_DAC_OVERRIDE, CAP_DAC_READ_SEARCH). ``--fast`` runs B alone (the
others compile every kernel, ~40 s each).
"""

from __future__ import annotations

import argparse
import os
import shutil
import stat
import subprocess
import sys
import tempfile
import time
from pathlib import Path

PROBE = """
import time
t = time.perf_counter()
try:
    from cosserat.numerics import cosserat as k
    from cosserat.numerics.runtime import warm_up
    warm_up()
    print(f"works, {time.perf_counter() - t:.1f} s; cache of solve_case: "
          f"{k.solve_case._cache._cache_path}")
except Exception as exc:
    print(f"FAILS after {time.perf_counter() - t:.1f} s: {type(exc).__name__}: {exc}")
"""


def read_only(path: Path) -> None:
    for p in [path, *path.rglob("*")]:
        mode = p.stat().st_mode
        p.chmod(mode & ~(stat.S_IWUSR | stat.S_IWGRP | stat.S_IWOTH))


def writable(path: Path) -> None:
    for p in [path, *path.rglob("*")]:
        p.chmod(p.stat().st_mode | stat.S_IWUSR)


def run(site: Path, home: Path, cache_dir: Path | None, cwd: Path) -> str:
    env = {k: v for k, v in os.environ.items() if k not in ("NUMBA_CACHE_DIR", "XDG_CACHE_HOME")}
    env.update(HOME=str(home), PYTHONPATH=str(site))
    if cache_dir is not None:
        env["NUMBA_CACHE_DIR"] = str(cache_dir)
    cmd = [sys.executable, "-c", PROBE]
    if os.geteuid() == 0:
        cmd = ["setpriv", "--bounding-set", "-dac_override,-dac_read_search", *cmd]
    t = time.perf_counter()
    res = subprocess.run(cmd, env=env, cwd=cwd, capture_output=True, text=True)
    lines = (res.stdout + res.stderr).strip().splitlines()
    return f"{lines[-1] if lines else '(no output)'}  [process {time.perf_counter() - t:.1f} s]"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--fast", action="store_true", help="skip the cases that compile")
    args = parser.parse_args()
    if os.geteuid() == 0 and shutil.which("setpriv") is None:
        sys.exit("running as root without setpriv: permission bits would not apply")
    import cosserat

    package = Path(cosserat.__file__).resolve().parent
    with tempfile.TemporaryDirectory(prefix="numba-probe-") as tmp:
        root = Path(tmp)
        site, home, ro_home, ro_cache, cache = (
            root / n for n in ("site", "home", "ro-home", "ro-cache", "cache")
        )
        for d in (home, ro_home, ro_cache, cache):
            d.mkdir()
        shutil.copytree(package, site / "cosserat", ignore=shutil.ignore_patterns("__pycache__"))
        read_only(site)
        read_only(ro_home)
        read_only(ro_cache)
        print(f"numba {__import__('numba').__version__}; package copied to {site}")
        cases = [
            ("A", "package read-only, HOME writable", home, None, not args.fast),
            ("B", "package and HOME read-only", ro_home, None, True),
            ("C", "NUMBA_CACHE_DIR read-only, HOME writable", home, ro_cache, not args.fast),
            (
                "E",
                "package and HOME read-only, NUMBA_CACHE_DIR writable",
                ro_home,
                cache,
                not args.fast,
            ),
        ]
        for label, what, h, c, do in cases:
            if do:
                print(f"{label}. {what}: {run(site, h, c, ro_home)}", flush=True)
        if not args.fast:
            # D: compile in place into the package's __pycache__, then make it read-only
            writable(site)
            fresh_home = root / "home-d"
            fresh_home.mkdir()
            first = run(site, fresh_home, None, ro_home)
            read_only(site)
            second = run(site, fresh_home, None, ro_home)
            print(f"D. package writable, first run: {first}")
            print(f"   the same, its __pycache__ now read-only, HOME writable: {second}")
        writable(root)


if __name__ == "__main__":
    main()
