"""The direct solver: w_m*, e, 1 - e^2 and the residual state of one impact, with no tables.

Each call integrates the JG law (JGM eqs 9, 25) by quadrature and inverts the energy balance (29)
by Newton's method (:mod:`fastrest.energy`), then applies the unloading model (eqs 33/35, 38;
:mod:`fastrest.unloading`). Relative error ~1e-15 against mpmath; tens of microseconds per point.
It is the reference the fast paths (tables, curves) are measured against; its functions are
named ``<quantity>_exact`` (:func:`e_exact`), the interpolated ones of the default table
``<quantity>_star`` (:func:`fastrest.e_star`).

Domain (every function): V1* >= 0 (V1* <= 1 is elastic: w_m* = V1*^0.8, e = 1); eps_y > 0;
0 <= nu < 0.5. Outside the validated 0.0005 <= eps_y <= 0.01, 0.2 <= nu <= 0.45 a
:class:`~fastrest.ValidityWarning` is issued. w_m* is limited to 425 (the paper's range):
beyond it a ValueError names the limit and its V1*, unless ``extrapolate=True``, which computes
with the same formulas up to the point where a/R = 1 and issues an
:class:`~fastrest.ExtrapolationWarning`.
"""
from __future__ import annotations

from typing import Any
from numpy.typing import ArrayLike, NDArray
import math

import numpy as np

from ._deprecation import alias, module_getattr
from ._doc import doc, paragraphs
from ._jit import jit
from ._validation import (OMEGA_M_STAR_MAX, ExtrapolationWarning, check_bool, check_eps_y, check_nu,
                          check_velocity, warn, warn_if_outside_validated)
from ._validation import broadcast_inputs, shaped
from .energy import V_SWITCH, omega_m_kernel
from .limits import raise_out_of_range, speed_limit, w_upper_model
from .loading import resolve as resolve_loading
from .unloading import get as unloading_model, restitution_kernel, warn_if_unfitted

__all__ = ["omega_m_exact", "e_exact", "loss_exact", "residual_exact", "solve"]

# The parameters, Raises and Warns of the functions below, written once (fastrest._doc).
_DOC = paragraphs(
    params_material="""
        Parameters
        ----------
        v1_star : float or array_like
            Normalised impact speed V1/V_c (-), JGM eq (30); >= 0 and finite, up to
            ``fastrest.limit(eps_y, nu).v1_star`` (about 1022 for eps_y = 0.005, nu = 0.33).
        eps_y : float or array_like
            Sy/E' (-), eq (11); > 0 (validated range 0.0005-0.01).
        nu : float or array_like
            Poisson's ratio of the yielding material (-), 0 <= nu < 0.5 (validated 0.2-0.45).
        """,
    params_law="""
        et_ratio : float or array_like, optional
            Tangent modulus over Young's modulus Et/E (-), 0 <= et_ratio < 1 (default 0: elastic-perfectly
            plastic). Above 0 the loading law is Ghaednia et al. (2019), docs/model.md section 12.
        loading : {None, "jackson-green", "ghaednia"}, optional
            The loading law (:mod:`fastrest.loading`); None picks it from ``et_ratio``.
        """,
    params="""
        {params_material}
        unloading : {"jcg", "etsion", "brake"}, optional
            Unloading model (residual interference): ``"jcg"`` JGM eq (35) (default), ``"etsion"``
            eqs (33)-(34), ``"brake"`` Brake (2015) as tmdsimpy implements it
            (:mod:`fastrest.unloading`).
        extrapolate : bool, optional
            Allow w_m* > 425 (JGM's range), with the same formulas up to a/R = 1 (and, for JCG, the end
            of eq 35 at w_m* = 10017.5). Default False.
        {params_law}
        """,
    params_no_unloading="""
        {params_material}
        extrapolate : bool, optional
            Allow w_m* > 425 (JGM's range), with the same formulas up to a/R = 1. Default False.
        {params_law}
        """,
    raises_type="""
        Raises
        ------
        TypeError
            A speed or material parameter is not a real number or array of them; ``extrapolate`` is not
            True or False.
        """,
    warns="""
        Warns
        -----
        ValidityWarning
            eps_y or nu outside the validated 0.0005 <= eps_y <= 0.01, 0.2 <= nu <= 0.45.
        ExtrapolationWarning
            With ``extrapolate=True``, when a result lies past w_m* = 425.
        """,
    raises="""
        {raises_type}
        ValueError
            v1_star negative, NaN or infinite; eps_y not finite and > 0; nu outside [0, 0.5); shapes
            that do not broadcast; an unknown ``unloading``; a speed past w_m* = 425 (without
            ``extrapolate``), past a/R = 1, or past the unloading model's end (the message names the
            limit and its V1*).

        {warns}
        """,
    raises_no_unloading="""
        {raises_type}
        ValueError
            v1_star negative, NaN or infinite; eps_y not finite and > 0; nu outside [0, 0.5); shapes
            that do not broadcast; a speed past w_m* = 425 (without ``extrapolate``) or past a/R = 1
            (the message names the limit and its V1*).

        {warns}
        """,
)


