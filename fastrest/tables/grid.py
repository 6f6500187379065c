"""What a table holds: the grid specification and its validation.

A grid (a plain dict, :data:`DEFAULT_GRID` for the shipped table) fixes the materials (eps_y, nu)
and speeds V1* a table covers and its node counts. :func:`normalise_grid` fills in defaults and
validates it before anything is allocated; :mod:`fastrest.tables.axes` turns it into the table's axes:

* nu: uniform nodes;
* the material axis C(nu) eps_y (:func:`c_eps_y`): uniform in xi = expm1(k C(nu) eps_y)/k
  (k = ``c_eps_y_map_rate``), denser where a/R is large; each block of V1* cells
  (``eps_y_blocks``) has its own number of nodes;
* V1*: bit-indexed cells, finer below ``fine_v1_star_max``;
* w* of the stored W*, on a plain eps_y axis of ``n_eps_y_energy`` nodes.
"""
from __future__ import annotations

from typing import Any, overload
import numpy as np
from numpy.typing import ArrayLike, NDArray
import hashlib
import json
import math

from .. import unloading as _unloading
from .._validation import EPS_Y_VALIDATED, NU_VALIDATED, check_count, check_nu, real_scalar
from ..materials import poisson_factor
from .hdf5 import FORMAT_VERSION

__all__ = ["DEFAULT_GRID", "GRID_COUNTS", "TABLE_EPS_Y", "MAP_RATE_MAX", "TABLE_BYTES_MAX", "QUANTITIES",
           "QUANTITY_META", "STENCIL_EPS", "STENCIL_NU", "OMEGA_GRID_HERTZ", "OMEGA_GRID_JG", "normalise_grid",
           "grid_key", "c_eps_y"]

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

#: Default grid of the shipped table, one that ``fastrest build --tol 1e-9`` reaches on the
#: adversarial sample of fastrest.tables.error: the cells up to V1* = 128, 256, 512 carry 28, 32, 47 nodes in the
#: mapped C(nu) eps_y and the top octaves 85 (the law's cos(pi a/R) term varies fastest near
#: w* = 425), 8 nodes in nu, 2^4 cells per octave up to V1* = 16 (the Etsion and Brake 1 - e^2 near
#: V1* = 8-16 and just above the switch). W* is stored on its own plain-eps_y grid (n_eps_y_energy).
DEFAULT_GRID: dict[str, Any] = dict(eps_y_min=EPS_Y_VALIDATED[0], eps_y_max=EPS_Y_VALIDATED[1], n_eps_y=85,
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


def normalise_grid(grid: dict[str, Any] | None = None, **overrides: Any) -> dict[str, Any]:
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
    g: dict[str, Any] = dict(DEFAULT_GRID)
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
    out: list[Any] = []
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


def grid_key(grid: dict[str, Any]) -> str:
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


@overload
def c_eps_y(eps_y: float, nu: float) -> float: ...
@overload
def c_eps_y(eps_y: ArrayLike, nu: ArrayLike) -> NDArray[np.float64]: ...


def c_eps_y(eps_y: Any, nu: Any) -> float | NDArray[np.float64]:
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
