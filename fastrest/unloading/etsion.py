"""Etsion, Kligerman & Kadin unloading, JGM eqs (33)-(34), normalised:

    w_m* - w_res* = P_m* / sqrt(A_m*)

with A_m* the Jackson-Green contact area at maximum load (eq 8; A* = w under Hertz loading, so
e = 1 exactly while w_m* <= 1.9). No end of its own: defined wherever the loading law is.
"""
import math

from .._jit import jit
from ..contact import W_SWITCH, a_star_kernel
from . import elastic

NAME = "etsion"
SHORT = "Etsion"
LABEL = "Etsion et al., JGM eqs (33)-(34)"
EQUATION = "eqs 33-34"
REFERENCE = ("Etsion I., Kligerman Y., Kadin Y. (2005) Unloading of an elastic-plastic loaded spherical "
             "contact, Int. J. Solids Struct. 42:3716-3729 (as JGM 2010 eqs 33-34)")
OMEGA_END = math.inf
CELLS_END = math.inf  # curves may tabulate up to the loading law's end


@jit(inline=True)
def residual(wm, wm1, p, eps_y, nu):
    """(w_res*, w_m* - w_res*) after loading to w_m* (p = P_m*)."""
    if wm <= W_SWITCH:
        return 0.0, wm  # Hertz loading: elastic unloading along the same curve
    delta = p / math.sqrt(a_star_kernel(wm, eps_y, nu))
    return wm - delta, delta


@jit(inline=True)
def restitution(f, wm, wm1, p, eps_y, nu):
    """(e^2, 1 - e^2, w_res*, delta, R_res/R) for loading energy f = F(w_m*) = V1*^2 (f > 1)."""
    if wm <= W_SWITCH:
        return 1.0, 0.0, 0.0, wm, 1.0  # Hertz loading and unloading: e = 1 exactly
    w_res, delta = residual(wm, wm1, p, eps_y, nu)
    return elastic.restitution(f, p, w_res, delta)
