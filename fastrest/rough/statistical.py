"""Statistical (Greenwood-Williamson) surfaces: expectations over the summit heights, the approach.

N = eta A_n summits have independent heights z with pdf phi. In the standardised height
zs = z/sigma, with the flat at zs_d = d/sigma and rho_w = sigma/omega_c (w* per unit of zs), a
summit at zs is at w* = (zs - zs_d) rho_w, and the sums over summits become N times expectations

    E[g] = int_{zs_d}^inf g((zs - zs_d) rho_w) phi(zs) dzs

(Greenwood & Williamson 1966; docs/rough.md section 4). The deepest approach solves N E[F] = E
(the impact energy over U_c) for zs_d by Newton's method on (N E[F])^0.4 with a bracket search.

The expectations are composite Gauss-Legendre quadrature in w* over the contacting heights, split
at w* = 1 and 1.9 where the law changes: the panel starting at w* = 0 uses w* = b u^2 (F ~ w^2.5
and P* ~ w^1.5 become polynomials in u); other panels are at most PANEL_ZS wide in zs and a factor
2 wide in w*. Gaussian heights are integrated up to zs_cut = sqrt(max(zs_d, 0)^2 + 2 TAIL_L), where
the integrand has fallen by exp(-TAIL_L) ~ 3e-20 relative to its value at max(zs_d, 0), and (when
the flat is below them) from zs = -sqrt(2 TAIL_L).
"""
import math
from collections import namedtuple

import numpy as np
from numba import prange

from .. import forward as fw
from .._jit import jit
from .._threads import run_parallel
from ..contact import W_SWITCH
from ..interpolation import cell_polynomial
from .common import FAILED, MAX_ITER, NEEDS_TABLE, OK, hertz_fp, summit_values

__all__ = ["GWData", "GL_ORDER", "PANEL_ZS", "TAIL_L", "ZS_UNDERFLOW", "HERTZ_CAP",
           "gw_hertz_sums_kernel", "gw_hertz_kernel", "gw_approach_kernel", "gw_hertz_array",
           "gw_impacts_array", "hertz_estimate", "solve_impacts"]

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
#: The Hertz estimate (the start of every JG solve) stops at this many times the w* where the law
#: ends (a/R = 1): JG summits sink deeper than Hertz ones, so beyond it so does the impact.
HERTZ_CAP = 4.0
_INV_SQRT_2PI = 1.0 / math.sqrt(2.0 * math.pi)

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
def _zs_top(g, zs_d):
    """Upper end of the height integration for the flat at zs_d."""
    if g.kind == 0:
        t = max(zs_d, 0.0)
        return math.sqrt(t * t + 2.0 * TAIL_L)
    return g.zs_hi


