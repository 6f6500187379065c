"""Loading laws: each one unit, registered here by name; every consumer asks the registry.

A law is a module of this package with

* ``NAME``, ``SHORT``, ``LABEL``, ``REFERENCE``: its public name and citation;
* ``W_SWITCH``: the w* up to which it is Hertz's (1.9 for both laws here, see below);
* ``HARDENING``: whether it takes the tangent modulus ratio Et/E (``et_ratio``; 0 otherwise);
* ``valid(et_ratio)``, ``p_star_above(w, eps_y, nu, C, B, et_ratio)`` (P* above the switch,
  with C = C(nu) and B = 0.14 exp(23 eps_y) precomputed), ``a_star_above(...)`` (A* = (a/a_c)^2
  above the switch) and ``omega_end(eps_y, nu, et_ratio)`` (the w* where it ends; NaN for an
  invalid et_ratio): ``@jit(inline=True)`` scalar kernels, compilable for the CUDA target.

To add a law: write its module and list it in :data:`_UNITS` and in the dispatchers below (its code
is its position). Python code names a law by string (``loading="ghaednia"``) and gets its
:class:`LoadingLaw` from :func:`get`; jitted code passes the integer code and ``et_ratio``, and an
unknown code or an invalid ``et_ratio`` gives NaN. Every law switches from Hertz at w* = 1.9 (the
energy module's closed forms below the switch, F = w^2.5, assume it): a law with another switch
would also need :mod:`fastrest.energy`'s ``F_SWITCH``/``V_SWITCH`` to ask the unit.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .._jit import jit
from numpy.typing import NDArray

from .._validation import OMEGA_STAR_SWITCH, as_float_array
from ..critical import c_of_nu
from . import ghaednia, jackson_green
from .jackson_green import area_exponent

__all__ = ["LoadingLaw", "LAWS", "NAMES", "JACKSON_GREEN", "GHAEDNIA", "get", "resolve"]

_UNITS = (jackson_green, ghaednia)
# Integer codes of the loading laws for jitted code: a law's code is its position in _UNITS.
#: Code of the Jackson-Green loading law (elastic-perfectly plastic, JGM eqs 8-15) in jitted code.
JACKSON_GREEN = 0
#: Code of Ghaednia et al.'s (2019) loading law (Jackson-Green with strain hardening) in jitted code.
GHAEDNIA = 1
N_LAWS = len(_UNITS)
for _u in _UNITS:  # the energy module's closed forms assume the one switch (see above)
    assert _u.W_SWITCH == OMEGA_STAR_SWITCH, _u.NAME


@dataclass(frozen=True)
class LoadingLaw:
    """A loading law as Python code sees it (the kernels live in its module).

    Built once per registered unit (:data:`LAWS`); get one with :func:`get`. Frozen; pickles.

    Parameters
    ----------
    name : str
        Public name (``loading=`` argument): ``"jackson-green"`` or ``"ghaednia"``.
    short : str
        Display name.
    code : int
        Integer passed to jitted kernels (:data:`JACKSON_GREEN`, :data:`GHAEDNIA`).
    label, reference : str
        What it is and where it comes from.
    hardening : bool
        Whether it takes the tangent modulus ratio ``et_ratio`` = Et/E (else ``et_ratio`` must be 0).

    Examples
    --------
    >>> from fastrest import loading
    >>> law = loading.get("ghaednia")
    >>> law.code, law.hardening
    (1, True)
    """

    name: str
    short: str
    code: int
    label: str
    reference: str
    hardening: bool


#: The registered laws by name, in code order.
LAWS = {u.NAME: LoadingLaw(u.NAME, u.SHORT, k, u.LABEL, u.REFERENCE, bool(u.HARDENING))
        for k, u in enumerate(_UNITS)}
#: Names of the loading laws (``"jackson-green"``, ``"ghaednia"``), in code order.
NAMES = tuple(LAWS)


def get(loading: str | LoadingLaw) -> LoadingLaw:
    """The registered :class:`LoadingLaw` called ``loading``.

    Parameters
    ----------
    loading : str or LoadingLaw
        A law name, one of :data:`NAMES`, or a law (returned as registered).

    Returns
    -------
    LoadingLaw

    Raises
    ------
    ValueError
        Anything else (the message lists the names).

    Examples
    --------
    >>> from fastrest import loading
    >>> loading.get("jackson-green").code == loading.JACKSON_GREEN
    True
    """
    if isinstance(loading, LoadingLaw):
        return LAWS[loading.name]
    if isinstance(loading, str) and loading in LAWS:
        return LAWS[loading]
    raise ValueError(f"loading must be one of {NAMES} or None; got {loading!r}")


def check_et_ratio(et_ratio: object, name: str = "et_ratio") -> NDArray[np.float64]:
    """Et/E as a float array, every value in [0, 1): TypeError for non-numbers, ValueError outside."""
    a = as_float_array(et_ratio, name)
    bad = ~((a >= 0.0) & (a < 1.0))  # also NaN
    if np.any(bad):
        v = float(a[bad].flat[0] if a.ndim else a)
        raise ValueError(f"{name} (tangent modulus over Young's modulus, Et/E) must be in [0, 1); got {v!r}")
    return a


def resolve(loading: str | LoadingLaw | None, et_ratio: object = 0.0, *, name: str = "et_ratio") -> LoadingLaw:
    """The law of a call: ``loading=None`` picks Jackson-Green where every Et/E is 0 and Ghaednia
    et al. (2019) otherwise (it equals Jackson-Green bit for bit at Et/E = 0); a law without
    hardening refuses Et/E > 0.

    Parameters
    ----------
    loading : str, LoadingLaw or None
        The law asked for, or None for the default.
    et_ratio : float or array_like
        Tangent modulus over Young's modulus Et/E (-), 0 <= et_ratio < 1.
    name : str
        The caller's name of ``et_ratio`` for messages (``Et`` for a :class:`fastrest.Material`).

    Returns
    -------
    LoadingLaw

    Raises
    ------
    TypeError
        ``et_ratio`` is not a real number or array of them.
    ValueError
        ``et_ratio`` outside [0, 1), an unknown law, or Et/E > 0 with a law without hardening.

    Examples
    --------
    >>> from fastrest import loading
    >>> loading.resolve(None, 0.0).name, loading.resolve(None, [0.0, 0.01]).name
    ('jackson-green', 'ghaednia')
    """
    h = check_et_ratio(et_ratio, name)
    hard = bool(np.any(h > 0.0))
    if loading is None:
        return LAWS[ghaednia.NAME if hard else jackson_green.NAME]
    law = get(loading)
    if hard and not law.hardening:
        raise ValueError(f"{name} = {float(h[h > 0].flat[0])!r}: the {law.name!r} loading law has no strain "
                         f"hardening (Et/E must be 0); use loading='ghaednia' or loading=None")
    return law


# --- the dispatchers: the one place that maps a code to its unit ----------------------------------

@jit(inline=True)
def valid(law, et_ratio):
    """True if ``law`` is a known code and accepts ``et_ratio``."""
    if law == JACKSON_GREEN:
        return jackson_green.valid(et_ratio)
    if law == GHAEDNIA:
        return ghaednia.valid(et_ratio)
    return False


@jit(inline=True)
def p_star_above(law, w, eps_y, nu, C, B, et_ratio):
    """P*(w) above the switch of law ``law`` (C, B precomputed; a/R not checked); NaN if unknown."""
    if law == JACKSON_GREEN:
        return jackson_green.p_star_above(w, eps_y, nu, C, B, et_ratio)
    if law == GHAEDNIA:
        return ghaednia.p_star_above(w, eps_y, nu, C, B, et_ratio)
    return np.nan


@jit(inline=True)
def a_star_above(law, w, eps_y, nu, C, B, et_ratio):
    """A*(w) above the switch of law ``law``; NaN if unknown."""
    if law == JACKSON_GREEN:
        return jackson_green.a_star_above(w, eps_y, nu, C, B, et_ratio)
    if law == GHAEDNIA:
        return ghaednia.a_star_above(w, eps_y, nu, C, B, et_ratio)
    return np.nan


@jit
def omega_end(law, eps_y, nu, et_ratio):
    """w* where law ``law`` ends (a/R = 1); NaN for an unknown code or an invalid et_ratio."""
    if law == JACKSON_GREEN:
        return jackson_green.omega_end(eps_y, nu, et_ratio)
    if law == GHAEDNIA:
        return ghaednia.omega_end(eps_y, nu, et_ratio)
    return np.nan


@jit
def p_star(law, w, eps_y, nu, et_ratio):
    """P*(w) of law ``law``: Hertz w^1.5 up to the switch, the law above; NaN for w < 0, past the
    law's end, or an invalid law/et_ratio."""
    if not (w >= 0.0 and valid(law, et_ratio)):
        return np.nan
    if w <= OMEGA_STAR_SWITCH:
        return w**1.5
    if not w < omega_end(law, eps_y, nu, et_ratio):
        return np.nan
    return p_star_above(law, w, eps_y, nu, c_of_nu(nu), area_exponent(eps_y), et_ratio)


