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
from ..loading.jackson_green import W_SWITCH

__all__ = ["force", "returned_energy", "residual_radius_ratio", "restitution", "area_residual",
           "area_restitution"]


@jit(inline=True)
def force(w, w_max, p_max, w_res, delta):
    """Force P*(w) on the elastic unloading/reloading branch through (w_max, p_max) (-).

    Parameters
    ----------
    w : float
        Interference w* = omega/omega_c (-).
    w_max : float
        Largest interference reached, w_m* (-), > 0.
    p_max : float
        Force there, P_m* (-).
    w_res : float
        Residual interference w_res* of the unloading model (-).
    delta : float
        w_max - w_res (> 0), as the model computed it (more accurate than the difference near
        w_res).

    Returns
    -------
    float
        P* = p_max ((w - w_res)/delta)^1.5 (-); 0 at or below w_res, p_max at and above w_max. NaN
        for a NaN w.

    Notes
    -----
    JGM eq (32), normalised. A jit kernel, inlined into its callers (no input checks; it never
    raises).

    Examples
    --------
    >>> from fastrest.unloading import elastic
    >>> round(elastic.force(5.0, 10.0, 25.0, 2.0, 8.0), 6)
    5.740992
    >>> elastic.force(1.0, 10.0, 25.0, 2.0, 8.0)  # below w_res: separated
    0.0
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
    """Energy the elastic branch stores between w_res and w, over U_c (-).

    Parameters
    ----------
    w : float
        Interference w* (-); not checked for NaN (a NaN w gives P_m* delta).
    w_max, p_max, w_res, delta : float
        The branch, as :func:`force`.

    Returns
    -------
    float
        P_m* delta x^2.5 with x = (w - w_res)/delta (-); 0 at or below w_res, P_m* delta (the
        whole rebound energy) at and above w_max.

    Notes
    -----
    (5/2) int_{w_res}^{w} P* dz of JGM eq (32), in units of U_c = (2/5) P_c omega_c (eq 24); at
    w_max it is the rebound energy of eq (38). A jit kernel, inlined into its callers (no input
    checks; it never raises).

    Examples
    --------
    >>> from fastrest.unloading import elastic
    >>> elastic.returned_energy(10.0, 10.0, 25.0, 2.0, 8.0)  # P_m* delta
    200.0
    >>> round(elastic.returned_energy(5.0, 10.0, 25.0, 2.0, 8.0), 6)
    17.222975
    """
    x = w - w_res
    if not x > 0.0:
        return 0.0 if x <= 0.0 else math.nan  # NaN in, NaN out
    s = min((delta - (w_max - w)) / delta, 1.0) if w < w_max else 1.0
    return p_max * delta * s * s * math.sqrt(s)


@jit(inline=True)
def residual_radius_ratio(p_max, delta):
    """Radius of curvature of the residual shape over the sphere's, R_res/R = P_m*^2 / delta^3 (-).

    Parameters
    ----------
    p_max : float
        Force at maximum interference, P_m* (-).
    delta : float
        w_m* - w_res* (-).

    Returns
    -------
    float
        R_res/R (-); ``inf`` for delta <= 0 (a flat residual shape).

    Notes
    -----
    JGM eq (36), normalised (for Etsion unloading the same as eq 34). A jit kernel, inlined into
    its callers (no input checks; it never raises).

    Examples
    --------
    >>> from fastrest.unloading import elastic
    >>> elastic.residual_radius_ratio(25.0, 8.0), elastic.residual_radius_ratio(25.0, 0.0)
    (1.220703125, inf)
    """
    if delta <= 0.0:
        return math.inf
    return p_max * p_max / delta**3


@jit(inline=True)
def restitution(f, p_max, w_res, delta):
    """Energy split of an impact from its loading energy and the unloading branch.

    e^2 = P_m* delta / V1*^2, the plain form (a model with a better-conditioned 1 - e^2 computes
    its own).

    Parameters
    ----------
    f : float
        Loading energy over U_c, F(w_m*) = V1*^2 (-), > 0.
    p_max : float
        P_m* (-).
    w_res : float
        Residual interference w_res* (-).
    delta : float
        w_m* - w_res* (-).

    Returns
    -------
    tuple of float
        (e^2, 1 - e^2, w_res*, delta, R_res/R), all dimensionless.

    Notes
    -----
    JGM eq (38) with eq (32), normalised (docs/model.md section 3); R_res/R from
    :func:`residual_radius_ratio` (eq 36). A jit kernel, inlined into its callers (no input
    checks; it never raises).

    Examples
    --------
    >>> from fastrest.unloading import elastic
    >>> e2, loss, w_res, delta, r = elastic.restitution(100.0, 14.5, 1.8, 4.7)
    >>> round(e2, 6), round(loss, 6)
    (0.6815, 0.3185)
    """
    e2 = p_max * delta / f
    return e2, 1.0 - e2, w_res, delta, residual_radius_ratio(p_max, delta)


@jit(inline=True)
def area_residual(wm, p_max, area):
    """Residual interference when the elastic recovery is set by the contact area at maximum load.

    delta = P_m* / sqrt(A_m*). Under Hertz loading (w_m* <= 1.9) unloading retraces loading:
    w_res* = 0, delta = w_m*.

    Parameters
    ----------
    wm : float
        Maximum interference w_m* (-).
    p_max : float
        P_m* (-).
    area : float
        Normalised contact area A_m* at maximum load (-), > 0.

    Returns
    -------
    w_res : float
        w_res* = w_m* - delta (-).
    delta : float
        w_m* - w_res* (-).

    Notes
    -----
    Etsion et al.'s JGM eq (33) normalised, with the JG area A_m* of eq (8); Brake's rule (as
    tmdsimpy) with A* = w_m*, the Hertz area. A jit kernel, inlined into its callers (no input
    checks; it never raises).

    Examples
    --------
    >>> from fastrest.unloading import elastic
    >>> w_res, delta = elastic.area_residual(6.55, 15.0, 8.0)
    >>> round(w_res, 6), round(delta, 6)
    (1.246699, 5.303301)
    >>> elastic.area_residual(1.5, 1.5**1.5, 1.5)  # Hertz loading
    (0.0, 1.5)
    """
    if wm <= W_SWITCH:
        return 0.0, wm
    delta = p_max / math.sqrt(area)
    return wm - delta, delta


@jit(inline=True)
def area_restitution(f, wm, p_max, area):
    """:func:`restitution` for an :func:`area_residual` model; e = 1 exactly under Hertz loading.

    Parameters
    ----------
    f : float
        Loading energy over U_c, F(w_m*) = V1*^2 (-), > 0.
    wm : float
        Maximum interference w_m* (-).
    p_max : float
        P_m* (-).
    area : float
        Contact area A_m* at maximum load (-), > 0.

    Returns
    -------
    tuple of float
        (e^2, 1 - e^2, w_res*, delta, R_res/R), all dimensionless.
        (1, 0, 0, w_m*, 1) for w_m* <= 1.9.

    Notes
    -----
    JGM eqs (33), (38) (Etsion) or Brake's rule, through :func:`area_residual` and
    :func:`restitution`. A jit kernel, inlined into its callers (no input checks; it never raises).

    Examples
    --------
    >>> from fastrest.unloading import elastic
    >>> out = elastic.area_restitution(100.0, 6.55, 15.0, 8.0)  # (e^2, 1 - e^2, w_res*, delta, R_res/R)
    >>> round(out[0], 6), round(out[1], 6)
    (0.795495, 0.204505)
    """
    if wm <= W_SWITCH:
        return 1.0, 0.0, 0.0, wm, 1.0
    w_res, delta = area_residual(wm, p_max, area)
    return restitution(f, p_max, w_res, delta)
