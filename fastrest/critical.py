"""Critical values at the onset of yield: from the two bodies' properties to the scales of the law.

JGM 2010 eqs (4)-(7), (11), (23)-(28). Every formula here is a plain compiled function of floats
(declared with ``fastrest._jit.jit``), callable from Python and from Numba code alike:
:class:`fastrest.Impact` and the DEM-side helper
:func:`critical_scales` run the very same compiled code, so they agree bit for bit.

SI units throughout: moduli and strengths in Pa, lengths in m, masses in kg, forces in N,
energies in J, speeds in m/s. A rigid or immovable counter-body has ``E2 = inf``, ``R2 = inf``
(a flat), ``m2 = inf`` and ``Sy2 = inf`` (never yields).
"""
import math
from collections import namedtuple

import numpy as np
from numba.core import types
from numba.extending import overload

from ._doc import doc, paragraphs
from ._jit import jit, mul_rn

__all__ = ["c_of_nu", "effective_modulus", "effective_radius", "effective_mass",
           "critical_interference", "critical_force", "critical_area", "critical_energy",
           "critical_velocity", "CriticalScales", "critical_scales", "yield_et_ratio"]

# The parameters of the four critical scales, written once (fastrest._doc).
_DOC = paragraphs(params="""
    Parameters
    ----------
    C : float
        C(nu) of the material that yields first (-), :func:`c_of_nu`.
    Sy : float
        Yield strength of the material that yields first (Pa), finite and > 0.
    E_eff : float
        Effective modulus E' (Pa), :func:`effective_modulus`.
    R : float
        Effective radius R' (m), :func:`effective_radius`.
    """)

# The jit NaN contract (docs/architecture.md): every function here returns NaN outside its domain
# (an input not > 0 where it must be, a division by zero, a result that is not finite) and never
# raises; integers and float32 are taken as float64 (converted once, at the top). The guards are
# comparisons only: inside the domain the arithmetic, hence every number, is unchanged.


@jit
def _finite(x):
    """``x`` if it is finite, NaN otherwise (a result that overflowed lies outside the domain)."""
    return x if abs(x) < math.inf else math.nan


@jit
def _reduced(x1, x2):
    """x1 x2/(x1 + x2), exactly x1 where x2 is inf (an effective radius or a reduced mass); NaN for
    a value not > 0 or a result that is not finite."""
    x1, x2 = np.float64(x1), np.float64(x2)
    if not (x1 > 0.0 and x2 > 0.0):
        return math.nan
    return _finite(x1 if x2 == math.inf else x1 * x2 / (x1 + x2))


@jit
def _positive(a, b, c, d):
    """True if all four are > 0 (False for NaN)."""
    return a > 0.0 and b > 0.0 and c > 0.0 and d > 0.0


def _exp(x):
    """exp of a float (``math.exp``, which compiles for the CPU and CUDA) or of an array
    (``np.exp``, CPU only: :func:`fastrest.poisson_factor`); jit code only. Numba compiles both
    to the same libm ``exp`` per element on the CPU, so scalars and arrays agree bit for bit."""
    raise TypeError("_exp is for Numba code")


# inline="never": an IR-inlined ``numba.extending.overload`` does not compile for CUDA
# (numba-cuda 0.30 mixes its IR classes with Numba's); LLVM inlines the call on both targets.
@overload(_exp)
def _exp_impl(x):
    if isinstance(x, types.Number):
        return lambda x: math.exp(x)
    if isinstance(x, types.Array):
        return lambda x: np.exp(x)
    return None


@jit
def c_of_nu(nu):
    """Critical yield stress coefficient C(nu) = 1.295 exp(0.736 nu) (-), the one definition of it.

    Parameters
    ----------
    nu : float or ndarray
        Poisson's ratio of the material that yields first (-); the model uses 0 <= nu < 0.5.

    Returns
    -------
    float or ndarray
        C (-), of the same shape as ``nu``.

    Notes
    -----
    JGM eq (5) (Jackson & Green 2005). A compiled formula with no input checks (it evaluates any
    float, NaN gives NaN): :func:`fastrest.poisson_factor` is the validating Python function (it
    raises ValueError outside 0 <= nu <= 0.5). Non-numbers give Numba's ``TypingError``.

    Examples
    --------
    >>> from fastrest.critical import c_of_nu
    >>> round(c_of_nu(0.33), 6)  # JGM Table 1 prints 1.651
    1.651016
    """
    return 1.295 * _exp(0.736 * nu)


