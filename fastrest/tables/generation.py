"""Computing a table's arrays from a grid (Numba, all cores; no I/O).

Every node is the direct solver's value (:mod:`fastrest.energy`, :mod:`fastrest.unloading`): w_m*
of each material at increasing V1* by Newton's method marching from one speed to the next, e and
1 - e^2 of every unloading model from it; and W* = 1 - F on the w* grid by cumulative quadrature.
The arrays travel in a :class:`GeneratedTable`, from which a :class:`~fastrest.tables.Table` is
built and a table file written.
"""
from __future__ import annotations

from typing import Any
from numpy.typing import ArrayLike, NDArray
from dataclasses import dataclass, replace

import numba as nb
import numpy as np

from .._deprecation import keyword_only
from .._jit import jit
from .._threads import run_parallel
from .._validation import OMEGA_M_STAR_MAX
from ..loading.jackson_green import W_SWITCH, area_exponent, omega_star_limit_kernel
from ..critical import c_of_nu
from ..energy import F_SWITCH, jg_integral, omega_m_sorted_kernel
from ..interpolation import DEGREE, share_edges
from ..limits import speed_limit
from ..loading import JACKSON_GREEN
from ..unloading import N_MODELS, restitution_kernel
from ..cells import jg_nodes
from .axes import cell_layout, energy_eps_y_axis, eps_y_blocks, nu_axis, omega_axis, v1_star_top
from .grid import QUANTITIES, c_eps_y, normalise_grid

__all__ = ["GeneratedTable", "generate", "quantity_rows_array", "w_star_rows_array"]


@dataclass(frozen=True, eq=False)
class GeneratedTable:
    """A table's arrays, as generated or read from a file (what a file stores, in memory).

    Attributes
    ----------
    grid : dict
        The normalised grid (:func:`~fastrest.tables.normalise_grid`).
    eps_y : ndarray
        (n_eps_y_energy,) plain eps_y nodes of ``W_star`` and ``v1_star_max``.
    nu : ndarray
        (n_nu,) nu nodes.
    v_top : float
        The largest V1* tabulated.
    base_fine, base : int
        First cell keys of the fine and coarse V1* cells (:func:`fastrest.interpolation.two_level_index`).
    edges : ndarray
        (ncell, 2) V1* at the start and end of every cell.
    nodes : ndarray
        (ncell, 6) V1* of every tabulated point.
    blocks : tuple of Block
        The blocks of cells with their material axes and values.
    omega_star : ndarray
        (256,) w* nodes of ``W_star``.
    W_star : ndarray
        (n_eps_y_energy, n_nu, 256) (W_ep)* = 1 - F(w*), JGM eq (25); NaN past a/R = 1.
    v1_star_max : ndarray
        (n_eps_y_energy, n_nu) V1* at which w_m* = 425.

    Notes
    -----
    What :func:`generate` returns, :func:`~fastrest.tables.schema.write_generated` writes and
    :func:`~fastrest.tables.schema.read_generated` reads back, bit for bit.

    Examples
    --------
    >>> from fastrest.tables.schema import read_generated
    >>> from fastrest.tables import default_table_path
    >>> gen, attrs = read_generated(default_table_path())
    >>> gen.W_star.shape, len(gen.blocks)
    ((32, 8, 256), 4)
    """

    grid: dict[str, Any]
    eps_y: np.ndarray
    nu: np.ndarray
    v_top: float
    base_fine: int
    base: int
    edges: np.ndarray
    nodes: np.ndarray
    blocks: tuple[Any, ...]
    omega_star: np.ndarray
    W_star: np.ndarray
    v1_star_max: np.ndarray


@jit(parallel=True)
def quantity_rows_array(eps_row, nu_nodes, v_nodes, out):
    """Every tabulated quantity at the V1* nodes of a row of materials (jit, parallel over nu).

    Parameters
    ----------
    eps_row : ndarray
        (n_nu,) eps_y = Sy/E' (-) of each material.
    nu_nodes : ndarray
        (n_nu,) Poisson's ratio (-) of each material.
    v_nodes : ndarray
        Increasing V1* (-), all above 1.9^1.25.
    out : ndarray
        (quantities, n_nu, v_nodes.size), written: out[q, j, k] is quantity q of
        :data:`~fastrest.tables.QUANTITIES` at V1* = v_nodes[k] for material j.

    Notes
    -----
    w_m* solves F(w_m*) = V1*^2 (JGM eq 29) by Newton's method marching through the speeds, up to
    w* = 1700 (past 425 and a/R = 1 the formulas are a smooth extension that stencils of nearby
    materials need); e and 1 - e^2 of every unloading model from JGM eq (38).

    Examples
    --------
    >>> import numpy as np
    >>> out = np.empty((7, 6, 1))
    >>> quantity_rows_array(np.full(6, 0.005), np.full(6, 0.33), np.array([5.0]), out)
    >>> round(float(out[1, 0, 0]), 6)
    0.898078
    """
    for j in nb.prange(nu_nodes.size):
        nu = nu_nodes[j]
        eps_y = eps_row[j]
        # Neighbours in an interpolation stencil may need w* > 425, even past a/R = 1 (for a
        # material whose own w_m* <= 425): there the formulas serve as a smooth extension.
        w_hi = 4.0 * OMEGA_M_STAR_MAX
        w = np.empty(v_nodes.size)
        omega_m_sorted_kernel(v_nodes, eps_y, nu, w_hi, JACKSON_GREEN, 0.0, w)  # tables: JG only
        for k in range(v_nodes.size):
            out[0, j, k] = w[k]
            for m in range(N_MODELS):
                e, loss, _, _ = restitution_kernel(v_nodes[k], w[k], w[k] - 1.0, eps_y, nu, m, JACKSON_GREEN, 0.0)
                out[1 + 2 * m, j, k] = e
                out[2 + 2 * m, j, k] = loss