@jit
def impact_kernel(v, eps_y, nu, model, extrapolate, law, et_ratio):
    """(w_m*, e, 1 - e^2, w_res*, R_res/R) for one impact under loading law ``law``; NaNs outside
    the domain."""
    w_hi = w_upper_model(eps_y, nu, extrapolate, model, law, et_ratio)
    wm = omega_m_kernel(v, eps_y, nu, w_hi, law, et_ratio)
    if not wm >= 0.0:
        return np.nan, np.nan, np.nan, np.nan, np.nan
    if v <= V_SWITCH:
        wm1 = math.expm1(0.8 * math.log(v)) if v > 0.0 else -1.0  # w_m - 1 without cancellation
    else:
        wm1 = wm - 1.0
    e, loss, w_res, r_res = restitution_kernel(v, wm, wm1, eps_y, nu, model, law, et_ratio)
    return wm, e, loss, w_res, r_res


@jit
def impact_array(v, eps_y, nu, et_ratio, model, extrapolate, law, out):
    """Batch driver: out[k, i] for k in (w_m*, e, loss, w_res*, R_res/R)."""
    for i in range(v.size):
        r = impact_kernel(v[i], eps_y[i], nu[i], model, extrapolate, law, et_ratio[i])
        for k in range(5):
            out[k, i] = r[k]


def _solve(v1_star, eps_y, nu, unloading, extrapolate, et_ratio, loading):
    model = unloading_model(unloading)
    extrapolate = check_bool(extrapolate, "extrapolate")
    (v, eps_y, nu, h), shape = broadcast_inputs((v1_star, "v1_star"), (eps_y, "eps_y"), (nu, "nu"),
                                                (et_ratio, "et_ratio"))
    check_velocity(v, "v1_star")
    check_eps_y(eps_y)
    check_nu(nu)
    law = resolve_loading(loading, h)
    warn_if_outside_validated(eps_y, nu)
    warn_if_unfitted(model, h)
    out = np.empty((5, v.size))
    if v.size == 0:
        return out, shape
    impact_array(v, eps_y, nu, h, model.code, bool(extrapolate), law.code, out)
    bad = np.isnan(out[0])
    if np.any(bad):
        raise_out_of_range(v[bad], eps_y[bad], nu[bad], extrapolate, unloading=unloading, et_ratio=h[bad],
                           loading=law)
    if extrapolate and np.any(out[0] > OMEGA_M_STAR_MAX):
        warn(f"extrapolated past w_m* = {OMEGA_M_STAR_MAX:g}, the largest interference "
             "JGM computed; the JG law is not validated there", ExtrapolationWarning)
    return out, shape


