"""Normalised loading energy of the JG contact law and its inverse, the maximum interference.

JGM 2010 eqs (17)-(31). With W(w) = (5/2) int_1^w P*(z) dz, eq (25) gives (W_ep)* = -W(w) and the
energy balance (29), divided by U_c (eq 24), reads

    V1*^2 = F(w_m),   F(w) = w^2.5                                   for w <= 1.9 (Hertz, eq 19)
                      F(w) = 1.9^2.5 + (5/2) int_1.9^w P*_JG(z) dz     for w > 1.9

so (W_ep)* = 1 - F(w) (zero at w = 1, negative above). The integral is evaluated by composite
Gauss-Legendre quadrature in t = ln z, where the integrand z P*(z) is an entire function of t, so a
few 24-point panels give machine precision. The inverse w_m(V1*) is a safeguarded Newton iteration
on ln F(w) = 2 ln V1* in ln w, with slope d ln F / d ln w = (5/2) w P*(w) / F(w).
"""
from __future__ import annotations

from typing import Any
from numpy.typing import ArrayLike, NDArray
import math

import numpy as np

from ._jit import jit
from ._doc import doc
from .contact import LAW_DOC, evaluate_law
from .loading.jackson_green import W_SWITCH, area_exponent
from .critical import c_of_nu
from .loading import JACKSON_GREEN, p_star_above, valid as law_valid


__all__ = ["W_star", "loading_energy"]

#: Gauss-Legendre order per panel and the widest panel in ln w; chosen by measurement against
#: mpmath (tests/test_direct.py): 24 points on panels <= 0.75 wide reach ~1e-16 relative.
GL_ORDER = 24
PANEL_WIDTH = 0.75
_GL_X, _GL_W = np.polynomial.legendre.leggauss(GL_ORDER)
#: F(1.9) = 1.9^2.5: the loading energy (over U_c) at the Hertz/JG switch.
F_SWITCH = W_SWITCH**2.5  # F(1.9)
#: V1* = 1.9^1.25 at which w_m* = 1.9, where e(V1*) jumps (docs/model.md section 3).
V_SWITCH = W_SWITCH**1.25  # V1* at which w_m = 1.9


@jit
def law_integral(w0, w1, eps_y, nu, C, B, law, et_ratio):
    """int_{w0}^{w1} P*(z) dz of loading law ``law`` for 1.9 <= w0 <= w1, by Gauss-Legendre in ln z."""
    t0 = math.log(w0)
    t1 = math.log(w1)
    n = int(math.ceil((t1 - t0) / PANEL_WIDTH))
    if n < 1:
        n = 1
    h = (t1 - t0) / n
    total = 0.0
    for k in range(n):
        mid = t0 + (k + 0.5) * h
        s = 0.0
        for j in range(GL_ORDER):
            z = math.exp(mid + 0.5 * h * _GL_X[j])
            s += _GL_W[j] * z * p_star_above(law, z, eps_y, nu, C, B, et_ratio)
        total += 0.5 * h * s
    return total


@jit
def jg_integral(w0, w1, eps_y, nu, C, B):
    """int_{w0}^{w1} P*_JG(z) dz for 1.9 <= w0 <= w1: :func:`law_integral` of the JG law."""
    return law_integral(w0, w1, eps_y, nu, C, B, JACKSON_GREEN, 0.0)


@jit
def f_star_kernel(w, eps_y, nu, law, et_ratio):
    """F(w) = V1*^2 that reaches maximum interference w (loading energy / U_c) under loading law
    ``law``; NaN for w < 0 or an invalid law/et_ratio (the law's end is not checked)."""
    if not (w >= 0.0 and law_valid(law, et_ratio)):
        return np.nan
    if w <= W_SWITCH:
        return w**2.5
    return F_SWITCH + 2.5 * law_integral(W_SWITCH, w, eps_y, nu, c_of_nu(nu), area_exponent(eps_y), law, et_ratio)


@jit
def newton_from_below(vv, w, f, w_hi, eps_y, nu, C, B, law, et_ratio):
    """Solve F(w_m) = vv = V1*^2 (> F(1.9)) by Newton's method on ln F in t = ln w, from (w, f = F(w)).

    Start near the root (callers start from the Hertz solution V1*^0.8, which lies below it where
    P*_JG < Hertz, i.e. for nu above about 0.32, or from the previous root when marching). Where
    ln F is concave in t (most of the range) the iterates from below rise monotonically to the
    root; elsewhere a step may overshoot, which the next steps correct (steps are clamped at w_hi
    itself, not at e^(ln w_hi), which can lie a few ulp above it). Each new F is the previous one
    plus the integral over the (short) step. Returns (w_m, w_last, f_last) where (w_last, f_last)
    is the last point evaluated, from which a caller marching through increasing speeds continues.
    w_m is NaN if it would exceed w_hi, and w_hi itself where the root lies within the iteration's
    convergence (or rounding) of it: at the limit speed sqrt(F(w_hi)), w_m = w_hi exactly.
    """
    hi = math.log(w_hi)
    t = math.log(w)
    for _ in range(60):
        # ln(F/V1*^2) and w e^dt, not ln F - 2 ln V1* and e^(t + dt): those carry the rounding of
        # ln w and ln V1* (~ulp(10) at w ~ 1e4), ~10 ulp of w_m*, which matters where e depends
        # steeply on w_m* (the end of JCG's eq 35)
        g = math.log(f / vv)
        dt = -g * f / (2.5 * w * p_star_above(law, w, eps_y, nu, C, B, et_ratio))
        t_new = t + dt
        if t_new > hi:
            if w == w_hi:
                # F(w_hi) < V1*^2: beyond the allowed range, unless by rounding only (V1* given as
                # the limit itself, whose F was summed along another path)
                return (w if g > -1e-14 else np.nan), w, f
            t_new = hi
            w_new = w_hi
        else:
            w_new = min(w * math.exp(dt), w_hi)
        if abs(dt) < 1e-9:
            return w_new, w, f  # quadratic convergence: the error of w_new is ~dt^2
        f += 2.5 * law_integral(w, w_new, eps_y, nu, C, B, law, et_ratio)
        t, w = t_new, w_new
    return np.nan, w, f


