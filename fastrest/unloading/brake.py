"""Brake's elastic unloading, as implemented by tmdsimpy (normalised):

    w_m* - w_res* = P_m* / sqrt(w_m*),      R_res/R = w_m*^1.5 / P_m*

i.e. eq (32) through (w_m*, P_m*) with the unloading contact radius at maximum load equal to the
Hertz radius sqrt(R omega_m), where Etsion's eq (33) uses the Jackson-Green area A_m*. Under Hertz
loading (w_m* <= 1.9) w_res* = 0 and e = 1 exactly; no end of its own.

Source: M.R.W. Brake (2015), An analytical elastic plastic contact model with strain hardening
and frictional effects for normal and oblique impacts, Int. J. Solids Struct. 62:104-123, in the
form of tmdsimpy (tmd-lab/tmdsimpy, ``tmdsimpy/jax/nlforces/roughcontact/_asperity_functions.py``,
``_normal_asperity_unloading``: deltabar = deltam (1 - Fm / (4/3 E* sqrt(Re) deltam^1.5)),
Rebar = Fm^2 / ((4/3 E*)^2 (deltam - deltabar)^3)) and of its MATLAB parent
(tmd-lab/microslip-rough-contact, ``SPHERE_PLASTIC_PRE.m``). Neither cites an equation number and
the paper's full text was not available to us: these are the peer implementation's equations,
checked against its published test data (tests/test_contact_law.py), not re-derived from the paper.
"""
import math

from .._jit import jit
from . import elastic

#: The unit's interface, read by the registry (fastrest/unloading/__init__.py).
__all__ = ["NAME", "SHORT", "LABEL", "EQUATION", "REFERENCE", "OMEGA_END", "CELLS_END", "FITS_HARDENING",
           "residual",
           "restitution"]

NAME = "brake"
SHORT = "Brake"
LABEL = "Brake (2015) as in tmdsimpy: eq (32) with the Hertz radius at maximum load"
EQUATION = "Brake 2015, as tmdsimpy"
REFERENCE = ("Brake M.R.W. (2015) An analytical elastic plastic contact model with strain hardening and "
             "frictional effects for normal and oblique impacts, Int. J. Solids Struct. 62:104-123; "
             "equations as implemented in tmdsimpy (tmd-lab)")
OMEGA_END = math.inf
CELLS_END = math.inf  # curves may tabulate up to the loading law's end
#: Meant for strain-hardening materials (Brake 2015 is); False: fitted to elastic-perfectly plastic FE.
FITS_HARDENING = True


@jit(inline=True)
def residual(wm, wm1, p, eps_y, nu, law, et_ratio):
    """(w_res*, w_m* - w_res*) after loading to w_m* (p = P_m*)."""
    return elastic.area_residual(wm, p, wm)


@jit(inline=True)
def restitution(f, wm, wm1, p, eps_y, nu, law, et_ratio):
    """(e^2, 1 - e^2, w_res*, delta, R_res/R) for loading energy f = F(w_m*) = V1*^2 (f > 1)."""
    return elastic.area_restitution(f, wm, p, wm)
