"""A table on a rectilinear (v1_star, eps_y, nu) grid for the xarray / NetCDF world:
:meth:`Table.to_xarray() <fastrest.tables.Table.to_xarray>`, ``fastrest export grid``
(:mod:`fastrest.export.grid`, which adds the file and the shipped table as default, and whose
module documentation describes the variables, the node placement and the error measured).
Here, below :class:`~fastrest.tables.Table` in the layers: the node placement, the values from the
table's kernel, and the measurement against the direct solver.
"""
import json
from typing import Any

import numpy as np

from .._deprecation import keyword_only
from .._placement import JUMP, place_rows, scaled_error as _err
from .._provenance import provenance
from .._validation import check_count, check_tol
from ..direct import impact_array
from ..loading import JACKSON_GREEN
from ..limits import speed_limit
from .. import unloading as _unloading
from .grid import QUANTITIES
from .kernel import table_array

__all__ = ["DEFAULT_TOL", "TOL_MIN", "MAX_NODES", "MIN_CHECK_POINTS", "MAX_CHECK_POINTS", "COORDS", "grid_arrays",
           "interpolate", "sample", "measure", "v_coordinate", "global_attrs", "dataset"]

#: Default relative interpolation error of the gridded export (``fastrest export grid --tol``).
DEFAULT_TOL = 1e-3
#: Smallest tol of the gridded export: the table's own error is ~1e-9; below 1e-6 its nodes would not be accurate enough to measure against.
TOL_MIN = 1e-6
#: Most grid nodes (V1* x eps_y x nu) an export may need to meet its tol.
MAX_NODES = 20_000_000
#: Lower bound of the random points of :func:`measure` (each costs a direct solve per model and ~1 kB).
MIN_CHECK_POINTS = 100
#: Upper bound of the random points of :func:`measure`.
MAX_CHECK_POINTS = 1_000_000


def _names(table):
    return QUANTITIES[:table.data.n_quantities]


def _var_name(q):
    return "omega_m" if q == "omega_m_star" else q


def _eval(table, v, e, n):
    """(nq, size) values of every quantity at broadcast points (NaN outside the model's domain)."""
    v, e, n = (np.ascontiguousarray(a, dtype=np.float64).ravel() for a in np.broadcast_arrays(v, e, n))
    out = np.empty((table.data.n_quantities, v.size))
    for q in range(out.shape[0]):
        table_array(table.data, q, v, e, n, out[q])
    return out


def _check_tol(tol):
    return check_tol(tol, TOL_MIN, "the grid's nodes come from a table accurate to ~1e-9")


def _check_n_check(n_check, allow_zero=False):
    if allow_zero and isinstance(n_check, int) and not isinstance(n_check, bool) and n_check == 0:
        return 0
    return check_count(n_check, "n_check", MIN_CHECK_POINTS, MAX_CHECK_POINTS)


def grid_arrays(table, *, tol=DEFAULT_TOL):
    """Nodes and values of the grid: dict(v1_star, eps_y, nu, values={name: (nv, ne, nn) array}).

    ``table``: a :class:`fastrest.tables.Table`; ``tol`` in [:data:`TOL_MIN`, 1). ValueError
    naming the parameter otherwise.
    """
    tol = _check_tol(tol)
    d = table.data
    e_lo, e_hi, n_lo, n_hi, v_top = d.eps_lo, d.eps_hi, d.nu_lo, d.nu_hi, d.v_top
    share = tol / 3.0
    pe, pn = np.linspace(e_lo, e_hi, 7), np.linspace(n_lo, n_hi, 4)
    PE, PN = [a.ravel() for a in np.meshgrid(pe, pn, indexing="ij")]

    def along_v(v):
        return _eval(table, v[None, :], PE[:, None], PN[:, None]).reshape(-1, v.size)

    seed = np.concatenate([np.geomspace(1.0, v_top, 41), JUMP])
    v = place_rows(along_v, seed, share, 20000, log=True, what="nodes in v1_star")
    # the elastic range: the table's kernel gives it exactly; linear in V1* (ln V1* ends at 0)
    elastic = place_rows(along_v, np.linspace(0.0, 1.0, 5), share, 20000, what="nodes in v1_star")
    v = np.unique(np.concatenate([elastic, v]))
    pv = np.unique(np.concatenate([np.geomspace(1.2, v_top, 60), v[-40:]]))
    PV, PN2 = [a.ravel() for a in np.meshgrid(pv, pn, indexing="ij")]

    def along_e(e):
        return _eval(table, PV[:, None], e[None, :], PN2[:, None]).reshape(-1, e.size)

    eps = place_rows(along_e, np.linspace(e_lo, e_hi, 5), share, 20000, what="nodes in eps_y")
    PV3, PE3 = [a.ravel() for a in np.meshgrid(pv, pe, indexing="ij")]

    def along_n(n):
        return _eval(table, PV3[:, None], PE3[:, None], n[None, :]).reshape(-1, n.size)

    nu = place_rows(along_n, np.linspace(n_lo, n_hi, 3), share, 20000, what="nodes in nu")
    if v.size * eps.size * nu.size > MAX_NODES:
        raise ValueError(f"tol = {tol!r} cannot be met within {MAX_NODES} grid nodes "
                         f"({v.size} x {eps.size} x {nu.size}); give a larger tol")
    vals = _eval(table, v[:, None, None], eps[None, :, None], nu[None, None, :])
    vals = vals.reshape(-1, v.size, eps.size, nu.size)
    return dict(v1_star=v, eps_y=eps, nu=nu, tol=tol,
                values={_var_name(q): vals[i] for i, q in enumerate(_names(table))})


