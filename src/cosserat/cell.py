"""Former home of :class:`CouetteCell`; kept so that ``from cosserat.cell import CouetteCell``
works. The class lives in :mod:`cosserat.analysis.cell`."""

from .analysis.cell import CouetteCell

__all__ = ["CouetteCell"]
