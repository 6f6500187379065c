"""Closed-form comparison models and the paper's empirical fits.

Jackson, Green & Marghitu (2010), "Predicting the coefficient of restitution of impacting
elastic-perfectly plastic spheres", Nonlinear Dyn. 60:217-229, doi:10.1007/s11071-009-9591-z
(JGM below) compare their model with the closed forms of

* Chang & Ling (1992), based on the CEB contact model (Chang, Etsion & Bogy 1987): JGM eq (1);
* Thornton (1997): JGM eq (2);
* Weir & Tallon (2005), which reduces to Johnson's (1985) simplified model for R1 = R: JGM eq (3);
* Wu, Li & Thornton (2003): JGM eqs (39)-(41);

and summarise their own numerical results by the empirical fits (42)-(44) (JCG unloading, eq 35)
and (45) (Etsion unloading, eq 33). This module implements all of them, without depending on the
JGM solver itself.

Conventions
-----------
* Normalised speeds are JGM's ``v1_star = V1 / V_c`` with V_c of JGM eq (28)
  (:attr:`fastrest.Impact.V_c`). Models that were published against their own yield velocity
  V_y (Thornton, Wu et al.) are converted with the ratios V_c / V_y of JGM Table 2
  (:func:`yield_velocity_ratio`).
* Every function is vectorised with NumPy broadcasting; a scalar input gives a Python ``float``.
* Invalid input raises :class:`ValueError` naming the parameter and its range: speeds must be
  finite and >= 0, ``0 <= nu < 0.5``, ``eps_y > 0``, dimensional material data finite and > 0.
* :data:`MODELS` maps a name to a function of ``(v1_star, eps_y, nu)``, so one can loop over the
  models; :func:`evaluate` is the dimensional form, taking an :class:`~fastrest.Impact` and V1 in m/s.
* No model output is clipped to e <= 1 unless the caller asks for it explicitly (only
  :func:`weir_tallon` / :func:`johnson` offer ``cap=True``). Where a published formula exceeds 1
  (Wu et al. eq 40 near V_c, Weir-Tallon below its unit-e speed) the formula's value is returned.

References
----------
.. [CL] W.R. Chang, F.F. Ling, "Normal impact model of rough surfaces", ASME J. Tribol. 114 (1992)
   439-447.
.. [CEB] W.R. Chang, I. Etsion, D.B. Bogy, "An elastic-plastic model for the contact of rough
   surfaces", ASME J. Tribol. 109 (1987) 257-263.
.. [Th] C. Thornton, "Coefficient of restitution for collinear collisions of elastic-perfectly
   plastic spheres", J. Appl. Mech. 64 (1997) 383-386.
.. [WT] G. Weir, S. Tallon, "The coefficient of restitution for normal incident, low velocity
   particle impacts", Chem. Eng. Sci. 60 (2005) 3637.
.. [J] K.L. Johnson, Contact Mechanics, Cambridge University Press (1985).
.. [Wu] C.Y. Wu, L.Y. Li, C. Thornton, "Rebound behaviour of spheres for plastic impacts",
   Int. J. Impact Eng. 28 (2003) 929-946.
"""
import math

import numba
import numpy as np

from ._validation import (
    EPS_Y_VALIDATED,
    ValidityWarning,
    broadcast_named,
    check_bool,
    check_eps_y,
    check_finite_result,
    check_finite_positive,
    check_nu,
    check_velocity,
    warn,
)
from .materials import critical_velocity_ratios, poisson_factor

__all__ = [
    "MODELS",
    "evaluate",
    "yield_velocity_ratio",
    "yield_velocity",
    "thornton",
    "THORNTON_COEFFICIENT",
    "weir_tallon",
    "weir_tallon_unit_velocity",
    "weir_tallon_normalised",
    "johnson",
    "ceb_hardness_factor",
    "chang_ling",
    "chang_ling_dimensional",
    "wu",
    "wu_finite_plastic_velocity",
    "jgm_fit_jcg",
    "jgm_fit_etsion",
    "jgm_fit_jcg_scalar",
    "jgm_fit_jcg_kernel",
    "JGM_FIT_V_MAX",
]

_V_STAR_UNIT = "(dimensionless, V1/V_c with V_c of JGM eq 28)"

