"""The base of every cell (:class:`Cell`), the registry it fills (:data:`CELLS`) and the export
names (:class:`Coordinate`); the package docstring (:mod:`cosserat.model.cells`) says what a cell
states."""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import Any, ClassVar

import numpy as np
from scipy.optimize import brentq

from ... import config
from ...errors import ParameterError
from ..constitutive import FloatArray
from ..declare import Param, declarations, param, validate

CELLS: dict[str, type[Cell]] = {}
"""Every cell class by its name (``"plane"``, ``"couette"``, ``"channel"``, ...), in the order
they were defined; a subclass of :class:`Cell` with a ``name`` adds itself when it is defined."""


@dataclass(frozen=True)
class Coordinate:
    """The names and meanings an export uses for one cell.

    Attributes
    ----------
    name : str
        Name of the wall-normal coordinate column (``y``, ``r``).
    meaning : str
        What it holds, with its scaling.
    position : callable
        ``position(cell, xi)``: the coordinate at the gap fractions ``xi`` [-].
    fields : mapping of str to (str, str)
        Profile field -> (export name, meaning) where the cell renames it.
    """

    name: str
    meaning: str
    position: Callable[[Any, FloatArray], FloatArray]
    fields: Mapping[str, tuple[str, str]] = field(default_factory=dict)


EPS_MIN = 1e-8
"""Smallest eps = d_p/H [-]: where the solvers' answers are verified. Couette's Delta (Ri = 1,
the paper's walls) converges to its limit 17.6688 (17.4472, 17.6461, 17.6665, 17.6685, 17.6687 at
eps = 1e-4 ... 1e-8) with residuals below 5e-8, and plane shear's residuals stay below 1e-9 at
1e-8; at 1e-12 they reach 6.5e-6, at 1e-16 the plane solve stalls and Couette's Delta is 16.875
(measured)."""


def eps_param() -> Any:
    """The declaration of eps = d_p/H, shared by every cell."""
    return param(
        meaning="grain diameter over gap, d_p/H",
        bounds=(EPS_MIN, 0.5),
        closed=(True, True),
        role="cell",
        reason=(
            "at least two grain diameters across the gap; below 1e-8 the solvers' answers are "
            "not verified"
        ),
        source="the run's geometry",
    )


def wall_inertial_number_param(where: str = "moving wall") -> Any:
    """The declaration of I_w, the inertial number of the wall speed (one default for every
    rheology that reads it, :data:`cosserat.config.MUI_I_W`)."""
    return param(
        config.MUI_I_W,
        f"inertial number of the {where}'s speed, V d / (H sqrt(N/rho_s)); default unless the "
        "stress is imposed instead",
        bounds=(0.0, config.MUI_I_W_MAX),
        closed=(False, True),
        fit_range=(1e-6, 1.0),
        scale="log",
        role="drive",
        optional=True,
        field_default=None,
        reason=(
            "dense flow, the range of mu(I); mu(I) and NGF also need I_w >= 1e-7 mu_s I_0/"
            "(mu_2 - mu_s) (NGF: 1e-7 mu_s/b), or the flow cannot be told from rest in double "
            "precision"
        ),
        source="slow, dense shear (mu(I) is calibrated for I up to about 0.5)",
    )


