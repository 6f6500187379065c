"""The figures of Jackson, Green & Marghitu (2010), drawn from fastrest.

One function per figure of the paper (Figs 2-8; Fig 1 is a sketch). Each takes ``ax=None`` (a
Matplotlib Axes to draw into; by default a new :class:`matplotlib.figure.Figure` is made, without
pyplot, so no GUI backend is ever touched) and returns ``(fig, ax)``. :func:`write_all` writes all
of them as PNG files (``fastrest figures --out DIR``).

Matplotlib is imported only when a figure is drawn, so ``import fastrest`` works without it
(``pip install fastrest[plot]`` installs it).

Every curve is computed with the exact solver (:mod:`fastrest.direct`) or the closed forms of
:mod:`fastrest.models`, and stays inside the model's domain: V1* up to
:func:`fastrest.direct.v1_star_limit` (w_m* = 425, or a/R = 1 if that comes first).

Figs 7-8 (alumina spheres on aluminium and on steel, JGM Tables 3-4): the tables list the density
of the *flat*, but the moving body is the alumina sphere. These figures use the alumina sphere's
mass, m = (4/3) pi R^3 rho, with an assumed alumina density :data:`ALUMINA_DENSITY` = 3950 kg/m^3
(not given in the paper), and E' from both bodies' elasticity (1/E' = sum (1-nu^2)/E). The
experimental points of Kharaz & Gorham (2000) shown in the paper are not reproduced (the data are
not available to fastrest).
"""
import math
from pathlib import Path

import numpy as np

from . import direct
from . import models
from .contact import P_star
from .energy import W_star
from .materials import Impact, Material
from .unloading import etsion
from .unloading.jcg import residual_ratio as jcg_residual_ratio

#: Density of the alumina (aluminium oxide) spheres of JGM Figs 7-8 (kg/m^3). An assumption:
#: JGM Tables 3-4 give only the flats' densities. Typical sintered alumina is 3900-3990 kg/m^3.
ALUMINA_DENSITY = 3950.0

#: Alumina sphere of JGM Tables 3-4 (never yields: JGM section 3.2, "the aluminum oxide spheres
#: were believed to only deform elastically").
ALUMINA = Material(E=370e9, nu=0.22, Sy=math.inf, rho=ALUMINA_DENSITY)
#: Flats of JGM Table 3 (aluminium) and Table 4 (steel), with the densities the tables print.
ALUMINIUM_FLAT = Material(E=68e9, nu=0.33, Sy=0.38e9, rho=2700.0)
STEEL_FLAT = Material(E=200e9, nu=0.29, Sy=1.03e9, rho=7800.0)
#: Sphere radius of JGM Tables 3-4 (m).
KHARAZ_RADIUS = 0.0025

#: JGM Table 1 benchmark (eps_y = 0.005, nu = 0.33), used by Figs 2-6 unless stated otherwise.
TABLE1_EPS_Y = 0.005
TABLE1_NU = 0.33
#: eps_y values of Figs 2, 3 and 5 (the paper's validated range is 0.0005-0.01).
EPS_Y_SERIES = (0.0005, 0.001, 0.002, 0.005, 0.01)

# Colours per model (the same in every figure) and for eps_y series.
_COLOURS = {
    "jcg": "#1f77b4", "etsion": "#d62728", "thornton": "#2ca02c", "wu": "#9467bd",
    "weir_tallon": "#8c564b", "chang_ling": "#ff7f0e", "hertz": "0.45", "brake": "#17becf",
}
_LABELS = {
    "jcg": "JGM, JCG unloading, eq (35)",
    "etsion": "JGM, Etsion unloading, eq (33)",
    "brake": "JG loading, Brake unloading (not in the paper)",
    "thornton": "Thornton (1997), eq (2)",
    "wu": "Wu et al. (2003), eqs (39)-(41)",
    "weir_tallon": "Weir & Tallon (2005), eq (3)",
    "chang_ling": "Chang & Ling (1992), CEB, eq (1)",
}
_FIGSIZE = (6.4, 4.8)


def _new_axes(ax, figsize=_FIGSIZE):
    """Return (fig, ax): ``ax`` and its figure, or a new pyplot-free Figure with one Axes."""
    if ax is not None:
        return ax.figure, ax
    from matplotlib.figure import Figure

    fig = Figure(figsize=figsize, layout="constrained")
    return fig, fig.add_subplot()


def _eps_colours(n):
    from matplotlib import colormaps

    cmap = colormaps["viridis"]
    return [cmap(x) for x in np.linspace(0.0, 0.85, n)]


