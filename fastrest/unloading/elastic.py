"""Elastic (Hertzian) unloading through the maximum point, JGM eq (32): shared by every unloading model.

After loading to (w_m*, P_m*) the contact unloads as a Hertz contact of a sphere of radius R_res
whose surface stands w_res* deep in the flat:

    P*(w) = P_m* ((w - w_res*) / (w_m* - w_res*))^1.5      for w_res* < w <= w_m*, 0 below,
    R_res/R = P_m*^2 / (w_m* - w_res*)^3                                         (eqs 32, 36)

so the energy the unloading returns, over U_c = (2/5) P_c omega_c (eq 24), is

    (5/2) int_{w_res}^{w} P* dz = P_m* delta (x^2.5),   x = (w - w_res*)/delta,  delta = w_m* - w_res*

and the whole unloading returns P_m* delta (eq 38 normalised). A model is the rule that gives
w_res* (and so delta) from the maximum point; these functions take delta from it.
"""
import math

from .._jit import jit
from ..contact import W_SWITCH

__all__ = ["force", "returned_energy", "residual_radius_ratio", "restitution", "area_residual",
           "area_restitution"]


@jit(inline=True)
def force(w, w_max, p_max, w_res, delta):
    """P*(w) on the unloading/reloading branch through (w_max, p_max) with residual w_res, eq (32).

    ``delta`` = w_max - w_res (> 0), as the model computed it (more accurate than the difference
    near w_res). 0 at or below w_res; p_max at w_max exactly.
    """
    x = w - w_res
    if x <= 0.0:
        return 0.0
    if w >= w_max:
        return p_max
    # (w - w_res)/delta with the gap to w_max taken exactly: x = delta - (w_max - w)
    s = (delta - (w_max - w)) / delta
    return p_max * s * math.sqrt(s)


@jit(inline=True)
def returned_energy(w, w_max, p_max, w_res, delta):
    """Energy the branch stores between w_res and w, over U_c: P_m* delta x^2.5 (0 below w_res)."""
    x = w - w_res
    if x <= 0.0:
        return 0.0
    s = min((delta - (w_max - w)) / delta, 1.0) if w < w_max else 1.0
    return p_max * delta * s * s * math.sqrt(s)


@jit(inline=True)
def residual_radius_ratio(p_max, delta):
    """R_res/R = P_m*^2 / delta^3, JGM eq (36) (inf where delta = 0: a flat residual shape)."""
    if delta <= 0.0:
        return math.inf
    return p_max * p_max / delta**3


@jit(inline=True)
def restitution(f, p_max, w_res, delta):
    """(e^2, 1 - e^2, w_res*, delta, R_res/R) of an impact with loading energy f = V1*^2 (eq 38):
    e^2 = P_m* delta / V1*^2 (the plain form; a model with a better-conditioned 1 - e^2 computes
    its own)."""
    e2 = p_max * delta / f
    return e2, 1.0 - e2, w_res, delta, residual_radius_ratio(p_max, delta)


@jit(inline=True)
def area_residual(wm, p_max, area):
    """(w_res*, delta) when the elastic recovery is set by the contact area A* at maximum load,
    delta = P_m* / sqrt(A_m*) (Etsion's eq 33 with the JG area; Brake's rule with A* = w_m*).
    Under Hertz loading (w_m* <= 1.9) unloading retraces loading: w_res* = 0, delta = w_m*."""
    if wm <= W_SWITCH:
        return 0.0, wm
    delta = p_max / math.sqrt(area)
    return wm - delta, delta


@jit(inline=True)
def area_restitution(f, wm, p_max, area):
    """:func:`restitution` for an :func:`area_residual` model; e = 1 exactly under Hertz loading."""
    if wm <= W_SWITCH:
        return 1.0, 0.0, 0.0, wm, 1.0
    w_res, delta = area_residual(wm, p_max, area)
    return restitution(f, p_max, w_res, delta)
