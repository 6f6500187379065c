"""Storage of precomputed tables in HDF5 files (no physics here).

Layout of a table file (format ``fastrest-table``, version 1)::

    /                     root attributes: format, format_version, fastrest_version,
                          checksum, checksum_algorithm, plus the caller's attributes
    /<axis>               1-D float64 dimension scale named after the axis;
                          attributes units, long_name
    /<dataset>            float64 (or integer) array, contiguous and uncompressed,
                          its dimensions attached to the axis scales; attributes units, long_name

Every axis is an HDF5 dimension scale named exactly like its dataset, so
``xarray.open_dataset(path, engine="h5netcdf")`` shows named coordinates and
``h5dump -H`` shows the structure. The checksum is a SHA-256 over the names, dtypes,
shapes and bytes of all arrays, so a reader detects damaged data without trusting HDF5.

Files are written to a temporary file beside the target and renamed over it, so a reader
sees either the old table or the new one, never a half-written file.
"""
from dataclasses import dataclass, field
import hashlib
import json
import os
import stat
import tempfile

import h5py
import numpy as np

from ._version import __version__

__all__ = ["FORMAT_NAME", "FORMAT_VERSION", "TableData", "TableFileError", "read_table",
           "write_table"]

FORMAT_NAME = "fastrest-table"
FORMAT_VERSION = 3  # 2: two-level V1* cells (finer just above the kink); 3: Lobatto nodes, unloading models list
_CHECKSUM_ALGORITHM = "sha256"
# Root attribute listing the attributes that hold JSON-encoded dicts, so that a
# caller's plain string that happens to look like JSON is never decoded by mistake.
_JSON_ATTRS_KEY = "json_attributes"
_RESERVED_ATTRS = {"format", "format_version", "fastrest_version", "checksum",
                   "checksum_algorithm", _JSON_ATTRS_KEY}


class TableFileError(ValueError):
    """A table file is missing, truncated, corrupted, foreign or of a newer format.

    The message names the file and the problem.
    """


@dataclass(frozen=True)
class TableData:
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
    """

    axes: dict
    datasets: dict
    attrs: dict
    units: dict
    path: str
    dims: dict = field(default_factory=dict)
    long_names: dict = field(default_factory=dict)


def write_table(path, axes, datasets, attrs):
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

    Raises
    ------
    TypeError, ValueError
        If the inputs cannot be stored; nothing is written then.

    Notes
    -----
    The table is written to ``tempfile.mkstemp(dir=<target directory>, suffix=".tmp")``,
    flushed to disk and renamed over the target with `os.replace`. If writing raises, the
    temporary file is removed and the target is untouched. If the process is killed while
    writing, the target is also untouched but a stray ``*.tmp`` file may remain in the
    directory; it is never mistaken for a table and can be deleted.

    The same content always gives a byte-identical file: h5py writes no timestamps and
    everything is written in sorted name order.
    """
    path = os.fspath(path)
    axes, datasets, attrs = _prepare(axes, datasets, attrs)
    arrays = {name: values for name, (values, _, _) in axes.items()}
    arrays.update({name: values for name, (values, _, _, _) in datasets.items()})
    attrs.update(format=FORMAT_NAME, format_version=FORMAT_VERSION,
                 fastrest_version=__version__, checksum=_checksum(arrays),
                 checksum_algorithm=_CHECKSUM_ALGORITHM)

    mode = _file_mode(path)
    fd, tmp = tempfile.mkstemp(dir=os.path.dirname(os.path.abspath(path)), suffix=".tmp")
    os.close(fd)
    try:
        # locking=False: HDF5 file locking fails on some network file systems, and the
        # temporary file is ours alone.
        with h5py.File(tmp, "w", locking=False) as f:
            scales = {}
            for name in sorted(axes):
                values, units, long_name = axes[name]
                scales[name] = _write_variable(f, name, values, units, long_name)
                scales[name].make_scale(name)
            for name in sorted(datasets):
                values, dims, units, long_name = datasets[name]
                dset = _write_variable(f, name, values, units, long_name)
                for i, axis in enumerate(dims):
                    dset.dims[i].attach_scale(scales[axis])
            for key in sorted(attrs):
                f.attrs[key] = attrs[key]
            f.flush()
        # Make the data durable before the rename makes it visible.
        with open(tmp, "r+b") as fh:
            os.fsync(fh.fileno())
        os.chmod(tmp, mode)
        os.replace(tmp, path)
    except BaseException:
        try:
            os.remove(tmp)
        except OSError:
            pass
        raise


