"""Etsion, Kligerman & Kadin unloading, JGM eqs (33)-(34), normalised:

    w_m* - w_res* = P_m* / sqrt(A_m*)

with A_m* the loading law's contact area at maximum load (eq 8 for Jackson-Green; A* = w under
Hertz loading, so e = 1 exactly while w_m* <= 1.9). No end of its own: defined wherever the
loading law is.
"""
import math

from .._jit import jit
from ..loading import a_star_unchecked
from . import elastic

#: The unit's interface, read by the registry (fastrest/unloading/__init__.py).
__all__ = ["NAME", "SHORT", "LABEL", "EQUATION", "REFERENCE", "OMEGA_END", "CELLS_END", "FITS_HARDENING",
           "residual",
           "restitution"]

NAME = "etsion"
SHORT = "Etsion"
LABEL = "Etsion et al., JGM eqs (33)-(34)"
EQUATION = "eqs 33-34"
REFERENCE = ("Etsion I., Kligerman Y., Kadin Y. (2005) Unloading of an elastic-plastic loaded spherical "
             "contact, Int. J. Solids Struct. 42:3716-3729 (as JGM 2010 eqs 33-34)")
OMEGA_END = math.inf
CELLS_END = math.inf  # curves may tabulate up to the loading law's end
#: Meant for strain-hardening materials (Brake 2015 is); False: fitted to elastic-perfectly plastic FE.
FITS_HARDENING = False


@jit(inline=True)
def residual(wm, wm1, p, eps_y, nu, law, et_ratio):
    """(w_res*, w_m* - w_res*) after loading to w_m* (p = P_m*)."""
    return elastic.area_residual(wm, p, a_star_unchecked(law, wm, eps_y, nu, et_ratio))


@jit(inline=True)
def restitution(f, wm, wm1, p, eps_y, nu, law, et_ratio):
    """(e^2, 1 - e^2, w_res*, delta, R_res/R) for loading energy f = F(w_m*) = V1*^2 (f > 1)."""
    return elastic.area_restitution(f, wm, p, a_star_unchecked(law, wm, eps_y, nu, et_ratio))
