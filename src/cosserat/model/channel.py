"""Deprecated module: the vertical channel is the cell
:class:`~cosserat.model.cells.channel.VerticalChannel` and the Cosserat model's equations on it
:mod:`cosserat.model.rheologies.cosserat.channel`. It keeps the old names importable for one
release: :func:`Channel` (a deprecated alias returning a
:class:`~cosserat.model.problem.Problem`), :class:`ChannelCase` and the compiled functions."""

from __future__ import annotations

from .aliases import Channel
from .cells.channel import shear_stress
from .rheologies.cosserat.channel import (
    FRICTION_MATCH_RTOL,
    ChannelCase,
    k_channel_radicand,
    k_torque_numerator,
)

__all__ = [
    "FRICTION_MATCH_RTOL",
    "Channel",
    "ChannelCase",
    "k_channel_radicand",
    "k_torque_numerator",
    "shear_stress",
]
