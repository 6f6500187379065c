"""Storage of precomputed tables in HDF5 files (no physics here).

Layout of a table file (format ``fastrest-table``, version 3)::

    bytes 0-511           the HDF5 user block: a text header with the file's size and the
                          SHA-256 digest of the bytes after it (see fastrest._tablefile)
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
full disk gives an OSError naming the file.
"""
from dataclasses import dataclass, field, replace
import hashlib
import io
import itertools
import json
import math
import os
import stat

import h5py
import numpy as np

from ._tablefile import USERBLOCK, TableFileError, read_verified, write_atomic
from ._version import __version__

__all__ = ["FORMAT_NAME", "FORMAT_VERSION", "TableData", "TableFileError", "read_table",
           "write_table"]

FORMAT_NAME = "fastrest-table"
FORMAT_VERSION = 3  # 2: two-level V1* cells; 3: header with digest, Lobatto nodes, unloading models list
#: Most objects at the root, and attributes per object, a table file may have.
_MAX_OBJECTS = 1024
_MAX_ATTRS = 64
_IMAGE_IDS = itertools.count()
_CHECKSUM_ALGORITHM = "sha256"
# Root attribute listing the attributes that hold JSON-encoded dicts, so that a
# caller's plain string that happens to look like JSON is never decoded by mistake.
_JSON_ATTRS_KEY = "json_attributes"
_RESERVED_ATTRS = {"format", "format_version", "fastrest_version", "checksum",
                   "checksum_algorithm", _JSON_ATTRS_KEY}


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
    digest : str
        SHA-256 hex digest of the file's bytes after its header (kept in the header).
    """

    axes: dict
    datasets: dict
    attrs: dict
    units: dict
    path: str
    dims: dict = field(default_factory=dict)
    long_names: dict = field(default_factory=dict)
    digest: str = ""


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
    """
    path = os.fspath(path)
    axes, datasets, attrs = _prepare(axes, datasets, attrs)
    arrays = {name: values for name, (values, _, _) in axes.items()}
    arrays.update({name: values for name, (values, _, _, _) in datasets.items()})
    attrs.update(format=FORMAT_NAME, format_version=FORMAT_VERSION,
                 fastrest_version=__version__, checksum=_checksum(arrays),
                 checksum_algorithm=_CHECKSUM_ALGORITHM)

    mode = _file_mode(path)
    # The whole file is built in memory and written by _tablefile: HDF5 never sees a write error
    # (h5py closing a file after a failed write, e.g. on a full disk, segfaulted).
    buffer = io.BytesIO()
    with h5py.File(buffer, "w", userblock_size=USERBLOCK) as f:
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
    write_atomic(path, buffer.getbuffer(), mode)


def read_table(path):
    """Read a table file written by `write_table` into memory.

    The file is read with plain reads and verified (regular file, size, SHA-256 digest of its
    bytes, see :mod:`fastrest._tablefile`) before HDF5 parses it from memory; then every object is
    checked (datasets only, no links, no virtual or external storage, float64 or integer data
    inside the file, bounded attributes) before any array is allocated.

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
        If the file does not exist, is not a regular file, is not a (complete) table file, fails
        its digest or its checks, is not a fastrest table, or has a newer format version than this
        fastrest reads. Nothing else: whatever a damaged or hostile file makes HDF5 or the checks
        raise becomes a TableFileError naming the file.
    """
    path = os.fspath(path)
    data, digest = read_verified(path)
    try:
        # HDF5 reads the verified bytes from memory: the file on disk may change meanwhile.
        fapl = h5py.h5p.create(h5py.h5p.FILE_ACCESS)
        fapl.set_fapl_core(backing_store=False)
        fapl.set_file_image(data)
        name = f"fastrest-table-image-{next(_IMAGE_IDS)}".encode()
        with h5py.File(h5py.h5f.open(name, h5py.h5f.ACC_RDONLY, fapl=fapl)) as f:
            table = _read_open_file(f, path, len(data))
    except TableFileError:
        raise
    except Exception as exc:  # anything a hostile file provokes in HDF5, h5py or the checks
        raise TableFileError(f"{path}: cannot be read as a table file (corrupted or not a fastrest "
                             f"table): {type(exc).__name__}: {exc}") from exc

    stored = table.attrs.get("checksum")
    if not isinstance(stored, str):
        raise TableFileError(f"{path}: no (string) checksum attribute; the file is incomplete or "
                             "corrupted, rebuild the table")
    algorithm = table.attrs.get("checksum_algorithm")
    if algorithm != _CHECKSUM_ALGORITHM:
        raise TableFileError(f"{path}: unknown checksum algorithm {algorithm!r}")
    computed = _checksum({**table.axes, **table.datasets})
    if computed != stored:
        raise TableFileError(f"{path}: checksum mismatch (stored {stored}, computed "
                             f"{computed}); the file is corrupted, rebuild the table")
    return replace(table, digest=digest)


