"""Cells: the geometry of an experiment, its statics and its wall kinematics, written once.

A cell is what an experiment fixes whatever the material: plane shear between parallel walls
(:class:`~cosserat.model.cells.plane.Plane`), cylindrical Couette flow
(:class:`~cosserat.model.cells.couette.Couette`), the vertical channel
(:class:`~cosserat.model.cells.channel.VerticalChannel`). A rheology
(:mod:`cosserat.model.rheologies`) is put on a cell to make a
:class:`~cosserat.model.problem.Problem`; the rheology reads the cell's statics and never
restates them.

What every cell states (coordinates: ``xi`` across the gap from 0, the lower wall or the inner
cylinder, to 1; ``docs/model.md``):

* **statics**, from the momentum balances alone: the normal stress across the gap
  (:meth:`Cell.normal_stress`, over the cell's stress scale), the shear stress on planes
  parallel to the walls for a *stress level* T (:meth:`Cell.shear_stress`: T is the stress
  ratio |sigma_yx|/sigma_yy at the wall where that ratio is largest, :attr:`Cell.peak_wall`),
  the shape of the stress ratio away from that wall (:meth:`Cell.ratio_shape`, with its
  complement written without cancellation), the curvature and the radius of the coordinate
  lines (:meth:`Cell.curvature`, :meth:`Cell.radius`);
* **wall kinematics**: which wall moves and at what velocity (:meth:`Cell.wall_velocity`,
  :attr:`Cell.moving_wall`), the sign of the slip condition ``eqn-bc3`` at each wall
  (:meth:`Cell.slip_sign`), the point and value that scale the velocity
  (:attr:`Cell.velocity_scale`), the wall a shear layer is measured from
  (:attr:`Cell.layer_wall`);
* **how the drive is given**: the wall's inertial number ``I_w`` (role ``drive``: the speed of
  the experiment, used by the rate-dependent rheologies only) or an imposed stress level;
* **names for exports**: the coordinate's name and meaning and the cell's names of the fields
  (:attr:`Cell.coordinate`).

Every cell class registers itself by its :attr:`Cell.name` when it is defined
(:data:`CELLS`, py-pde's solver-registry pattern); a new cell is one module with one subclass
(``docs/architecture.md``, "The cell x rheology seam").
"""

from __future__ import annotations

from .base import CELLS, Cell, Coordinate, cell_class, eps_param, wall_inertial_number_param

# The built-in cells register themselves on import, in this order (the order of every listing).
# isort: off
from .plane import Plane
from .couette import Couette
from .channel import VerticalChannel
# isort: on

__all__ = [
    "CELLS",
    "Cell",
    "Coordinate",
    "Couette",
    "Plane",
    "VerticalChannel",
    "cell_class",
    "eps_param",
    "wall_inertial_number_param",
]
