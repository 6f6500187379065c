"""Domain of the model, the package's warning class, and input checks shared by every API layer.

The Python layer validates and raises; the jitted kernels underneath return NaN for points outside
the model's definition, so batch loops never raise.
"""
from __future__ import annotations

from types import FrameType
from typing import Any
from numpy.typing import NDArray
import math
import numbers
import os
import sys
import warnings

import numpy as np

__all__ = ["EPS_Y_VALIDATED", "NU_VALIDATED", "OMEGA_M_STAR_MAX", "EDGE_TOL", "OMEGA_STAR_SWITCH",
           "ValidityWarning", "ExtrapolationWarning", "as_float_array", "real_scalar", "check_bool",
           "check_count", "check_tol", "short_repr", "broadcast_named", "broadcast_inputs", "kernel_array", "shaped",
           "check_finite_result", "check_finite_positive", "check_nu", "check_eps_y", "check_velocity", "warn",
           "warn_if_outside_validated"]

# Range the paper validated (JGM 2010, section 3.3 and end of section 3.3).
EPS_Y_VALIDATED = (0.0005, 0.01)
NU_VALIDATED = (0.2, 0.45)
#: Largest normalised maximum interference the paper computed (JGM 2010, section 3.3).
OMEGA_M_STAR_MAX = 425.0
#: Relative slack at the edges of a range of material parameters: last-ulp rounding of an edge
#: value (0.001 + 0.0005 * 18 = 0.010000000000000002) is at the edge, not outside it.
EDGE_TOL = 4.0 * 2.0**-52
#: JG (2005) switches from Hertz to its elasto-plastic fit at w* = 1.9 (eqs 8-9).
OMEGA_STAR_SWITCH = 1.9


class ValidityWarning(UserWarning):
    """Input is inside the model's definition but outside the range the paper validated
    (0.0005 <= eps_y <= 0.01, 0.2 <= nu <= 0.45, w_m* <= 425).

    The result is computed with the model's formulas as defined; it is not validated there.
    Attributed to the caller's line (not to fastrest's internals).

    Parameters
    ----------
    message : str
        What lies outside the range (raised by fastrest, not by users).

    Notes
    -----
    JGM section 3.3 states the validated range (docs/model.md section 4). Filter it like any
    warning, e.g. ``warnings.simplefilter("error", fastrest.ValidityWarning)`` to refuse such
    input; :class:`ExtrapolationWarning` is a subclass.

    Examples
    --------
    >>> import warnings, fastrest
    >>> with warnings.catch_warnings(record=True) as caught:
    ...     warnings.simplefilter("always")
    ...     e = fastrest.direct.e_exact(10.0, 0.02, 0.33)  # eps_y above 0.01
    >>> caught[0].category.__name__
    'ValidityWarning'
    """


class ExtrapolationWarning(ValidityWarning):
    """A result was extrapolated past w_m* = 425 at the caller's request (``extrapolate=True``).

    Parameters
    ----------
    message : str
        Where the extrapolation starts (raised by fastrest, not by users).

    Notes
    -----
    w_m* = 425 is the largest interference JGM computed (section 3.3); past it the same formulas
    are used up to a/R = 1 (eq 12), where the Jackson-Green law ends (docs/model.md section 4).
    A subclass of :class:`ValidityWarning`.

    Examples
    --------
    >>> import warnings, fastrest
    >>> with warnings.catch_warnings(record=True) as caught:
    ...     warnings.simplefilter("always")
    ...     e = fastrest.direct.e_exact(2000.0, 0.005, 0.33, extrapolate=True)
    >>> caught[0].category.__name__
    'ExtrapolationWarning'
    """


_NOT_REAL = (str, bytes, bytearray, memoryview, bool, np.bool_)


def _any_not_real(items):
    # nested lists too: NumPy would read [[1.0, True]] as [[1.0, 1.0]]
    return any(el is None or isinstance(el, _NOT_REAL)
               or (isinstance(el, (list, tuple)) and _any_not_real(el)) for el in items)


def _type_error(name, x):
    return TypeError(f"{name} must be a real number or array of real numbers, got {_short(x)} "
                     f"({type(x).__name__})")


def _short(x):
    r = repr(x)
    return r if len(r) <= 80 else r[:77] + "..."


#: ``repr(x)``, cut at 80 characters: a value quoted in an error message.
short_repr = _short


