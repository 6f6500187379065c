"""Where the model ends, and the errors that say so: one module for every API.

Three limits bound the maximum interference w_m* = omega_m/omega_c:

* w_m* = 425 (:data:`OMEGA_M_STAR_MAX`): the largest interference JGM computed (section 3.3);
  ``extrapolate=True`` lifts it;
* a/R = 1: the Jackson-Green law ends (eq 12 needs 0 < a/R < 1); its w* comes from
  :func:`fastrest.contact.omega_star_limit_kernel`;
* the end of the unloading model (``OMEGA_END`` of its unit in :mod:`fastrest.unloading`: JCG's
  eq 35 at w_m* = 10017.5, where w_res reaches w_m; the others never end).

Speed limits follow through the energy balance, V1*^2 = F(w_m*) (eq 29). Kernels return NaN past a
limit; the Python layer raises through the functions below.
"""
from __future__ import annotations

from typing import Any
import math
from typing import NamedTuple

import numpy as np

from ._deprecation import alias, module_getattr
from ._jit import jit
from ._validation import OMEGA_M_STAR_MAX, check_bool, check_eps_y, check_nu, real_scalar
from .contact import past_law_end
from .loading.jackson_green import omega_star_limit_kernel
from .energy import f_star_kernel
from . import loading as _loading
from . import unloading as _unloading

__all__ = ["OMEGA_M_STAR_MAX", "Limit", "limit"]

EXTRAPOLATE_HINT = "Pass extrapolate=True to compute beyond it (up to a/R = 1) with the same formulas"


@jit
def w_upper(eps_y, nu, extrapolate, law, et_ratio):
    """Largest w* of loading law ``law``: 425, or with extrapolation the law's end (a/R = 1);
    NaN for an invalid law/et_ratio."""
    lim = _loading.omega_end(law, eps_y, nu, et_ratio)
    if extrapolate:
        return lim
    return min(OMEGA_M_STAR_MAX, lim)


@jit
def w_upper_model(eps_y, nu, extrapolate, model, law, et_ratio):
    """:func:`w_upper`, and no further than unloading model ``model`` is defined (NaN if unknown)."""
    end = _unloading.omega_end(model)
    lim = w_upper(eps_y, nu, extrapolate, law, et_ratio)
    if not (end > 0.0 and lim >= 0.0):  # lim: NaN for an invalid law, 0 where a/R = 1 at once
        return np.nan
    return min(lim, end)


def _code(unloading):
    return -1 if unloading is None else _unloading.get(unloading).code


class Limit(NamedTuple):
    """The largest impact a material allows, as an interference and as a speed (:func:`limit`).

    Parameters
    ----------
    omega_m_star : float
        Largest maximum interference w_m* = omega_m/omega_c (-).
    v1_star : float
        Largest impact speed V1* = V1/V_c (-) (``inf`` if the law never ends).

    Examples
    --------
    >>> import fastrest
    >>> w, v = fastrest.limit(0.005, 0.33)  # a named tuple
    >>> w, round(v, 2)
    (425.0, 1022.39)
    """

    #: Largest maximum interference w_m* = omega_m/omega_c (-).
    omega_m_star: float
    #: Largest impact speed V1* = V1/V_c (-), with V1*^2 = F(w_m*) (JGM eq 29); ``inf`` if none.
    v1_star: float


