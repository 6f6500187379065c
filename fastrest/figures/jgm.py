"""JGM Figs 2-4: the model's own quantities (energy, maximum and residual interference)."""
from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING
if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure
import numpy as np

from .. import direct
from ..contact import P_star
from ..energy import W_star
from ..unloading import etsion
from ..unloading.jcg import residual_ratio as jcg_residual_ratio
from .._doc import doc
from ._common import (COLOURS, EPS_Y_SERIES, FIGURE_DOC, TABLE1_EPS_Y, TABLE1_NU, eps_colours, eps_label,
                      finish_axes, mark, new_axes, omega_grid, v_grid)

__all__ = ["figure2", "figure3", "figure4"]


@doc(FIGURE_DOC)
def figure2(*, ax: Axes | None = None, eps_y: Sequence[float] = EPS_Y_SERIES, nu: float = TABLE1_NU,
            n: int = 300) -> tuple[Figure, Axes]:
    """JGM Fig 2: normalised elasto-plastic energy -(W_ep)* (eq 25) against w* (eq 13), log axes.

    -(W_ep)* = (5/2) int_1^w* P* dz (work done past the onset of yield, in units of U_c, eq 24),
    for several eps_y at nu = ``nu``, up to w* = 425. The Hertz value w*^2.5 - 1 (eq 19, no
    plasticity) is shown for reference.

    {params_series}

    {returns_material}

    Notes
    -----
    JGM eqs (9), (19), (24), (25) (:func:`fastrest.W_star`).

    Examples
    --------
    >>> from fastrest.figures import figure2
    >>> fig, ax = figure2(n=20)
    >>> len(ax.lines)
    6
    """
    fig, ax = new_axes(ax)
    w_ref = np.geomspace(1.01, 425.0, n)
    ax.plot(w_ref, w_ref**2.5 - 1.0, color=COLOURS["hertz"], ls="--", lw=1.2,
            label=r"Hertz, $w^{*5/2} - 1$ (eq 19)")
    for eps, col in zip(eps_y, eps_colours(len(eps_y))):
        w = omega_grid(eps, nu, 1.01, n)
        ax.plot(w, -np.asarray(W_star(w, eps, nu)), color=col, lw=1.6,
                label=f"JGM (eqs 9, 25), {eps_label(eps)}")
    finish_axes(ax, xlabel=r"normalised interference $\omega^* = \omega/\omega_c$ (eq 13) [-]",
                ylabel=r"normalised energy $-(W_{ep})^* = -W_{ep}/U_c$ (eq 25) [-]",
                title=rf"Fig. 2: elasto-plastic energy ($\nu$ = {nu:g})", xlim=(1.0, 425.0), ylog=True,
                legend_loc="upper left")
    return fig, ax


@doc(FIGURE_DOC)
def figure3(*, ax: Axes | None = None, eps_y: Sequence[float] = EPS_Y_SERIES, nu: float = TABLE1_NU,
            n: int = 300) -> tuple[Figure, Axes]:
    """JGM Fig 3: normalised maximum interference w_m* (eq 31) against V1* = V1/V_c (eq 30).

    Solution of the energy balance (29) for several eps_y at nu = ``nu``, each up to its own
    w_m* = 425 (or a/R = 1). The Hertz value w_m* = V1*^(4/5) (no plasticity) for reference.

    {params_series}

    {returns_material}

    Notes
    -----
    JGM eqs (19), (29)-(31), with the exact solver :func:`fastrest.direct.omega_m_exact`.

    Examples
    --------
    >>> from fastrest.figures import figure3
    >>> fig, ax = figure3(eps_y=(0.005,), n=20)
    >>> len(ax.lines)
    3
    """
    fig, ax = new_axes(ax)
    v_ref = np.geomspace(1.0, 1200.0, n)
    ax.plot(v_ref, v_ref**0.8, color=COLOURS["hertz"], ls="--", lw=1.2,
            label=r"Hertz, $V_1^{*4/5}$ (eq 19)")
    for eps, col in zip(eps_y, eps_colours(len(eps_y))):
        v = v_grid(eps, nu, 1.0, n)
        ax.plot(v, direct.omega_m_exact(v, eps, nu), color=col, lw=1.6,
                label=f"JGM (eq 29), {eps_label(eps)}")
    mark(ax, 425.0, r"model limit $\omega_m^*$ = 425", (1.1, 425.0), vertical=False, offset=(0, 4))
    finish_axes(ax, xlabel=r"normalised impact speed $V_1^* = V_1/V_c$ (eq 30) [-]",
                ylabel=r"normalised maximum interference $\omega_m^* = \omega_m/\omega_c$ (eq 31) [-]",
                title=rf"Fig. 3: maximum interference ($\nu$ = {nu:g})", xlim=(1.0, 1200.0), ylim=(0.8, 800.0),
                ylog=True, legend_loc="lower right")
    return fig, ax