def _eps_label(eps_y):
    return rf"$\varepsilon_y$ = {eps_y:g}"


def _omega_grid(eps_y, nu, w_lo, n):
    """Log-spaced w* from w_lo to the model's end (425, or just below a/R = 1)."""
    from .contact import omega_star_limit

    w_hi = min(425.0, float(omega_star_limit(eps_y, nu)) * (1.0 - 1e-9))
    return np.geomspace(w_lo, w_hi, n)


def _v_grid(eps_y, nu, v_lo, n):
    """Log-spaced V1* from v_lo to the model's limit, with nodes either side of V1* = 1.9^1.25."""
    from .energy import V_SWITCH

    v_hi = direct.v1_star_limit(eps_y, nu)
    v = np.geomspace(v_lo, v_hi, n)
    v[-1] = v_hi
    extra = [1.0, V_SWITCH, np.nextafter(V_SWITCH, np.inf)]
    return np.unique(np.concatenate([v, [x for x in extra if v_lo <= x <= v_hi]]))


# ---------------------------------------------------------------------------------------------
# Fig 2: normalised elasto-plastic energy
# ---------------------------------------------------------------------------------------------
def figure2(ax=None, eps_y=EPS_Y_SERIES, nu=TABLE1_NU, n=300):
    """JGM Fig 2: normalised elasto-plastic energy -(W_ep)* (eq 25) against w* (eq 13), log axes.

    -(W_ep)* = (5/2) int_1^w* P* dz (work done past the onset of yield, in units of U_c, eq 24),
    for several eps_y at nu = ``nu``, up to w* = 425. The Hertz value w*^2.5 - 1 (eq 19, no
    plasticity) is shown for reference.
    """
    fig, ax = _new_axes(ax)
    w_ref = np.geomspace(1.01, 425.0, n)
    ax.plot(w_ref, w_ref**2.5 - 1.0, color=_COLOURS["hertz"], ls="--", lw=1.2,
            label=r"Hertz, $w^{*5/2} - 1$ (eq 19)")
    for eps, col in zip(eps_y, _eps_colours(len(eps_y))):
        w = _omega_grid(eps, nu, 1.01, n)
        ax.plot(w, -np.asarray(W_star(w, eps, nu)), color=col, lw=1.6,
                label=f"JGM (eqs 9, 25), {_eps_label(eps)}")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlim(1.0, 425.0)
    ax.set_xlabel(r"normalised interference $\omega^* = \omega/\omega_c$ (eq 13) [-]")
    ax.set_ylabel(r"normalised energy $-(W_{ep})^* = -W_{ep}/U_c$ (eq 25) [-]")
    ax.set_title(rf"Fig. 2: elasto-plastic energy ($\nu$ = {nu:g})")
    ax.grid(True, which="major", alpha=0.3)
    ax.legend(fontsize=8, loc="upper left")
    return fig, ax


# ---------------------------------------------------------------------------------------------
# Fig 3: maximum interference
# ---------------------------------------------------------------------------------------------
def figure3(ax=None, eps_y=EPS_Y_SERIES, nu=TABLE1_NU, n=300):
    """JGM Fig 3: normalised maximum interference w_m* (eq 31) against V1* = V1/V_c (eq 30).

    Solution of the energy balance (29) for several eps_y at nu = ``nu``, each up to its own
    w_m* = 425 (or a/R = 1). The Hertz value w_m* = V1*^(4/5) (no plasticity) for reference.
    """
    fig, ax = _new_axes(ax)
    v_ref = np.geomspace(1.0, 1200.0, n)
    ax.plot(v_ref, v_ref**0.8, color=_COLOURS["hertz"], ls="--", lw=1.2,
            label=r"Hertz, $V_1^{*4/5}$ (eq 19)")
    for eps, col in zip(eps_y, _eps_colours(len(eps_y))):
        v = _v_grid(eps, nu, 1.0, n)
        ax.plot(v, direct.omega_m_star(v, eps, nu), color=col, lw=1.6,
                label=f"JGM (eq 29), {_eps_label(eps)}")
    ax.axhline(425.0, color="k", lw=0.8, ls=":")
    ax.annotate(r"model limit $\omega_m^*$ = 425", (1.1, 425.0), xytext=(0, 4),
                textcoords="offset points", fontsize=8)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlim(1.0, 1200.0)
    ax.set_ylim(0.8, 800.0)
    ax.set_xlabel(r"normalised impact speed $V_1^* = V_1/V_c$ (eq 30) [-]")
    ax.set_ylabel(r"normalised maximum interference $\omega_m^* = \omega_m/\omega_c$ (eq 31) [-]")
    ax.set_title(rf"Fig. 3: maximum interference ($\nu$ = {nu:g})")
    ax.grid(True, which="major", alpha=0.3)
    ax.legend(fontsize=8, loc="lower right")
    return fig, ax


