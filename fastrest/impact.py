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
from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING, Any, overload
from numpy.typing import ArrayLike, NDArray
if TYPE_CHECKING:
    from .force_law import ContactLaw
import math
import sys
import warnings

import numpy as np

from . import direct
from ._deprecation import alias, warn_deprecated
from ._doc import doc, paragraphs
from ._validation import (EDGE_TOL, EPS_Y_VALIDATED, NU_VALIDATED, ValidityWarning, as_float_array,
                          check_finite_positive, check_velocity, real_scalar, warn)
from .critical import (critical_area, critical_energy, critical_force, critical_interference,
                       critical_velocity, effective_mass, effective_modulus, effective_radius, yield_et_ratio)
from .limits import raise_out_of_range, speed_limit
from .loading import LAWS, LoadingLaw, resolve as resolve_loading
from .materials import UNITS_HINT, Material, implausible, poisson_factor
from .repeated import RepeatedImpacts, repeated_impacts

__all__ = ["Impact"]

# The parameters, Warns and examples' first lines shared by the methods of Impact, written once
# (fastrest._doc).
_DOC = paragraphs(
    params_V1="""
        Parameters
        ----------
        V1 : float or array_like
            Impact speed (m/s), see :meth:`v1_star`.
        extrapolate : bool, optional
            Accept speeds past w_m* = 425.
        """,
    params_V1_unloading="""
        Parameters
        ----------
        V1 : float or array_like
            Impact speed (m/s), see :meth:`v1_star`.
        unloading : {"jcg", "etsion", "brake"}, optional
            Unloading model (see :mod:`fastrest.unloading`).
        extrapolate : bool, optional
            Accept speeds past w_m* = 425.
        """,
    warns_validity="""
        Warns
        -----
        ValidityWarning
            eps_y or nu of this impact outside the validated 0.0005-0.01, 0.2-0.45; JCG or Etsion
            unloading of a hardening body (``et_ratio > 0``: fitted without hardening), once per call.
        """,
    warns="""
        {warns_validity}
        ExtrapolationWarning
            With ``extrapolate=True``, past w_m* = 425.
        """,
    raises_options="""
        Raises
        ------
        TypeError
            ``extrapolate`` is not True or False.
        ValueError
            An unknown ``unloading``.
        """,
    raises_as_e="""
        Raises
        ------
        TypeError, ValueError
            As :meth:`e`.

        Warns
        -----
        ValidityWarning, ExtrapolationWarning
            As :meth:`e`.
        """,
    examples="""
        Examples
        --------
        >>> import fastrest
        >>> steel = fastrest.Material(200e9, 0.33, 1.12e9)  # JGM Table 1
        >>> imp = fastrest.Impact(steel, 0.01, mass=0.0327)
        """,
)


def _critical_value(scale: Callable[[float, float, float, float], float], text: str) -> Any:
    """A read-only property of :class:`Impact`: the critical scale ``scale`` (a function of
    :mod:`fastrest.critical`) of the contact's C, Sy, E' and R', documented by ``text``."""
    def get(self: Impact) -> float:
        return scale(self.C, self.Sy, self.E_eff, self.R_eff)

    get.__doc__ = text
    return property(get)