def as_float_array(x: object, name: str) -> NDArray[np.float64]:
    """Return ``x`` as a float64 ndarray.

    Raises TypeError naming ``name`` for anything that is not real-valued: strings (NumPy would
    parse ``"5"``), booleans, None (NumPy would make it NaN), complex numbers, datetimes, masked
    arrays (NumPy would drop the mask); ValueError for integers beyond the float range.
    """
    if x is None or isinstance(x, _NOT_REAL):
        raise _type_error(name, x)
    if isinstance(x, np.ma.MaskedArray):
        raise TypeError(f"{name}: masked arrays are not accepted (the mask would be ignored); pass "
                        "x.compressed() or x.filled(value)")
    if isinstance(x, (list, tuple)) and _any_not_real(x):
        raise _type_error(name, x)  # NumPy would read [1.0, True] as [1.0, 1.0]
    try:
        a = np.asarray(x)
    except (TypeError, ValueError) as exc:  # e.g. ragged nested lists
        raise _type_error(name, x) from exc
    except OverflowError as exc:
        raise ValueError(f"{name} = {_short(x)} is beyond the range of a float64") from exc
    kind = a.dtype.kind
    if kind == "O":
        if _any_not_real(a.flat) or not all(isinstance(el, numbers.Real) for el in a.flat):
            raise _type_error(name, x)
        try:
            return a.astype(np.float64)
        except OverflowError as exc:  # a Python int beyond the float range
            raise ValueError(f"{name} = {_short(x)} is beyond the range of a float64 "
                             f"(|x| < {sys.float_info.max:.4g})") from exc
        except (TypeError, ValueError) as exc:
            raise _type_error(name, x) from exc
    if kind not in "iuf":
        raise _type_error(name, x)
    return a if a.dtype == np.float64 else a.astype(np.float64)


def real_scalar(x: object, name: str) -> float:
    """``x`` as a Python float; TypeError naming ``name`` unless it is one real number."""
    a = as_float_array(x, name)
    if a.ndim != 0:
        raise TypeError(f"{name} must be a single real number, got an array of shape {a.shape}")
    return float(a)


def check_bool(x: object, name: str) -> bool:
    """``x`` as a Python bool: only ``True``/``False`` (or NumPy booleans) are accepted.

    A flag read by truthiness would take ``"False"``, ``"no"``, 2.5 or NaN as True.
    """
    if isinstance(x, (bool, np.bool_)):
        return bool(x)
    raise TypeError(f"{name} must be True or False, got {_short(x)} ({type(x).__name__})")


def check_count(x: object, name: str, lo: int, hi: int) -> int:
    """A whole number ``lo <= x <= hi`` (an int); TypeError for non-numbers, ValueError otherwise."""
    if isinstance(x, (np.timedelta64, np.datetime64)):  # numbers.Integral, yet a duration or a date
        raise TypeError(f"{name} must be a whole number, got {_short(x)} ({type(x).__name__})")
    if isinstance(x, numbers.Integral) and not isinstance(x, (bool, np.bool_)):
        v = int(x)
    else:
        f = real_scalar(x, name)
        if not (math.isfinite(f) and f.is_integer()):
            raise ValueError(f"{name} must be a whole number in [{lo}, {hi}]; got {_short(x)}")
        v = int(f)
    if not lo <= v <= hi:
        raise ValueError(f"{name} must be a whole number in [{lo}, {hi}]; got {_short(x)}")
    return v


def check_tol(tol: object, tol_min: float, meaning: str) -> float:
    """A tolerance ``tol_min <= tol < 1`` (a float): TypeError unless one real number, ValueError
    otherwise, with ``meaning`` (what the tolerance bounds, and why its floor) in the message."""
    t = real_scalar(tol, "tol")
    if not (tol_min <= t < 1.0):
        raise ValueError(f"tol must be in [{tol_min:g}, 1) ({meaning}); got {t!r}")
    return t


def broadcast_named(*named):
    """np.broadcast_shapes of (array, name) pairs, with a ValueError naming the parameters."""
    try:
        return np.broadcast_shapes(*(np.shape(a) for a, _ in named))
    except ValueError:
        shapes = ", ".join(f"{n} {np.shape(a)}" for a, n in named)
        raise ValueError(f"the shapes of {shapes} do not broadcast together (each must be a "
                         "scalar, or arrays of equal or broadcastable shapes)") from None


def kernel_array(a: NDArray[Any], dtype: Any = np.float64) -> NDArray[Any]:
    """``a`` as the array every jit array kernel is compiled for: flat (1-d), C-contiguous, aligned,
    writeable, native-endian ``dtype``.

    The one place the Python layer shapes arrays for Numba: a read-only (memory-mapped, xarray),
    strided, unaligned or byte-swapped input would otherwise be a new Numba type and compile the
    kernel again (seconds) although warm-up compiled it. Copies only when ``a`` is not already
    such an array (a read-only array is copied: one memcpy, ~1 ns per element).
    """
    if type(a) is np.ndarray and a.dtype == dtype:
        f = a.flags
        if f.c_contiguous and f.writeable and f.aligned:
            return a.ravel()  # a view, no copy
    return np.require(a, dtype, ("C", "A", "W")).ravel()


