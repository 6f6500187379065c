"""Materials and the Poisson-ratio factor C(nu) of the onset of yield.

Jackson, Green & Marghitu (2010), "Predicting the coefficient of restitution of impacting
elastic-perfectly plastic spheres", Nonlinear Dyn. 60:217-229, doi:10.1007/s11071-009-9591-z
(JGM below), eq (5) and section 2.5. The impact itself (effective properties, critical values,
the dimensional e and w_m) is :class:`fastrest.impact.Impact`.

All quantities are SI: moduli and strengths in Pa, lengths in m, masses in kg, forces in N,
energies in J, velocities in m/s.

Note: JGM Tables 1, 3 and 4 print omega_c and P_c smaller than eqs (4) and (6) give, by the factor
(1 - nu^2)^2 of the yielding material; their eps_y and C agree with eqs (5) and (11). This module
implements the equations as printed, not the table values (see docs/model.md).
"""
from dataclasses import dataclass
import math

import numpy as np

from ._validation import check_finite_positive, check_nu, kernel_array, real_scalar
from .critical import c_of_nu

__all__ = ["Material", "poisson_factor", "critical_velocity_ratios"]


def poisson_factor(nu):
    """Critical yield stress coefficient C(nu) = 1.295 exp(0.736 nu), JGM eq (5).

    Parameters
    ----------
    nu : float or array_like
        Poisson's ratio of the material that yields first, 0 <= nu <= 0.5 (dimensionless; the
        formula accepts the incompressible limit 0.5 that Table 2 prints, the contact model does not).

    Returns
    -------
    float or ndarray
        C (dimensionless), from :func:`fastrest.critical.c_of_nu`; a float for a scalar ``nu``,
        else an array of its shape.

    Raises
    ------
    TypeError
        ``nu`` is not a real number or array of them (strings, booleans, None, complex).
    ValueError
        Any ``nu`` outside [0, 0.5] or NaN.

    Notes
    -----
    JGM eq (5), from Jackson & Green (2005).

    Examples
    --------
    >>> import fastrest
    >>> round(fastrest.poisson_factor(0.33), 4)  # JGM Table 1: c = 1.651
    1.651
    >>> fastrest.poisson_factor([0.2, 0.5]).round(4)
    array([1.5004, 1.8711])
    """
    nu = check_nu(nu, allow_half=True)
    if nu.ndim == 0:
        return float(c_of_nu(float(nu)))
    return c_of_nu(kernel_array(nu)).reshape(nu.shape)


def critical_velocity_ratios(nu):
    """Ratios V_c / V_y of JGM eq (28) to the yield velocities of Johnson, Wu et al. and Thornton.

    JGM section 2.5 (formulas above Table 2)::

        V_c/(V_y)_Johnson  = sqrt((pi C)^5 / 3180)
        V_c/(V_y)_Wu       = sqrt((C / 1.6)^5)
        V_c/(V_y)_Thornton = sqrt(C^5)

    Parameters
    ----------
    nu : float or array_like
        Poisson's ratio, 0 <= nu <= 0.5.

    Returns
    -------
    dict
        Keys ``"johnson"``, ``"wu"``, ``"thornton"`` (dimensionless): floats for a scalar ``nu``,
        arrays of its shape otherwise.

    Raises
    ------
    TypeError
        ``nu`` is not a real number or array of them.
    ValueError
        Any ``nu`` outside [0, 0.5] or NaN.

    Notes
    -----
    JGM Table 2 lists these ratios for nu = 0.3 (1.028, 1.024, 3.314) and other nu; the formulas
    use C(nu) of eq (5) (:func:`poisson_factor`). :func:`fastrest.models.yield_velocity_ratio`
    gives the same ratios by model name.

    Examples
    --------
    >>> import fastrest
    >>> r = fastrest.critical_velocity_ratios(0.3)
    >>> round(r["johnson"], 3), round(r["wu"], 3), round(r["thornton"], 3)
    (1.028, 1.024, 3.314)
    """
    C = np.asarray(poisson_factor(nu))

    def out(x):
        return float(x) if x.ndim == 0 else x

    return {
        "johnson": out(np.sqrt((np.pi * C) ** 5 / 3180.0)),
        "wu": out(np.sqrt((C / 1.6) ** 5)),
        "thornton": out(np.sqrt(C**5)),
    }


@dataclass(frozen=True)
class Material:
    """An isotropic elastic-perfectly plastic material (SI units).

    Parameters
    ----------
    E : float
        Young's modulus (Pa), finite and > 0.
    nu : float
        Poisson's ratio, 0 <= nu < 0.5.
    Sy : float
        Yield strength (Pa), finite and > 0. Use ``math.inf`` for a body that never yields
        (e.g. the alumina spheres of JGM Tables 3-4).
    rho : float, optional
        Density (kg/m^3), finite and > 0; needed only to compute a sphere's mass.

    Attributes
    ----------
    E, nu, Sy, rho : float
        The inputs as Python floats (``rho`` may be None). The instance is frozen and pickles.

    Raises
    ------
    TypeError
        A parameter is not a single real number (strings, booleans, None except for ``rho``,
        arrays).
    ValueError
        E not finite and > 0; nu outside [0, 0.5); Sy not > 0 or NaN; rho not finite and > 0.

    Notes
    -----
    Elastic-perfectly plastic (no hardening, no rate effects: docs/model.md section 8), as JGM
    assume. The critical values of an impact (eqs 4-7, 23-28) need two bodies: see
    :class:`fastrest.Impact`.

    Examples
    --------
    JGM Table 1 steel (E = 200 GPa, nu = 0.33, Sy = 1.12 GPa):

    >>> import fastrest
    >>> steel = fastrest.Material(200e9, 0.33, 1.12e9, rho=7850.0)
    >>> steel.nu, steel.Sy
    (0.33, 1120000000.0)
    >>> fastrest.Material(200e9, 0.5, 1.12e9)
    Traceback (most recent call last):
        ...
    ValueError: nu (Poisson's ratio) must be in [0, 0.5); got 0.5
    """

    E: float
    nu: float
    Sy: float
    rho: float | None = None

    def __post_init__(self):
        # store plain floats: a string or a 1-element array here would fail far from its cause
        for name in ("E", "nu", "Sy") + (("rho",) if self.rho is not None else ()):
            object.__setattr__(self, name, real_scalar(getattr(self, name), name))
        check_finite_positive(self.E, "E", "(Pa)")
        check_nu(self.nu)
        if not (self.Sy > 0) or math.isnan(self.Sy):
            raise ValueError(f"Sy must be > 0 (Pa) (math.inf for a body that never yields); got {self.Sy!r}")
        if self.rho is not None:
            check_finite_positive(self.rho, "rho", "(kg/m^3)")

    @property
    def yield_product(self):
        """C(nu) Sy (Pa): of two bodies, the one with the smaller product yields first (JGM eq 5).

        ``inf`` for a body that never yields (``Sy = math.inf``).

        Examples
        --------
        >>> import fastrest
        >>> round(fastrest.Material(200e9, 0.33, 1.12e9).yield_product / 1e9, 4)  # GPa
        1.8491
        """
        return poisson_factor(self.nu) * self.Sy


def __getattr__(name):
    # Impact lived here before it moved to fastrest.impact (it sits above the solver); old imports
    # and pickles that name fastrest.materials.Impact keep working
    if name == "Impact":
        from .impact import Impact

        return Impact
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
