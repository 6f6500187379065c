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
from __future__ import annotations

from types import FrameType
from typing import Any, overload
from numpy.typing import ArrayLike, NDArray
from dataclasses import dataclass
import math
import os
import sys
import warnings

import numpy as np

from ._deprecation import module_getattr
from ._validation import ValidityWarning, check_finite_positive, check_nu, kernel_array, real_scalar
from .critical import c_of_nu

__all__ = ["Material", "poisson_factor", "critical_velocity_ratios", "PLAUSIBLE", "UNITS_HINT"]

#: Ranges of engineering solids, in SI units. A value outside its range is almost always a unit
#: mistake (E or Sy in GPa or MPa, rho in g/cm^3): :class:`Material` and :class:`fastrest.Impact`
#: then warn (:class:`fastrest.ValidityWarning`) with :data:`UNITS_HINT`, and an impact speed the
#: model refuses names the implausible value. The model still evaluates such input as given.
#:
#: * ``E``: 1e6 Pa (soft elastomers) to 1e13 Pa (diamond is 1.2e12);
#: * ``Sy``: 1e5 Pa to 1e11 Pa (soft metals yield at a few MPa; ``math.inf`` is never checked);
#: * ``rho``: 30 to 3e4 kg/m^3 (osmium is 2.26e4; a density in g/cm^3 is at most 22.6);
#: * ``Sy/E`` of a material and ``eps_y`` = Sy/E' of an impact: 1e-5 to 0.1 (annealed pure metals
#:   are ~1e-4, polymers ~0.03).
PLAUSIBLE = {"E": (1e6, 1e13), "Sy": (1e5, 1e11), "rho": (30.0, 3e4), "eps_y": (1e-5, 0.1)}
#: The reminder of fastrest's units appended to every plausibility warning and message.
UNITS_HINT = ("check the units: E and Sy in Pa (steel: E = 2e11, Sy = 1e9), rho in kg/m^3 (steel: 7850), "
              "R in m, mass in kg, V in m/s")


_PACKAGE_DIR = os.path.dirname(os.path.abspath(__file__)) + os.sep


def _warn_caller(message):
    """A ValidityWarning from ``Material.__post_init__`` attributed to the first line outside
    fastrest that built the material (past the dataclass's generated ``__init__``)."""
    f: FrameType | None = sys._getframe(2)  # the frame that called __post_init__: the generated __init__
    level = 3
    if f is not None and f.f_code.co_name == "__init__" and not f.f_code.co_filename.startswith(_PACKAGE_DIR):
        f, level = f.f_back, level + 1
    while f is not None and f.f_code.co_filename.startswith(_PACKAGE_DIR):
        f, level = f.f_back, level + 1
    warnings.warn(message, ValidityWarning, stacklevel=level)


def implausible(E=None, Sy=None, rho=None, eps_y=None, prefix=""):
    """'name = value' texts of the values outside :data:`PLAUSIBLE` (empty if none); ``prefix``
    names the owner (``"sphere."``). Used by :class:`Material` and :class:`fastrest.Impact`."""
    out = []
    for name, unit, x in (("E", " Pa", E), ("Sy", " Pa", Sy), ("rho", " kg/m^3", rho), ("eps_y", "", eps_y)):
        if x is None or math.isinf(x):
            continue
        lo, hi = PLAUSIBLE[name]
        if not lo <= x <= hi:
            label = "eps_y = Sy/E'" if name == "eps_y" else prefix + name
            out.append(f"{label} = {x!r}{unit} is {'below' if x < lo else 'above'} {lo if x < lo else hi:g}{unit}")
    return out


@overload
def poisson_factor(nu: float) -> float: ...
@overload
def poisson_factor(nu: ArrayLike) -> float | NDArray[np.float64]: ...


def poisson_factor(nu: ArrayLike) -> float | NDArray[np.float64]:
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


