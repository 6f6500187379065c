"""Chang & Ling (1992), from the CEB contact model (Chang, Etsion & Bogy 1987): JGM eq (1).

.. [CL] W.R. Chang, F.F. Ling, "Normal impact model of rough surfaces", ASME J. Tribol. 114 (1992)
   439-447.
.. [CEB] W.R. Chang, I. Etsion, D.B. Bogy, "An elastic-plastic model for the contact of rough
   surfaces", ASME J. Tribol. 109 (1987) 257-263.
"""
from __future__ import annotations

from typing import TYPE_CHECKING, Any
from numpy.typing import ArrayLike, NDArray
if TYPE_CHECKING:
    from ..impact import Impact
import math

import numpy as np

from .._validation import check_nu, check_velocity
from ..materials import poisson_factor
from .._doc import doc
from ._common import MODEL_DOC, check_impact, finite_out, v_star_inputs

__all__ = ["ceb_hardness_factor", "chang_ling", "chang_ling_dimensional"]


def ceb_hardness_factor(nu: ArrayLike) -> float | NDArray[np.float64]:
    """Mean contact pressure of the CEB model in units of Sy: K H / Sy = 2.8 (0.454 + 0.41 nu).

    Chang, Etsion & Bogy (1987) [CEB]_: hardness H = 2.8 Sy and hardness factor
    K = 0.454 + 0.41 nu; K H is the mean pressure of a plastically deformed contact and the maximum
    Hertz pressure at CEB's onset of yield. Used by JGM eq (1).

    JGM print eq (1) with pi (1.282 + 1.158 nu) Sy, i.e. K H = (1.282 + 1.158 nu) Sy, which is
    0.86 % above 2.8 (0.454 + 0.41 nu) = 1.2712 + 1.148 nu (as if H = 2.824 Sy). This module uses
    CEB's own constants.

    Parameters
    ----------
    nu : float or array_like
        Poisson's ratio of the yielding material, 0 <= nu < 0.5 (dimensionless).

    Returns
    -------
    float or ndarray
        K H / Sy (dimensionless).

    Raises
    ------
    TypeError
        An input is not real.
    ValueError
        nu outside [0, 0.5), or shapes that do not broadcast (the message names the parameter).

    Notes
    -----
    CEB (1987): H = 2.8 Sy, K = 0.454 + 0.41 nu; JGM eq (1) prints K H = (1.282 + 1.158 nu) Sy.

    Examples
    --------
    >>> from fastrest.models import ceb_hardness_factor
    >>> round(ceb_hardness_factor(0.3), 4)
    1.6156
    """
    nu = check_nu(nu)
    return finite_out(2.8 * (0.454 + 0.41 * nu))


_CL_CRITICAL = ("ceb", "jgm")


def _cl_params(nu, critical):
    """Return (r, s_per_v): e = (1 + (16/15) r (s^2 - 1))^(3/8) / s with s = v1_star * s_per_v."""
    if critical not in _CL_CRITICAL:
        raise ValueError(f"critical must be one of {_CL_CRITICAL}; got {critical!r}")
    C = np.asarray(poisson_factor(nu))
    k = np.asarray(ceb_hardness_factor(nu))
    if critical == "ceb":
        return np.ones_like(C), (C / k) ** 2.5
    return C / k, np.ones_like(C)


def _cl_e(s, r):
    """Normalised Chang-Ling e(s), s = V1 / V_onset; e = 1 for s <= 1.

    Evaluated as s^(-1/4) (k + (1 - k)/s^2)^(3/8), k = (16/15) r, the same expression divided by
    s^(3/4) inside and out: s^2 does not overflow for large s (V1* = 1e160 gave inf).
    """
    plastic = s > 1.0
    s_safe = np.where(plastic, s, 1.0)
    k = (16.0 / 15.0) * r
    with np.errstate(under="ignore"):
        e = s_safe**-0.25 * (k + (1.0 - k) / s_safe / s_safe) ** 0.375
    return np.where(plastic, e, 1.0)


