"""Expectations over the summit heights of a statistical (Greenwood-Williamson) surface.

N = eta A_n summits have independent heights z with pdf phi. In the standardised height
zs = z/sigma, with the flat at zs_d = d/sigma and rho_w = sigma/omega_c (w* per unit of zs), a
summit at zs is at w* = (zs - zs_d) rho_w, and the sums over summits become N times expectations

    E[g] = int_{zs_d}^inf g((zs - zs_d) rho_w) phi(zs) dzs

(Greenwood & Williamson 1966; docs/rough.md section 4). They are composite Gauss-Legendre
quadrature in w* over the contacting heights, split at w* = 1 and 1.9 where the law changes: the
panel starting at w* = 0 uses w* = b u^2 (F ~ w^2.5 and P* ~ w^1.5 become polynomials in u);
other panels are at most PANEL_ZS wide in zs and a factor 2 wide in w*. Gaussian heights are
integrated up to zs_cut = sqrt(max(zs_d, 0)^2 + 2 TAIL_L), where the integrand has fallen by
exp(-TAIL_L) ~ 3e-20 relative to its value at max(zs_d, 0), and (when the flat is below them)
from zs = -sqrt(2 TAIL_L).
"""
import math
from collections import namedtuple

import numpy as np

from .. import forward as fw
from .._doc import doc, paragraphs
from .._jit import jit
from .._validation import OMEGA_STAR_SWITCH as W_SWITCH  # every loading law's Hertz switch (fastrest.loading)
from ..interpolation import cell_polynomial
from .common import hertz_fp, summit_values

__all__ = ["GWData", "GL_ORDER", "PANEL_ZS", "TAIL_L", "ZS_UNDERFLOW", "zs_top_kernel",
           "zs_covered_kernel", "gw_hertz_sums_kernel", "gw_jg_sums_kernel", "gw_impact_sums_kernel"]

#: Gauss-Legendre order per quadrature panel.
GL_ORDER = 16
_GL_X, _GL_W = np.polynomial.legendre.leggauss(GL_ORDER)
#: Widest quadrature panel in zs = z/sigma; chosen by measurement against scipy.integrate.quad
#: (tests/test_rough.py).
PANEL_ZS = 0.5
#: Gaussian tail cut (see the module docstring): exp(-TAIL_L) ~ 3e-20.
TAIL_L = 45.0
#: Gaussian heights: the density exp(-zs^2/2) underflows soon after zs = 37 (1e-298).
ZS_UNDERFLOW = 36.0
_INV_SQRT_2PI = 1.0 / math.sqrt(2.0 * math.pi)

# The first parameter and the examples' first lines of the kernels below, written once
# (fastrest._doc).
_DOC = paragraphs(
    param_g="""
        Parameters
        ----------
        g : GWData
            The surface's height statistics.
        """,
    examples="""
        Examples
        --------
        >>> from fastrest.rough import expectations, heights
        >>> g, _ = heights.gw_data(heights.GreenwoodWilliamson(eta=1e10, sigma=1e-8, A_n=1e-4), 1e-8)
        """,
)

GWData = namedtuple("GWData", ["kind", "n_total", "rho_w", "zs_lo", "zs_hi", "inv_h", "pdf_rows"])
GWData.__doc__ = """Numba-friendly statistical surface (built by :func:`fastrest.rough.heights.gw_data`).

kind: 0 = Gaussian heights, 1 = tabulated pdf of zs = z/sigma on uniform degree-5 cells from zs_lo
to zs_hi (1/cell width = inv_h, rows [center, 1/half width, c0..c5] in pdf_rows); n_total = eta A_n
(-); rho_w = sigma/omega_c (w* per unit of zs, -).
"""


@jit
def _pdf(g, zs):
    """Probability density of the standardised summit height zs = z/sigma (-)."""
    if g.kind == 0:
        return math.exp(-0.5 * zs * zs) * _INV_SQRT_2PI
    if zs < g.zs_lo or zs > g.zs_hi:
        return 0.0
    i = int((zs - g.zs_lo) * g.inv_h)
    if i >= g.pdf_rows.shape[0]:
        i = g.pdf_rows.shape[0] - 1
    return cell_polynomial(g.pdf_rows, i, zs)