def _read_open_file(f, path, limit):
    """Check the format attributes and every object of an open file, then read its contents.

    ``limit``: the file's size in bytes; nothing declaring more data than that is read.
    """
    attrs = {key: _plain(value) for key, value in _checked_attrs(f, path, limit, "the root group")}
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

    names = list(f)
    if len(names) > _MAX_OBJECTS:
        raise TableFileError(f"{path}: {len(names)} objects, more than a table holds ({_MAX_OBJECTS})")
    axes, datasets, units, long_names, dims = {}, {}, {}, {}, {}
    for name in names:
        obj = _checked_dataset(f, name, path, limit)
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


def _checked_attrs(obj, path, limit, where):
    """(name, value) of every attribute of ``obj``, each checked to declare at most ``limit``
    bytes before it is read."""
    names = list(obj.attrs)
    if len(names) > _MAX_ATTRS:
        raise TableFileError(f"{path}: {where} has {len(names)} attributes, more than a table "
                             f"holds ({_MAX_ATTRS})")
    out = []
    for name in names:
        aid = obj.attrs.get_id(name)
        if math.prod(aid.shape or ()) * aid.dtype.itemsize > limit:
            raise TableFileError(f"{path}: attribute {name!r} of {where} declares shape {aid.shape}, "
                                 "more data than the file holds")
        out.append((name, obj.attrs[name]))
    return out


def _checked_dataset(f, name, path, limit):
    """The dataset ``name`` after checking that it is a plain array stored inside the file."""
    link = f.get(name, getlink=True)
    if not isinstance(link, h5py.HardLink):
        kind = "an external link" if isinstance(link, h5py.ExternalLink) else "a soft link"
        raise TableFileError(f"{path}: {name!r} is {kind}; a table file holds only datasets")
    obj = f[name]
    if not isinstance(obj, h5py.Dataset):
        raise TableFileError(f"{path}: {name!r} is a {type(obj).__name__}; a table file holds "
                             "only datasets")
    dt = obj.dtype
    if not (dt.kind in "iuf" and dt.names is None and dt.shape == () and dt.itemsize <= 8
            and (dt.kind != "f" or dt.itemsize == 8) and h5py.check_enum_dtype(dt) is None):
        raise TableFileError(f"{path}: dataset {name!r} has data type {dt}; a table file holds "
                             "float64 and integer arrays only")
    plist = obj.id.get_create_plist()
    layout = plist.get_layout()
    if layout == h5py.h5d.VIRTUAL:
        raise TableFileError(f"{path}: dataset {name!r} is a virtual dataset (data from other "
                             "files); refused")
    if plist.get_external_count():
        raise TableFileError(f"{path}: dataset {name!r} keeps its data in external files; refused")
    if layout != h5py.h5d.CONTIGUOUS or plist.get_nfilters():
        raise TableFileError(f"{path}: dataset {name!r} is not stored contiguously and "
                             "uncompressed, as fastrest writes it")
    nbytes = math.prod(obj.shape or ()) * dt.itemsize
    offset, stored = obj.id.get_offset(), obj.id.get_storage_size()
    if nbytes and (offset is None or stored != nbytes or not 0 <= offset <= limit - nbytes):
        raise TableFileError(f"{path}: dataset {name!r} declares shape {obj.shape} ({nbytes} "
                             f"bytes) but its data is not inside the file")
    _checked_attrs(obj, path, limit, f"dataset {name!r}")
    return obj


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
