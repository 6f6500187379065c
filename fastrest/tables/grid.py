"""What a table holds and where: the grid specification, its validation, and the axes it implies.

A grid (a plain dict, :data:`DEFAULT_GRID` for the shipped table) fixes the materials (eps_y, nu)
and speeds V1* a table covers and its node counts. :func:`normalise_grid` fills in defaults and
validates it before anything is allocated; the other functions turn it into the table's axes:

* nu: uniform nodes;
* the material axis c_eps_y = C(nu) eps_y (:func:`c_eps_y`): uniform in
  xi = expm1(k c_eps_y)/k (k = ``c_eps_y_map_rate``, :func:`xi_range`), denser where a/R is large;
  each block of V1* cells (``eps_y_blocks``) has its own number of nodes (:func:`eps_y_blocks`);
* V1*: bit-indexed cells, finer below ``fine_v1_star_max`` (:func:`cell_layout`);
* w* of the stored W* (:func:`omega_axis`), on a plain eps_y axis of ``n_eps_y_energy`` nodes.

Axes are computed with the math module's scalar exp and log: NumPy's vectorised ones differ in the
last bit between CPU instruction sets, and the table must be bit-reproducible.
"""
import hashlib
import json
import math
from dataclasses import dataclass

import numpy as np

from .. import unloading as _unloading
from .._validation import EPS_Y_VALIDATED, NU_VALIDATED, OMEGA_M_STAR_MAX, check_count, check_nu, real_scalar
from ..contact import W_SWITCH
from ..energy import V_SWITCH
from ..interpolation import two_level_cells
from ..limits import v1_star_limit
from ..materials import poisson_factor
from .hdf5 import FORMAT_VERSION

__all__ = ["DEFAULT_GRID", "GRID_COUNTS", "TABLE_EPS_Y", "MAP_RATE_MAX", "TABLE_BYTES_MAX", "QUANTITIES",
           "QUANTITY_META", "STENCIL_EPS", "STENCIL_NU", "OMEGA_GRID_HERTZ", "OMEGA_GRID_JG", "Block",
           "normalise_grid", "grid_key", "c_eps_y", "xi_range", "c_eps_y_of_xi", "nu_axis", "energy_eps_y_axis",
           "omega_axis", "cell_layout", "eps_y_blocks", "v1_star_top"]

#: Every registered unloading model is tabulated, in code order: quantity 1 + 2 code is its e,
#: 2 + 2 code its 1 - e^2.
QUANTITIES = ("omega_m_star",) + tuple(f"{q}_{name}" for name in _unloading.NAMES for q in ("e", "loss"))
#: (units, long_name) of every quantity, as written into a table file.
QUANTITY_META = {"omega_m_star": ("1", "normalised maximum interference omega_m/omega_c (JGM eq 29, 31)")}
for _m in _unloading.MODELS.values():
    QUANTITY_META[f"e_{_m.name}"] = ("1", f"coefficient of restitution, {_m.label} (JGM eq 38)")
    QUANTITY_META[f"loss_{_m.name}"] = ("1", f"dissipated fraction 1 - e^2, {_m.label}")

#: Interpolation stencils across materials (points per axis). The JG law varies with eps_y through
#: cos(pi a/R), a/R ~ C eps_y w^0.6, which at w* ~ 425 spans half a period over the validated
#: range: 6-point (quintic) stencils reach ~1e-9 with 64 x 6 nodes where cubic ones stay near 1e-7
#: (measured while choosing the grid; bench/ reports the error of several grids).
STENCIL_EPS = 6
#: Points of the stencil across nu.
STENCIL_NU = 6
#: Nodes of the W* grid on [0, 1.9] (uniform).
OMEGA_GRID_HERTZ = 20
#: Nodes of the W* grid on (1.9, 425] (geometric).
OMEGA_GRID_JG = 236

