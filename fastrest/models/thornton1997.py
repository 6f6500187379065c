"""Thornton (1997), JGM eq (2).

.. [Th] C. Thornton, "Coefficient of restitution for collinear collisions of elastic-perfectly
   plastic spheres", J. Appl. Mech. 64 (1997) 383-386.
"""
from __future__ import annotations

from typing import Any
from numpy.typing import ArrayLike, NDArray
import math

import numpy as np

from ..materials import critical_velocity_ratios
from ._common import finite_out, v_star_inputs

__all__ = ["THORNTON_COEFFICIENT", "thornton"]

#: Exact prefactor of Thornton's eq (JGM eq 2): sqrt(6 sqrt(3) / 5) = 1.44169...; JGM print 1.442.
THORNTON_COEFFICIENT = math.sqrt(6.0 * math.sqrt(3.0) / 5.0)


def thornton(v1_star: ArrayLike, nu: ArrayLike) -> float | NDArray[np.float64]:
    """Coefficient of restitution of Thornton (1997) [Th]_, JGM eq (2).

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

    Raises
    ------
    TypeError
        An input is not real.
    ValueError
        v1_star negative or not finite, nu outside [0, 0.5), or shapes that do not broadcast.

    Notes
    -----
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

    Examples
    --------
    >>> from fastrest.models import thornton
    >>> thornton([0.1, 10.0], 0.3).round(4)  # below the onset of yield, and above
    array([1.    , 0.4922])
    """
    v, nu = v_star_inputs(v1_star, nu=nu)
    ratio = v * np.asarray(critical_velocity_ratios(nu)["thornton"])  # V1 / V_y,Th
    plastic = ratio > 1.0
    x = 1.0 / np.where(plastic, ratio, 1.0)
    e = (THORNTON_COEFFICIENT * np.sqrt(1.0 - x * x / 6.0)
         * (x / (x + 2.0 * np.sqrt((6.0 - x * x) / 5.0))) ** 0.25)
    return finite_out(np.where(plastic, e, 1.0), ("v1_star", v), ("nu", nu))
