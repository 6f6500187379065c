"""Jackson & Green (2005) elastic-perfectly plastic loading, JGM 2010 eqs (8)-(15): the default unit.

Normalised by the critical values of eqs (4)-(7): w = omega/omega_c, P* = P/P_c, A* = A/A_c.
For w <= 1.9 the Hertz solution (eqs 14-15); above, JG's fit:

    A* = w (w/1.9)^B,  B = 0.14 exp(23 eps_y)                          (8), (10)
    a/R = (pi C eps_y / 2) sqrt(A*)                                     (from a = sqrt(A/pi), eq 4)
    H_G/Sy = 2.84 - 0.92 (1 - cos(pi a/R)),  valid for 0 < a/R < 1     (12)
    P* = exp(-w^(5/12)/4) w^1.5 + 4 (H_G/Sy)/C (1 - exp(-w^(5/9)/25)) w (9)

P* depends on nu only through C(nu) = 1.295 exp(0.736 nu) (5). P* jumps by about -0.16 % at
w = 1.9; integrals are split there. Past a/R = 1 the law is undefined: kernels return NaN. The
law has no material parameter of its own: ``et_ratio`` must be 0 (hardening: :mod:`.ghaednia`).
The validating Python functions are :func:`fastrest.P_star` and :func:`fastrest.A_star`.
"""

import math

import numpy as np

from .._jit import jit, mul_rn
from .._validation import OMEGA_STAR_SWITCH
from ..critical import c_of_nu

W_SWITCH = OMEGA_STAR_SWITCH
LN_SWITCH = math.log(W_SWITCH)


@jit
def area_exponent(eps_y):
    """B = 0.14 exp(23 eps_y), JGM eq (10)."""
    return mul_rn(0.14, math.exp(23.0 * eps_y))  # 1.0 + B: not fused on CUDA either (fastrest._jit)


@jit
def a_star_kernel(w, eps_y, nu):
    """A*(w): Hertz A* = w for w <= 1.9, JG eq (8) above."""
    if w <= W_SWITCH:
        return w
    return a_star_above(w, eps_y, nu, 0.0, area_exponent(eps_y), 0.0)


@jit
def radius_ratio_kernel(w, eps_y, nu):
    """Contact radius over sphere radius, a/R = (pi C eps_y/2) sqrt(A*)."""
    return 0.5 * math.pi * c_of_nu(nu) * eps_y * math.sqrt(a_star_kernel(w, eps_y, nu))


@jit
def p_star_jg(w, eps_y, nu, C, B):
    """JG branch of P*(w) (eq 9) with C and B precomputed, for w >= 1.9.

    Not checked against a/R < 1: callers bound w (the solvers by the a/R = 1 point, see
    :func:`omega_star_limit_kernel`); the table generator evaluates the formula a little past it
    on purpose, as a smooth extension that keeps interpolation stencils of valid materials whole.
    """
    lw = math.log(w)  # one logarithm serves the four powers of w (~1.5x faster than **)
    a_star = w * math.exp(B * (lw - LN_SWITCH))
    a_over_r = 0.5 * math.pi * C * eps_y * math.sqrt(a_star)
    # mul_rn: the products feeding the sums are rounded on their own on CUDA too (fastrest._jit)
    hg = 2.84 - mul_rn(0.92, 1.0 - math.cos(math.pi * a_over_r))
    return (mul_rn(math.exp(-0.25 * math.exp(lw * (5.0 / 12.0))) * w, math.sqrt(w))
            + mul_rn(4.0 * hg / C * (-math.expm1(-math.exp(lw * (5.0 / 9.0)) / 25.0)), w))


@jit
def p_star_kernel(w, eps_y, nu):
    """P*(w): Hertz w^1.5 for w <= 1.9 (eq 14), JG eq (9) above; NaN past a/R = 1 or for w < 0."""
    if not w >= 0.0:
        return np.nan
    if w <= W_SWITCH:
        return w**1.5
    if not radius_ratio_kernel(w, eps_y, nu) < 1.0:
        return np.nan
    return p_star_jg(w, eps_y, nu, c_of_nu(nu), area_exponent(eps_y))


@jit
def omega_star_limit_kernel(eps_y, nu):
    """The w* at which a/R reaches 1 (the JG law's end, eq 12); inf-free for eps_y > 0."""
    C = c_of_nu(nu)
    a_lim = (2.0 / (math.pi * C * eps_y)) ** 2  # A* at a/R = 1
    if a_lim <= W_SWITCH:
        return a_lim  # Hertz branch: A* = w
    B = area_exponent(eps_y)
    # w^(1+B) / 1.9^B = a_lim
    return math.exp((math.log(a_lim) + mul_rn(B, math.log(W_SWITCH))) / (1.0 + B))



#: The unit's interface, read by the registry (fastrest/loading/__init__.py).
__all__ = ["NAME", "SHORT", "LABEL", "REFERENCE", "W_SWITCH", "HARDENING", "valid", "p_star_above",
           "a_star_above", "omega_end"]

NAME = "jackson-green"
SHORT = "JG"
LABEL = "Jackson & Green (2005), elastic-perfectly plastic (JGM eqs 8-15)"
REFERENCE = ("Jackson R.L., Green I. (2005) A finite element study of elasto-plastic hemispherical "
             "contact against a rigid flat, J. Tribol. 127:343-354 (as JGM 2010 eqs 8-15)")
#: Whether the law takes the tangent modulus ratio Et/E (``et_ratio``); False: it must be 0.
HARDENING = False


@jit(inline=True)
def valid(et_ratio):
    """True if ``et_ratio`` is allowed: only 0 (this law has no hardening)."""
    return et_ratio == 0.0


@jit(inline=True)
def p_star_above(w, eps_y, nu, C, B, et_ratio):
    """P*(w) for w >= 1.9 (eq 9) with C = C(nu) and B of eq (10) precomputed; a/R not checked."""
    return p_star_jg(w, eps_y, nu, C, B)


@jit(inline=True)
def a_star_above(w, eps_y, nu, C, B, et_ratio):
    """A*(w) = w (w/1.9)^B for w >= 1.9 (eq 8); the one place of the formula."""
    return mul_rn(w, (w / W_SWITCH) ** B)  # mul_rn: the hardening law adds to it (fastrest._jit)


@jit(inline=True)
def omega_end(eps_y, nu, et_ratio):
    """w* where the law ends: a/R = 1 (eq 12), :func:`fastrest.contact.omega_star_limit_kernel`."""
    if not valid(et_ratio):
        return np.nan
    return omega_star_limit_kernel(eps_y, nu)