# ---------------------------------------------------------------------------------------------
# Fig 4: residual interference fit
# ---------------------------------------------------------------------------------------------
def figure4(ax=None, eps_y=TABLE1_EPS_Y, nu=TABLE1_NU, n=400):
    """JGM Fig 4: residual interference ratio w_res/w_m against w_m*: the JCG fit, eq (35).

    The finite element points of Jackson, Chusoipin & Green (2005) that the paper plots with the
    fit are not available and are not shown. For comparison, the ratio implied by Etsion et al.'s
    eq (33) for one material (normalised: w_res/w_m = 1 - P_m*/(sqrt(A_m*) w_m*),
    :mod:`fastrest.unloading.etsion`) is drawn too.
    """
    fig, ax = _new_axes(ax)
    w = np.geomspace(1.0, 425.0, n)
    r_jcg = np.array([jcg_residual_ratio(x - 1.0) for x in w])
    ax.plot(w, r_jcg, color=_COLOURS["jcg"], lw=1.8,
            label=r"JCG fit, eq (35): $1.02\,[1 - ((\omega_m^*+5.9)/6.9)^{-0.54}]$")
    we = _omega_grid(eps_y, nu, 1.0, n)
    p = np.asarray(P_star(we, eps_y, nu))
    r_ets = np.array([etsion.residual(w, w - 1.0, pm, eps_y, nu)[0] / w for w, pm in zip(we, p)])
    ax.plot(we, r_ets, color=_COLOURS["etsion"], lw=1.4, ls="--",
            label=rf"Etsion et al., eq (33) ($\varepsilon_y$ = {eps_y:g}, $\nu$ = {nu:g})")
    ax.axvline(1.9, color="k", lw=0.8, ls=":")
    ax.annotate(r"JG law from $\omega^*$ = 1.9", (1.9, 0.9), xytext=(4, 0),
                textcoords="offset points", fontsize=8)
    ax.set_xscale("log")
    ax.set_xlim(1.0, 425.0)
    ax.set_ylim(0.0, 1.0)
    ax.set_xlabel(r"normalised maximum interference $\omega_m^* = \omega_m/\omega_c$ [-]")
    ax.set_ylabel(r"residual interference ratio $\omega_{res}/\omega_m$ [-]")
    ax.set_title("Fig. 4: residual interference after unloading")
    ax.grid(True, which="major", alpha=0.3)
    ax.legend(fontsize=8, loc="lower right")
    return fig, ax


# ---------------------------------------------------------------------------------------------
# Fig 5: e against V1*, this model and Chang-Ling
# ---------------------------------------------------------------------------------------------
def figure5(ax=None, eps_y=EPS_Y_SERIES, nu=TABLE1_NU, n=400):
    """JGM Fig 5: e against V1* for several eps_y, this model (JCG unloading, eq 35) and Chang-Ling.

    Chang & Ling's eq (1) (CEB contact law; see :func:`fastrest.models.chang_ling` for the reading
    of the misprinted equation) does not depend on eps_y once V1 is normalised by V_c: one curve.
    """
    fig, ax = _new_axes(ax)
    v_lo = 0.5
    v_top = 0.0
    for eps, col in zip(eps_y, _eps_colours(len(eps_y))):
        v = _v_grid(eps, nu, v_lo, n)
        v_top = max(v_top, v[-1])
        ax.plot(v, direct.e_star(v, eps, nu, "jcg"), color=col, lw=1.6,
                label=f"JGM, eq (35), {_eps_label(eps)}")
    v = np.geomspace(v_lo, v_top, n)
    ax.plot(v, models.chang_ling(v, TABLE1_EPS_Y, nu), color=_COLOURS["chang_ling"], lw=1.6, ls="--",
            label=_LABELS["chang_ling"] + r" (any $\varepsilon_y$)")
    ax.set_xscale("log")
    ax.set_xlim(v_lo, v_top)
    ax.set_ylim(0.0, 1.05)
    ax.set_xlabel(r"normalised impact speed $V_1^* = V_1/V_c$ (eq 30) [-]")
    ax.set_ylabel(r"coefficient of restitution $e = V_2/V_1$ (eq 16) [-]")
    ax.set_title(rf"Fig. 5: JGM (JCG unloading) vs Chang-Ling ($\nu$ = {nu:g})")
    ax.grid(True, which="major", alpha=0.3)
    ax.legend(fontsize=8, loc="lower left")
    return fig, ax


