"""The result of a rough-surface impact: :class:`RoughImpact`."""
from __future__ import annotations

from typing import Any
from numpy.typing import ArrayLike, NDArray
from dataclasses import dataclass, field, fields

import numpy as np

__all__ = ["RoughImpact"]


@dataclass
class RoughImpact:
    """Result of :meth:`RoughSurface.impact`: arrays over V1 (floats for a scalar V1).

    Attributes
    ----------
    V1 : ndarray or float
        Impact speed (m/s).
    M : float
        Mass of the flat (kg).
    unloading : str
        "jcg", "etsion" or "brake".
    V1_star : ndarray or float
        V1 / V_c (-), V_c = sqrt(2 U_c / M) of one summit (JGM eq 28 with the flat's mass).
    e : ndarray or float
        Coefficient of restitution of the surface e_s = V2 / V1 (-).
    loss : ndarray or float
        Dissipated fraction 1 - e_s^2 (-), accurate near 0 (also near the onset of yield).
    d_min : ndarray or float
        Deepest approach: distance of the flat above the mean summit plane (m); negative when the
        flat ends below that plane.
    force_max : ndarray or float
        Total contact force at d_min (N), the largest force of the impact.
    n_contact : ndarray or int or float
        Summits in contact at d_min (w* > 0): a count for explicit summits, the expected number
        (float) for a statistical surface.
    n_yielded : ndarray or int or float
        Summits loaded past the onset of yield (w* > 1), same convention.
    dissipated : ndarray or float
        Energy dissipated (J) = loss * energy_in.
    energy_in : ndarray or float
        (1/2) M V1^2 (J).
    w_star_max : ndarray or float
        Explicit summits: w* of the tallest summit at d_min; statistical: w* at the upper end of
        the height integration (where the height distribution is truncated) (-).
    kind : str
        "explicit" or "statistical".

    Notes
    -----
    e_s^2 = 1 - sum_i L(w_i) / (V1/V_c)^2 with L the energy a summit dissipates (JGM eq 38 per
    summit); docs/rough.md section 3.

    Examples
    --------
    >>> import fastrest
    >>> from fastrest import rough
    >>> s = rough.RoughSurface(fastrest.Material(E=200e9, nu=0.3, Sy=1e9), 1e-4, heights=[0.0, 1e-8])
    >>> r = s.impact(0.01, 1e-3)
    >>> r.n_contact, round(r.e, 6) == round(r["e"], 6)
    (2, True)
    """

    V1: float | np.ndarray
    M: float
    unloading: str
    V1_star: float | np.ndarray
    e: float | np.ndarray
    loss: float | np.ndarray
    d_min: float | np.ndarray
    force_max: float | np.ndarray
    n_contact: float | np.ndarray
    n_yielded: float | np.ndarray
    dissipated: float | np.ndarray
    energy_in: float | np.ndarray
    w_star_max: float | np.ndarray
    kind: str = field(default="explicit")

    def as_dict(self) -> dict[str, Any]:
        """The fields as a plain dict (name -> value)."""
        return {f.name: getattr(self, f.name) for f in fields(self)}

    def __getitem__(self, key):
        return getattr(self, key)