class Impact:
    """A sphere striking a flat (rigid or elastic-plastic), or two spheres, in JGM's equivalent form.

    JGM reduce every case to an equivalent sphere of radius ``R_eff`` and modulus ``E_eff`` against a
    rigid flat (section 2.1). The material that yields first (smaller C(nu) Sy) supplies nu, Sy and C
    (JGM after eq 5), and eps_y = Sy / E' (eq 11).

    Sphere on sphere: use :meth:`Impact.two_spheres`, which sets R_eff = R1 R2 / (R1 + R2) and
    the reduced mass m1 m2 / (m1 + m2) (standard two-body reduction; JGM do not state it).

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
    loading : {None, "jackson-green", "ghaednia"}, optional
        Loading law (:mod:`fastrest.loading`), keyword-only. None (default): Jackson-Green where the
        yielding body has ``Et = 0``, Ghaednia et al. (2019) where it hardens (``Et > 0``).

    Attributes
    ----------
    sphere, flat : Material
        The inputs (``flat`` None for a rigid flat).
    yielding : Material
        The body that yields first.
    et_ratio : float
        Et/E of the yielding body (-): the hardening parameter passed to the normalised API.
    loading : str
        The loading law's name, ``"jackson-green"`` or ``"ghaednia"``.
    E_eff : float
        Effective modulus E' (Pa).
    R_eff : float
        Effective radius (m).
    mass : float
        Mass of the moving body, or the reduced mass (kg).

    Raises
    ------
    TypeError
        ``sphere`` (or ``flat``) is not a :class:`fastrest.Material` (or None); R or mass not a
        single real number.
    ValueError
        R or mass not finite and > 0; no mass given and ``sphere.rho`` is None; neither body can
        yield (Sy = inf for both); inputs so extreme that a critical value is not a finite, normal
        double (the message names it); an unknown ``loading``, or ``loading="jackson-green"`` with a
        hardening yielding body.

    Warns
    -----
    ValidityWarning
        eps_y or nu of the impact outside the range JGM validated (0.0005-0.01, 0.2-0.45), when the
        impact is built (each evaluation warns again); with a reminder of the units where an input
        is outside the ranges of engineering solids (:data:`fastrest.materials.PLAUSIBLE`, e.g.
        eps_y > 0.1: E in GPa or Sy in MPa). A speed the model refuses names such inputs too.

    Notes
    -----
    JGM section 2.1 (equivalent sphere), eqs (4)-(7), (11), (23), (28) for the critical values
    (properties ``omega_c``, ``P_c``, ``A_c``, ``U_c``, ``V_c``, ``eps_y``, ``C``, ``nu``, ``Sy``,
    from :mod:`fastrest.critical`), and the restitution methods on top of
    :mod:`fastrest.direct` (eqs 16, 29-38). Instances pickle.

    Strain hardening: the yielding body's ``Et`` gives ``et_ratio`` = Et/E of that body, and every
    method passes it, with the loading law, to the normalised API. The law (Ghaednia et al. 2019)
    takes E/Sy as (1 - nu^2)/eps_y: exact for a sphere on a rigid flat, JGM's equivalent sphere
    (E' of both bodies) otherwise. JCG and Etsion unloading were fitted to elastic-perfectly
    plastic finite elements: with ``et_ratio > 0`` they warn once per call (ValidityWarning);
    ``unloading="brake"`` is the pairing the law's peers use.

    Examples
    --------
    JGM Table 1 (steel sphere, R = 10 mm, m = 32.7 g, on a rigid flat):

    >>> import fastrest
    >>> steel = fastrest.Material(200e9, 0.33, 1.12e9)  # JGM Table 1
    >>> imp = fastrest.Impact(steel, 0.01, mass=0.0327)
    >>> round(imp.eps_y, 6), round(imp.V_c, 5)  # m/s
    (0.00499, 0.05155)
    >>> round(imp.e(1.0), 6)  # at 1 m/s
    0.750144

    A hardening steel (tangent modulus 2 GPa, Et/E = 0.01) rebounds a little more:

    >>> hard = fastrest.Material(200e9, 0.33, 1.12e9, Et=2e9)
    >>> imp_h = fastrest.Impact(hard, 0.01, mass=0.0327)
    >>> imp_h.et_ratio, imp_h.loading
    (0.01, 'ghaednia')
    >>> round(imp_h.e(1.0, "brake"), 6) > round(imp.e(1.0, "brake"), 6)
    True
    """

    #: Read by instances pickled before hardening existed (their yielding body has Et = 0).
    _law: LoadingLaw = LAWS["jackson-green"]

    def __init__(self, sphere: Material, R: float, flat: Material | None = None, mass: float | None = None, *,
                 loading: str | None = None) -> None:
        self._init(sphere, real_scalar(R, "R"), flat, None, mass,
                   names=("sphere", "flat", "R", None, "mass" if mass is not None else None), loading=loading)

    @classmethod
    def two_spheres(cls, sphere1: Material, R1: float, sphere2: Material, R2: float, mass1: float | None = None,
                    mass2: float | None = None, *, loading: str | None = None) -> Impact:
        """An impact of two free spheres; V1 is then their relative normal speed.

        Parameters
        ----------
        sphere1, sphere2 : Material
            The two spheres' materials.
        R1, R2 : float
            Their radii (m), finite and > 0.
        mass1, mass2 : float, optional
            Their masses (kg), finite and > 0. Default: (4/3) pi R^3 rho from the material's rho.
        loading : {None, "jackson-green", "ghaednia"}, optional
            Loading law, keyword-only (see :class:`Impact`).

        Returns
        -------
        Impact
            With R_eff = R1 R2/(R1 + R2) and the reduced mass m1 m2/(m1 + m2).

        Raises
        ------
        TypeError
            A sphere is not a :class:`fastrest.Material`; a radius or mass not a single real number.
        ValueError
            A radius or mass not finite and > 0; a mass missing where the material has no rho;
            neither body can yield; a ``loading`` the yielding body's ``Et`` rules out.

        Notes
        -----
        JGM section 2.1 (1/R = 1/R1 + 1/R2 and the combined modulus E'); the reduced mass is the
        standard two-body reduction, which JGM do not state (docs/model.md section 1).

        Examples
        --------
        >>> import fastrest
        >>> steel = fastrest.Material(200e9, 0.33, 1.12e9)
        >>> imp = fastrest.Impact.two_spheres(steel, 0.01, steel, 0.01, 0.0327, 0.0327)
        >>> imp.R_eff, imp.mass
        (0.005, 0.01635)
        """
        for name, m in (("sphere1", sphere1), ("sphere2", sphere2)):
            if not isinstance(m, Material):
                raise TypeError(f"{name} must be a fastrest.Material, got {type(m).__name__}")
        R1, R2 = real_scalar(R1, "R1"), real_scalar(R2, "R2")
        check_finite_positive(R1, "R1", "(m)")
        check_finite_positive(R2, "R2", "(m)")
        m1 = _sphere_mass(sphere1, R1, mass1, "mass1", "R1")
        m2 = _sphere_mass(sphere2, R2, mass2, "mass2", "R2")
        m = effective_mass(m1, m2)
        if not (math.isfinite(m) and m >= sys.float_info.min):
            raise ValueError(f"the reduced mass of mass1 = {m1!r} kg and mass2 = {m2!r} kg is not a finite, normal "
                             "double: check the units (kg)")
        self = cls.__new__(cls)
        self._init(sphere1, real_scalar(R1, "R1"), sphere2, real_scalar(R2, "R2"), m,
                   names=("sphere1", "sphere2", "R1", "R2", "mass1" if m1 <= m2 else "mass2"), loading=loading)
        return self

    def _init(self, sphere, R1, other, R2, mass, names, loading=None):
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
        # Et/E by the jit rule (the yielding body's; on a tie the smaller, whatever the order)
        flat = (math.inf, 0.0, math.inf, 0.0) if other is None else (other.E, other.nu, other.Sy, other.Et)
        self._et_ratio = float(yield_et_ratio(sphere.E, sphere.nu, sphere.Sy, sphere.Et, *flat))
        self._law = resolve_loading(loading, self._et_ratio, name="Et/E of the yielding body")
        self.mass = _sphere_mass(sphere, R1, mass, "mass")
        self._check_scales(sphere, R1, other, R2, names)
        self._warn_validity()

    def _unit_hints(self):
        """'name = value ...' of this impact's inputs outside :data:`fastrest.materials.PLAUSIBLE`."""
        out = implausible(eps_y=self.eps_y)
        for prefix, m in (("sphere.", self.sphere), ("flat.", self.flat)):
            if m is not None:
                out += implausible(m.E, m.Sy, m.rho, prefix=prefix)
        return out

    def _warn_validity(self):
        """One ValidityWarning at construction: eps_y or nu outside the paper's validated range
        (which every evaluation also warns of), and inputs outside the ranges of engineering solids
        with a reminder of the units."""
        lo, hi = EPS_Y_VALIDATED
        lo_n, hi_n = NU_VALIDATED
        parts = []
        if not lo * (1.0 - EDGE_TOL) <= self.eps_y <= hi * (1.0 + EDGE_TOL):
            parts.append(f"eps_y = Sy/E' = {self.eps_y:.4g} outside [{lo}, {hi}]")
        if not lo_n * (1.0 - EDGE_TOL) <= self.nu <= hi_n * (1.0 + EDGE_TOL):
            parts.append(f"nu = {self.nu!r} outside [{lo_n}, {hi_n}]")
        if not parts:
            return
        msg = ("Impact: " + " and ".join(parts) + ", the range validated by Jackson, Green & Marghitu (2010); "
               "the model is computed as defined but is not validated there")
        hints = self._unit_hints()
        if hints:
            msg += f"; implausible for solids: {'; '.join(hints)}; {UNITS_HINT}"
        warn(msg, ValidityWarning)

    def _check_scales(self, sphere, R1, other, R2, names):
        """Every scale the model divides by must be a finite, normal float: inputs far outside any
        physical range (R = 1e300 m, E = 1e-300 Pa) are refused here with a ValueError naming the
        parameters (``names``: the caller's names of sphere, other, R1, R2 and the mass, None for a
        mass computed from rho), not by an OverflowError or a NaN later."""
        vals = self.critical_values()
        for k, v in vals.items():
            if k == "nu":
                continue
            if not (isinstance(v, float) and math.isfinite(v) and v >= sys.float_info.min):
                culprits = _culprits(sphere, R1, other, R2, self.yielding, self.mass, names)
                raise ValueError(
                    f"{culprits}: outside the range this model can evaluate in double precision "
                    f"(this impact's {k} = {v!r} is not a finite, normal double). Check the units: "
                    "E and Sy in Pa (steel: E = 2e11, Sy = 1e9), R in m, mass in kg, rho in kg/m^3")

    # --- material parameters of the normalised law ---
    @property
    def nu(self) -> float:
        """Poisson's ratio of the material that yields first (-)."""
        return self.yielding.nu

    @property
    def Sy(self) -> float:
        """Yield strength of the material that yields first (Pa)."""
        return self.yielding.Sy

    @property
    def C(self) -> float:
        """C(nu) of eq (5) for the material that yields first (-)."""
        return poisson_factor(self.nu)

    @property
    def eps_y(self) -> float:
        """eps_y = Sy / E' (-), JGM eq (11)."""
        return self.Sy / self.E_eff

    @property
    def et_ratio(self) -> float:
        """Et/E of the material that yields first (-), 0 for elastic-perfectly plastic; where both
        yield at once (equal C(nu) Sy), the smaller of the two (the order of the bodies does not
        matter)."""
        return getattr(self, "_et_ratio", self.yielding.et_ratio)  # pickles from before Et

    @property
    def loading(self) -> str:
        """The loading law's name (:mod:`fastrest.loading`): ``"jackson-green"`` or ``"ghaednia"``."""
        return self._law.name

    def _law_kw(self):
        """The hardening keywords of the normalised API for this impact."""
        return dict(et_ratio=self.et_ratio, loading=self._law.name)

    # --- critical values, eqs (4), (6), (7), (23), (28): properties of (C, Sy, E', R') ---
    omega_c: float = _critical_value(critical_interference, "Critical interference (m), eq (4).")
    P_c: float = _critical_value(critical_force, "Critical force (N), eq (6).")
    A_c: float = _critical_value(critical_area, "Critical contact area (m^2), eq (7).")
    U_c: float = _critical_value(critical_energy, "Critical strain energy (J), eq (23).")

    @property
    def V_c(self) -> float:
        """Critical initial velocity (m/s), eq (28)."""
        return critical_velocity(self.U_c, self.mass)

    @doc(_DOC)
    def critical_values(self) -> dict[str, float]:
        """All critical and effective values as a dict (SI units).

        Returns
        -------
        dict
            ``E_eff`` (Pa), ``R_eff`` (m), ``mass`` (kg), ``nu`` (-), ``Sy`` (Pa), ``C`` (-),
            ``eps_y`` (-), ``omega_c`` (m), ``P_c`` (N), ``A_c`` (m^2), ``U_c`` (J), ``V_c`` (m/s):
            the fields of :class:`fastrest.critical.CriticalScales`.

        Notes
        -----
        JGM eqs (4)-(7), (11), (23), (28). The omega_c and P_c of JGM Tables 1, 3, 4 are smaller by
        (1 - nu^2)^2; fastrest implements the equations (docs/model.md section 6).

        {examples}
        >>> cv = imp.critical_values()
        >>> round(cv["omega_c"] * 1e6, 4), round(cv["P_c"], 3)  # um, N
        (1.6748, 64.863)
        """
        return {
            "E_eff": self.E_eff, "R_eff": self.R_eff, "mass": self.mass, "nu": self.nu,
            "Sy": self.Sy, "C": self.C, "eps_y": self.eps_y, "omega_c": self.omega_c,
            "P_c": self.P_c, "A_c": self.A_c, "U_c": self.U_c, "V_c": self.V_c,
        }

    def __repr__(self) -> str:
        flat = "rigid flat" if self.flat is None else repr(self.flat)
        law = "" if self._law == resolve_loading(None, self.et_ratio) else f", loading={self._law.name!r}"
        return f"Impact(sphere={self.sphere!r}, R_eff={self.R_eff!r}, flat={flat}, mass={self.mass!r}{law})"

    # --- dimensional restitution API (eqs 16, 29-38) ---
    @doc(_DOC)
    def V_max(self, unloading: str = "jcg", *, extrapolate: bool = False) -> float:
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

        {raises_options}

        Notes
        -----
        ``fastrest.limit(eps_y, nu, unloading, extrapolate=...).v1_star`` (the energy balance,
        eq 29, at the interference limit) times V_c (docs/model.md section 4): the model's one limit
        (:func:`fastrest.limit`) in m/s for this impact.

        {examples}
        >>> round(imp.V_max(), 4), round(imp.V_max(extrapolate=True), 4)  # m/s
        (52.7211, 199.2743)
        """
        return speed_limit(self.eps_y, self.nu, extrapolate=extrapolate, unloading=unloading, **self._law_kw()) * self.V_c

    @doc(_DOC)
    def v1_star(self, V1: ArrayLike, unloading: str | None = None, *, extrapolate: bool = False) -> float | NDArray[np.float64]:
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
            V1 < 0, not finite, or above :meth:`V_max` (the message gives the limit in m/s); an
            unknown ``unloading``.

        Notes
        -----
        JGM eq (30) with V_c of eq (28). Every normalised API of fastrest takes V1*.

        {examples}
        >>> print(round(imp.v1_star(1.0), 6))
        19.397414
        """
        V = check_velocity(V1, "V1", "(m/s)")
        v = V / self.V_c
        law = self._law_kw()
        over = self._past_end(v, unloading, extrapolate)
        if np.any(over):
            try:
                raise_out_of_range(np.ravel(V[over]), [self.eps_y], [self.nu], extrapolate, "V1", unloading,
                                   V_c=self.V_c, **law)
            except ValueError as exc:
                hints = self._unit_hints()
                more = (f" (implausible for solids: {'; '.join(hints)}; {UNITS_HINT})"
                        if hints else " (V1 in m/s)")
                raise ValueError(f"{exc}{more}") from None
        return float(v) if v.ndim == 0 else v

    @doc(_DOC)
    def max_interference(self, V1: ArrayLike, *, extrapolate: bool = False) -> float | NDArray[np.float64]:
        """Maximum interference omega_m (m) for impact speed V1 (m/s): w_m* omega_c, JGM eq (29).

        {params_V1}

        Returns
        -------
        float or ndarray
            omega_m (m). (:meth:`fastrest.Curve.omega_m` is the dimensionless w_m* = omega_m / omega_c.)

        Raises
        ------
        TypeError, ValueError
            As :meth:`v1_star`.

        {warns}

        Notes
        -----
        :func:`fastrest.direct.omega_m_exact` (eq 29) times omega_c (eq 4), at V1* of eq (30).

        {examples}
        >>> round(imp.max_interference(1.0) * 1e6, 4)  # um
        19.2188
        """
        return direct.omega_m_exact(self.v1_star(V1, extrapolate=extrapolate), self.eps_y, self.nu,
                                   extrapolate=extrapolate, **self._law_kw()) * self.omega_c

    @doc(_DOC)
    def omega_m(self, V1: ArrayLike, extrapolate: bool = False) -> float | NDArray[np.float64]:
        """Deprecated name of :meth:`max_interference` (metres, unlike the dimensionless
        ``Curve.omega_m``).

        {params_V1}

        Returns
        -------
        float or ndarray
            omega_m (m), as :meth:`max_interference`.

        Raises
        ------
        TypeError, ValueError
            As :meth:`max_interference`.

        Warns
        -----
        DeprecationWarning
            Always: use :meth:`max_interference`.

        Examples
        --------
        >>> import warnings
        >>> import fastrest
        >>> steel = fastrest.Material(200e9, 0.33, 1.12e9)  # JGM Table 1
        >>> imp = fastrest.Impact(steel, 0.01, mass=0.0327)
        >>> with warnings.catch_warnings():
        ...     warnings.simplefilter("ignore", DeprecationWarning)
        ...     imp.omega_m(1.0) == imp.max_interference(1.0)
        True
        """
        warn_deprecated("Impact.omega_m", "Impact.max_interference (m)")
        return self.max_interference(V1, extrapolate=extrapolate)

    @overload
    def e(self, V1: float, unloading: str = "jcg", *, extrapolate: bool = False, past_end: str = "raise") -> float: ...
    @overload
    def e(self, V1: ArrayLike, unloading: str = "jcg", *, extrapolate: bool = False,
          past_end: str = "raise") -> float | NDArray[np.float64]: ...

    @doc(_DOC)
    def e(self, V1: ArrayLike, unloading: str = "jcg", *, extrapolate: bool = False,
          past_end: str = "raise") -> float | NDArray[np.float64]:
        """Coefficient of restitution e = V2 / V1 (-), JGM eqs (16), (38).

        {params_V1_unloading}
        past_end : {"raise", "nan"}, optional
            A speed past the model's end (:meth:`V_max`): "raise" (default) refuses the call with
            a ValueError naming it; "nan" gives NaN there, the other speeds their e, with one
            RuntimeWarning naming the first refused speed and the end.

        Returns
        -------
        float or ndarray
            e (-); 1 below the onset of yield (V1 <= V_c).

        Raises
        ------
        TypeError, ValueError
            As :meth:`v1_star`; ValueError for an unknown ``unloading``.

        {warns}

        Notes
        -----
        :func:`fastrest.direct.e_exact` at V1* = V1/V_c (eq 30): e^2 = P_m* (w_m* - w_res*)/V1*^2
        from eqs (29), (32), (38) and the unloading model (eq 35, eqs 33-34 or Brake's), with this
        impact's ``et_ratio`` and ``loading``.

        Examples
        --------
        >>> import fastrest
        >>> steel = fastrest.Material(200e9, 0.32, 1.0e9, 7850.0)
        >>> round(fastrest.Impact(steel, 0.01).e(1.0), 4)
        0.7132

        A sweep that runs past the model's end keeps its valid speeds with ``past_end="nan"``:

        >>> import warnings
        >>> with warnings.catch_warnings():
        ...     warnings.simplefilter("ignore")
        ...     fastrest.Impact(steel, 0.01).e([1.0, 100.0], past_end="nan").round(4)
        array([0.7132,    nan])
        """
        if past_end == "nan":
            return self._nan_past_end(V1, unloading, extrapolate)
        if past_end != "raise":
            raise ValueError(f"past_end must be 'raise' or 'nan'; got {past_end!r}")
        return direct.e_exact(self.v1_star(V1, unloading, extrapolate=extrapolate), self.eps_y, self.nu,
                             unloading=unloading, extrapolate=extrapolate, **self._law_kw())

    def _past_end(self, v1_star, unloading, extrapolate):
        """Where the normalised speeds ``v1_star`` lie past the model's end: the rule of
        :meth:`v1_star` (a few ulp of slack: V_max() itself, lim * V_c / V_c, must pass; the solver
        decides there)."""
        lim = speed_limit(self.eps_y, self.nu, extrapolate=extrapolate, unloading=unloading, **self._law_kw())
        return v1_star > lim * (1.0 + 1e-12)

    def _nan_past_end(self, V1, unloading, extrapolate):
        """e at the speeds the model covers, NaN past its end, one RuntimeWarning naming the first."""
        V = check_velocity(V1, "V1", "(m/s)")  # bad input is still an error
        top = self.V_max(unloading, extrapolate=extrapolate)
        inside = ~self._past_end(V / self.V_c, unloading, extrapolate)
        out = np.full(V.shape, np.nan)
        if inside.any():
            out[inside] = self.e(V[inside], unloading, extrapolate=extrapolate)
        if not inside.all():
            first = float(V[~inside].ravel()[0])
            warn(f"{int((~inside).sum())} of {V.size} speeds are past the model's end and give NaN (the first, "
                 f"V1 = {first!r} m/s; the end: V1 = {top:.10g} m/s{'' if extrapolate else ', w_m* = 425'})",
                 RuntimeWarning)
        return float(out) if out.ndim == 0 else out

    @doc(_DOC)
    def rebound_velocity(self, V1: ArrayLike, unloading: str = "jcg", *, extrapolate: bool = False) -> float | NDArray[np.float64]:
        """Rebound speed V2 = e V1 (m/s) for impact speed V1 (m/s).

        {params_V1_unloading}

        Returns
        -------
        float or ndarray
            V2 (m/s), of the shape of V1.

        {raises_as_e}

        Notes
        -----
        JGM eqs (37), (38) (via e, eq 16).

        {examples}
        >>> imp.rebound_velocity([0.5, 1.0]).round(6)  # m/s
        array([0.416044, 0.750144])
        """
        out = self.e(V1, unloading=unloading, extrapolate=extrapolate)  # validates V1
        out = out * as_float_array(V1, "V1")
        return float(out) if np.ndim(out) == 0 else out

    def repeated_impacts(self, V1: ArrayLike, n: int | None = None, unloading: str = "jcg", *,
                         extrapolate: bool = False) -> RepeatedImpacts:
        """Successive impacts on the same spot: e, largest and residual interference of each.

        Exact (the energy balance on the reloading curve, docs/model.md "Repeated impacts"): an impact
        reloads along the last unloading curve (elastic, e = 1 while it stays there) and goes on
        along the virgin law past the earlier maximum; one exact solve per impact.

        Parameters
        ----------
        V1 : float or array_like
            Impact speed (m/s), > 0: one speed repeated ``n`` times, or a 1-D sequence (one per
            impact).
        n : int, optional
            Number of impacts at the one speed (1 to 1e6).
        unloading : {"jcg", "etsion", "brake"}
            Unloading model (as in :meth:`e`).
        extrapolate : bool
            As in :meth:`e`.

        Returns
        -------
        RepeatedImpacts
            ``.e``, ``.max_interference`` (m), ``.residual_interference`` (m), ``.plastic`` per
            impact; ``.shakedown(e_min)`` the first impact with e >= e_min.

        Raises
        ------
        TypeError
            Non-numbers.
        ValueError
            A speed not finite and > 0; ``n`` missing for one speed, given with a sequence, not a
            whole number or outside 1 to 1e6; a sequence that is not 1-D or empty; an impact that takes the
            contact past the model's end (the message names the impact).

        Examples
        --------
        >>> import fastrest
        >>> steel = fastrest.Material(200e9, 0.3, 1e9, rho=7850.0)
        >>> r = fastrest.Impact(steel, 0.01).repeated_impacts(0.5, 3)
        >>> r.e.round(4), r.plastic
        (array([0.7989, 0.9108, 0.9572]), array([ True,  True,  True]))
        """
        return repeated_impacts(self, V1, n, unloading, extrapolate=extrapolate)

    @doc(_DOC)
    def contact_law(self, unloading: str = "jcg", *, extrapolate: bool = False) -> ContactLaw:
        """The time-domain contact law of this contact in SI units (:func:`fastrest.contact_law`).

        ``law.force(omega)`` takes interferences omega (m) in time order and returns forces (N).

        Parameters
        ----------
        unloading : {"jcg", "etsion", "brake"}, optional
            Unloading model (see :mod:`fastrest.unloading`).
        extrapolate : bool, optional
            Serve interferences past w* = 425 (up to a/R = 1 and the unloading model's end).

        Returns
        -------
        ContactLaw
            With ``omega_c`` (m) and ``P_c`` (N) of this impact as units; ``law.data`` stays
            normalised, for :func:`fastrest.jit.contact_force`.

        {raises_options}

        {warns_validity}

        Notes
        -----
        JGM eqs (8)-(15) for loading and (32)-(35) for unloading, in time (docs/model.md
        section 10).

        {examples}
        >>> law = imp.contact_law()
        >>> law.force([0.0, 1e-6, 2e-6]).round(4)  # interference in m, force in N
        array([ 0.    , 29.9256, 84.6423])
        """
        from .force_law import contact_law

        return contact_law(self.eps_y, self.nu, unloading, extrapolate=extrapolate, omega_c=self.omega_c,
                           P_c=self.P_c, **self._law_kw())

    @doc(_DOC)
    def residual(self, V1: ArrayLike, unloading: str = "jcg", *, extrapolate: bool = False) -> tuple[float | NDArray[np.float64], float | NDArray[np.float64]]:
        """Residual interference omega_res (m) and residual radius R_res (m), JGM eqs (33)-(36).

        {params_V1_unloading}

        Returns
        -------
        (omega_res, R_res) : tuple of float or ndarray
            Metres.

        {raises_as_e}

        Notes
        -----
        :func:`fastrest.direct.residual_exact` times omega_c (eq 4) and R_eff.

        {examples}
        >>> omega_res, R_res = imp.residual(1.0)
        >>> round(omega_res * 1e6, 4), round(R_res * 1e3, 4)  # um, mm
        (7.6978, 29.1037)
        """
        w_res, r_ratio = direct.residual_exact(self.v1_star(V1, unloading, extrapolate=extrapolate), self.eps_y,
                                              self.nu, unloading=unloading, extrapolate=extrapolate, **self._law_kw())
        return w_res * self.omega_c, r_ratio * self.R_eff


