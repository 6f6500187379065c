"""Weir & Tallon (2005) and Johnson (1985), JGM eq (3).

.. [WT] G. Weir, S. Tallon, "The coefficient of restitution for normal incident, low velocity
   particle impacts", Chem. Eng. Sci. 60 (2005) 3637.
.. [J] K.L. Johnson, Contact Mechanics, Cambridge University Press (1985).
"""
from __future__ import annotations

from typing import Any
from numpy.typing import ArrayLike, NDArray
import math

import numpy as np

from .._validation import broadcast_named, check_bool, check_finite_positive, check_velocity
from ..materials import poisson_factor
from .._doc import doc
from ._common import MODEL_DOC, finite_out, refuse_zero_speed, v_star_inputs

__all__ = ["weir_tallon", "johnson", "weir_tallon_unit_velocity", "weir_tallon_normalised"]


def _radius_ratio(R1, R):
    if R1 is None and R is None:
        return np.float64(1.0)
    if R is None:
        raise ValueError("R (m) is required when R1 is given (eq 3 uses the ratio R1/R)")
    R = check_finite_positive(R, "R", "(m)")
    R1 = R if R1 is None else check_finite_positive(R1, "R1", "(m)")
    return R1 / R


@doc(MODEL_DOC)
def weir_tallon(V1: ArrayLike, Sy: ArrayLike, E_eff: ArrayLike, rho: ArrayLike, R1: float | None = None, R: float | None = None, *,
                cap: bool = False) -> float | NDArray[np.float64]:
    """Coefficient of restitution of Weir & Tallon (2005) [WT]_, JGM eq (3), in SI units.

    .. math::

        e = 3.1 \\left(\\frac{S_y}{E'}\\right)^{5/8} \\left(\\frac{R_1}{R}\\right)^{3/8}
            \\left(\\sqrt{\\frac{E'}{\\rho}}\\,\\frac{1}{V_1}\\right)^{1/4}

    With R1 = R (the default, a sphere on a flat) this is Johnson's (1985) simplified
    fully-plastic model [J]_ (see :func:`johnson`).

    Below its own unit-e speed: eq (3) is a high-speed (fully plastic) power law with no yield
    velocity of its own. By default the formula is returned as printed for every V1: it exceeds 1
    for V1 < :func:`weir_tallon_unit_velocity` (the speed where it equals 1, about 17 V_c for the
    JGM Table 1 material, much larger than any yield velocity, as JGM note under Figs 7-8). At V1 = 0
    it is infinite: ValueError (with ``cap=True``, 1). Pass ``cap=True`` to get min(1, e) instead;
    this is an explicit choice of the caller, never applied silently.

    Radii: JGM print (R1/R)^(3/8) without defining R1 beyond "R1 = R is the current case". The
    formula depends on rho and the radii only through the mass of the impacting body; a Johnson-type
    energy argument with m = (4/3) pi rho R1^3 and contact radius R gives (R/R1)^(3/8), the
    reciprocal of the printed factor, and this could not be checked against [WT]_. The printed
    form is implemented; for R1 = R the question does not arise. :func:`~fastrest.models.evaluate` uses R1 = R = R'
    and the mass-equivalent density rho = 3 m / (4 pi R'^3), which makes the result depend on
    the impact's mass and R' exactly as Johnson's derivation requires.

    Parameters
    ----------
    V1 : float or array_like
        Impact speed (m/s), finite and >= 0.
    Sy : float or array_like
        Yield strength of the yielding material (Pa), finite and > 0.
    E_eff : float or array_like
        Combined elastic modulus E' (Pa), JGM section 2.1; finite and > 0.
    rho : float or array_like
        Density of the impacting sphere (kg/m^3), finite and > 0.
    R1 : float or array_like, optional
        Radius R1 of eq (3) (m); defaults to R.
    R : float or array_like, optional
        Radius R of eq (3), JGM's equivalent radius (m). If both radii are omitted, R1/R = 1.
    cap : bool, optional
        If True return min(1, e) (documented cap); default False returns the formula.

    {returns_e}
    ValueError
        V1 negative or not finite (V1 = 0 without ``cap``), Sy, E_eff, rho or a radius not finite and > 0, R1 given without R, or shapes that do not broadcast (the message names the parameter).

    Notes
    -----
    JGM eq (3) as printed, in SI units.

    Examples
    --------
    >>> from fastrest.models import weir_tallon
    >>> round(weir_tallon(1.0, 1e9, 2e11, 7800.0), 4), weir_tallon(0.01, 1e9, 2e11, 7800.0, cap=True)
    (0.9535, 1.0)
    """
    V1 = check_velocity(V1, "V1", "(m/s)")
    Sy = check_finite_positive(Sy, "Sy", "(Pa)")
    E_eff = check_finite_positive(E_eff, "E_eff", "(Pa)")
    rho = check_finite_positive(rho, "rho", "(kg/m^3)")
    cap = check_bool(cap, "cap")
    ratio = _radius_ratio(R1, R)
    broadcast_named((V1, "V1"), (Sy, "Sy"), (E_eff, "E_eff"), (rho, "rho"), (ratio, "R1/R"))
    if not cap:  # capped, e = 1 at V1 = 0 is the formula's limit
        refuse_zero_speed(V1, "V1", "Weir & Tallon's eq (3)")
    with np.errstate(all="ignore"):
        e = (3.1 * (Sy / E_eff) ** 0.625 * ratio ** 0.375
             * (np.sqrt(E_eff / rho) / V1) ** 0.25)
    if cap:
        e = np.minimum(e, 1.0)
    return finite_out(e, ("V1", V1), ("Sy", Sy), ("E_eff", E_eff), ("rho", rho))