def read_table(path):
    """Read a table file written by `write_table` into memory.

    The file is opened once, read completely into NumPy arrays and closed.

    Parameters
    ----------
    path : str or os.PathLike
        The table file.

    Returns
    -------
    TableData

    Raises
    ------
    TableFileError
        If the file does not exist, is not a (complete) HDF5 file, is not a fastrest table,
        has a newer format version than this fastrest reads, or fails its integrity checks
        (missing axis, missing or mismatching checksum).
    """
    path = os.fspath(path)
    if not os.path.exists(path):
        raise TableFileError(f"{path}: table file does not exist")
    try:
        # locking=False: HDF5 file locking fails on some network file systems; files are
        # replaced atomically, so a reader never sees one being written.
        with h5py.File(path, "r", locking=False) as f:
            table = _read_open_file(f, path)
    except TableFileError:
        raise
    except (OSError, KeyError, RuntimeError, ValueError, TypeError) as exc:
        raise TableFileError(f"{path}: cannot be read as HDF5 (not an HDF5 file, or "
                             f"truncated or corrupted): {exc}") from exc

    stored = table.attrs.get("checksum")
    if not isinstance(stored, str):
        raise TableFileError(f"{path}: no checksum attribute; the file is incomplete or "
                             "corrupted, rebuild the table")
    algorithm = table.attrs.get("checksum_algorithm")
    if algorithm != _CHECKSUM_ALGORITHM:
        raise TableFileError(f"{path}: unknown checksum algorithm {algorithm!r}")
    computed = _checksum({**table.axes, **table.datasets})
    if computed != stored:
        raise TableFileError(f"{path}: checksum mismatch (stored {stored}, computed "
                             f"{computed}); the file is corrupted, rebuild the table")
    return table


def _read_open_file(f, path):
    """Check the format attributes of an open file and read its contents."""
    attrs = {key: _plain(value) for key, value in f.attrs.items()}
    if attrs.get("format") != FORMAT_NAME:
        raise TableFileError(f"{path}: not a fastrest table (HDF5 file without the root "
                             f"attribute format={FORMAT_NAME!r})")
    version = attrs.get("format_version")
    if not isinstance(version, int) or version < 1:
        raise TableFileError(f"{path}: invalid table format_version {version!r}")
    if version > FORMAT_VERSION:
        raise TableFileError(
            f"{path}: table has format version {version}, but this fastrest "
            f"({__version__}) reads format version {FORMAT_VERSION} and older; upgrade "
            "fastrest or rebuild the table with this version")

    for key in json.loads(attrs.pop(_JSON_ATTRS_KEY, "[]")):
        attrs[key] = json.loads(attrs[key])

    axes, datasets, units, long_names, dims = {}, {}, {}, {}, {}
    for name, obj in f.items():
        if not isinstance(obj, h5py.Dataset):
            continue  # not part of format version 1; tolerated
        values = np.asarray(obj[()])
        (axes if h5py.h5ds.is_scale(obj.id) else datasets)[name] = values
        units[name] = _plain(obj.attrs.get("units", ""))
        long_names[name] = _plain(obj.attrs.get("long_name", ""))

    for name, values in datasets.items():
        dims[name] = tuple(_dim_axis(f[name], i, axes, path) for i in range(values.ndim))
        for i, axis in enumerate(dims[name]):
            if axes[axis].shape != (values.shape[i],):
                raise TableFileError(f"{path}: dimension {i} of dataset {name!r} has length "
                                     f"{values.shape[i]} but axis {axis!r} has shape "
                                     f"{axes[axis].shape}")
    return TableData(axes=axes, datasets=datasets, attrs=attrs, units=units, path=path,
                     dims=dims, long_names=long_names)


def _dim_axis(dset, i, axes, path):
    """Name of the axis attached to dimension ``i`` of ``dset``, checked to exist."""
    scales = dset.dims[i].values()
    # A deleted axis survives as an anonymous object (name None) while referenced.
    names = [(scale.name or "").lstrip("/") for scale in scales]
    if len(names) != 1 or names[0] not in axes:
        raise TableFileError(f"{path}: dimension {i} of dataset {dset.name.lstrip('/')!r} "
                             f"refers to a missing axis (attached: {names})")
    return names[0]


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
        out_attrs[_JSON_ATTRS_KEY] = json.dumps(sorted(json_keys))
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


def _plain(value):
    """Turn an HDF5 attribute value into a plain Python value (arrays stay arrays)."""
    if isinstance(value, bytes):
        return value.decode("utf-8")
    if isinstance(value, np.generic):
        return value.item()
    return value


def _checksum(arrays):
    """SHA-256 hex digest over the name, dtype, shape and bytes of every array.

    Arrays are taken in sorted name order and in little-endian C order, so the digest does
    not depend on the platform or on how the arrays are laid out in memory or in the file.
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


def _write_variable(f, name, values, units, long_name):
    """Create one contiguous, uncompressed dataset at the root with its CF attributes."""
    dset = f.create_dataset(name, data=values, track_times=False)
    dset.attrs["units"] = units
    dset.attrs["long_name"] = long_name
    return dset


def _file_mode(path):
    """Permissions for the new file: those of the file it replaces, else 0o666 - umask."""
    # mkstemp creates files readable by the owner only; a shared table must not be.
    try:
        return stat.S_IMODE(os.stat(path).st_mode)
    except FileNotFoundError:
        umask = os.umask(0)
        os.umask(umask)
        return 0o666 & ~umask