# ---------------------------------------------------------------------------------------------
# Fig 6: unloading models and Wu et al.
# ---------------------------------------------------------------------------------------------
def figure6(ax=None, eps_y=TABLE1_EPS_Y, nu=TABLE1_NU, n=400):
    """JGM Fig 6: e against V1* with JCG (eq 35) and Etsion (eq 33) unloading, and Wu et al.;
    with, as an extra curve not in the paper, the JG loading with Brake's unloading
    (:mod:`fastrest.unloading.brake`).

    Wu et al.'s eqs (40) (below V_fp) and (41) (above) are drawn solid where each applies and
    dotted outside; the vertical line is V_fp of eq (39), 0.008 V_c (E'/Sy)^2 (V1* = 320 for
    the Table 1 material). Eq (40) exceeds 1 for V1* < 2.08^4 = 18.7 (up to 2.08 just above
    V_c) and runs off the top of the plot, as the paper notes.
    """
    fig, ax = _new_axes(ax)
    v = _v_grid(eps_y, nu, 0.5, n)
    for model in ("jcg", "etsion", "brake"):
        ax.plot(v, direct.e_star(v, eps_y, nu, model), color=_COLOURS[model], lw=1.8,
                ls="--" if model == "brake" else "-", label=_LABELS[model])
    v_fp = float(models.wu_finite_plastic_velocity(eps_y))
    vp = v[v > 1.0]
    e40, e41 = models.wu_branches(vp, eps_y)
    below = vp <= v_fp
    # e = 1 below V_c (as this model); drawn from V_c up, so the jump to 2.08 at V_c is not a line
    ax.plot(vp, models.wu(vp, eps_y), color=_COLOURS["wu"], lw=1.6, label=_LABELS["wu"])
    ax.plot(vp[~below], e40[~below], color=_COLOURS["wu"], lw=1.0, ls=":",
            label="Wu et al., eqs (40), (41) outside their ranges")
    ax.plot(vp[below], e41[below], color=_COLOURS["wu"], lw=1.0, ls=":")
    ax.axvline(v_fp, color="k", lw=0.9, ls="--")
    ax.annotate(rf"$V_{{fp}}$ (eq 39) = {v_fp:.0f} $V_c$", (v_fp, 1.12), xytext=(-4, 0),
                textcoords="offset points", fontsize=8, ha="right")
    ax.set_xscale("log")
    ax.set_xlim(0.5, v[-1])
    ax.set_ylim(0.0, 1.2)
    ax.set_xlabel(r"normalised impact speed $V_1^* = V_1/V_c$ (eq 30) [-]")
    ax.set_ylabel(r"coefficient of restitution $e = V_2/V_1$ (eq 16) [-]")
    ax.set_title(rf"Fig. 6: effect of the unloading model ($\varepsilon_y$ = {eps_y:g}, $\nu$ = {nu:g})")
    ax.grid(True, which="major", alpha=0.3)
    ax.legend(fontsize=8, loc="lower left")
    return fig, ax


# ---------------------------------------------------------------------------------------------
# Figs 7-8: alumina spheres on aluminium and steel (dimensional)
# ---------------------------------------------------------------------------------------------
def kharaz_impact(flat):
    """The impact of JGM Figs 7-8: an alumina sphere (R = 2.5 mm) on a flat ``"aluminium"`` or ``"steel"``.

    The mass is the alumina sphere's, (4/3) pi R^3 :data:`ALUMINA_DENSITY` (an assumed density;
    the paper's Tables 3-4 list only the flats' densities). E' combines both bodies
    (1/E' = (1 - 0.22^2)/370 GPa + (1 - nu^2)/E_flat); the flat yields (the sphere never does),
    so nu, Sy and C are the flat's.
    """
    mats = {"aluminium": ALUMINIUM_FLAT, "steel": STEEL_FLAT}
    if flat not in mats:
        raise ValueError(f"flat must be one of {sorted(mats)}; got {flat!r}")
    return Impact(ALUMINA, KHARAZ_RADIUS, flat=mats[flat])


