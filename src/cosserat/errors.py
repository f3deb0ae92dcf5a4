"""The package's exception family.

Every error the library raises on purpose derives from :class:`CosseratError`, so a caller
(and the command line) can tell a model or input problem from a programming error.
"""

from __future__ import annotations


class CosseratError(Exception):
    """Root of the package's exceptions."""


class ParameterError(CosseratError, ValueError):
    """A parameter is outside the bounds the model allows.

    The message names the parameter, the bound that was tested and the value received.
    """


class NoSolutionError(CosseratError, ValueError):
    """The model has no real solution for these parameters.

    Raised where the square root of the yield condition (``eqn-nd_sigxy``) turns negative, so
    that the second shear stress would be complex. The message says where in the gap and why.
    """


class MethodNotAvailableError(CosseratError, ValueError):
    """The requested solution route does not exist for this problem (e.g. no closed form)."""


class ConvergenceError(CosseratError, RuntimeError):
    """A numerical method failed to reach the requested tolerance."""


class InputError(CosseratError, ValueError):
    """An input or output the user named (a file, a folder, an address) cannot be used.

    The message names it and says why (no such file, a directory, permission denied, ...).
    """


def shown(value: object) -> str:
    """A value as error messages show it: a number plainly (a NumPy scalar too: ``-1.0``, not
    ``np.float64(-1.0)``), anything else by its ``repr`` (a string in quotes)."""
    if isinstance(value, bool) or not hasattr(value, "__float__"):
        return repr(value)
    if hasattr(value, "item") and type(value).__module__ == "numpy":  # a NumPy scalar
        value = value.item()
    return repr(value)