@doc(MODEL_DOC)
def johnson(V1: ArrayLike, Sy: ArrayLike, E_eff: ArrayLike, rho: ArrayLike, *, cap: bool = False) -> float | NDArray[np.float64]:
    """Johnson's (1985) simplified fully-plastic impact model [J]_: JGM eq (3) with R1 = R.

    e = 3.1 (Sy/E')^(5/8) (sqrt(E'/rho) / V1)^(1/4). Identical to
    ``weir_tallon(V1, Sy, E_eff, rho)``; see :func:`weir_tallon` for the behaviour at low speed
    (the formula is returned, > 1 below :func:`weir_tallon_unit_velocity`, unless ``cap=True``).
    Note that this speed is not Johnson's yield velocity (``yield_velocity(impact, "johnson")``,
    JGM Table 2), which is about V_c.

    Parameters
    ----------
    V1 : float or array_like
        Impact speed (m/s), finite and >= 0.
    Sy : float or array_like
        Yield strength (Pa), finite and > 0.
    E_eff : float or array_like
        Combined modulus E' (Pa), finite and > 0.
    rho : float or array_like
        Density of the sphere (kg/m^3), finite and > 0.
    cap : bool, optional
        If True return min(1, e); default False.

    {returns_e}
    ValueError
        V1 negative or not finite (V1 = 0 without ``cap``), Sy, E_eff or rho not finite and > 0, or shapes that do not broadcast (the message names the parameter).

    Notes
    -----
    JGM eq (3) with R1 = R; Johnson (1985) section 11.5.

    Examples
    --------
    >>> from fastrest.models import johnson
    >>> round(johnson(1.0, 1e9, 2e11, 7800.0), 4)
    0.9535
    """
    return weir_tallon(V1, Sy, E_eff, rho, cap=cap)


