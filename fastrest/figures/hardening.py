"""Not in JGM: e against V1* with strain hardening (Ghaednia et al. 2019) beside the
elastic-perfectly plastic curve (docs/model.md section 12)."""
from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING
if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure
import numpy as np

from .. import direct
from ..limits import speed_limit
from .._doc import doc
from ._common import FIGURE_DOC, TABLE1_EPS_Y, TABLE1_NU, finish_axes, new_axes

__all__ = ["figure_hardening", "ET_RATIO_SERIES"]

#: Tangent modulus ratios Et/E of :func:`figure_hardening` (0: elastic-perfectly plastic, JG).
ET_RATIO_SERIES = (0.0, 0.001, 0.01, 0.05, 0.2)


@doc(FIGURE_DOC)
def figure_hardening(*, ax: Axes | None = None, et_ratio: Sequence[float] = ET_RATIO_SERIES,
                     eps_y: float = TABLE1_EPS_Y, nu: float = TABLE1_NU, unloading: str = "brake",
                     n: int = 300) -> tuple[Figure, Axes]:
    """e against V1* for several tangent moduli Et/E (Ghaednia et al. 2019), with Et/E = 0 (JG).

    {param_ax}
    et_ratio : sequence of float
        Et/E (-) of each curve, each in [0, 1); default :data:`ET_RATIO_SERIES`.
    eps_y, nu : float
        Material (-); default JGM Table 1 (0.005, 0.33).
    unloading : str
        Unloading model; default ``"brake"``, the pairing the hardening law's peers use.
    n : int
        Points per curve.

    {returns}
    ValueError
        A parameter outside the model's domain.

    Notes
    -----
    The exact solver (:func:`fastrest.direct.e_exact` with ``et_ratio``), each curve up to its own
    limit speed (w_m* = 425; hardening needs more energy to get there).

    Examples
    --------
    >>> from fastrest.figures.hardening import figure_hardening
    >>> fig, ax = figure_hardening(n=20)
    >>> len(ax.lines)
    5
    """
    fig, ax = new_axes(ax)
    v_top = 0.0
    for h in et_ratio:
        lim = speed_limit(eps_y, nu, et_ratio=h)
        v_top = max(v_top, lim)
        v = np.geomspace(0.5, lim, n)
        e = direct.e_exact(v, eps_y, nu, unloading, et_ratio=h)
        label = "Et/E = 0 (Jackson-Green, elastic-perfectly plastic)" if h == 0 else f"Et/E = {h:g}"
        ax.plot(v, e, lw=2.0 if h == 0 else 1.2, ls="-" if h == 0 else "--", label=label)
    finish_axes(ax, xlabel=r"normalised impact speed $V_1^* = V_1/V_c$ (eq 30) [-]",
                ylabel=r"coefficient of restitution $e = V_2/V_1$ [-]",
                title=f"Ghaednia et al. (2019) hardening, {unloading} unloading, eps_y = {eps_y:g}, nu = {nu:g}",
                xlim=(0.5, v_top), legend_loc="lower left")
    return fig, ax