def limit(eps_y: float, nu: float, unloading: str | None = None, *, extrapolate: bool = False,
          et_ratio: float = 0.0, loading: str | None = None) -> Limit:
    """Where the model ends for one material: the largest w_m* and the largest V1* it accepts.

    The one function for the model's limits. (:func:`fastrest.omega_star_limit` is the contact
    law's own end, a/R = 1, one of the limits this combines; :meth:`fastrest.Impact.V_max` is
    ``limit(...).v1_star`` of an impact in m/s.)

    Parameters
    ----------
    eps_y : float
        Sy/E' (-), finite and > 0.
    nu : float
        Poisson's ratio of the yielding material (-), 0 <= nu < 0.5.
    unloading : {"jcg", "etsion", "brake"} or None, optional
        An unloading model: no further than it is defined (JCG's eq 35 ends at w_m* = 10017.5,
        which matters only with ``extrapolate=True``). None (default): the loading law alone.
    extrapolate : bool, optional
        False (default): no further than w_m* = 425 (JGM section 3.3). True: up to a/R = 1 (eq 12).
    et_ratio : float, optional
        Tangent modulus over Young's modulus Et/E (-), 0 <= et_ratio < 1; default 0.
    loading : {None, "jackson-green", "ghaednia"}, optional
        The loading law (:func:`fastrest.P_star`); None picks it from ``et_ratio``. Both laws end
        at the same w* (docs/model.md section 12); the speed that reaches it differs.

    Returns
    -------
    Limit
        ``(omega_m_star, v1_star)``: the smallest of 425 (unless extrapolating), the w* where
        a/R = 1 and the unloading model's end (-); and the speed that reaches it (-), through the
        energy balance V1*^2 = F(w_m*) (JGM eq 29).

    Raises
    ------
    TypeError
        ``eps_y`` or ``nu`` is not a real number, or ``extrapolate`` is not True or False.
    ValueError
        ``eps_y`` or ``nu`` out of range, or an unknown ``unloading``.

    Notes
    -----
    The limits of docs/model.md section 4: w_m* = 425 (JGM section 3.3), a/R = 1 where the hardness
    of JGM eq (12) ends (:func:`fastrest.omega_star_limit`), and ``OMEGA_END`` of the unloading
    model (:mod:`fastrest.unloading`); the speed from the loading energy F of JGM eqs (19), (25)
    (:func:`fastrest.loading_energy`).

    Examples
    --------
    >>> import fastrest
    >>> lim = fastrest.limit(0.005, 0.33)
    >>> lim.omega_m_star, round(lim.v1_star, 2)
    (425.0, 1022.39)
    >>> round(fastrest.limit(0.005, 0.33, extrapolate=True).omega_m_star, 4)  # a/R = 1
    1994.4444
    >>> round(fastrest.limit(0.0005, 0.33, "jcg", extrapolate=True).omega_m_star, 4)  # end of eq (35)
    10017.5236
    """
    w = interference_limit(eps_y, nu, extrapolate=extrapolate, unloading=unloading, et_ratio=et_ratio,
                           loading=loading)  # validates
    return Limit(w, _speed_at(w, eps_y, nu, et_ratio, loading))


def _law(loading, et_ratio):
    h = real_scalar(et_ratio, "et_ratio")
    return _loading.resolve(loading, h), h


def interference_limit(eps_y, nu, *, extrapolate=False, unloading=None, et_ratio=0.0, loading=None):
    """``limit(...).omega_m_star`` without the speed (for fastrest's own callers): validates, and
    returns the largest w_m* (a float)."""
    e, n = real_scalar(eps_y, "eps_y"), real_scalar(nu, "nu")
    check_eps_y(e)
    check_nu(n)
    x = check_bool(extrapolate, "extrapolate")
    law, h = _law(loading, et_ratio)
    return float(w_upper(e, n, x, law.code, h) if unloading is None
                 else w_upper_model(e, n, x, _code(unloading), law.code, h))


def speed_limit(eps_y, nu, *, extrapolate=False, unloading=None, et_ratio=0.0, loading=None):
    """``limit(...).v1_star`` (for fastrest's own callers): validates, and returns the largest V1*."""
    w = interference_limit(eps_y, nu, extrapolate=extrapolate, unloading=unloading, et_ratio=et_ratio,
                           loading=loading)  # validates
    return _speed_at(w, eps_y, nu, et_ratio, loading)


def _speed_at(w, eps_y, nu, et_ratio=0.0, loading=None):
    law, h = _law(loading, et_ratio)
    return math.sqrt(f_star_kernel(w, float(eps_y), float(nu), law.code, h)) if w < math.inf else math.inf


__getattr__ = module_getattr(__name__)
alias(__name__, "omega_limit", "fastrest.limit(eps_y, nu, ...).omega_m_star", lambda: interference_limit)
alias(__name__, "v1_star_limit", "fastrest.limit(eps_y, nu, ...).v1_star", lambda: speed_limit)


