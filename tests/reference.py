"""Reference values written out independently of the package (used by several test files)."""

from __future__ import annotations

import math


def delta_limit_by_hand(
    phi: float = 28.5, delta: float = 20.0, L: float = 10.0, f: float = 0.05
) -> float:
    """eqn-delta_soln: -ln f L tan(delta) / (2 sqrt(sin^2 phi - tan^2 delta)); 17.67 for the
    paper's parameters."""
    s, t = math.sin(math.radians(phi)), math.tan(math.radians(delta))
    return -math.log(f) * L * t / (2.0 * math.sqrt(s * s - t * t))
