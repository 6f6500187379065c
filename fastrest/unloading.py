"""Elastic unloading after maximum interference, and the restitution it implies.

JGM 2010 eqs (32)-(38). Unloading is Hertzian with residual interference w_res and radius R_res
fixed by (32). Eq (38) then simplifies exactly, in both unloading models, to

    (V2/V_c)^2 = P_m* (w_m - w_res*),   so   e^2 = P_m* (w_m - w_res*) / V1*^2.

Two models of w_res:
  * ``"jcg"``: Jackson, Chusoipin & Green (2005) fit, eq (35):
        w_res/w_m = 1.02 (1 - ((w_m + 5.9)/6.9)^-0.54)
  * ``"etsion"``: Etsion, Kligerman & Kadin (2005), eqs (33)-(34), normalised:
        w_m - w_res* = P_m* / sqrt(A_m*)   (e = 1 exactly while w_m <= 1.9, Hertz loading)
and R_res/R = P_m*^2 / (w_m - w_res*)^3 from (32) in both (eq 36; eq 34 is the same for Etsion).

The kernels take w_m together with w_m - 1 (computed without cancellation by the caller) so that
1 - e^2 keeps full relative accuracy as V1* -> 1, where multi-asperity codes sum many tiny losses.
"""
import math

import numba as nb
import numpy as np

from .contact import W_SWITCH, a_star_kernel, p_star_unchecked

UNLOADING_MODELS = ("jcg", "etsion")
JCG, ETSION = 0, 1
#: JCG eq (35), w_res/w_m = 1.02 (1 - (1 + (w_m - 1)/6.9)^-0.54), reaches 1 at this w_m*: past it
#: w_res > w_m and e is undefined. Only extrapolation (w_m* > 425) gets there.
JCG_OMEGA_END = 1.0 + 6.9 * ((1.0 - 1.0 / 1.02) ** (-1.0 / 0.54) - 1.0)


def unloading_code(unloading):
    """Map the public name to the kernels' integer code, with a clear error."""
    try:
        return UNLOADING_MODELS.index(unloading)
    except ValueError:
        raise ValueError(f"unloading must be one of {UNLOADING_MODELS}; got {unloading!r}") from None


@nb.njit(cache=True)
def jcg_residual_ratio(wm1):
    """w_res/w_m of JCG eq (35) given wm1 = w_m - 1 (0 for w_m <= 1), without cancellation near 1."""
    if wm1 <= 0.0:
        return 0.0
    # 1 - (1 + wm1/6.9)^-0.54 = -expm1(-0.54 log1p(wm1/6.9))
    return -1.02 * math.expm1(-0.54 * math.log1p(wm1 / 6.9))


@nb.njit(cache=True)
def restitution_kernel(v, wm, wm1, eps_y, nu, model):
    """(e, 1 - e^2, w_res*, R_res/R) at impact speed v = V1* with maximum interference wm.

    ``wm1`` is wm - 1 computed accurately by the caller. NaN in gives NaN out.
    """
    if not (wm >= 0.0 and v >= 0.0):
        return np.nan, np.nan, np.nan, np.nan
    if wm1 <= 0.0 or (model == ETSION and wm <= W_SWITCH):
        # Elastic impact (V1* <= 1), or Etsion unloading after Hertz loading: e = 1 exactly.
        return 1.0, 0.0, 0.0, 1.0
    p = p_star_unchecked(wm, eps_y, nu)  # wm is bounded by the solver
    if model == JCG:
        r = jcg_residual_ratio(wm1)
        w_res = r * wm
        if wm <= W_SWITCH:
            loss = r  # P_m* w_m = w_m^2.5 = V1*^2 exactly under Hertz loading
            e2 = 1.0 - r
        else:
            q = p * wm / (v * v)
            loss = (1.0 - q) + q * r
            e2 = q * (1.0 - r)
        elastic = wm - w_res
        if elastic <= 0.0:
            # the end of eq (35), w_m* = JCG_OMEGA_END (callers stop there): e = 0, flat residual
            # shape; a negative value here is rounding
            return 0.0, 1.0, wm, np.inf
    else:
        elastic = p / math.sqrt(a_star_kernel(wm, eps_y, nu))
        w_res = wm - elastic
        e2 = p * elastic / (v * v)
        loss = 1.0 - e2
    return math.sqrt(e2), loss, w_res, p * p / elastic**3
