"""A problem from a plain mapping of named parameters: the one recipe the command line, the
sweeps and any other front end share.

The names are those of the command line and of sweep specs (``docs/model.md`` gives the
symbols and units)::

    geometry      "plane" (default), "couette" or "channel"
    phi, L, A     the material [deg, -, -]
    delta, K      the moving wall (the upper plate, or both cylinders), or both channel walls
                    [deg or "fully-rough", -]
    delta_lower,  the fixed lower plate (plane; default: as the upper wall) [deg or
    K_lower         "fully-rough", -]
    B, nu         gravity parameter and solids fraction (plane, channel) [-]; in the channel
                    B = rho_p g H / N with N the wall normal stress, and its default (absent,
                    None or 0) is B nu = 2 tan(delta): wall friction fully mobilised
    m_wall        couple stress at the wall that does not slip (plane; default eqn-nd_bc4) [-]
    Ri            inner radius over gap (Couette) [-]
    eps           grain diameter over gap, d_p/H [-] (required)

Missing keys, and keys whose value is None, take the paper's defaults (:data:`DEFAULTS`, from
:mod:`cosserat.config`).
"""

from __future__ import annotations

from collections.abc import Mapping
from types import MappingProxyType
from typing import Any, Literal

from .. import config
from ..errors import ParameterError, shown
from .channel import Channel
from .couette import CouetteFlow
from .parameters import FULLY_ROUGH, Material, Wall
from .plane import PlaneShear

GEOMETRIES: tuple[str, ...] = ("plane", "couette", "channel")
"""The cells a problem can be built for."""

PARAMETERS: tuple[str, ...] = (
    "geometry",
    "phi",
    "L",
    "A",
    "delta",
    "K",
    "delta_lower",
    "K_lower",
    "B",
    "nu",
    "m_wall",
    "Ri",
    "eps",
)
"""Every name :func:`build_problem` accepts, in the order tables list them."""

DEFAULTS: Mapping[str, Any] = MappingProxyType(
    {
        "geometry": "plane",
        "phi": config.PHI,
        "L": config.L,
        "A": config.A,
        "delta": config.DELTA,
        "K": config.K,
        "B": config.B,
        "nu": config.NU,
        "Ri": config.RI,
    }
)
"""The value of every parameter that has a default (read-only). ``delta_lower`` and ``K_lower``
default to the upper wall's, ``m_wall`` to ``eqn-nd_bc4``; ``eps`` has none."""

APPLIES_TO: Mapping[str, str] = MappingProxyType(
    {
        "delta_lower": "plane",
        "K_lower": "plane",
        "B": "plane",
        "nu": "plane",
        "m_wall": "plane",
        "Ri": "couette",
    }
)
"""Parameters of one geometry only; given for the other, they must be None or the default."""

ALSO_APPLIES_TO: Mapping[str, tuple[str, ...]] = MappingProxyType(
    {"B": ("channel",), "nu": ("channel",)}
)
"""Further geometries a parameter of :data:`APPLIES_TO` applies to (the channel's B and nu)."""

ROUGH_WORDS = ("fully-rough", "fully_rough", "rough")
"""Spellings of a fully rough wall accepted for ``delta`` and ``delta_lower`` (any case)."""

_NUMBERS = ("phi", "L", "A", "K", "K_lower", "B", "nu", "m_wall", "Ri", "eps")


def wall_angle(name: str, value: Any) -> float | Literal["fully-rough"]:
    """``value`` as a :class:`Wall` takes it: an angle [deg] (validated by the wall), or
    :data:`FULLY_ROUGH` for any of ``ROUGH_WORDS`` ("fully-rough", "fully_rough", "rough").

    Raises
    ------
    ParameterError
        A string other than those words, or a boolean (the message names ``name``).
    """
    if isinstance(value, str):
        if value.strip().lower() in ROUGH_WORDS:
            return FULLY_ROUGH
        try:
            return float(value)
        except ValueError:
            raise ParameterError(
                f"{name} must be an angle in degrees or 'fully-rough'; got {value!r}"
            ) from None
    if isinstance(value, bool):
        raise ParameterError(f"{name} must be an angle in degrees or 'fully-rough'; got {value!r}")
    return value  # type: ignore[no-any-return]


