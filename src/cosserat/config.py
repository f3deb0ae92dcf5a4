"""The paper's defaults and the package's tolerances, each defined once.

Everything that has a default value anywhere in the package (parameter classes, the command
line, sweeps, figures, fitting) reads it from here. Units as in :mod:`cosserat.model.parameters`:
angles in degrees, everything else dimensionless.
"""

from __future__ import annotations

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
