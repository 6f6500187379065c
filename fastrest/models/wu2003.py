"""Wu, Li & Thornton (2003), JGM eqs (39)-(41).

.. [Wu] C.Y. Wu, L.Y. Li, C. Thornton, "Rebound behaviour of spheres for plastic impacts",
   Int. J. Impact Eng. 28 (2003) 929-946.
"""
from __future__ import annotations

from typing import Any
from numpy.typing import ArrayLike, NDArray
import numpy as np

from .._validation import check_eps_y, check_nu
from ..materials import critical_velocity_ratios
from .._doc import doc
from ._common import MODEL_DOC, broadcast, check_v_star, finite_out, refuse_zero_speed

__all__ = ["wu", "wu_finite_plastic_velocity", "wu_branches"]


_WU_SCALES = ("jgm", "wu")


def _wu_inputs(v, eps, nu, scale):
    """Validate and broadcast; return (V, eps) with V the speed in the unit of eqs (39)-(41)."""
    if scale not in _WU_SCALES:
        raise ValueError(f"scale must be one of {_WU_SCALES}; got {scale!r}")
    if nu is None:
        if scale == "wu":
            raise ValueError("nu (Poisson's ratio, in [0, 0.5)) is required when scale='wu'")
        return broadcast((v, "v1_star"), (eps, "eps_y"))
    v, eps, nu = broadcast((v, "v1_star"), (eps, "eps_y"), (check_nu(nu), "nu"))
    if scale == "wu":
        v = v * np.asarray(critical_velocity_ratios(nu)["wu"])  # V1/V_y,Wu
    return v, eps


def wu_finite_plastic_velocity(eps_y: ArrayLike, nu: ArrayLike | None = None, *, scale: str = "jgm") -> float | NDArray[np.float64]:
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

    Raises
    ------
    TypeError
        An input is not real.
    ValueError
        eps_y <= 0, nu outside [0, 0.5), nu missing for ``scale='wu'``, an unknown ``scale``, a result that overflows, or shapes that do not broadcast (the message names the parameter).

    Notes
    -----
    JGM eq (39).

    Examples
    --------
    >>> from fastrest.models import wu_finite_plastic_velocity
    >>> wu_finite_plastic_velocity(0.005)
    320.0
    """
    eps = check_eps_y(eps_y)
    one, eps = _wu_inputs(np.float64(1.0), eps, nu, scale)  # one = V_c / V_y in this scale
    with np.errstate(over="ignore"):
        out = 0.008 / (eps * eps) / one
    return finite_out(out, ("eps_y", eps))


@doc(MODEL_DOC)
def wu(v1_star: ArrayLike, eps_y: ArrayLike, nu: ArrayLike | None = None, *, scale: str = "jgm") -> float | NDArray[np.float64]:
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

    {params_v1_eps_y}
    nu : float or array_like, optional
        Poisson's ratio, 0 <= nu < 0.5; required for ``scale="wu"``, ignored (but validated and
        broadcast) for ``scale="jgm"``.
    scale : {"jgm", "wu"}, optional
        Velocity unit of eqs (39)-(41): JGM's V_c (default) or Wu et al.'s V_y,Wu.

    {returns_e}
    ValueError
        v1_star negative or not finite, eps_y <= 0, nu outside [0, 0.5), nu missing for ``scale='wu'``, an unknown ``scale``, or shapes that do not broadcast (the message names the parameter).

    Notes
    -----
    JGM eqs (39)-(41) as described above; both branches everywhere: :func:`wu_branches`.

    Examples
    --------
    >>> from fastrest.models import wu
    >>> wu(0.5, 0.005), round(wu(10.0, 0.005), 4), round(wu(500.0, 0.005), 4)
    (1.0, 1.1697, 0.3921)
    """
    v = check_v_star(v1_star)
    eps = check_eps_y(eps_y)
    V, eps = _wu_inputs(v, eps, nu, scale)
    with np.errstate(all="ignore"):
        V_fp = 0.008 / (eps * eps)
        plastic = V > 1.0
        Vs = np.where(plastic, V, 1.0)
        e40, e41 = _eqs_40_41(Vs, eps)
        e = np.where(Vs <= V_fp, e40, e41)
    return finite_out(np.where(plastic, e, 1.0), ("v1_star", V), ("eps_y", eps))


def _eqs_40_41(V, eps):
    """e of Wu et al.'s eq (40) and of eq (41) at V (in the unit of eqs 39-41), as printed."""
    return 2.08 * V**-0.25, 0.62 * (V * eps) ** -0.5


def wu_branches(v1_star: ArrayLike, eps_y: ArrayLike, nu: ArrayLike | None = None, *, scale: str = "jgm") -> tuple[Any, Any]:
    """Both branches of Wu et al. (2003) [Wu]_, JGM eqs (40) and (41), each at every speed.

    :func:`wu` takes eq (40) up to V_fp (eq 39) and eq (41) above; this gives both everywhere, for
    drawing each outside its range (JGM Fig 6).

    Parameters
    ----------
    v1_star : float or array_like
        V1 / V_c, V_c of JGM eq (28); finite and > 0 (dimensionless).
    eps_y : float or array_like
        Sy / E' (dimensionless), > 0.
    nu : float or array_like, optional
        Poisson's ratio, 0 <= nu < 0.5; required for ``scale="wu"`` (as in :func:`wu`).
    scale : {"jgm", "wu"}, optional
        Velocity unit of eqs (39)-(41): JGM's V_c (default) or Wu et al.'s V_y,Wu.

    Returns
    -------
    e40, e41 : float or ndarray
        2.08 V^(-1/4) (eq 40) and 0.62 (V eps_y)^(-1/2) (eq 41) (dimensionless), not clipped.

    Raises
    ------
    TypeError
        An input is not real.
    ValueError
        v1_star <= 0 or not finite (both formulas are infinite at 0), eps_y <= 0, nu outside
        [0, 0.5), an unknown ``scale``, or shapes that do not broadcast.

    Notes
    -----
    JGM eqs (40), (41); :func:`wu` is ``where(V <= V_fp, e40, e41)`` for V > 1 and 1 below.

    Examples
    --------
    >>> from fastrest.models import wu_branches
    >>> e40, e41 = wu_branches(16.0, 0.005)
    >>> e40, round(e41, 4)
    (1.04, 2.192)
    """
    v = check_v_star(v1_star)
    eps = check_eps_y(eps_y)
    V, eps = _wu_inputs(v, eps, nu, scale)
    refuse_zero_speed(V, "v1_star", "Wu et al.'s eqs (40)-(41)")
    with np.errstate(all="ignore"):  # overflow: refused by finite_out below
        e40, e41 = _eqs_40_41(V, eps)
    return finite_out(e40, ("v1_star", V)), finite_out(e41, ("v1_star", V), ("eps_y", eps))
