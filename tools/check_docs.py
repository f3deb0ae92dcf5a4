"""Check the built documentation: every internal link, anchor and image resolves, equations
are typeset by a local MathJax, and the gallery has its figures.

Run after the build (``sphinx-build -W --keep-going -b html docs docs/_build/html``)::

    python tools/check_docs.py [docs/_build/html]

Sphinx's own ``linkcheck`` needs the network; this needs none. Exit status 1 and one line per
problem if anything is wrong.
"""

from __future__ import annotations

import sys
from html.parser import HTMLParser
from pathlib import Path
from urllib.parse import unquote, urlsplit

MIN_GALLERY = 10
EXTERNAL = ("http:", "https:", "mailto:", "javascript:", "data:", "ftp:")


class _Page(HTMLParser):
    """The ids, links and scripts of one HTML page."""

    def __init__(self) -> None:
        super().__init__(convert_charrefs=True)
        self.ids: set[str] = set()
        self.links: list[tuple[str, str]] = []  # (tag, url)
        self.scripts: list[str] = []
        self.images = 0
        self.math = False

    def handle_starttag(self, tag: str, attrs: list[tuple[str, str | None]]) -> None:
        a = {k: v or "" for k, v in attrs}
        for key in ("id", "name"):
            if a.get(key):
                self.ids.add(a[key])
        if tag == "a" and "href" in a:
            self.links.append((tag, a["href"]))
        elif tag == "img" and "src" in a:
            self.links.append((tag, a["src"]))
            self.images += 1
        elif tag == "link" and a.get("rel") == "stylesheet" and "href" in a:
            self.links.append((tag, a["href"]))
        elif tag == "script" and a.get("src"):
            self.scripts.append(a["src"])
            self.links.append((tag, a["src"]))
        if "math" in a.get("class", "").split():
            self.math = True


def parse(path: Path) -> _Page:
    page = _Page()
    page.feed(path.read_text(encoding="utf-8"))
    return page


def check(html: Path) -> list[str]:
    """Every problem of the site in ``html``, one line each (empty: all good)."""
    if not (html / "index.html").is_file():
        return [f"{html}: no index.html (build the docs first)"]
    pages = {p: parse(p) for p in sorted(html.rglob("*.html"))}
    problems: list[str] = []
    for path, page in pages.items():
        where = path.relative_to(html)
        for tag, url in page.links:
            if url.startswith(EXTERNAL) or url.startswith("//"):
                if tag == "script":
                    problems.append(f"{where}: script loaded from the network: {url}")
                continue
            parts = urlsplit(url)
            target = path if not parts.path else (path.parent / unquote(parts.path)).resolve()
            if not target.exists():
                problems.append(f"{where}: broken {tag} -> {url}")
                continue
            if target.is_dir():
                target = target / "index.html"
            fragment = unquote(parts.fragment)
            if fragment and target.suffix == ".html":
                ids = pages[target].ids if target in pages else parse(target).ids
                if fragment not in ids:
                    problems.append(f"{where}: missing anchor -> {url}")
        if page.math and not any("mathjax" in s.lower() for s in page.scripts):
            problems.append(f"{where}: has equations but loads no MathJax")
    gallery = [p for p in pages if p.parent.name == "auto_examples" and p.stem.startswith("plot_")]
    if len(gallery) < MIN_GALLERY:
        problems.append(f"gallery: {len(gallery)} examples, fewer than {MIN_GALLERY}")
    for p in gallery:
        if pages[p].images == 0:
            problems.append(f"{p.relative_to(html)}: a gallery example without a figure")
    return problems


def main(argv: list[str]) -> int:
    html = Path(argv[0] if argv else "docs/_build/html").resolve()
    problems = check(html)
    for line in problems:
        print(line)
    n = len(list(html.rglob("*.html")))
    print(f"{n} pages checked, {len(problems)} problem(s)", file=sys.stderr)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
