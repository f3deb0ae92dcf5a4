"""The version is stated in one place, ``src/cosserat/_version.py``: what reads it (the build,
the docs, the command line, profiles' metadata) reads it, and what cannot read it (the citation
file, the changelog) is checked against it here."""

from __future__ import annotations

import re
import tomllib
from pathlib import Path

import pytest

import cosserat
from cosserat._version import __version__

ROOT = Path(__file__).resolve().parents[1]


def release_of(version: str) -> tuple[str, bool]:
    """('0.2.0', True) for '0.2.0.dev0': the release and whether this is a development one."""
    match = re.fullmatch(r"(\d+\.\d+\.\d+)((?:a|b|rc)\d+)?(\.dev\d+)?", version)
    assert match, f"{version!r} is not a version of the form X.Y.Z[aN|bN|rcN][.devN]"
    return match[1] + (match[2] or ""), match[3] is not None


def test_the_package_and_its_build_read_the_one_version():
    assert cosserat.__version__ == __version__
    meta = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))
    assert "version" not in meta["project"] and "version" in meta["project"]["dynamic"]
    assert meta["tool"]["setuptools"]["dynamic"]["version"] == {
        "attr": "cosserat._version.__version__"
    }
    conf = (ROOT / "docs" / "conf.py").read_text(encoding="utf-8")
    assert "release = cosserat.__version__" in conf


def test_the_command_line_says_the_version(capsys):
    from cosserat.cli import main

    with pytest.raises(SystemExit) as stop:
        main(["--version"])
    assert stop.value.code == 0 and capsys.readouterr().out == f"cosserat {__version__}\n"


def test_the_citation_file_states_the_same_version():
    text = (ROOT / "CITATION.cff").read_text(encoding="utf-8")
    stated = re.findall(r"^version:\s*\"?([^\"\s]+)\"?\s*$", text, flags=re.MULTILINE)
    assert stated == [__version__], "update CITATION.cff's version with src/cosserat/_version.py"


def test_the_changelog_heads_with_this_release():
    release, dev = release_of(__version__)
    text = (ROOT / "CHANGELOG.md").read_text(encoding="utf-8")
    first = next(line for line in text.splitlines() if line.startswith("## "))
    assert first.startswith(f"## {release} "), f"CHANGELOG.md's newest section: {first!r}"
    assert ("(unreleased)" in first) == dev, (
        "a development version's section says (unreleased); a release's says its date"
    )