@dataclass(frozen=True, kw_only=True)
class Cell:
    """Base of every cell: a frozen, validated dataclass whose fields are declared with
    :func:`~cosserat.model.declare.param` (module docstring: what a cell states).

    Subclasses set the class attributes below, declare their fields and implement
    :meth:`normal_stress`, :meth:`shear_stress` and :meth:`ratio_shape` (and
    :meth:`distance_of_ratio` and :attr:`ratio_slope` where a closed form exists).
    """

    name: ClassVar[str] = ""
    """The cell's name on the command line and in the registry."""
    title: ClassVar[str] = ""
    """Its name in descriptions ("plane shear")."""
    coordinate: ClassVar[Coordinate]
    """Export names (:class:`Coordinate`)."""
    peak_wall: ClassVar[float] = 1.0
    """xi of the wall where the stress ratio |sigma_yx|/sigma_yy is largest (one of them if
    :attr:`~cosserat.model.cells.base.Cell.symmetric`) [-]."""
    symmetric: ClassVar[bool] = False
    """True if the flow is symmetric about xi = 1/2 (then distances run over half the gap)."""
    straight: ClassVar[bool] = True
    """True if the coordinate lines are straight: :meth:`curvature` 0 and :meth:`radius` 1
    (False for a cell that overrides them)."""
    moving_wall: ClassVar[float | None] = 1.0
    """xi of the wall that moves (None: none moves, the flow is driven otherwise)."""
    velocity_scale: ClassVar[tuple[float, float]] = (1.0, 1.0)
    """(xi, u): the point where the velocity is fixed to scale it, and its value there."""
    layer_wall: ClassVar[float] = 1.0
    """xi of the wall a shear layer is measured from (Delta) for a rheology without slip."""
    reference_velocity: ClassVar[float] = 0.0
    """u_0 of ``eqn-delta_defn``: the velocity far from :attr:`layer_wall` [-]."""
    level_name: ClassVar[str] = "stress_ratio"
    """The field that imposes the stress level instead of the wall speed."""
    peak_wall_name: ClassVar[str] = "wall"
    """What :attr:`peak_wall` is called in messages ("moving upper wall")."""

    eps: float = eps_param()

    def __init_subclass__(cls, **kwargs: Any) -> None:
        super().__init_subclass__(**kwargs)
        name = cls.__dict__.get("name", "")
        if not name:
            return
        known = CELLS.get(name)
        if known is not None and known.__qualname__ != cls.__qualname__:
            raise ParameterError(
                f"a cell named {name!r} is already registered ({known.__module__}."
                f"{known.__qualname__})"
            )
        CELLS[name] = cls

    def __post_init__(self) -> None:
        validate(self)
        if getattr(self, "I_w", None) is not None and self.imposed_level() is not None:
            raise ParameterError(
                f"give either I_w (imposed wall speed) or {self.level_name} (imposed stress), "
                "not both"
            )

    # ----------------------------------------------------------------- declarations
    @classmethod
    def declared(cls) -> dict[str, Param]:
        """Every declared parameter by its command-line key, in field order."""
        return {p.cli_key: p for p in declarations(cls).values()}

    def values(self) -> dict[str, Any]:
        """Declared key -> value."""
        return {p.cli_key: getattr(self, n) for n, p in declarations(self).items()}

    # ----------------------------------------------------------------- drive
    def imposed_level(self) -> float | None:
        """The stress level T imposed instead of the wall speed, or None [-]."""
        value = getattr(self, self.level_name, None)
        return None if value is None else float(value)

    @property
    def wall_inertial_number(self) -> float | None:
        """I_w that drives a rate-dependent rheology: the given one, its declared default
        (:data:`cosserat.config.MUI_I_W`) if neither it nor the stress is given, or None when
        the stress is imposed [-]."""
        if self.imposed_level() is not None:
            return None
        I_w = getattr(self, "I_w", None)
        return config.MUI_I_W if I_w is None else float(I_w)

    # ----------------------------------------------------------------- statics
    def normal_stress(self, xi: FloatArray) -> FloatArray:  # pragma: no cover - abstract
        """sigma_yy (sigma_c) across the gap over the cell's stress scale [-]."""
        raise NotImplementedError

    def shear_stress(self, xi: FloatArray, level: float) -> FloatArray:  # pragma: no cover
        """sigma_yx across the gap for the stress level ``level`` (the largest stress ratio)
        [-]; negative where the material above moves in +x relative to the material below."""
        raise NotImplementedError

    def stress_ratio_profile(self, xi: FloatArray, level: float) -> FloatArray:
        """|sigma_yx|/sigma_yy across the gap for the stress level ``level`` [-]."""
        q, _ = self.ratio_shape(self.distance(xi))
        return level * q

    def ratio_shape(self, t: FloatArray) -> tuple[FloatArray, FloatArray]:  # pragma: no cover
        """(q, 1 - q): the stress ratio over its largest value at the distance ``t`` from
        :attr:`peak_wall`, and its complement computed without cancellation [-]."""
        raise NotImplementedError

    def distance_of_ratio(self, r: float) -> float:
        """The distance t from :attr:`peak_wall` where the stress ratio has fallen to 1/r of
        its largest value (r >= 1); inf if it never does within :attr:`span` [-].

        Generic: Brent's method on :meth:`ratio_shape`; cells with a closed form override it.
        """
        target = 1.0 / r
        q_end = float(self.ratio_shape(np.array([self.span]))[0][0])
        if q_end > target:
            return math.inf
        if r == 1.0:
            return 0.0
        return float(
            brentq(
                lambda t: float(self.ratio_shape(np.array([t]))[0][0]) - target,
                0.0,
                self.span,
                xtol=1e-15,
                rtol=4 * np.finfo(float).eps,
            )
        )

    def distance_of_complement(self, delta: float) -> float:
        """The distance t from :attr:`peak_wall` where the complement 1 - q of the ratio
        shape reaches ``delta`` (0 <= delta <= 1), found without cancellation however small
        delta is; inf if it never does within :attr:`span` [-].

        Generic: Brent's method on the complement of :meth:`ratio_shape`, relative tolerance
        1e-10 (a layer of width 1e-150 is found as such)."""
        if delta <= 0.0:
            return 0.0
        if float(self.ratio_shape(np.array([self.span]))[1][0]) < delta:
            return math.inf
        return float(
            brentq(
                lambda t: float(self.ratio_shape(np.array([t]))[1][0]) - delta,
                0.0,
                self.span,
                xtol=np.finfo(float).tiny,
                rtol=1e-10,
                maxiter=2000,
            )
        )

    @property
    def ratio_slope(self) -> float | None:
        """d(1 - q)/dt at the peak wall, how fast the stress ratio falls away from it, where the
        cell states it in closed form; None otherwise (the rheologies then use
        :meth:`distance_of_complement`) [-]."""
        return None

    def curvature(self, xi: FloatArray) -> FloatArray:
        """kappa = 1/r of the coordinate lines: 0 between plane walls [-]."""
        return np.zeros_like(np.asarray(xi, dtype=float))

    def radius(self, xi: FloatArray) -> FloatArray:
        """r/H of the coordinate lines (1 between plane walls) [-]; a shear rate is
        ``r d(u/r)/dxi``."""
        return np.ones_like(np.asarray(xi, dtype=float))

    # ----------------------------------------------------------------- distances
    @property
    def span(self) -> float:
        """The largest distance from :attr:`peak_wall`: the gap, or half of it if
        :attr:`symmetric` [-]."""
        return 0.5 if self.symmetric else 1.0

    def distance(self, xi: FloatArray) -> FloatArray:
        """t = the distance from :attr:`peak_wall` (from the nearer wall if
        :attr:`symmetric`) [-]."""
        x = np.asarray(xi, dtype=float)
        if self.symmetric:
            return np.minimum(x, 1.0 - x)
        return np.abs(x - self.peak_wall)

    def position(self, t: FloatArray) -> FloatArray:
        """xi at the distance ``t`` from :attr:`peak_wall` [-]."""
        tt = np.asarray(t, dtype=float)
        return tt if self.peak_wall == 0.0 else 1.0 - tt

    def normal_stress_at(self, t: FloatArray) -> FloatArray:
        """:meth:`normal_stress` at the distance ``t`` from :attr:`peak_wall` (cells override
        it where xi = 1 - t would lose the digits of a small t) [-]."""
        return self.normal_stress(self.position(t))

    def radius_at(self, t: FloatArray) -> FloatArray:
        """:meth:`radius` at the distance ``t`` from :attr:`peak_wall` [-]."""
        return self.radius(self.position(t))

    def region_below(self, level: float, threshold: float) -> tuple[float, float] | None:
        """The interval of xi where the stress ratio is at most ``threshold`` for the stress
        level ``level`` (the plug of a local law, the creeping region of a nonlocal one), or
        None if there is none [-]."""
        if level <= threshold:
            return (0.0, 1.0)
        t = self.distance_of_ratio(level / threshold)
        if not t < self.span:
            return None
        if self.symmetric:
            return (t, 1.0 - t)
        return (0.0, 1.0 - t) if self.peak_wall == 1.0 else (t, 1.0)

    # ----------------------------------------------------------------- wall kinematics
    def wall_velocity(self, xi_wall: float) -> float:
        """Velocity of the wall at ``xi_wall`` over the velocity scale [-]."""
        return 1.0 if xi_wall == self.moving_wall else 0.0

    @staticmethod
    def slip_sign(xi_wall: float) -> float:
        """s in the slip condition ``u = u_wall + s eps K omega`` (``eqn-bc3``) at the wall
        ``xi_wall``: with n the normal into the material, +1 at xi = 1, -1 at xi = 0."""
        return 1.0 if xi_wall == 1.0 else -1.0

    # ----------------------------------------------------------------- text and records
    def describe(self, keys: tuple[str, ...] | None = None) -> str:
        """``eps = 0.01, B = 0, nu = 1`` for the parameters ``keys`` (default: every one that is
        set)."""
        vals = self.values()
        keys = tuple(k for k in vals if vals[k] is not None) if keys is None else keys
        return ", ".join(f"{k} = {_text(vals[k])}" for k in keys if vals.get(k) is not None)

    def parameters(self, keys: tuple[str, ...] | None = None) -> dict[str, Any]:
        """Plain-data record: ``geometry`` and the parameters ``keys`` (default: all)."""
        vals = self.values()
        out: dict[str, Any] = {"geometry": self.name}
        out.update({k: v for k, v in vals.items() if keys is None or k in keys})
        return out


def _text(value: Any) -> str:
    return f"{value:g}" if isinstance(value, float) else str(value)


def cell_class(name: str) -> type[Cell]:
    """The registered cell class called ``name``.

    Raises
    ------
    ParameterError
        No such cell (the message lists the registered ones).
    """
    try:
        return CELLS[name]
    except (KeyError, TypeError):
        raise ParameterError(
            f"cell must be one of {', '.join(repr(c) for c in CELLS)}; got {name!r}"
        ) from None