@doc(FIGURE_DOC)
def figure4(*, ax: Axes | None = None, eps_y: float = TABLE1_EPS_Y, nu: float = TABLE1_NU, n: int = 400) -> tuple[Figure, Axes]:
    """JGM Fig 4: residual interference ratio w_res/w_m against w_m*: the JCG fit, eq (35).

    The finite element points of Jackson, Chusoipin & Green (2005) that the paper plots with the
    fit are not available and are not shown. For comparison, the ratio implied by Etsion et al.'s
    eq (33) for one material (:mod:`fastrest.unloading.etsion`: w_res/w_m = 1 - P_m*/(sqrt(A_m*)
    w_m*) normalised) is drawn too.

    {param_ax}
    eps_y : float
        Sy/E' (-) of the Etsion curve; default 0.005 (JGM Table 1).
    nu : float
        Poisson's ratio (-) of the Etsion curve; default 0.33.
    n : int
        Points per curve.

    {returns_material}

    Notes
    -----
    JGM eq (35) (:mod:`fastrest.unloading.jcg`) and eqs (33)-(34) with the JG area, eq (8).

    Examples
    --------
    >>> from fastrest.figures import figure4
    >>> fig, ax = figure4(n=20)
    >>> [line.get_label()[:8] for line in ax.lines[:2]]
    ['JCG fit,', 'Etsion e']
    """
    fig, ax = new_axes(ax)
    w = np.geomspace(1.0, 425.0, n)
    r_jcg = np.array([jcg_residual_ratio(x - 1.0) for x in w])
    ax.plot(w, r_jcg, color=COLOURS["jcg"], lw=1.8,
            label=r"JCG fit, eq (35): $1.02\,[1 - ((\omega_m^*+5.9)/6.9)^{-0.54}]$")
    we = omega_grid(eps_y, nu, 1.0, n)
    p = np.asarray(P_star(we, eps_y, nu))
    r_ets = np.array([etsion.residual(w, w - 1.0, pm, eps_y, nu, 0, 0.0)[0] / w for w, pm in zip(we, p)])
    ax.plot(we, r_ets, color=COLOURS["etsion"], lw=1.4, ls="--",
            label=rf"Etsion et al., eq (33) ($\varepsilon_y$ = {eps_y:g}, $\nu$ = {nu:g})")
    mark(ax, 1.9, r"JG law from $\omega^*$ = 1.9", (1.9, 0.9), vertical=True, offset=(4, 0))
    finish_axes(ax, xlabel=r"normalised maximum interference $\omega_m^* = \omega_m/\omega_c$ [-]",
                ylabel=r"residual interference ratio $\omega_{res}/\omega_m$ [-]",
                title="Fig. 4: residual interference after unloading", xlim=(1.0, 425.0), ylim=(0.0, 1.0),
                legend_loc="lower right")
    return fig, ax
