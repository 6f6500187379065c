"""The cells curves, scenes and tables share: the Hertz range's closed forms and the JG nodes.

Below V1* = 1.9^1.25 (w_m* <= 1.9, Hertz loading) w_m*, e and 1 - e^2 do not depend on the
material: :func:`hertz_rows` fits them once per unloading model on :data:`N_HERTZ` cells of
2^:data:`HERTZ_BITS_PER_OCTAVE` per octave (:mod:`fastrest.interpolation`), and every curve,
scene and table stores those rows first. Above the kink each builder places its own cells;
:func:`jg_nodes` gives their interpolation points, kept on the JG side of the kink.

The cell of 1 < V1* <= 1.9^1.25 is ``(bits(V1*) >> HERTZ_SHIFT) - HERTZ_BASE``.
"""
from __future__ import annotations

from typing import Any
from numpy.typing import ArrayLike, NDArray
import math

import numpy as np

from ._jit import jit
from . import unloading as _unloading
from .loading.jackson_green import W_SWITCH
from .energy import V_SWITCH
from .interpolation import MANTISSA_BITS, cell_edges, chebyshev_nodes, fit_cells, share_edges

__all__ = ["closed_form", "HERTZ_BITS_PER_OCTAVE", "HERTZ_SHIFT", "HERTZ_BASE", "HERTZ_EDGES", "N_HERTZ",
           "hertz_rows", "jg_nodes"]


@jit
def closed_form(v, model):
    """(w_m*, e, 1 - e^2) at 0 <= V1* <= 1.9^1.25 (Hertz loading), exact.

    The same for every material: under Hertz loading P_m* = w_m*^1.5 and every registered
    unloading model's w_res* depends on w_m* alone (tests/test_unloading.py).

    Parameters
    ----------
    v : float
        V1* = V1/V_c (-), JGM eq (30); 0 <= v <= 1.9^1.25.
    model : int
        Unloading model code (``fastrest.unloading.JCG``, ``ETSION``, ``BRAKE``).

    Returns
    -------
    tuple of float
        w_m* (-), e (-) and 1 - e^2 (-). NaN for an unknown ``model`` (no exception: a kernel).

    Notes
    -----
    w_m* = V1*^0.8 (JGM eq 19 in the energy balance 29), e from the unloading model's residual
    (eqs 33, 35) through eq (38); for V1* <= 1 the impact is elastic: e = 1, 1 - e^2 = 0.

    Examples
    --------
    >>> from fastrest.cells import closed_form
    >>> w, e, loss = closed_form(1.5, 0)
    >>> bool(abs(w - 1.5**0.8) < 1e-15 and 0 < e < 1)
    True
    """
    if v <= 1.0:
        return v**0.8, 1.0, 0.0
    lv = math.log(v)
    w = min(math.exp(0.8 * lv), W_SWITCH)
    # eps_y and nu are not read under Hertz loading: NaN would show if a model did
    e2, loss, _, _, _ = _unloading.restitution(model, v * v, w, math.expm1(0.8 * lv), w**1.5, np.nan, np.nan, 0, 0.0)
    return w, math.sqrt(e2), loss


@jit
def _hertz_node_array(v, model, out):
    """out[:, i] = (w_m*, e, (1 - e^2)/(V1* - 1)) at 1 < v[i] <= 1.9^1.25: what the Hertz cells fit.

    The loss is fitted divided by V1* - 1 (exact in floating point for 1 < V1* <= 2) and multiplied
    back on evaluation, so 1 - e^2 keeps its relative accuracy as V1* -> 1.
    """
    for i in range(v.size):
        w, e, loss = closed_form(v[i], model)
        out[0, i] = w
        out[1, i] = e
        out[2, i] = loss / (v[i] - 1.0)


#: Cells per octave of the Hertz-range cells (2^6): the closed forms to ~1e-16 (measured in
#: tests/test_curve.py; 2^5 leaves ~5e-15 on w_m* = V1*^0.8 near V1* = 2).
HERTZ_BITS_PER_OCTAVE = 6
#: Right shift of V1*'s bits that gives its Hertz-range cell key.
HERTZ_SHIFT = MANTISSA_BITS - HERTZ_BITS_PER_OCTAVE


def _hertz_layout():
    base, edges = cell_edges(1.0, V_SWITCH, HERTZ_BITS_PER_OCTAVE)
    return int(base), edges


#: Key of the first Hertz-range cell (V1* = 1), and the cells' [lo, hi] edges, shape (N_HERTZ, 2).
HERTZ_BASE, HERTZ_EDGES = _hertz_layout()
#: Rows of the Hertz-range cells, which come first in every curve's, scene's and table's row arrays.
N_HERTZ = HERTZ_EDGES.shape[0]


def hertz_rows(model: int) -> NDArray[np.float64]:
    """Cell rows of the closed forms over 1 < V1* <= 1.9^1.25 for one unloading model.

    Parameters
    ----------
    model : int
        Unloading model code (``fastrest.unloading.JCG``, ``ETSION``, ``BRAKE``).

    Returns
    -------
    ndarray
        Shape (3, N_HERTZ, 8): rows [center, 1/half_width, c0..c5] (:mod:`fastrest.interpolation`)
        of w_m* (-), e (-) and (1 - e^2)/(V1* - 1) (-), in that order.

    Notes
    -----
    Fits :func:`closed_form` (JGM eqs 19, 33, 35, 38) at each cell's Chebyshev-Lobatto points;
    the loss is fitted divided by V1* - 1 so that it keeps its relative accuracy as V1* -> 1.

    Examples
    --------
    >>> from fastrest.cells import N_HERTZ, hertz_rows
    >>> hertz_rows(0).shape == (3, N_HERTZ, 8)
    True
    """
    nodes = chebyshev_nodes(HERTZ_EDGES)
    nodes[0, 0] = np.nextafter(1.0, 2.0)  # (1 - e^2)/(V1* - 1) is 0/0 at 1: its limit, one ulp in
    flat = nodes.ravel()
    vals = np.empty((3, flat.size))
    _hertz_node_array(flat, model, vals)
    return fit_cells(HERTZ_EDGES, share_edges(vals.reshape((3,) + nodes.shape)))


def jg_nodes(edges: NDArray[np.float64], v_top: float) -> NDArray[np.float64]:
    """The interpolation points of cells above the kink, flattened and increasing.

    Parameters
    ----------
    edges : ndarray
        Cell edges [lo, hi] (-), shape (ncell, 2), from :func:`fastrest.interpolation.cell_edges`
        starting at V1* = 1.9^1.25.
    v_top : float
        Largest V1* the cells cover (-).

    Returns
    -------
    ndarray
        The cells' Chebyshev-Lobatto points (-), shape (ncell * 6,), C-contiguous, inside
        (1.9^1.25, v_top].

    Notes
    -----
    The first cell's left end takes the JG side's limit (one ulp above the kink at w* = 1.9,
    JGM eqs 8-9); in cells a few ulp wide no rounded point falls outside (nodes an ulp from where
    the fit places them change values by ~1e-16 relative).

    Examples
    --------
    >>> from fastrest.cells import jg_nodes
    >>> from fastrest.energy import V_SWITCH
    >>> from fastrest.interpolation import cell_edges
    >>> nodes = jg_nodes(cell_edges(V_SWITCH, 10.0, 5)[1], 10.0)
    >>> bool(nodes[0] > V_SWITCH and nodes[-1] == 10.0)
    True
    """
    nodes = chebyshev_nodes(edges)
    return np.ascontiguousarray(np.clip(nodes, np.nextafter(V_SWITCH, np.inf), v_top).ravel())