@jit
def effective_modulus(E1, nu1, E2, nu2):
    """Combined (effective) modulus E' (Pa) of two elastic bodies in contact.

    Parameters
    ----------
    E1 : float
        Young's modulus of body 1 (Pa), finite and > 0.
    nu1 : float
        Poisson's ratio of body 1 (-), 0 <= nu1 < 0.5.
    E2 : float
        Young's modulus of body 2 (Pa), > 0; ``math.inf`` for a rigid body.
    nu2 : float
        Poisson's ratio of body 2 (-), 0 <= nu2 < 0.5; unused if ``E2`` is infinite.

    Returns
    -------
    float
        E' (Pa), 1/E' = (1 - nu1^2)/E1 + (1 - nu2^2)/E2.

    Notes
    -----
    JGM section 2.1 (the equivalent sphere on a rigid flat). A jit function: NaN (never an
    exception) for a modulus not > 0, 1/E' not > 0 (nu > 1, or both bodies rigid) or a result
    that overflows; it does not check nu. :class:`fastrest.Impact` validates its materials first.

    Examples
    --------
    >>> import math
    >>> from fastrest.critical import effective_modulus
    >>> round(effective_modulus(200e9, 0.33, math.inf, 0.0) / 1e9, 4)  # GPa, rigid flat
    224.4417
    """
    E1, nu1, E2, nu2 = np.float64(E1), np.float64(nu1), np.float64(E2), np.float64(nu2)
    if not (E1 > 0.0 and E2 > 0.0):
        return math.nan
    inv = (1.0 - mul_rn(nu1, nu1)) / E1  # mul_rn: not fused into the subtraction on CUDA either
    if E2 < math.inf:
        inv += (1.0 - mul_rn(nu2, nu2)) / E2
    if not inv > 0.0:  # nu > 1, or both bodies rigid
        return math.nan
    E_eff = 1.0 / inv
    return E_eff if E_eff > 0.0 and E_eff < math.inf else math.nan  # 0: 1/E' overflowed


@jit
def effective_radius(R1, R2):
    """Effective radius R' = R1 R2/(R1 + R2) (m) of two curved surfaces in contact.

    Parameters
    ----------
    R1 : float
        Radius of curvature of body 1 (m), finite and > 0.
    R2 : float
        Radius of curvature of body 2 (m), > 0; ``math.inf`` for a flat (then R' = R1 exactly).

    Returns
    -------
    float
        R' (m), 1/R' = 1/R1 + 1/R2.

    Notes
    -----
    JGM section 2.1. A jit function: NaN (never an exception) for a radius not > 0 or a result
    that overflows (:class:`fastrest.Impact` raises).

    Examples
    --------
    >>> import math
    >>> from fastrest.critical import effective_radius
    >>> effective_radius(0.01, math.inf), round(effective_radius(0.01, 0.02), 9)
    (0.01, 0.006666667)
    """
    return _reduced(R1, R2)


@jit
def effective_mass(m1, m2):
    """Reduced mass m' = m1 m2/(m1 + m2) (kg) of two free bodies.

    Parameters
    ----------
    m1 : float
        Mass of body 1 (kg), finite and > 0.
    m2 : float
        Mass of body 2 (kg), > 0; ``math.inf`` for an immovable body (then m' = m1 exactly).

    Returns
    -------
    float
        m' (kg).

    Notes
    -----
    The standard two-body reduction (JGM use the sphere's mass against a fixed flat and do not
    state the two-sphere case; see docs/model.md section 1). NaN for a mass not > 0 or a result
    that overflows (a jit function: it never raises).

    Examples
    --------
    >>> import math
    >>> from fastrest.critical import effective_mass
    >>> effective_mass(0.0327, math.inf), effective_mass(1.0, 3.0)
    (0.0327, 0.75)
    """
    return _reduced(m1, m2)


