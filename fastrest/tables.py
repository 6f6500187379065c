"""Multi-material tables: generation (Numba, both cores), HDF5 storage, loading and evaluation.

A table holds, on a grid over the material, everything the fast multi-material path needs:

* ``W_star`` (eps_y, nu, omega_star): the normalised energy (W_ep)* = 1 - F(w*) of JGM eq (25),
  up to w* = 425 (by composite Gauss-Legendre quadrature, :mod:`fastrest.energy`);
* ``omega_m_star``, ``e_jcg``, ``loss_jcg``, ``e_etsion``, ``loss_etsion`` (c_eps_y, nu, cell, node):
  the direct solver's w_m*, e and 1 - e^2 at the Chebyshev points of bit-indexed cells in V1*
  (:mod:`fastrest.interpolation`) from 1.9^1.25 up to the largest V1* any grid material allows
  (2^4 cells per octave below V1* = 8, where 1 - e^2 is small and curved, 2^3 above), on a grid
  over s = C(nu) eps_y (mapped, see :func:`xi_range`) and nu.

Evaluation at (V1*, eps_y, nu): the degree-5 polynomial of V1*'s cell at each of the 6 x 6 nearest
material nodes, combined with 6-point Lagrange weights in the mapped s and in nu. Below 1.9^1.25
the answer does not depend on the material: the closed forms (Hertz loading), evaluated by the same
few-ulp cells as :mod:`fastrest.curve`; V1* <= 1 is exact (elastic). Nodes are computed past w* = 425 where a neighbour needs it
(the same formulas as a smooth extension, even past a/R = 1), but a query whose interpolated w_m*
exceeds 425 (by more than :data:`OMEGA_LIMIT_TOL`) is refused.
"""
import hashlib
import json
import math
import os
import warnings
from collections import namedtuple
from pathlib import Path

import numba as nb
import numpy as np

from . import _hdf5, _tablefile
from ._jit import compiled_entry
from ._threads import run_parallel
from ._validation import (EPS_Y_VALIDATED, NU_VALIDATED, OMEGA_M_STAR_MAX, EDGE_TOL, check_count, check_nu,
                          check_eps_y, real_scalar,
                          check_velocity, warn_if_outside_validated)
from ._version import __version__
from .contact import W_SWITCH, area_exponent, omega_star_limit_kernel
from ._validation import broadcast_inputs, shaped
from .critical import c_of_nu
from .materials import poisson_factor
from .curve import HERTZ_BASE, HERTZ_SHIFT, N_HERTZ, _fast_scalar, hertz_rows, jg_nodes
from .direct import impact_array
from .limits import raise_out_of_range, v1_star_limit
from .energy import F_SWITCH, GL_ORDER, PANEL_WIDTH, V_SWITCH, jg_integral, omega_m_sorted_kernel
from .interpolation import (CHEB_U, DEGREE, MANTISSA_BITS, cell_index, cell_polynomial, fma, share_edges,
                            two_level_cells, two_level_index, values_to_coeffs)
from . import unloading as _unloading
from .unloading import N_MODELS, restitution_kernel

#: Every registered unloading model is tabulated, in code order: quantity 1 + 2 code is its e,
#: 2 + 2 code its 1 - e^2.
QUANTITIES = ("omega_m_star",) + tuple(f"{q}_{name}" for name in _unloading.NAMES for q in ("e", "loss"))
QUANTITY_META = {"omega_m_star": ("1", "normalised maximum interference omega_m/omega_c (JGM eq 29, 31)")}
for _m in _unloading.MODELS.values():
    QUANTITY_META[f"e_{_m.name}"] = ("1", f"coefficient of restitution, {_m.label} (JGM eq 38)")
    QUANTITY_META[f"loss_{_m.name}"] = ("1", f"dissipated fraction 1 - e^2, {_m.label}")
#: The w_m* <= 425 check is made on the interpolated w_m*, with the table's accuracy as tolerance.
OMEGA_LIMIT_TOL = 1e-9
OMEGA_LIMIT = OMEGA_M_STAR_MAX * (1.0 + OMEGA_LIMIT_TOL)
#: Below this eps_y the JG law's end (a/R = 1, eq 12) lies past w* = 425 for every 0 <= nu <= 0.5
#: (it reaches 425 at eps_y = 0.010223 for nu = 0.5, 0.0141 for nu = 0; tested), so only wider
#: tables pay for the per-point a/R limit.
EPS_Y_AR_BINDS = 0.0102
OMEGA_GRID_HERTZ = 20  # nodes of the W* grid on [0, 1.9]
OMEGA_GRID_JG = 236    # log-spaced nodes on [1.9, 425]

#: Default grid of the shipped table: what `fastrest build --tol 1e-9` reaches from the earlier
#: grid (24/32/40/72 nodes in C(nu) eps_y, 6 in nu, fine cells up to V1* = 8) on the adversarial
#: sample of fastrest.table_error: the cells up to V1* = 128, 256, 512 carry 28, 32, 47 nodes in the
#: mapped C(nu) eps_y and the top octaves 85 (the law's cos(pi a/R) term varies fastest near
#: w* = 425), 8 nodes in nu, 2^4 cells per octave up to V1* = 16 (the Etsion and Brake 1 - e^2 near
#: V1* = 8-16 and just above the switch). W* is stored on its own plain-eps_y grid (n_eps_y_energy).
DEFAULT_GRID = dict(eps_y_min=EPS_Y_VALIDATED[0], eps_y_max=EPS_Y_VALIDATED[1], n_eps_y=85,
                    nu_min=NU_VALIDATED[0], nu_max=NU_VALIDATED[1], n_nu=8, bits_per_octave=3,
                    fine_bits_per_octave=4, fine_v1_star_max=16.0, c_eps_y_map_rate=30.0,
                    eps_y_blocks=[[128.0, 28], [256.0, 32], [512.0, 47]], n_eps_y_energy=32)


def default_table_path():
    """The shipped default table: inside the installed package, or ``tables/`` of a source tree."""
    here = Path(__file__).resolve().parent
    for p in (here / "_tables" / "default.h5", here.parent / "tables" / "default.h5"):
        if p.exists():
            return p
    raise FileNotFoundError("fastrest's default table is missing (expected fastrest/_tables/default.h5 "
                            "or tables/default.h5); rebuild it with `fastrest build --default`")


def source_tree_table_path():
    """``tables/default.h5`` of the source checkout this fastrest runs from, or None if installed
    without one (``fastrest build --default`` rebuilds it there, whatever the working directory)."""
    root = Path(__file__).resolve().parent.parent
    if (root / "pyproject.toml").is_file() and (root / "tables").is_dir():
        return root / "tables" / "default.h5"
    return None


def cache_dir():
    """User cache for tables of other grids: $FASTREST_CACHE_DIR, else $XDG_CACHE_HOME/fastrest."""
    d = os.environ.get("FASTREST_CACHE_DIR")
    if not d:
        d = os.path.join(os.environ.get("XDG_CACHE_HOME", os.path.expanduser("~/.cache")), "fastrest")
    return Path(d)


def grid_key(grid):
    """Cache key of a grid: format version + a hash of the generation parameters."""
    blob = json.dumps({"format_version": _hdf5.FORMAT_VERSION, **normalise_grid(grid)}, sort_keys=True)
    return f"v{_hdf5.FORMAT_VERSION}-{hashlib.sha256(blob.encode()).hexdigest()[:16]}"


#: Bounds of a table's grid (checked before anything is allocated): counts, eps_y (tables;
#: past 0.1 the law ends, a/R = 1, close to the Hertz range), the s-axis map rate (expm1 of it), bytes.
GRID_COUNTS = {"n_eps_y": (6, 4096), "n_nu": (6, 256), "n_eps_y_energy": (2, 4096),
               "bits_per_octave": (1, 10), "fine_bits_per_octave": (1, 10)}