@doc(_DOC)
def omega_m_exact(v1_star: ArrayLike, eps_y: ArrayLike, nu: ArrayLike, *,
                  extrapolate: bool = False, et_ratio: ArrayLike = 0.0,
                  loading: str | None = None) -> float | NDArray[np.float64]:
    """Normalised maximum interference w_m* = omega_m/omega_c of an impact at V1* (-).

    w_m* does not depend on the unloading model: there is no ``unloading`` parameter.

    {params_no_unloading}

    Returns
    -------
    float or ndarray
        w_m* (-), JGM eq (31), broadcast over the inputs (a float if all are scalars).

    {raises_no_unloading}

    Notes
    -----
    Solves the energy balance JGM eq (29), V1*^2 = F(w_m*) with F the loading energy of eqs (19),
    (25) (:func:`fastrest.loading_energy`): w_m* = V1*^0.8 in closed form up to V1* = 1.9^1.25,
    Newton's method in ln w above (docs/model.md section 7). Relative error ~1e-15.

    Examples
    --------
    >>> from fastrest import direct
    >>> round(direct.omega_m_exact(10.0, 0.005, 0.33), 9)  # JGM check value (docs/model.md section 3)
    6.549856323
    >>> direct.omega_m_exact(2000.0, 0.005, 0.33)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
        ...
    ValueError: v1_star = 2000.0 gives w_m* > 425, the model's limit (JGM section 3.3); ...
    """
    # w_m* does not depend on the unloading model; Etsion's is defined wherever w_m* is
    out, shape = _solve(v1_star, eps_y, nu, "brake", extrapolate, et_ratio, loading)  # w_m* alone: any model that never ends
    return shaped(out[0], shape)


@doc(_DOC)
def e_exact(v1_star: ArrayLike, eps_y: ArrayLike, nu: ArrayLike, unloading: str = "jcg", *,
            extrapolate: bool = False, et_ratio: ArrayLike = 0.0,
            loading: str | None = None) -> float | NDArray[np.float64]:
    """Coefficient of restitution e = V2/V1 (-) of an impact at V1*, by the exact solver.

    {params}

    Returns
    -------
    float or ndarray
        e (-), broadcast over the inputs (a float if all are scalars); 1 for V1* <= 1 (elastic).
        The model can give e slightly above 1 just above V1* = 1.9^1.25 for small nu
        (docs/model.md section 5); it is not clipped.

    {raises}

    Notes
    -----
    JGM eq (16) with the rebound energy of eq (38) after elastic unloading (eq 32) from the maximum
    interference of eq (29) (:func:`omega_m_exact`): e^2 = P_m* (w_m* - w_res*)/V1*^2, w_res* from
    the unloading model (eq 35, eq 33 or Brake's; docs/model.md section 3).

    Examples
    --------
    JGM check values (docs/model.md section 3):

    >>> from fastrest import direct
    >>> round(direct.e_exact(10.0, 0.005, 0.33), 9)
    0.828732573
    >>> round(direct.e_exact(10.0, 0.005, 0.33, "etsion"), 9)
    0.865201797
    >>> direct.e_exact([0.5, 2.2], 0.005, 0.33).round(6)
    array([1.      , 0.967494])
    """
    out, shape = _solve(v1_star, eps_y, nu, unloading, extrapolate, et_ratio, loading)
    return shaped(out[1], shape)


@doc(_DOC)
def loss_exact(v1_star: ArrayLike, eps_y: ArrayLike, nu: ArrayLike, unloading: str = "jcg", *,
               extrapolate: bool = False, et_ratio: ArrayLike = 0.0,
               loading: str | None = None) -> float | NDArray[np.float64]:
    """Fraction of the impact energy dissipated, 1 - e^2 (-), computed without cancellation.

    Keeps full relative accuracy as V1* -> 1 (e.g. V1* = 1 + 1e-9), where 1 - e_exact(...)**2
    would lose most digits (multi-asperity codes sum many barely plastic contacts).

    {params}

    Returns
    -------
    float or ndarray
        1 - e^2 (-), broadcast over the inputs (a float if all are scalars); 0 for V1* <= 1.

    {raises}

    Notes
    -----
    JGM eqs (16), (38) as :func:`e_exact`, with the JCG ratio of eq (35) evaluated through
    expm1/log1p from w_m* - 1 (docs/model.md section 3, "JCG unloading below the switch").

    Examples
    --------
    >>> from fastrest import direct
    >>> round(direct.loss_exact(10.0, 0.005, 0.33), 9)
    0.313202323
    >>> f"{direct.loss_exact(1 + 1e-9, 0.005, 0.33):.6e}"
    '6.386087e-11'
    """
    out, shape = _solve(v1_star, eps_y, nu, unloading, extrapolate, et_ratio, loading)
    return shaped(out[2], shape)


