"""The Python side of the scalar fast paths (``Curve.e(5.0)``, ``Table.e(...)``).

A scalar call from Python is dominated by checks and dispatch, not by the evaluation (a few ns):
the curves and tables call a compiled entry point (:func:`fastrest._jit.compiled_entry`) directly
when the argument is a plain real scalar, and take the checked array path otherwise (and whenever
the kernel returns NaN, so that the checked path raises the right error). :func:`fast_scalar` is
that one decision.
"""
from __future__ import annotations

from typing import Any
import numpy as np

__all__ = ["fast_scalar", "FAST_FLOAT", "FAST_CONVERT"]

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