@jit(parallel=True)
def w_star_rows_array(eps_y, nu_nodes, omega_grid, out):
    """W* at the w* nodes of a row of materials (jit, parallel over nu).

    Parameters
    ----------
    eps_y : float
        Sy/E' (-) of the row.
    nu_nodes : ndarray
        (n_nu,) Poisson's ratios (-).
    omega_grid : ndarray
        Increasing w* (-) from 0.
    out : ndarray
        (n_nu, omega_grid.size), written: (W_ep)* = 1 - F(w*) (-).

    Notes
    -----
    JGM eqs (19), (25): the closed form 1 - w*^2.5 up to 1.9, cumulative Gauss-Legendre quadrature
    of the JG law above, NaN from the end of the law (a/R = 1, eq 12) on.

    Examples
    --------
    >>> import numpy as np
    >>> out = np.empty((1, 2))
    >>> w_star_rows_array(0.005, np.array([0.33]), np.array([1.0, 100.0]), out)
    >>> float(out[0, 0])
    0.0
    """
    for j in nb.prange(nu_nodes.size):
        nu = nu_nodes[j]
        C = c_of_nu(nu)
        B = area_exponent(eps_y)
        f = F_SWITCH
        prev = W_SWITCH
        for k in range(omega_grid.size):
            z = omega_grid[k]
            if z <= W_SWITCH:
                out[j, k] = 1.0 - z**2.5
            elif z >= omega_star_limit_kernel(eps_y, nu):
                out[j, k] = np.nan
            else:
                f += 2.5 * jg_integral(prev, z, eps_y, nu, C, B)
                prev = z
                out[j, k] = 1.0 - f


def _progress(jobs, progress):
    if progress is False:
        return jobs
    try:
        from tqdm import tqdm
    except ImportError:
        return jobs
    return tqdm(jobs, desc="fastrest build", unit="eps_y row", disable=None)


@keyword_only("progress")
def generate(grid: dict[str, Any] | None = None, *, progress: Any = None) -> GeneratedTable:
    """Compute a table's arrays (no I/O).

    Parameters
    ----------
    grid : dict or None
        Grid specification (:func:`~fastrest.tables.normalise_grid`); None: the shipped table's.
    progress : None or bool
        None: a progress bar (tqdm) if on a terminal and tqdm is installed; False: none.

    Returns
    -------
    GeneratedTable
        Every array of the table; ``Table(generate(grid))`` evaluates it without a file.

    Raises
    ------
    TypeError, ValueError
        A bad grid (:func:`~fastrest.tables.normalise_grid`).

    Notes
    -----
    w_m* solves the energy balance F(w_m*) = V1*^2 (JGM eq 29); e is JGM eq (38) with the
    unloading model's residual interference; W* is JGM eq (25). The result is bit-reproducible
    (independent of thread count and CPU instruction set).

    Examples
    --------
    >>> from fastrest.tables import Table, generate
    >>> g = generate(dict(eps_y_min=0.004, eps_y_max=0.006, n_eps_y=6, nu_min=0.3, nu_max=0.35,
    ...                   n_nu=6, bits_per_octave=1, eps_y_blocks=[], n_eps_y_energy=6), progress=False)
    >>> round(Table(g).e(5.0, 0.005, 0.33), 4)
    0.8981
    """
    g = normalise_grid(grid)
    nus = nu_axis(g)
    v_top = v1_star_top(g)
    base_fine, base, edges = cell_layout(g, v_top)
    omega = omega_axis()
    eps_w = energy_eps_y_axis(g)
    nodes = jg_nodes(edges, v_top).reshape(edges.shape[0], -1)
    blocks = [replace(b, values=np.empty((len(QUANTITIES), b.n, nus.size, b.cstop - b.cell0, DEGREE + 1)))
              for b in eps_y_blocks(g, edges)]
    w_star = np.empty((eps_w.size, nus.size, omega.size))
    jobs = [(b, i) for b in blocks for i in range(b.n)] + [(None, i) for i in range(eps_w.size)]
    for b, i in _progress(jobs, progress):
        if b is None:
            run_parallel(w_star_rows_array, None, float(eps_w[i]), nus, omega, w_star[i])
            continue
        eps_row = b.c_eps_y[i] / c_eps_y(1.0, nus)  # eps_y of the row's nodes
        flat = nodes[b.cell0:b.cstop].ravel()
        out = np.empty((len(QUANTITIES), nus.size, flat.size))
        run_parallel(quantity_rows_array, None, eps_row, nus, flat, out)
        b.values[:, i] = share_edges(out.reshape(out.shape[:2] + (-1, DEGREE + 1)))
    v_max = np.array([[speed_limit(e, n) for n in nus] for e in eps_w])
    return GeneratedTable(grid=g, eps_y=eps_w, nu=nus, v_top=v_top, base_fine=base_fine, base=base,
                          edges=edges, nodes=nodes, blocks=tuple(blocks), omega_star=omega, W_star=w_star,
                          v1_star_max=v_max)
