"""The kinetic (hydrodynamic) model of Bocquet et al.: why it is not implemented.

Issue 11 asks for this rheology only if its equations can be established from the published
record. They could not: what can be read gives the model's structure (Haff's dense kinetic
theory with a shear viscosity that diverges faster than Enskog's at random close packing, the
granular temperature taken as the squared velocity fluctuation) but not its equations, and
says nothing of its wall conditions. ``docs/derivation_kinetic.md`` lists what the record
gives, with sources, what is missing, where we looked, and what would be needed.

Nothing is registered: ``cosserat.routes.RHEOLOGIES`` has no ``"kinetic"`` entry. The command
line (or any caller) can print :data:`KINETIC_NOT_AVAILABLE` or raise :func:`unavailable`.
"""

from __future__ import annotations

from ..errors import MethodNotAvailableError

REFERENCES: tuple[str, ...] = (
    "L. Bocquet, W. Losert, D. Schalk, T. C. Lubensky & J. P. Gollub, Granular shear flow "
    "dynamics and forces: experiment and continuum theory, Phys. Rev. E 65, 011307 (2002), "
    "arXiv:cond-mat/0012356",
    "W. Losert, L. Bocquet, T. C. Lubensky & J. P. Gollub, Particle dynamics in sheared "
    "granular matter, Phys. Rev. Lett. 85, 1428 (2000), arXiv:cond-mat/0004401",
    "L. Bocquet, J. Errami & T. C. Lubensky, Hydrodynamic model for a dynamical "
    "jammed-to-flowing transition in gravity driven granular media, Phys. Rev. Lett. 89, "
    "184301 (2002), arXiv:cond-mat/0112072",
    "P. K. Haff, Grain flow as a fluid-mechanical phenomenon, J. Fluid Mech. 134, 401 (1983)",
)
"""The publications the model comes from; their equations could not be read here."""

MISSING: tuple[str, ...] = (
    "shear viscosity eta(nu, T): functional form, exponent of its divergence, nu_c, prefactor",
    "thermal conductivity kappa(nu, T): density dependence and prefactor",
    "collisional dissipation Gamma(nu, T, e): density dependence and prefactor",
    "equation of state p(nu, T) near random close packing",
    "wall boundary condition for the velocity (no slip or a slip law)",
    "wall boundary condition for the granular temperature (value or heat flux)",
)
"""What a boundary-value problem needs and the readable record does not give."""

KINETIC_NOT_AVAILABLE = (
    "the kinetic model of Bocquet et al. (Phys. Rev. E 65, 011307 (2002)) is not implemented: "
    "the published record we could read gives its structure (Haff's dense kinetic theory with "
    "a shear viscosity diverging faster than Enskog's at random close packing) but not its "
    "equations, namely the density dependence and prefactors of the viscosity, conductivity, "
    "dissipation and pressure, and the wall conditions for the velocity and the granular "
    "temperature; see docs/derivation_kinetic.md"
)
"""One sentence for users: why ``--model kinetic`` does not exist."""


def unavailable(cell: str | None = None) -> MethodNotAvailableError:
    """The error to raise when the kinetic model is asked for.

    Parameters
    ----------
    cell : str, optional
        The cell it was asked for (``plane``, ``couette``, ``channel``), named in the message.

    Returns
    -------
    MethodNotAvailableError
        Its message is :data:`KINETIC_NOT_AVAILABLE` and the models that do exist.
    """
    where = f" (asked for on the {cell} cell)" if cell else ""
    return MethodNotAvailableError(
        f"{KINETIC_NOT_AVAILABLE}{where}; `cosserat models` lists the models that are available"
    )


__all__ = ["KINETIC_NOT_AVAILABLE", "MISSING", "REFERENCES", "unavailable"]
