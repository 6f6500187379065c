"""The reader of a table's stored W* = 1 - F(w*): the loading energy of many materials.

A table file stores (W_ep)* = 1 - F(w*) (JGM eq 25) on a plain grid: eps_y (``n_eps_y_energy``
uniform nodes), nu (the table's nodes) and w* (20 uniform nodes on [0, 1.9], 236 geometric on
(1.9, 425]). F is V1*^2 of the impact whose maximum interference is w* (eq 29). Up to w* = 1.9
F = w*^2.5 exactly (Hertz, eq 19), for every material; above, this module interpolates ln F with
10-point Lagrange stencils (:data:`STENCIL_W`) in ln w* (where the integrand of F is an entire
function, so ln F is very smooth), in eps_y and in nu. :meth:`fastrest.tables.Table.W_star` and
:meth:`~fastrest.tables.Table.loading_energy` call it.
"""
from __future__ import annotations

from typing import TYPE_CHECKING
if TYPE_CHECKING:
    from .generation import GeneratedTable
import math
from collections import namedtuple

import numpy as np

from .._jit import jit
from .._validation import EDGE_TOL, OMEGA_M_STAR_MAX
from ..loading.jackson_green import W_SWITCH, omega_star_limit_kernel
from .grid import OMEGA_GRID_HERTZ
from .kernel import EPS_Y_AR_BINDS, _first_node

__all__ = ["EnergyData", "W_STAR_OMEGA_MAX", "STENCIL_W", "energy_data", "loading_energy_kernel", "loading_energy_array"]

#: The stored W* ends at w* = 425.
W_STAR_OMEGA_MAX = OMEGA_M_STAR_MAX
#: Lagrange points per axis (at most; fewer on an axis with fewer nodes). The stored eps_y and nu
#: axes are plain (not the mapped C(nu) eps_y of the restitution blocks) and coarse (32 x 8 nodes):
#: on the shipped table 10-point stencils reach 8e-11 relative where 6 and 8 points leave 2e-8 and
#: 4e-10 near w* = 425 (bench/w_star_reader.py; 12 points gain nothing more).
STENCIL_W = 10

EnergyData = namedtuple("EnergyData", ["eps_lo", "eps_hi", "inv_h_eps", "n_eps", "nu_lo", "nu_hi", "inv_h_nu",
                                       "n_nu", "ln_w0", "inv_h_ln_w", "n_w", "ln_f", "stencil"])
EnergyData.__doc__ = """Numba-friendly stored W* of a :class:`~fastrest.tables.Table` (``table.energy``).

Built by :func:`energy_data` only (by keyword).

Parameters
----------
eps_lo, eps_hi, inv_h_eps, n_eps : float, float, float, int
    The uniform eps_y = Sy/E' nodes (-): first, last, 1/spacing, count.
nu_lo, nu_hi, inv_h_nu, n_nu : float, float, float, int
    The uniform nu nodes (-).
ln_w0, inv_h_ln_w, n_w : float, float, int
    The w* nodes from 1.9 to 425, uniform in ln w*: ln 1.9, 1/spacing, count.
ln_f : ndarray
    (n_eps, n_nu, n_w) ln F = ln(1 - W*) at those nodes (NaN past a/R = 1), JGM eq (25).
stencil : int
    Lagrange points per axis (at most).

Examples
--------
>>> import fastrest
>>> fastrest.load_table().energy.ln_f.shape
(32, 8, 237)
"""


def energy_data(gen: GeneratedTable, stencil: int = STENCIL_W) -> EnergyData:
    """The :class:`EnergyData` of a table's arrays.

    Parameters
    ----------
    gen : GeneratedTable
        The arrays (its ``W_star``, ``eps_y``, ``nu``, ``omega_star``).
    stencil : int
        Lagrange points per axis, 2 to 12 (bench/w_star_reader.py compares them).

    Returns
    -------
    EnergyData

    Raises
    ------
    ValueError
        ``stencil`` outside [2, 12].

    Examples
    --------
    >>> from fastrest.tables import default_table_path
    >>> from fastrest.tables.schema import read_generated
    >>> energy_data(read_generated(default_table_path())[0], stencil=6).stencil
    6
    """
    if not 2 <= stencil <= 12:
        raise ValueError(f"stencil must be in [2, 12]; got {stencil!r}")
    eps, nus, omega = gen.eps_y, gen.nu, gen.omega_star
    jg = omega[OMEGA_GRID_HERTZ - 1:]  # 1.9 and the geometric nodes above it
    with np.errstate(invalid="ignore"):
        ln_f = np.log(1.0 - gen.W_star[:, :, OMEGA_GRID_HERTZ - 1:])
    return EnergyData(
        eps_lo=float(eps[0]), eps_hi=float(eps[-1]), inv_h_eps=float((eps.size - 1) / (eps[-1] - eps[0])),
        n_eps=int(eps.size), nu_lo=float(nus[0]), nu_hi=float(nus[-1]),
        inv_h_nu=float((nus.size - 1) / (nus[-1] - nus[0])), n_nu=int(nus.size), ln_w0=math.log(jg[0]),
        inv_h_ln_w=float((jg.size - 1) / (math.log(jg[-1]) - math.log(jg[0]))), n_w=int(jg.size),
        ln_f=np.ascontiguousarray(ln_f), stencil=int(stencil))