@jit
@doc(_DOC)
def critical_interference(C, Sy, E_eff, R):
    """Critical interference omega_c = (pi C Sy / (2 E'))^2 R (m): the interference at yield onset.

    JGM eq (4); the unit of the normalised interference w = omega/omega_c.

    {params}

    Returns
    -------
    float
        omega_c (m).

    Notes
    -----
    NaN unless C, Sy, E', R > 0, and where the result overflows (a jit function: it
    never raises; see :func:`critical_scales`). JGM Table 1 prints 1.335 um for
    these inputs, smaller by the factor (1 - nu^2)^2; fastrest implements the equation as printed
    (docs/model.md section 6).

    Examples
    --------
    >>> from fastrest.critical import c_of_nu, critical_interference
    >>> E_eff = 200e9 / (1 - 0.33**2)  # JGM Table 1: steel on a rigid flat
    >>> round(critical_interference(c_of_nu(0.33), 1.12e9, E_eff, 0.01) * 1e6, 4)  # um
    1.6748
    """
    C, Sy, E_eff, R = np.float64(C), np.float64(Sy), np.float64(E_eff), np.float64(R)
    if not _positive(C, Sy, E_eff, R):
        return math.nan
    return _finite((math.pi * C * Sy / (2.0 * E_eff)) ** 2 * R)


@jit
@doc(_DOC)
def critical_force(C, Sy, E_eff, R):
    """Critical force P_c = (4/3) (R/E')^2 (pi C Sy / 2)^3 (N): the contact force at yield onset.

    JGM eq (6), equal to (4/3) E' sqrt(R) omega_c^1.5; the unit of the normalised force P* = P/P_c.

    {params}

    Returns
    -------
    float
        P_c (N).

    Notes
    -----
    NaN unless C, Sy, E', R > 0, and where
    the result overflows (a jit function: it never raises; see :func:`critical_scales`).

    Examples
    --------
    >>> from fastrest.critical import c_of_nu, critical_force
    >>> round(critical_force(c_of_nu(0.33), 1.12e9, 200e9 / (1 - 0.33**2), 0.01), 3)
    64.863
    """
    C, Sy, E_eff, R = np.float64(C), np.float64(Sy), np.float64(E_eff), np.float64(R)
    if not _positive(C, Sy, E_eff, R):
        return math.nan
    return _finite(4.0 / 3.0 * (R / E_eff) ** 2 * (math.pi * C * Sy / 2.0) ** 3)


@jit
@doc(_DOC)
def critical_area(C, Sy, E_eff, R):
    """Critical contact area A_c = pi^3 (C Sy R / (2 E'))^2 (m^2), the area at the onset of yield.

    JGM eq (7), equal to pi R omega_c; the unit of the normalised area A* = A/A_c.

    {params}

    Returns
    -------
    float
        A_c (m^2).

    Notes
    -----
    NaN unless C, Sy, E', R > 0, and where the result overflows (a jit function: it
    never raises; see :func:`critical_scales`).

    Examples
    --------
    >>> from fastrest.critical import c_of_nu, critical_area
    >>> round(critical_area(c_of_nu(0.33), 1.12e9, 200e9 / (1 - 0.33**2), 0.01) * 1e6, 5)  # mm^2
    0.05262
    """
    C, Sy, E_eff, R = np.float64(C), np.float64(Sy), np.float64(E_eff), np.float64(R)
    if not _positive(C, Sy, E_eff, R):
        return math.nan
    return _finite(math.pi**3 * (C * Sy * R / (2.0 * E_eff)) ** 2)


