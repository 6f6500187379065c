"""Jackson-Chusoipin-Green unloading: the fit of JGM eq (35).

    w_res*/w_m* = 1.02 (1 - ((w_m* + 5.9)/6.9)^-0.54),   0 for w_m* <= 1

computed as -1.02 expm1(-0.54 log1p((w_m* - 1)/6.9)) from w_m* - 1, so that 1 - e^2 keeps its
relative accuracy as V1* -> 1. The ratio reaches 1 at w_m* = :data:`OMEGA_END` (10017.5): past it
w_res > w_m and e is undefined (only reachable extrapolating far past w_m* = 425). Towards that end
e^2 is proportional to 1 - w_res*/w_m*, which is formed there from the distance to the end,

    1 - w_res*/w_m* = 0.02 expm1(-0.54 log1p((w_m* - OMEGA_END)/(OMEGA_END + 5.9)))

(the same fit: 1.02 x^-0.54 - 0.02 with x = (w_m* + 5.9)/6.9 and x_end^-0.54 = 1/51), so that e keeps
its relative accuracy up to the end. With Hertz loading (w_m* <= 1.9), P_m* w_m* = w_m*^2.5 = V1*^2
exactly, so 1 - e^2 = w_res*/w_m*.
"""
import math

from .._jit import jit, mul_rn
from ..loading.jackson_green import W_SWITCH
from . import elastic

#: The unit's interface, read by the registry (fastrest/unloading/__init__.py).
__all__ = ["NAME", "SHORT", "LABEL", "EQUATION", "REFERENCE", "OMEGA_END", "CELLS_END", "FITS_HARDENING",
           "residual",
           "restitution", "residual_ratio", "residual_ratios"]

NAME = "jcg"
SHORT = "JCG"
LABEL = "Jackson-Chusoipin-Green fit, JGM eq (35)"
EQUATION = "eq 35"
REFERENCE = ("Jackson R.L., Chusoipin I., Green I. (2005) A finite element study of the residual stress "
             "and deformation in hemispherical contacts, J. Tribol. 127:484-493 (as JGM 2010 eq 35)")
#: w_m* at which eq (35) gives w_res = w_m: 6.9 x 51^(1/0.54) - 5.9, correctly rounded (checked with
#: mpmath in tests/test_unloading.py; evaluating the formula in doubles lands 25 ulp off, which near
#: the end is a relative error of 1e-15/d in e at a distance d from it).
OMEGA_END = 10017.523577897808
#: From this w_m* on, 1 - w_res*/w_m* is formed from w_m* - OMEGA_END (fewer rounding errors than
#: 1 - w_res*/w_m*: ~20 ulp either way at 600, measured against mpmath; 6 vs 140 ulp at 3000-6000).
GAP_FROM_END = 600.0
#: Largest w_m* a curve tabulates (extrapolating): towards OMEGA_END e falls to 0 like a square root,
#: which piecewise polynomials in V1* cannot follow; up to 0.6 OMEGA_END they keep ~1e-13
#: (measured, tests/test_accuracy_bounds.py). The direct solver goes on to OMEGA_END.
CELLS_END = 0.6 * OMEGA_END
#: Meant for strain-hardening materials (Brake 2015 is); False: fitted to elastic-perfectly plastic FE.
FITS_HARDENING = False


@jit(inline=True)
def residual_ratio(wm1):
    """w_res*/w_m* of eq (35) from wm1 = w_m* - 1 (0 for w_m* <= 1), without cancellation near 1."""
    if wm1 <= 0.0:
        return 0.0
    return mul_rn(-1.02, math.expm1(-0.54 * math.log1p(wm1 / 6.9)))  # 1.0 - r: not fused on CUDA either


@jit(inline=True)
def residual_ratios(wm, wm1):
    """(r, 1 - r), r = w_res*/w_m* of eq (35), each without cancellation (wm1 = w_m* - 1).

    r from w_m* - 1 (accurate as w_m* -> 1); from :data:`GAP_FROM_END` on, 1 - r from the distance
    to :data:`OMEGA_END` (accurate as w_m* -> OMEGA_END, where e^2 ~ 1 - r -> 0; negative past it).
    """
    if wm <= GAP_FROM_END:
        r = residual_ratio(wm1)
        return r, 1.0 - r
    # mul_rn: 1.0 - gap is not fused into a multiply-add on CUDA either (fastrest._jit)
    gap = mul_rn(0.02, math.expm1(-0.54 * math.log1p((wm - OMEGA_END) / (OMEGA_END + 5.9))))
    return 1.0 - gap, gap


@jit(inline=True)
def residual(wm, wm1, p, eps_y, nu, law, et_ratio):
    """(w_res*, w_m* - w_res*) after loading to w_m* (wm1 = w_m* - 1, p = P_m*)."""
    r, gap = residual_ratios(wm, wm1)
    return r * wm, gap * wm


@jit(inline=True)
def restitution(f, wm, wm1, p, eps_y, nu, law, et_ratio):
    """(e^2, 1 - e^2, w_res*, delta, R_res/R) for loading energy f = F(w_m*) = V1*^2 (f > 1)."""
    r, gap = residual_ratios(wm, wm1)
    w_res = r * wm
    delta = gap * wm
    if delta <= 0.0:
        # the end of eq (35) (callers stop there): no rebound, flat residual shape
        return 0.0, 1.0, wm, 0.0, math.inf
    if wm <= W_SWITCH:
        loss = r
        e2 = gap
    else:
        q = p * wm / f
        loss = (1.0 - q) + mul_rn(q, r)
        e2 = q * gap
    return e2, loss, w_res, delta, elastic.residual_radius_ratio(p, delta)