TABLE_EPS_Y = (1e-6, 0.1)
MAP_RATE_MAX = 1000.0
TABLE_BYTES_MAX = 4 * 2**30


def normalise_grid(grid=None, **overrides):
    """Fill in defaults and validate a grid specification; returns a plain dict."""
    if grid is not None and not isinstance(grid, dict):
        raise TypeError(f"grid must be a dict of grid parameters or None, got {type(grid).__name__}")
    g = dict(DEFAULT_GRID)
    g.update(grid or {})
    g.update(overrides)
    unknown = set(g) - set(DEFAULT_GRID)
    if unknown:
        raise ValueError(f"unknown grid parameter(s) {sorted(unknown)}; valid: {sorted(DEFAULT_GRID)}")
    for k, (lo, hi) in GRID_COUNTS.items():
        g[k] = check_count(g[k], k, lo, hi)
    for k in ("eps_y_min", "eps_y_max", "nu_min", "nu_max", "c_eps_y_map_rate", "fine_v1_star_max"):
        g[k] = real_scalar(g[k], k)
    g["eps_y_blocks"] = _normalise_blocks(g["eps_y_blocks"])
    g["fine_v1_star_max"] = float(g["fine_v1_star_max"])
    m, _ = math.frexp(g["fine_v1_star_max"])
    if not (m == 0.5 and 1.0 <= g["fine_v1_star_max"] <= 2.0**20):
        raise ValueError("fine_v1_star_max (end of the finer V1* cells) must be a power of two in "
                         f"[1, 2^20]; got {g['fine_v1_star_max']}")
    for k in ("eps_y_min", "eps_y_max", "nu_min", "nu_max", "c_eps_y_map_rate"):
        g[k] = float(g[k])
    if not 0.0 <= g["c_eps_y_map_rate"] <= MAP_RATE_MAX:
        raise ValueError(f"c_eps_y_map_rate must be in [0, {MAP_RATE_MAX:g}]; got {g['c_eps_y_map_rate']}")
    for k in ("eps_y_min", "eps_y_max"):
        if not TABLE_EPS_Y[0] <= g[k] <= TABLE_EPS_Y[1]:
            raise ValueError(f"{k} must be in [{TABLE_EPS_Y[0]:g}, {TABLE_EPS_Y[1]:g}] (the eps_y range "
                             f"tables are built for; fastrest.direct and fastrest.curve take any eps_y > 0); got {g[k]!r}")
    check_nu(g["nu_min"], "nu_min")
    check_nu(g["nu_max"], "nu_max")
    if not g["eps_y_max"] > g["eps_y_min"]:
        raise ValueError("eps_y_max must be > eps_y_min")
    if not g["nu_max"] > g["nu_min"]:
        raise ValueError("nu_max must be > nu_min")
    # a bound on the arrays before anything is allocated: cells <= 2^bits per octave over the
    # at most 10 octaves of V1* from 1.9^1.25 to the largest speed of eps_y >= 1e-6
    n_eps = max([g["n_eps_y"]] + [n for _, n in g["eps_y_blocks"]])
    cells = 2 ** max(g["bits_per_octave"], g["fine_bits_per_octave"]) * 10
    size = cells * n_eps * g["n_nu"] * 6 * len(QUANTITIES) * 8
    if size > TABLE_BYTES_MAX:
        raise ValueError(f"this grid would need up to {size / 2**30:.3g} GiB of table arrays (n_eps_y = {n_eps}, "
                         f"n_nu = {g['n_nu']}, 2^{max(g['bits_per_octave'], g['fine_bits_per_octave'])} cells "
                         f"per octave); the limit is {TABLE_BYTES_MAX / 2**30:g} GiB: use fewer nodes or cells")
    return g


def _normalise_blocks(blocks):
    """eps_y_blocks: [[V1*_end, n], ...]: cells ending at or below V1*_end (a power of two,
    increasing) use n nodes in the mapped C(nu) eps_y (>= the stencil's 6); the rest n_eps_y."""
    out = []
    if isinstance(blocks, (str, bytes, bytearray)) or (blocks and not isinstance(blocks, (list, tuple))):
        raise TypeError(f"eps_y_blocks must be a list of [V1*_end, n_eps_y] pairs; got {blocks!r}")
    try:
        pairs = [(real_scalar(v, "eps_y_blocks"), real_scalar(n, "eps_y_blocks")) for v, n in (blocks or [])]
    except (TypeError, ValueError):
        raise ValueError(f"eps_y_blocks must be a list of [V1*_end, n_eps_y] pairs; got {blocks!r}") from None
    if not all(math.isfinite(n) and n.is_integer() for _, n in pairs):
        raise ValueError(f"eps_y_blocks: node counts must be whole numbers; got {blocks!r}")
    pairs = [(v, int(n)) for v, n in pairs]
    for v, n in pairs:
        if not (math.frexp(v)[0] == 0.5 and 2.0 <= v <= 2.0**20) or (out and v <= out[-1][0]):
            raise ValueError(f"eps_y_blocks: each V1*_end must be a power of two in [2, 2^20], increasing; got {v}")
        if not STENCIL_EPS <= n <= GRID_COUNTS["n_eps_y"][1]:
            raise ValueError(f"eps_y_blocks: n_eps_y must be in [{STENCIL_EPS}, {GRID_COUNTS['n_eps_y'][1]}]; got {n}")
        out.append([v, n])
    return out


# --- generation -------------------------------------------------------------------------------

@nb.njit(cache=True, parallel=True)
def _generate_row(eps_row, nu_nodes, v_nodes, omega_grid, out, w_star):
    """Fill out[q, j, k] (quantities at V1* = v_nodes[k]) and w_star[j, :] for (eps_row[j], nu_j)."""
    for j in nb.prange(nu_nodes.size):
        nu = nu_nodes[j]
        eps_y = eps_row[j]
        # Neighbours in an interpolation stencil may need w* > 425, even past a/R = 1 (for a
        # material whose own w_m* <= 425): there the formulas serve as a smooth extension.
        w_hi = 4.0 * OMEGA_M_STAR_MAX
        w = np.empty(v_nodes.size)
        omega_m_sorted_kernel(v_nodes, eps_y, nu, w_hi, w)
        for k in range(v_nodes.size):
            out[0, j, k] = w[k]
            for m in range(N_MODELS):
                e, loss, _, _ = restitution_kernel(v_nodes[k], w[k], w[k] - 1.0, eps_y, nu, m)
                out[1 + 2 * m, j, k] = e
                out[2 + 2 * m, j, k] = loss
        # W* = 1 - F on the omega grid (cumulative quadrature above 1.9)
        C = c_of_nu(nu)
        B = area_exponent(eps_y)
        f = F_SWITCH
        prev = W_SWITCH
        for k in range(omega_grid.size):
            z = omega_grid[k]
            if z <= W_SWITCH:
                w_star[j, k] = 1.0 - z**2.5
            elif z >= omega_star_limit_kernel(eps_y, nu):
                w_star[j, k] = np.nan
            else:
                f += 2.5 * jg_integral(prev, z, eps_y, nu, C, B)
                prev = z
                w_star[j, k] = 1.0 - f


def yield_parameter(eps_y, nu):
    """s = C(nu) eps_y, the table's first material axis (a/R = (pi/2) s sqrt(A*), JGM eqs 5, 12).

    The law depends on eps_y mostly through a/R, i.e. through s: on a grid uniform in (s, nu) the
    remaining dependence on nu is very smooth, where on an (eps_y, nu) grid both axes carry the
    fast variation of cos(pi a/R) at large w* (bench/RESULTS.md compares grids).
    """
    return poisson_factor(nu) * eps_y


def xi_range(g):
    """The s axis is uniform in xi = expm1(k s)/k (k = c_eps_y_map_rate; xi = s for k = 0), denser
    where s, and with it a/R, is large and the law varies fastest (bench/RESULTS.md compares grids)."""
    k = g["c_eps_y_map_rate"]
    lo = float(yield_parameter(g["eps_y_min"], g["nu_min"]))
    hi = float(yield_parameter(g["eps_y_max"], g["nu_max"]))
    return (math.expm1(k * lo) / k, math.expm1(k * hi) / k) if k > 0 else (lo, hi)