#: Exact prefactor of Thornton's eq (JGM eq 2): sqrt(6 sqrt(3) / 5) = 1.44169...; JGM print 1.442.
THORNTON_COEFFICIENT = math.sqrt(6.0 * math.sqrt(3.0) / 5.0)

#: Upper end of the range of JGM's fit (44), V1* <= 1000.
JGM_FIT_V_MAX = 1000.0


def _out(a, *inputs):
    """A 0-d result becomes a Python float; arrays are returned as they are. A result that is not
    finite (the formula overflowed double precision) raises ValueError naming ``inputs``, (name,
    value) pairs, instead of being returned."""
    a = np.asarray(a, dtype=np.float64)
    check_finite_result(a, "e", inputs)
    return float(a) if a.ndim == 0 else a


def _bcast(*named):
    """np.broadcast_arrays with a ValueError naming the parameters whose shapes differ."""
    broadcast_named(*named)
    return np.broadcast_arrays(*(a for a, _ in named))


def _positive_speed(V1, name, eq):
    """Power laws in 1/V1 are infinite at V1 = 0: refuse it rather than return inf."""
    if np.any(V1 == 0.0):
        raise ValueError(f"{name} must be > 0 for {eq}: the formula is infinite at {name} = 0 "
                         "(it has no elastic range of its own; see the docstring)")


def _v_star(v1_star):
    return check_velocity(v1_star, "v1_star", _V_STAR_UNIT)


# ---------------------------------------------------------------------------------------------
# Yield velocities of the other models (JGM section 2.5, Table 2)
# ---------------------------------------------------------------------------------------------
_YIELD_MODELS = ("jgm", "johnson", "wu", "thornton", "ceb")


