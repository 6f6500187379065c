"""Slow, high-precision reference of Ghaednia et al. (2019) strain-hardening loading, for the tests.

Independent of ``fastrest`` (nothing imported from it): the normalised law written from
Ghaednia, Brake, Berryhill & Jackson (2019) (the form tmdsimpy's
``_normal_pl_asperity_loading`` implements), on top of :mod:`reference`'s 40-digit Jackson-Green
machinery (its loading energy F, by Gauss-Legendre checked segment by segment against mpmath's
adaptive tanh-sinh quadrature, and its safeguarded Newton root find for w_m), which only needs
P*(w) and A*(w) above w = 1.9:

    k = pi C eps_y / 2 (a/R = k sqrt(A*), delta_c/R = k^2),  sqrt(E/Sy) = sqrt((1 - nu^2)/eps_y)
    a_p/R = k sqrt(w (w/1.9)^B),  a_e/R = k sqrt(w)
    Upsilon = -2 sqrt(E/Sy) h^(1 - (w - 1) k^2) / ((4 - 3 exp(-2 sqrt(E/Sy) h)) (1 - h))
    a/R = a_e/R + (a_p/R - a_e/R) exp(Upsilon)
    H/Sy = 2.84 - 0.92 (1 - cos(pi a/R))
    P_p = exp(-w^(5/12)/4) w^1.5 + 4 H/(C Sy) (1 - exp(-w^(5/9)/25)) w
    P* = P_p + (w^1.5 - P_p) (1 - exp(-3.3 h)),  A* = (a/R / k)^2

Restitution (JGM eqs 32, 38): e^2 = P*(w_m) (w_m - w_res*) / V1*^2 with w_m - w_res* from Brake
(P_m/sqrt(w_m)), Etsion (P_m/sqrt(A_m*), the law's own area) or JCG (eq 35, w_res/w_m from w_m).
"""
from __future__ import annotations

import functools

from reference import _F3_2, _F5_12, _F5_9, _Law, _W19, _ctx, _jcg_ratio, _mpf

__all__ = ["HardeningLaw", "hard_law", "hard_omega_m", "hard_e"]


class HardeningLaw(_Law):
    """Ghaednia et al. (2019) loading for one (eps_y, nu, h = Et/E); F and w_m from :class:`_Law`."""

    def __init__(self, eps_y: float, nu: float, et_ratio: float):
        super().__init__(eps_y, nu)
        ctx = _ctx
        self.h = _mpf(et_ratio)
        self.r = ctx.sqrt((1 - self.nu ** 2) / self.eps)
        self.ups_coeff = -2 * self.r / ((4 - 3 * ctx.exp(-2 * self.r * self.h)) * (1 - self.h))
        self.blend = -ctx.expm1(-_mpf("3.3") * self.h)

    def _aR(self, w):
        """(a/R of the hardening law, a_p/R of JG's)."""
        ctx = _ctx
        ap = self.k_aR * ctx.sqrt(w * (w / _W19) ** self.B)
        ae = self.k_aR * ctx.sqrt(w)
        if self.h == 0:
            return ap, ap
        ups = self.ups_coeff * self.h ** (1 - (w - 1) * self.k_aR ** 2)
        return ae + (ap - ae) * ctx.exp(ups), ap

    def A_jg(self, w):
        return (self._aR(w)[0] / self.k_aR) ** 2

    def P_jg(self, w):
        ctx = _ctx
        aR, ap = self._aR(w)
        if ap > 1 + _mpf("1e-30"):
            raise ValueError(f"a_p/R = {float(ap):.6g} > 1 at w = {float(w):.6g}: past the law's end")
        lw = ctx.ln(w)
        hg = _mpf("2.84") - _mpf("0.92") * (1 - ctx.cos(ctx.pi * aR))
        pp = (ctx.exp(_F3_2 * lw - ctx.exp(_F5_12 * lw) / 4)
              + (4 * hg / self.C) * (-ctx.expm1(-ctx.exp(_F5_9 * lw) / 25)) * w)
        return pp + (w ** _F3_2 - pp) * self.blend


@functools.lru_cache(maxsize=None)
def hard_law(eps_y: float, nu: float, et_ratio: float) -> HardeningLaw:
    return HardeningLaw(eps_y, nu, et_ratio)


@functools.lru_cache(maxsize=4096)
def hard_omega_m(v1_star: float, eps_y: float, nu: float, et_ratio: float):
    """w_m* (mpf) solving F(w_m) = V1*^2 under the hardening law."""
    return hard_law(eps_y, nu, et_ratio).omega_m(_mpf(v1_star))


def hard_e(v1_star: float, eps_y: float, nu: float, et_ratio: float, unloading: str) -> tuple[float, float, float]:
    """(w_m*, e, 1 - e^2) as floats for V1* > 1.9^1.25 (w_m > 1.9)."""
    law = hard_law(eps_y, nu, et_ratio)
    v1 = _mpf(v1_star)
    wm = hard_omega_m(v1_star, eps_y, nu, et_ratio)
    if not wm > _W19:
        raise ValueError("this reference is for w_m > 1.9 (plastic loading)")
    P = law.P_jg(wm)
    if unloading == "brake":
        d = P / _ctx.sqrt(wm)
    elif unloading == "etsion":
        d = P / _ctx.sqrt(law.A_jg(wm))
    elif unloading == "jcg":
        d = wm * (1 - _jcg_ratio(wm))
    else:
        raise ValueError(unloading)
    e2 = P * d / (v1 * v1)
    return float(wm), float(_ctx.sqrt(e2)), float(1 - e2)
