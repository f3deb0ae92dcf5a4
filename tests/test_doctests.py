"""The ``Examples`` sections of the docstrings, and the ``>>>`` examples of the docs pages,
run as doctests.

Every module of ``cosserat`` is imported and searched, except ``cosserat.dem`` (its LAMMPS path
needs an optional, separately installed program) and the command-line entry modules
(``__main__``), which run the program when imported.
"""

from __future__ import annotations

import doctest
import importlib
import pkgutil
from pathlib import Path

import matplotlib
import pytest

import cosserat

matplotlib.use("Agg")

ROOT = Path(__file__).resolve().parents[1]
SKIP_PREFIXES = ("cosserat.dem",)
FLAGS = doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE


def module_names() -> list[str]:
    """Every importable module of the package, but those in SKIP_PREFIXES and ``__main__``."""
    names = ["cosserat"]
    for info in pkgutil.walk_packages(cosserat.__path__, prefix="cosserat."):
        name = info.name
        if name.startswith(SKIP_PREFIXES) or name.rsplit(".", 1)[-1] == "__main__":
            continue
        names.append(name)
    return sorted(names)


def docstring_tests() -> list[doctest.DocTest]:
    finder = doctest.DocTestFinder(exclude_empty=True)
    tests = []
    for name in module_names():
        module = importlib.import_module(name)
        for test in finder.find(module, name):
            # re-exported objects are found again in each package that imports them
            if test.examples and (test.filename or "").startswith(str(ROOT / "src")):
                tests.append(test)
    unique = {(t.name, t.filename, t.lineno): t for t in tests}
    return sorted(unique.values(), key=lambda t: t.name)


DOCSTRING_TESTS = docstring_tests()
DOC_PAGES = sorted(p for p in (ROOT / "docs").rglob("*.rst") if ">>>" in p.read_text())


def run(test: doctest.DocTest) -> None:
    runner = doctest.DocTestRunner(optionflags=FLAGS)
    report: list[str] = []
    runner.run(test, out=report.append)
    result = runner.summarize(verbose=False)
    assert result.failed == 0, "".join(report)


def test_there_are_docstring_examples() -> None:
    # The public entry points carry runnable examples; losing them all would pass silently.
    names = {t.name for t in DOCSTRING_TESTS}
    assert "cosserat" in names
    assert len(DOCSTRING_TESTS) >= 10, sorted(names)


@pytest.mark.parametrize("test", DOCSTRING_TESTS, ids=lambda t: t.name)
def test_docstring_examples(test: doctest.DocTest) -> None:
    run(test)


@pytest.mark.parametrize("page", DOC_PAGES, ids=lambda p: str(p.relative_to(ROOT)))
def test_doc_page_examples(page: Path) -> None:
    parser = doctest.DocTestParser()
    test = parser.get_doctest(page.read_text(), {}, page.name, str(page), 0)
    run(test)
