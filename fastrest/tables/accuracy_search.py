"""The search behind a table's stated error: material lattices, diverse starts, local maxima.

Used by :func:`fastrest.tables.accuracy.measure` (which documents the whole measurement); this
module sits below it. Between a table's nodes the error is smooth, with one hump per node interval
of each axis: per V1* cell, per interval of the mapped material axis xi (the cell's block's nodes)
and per nu interval. The worst lies at the top of one of those humps or on an edge of the domain,
and the humps' heights vary slowly from one interval to the next, so:

1. :func:`lattice_points` evaluates, in the V1* cells where a first sample is worst, a lattice of
   materials with a point in every hump (every xi interval's centre x every nu interval's centre,
   the same along the four edges of the (eps_y, nu) rectangle, its corners, and the material nodes
   +/- 1 ulp along the edges), at the V1* where that cell's error peaked, its midpoint and, where
   the material's w_m* = 425 speed falls in the cell, that speed;
2. :func:`search_starts` picks the worst point of each of the most distinct humps (one per
   (cell, xi interval, nu interval, edge) key), not the worst points overall, which cluster on one
   hump;
3. :func:`climb` climbs from each start to the top of its hump (a compass search).

Every coordinate is computed with the math module's scalar exp/log/log1p/expm1 (NumPy's vectorised
ones differ in the last bit between CPU instruction sets; the result is stored in the table file).
"""
from __future__ import annotations

import math
from typing import Any

import numpy as np
from numpy.typing import NDArray

from .._deprecation import keyword_only
from .._doc import doc, paragraphs
from ..critical import c_of_nu
from ..direct import impact_array
from ..energy import V_SWITCH
from ..limits import speed_limit
from ..loading import JACKSON_GREEN
from .kernel import interpolant_array

# ``table`` parameters are Tables, typed Any: this module sits below fastrest.tables.table, and
# imports point down even for types (tests/test_layering.py).
_Table = Any

__all__ = ["SIGN_CHANGE_FLOOR", "LOCAL_STARTS", "LOCAL_MIN_STEP", "LOCAL_ITERATIONS", "RIDGE_STARTS", "LATTICE_CELLS",
           "KNOWN_WORST", "lattice_points", "search_starts", "climb"]

#: The options of the local search, written once (fastrest._doc; :func:`climb` and
#: :func:`fastrest.tables.accuracy.local_search`).
SEARCH_DOC = paragraphs(search_steps="""
    min_step : float
        The search ends when its steps have shrunk to this fraction of the first.
    max_iterations : int
        At most this many rounds of the search.
    """)

#: A sign-changing 1 - e^2 is measured relative to max(abs(1 - e^2), SIGN_CHANGE_FLOOR).
SIGN_CHANGE_FLOOR = 0.1
#: Local search (:func:`climb`): distinct humps per quantity it starts from.
LOCAL_STARTS = 16
#: Local search: the step (fraction of the first) at which it stops.
LOCAL_MIN_STEP = 2.0**-20
#: Local search: its largest number of rounds.
LOCAL_ITERATIONS = 120
#: Starts of :func:`search_starts` on one ridge: the same V1* cell and xi interval, or nu interval.
RIDGE_STARTS = 3
#: Per quantity, the V1* cells (the worst of the first sample) that get a material lattice.
LATTICE_CELLS = 4
#: Points (V1*, eps_y, nu) where denser searches over the shipped table's domain found its worst
#: errors (1 - e^2 of each model just past the switch, e on the eps_y = 0.01 edge in the last cell):
#: extra starts of :func:`climb` for any table whose domain holds them.
KNOWN_WORST = (
    (2.2767236719200152, 0.0006858563735723869, 0.2),
    (2.311916775600111, 0.0012709453725046616, 0.21187302101907957),
    (2.311905558932348, 0.0012717559046712703, 0.21189008581722493),
    (800.8670058701113, 0.01, 0.44606368972458),
)


