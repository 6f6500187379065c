"""The axes a grid implies: material nodes, V1* cells and blocks, the w* nodes of the stored W*.

* the material axis C(nu) eps_y (:func:`~fastrest.tables.grid.c_eps_y`): uniform in
  xi = expm1(k C(nu) eps_y)/k (k = ``c_eps_y_map_rate``, :func:`xi_range`), denser where a/R is
  large; each block of V1* cells (``eps_y_blocks``) has its own number of nodes (:func:`eps_y_blocks`);
* V1*: bit-indexed cells, finer below ``fine_v1_star_max`` (:func:`cell_layout`);
* w* of the stored W* (:func:`omega_axis`), on a plain eps_y axis (:func:`energy_eps_y_axis`).

Axes are computed with the math module's scalar exp and log: NumPy's vectorised ones differ in the
last bit between CPU instruction sets, and the table must be bit-reproducible.
"""
from __future__ import annotations

from typing import Any
from numpy.typing import ArrayLike, NDArray
import math
from dataclasses import dataclass

import numpy as np

from .._doc import doc, paragraphs
from .._validation import OMEGA_M_STAR_MAX
from ..loading.jackson_green import W_SWITCH
from ..energy import V_SWITCH
from ..interpolation import two_level_cells
from ..limits import speed_limit
from .grid import OMEGA_GRID_HERTZ, OMEGA_GRID_JG, c_eps_y
from .grid import normalise_grid  # noqa: F401 (used by the examples)

__all__ = ["Block", "xi_range", "c_eps_y_of_xi", "nu_axis", "energy_eps_y_axis", "omega_axis", "cell_layout",
           "eps_y_blocks", "v1_star_top"]

# The parameter of the functions of one grid, written once (fastrest._doc).
_DOC = paragraphs(param_grid="""
    Parameters
    ----------
    g : dict
        A normalised grid (:func:`normalise_grid`).
    """)


@doc(_DOC)
def xi_range(g: dict[str, Any]) -> tuple[float, float]:
    """The range of the mapped material axis xi of a grid.

    {param_grid}

    Returns
    -------
    (float, float)
        xi = expm1(k C(nu) eps_y)/k (k = ``c_eps_y_map_rate``; xi = C(nu) eps_y for k = 0) at the
        grid's smallest and largest C(nu) eps_y (-).

    Notes
    -----
    Material nodes are uniform in xi: denser where C(nu) eps_y, and with it a/R (JGM eq 12), is
    large and the law varies fastest.

    Examples
    --------
    >>> lo, hi = xi_range(normalise_grid(None))
    >>> lo < hi
    True
    """
    k = g["c_eps_y_map_rate"]
    lo = float(c_eps_y(g["eps_y_min"], g["nu_min"]))
    hi = float(c_eps_y(g["eps_y_max"], g["nu_max"]))
    return (math.expm1(k * lo) / k, math.expm1(k * hi) / k) if k > 0 else (lo, hi)


def c_eps_y_of_xi(xi: ArrayLike, k: float) -> NDArray[np.float64]:
    """C(nu) eps_y at mapped positions xi: the inverse of the map of :func:`xi_range`.

    Parameters
    ----------
    xi : array_like
        Mapped positions (-).
    k : float
        The map rate ``c_eps_y_map_rate`` (0: no map).

    Returns
    -------
    ndarray
        log1p(k xi)/k (-), element by element with math.log1p (bit-reproducible across CPUs).

    Examples
    --------
    >>> float(c_eps_y_of_xi([0.5], 0.0)[0])
    0.5
    """
    xi = np.asarray(xi, dtype=np.float64)
    if not k > 0:
        return xi
    return np.array([math.log1p(k * x) / k for x in xi.ravel()]).reshape(xi.shape)


@doc(_DOC)
def nu_axis(g: dict[str, Any]) -> NDArray[np.float64]:
    """The nu nodes (-) of a grid: ``n_nu`` uniform nodes from ``nu_min`` to ``nu_max``.

    {param_grid}

    Examples
    --------
    >>> nu_axis(normalise_grid(None))[[0, -1]]
    array([0.2 , 0.45])
    """
    return np.linspace(g["nu_min"], g["nu_max"], g["n_nu"])


@doc(_DOC)
def energy_eps_y_axis(g: dict[str, Any]) -> NDArray[np.float64]:
    """The plain eps_y nodes (-) of a grid's stored W* and ``v1_star_max``: ``n_eps_y_energy`` uniform
    nodes from ``eps_y_min`` to ``eps_y_max``.

    {param_grid}

    Examples
    --------
    >>> energy_eps_y_axis(normalise_grid(None)).size
    32
    """
    return np.linspace(g["eps_y_min"], g["eps_y_max"], g["n_eps_y_energy"])