@jit
@doc(_DOC)
def zs_top_kernel(g, zs_d):
    """Upper end of the height integration (-, in units of sigma) for the flat at zs_d.

    {param_g}
    zs_d : float
        Position of the flat over sigma (-).

    Returns
    -------
    float
        Gaussian: sqrt(max(zs_d, 0)^2 + 2 TAIL_L), where the integrand has fallen by exp(-TAIL_L)
        (Greenwood-Williamson integrals, docs/rough.md section 4); a user pdf: its support's end.

    {examples}
    >>> expectations.zs_top_kernel(g, 0.0) == (2 * expectations.TAIL_L) ** 0.5
    True
    """
    if g.kind == 0:
        t = max(zs_d, 0.0)
        return math.sqrt(t * t + 2.0 * TAIL_L)
    return g.zs_hi


@jit
@doc(_DOC)
def zs_covered_kernel(g, w_cap):
    """Lowest flat position whose integration range stays within w* <= w_cap.

    {param_g}
    w_cap : float
        Largest w* (-) served (a forward table's end, or the model's).

    Returns
    -------
    float
        zs_d (-) at which (zs_top_kernel(zs_d) - zs_d) rho_w = w_cap.

    {examples}
    >>> zs = expectations.zs_covered_kernel(g, 20.0)
    >>> abs((expectations.zs_top_kernel(g, zs) - zs) * g.rho_w - 20.0) < 1e-12
    True
    """
    u = w_cap / g.rho_w  # largest (zs - zs_d) served
    if g.kind == 1:
        return g.zs_hi - u
    two_l = 2.0 * TAIL_L
    if u * u >= two_l:
        return math.sqrt(two_l) - u
    return (two_l - u * u) / (2.0 * u)


@jit(inline=True)
def _w_range(g, zs_d):
    """(w_a, w_b): w* of the lowest and highest contacting heights integrated."""
    w_a = 0.0
    zs_lo = g.zs_lo if g.kind == 1 else -math.sqrt(2.0 * TAIL_L)  # Gaussian: also cut below
    if zs_lo > zs_d:
        w_a = (zs_lo - zs_d) * g.rho_w
    return w_a, (zs_top_kernel(g, zs_d) - zs_d) * g.rho_w


@jit(inline=True)
def _panel_end(p, w_b, hw):
    """End of the quadrature panel starting at w* = p: at most hw wide and (above 0) a factor 2,
    never across w* = 1 or 1.9 or past w_b."""
    end = w_b
    if p < 1.0:
        end = min(end, 1.0)
    elif p < W_SWITCH:
        end = min(end, W_SWITCH)
    q = min(end, hw) if p == 0.0 else min(end, p + hw, 2.0 * p)
    return q if q > p else end  # a panel below the rounding of p: end the segment


@jit(inline=True)
def _node(g, zs_d, p, q, j):
    """(w*, weight) of Gauss node j on the panel [p, q]; the weight includes pdf dzs/dw."""
    if p == 0.0:  # w = q u^2: F, P* polynomials in u
        u = 0.5 * (1.0 + _GL_X[j])
        w = q * u * u
        wt = _GL_W[j] * q * u  # 0.5 W_j * 2 q u
    else:
        hh = 0.5 * (q - p)
        w = 0.5 * (p + q) + hh * _GL_X[j]
        wt = hh * _GL_W[j]
    return w, wt * (_pdf(g, zs_d + w / g.rho_w) / g.rho_w)


@jit(inline=True)
def _expectations(term, data, g, zs_d, w_b):
    """Per-summit expectations of the 4 values ``term(data, w, yielded)`` over the contacting
    heights up to w* = w_b (composite Gauss-Legendre; ``yielded``: the panel lies above w* = 1)."""
    w_a, w_top = _w_range(g, zs_d)
    w_b = min(w_top, w_b)
    hw = PANEL_ZS * g.rho_w
    e0 = e1 = e2 = e3 = 0.0
    p = w_a
    while p < w_b:
        q = _panel_end(p, w_b, hw)
        for j in range(GL_ORDER):
            w, wt = _node(g, zs_d, p, q, j)
            v0, v1, v2, v3 = term(data, w, p >= 1.0)
            e0 += wt * v0
            e1 += wt * v1
            e2 += wt * v2
            e3 += wt * v3
        p = q
    return e0, e1, e2, e3


