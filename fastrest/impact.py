"""An impact: two bodies reduced to JGM's equivalent sphere on a rigid flat, in SI units.

Jackson, Green & Marghitu (2010), Nonlinear Dyn. 60:217-229 (JGM): effective properties (section
2.1), critical values eqs (4), (6), (7), (11), (23), (28), and the dimensional restitution API
(eqs 16, 29-38) on top of the normalised solver :mod:`fastrest.direct`.

All quantities are SI: moduli and strengths in Pa, lengths in m, masses in kg, forces in N,
energies in J, velocities in m/s.

Note: JGM Tables 1, 3 and 4 print omega_c and P_c smaller than eqs (4) and (6) give, by the factor
(1 - nu^2)^2 of the yielding material; their eps_y and C agree with eqs (5) and (11). This module
implements the equations as printed, not the table values (see docs/model.md).
"""
import math
import sys
import warnings

import numpy as np

from . import direct
from ._validation import as_float_array, check_finite_positive, check_velocity, real_scalar
from .critical import (critical_area, critical_energy, critical_force, critical_interference,
                       critical_velocity, effective_mass, effective_modulus, effective_radius)
from .limits import raise_out_of_range, v1_star_limit
from .materials import Material, poisson_factor

__all__ = ["Impact"]


class Impact:
    """A sphere striking a flat (rigid or elastic-plastic), or two spheres, in JGM's equivalent form.

    JGM reduce every case to an equivalent sphere of radius ``R_eff`` and modulus ``E_eff`` against a
    rigid flat (section 2.1). The material that yields first (smaller C(nu) Sy) supplies nu, Sy and C
    (JGM after eq 5), and eps_y = Sy / E' (eq 11).

    Parameters
    ----------
    sphere : Material
        The impacting sphere.
    R : float
        Radius of the sphere (m).
    flat : Material, optional
        The flat's material; ``None`` (default) is a rigid flat.
    mass : float, optional
        Mass of the moving body (kg). Default: the sphere's mass (4/3) pi R^3 rho from
        ``sphere.rho``. Against a fixed flat this is the sphere's mass (JGM Table 1: m = 0.0327 kg).

    Sphere on sphere: use :meth:`Impact.two_spheres`, which sets R_eff = R1 R2 / (R1 + R2) and
    the reduced mass m1 m2 / (m1 + m2) (standard two-body reduction; JGM do not state it).
    """

    def __init__(self, sphere, R, flat=None, mass=None):
        self._init(sphere, real_scalar(R, "R"), flat, None, mass)

    @classmethod
    def two_spheres(cls, sphere1, R1, sphere2, R2, mass1=None, mass2=None):
        """Two free spheres: R_eff = R1 R2/(R1+R2), reduced mass m1 m2/(m1+m2), V1 = relative speed."""
        for name, m in (("sphere1", sphere1), ("sphere2", sphere2)):
            if not isinstance(m, Material):
                raise TypeError(f"{name} must be a fastrest.Material, got {type(m).__name__}")
        R1, R2 = real_scalar(R1, "R1"), real_scalar(R2, "R2")
        check_finite_positive(R1, "R1", "(m)")
        check_finite_positive(R2, "R2", "(m)")
        m1 = _sphere_mass(sphere1, R1, mass1, "mass1", "R1")
        m2 = _sphere_mass(sphere2, R2, mass2, "mass2", "R2")
        self = cls.__new__(cls)
        self._init(sphere1, real_scalar(R1, "R1"), sphere2, real_scalar(R2, "R2"), effective_mass(m1, m2))
        return self

    def _init(self, sphere, R1, other, R2, mass):
        if not isinstance(sphere, Material):
            raise TypeError(f"sphere must be a fastrest.Material, got {type(sphere).__name__}")
        if other is not None and not isinstance(other, Material):
            raise TypeError(f"flat must be a fastrest.Material or None (rigid flat), got {type(other).__name__}")
        check_finite_positive(R1, "R", "(m)")
        self.sphere, self.flat = sphere, other
        self.R_eff = R1 if R2 is None else effective_radius(R1, R2)
        if other is None:
            self.E_eff = effective_modulus(sphere.E, sphere.nu, math.inf, 0.0)
            yielding = sphere
        else:
            self.E_eff = effective_modulus(sphere.E, sphere.nu, other.E, other.nu)
            yielding = sphere if sphere.yield_product <= other.yield_product else other
        if math.isinf(yielding.Sy):
            raise ValueError("neither body can yield (Sy = inf for both): the impact is elastic, e = 1")
        self.yielding = yielding
        self.mass = _sphere_mass(sphere, R1, mass, "mass")
        self._check_scales()

    def _check_scales(self):
        """Every scale the model divides by must be a finite, normal float: inputs far outside any
        physical range (R = 1e300 m, E = 1e70 Pa) are refused here, not by an OverflowError or a
        NaN later."""
        try:
            vals = self.critical_values()
        except (OverflowError, ZeroDivisionError, ValueError) as exc:
            vals = {"error": exc}
        for k, v in vals.items():
            if k == "nu":
                continue
            if not (isinstance(v, float) and math.isfinite(v) and v >= sys.float_info.min):
                raise ValueError(
                    f"this impact's {k} = {v!r} is not a finite, normal double: E, Sy, R and the mass "
                    f"(SI units: Pa, Pa, m, kg) are too large or too small together (E_eff = "
                    f"{self.E_eff!r} Pa, Sy = {self.yielding.Sy!r} Pa, R_eff = {self.R_eff!r} m, "
                    f"mass = {self.mass!r} kg)")

    # --- material parameters of the normalised law ---
    @property
    def nu(self):
        """Poisson's ratio of the material that yields first (-)."""
        return self.yielding.nu

    @property
    def Sy(self):
        """Yield strength of the material that yields first (Pa)."""
        return self.yielding.Sy

    @property
    def C(self):
        """C(nu) of eq (5) for the material that yields first (-)."""
        return poisson_factor(self.nu)

    @property
    def eps_y(self):
        """eps_y = Sy / E' (-), JGM eq (11)."""
        return self.Sy / self.E_eff

    # --- critical values, eqs (4), (6), (7), (23), (28) ---
    @property
    def omega_c(self):
        """Critical interference (m), eq (4)."""
        return critical_interference(self.C, self.Sy, self.E_eff, self.R_eff)

    @property
    def P_c(self):
        """Critical force (N), eq (6)."""
        return critical_force(self.C, self.Sy, self.E_eff, self.R_eff)

    @property
    def A_c(self):
        """Critical contact area (m^2), eq (7)."""
        return critical_area(self.C, self.Sy, self.E_eff, self.R_eff)

    @property
    def U_c(self):
        """Critical strain energy (J), eq (23)."""
        return critical_energy(self.C, self.Sy, self.E_eff, self.R_eff)

    @property
    def V_c(self):
        """Critical initial velocity (m/s), eq (28)."""
        return critical_velocity(self.U_c, self.mass)

    def critical_values(self):
        """All critical and effective values as a dict (SI units)."""
        return {
            "E_eff": self.E_eff, "R_eff": self.R_eff, "mass": self.mass, "nu": self.nu,
            "Sy": self.Sy, "C": self.C, "eps_y": self.eps_y, "omega_c": self.omega_c,
            "P_c": self.P_c, "A_c": self.A_c, "U_c": self.U_c, "V_c": self.V_c,
        }

    def __repr__(self):
        flat = "rigid flat" if self.flat is None else repr(self.flat)
        return f"Impact(sphere={self.sphere!r}, R_eff={self.R_eff!r}, flat={flat}, mass={self.mass!r})"

    # --- dimensional restitution API (eqs 16, 29-38) ---
    def V_max(self, unloading="jcg", *, extrapolate=False):
        """Largest impact speed the model accepts (m/s).

        Parameters
        ----------
        unloading : {"jcg", "etsion", "brake"} or None, optional
            Unloading model; it matters only with ``extrapolate=True`` (JCG's eq 35 ends first).
            None: the loading law's own limit.
        extrapolate : bool, optional
            False (default): w_m* = 425, the end of JGM's validated range (section 3.3). True: where
            the contact radius reaches the sphere's (a/R = 1, eq 12) or, for JCG unloading, where
            eq (35) ends (w_res = w_m, at w_m* = 10017.5) if that comes first.

        Returns
        -------
        float
            V1 (m/s) = V1*_max V_c, eq (28).
        """
        return v1_star_limit(self.eps_y, self.nu, extrapolate=extrapolate, unloading=unloading) * self.V_c

    def v1_star(self, V1, unloading=None, *, extrapolate=False):
        """Normalised impact speed V1* = V1 / V_c (-), JGM eq (28).

        Parameters
        ----------
        V1 : float or array_like
            Impact speed (m/s), >= 0 and <= :meth:`V_max`.
        unloading : str or None, optional
            A model name (e.g. "jcg"); it matters only with ``extrapolate=True`` (see :meth:`V_max`).
            None: the contact law's own limit.
        extrapolate : bool, optional
            Accept speeds past w_m* = 425 (see :meth:`V_max`).

        Returns
        -------
        float or ndarray

        Raises
        ------
        TypeError
            V1 is not a real number or array of them.
        ValueError
            V1 < 0, not finite, or above :meth:`V_max` (the message gives the limit in m/s).
        """
        V = check_velocity(V1, "V1", "(m/s)")
        v = V / self.V_c
        # a few ulp of slack: V_max() itself (lim * V_c / V_c) must pass; the solver decides there
        over = v > v1_star_limit(self.eps_y, self.nu, extrapolate=extrapolate, unloading=unloading) * (1.0 + 1e-12)
        if np.any(over):
            raise_out_of_range(np.ravel(V[over]), [self.eps_y], [self.nu], extrapolate, "V1", unloading,
                               V_c=self.V_c)
        return v

    def max_interference(self, V1, *, extrapolate=False):
        """Maximum interference omega_m (m) for impact speed V1 (m/s): w_m* omega_c, JGM eq (29).

        Parameters
        ----------
        V1 : float or array_like
            Impact speed (m/s), see :meth:`v1_star`.
        extrapolate : bool, optional
            Accept speeds past w_m* = 425.

        Returns
        -------
        float or ndarray
            omega_m (m). (:meth:`fastrest.Curve.omega_m` is the dimensionless w_m* = omega_m / omega_c.)
        """
        return direct.omega_m_star(self.v1_star(V1, extrapolate=extrapolate), self.eps_y, self.nu,
                                   extrapolate=extrapolate) * self.omega_c

    def omega_m(self, V1, extrapolate=False):
        """Deprecated name of :meth:`max_interference` (metres, unlike the dimensionless
        ``Curve.omega_m``)."""
        warnings.warn("Impact.omega_m is deprecated: use Impact.max_interference (m)", DeprecationWarning,
                      stacklevel=2)
        return self.max_interference(V1, extrapolate=extrapolate)

    def e(self, V1, unloading="jcg", *, extrapolate=False):
        """Coefficient of restitution e = V2 / V1 (-), JGM eqs (16), (38).

        Parameters
        ----------
        V1 : float or array_like
            Impact speed (m/s), see :meth:`v1_star`.
        unloading : {"jcg", "etsion", "brake"}, optional
            Unloading model (see :mod:`fastrest.unloading`).
        extrapolate : bool, optional
            Accept speeds past w_m* = 425.

        Returns
        -------
        float or ndarray
            e (-); 1 below the onset of yield (V1 <= V_c).

        Raises
        ------
        TypeError, ValueError
            As :meth:`v1_star`; ValueError for an unknown ``unloading``.

        Examples
        --------
        >>> import fastrest
        >>> steel = fastrest.Material(200e9, 0.32, 1.0e9, 7850.0)
        >>> round(fastrest.Impact(steel, 0.01).e(1.0), 4)
        0.7132
        """
        return direct.e_star(self.v1_star(V1, unloading, extrapolate=extrapolate), self.eps_y, self.nu,
                             unloading=unloading, extrapolate=extrapolate)

    def rebound_velocity(self, V1, unloading="jcg", *, extrapolate=False):
        """Rebound speed V2 = e V1 (m/s) for impact speed V1 (m/s), JGM eq (38); arguments as :meth:`e`."""
        out = self.e(V1, unloading=unloading, extrapolate=extrapolate)  # validates V1
        out = out * as_float_array(V1, "V1")
        return float(out) if np.ndim(out) == 0 else out

    def contact_law(self, unloading="jcg", *, extrapolate=False):
        """The time-domain contact law of this contact in SI units (:func:`fastrest.contact_law`):
        ``law.force(omega)`` takes interferences omega (m) in time order and returns forces (N)."""
        from .force_law import contact_law

        return contact_law(self.eps_y, self.nu, unloading, extrapolate=extrapolate, omega_c=self.omega_c,
                           P_c=self.P_c)

    def residual(self, V1, unloading="jcg", *, extrapolate=False):
        """Residual interference omega_res (m) and residual radius R_res (m), JGM eqs (33)-(36).

        Parameters
        ----------
        V1, unloading, extrapolate
            As :meth:`e`.

        Returns
        -------
        (omega_res, R_res) : tuple of float or ndarray
            Metres.
        """
        w_res, r_ratio = direct.residual_star(self.v1_star(V1, unloading, extrapolate=extrapolate), self.eps_y,
                                              self.nu, unloading=unloading, extrapolate=extrapolate)
        return w_res * self.omega_c, r_ratio * self.R_eff


def _sphere_mass(material, R, mass, name, R_name="R"):
    if mass is not None:
        return float(check_finite_positive(real_scalar(mass, name), name, "(kg)"))
    if material.rho is None:
        raise ValueError(f"{name} is required (kg) when the sphere's Material has no density rho")
    m = 4.0 / 3.0 * math.pi * float(R) ** 3 * material.rho if float(R) < 1e100 else math.inf
    if not (math.isfinite(m) and m >= sys.float_info.min):
        raise ValueError(f"the sphere's mass (4/3) pi R^3 rho = {m!r} kg ({R_name} = {float(R)!r} m, rho = "
                         f"{material.rho!r} kg/m^3) is not a finite, normal double; give mass= (kg)")
    return m