def _reference(table: _Table, v: NDArray[np.float64], e: NDArray[np.float64], n: NDArray[np.float64],
              models: Any = None) -> NDArray[np.float64]:
    """(n_quantities, N) direct-solver values: w_m*, then e and 1 - e^2 of each model (NaN rows for
    models not in ``models``; JGM eqs 29, 38)."""
    nq = table.data.n_quantities
    ref = np.full((nq, v.size), np.nan)
    for m in range((nq - 1) // 2):
        if models is not None and m not in models:
            continue
        sol = np.empty((5, v.size))
        impact_array(v, e, n, np.zeros_like(v), m, False, JACKSON_GREEN, sol)
        ref[0], ref[1 + 2 * m], ref[2 + 2 * m] = sol[0], sol[1], sol[2]
    return ref


def _interpolated(table: _Table, q: int, v: NDArray[np.float64], e: NDArray[np.float64],
                 n: NDArray[np.float64]) -> NDArray[np.float64]:
    """Quantity q of the table at the points, without the w_m* <= 425 check."""
    got = np.empty(v.size)
    interpolant_array(table.data, q, v, e, n, got)
    return got


def _error(got: NDArray[np.float64], ref: NDArray[np.float64], floored: bool) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Error in the quantity's metric, and the absolute difference (inf where not finite)."""
    diff = np.abs(got - ref)
    den = np.maximum(np.abs(ref), SIGN_CHANGE_FLOOR if floored else 0.0)
    err = np.where(den > 0, diff / np.where(den > 0, den, 1.0), diff)
    return np.where(np.isfinite(err), err, np.inf), np.where(np.isfinite(diff), diff, np.inf)


def _xi_map(table):
    """(xi of (eps_y, nu), eps_y of (xi, nu)) of the table's material axis (math, scalar)."""
    k = table.grid["c_eps_y_map_rate"]
    if k > 0:
        return (lambda e, n: math.expm1(k * c_of_nu(n) * e) / k,
                lambda x, n: math.log1p(k * x) / k / c_of_nu(n))
    return (lambda e, n: c_of_nu(n) * e, lambda x, n: x / c_of_nu(n))


def _block_materials(table, b):
    """(eps_y, nu) of block b's lattice: a point in every hump and on every edge (module doc)."""
    g, d = table.grid, table.data
    e0, e1, n0, n1 = g["eps_y_min"], g["eps_y_max"], g["nu_min"], g["nu_max"]
    xi_of, eps_of = _xi_map(table)
    h = 1.0 / float(d.block_inv_h[b])
    nx = int(d.block_n[b])
    nu_nodes = [n0 + (n1 - n0) * j / (g["n_nu"] - 1) for j in range(g["n_nu"])] if g["n_nu"] > 1 else [n0]
    nu_mid = [0.5 * (a + c) for a, c in zip(nu_nodes[:-1], nu_nodes[1:])]
    out = [(e, n) for e in (e0, e1) for n in (n0, n1)]
    for nu in nu_mid + [n0, n1]:
        lo, hi = xi_of(e0, nu), xi_of(e1, nu)
        for i in range(nx - 1):
            a, c = max(float(d.xi0) + i * h, lo), min(float(d.xi0) + (i + 1) * h, hi)
            if c > a:
                out.append((min(max(eps_of(0.5 * (a + c), nu), e0), e1), nu))
        if nu in (n0, n1):  # the material nodes +/- 1 ulp along the nu edges
            for i in range(nx):
                x = float(d.xi0) + i * h
                if lo < x < hi:
                    e = eps_of(x, nu)
                    out += [(np.nextafter(e, 0.0), nu), (e, nu), (np.nextafter(e, 1.0), nu)]
    for e in (e0, e1):  # nu centres and nodes +/- 1 ulp along the eps_y edges
        out += [(e, nu) for nu in nu_mid]
        out += [(e, x) for nu in nu_nodes[1:-1] for x in (np.nextafter(nu, 0.0), nu, np.nextafter(nu, 1.0))]
    return sorted(set((float(e), float(n)) for e, n in out))


def lattice_points(table: _Table, speeds: dict[int, list[float]]) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
    """Every material of the lattice of each V1* cell, at the given speeds in that cell.

    Parameters
    ----------
    table : Table
    speeds : dict
        V1* cell index -> speeds in it (-).

    Returns
    -------
    v1_star, eps_y, nu : ndarray
        A point in every hump of the error between material nodes (module doc) at each speed, the
        speed moved down to the material's w_m* = 425 speed (JGM section 3.3) where it is past it,
        and that speed itself where it lies in the cell. The first cell of a block also gets the
        previous block's lattice (it is blended from that block's grid).

    Examples
    --------
    >>> import fastrest
    >>> v, e, n = lattice_points(fastrest.load_table(), {2: [2.4]})
    >>> bool((v == 2.4).all()) and e.size > 200
    True
    """
    d = table.data
    edges = table.cell_edges
    mats: dict[int, list[tuple[float, float]]] = {}
    limits: dict[tuple[float, float], float] = {}
    v, e, n = [], [], []
    for c in sorted(speeds):
        b = int(d.cell_block[c])
        blocks = (b, b - 1) if b > 0 and c == int(d.block_cell0[b]) else (b,)
        cell_mats = sorted(set(m for k in blocks for m in mats.setdefault(k, _block_materials(table, k))))
        lo, hi = float(edges[c, 0]), float(edges[c, 1])
        for m in cell_mats:
            if m not in limits:
                limits[m] = speed_limit(*m)
            lim = limits[m]
            pts = {min(s, lim) for s in speeds[c]}
            if lo < lim <= hi:
                pts.add(lim)
            for s in pts:
                if s > V_SWITCH:
                    v.append(s)
                    e.append(m[0])
                    n.append(m[1])
    return np.array(v, dtype=float), np.array(e, dtype=float), np.array(n, dtype=float)


def _hump_keys(table, v, e, n):
    """A key per point naming its hump: (V1* cell, xi interval, nu interval, eps_y edge, nu edge)."""
    g, d = table.grid, table.data
    xi_of = _xi_map(table)[0]
    cell = np.searchsorted(table.cell_edges[:, 1], v, side="left")
    keys: list[tuple[Any, ...]] = []
    for vv, c, ee, nn in zip(v, cell, e, n):
        if not vv > V_SWITCH:
            keys.append(("below", float(vv)))
            continue
        c = min(int(c), d.cell_block.size - 1)
        b = int(d.cell_block[c])
        i = math.floor((xi_of(ee, nn) - float(d.xi0)) * float(d.block_inv_h[b]))
        j = math.floor((nn - float(d.nu0)) * float(d.inv_h_nu))
        keys.append((c, i, j, ee in (g["eps_y_min"], g["eps_y_max"]), nn in (g["nu_min"], g["nu_max"])))
    return keys


def search_starts(table: _Table, v: NDArray[np.float64], e: NDArray[np.float64], n: NDArray[np.float64],
                  err: NDArray[np.float64], starts: int) -> list[int]:
    """Indices of the worst point of each of the ``starts`` worst distinct humps of one quantity.

    Parameters
    ----------
    table : Table
    v, e, n : ndarray
        Points (V1*, eps_y, nu).
    err : ndarray
        The quantity's error at them.
    starts : int
        Humps wanted.

    Returns
    -------
    list of int
        Worst first; only finite, positive errors.

    Examples
    --------
    >>> import numpy as np, fastrest
    >>> v, e, n = np.array([5.0, 5.0, 500.0]), np.array([0.005, 0.005, 0.005]), np.array([0.3, 0.3, 0.3])
    >>> search_starts(fastrest.load_table(), v, e, n, np.array([1.0, 2.0, 0.5]), 4)
    [1, 2]
    """
    order = [int(i) for i in np.argsort(-err, kind="stable") if math.isfinite(err[i]) and err[i] > 0.0]
    out: list[int] = []
    seen: set[Any] = set()
    ridge_count: dict[Any, int] = {}
    for c0 in range(0, len(order), 1024):  # keys for the worst points first: usually all it takes
        chunk = order[c0:c0 + 1024]
        for i, key in zip(chunk, _hump_keys(table, v[chunk], e[chunk], n[chunk])):
            if key in seen:
                continue
            seen.add(key)
            # a ridge (the error of one axis' interpolation, nearly the same across the other
            # axis' intervals) takes at most RIDGE_STARTS starts
            ridges = [] if key[0] == "below" else [("xi", key[0], key[1], key[3]), ("nu", key[0], key[2], key[4])]
            if any(ridge_count.get(r, 0) >= RIDGE_STARTS for r in ridges):
                continue
            for r in ridges:
                ridge_count[r] = ridge_count.get(r, 0) + 1
            out.append(i)
            if len(out) == starts:
                return out
    return out


def _project(table, lnv, eps, nu):
    """A search point moved into the table's domain: eps_y and nu clamped to the rectangle, V1* to
    [1, the material's w_m* = 425 speed] (math, not NumPy: the result is stored in the file)."""
    g = table.grid
    eps = min(max(eps, g["eps_y_min"]), g["eps_y_max"])
    nu = min(max(nu, g["nu_min"]), g["nu_max"])
    v = max(math.exp(lnv), 1.0)
    if not v < table.data.v_safe:  # below v_safe every material of the table is inside its limit
        v = min(v, speed_limit(eps, nu))
    return math.log(v), v, eps, nu


def worst_cells(table: _Table, v: NDArray[np.float64], err: NDArray[np.float64], n_cells: int) -> dict[int, list[float]]:
    """V1* cell -> speeds for its lattice: per quantity, the ``n_cells`` cells above the switch where
    its error is largest, each at the speed of that maximum and at 1/6, 1/2 and 5/6 of the cell."""
    edges = table.cell_edges
    above = v > V_SWITCH
    cell = np.minimum(np.searchsorted(edges[:, 1], v, side="left"), edges.shape[0] - 1)
    out: dict[int, set[float]] = {}
    for q in range(err.shape[0]):
        best: dict[int, tuple[float, float]] = {}
        for i in np.flatnonzero(above & np.isfinite(err[q])):
            c = int(cell[i])
            if c not in best or err[q, i] > best[c][0]:
                best[c] = (float(err[q, i]), float(v[i]))
        for c in sorted(best, key=lambda c: -best[c][0])[:n_cells]:
            lo, hi = max(float(edges[c, 0]), V_SWITCH), float(edges[c, 1])
            out.setdefault(c, set()).update([best[c][1]] + [lo + f * (hi - lo) for f in (1 / 6, 0.5, 5 / 6)])
    return {c: sorted(s) for c, s in out.items()}


def in_domain(table: _Table, pts: Any) -> list[tuple[float, float, float]]:
    """The points (V1*, eps_y, nu) inside the table's domain above the switch, up to each limit."""
    g = table.grid
    return [(v, e, n) for v, e, n in pts
            if g["eps_y_min"] <= e <= g["eps_y_max"] and g["nu_min"] <= n <= g["nu_max"]
            and V_SWITCH < v <= min(speed_limit(e, n), float(table.cell_edges[-1, 1]))]


@keyword_only("min_step", "max_iterations")
@doc(SEARCH_DOC)
def climb(table: _Table, starts: list[tuple[int, float, float, float, float]], floored: Any, *,
                 min_step: float = LOCAL_MIN_STEP,
                 max_iterations: int = LOCAL_ITERATIONS) -> tuple[NDArray[np.float64], ...]:
    """Local maxima of the quantities' errors, climbed from starting points.

    Parameters
    ----------
    table : Table
    starts : list of (int, float, float, float, float)
        (quantity, V1*, eps_y, nu, its error there) per start.
    floored : list of bool
        Per quantity: a sign-changing loss, measured relative to max(abs(x), 0.1).
    {search_steps}

    Returns
    -------
    q, v, e, n : ndarray
        The quantity and the maximum found (V1*, eps_y, nu) per start, inside the domain (V1* up
        to each material's limit).

    Notes
    -----
    A compass search in (ln V1*, eps_y, nu), all starts together: each round evaluates the 6 points
    one step away along each coordinate (moved into the domain: the edges of the (eps_y, nu)
    rectangle, V1* >= 1 and w_m* <= 425), moves to the best if it raises the error, else halves the
    steps. First steps: 1/32 octave of V1* (half a fine cell), 1/512 of the eps_y range (about 1/5
    of the finest node spacing), 1/8 of the nu node spacing. Between the table's nodes the error is
    smooth and has one hump per node interval, so the search climbs to the nearest hump's top (or to
    an edge or corner of the domain, a V1* cell boundary or the limit speed) from each start.
    Deterministic: the coordinates use the math module's exp and log.

    Examples
    --------
    >>> import fastrest
    >>> t = fastrest.load_table()
    >>> q, v, e, n = climb(t, [(1, 800.0, 0.01, 0.44, 1e-10)], [False] * 7, max_iterations=3)
    >>> int(q[0]), bool(e[0] <= 0.01)
    (1, True)
    """
    g = table.grid
    s0 = (math.log(2.0) / 32.0, (g["eps_y_max"] - g["eps_y_min"]) / 512.0,
          (g["nu_max"] - g["nu_min"]) / (8.0 * max(g["n_nu"] - 1, 1)))
    jobs = [[int(q), math.log(v), float(e), float(n), float(x), 1.0] for q, v, e, n, x in starts]
    moves = [(d, sign) for d in range(3) for sign in (1.0, -1.0)]
    for _ in range(max_iterations):
        active = [j for j in jobs if j[5] >= min_step]
        if not active:
            break
        cand = []  # (job, lnv, v, eps, nu)
        for j in active:
            for d, sign in moves:
                x = [j[1], j[2], j[3]]
                x[d] += sign * j[5] * s0[d]
                cand.append((j,) + _project(table, *x))
        cv, ce, cn = (np.array([c[k] for c in cand]) for k in (2, 3, 4))
        qs = np.array([c[0][0] for c in cand])
        val = np.full(cv.size, -1.0)
        for q in sorted(set(qs.tolist())):
            k = qs == q
            ref = _reference(table, cv[k], ce[k], cn[k], models=None if q == 0 else {(q - 1) // 2})
            val[k] = _error(_interpolated(table, q, cv[k], ce[k], cn[k]), ref[q], floored[q])[0]
        for a, j in enumerate(active):
            block = val[6 * a: 6 * a + 6]
            b = int(np.argmax(block))
            if block[b] > j[4]:
                c = cand[6 * a + b]
                j[1], j[2], j[3], j[4] = c[1], c[3], c[4], float(block[b])
            else:
                j[5] *= 0.5
    found = [(j[0],) + _project(table, j[1], j[2], j[3])[1:] for j in jobs]
    if not found:
        return np.empty(0, dtype=int), np.empty(0), np.empty(0), np.empty(0)
    fq, fv, fe, fn = zip(*found)
    return np.array(fq, dtype=int), np.array(fv), np.array(fe), np.array(fn)
