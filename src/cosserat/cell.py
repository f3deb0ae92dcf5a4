"""Former home of :class:`CouetteCell`; kept so that ``from cosserat.cell import CouetteCell``
works. The laboratory cells live in :mod:`cosserat.analysis.cell`."""

from .analysis.cell import ChannelCell, CouetteCell, PlaneCell

__all__ = ["ChannelCell", "CouetteCell", "PlaneCell"]