# --- measuring --------------------------------------------------------------------------------

def _stencil(x, xq, m, breaks=()):
    """Indices and weights of the m-point Lagrange stencil of nodes x at points xq (m = 2: linear).

    ``breaks``: pairs (j, after) of a node index j where the function jumps or kinks: stencils of
    points up to x[j] end at j, those of later points start at ``after`` (j + 1 past a jump, j at
    a kink).
    """
    m = min(m, x.size)  # a coarse axis (a large tol) may have fewer nodes than the stencil
    i = np.clip(np.searchsorted(x, xq, side="right") - 1, 0, x.size - 2)
    first = i - (m // 2 - 1)
    for brk, after in breaks:
        first = np.where(xq <= x[brk], np.minimum(first, brk - m + 1), np.maximum(first, after))
    first = np.clip(first, 0, x.size - m)
    idx = first[:, None] + np.arange(m)[None, :]
    xs = x[idx]
    w = np.ones((xq.size, m))
    for a in range(m):
        for b in range(m):
            if a != b:
                w[:, a] *= (xq - xs[:, b]) / (xs[:, a] - xs[:, b])
    return idx, w


def v_coordinate(v):
    """The V1* coordinate :func:`interpolate` is linear in: V1* - 1 up to 1 (the elastic range, from
    V1* = 0), ln V1* above (the two meet with equal slopes at V1* = 1)."""
    v = np.asarray(v, dtype=np.float64)
    return np.where(v < 1.0, v - 1.0, np.log(np.maximum(v, 1.0)))


def interpolate(grid, name, v, e, n, m=2):
    """Tensor-product m-point Lagrange interpolation of ``grid['values'][name]`` in
    (:func:`v_coordinate` (V1*), eps_y, nu) (m = 2 trilinear, m = 4 tricubic; its stencils in V1*
    stay on one side of the kink at V1* = 1 and of the jump at 1.9^1.25); NaN where a stencil
    node is NaN."""
    x = grid["v1_star"]
    breaks = []
    if m > 2:
        breaks = [(int(j), int(j) + shift) for at, shift in ((1.0, 0), (JUMP[0], 1)) for j in np.flatnonzero(x == at)]
    iv, wv = _stencil(v_coordinate(x), v_coordinate(v), m, breaks)
    ie, we = _stencil(grid["eps_y"], e, m)
    jn, wn = _stencil(grid["nu"], n, m)
    f = grid["values"][name]
    out = np.zeros(v.size)
    for a in range(wv.shape[1]):
        for b in range(we.shape[1]):
            for c in range(wn.shape[1]):
                out += wv[:, a] * we[:, b] * wn[:, c] * f[iv[:, a], ie[:, b], jn[:, c]]
    return out


@keyword_only("seed")
def sample(grid, n_points, *, seed=2014):
    """Random points in the model's domain over the grid: uniform in (eps_y, nu); in V1*, one in
    ten uniform in the elastic range [0, 1], the others log-uniform from 1 to the material's
    w_m* = 425 speed."""
    rng = np.random.default_rng(seed)
    e = rng.uniform(grid["eps_y"][0], grid["eps_y"][-1], n_points)
    n = rng.uniform(grid["nu"][0], grid["nu"][-1], n_points)
    lim = np.array([speed_limit(a, b) for a, b in zip(e, n)])
    v = np.exp(rng.uniform(0.0, 1.0, n_points) * np.log(lim))
    elastic = np.arange(n_points) % 10 == 0
    v[elastic] = rng.uniform(0.0, 1.0, np.count_nonzero(elastic))
    return v, e, n


@keyword_only("seed")
def measure(grid, n_points=20000, *, seed=2014):
    """Worst error of trilinear and tricubic interpolation against the direct solver at
    ``n_points`` (in [:data:`MIN_CHECK_POINTS`, :data:`MAX_CHECK_POINTS`]) random points."""
    n_points = check_count(n_points, "n_points", MIN_CHECK_POINTS, MAX_CHECK_POINTS)
    v, e, n = sample(grid, n_points, seed=seed)
    names = list(grid["values"])
    nm = (len(names) - 1) // 2
    ref = {}
    sol = np.empty((5, v.size))
    for m in range(nm):
        impact_array(v, e, n, np.zeros_like(v), m, False, JACKSON_GREEN, sol)
        ref["omega_m"] = sol[0].copy()
        ref[f"e_{_unloading.NAMES[m]}"] = sol[1].copy()
        ref[f"loss_{_unloading.NAMES[m]}"] = sol[2].copy()
    out: dict[str, Any] = {"n_check": int(v.size)}
    nan = np.zeros(v.size, bool)
    for method, m in (("linear", 2), ("cubic", 4)):
        out[method] = {}
        for q in names:
            got = interpolate(grid, q, v, e, n, m)
            if m == 2:
                nan |= np.isnan(got)
            err = _err(got, ref[q])
            out[method][q] = float(np.nanmax(err))
    out["nan_fraction"] = float(nan.mean())
    return out


# --- files ------------------------------------------------------------------------------------

COORDS = {
    "v1_star": ("1", "normalised impact speed V1* = V1/V_c (JGM eq 30); V1* <= 1 is elastic (e = 1, "
                     "w_m* = V1*^0.8)"),
    "eps_y": ("1", "yield strain eps_y = Sy/E' (JGM eq 11)"),
    "nu": ("1", "Poisson's ratio of the yielding material"),
}


def _var_meta(name):
    if name == "omega_m":
        return "1", "normalised maximum interference w_m* = omega_m/omega_c (JGM eq 29)"
    q, model = name.split("_", 1)
    label = _unloading.get(model).label
    if q == "e":
        return "1", f"coefficient of restitution e, {label} (JGM eq 38)"
    return "1", f"dissipated fraction 1 - e^2, {label}"


def global_attrs(table, grid, report):
    prov = provenance()
    src = {"path": table.path, "format_version": table.attrs.get("format_version"),
           "checksum": table.attrs.get("checksum"), "fastrest_version": table.attrs.get("fastrest_version")}
    attrs = {
        "Conventions": "CF-1.8",
        "title": "fastrest: Jackson-Green-Marghitu (2010) coefficient of restitution on a rectilinear grid",
        "references": prov["references"],
        "source": "fastrest table (fastrest.tables) interpolated at the grid's nodes; table: " + json.dumps(src),
        "history": f"fastrest {prov['fastrest_version']}: fastrest export grid (tol {grid['tol']:g})",
        "comment": ("NaN where the model is undefined (w_m* > 425 for that material, JGM section 3.3). "
                    "Interpolate linearly in (v1_star, eps_y, nu), or in ln v1_star above v1_star = 1; "
                    "the error is |interpolated - exact| / max(|exact|, 1)."),
        "fastrest_version": prov["fastrest_version"],
        "unloading_models": ",".join(_unloading.NAMES[:(len(grid["values"]) - 1) // 2]),
        "interpolation_tolerance": grid["tol"],
    }
    if report:
        attrs["measured_error"] = json.dumps({k: report[k] for k in ("n_check", "linear", "cubic", "nan_fraction")})
        for method in ("linear", "cubic"):
            for q, e in report[method].items():
                attrs[f"max_error_{method}_{q}"] = e
    return attrs


def dataset(table, *, tol=DEFAULT_TOL, n_check=20000):
    """``table`` (a :class:`~fastrest.tables.Table`) on the grid as an :class:`xarray.Dataset` (needs
    xarray: ``pip install fastrest[xarray]``); ``n_check`` = 0: not measured."""
    try:
        import xarray as xr
    except ImportError:
        raise ImportError("Table.to_xarray needs xarray: pip install fastrest[xarray]") from None
    tol = _check_tol(tol)
    n_check = _check_n_check(n_check, allow_zero=True)
    grid = grid_arrays(table, tol=tol)
    report = measure(grid, n_check) if n_check else None
    coords = {k: (k, grid[k], {"units": u, "long_name": ln}) for k, (u, ln) in COORDS.items()}
    data = {}
    for name, arr in grid["values"].items():
        units, ln = _var_meta(name)
        data[name] = (("v1_star", "eps_y", "nu"), arr, {"units": units, "long_name": ln})
    return xr.Dataset(data, coords=coords, attrs=global_attrs(table, grid, report))