@jit
def _zs_covered(g, w_cap):
    """Lowest zs_d whose integration range stays within w* <= w_cap."""
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
    return w_a, (_zs_top(g, zs_d) - zs_d) * g.rho_w


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
def _expectations(term, law, g, zs_d, w_b):
    """Per-summit expectations of the 4 values ``term(law, w, yielded)`` over the contacting
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
            v0, v1, v2, v3 = term(law, w, p >= 1.0)
            e0 += wt * v0
            e1 += wt * v1
            e2 += wt * v2
            e3 += wt * v3
        p = q
    return e0, e1, e2, e3


@jit(inline=True)
def _hertz_term(law, w, yielded):
    """(F, P*, 0, 0) of a Hertzian summit (``law`` unused)."""
    f, pf = hertz_fp(w)
    return f, pf, 0.0, 0.0


@jit(inline=True)
def _jg_term(law, w, yielded):
    """(F, P*, 0, 0) under the JG law: F and the slope P* from the forward table ``law``."""
    f, pf = fw.FP_table_forward(law, w)
    return f, pf, 0.0, 0.0


@jit(inline=True)
def _impact_term(law, w, yielded):
    """(P*, L, 1, yielded) at the deepest approach (exact P*; JGM eqs 9, 14, 38)."""
    _, pf, _, loss = summit_values(law, w, w - 1.0)
    return pf, loss, 1.0, (1.0 if yielded else 0.0)


@jit
def gw_hertz_sums_kernel(g, zs_d):
    """(E[F], E[P*]) per summit with every summit Hertzian (F = w^2.5, P* = w^1.5 at any w*)."""
    e_f, e_p, _, _ = _expectations(_hertz_term, None, g, zs_d, np.inf)
    return e_f, e_p


@jit
def _jg_sums(data, g, zs_d, w_cap):
    """(E[F], E[P*]) per summit under the JG law (F and the slope P* from the forward table); the
    heights are integrated up to w* = w_cap (rounding only: callers keep zs_d above
    _zs_covered(w_cap))."""
    e_f, e_p, _, _ = _expectations(_jg_term, data, g, zs_d, w_cap)
    return e_f, e_p


@jit
def _impact_sums(data, g, zs_d, w_cap):
    """(E P*, E L, P(contact), P(w* > 1), w* at the top of the integration) per summit."""
    e_p, e_l, p_c, p_y = _expectations(_impact_term, data, g, zs_d, w_cap)
    return e_p, e_l, p_c, p_y, min(_w_range(g, zs_d)[1], w_cap)


# --- the approach: Newton on (N E[F])^0.4 with a bracket search -----------------------------------

_ZS, _LO, _HI, _STEP, _DX_PREV = 0, 1, 2, 3, 4


@jit(inline=True)
def _start(g, zs0):
    """Solver state from zs0: no bracket yet (a bounded pdf: nothing in contact above zs_hi)."""
    st = np.empty(5)
    st[_LO], st[_HI] = -np.inf, np.inf
    if g.kind == 1:
        st[_HI] = g.zs_hi
    st[_ZS] = zs0 if zs0 < st[_HI] else st[_HI] - 0.5
    st[_STEP], st[_DX_PREV] = 0.5, np.inf
    return st


@jit(inline=True)
def _advance(st, g, e_f, e_p, energy):
    """One step from the point in ``st`` with per-summit expectations (e_f, e_p); True when
    converged (the solution is then the point in ``st``)."""
    zs = st[_ZS]
    n_tot = g.n_total
    gs = n_tot * e_f
    if gs >= energy:
        st[_LO] = zs
    else:
        st[_HI] = zs
    if gs == energy:
        return True
    newton = np.nan
    if gs > 0.0 and e_p > 0.0:
        newton = zs + (gs**0.4 - energy**0.4) * gs**0.6 / (n_tot * g.rho_w * e_p)
    if st[_LO] == -np.inf or st[_HI] == np.inf:
        # no bracket yet: steps doubling away from the start, or Newton's step when it points
        # the same way and goes further (Newton alone creeps up a Gaussian tail, 2.5/zs per step)
        step = st[_STEP]
        zn = zs - step if st[_LO] == -np.inf else zs + step
        if (st[_LO] == -np.inf and newton < zn) or (st[_HI] == np.inf and newton > zn):
            zn = newton
            step *= 0.5
        st[_STEP] = 2.0 * step
        st[_ZS] = zn
        return False
    scale = max(1.0, abs(zs))
    if newton == newton:
        dx = abs(newton - zs)
        if dx <= 4e-16 * scale or (dx < 1e-12 * scale and dx >= 0.5 * st[_DX_PREV]):
            st[_ZS] = newton
            return True
        st[_DX_PREV] = dx
    if newton > st[_LO] and newton < st[_HI]:
        st[_ZS] = newton
        return False
    st[_ZS] = 0.5 * (st[_LO] + st[_HI])
    return st[_HI] - st[_LO] <= 4e-16 * scale


@jit(inline=True)
def _coverage(g, w_cap):
    """zs_d below which the integration would pass w* = w_cap (with a rounding margin)."""
    zs_cov = _zs_covered(g, w_cap)
    return zs_cov + 1e-12 * (1.0 + abs(zs_cov))


@jit(inline=True)
def _approach(sums, law, g, energy, zs0, w_cap, clamp):
    """(status, zs_d, w* at the top) solving N E[F] = energy with ``sums(law, g, zs_d, w_cap)`` ->
    (E[F], E[P*]). Trial points whose heights reach past ``w_cap`` return NEEDS_TABLE, or with
    ``clamp`` (w_cap is the model's end) are moved to it: NEEDS_TABLE then means the solution is
    beyond it."""
    zs_cov = _coverage(g, w_cap)
    st = _start(g, zs0)
    for _ in range(MAX_ITER):
        if st[_ZS] < zs_cov:
            if not (clamp and st[_HI] > zs_cov):
                break
            st[_ZS] = zs_cov
        e_f, e_p = sums(law, g, st[_ZS], w_cap)
        if _advance(st, g, e_f, e_p, energy):
            break
    else:
        return FAILED, st[_ZS], np.nan
    zs = st[_ZS]
    return (OK if zs >= zs_cov else NEEDS_TABLE), zs, (_zs_top(g, zs) - zs) * g.rho_w


@jit(inline=True)
def _hertz_sums(law, g, zs_d, w_cap):
    """:func:`gw_hertz_sums_kernel` with the arguments of :func:`_jg_sums` (``law``, ``w_cap`` unused)."""
    return gw_hertz_sums_kernel(g, zs_d)


@jit
def gw_hertz_kernel(g, energy, zs0, w_cap):
    """(status, zs_d, w* at the top) of the impact of energy ``energy`` (over U_c) with every
    summit Hertzian: the estimate that starts every JG solve and sizes its table. Trial points
    whose heights reach past ``w_cap`` are moved to it; NEEDS_TABLE: the solution is beyond it."""
    return _approach(_hertz_sums, None, g, energy, zs0, w_cap, True)


@jit
def gw_approach_kernel(data, g, energy, zs0, w_model):
    """(status, zs_d, w* at the top) of the deepest approach under the JG law.

    A trial point whose heights reach past the table (data.w_max) returns NEEDS_TABLE with the w*
    it needs. Once the table reaches ``w_model`` (the model's end) trial points are moved to it,
    and NEEDS_TABLE means the solution itself is beyond the model.
    """
    return _approach(_jg_sums, data, g, energy, zs0, min(data.w_max, w_model), data.w_max >= w_model)


@jit
def _hertz_one(g, energies, zs0, w_cap, out, k):
    out[0, k], out[1, k], out[2, k] = gw_hertz_kernel(g, energies[k], zs0, w_cap)


@jit(parallel=True)
def gw_hertz_array(g, energies, zs0, w_cap, out):
    """out[:, k] = :func:`gw_hertz_kernel` of impact k, all started at zs0 (in parallel)."""
    for k in prange(energies.size):
        _hertz_one(g, energies, zs0, w_cap, out, k)


@jit
def _gw_hertz_serial(g, energies, zs0, w_cap, out):
    for k in range(energies.size):
        _hertz_one(g, energies, zs0, w_cap, out, k)


@jit
def _impact_one(data, g, energies, zs0, w_model, out, k):
    status, zs, need = gw_approach_kernel(data, g, energies[k], zs0[k], w_model)
    out[0, k], out[1, k], out[2, k] = status, need, zs
    if status == OK:
        e_p, e_l, p_c, p_y, w_top = _impact_sums(data, g, zs, min(data.w_max, w_model))
        out[3, k], out[4, k], out[5, k], out[6, k], out[7, k] = w_top, e_p, e_l, p_c, p_y


@jit(parallel=True)
def gw_impacts_array(data, g, energies, zs0, w_model, out):
    """out[:, k] = (status, w* needed, zs_d, w* at the top, E P*, E L, P(contact), P(yield)) of
    impact k, per summit (times N for the surface), in parallel (impacts are independent)."""
    for k in prange(energies.size):
        _impact_one(data, g, energies, zs0, w_model, out, k)


@jit
def _gw_impacts_serial(data, g, energies, zs0, w_model, out):
    for k in range(energies.size):
        _impact_one(data, g, energies, zs0, w_model, out, k)


def _run(n, parallel, serial, *args):
    """n impacts: in parallel from 4 on (fewer: no parallel start-up, no waiting for threads)."""
    if n >= 4:
        return run_parallel(parallel, serial, *args)
    return serial(*args)


def hertz_estimate(g, energy, w_cap):
    """(3, n) array (status, zs_d, w* at the top) of every impact with all summits Hertzian."""
    out = np.zeros((3, energy.size))
    zs0 = 0.0 if g.kind == 0 else 0.5 * (g.zs_lo + g.zs_hi)
    _run(energy.size, gw_hertz_array, _gw_hertz_serial, g, energy, zs0, w_cap, out)
    return out


def solve_impacts(data, g, energy, zs0, w_model):
    """The (8, n) output of :func:`gw_impacts_array` for the given forward table."""
    out = np.zeros((8, energy.size))
    _run(energy.size, gw_impacts_array, _gw_impacts_serial, data, g, energy, zs0, w_model, out)
    return out
