"""Successive impacts on the same spot, exact: the energy balance on the reloading curve.

JGM's contact law remembers: a contact that unloaded from its largest interference w_max reloads
along the same elastic unloading curve (JGM eq 32: P = P_max ((w - w_res)/(w_max - w_res))^(3/2),
reversible) up to w_max, then follows the virgin law again, and unloads from the new maximum by
the unloading model (which depends on w_max alone). So the energy an impact at speed V puts into
the contact, (1/2) m V^2, first fills the reloading curve, which holds what the last impact gave
back, R = (1/2) m (e_eq V_eq)^2, and goes on along the virgin law:

* V^2 <= (e_eq V_eq)^2: the impact stays on the reloading curve; e = 1, nothing changes, and the
  largest interference is w_res + (w_max - w_res) (V^2 / (e_eq V_eq)^2)^(2/5);
* otherwise the contact reaches the w_max of a single impact at the equivalent speed
  V_eq'^2 = V^2 - (e_eq V_eq)^2 + V_eq^2 (the virgin law's work up to it equals the work up to
  the old maximum plus what the impact puts in beyond the reloading curve), unloads as that impact
  does, and e = e(V_eq') V_eq' / V.

Here V_eq is the speed whose single impact reaches the contact's present w_max (0 for a fresh
contact), so each impact costs one exact solve (:meth:`fastrest.Impact.e`). The model assumes
what the law does: reloading elastic along the unloading curve and no further plasticity below
w_max (Kadin, Kligerman & Etsion 2006 found reloading elastic up to the previous maximum in their
finite elements, and elastic shakedown after a few cycles at a constant load); no cyclic
plasticity, no wear, no rate effects.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ._validation import as_float_array, check_bool, check_count, real_scalar

__all__ = ["RepeatedImpacts", "repeated_impacts"]


@dataclass(frozen=True)
class RepeatedImpacts:
    """Successive impacts on one spot (:meth:`fastrest.Impact.repeated_impacts`), one entry per
    impact, in order.

    Attributes
    ----------
    V : ndarray
        Impact speeds (m/s).
    e : ndarray
        Coefficient of restitution of each impact (-); 1 where it stayed on the reloading curve.
    max_interference : ndarray
        Largest interference of each impact (m).
    residual_interference : ndarray
        Residual interference after each impact (m): the depth of the permanent dent.
    plastic : ndarray of bool
        Where the impact went past the contact's earlier largest interference (new plasticity).

    Examples
    --------
    >>> import fastrest
    >>> steel = fastrest.Material(200e9, 0.3, 1e9, rho=7850.0)
    >>> r = fastrest.Impact(steel, 0.01).repeated_impacts(0.5, 6)
    >>> [round(x, 4) for x in r.e]
    [0.7989, 0.9108, 0.9572, 0.9789, 0.9894, 0.9947]
    >>> r.shakedown(0.98)  # the first impact with e >= 0.98 (1-based)
    5
    """

    V: NDArray[np.float64]
    e: NDArray[np.float64]
    max_interference: NDArray[np.float64]
    residual_interference: NDArray[np.float64]
    plastic: NDArray[np.bool_]

    def shakedown(self, e_min: float = 0.99) -> int | None:
        """The number (1-based) of the first impact whose e >= ``e_min``, or None if none is.

        Parameters
        ----------
        e_min : float
            In (0, 1] (default 0.99).

        Returns
        -------
        int or None

        Raises
        ------
        TypeError
            ``e_min`` not a real number.
        ValueError
            ``e_min`` outside (0, 1].

        Examples
        --------
        >>> import fastrest
        >>> r = fastrest.Impact(fastrest.Material(200e9, 0.3, 1e9, rho=7850.0), 0.01).repeated_impacts(0.5, 3)
        >>> r.shakedown(1.0) is None
        True
        """
        x = real_scalar(e_min, "e_min")
        if not 0.0 < x <= 1.0:
            raise ValueError(f"e_min must be in (0, 1]; got {e_min!r}")
        hit = np.flatnonzero(self.e >= x)
        return int(hit[0]) + 1 if hit.size else None


def repeated_impacts(impact: Any, V1: ArrayLike, n: int | None = None, unloading: str = "jcg", *,
                     extrapolate: bool = False) -> RepeatedImpacts:
    """Successive impacts at speeds ``V1`` on the same spot of a fresh contact (module docstring).

    Parameters
    ----------
    impact : fastrest.Impact
        The bodies (:meth:`fastrest.Impact.repeated_impacts` calls this with itself).
    V1 : float or array_like
        Impact speed (m/s), > 0 and finite: one speed repeated ``n`` times, or a sequence of
        speeds (one per impact, 1-D).
    n : int, optional
        Number of impacts at the one speed ``V1`` (1 to 1e6); not given with a sequence of speeds.
    unloading : {"jcg", "etsion", "brake"}
        Unloading model (as in :meth:`fastrest.Impact.e`).
    extrapolate : bool
        As in :meth:`fastrest.Impact.e`.

    Returns
    -------
    RepeatedImpacts

    Raises
    ------
    TypeError
        Non-numbers.
    ValueError
        A speed not finite and > 0; ``n`` missing for one speed, given with a sequence, not a whole
        number or outside 1 to 1e6; a sequence that is not 1-D or empty; an equivalent speed past the model's end
        (the message of :meth:`fastrest.Impact.e`, naming the impact).
    """
    speeds = as_float_array(V1, "V1")
    if speeds.ndim == 0:
        if n is None:
            raise ValueError("n (the number of impacts) is required with one speed V1")
        speeds = np.full(check_count(n, "n", 1, 10**6), float(speeds))
    else:
        if n is not None:
            raise ValueError("n is for one speed V1; a sequence of speeds gives one impact each")
        if speeds.ndim != 1 or speeds.size == 0:
            raise ValueError(f"V1 must be one speed or a 1-D sequence of speeds; got shape {speeds.shape}")
    bad = ~(np.isfinite(speeds) & (speeds > 0.0))
    if bad.any():
        i = int(np.flatnonzero(bad)[0])
        raise ValueError(f"V1 must be finite and > 0 (m/s); impact {i + 1} has {float(speeds[i])!r}")
    check_bool(extrapolate, "extrapolate")
    count = speeds.size
    e = np.empty(count)
    w_top = np.empty(count)
    w_res = np.empty(count)
    plastic = np.zeros(count, dtype=bool)
    v_eq, back2, top, res = 0.0, 0.0, 0.0, 0.0  # a fresh contact: nothing to reload
    for k, v in enumerate(speeds):
        v2 = v * v
        if v2 <= back2:  # on the reloading curve (elastic): the dent and the maximum stay
            e[k] = 1.0
            w_top[k] = res + (top - res) * (v2 / back2) ** 0.4
            w_res[k] = res
            continue
        v_eq = math.sqrt(v2 - back2 + v_eq * v_eq)
        try:
            e_eq = float(impact.e(v_eq, unloading, extrapolate=extrapolate))
            top = float(impact.max_interference(v_eq, extrapolate=extrapolate))
            res = float(impact.residual(v_eq, unloading, extrapolate=extrapolate)[0])
        except ValueError as exc:
            raise ValueError(f"impact {k + 1} at V1 = {float(v)!r} m/s takes the contact to the maximum of a single "
                             f"impact at {v_eq!r} m/s: {exc}") from None
        back2 = (e_eq * v_eq) ** 2
        e[k] = e_eq * v_eq / v
        w_top[k], w_res[k], plastic[k] = top, res, True
    return RepeatedImpacts(speeds, e, w_top, w_res, plastic)
