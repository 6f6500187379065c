"""The error of a table against the direct solver, on a sample built to find the worst.

Public from :mod:`fastrest.tables.error` (which adds :func:`~fastrest.tables.error.build_to_tolerance`);
this module sits below :mod:`fastrest.tables.table`, whose :meth:`~fastrest.tables.Table.measure_error`
calls it.

A table's stated error is the worst found by a search (:mod:`fastrest.tables.accuracy_search`):
first a sample that includes what random points miss (the corners and edges of its (eps_y, nu)
rectangle, every V1* cell boundary and +/- 1 ulp around it, cell midpoints, both sides of the switch
at V1* = 1.9^1.25, V1* -> 1, and the last cell before each material's w_m* = 425 speed, down to the
limit itself, besides random materials and speeds); then, in the :data:`LATTICE_CELLS` V1* cells
where each quantity's sample error is worst, a lattice of materials with a point in every hump of
the error between material nodes (and the nodes +/- 1 ulp along the edges), at four speeds per cell
and at each material's limit speed; then a local maximisation (a compass search in (ln V1*, eps_y,
nu), clamped to the rectangle and to each material's w_m* = 425 speed) from the worst point of each
of the :data:`LOCAL_STARTS` worst distinct humps of each quantity, and from :data:`KNOWN_WORST`.
On the shipped table the lattice and the diverse starts find the 1 - e^2 maxima just past the switch
(V1* ~ 2.28-2.31, small eps_y, nu at or just above 0.2: 2.84e-10 JCG, where a search from the 8
worst sample points had settled on a smaller hump, 2.42e-10) without the known points; the whole
measurement costs ~25 s on 2 loaded cores (the sample alone ~1 s).

Metrics: w_m*, e and 1 - e^2 relative to the direct solver's value. A 1 - e^2 that changes sign
in the table's domain (Etsion's and Brake's, where the model gives e > 1 just above the switch) has
no relative error bound at its zero: its error is taken relative to max(abs(1 - e^2), 0.1), i.e. a
tolerance ``tol`` is ``tol / 10`` absolute where abs(1 - e^2) <= 0.1 (around the zero) and ``tol``
relative above (the default table: 1e-10 absolute, 1e-9 relative).
"""
from __future__ import annotations

from typing import Any
from numpy.typing import ArrayLike, NDArray
# ``table`` parameters are Tables, typed Any: this module sits below fastrest.tables.table, and
# imports point down even for types (tests/test_layering.py).
_Table = Any
import math

import numpy as np

from .._deprecation import keyword_only
from .._doc import doc
from .._validation import warn
from ..energy import V_SWITCH
from ..limits import speed_limit
from .accuracy_search import (KNOWN_WORST, LATTICE_CELLS, LOCAL_ITERATIONS, LOCAL_MIN_STEP, LOCAL_STARTS,
                              SIGN_CHANGE_FLOOR, climb, in_domain, lattice_points, search_starts, worst_cells)
from .accuracy_search import SEARCH_DOC, _error, _interpolated, _reference
from .grid import QUANTITIES, normalise_grid

__all__ = ["AccuracyWarning", "DEFAULT_TOL", "SAFETY", "SIGN_CHANGE_FLOOR", "adversarial_points", "sample_points",
           "local_search", "measure", "meets", "worst", "warn_if_inaccurate"]

#: The accuracy the shipped table is built to (relative; sign-changing losses: see the module doc).
DEFAULT_TOL = 1e-9
#: A table is built until its measured error is within SAFETY x tol. The measured error is the worst
#: the search finds (the module doc), not a sample's maximum; bench/adversarial.py (a denser,
#: independent sample and a different search, golden-section line searches) checks it. The 10 % left
#: covers a hump that no start reaches.
SAFETY = 0.9


