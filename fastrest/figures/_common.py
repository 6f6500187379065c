"""What every figure shares: the Table 1 material, colours and labels, axes, speed grids, and the
parameters, Returns and Raises of their docstrings."""
import numpy as np

from .._doc import paragraphs
from ..limits import limit

__all__ = ["TABLE1_EPS_Y", "TABLE1_NU", "EPS_Y_SERIES", "COLOURS", "LABELS", "FIGURE_DOC", "new_axes",
           "eps_colours", "eps_label", "omega_grid", "v_grid", "mark", "finish_axes"]

#: The docstring paragraphs every figure function shares (:func:`fastrest._doc.doc`).
FIGURE_DOC = paragraphs(
    param_ax="""
        Parameters
        ----------
        ax : matplotlib.axes.Axes, optional
            Axes to draw into; default a new pyplot-free Figure. All parameters are keyword-only.
        """,
    params_series="""
        {param_ax}
        eps_y : sequence of float
            Sy/E' (-) of each curve; default :data:`~fastrest.figures.EPS_Y_SERIES`.
        nu : float
            Poisson's ratio (-); default 0.33 (JGM Table 1).
        n : int
            Points per curve.
        """,
    returns="""
        Returns
        -------
        fig : matplotlib.figure.Figure
            The figure of ``ax``, or the new one.
        ax : matplotlib.axes.Axes
            The axes drawn into.

        Raises
        ------
        ImportError
            Matplotlib is not installed (``pip install fastrest[plot]``).
        """,
    returns_material="""
        {returns}
        ValueError
            eps_y or nu outside the model's domain (eps_y > 0, 0 <= nu < 0.5).
        """,
)

#: JGM Table 1 benchmark (eps_y = 0.005, nu = 0.33), used by Figs 2-6 unless stated otherwise.
TABLE1_EPS_Y = 0.005
#: Poisson's ratio of the JGM Table 1 benchmark.
TABLE1_NU = 0.33
#: eps_y values of Figs 2, 3 and 5 (the paper's validated range is 0.0005-0.01).
EPS_Y_SERIES = (0.0005, 0.001, 0.002, 0.005, 0.01)
#: Colour per model (the same in every figure).
COLOURS = {
    "jcg": "#1f77b4", "etsion": "#d62728", "thornton": "#2ca02c", "wu": "#9467bd",
    "weir_tallon": "#8c564b", "chang_ling": "#ff7f0e", "hertz": "0.45", "brake": "#17becf",
}
#: Legend label per model.
LABELS = {
    "jcg": "JGM, JCG unloading, eq (35)",
    "etsion": "JGM, Etsion unloading, eq (33)",
    "brake": "JG loading, Brake unloading (not in the paper)",
    "thornton": "Thornton (1997), eq (2)",
    "wu": "Wu et al. (2003), eqs (39)-(41)",
    "weir_tallon": "Weir & Tallon (2005), eq (3)",
    "chang_ling": "Chang & Ling (1992), CEB, eq (1)",
}
_FIGSIZE = (6.4, 4.8)


def new_axes(ax, figsize=_FIGSIZE):
    """Return (fig, ax): ``ax`` and its figure, or a new pyplot-free Figure with one Axes."""
    if ax is not None:
        return ax.figure, ax
    from matplotlib.figure import Figure

    fig = Figure(figsize=figsize, layout="constrained")
    return fig, fig.add_subplot()


def eps_colours(n):
    """``n`` colours for a series of eps_y (viridis)."""
    from matplotlib import colormaps

    cmap = colormaps["viridis"]
    return [cmap(x) for x in np.linspace(0.0, 0.85, n)]


def eps_label(eps_y):
    """Legend text for one eps_y."""
    return rf"$\varepsilon_y$ = {eps_y:g}"


def omega_grid(eps_y, nu, w_lo, n):
    """Log-spaced w* from w_lo to the model's end (425, or just below a/R = 1)."""
    from ..contact import omega_star_limit

    w_hi = min(425.0, float(omega_star_limit(eps_y, nu)) * (1.0 - 1e-9))
    return np.geomspace(w_lo, w_hi, n)


def v_grid(eps_y, nu, v_lo, n):
    """Log-spaced V1* from v_lo to the model's limit, with nodes either side of V1* = 1.9^1.25."""
    from ..energy import V_SWITCH

    v_hi = limit(eps_y, nu).v1_star
    v = np.geomspace(v_lo, v_hi, n)
    v[-1] = v_hi
    extra = [1.0, V_SWITCH, np.nextafter(V_SWITCH, np.inf)]
    return np.unique(np.concatenate([v, [x for x in extra if v_lo <= x <= v_hi]]))


def mark(ax, value, text, at, *, vertical, offset):
    """A dotted black reference line at ``value`` (x if ``vertical``, else y), labelled ``text`` at
    the data point ``at``, shifted by ``offset`` points."""
    (ax.axvline if vertical else ax.axhline)(value, color="k", lw=0.8, ls=":")
    ax.annotate(text, at, xytext=offset, textcoords="offset points", fontsize=8)


def finish_axes(ax, *, xlabel, ylabel, title, xlim, ylim=None, xlog=True, ylog=False, legend_loc,
                legend_size=8, grid_which="major"):
    """Scales, limits, labels, title, grid and legend of a figure, in the order every figure sets them."""
    if xlog:
        ax.set_xscale("log")
    if ylog:
        ax.set_yscale("log")
    ax.set_xlim(*xlim)
    if ylim is not None:
        ax.set_ylim(*ylim)
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.set_title(title)
    ax.grid(True, which=grid_which, alpha=0.3)
    ax.legend(fontsize=legend_size, loc=legend_loc)
