"""The direct solver: w_m*, e, 1 - e^2 and the residual state of one impact, with no tables.

Each call integrates the JG law (JGM eqs 9, 25) by quadrature and inverts the energy balance (29)
by Newton's method (:mod:`fastrest.energy`), then applies the unloading model (eqs 33/35, 38;
:mod:`fastrest.unloading`). Relative error ~1e-15 against mpmath; tens of microseconds per point.
It is the reference the fast paths (tables, curves) are measured against.

Domain (every function): V1* >= 0 (V1* <= 1 is elastic: w_m* = V1*^0.8, e = 1); eps_y > 0;
0 <= nu < 0.5. Outside the validated 0.0005 <= eps_y <= 0.01, 0.2 <= nu <= 0.45 a
:class:`~fastrest.ValidityWarning` is issued. w_m* is limited to 425 (the paper's range):
beyond it a ValueError names the limit and its V1*, unless ``extrapolate=True``, which computes
with the same formulas up to the point where a/R = 1 and issues an
:class:`~fastrest.ExtrapolationWarning`.
"""
import math

import numpy as np

from ._jit import jit
from ._validation import (OMEGA_M_STAR_MAX, ExtrapolationWarning, check_bool, check_eps_y, check_nu,
                          check_velocity, warn, warn_if_outside_validated)
from ._validation import broadcast_inputs, shaped
from .energy import V_SWITCH, omega_m_kernel
from .limits import raise_out_of_range, v1_star_limit, w_upper_model
from .unloading import get as unloading_model, restitution_kernel

__all__ = ["omega_m_star", "e_star", "loss_star", "residual_star", "solve", "v1_star_limit"]


@jit
def impact_kernel(v, eps_y, nu, model, extrapolate):
    """(w_m*, e, 1 - e^2, w_res*, R_res/R) for one impact; NaNs outside the domain."""
    w_hi = w_upper_model(eps_y, nu, extrapolate, model)
    wm = omega_m_kernel(v, eps_y, nu, w_hi)
    if not wm >= 0.0:
        return np.nan, np.nan, np.nan, np.nan, np.nan
    if v <= V_SWITCH:
        wm1 = math.expm1(0.8 * math.log(v)) if v > 0.0 else -1.0  # w_m - 1 without cancellation
    else:
        wm1 = wm - 1.0
    e, loss, w_res, r_res = restitution_kernel(v, wm, wm1, eps_y, nu, model)
    return wm, e, loss, w_res, r_res


@jit
def impact_array(v, eps_y, nu, model, extrapolate, out):
    """Batch driver: out[k, i] for k in (w_m*, e, loss, w_res*, R_res/R)."""
    for i in range(v.size):
        r = impact_kernel(v[i], eps_y[i], nu[i], model, extrapolate)
        for k in range(5):
            out[k, i] = r[k]


def _solve(v1_star, eps_y, nu, unloading, extrapolate):
    model = unloading_model(unloading).code
    extrapolate = check_bool(extrapolate, "extrapolate")
    (v, eps_y, nu), shape = broadcast_inputs((v1_star, "v1_star"), (eps_y, "eps_y"), (nu, "nu"))
    check_velocity(v, "v1_star")
    check_eps_y(eps_y)
    check_nu(nu)
    warn_if_outside_validated(eps_y, nu)
    out = np.empty((5, v.size))
    if v.size == 0:
        return out, shape
    impact_array(v, eps_y, nu, model, bool(extrapolate), out)
    bad = np.isnan(out[0])
    if np.any(bad):
        raise_out_of_range(v[bad], eps_y[bad], nu[bad], extrapolate, unloading=unloading)
    if extrapolate and np.any(out[0] > OMEGA_M_STAR_MAX):
        warn(f"extrapolated past w_m* = {OMEGA_M_STAR_MAX:g}, the largest interference "
             "JGM computed; the JG law is not validated there", ExtrapolationWarning)
    return out, shape


def omega_m_star(v1_star, eps_y, nu, *, extrapolate=False):
    """Normalised maximum interference w_m* = omega_m/omega_c, solving JGM eq (29).

    Parameters
    ----------
    v1_star : float or array_like
        Normalised impact speed V1/V_c (-), eq (30); >= 0.
    eps_y : float or array_like
        Sy/E' (-), eq (11); > 0.
    nu : float or array_like
        Poisson's ratio of the yielding material, 0 <= nu < 0.5.
    extrapolate : bool
        Allow w_m* > 425 (up to a/R = 1), with a warning.

    Returns
    -------
    float or ndarray
        w_m* (-), broadcast over the inputs.
    """
    # w_m* does not depend on the unloading model; Etsion's is defined wherever w_m* is
    out, shape = _solve(v1_star, eps_y, nu, "etsion", extrapolate)
    return shaped(out[0], shape)


def e_star(v1_star, eps_y, nu, unloading="jcg", *, extrapolate=False):
    """Coefficient of restitution e = V2/V1 (-), JGM eqs (16), (38) with unloading (35) or (33).

    Parameters as :func:`omega_m_star`; ``unloading`` names the unloading model:
    ``"jcg"`` (eq 35, default), ``"etsion"`` (eq 33) or ``"brake"`` (Brake 2015, see
    :mod:`fastrest.unloading.brake`).
    """
    out, shape = _solve(v1_star, eps_y, nu, unloading, extrapolate)
    return shaped(out[1], shape)


def loss_star(v1_star, eps_y, nu, unloading="jcg", *, extrapolate=False):
    """Fraction of the impact energy dissipated, 1 - e^2 (-), computed without cancellation.

    Keeps full relative accuracy as V1* -> 1 (e.g. V1* = 1 + 1e-9). Parameters as :func:`e_star`.
    """
    out, shape = _solve(v1_star, eps_y, nu, unloading, extrapolate)
    return shaped(out[2], shape)


def residual_star(v1_star, eps_y, nu, unloading="jcg", *, extrapolate=False):
    """Residual state after the impact: (w_res*, R_res/R), JGM eqs (33)-(36).

    w_res* = omega_res/omega_c (-) and R_res/R (-), each broadcast over the inputs.
    Parameters as :func:`e_star`.
    """
    out, shape = _solve(v1_star, eps_y, nu, unloading, extrapolate)
    return shaped(out[3], shape), shaped(out[4], shape)


def solve(v1_star, eps_y, nu, unloading="jcg", *, extrapolate=False):
    """Everything at once: dict of w_m*, e, loss (1 - e^2), w_res*, R_res/R (one solve)."""
    out, shape = _solve(v1_star, eps_y, nu, unloading, extrapolate)
    keys = ("omega_m_star", "e", "loss", "omega_res_star", "R_res_ratio")
    return {k: shaped(out[i], shape) for i, k in enumerate(keys)}
