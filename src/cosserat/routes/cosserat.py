"""The Cosserat model's routes, registered per (cell, method) (:mod:`.registry`).

* "numerical": the compiled kernels, :mod:`cosserat.routes.numerical` (plane shear, Couette
  flow) and :mod:`cosserat.routes.channel` (the vertical channel);
* "closed-form": plane shear without gravity (:mod:`cosserat.routes.closed_form`);
* "asymptotic": the leading order in eps of the paper's Appendix
  (:mod:`cosserat.routes.asymptotic`, :func:`cosserat.routes.channel.solve_asymptotic`).
"""

from __future__ import annotations

from . import asymptotic, channel, closed_form, numerical
from .registry import register_routes

TABLE = {
    ("plane", "numerical"): numerical.solve_plane,
    ("couette", "numerical"): numerical.solve_couette,
    ("channel", "numerical"): channel.solve_numerical,
    ("plane", "closed-form"): closed_form.solve_plane,
    ("plane", "asymptotic"): asymptotic.solve_plane,
    ("couette", "asymptotic"): asymptotic.solve_couette,
    ("channel", "asymptotic"): channel.solve_asymptotic,
}
"""(cell, method) -> route of the Cosserat model."""

register_routes(
    "cosserat",
    TABLE,
    picklable=(numerical.solve_plane, numerical.solve_couette, channel.solve_numerical),
)

__all__ = ["TABLE"]