@jit
def p_star_unchecked(law, w, eps_y, nu, et_ratio):
    """P*(w) without the end check (callers bound w themselves); NaN for an unknown law."""
    if w <= OMEGA_STAR_SWITCH:
        return w**1.5
    return p_star_above(law, w, eps_y, nu, c_of_nu(nu), area_exponent(eps_y), et_ratio)


@jit
def a_star(law, w, eps_y, nu, et_ratio):
    """A*(w) of law ``law``: Hertz A* = w up to the switch; NaN as :func:`p_star`."""
    if not (w >= 0.0 and valid(law, et_ratio)):
        return np.nan
    if w <= OMEGA_STAR_SWITCH:
        return w
    if not w < omega_end(law, eps_y, nu, et_ratio):
        return np.nan
    return a_star_above(law, w, eps_y, nu, c_of_nu(nu), area_exponent(eps_y), et_ratio)


@jit(inline=True)
def a_star_unchecked(law, w, eps_y, nu, et_ratio):
    """A*(w) without the end check. Inlined: Etsion's residual calls it inside contact_force, and a
    call left in the caller's force loop (even in its rarely taken unloading branch) made the loop
    ~5x slower (bench/FORCE_LAW.md)."""
    if w <= OMEGA_STAR_SWITCH:
        return w
    return a_star_above(law, w, eps_y, nu, c_of_nu(nu), area_exponent(eps_y), et_ratio)


