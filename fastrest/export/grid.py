"""A rectilinear grid for the xarray / NetCDF world: ``fastrest export grid``, ``Table.to_xarray()``.

Variables ``omega_m`` (w_m*), ``e_<model>`` and ``loss_<model>`` (1 - e^2) of every unloading model
a table holds, on coordinates ``v1_star`` (V1* = V1/V_c), ``eps_y`` and ``nu``, with NaN wherever
the model is undefined (w_m* > 425 for that material, or past a/R = 1). Node values come from the
table (:mod:`fastrest.tables`, ~1e-9 of the direct solver), the elastic range 0 <= V1* <= 1
included (e = 1, 1 - e^2 = 0, w_m* = V1*^0.8, evaluated by the table's kernel): the grid starts
at V1* = 0.

Node placement: each axis is refined by bisection, independently, until linear interpolation along
it is within tol/3 at 7 points inside every interval, for probe lines across the other two axes;
the V1* axis is checked linear in V1* (what ``xarray``'s ``.interp`` does) and, above V1* = 1,
also linear in ln V1*, and has nodes on both sides of the model's jump at V1* = 1.9^1.25 (:data:`fastrest._placement.JUMP`:
the Jackson-Green loading law does not meet Hertz's at w* = 1.9, so e jumps there). The result is then measured at random points against
the direct solver (:mod:`fastrest.direct`): trilinear and tricubic (4-point Lagrange per axis)
interpolation in (:func:`v_coordinate` (V1*), eps_y, nu): V1* - 1 up to V1* = 1, ln V1* above. Error: ``|interpolated - exact| / max(|exact|, 1)``, i.e.
absolute for e and 1 - e^2, relative for w_m* > 1.
"""
from __future__ import annotations

import os
from typing import TYPE_CHECKING, Any
if TYPE_CHECKING:
    import xarray
    from ..tables import Table
import numpy as np

from .._deprecation import keyword_only
from ..tables import Table, load_table
# the grid is computed by fastrest.tables._rectilinear, below the Table whose to_xarray() uses it
from ..tables._rectilinear import (COORDS, DEFAULT_TOL, MAX_CHECK_POINTS, MAX_NODES, MIN_CHECK_POINTS, TOL_MIN,  # noqa: F401
                                  _check_n_check, _check_tol, _var_meta, dataset, global_attrs, interpolate, measure,
                                  sample, v_coordinate)
from ..tables import _rectilinear
from ._io import check_target, write_files

__all__ = ["DEFAULT_TOL", "TOL_MIN", "MAX_NODES", "MIN_CHECK_POINTS", "MAX_CHECK_POINTS", "grid_arrays",
           "measure", "v_coordinate", "to_xarray", "write_grid"]


def _check_table(table):
    if table is None:
        return load_table()
    if not isinstance(table, Table):
        raise TypeError(f"table must be a fastrest Table (fastrest.load_table) or None, got "
                        f"{type(table).__name__}")
    return table


@keyword_only("tol")
def grid_arrays(table: Table | None = None, *, tol: float = DEFAULT_TOL) -> dict[str, Any]:
    """Nodes and values of the grid: dict(v1_star, eps_y, nu, values={name: (nv, ne, nn) array}).

    ``table``: a :class:`fastrest.tables.Table` or None (the shipped one); ``tol`` in
    [:data:`TOL_MIN`, 1). TypeError or ValueError naming the parameter otherwise.
    """
    tol = _check_tol(tol)
    return _rectilinear.grid_arrays(_check_table(table), tol=tol)


@keyword_only("tol", "n_check")
def to_xarray(table: Table | None = None, *, tol: float = DEFAULT_TOL, n_check: int = 20000) -> xarray.Dataset:
    """The grid as an :class:`xarray.Dataset` (needs xarray: ``pip install fastrest[xarray]``)."""
    tol = _check_tol(tol)
    n_check = _check_n_check(n_check, allow_zero=True)
    return dataset(_check_table(table), tol=tol, n_check=n_check)


def _hdf5_image(grid, attrs):
    """The NetCDF4/HDF5 file's bytes, built in memory: HDF5 never writes to disk (after a failed
    write, e.g. on a full disk, h5py closing the file segfaulted)."""
    import io

    import h5py

    buffer = io.BytesIO()
    with h5py.File(buffer, "w") as f:
        scales = {}
        for k, (units, ln) in COORDS.items():
            ds = f.create_dataset(k, data=grid[k].astype(np.float64))
            ds.attrs["units"], ds.attrs["long_name"] = units, ln
            ds.make_scale(k)
            scales[k] = ds
        for name, arr in grid["values"].items():
            units, ln = _var_meta(name)
            ds = f.create_dataset(name, data=arr, fillvalue=np.nan, chunks=True, compression="gzip",
                                  shuffle=True)
            ds.attrs["units"], ds.attrs["long_name"] = units, ln
            ds.attrs["_FillValue"] = np.float64(np.nan)
            for i, k in enumerate(("v1_star", "eps_y", "nu")):
                ds.dims[i].attach_scale(scales[k])
        for k, val in attrs.items():
            f.attrs[k] = val
    return buffer.getbuffer()


@keyword_only("tol", "table_path", "n_check")
def write_grid(path: str | os.PathLike[str], *, tol: float | None = None,
               table_path: str | os.PathLike[str] | None = None, n_check: int = 20000) -> tuple[Any, Any]:
    """Build the grid, measure it, and write a CF NetCDF4/HDF5 file (atomically).

    Every argument is checked before anything is computed or written: ``path`` must be a regular
    file or a new path in a writable directory, ``tol`` in [:data:`TOL_MIN`, 1) (None:
    :data:`DEFAULT_TOL`), ``n_check`` a whole number in [:data:`MIN_CHECK_POINTS`,
    :data:`MAX_CHECK_POINTS`]. A failed write (full disk) raises OSError naming ``path`` and
    leaves the old file intact and no temporary file.

    Returns (grid, report) with report: shape, variables, tol, n_check, linear, cubic, nan_fraction.
    """
    tol = _check_tol(DEFAULT_TOL if tol is None else tol)
    n_check = _check_n_check(n_check)
    path = check_target(path, "path", "the grid file")
    table = load_table(table_path)
    grid = _rectilinear.grid_arrays(table, tol=tol)
    report = measure(grid, n_check)
    write_files({path: _hdf5_image(grid, global_attrs(table, grid, report))}, "path", "the grid file")
    report.update(shape={k: int(grid[k].size) for k in COORDS}, variables=list(grid["values"]), tol=grid["tol"])
    return grid, report
