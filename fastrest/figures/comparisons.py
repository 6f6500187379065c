"""JGM Figs 5-6: e against V1*, this model beside Chang-Ling, the unloading models and Wu et al."""
from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING
if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure
import numpy as np

from .. import direct
from .. import models
from .._doc import doc
from ._common import (COLOURS, EPS_Y_SERIES, FIGURE_DOC, LABELS, TABLE1_EPS_Y, TABLE1_NU, eps_colours, eps_label,
                      finish_axes, new_axes, v_grid)

__all__ = ["figure5", "figure6"]

_V_LABEL = r"normalised impact speed $V_1^* = V_1/V_c$ (eq 30) [-]"
_E_LABEL = r"coefficient of restitution $e = V_2/V_1$ (eq 16) [-]"


@doc(FIGURE_DOC)
def figure5(*, ax: Axes | None = None, eps_y: Sequence[float] = EPS_Y_SERIES, nu: float = TABLE1_NU,
            n: int = 400) -> tuple[Figure, Axes]:
    """JGM Fig 5: e against V1* for several eps_y, this model (JCG unloading, eq 35) and Chang-Ling.

    Chang & Ling's eq (1) (CEB contact law; see :func:`fastrest.models.chang_ling` for the reading
    of the misprinted equation) does not depend on eps_y once V1 is normalised by V_c: one curve.

    {params_series}

    {returns_material}

    Notes
    -----
    JGM eqs (16), (29), (35), (38) with the exact solver :func:`fastrest.direct.e_exact`; eq (1).

    Examples
    --------
    >>> from fastrest.figures import figure5
    >>> fig, ax = figure5(eps_y=(0.002, 0.005), n=20)
    >>> len(ax.lines)
    3
    """
    fig, ax = new_axes(ax)
    v_lo = 0.5
    v_top = 0.0
    for eps, col in zip(eps_y, eps_colours(len(eps_y))):
        v = v_grid(eps, nu, v_lo, n)
        v_top = max(v_top, v[-1])
        ax.plot(v, direct.e_exact(v, eps, nu, "jcg"), color=col, lw=1.6,
                label=f"JGM, eq (35), {eps_label(eps)}")
    v = np.geomspace(v_lo, v_top, n)
    ax.plot(v, models.chang_ling(v, TABLE1_EPS_Y, nu), color=COLOURS["chang_ling"], lw=1.6, ls="--",
            label=LABELS["chang_ling"] + r" (any $\varepsilon_y$)")
    finish_axes(ax, xlabel=_V_LABEL, ylabel=_E_LABEL,
                title=rf"Fig. 5: JGM (JCG unloading) vs Chang-Ling ($\nu$ = {nu:g})", xlim=(v_lo, v_top),
                ylim=(0.0, 1.05), legend_loc="lower left")
    return fig, ax


@doc(FIGURE_DOC)
def figure6(*, ax: Axes | None = None, eps_y: float = TABLE1_EPS_Y, nu: float = TABLE1_NU, n: int = 400) -> tuple[Figure, Axes]:
    """JGM Fig 6: e against V1* with JCG (eq 35) and Etsion (eq 33) unloading, and Wu et al.

    With, as an extra curve not in the paper, the JG loading with Brake's unloading
    (:mod:`fastrest.unloading.brake`). Wu et al.'s eqs (40) (below V_fp) and (41) (above) are drawn
    solid where each applies and dotted outside (:func:`fastrest.models.wu_branches`); the
    vertical line is V_fp of eq (39), 0.008 V_c (E'/Sy)^2 (V1* = 320 for the Table 1 material).
    Eq (40) exceeds 1 for V1* < 2.08^4 = 18.7 (up to 2.08 just above V_c) and runs off the top of
    the plot, as the paper notes.

    {param_ax}
    eps_y : float
        Sy/E' (-); default 0.005 (JGM Table 1).
    nu : float
        Poisson's ratio (-); default 0.33.
    n : int
        Points per curve.

    {returns_material}

    Notes
    -----
    JGM eqs (33), (35), (38) (exact solver) and eqs (39)-(41).

    Examples
    --------
    >>> from fastrest.figures import figure6
    >>> fig, ax = figure6(n=20)
    >>> ax.lines[3].get_label()
    'Wu et al. (2003), eqs (39)-(41)'
    """
    fig, ax = new_axes(ax)
    v = v_grid(eps_y, nu, 0.5, n)
    for model in ("jcg", "etsion", "brake"):
        ax.plot(v, direct.e_exact(v, eps_y, nu, model), color=COLOURS[model], lw=1.8,
                ls="--" if model == "brake" else "-", label=LABELS[model])
    v_fp = float(models.wu_finite_plastic_velocity(eps_y))
    vp = v[v > 1.0]
    e40, e41 = models.wu_branches(vp, eps_y)
    below = vp <= v_fp
    # e = 1 below V_c (as this model); drawn from V_c up, so the jump to 2.08 at V_c is not a line
    ax.plot(vp, models.wu(vp, eps_y), color=COLOURS["wu"], lw=1.6, label=LABELS["wu"])
    ax.plot(vp[~below], e40[~below], color=COLOURS["wu"], lw=1.0, ls=":",
            label="Wu et al., eqs (40), (41) outside their ranges")
    ax.plot(vp[below], e41[below], color=COLOURS["wu"], lw=1.0, ls=":")
    ax.axvline(v_fp, color="k", lw=0.9, ls="--")
    ax.annotate(rf"$V_{{fp}}$ (eq 39) = {v_fp:.0f} $V_c$", (v_fp, 1.12), xytext=(-4, 0),
                textcoords="offset points", fontsize=8, ha="right")
    finish_axes(ax, xlabel=_V_LABEL, ylabel=_E_LABEL,
                title=rf"Fig. 6: effect of the unloading model ($\varepsilon_y$ = {eps_y:g}, $\nu$ = {nu:g})",
                xlim=(0.5, v[-1]), ylim=(0.0, 1.2), legend_loc="lower left")
    return fig, ax
