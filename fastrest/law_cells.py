"""The contact law's cells: virgin-loading force and unloading residual behind one index, read
without a branch.

A DEM code steps every contact at every time step (step-major): neighbouring contacts are in
different states (loading, unloading, apart), so a force law that branches on the state
mispredicts, and one that computes the unloading model's residual w_res* (a log1p and an expm1
for JCG, a pow for Etsion) when a contact first unloads stalls the loop. This law does neither:

* the residual is tabulated beside P* on the same cells, so every virgin-loading step stores
  delta = w_max - w_res* with the maximum: the history row is complete at every step;
* loading, unloading/reloading and apart are computed together and chosen by selects
  (:func:`fastrest.interpolation.select`), with one division and two square roots, no call.

Each row holds :data:`LAW_ROW` float64: ``[center, 1/half_width, P* c0..c5, delta c0..c5, 0, 0]``
(the two degree-5 polynomials of :mod:`fastrest.interpolation` in one local coordinate; 128 bytes,
two cache lines). Cells: 2^5 per octave of w from w = 1, the cell holding w = 1.9 cut there, so the
row of w > 1 is ``(bits(w) >> 47) - KEY_ONE + (w > 1.9)`` (:func:`law_row`); above 1.9 they are the
cells of ``ForwardData.p_rows`` and hold its P* coefficients bit for bit. Below 1.9 P* is Hertz's
w^1.5, computed (the rows hold its fit, unused); delta is tabulated from w = 1 (JCG's residual
starts there; Etsion's and Brake's are 0 under Hertz loading, delta = w) and is w up to w = 1.

delta is interpolated to 3.3e-14 relative of the unloading model's formula (eq 35, eqs 33-34,
Brake's; the worst of a search over every cell, tests/test_law_cells.py), the level of the P*
cells; the unloading force P_max s^1.5, s = (w - w_res*)/delta, moves by 1.5 (1 - s)/s of it:
within 1e-12 relative for s >= 0.1 (9.4e-13 at 0.05) and 2e-14 of P_max everywhere
(docs/model.md section 10).
"""
from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

from ._jit import jit
from .interpolation import (MANTISSA_BITS, ROW, cell_edges, cell_key, chebyshev_nodes, estrin5, fdiv, fit_cells,
                            float_bits, select, share_edges)
from .loading import p_star_unchecked
from .loading.jackson_green import W_SWITCH
from .unloading import residual

__all__ = ["LAW_ROW", "LAW_BITS_PER_OCTAVE", "KEY_ONE", "law_rows", "law_row", "virgin", "elastic_back",
           "outside", "material_law", "law_step", "law_step_branching"]

#: float64 per row: center, 1/half_width, six coefficients of P*, six of delta, two zeros.
LAW_ROW = 16
#: Cells per octave of w are 2^LAW_BITS_PER_OCTAVE (those of ``ForwardData.p_rows``).
LAW_BITS_PER_OCTAVE = 5
_SHIFT = MANTISSA_BITS - LAW_BITS_PER_OCTAVE
#: Cell key of w = 1, where the rows start.
KEY_ONE = cell_key(1.0, LAW_BITS_PER_OCTAVE)
_TINY = 2.2250738585072014e-308


@jit
def _delta_nodes(w, model, eps_y, nu, law, et_ratio, out):
    for j in range(w.size):
        x = w[j]
        _, out[j] = residual(model, x, x - 1.0, p_star_unchecked(law, x, eps_y, nu, et_ratio), eps_y, nu, law,
                             et_ratio)


def law_rows(edges: NDArray[np.float64], p_rows: NDArray[np.float64], eps_y: float, nu: float, model: int,
             law: int, et_ratio: float) -> NDArray[np.float64]:
    """The rows of one material's contact law (see the module doc).

    Parameters
    ----------
    edges : ndarray
        (n, 2) edges of the cells of ``p_rows`` above w = 1.9 (the first starting at 1.9); (0, 2)
        for a law that ends at or below 1.9.
    p_rows : ndarray
        (n, 8) rows of P* on ``edges`` (:func:`fastrest.forward.forward_data`).
    eps_y, nu : float
        The material (-).
    model, law : int
        Unloading model and loading law codes (:mod:`fastrest.unloading`, :mod:`fastrest.loading`).
    et_ratio : float
        Et/E (-).

    Returns
    -------
    ndarray
        (29 + n, :data:`LAW_ROW`) float64, C-contiguous.
    """
    _, low = cell_edges(1.0, W_SWITCH, LAW_BITS_PER_OCTAVE)  # 1 .. 1.9, the last cell cut at 1.9
    all_edges = np.concatenate([low, edges])
    nodes = chebyshev_nodes(all_edges)
    at = nodes.copy()
    at[low.shape[0]:, 0] = np.nextafter(at[low.shape[0]:, 0], np.inf)  # a cell starting at 1.9: the JG side
    delta = np.empty(at.size)
    _delta_nodes(np.ascontiguousarray(at.ravel()), model, eps_y, nu, law, et_ratio, delta)
    delta = delta.reshape(at.shape)
    n_low = low.shape[0]
    rows = np.zeros((all_edges.shape[0], LAW_ROW))
    rows[:n_low, :ROW] = fit_cells(low, nodes[:n_low] * np.sqrt(nodes[:n_low]))
    rows[n_low:, :ROW] = p_rows[:edges.shape[0]]
    rows[:n_low, ROW:ROW + 6] = fit_cells(low, share_edges(delta[:n_low]))[:, 2:]
    rows[n_low:, ROW:ROW + 6] = fit_cells(edges, share_edges(delta[n_low:]))[:, 2:]
    return np.ascontiguousarray(rows)


