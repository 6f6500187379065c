"""The Numba-friendly form of a table, :class:`TableData`, built by keyword in one place
(:func:`table_data`); :mod:`fastrest.tables.kernel` evaluates it."""
from __future__ import annotations

from typing import TYPE_CHECKING, Any
from numpy.typing import ArrayLike, NDArray
if TYPE_CHECKING:
    from .generation import GeneratedTable
from collections import namedtuple

import numpy as np

from ..interpolation import MANTISSA_BITS, values_to_coeffs
from ..cells import hertz_rows
from .axes import xi_range

__all__ = ["TableData", "table_data"]

TableData = namedtuple("TableData", ["map_rate", "xi0", "nu0", "inv_h_nu", "n_nu",
                                     "eps_lo", "eps_hi", "nu_lo", "nu_hi", "v_split", "shift_fine",
                                     "base_fine", "shift", "base", "v_top", "v_safe", "cells",
                                     "cell_block", "block_inv_h", "block_n", "block_cell0",
                                     "block_offset", "block_qstride", "coef", "hertz", "n_quantities"],
                      module="fastrest.tables")  # its public home: pickles and Numba's cache refer to it there
TableData.__doc__ = """Numba-friendly data of a :class:`~fastrest.tables.Table` (``table.data``), for :mod:`fastrest.jit`.

A namedtuple of floats, ints and contiguous arrays, built only inside fastrest (by keyword).
Pass it into your own jitted code and call ``fastrest.jit.e_table(data, v1_star, eps_y, nu, JCG)``.
The kernels read its arrays through raw data pointers (no reference counting per point,
``python -m bench.stencil``), so the arrays must outlive the call: pass the data from Python as an
argument of your jitted function, as above. A TableData assembled inside jitted code from arrays
allocated there, and dropped at the call, is not supported (its arrays can be freed before they
are read).

Parameters
----------
map_rate : float
    k of the material axis map xi = expm1(k C(nu) eps_y)/k (xi = C(nu) eps_y for k = 0) (-).
xi0 : float
    xi of the first material node (-).
nu0, inv_h_nu : float
    First nu node and 1/spacing of the uniform nu nodes (-).
n_nu : int
    Number of nu nodes.
eps_lo, eps_hi, nu_lo, nu_hi : float
    The table's materials: eps_y = Sy/E' (-) and nu (-) ranges.
v_split, shift_fine, base_fine, shift, base : float, int
    V1* cell layout (:func:`fastrest.interpolation.two_level_index`): fine cells below V1* = v_split.
v_top : float
    The largest V1* held (-).
v_safe : float
    Below this V1* every material of the table has w_m* <= 425 (no limit check needed) (-).
cells : ndarray
    (ncell, 2) [center, 1/half_width] of each V1* cell.
cell_block : ndarray of int64
    The block of material nodes each cell uses.
block_inv_h, block_n, block_cell0, block_offset, block_qstride : ndarray
    Per block: 1/spacing in xi, node count, first cell, offset in ``coef``, stride per quantity.
coef : ndarray
    1-D: for each block b from block_offset[b] a C-order (n_quantities, cells of b, block_n[b],
    n_nu, 6) array of the cell polynomials' coefficients of :data:`~fastrest.tables.QUANTITIES`.
hertz : ndarray
    (n_quantities x N_HERTZ, 8) rows of the material-independent closed forms below V1* = 1.9^1.25
    (:mod:`fastrest.curve`'s cells).
n_quantities : int
    1 + 2 x the number of unloading models held.

Notes
-----
The tabulated quantities are the direct solver's w_m* (JGM eq 29), e (eq 38) and 1 - e^2; see
docs/table-format.md for the layout and the evaluation rule.

Examples
--------
>>> import fastrest
>>> from fastrest import jit as frj
>>> data = fastrest.load_table().data
>>> round(frj.e_table(data, 5.0, 0.005, 0.33, frj.JCG), 6)
0.898078
"""


def _hertz_table_rows(n_models):
    """Hertz-range rows for the table's quantities (q * N_HERTZ + cell): w_m*, then e and 1 - e^2
    of the first ``n_models`` unloading models."""
    rows = [hertz_rows(code) for code in range(n_models)]
    return np.ascontiguousarray(np.concatenate([rows[0][0]] + [r[k] for r in rows for k in (1, 2)]))


def table_data(gen: GeneratedTable) -> TableData:
    """The :class:`TableData` of a table's arrays (the one place it is built, by keyword).

    Parameters
    ----------
    gen : GeneratedTable
        The arrays (:func:`~fastrest.tables.generate`, or read from a file).

    Returns
    -------
    TableData
        The cell polynomials' coefficients (from the node values, :func:`fastrest.interpolation.values_to_coeffs`)
        and the grid's constants.

    Examples
    --------
    >>> import fastrest
    >>> fastrest.load_table().data.n_quantities
    7
    """
    g = gen.grid
    eps, nus, edges = gen.eps_y, gen.nu, gen.edges
    center = 0.5 * (edges[:, 0] + edges[:, 1])
    half = 0.5 * (edges[:, 1] - edges[:, 0])
    xi0, xi1 = xi_range(g)
    blocks = gen.blocks
    nq = blocks[0].values.shape[0]
    # per block (nq, n_eps, n_nu, ncell, 6) -> (nq, ncell, n_eps, n_nu, 6), flattened one after another
    parts = [np.ascontiguousarray(values_to_coeffs(b.values).transpose(0, 3, 1, 2, 4)).ravel() for b in blocks]
    cell_block = np.empty(edges.shape[0], dtype=np.int64)
    for k, b in enumerate(blocks):
        cell_block[b.cell0:b.cell1] = k

    def i64(x):
        return np.array(x, dtype=np.int64)

    return TableData(
        map_rate=g["c_eps_y_map_rate"], xi0=float(xi0),
        nu0=float(nus[0]), inv_h_nu=float((nus.size - 1) / (nus[-1] - nus[0])), n_nu=int(nus.size),
        eps_lo=float(eps[0]), eps_hi=float(eps[-1]), nu_lo=float(nus[0]), nu_hi=float(nus[-1]),
        v_split=g["fine_v1_star_max"], shift_fine=MANTISSA_BITS - g["fine_bits_per_octave"],
        base_fine=int(gen.base_fine), shift=MANTISSA_BITS - g["bits_per_octave"], base=int(gen.base),
        v_top=float(gen.v_top), v_safe=float(np.min(gen.v1_star_max)),
        cells=np.ascontiguousarray(np.stack([center, 1.0 / half], 1)), cell_block=cell_block,
        block_inv_h=np.array([(b.n - 1) / (xi1 - xi0) for b in blocks]), block_n=i64([b.n for b in blocks]),
        block_cell0=i64([b.cell0 for b in blocks]), block_offset=i64(np.cumsum([0] + [p.size for p in parts[:-1]])),
        block_qstride=i64([p.size // nq for p in parts]), coef=np.concatenate(parts),
        hertz=_hertz_table_rows((nq - 1) // 2), n_quantities=nq)