@doc(MODEL_DOC)
def chang_ling(v1_star: ArrayLike, eps_y: ArrayLike, nu: ArrayLike, *, critical: str = "ceb") -> float | NDArray[np.float64]:
    """Coefficient of restitution of Chang & Ling (1992) [CL]_, from the CEB model, JGM eq (1).

    Derivation (dimensional form: :func:`chang_ling_dimensional`). CEB [CEB]_: for
    omega <= omega_c the contact is Hertzian, P = (4/3) E' sqrt(R) omega^(3/2); for omega > omega_c
    it is plastic with area A = pi R (2 omega - omega_c) and mean pressure K H,
    K H = 2.8 (0.454 + 0.41 nu) Sy (:func:`ceb_hardness_factor`). CEB's critical interference is
    its own, omega_c,CEB = (pi K H / (2 E'))^2 R (maximum Hertz pressure = K H); JGM's eq (4) has
    C(nu) Sy in place of K H (K H / (C Sy) is within 0.15 % of 1 for 0.2 <= nu <= 0.35, 0.87 % below
    at nu = 0.45, 1.8 % below at nu = 0).

    * Loading (denominator of eq 1 = (1/2) m V1^2): Hertz energy up to omega_c plus the plastic
      work, (8/15) E' sqrt(R) omega_c^(5/2) + pi K H R omega_m (omega_m - omega_c).
    * Unloading (numerator, elastic rebound energy): as printed, [omega_c omega_m (2 -
      omega_c/omega_m)]^(3/2) has units m^3.5 and cannot be right. The reading used here is
      (8/15) E' sqrt(R) omega_c [omega_m (2 - omega_c/omega_m)]^(3/2)
      = U_c (a_m / a_c)^3, a_m^2 = R (2 omega_m - omega_c) being CEB's contact radius: the elastic
      energy released by a contact of radius a at a fixed mean pressure scales as a^3 and equals
      the Hertz energy U_c at the onset. It is dimensionally consistent and gives e = 1 exactly at
      omega_m = omega_c (the alternative exponent 5/4 on the printed bracket is also consistent but
      has no such interpretation). "(omega_c)^{5.2}" in the denominator is read as omega_c^(5/2).

    Normalised with u = omega_m / omega_c and U_c = (8/15) E' sqrt(R) omega_c^(5/2), using
    pi K H R = 2 E' sqrt(R omega_c) (CEB's omega_c): s^2 = 1 + (15/4) u (u - 1) and
    e^2 = (2u - 1)^(3/2) / s^2, s = V1 / V_c,CEB, hence the closed form

    .. math::

        e = \\frac{\\left[1 + \\tfrac{16}{15}(s^2 - 1)\\right]^{3/8}}{s},\\quad
        s = V_1^* \\left(\\frac{C(\\nu)}{K H / S_y}\\right)^{5/2}\\quad (s > 1),

    and e = 1 for s <= 1 (V1* <= (K H/(C Sy))^(5/2), CEB's onset). e is continuous at the onset,
    and e ~ (16/15)^(3/8) s^(-1/4) = 1.0245 s^(-1/4) at high speed. eps_y cancels exactly (so do R
    and m): in this reading the CL curve of JGM Fig 5 does not change with eps_y at all (JGM write
    that it "changes fairly little").
    u is obtained from V1* in closed form: 2u - 1 = sqrt(1 + (16/15)(s^2 - 1)).

    With ``critical="jgm"`` the CEB law is used with JGM's omega_c (eq 4) instead; then
    s = V1*, and the plastic-work term carries r = C/(K H/Sy): e = [1 + (16/15)(C/(K H/Sy))(V1*^2 - 1)]^(3/8) / V1*.

    The mean pressure printed in JGM eq (1), (1.282 + 1.158 nu) Sy, is 0.86 % above CEB's
    2.8 (0.454 + 0.41 nu) Sy; CEB's constants are used (:func:`ceb_hardness_factor`).

    Parameters
    ----------
    v1_star : float or array_like
        V1 / V_c, V_c of JGM eq (28); finite and >= 0 (dimensionless).
    eps_y : float or array_like
        Sy / E' (dimensionless), > 0; validated and broadcast, cancels out (see above).
    nu : float or array_like
        Poisson's ratio of the yielding material, 0 <= nu < 0.5 (dimensionless).
    critical : {"ceb", "jgm"}, optional
        Critical interference of the CEB law: CEB's own (default) or JGM eq (4).

    {returns_e}
    ValueError
        v1_star negative or not finite, eps_y <= 0, nu outside [0, 0.5), an unknown ``critical``, or shapes that do not broadcast (the message names the parameter).

    Notes
    -----
    JGM eq (1), read as derived above.

    Examples
    --------
    >>> from fastrest.models import chang_ling
    >>> chang_ling(0.5, 0.005, 0.3), round(chang_ling(10.0, 0.005, 0.3), 4)
    (1.0, 0.5761)
    """
    v, eps, nu = v_star_inputs(v1_star, eps_y=eps_y, nu=nu)
    r, s_per_v = _cl_params(nu, critical)
    return finite_out(_cl_e(v * s_per_v, r), ("v1_star", v))