@jit(inline=True)
def law_row(w, first, last):
    """Row of w in a law's rows ``first .. first + last``: w's cell for 1 < w <= the top; the first
    row for smaller (and negative) w, the last for larger, infinite or NaN w (whose values the
    selects of :func:`law_step` do not use)."""
    key = (float_bits(w) >> _SHIFT) - KEY_ONE + select(w > W_SWITCH, 1, 0)
    key = select(key < 0, 0, key)
    return first + select(key > last, last, key)


@jit(inline=True)
def virgin(rows, first, last, w):
    """(P*, delta) of virgin loading to w > 0: Hertz's w^1.5 up to 1.9 (eq 14), the cells above
    (eq 9); delta = w up to w = 1 (w_res* = 0), the cells above."""
    i = np.uint64(law_row(w, first, last))  # >= 0: no wraparound code
    u = (w - rows[i, 0]) * rows[i, 1]
    p_cell = estrin5(u, rows[i, 2], rows[i, 3], rows[i, 4], rows[i, 5], rows[i, 6], rows[i, 7])
    d_cell = estrin5(u, rows[i, 8], rows[i, 9], rows[i, 10], rows[i, 11], rows[i, 12], rows[i, 13])
    w_pos = select(w > 0.0, w, 0.0)
    # delta > 0 always: at JCG's end (w* = 10017.5, extrapolating) the formula's 0 may interpolate
    # to <= 0, which would read as no history; the smallest normal double unloads at once instead
    d_cell = select(d_cell > 0.0, d_cell, _TINY)
    return select(w <= W_SWITCH, w_pos * math.sqrt(w_pos), p_cell), select(w <= 1.0, w, d_cell)


@jit(inline=True)
def elastic_back(w_max, p_max, delta, w):
    """P* on the elastic branch through the maximum, eq (32): p_max s^1.5, s = (w - w_res*)/delta
    with the gap to w_max taken exactly; 0 at or below w_res* (apart) and for delta = 0 (virgin)."""
    s = fdiv(delta - (w_max - w), select(delta > 0.0, delta, 1.0))
    s = select(s > 0.0, s, 0.0)
    return p_max * (s * math.sqrt(s))


@jit(inline=True)
def outside(w_end, w_max, delta, w):
    """0.0, or NaN where the law does not apply: w NaN, -inf or past ``w_end``; a row with w_max
    < 0, NaN or past ``w_end``, or w_max > 0 with delta <= 0 (no history of a law). Selects on one
    comparison each."""
    bad = select(w <= w_end, 0.0, math.nan)
    bad = select(w > -math.inf, bad, math.nan)
    bad = select(w_max >= 0.0, bad, math.nan)
    bad = select(w_max <= w_end, bad, math.nan)
    return select(delta > 0.0, bad, select(w_max == 0.0, bad, math.nan))


@jit(inline=True)
def material_law(first, last, w_end, k):
    """(first row, last row offset, end) of material ``k`` of stacked laws; for k outside
    0 .. n - 1 material 0's rows with the end NaN (every step then gives NaN), no branch."""
    ok = select(k >= 0, select(k < first.size, 1, 0), 0)
    k = select(ok == 1, k, 0)
    return first[k], last[k], select(ok == 1, w_end[k], math.nan)


@jit(inline=True)
def law_step(rows, first, last, w_end, state, w):
    """Normal force P* at interference w, updating the contact's history row, without a branch.

    Parameters
    ----------
    rows : ndarray
        (n, :data:`LAW_ROW`) rows of one or several laws (:func:`law_rows`).
    first, last : int
        This law's rows are ``first .. first + last``.
    w_end : float
        The law's end (its ``w_max``, -).
    state : float64 array of 4
        [w_max, P*(w_max), w_res*, delta]; zeros for a virgin contact. Updated in place.
    w : float64
        Interference w* (-).

    Returns
    -------
    float
        P* (-). NaN, and the row set to NaN, for w NaN, -inf or past ``w_end``, and for a row that
        is no history of a law (w_max < 0, NaN or past ``w_end``; w_max > 0 with delta <= 0).
    """
    w_max = state[0]
    p_max = state[1]
    delta = state[3]
    p_load, d_load = virgin(rows, first, last, w)
    p_back = elastic_back(w_max, p_max, delta, w)
    bad = outside(w_end, w_max, delta, w)
    top = select(w > w_max, w, w_max)
    d_top = select(w > w_max, d_load, delta)
    state[0] = top + bad
    state[1] = select(w > w_max, p_load, p_max) + bad
    state[2] = (top - d_top) + bad
    state[3] = d_top + bad
    return select(w > w_max, p_load, p_back) + bad


@jit(inline=True)
def law_step_branching(rows, first, last, w_end, state, w):
    """:func:`law_step` with branches: the same values bit for bit, fewer instructions per call.

    For loops that step one contact through time (``ContactLaw.force``, ``ContactLaw.impact``),
    where every branch is predictable and each call waits for the previous one: there computing
    every case costs more than the branches (bench/LAW_AB.md). A loop over many contacts in
    different states (a DEM step) mispredicts them: :func:`law_step` (bench/DEM_LOOP.md).
    """
    w_max = state[0]
    p_max = state[1]
    delta = state[3]
    bad = outside(w_end, w_max, delta, w)
    if bad == 0.0:
        if w > w_max:
            p_load, d_load = virgin(rows, first, last, w)
            state[0] = w
            state[1] = p_load
            state[2] = w - d_load
            state[3] = d_load
            return p_load
        return elastic_back(w_max, p_max, delta, w)
    state[0] = state[1] = state[2] = state[3] = math.nan
    return math.nan
