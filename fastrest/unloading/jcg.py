"""Jackson-Chusoipin-Green unloading: the fit of JGM eq (35).

    w_res*/w_m* = 1.02 (1 - ((w_m* + 5.9)/6.9)^-0.54),   0 for w_m* <= 1

computed as -1.02 expm1(-0.54 log1p((w_m* - 1)/6.9)) from w_m* - 1, so that 1 - e^2 keeps its
relative accuracy as V1* -> 1. The ratio reaches 1 at w_m* = :data:`OMEGA_END` (10017.5): past it
w_res > w_m and e is undefined (only reachable extrapolating far past w_m* = 425). With Hertz
loading (w_m* <= 1.9), P_m* w_m* = w_m*^2.5 = V1*^2 exactly, so 1 - e^2 = w_res*/w_m*.
"""
import math

from .._jit import jit
from ..contact import W_SWITCH
from . import elastic

#: The unit's interface, read by the registry (fastrest/unloading/__init__.py).
__all__ = ["NAME", "SHORT", "LABEL", "EQUATION", "REFERENCE", "OMEGA_END", "CELLS_END", "residual",
           "restitution", "residual_ratio"]

NAME = "jcg"
SHORT = "JCG"
LABEL = "Jackson-Chusoipin-Green fit, JGM eq (35)"
EQUATION = "eq 35"
REFERENCE = ("Jackson R.L., Chusoipin I., Green I. (2005) A finite element study of the residual stress "
             "and deformation in hemispherical contacts, J. Tribol. 127:484-493 (as JGM 2010 eq 35)")
#: w_m* at which eq (35) gives w_res = w_m.
OMEGA_END = 1.0 + 6.9 * ((1.0 - 1.0 / 1.02) ** (-1.0 / 0.54) - 1.0)
#: Largest w_m* a curve tabulates (extrapolating): towards OMEGA_END e falls to 0 like a square root,
#: which piecewise polynomials in V1* cannot follow; up to 0.6 OMEGA_END they keep ~1e-13
#: (measured, tests/test_accuracy_bounds.py). The direct solver goes on to OMEGA_END.
CELLS_END = 0.6 * OMEGA_END


@jit(inline=True)
def residual_ratio(wm1):
    """w_res*/w_m* of eq (35) from wm1 = w_m* - 1 (0 for w_m* <= 1), without cancellation near 1."""
    if wm1 <= 0.0:
        return 0.0
    return -1.02 * math.expm1(-0.54 * math.log1p(wm1 / 6.9))


@jit(inline=True)
def residual(wm, wm1, p, eps_y, nu):
    """(w_res*, w_m* - w_res*) after loading to w_m* (wm1 = w_m* - 1, p = P_m*)."""
    w_res = residual_ratio(wm1) * wm
    return w_res, wm - w_res


@jit(inline=True)
def restitution(f, wm, wm1, p, eps_y, nu):
    """(e^2, 1 - e^2, w_res*, delta, R_res/R) for loading energy f = F(w_m*) = V1*^2 (f > 1)."""
    r = residual_ratio(wm1)
    w_res = r * wm
    delta = wm - w_res
    if delta <= 0.0:
        # the end of eq (35) (callers stop there): no rebound, flat residual shape
        return 0.0, 1.0, wm, 0.0, math.inf
    if wm <= W_SWITCH:
        loss = r
        e2 = 1.0 - r
    else:
        q = p * wm / f
        loss = (1.0 - q) + q * r
        e2 = q * (1.0 - r)
    return e2, loss, w_res, delta, elastic.residual_radius_ratio(p, delta)
