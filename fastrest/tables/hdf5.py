"""Storage of precomputed tables in HDF5 files: the layout, and the writer (no physics here).

Layout of a table file (format ``fastrest-table``, version 3)::

    bytes 0-511           the HDF5 user block: a text header with the file's size and the
                          SHA-256 digest of the bytes after it (see fastrest.tables.file)
    /                     root attributes: format, format_version, fastrest_version,
                          checksum, checksum_algorithm, plus the caller's attributes
    /<axis>               1-D float64 dimension scale named after the axis;
                          attributes units, long_name
    /<dataset>            float64 (or integer) array, contiguous and uncompressed,
                          its dimensions attached to the axis scales; attributes units, long_name

Every axis is an HDF5 dimension scale named exactly like its dataset, so
``xarray.open_dataset(path, engine="h5netcdf")`` shows named coordinates and
``h5dump -H`` shows the structure (HDF5 skips the user block). A reader checks the header's
size and digest with plain reads before HDF5 parses anything, then the structure (datasets only,
stored inside the file, float64 or integer) before it allocates anything. The ``checksum``
attribute, a SHA-256 over the names, dtypes, shapes and bytes of all arrays, also ties the
arrays to the metadata HDF5 reports.

Files are built in memory and written to a temporary file beside the target, which is renamed
over it, so a reader sees either the old table or the new one, never a half-written file, and a
full disk gives an OSError naming the file. The reader is :mod:`fastrest.tables.hdf5_read`.
"""
from __future__ import annotations

from collections.abc import Mapping
from typing import Any
from numpy.typing import ArrayLike, NDArray
from dataclasses import dataclass, field
import hashlib
import io
import json
import os

import h5py
import numpy as np

from .._version import __version__
from .file import USERBLOCK, TableFileError, write_atomic
from .probe import trust

__all__ = ["FORMAT_NAME", "FORMAT_VERSION", "CHECKSUM_ALGORITHM", "JSON_ATTRS_KEY", "FileContents",
           "TableFileError", "checksum_arrays", "write_table", "write_variable"]

#: The ``format`` root attribute of a table file.
FORMAT_NAME = "fastrest-table"
#: 2: two-level V1* cells; 3: header with digest, Lobatto nodes, unloading models list.
FORMAT_VERSION = 3
#: The ``checksum_algorithm`` root attribute.
CHECKSUM_ALGORITHM = "sha256"
#: Root attribute listing the attributes that hold JSON-encoded dicts, so that a caller's plain
#: string that happens to look like JSON is never decoded by mistake.
JSON_ATTRS_KEY = "json_attributes"
_RESERVED_ATTRS = {"format", "format_version", "fastrest_version", "checksum",
                   "checksum_algorithm", JSON_ATTRS_KEY}


@dataclass(frozen=True)
class FileContents:
    """Everything stored in a table file, read into memory.

    Attributes
    ----------
    axes : dict of str to ndarray
        1-D coordinate arrays by axis name.
    datasets : dict of str to ndarray
        Data arrays by name.
    attrs : dict
        Root attributes (including ``format``, ``format_version``, ``fastrest_version``,
        ``checksum``, ``checksum_algorithm``); JSON-encoded dicts are decoded back to dicts.
    units : dict of str to str
        Units of every axis and dataset.
    path : str
        The file the table was read from.
    dims : dict of str to tuple of str
        Axis names along each dimension of every dataset (``()`` for a scalar).
    long_names : dict of str to str
        Descriptive name of every axis and dataset.
    digest : str
        SHA-256 hex digest of the file's bytes after its header (kept in the header).

    Examples
    --------
    >>> from fastrest.tables import default_table_path
    >>> from fastrest.tables.hdf5_read import read_table
    >>> read_table(default_table_path()).dims["W_star"]
    ('eps_y', 'nu', 'omega_star')
    """

    axes: dict[str, Any]
    datasets: dict[str, Any]
    attrs: dict[str, Any]
    units: dict[str, Any]
    path: str
    dims: dict[str, Any] = field(default_factory=dict)
    long_names: dict[str, Any] = field(default_factory=dict)
    digest: str = ""


