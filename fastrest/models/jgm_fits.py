"""JGM's empirical fits to their own model: eqs (42)-(44) (JCG unloading) and (45) (Etsion).

NumPy functions that validate and warn (:func:`jgm_fit_jcg`, :func:`jgm_fit_etsion`) and Numba
functions that do neither (``*_kernel``: one point, NaN outside the domain; ``*_array``: a loop
over arrays writing into ``out``), the speed reference of the benchmarks.
"""
from __future__ import annotations

from typing import Any
from numpy.typing import ArrayLike, NDArray
import math

import numpy as np

from .._jit import jit
from .._validation import EPS_Y_VALIDATED, ValidityWarning, warn
from .._doc import doc, paragraphs
from ._common import MODEL_DOC, finite_out, v_star_inputs

__all__ = ["JGM_FIT_V_MAX", "jgm_fit_jcg", "jgm_fit_etsion", "jgm_fit_jcg_kernel", "jgm_fit_jcg_array",
           "jgm_fit_etsion_kernel", "jgm_fit_jcg_scalar"]

#: Upper end of the range of JGM's fit (44), V1* <= 1000.
JGM_FIT_V_MAX = 1000.0

# What the two fits raise and warn, written once (fastrest._doc).
_DOC = {**MODEL_DOC, **paragraphs(returns_fit="""
    {returns_e}
    ValueError
        v1_star negative or not finite, eps_y <= 0, or shapes that do not broadcast (the message names the parameter).

    Warns
    -----
    ValidityWarning
    """)}


def _warn_fit(v, eps, check_v_max):
    lo, hi = EPS_Y_VALIDATED
    parts = []
    if np.any((eps < lo) | (eps > hi)):
        parts.append(f"eps_y outside [{lo}, {hi}]")
    if check_v_max and np.any(v > JGM_FIT_V_MAX):
        parts.append(f"v1_star > {JGM_FIT_V_MAX:g} (beyond the range of eq 44)")
    if parts:
        warn("JGM empirical fit used outside its fitted range: " + " and ".join(parts)
             + "; the formula is evaluated as printed", ValidityWarning)


@doc(_DOC)
def jgm_fit_jcg(v1_star: ArrayLike, eps_y: ArrayLike) -> float | NDArray[np.float64]:
    """JGM's empirical fit to their model with JCG unloading (eq 35): eqs (42)-(44).

    * V1* <= 1: e = 1 (eq 42);
    * 1 < V1* <= 60: e = 1 - 0.1 ln(V1*) ((V1* - 1)/59)^0.156 (eq 43);
    * V1* > 60: e = 1 - 0.1 ln 60 - 0.11 ln(V1*/60) (V1* - 60)^(2.36 eps_y) (eq 44).

    The pieces are continuous: at V1* = 1, ln 1 = 0; at V1* = 60 both (43) and (44) equal
    1 - 0.1 ln 60 = 0.590566 exactly (the last factor of 43 is 1 and the last term of 44 is 0), as
    the paper claims; the slope is not continuous there. JGM state the fit differs from their
    numerical results by 1.5 % on average and 4.5 % at most for V1* <= 1000,
    0.0005 < eps_y < 0.01, 0.2 < nu < 0.45. Outside 0.0005 <= eps_y <= 0.01 or above V1* = 1000 the
    formula is still evaluated and a :class:`~fastrest.ValidityWarning` is issued. A Numba version
    is :func:`jgm_fit_jcg_kernel`.

    {params_v1_eps_y}

    {returns_fit}
        eps_y outside 0.0005-0.01 or v1_star > 1000 (:data:`JGM_FIT_V_MAX`): the formula as printed.

    Notes
    -----
    JGM eqs (42)-(44).

    Examples
    --------
    >>> from fastrest.models import jgm_fit_jcg
    >>> jgm_fit_jcg(0.5, 0.005), round(jgm_fit_jcg(10.0, 0.005), 4)
    (1.0, 0.8283)
    """
    v, eps = v_star_inputs(v1_star, eps_y=eps_y)
    _warn_fit(v, eps, True)
    low = np.where(v > 1.0, np.minimum(v, 60.0), 2.0)
    high = np.where(v > 60.0, v, 61.0)
    e43 = 1.0 - 0.1 * np.log(low) * ((low - 1.0) / 59.0) ** 0.156
    e44 = 1.0 - 0.1 * math.log(60.0) - 0.11 * np.log(high / 60.0) * (high - 60.0) ** (2.36 * eps)
    e = np.where(v <= 1.0, 1.0, np.where(v <= 60.0, e43, e44))
    return finite_out(e, ("v1_star", v), ("eps_y", eps))


