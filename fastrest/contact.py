"""Normalised Jackson-Green (2005) elastic-perfectly plastic contact law of a sphere on a rigid flat.

JGM 2010 eqs (8)-(15), normalised by the critical values of eqs (4)-(7): w = omega/omega_c,
P* = P/P_c, A* = A/A_c. For w <= 1.9 the Hertz solution is used (eqs 14-15); above, JG's fit:

    A* = w (w/1.9)^B,  B = 0.14 exp(23 eps_y)                          (8), (10)
    a/R = (pi C eps_y / 2) sqrt(A*)                                     (from a = sqrt(A/pi), eq 4)
    H_G/Sy = 2.84 - 0.92 (1 - cos(pi a/R)),  valid for 0 < a/R < 1     (12)
    P* = exp(-w^(5/12)/4) w^1.5 + 4 (H_G/Sy)/C (1 - exp(-w^(5/9)/25)) w (9)

P* depends on nu only through C(nu) = 1.295 exp(0.736 nu) (5). P* jumps by about -0.16 % at
w = 1.9; integrals are split there. Past a/R = 1 the law is undefined: kernels return NaN and the
Python wrappers raise.

Kernels are plain compiled functions of floats (``fastrest._jit.jit``); the public functions below
validate and broadcast.
"""
from __future__ import annotations

from typing import Any
from numpy.typing import ArrayLike, NDArray

import numpy as np

from ._doc import doc, paragraphs
from ._jit import jit
from ._validation import broadcast_inputs, check_eps_y, check_finite_result, check_nu, shaped
from . import loading as _loading
from .loading.jackson_green import omega_star_limit_kernel


__all__ = ["P_star", "A_star", "omega_star_limit"]


#: The parameters and Raises of every function of a loading law evaluated at w
#: (:func:`evaluate_law`: :func:`P_star`, :func:`A_star`, :func:`fastrest.loading_energy`,
#: :func:`fastrest.W_star`), written once (fastrest._doc).
LAW_DOC = paragraphs(
    law_params="""
        Parameters
        ----------
        w : float or array_like
            Normalised interference omega/omega_c (-), >= 0 and below the point where a/R = 1
            (:func:`fastrest.omega_star_limit`; not limited to w* = 425).
        eps_y : float or array_like
            Sy/E' (-), > 0 (validated range 0.0005-0.01).
        nu : float or array_like
            Poisson's ratio of the yielding material, 0 <= nu < 0.5.
        et_ratio : float or array_like, optional
            Tangent modulus over Young's modulus Et/E (-), 0 <= et_ratio < 1; 0 (default) is
            elastic-perfectly plastic. Above 0 the law is Ghaednia et al. (2019)
            (:mod:`fastrest.loading.ghaednia`).
        loading : {None, "jackson-green", "ghaednia"}, optional
            The loading law (:mod:`fastrest.loading`); None picks Jackson-Green where every
            ``et_ratio`` is 0 and Ghaednia et al. otherwise (equal bit for bit at 0).
        """,
    law_raises="""
        Raises
        ------
        TypeError
            An input is not a real number or array of them (strings, booleans, None, complex).
        ValueError
            w negative, NaN or infinite, or at or past the point where a/R = 1 (the message gives that
            w*); eps_y not finite and > 0; nu outside [0, 0.5) or NaN; et_ratio outside [0, 1); an
            unknown ``loading``, or et_ratio > 0 with ``loading="jackson-green"``; shapes that do not
            broadcast.
        """,
)


@jit
def _p_star_array(w, eps_y, nu, et_ratio, law, out):
    for i in range(w.size):
        out[i] = _loading.p_star(law, w[i], eps_y[i], nu[i], et_ratio[i])


@jit
def _a_star_array(w, eps_y, nu, et_ratio, law, out):
    for i in range(w.size):
        out[i] = _loading.a_star(law, w[i], eps_y[i], nu[i], et_ratio[i])


def check_omega(w, eps_y, nu, name="w"):
    """Raise ValueError for w < 0 / NaN, or where a/R >= 1 (JG eq 12 undefined)."""
    bad = ~(np.isfinite(w) & (w >= 0))
    if np.any(bad):
        raise ValueError(f"{name} (normalised interference omega/omega_c) must be finite and >= 0; "
                         f"got {float(w[bad][0])!r}")
    lim = np.array([omega_star_limit_kernel(e, n) for e, n in zip(eps_y, nu)]) if w.size else w
    past = w >= lim
    if np.any(past):
        i = int(np.flatnonzero(past)[0])
        e, n = float(eps_y[i]), float(nu[i])
        raise ValueError(f"{name} = {float(w[i])!r} {past_law_end(e, n, float(omega_star_limit_kernel(e, n)))}")


def past_law_end(eps_y, nu, w_ar):
    """The phrase for a point past this law's end, a/R = 1 at w* = ``w_ar`` (its
    :func:`omega_star_limit_kernel`): "is past the end of the Jackson-Green law ...". Written once
    here, where the law ends; :mod:`fastrest.limits` words the model's other limits around it."""
    return (f"is past the end of the Jackson-Green law (a/R = 1, eq 12) for eps_y = {eps_y!r}, nu = {nu!r}: "
            f"a/R reaches 1 at w* = {w_ar:.6g}")