def write_table(path: str | os.PathLike[str], axes: dict[str, Any], datasets: dict[str, Any],
                attrs: dict[str, Any]) -> str:
    """Write a table to an HDF5 file, atomically.

    Parameters
    ----------
    path : str or os.PathLike
        Target file; its directory must exist. An existing file is replaced.
    axes : dict
        ``name -> (values, units, long_name)``; ``values`` is 1-D and stored as float64.
    datasets : dict
        ``name -> (values, dims, units, long_name)``; ``dims`` is a tuple of axis names,
        one per dimension of ``values`` (``()`` for a scalar). Integer arrays keep their
        dtype, other real arrays are stored as float64; booleans are refused because
        netCDF tools cannot read them.
    attrs : dict
        Root attributes: str, int, float, 1-D numeric arrays, or dicts (stored as JSON
        strings and decoded by `read_table`).

    Returns
    -------
    str
        The SHA-256 digest of the file's bytes after its header (trusted when this process reads
        the file back, :mod:`fastrest.tables.probe`).

    Raises
    ------
    TypeError, ValueError
        If the inputs cannot be stored; nothing is written then.
    OSError
        If the file cannot be written (disk full, read-only, a directory...); the message names
        ``path``, the old file is untouched and no temporary file remains.

    Notes
    -----
    The file is built in memory (HDF5 never writes to disk), then written to
    ``tempfile.mkstemp(dir=<target directory>, suffix=".tmp")``, flushed to disk and renamed over the target with `os.replace`. If writing raises, the
    temporary file is removed and the target is untouched. If the process is killed while
    writing, the target is also untouched but a stray ``*.tmp`` file may remain in the
    directory; it is never mistaken for a table and can be deleted.

    The same content always gives a byte-identical file: h5py writes no timestamps and
    everything is written in sorted name order.

    Examples
    --------
    >>> import tempfile, os
    >>> import numpy as np
    >>> from fastrest.tables.hdf5_read import read_table
    >>> with tempfile.TemporaryDirectory() as d:
    ...     p = os.path.join(d, "t.h5")
    ...     digest = write_table(p, {"x": (np.arange(3.0), "1", "x")}, {"y": (np.ones(3), ("x",), "1", "y")},
    ...                          {"title": "t"})
    ...     read_table(p).datasets["y"]
    array([1., 1., 1.])
    """
    path = os.fspath(path)
    axes, datasets, attrs = _prepare(axes, datasets, attrs)
    arrays = {name: values for name, (values, _, _) in axes.items()}
    arrays.update({name: values for name, (values, _, _, _) in datasets.items()})
    attrs.update(format=FORMAT_NAME, format_version=FORMAT_VERSION,
                 fastrest_version=__version__, checksum=checksum_arrays(arrays),
                 checksum_algorithm=CHECKSUM_ALGORITHM)

    # The whole file is built in memory and written by fastrest.tables.file: HDF5 never sees a write error
    # (h5py closing a file after a failed write, e.g. on a full disk, segfaulted).
    buffer = io.BytesIO()
    with h5py.File(buffer, "w", userblock_size=USERBLOCK) as f:
        scales: dict[str, Any] = {}
        for name in sorted(axes):
            values, units, long_name = axes[name]
            scales[name] = write_variable(f, name, values, units, long_name)
            scales[name].make_scale(name)
        for name in sorted(datasets):
            values, dims, units, long_name = datasets[name]
            dset = write_variable(f, name, values, units, long_name)
            for i, axis in enumerate(dims):
                dset.dims[i].attach_scale(scales[axis])
        for key in sorted(attrs):
            f.attrs[key] = attrs[key]
    digest = write_atomic(path, buffer.getbuffer())
    trust(digest)  # bytes this process made: parsed in-process when read back
    return digest


def _prepare(axes, datasets, attrs):
    """Check and convert the inputs of `write_table`; raise before any file is touched."""
    out_axes = {}
    for name, (values, units, long_name) in axes.items():
        _check_name(name)
        values = np.asarray(values)
        _check_real(values, f"axis {name!r}")
        values = values.astype(np.float64)
        if values.ndim != 1:
            raise ValueError(f"axis {name!r} must be 1-D, got shape {values.shape}")
        out_axes[name] = (values, _check_str(units, name), _check_str(long_name, name))

    out_datasets = {}
    for name, (values, dims, units, long_name) in datasets.items():
        _check_name(name)
        if name in axes:
            raise ValueError(f"dataset {name!r} has the same name as an axis")
        values = np.asarray(values)
        _check_real(values, f"dataset {name!r}")
        if values.dtype.kind in "iu":
            values = values.astype(values.dtype.newbyteorder("="))
        else:
            values = values.astype(np.float64)
        dims = tuple(dims)
        if len(dims) != values.ndim:
            raise ValueError(f"dataset {name!r} has {values.ndim} dimensions but dims "
                             f"{dims} names {len(dims)} axes")
        for i, axis in enumerate(dims):
            if axis not in out_axes:
                raise ValueError(f"dataset {name!r} refers to unknown axis {axis!r}")
            if out_axes[axis][0].shape != (values.shape[i],):
                raise ValueError(f"dimension {i} of dataset {name!r} has length "
                                 f"{values.shape[i]} but axis {axis!r} has length "
                                 f"{out_axes[axis][0].size}")
        out_datasets[name] = (values, dims, _check_str(units, name),
                              _check_str(long_name, name))

    out_attrs = {}
    json_keys = []
    for key, value in attrs.items():
        if not isinstance(key, str) or key in _RESERVED_ATTRS:
            raise ValueError(f"attribute name {key!r} is reserved or not a string")
        if isinstance(value, dict):
            # sort_keys: identical content must give identical bytes.
            out_attrs[key] = json.dumps(value, sort_keys=True, default=_json_default)
            json_keys.append(key)
        else:
            out_attrs[key] = _attr_value(key, value)
    if json_keys:
        out_attrs[JSON_ATTRS_KEY] = json.dumps(sorted(json_keys))
    return out_axes, out_datasets, out_attrs


