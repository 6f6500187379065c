"""Critical values at the onset of yield: from the two bodies' properties to the scales of the law.

JGM 2010 eqs (4)-(7), (11), (23)-(28). Every formula here is a plain ``@njit`` function of floats,
callable from Python and from Numba code alike: :class:`fastrest.Impact` and the DEM-side helper
:func:`critical_scales` run the very same compiled code, so they agree bit for bit.

SI units throughout: moduli and strengths in Pa, lengths in m, masses in kg, forces in N,
energies in J, speeds in m/s. A rigid or immovable counter-body has ``E2 = inf``, ``R2 = inf``
(a flat), ``m2 = inf`` and ``Sy2 = inf`` (never yields).
"""
import math
from collections import namedtuple

import numpy as np

from ._jit import jit

__all__ = ["c_of_nu", "effective_modulus", "effective_radius", "effective_mass",
           "critical_interference", "critical_force", "critical_area", "critical_energy",
           "critical_velocity", "CriticalScales", "critical_scales"]


@jit
def c_of_nu(nu):
    """C(nu) = 1.295 exp(0.736 nu), JGM eq (5): the one definition in fastrest (floats or arrays)."""
    return 1.295 * np.exp(0.736 * nu)


@jit
def effective_modulus(E1, nu1, E2, nu2):
    """Combined modulus E' (Pa): 1/E' = (1 - nu1^2)/E1 + (1 - nu2^2)/E2; ``E2 = inf`` is rigid."""
    inv = (1.0 - nu1**2) / E1
    if E2 < math.inf:
        inv += (1.0 - nu2**2) / E2
    return 1.0 / inv


@jit
def effective_radius(R1, R2):
    """R' = R1 R2/(R1 + R2) (m); ``R2 = inf`` is a flat (R' = R1 exactly)."""
    return R1 if R2 == math.inf else R1 * R2 / (R1 + R2)


@jit
def effective_mass(m1, m2):
    """Reduced mass m' = m1 m2/(m1 + m2) (kg); ``m2 = inf`` is an immovable body (m' = m1 exactly)."""
    return m1 if m2 == math.inf else m1 * m2 / (m1 + m2)


@jit
def critical_interference(C, Sy, E_eff, R):
    """omega_c = (pi C Sy / (2 E'))^2 R (m), JGM eq (4). C (-), Sy (Pa), E' (Pa), R (m)."""
    return (math.pi * C * Sy / (2.0 * E_eff)) ** 2 * R


@jit
def critical_force(C, Sy, E_eff, R):
    """P_c = (4/3) (R/E')^2 (pi C Sy / 2)^3 (N), JGM eq (6)."""
    return 4.0 / 3.0 * (R / E_eff) ** 2 * (math.pi * C * Sy / 2.0) ** 3


@jit
def critical_area(C, Sy, E_eff, R):
    """A_c = pi^3 (C Sy R / (2 E'))^2 (m^2), JGM eq (7)."""
    return math.pi**3 * (C * Sy * R / (2.0 * E_eff)) ** 2


@jit
def critical_energy(C, Sy, E_eff, R):
    """U_c = (pi C Sy)^5 R^3 / (60 E'^4) (J), JGM eq (23); equal to (2/5) P_c omega_c, eq (24)."""
    return (math.pi * C * Sy) ** 5 * R**3 / (60.0 * E_eff**4)


@jit
def critical_velocity(U_c, mass):
    """V_c = sqrt(2 U_c / m) (m/s), JGM eq (28). U_c in J, mass in kg."""
    return math.sqrt(2.0 * U_c / mass)


CriticalScales = namedtuple("CriticalScales", ["E_eff", "R_eff", "mass", "nu", "Sy", "C", "eps_y",
                                               "omega_c", "P_c", "A_c", "U_c", "V_c"])
CriticalScales.__doc__ = """Effective properties and critical values of one contact (SI units).

E_eff (Pa), R_eff (m), mass (kg, reduced), nu (-) and Sy (Pa) of the body that yields first,
C = C(nu) (-), eps_y = Sy/E' (-), omega_c (m), P_c (N), A_c (m^2), U_c (J), V_c (m/s).
Normalised variables: w = omega/omega_c, P* = P/P_c, V1* = V1/V_c.
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
        All fields NaN if neither body can yield or an input is not finite and positive where it
        must be (the Python :class:`fastrest.Impact` raises instead).
    """
    nan = math.nan
    ok = (E1 > 0.0 and R1 > 0.0 and m1 > 0.0 and Sy1 > 0.0 and E2 > 0.0 and R2 > 0.0
          and m2 > 0.0 and Sy2 > 0.0 and nu1 >= 0.0 and nu1 < 0.5 and nu2 >= 0.0 and nu2 < 0.5
          and E1 < math.inf and R1 < math.inf and m1 < math.inf)
    c1 = c_of_nu(nu1)
    c2 = c_of_nu(nu2)
    first = c1 * Sy1 <= c2 * Sy2
    nu = nu1 if first else nu2
    Sy = Sy1 if first else Sy2
    C = c1 if first else c2
    if not (ok and Sy < math.inf):
        return CriticalScales(nan, nan, nan, nan, nan, nan, nan, nan, nan, nan, nan, nan)
    E_eff = effective_modulus(E1, nu1, E2, nu2)
    R = effective_radius(R1, R2)
    m = effective_mass(m1, m2)
    U_c = critical_energy(C, Sy, E_eff, R)
    return CriticalScales(E_eff, R, m, nu, Sy, C, Sy / E_eff, critical_interference(C, Sy, E_eff, R),
                          critical_force(C, Sy, E_eff, R), critical_area(C, Sy, E_eff, R), U_c,
                          critical_velocity(U_c, m))
