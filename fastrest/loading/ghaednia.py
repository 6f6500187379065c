"""Ghaednia, Brake, Berryhill & Jackson (2019): Jackson-Green loading with strain hardening.

Sphere on a rigid flat, normalised by the critical values of JGM eqs (4)-(7) (w = delta/delta_c,
P* = F/F_c, A* = A/A_c = (a/a_c)^2), with h = Et/E (``et_ratio``), the tangent modulus over Young's
modulus. Hertz for w <= 1.9; above, with k = pi C eps_y / 2 (so delta_c/R = k^2, a_e/R = k sqrt(w)):

    a_p/R  = k sqrt(w (w/1.9)^B),  B = 0.14 exp(23 eps_y)            (JG's area, eq 8)
    Upsilon = -2 sqrt(E/Sy) h^(1 - (w - 1) k^2) / [(4 - 3 exp(-2 sqrt(E/Sy) h)) (1 - h)]
    a = a_p + (a_e - a_p) t,  t = 1 - exp(Upsilon)                      (eq 25)
    H/Sy = 2.84 - 0.92 (1 - cos(pi a/R))                                (JG's eq 12 at a)
    P*_p = exp(-w^(5/12)/4) w^1.5 + 4 (H/Sy)/C (1 - exp(-w^(5/9)/25)) w (JG's eq 9 with that H)
    P*   = P*_p + (w^1.5 - P*_p) s,  s = 1 - exp(-3.3 h)

with E/Sy = (1 - nu^2)/eps_y (eps_y = Sy/E', E' = E/(1 - nu^2) of the sphere on a rigid flat; for
two bodies, of JGM's equivalent sphere). Written as a_p + (a_e - a_p) t and P*_p + (...) s with
t = -expm1(Upsilon), s = -expm1(-3.3 h): at h = 0 both corrections are exactly 0 and every number
is Jackson-Green's bit for bit. The form is the one both peer implementations use (tmdsimpy's
``_normal_pl_asperity_loading``, tmd-lab/microslip-rough-contact's ``GHAEDNIA_ET_AL_FLATTENING.m``);
tmdsimpy notes that the printed eq 26 is doubtful ("not sure about the square root in the
denominator"): docs/model.md section 12 records the sources and what we could not check.

End: a <= a_p (a lies between a_e and a_p), so the hardness fit stays inside 0 < a/R < 1 wherever
JG's does; the law is taken to end where JG's does (a_p/R = 1), a conservative choice.
Domain: 0 <= h < 1 (h -> 1: Upsilon -> -inf, a -> a_e, P* -> P*_p + 0.963 (w^1.5 - P*_p)).
"""
import math

import numpy as np

from .._jit import jit, mul_rn
from . import jackson_green
from .jackson_green import LN_SWITCH, omega_star_limit_kernel

#: The unit's interface, read by the registry (fastrest/loading/__init__.py).
__all__ = ["NAME", "SHORT", "LABEL", "REFERENCE", "W_SWITCH", "HARDENING", "valid", "p_star_above",
           "a_star_above", "omega_end"]

NAME = "ghaednia"
SHORT = "Ghaednia"
LABEL = "Ghaednia, Brake, Berryhill & Jackson (2019), JG with strain hardening (tangent modulus Et)"
REFERENCE = ("Ghaednia H., Brake M.R.W., Berryhill M., Jackson R.L. (2019) Strain hardening from "
             "elastic-perfectly plastic to perfectly elastic flattening single asperity contact, "
             "J. Tribol. 141(3):031402; equations as implemented by tmdsimpy (tmd-lab)")
W_SWITCH = 1.9
HARDENING = True


@jit(inline=True)
def valid(et_ratio):
    """True for 0 <= Et/E < 1 (False for NaN)."""
    return et_ratio >= 0.0 and et_ratio < 1.0


@jit(inline=True)
def _blend_terms(w, eps_y, nu, C, B, et_ratio):
    """(sqrt(A_p*), sqrt(w) - sqrt(A_p*), t): JG's sqrt area, the Hertz one minus it, and
    t = 1 - e^Upsilon (exactly 0 at et_ratio = 0)."""
    lw = math.log(w)
    sq_ap = math.sqrt(w * math.exp(B * (lw - LN_SWITCH)))  # as jackson_green.p_star_jg computes A_p*
    k = 0.5 * math.pi * C * eps_y
    r = math.sqrt((1.0 - mul_rn(nu, nu)) / eps_y)  # sqrt(E/Sy); mul_rn: see fastrest._jit
    # h^(1 - (delta - delta_c)/R) with (delta - delta_c)/R = (w - 1) k^2; 0 for h = 0
    power = et_ratio ** (1.0 - mul_rn((w - 1.0) * k, k))
    ups = -2.0 * r * power / ((4.0 - mul_rn(3.0, math.exp(-2.0 * r * et_ratio))) * (1.0 - et_ratio))
    return sq_ap, math.sqrt(w) - sq_ap, -math.expm1(ups)


@jit(inline=True)
def p_star_above(w, eps_y, nu, C, B, et_ratio):
    """P*(w) for w >= 1.9 with C = C(nu) and B = 0.14 exp(23 eps_y) precomputed; a/R not checked."""
    sq_ap, d, t = _blend_terms(w, eps_y, nu, C, B, et_ratio)
    a_over_r = 0.5 * math.pi * C * eps_y * (sq_ap + mul_rn(t, d))
    hg = 2.84 - mul_rn(0.92, 1.0 - math.cos(math.pi * a_over_r))
    lw = math.log(w)
    hertz = mul_rn(w, math.sqrt(w))
    # the operations of jackson_green.p_star_jg, in its order (bit-identical at et_ratio = 0)
    p_plastic = (mul_rn(math.exp(-0.25 * math.exp(lw * (5.0 / 12.0))) * w, math.sqrt(w))
                 + mul_rn(4.0 * hg / C * (-math.expm1(-math.exp(lw * (5.0 / 9.0)) / 25.0)), w))
    return p_plastic + mul_rn(hertz - p_plastic, -math.expm1(-3.3 * et_ratio))


@jit(inline=True)
def a_star_above(w, eps_y, nu, C, B, et_ratio):
    """A*(w) = (a/a_c)^2 for w >= 1.9: (sqrt(A_p*) + t (sqrt(w) - sqrt(A_p*)))^2, written so that
    t = 0 returns JG's A_p* = w (w/1.9)^B exactly."""
    sq_ap, d, t = _blend_terms(w, eps_y, nu, C, B, et_ratio)
    td = mul_rn(t, d)
    return jackson_green.a_star_above(w, eps_y, nu, C, B, 0.0) + mul_rn(td, mul_rn(2.0, sq_ap) + td)


@jit(inline=True)
def omega_end(eps_y, nu, et_ratio):
    """w* where the law ends: JG's a_p/R = 1 (a <= a_p, see the module notes); NaN if h is invalid."""
    if not valid(et_ratio):
        return np.nan
    return omega_star_limit_kernel(eps_y, nu)
