"""Yield velocities of the other models against JGM's critical velocity (JGM section 2.5, Table 2)."""
from __future__ import annotations

from typing import TYPE_CHECKING, Any
from numpy.typing import ArrayLike, NDArray
if TYPE_CHECKING:
    from ..impact import Impact
import numpy as np

from .._validation import check_nu
from ..materials import critical_velocity_ratios, poisson_factor
from ._common import finite_out
from .chang_ling1992 import ceb_hardness_factor

__all__ = ["yield_velocity_ratio", "yield_velocity"]

_YIELD_MODELS = ("jgm", "johnson", "wu", "thornton", "ceb")


def yield_velocity_ratio(nu: ArrayLike, model: str) -> float | NDArray[np.float64]:
    """Ratio V_c / V_y of JGM's critical velocity (eq 28) to another model's yield velocity.

    JGM section 2.5 and Table 2. ``"johnson"``, ``"wu"`` and ``"thornton"`` come from
    :func:`fastrest.materials.critical_velocity_ratios` (sqrt((pi C)^5 / 3180), (C/1.6)^(5/2) and
    C^(5/2) with C = C(nu) of eq 5). Two more are provided for convenience:

    * ``"jgm"``: 1;
    * ``"ceb"``: (C / (K H / Sy))^(5/2), with K H of :func:`~fastrest.models.ceb_hardness_factor`. CEB's onset of
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

    Raises
    ------
    TypeError
        An input is not real.
    ValueError
        nu outside [0, 0.5), an unknown ``model``, or shapes that do not broadcast (the message names the parameter).

    Notes
    -----
    JGM Table 2, with C(nu) of JGM eq (5).

    Examples
    --------
    >>> from fastrest.models import yield_velocity_ratio
    >>> yield_velocity_ratio(0.3, "jgm"), round(yield_velocity_ratio(0.3, "thornton"), 4)
    (1.0, 3.3144)
    """
    if model not in _YIELD_MODELS:
        raise ValueError(f"model must be one of {_YIELD_MODELS}; got {model!r}")
    nu_a = check_nu(nu)
    if model == "jgm":
        return finite_out(np.ones_like(nu_a))
    if model == "ceb":
        C = np.asarray(poisson_factor(nu_a))
        return finite_out((C / np.asarray(ceb_hardness_factor(nu_a))) ** 2.5)
    return finite_out(critical_velocity_ratios(nu_a)[model])


def yield_velocity(impact: Impact, model: str) -> float:
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

    Raises
    ------
    ValueError
        An unknown ``model``, or the impact's nu outside [0, 0.5).

    Notes
    -----
    JGM eq (28) and Table 2.

    Examples
    --------
    >>> import fastrest
    >>> from fastrest.models import yield_velocity
    >>> imp = fastrest.Impact(fastrest.Material(E=200e9, nu=0.33, Sy=1.12e9, rho=7800.0), R=0.01)
    >>> yield_velocity(imp, "jgm") == imp.V_c
    True
    """
    return float(impact.V_c / yield_velocity_ratio(impact.nu, model))
