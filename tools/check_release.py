"""Check that the package is release-ready: what a user installs from the index works.

Builds the sdist and, from it, the wheel (``python -m build``), checks their metadata
(``twine check --strict``), installs the wheel into a fresh virtual environment and, from a
folder outside the source tree (so that only the installed files can be imported), runs the
README's main job ``cosserat reproduce --out DIR`` and ``cosserat validate`` on the shipped
corpus: the package data (the corpus, the synthetic profile) must be in the wheel. Checks that
the built files carry the version of ``src/cosserat/_version.py``, and that the sdist holds
what running the tests from it needs.

Run from the repository (``.ci/run`` does, after the tests)::

    python tools/check_release.py [--keep DIR]

Exit status 1 and a line per problem if anything is wrong; the time of each step is printed.
"""

from __future__ import annotations

import argparse
import os
import re
import subprocess
import sys
import tarfile
import tempfile
import time
import zipfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
FIGURES = 15
"""Figures ``cosserat reproduce`` writes (fig01 ... fig15), each as PNG, PDF and CSV."""
IN_WHEEL = [
    "cosserat/py.typed",
    "cosserat/data/synthetic_couette.csv",
    "cosserat/data/corpus/plane_rough_H20.csv",
    "cosserat/data/corpus/plane_rough_H20.json",
]
IN_SDIST = [
    "pyproject.toml",
    "README.md",
    "LICENSE",
    "CHANGELOG.md",
    "CITATION.cff",
    "src/cosserat/_version.py",
    "src/cosserat/data/corpus/plane_rough_H20.csv",
    "tests/conftest.py",
    "tests/data/v010_reference.json",
    "docs/conf.py",
]


def version() -> str:
    text = (ROOT / "src" / "cosserat" / "_version.py").read_text(encoding="utf-8")
    match = re.search(r'__version__ = "([^"]+)"', text)
    if match is None:
        raise SystemExit("no __version__ in src/cosserat/_version.py")
    return match[1]


def run(
    step: str, argv: list[str], cwd: Path | None = None, env: dict[str, str] | None = None
) -> subprocess.CompletedProcess[str]:
    """Run ``argv``, print its time; on failure print its output's end and stop."""
    start = time.perf_counter()
    proc = subprocess.run(argv, text=True, capture_output=True, check=False, cwd=cwd, env=env)
    print(f"  {step}: {time.perf_counter() - start:.1f} s", flush=True)
    if proc.returncode != 0:
        print(proc.stdout[-4000:], proc.stderr[-4000:], sep="\n", file=sys.stderr)
        raise SystemExit(f"check_release: {step} failed (exit status {proc.returncode})")
    return proc


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--keep", type=Path, help="work in this folder and keep it")
    args = parser.parse_args()
    expected = version()
    problems: list[str] = []
    with tempfile.TemporaryDirectory(prefix="cosserat-release-") as scratch:
        work = args.keep.resolve() if args.keep else Path(scratch)
        work.mkdir(parents=True, exist_ok=True)
        dist = work / "dist"
        print(f"release check of cosserat {expected} in {work}", flush=True)
        run("build the sdist, then the wheel from it", [sys.executable, "-m", "build",
            "--outdir", str(dist), str(ROOT)])  # fmt: skip
        sdists = sorted(dist.glob("*.tar.gz"))
        wheels = sorted(dist.glob("*.whl"))
        if len(sdists) != 1 or len(wheels) != 1:
            raise SystemExit(f"check_release: expected one sdist and one wheel in {dist}")
        sdist, wheel = sdists[0], wheels[0]
        for built in (sdist, wheel):
            if f"-{expected}" not in built.name:
                problems.append(f"{built.name} does not carry the version {expected}")
        run("twine check --strict", [sys.executable, "-m", "twine", "check", "--strict",
            str(sdist), str(wheel)])  # fmt: skip
        names = set(zipfile.ZipFile(wheel).namelist())
        problems += [f"the wheel lacks {n}" for n in IN_WHEEL if n not in names]
        with tarfile.open(sdist) as tar:
            top = tar.getnames()[0].split("/")[0]
            held = {n.removeprefix(top + "/") for n in tar.getnames()}
        problems += [f"the sdist lacks {n}" for n in IN_SDIST if n not in held]
        problems += [f"the sdist holds the generated {n}" for n in held if "__pycache__" in n]

        venv = work / "venv"
        run("a fresh virtual environment", [sys.executable, "-m", "venv", str(venv)])
        bindir = venv / ("Scripts" if os.name == "nt" else "bin")
        python = bindir / "python"
        run("install the wheel (and its dependencies)",
            [str(python), "-m", "pip", "install", "--quiet", str(wheel)])  # fmt: skip
        outside = work / "user"  # no src/ here: only the installed package imports
        outside.mkdir(exist_ok=True)
        env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "NUMBA_CACHE_DIR")}
        env["MPLBACKEND"] = "Agg"
        shown = run("cosserat --version", [str(bindir / "cosserat"), "--version"], cwd=outside,
                    env=env).stdout.strip()  # fmt: skip
        if shown != f"cosserat {expected}":
            problems.append(f"cosserat --version says {shown!r}, not 'cosserat {expected}'")
        where = run("import from the installed wheel", [str(python), "-c",
                    "import cosserat; print(cosserat.__file__)"], cwd=outside, env=env)  # fmt: skip
        if not Path(where.stdout.strip()).is_relative_to(venv):
            problems.append(f"cosserat imports from {where.stdout.strip()}, not the fresh venv")
        results = outside / "results"
        run("cosserat reproduce --out results (first run: compiles the kernels)",
            [str(bindir / "cosserat"), "reproduce", "--out", str(results)], cwd=outside,
            env=env)  # fmt: skip
        for name in ("index.html", "report.md", "claims.csv", "claims.json", "figures.json"):
            if not (results / name).is_file():
                problems.append(f"reproduce did not write {name}")
        for suffix in ("png", "pdf", "csv"):
            found = len(list(results.glob(f"fig[0-9][0-9]_*.{suffix}")))
            if found != FIGURES:
                problems.append(f"reproduce wrote {found} .{suffix} figures, not {FIGURES}")
        report = outside / "validation"
        run("cosserat validate (the shipped corpus)",
            [str(bindir / "cosserat"), "validate", "--out", str(report)], cwd=outside,
            env=env)  # fmt: skip
        if not (report / "results.json").is_file():
            problems.append("validate did not write results.json")
    for problem in problems:
        print(f"check_release: {problem}", file=sys.stderr)
    if not problems:
        print(f"release check passed: {sdist.name}, {wheel.name}")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