def critical_velocity_ratios(nu: ArrayLike) -> dict[str, float | NDArray[np.float64]]:
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
    """An isotropic elastic-plastic material (SI units): elastic-perfectly plastic, or with linear
    strain hardening of tangent modulus ``Et``.

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
    Et : float, optional
        Tangent modulus of linear strain hardening (Pa), 0 <= Et < E. Default 0: elastic-perfectly
        plastic, JGM's material (every number exactly as without ``Et``). Above 0 an
        :class:`fastrest.Impact` whose yielding body this is loads by Ghaednia et al. (2019)
        (:mod:`fastrest.loading.ghaednia`) with Et/E = ``et_ratio``.

    Attributes
    ----------
    E, nu, Sy, rho, Et : float
        The inputs as Python floats (``rho`` may be None). The instance is frozen and pickles.
    et_ratio : float
        Et/E (-), the hardening parameter of the normalised API.

    Raises
    ------
    TypeError
        A parameter is not a single real number (strings, booleans, None except for ``rho``,
        arrays).
    ValueError
        E not finite and > 0; nu outside [0, 0.5); Sy not > 0 or NaN; rho not finite and > 0;
        Et negative, NaN, or not below E.

    Warns
    -----
    ValidityWarning
        E, Sy, rho or Sy/E outside the ranges of engineering solids (:data:`PLAUSIBLE`: E 1e6 to
        1e13 Pa, Sy 1e5 to 1e11 Pa, rho 30 to 3e4 kg/m^3, Sy/E 1e-5 to 0.1), almost always a unit
        mistake (E in GPa, Sy in MPa, rho in g/cm^3): the message says which value and the units.

    Notes
    -----
    Elastic-perfectly plastic (``Et = 0``, as JGM assume) or bilinear hardening (``Et > 0``); no rate
    effects (docs/model.md section 8). The critical values of an impact (eqs 4-7, 23-28) need two
    bodies: see :class:`fastrest.Impact`. The repr shows ``Et`` only when it is not 0.

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

    With strain hardening (tangent modulus 2 GPa, Et/E = 0.01):

    >>> hard = fastrest.Material(200e9, 0.33, 1.12e9, rho=7850.0, Et=2e9)
    >>> hard.et_ratio
    0.01
    >>> hard
    Material(E=200000000000.0, nu=0.33, Sy=1120000000.0, rho=7850.0, Et=2000000000.0)

    A modulus in GPa instead of Pa warns:

    >>> import warnings
    >>> with warnings.catch_warnings(record=True) as caught:
    ...     warnings.simplefilter("always")
    ...     m = fastrest.Material(200, 0.33, 1.12e9)
    >>> print(caught[0].message)  # doctest: +ELLIPSIS
    Material: E = 200.0 Pa is below 1e+06 Pa, implausible for a solid; check the units: E and Sy in Pa ...
    """

    E: float
    nu: float
    Sy: float
    rho: float | None = None
    Et: float = 0.0  # a class attribute too: pickles from before Et existed read 0 (no hardening)

    def __post_init__(self) -> None:
        # store plain floats: a string or a 1-element array here would fail far from its cause
        for name in ("E", "nu", "Sy") + (("rho",) if self.rho is not None else ()) + ("Et",):
            object.__setattr__(self, name, real_scalar(getattr(self, name), name))
        check_finite_positive(self.E, "E", "(Pa)")
        if not 0.0 <= self.Et < self.E:  # also NaN
            raise ValueError(f"Et (tangent modulus, Pa) must be >= 0 and below E = {self.E!r} Pa; got {self.Et!r}")
        object.__setattr__(self, "Et", self.Et + 0.0)  # -0.0 -> 0.0
        check_nu(self.nu)
        if not (self.Sy > 0) or math.isnan(self.Sy):
            raise ValueError(f"Sy must be > 0 (Pa) (math.inf for a body that never yields); got {self.Sy!r}")
        if self.rho is not None:
            check_finite_positive(self.rho, "rho", "(kg/m^3)")
        bad = implausible(self.E, self.Sy, self.rho)
        ratio = self.Sy / self.E
        lo, hi = PLAUSIBLE["eps_y"]
        if not bad and math.isfinite(ratio) and not lo <= ratio <= hi:
            bad = [f"Sy/E = {ratio:.3g} is {'below' if ratio < lo else 'above'} {lo if ratio < lo else hi:g}"]
        if bad:
            _warn_caller(f"Material: {'; '.join(bad)}, implausible for a solid; {UNITS_HINT}")

    def __repr__(self) -> str:
        et = f", Et={self.Et!r}" if self.Et != 0.0 else ""
        return f"Material(E={self.E!r}, nu={self.nu!r}, Sy={self.Sy!r}, rho={self.rho!r}{et})"

    @property
    def et_ratio(self) -> float:
        """Et/E (-): the tangent modulus over Young's modulus, 0 for elastic-perfectly plastic.

        Examples
        --------
        >>> import fastrest
        >>> fastrest.Material(200e9, 0.33, 1.12e9).et_ratio, fastrest.Material(200e9, 0.33, 1.12e9, Et=1e10).et_ratio
        (0.0, 0.05)
        """
        return self.Et / self.E

    @property
    def yield_product(self) -> float:
        """C(nu) Sy (Pa): of two bodies, the one with the smaller product yields first (JGM eq 5).

        ``inf`` for a body that never yields (``Sy = math.inf``).

        Examples
        --------
        >>> import fastrest
        >>> round(fastrest.Material(200e9, 0.33, 1.12e9).yield_product / 1e9, 4)  # GPa
        1.8491
        """
        return poisson_factor(self.nu) * self.Sy


# Impact lived here before it moved to fastrest.impact (it sits above the solver): old imports and
# pickles that name fastrest.materials.Impact keep working, with a DeprecationWarning. The alias is
# registered by fastrest.impact (imported with the package), so this module never imports upward.
__getattr__ = module_getattr(__name__)