@jit(inline=True)
def _weights(pos, n, stencil, w):
    """First node and Lagrange weights w[:m] (m = min(stencil, n)) at position ``pos`` on a uniform grid of n
    nodes (unit spacing), the stencil centred and moved inside at the ends; returns (first, m)."""
    m = min(stencil, n)
    i = _first_node(pos, m, n)
    t = pos - i
    for a in range(m):
        p = 1.0
        for b in range(m):
            if b != a:
                p *= (t - b) / (a - b)
        w[a] = p
    return i, m


@jit
def loading_energy_kernel(tab, w, eps_y, nu):
    """The loading energy F(w*) = 1 - W* of one material from a table's stored W* (jit).

    Parameters
    ----------
    tab : EnergyData
        The stored W* of a table, ``table.energy``.
    w : float
        Normalised interference w* = omega/omega_c (-).
    eps_y : float
        Sy/E' (-).
    nu : float
        Poisson's ratio (-).

    Returns
    -------
    float
        F (-), V1*^2 of the impact reaching w* (JGM eqs 19, 25, 29); NaN outside the table (eps_y,
        nu beyond its range by more than a few ulp, w* outside [0, 425] or NaN) and where a stencil
        node or the point itself lies past a/R = 1.

    Notes
    -----
    w* <= 1.9: w*^2.5 exactly. Above: Lagrange interpolation of ln F in ln w*, eps_y and nu.

    Examples
    --------
    >>> import fastrest
    >>> loading_energy_kernel(fastrest.load_table().energy, 1.0, 0.005, 0.33)
    1.0
    """
    eps_lo, eps_hi, nu_lo, nu_hi = tab.eps_lo, tab.eps_hi, tab.nu_lo, tab.nu_hi
    ln_f, stencil = tab.ln_f, tab.stencil
    if not (eps_y >= eps_lo * (1.0 - EDGE_TOL) and eps_y <= eps_hi * (1.0 + EDGE_TOL)
            and nu >= nu_lo * (1.0 - EDGE_TOL) and nu <= nu_hi * (1.0 + EDGE_TOL)):
        return np.nan
    if not (w >= 0.0 and w <= W_STAR_OMEGA_MAX):
        return np.nan
    if w <= W_SWITCH:
        return w**2.5
    eps_y = min(max(eps_y, eps_lo), eps_hi)
    nu = min(max(nu, nu_lo), nu_hi)
    if eps_y > EPS_Y_AR_BINDS and not w < omega_star_limit_kernel(eps_y, nu):
        return np.nan
    we = np.empty(stencil)
    wn = np.empty(stencil)
    ww = np.empty(stencil)
    i, me = _weights((eps_y - eps_lo) * tab.inv_h_eps, tab.n_eps, stencil, we)
    j, mn = _weights((nu - nu_lo) * tab.inv_h_nu, tab.n_nu, stencil, wn)
    k, mw = _weights((math.log(w) - tab.ln_w0) * tab.inv_h_ln_w, tab.n_w, stencil, ww)
    total = 0.0
    for a in range(me):
        for b in range(mn):
            s = 0.0
            for c in range(mw):
                s += ww[c] * ln_f[i + a, j + b, k + c]
            total += we[a] * wn[b] * s
    return math.exp(total)


@jit
def loading_energy_array(tab, w, eps_y, nu, out):
    """out[k] = :func:`loading_energy_kernel` (tab, w[k], eps_y[k], nu[k]) (jit loop).

    Parameters
    ----------
    tab : EnergyData
    w, eps_y, nu : ndarray
        Flat float64 arrays of equal size: w* (-), Sy/E' (-), Poisson's ratio (-).
    out : ndarray
        Flat float64 array written in place (NaN where the table has no answer).

    Examples
    --------
    >>> import numpy as np, fastrest
    >>> out = np.empty(1)
    >>> loading_energy_array(fastrest.load_table().energy, np.array([4.0]), np.array([0.005]), np.array([0.33]), out)
    >>> bool(out[0] > 1.9**2.5)
    True
    """
    for k in range(w.size):
        out[k] = loading_energy_kernel(tab, w[k], eps_y[k], nu[k])