@jit
@doc(_DOC)
def critical_energy(C, Sy, E_eff, R):
    """Critical strain energy U_c = (pi C Sy)^5 R^3 / (60 E'^4) (J), stored at the onset of yield.

    JGM eq (23), equal to (2/5) P_c omega_c (eq 24): the unit of every normalised energy.

    {params}

    Returns
    -------
    float
        U_c (J).

    Notes
    -----
    The Hertz energy (8/15) E' sqrt(R) omega_c^2.5 at omega_c (eqs 17-21). NaN unless C, Sy, E',
    R > 0, where E'^4 underflows and where the result overflows (a jit function: it never raises;
    see :func:`critical_scales`).

    Examples
    --------
    >>> from fastrest.critical import c_of_nu, critical_energy
    >>> round(critical_energy(c_of_nu(0.33), 1.12e9, 200e9 / (1 - 0.33**2), 0.01) * 1e6, 3)  # uJ
    43.454
    """
    C, Sy, E_eff, R = np.float64(C), np.float64(Sy), np.float64(E_eff), np.float64(R)
    if not _positive(C, Sy, E_eff, R):
        return math.nan
    den = 60.0 * E_eff**4
    if not den > 0.0:  # E'^4 underflows
        return math.nan
    return _finite((math.pi * C * Sy) ** 5 * R**3 / den)


@jit
def critical_velocity(U_c, mass):
    """Critical impact speed V_c = sqrt(2 U_c / m) (m/s): the fastest impact that stays elastic.

    Parameters
    ----------
    U_c : float
        Critical energy (J), :func:`critical_energy`; >= 0.
    mass : float
        Mass of the moving body (kg), or the reduced mass :func:`effective_mass`; > 0.

    Returns
    -------
    float
        V_c (m/s); NaN for U_c < 0, a mass not > 0, or a result that overflows (a jit function:
        it never raises).

    Notes
    -----
    JGM eq (28) (from eq 27: (1/2) m V_c^2 = U_c). Normalised speeds are V1* = V1/V_c (eq 30).

    Examples
    --------
    >>> from fastrest.critical import critical_velocity
    >>> round(critical_velocity(4.3454e-5, 0.0327), 5)  # JGM Table 1's mass
    0.05155
    """
    U_c, mass = np.float64(U_c), np.float64(mass)
    if not (U_c >= 0.0 and mass > 0.0):
        return math.nan
    return _finite(math.sqrt(2.0 * U_c / mass))


@jit
def _yields_first(nu1, Sy1, nu2, Sy2):
    """True if body 1 yields first: the smaller C(nu) Sy (JGM after eq 5; ties go to body 1)."""
    return c_of_nu(nu1) * Sy1 <= c_of_nu(nu2) * Sy2


CriticalScales = namedtuple("CriticalScales", ["E_eff", "R_eff", "mass", "nu", "Sy", "C", "eps_y",
                                               "omega_c", "P_c", "A_c", "U_c", "V_c"])
CriticalScales.__doc__ = """Effective properties and critical values of one contact (SI units).

Built by :func:`critical_scales` (Python or Numba code); the fields are plain floats, so a
``CriticalScales`` passes into and out of jitted functions.

Parameters
----------
E_eff : float
    Effective modulus E' (Pa), :func:`effective_modulus`.
R_eff : float
    Effective radius R' (m), :func:`effective_radius`.
mass : float
    Mass of the moving body, or the reduced mass of two free bodies (kg).
nu : float
    Poisson's ratio of the body that yields first (-).
Sy : float
    Yield strength of the body that yields first (Pa).
C : float
    C(nu) (-), JGM eq (5).
eps_y : float
    Sy/E' (-), JGM eq (11).
omega_c, P_c, A_c, U_c, V_c : float
    Critical interference (m), force (N), area (m^2), energy (J) and speed (m/s), JGM eqs (4),
    (6), (7), (23), (28).

Notes
-----
Normalised variables: w = omega/omega_c, P* = P/P_c, A* = A/A_c, W* = W/U_c, V1* = V1/V_c.
All fields are NaN when :func:`critical_scales` received invalid input.

Examples
--------
>>> from fastrest.critical import CriticalScales
>>> CriticalScales._fields[:4]
('E_eff', 'R_eff', 'mass', 'nu')
"""