@doc(MODEL_DOC)
def chang_ling_dimensional(impact: Impact, V1: ArrayLike, *, critical: str = "ceb") -> float | NDArray[np.float64]:
    """Chang & Ling (1992) e for an :class:`~fastrest.Impact` at speed V1 (m/s): JGM eq (1) in SI units.

    Evaluates eq (1) term by term, with the reading and constants documented in
    :func:`chang_ling`: omega_c = (pi K H / (2 E'))^2 R (CEB, default) or JGM eq (4)
    (``critical="jgm"``); omega_m from (1/2) m V1^2 = (8/15) E' sqrt(R) omega_c^(5/2)
    + pi K H R omega_m (omega_m - omega_c) (a quadratic in omega_m); then
    e^2 = (8/15) E' sqrt(R) omega_c (2 omega_m - omega_c)^(3/2) / ((1/2) m V1^2). e = 1 while
    (1/2) m V1^2 <= (8/15) E' sqrt(R) omega_c^(5/2). Equal to
    ``chang_ling(V1 / impact.V_c, impact.eps_y, impact.nu)`` up to rounding.

    Parameters
    ----------
    impact : fastrest.Impact
        Uses E_eff (Pa), R_eff (m), mass (kg), Sy (Pa), nu (-) and, for ``critical="jgm"``,
        omega_c (m).
    V1 : float or array_like
        Impact speed (m/s), finite and >= 0.
    critical : {"ceb", "jgm"}, optional
        Critical interference, as in :func:`chang_ling`.

    {returns_e_impact}
    ValueError
        V1 negative or not finite, an unknown ``critical``, or a result that overflows.

    Notes
    -----
    JGM eq (1) in SI units (see :func:`chang_ling` for the reading of the misprinted equation).

    Examples
    --------
    >>> import fastrest
    >>> from fastrest.models import chang_ling_dimensional
    >>> imp = fastrest.Impact(fastrest.Material(E=200e9, nu=0.33, Sy=1.12e9, rho=7800.0), R=0.01)
    >>> round(chang_ling_dimensional(imp, 1.0), 4)
    0.488
    """
    if critical not in _CL_CRITICAL:
        raise ValueError(f"critical must be one of {_CL_CRITICAL}; got {critical!r}")
    check_impact(impact)
    V1 = check_velocity(V1, "V1", "(m/s)")
    E, R, m = impact.E_eff, impact.R_eff, impact.mass
    KH = ceb_hardness_factor(impact.nu) * impact.Sy
    if critical == "ceb":
        w_c = (math.pi * KH / (2.0 * E)) ** 2 * R
    else:
        w_c = impact.omega_c
    U_elastic = 8.0 / 15.0 * E * math.sqrt(R) * w_c**2.5
    with np.errstate(all="ignore"):  # overflow: refused by _out below
        kinetic = 0.5 * m * V1 * V1
        plastic = kinetic > U_elastic
        work = np.where(plastic, kinetic - U_elastic, 0.0)
        w_m = 0.5 * (w_c + np.sqrt(w_c * w_c + 4.0 * work / (math.pi * KH * R)))
        rebound = 8.0 / 15.0 * E * math.sqrt(R) * w_c * (2.0 * w_m - w_c) ** 1.5
        e = np.sqrt(rebound / np.where(plastic, kinetic, U_elastic))
    return finite_out(np.where(plastic, e, 1.0), ("V1", V1))
