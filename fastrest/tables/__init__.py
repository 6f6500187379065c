"""Multi-material tables: generation (Numba, all cores), HDF5 storage, loading and evaluation.

A table holds, on a grid over the material, everything the fast multi-material path needs:

* ``omega_m_star``, ``e_<model>``, ``loss_<model>`` (:data:`QUANTITIES`) on (C(nu) eps_y, nu, V1*
  cell, node): the direct solver's w_m*, e and 1 - e^2 at the Chebyshev-Lobatto points of
  bit-indexed cells in V1* from 1.9^1.25 up to the largest V1* any grid material allows;
* ``W_star`` (eps_y, nu, w*): the normalised loading energy (W_ep)* = 1 - F(w*) of JGM eq (25), up
  to w* = 425, read by :meth:`Table.W_star` and :meth:`Table.loading_energy`.

Where things are:

* :mod:`~fastrest.tables.grid`: the grid specification (:data:`DEFAULT_GRID`, :func:`normalise_grid`);
  :mod:`~fastrest.tables.axes`: the axes it implies;
* :mod:`~fastrest.tables.generation`: computing the arrays (:func:`generate`, a :class:`GeneratedTable`);
* :mod:`~fastrest.tables.data` (:class:`TableData`) and :mod:`~fastrest.tables.kernel`
  (``table_value_kernel``): the compiled evaluator; :mod:`~fastrest.tables.w_star`: the W* reader;
* :mod:`~fastrest.tables.table`: the :class:`Table` object; :mod:`~fastrest.tables.store`: the
  shipped table (package data ``default.h5``), the user cache, :func:`build`, :func:`read`,
  :func:`load_table`; :mod:`~fastrest.tables.default`: ``fastrest.e_star`` and friends;
* :mod:`~fastrest.tables.error`: the error against the direct solver (measured by
  :mod:`~fastrest.tables.accuracy`, below :class:`Table`), tables built to a tolerance;
* :mod:`~fastrest.tables.schema` (arrays <-> file), :mod:`~fastrest.tables.hdf5` and
  :mod:`~fastrest.tables.hdf5_read` (the HDF5 layout), :mod:`~fastrest.tables.file` (the verified
  bytes): the file format of docs/table-format.md; :mod:`~fastrest.tables.probe`: untrusted files
  are parsed in a check process first.
"""
from .default import e_star, loss_star, omega_m_star
from .error import AccuracyWarning
from .file import TableFileError
from .generation import GeneratedTable, generate
from .grid import DEFAULT_GRID, GRID_COUNTS, QUANTITIES, grid_key, normalise_grid
from .data import TableData
from .kernel import EPS_Y_AR_BINDS, table_value, table_value_kernel
from .store import build, cache_dir, cached_table, default_table_path, load_table, read, source_tree_table_path
from .table import PARALLEL_MIN_POINTS, Table

__all__ = ["Table", "TableData", "GeneratedTable", "TableFileError", "AccuracyWarning", "load_table",
           "cached_table", "build", "generate", "read", "default_table_path", "source_tree_table_path",
           "cache_dir", "normalise_grid", "grid_key", "DEFAULT_GRID", "GRID_COUNTS", "QUANTITIES",
           "EPS_Y_AR_BINDS", "PARALLEL_MIN_POINTS", "omega_m_star", "e_star", "loss_star",
           "table_value_kernel", "table_value"]