def ceb_hardness_factor(nu):
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
    """
    nu = check_nu(nu)
    return _out(2.8 * (0.454 + 0.41 * nu))


def yield_velocity_ratio(nu, model):
    """Ratio V_c / V_y of JGM's critical velocity (eq 28) to another model's yield velocity.

    JGM section 2.5 and Table 2. ``"johnson"``, ``"wu"`` and ``"thornton"`` come from
    :func:`fastrest.materials.critical_velocity_ratios` (sqrt((pi C)^5 / 3180), (C/1.6)^(5/2) and
    C^(5/2) with C = C(nu) of eq 5). Two more are provided for convenience:

    * ``"jgm"``: 1;
    * ``"ceb"``: (C / (K H / Sy))^(5/2), with K H of :func:`ceb_hardness_factor`. CEB's onset of
      yield is at omega_c,CEB = (pi K H / (2 E'))^2 R (instead of JGM eq 4, which has C Sy in
      place of K H), and V_c scales as omega_c^(5/4) (eqs 23, 28).

    Parameters
    ----------
    nu : float or array_like
        Poisson's ratio of the material that yields first, 0 <= nu < 0.5 (dimensionless). Table 2
        also prints nu = 0.5, which lies outside the model's domain and raises ValueError.
    model : {"jgm", "johnson", "wu", "thornton", "ceb"}
        Whose yield velocity V_y.

    Returns
    -------
    float or ndarray
        V_c / V_y (dimensionless). A speed V1 is ``V1/V_y = (V1/V_c) * ratio``.
    """
    if model not in _YIELD_MODELS:
        raise ValueError(f"model must be one of {_YIELD_MODELS}; got {model!r}")
    nu_a = check_nu(nu)
    if model == "jgm":
        return _out(np.ones_like(nu_a))
    if model == "ceb":
        C = np.asarray(poisson_factor(nu_a))
        return _out((C / np.asarray(ceb_hardness_factor(nu_a))) ** 2.5)
    return _out(critical_velocity_ratios(nu_a)[model])


def yield_velocity(impact, model):
    """Yield velocity V_y (m/s) of ``model`` for an impact: V_c / :func:`yield_velocity_ratio`.

    Parameters
    ----------
    impact : fastrest.Impact
        The impact; uses ``impact.V_c`` (m/s, JGM eq 28) and ``impact.nu`` (-).
    model : {"jgm", "johnson", "wu", "thornton", "ceb"}
        Whose yield velocity.

    Returns
    -------
    float
        V_y in m/s.
    """
    return float(impact.V_c / yield_velocity_ratio(impact.nu, model))


# ---------------------------------------------------------------------------------------------
# Thornton (1997), JGM eq (2)
# ---------------------------------------------------------------------------------------------
def thornton(v1_star, nu):
    """Coefficient of restitution of Thornton (1997) [Th]_, JGM eq (2).

    .. math::

        e = \\sqrt{6\\sqrt3/5}\\,\\sqrt{1 - x^2/6}\\,
            \\left(\\frac{x}{x + 2\\sqrt{(6 - x^2)/5}}\\right)^{1/4},\\qquad x = V_{y,Th}/V_1,

    for V1 > V_y,Th, and e = 1 for V1 <= V_y,Th (elastic impact).

    The "V_c" printed in JGM eq (2) is Thornton's own yield velocity V_y,Th, not JGM's eq (28):
    by JGM Table 2, V_c / V_y,Th = C(nu)^(5/2), so ``V1 / V_y,Th = v1_star * C^(5/2)``. Thornton
    therefore predicts yield at V1* = C^(-5/2) (about 0.3 for nu = 0.3), well below JGM's V_c.

    The prefactor is the exact sqrt(6 sqrt(3)/5) = 1.441687 (:data:`THORNTON_COEFFICIENT`) of
    Thornton's derivation; JGM print it rounded as 1.442, which would give e = 1.0002 instead of
    exactly 1 at V1 = V_y,Th. With the exact value e is continuous (= 1) at the onset of yield,
    with zero slope there (d ln e / dx = -1/5 + 1/5 = 0 at x = 1), so just above the onset e may
    round to 1 + 2e-16.
    At high speed e ~ 1.2 (V_y,Th / V1)^(1/4), i.e. d ln e / d ln V1 -> -1/4.

    Parameters
    ----------
    v1_star : float or array_like
        Impact speed V1 / V_c, V_c of JGM eq (28); finite and >= 0 (dimensionless).
    nu : float or array_like
        Poisson's ratio of the yielding material, 0 <= nu < 0.5 (dimensionless).

    Returns
    -------
    float or ndarray
        e (dimensionless), broadcast shape of the inputs.
    """
    v = _v_star(v1_star)
    nu = check_nu(nu)
    v, nu = _bcast((v, "v1_star"), (nu, "nu"))
    ratio = v * np.asarray(critical_velocity_ratios(nu)["thornton"])  # V1 / V_y,Th
    plastic = ratio > 1.0
    x = 1.0 / np.where(plastic, ratio, 1.0)
    e = (THORNTON_COEFFICIENT * np.sqrt(1.0 - x * x / 6.0)
         * (x / (x + 2.0 * np.sqrt((6.0 - x * x) / 5.0))) ** 0.25)
    return _out(np.where(plastic, e, 1.0), ("v1_star", v), ("nu", nu))


# ---------------------------------------------------------------------------------------------
# Weir & Tallon (2005) / Johnson (1985), JGM eq (3)
# ---------------------------------------------------------------------------------------------
def _radius_ratio(R1, R):
    if R1 is None and R is None:
        return np.float64(1.0)
    if R is None:
        raise ValueError("R (m) is required when R1 is given (eq 3 uses the ratio R1/R)")
    R = check_finite_positive(R, "R", "(m)")
    R1 = R if R1 is None else check_finite_positive(R1, "R1", "(m)")
    return R1 / R


def weir_tallon(V1, Sy, E_eff, rho, R1=None, R=None, *, cap=False):
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
    form is implemented; for R1 = R the question does not arise. :func:`evaluate` uses R1 = R = R'
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

    Returns
    -------
    float or ndarray
        e (dimensionless).
    """
    V1 = check_velocity(V1, "V1", "(m/s)")
    Sy = check_finite_positive(Sy, "Sy", "(Pa)")
    E_eff = check_finite_positive(E_eff, "E_eff", "(Pa)")
    rho = check_finite_positive(rho, "rho", "(kg/m^3)")
    cap = check_bool(cap, "cap")
    ratio = _radius_ratio(R1, R)
    broadcast_named((V1, "V1"), (Sy, "Sy"), (E_eff, "E_eff"), (rho, "rho"), (ratio, "R1/R"))
    if not cap:  # capped, e = 1 at V1 = 0 is the formula's limit
        _positive_speed(V1, "V1", "Weir & Tallon's eq (3)")
    with np.errstate(all="ignore"):
        e = (3.1 * (Sy / E_eff) ** 0.625 * ratio ** 0.375
             * (np.sqrt(E_eff / rho) / V1) ** 0.25)
    if cap:
        e = np.minimum(e, 1.0)
    return _out(e, ("V1", V1), ("Sy", Sy), ("E_eff", E_eff), ("rho", rho))


def johnson(V1, Sy, E_eff, rho, *, cap=False):
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

    Returns
    -------
    float or ndarray
        e (dimensionless).
    """
    return weir_tallon(V1, Sy, E_eff, rho, cap=cap)


def weir_tallon_unit_velocity(Sy, E_eff, rho, R1=None, R=None):
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
    """
    Sy = check_finite_positive(Sy, "Sy", "(Pa)")
    E_eff = check_finite_positive(E_eff, "E_eff", "(Pa)")
    rho = check_finite_positive(rho, "rho", "(kg/m^3)")
    ratio = _radius_ratio(R1, R)
    broadcast_named((Sy, "Sy"), (E_eff, "E_eff"), (rho, "rho"), (ratio, "R1/R"))
    with np.errstate(all="ignore"):
        out = 3.1**4 * (Sy / E_eff) ** 2.5 * ratio**1.5 * np.sqrt(E_eff / rho)
    return _out(out, ("Sy", Sy), ("E_eff", E_eff), ("rho", rho))


def weir_tallon_normalised(v1_star, eps_y, nu):
    """JGM eq (3) with R1 = R (Johnson) in JGM's normalisation: e = 3.1 (40 pi)^(1/8) (pi C)^(-5/8) V1*^(-1/4).

    Derivation: for a sphere of density rho and radius R on a flat, m = (4/3) pi rho R^3, and
    JGM eqs (23), (28) give V_c^2 = (pi C Sy)^5 / (40 pi E'^4 rho), so
    sqrt(E'/rho) / V1 = sqrt(40 pi) (pi C eps_y)^(-5/2) / V1*. Substituting in eq (3), eps_y cancels
    exactly: e depends on V1* and nu only (e = 2.027 V1*^(-1/4) for nu = 0.33, i.e. e = 1 at
    V1* = 16.9). The same holds for any mass if rho is the mass-equivalent density 3 m/(4 pi R^3),
    as :func:`evaluate` uses. The formula is returned for all V1* > 0 (> 1 below the unit-e speed;
    V1* = 0, where it is infinite, raises ValueError); see :func:`weir_tallon`.

    Parameters
    ----------
    v1_star : float or array_like
        V1 / V_c, V_c of JGM eq (28); finite and >= 0 (dimensionless).
    eps_y : float or array_like
        Sy / E' (dimensionless), > 0. Validated and broadcast, but it cancels out.
    nu : float or array_like
        Poisson's ratio, 0 <= nu < 0.5 (dimensionless).

    Returns
    -------
    float or ndarray
        e (dimensionless).
    """
    v = _v_star(v1_star)
    eps = check_eps_y(eps_y)
    nu = check_nu(nu)
    broadcast_named((v, "v1_star"), (eps, "eps_y"), (nu, "nu"))
    v, eps, nu = np.broadcast_arrays(v, eps, nu)
    _positive_speed(v, "v1_star", "Weir & Tallon's eq (3)")
    C = np.asarray(poisson_factor(nu))
    e = 3.1 * (40.0 * math.pi) ** 0.125 * (math.pi * C) ** -0.625 * v**-0.25
    return _out(e, ("v1_star", v))


# ---------------------------------------------------------------------------------------------
# Chang & Ling (1992) / CEB (1987), JGM eq (1)
# ---------------------------------------------------------------------------------------------
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


def chang_ling(v1_star, eps_y, nu, *, critical="ceb"):
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

    Returns
    -------
    float or ndarray
        e (dimensionless).
    """
    v = _v_star(v1_star)
    eps = check_eps_y(eps_y)
    nu = check_nu(nu)
    broadcast_named((v, "v1_star"), (eps, "eps_y"), (nu, "nu"))
    v, eps, nu = np.broadcast_arrays(v, eps, nu)
    r, s_per_v = _cl_params(nu, critical)
    return _out(_cl_e(v * s_per_v, r), ("v1_star", v))


def chang_ling_dimensional(impact, V1, *, critical="ceb"):
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

    Returns
    -------
    float or ndarray
        e (dimensionless).
    """
    if critical not in _CL_CRITICAL:
        raise ValueError(f"critical must be one of {_CL_CRITICAL}; got {critical!r}")
    _check_impact(impact)
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
    return _out(np.where(plastic, e, 1.0), ("V1", V1))


# ---------------------------------------------------------------------------------------------
# Wu, Li & Thornton (2003), JGM eqs (39)-(41)
# ---------------------------------------------------------------------------------------------
_WU_SCALES = ("jgm", "wu")


def _wu_inputs(v, eps, nu, scale):
    """Validate and broadcast; return (V, eps) with V the speed in the unit of eqs (39)-(41)."""
    if scale not in _WU_SCALES:
        raise ValueError(f"scale must be one of {_WU_SCALES}; got {scale!r}")
    if nu is None:
        if scale == "wu":
            raise ValueError("nu (Poisson's ratio, in [0, 0.5)) is required when scale='wu'")
        return _bcast((v, "v1_star"), (eps, "eps_y"))
    v, eps, nu = _bcast((v, "v1_star"), (eps, "eps_y"), (check_nu(nu), "nu"))
    if scale == "wu":
        v = v * np.asarray(critical_velocity_ratios(nu)["wu"])  # V1/V_y,Wu
    return v, eps


def wu_finite_plastic_velocity(eps_y, nu=None, *, scale="jgm"):
    """Onset of "finite plastic deformation" of Wu et al. (2003) [Wu]_, JGM eq (39), as V_fp / V_c.

    V_fp = 0.008 V_c (E'/Sy)^2, i.e. V_fp / V_c = 0.008 / eps_y^2 with the default
    ``scale="jgm"`` (V_c of JGM eq 28, as printed and as plotted in JGM Fig 6: 320 for
    eps_y = 0.005). With ``scale="wu"`` the V_c of eqs (39)-(41) is Wu et al.'s own yield velocity
    V_y,Wu, and the result, still returned in units of JGM's V_c, is
    0.008 / eps_y^2 / (V_c/V_y,Wu), with V_c/V_y,Wu = (C/1.6)^(5/2) (Table 2).

    Parameters
    ----------
    eps_y : float or array_like
        Sy / E' (dimensionless), > 0.
    nu : float or array_like, optional
        Poisson's ratio, 0 <= nu < 0.5; required only for ``scale="wu"``.
    scale : {"jgm", "wu"}, optional
        Meaning of V_c in eqs (39)-(41) (see :func:`wu`).

    Returns
    -------
    float or ndarray
        V_fp / V_c (dimensionless, V_c of JGM eq 28).
    """
    eps = check_eps_y(eps_y)
    one, eps = _wu_inputs(np.float64(1.0), eps, nu, scale)  # one = V_c / V_y in this scale
    with np.errstate(over="ignore"):
        out = 0.008 / (eps * eps) / one
    return _out(out, ("eps_y", eps))


def wu(v1_star, eps_y, nu=None, *, scale="jgm"):
    """Coefficient of restitution of Wu, Li & Thornton (2003) [Wu]_, JGM eqs (39)-(41).

    With V the impact speed in units of the model's critical velocity (see ``scale``):

    * V <= 1: e = 1 (elastic impact; eqs 40-41 are fits to plastic impacts only);
    * 1 < V <= V_fp = 0.008 / eps_y^2 (eq 39): e = 2.08 V^(-1/4) (eq 40);
    * V > V_fp: e = 0.62 (V eps_y)^(-1/2) (eq 41).

    Not clipped: eq (40) gives e > 1 for 1 < V < 2.08^4 = 18.7 (e = 2.08 just above V_c), as
    JGM point out under Fig 6, so e jumps from 1 to 2.08 at V = 1. The two branches meet at V_fp
    to within 0.33 % (2.08 * 0.008^(-1/4) = 6.955 vs 0.62 / sqrt(0.008) = 6.932, times
    sqrt(eps_y)); eq (40) is used at V = V_fp exactly.

    Which V_c: JGM print eqs (39)-(41) with V_c and plot them against their own V1* (Fig 6), so
    the default ``scale="jgm"`` uses V = v1_star (V_c of JGM eq 28): the paper's comparison as
    printed. Wu et al. fitted the constants 0.008, 2.08 and 0.62 against their own yield velocity
    V_y,Wu; ``scale="wu"`` (needs ``nu``) evaluates them with V = V1/V_y,Wu =
    v1_star (C/1.6)^(5/2) (JGM Table 2), which differs by -15 % .. +35 % in speed over
    0.2 <= nu <= 0.45 (2 % at nu = 0.3).

    Parameters
    ----------
    v1_star : float or array_like
        V1 / V_c, V_c of JGM eq (28); finite and >= 0 (dimensionless).
    eps_y : float or array_like
        Sy / E' (dimensionless), > 0.
    nu : float or array_like, optional
        Poisson's ratio, 0 <= nu < 0.5; required for ``scale="wu"``, ignored (but validated and
        broadcast) for ``scale="jgm"``.
    scale : {"jgm", "wu"}, optional
        Velocity unit of eqs (39)-(41): JGM's V_c (default) or Wu et al.'s V_y,Wu.

    Returns
    -------
    float or ndarray
        e (dimensionless).
    """
    v = _v_star(v1_star)
    eps = check_eps_y(eps_y)
    V, eps = _wu_inputs(v, eps, nu, scale)
    with np.errstate(all="ignore"):
        V_fp = 0.008 / (eps * eps)
        plastic = V > 1.0
        Vs = np.where(plastic, V, 1.0)
        e40 = 2.08 * Vs**-0.25
        e41 = 0.62 * (Vs * eps) ** -0.5
        e = np.where(Vs <= V_fp, e40, e41)
    return _out(np.where(plastic, e, 1.0), ("v1_star", V), ("eps_y", eps))


# ---------------------------------------------------------------------------------------------
# JGM empirical fits, eqs (42)-(45)
# ---------------------------------------------------------------------------------------------
def _warn_fit(v, eps, check_v_max):
    lo, hi = EPS_Y_VALIDATED
    parts = []
    if np.any((eps < lo) | (eps > hi)):
        parts.append(f"eps_y outside [{lo}, {hi}]")
    if check_v_max and np.any(v > JGM_FIT_V_MAX):
        parts.append(f"v1_star > {JGM_FIT_V_MAX:g} (beyond the range of eq 44)")
    if parts:
        warn("JGM empirical fit used outside its fitted range: " + " and ".join(parts)
             + "; the formula is evaluated as printed", ValidityWarning)


def jgm_fit_jcg(v1_star, eps_y):
    """JGM's empirical fit to their model with JCG unloading (eq 35): eqs (42)-(44).

    * V1* <= 1: e = 1 (eq 42);
    * 1 < V1* <= 60: e = 1 - 0.1 ln(V1*) ((V1* - 1)/59)^0.156 (eq 43);
    * V1* > 60: e = 1 - 0.1 ln 60 - 0.11 ln(V1*/60) (V1* - 60)^(2.36 eps_y) (eq 44).

    The pieces are continuous: at V1* = 1, ln 1 = 0; at V1* = 60 both (43) and (44) equal
    1 - 0.1 ln 60 = 0.590569 exactly (the last factor of 43 is 1 and the last term of 44 is 0), as
    the paper claims; the slope is not continuous there. JGM state the fit differs from their
    numerical results by 1.5 % on average and 4.5 % at most for V1* <= 1000,
    0.0005 < eps_y < 0.01, 0.2 < nu < 0.45. Outside 0.0005 <= eps_y <= 0.01 or above V1* = 1000 the
    formula is still evaluated and a :class:`~fastrest.ValidityWarning` is issued. A Numba version
    is :func:`jgm_fit_jcg_kernel`.

    Parameters
    ----------
    v1_star : float or array_like
        V1 / V_c, V_c of JGM eq (28); finite and >= 0 (dimensionless).
    eps_y : float or array_like
        Sy / E' (dimensionless), > 0.

    Returns
    -------
    float or ndarray
        e (dimensionless).
    """
    v = _v_star(v1_star)
    eps = check_eps_y(eps_y)
    v, eps = _bcast((v, "v1_star"), (eps, "eps_y"))
    _warn_fit(v, eps, True)
    low = np.where(v > 1.0, np.minimum(v, 60.0), 2.0)
    high = np.where(v > 60.0, v, 61.0)
    e43 = 1.0 - 0.1 * np.log(low) * ((low - 1.0) / 59.0) ** 0.156
    e44 = 1.0 - 0.1 * math.log(60.0) - 0.11 * np.log(high / 60.0) * (high - 60.0) ** (2.36 * eps)
    e = np.where(v <= 1.0, 1.0, np.where(v <= 60.0, e43, e44))
    return _out(e, ("v1_star", v), ("eps_y", eps))


def jgm_fit_etsion(v1_star, eps_y):
    """JGM's empirical fit to their model with Etsion et al. unloading (eq 33): eq (45).

    e = 1 - 0.0361 eps_y^(-0.114) ln(V1*) (V1* - 1)^(9.5 eps_y) for V1* > 1, and e = 1 for
    V1* <= 1 (continuous there). JGM: differs from their results by 5.3 % on average and 8.4 % at
    most, for 0.0005 < eps_y < 0.01, 0.2 < nu < 0.45 (no upper speed is stated; their computations
    end at omega_m* = 425). Outside that eps_y range a :class:`~fastrest.ValidityWarning` is issued.

    Parameters
    ----------
    v1_star : float or array_like
        V1 / V_c, V_c of JGM eq (28); finite and >= 0 (dimensionless).
    eps_y : float or array_like
        Sy / E' (dimensionless), > 0.

    Returns
    -------
    float or ndarray
        e (dimensionless).
    """
    v = _v_star(v1_star)
    eps = check_eps_y(eps_y)
    v, eps = _bcast((v, "v1_star"), (eps, "eps_y"))
    _warn_fit(v, eps, False)
    vs = np.where(v > 1.0, v, 2.0)
    e = 1.0 - 0.0361 * eps**-0.114 * np.log(vs) * (vs - 1.0) ** (9.5 * eps)
    return _out(np.where(v > 1.0, e, 1.0), ("v1_star", v), ("eps_y", eps))


@numba.njit(cache=True)
def jgm_fit_jcg_scalar(v1_star, eps_y):
    """Numba scalar kernel of JGM eqs (42)-(44) (see :func:`jgm_fit_jcg`).

    Parameters
    ----------
    v1_star : float
        V1 / V_c, V_c of JGM eq (28) (dimensionless).
    eps_y : float
        Sy / E' (dimensionless).

    Returns
    -------
    float
        e (dimensionless); NaN unless v1_star is finite and >= 0 and eps_y finite and > 0
        (no validation, no warnings).
    """
    if not (v1_star >= 0.0 and v1_star < math.inf and eps_y > 0.0 and eps_y < math.inf):
        return math.nan
    if v1_star <= 1.0:
        return 1.0
    if v1_star <= 60.0:
        return 1.0 - 0.1 * math.log(v1_star) * ((v1_star - 1.0) / 59.0) ** 0.156
    return (1.0 - 0.1 * math.log(60.0)
            - 0.11 * math.log(v1_star / 60.0) * (v1_star - 60.0) ** (2.36 * eps_y))


@numba.njit(cache=True)
def jgm_fit_jcg_kernel(v1_star_array, eps_y_array, out):
    """Numba array kernel of JGM eqs (42)-(44): ``out[i] = e(v1_star_array[i], eps_y_array[i])``.

    Parameters
    ----------
    v1_star_array : 1-D float64 ndarray
        V1 / V_c (dimensionless).
    eps_y_array : 1-D float64 ndarray
        Sy / E' (dimensionless), same length as ``v1_star_array`` or length 1 (one material).
    out : 1-D float64 ndarray
        Output e (dimensionless), same length as ``v1_star_array``; written in place.

    Invalid points give NaN (no exception, no warning). This is the "closed-form fit" speed
    reference of the benchmarks; the validated NumPy path is :func:`jgm_fit_jcg`.
    """
    n = v1_star_array.shape[0]
    if out.shape[0] != n:
        raise ValueError("out must have the length of v1_star_array")
    ne = eps_y_array.shape[0]
    if ne == 1:
        eps = eps_y_array[0]
        for i in range(n):
            out[i] = jgm_fit_jcg_scalar(v1_star_array[i], eps)
    elif ne == n:
        for i in range(n):
            out[i] = jgm_fit_jcg_scalar(v1_star_array[i], eps_y_array[i])
    else:
        raise ValueError("eps_y_array must have length 1 or the length of v1_star_array")
    return out


# ---------------------------------------------------------------------------------------------
# Common calling convention
# ---------------------------------------------------------------------------------------------
def _registry(fn, args):
    """Wrap ``fn`` as ``(v1_star, eps_y, nu) -> e``; ``args`` names the arguments ``fn`` takes."""
    def model(v1_star, eps_y, nu):
        given = {"v1_star": _v_star(v1_star), "eps_y": check_eps_y(eps_y), "nu": check_nu(nu)}
        shape = broadcast_named(*((a, n) for n, a in given.items()))
        e = fn(*(given[a] for a in args))
        return _out(np.broadcast_to(e, shape).copy() if shape else e)

    model.__name__ = model.__qualname__ = fn.__name__
    model.__doc__ = (f"Registry form ``(v1_star, eps_y, nu) -> e`` of :func:`{fn.__name__}`: all three "
                     f"arguments are validated and broadcast, {fn.__name__} receives {', '.join(args)}."
                     "\n\n" + (fn.__doc__ or ""))
    return model


#: Comparison models and fits under one convention: ``MODELS[name](v1_star, eps_y, nu) -> e``,
#: v1_star = V1/V_c with V_c of JGM eq (28), eps_y = Sy/E', nu = Poisson's ratio (all
#: dimensionless). "wu" uses JGM's V_c in eqs (39)-(41) (``scale="jgm"``), "chang_ling" CEB's
#: own critical interference, "weir_tallon" is eq (3) with R1 = R (= Johnson) normalised with
#: m = (4/3) pi rho R^3. The JGM model itself is not included here.
MODELS = {
    "thornton": _registry(thornton, ("v1_star", "nu")),
    "weir_tallon": _registry(weir_tallon_normalised, ("v1_star", "eps_y", "nu")),
    "chang_ling": _registry(chang_ling, ("v1_star", "eps_y", "nu")),
    "wu": _registry(wu, ("v1_star", "eps_y")),
    "jgm_fit_jcg": _registry(jgm_fit_jcg, ("v1_star", "eps_y")),
    "jgm_fit_etsion": _registry(jgm_fit_etsion, ("v1_star", "eps_y")),
}


def _check_impact(impact):
    from .materials import Impact

    if not isinstance(impact, Impact):
        raise TypeError(f"impact must be a fastrest.Impact, got {type(impact).__name__}")


def evaluate(model_name, impact, V1, *, rho=None):
    """Coefficient of restitution of a comparison model for an impact at speed V1 (m/s).

    For every model except Weir-Tallon and Chang-Ling this is
    ``MODELS[model_name](V1 / impact.V_c, impact.eps_y, impact.nu)``.

    * ``"chang_ling"``: :func:`chang_ling_dimensional` (eq 1 in SI units; equal to the normalised
      form).
    * ``"weir_tallon"``: :func:`weir_tallon` with Sy = ``impact.Sy``, E' = ``impact.E_eff``,
      R1 = R = ``impact.R_eff`` and the density of the sphere taken as the mass-equivalent
      rho = 3 m / (4 pi R_eff^3), m = ``impact.mass``. For a sphere on a flat with the mass computed
      from ``sphere.rho`` this is exactly the sphere's density (for JGM Figs 7-8 the alumina
      sphere's, not the flat's density that Tables 3-4 list); for two spheres it keeps eq (3)
      consistent with the reduced mass, and it equals ``MODELS["weir_tallon"]`` at V1/V_c.
      ``rho`` (kg/m^3) overrides it (then R1 = R = R_eff with the given density).

    Parameters
    ----------
    model_name : str
        A key of :data:`MODELS`.
    impact : fastrest.Impact
        The impact (uses V_c (m/s), eps_y (-), nu (-); Weir-Tallon also Sy (Pa), E_eff (Pa), R_eff (m),
        mass (kg)).
    V1 : float or array_like
        Impact speed (m/s), finite and >= 0.
    rho : float, optional
        Density (kg/m^3) for Weir-Tallon only; default mass-equivalent (see above).

    Returns
    -------
    float or ndarray
        e (dimensionless).
    """
    if not (isinstance(model_name, str) and model_name in MODELS):
        raise ValueError(f"model_name must be one of {sorted(MODELS)}; got {model_name!r}")
    _check_impact(impact)
    if rho is not None and model_name != "weir_tallon":
        raise ValueError("rho (kg/m^3) applies only to model_name='weir_tallon'")
    V1 = check_velocity(V1, "V1", "(m/s)")
    if model_name == "chang_ling":
        return chang_ling_dimensional(impact, V1)
    if model_name == "weir_tallon":
        if rho is None:
            rho = 3.0 * impact.mass / (4.0 * math.pi * impact.R_eff**3)
        return weir_tallon(V1, impact.Sy, impact.E_eff, rho, R=impact.R_eff)
    return MODELS[model_name](V1 / impact.V_c, impact.eps_y, impact.nu)
