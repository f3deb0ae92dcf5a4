"""Screenshots of every page of the built documentation, with headless Chromium.

Run after the docs build::

    python tools/screenshot_docs.py [docs/_build/html] [/tmp/docs_shots]

Each HTML page (the highlighted-source pages under ``_modules/`` excepted) becomes a PNG in the
output folder, named after its path (``api/model.html`` -> ``api__model.png``). Chromium is
Debian's ``chromium`` package; the pages are opened from the file system, so a page that needs
the network (a CDN script) shows it. Look at the PNGs before calling the docs done.
"""

from __future__ import annotations

import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

FLAGS = [
    "--headless",
    "--no-sandbox",
    "--disable-gpu",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
    "--no-first-run",
    "--hide-scrollbars",
    "--virtual-time-budget=4000",  # let MathJax typeset before the shot
]


def pages(html: Path) -> list[Path]:
    """The HTML pages worth looking at, in a stable order."""
    skip = {"_modules", "_sources", "_static", "_images", "_downloads"}
    return sorted(
        p
        for p in html.rglob("*.html")
        if not skip.intersection(p.relative_to(html).parts) and p.name not in {"genindex.html"}
    )


def shoot(page: Path, out: Path, height: int = 2000) -> None:
    """One screenshot of ``page`` (1280 px wide) into ``out``."""
    browser = shutil.which("chromium") or shutil.which("chromium-browser")
    if browser is None:
        raise SystemExit("chromium not found: apt-get install -y chromium")
    with tempfile.TemporaryDirectory() as profile:
        subprocess.run(
            [
                browser,
                *FLAGS,
                f"--user-data-dir={profile}",
                f"--screenshot={out}",
                f"--window-size=1280,{height}",
                page.resolve().as_uri(),
            ],
            check=True,
            capture_output=True,
            timeout=120,
        )


def main(argv: list[str]) -> int:
    html = Path(argv[0] if argv else "docs/_build/html")
    out = Path(argv[1] if len(argv) > 1 else "/tmp/docs_shots")
    out.mkdir(parents=True, exist_ok=True)
    for page in pages(html):
        name = "__".join(page.relative_to(html).with_suffix(".png").parts)
        shoot(page, out / name)
        print(out / name)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