# Order of magnitude of each input, only to name the one(s) farthest from any physical value.
_TYPICAL = {"E": 1e11, "Sy": 3e8, "R": 1e-2, "mass": 1e-2, "rho": 5e3}


def _culprits(sphere, R1, other, R2, yielding, mass, names):
    """'name = value unit' of the inputs farthest (in orders of magnitude) from physical values."""
    b1, b2, r1, r2, m_name = names
    cand = []

    def add(label, value, kind, unit):
        dev = abs(math.log10(value / _TYPICAL[kind])) if 0.0 < value < math.inf else math.inf
        cand.append((dev, f"{label} = {value!r} {unit}"))

    soft = sphere if other is None or (1 - sphere.nu**2) / sphere.E >= (1 - other.nu**2) / other.E else other
    add(f"{b1 if soft is sphere else b2}.E", soft.E, "E", "Pa")
    add(f"{b1 if yielding is sphere else b2}.Sy", yielding.Sy, "Sy", "Pa")
    add(r1 if R2 is None or R1 <= R2 else r2, R1 if R2 is None else min(R1, R2), "R", "m")
    if m_name is None:
        add(f"{b1}.rho", sphere.rho, "rho", "kg/m^3")
    else:
        add(m_name, mass, "mass", "kg")
    worst = max(d for d, _ in cand)
    return " and ".join(t for d, t in cand if d >= 0.5 * worst)


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


# fastrest.materials.Impact (the class's first home), deprecated: registered here, where it is defined
alias("fastrest.materials", "Impact", "fastrest.Impact", lambda: Impact)
