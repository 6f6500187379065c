"""JGM Figs 7-8: alumina spheres on aluminium and on steel (Kharaz & Gorham's impacts), in m/s.

The tables (JGM Tables 3-4) list the density of the *flat*, but the moving body is the alumina
sphere. These figures use the alumina sphere's mass, m = (4/3) pi R^3 rho, with an assumed alumina
density :data:`ALUMINA_DENSITY` = 3950 kg/m^3 (not given in the paper), and E' from both bodies'
elasticity (1/E' = sum (1-nu^2)/E). The experimental points of Kharaz & Gorham (2000) shown in the
paper are not reproduced (the data are not available to fastrest).
"""
from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING
if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure
import math

import numpy as np

from .. import models
from ..impact import Impact
from ..materials import Material
from .._doc import fill
from ._common import COLOURS, FIGURE_DOC, LABELS, finish_axes, mark, new_axes

__all__ = ["ALUMINA_DENSITY", "ALUMINA", "ALUMINIUM_FLAT", "STEEL_FLAT", "KHARAZ_RADIUS", "kharaz_impact", "figure7",
           "figure8"]

#: Density of the alumina (aluminium oxide) spheres of JGM Figs 7-8 (kg/m^3). An assumption:
#: JGM Tables 3-4 give only the flats' densities. Typical sintered alumina is 3900-3990 kg/m^3.
ALUMINA_DENSITY = 3950.0

#: Alumina sphere of JGM Tables 3-4 (never yields: JGM section 3.2, "the aluminum oxide spheres
#: were believed to only deform elastically").
ALUMINA = Material(E=370e9, nu=0.22, Sy=math.inf, rho=ALUMINA_DENSITY)
#: Flat of JGM Table 3 (aluminium), with the density the table prints.
ALUMINIUM_FLAT = Material(E=68e9, nu=0.33, Sy=0.38e9, rho=2700.0)
#: Flat of JGM Table 4 (steel), with the density the table prints.
STEEL_FLAT = Material(E=200e9, nu=0.29, Sy=1.03e9, rho=7800.0)
#: Sphere radius of JGM Tables 3-4 (m).
KHARAZ_RADIUS = 0.0025


def kharaz_impact(flat: str) -> Impact:
    """The impact of JGM Figs 7-8: an alumina sphere (R = 2.5 mm) on a flat ``"aluminium"`` or ``"steel"``.

    The mass is the alumina sphere's, (4/3) pi R^3 :data:`ALUMINA_DENSITY` (an assumed density;
    the paper's Tables 3-4 list only the flats' densities). E' combines both bodies
    (1/E' = (1 - 0.22^2)/370 GPa + (1 - nu^2)/E_flat); the flat yields (the sphere never does),
    so nu, Sy and C are the flat's.

    Parameters
    ----------
    flat : {"aluminium", "steel"}
        The flat of JGM Table 3 (aluminium) or Table 4 (steel).

    Returns
    -------
    fastrest.Impact
        Sphere :data:`ALUMINA` of radius :data:`KHARAZ_RADIUS` (m) on the flat.

    Raises
    ------
    ValueError
        Another ``flat``.

    Notes
    -----
    JGM Tables 3-4; E' of JGM section 2.1, V_c of eq (28).

    Examples
    --------
    >>> from fastrest.figures import kharaz_impact
    >>> round(kharaz_impact("steel").V_c, 4)
    0.1407
    """
    mats = {"aluminium": ALUMINIUM_FLAT, "steel": STEEL_FLAT}
    if flat not in mats:
        raise ValueError(f"flat must be one of {sorted(mats)}; got {flat!r}")
    return Impact(ALUMINA, KHARAZ_RADIUS, flat=mats[flat])