class AccuracyWarning(UserWarning):
    """A table's measured error exceeds the accuracy asked for (or fastrest's default, 1e-9).

    Issued by :func:`~fastrest.tables.load_table`, :func:`~fastrest.tables.build` and
    :func:`~fastrest.tables.cached_table` (:func:`warn_if_inaccurate`), attributed to the caller's
    line; public as ``fastrest.tables.AccuracyWarning`` and ``fastrest.tables.error.AccuracyWarning``.

    Examples
    --------
    >>> import warnings
    >>> with warnings.catch_warnings(record=True) as rec:
    ...     warnings.simplefilter("always")
    ...     warn_if_inaccurate({"e_jcg": {"max_rel_error": 1e-6, "max_error": 1e-6}}, 1e-9, "t")
    >>> rec[0].category is AccuracyWarning
    True
    """


def _materials(g, n_random, rng):
    e0, e1, n0, n1 = g["eps_y_min"], g["eps_y_max"], g["nu_min"], g["nu_max"]
    # the last ulp inside each edge too: a stencil at the very edge of the table
    e_in, n_in = (np.nextafter(e0, e1), np.nextafter(e1, e0)), (np.nextafter(n0, n1), np.nextafter(n1, n0))
    pts = [(e, n) for e in (e0, e1) + e_in for n in (n0, n1) + n_in]                 # corners
    for t in np.linspace(0.0, 1.0, 27)[1:-1]:                                         # edges
        t = float(t)
        pts += [(e0, n0 + t * (n1 - n0)), (e1, n0 + t * (n1 - n0)),
                (e0 * math.pow(e1 / e0, t), n0), (e0 * math.pow(e1 / e0, t), n1)]
    pts += list(zip(rng.uniform(e0, e1, n_random), rng.uniform(n0, n1, n_random)))    # inside
    return np.array(pts)


@keyword_only("n_random_materials", "n_random_speeds", "seed")
def adversarial_points(table: _Table, *, n_random_materials: int = 24, n_random_speeds: int = 16,
                       seed: int = 2026) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
    """The sample a table's error is measured on: what random points miss, and random points.

    Parameters
    ----------
    table : Table
        The table (its grid and V1* cells).
    n_random_materials, n_random_speeds : int
        Random materials besides the corners and edges of the (eps_y, nu) rectangle; random speeds
        per material (log-uniform up to its limit).
    seed : int
        Random seed (the sample is reproducible).

    Returns
    -------
    v1_star, eps_y, nu : ndarray
        Every material of the sample at every speed of the sample up to its own w_m* = 425 speed
        (JGM section 3.3): cell boundaries and +/- 1 ulp, cell midpoints, both sides of the switch
        at 1.9^1.25, V1* -> 1, and the last cell before the limit (see the module doc).

    Examples
    --------
    >>> import fastrest
    >>> v, e, n = adversarial_points(fastrest.load_table())
    >>> v.shape == e.shape == n.shape
    True
    """
    rng = np.random.default_rng(seed)
    g = table.grid
    edges = table.cell_edges
    inner = edges[1:, 0]
    cell_pts = np.concatenate([np.nextafter(inner, 0), inner, np.nextafter(inner, np.inf),
                               0.5 * (edges[:, 0] + edges[:, 1]),
                               [V_SWITCH, np.nextafter(V_SWITCH, np.inf), V_SWITCH * (1 + 1e-12),
                                np.nextafter(V_SWITCH, 0), 1.0 + 1e-12, 1.0 + 1e-9, 1.5]])
    v, e, n = [], [], []
    for eps, nu in _materials(g, n_random_materials, rng):
        lim = speed_limit(eps, nu)
        last = [lim, lim * (1 - 1e-12), lim * (1 - 1e-6), lim * (1 - 1e-3)]
        # math, not NumPy's vectorised exp: its last bit depends on the CPU's instruction set, and
        # the measured error (stored in the file) must not
        rand = np.array([math.exp(x) for x in rng.uniform(0.0, math.log(lim), n_random_speeds)])
        s = np.concatenate([cell_pts[cell_pts <= lim], last, rand])
        v.append(s)
        e.append(np.full(s.size, eps))
        n.append(np.full(s.size, nu))
    return np.concatenate(v), np.concatenate(e), np.concatenate(n)


