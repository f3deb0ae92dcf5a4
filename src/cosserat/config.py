"""The paper's defaults and the package's tolerances, each defined once.

Everything that has a default value anywhere in the package (parameter classes, the command
line, sweeps, figures, fitting) reads it from here. Units as in :mod:`cosserat.model.parameters`:
angles in degrees, everything else dimensionless.
"""

from __future__ import annotations

import math
from fractions import Fraction
from typing import Final

# ----------------------------------------------------------------- the paper's parameters
PHI: Final = 28.5
"""Angle of internal friction of the paper's figures (glass beads) [deg]."""
L: Final = 10.0
"""Material length scale over grain diameter in ``eqn-yc2`` [-]."""
A: Final = 1.0 / 3.0
"""Ratio a2/a1 of the yield-condition constants (``eqn-yc2``) [-]."""
DELTA: Final = 20.0
"""Angle of wall friction of the paper's smooth walls [deg]."""
K: Final = 0.5
"""Slip coefficient of ``eqn-bc3``: a grain rolling without sliding [-]."""
B: Final = 0.0
"""Gravity parameter rho_p g H / N [-]; 0: no gravity."""
NU: Final = 1.0
"""Solids fraction [-] (only B nu enters)."""
EPS: Final = 0.04
"""Grain diameter over gap of most of the paper's profile figures [-]."""
RI: Final = 1.0
"""Inner radius over gap of the paper's Couette figures [-]."""

# ----------------------------------------------------------------- derived quantities
DEFAULT_F: Final = 0.05
"""Velocity fraction that defines the shear-layer thickness Delta (``eqn-delta_defn``) [-]."""

# ----------------------------------------------------------------- numerical tolerances
RTOL: Final = 1e-8
"""Default relative tolerance of the numerical route [-]."""
RTOL_RANGE: Final = (1e-13, 1e-2)
"""Admissible relative tolerances of the numerical route [-]."""
ATOL_OVER_RTOL: Final = 1e-2
"""Default absolute tolerance as a fraction of rtol (the fields are O(1)) [-]."""
MAX_STEPS: Final = 20_000
"""Step budget of one integration pass; beyond it the solver stops with ConvergenceError."""
OUTPUT_POINTS: Final = 201
"""Default number of points of a returned profile."""
CHECK_POINTS: Final = 801
"""Points of the layer-resolving grid on which the residuals are recomputed."""
FULLY_ROUGH_RTOL: Final = 1e-12
"""A wall with tan(delta) within this relative distance of sin(phi) is fully rough [-]
(absorbs the round-off of atan/tan, so that ``Wall(material.fully_rough_delta)`` is fully rough).
"""

# ----------------------------------------------------------------- bounds
EXISTENCE_BOUND_TOL: Final = 1e-4
"""Width to which the bisection for the existence bound in A is carried [-]."""


# ----------------------------------------------------------------- local mu(I) rheology
# mu(I) = mu_s + (mu_2 - mu_s)/(I_0/I + 1) with I = gamma_dot d / sqrt(p / rho_s): GDR MiDi,
# Eur. Phys. J. E 14, 341 (2004); the glass-bead values of Jop, Forterre & Pouliquen,
# Nature 441, 727 (2006) (``docs/derivation_mui.md``).
MUI_ANGLE_S: Final = 20.9
"""Static friction angle of glass beads, mu_s = tan(20.9 deg) (Jop et al. 2006) [deg]."""
MUI_ANGLE_2: Final = 32.76
"""Limiting friction angle of glass beads, mu_2 = tan(32.76 deg) (Jop et al. 2006) [deg]."""
MUI_MU_S: Final = math.tan(math.radians(MUI_ANGLE_S))
"""Static friction coefficient mu_s of mu(I), tan(:data:`MUI_ANGLE_S`) [-]."""
MUI_MU_2: Final = math.tan(math.radians(MUI_ANGLE_2))
"""Limiting friction coefficient mu_2 of mu(I) (mu -> mu_2 as I -> infinity) [-]."""
MUI_I0: Final = 0.279
"""Inertial number I_0 of mu(I) at which mu is halfway from mu_s to mu_2 (Jop et al. 2006) [-]."""
MUI_I_W: Final = 0.01
"""Inertial number of the wall speed, I_w = V d / (H sqrt(N / rho_s)), of a mu(I) cell [-]:
slow, dense shear (mu(I) is calibrated for I up to about 0.5)."""
MUI_I_W_MAX: Final = 1.0
"""Largest admissible I_w [-]: beyond, the flow is no longer dense (mu(I)'s range)."""
MUI_RTOL: Final = 1e-12
"""Relative tolerance of the mu(I) routes' quadratures and stress-level root-find [-]."""


def text(value: float) -> str:
    """A value as help texts and captions show it: ``{value:g}`` if that is exact, else a
    simple fraction if one is (``1/3`` for :data:`A`), else ``{value:g}``."""
    short = f"{value:g}"
    if float(short) == value:
        return short
    frac = Fraction(value).limit_denominator(12)
    return f"{frac.numerator}/{frac.denominator}" if float(frac) == value else short
