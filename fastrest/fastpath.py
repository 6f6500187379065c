"""The Python side of the scalar fast paths (``Curve.e(5.0)``, ``Table.e(...)``).

A scalar call from Python is dominated by checks and dispatch, not by the evaluation (a few ns):
the curves and tables call a compiled entry point (:func:`fastrest._jit.compiled_entry`) directly
when the argument is a plain real scalar, and take the checked array path otherwise (and whenever
the kernel returns NaN, so that the checked path raises the right error). :func:`fast_scalar` is
that one decision.

The typing side of the same contract, "a float in gives a float out, a sequence an array", is
written once here for every quantity method and function (w_m*, e, 1 - e^2 of curves, scenes,
tables and the default table): one callable :class:`~typing.Protocol` per call signature, each
with its ``@overload`` stack, and a decorator that declares a function of that type to mypy
(:func:`curve_quantity`, :func:`scene_quantity`, :func:`table_omega`, :func:`table_quantity`). At
run time each decorator returns its function unchanged.
"""
from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import Any, Protocol, cast, overload

import numpy as np
from numpy.typing import ArrayLike, NDArray

# (the protocols are typing only: not in __all__)
__all__ = ["fast_scalar", "FAST_FLOAT", "FAST_CONVERT", "curve_quantity", "scene_quantity", "table_omega",
           "table_quantity"]

#: Scalar types the fast paths take as they are (NumPy's float64 is a subclass of float).
FAST_FLOAT = (float, np.float64)
#: Scalar types the fast paths convert to float exactly (NumPy floats and integers).
FAST_CONVERT = (np.float32, np.float16, np.int8, np.int16, np.int32, np.int64, np.uint8, np.uint16,
                np.uint32, np.uint64)


def fast_scalar(x: Any) -> float | None:
    """``x`` as a float if it is a real scalar a scalar fast path may take; None otherwise.

    Parameters
    ----------
    x : object
        A speed or material parameter as the caller passed it (units of the caller's parameter).

    Returns
    -------
    float or None
        ``x`` itself for a Python float or NumPy float64; ``float(x)`` for another NumPy float or
        integer scalar (what a loop over an array yields) or a Python int within +/- 2^53 (exact);
        None for anything else (booleans, strings, arrays, ...): the checked path decides, and
        raises TypeError or ValueError naming the parameter.

    Notes
    -----
    A type test, not ``isinstance``: subclasses (``bool`` is an ``int``) go to the checked path.

    Examples
    --------
    >>> import numpy as np
    >>> from fastrest.fastpath import fast_scalar
    >>> fast_scalar(np.float32(0.5)), fast_scalar(3), fast_scalar(True)
    (0.5, 3.0, None)
    """
    t = type(x)
    if t in FAST_FLOAT:
        return x
    if t in FAST_CONVERT:
        return float(x)
    if t is int and -2**53 <= x <= 2**53:
        return float(x)
    return None


# --- the typing of the quantity methods: a float in gives a float out, a sequence an array ----------

_Result = float | NDArray[np.float64]


class CurveQuantity(Protocol):
    """``Curve.omega_m``, ``Curve.e``, ``Curve.loss``: ``(v1_star)``."""

    @overload
    def __call__(self, v1_star: float) -> float: ...
    @overload
    def __call__(self, v1_star: Sequence[float]) -> NDArray[np.float64]: ...
    @overload
    def __call__(self, v1_star: ArrayLike) -> float | NDArray[np.float64]: ...


class SceneQuantity(Protocol):
    """``Scene.omega_m``, ``Scene.e``, ``Scene.loss``: ``(v1_star, material)``."""

    @overload
    def __call__(self, v1_star: float, material: int) -> float: ...
    @overload
    def __call__(self, v1_star: Sequence[float], material: ArrayLike) -> NDArray[np.float64]: ...
    @overload
    def __call__(self, v1_star: ArrayLike, material: ArrayLike) -> float | NDArray[np.float64]: ...


class TableOmega(Protocol):
    """``Table.omega_m`` and ``fastrest.omega_m_star``: ``(v1_star, eps_y, nu)``."""

    @overload
    def __call__(self, v1_star: float, eps_y: float, nu: float) -> float: ...
    @overload
    def __call__(self, v1_star: ArrayLike, eps_y: ArrayLike, nu: ArrayLike) -> float | NDArray[np.float64]: ...


class TableQuantity(Protocol):
    """``Table.e``, ``Table.loss``, ``fastrest.e_star``, ``fastrest.loss_star``:
    ``(v1_star, eps_y, nu, unloading="jcg")``."""

    @overload
    def __call__(self, v1_star: float, eps_y: float, nu: float, unloading: str = "jcg") -> float: ...
    @overload
    def __call__(self, v1_star: ArrayLike, eps_y: ArrayLike, nu: ArrayLike,
                 unloading: str = "jcg") -> float | NDArray[np.float64]: ...


# A method decorated with one of these is an attribute of the protocol's type to mypy (not bound:
# the protocol's signature has no ``self``); at run time it is the function itself.

def curve_quantity(f: Callable[..., _Result]) -> CurveQuantity:
    """Declare ``f`` a :class:`CurveQuantity` (typing only; returns ``f``)."""
    return cast(CurveQuantity, f)


def scene_quantity(f: Callable[..., _Result]) -> SceneQuantity:
    """Declare ``f`` a :class:`SceneQuantity` (typing only; returns ``f``)."""
    return cast(SceneQuantity, f)


def table_omega(f: Callable[..., _Result]) -> TableOmega:
    """Declare ``f`` a :class:`TableOmega` (typing only; returns ``f``)."""
    return cast(TableOmega, f)


def table_quantity(f: Callable[..., _Result]) -> TableQuantity:
    """Declare ``f`` a :class:`TableQuantity` (typing only; returns ``f``)."""
    return cast(TableQuantity, f)