def sample_points(grid: dict[str, Any], n_points: int, seed: int) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
    """Test points over a table's domain: random plus hard cases (bench/table_details.py).

    Parameters
    ----------
    grid : dict or None
        Grid specification (:func:`~fastrest.tables.normalise_grid`).
    n_points : int
        Random materials (uniform in eps_y, nu), each at a V1* log-uniform up to its w_m* = 425 speed.
    seed : int
        Random seed.

    Returns
    -------
    v1_star, eps_y, nu : ndarray
        The points, followed by hard speeds (1, 1 + 1e-12, around 1.9^1.25, ...) and the limit
        speeds of the first materials.

    Examples
    --------
    >>> v, e, n = sample_points(None, 10, 1)
    >>> v.size
    26
    """
    rng = np.random.default_rng(seed)
    g = normalise_grid(grid)
    e = rng.uniform(g["eps_y_min"], g["eps_y_max"], n_points)
    n = rng.uniform(g["nu_min"], g["nu_max"], n_points)
    vmax = np.array([speed_limit(a, b) for a, b in zip(e, n)])
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


def _errors(table, v, e, n, ref, floored):
    """(n_quantities, N) errors in each quantity's metric and absolute differences."""
    nq = table.data.n_quantities
    pairs = [_error(_interpolated(table, q, v, e, n), ref[q], floored[q]) for q in range(nq)]
    return (np.array([p[k] for p in pairs]).reshape(nq, v.size) for k in (0, 1))


@keyword_only("starts", "min_step", "max_iterations")
@doc(SEARCH_DOC)
def local_search(table: _Table, v: NDArray[np.float64], e: NDArray[np.float64], n: NDArray[np.float64], err: NDArray[np.float64], floored: Any, *,
                 starts: int = LOCAL_STARTS, min_step: float = LOCAL_MIN_STEP,
                 max_iterations: int = LOCAL_ITERATIONS) -> Any:
    """Local maxima of each quantity's error, climbed from the worst humps of a sample.

    Parameters
    ----------
    table : Table
    v, e, n : ndarray
        The sample (V1*, eps_y, nu).
    err : ndarray
        (n_quantities, N) the sample's errors (in each quantity's metric).
    floored : list of bool
        Per quantity: a sign-changing loss, measured relative to max(abs(x), 0.1).
    starts : int
        Distinct humps per quantity to start from (the worst point of each of its worst humps:
        :func:`~fastrest.tables.accuracy_search.search_starts`).
    {search_steps}

    Returns
    -------
    v, e, n : ndarray
        The maxima found (one per start), inside the domain (V1* up to each material's limit).

    Notes
    -----
    The compass search of :func:`~fastrest.tables.accuracy_search.climb` in (ln V1*, eps_y, nu):
    between the table's nodes the error is smooth and has one hump per node interval, so it climbs
    to the nearest hump's top (or to an edge or corner of the domain, a V1* cell boundary or the
    limit speed) from each start. Deterministic: the coordinates use the math module's exp and log.

    Examples
    --------
    >>> import numpy as np, fastrest
    >>> t = fastrest.load_table()
    >>> nq = t.data.n_quantities
    >>> v, e, n = np.array([800.0]), np.array([0.01]), np.array([0.44])
    >>> err = np.full((nq, 1), 1e-10)          # the sample's errors (here: one point, any value > 0)
    >>> fv, fe, fn = local_search(t, v, e, n, err, [False] * nq, starts=1, max_iterations=3)
    >>> fv.size == nq and bool(np.all(fe <= 0.01))
    True
    """
    jobs = [(q, float(v[i]), float(e[i]), float(n[i]), float(err[q, i]))
            for q in range(err.shape[0]) for i in search_starts(table, v, e, n, err[q], starts)]
    return climb(table, jobs, floored, min_step=min_step, max_iterations=max_iterations)[1:]