def _figure_kharaz(ax, flat, fig_no, v_max, n):
    fig, ax = new_axes(ax)
    imp = kharaz_impact(flat)
    V = np.unique(np.concatenate([np.linspace(0.0, v_max, n)[1:], imp.V_c * np.geomspace(0.5, 4.0, 40)]))
    V = V[V <= v_max]
    # this model: e = 1 up to V_c, both unloadings (exact solver)
    for model in ("jcg", "etsion"):
        ax.plot(V, imp.e(V, unloading=model), color=COLOURS[model], lw=1.9, label=LABELS[model])
    for model, ls in (("thornton", "-."), ("wu", "--"), ("weir_tallon", ":")):
        e = np.asarray(models.evaluate(model, imp, V))
        if model == "wu":  # e = 1 up to V_c, then eq (40) jumps to 2.08: do not draw the jump
            e = np.where(V > imp.V_c, e, np.nan)
        ax.plot(V, e, color=COLOURS[model], lw=1.5, ls=ls, label=LABELS[model])
    mark(ax, imp.V_c, rf"$V_c$ (eq 28) = {imp.V_c * 1e3:.0f} mm/s", (imp.V_c, 0.12), vertical=True, offset=(3, 0))
    flat_name = {"aluminium": "an aluminium", "steel": "a steel"}[flat]
    table = {"aluminium": 3, "steel": 4}[flat]
    info = (f"inputs of JGM Table {table}; sphere mass m = {imp.mass * 1e3:.3f} g "
            f"(alumina, assumed $\\rho$ = {ALUMINA_DENSITY:.0f} kg/m$^3$)\n"
            f"E' = {imp.E_eff / 1e9:.1f} GPa (sphere + flat), $\\varepsilon_y$ = {imp.eps_y:.4f}, "
            f"$\\nu$ = {imp.nu:g}, $V_c$ = {imp.V_c:.4f} m/s; Kharaz-Gorham data not shown")
    ax.text(0.99, 0.015, info, transform=ax.transAxes, fontsize=6.5, ha="right", va="bottom",
            bbox=dict(boxstyle="round", fc="white", ec="0.7", alpha=0.9))
    finish_axes(ax, xlabel=r"impact speed $V_1$ [m/s]", ylabel=r"coefficient of restitution $e = V_2/V_1$ [-]",
                title=f"Fig. {fig_no}: alumina sphere (R = {KHARAZ_RADIUS * 1e3:g} mm) on {flat_name} flat",
                xlim=(0.0, v_max), ylim=(0.0, 1.4), xlog=False, legend_loc="upper right", legend_size=7.5)
    return fig, ax


_KHARAZ_DOC = """JGM Fig {no}: e against V1 (m/s), alumina sphere on {a} {flat} flat (Table {table} inputs).

This model with both unloadings (eqs 33, 35), Thornton (eq 2), Wu et al. (eqs 39-41) and
Weir-Tallon (eq 3). Mass and E' as in :func:`kharaz_impact`. Curves above e = 1.4 (Wu et al.
and Weir-Tallon at low speed) run off the plot.

{{param_ax}}
v_max : float
    Largest impact speed drawn (m/s).
n : int
    Speeds per curve (plus 40 around V_c).

{{returns}}

Notes
-----
JGM eqs (2), (3), (28), (33), (35), (39)-(41) for :func:`kharaz_impact` ``("{flat}")``.

Examples
--------
>>> from fastrest.figures import figure{no}
>>> fig, ax = figure{no}(v_max=1.0, n=20)
>>> len(ax.lines)
6
"""


def figure7(*, ax: Axes | None = None, v_max: float = 5.0, n: int = 400) -> tuple[Figure, Axes]:
    return _figure_kharaz(ax, "aluminium", 7, v_max, n)


def figure8(*, ax: Axes | None = None, v_max: float = 5.0, n: int = 400) -> tuple[Figure, Axes]:
    return _figure_kharaz(ax, "steel", 8, v_max, n)


# the figure's fields, then the shared paragraphs (``{{name}}`` in the template)
figure7.__doc__ = fill(_KHARAZ_DOC.format(no=7, a="an", flat="aluminium", table=3), FIGURE_DOC)
figure8.__doc__ = fill(_KHARAZ_DOC.format(no=8, a="a", flat="steel", table=4), FIGURE_DOC)
