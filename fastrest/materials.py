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

from ._validation import check_finite_positive, check_nu, real_scalar
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
        C (dimensionless), from :func:`fastrest.critical.c_of_nu`.
    """
    nu = check_nu(nu, allow_half=True)
    if nu.ndim == 0:
        return float(c_of_nu(float(nu)))
    return c_of_nu(np.ascontiguousarray(nu).ravel()).reshape(nu.shape)


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
        Keys ``"johnson"``, ``"wu"``, ``"thornton"`` (dimensionless).
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
        Density (kg/m^3); needed only to compute a sphere's mass.
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
        """C(nu) * Sy (Pa): the smaller of two bodies' products yields first (JGM after eq 5)."""
        return poisson_factor(self.nu) * self.Sy


def __getattr__(name):
    # Impact lived here before it moved to fastrest.impact (it sits above the solver); old imports
    # and pickles that name fastrest.materials.Impact keep working
    if name == "Impact":
        from .impact import Impact

        return Impact
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
