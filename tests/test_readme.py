"""The README's Python examples run as written (the public API keeps working)."""

from __future__ import annotations

import contextlib
import io
import re
from pathlib import Path

import pytest

README = (Path(__file__).resolve().parents[1] / "README.md").read_text()
BLOCKS = re.findall(r"```python\n(.*?)```", README, flags=re.DOTALL)


def test_the_readme_has_python_examples():
    assert len(BLOCKS) >= 2


@pytest.mark.parametrize("index", range(len(BLOCKS)))
def test_readme_example_runs(index, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        exec(compile(BLOCKS[index], f"README block {index}", "exec"), {})
    for line in BLOCKS[index].splitlines():
        # a printed value the README quotes in a comment must be what the code prints
        m = re.match(r"print\((.*)\)\s+#\s*([0-9.]+)", line.strip())
        if m:
            assert m.group(2) in out.getvalue()