def s_of_xi(xi, k):
    """Inverse of the xi map, element by element with math.log1p (see :func:`_geomspace`: NumPy's
    vectorised log1p is not bit-reproducible across CPUs)."""
    xi = np.asarray(xi, dtype=np.float64)
    if not k > 0:
        return xi
    return np.array([math.log1p(k * x) / k for x in xi.ravel()]).reshape(xi.shape)


def grid_axes(g):
    """The axes and cell layout of a normalised grid."""
    nus = np.linspace(g["nu_min"], g["nu_max"], g["n_nu"])
    s = s_of_xi(np.linspace(*xi_range(g), g["n_eps_y"]), g["c_eps_y_map_rate"])
    eps = s[:, None] / yield_parameter(1.0, nus)[None, :]  # eps_y of every table node
    # V1* range: up to the largest w* = 425 speed over the grid's materials
    v_top = max(v1_star_limit(min(max(e, g["eps_y_min"]), g["eps_y_max"]), n)
                for e, n in zip(eps.ravel(), np.broadcast_to(nus, eps.shape).ravel()))
    layout = cell_layout(g, v_top)
    return s, eps, nus, v_top, layout, grid_axes_omega()


def grid_axes_omega():
    """The w* grid of W*: uniform on [0, 1.9], log-spaced on [1.9, 425]."""
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


def eps_y_blocks(g, edges):
    """The non-empty blocks of cells with their own C(nu) eps_y axis: list of dicts
    (cell0, cell1: cell range; cstop: cells stored, cell1 + 1 but for the last block, whose grid
    also holds the next block's first cell for the blend across the boundary (:func:`_cell_value`);
    n: nodes; c_eps_y: the axis; eps_y: (n, n_nu) eps_y of each node)."""
    nus = np.linspace(g["nu_min"], g["nu_max"], g["n_nu"])
    out, c0 = [], 0
    for v_end, n in g["eps_y_blocks"] + [[math.inf, g["n_eps_y"]]]:
        c1 = int(np.searchsorted(edges[:, 1], v_end, side="right"))
        if c1 > c0:
            s = s_of_xi(np.linspace(*xi_range(g), n), g["c_eps_y_map_rate"])
            out.append(dict(cell0=c0, cell1=c1, cstop=c1, n=n, c_eps_y=s,
                            eps_y=s[:, None] / yield_parameter(1.0, nus)[None, :]))
            c0 = c1
    for b in out[:-1]:
        b["cstop"] = b["cell1"] + 1
    return out


def cell_layout(g, v_top):
    """The V1* cells over (1.9^1.25, v_top]: 2^fine_bits_per_octave per octave below
    fine_v1_star_max (where 1 - e^2 is small and curved, just above the kink at w* = 1.9), then
    2^bits_per_octave. Returns dict(base_fine, base, edges)."""
    base_f, base, edges = two_level_cells(V_SWITCH, g["fine_v1_star_max"], v_top,
                                          g["fine_bits_per_octave"], g["bits_per_octave"])
    return dict(base_fine=int(base_f), base=int(base), edges=edges)


def generate(grid=None, progress=None):
    """Compute a table's arrays (no I/O). ``progress``: None = bar if a terminal, False = none."""
    g = normalise_grid(grid)
    _, _, nus, v_top, layout, omega = grid_axes(g)
    edges = layout["edges"]
    eps_w = np.linspace(g["eps_y_min"], g["eps_y_max"], g["n_eps_y_energy"])  # W* grid: plain eps_y
    nodes = jg_nodes(edges, v_top).reshape(edges.shape[0], -1)
    blocks = eps_y_blocks(g, edges)
    jobs = [(b, i) for b in blocks for i in range(b["n"])] + [(None, i) for i in range(eps_w.size)]
    if progress is not False:
        try:
            from tqdm import tqdm
            jobs = tqdm(jobs, desc="fastrest build", unit="eps_y row", disable=None)
        except ImportError:
            pass
    for b in blocks:
        b["values"] = np.empty((len(QUANTITIES), b["n"], nus.size, b["cstop"] - b["cell0"], DEGREE + 1))
    w_star = np.empty((eps_w.size, nus.size, omega.size))
    for b, i in jobs:
        if b is None:  # W* = 1 - F at eps_w[i]
            run_parallel(_generate_row, None, np.full(nus.size, eps_w[i]), nus, nodes[:0].ravel(), omega,
                         np.empty((len(QUANTITIES), nus.size, 0)), w_star[i])
            continue
        flat = nodes[b["cell0"]:b["cstop"]].ravel()
        out = np.empty((len(QUANTITIES), nus.size, flat.size))
        run_parallel(_generate_row, None, b["eps_y"][i], nus, flat, omega[:0], out, np.empty((nus.size, 0)))
        b["values"][:, i] = share_edges(out.reshape(out.shape[:2] + (-1, DEGREE + 1)))
    v_max = np.array([[v1_star_limit(e, n) for n in nus] for e in eps_w])
    return dict(grid=g, eps_y=eps_w, nu=nus, v_top=v_top, base_fine=layout["base_fine"],
                base=layout["base"], edges=edges, nodes=nodes, blocks=blocks,
                omega_star=omega, W_star=w_star, v1_star_max=v_max)


# --- evaluation -------------------------------------------------------------------------------

TableData = namedtuple("TableData", ["s_rate", "xi0", "nu0", "inv_h_nu", "n_nu",
                                     "eps_lo", "eps_hi", "nu_lo", "nu_hi", "v_split", "shift_fine",
                                     "base_fine", "shift", "base", "v_top", "v_safe", "cells",
                                     "cell_block", "block_inv_h", "block_n", "block_cell0",
                                     "block_offset", "block_qstride", "coef", "hertz", "n_quantities"])
TableData.__doc__ = """Numba-friendly data of a :class:`Table` (see :mod:`fastrest.jit`).

eps_y enters through s = C(nu) eps_y and xi = expm1(s_rate s)/s_rate, uniform from xi0 with
spacing 1/block_inv_h[b] over block_n[b] nodes in block b of cells.
cells: (ncell, 2) [center, 1/half_width] of each V1* cell (row of V1*:
:func:`fastrest.interpolation.two_level_index` with v_split, shift_fine, base_fine, shift, base);
cell_block: the block of each cell; coef: 1-D, for each block b from block_offset[b] a C-order
(n_quantities, cells of b, block_n[b], n_nu, 6) array (block_qstride[b] per quantity) of the
polynomial coefficients of :data:`QUANTITIES` (omega_m_star, then e and 1 - e^2 of each unloading
model the table holds, by code); v_safe: below this V1* every material of the table has w_m* <= 425; hertz: (5 *
N_HERTZ, 8) rows of the material-independent Hertz-range closed forms (see :mod:`fastrest.curve`);
n_quantities: 1 + 2 x the number of unloading models held.
"""


#: Interpolation stencils across materials (points per axis). The JG law varies with eps_y through
#: cos(pi a/R), a/R ~ C eps_y w^0.6, which at w* ~ 425 spans half a period over the validated
#: range: 6-point (quintic) stencils reach ~1e-9 with 64 x 6 nodes where cubic ones stay near 1e-7
#: (measured while choosing the grid; bench/ reports the error of several grids).
STENCIL_EPS = 6
STENCIL_NU = 6


