"""The documentation's sources and its checker (the build itself runs in CI: ``.ci/run``).

* every Markdown note and page in ``docs/`` is reachable from the index (a page outside every
  toctree fails the ``-W`` build only after a minute of gallery; this says which at once);
* the gallery has at least 10 examples, each with a title;
* ``tools/check_docs.py`` finds broken links, anchors, images and network scripts, on a small
  site made here.
"""

from __future__ import annotations

import ast
import fnmatch
import importlib.util
import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
DOCS = ROOT / "docs"
GENERATED = ("_build", "auto_examples", "api/generated", "_templates", "_static")


def _load_checker():  # type: ignore[no-untyped-def]
    spec = importlib.util.spec_from_file_location("check_docs", ROOT / "tools" / "check_docs.py")
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


check_docs = _load_checker()


def source_pages() -> set[str]:
    pages = set()
    for path in DOCS.rglob("*"):
        rel = path.relative_to(DOCS).as_posix()
        if path.suffix in (".rst", ".md") and not rel.startswith(GENERATED):
            pages.add(rel.rsplit(".", 1)[0])
    return pages


def toctree_entries(page: str) -> list[str]:
    """The entries of every toctree (and optional-toctree) of ``page``, relative to docs/."""
    path = next(DOCS.glob(page + ".*"))
    text = path.read_text()
    base = str(Path(page).parent)
    entries = []
    for block in re.findall(r"\.\. (?:optional-)?toctree::\n((?:[ \t]+.*\n|\n)+)", text):
        for line in block.splitlines():
            line = line.strip()
            if line and not line.startswith(":"):
                line = line.split("<")[-1].rstrip(">").strip()
                entries.append(line if base == "." else f"{base}/{line}")
    return entries


def test_every_docs_page_is_in_a_toctree() -> None:
    pages = source_pages()
    reached = {"index"}
    todo = ["index"]
    while todo:
        page = todo.pop()
        for entry in toctree_entries(page):
            for name in sorted(pages):
                if name not in reached and fnmatch.fnmatch(name, entry):
                    reached.add(name)
                    todo.append(name)
    orphans = sorted(pages - reached)
    assert not orphans, f"pages in no toctree of docs/index.rst (add them): {orphans}"


def test_gallery_has_ten_titled_examples() -> None:
    examples = sorted((ROOT / "examples").glob("plot_*.py"))
    assert len(examples) >= 10
    for path in examples:
        doc = ast.get_docstring(ast.parse(path.read_text()))
        assert doc, f"{path.name}: no docstring (the gallery needs a title)"
        title, underline = doc.splitlines()[:2]
        assert set(underline) == {"="} and len(underline) >= len(title), path.name


def test_mathjax_is_served_locally() -> None:
    text = (DOCS / "conf.py").read_text()
    assert '"sphinx-mathjax-offline"' in text


def _site(tmp_path: Path, body: str) -> Path:
    html = tmp_path / "html"
    (html / "auto_examples").mkdir(parents=True)
    (html / "index.html").write_text(f"<html><body><h1 id='top'>x</h1>{body}</body></html>")
    (html / "page.html").write_text("<html><body><p id='here'>y</p></body></html>")
    for i in range(10):
        (html / "auto_examples" / f"plot_{i}.html").write_text("<img src='../fig.png'>")
    (html / "fig.png").write_bytes(b"")
    return html


def test_checker_accepts_a_good_site(tmp_path: Path) -> None:
    html = _site(tmp_path, "<a href='page.html#here'>ok</a><a href='#top'>up</a>")
    assert check_docs.check(html) == []


@pytest.mark.parametrize(
    ("body", "problem"),
    [
        ("<a href='missing.html'>x</a>", "broken a -> missing.html"),
        ("<a href='page.html#nowhere'>x</a>", "missing anchor -> page.html#nowhere"),
        ("<img src='nothing.png'>", "broken img -> nothing.png"),
        ("<script src='https://cdn.example/x.js'></script>", "script loaded from the network"),
        ("<span class='math'>x</span>", "has equations but loads no MathJax"),
    ],
)
def test_checker_finds_each_problem(tmp_path: Path, body: str, problem: str) -> None:
    problems = check_docs.check(_site(tmp_path, body))
    assert len(problems) == 1 and problem in problems[0], problems


def test_checker_counts_the_gallery(tmp_path: Path) -> None:
    html = _site(tmp_path, "")
    (html / "auto_examples" / "plot_0.html").unlink()
    (html / "auto_examples" / "plot_1.html").write_text("<p>no figure</p>")
    problems = check_docs.check(html)
    assert any("fewer than 10" in p for p in problems)
    assert any("plot_1.html: a gallery example without a figure" in p for p in problems)
