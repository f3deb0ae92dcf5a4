"""The three experiments the paper compares with, as presets (section "Comparison with
experimental data").

Walls are taken at the outer edges of the glued grain layers, as in the paper. phi, eps, Ri and
K are the paper's choices (phi from the literature, K matched to the reported wall slip); L and
A keep the paper's values (``config.L``, ``config.A``); the glass beads' phi is the paper's
default, ``config.PHI``. The measured points are not public: load your own with
:func:`cosserat.measurements.read_profile` and overlay or fit them.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Literal

from .. import config
from ..model import Cosserat, Couette, Problem
from ..model.parameters import Material, Wall


@dataclass(frozen=True)
class ExperimentPreset:
    """A Couette experiment of the paper.

    Parameters
    ----------
    name, description : str
    phi : float
        Angle of internal friction [deg].
    eps : float
        Grain diameter over gap, d_p/H [-].
    Ri : float
        Inner radius over gap, R_i/H [-].
    K : float
        Slip coefficient of both walls [-].
    L, A : float, default :data:`cosserat.config.L`, :data:`cosserat.config.A`
        Yield-condition constants [-].
    """

    name: str
    description: str
    phi: float
    eps: float
    Ri: float
    K: float
    L: float = config.L
    A: float = config.A

    @property
    def material(self) -> Material:
        return Material(self.phi, L=self.L, A=self.A)

    @property
    def default_delta(self) -> float:
        """atan(sin phi) - 2 deg: the paper's solid lines, which fit the data better [deg]."""
        return self.material.fully_rough_delta - 2.0

    def problem(self, delta: float | Literal["fully-rough"] | None = None) -> Problem:
        """The preset cell with the Cosserat model, wall friction ``delta`` [deg] or
        "fully-rough" (default: :attr:`default_delta`)."""
        wall = Wall(self.default_delta if delta is None else delta, self.K)
        return Problem(
            Couette(eps=self.eps, Ri=self.Ri), Cosserat(material=self.material, wall=wall)
        )


PRESETS = {
    "mustard": ExperimentPreset(
        "mustard", "mustard seeds, MRI (Mueth et al. 2000)", phi=25.0, eps=0.15, Ri=2.29, K=0.65
    ),
    "poppy": ExperimentPreset(
        "poppy", "poppy seeds, MRI (Mueth et al. 2000)", phi=31.0, eps=0.058, Ri=1.89, K=0.0
    ),
    "glass": ExperimentPreset(
        "glass",
        "glass beads, free-surface video (Bocquet et al. 2001)",
        phi=config.PHI,
        eps=0.067,
        Ri=4.25,
        K=0.0,
    ),
}