def _figure_kharaz(ax, flat, fig_no, v_max, n):
    fig, ax = _new_axes(ax)
    imp = kharaz_impact(flat)
    V = np.unique(np.concatenate([np.linspace(0.0, v_max, n)[1:], imp.V_c * np.geomspace(0.5, 4.0, 40)]))
    V = V[V <= v_max]
    # this model: e = 1 up to V_c, both unloadings (exact solver)
    for model in ("jcg", "etsion"):
        ax.plot(V, imp.e(V, unloading=model), color=_COLOURS[model], lw=1.9, label=_LABELS[model])
    for model, ls in (("thornton", "-."), ("wu", "--"), ("weir_tallon", ":")):
        e = np.asarray(models.evaluate(model, imp, V))
        if model == "wu":  # e = 1 up to V_c, then eq (40) jumps to 2.08: do not draw the jump
            e = np.where(V > imp.V_c, e, np.nan)
        ax.plot(V, e, color=_COLOURS[model], lw=1.5, ls=ls, label=_LABELS[model])
    ax.axvline(imp.V_c, color="k", lw=0.8, ls=":")
    ax.annotate(rf"$V_c$ (eq 28) = {imp.V_c * 1e3:.0f} mm/s", (imp.V_c, 0.12), xytext=(3, 0),
                textcoords="offset points", fontsize=8)
    flat_name = {"aluminium": "an aluminium", "steel": "a steel"}[flat]
    table = {"aluminium": 3, "steel": 4}[flat]
    info = (f"inputs of JGM Table {table}; sphere mass m = {imp.mass * 1e3:.3f} g "
            f"(alumina, assumed $\\rho$ = {ALUMINA_DENSITY:.0f} kg/m$^3$)\n"
            f"E' = {imp.E_eff / 1e9:.1f} GPa (sphere + flat), $\\varepsilon_y$ = {imp.eps_y:.4f}, "
            f"$\\nu$ = {imp.nu:g}, $V_c$ = {imp.V_c:.4f} m/s; Kharaz-Gorham data not shown")
    ax.text(0.99, 0.015, info, transform=ax.transAxes, fontsize=6.5, ha="right", va="bottom",
            bbox=dict(boxstyle="round", fc="white", ec="0.7", alpha=0.9))
    ax.set_xlim(0.0, v_max)
    ax.set_ylim(0.0, 1.4)
    ax.set_xlabel(r"impact speed $V_1$ [m/s]")
    ax.set_ylabel(r"coefficient of restitution $e = V_2/V_1$ [-]")
    ax.set_title(f"Fig. {fig_no}: alumina sphere (R = {KHARAZ_RADIUS * 1e3:g} mm) on {flat_name} flat")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=7.5, loc="upper right")
    return fig, ax


def figure7(ax=None, v_max=5.0, n=400):
    """JGM Fig 7: e against V1 (m/s), alumina sphere on an aluminium flat (Table 3 inputs).

    This model with both unloadings (eqs 33, 35), Thornton (eq 2), Wu et al. (eqs 39-41) and
    Weir-Tallon (eq 3). Mass and E' as in :func:`kharaz_impact`. Curves above e = 1.4 (Wu et al.
    and Weir-Tallon at low speed) run off the plot.
    """
    return _figure_kharaz(ax, "aluminium", 7, v_max, n)


def figure8(ax=None, v_max=5.0, n=400):
    """JGM Fig 8: e against V1 (m/s), alumina sphere on a steel flat (Table 4 inputs). As :func:`figure7`."""
    return _figure_kharaz(ax, "steel", 8, v_max, n)


#: Output file stem -> figure function, in the paper's order.
FIGURES = {
    "fig2_energy": figure2,
    "fig3_max_interference": figure3,
    "fig4_residual_interference": figure4,
    "fig5_e_vs_chang_ling": figure5,
    "fig6_unloading_models": figure6,
    "fig7_alumina_on_aluminium": figure7,
    "fig8_alumina_on_steel": figure8,
}


def write_all(out_dir, dpi=150):
    """Draw every figure into ``out_dir`` as PNG (created if needed); return the list of paths.

    Files are named after :data:`FIGURES` (``fig2_energy.png`` ...). PNG metadata carry no software
    version (``metadata={"Software": None}``), so the bytes depend only on the data and on the
    Matplotlib version and fonts.
    """
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    paths = []
    for stem, fn in FIGURES.items():
        fig, _ = fn()
        p = out / f"{stem}.png"
        fig.savefig(p, dpi=dpi, metadata={"Software": None})
        paths.append(p)
    return paths