def weir_tallon_unit_velocity(Sy: ArrayLike, E_eff: ArrayLike, rho: ArrayLike, R1: float | None = None,
                              R: float | None = None) -> float | NDArray[np.float64]:
    """Speed (m/s) at which JGM eq (3) equals 1: V = 3.1^4 (Sy/E')^(5/2) (R1/R)^(3/2) sqrt(E'/rho).

    This is the apparent "critical velocity" of Weir & Tallon's closed form [WT]_ that JGM contrast
    with their V_c (section 3.2, Figs 7-8); eq (3) exceeds 1 below it.

    Parameters
    ----------
    Sy : float or array_like
        Yield strength (Pa), finite and > 0.
    E_eff : float or array_like
        Combined modulus E' (Pa), finite and > 0.
    rho : float or array_like
        Density of the impacting sphere (kg/m^3), finite and > 0.
    R1, R : float or array_like, optional
        Radii of eq (3) (m), as in :func:`weir_tallon`; R1/R = 1 by default.

    Returns
    -------
    float or ndarray
        Speed in m/s.

    Raises
    ------
    TypeError
        An input is not real.
    ValueError
        Sy, E_eff, rho or a radius not finite and > 0, R1 given without R, or shapes that do not broadcast (the message names the parameter).

    Notes
    -----
    JGM eq (3) solved for e = 1.

    Examples
    --------
    >>> from fastrest.models import weir_tallon_unit_velocity
    >>> round(weir_tallon_unit_velocity(1e9, 2e11, 7800.0), 4)
    0.8267
    """
    Sy = check_finite_positive(Sy, "Sy", "(Pa)")
    E_eff = check_finite_positive(E_eff, "E_eff", "(Pa)")
    rho = check_finite_positive(rho, "rho", "(kg/m^3)")
    ratio = _radius_ratio(R1, R)
    broadcast_named((Sy, "Sy"), (E_eff, "E_eff"), (rho, "rho"), (ratio, "R1/R"))
    with np.errstate(all="ignore"):
        out = 3.1**4 * (Sy / E_eff) ** 2.5 * ratio**1.5 * np.sqrt(E_eff / rho)
    return finite_out(out, ("Sy", Sy), ("E_eff", E_eff), ("rho", rho))


@doc(MODEL_DOC)
def weir_tallon_normalised(v1_star: ArrayLike, eps_y: ArrayLike, nu: ArrayLike) -> float | NDArray[np.float64]:
    """JGM eq (3) with R1 = R (Johnson) in JGM's normalisation: e = 3.1 (40 pi)^(1/8) (pi C)^(-5/8) V1*^(-1/4).

    Derivation: for a sphere of density rho and radius R on a flat, m = (4/3) pi rho R^3, and
    JGM eqs (23), (28) give V_c^2 = (pi C Sy)^5 / (40 pi E'^4 rho), so
    sqrt(E'/rho) / V1 = sqrt(40 pi) (pi C eps_y)^(-5/2) / V1*. Substituting in eq (3), eps_y cancels
    exactly: e depends on V1* and nu only (e = 2.027 V1*^(-1/4) for nu = 0.33, i.e. e = 1 at
    V1* = 16.9). The same holds for any mass if rho is the mass-equivalent density 3 m/(4 pi R^3),
    as :func:`~fastrest.models.evaluate` uses. The formula is returned for all V1* > 0 (> 1 below the unit-e speed;
    V1* = 0, where it is infinite, raises ValueError); see :func:`weir_tallon`.

    Parameters
    ----------
    v1_star : float or array_like
        V1 / V_c, V_c of JGM eq (28); finite and >= 0 (dimensionless).
    eps_y : float or array_like
        Sy / E' (dimensionless), > 0. Validated and broadcast, but it cancels out.
    nu : float or array_like
        Poisson's ratio, 0 <= nu < 0.5 (dimensionless).

    {returns_e}
    ValueError
        v1_star = 0, negative or not finite, eps_y <= 0, nu outside [0, 0.5), or shapes that do not broadcast (the message names the parameter).

    Notes
    -----
    JGM eq (3) with R1 = R, normalised with JGM eqs (23), (28) as derived above.

    Examples
    --------
    >>> from fastrest.models import weir_tallon_normalised
    >>> round(weir_tallon_normalised(16.0, 0.005, 0.33), 4)
    1.0137
    """
    v, eps, nu = v_star_inputs(v1_star, eps_y=eps_y, nu=nu)
    refuse_zero_speed(v, "v1_star", "Weir & Tallon's eq (3)")
    C = np.asarray(poisson_factor(nu))
    e = 3.1 * (40.0 * math.pi) ** 0.125 * (math.pi * C) ** -0.625 * v**-0.25
    return finite_out(e, ("v1_star", v))