#: Default grid of the shipped table: what `fastrest build --tol 1e-9` reaches from the earlier
#: grid (24/32/40/72 nodes in C(nu) eps_y, 6 in nu, fine cells up to V1* = 8) on the adversarial
#: sample of fastrest.tables.error: the cells up to V1* = 128, 256, 512 carry 28, 32, 47 nodes in the
#: mapped C(nu) eps_y and the top octaves 85 (the law's cos(pi a/R) term varies fastest near
#: w* = 425), 8 nodes in nu, 2^4 cells per octave up to V1* = 16 (the Etsion and Brake 1 - e^2 near
#: V1* = 8-16 and just above the switch). W* is stored on its own plain-eps_y grid (n_eps_y_energy).
DEFAULT_GRID = dict(eps_y_min=EPS_Y_VALIDATED[0], eps_y_max=EPS_Y_VALIDATED[1], n_eps_y=85,
                    nu_min=NU_VALIDATED[0], nu_max=NU_VALIDATED[1], n_nu=8, bits_per_octave=3,
                    fine_bits_per_octave=4, fine_v1_star_max=16.0, c_eps_y_map_rate=30.0,
                    eps_y_blocks=[[128.0, 28], [256.0, 32], [512.0, 47]], n_eps_y_energy=32)

#: Bounds of a table's node counts (checked before anything is allocated).
GRID_COUNTS = {"n_eps_y": (6, 4096), "n_nu": (6, 256), "n_eps_y_energy": (2, 4096),
               "bits_per_octave": (1, 10), "fine_bits_per_octave": (1, 10)}
#: eps_y range tables are built for (past 0.1 the law ends, a/R = 1, close to the Hertz range).
TABLE_EPS_Y = (1e-6, 0.1)
#: Largest c_eps_y_map_rate (expm1 of it must stay finite).
MAP_RATE_MAX = 1000.0
#: Largest table arrays a grid may ask for (bytes).
TABLE_BYTES_MAX = 4 * 2**30


def normalise_grid(grid=None, **overrides):
    """Fill in the defaults of a grid specification and validate it.

    Parameters
    ----------
    grid : dict or None
        Grid parameters (the keys of :data:`DEFAULT_GRID`); missing keys take the default. None:
        the shipped table's grid.
    **overrides
        Parameters that replace those of ``grid``.

    Returns
    -------
    dict
        Every key of :data:`DEFAULT_GRID`, with counts as int, ranges and rates as float,
        ``eps_y_blocks`` as a list of [float, int] pairs. Equal grids give equal dicts (the cache key
        :func:`grid_key` depends on that).

    Raises
    ------
    TypeError
        ``grid`` is not a dict, or a value is not a real number.
    ValueError
        An unknown key, a count outside :data:`GRID_COUNTS`, eps_y outside :data:`TABLE_EPS_Y`,
        nu outside [0, 0.5), an empty range, ``fine_v1_star_max`` not a power of two in [1, 2^20],
        a map rate outside [0, :data:`MAP_RATE_MAX`], malformed ``eps_y_blocks``, or a grid
        needing more than :data:`TABLE_BYTES_MAX` of arrays; the message names the parameter.

    Examples
    --------
    >>> from fastrest.tables import normalise_grid
    >>> normalise_grid(dict(n_nu=6.0))["n_nu"]
    6
    """
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


def grid_key(grid):
    """The cache key of a grid: the file format version and a hash of the generation parameters.

    Parameters
    ----------
    grid : dict or None
        A grid specification (see :func:`normalise_grid`).

    Returns
    -------
    str
        ``v<format version>-<16 hex digits>``; grids that normalise to the same dict share a key.

    Raises
    ------
    TypeError, ValueError
        As :func:`normalise_grid`.

    Examples
    --------
    >>> from fastrest.tables import grid_key
    >>> grid_key(None) == grid_key(dict(n_nu=8.0))
    True
    """
    blob = json.dumps({"format_version": FORMAT_VERSION, **normalise_grid(grid)}, sort_keys=True)
    return f"v{FORMAT_VERSION}-{hashlib.sha256(blob.encode()).hexdigest()[:16]}"


