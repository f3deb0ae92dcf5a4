"""The kinetic model of Bocquet et al. is not implemented (``docs/derivation_kinetic.md``).

What is tested is the explanation others print: it names the model's source and every missing
piece, the error built from it is the package's ``MethodNotAvailableError``, and the document
it points to exists and covers each item of ``MISSING``.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from cosserat import CosseratError
from cosserat.errors import MethodNotAvailableError
from cosserat.model import kinetic
from cosserat.model.kinetic import KINETIC_NOT_AVAILABLE, MISSING, REFERENCES, unavailable

DOC = Path(__file__).resolve().parents[1] / "docs" / "derivation_kinetic.md"


def test_message_names_the_source_and_what_is_missing() -> None:
    text = KINETIC_NOT_AVAILABLE
    assert "Bocquet" in text and "011307" in text
    for word in ("viscosity", "conductivity", "dissipation", "pressure", "wall conditions"):
        assert word in text, word
    assert "docs/derivation_kinetic.md" in text


def test_missing_items_cover_the_issue_list() -> None:
    joined = " ".join(MISSING)
    for word in ("viscosity", "conductivity", "dissipation", "equation of state", "boundary"):
        assert word in joined, word
    assert sum("boundary condition" in item for item in MISSING) == 2  # velocity and T


def test_references_cite_the_three_papers() -> None:
    joined = " ".join(REFERENCES)
    for key in ("Phys. Rev. E 65, 011307", "Phys. Rev. Lett. 85, 1428", "Phys. Rev. Lett. 89"):
        assert key in joined, key


@pytest.mark.parametrize("cell", [None, "couette", "plane"])
def test_unavailable_is_a_method_not_available_error(cell: str | None) -> None:
    err = unavailable(cell)
    assert isinstance(err, MethodNotAvailableError) and isinstance(err, CosseratError)
    message = str(err)
    assert message.startswith(KINETIC_NOT_AVAILABLE)
    if cell is not None:
        assert f"{cell} cell" in message
    with pytest.raises(MethodNotAvailableError, match="not implemented"):
        raise err


def test_document_exists_and_covers_each_missing_item() -> None:
    text = DOC.read_text(encoding="utf-8")
    for heading in ("## 1. Item by item", "## 4. What would be needed", "## 5. Where we looked"):
        assert heading in text, heading
    for symbol in ("`η(ν, T)`", "`κ(ν, T)`", "`Γ(ν, T, e)`", "`p(ν, T)`", "wall condition for"):
        assert symbol in text, symbol
    for arxiv in ("cond-mat/0012356", "cond-mat/0004401", "cond-mat/0112072"):
        assert arxiv in text, arxiv


def test_the_module_defines_no_solver() -> None:
    # the honest state: an explanation, no problem class or route to register
    public = set(kinetic.__all__)
    assert public == {"KINETIC_NOT_AVAILABLE", "MISSING", "REFERENCES", "unavailable"}