@jit(inline=True)
def _hertz_term(data, w, yielded):
    """(F, P*, 0, 0) of a Hertzian summit (``data`` unused)."""
    f, pf = hertz_fp(w)
    return f, pf, 0.0, 0.0


@jit(inline=True)
def _jg_term(data, w, yielded):
    """(F, P*, 0, 0) under the table's loading law: F and the slope P* from the forward table ``data``."""
    f, pf = fw.FP_table_forward(data, w)
    return f, pf, 0.0, 0.0


@jit(inline=True)
def _impact_term(data, w, yielded):
    """(P*, L, 1, yielded) at the deepest approach (exact P*; JGM eqs 9, 14, 38)."""
    _, pf, _, loss = summit_values(data, w, w - 1.0)
    return pf, loss, 1.0, (1.0 if yielded else 0.0)


@jit
@doc(_DOC)
def gw_hertz_sums_kernel(g, zs_d):
    """Per-summit expected loading energy and force with every summit Hertzian.

    {param_g}
    zs_d : float
        Position of the flat over sigma (-): d/sigma above the mean summit plane.

    Returns
    -------
    (float, float)
        E[F] and E[P*] (-): F = w^2.5 (over U_c) and P* = w^1.5 (over P_c) at any w* (JGM eqs 19,
        14), over the contacting heights; times N = eta A_n for the surface.

    Notes
    -----
    The Hertz estimate of every statistical impact; also the test of an impact too light for the
    Gaussian's resolution (the flat at zs_d = ZS_UNDERFLOW). Quadrature as the module docstring.

    {examples}
    >>> e_f, e_p = expectations.gw_hertz_sums_kernel(g, 0.0)
    >>> bool(e_f > e_p > 0.0)  # E[w^2.5] > E[w^1.5] over a half-normal w
    True
    """
    return _expectations(_hertz_term, None, g, zs_d, np.inf)[:2]  # (E[F], E[P*])


@jit
@doc(_DOC)
def gw_jg_sums_kernel(data, g, zs_d, w_cap):
    """Per-summit expected loading energy and force under the loading law of ``data``.

    Parameters
    ----------
    data : fastrest.forward.ForwardData
        Forward table of one summit (its loading law: JG, or Ghaednia et al. with hardening).
    g : GWData
        The surface's height statistics.
    zs_d : float
        Position of the flat over sigma (-).
    w_cap : float
        Heights are integrated up to w* = w_cap (-) (rounding only: callers keep zs_d above
        :func:`zs_covered_kernel` (w_cap)).

    Returns
    -------
    (float, float)
        E[F] (over U_c) and E[P*] (over P_c) (-), F (JGM eqs 19, 25) and the Newton slope P* from
        the forward table; times N for the surface.

    {examples}
    >>> from fastrest import forward
    >>> data = forward.forward_data(0.005, 0.3, w_max=40.0)
    >>> jg = expectations.gw_jg_sums_kernel(data, g, 1.0, 40.0)
    >>> hz = expectations.gw_hertz_sums_kernel(g, 1.0)
    >>> bool(abs(jg[0] / hz[0] - 1) < 0.05)  # mostly Hertzian at zs_d = 1, rho_w = 1
    True
    """
    return _expectations(_jg_term, data, g, zs_d, w_cap)[:2]  # (E[F], E[P*])


@jit
@doc(_DOC)
def gw_impact_sums_kernel(data, g, zs_d, w_cap):
    """Per-summit expectations at the deepest approach.

    Parameters
    ----------
    data, g, zs_d, w_cap
        As :func:`gw_jg_sums_kernel` (``data`` also gives the unloading model).

    Returns
    -------
    (float, float, float, float, float)
        E[P*] (exact P*, JGM eqs 9, 14), E[L] (dissipated energy, eq 38 with the unloading model),
        P(contact), P(w* > 1) (-), and the w* at the top of the integration (-).

    {examples}
    >>> from fastrest import forward
    >>> data = forward.forward_data(0.005, 0.3, w_max=40.0)
    >>> e_p, e_l, p_c, p_y, w_top = expectations.gw_impact_sums_kernel(data, g, 0.0, 40.0)
    >>> round(p_c, 12), bool(0.0 < p_y < p_c)
    (0.5, True)
    """
    e_p, e_l, p_c, p_y = _expectations(_impact_term, data, g, zs_d, w_cap)
    return e_p, e_l, p_c, p_y, min(_w_range(g, zs_d)[1], w_cap)