def _past_law(lead, e, n, w_ar, at):
    return ValueError(f"{lead} {past_law_end(e, n, w_ar)}{at}")


def raise_out_of_range(v, eps_y, nu, extrapolate, name="v1_star", unloading=None, V_c=None,
                       hint=EXTRAPOLATE_HINT, et_ratio=0.0, loading=None):
    """Raise the ValueError for the first impact speed beyond the allowed range.

    The one place that says which limit applies (w_m* = 425, a/R = 1, the end of the unloading
    model). ``v``: speeds in the caller's unit, V1* or, with ``V_c`` (m/s), V1 in m/s; ``name``:
    the caller's parameter they came from (e.g. ``v_max``); ``hint`` ends the w_m* = 425 message.
    """
    v, e, n = float(np.ravel(v)[0]), float(np.ravel(eps_y)[0]), float(np.ravel(nu)[0])
    h = float(np.ravel(et_ratio)[0])
    lead = f"{name} = {v!r}" if V_c is None else f"{name} = {v!r} m/s"
    law = dict(et_ratio=h, loading=loading)
    hard = f", et_ratio = {h!r}" if h > 0.0 else ""  # hardening moves the speed limits

    def at(v_star):
        return f"V1* = {v_star:.10g}" if V_c is None else f"V1 = {v_star * V_c:.10g} m/s (V1* = {v_star:.6g})"

    w_ar = float(omega_star_limit_kernel(e, n))
    if unloading is not None:
        model = _unloading.get(unloading)
        if model.omega_end < w_ar and (extrapolate or model.omega_end < OMEGA_M_STAR_MAX):
            lim = speed_limit(e, n, extrapolate=extrapolate, unloading=model, **law)
            if (v if V_c is None else v / V_c) > lim:
                raise ValueError(
                    f"{lead} is past the end of {model.short} unloading ({model.equation}) for "
                    f"eps_y = {e!r}, nu = {n!r}: its w_res reaches w_m at w_m* = {model.omega_end:.6g}, "
                    f"i.e. {at(lim)}, and e is undefined beyond (other unloading models go on to a/R = 1)")
    if extrapolate or w_ar <= OMEGA_M_STAR_MAX:
        raise _past_law(lead, e, n, w_ar, f", i.e. {at(speed_limit(e, n, extrapolate=True, **law))}")
    raise ValueError(
        f"{lead} gives w_m* > {OMEGA_M_STAR_MAX:g}, the model's limit (JGM section 3.3); "
        f"for eps_y = {e!r}, nu = {n!r}{hard} that limit is {at(speed_limit(e, n, **law))}. {hint}")


def interference_limit_message(w, eps_y, nu, extrapolate, unloading=None):
    """What an interference w* beyond the allowed range is past: the end of the unloading model,
    a/R = 1, or w* = 425 (with the hint to extrapolate). A phrase: "is past the end of ..."."""
    w, e, n = float(np.ravel(w)[0]), float(np.ravel(eps_y)[0]), float(np.ravel(nu)[0])
    w_ar = float(omega_star_limit_kernel(e, n))
    if unloading is not None:
        model = _unloading.get(unloading)
        if w > model.omega_end and model.omega_end < w_ar:
            return (f"is past the end of {model.short} unloading ({model.equation}): its w_res "
                    f"reaches w_m at w* = {model.omega_end:.6g}")
    if extrapolate or w_ar <= OMEGA_M_STAR_MAX or w >= w_ar:
        return past_law_end(e, n, w_ar)
    return (f"is beyond w* = {OMEGA_M_STAR_MAX:g}, the largest interference the model covers (JGM "
            f"section 3.3); pass extrapolate=True to go up to a/R = 1 (w* = {w_ar:.6g}) with the same formulas")


def raise_interference_out_of_range(w, eps_y, nu, extrapolate, name="w", unloading=None):
    """Raise the ValueError for an interference w* = omega/omega_c beyond the allowed range (the APIs
    that take w* directly: the loading law, the forward map, the contact law)."""
    raise ValueError(f"{name} = {float(np.ravel(w)[0])!r} "
                     + interference_limit_message(w, eps_y, nu, extrapolate, unloading))