@jit
def critical_scales(E1, nu1, Sy1, R1, m1, E2, nu2, Sy2, R2, m2):
    """Everything the normalised law needs, from two bodies' properties (JGM eqs 4-7, 11, 23-28).

    Parameters
    ----------
    E1, nu1, Sy1, R1, m1 : float
        Body 1: Young's modulus (Pa), Poisson's ratio (-), yield strength (Pa; ``inf`` never
        yields), radius of curvature (m), mass (kg).
    E2, nu2, Sy2, R2, m2 : float
        Body 2, the same; a rigid fixed flat is ``E2 = R2 = m2 = Sy2 = inf`` (nu2 unused).

    Returns
    -------
    CriticalScales
        The body with the smaller C(nu) Sy yields first and supplies nu, Sy, C (JGM after eq 5).
        All fields NaN if neither body can yield, an input is not finite and positive where it
        must be, or a scale (E', R', mass, eps_y, omega_c, P_c, A_c, U_c, V_c) is not a finite,
        normal double (E1 = 1e-320 Pa, R1 = 1e300 m): the Python :class:`fastrest.Impact` raises
        instead. Integers and float32 are taken as float64.

    Notes
    -----
    JGM eqs (4)-(7), (11), (23)-(28) with the effective properties of section 2.1, composed from
    the functions of this module; :class:`fastrest.Impact` calls the same compiled functions, so
    the two agree bit for bit. A jit function: it never raises for bad values (NaN fields
    instead); non-numbers give Numba's ``TypingError``. Also exported as
    :func:`fastrest.jit.critical_scales`.

    Examples
    --------
    JGM Table 1 (steel sphere, R = 10 mm, m = 32.7 g, on a rigid flat):

    >>> import math
    >>> from fastrest.critical import critical_scales
    >>> inf = math.inf
    >>> s = critical_scales(200e9, 0.33, 1.12e9, 0.01, 0.0327, inf, 0.0, inf, inf, inf)
    >>> round(s.eps_y, 6), round(s.C, 4), round(s.V_c, 5)
    (0.00499, 1.651, 0.05155)
    >>> math.isnan(critical_scales(200e9, 0.33, inf, 0.01, 0.0327, inf, 0.0, inf, inf, inf).V_c)
    True
    """
    nan = math.nan
    E1, nu1, Sy1, R1, m1 = np.float64(E1), np.float64(nu1), np.float64(Sy1), np.float64(R1), np.float64(m1)
    E2, nu2, Sy2, R2, m2 = np.float64(E2), np.float64(nu2), np.float64(Sy2), np.float64(R2), np.float64(m2)
    ok = (E1 > 0.0 and R1 > 0.0 and m1 > 0.0 and Sy1 > 0.0 and E2 > 0.0 and R2 > 0.0
          and m2 > 0.0 and Sy2 > 0.0 and nu1 >= 0.0 and nu1 < 0.5 and nu2 >= 0.0 and nu2 < 0.5
          and E1 < math.inf and R1 < math.inf and m1 < math.inf)
    c1 = c_of_nu(nu1)
    c2 = c_of_nu(nu2)
    first = _yields_first(nu1, Sy1, nu2, Sy2)
    nu = nu1 if first else nu2
    Sy = Sy1 if first else Sy2
    C = c1 if first else c2
    if not (ok and Sy < math.inf):
        return CriticalScales(nan, nan, nan, nan, nan, nan, nan, nan, nan, nan, nan, nan)
    E_eff = effective_modulus(E1, nu1, E2, nu2)
    R = effective_radius(R1, R2)
    m = effective_mass(m1, m2)
    if not (E_eff > 0.0 and R > 0.0 and m > 0.0):  # NaN, or underflowed to 0 (E1 = 1e-320)
        return CriticalScales(nan, nan, nan, nan, nan, nan, nan, nan, nan, nan, nan, nan)
    U_c = critical_energy(C, Sy, E_eff, R)
    s = CriticalScales(E_eff, R, m, nu, Sy, C, Sy / E_eff, critical_interference(C, Sy, E_eff, R),
                       critical_force(C, Sy, E_eff, R), critical_area(C, Sy, E_eff, R), U_c,
                       critical_velocity(U_c, m))
    # every scale the law divides by must be a finite, normal double (as :class:`fastrest.Impact`
    # requires): E1 = 1e-320 or R1 = 1e300 lie outside double precision
    tiny = 2.2250738585072014e-308
    if not (s.E_eff >= tiny and s.R_eff >= tiny and s.mass >= tiny and s.eps_y >= tiny and s.omega_c >= tiny
            and s.P_c >= tiny and s.A_c >= tiny and s.U_c >= tiny and s.V_c >= tiny
            and s.E_eff < math.inf and s.omega_c < math.inf and s.P_c < math.inf and s.A_c < math.inf
            and s.U_c < math.inf and s.V_c < math.inf and s.eps_y < math.inf):
        return CriticalScales(nan, nan, nan, nan, nan, nan, nan, nan, nan, nan, nan, nan)
    return s