def c_eps_y(eps_y, nu):
    """C(nu) eps_y, the table's first material axis (-).

    a/R = (pi/2) C(nu) eps_y sqrt(A*) (JGM eqs 5, 12): the law depends on eps_y mostly through
    a/R, i.e. through C(nu) eps_y. On a grid uniform in (C(nu) eps_y, nu) the remaining dependence
    on nu is very smooth, where on an (eps_y, nu) grid both axes carry the fast variation of
    cos(pi a/R) at large w* (bench/RESULTS.md compares grids).

    Parameters
    ----------
    eps_y : float or ndarray
        Sy/E' (-), JGM eq (11).
    nu : float or ndarray
        Poisson's ratio (-).

    Returns
    -------
    float or ndarray
        C(nu) eps_y (-), C(nu) = 1.295 exp(0.736 nu) (JGM eq 5).

    Examples
    --------
    >>> from fastrest.tables.grid import c_eps_y
    >>> round(float(c_eps_y(0.005, 0.3)), 6)
    0.008075
    """
    return poisson_factor(nu) * eps_y


def xi_range(g):
    """The mapped material axis: xi = expm1(k c_eps_y)/k (k = ``c_eps_y_map_rate``; xi = c_eps_y
    for k = 0) from the grid's smallest to its largest C(nu) eps_y. Nodes are uniform in xi, denser
    where C(nu) eps_y, and with it a/R, is large and the law varies fastest."""
    k = g["c_eps_y_map_rate"]
    lo = float(c_eps_y(g["eps_y_min"], g["nu_min"]))
    hi = float(c_eps_y(g["eps_y_max"], g["nu_max"]))
    return (math.expm1(k * lo) / k, math.expm1(k * hi) / k) if k > 0 else (lo, hi)


def c_eps_y_of_xi(xi, k):
    """Inverse of the xi map (element by element with math.log1p: bit-reproducible)."""
    xi = np.asarray(xi, dtype=np.float64)
    if not k > 0:
        return xi
    return np.array([math.log1p(k * x) / k for x in xi.ravel()]).reshape(xi.shape)


def nu_axis(g):
    """The nu nodes of a normalised grid (uniform)."""
    return np.linspace(g["nu_min"], g["nu_max"], g["n_nu"])


def energy_eps_y_axis(g):
    """The plain eps_y nodes of the stored W* and of ``v1_star_max`` (uniform)."""
    return np.linspace(g["eps_y_min"], g["eps_y_max"], g["n_eps_y_energy"])


def v1_star_top(g):
    """The largest V1* a table of grid ``g`` holds: the largest w_m* = 425 speed over the materials
    of its top block's nodes (clamped into the grid's eps_y range)."""
    nus = nu_axis(g)
    top = c_eps_y_of_xi(np.linspace(*xi_range(g), g["n_eps_y"]), g["c_eps_y_map_rate"])
    eps = top[:, None] / c_eps_y(1.0, nus)[None, :]
    return max(v1_star_limit(min(max(e, g["eps_y_min"]), g["eps_y_max"]), n)
               for e, n in zip(eps.ravel(), np.broadcast_to(nus, eps.shape).ravel()))


def omega_axis():
    """The w* nodes of the stored W*: uniform on [0, 1.9], geometric on (1.9, 425]."""
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


def cell_layout(g, v_top):
    """The V1* cells over (1.9^1.25, v_top]: 2^fine_bits_per_octave per octave below
    fine_v1_star_max (where 1 - e^2 is small and curved, just above the kink at w* = 1.9), then
    2^bits_per_octave. Returns (base_fine, base, edges): the first cell keys and the (ncell, 2)
    [start, end] of every cell (:func:`fastrest.interpolation.two_level_cells`)."""
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
    """

    cell0: int
    cell1: int
    cstop: int
    n: int
    c_eps_y: np.ndarray
    values: np.ndarray = None


def eps_y_blocks(g, edges):
    """The non-empty blocks of cells of grid ``g`` (:class:`Block` without values), given the
    cells' (ncell, 2) ``edges``."""
    out, c0 = [], 0
    for v_end, n in g["eps_y_blocks"] + [[math.inf, g["n_eps_y"]]]:
        c1 = int(np.searchsorted(edges[:, 1], v_end, side="right"))
        if c1 > c0:
            axis = c_eps_y_of_xi(np.linspace(*xi_range(g), n), g["c_eps_y_map_rate"])
            out.append((c0, c1, n, axis))
            c0 = c1
    return [Block(cell0=c0, cell1=c1, cstop=c1 + (k < len(out) - 1), n=n, c_eps_y=axis)
            for k, (c0, c1, n, axis) in enumerate(out)]