def _check_name(name):
    # A "/" would create HDF5 groups, and netCDF names cannot start with a dot.
    if not isinstance(name, str) or not name or "/" in name or name.startswith("."):
        raise ValueError(f"invalid axis or dataset name {name!r}")


def _check_str(value, name):
    if not isinstance(value, str):
        raise TypeError(f"units and long_name of {name!r} must be str, got {value!r}")
    return value


def _check_real(values, what):
    if values.dtype.kind not in "iuf":
        raise TypeError(f"{what} must be a real numeric array (not boolean, complex or "
                        f"object), got dtype {values.dtype}")


def _attr_value(key, value):
    """Convert one root attribute to a value h5py stores in a netCDF-readable way."""
    if isinstance(value, (bool, np.bool_)):
        raise TypeError(f"attribute {key!r}: booleans are not supported, use 0 or 1")
    if isinstance(value, str):
        return value
    if isinstance(value, (int, np.integer)):
        return np.int64(value)
    if isinstance(value, (float, np.floating)):
        return np.float64(value)
    array = np.asarray(value)
    if array.ndim == 1 and array.dtype.kind in "iuf":
        return array
    raise TypeError(f"attribute {key!r}: unsupported value {value!r} (use str, int, float, "
                    "a 1-D numeric array or a dict)")


def _json_default(value):
    # NumPy scalars and arrays inside dict attributes.
    if isinstance(value, (np.generic, np.ndarray)):
        return value.tolist()
    raise TypeError(f"cannot store {value!r} in a JSON attribute")


def checksum_arrays(arrays: Mapping[str, NDArray[Any]]) -> str:
    """The ``checksum`` attribute: SHA-256 over the name, dtype, shape and bytes of every array.

    Parameters
    ----------
    arrays : dict of str to array_like
        Every axis and dataset of a file.

    Returns
    -------
    str
        Lowercase hex digest (docs/table-format.md, section 1.2).

    Notes
    -----
    Arrays are taken in sorted name order and in little-endian C order, so the digest does not
    depend on the platform or on how the arrays are laid out in memory or in the file.

    Examples
    --------
    >>> import numpy as np
    >>> len(checksum_arrays({"x": np.arange(3.0)}))
    64
    """
    digest = hashlib.sha256()
    for name in sorted(arrays):
        values = np.asarray(arrays[name])
        values = values.astype(values.dtype.newbyteorder("<"), copy=False)
        # The JSON header is self-delimiting, and dtype and shape fix the data length.
        header = json.dumps([name, values.dtype.str, list(values.shape)])
        digest.update(header.encode("utf-8") + b"\n")
        digest.update(values.tobytes(order="C"))
    return digest.hexdigest()


def write_variable(f: Any, name: str, values: NDArray[Any], units: str, long_name: str) -> Any:
    """Create one contiguous, uncompressed dataset at the root of an open file, with its CF attributes.

    Parameters
    ----------
    f : h5py.File
        The file being written.
    name : str
        Dataset name.
    values : ndarray
        Its data.
    units, long_name : str
        Its ``units`` and ``long_name`` attributes.

    Returns
    -------
    h5py.Dataset

    Examples
    --------
    >>> import io, h5py, numpy as np
    >>> with h5py.File(io.BytesIO(), "w") as f:
    ...     write_variable(f, "x", np.arange(3.0), "1", "x").attrs["units"]
    '1'
    """
    dset = f.create_dataset(name, data=values, track_times=False)
    dset.attrs["units"] = units
    dset.attrs["long_name"] = long_name
    return dset