@doc(_DOC)
def v1_star_top(g: dict[str, Any]) -> float:
    """The largest V1* (-) a table of grid ``g`` holds.

    The largest w_m* = 425 speed (:func:`fastrest.limit`, JGM section 3.3) over the
    materials of the top block's nodes, clamped into the grid's eps_y range.

    {param_grid}

    Examples
    --------
    >>> 800 < v1_star_top(normalise_grid(None)) < 2000
    True
    """
    nus = nu_axis(g)
    top = c_eps_y_of_xi(np.linspace(*xi_range(g), g["n_eps_y"]), g["c_eps_y_map_rate"])
    eps = top[:, None] / c_eps_y(1.0, nus)[None, :]
    return max(speed_limit(min(max(e, g["eps_y_min"]), g["eps_y_max"]), n)
               for e, n in zip(eps.ravel(), np.broadcast_to(nus, eps.shape).ravel()))


def omega_axis() -> NDArray[np.float64]:
    """The w* nodes (-) of the stored W*: :data:`OMEGA_GRID_HERTZ` uniform on [0, 1.9], then
    :data:`OMEGA_GRID_JG` geometric on (1.9, 425] (math.exp: bit-reproducible).

    Examples
    --------
    >>> w = omega_axis()
    >>> w.size, float(w[19]), float(w[-1])
    (256, 1.9, 425.0)
    """
    return np.concatenate([np.linspace(0.0, W_SWITCH, OMEGA_GRID_HERTZ),
                           _geomspace(W_SWITCH, OMEGA_M_STAR_MAX, OMEGA_GRID_JG + 1)[1:]])


def _geomspace(a, b, n):
    """np.geomspace with the math module's scalar exp and log: NumPy's vectorised exp, log,
    log1p and expm1 differ in the last bit between CPU instruction sets (AVX-512 or not), which
    made the shipped table differ by ~1e-15 from one machine to another."""
    la, lb = math.log(a), math.log(b)
    out = np.array([math.exp(la + (lb - la) * i / (n - 1)) for i in range(n)])
    out[0], out[-1] = a, b
    return out


def cell_layout(g: dict[str, Any], v_top: float) -> Any:
    """The V1* cells of a table over (1.9^1.25, v_top].

    Parameters
    ----------
    g : dict
        A normalised grid: 2^fine_bits_per_octave cells per octave below fine_v1_star_max (where
        1 - e^2 is small and curved, just above the kink at w* = 1.9), then 2^bits_per_octave.
    v_top : float
        The last V1* covered (-).

    Returns
    -------
    base_fine, base : int
        The first cell keys of the fine and coarse cells.
    edges : ndarray
        (ncell, 2) [start, end] V1* of every cell (:func:`fastrest.interpolation.two_level_cells`).

    Examples
    --------
    >>> g = normalise_grid(None)
    >>> cell_layout(g, v1_star_top(g))[2].shape
    (96, 2)
    """
    base_f, base, edges = two_level_cells(V_SWITCH, g["fine_v1_star_max"], v_top,
                                          g["fine_bits_per_octave"], g["bits_per_octave"])
    return int(base_f), int(base), edges


@dataclass(frozen=True, eq=False)
class Block:
    """A block of V1* cells with its own material axis.

    Attributes
    ----------
    cell0, cell1 : int
        The cells ``cell0 <= c < cell1`` of the block.
    cstop : int
        End of the cells stored: ``cell1 + 1`` for every block but the last, which also stores the
        next block's first cell on its own material grid (for the blend across the boundary).
    n : int
        Nodes of the block's material axis.
    c_eps_y : ndarray
        The block's C(nu) eps_y nodes (n,).
    values : ndarray or None
        (quantities, n, n_nu, cstop - cell0, 6): every quantity at the cell nodes of every
        material node; None for a layout without values.

    Examples
    --------
    >>> g = normalise_grid(None)
    >>> [(b.cell0, b.cell1, b.n) for b in eps_y_blocks(g, cell_layout(g, v1_star_top(g))[2])]
    [(0, 71, 28), (71, 79, 32), (79, 87, 47), (87, 96, 85)]
    """

    cell0: int
    cell1: int
    cstop: int
    n: int
    c_eps_y: np.ndarray
    values: np.ndarray | None = None


def eps_y_blocks(g: dict[str, Any], edges: NDArray[np.float64]) -> list[Block]:
    """The non-empty blocks of V1* cells of a grid, each with its own material axis.

    Parameters
    ----------
    g : dict
        A normalised grid (``eps_y_blocks``: cells ending at or below V1*_end use n nodes).
    edges : ndarray
        (ncell, 2) [start, end] V1* of every cell (:func:`cell_layout`).

    Returns
    -------
    list of Block
        Without values; every block but the last stores the next block's first cell too.

    Examples
    --------
    >>> g = normalise_grid(None)
    >>> len(eps_y_blocks(g, cell_layout(g, v1_star_top(g))[2]))
    4
    """
    out, c0 = [], 0
    for v_end, n in g["eps_y_blocks"] + [[math.inf, g["n_eps_y"]]]:
        c1 = int(np.searchsorted(edges[:, 1], v_end, side="right"))
        if c1 > c0:
            axis = c_eps_y_of_xi(np.linspace(*xi_range(g), n), g["c_eps_y_map_rate"])
            out.append((c0, c1, n, axis))
            c0 = c1
    return [Block(cell0=c0, cell1=c1, cstop=c1 + (k < len(out) - 1), n=n, c_eps_y=axis)
            for k, (c0, c1, n, axis) in enumerate(out)]