def broadcast_inputs(*named: tuple[object, str]) -> tuple[list[NDArray[np.float64]], tuple[int, ...]]:
    """Broadcast (array, name) pairs to flat float64 arrays (:func:`kernel_array`); return
    (flat arrays, shape)."""
    arrays = [as_float_array(a, n) for a, n in named]
    shape = broadcast_named(*zip(arrays, (n for _, n in named)))
    # broadcast_to + copy, not broadcast_arrays: its views warn (FutureWarning) when Numba reads
    # their writeable flag
    return [kernel_array(a) if a.shape == shape else np.broadcast_to(a, shape).copy().ravel()
            for a in arrays], shape


def shaped(out: NDArray[np.float64], shape: tuple[int, ...]) -> float | NDArray[np.float64]:
    """Give a kernel's flat output the broadcast shape; 0-d becomes a Python float."""
    out = out.reshape(shape)
    return float(out) if out.ndim == 0 else out


def check_finite_result(out, what, inputs):
    """ValueError unless every element of ``out`` is finite: a formula that overflows or
    underflows double precision says so instead of returning inf or NaN. ``inputs``: (name, value)
    pairs reported in the message."""
    a = np.asarray(out)
    if np.all(np.isfinite(a)):
        return out
    i = int(np.flatnonzero(~np.isfinite(np.ravel(a)))[0])
    parts = []
    for n, v in inputs:
        v = np.ravel(np.broadcast_to(np.asarray(v, dtype=np.float64), a.shape))[i] if np.size(v) else v
        parts.append(f"{n} = {float(v)!r}")
    at = f" at {', '.join(parts)}" if parts else ""
    raise ValueError(f"{what} is not a finite number{at}: the inputs lie outside "
                     "the range where the formula can be evaluated in double precision")


def check_finite_positive(x: object, name: str, unit: str) -> NDArray[np.float64]:
    """Raise ValueError unless every element of ``x`` is finite and > 0."""
    a = as_float_array(x, name)
    bad = ~(np.isfinite(a) & (a > 0))
    if np.any(bad):
        v = float(a[bad].flat[0] if a.ndim else a)
        raise ValueError(f"{name} must be finite and > 0 {unit}; got {v!r}")
    return a


def check_nu(nu: object, name: str = "nu", allow_half: bool = False) -> NDArray[np.float64]:
    """Poisson's ratio: the model is defined for 0 <= nu < 0.5 (<= 0.5 for the pure formulas of C)."""
    a = as_float_array(nu, name)
    hi_ok = (a <= 0.5) if allow_half else (a < 0.5)
    bad = ~((a >= 0.0) & hi_ok)  # also catches NaN
    if np.any(bad):
        v = float(a[bad].flat[0] if a.ndim else a)
        rng = "[0, 0.5]" if allow_half else "[0, 0.5)"
        raise ValueError(f"{name} (Poisson's ratio) must be in {rng}; got {v!r}")
    return a


def check_eps_y(eps_y: object, name: str = "eps_y") -> NDArray[np.float64]:
    """eps_y = Sy/E' must be finite and > 0."""
    return check_finite_positive(eps_y, name, "(dimensionless, Sy/E')")


def check_velocity(v: object, name: str, unit: str = "(dimensionless, V1/Vc)") -> NDArray[np.float64]:
    """An impact speed must be finite and >= 0 (0 is the elastic limit, e = 1)."""
    a = as_float_array(v, name)
    bad = ~(np.isfinite(a) & (a >= 0))
    if np.any(bad):
        val = float(a[bad].flat[0] if a.ndim else a)
        raise ValueError(f"{name} must be finite and >= 0 {unit}; got {val!r}")
    return a


_PACKAGE_DIR = os.path.dirname(os.path.abspath(__file__)) + os.sep


def warn(message: str, category: type[Warning]) -> None:
    """warnings.warn attributed to the first caller outside fastrest (the user's line), however
    deep inside the package the warning is raised."""
    f: FrameType | None = sys._getframe(0)
    level = 1
    while f is not None and f.f_code.co_filename.startswith(_PACKAGE_DIR):
        f = f.f_back
        level += 1
    warnings.warn(message, category, stacklevel=level)


def warn_if_outside_validated(eps_y, nu):
    """Warn once (per call) if any material lies outside the paper's validated range."""
    eps_y = np.asarray(eps_y)
    nu = np.asarray(nu)
    lo, hi = EPS_Y_VALIDATED
    out_e = np.any((eps_y < lo * (1.0 - EDGE_TOL)) | (eps_y > hi * (1.0 + EDGE_TOL)))
    lo_n, hi_n = NU_VALIDATED
    out_n = np.any((nu < lo_n * (1.0 - EDGE_TOL)) | (nu > hi_n * (1.0 + EDGE_TOL)))
    if out_e or out_n:
        parts = []
        if out_e:
            parts.append(f"eps_y outside [{lo}, {hi}]")
        if out_n:
            parts.append(f"nu outside [{lo_n}, {hi_n}]")
        warn("input outside the range validated by Jackson, Green & Marghitu (2010): "
             + " and ".join(parts) + "; the model is computed as defined but is not validated there",
             ValidityWarning)