@doc(_DOC)
def jgm_fit_etsion(v1_star: ArrayLike, eps_y: ArrayLike) -> float | NDArray[np.float64]:
    """JGM's empirical fit to their model with Etsion et al. unloading (eq 33): eq (45).

    e = 1 - 0.0361 eps_y^(-0.114) ln(V1*) (V1* - 1)^(9.5 eps_y) for V1* > 1, and e = 1 for
    V1* <= 1 (continuous there). JGM: differs from their results by 5.3 % on average and 8.4 % at
    most, for 0.0005 < eps_y < 0.01, 0.2 < nu < 0.45 (no upper speed is stated; their computations
    end at omega_m* = 425). Outside that eps_y range a :class:`~fastrest.ValidityWarning` is issued.

    {params_v1_eps_y}

    {returns_fit}
        eps_y outside 0.0005-0.01: the formula as printed.

    Notes
    -----
    JGM eq (45). A Numba version is :func:`jgm_fit_etsion_kernel`.

    Examples
    --------
    >>> from fastrest.models import jgm_fit_etsion
    >>> jgm_fit_etsion([0.5, 10.0], 0.005).round(4)
    array([1.    , 0.8312])
    """
    v, eps = v_star_inputs(v1_star, eps_y=eps_y)
    _warn_fit(v, eps, False)
    vs = np.where(v > 1.0, v, 2.0)
    e = 1.0 - 0.0361 * eps**-0.114 * np.log(vs) * (vs - 1.0) ** (9.5 * eps)
    return finite_out(np.where(v > 1.0, e, 1.0), ("v1_star", v), ("eps_y", eps))


@jit
@doc(MODEL_DOC)
def jgm_fit_jcg_kernel(v1_star, eps_y):
    """JGM eqs (42)-(44) at one point, in Numba code: the kernel of :func:`jgm_fit_jcg`.

    {params_kernel}

    {returns_kernel}

    Notes
    -----
    Eqs (42)-(44) as in :func:`jgm_fit_jcg`; ``jgm_fit_jcg_scalar`` is another name of this
    function, and :func:`jgm_fit_jcg_array` its loop over arrays.

    Examples
    --------
    >>> from fastrest.models import jgm_fit_jcg_kernel
    >>> jgm_fit_jcg_kernel(0.5, 0.005), round(jgm_fit_jcg_kernel(60.0, 0.005), 6)
    (1.0, 0.590566)
    """
    if not (v1_star >= 0.0 and v1_star < math.inf and eps_y > 0.0 and eps_y < math.inf):
        return math.nan
    if v1_star <= 1.0:
        return 1.0
    if v1_star <= 60.0:
        return 1.0 - 0.1 * math.log(v1_star) * ((v1_star - 1.0) / 59.0) ** 0.156
    return (1.0 - 0.1 * math.log(60.0)
            - 0.11 * math.log(v1_star / 60.0) * (v1_star - 60.0) ** (2.36 * eps_y))


#: Another name of :func:`jgm_fit_jcg_kernel` (the same object).
jgm_fit_jcg_scalar = jgm_fit_jcg_kernel


@jit
def jgm_fit_jcg_array(v1_star, eps_y, out):
    """JGM eqs (42)-(44) over arrays in Numba: ``out[i] = e(v1_star[i], eps_y[i])``.

    Parameters
    ----------
    v1_star : ndarray
        1-D float64 V1 / V_c (dimensionless).
    eps_y : ndarray
        1-D float64 Sy / E' (dimensionless), the length of ``v1_star`` or length 1 (one material).
    out : ndarray
        1-D float64 output e (dimensionless), the length of ``v1_star``; written in place.

    Returns
    -------
    ndarray
        ``out``.

    Raises
    ------
    ValueError
        ``out`` or ``eps_y`` of the wrong length.

    Notes
    -----
    :func:`jgm_fit_jcg_kernel` per point: invalid points give NaN (no exception, no warning). The
    "closed-form fit" speed reference of the benchmarks; the validated NumPy path is
    :func:`jgm_fit_jcg`.

    Examples
    --------
    >>> import numpy as np
    >>> from fastrest.models import jgm_fit_jcg_array
    >>> jgm_fit_jcg_array(np.array([0.5, 60.0]), np.array([0.005]), np.empty(2)).round(6).tolist()
    [1.0, 0.590566]
    """
    n = v1_star.shape[0]
    if out.shape[0] != n:
        raise ValueError("out must have the length of v1_star")
    ne = eps_y.shape[0]
    if ne == 1:
        eps = eps_y[0]
        for i in range(n):
            out[i] = jgm_fit_jcg_kernel(v1_star[i], eps)
    elif ne == n:
        for i in range(n):
            out[i] = jgm_fit_jcg_kernel(v1_star[i], eps_y[i])
    else:
        raise ValueError("eps_y must have length 1 or the length of v1_star")
    return out


@jit
@doc(MODEL_DOC)
def jgm_fit_etsion_kernel(v1_star, eps_y):
    """JGM eq (45) at one point, in Numba code: the kernel of :func:`jgm_fit_etsion`.

    e = 1 - 0.0361 eps_y^(-0.114) ln(V1*) (V1* - 1)^(9.5 eps_y) for V1* > 1, 1 below (eq 45).

    {params_kernel}

    {returns_kernel}

    Examples
    --------
    >>> from fastrest.models import jgm_fit_etsion_kernel
    >>> [round(jgm_fit_etsion_kernel(v, 0.005), 6) for v in (0.5, 20.0)]
    [1.0, 0.772454]
    """
    if not (v1_star >= 0.0 and v1_star < math.inf and eps_y > 0.0 and eps_y < math.inf):
        return math.nan
    if v1_star <= 1.0:
        return 1.0
    return 1.0 - 0.0361 * eps_y**-0.114 * math.log(v1_star) * (v1_star - 1.0) ** (9.5 * eps_y)