@keyword_only("search")
def measure(table: _Table, points: tuple[ArrayLike, ArrayLike, ArrayLike] | None = None, *,
            search: bool = True) -> dict[str, dict[str, Any]]:
    """Worst error of every quantity of a table against the direct solver.

    Parameters
    ----------
    table : Table
    points : (ndarray, ndarray, ndarray), optional
        (v1_star, eps_y, nu); default :func:`adversarial_points`.
    search : bool
        Also search for the worst beyond the points (default True): a material lattice with a
        point in every hump of the error in the :data:`LATTICE_CELLS` worst V1* cells of each
        quantity (:func:`~fastrest.tables.accuracy_search.lattice_points`), then local maxima
        climbed from the worst point of each of the :data:`LOCAL_STARTS` worst humps of each
        quantity and from :data:`KNOWN_WORST` (:func:`local_search`); all are included.

    Returns
    -------
    dict
        Quantity name -> {metric ("relative", or ``"relative to max(|x|, 0.1)"`` for a sign-changing
        loss), max_error, max_rel_error (the same number, kept for older readers), max_abs_error,
        at_v1_star, at_eps_y, at_nu, by_block (worst per block of V1* cells)}. The interpolant is
        evaluated without the w_m* <= 425 check (:func:`~fastrest.tables.kernel.interpolant_array`).

    Notes
    -----
    Reference: :func:`fastrest.direct.impact_array` (JGM eqs 29, 38 by quadrature and Newton).

    Examples
    --------
    >>> import numpy as np, fastrest
    >>> pts = (np.array([5.0, 300.0]), np.array([0.005, 0.009]), np.array([0.33, 0.4]))
    >>> measure(fastrest.load_table(), pts, search=False)["omega_m_star"]["max_error"] < 1e-9
    True
    """
    v, e, n = adversarial_points(table) if points is None else points
    v, e, n = (np.ascontiguousarray(x, dtype=np.float64) for x in (v, e, n))
    nq = table.data.n_quantities
    names = QUANTITIES[:nq]
    ref = _reference(table, v, e, n)
    floored = [name.startswith("loss_") and bool(np.any(ref[q] < 0)) for q, name in enumerate(names)]
    err, diff = _errors(table, v, e, n, ref, floored)
    if search and v.size:
        # 2. a point in every hump of the worst cells, and the known worst points
        lv, le, ln = lattice_points(table, worst_cells(table, v, err, LATTICE_CELLS))
        known = in_domain(table, KNOWN_WORST)
        if known:
            kv, ke, kn = (np.array(x) for x in zip(*known))
            lv, le, ln = np.concatenate([lv, kv]), np.concatenate([le, ke]), np.concatenate([ln, kn])
        if lv.size:
            lerr, ldiff = _errors(table, lv, le, ln, _reference(table, lv, le, ln), floored)
            v, e, n = np.concatenate([v, lv]), np.concatenate([e, le]), np.concatenate([n, ln])
            err, diff = np.concatenate([err, lerr], axis=1), np.concatenate([diff, ldiff], axis=1)
        # 3. climb from the worst humps, and from the known worst points for every quantity
        jobs = [(q, float(v[i]), float(e[i]), float(n[i]), float(err[q, i]))
                for q in range(nq) for i in search_starts(table, v, e, n, err[q], LOCAL_STARTS)]
        k0 = v.size - len(known)
        jobs += [(q, float(v[i]), float(e[i]), float(n[i]), float(err[q, i]))
                 for q in range(nq) for i in range(k0, v.size)]
        fq, fv, fe, fn = climb(table, jobs, floored)
        if fv.size:
            ferr, fdiff = _errors(table, fv, fe, fn, _reference(table, fv, fe, fn), floored)
            v, e, n = np.concatenate([v, fv]), np.concatenate([e, fe]), np.concatenate([n, fn])
            err, diff = np.concatenate([err, ferr], axis=1), np.concatenate([diff, fdiff], axis=1)
    edges = table.cell_edges
    cell = np.searchsorted(edges[:, 1], v, side="left")
    block = np.full(v.size, -1)
    above = v > V_SWITCH
    for k, (c0, c1) in enumerate(table.block_cells):
        block[above & (cell >= c0) & (cell < c1)] = k
    out = {}
    for q, name in enumerate(names):
        k = int(np.argmax(err[q]))
        by_block = [float(err[q][block == b].max()) if np.any(block == b) else 0.0
                    for b in range(len(table.block_cells))]
        out[name] = {"metric": f"relative to max(|x|, {SIGN_CHANGE_FLOOR:g})" if floored[q] else "relative",
                     "max_error": float(err[q, k]), "max_rel_error": float(err[q, k]),
                     "max_abs_error": float(np.max(diff[q])),
                     "at_v1_star": float(v[k]), "at_eps_y": float(e[k]), "at_nu": float(n[k]),
                     "by_block": by_block}
    return out