def _is_default(name: str, value: Any) -> bool:
    default = DEFAULTS.get(name)
    if default is None or isinstance(value, bool) or not isinstance(value, int | float | str):
        return False
    try:
        return float(value) == default
    except ValueError:
        return False


def build_problem(parameters: Mapping[str, Any]) -> PlaneShear | CouetteFlow | Channel:
    """The :class:`PlaneShear` or :class:`CouetteFlow` that ``parameters`` describe.

    Parameters
    ----------
    parameters : mapping of str to value
        Names among :data:`PARAMETERS` (module docstring: meaning and units). Absent names and
        None values take :data:`DEFAULTS`; ``eps`` is required. Numbers may also be given as
        numeric strings (as read from a file); ``delta`` and ``delta_lower`` also as
        "fully-rough" (or "rough").

    Returns
    -------
    PlaneShear or CouetteFlow
        Validated: every bound of the model is checked on construction.

    Raises
    ------
    ParameterError
        An unknown name (listing the known ones), an unknown geometry (listing the allowed
        ones), a missing ``eps``, a parameter of the other geometry set to a value other than
        its default, or a value out of its bounds; the message names the parameter.
    """
    if not isinstance(parameters, Mapping):
        raise ParameterError(
            f"the parameters must be a mapping of name to value; got {type(parameters).__name__}"
        )
    unknown = sorted(str(k) for k in parameters if k not in PARAMETERS)
    if unknown:
        raise ParameterError(
            f"unknown parameter(s) {', '.join(unknown)}; known: {', '.join(PARAMETERS)}"
        )
    given = {k: v for k, v in parameters.items() if v is not None}
    geometry = given.get("geometry", DEFAULTS["geometry"])
    if not isinstance(geometry, str) or geometry not in GEOMETRIES:
        raise ParameterError(
            f"geometry must be one of {', '.join(repr(g) for g in GEOMETRIES)}; got {geometry!r}"
        )
    if "eps" not in given:
        raise ParameterError(
            "eps (grain diameter over gap, d_p/H) must be given; it has no default"
        )
    for name in _NUMBERS:
        if isinstance(given.get(name), bool):
            raise ParameterError(f"{name} must be a number; got {given[name]!r}")
    for name, where in APPLIES_TO.items():
        if where != geometry and geometry not in ALSO_APPLIES_TO.get(name, ()):
            if name not in given or _is_default(name, given[name]):
                continue
            raise ParameterError(
                f"{name} applies to geometry {where!r} only; got {name} = {shown(given[name])} for "
                f"geometry {geometry!r}"
            )
    p = {**DEFAULTS, **given}
    material = Material(p["phi"], p["L"], p["A"])
    delta = wall_angle("delta", p["delta"])
    upper = Wall(delta, p["K"])
    if geometry == "couette":
        return CouetteFlow(material=material, wall=upper, eps=p["eps"], Ri=p["Ri"])
    if geometry == "channel":  # B absent or at the plane default (0): friction mobilised
        B = None if _is_default("B", p["B"]) else p["B"]
        return Channel(material=material, wall=upper, eps=p["eps"], B=B, nu=p["nu"])
    lower = None
    if "delta_lower" in given or "K_lower" in given:
        delta_lower = wall_angle("delta_lower", given.get("delta_lower", delta))
        try:
            lower = Wall(delta_lower, given.get("K_lower", p["K"]))
        except ParameterError as exc:
            raise ParameterError(f"lower wall (delta_lower, K_lower): {exc}") from None
    return PlaneShear(
        material=material,
        upper=upper,
        lower=lower,
        eps=p["eps"],
        B=p["B"],
        nu=p["nu"],
        m_fixed_wall=p.get("m_wall"),
    )


__all__ = [
    "ALSO_APPLIES_TO",
    "APPLIES_TO",
    "DEFAULTS",
    "GEOMETRIES",
    "PARAMETERS",
    "build_problem",
    "wall_angle",
]