@doc(_DOC)
def residual_exact(v1_star: ArrayLike, eps_y: ArrayLike, nu: ArrayLike, unloading: str = "jcg", *,
                   extrapolate: bool = False, et_ratio: ArrayLike = 0.0,
                   loading: str | None = None) -> tuple[float | NDArray[np.float64], float | NDArray[np.float64]]:
    """Residual state after the impact: residual interference and radius of curvature (-).

    {params}

    Returns
    -------
    w_res : float or ndarray
        Residual interference w_res* = omega_res/omega_c (-), 0 for V1* <= 1.
    R_res_ratio : float or ndarray
        Radius of curvature of the residual shape over the sphere's, R_res/R (-); 1 for V1* <= 1.
        Both broadcast over the inputs.

    {raises}

    Notes
    -----
    w_res* from the unloading model: JGM eq (35) (JCG), eqs (33)-(34) (Etsion) or Brake's rule;
    R_res/R = P_m*^2/(w_m* - w_res*)^3, eq (36) normalised (docs/model.md section 3).

    Examples
    --------
    >>> from fastrest import direct
    >>> w_res, r = direct.residual_exact(10.0, 0.005, 0.33)
    >>> round(w_res, 6), round(r, 6)
    (1.823254, 1.999458)
    """
    out, shape = _solve(v1_star, eps_y, nu, unloading, extrapolate, et_ratio, loading)
    return shaped(out[3], shape), shaped(out[4], shape)


@doc(_DOC)
def solve(v1_star: ArrayLike, eps_y: ArrayLike, nu: ArrayLike, unloading: str = "jcg", *,
          extrapolate: bool = False, et_ratio: ArrayLike = 0.0,
          loading: str | None = None) -> dict[str, float | NDArray[np.float64]]:
    """Everything the direct solver computes for an impact, from one solve.

    {params}

    Returns
    -------
    dict
        ``"omega_m_star"`` (w_m*), ``"e"``, ``"loss"`` (1 - e^2), ``"omega_res_star"`` (w_res*),
        ``"R_res_ratio"`` (R_res/R), all dimensionless, each as :func:`omega_m_exact`,
        :func:`e_exact`, :func:`loss_exact` and :func:`residual_exact` return them.

    {raises}

    Notes
    -----
    JGM eqs (29), (16), (38) and (33)-(36); cheaper than calling the four functions.

    Examples
    --------
    >>> from fastrest import direct
    >>> r = direct.solve(10.0, 0.005, 0.33)
    >>> {k: round(v, 6) for k, v in r.items()}  # doctest: +NORMALIZE_WHITESPACE
    {'omega_m_star': 6.549856, 'e': 0.828733, 'loss': 0.313202, 'omega_res_star': 1.823254,
     'R_res_ratio': 1.999458}
    """
    out, shape = _solve(v1_star, eps_y, nu, unloading, extrapolate, et_ratio, loading)
    keys = ("omega_m_star", "e", "loss", "omega_res_star", "R_res_ratio")
    return {k: shaped(out[i], shape) for i, k in enumerate(keys)}


# the exact solver's functions were named like the table's (fastrest.e_star is the default table)
__getattr__ = module_getattr(__name__)
alias(__name__, "omega_m_star", "fastrest.direct.omega_m_exact", lambda: omega_m_exact)
alias(__name__, "e_star", "fastrest.direct.e_exact", lambda: e_exact)
alias(__name__, "loss_star", "fastrest.direct.loss_exact", lambda: loss_exact)
alias(__name__, "residual_star", "fastrest.direct.residual_exact", lambda: residual_exact)
alias(__name__, "v1_star_limit", "fastrest.limit(eps_y, nu, ...).v1_star", lambda: speed_limit)