@nb.njit(cache=True, inline="always")
def _first_node(s, m, n):
    i = int(math.floor(s)) - (m // 2 - 1)
    if i < 0:
        return 0
    if i > n - m:
        return n - m
    return i


@nb.njit(cache=True, inline="always")
def _lagrange6(x, x0, inv_h, n):
    """First index and weights of the 6-node Lagrange stencil at x on a uniform grid."""
    s = (x - x0) * inv_h
    i = _first_node(s, 6, n)
    t = s - i
    t1, t2, t3, t4, t5 = t - 1.0, t - 2.0, t - 3.0, t - 4.0, t - 5.0
    # a flat (index, w0..w5) tuple: a nested weights tuple trips Numba's parfor array analysis
    # when this is inlined into a parallel loop (AssertionError "Dimension mismatch")
    return (i, -t1 * t2 * t3 * t4 * t5 / 120.0, t * t2 * t3 * t4 * t5 / 24.0,
            -t * t1 * t3 * t4 * t5 / 12.0, t * t1 * t2 * t4 * t5 / 12.0,
            -t * t1 * t2 * t3 * t5 / 24.0, t * t1 * t2 * t3 * t4 / 120.0)


@nb.njit(cache=True, inline="always")
def table_value(tab, q, v, eps_y, nu):
    """Quantity q of :data:`QUANTITIES` (0 w_m*, 1 + 2 code e, 2 + 2 code 1 - e^2) at (V1*, eps_y, nu).

    NaN outside the table (eps_y, nu or V1* out of range, w_m* > 425, or past a/R = 1 for eps_y > 0.0102) or for invalid input
    (including a q the table does not hold).
    """
    if not (q >= 0 and q < tab.n_quantities):
        return np.nan
    # float32 and integer inputs, as the Python API takes them
    return _interpolate(tab, q, np.float64(v), np.float64(eps_y), np.float64(nu), True)


@nb.njit(cache=True, inline="always")
def _interpolate(tab, q, v, eps_y, nu, check_limit):
    # every field is read here, unconditionally: a namedtuple field read inside a rarely taken
    # branch (the blend of a block's first cell) made the whole loop ~7x slower (Numba; measured)
    eps_lo, eps_hi, nu_lo, nu_hi, v_top, v_safe = tab.eps_lo, tab.eps_hi, tab.nu_lo, tab.nu_hi, tab.v_top, tab.v_safe
    hertz, cells, cell_block, block_cell0 = tab.hertz, tab.cells, tab.cell_block, tab.block_cell0
    g = (tab.coef, tab.block_offset, block_cell0, tab.block_inv_h, tab.block_n, tab.block_qstride,
         tab.xi0, tab.nu0, tab.inv_h_nu, tab.n_nu)
    s_rate = tab.s_rate
    split = (tab.v_split, tab.shift_fine, tab.base_fine, tab.shift, tab.base)
    # a material a few ulp outside an edge (0.001 + 0.0005 * 18 = 0.010000000000000002) is at
    # the edge: clamped there, never extrapolated further
    e_lo, e_hi, n_lo, n_hi = eps_lo, eps_hi, nu_lo, nu_hi
    if not (eps_y >= e_lo * (1.0 - EDGE_TOL) and eps_y <= e_hi * (1.0 + EDGE_TOL)
            and nu >= n_lo * (1.0 - EDGE_TOL) and nu <= n_hi * (1.0 + EDGE_TOL)):
        return np.nan
    eps_y = min(max(eps_y, e_lo), e_hi)
    nu = min(max(nu, n_lo), n_hi)
    if not v > V_SWITCH:
        if v > 1.0:  # Hertz loading: the closed forms' cells, the same for every material
            r = cell_polynomial(hertz, q * N_HERTZ + cell_index(v, HERTZ_SHIFT, HERTZ_BASE), v)
            return r * (v - 1.0) if q > 0 and q % 2 == 0 else r  # the losses
        if v >= 0.0:  # elastic, exact
            if q == 0:
                return v**0.8
            return 1.0 if q % 2 == 1 else 0.0
        return np.nan
    if not v <= v_top:
        return np.nan
    cell = two_level_index(v, split[0], split[1], split[2], split[3], split[4])
    u = (v - cells[cell, 0]) * cells[cell, 1]
    s = c_of_nu(nu) * eps_y
    xi = math.expm1(s_rate * s) / s_rate if s_rate > 0.0 else s
    b = cell_block[cell]
    blend = cell == block_cell0[b] and b > 0
    w_lim = OMEGA_LIMIT
    check = check_limit and v > v_safe
    if check and eps_y > EPS_Y_AR_BINDS:  # the law may end (a/R = 1) before w* = 425
        w_lim = min(w_lim, omega_star_limit_kernel(eps_y, nu) * (1.0 + OMEGA_LIMIT_TOL))
    if not (blend or (check and q != 0)):  # the common case, straight-line
        r = _block_value(g, q, b, cell, u, xi, nu)
        if check and not r <= w_lim:
            return np.nan
        return r
    # otherwise one more call site of the (inlined) stencil sum, in loops: passes over (w_m* for
    # the limit check, then q) and over (this block, the previous one for a blended cell)
    r = np.nan
    for p in range(2 if check and q != 0 else 1):
        qq = 0 if p == 0 and check and q != 0 else q
        val = 0.0
        for k in range(2 if blend else 1):
            x = _block_value(g, qq, b - k, cell, u, xi, nu)
            if k == 0:
                val = x
            else:  # smoothstep from the previous block's grid (left edge) to this block's (right)
                t = min(max(0.5 * (u + 1.0), 0.0), 1.0)
                val = x + t * t * (3.0 - 2.0 * t) * (val - x)
        if check and qq == 0 and not val <= w_lim:
            return np.nan
        r = val
    return r


@nb.njit(cache=True, inline="always")
def _block_value(g, q, b, cell, u, xi, nu):
    """Quantity q in ``cell`` interpolated across materials on block b's grid; ``g`` is the
    table's (coef, block_offset, block_cell0, block_inv_h, block_n, block_qstride, xi0, nu0,
    inv_h_nu, n_nu). The first cell of a block b > 0 is blended by :func:`_interpolate` from the
    previous block's grid at its left edge (where the previous cell ends on that grid) to its own
    at its right edge, so the table is continuous across block boundaries to a few ulp although
    the two grids interpolate materials differently (by up to the table's error, ~1e-10)."""
    coef, offset, cell0, inv_h, block_n, qstride, xi0, nu0, inv_h_nu, n_nu = g
    n = block_n[b]
    i, e0, e1, e2, e3, e4, e5 = _lagrange6(xi, xi0, inv_h[b], n)
    j, n0, n1, n2, n3, n4, n5 = _lagrange6(nu, nu0, inv_h_nu, n_nu)
    row = 6 * n_nu  # one eps_y node's coefficients
    first = offset[b] + ((cell - cell0[b]) * n + i) * row + 6 * j
    return _stencil_sum(coef, first + q * qstride[b], row, u, (e0, e1, e2, e3, e4, e5), (n0, n1, n2, n3, n4, n5))


@nb.njit(cache=True)
def _interpolant_array(tab, q, v, eps_y, nu, out):
    """The interpolant without the w_m* <= 425 check (for measuring its error at the limit)."""
    for k in range(v.size):
        out[k] = _interpolate(tab, q, v[k], eps_y[k], nu[k], False)


@nb.njit(cache=True, inline="always")
def _stencil_sum(coef, first, row, u, we, wn):
    """sum_ab we[a] wn[b] p_ab(u): combine the coefficients first, then one polynomial (Estrin).

    ``first``: index in the flat ``coef`` of the stencil's first node; ``row``: stride of one eps_y
    node. The sums stay plain multiply-adds (fused ones lengthen their dependency chains: measured
    ~10 % slower); the final polynomial uses fma.
    """
    c0 = c1 = c2 = c3 = c4 = c5 = 0.0
    for a in range(STENCIL_EPS):
        for b in range(STENCIL_NU):
            w = we[a] * wn[b]
            k = np.uint64(first + a * row + 6 * b)
            c0 += w * coef[k]
            c1 += w * coef[k + np.uint64(1)]
            c2 += w * coef[k + np.uint64(2)]
            c3 += w * coef[k + np.uint64(3)]
            c4 += w * coef[k + np.uint64(4)]
            c5 += w * coef[k + np.uint64(5)]
    u2 = u * u
    return fma(u2 * u2, fma(u, c5, c4), fma(u2, fma(u, c3, c2), fma(u, c1, c0)))


@nb.njit(cache=True)
def _table_array(tab, q, v, eps_y, nu, out):
    for k in range(v.size):
        out[k] = table_value(tab, q, v[k], eps_y[k], nu[k])


@nb.njit(cache=True, parallel=True)
def _table_array_parallel(tab, q, v, eps_y, nu, out):
    for k in nb.prange(v.size):
        out[k] = table_value(tab, q, v[k], eps_y[k], nu[k])


def _hertz_table_rows(n_models):
    """Hertz-range rows for the table's quantities (q * N_HERTZ + cell): w_m*, then e and 1 - e^2
    of the first ``n_models`` unloading models."""
    rows = [hertz_rows(code) for code in range(n_models)]
    return np.ascontiguousarray(np.concatenate([rows[0][0]] + [r[k] for r in rows for k in (1, 2)]))


#: Batches at least this large use all cores (the threads' start-up costs ~10 us).
PARALLEL_MIN_POINTS = 20000


class Table:
    """A loaded multi-material table (see :func:`load_table`).

    Methods broadcast over (v1_star, eps_y, nu); each point may have its own material.

    Attributes
    ----------
    data : TableData
        Numba-friendly data for :mod:`fastrest.jit` (``fastrest.jit.e_table(data, v, eps_y, nu)``).
    grid : dict
        Generation parameters.
    attrs : dict
        The file's root attributes (provenance, measured error).
    path : str or None
    """

    def __init__(self, gen, attrs=None, path=None):
        g = gen["grid"]
        eps, nus, edges = gen["eps_y"], gen["nu"], gen["edges"]
        center = 0.5 * (edges[:, 0] + edges[:, 1])
        half = 0.5 * (edges[:, 1] - edges[:, 0])
        xi0, xi1 = xi_range(g)
        blocks = gen["blocks"]
        nq = blocks[0]["values"].shape[0]
        # per block (nq, n_eps, n_nu, ncell, 6) -> (nq, ncell, n_eps, n_nu, 6), flattened one after another
        parts = [np.ascontiguousarray(values_to_coeffs(b["values"]).transpose(0, 3, 1, 2, 4)).ravel()
                 for b in blocks]
        cell_block = np.empty(edges.shape[0], dtype=np.int64)
        for k, b in enumerate(blocks):
            cell_block[b["cell0"]:b["cell1"]] = k
        i64 = lambda x: np.array(x, dtype=np.int64)  # noqa: E731
        self.data = TableData(
            g["c_eps_y_map_rate"], float(xi0),
            float(nus[0]), float((nus.size - 1) / (nus[-1] - nus[0])), int(nus.size),
            float(eps[0]), float(eps[-1]), float(nus[0]), float(nus[-1]),
            g["fine_v1_star_max"], MANTISSA_BITS - g["fine_bits_per_octave"], int(gen["base_fine"]),
            MANTISSA_BITS - g["bits_per_octave"], int(gen["base"]), float(gen["v_top"]),
            float(np.min(gen["v1_star_max"])), np.ascontiguousarray(np.stack([center, 1.0 / half], 1)),
            cell_block, np.array([(b["n"] - 1) / (xi1 - xi0) for b in blocks]), i64([b["n"] for b in blocks]),
            i64([b["cell0"] for b in blocks]), i64(np.cumsum([0] + [p.size for p in parts[:-1]])),
            i64([p.size // nq for p in parts]), np.concatenate(parts), _hertz_table_rows((nq - 1) // 2), nq)
        self.grid = g
        self.gen = gen
        self._entry = None
        self.attrs = attrs or {}
        self.path = path

    # the compiled entry point does not pickle: dropped, rebuilt on the first scalar call
    def __getstate__(self):
        state = self.__dict__.copy()
        state["_entry"] = None
        return state

    def __repr__(self):
        g = self.grid
        return (f"Table(eps_y=[{g['eps_y_min']}, {g['eps_y_max']}] x {g['n_eps_y']}, "
                f"nu=[{g['nu_min']}, {g['nu_max']}] x {g['n_nu']}, cells={self.data.cells.shape[0]}, "
                f"path={self.path!r})")

    def _scalar(self, q, v1_star, eps_y, nu):
        """One point from Python floats: the kernel's compiled entry point (~1 us instead of ~30 us
        through the array machinery); anything unusual (NaN result, outside the validated range,
        which warns) goes the checked array way."""
        v, e, n = _fast_scalar(v1_star), _fast_scalar(eps_y), _fast_scalar(nu)
        if (v is not None and e is not None and n is not None
                and EPS_Y_VALIDATED[0] <= e <= EPS_Y_VALIDATED[1] and NU_VALIDATED[0] <= n <= NU_VALIDATED[1]):
            v1_star, eps_y, nu = v, e, n
            if self._entry is None:
                self._entry = compiled_entry(table_value, (nb.typeof(self.data), nb.int64, nb.float64,
                                                          nb.float64, nb.float64))
            r = self._entry(self.data, q, v1_star, eps_y, nu)
            if r == r:
                return r
        return self._eval(q, v1_star, eps_y, nu)

    def _eval(self, q, v1_star, eps_y, nu):
        (v, e, n), shape = broadcast_inputs((v1_star, "v1_star"), (eps_y, "eps_y"), (nu, "nu"))
        out = np.empty(v.size)
        if v.size == 0:
            return shaped(out, shape)
        if v.size >= PARALLEL_MIN_POINTS:
            run_parallel(_table_array_parallel, _table_array, self.data, q, v, e, n, out)
        else:
            _table_array(self.data, q, v, e, n, out)
        bad = np.isnan(out)
        if bad.any():
            self._raise(v[bad], e[bad], n[bad])
        warn_if_outside_validated(e, n)
        return shaped(out, shape)

    def _raise(self, v, e, n):
        check_velocity(v, "v1_star")
        check_eps_y(e)
        check_nu(n)
        d = self.data
        for name, x, lo, hi in (("eps_y", e, d.eps_lo, d.eps_hi), ("nu", n, d.nu_lo, d.nu_hi)):
            out = (x < lo) | (x > hi)
            if out.any():
                raise ValueError(f"{name} = {float(x[out][0])!r} is outside this table's range [{lo}, {hi}] "
                                 "(use fastrest.direct, fastrest.curve, or build a wider table)")
        v0, e0, n0 = float(v[0]), float(e[0]), float(n[0])
        lim = v1_star_limit(e0, n0)
        if v0 > lim:
            raise_out_of_range(v, e, n, False,
                               hint="fastrest.direct and fastrest.curve accept extrapolate=True")
        raise ValueError(f"v1_star = {v0!r} at eps_y = {e0!r}, nu = {n0!r} lies within the interpolation "
                         f"error of the w_m* = {OMEGA_M_STAR_MAX:g} limit (V1* = {lim:.10g}) or outside "
                         "this table's coverage")

    def omega_m_star(self, v1_star, eps_y, nu):
        """Interpolated w_m* (-); see :func:`fastrest.direct.omega_m_star` for the parameters."""
        return self._scalar(0, v1_star, eps_y, nu)

    def _model_code(self, unloading):
        code = _unloading.get(unloading).code
        if not 2 + 2 * code < self.data.n_quantities:
            raise ValueError(f"this table holds no values for unloading={unloading!r} (it was built for "
                             f"{_unloading.NAMES[:(self.data.n_quantities - 1) // 2]}); rebuild it with "
                             "`fastrest build` or use fastrest.curve / fastrest.direct")
        return code

    def e_star(self, v1_star, eps_y, nu, unloading="jcg"):
        """Interpolated e (-); see :func:`fastrest.direct.e_star`."""
        return self._scalar(1 + 2 * self._model_code(unloading), v1_star, eps_y, nu)

    def loss_star(self, v1_star, eps_y, nu, unloading="jcg"):
        """Interpolated 1 - e^2 (-); see :func:`fastrest.direct.loss_star`."""
        return self._scalar(2 + 2 * self._model_code(unloading), v1_star, eps_y, nu)

    def to_xarray(self, tol=1e-3, n_check=20000):
        """This table on a rectilinear (v1_star, eps_y, nu) grid as an :class:`xarray.Dataset`.

        Variables ``omega_m``, ``e_<model>``, ``loss_<model>`` (NaN past w_m* = 425), nodes placed
        so that linear interpolation (``ds.e_jcg.interp(...)``) is within ``tol`` of the direct
        solver where it can be; the measured errors are in the attributes. Needs xarray
        (``pip install fastrest[xarray]``); see :mod:`fastrest.export.grid`.
        """
        from .export.grid import to_xarray

        return to_xarray(self, tol, n_check)

    # --- accuracy against the direct solver ---
    def measure_error(self, points=None):
        """Worst error of every quantity against the direct solver, on the adversarial sample of
        :func:`fastrest.table_error.adversarial_points` (edges, corners, every cell boundary +/- 1
        ulp, the last cell) unless ``points`` = (v1_star, eps_y, nu) is given. A dict; see
        :func:`fastrest.table_error.measure`."""
        from .table_error import measure

        return measure(self, points)


def sample_points(grid, n_points, seed):
    """Test points over a table's domain (fixed seed): random plus hard cases."""
    rng = np.random.default_rng(seed)
    g = normalise_grid(grid)
    e = rng.uniform(g["eps_y_min"], g["eps_y_max"], n_points)
    n = rng.uniform(g["nu_min"], g["nu_max"], n_points)
    vmax = np.array([v1_star_limit(a, b) for a, b in zip(e, n)])
    # math.exp/log per point: NumPy's vectorised ones are not bit-reproducible across CPUs, and
    # the measured error is written into the table file
    v = np.array([math.exp(u * math.log(m)) for u, m in zip(rng.uniform(0.0, 1.0, n_points), vmax)])
    hard = np.array([1.0, 1 + 1e-12, 1 + 1e-9, V_SWITCH * (1 - 1e-12), V_SWITCH * (1 + 1e-12),
                     V_SWITCH * (1 + 1e-6), 3.0, 60.0])
    k = len(hard)
    v = np.concatenate([v, hard, vmax[:k]])
    e = np.concatenate([e, e[:k], e[:k]])
    n = np.concatenate([n, n[:k], n[:k]])
    return v, e, n


# --- files ------------------------------------------------------------------------------------

MODEL_ATTRS = {
    "title": "fastrest table: Jackson-Green-Marghitu (2010) coefficient of restitution",
    "references": "Jackson R.L., Green I., Marghitu D.B. (2010) Nonlinear Dyn. 60:217-229, "
                  "doi:10.1007/s11071-009-9591-z",
    "source": "fastrest direct solver (composite Gauss-Legendre quadrature + Newton)",
    "model": {"paper": "Jackson, Green & Marghitu 2010", "doi": "10.1007/s11071-009-9591-z",
              "loading": "Jackson & Green 2005 elasto-plastic law, JGM eqs 8-15",
              "energy": "JGM eqs 22-31", "restitution": "JGM eq 38",
              **{f"unloading_{m.name}": m.label for m in _unloading.MODELS.values()}},
}


def write(gen, path, errors=None):
    """Write generated arrays to an HDF5 table file (atomically)."""
    g = gen["grid"]
    ncell = gen["edges"].shape[0]
    axes = {
        "eps_y": (gen["eps_y"], "1", "yield strain Sy/E' (JGM eq 11)"),
        "nu": (gen["nu"], "1", "Poisson's ratio of the yielding material"),
        "cell": (gen["edges"][:, 0], "1", "V1* = V1/V_c at the start of each interpolation cell"),
        "node": (CHEB_U, "1", "Chebyshev-Lobatto point of the cell, in [-1, 1] across the cell (-1 and 1: its edges)"),
        "omega_star": (gen["omega_star"], "1", "normalised interference omega/omega_c"),
    }
    datasets = {
        "W_star": (gen["W_star"], ("eps_y", "nu", "omega_star"), "1",
                   "normalised elasto-plastic energy (W_ep)* = 1 - F(w*), JGM eq 25"),
        "v1_star_max": (gen["v1_star_max"], ("eps_y", "nu"), "1", "V1* at which w_m* = 425"),
        "cell_end": (gen["edges"][:, 1], ("cell",), "1", "V1* at the end of each cell"),
        "v1_star_nodes": (gen["nodes"], ("cell", "node"), "1", "V1* of each tabulated point"),
    }
    for k, b in enumerate(gen["blocks"]):
        axes[f"c_eps_y_{k}"] = (b["c_eps_y"], "1", f"C(nu) eps_y (JGM eqs 5, 11): grid axis of block {k} of cells")
        axes[f"cell_{k}"] = (gen["edges"][b["cell0"]:b["cstop"], 0], "1",
                             f"V1* at the start of each cell of block {k} (and of the next block's first cell, "
                             "for the blend across the boundary)")
        for q, name in enumerate(QUANTITIES):
            units, long_name = QUANTITY_META[name]
            datasets[f"{name}_{k}"] = (b["values"][q], (f"c_eps_y_{k}", "nu", f"cell_{k}", "node"), units,
                                       f"{long_name}; block {k} of cells")
    attrs = dict(MODEL_ATTRS)
    attrs.update({
        "grid": g,
        "cells": {"bits_per_octave": g["bits_per_octave"], "fine_bits_per_octave": g["fine_bits_per_octave"],
                  "fine_v1_star_max": g["fine_v1_star_max"], "degree": DEGREE, "count": ncell,
                  "first_key_fine": int(gen["base_fine"]), "first_key": int(gen["base"]),
                  "v1_star_top": float(gen["v_top"]),
                  "blocks": [[b["cell0"], b["cell1"], b["n"]] for b in gen["blocks"]]},
        "quadrature": {"rule": "composite Gauss-Legendre in ln w", "order": GL_ORDER,
                       "panel_width_ln_w": PANEL_WIDTH, "newton_step_tolerance_ln_w": 1e-9},
        "validated_range": {"eps_y": list(EPS_Y_VALIDATED), "nu": list(NU_VALIDATED),
                            "omega_m_star_max": OMEGA_M_STAR_MAX},
        "history": f"built by fastrest {__version__} (fastrest build)",
        "unloading_models": ",".join(_unloading.NAMES),
    })
    if errors is not None:
        attrs["measured_error"] = errors
    _hdf5.write_table(path, axes, datasets, attrs)


def build(path=None, grid=None, progress=None, measure=True, tol=None):
    """Generate a table, measure its error against the direct solver, write it; return the Table.

    ``path`` None writes to the user cache (:func:`cache_dir`) under :func:`grid_key`. ``tol``
    (e.g. 1e-9): refine the grid's node counts until the measured error meets it, or raise
    ValueError naming the error reached (:func:`fastrest.table_error.build_to_tolerance`).
    Without ``tol`` a table whose measured error exceeds 1e-9 is written with an
    :class:`~fastrest.table_error.AccuracyWarning`. Raises OSError naming the file, before the
    (long) generation where it can tell, if the file cannot be written (a directory, a read-only
    or full file system); an existing file is then unchanged.
    """
    from . import table_error

    g = normalise_grid(grid)
    if tol is not None:
        tol = _check_tol(tol)
    if path is None:
        path = cache_dir() / f"{grid_key(g)}.h5"
    path = Path(path)
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise OSError(exc.errno, f"cannot create the directory of table file {str(path)!r}: "
                                 f"{exc.strerror}") from None
    _tablefile.check_target(path)
    if tol is not None:
        gen, table, errors, _ = table_error.build_to_tolerance(g, tol, progress=progress)
    else:
        gen = generate(g, progress=progress)
        table = Table(gen)
        errors = table.measure_error() if measure else None
        if errors is not None:
            table_error.warn_if_inaccurate(errors, None, "fastrest.tables.build")
    write(gen, path, errors)
    table.attrs = {"measured_error": errors} if errors else {}
    table.path = str(path)
    return table


def read(path):
    """Read a table file into a :class:`Table`.

    Verifies the file (see :func:`fastrest._hdf5.read_table`: digest, structure), its format
    version, and that every array has the dtype (float64), dimensions, shape and finiteness the grid
    attributes imply, with the counts checked before anything sized by them is allocated. Raises
    TableFileError (naming the file) and nothing else for a damaged, foreign or hostile file.
    """
    td = _hdf5.read_table(path)
    a = td.attrs
    if a.get("format_version") != _hdf5.FORMAT_VERSION:
        raise _hdf5.TableFileError(
            f"{path}: table format version {a.get('format_version')} is older than this fastrest's "
            f"({_hdf5.FORMAT_VERSION}); rebuild it with `fastrest build`")
    try:
        g = normalise_grid(a["grid"])
        cells = a["cells"]
        ds = td.datasets
        held = str(a.get("unloading_models", "jcg,etsion")).split(",")  # files before Brake: two models
        if held != list(_unloading.NAMES[:len(held)]) or not held:
            raise ValueError(f"unloading models {held} are not a prefix of this fastrest's {_unloading.NAMES}")
        _check_file_arrays(td, g, cells, QUANTITIES[:1 + 2 * len(held)])
        blocks = [dict(cell0=int(c0), cell1=int(c1), n=int(n), c_eps_y=td.axes[f"c_eps_y_{k}"],
                       values=np.stack([ds[f"{q}_{k}"] for q in QUANTITIES[:1 + 2 * len(held)]]))
                  for k, (c0, c1, n) in enumerate(cells["blocks"])]
        gen = dict(grid=g, eps_y=td.axes["eps_y"], nu=td.axes["nu"], v_top=float(cells["v1_star_top"]),
                   base_fine=cells["first_key_fine"], base=cells["first_key"],
                   edges=np.stack([td.axes["cell"], ds["cell_end"]], 1), nodes=ds["v1_star_nodes"],
                   blocks=blocks, omega_star=td.axes["omega_star"], W_star=ds["W_star"],
                   v1_star_max=ds["v1_star_max"])
        if cells["degree"] != DEGREE or not np.array_equal(td.axes["node"], CHEB_U):
            raise ValueError("cell polynomial degree or nodes differ from this fastrest's")
        _check_axes_match_grid(gen)
        table = Table(gen, attrs=a, path=str(path))
    except Exception as exc:  # whatever a damaged or hostile file provokes: a file error
        raise _hdf5.TableFileError(f"{path}: not a valid fastrest restitution table "
                                   f"({type(exc).__name__}: {exc})") from exc
    return table


#: Bounds on what a table's attributes may declare (checked before anything is allocated).
MAX_NODES = 100000
MAX_V1_STAR_TOP = 2.0**20


def _check_file_arrays(td, g, cells, quantities):
    """Datasets, dims, dtypes, shapes and finiteness of a read file against its grid attributes;
    the counts the grid declares must equal the stored ones (bounded by the file's size) before
    :func:`_check_axes_match_grid` allocates arrays of those sizes."""
    blocks = cells["blocks"]
    if not (isinstance(blocks, list) and 1 <= len(blocks) <= 64 and all(
            isinstance(b, list) and len(b) == 3 and all(type(x) is int and 0 <= x <= MAX_NODES for x in b)
            for b in blocks)):
        raise ValueError(f"cells: blocks must be up to 64 [cell0, cell1, n] of integers; got {str(blocks)[:200]}")
    counts = [g["n_eps_y"], g["n_nu"], g["n_eps_y_energy"]] + [n for _, n in g["eps_y_blocks"]]
    if not all(1 <= n <= MAX_NODES for n in counts):
        raise ValueError(f"grid: node counts {counts} outside [1, {MAX_NODES}]")
    v_top = cells["v1_star_top"]
    if not (type(v_top) is float and V_SWITCH < v_top <= MAX_V1_STAR_TOP):
        raise ValueError(f"cells: v1_star_top = {v_top!r} outside ({V_SWITCH:.6g}, {MAX_V1_STAR_TOP:g}]")
    ncell = blocks[-1][1]
    if cells["count"] != ncell or blocks[0][0] != 0 or any(b[0] != a[1] or b[1] <= b[0]
                                                            for a, b in zip(blocks, blocks[1:])):
        raise ValueError("cells: blocks do not cover the cells one after another")
    want = {"eps_y": (), "nu": (), "cell": (), "node": (), "omega_star": (),
            "W_star": ("eps_y", "nu", "omega_star"), "v1_star_max": ("eps_y", "nu"),
            "cell_end": ("cell",), "v1_star_nodes": ("cell", "node")}
    for k in range(len(blocks)):
        want.update({f"c_eps_y_{k}": (), f"cell_{k}": ()})
        want.update({f"{q}_{k}": (f"c_eps_y_{k}", "nu", f"cell_{k}", "node") for q in quantities})
    got = dict.fromkeys(td.axes, ())
    got.update(td.dims)
    if got != want:
        raise ValueError(f"datasets and dimensions {sorted(got.items())} differ from the layout of "
                         f"a restitution table")
    sizes = {"eps_y": g["n_eps_y_energy"], "nu": g["n_nu"], "cell": ncell, "node": DEGREE + 1,
             "omega_star": OMEGA_GRID_HERTZ + OMEGA_GRID_JG}
    for k, (c0, c1, n) in enumerate(blocks):
        # every block but the last also stores the next block's first cell (the blend)
        sizes.update({f"c_eps_y_{k}": n, f"cell_{k}": c1 - c0 + (k < len(blocks) - 1)})
    for name, n in sizes.items():
        if td.axes[name].shape != (n,):
            raise ValueError(f"axis {name!r} has shape {td.axes[name].shape}, the attributes say ({n},)")
    for name, values in {**td.axes, **td.datasets}.items():
        if values.dtype != np.float64:
            raise ValueError(f"{name!r} has dtype {values.dtype}, not float64")
        if name != "W_star" and not np.isfinite(values).all():
            raise ValueError(f"{name!r} holds NaN or infinite values")
    # Plausibility (a file with recomputed checksums can hold any finite numbers): w_m* > 1 above
    # the elastic range, 0 < e < 2, and each loss equal to 1 - e^2 to rounding
    for k in range(len(blocks)):
        if not (td.datasets[f"omega_m_star_{k}"] > 1.0).all():
            raise ValueError(f"'omega_m_star_{k}' holds values <= 1 (the table starts above the elastic range)")
        for q in quantities[1::2]:
            e, loss = td.datasets[f"{q}_{k}"], td.datasets[f"loss{q[1:]}_{k}"]
            if not ((e > 0.0) & (e < 2.0) & (np.abs(loss - (1.0 - e * e)) <= 1e-12)).all():
                raise ValueError(f"'{q}_{k}' or 'loss{q[1:]}_{k}' is not a coefficient of restitution and its "
                                 "1 - e^2")
    # W* = 1 - F is NaN exactly past the end of the law (a/R = 1), where the generator leaves it so
    w, e, n = td.axes["omega_star"], td.axes["eps_y"], td.axes["nu"]
    lim = np.array([[omega_star_limit_kernel(x, y) for y in n] for x in e])[:, :, None]
    past = (w > W_SWITCH) & (w >= lim * (1 + 1e-12))
    before = (w <= W_SWITCH) | (w < lim * (1 - 1e-12))
    ws = td.datasets["W_star"]
    if np.isinf(ws).any() or not np.isnan(ws[past]).all() or np.isnan(ws[before]).any():
        raise ValueError("'W_star' holds NaN or infinite values where the law is defined")


def _check_axes_match_grid(gen):
    """The checksum covers the arrays; this ties the grid attributes to them."""
    g = gen["grid"]
    nus = np.linspace(g["nu_min"], g["nu_max"], g["n_nu"])
    eps_w = np.linspace(g["eps_y_min"], g["eps_y_max"], g["n_eps_y_energy"])
    layout = cell_layout(g, gen["v_top"])
    blocks = eps_y_blocks(g, layout["edges"])
    if [(b["cell0"], b["cell1"], b["n"]) for b in blocks] != [(b["cell0"], b["cell1"], b["n"]) for b in gen["blocks"]]:
        raise ValueError("blocks of cells do not match the grid attributes")
    for b, got in zip(blocks, gen["blocks"]):
        if got["values"].shape[1:] != (b["n"], nus.size, b["cstop"] - b["cell0"], DEGREE + 1):
            raise ValueError("a block's values do not have the shape of the grid attributes")
    omega = grid_axes_omega()
    v_max = np.array([[v1_star_limit(e, n) for n in gen["nu"]] for e in gen["eps_y"]])
    checks = [("nu", nus, gen["nu"]), ("eps_y", eps_w, gen["eps_y"]), ("cell", layout["edges"], gen["edges"]),
              ("omega_star", omega, gen["omega_star"]),
              ("v1_star_nodes", jg_nodes(layout["edges"], gen["v_top"]).reshape(gen["nodes"].shape), gen["nodes"]),
              ("v1_star_max", v_max, gen["v1_star_max"])]
    checks += [(f"c_eps_y_{k}", b["c_eps_y"], got["c_eps_y"]) for k, (b, got) in enumerate(zip(blocks, gen["blocks"]))]
    for name, want, got in checks:
        if want.shape != got.shape or not np.allclose(want, got, rtol=1e-12, atol=0):
            raise ValueError(f"axis {name!r} does not match the grid attributes")
    if layout["base"] != gen["base"] or layout["base_fine"] != gen["base_fine"]:
        raise ValueError("cell keys do not match the grid attributes")


_LOADED = {}


def _check_tol(tol):
    tol = real_scalar(tol, "tol")
    if not (1e-14 <= tol < 1.0):
        raise ValueError(f"tol (relative error asked of the table) must be in [1e-14, 1); got {tol!r}")
    return tol


def load_table(path=None, tol=None):
    """Load a restitution table once per process and return it.

    The file is read into NumPy arrays and closed; later calls with the same path return the same
    :class:`Table` without touching the file again.

    Parameters
    ----------
    path : str or path-like, optional
        An HDF5 table written by ``fastrest build``. Default: the shipped table
        (0.0005 <= eps_y <= 0.01, 0.2 <= nu <= 0.45, up to w_m* = 425).
    tol : float, optional
        The accuracy the caller needs (relative; see :mod:`fastrest.table_error`): an
        :class:`~fastrest.table_error.AccuracyWarning` if the file's measured error exceeds it.
        Without it, a table is checked against 1e-9 when first read.

    Returns
    -------
    Table

    Raises
    ------
    TableFileError
        The file is missing, truncated, corrupted (checksum), not a fastrest table, or of an older
        or newer format version; the message names the file and what is wrong.
    """
    from .table_error import warn_if_inaccurate

    key = str(Path(path).resolve()) if path is not None else None
    if key not in _LOADED:
        _LOADED[key] = read(default_table_path() if path is None else path)
        if tol is None:
            warn_if_inaccurate(_LOADED[key].attrs.get("measured_error"), None, f"table {_LOADED[key].path}")
    if tol is not None:
        warn_if_inaccurate(_LOADED[key].attrs.get("measured_error"), _check_tol(tol), f"table {_LOADED[key].path}")
    return _LOADED[key]


def cached_table(grid=None, progress=None, tol=None):
    """A table for any grid: the shipped one if it matches, else the user cache, built on first use.

    ``tol``: build it to that accuracy (refining the grid's node counts; see :func:`build`), and
    warn if a table found in the cache does not meet it. A cached file that fails verification
    (:class:`TableFileError`) is rebuilt with a RuntimeWarning. Raises OSError naming the file if
    it cannot be written (e.g. a full disk).
    """
    g = normalise_grid(grid)
    if tol is not None:
        tol = _check_tol(tol)
    if g == normalise_grid(None):
        return load_table(tol=tol)
    key = grid_key(g) if tol is None else f"{grid_key(g)}-tol{tol:.0e}"
    path = cache_dir() / f"{key}.h5"
    if os.path.lexists(path):
        try:
            return load_table(path, tol=tol)
        except _hdf5.TableFileError as exc:
            # a damaged cache entry is rebuilt, not re-raised on every call
            warnings.warn(f"rebuilding the cached table: {exc}", RuntimeWarning, stacklevel=2)
            if not path.is_file() and not path.is_dir():
                path.unlink()  # a FIFO, device or link to one in the cache: a table never replaces those
    build(path, g, progress=progress, tol=tol)
    return load_table(path, tol=tol)


# --- the default-table fast API (fastrest.omega_m_star, e_star, loss_star) -----------------------

_TOP_DOC = """{what}, from the shipped default table.

    Each point may have its own material. Interpolates the table of :func:`load_table` (accuracy:
    ``load_table().attrs["measured_error"]``, or ``fastrest info``; for the shipped table <= 1e-9 relative,
    except the Etsion 1 - e^2 near its zero crossing, see the README). For one material
    :func:`fastrest.curve` is faster and more accurate; :mod:`fastrest.direct` is the exact solver.

    Parameters
    ----------
    v1_star : float or array_like
        Normalised impact speed V1* = V1/V_c (-), JGM eq (30); >= 0. V1* <= 1 is elastic (e = 1).
    eps_y : float or array_like
        Sy/E' (-), JGM eq (11); within the table's range (shipped: 0.0005-0.01).
    nu : float or array_like
        Poisson's ratio of the yielding material (-); within the table's range (shipped: 0.2-0.45).{extra}

    Returns
    -------
    float or ndarray
        {returns}, broadcast over the three inputs (a float for scalar inputs).

    Raises
    ------
    TypeError
        An input is not a real number (string, bool, None, complex).
    ValueError
        v1_star negative or NaN; eps_y or nu outside the table; V1* past the model's limit
        w_m* = 425 (JGM section 3.3; the message gives that V1* for the material). No
        ``extrapolate`` here: use :mod:`fastrest.direct` or :func:`fastrest.curve`.

    Warns
    -----
    ValidityWarning
        Only for tables wider than the paper's validated range, at points outside it.
    """

_UNLOADING_DOC = """
    unloading : {"jcg", "etsion", "brake"}
        Unloading model: Jackson-Chusoipin-Green, JGM eq (35) (default), Etsion et al., eq (33), or Brake (2015)."""


def omega_m_star(v1_star, eps_y, nu):
    return load_table().omega_m_star(v1_star, eps_y, nu)


def e_star(v1_star, eps_y, nu, unloading="jcg"):
    return load_table().e_star(v1_star, eps_y, nu, unloading)


def loss_star(v1_star, eps_y, nu, unloading="jcg"):
    return load_table().loss_star(v1_star, eps_y, nu, unloading)


omega_m_star.__doc__ = _TOP_DOC.format(
    what="Normalised maximum interference w_m* = omega_m/omega_c (JGM eq 29)", extra="", returns="w_m* (-)")
e_star.__doc__ = _TOP_DOC.format(
    what="Coefficient of restitution e = V2/V1 (JGM eqs 16, 38)", extra=_UNLOADING_DOC, returns="e (-)")
loss_star.__doc__ = _TOP_DOC.format(
    what="Dissipated fraction of the impact energy 1 - e^2", extra=_UNLOADING_DOC, returns="1 - e^2 (-)")