@jit
def omega_m_kernel(v, eps_y, nu, w_hi, law, et_ratio):
    """w_m(V1*) solving F(w_m) = V1*^2 (eq 29) under loading law ``law``; NaN if V1* < 0, w_m would
    exceed w_hi, or the law/et_ratio is invalid.

    Closed form w_m = V1*^0.8 for V1* <= 1.9^1.25; above, :func:`newton_from_below` started at
    the Hertz solution V1*^0.8 (a lower bound where P*_JG < Hertz).
    """
    if not (v >= 0.0 and law_valid(law, et_ratio)):
        return np.nan
    if v <= V_SWITCH:
        w = min(v**0.8, W_SWITCH)  # v = 1.9^1.25 exactly would round to 1.9 + 1 ulp
        return w if w <= w_hi else np.nan
    if not w_hi > W_SWITCH:
        return np.nan
    C = c_of_nu(nu)
    B = area_exponent(eps_y)
    hi = math.log(w_hi)
    t = max(math.log(W_SWITCH), 0.8 * math.log(v))
    if t > hi:
        return np.nan
    w = min(math.exp(t), w_hi)
    f = F_SWITCH + 2.5 * law_integral(W_SWITCH, w, eps_y, nu, C, B, law, et_ratio)
    return newton_from_below(v * v, w, f, w_hi, eps_y, nu, C, B, law, et_ratio)[0]


@jit
def omega_m_sorted_kernel(v, eps_y, nu, w_hi, law, et_ratio, out):
    """w_m at increasing speeds v[0] <= v[1] <= ... (all > 1.9^1.25), marching one solution into the next.

    Much cheaper per point than :func:`omega_m_kernel` when the speeds are dense (table building).
    """
    C = c_of_nu(nu)
    B = area_exponent(eps_y)
    w = W_SWITCH
    f = F_SWITCH
    for i in range(v.size):
        if not v[i] > V_SWITCH:
            out[i] = np.nan
            continue
        out[i], w, f = newton_from_below(v[i] * v[i], w, f, w_hi, eps_y, nu, C, B, law, et_ratio)


@jit
def _f_star_array(w, eps_y, nu, et_ratio, law, out):
    for i in range(w.size):
        out[i] = f_star_kernel(w[i], eps_y[i], nu[i], law, et_ratio[i])


@doc(LAW_DOC)
def loading_energy(w: ArrayLike, eps_y: ArrayLike, nu: ArrayLike, *, et_ratio: ArrayLike = 0.0,
                   loading: str | None = None) -> float | NDArray[np.float64]:
    """Loading energy F(w) = 1 - (W_ep)*(w) to maximum interference w, over U_c (-).

    Equal to V1*^2 of the impact whose maximum interference is w (the energy balance, JGM eq 29).

    {law_params}

    Returns
    -------
    float or ndarray
        F (-), broadcast over the inputs (a float if all are scalars); w^2.5 for w <= 1.9.

    {law_raises}

    Notes
    -----
    JGM eqs (19), (25), (29) divided by U_c (eq 24): F = w^2.5 for w <= 1.9 (Hertz), and
    F = 1.9^2.5 + (5/2) int_1.9^w P*_JG(z) dz above, by Gauss-Legendre quadrature in ln z
    (~1e-16 relative against mpmath; docs/model.md sections 3 and 7). No ValidityWarning.

    Examples
    --------
    JGM check value (docs/model.md section 3): V1* = 10 reaches w_m* = 6.549856322605.

    >>> import fastrest
    >>> round(fastrest.loading_energy(6.549856322605, 0.005, 0.33), 9)
    100.0
    >>> fastrest.loading_energy(1.0, 0.005, 0.33)
    1.0
    """
    return evaluate_law(_f_star_array, w, eps_y, nu, et_ratio, loading)


@doc(LAW_DOC)
def W_star(w: ArrayLike, eps_y: ArrayLike, nu: ArrayLike, *, et_ratio: ArrayLike = 0.0,
           loading: str | None = None) -> float | NDArray[np.float64]:
    """Normalised elasto-plastic energy (W_ep)* of JGM eq (25): -(5/2) int_1^w P* dz (-).

    Zero at w = 1, negative above; for 0 <= w < 1 the same integral over the Hertz law, 1 - w^2.5.
    Equal to 1 - F(w) (see :func:`loading_energy`).

    {law_params}

    Returns
    -------
    float or ndarray
        (W_ep)* (-), broadcast over the inputs (a float if all are scalars).

    {law_raises}

    Notes
    -----
    JGM eqs (22), (25), normalised by U_c (eq 24); computed as 1 - :func:`loading_energy`. Plotted
    (as -(W_ep)*) in JGM Fig. 2. No ValidityWarning.

    Examples
    --------
    >>> import fastrest
    >>> round(fastrest.W_star(10.0, 0.005, 0.33), 6)
    -271.276805
    >>> fastrest.W_star(1.0, 0.005, 0.33), round(fastrest.W_star(0.5, 0.005, 0.33), 6)
    (0.0, 0.823223)
    """
    f = loading_energy(w, eps_y, nu, et_ratio=et_ratio, loading=loading)
    return 1.0 - f