def meets(errors: dict[str, dict[str, Any]], tol: float) -> bool:
    """Whether every quantity's measured error is within ``tol`` (in its metric).

    Parameters
    ----------
    errors : dict
        As :func:`measure` returns.
    tol : float
        The tolerance.

    Returns
    -------
    bool

    Examples
    --------
    >>> meets({"e_jcg": {"max_error": 2e-10}}, 1e-9)
    True
    """
    return all(d["max_error"] <= tol for d in errors.values())


def worst(errors: dict[str, dict[str, Any]], tol: float | None) -> tuple[str, float, float | None]:
    """The quantity with the largest measured error.

    Parameters
    ----------
    errors : dict
        As :func:`measure` returns.
    tol : float
        Returned as is (for messages).

    Returns
    -------
    (str, float, float)
        (name, its error, tol).

    Examples
    --------
    >>> worst({"a": {"max_error": 1e-9}, "b": {"max_error": 3e-9}}, 1e-9)
    ('b', 3e-09, 1e-09)
    """
    name = max(errors, key=lambda k: errors[k]["max_error"])
    return name, errors[name]["max_error"], tol


def warn_if_inaccurate(errors: dict[str, dict[str, Any]] | None, tol: float | None, where: str) -> None:
    """Warn if a table's stored measured error exceeds a tolerance.

    Parameters
    ----------
    errors : dict or None
        The ``measured_error`` attribute (as :func:`measure`); None or empty: unknown accuracy.
    tol : float or None
        The tolerance; None: :data:`DEFAULT_TOL`.
    where : str
        Names the table in the message.

    Warns
    -----
    AccuracyWarning
        The error exceeds ``tol``, or is not recorded.

    Examples
    --------
    >>> import fastrest
    >>> warn_if_inaccurate(fastrest.load_table().attrs["measured_error"], 1e-9, "default")  # no warning
    """
    tol = DEFAULT_TOL if tol is None else tol
    if not errors:
        warn(f"{where}: the table records no measured error; its accuracy is unknown", AccuracyWarning)
        return
    errors = {k: dict(d, metric=d.get("metric", "relative"), max_error=d.get("max_error", d["max_rel_error"]))
              for k, d in errors.items()}
    if not meets(errors, tol):
        name, err, lim = worst(errors, tol)
        warn(f"{where}: measured {errors[name]['metric']} error of {name} is {err:.3g}, above "
             f"{lim:.3g} (tol = {tol:g}); rebuild with `fastrest build --tol {tol:g}` or "
             "tables.cached_table(grid, tol=...)", AccuracyWarning)

