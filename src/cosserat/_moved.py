"""Names that moved to another module, kept importable for one release with a warning."""

from __future__ import annotations

import importlib
import warnings
from collections.abc import Callable, Mapping
from typing import Any


def moved_names(
    module: str, moved: Mapping[str, tuple[str, str]], why: str = ""
) -> Callable[[str], Any]:
    """A module ``__getattr__`` that resolves each deprecated name of ``moved`` (name ->
    (module, name) of its replacement) on access only, with a :class:`DeprecationWarning`
    naming the replacement (and ``why``, in brackets, when given)."""

    def resolve(name: str) -> Any:
        if name in moved:
            home, new = moved[name]
            reason = f" ({why})" if why else ""
            warnings.warn(
                f"{module}.{name} is deprecated and will be removed in the next release: use "
                f"{home}.{new}{reason}",
                DeprecationWarning,
                stacklevel=2,
            )
            return getattr(importlib.import_module(home), new)
        raise AttributeError(f"module {module!r} has no attribute {name!r}")

    return resolve