def evaluate_law(kernel, w, eps_y, nu, et_ratio=0.0, loading=None):
    """Validate (w, eps_y, nu, et_ratio) and the law, broadcast them, and fill the output with
    ``kernel(w, eps_y, nu, et_ratio, law_code, out)``."""
    (w, eps_y, nu, h), shape = broadcast_inputs((w, "w"), (eps_y, "eps_y"), (nu, "nu"), (et_ratio, "et_ratio"))
    check_eps_y(eps_y)
    check_nu(nu)
    law = _loading.resolve(loading, h)
    check_omega(w, eps_y, nu)
    out = np.empty_like(w)
    kernel(w, eps_y, nu, h, law.code, out)
    return shaped(out, shape)


@doc(LAW_DOC)
def P_star(w: ArrayLike, eps_y: ArrayLike, nu: ArrayLike, *, et_ratio: ArrayLike = 0.0,
           loading: str | None = None) -> float | NDArray[np.float64]:
    """Normalised contact force P* = P/P_c of the loading law (JG: JGM eqs 9, 14).

    {law_params}

    Returns
    -------
    float or ndarray
        P* (-), broadcast over the inputs (a float if all are scalars).

    {law_raises}

    Notes
    -----
    Hertz P* = w^1.5 for w <= 1.9 (JGM eq 14), the Jackson-Green (2005) fit above (eq 9, with the
    hardness of eq 12 and the area of eqs 8, 10); P* jumps by about -0.16 % at w = 1.9
    (docs/model.md section 3). With hardening, Ghaednia et al. (2019) blend it towards Hertz
    (docs/model.md section 12); the law ends where JG's does. No ValidityWarning: this is the law
    itself, evaluated wherever it is defined.

    Examples
    --------
    >>> import fastrest
    >>> round(fastrest.P_star(10.0, 0.005, 0.33), 6)
    25.647583
    >>> fastrest.P_star([1.0, 1.9], 0.005, 0.33).round(6)  # Hertz side of the switch
    array([1.      , 2.618969])
    >>> round(fastrest.P_star(10.0, 0.005, 0.33, et_ratio=0.01), 6)  # Ghaednia et al., Et = E/100
    25.842654
    """
    return evaluate_law(_p_star_array, w, eps_y, nu, et_ratio, loading)


@doc(LAW_DOC)
def A_star(w: ArrayLike, eps_y: ArrayLike, nu: ArrayLike, *, et_ratio: ArrayLike = 0.0,
           loading: str | None = None) -> float | NDArray[np.float64]:
    """Normalised contact area A* = A/A_c of the loading law (JG: JGM eqs 8, 15) (-).

    Hertz A* = w for w <= 1.9 (JGM eq 15), the Jackson-Green (2005) fit A* = w (w/1.9)^B with
    B = 0.14 exp(23 eps_y) above (eqs 8, 10).

    {law_params}

    Returns
    -------
    float or ndarray
        A* (-), broadcast over the inputs (a float if all are scalars); continuous at w = 1.9.

    {law_raises}

    Examples
    --------
    >>> import fastrest
    >>> round(fastrest.A_star(10.0, 0.005, 0.33), 6)
    12.980177
    >>> fastrest.A_star([1.0, 1.9], 0.005, 0.33).tolist()  # Hertz up to w = 1.9
    [1.0, 1.9]
    """
    return evaluate_law(_a_star_array, w, eps_y, nu, et_ratio, loading)


def omega_star_limit(eps_y: ArrayLike, nu: ArrayLike) -> float | NDArray[np.float64]:
    """Normalised interference w* at which the contact radius reaches the sphere's (a/R = 1) (-).

    The Jackson-Green law ends there: its hardness (JGM eq 12) is stated for 0 < a/R < 1. This is
    the contact law's own end (the domain of :func:`P_star`, :func:`A_star`), one of the three
    limits of the impact model: for the largest w_m* and V1* an impact may reach, use
    :func:`fastrest.limit`.

    Parameters
    ----------
    eps_y : float or array_like
        Sy/E' (-), > 0.
    nu : float or array_like
        Poisson's ratio of the yielding material, 0 <= nu < 0.5.

    Returns
    -------
    float or ndarray
        w* at a/R = 1 (-), broadcast over the inputs. It lies below w* = 425 (the model's range)
        when eps_y is above about 0.0114 (nu = 0.33).

    Raises
    ------
    TypeError
        An input is not a real number or array of them.
    ValueError
        eps_y not finite and > 0; nu outside [0, 0.5) or NaN; shapes that do not broadcast; or an
        eps_y so small that w* overflows double precision (e.g. 1e-300).

    Notes
    -----
    Solves a/R = (pi C eps_y / 2) sqrt(A*(w)) = 1 in closed form, with A* of eq (8) (or A* = w on
    the Hertz branch) and C of eq (5). :func:`fastrest.limit` combines it with
    w* = 425 and the unloading model's end.

    Examples
    --------
    >>> import fastrest
    >>> round(fastrest.omega_star_limit(0.005, 0.33), 4)
    1994.4444
    >>> round(fastrest.omega_star_limit(0.01, 0.33), 4)
    548.0114
    """
    (eps_y, nu), shape = broadcast_inputs((eps_y, "eps_y"), (nu, "nu"))
    check_eps_y(eps_y)
    check_nu(nu)
    out = np.array([omega_star_limit_kernel(e, n) for e, n in zip(eps_y, nu)], dtype=np.float64)
    # a/R = (pi/2) C eps_y sqrt(A*) reaches 1 only at w* beyond double precision for tiny eps_y
    check_finite_result(out, "the w* where a/R = 1", [("eps_y", eps_y)])
    return shaped(out, shape)
