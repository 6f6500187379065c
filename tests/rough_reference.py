"""Slow reference paths for rough-surface impacts (test and benchmark use only).

* :func:`reference_impact`: brute force on explicit summits, no forward tables and no rough
  kernels: every summit's loading energy is :func:`fastrest.energy.f_star_kernel` (quadrature),
  its force :func:`fastrest.loading.p_star` (the loading law's, JG or Ghaednia et al. with
  ``et_ratio``) and its unloading
  :func:`fastrest.unloading.restitution_kernel` (the single-sphere solver's own expressions, at
  V1* = sqrt(F)); the approach solving sum F = (V1/V_c)^2 comes from :func:`scipy.optimize.brentq`.
  Milliseconds per summit: for N up to a few hundred. Like the single-sphere kernels it forms
  w* - 1 from w*, so it is not a reference for 1 - e^2 right at the onset of yield.
* :func:`onset_reference`: 40-digit mpmath for impacts in which every summit stays Hertzian
  (w* <= 1.9), with JCG unloading (JGM eq 35): the reference near the onset of yield.
"""
import math

import mpmath
import numpy as np
from scipy import integrate, optimize

import fastrest
from fastrest import loading as _loading
from fastrest.energy import f_star_kernel
from fastrest.unloading import restitution_kernel, unloading_code

__all__ = ["reference_impact", "onset_reference", "gw_quad_reference"]

_ctx = mpmath.MPContext()
_ctx.dps = 40


def reference_impact(material, R_a, heights, V1, M, unloading="jcg", et_ratio=0.0, loading=None):
    """Brute-force impact of a flat of mass M (kg) at V1 (m/s) on summits of radius R_a (m) at
    ``heights`` (m), with the loading law of (loading, et_ratio) (:func:`fastrest.loading.resolve`).
    Returns a dict with the scalar fields of :class:`fastrest.rough.RoughImpact`
    (e, loss, d_min, force_max, n_contact, n_yielded, dissipated, w_star_max)."""
    from scipy.optimize import brentq

    model = unloading_code(unloading)
    law, h_r = _loading.resolve(loading, et_ratio).code, float(et_ratio)
    ip = fastrest.Impact(material, R_a, mass=M)
    eps, nu, wc = float(ip.eps_y), float(ip.nu), ip.omega_c
    z = np.asarray(heights, dtype=np.float64).ravel()
    z_top = float(z.max())
    h = (z - z_top) / wc
    energy = (float(V1) / ip.V_c) ** 2
    w_end = float(fastrest.omega_star_limit(eps, nu))

    def excess(x):
        return sum(f_star_kernel(hi + x, eps, nu, law, h_r) for hi in h if hi + x > 0.0) - energy

    # bracket the approach by doubling from the Hertz single-summit value (an upper bound while
    # the tallest summit stays elastic)
    x_hi = energy**0.4
    while excess(x_hi) < 0.0:
        if x_hi >= w_end:
            raise ValueError(f"V1 = {V1!r} m/s drives summits past a/R = 1")
        x_hi = min(2.0 * x_hi, w_end)
    x = brentq(excess, 0.0, x_hi, xtol=1e-300, rtol=1e-15, maxiter=1000)
    f_sum = p_sum = l_sum = 0.0
    n_c = n_y = 0
    for hi in h:
        w = hi + x
        if w <= 0.0:
            continue
        f = f_star_kernel(w, eps, nu, law, h_r)
        _, loss, _, _ = restitution_kernel(math.sqrt(f), w, w - 1.0, eps, nu, model, law, h_r)
        f_sum += f
        p_sum += _loading.p_star(law, w, eps, nu, h_r)
        l_sum += loss * f
        n_c += 1
        n_y += w > 1.0
    loss = l_sum / energy
    return {"e": math.sqrt(1.0 - loss), "loss": loss, "d_min": (z_top - float(z.mean())) - x * wc,
            "force_max": ip.P_c * p_sum, "n_contact": n_c, "n_yielded": n_y,
            "dissipated": ip.U_c * l_sum, "w_star_max": x}


def onset_reference(h, V1, M, U_c):
    """(1 - e_s^2, w* - 1 of the tallest summit) at 40 digits for Hertzian summits, JCG unloading.

    ``h``: the summits' heights below the tallest over omega_c (floats, taken exactly, as the
    solver sees them); the impact energy E = M V1^2 / (2 U_c) is formed exactly from the doubles
    V1 (m/s), M (kg), U_c (J). Solves sum_i (1 + delta + h_i)^2.5 = E (JGM eq 29 with eq 19 per
    summit) and returns sum_i r_i (1 + delta + h_i)^2.5 / E with r = w_res/w_m of eq (35),
    1.02 (1 - ((w + 5.9)/6.9)^-0.54) (for Hertz loading 1 - e^2 = r per summit).
    """
    c = _ctx
    hs = [c.mpf(float(x)) for x in h]
    E = c.mpf(float(M)) * c.mpf(float(V1)) ** 2 / (2 * c.mpf(float(U_c)))

    def energy(delta):
        return c.fsum((1 + delta + x) ** c.mpf(2.5) for x in hs if 1 + delta + x > 0)

    lo, hi = c.mpf(-1), c.mpf(1)
    for _ in range(400):  # bisection to 40 digits (the energy is increasing in delta)
        mid = (lo + hi) / 2
        if energy(mid) < E:
            lo = mid
        else:
            hi = mid
    delta = (lo + hi) / 2
    if not 1 + delta <= c.mpf("1.9"):
        raise ValueError("onset_reference covers Hertzian summits only (w* <= 1.9)")

    def ratio(d):  # eq (35) from d = w - 1 without cancellation
        return c.mpf("1.02") * -c.expm1(c.mpf("-0.54") * c.log1p(d / c.mpf("6.9"))) if d > 0 else 0

    loss = c.fsum(ratio(delta + x) * (1 + delta + x) ** c.mpf(2.5) for x in hs if 1 + delta + x > 0) / E
    return float(loss), float(delta)


def gw_quad_reference(s, V1, M, model="jcg"):
    """zs_d and e of a Gaussian Greenwood-Williamson surface by scipy quad + brentq, with the
    per-summit loading energy of the surface's law (energy.f_star_kernel) and its unloading."""
    eps, nu, r, h = s.eps_y, s.nu, s.sigma / s.omega_c, s.et_ratio
    law = s.law.code
    N = s.n_summits
    code = unloading_code(model)
    E = M * V1**2 / (2 * s.U_c)

    def phi(x):
        return math.exp(-0.5 * x * x) / math.sqrt(2 * math.pi)

    def F(w):
        return f_star_kernel(w, eps, nu, law, h) if w > 0 else 0.0

    def L(w):
        if w <= 1.0:
            return 0.0
        f = f_star_kernel(w, eps, nu, law, h)
        return restitution_kernel(math.sqrt(f), w, w - 1.0, eps, nu, code, law, h)[1] * f

    def expect(sd, fun):
        top = max(sd, 0.0) + 12.0
        pts = [p for p in (sd + 1.0 / r, sd + 1.9 / r) if p < top]
        return integrate.quad(lambda x: fun((x - sd) * r) * phi(x), sd, top, points=pts or None,
                              limit=500, epsabs=0.0, epsrel=1e-13)[0]

    sd = optimize.brentq(lambda x: N * expect(x, F) - E, -30.0, 12.0, xtol=1e-14, rtol=1e-15)
    return sd, math.sqrt(1.0 - N * expect(sd, L) / E)