@jit
def yield_et_ratio(E1, nu1, Sy1, Et1, E2, nu2, Sy2, Et2):
    """Strain hardening of a contact: Et/E of the body that yields first (-), for the loading law.

    Parameters
    ----------
    E1, nu1, Sy1, Et1 : float
        Body 1: Young's modulus (Pa), Poisson's ratio (-), yield strength (Pa; ``inf`` never
        yields), tangent modulus of its plastic range (Pa; 0: elastic-perfectly plastic).
    E2, nu2, Sy2, Et2 : float
        Body 2, the same; a rigid flat is ``E2 = Sy2 = inf`` (``nu2``, ``Et2`` unused: pass 0.0).

    Returns
    -------
    float
        et_ratio = Et/E (-) of the body with the smaller C(nu) Sy, the one that supplies nu, Sy
        and C to :func:`critical_scales` (the same rule, the same compiled comparison); where
        both yield at once (equal C(nu) Sy), the smaller of the two, whatever the order: pass it
        with that contact's eps_y and nu to the law (:func:`fastrest.contact_law` ``et_ratio=``).
        NaN if neither body can yield, an input is not positive where it must be (E, Sy; nu
        outside [0, 0.5); E1 not finite), or the yielding body's Et is not in [0, E) (a jit
        function: it never raises). Integers and float32 are taken as float64.

    Notes
    -----
    A separate function rather than a field of :class:`CriticalScales`, so code unpacking
    :func:`critical_scales` keeps working: hardening does not change the critical values (the
    onset of yield, JGM eqs 4-7), only the loading law above it (Ghaednia et al. 2019,
    :mod:`fastrest.loading`), which reads Et/E of the yielding material. Also exported as
    :func:`fastrest.jit.yield_et_ratio`.

    Examples
    --------
    A steel sphere (Et = 2 GPa) on a rigid flat, and on a softer aluminium flat (Et = 0.7 GPa),
    which yields first:

    >>> import math
    >>> from fastrest.critical import yield_et_ratio
    >>> inf = math.inf
    >>> yield_et_ratio(200e9, 0.3, 1.0e9, 2e9, inf, 0.0, inf, 0.0)
    0.01
    >>> yield_et_ratio(200e9, 0.3, 1.0e9, 2e9, 70e9, 0.33, 0.28e9, 0.7e9)
    0.01
    >>> math.isnan(yield_et_ratio(200e9, 0.3, 1.0e9, 200e9, inf, 0.0, inf, 0.0))  # Et = E
    True
    """
    E1, nu1, Sy1, Et1 = np.float64(E1), np.float64(nu1), np.float64(Sy1), np.float64(Et1)
    E2, nu2, Sy2, Et2 = np.float64(E2), np.float64(nu2), np.float64(Sy2), np.float64(Et2)
    ok = (E1 > 0.0 and E1 < math.inf and E2 > 0.0 and Sy1 > 0.0 and Sy2 > 0.0 and nu1 >= 0.0 and nu1 < 0.5
          and nu2 >= 0.0 and nu2 < 0.5 and min(Sy1, Sy2) < math.inf)
    if not ok:
        return math.nan
    first = _yields_first(nu1, Sy1, nu2, Sy2)
    E = E1 if first else E2
    Et = Et1 if first else Et2
    h = Et / E
    if not (Et >= 0.0 and Et < E and h >= 0.0 and h < 1.0):  # also NaN
        return math.nan
    if first and _yields_first(nu2, Sy2, nu1, Sy1):  # both yield at once: the one hardening less
        h2 = Et2 / E2
        if not (Et2 >= 0.0 and Et2 < E2 and h2 >= 0.0 and h2 < 1.0):
            return math.nan
        h = min(h, h2)
    return h
