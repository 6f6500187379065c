"""Reading a table file into memory: verified bytes first, then every HDF5 object checked.

The file's bytes are read with plain reads and verified (:mod:`fastrest.tables.file`: regular file,
size, SHA-256 digest in the header) before HDF5 parses them from memory, first in a check process
unless the digest is trusted (:mod:`fastrest.tables.probe`: HDF5 can crash or hang on a hostile
file); every object is checked (datasets only, no links, no virtual or external storage, float64
or integer data inside the file, bounded attributes) before any array is allocated. The layout is
:mod:`fastrest.tables.hdf5`.
"""
from __future__ import annotations

from typing import Any
from dataclasses import replace
import itertools
import json
import math
import os

import h5py
import numpy as np

from .._version import __version__
from .file import TableFileError, read_verified
from .probe import check_image
from .hdf5 import CHECKSUM_ALGORITHM, FORMAT_NAME, FORMAT_VERSION, JSON_ATTRS_KEY, FileContents, checksum_arrays

__all__ = ["read_table", "parse_image", "walk_image"]

#: Most objects at the root, and attributes per object, a table file may have.
_MAX_OBJECTS = 1024
_MAX_ATTRS = 64
_IMAGE_IDS = itertools.count()


def read_table(path: str | os.PathLike[str]) -> FileContents:
    """Read a table file written by `write_table` into memory.

    The file is read with plain reads and verified (regular file, size, SHA-256 digest of its
    bytes, see :mod:`fastrest.tables.file`) before HDF5 parses it from memory, first in a check
    process unless its digest is trusted (:func:`fastrest.tables.probe.check_image`); then every
    object is checked (datasets only, no links, no virtual or external storage, float64 or integer
    data inside the file, bounded attributes) before any array is allocated.

    Parameters
    ----------
    path : str or os.PathLike
        The table file.

    Returns
    -------
    FileContents

    Raises
    ------
    TableFileError
        If the file does not exist, is not a regular file, is not a (complete) table file, fails
        its digest or its checks, is not a fastrest table, or has a newer format version than this
        fastrest reads, or makes HDF5 crash or hang in the check process. Nothing else: whatever a
        damaged or hostile file makes HDF5 or the checks raise becomes a TableFileError naming the file.

    Examples
    --------
    >>> from fastrest.tables import default_table_path
    >>> read_table(default_table_path()).attrs["format"]
    'fastrest-table'
    """
    path = os.fspath(path)
    data, digest = read_verified(path)
    # HDF5 reads the verified bytes from memory (the file on disk may change meanwhile), after a
    # check process parsed the same bytes, unless the digest is trusted (the shipped table's)
    check_image(data, digest, path)
    table = parse_image(data, path)
    stored = table.attrs.get("checksum")
    if not isinstance(stored, str):
        raise TableFileError(f"{path}: no (string) checksum attribute; the file is incomplete or "
                             "corrupted, rebuild the table")
    algorithm = table.attrs.get("checksum_algorithm")
    if algorithm != CHECKSUM_ALGORITHM:
        raise TableFileError(f"{path}: unknown checksum algorithm {algorithm!r}")
    computed = checksum_arrays({**table.axes, **table.datasets})
    if computed != stored:
        raise TableFileError(f"{path}: checksum mismatch (stored {stored}, computed "
                             f"{computed}); the file is corrupted, rebuild the table")
    return replace(table, digest=digest)


def _open_image(data):
    fapl = h5py.h5p.create(h5py.h5p.FILE_ACCESS)
    fapl.set_fapl_core(backing_store=False)
    fapl.set_file_image(data)
    name = f"fastrest-table-image-{next(_IMAGE_IDS)}".encode()
    return h5py.File(h5py.h5f.open(name, h5py.h5f.ACC_RDONLY, fapl=fapl))


def parse_image(data: bytes, path: str | os.PathLike[str]) -> FileContents:
    """Parse a table file's bytes with HDF5, from memory, checking every object before reading it.

    Parameters
    ----------
    data : bytes
        The whole file (header included), already verified against its digest.
    path : str
        The file (for messages).

    Returns
    -------
    FileContents
        Without ``digest``; the ``checksum`` attribute is not checked yet (:func:`read_table` does).

    Raises
    ------
    TableFileError
        Whatever the file makes HDF5, h5py or the structure checks raise, naming the file. (HDF5
        itself may crash or hang on a hostile file: :func:`read_table` runs this in a check process
        first, :mod:`fastrest.tables.probe`.)

    Examples
    --------
    >>> from fastrest.tables import default_table_path
    >>> from fastrest.tables.file import read_verified
    >>> data, _ = read_verified(default_table_path())
    >>> parse_image(data, "default.h5").dims["W_star"]
    ('eps_y', 'nu', 'omega_star')
    """
    try:
        with _open_image(data) as f:
            return _read_open_file(f, path, len(data))
    except TableFileError:
        raise
    except Exception as exc:  # anything a hostile file provokes in HDF5, h5py or the checks
        raise TableFileError(f"{path}: cannot be read as a table file (corrupted or not a fastrest "
                             f"table): {type(exc).__name__}: {exc}") from exc


def walk_image(data: bytes) -> Any:
    """Visit every object of a table file's bytes and read every attribute and dataset (the check
    process runs this after :func:`parse_image` accepted the bytes, which bounds every size).

    Parameters
    ----------
    data : bytes
        The whole file.

    Returns
    -------
    int
        The number of objects visited.

    Examples
    --------
    >>> from fastrest.tables import default_table_path
    >>> from fastrest.tables.file import read_verified
    >>> walk_image(read_verified(default_table_path())[0])
    45
    """
    seen = []

    def visit(name, obj):
        for key in obj.attrs:
            obj.attrs[key]
        if isinstance(obj, h5py.Dataset):
            obj[()]
        seen.append(name)

    with _open_image(data) as f:
        for key in f.attrs:
            f.attrs[key]
        f.visititems(visit)
    return len(seen)


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

    for key in json.loads(attrs.pop(JSON_ATTRS_KEY, "[]")):
        attrs[key] = json.loads(attrs[key])

    names = list(f)
    if len(names) > _MAX_OBJECTS:
        raise TableFileError(f"{path}: {len(names)} objects, more than a table holds ({_MAX_OBJECTS})")
    axes: dict[str, Any]
    datasets: dict[str, Any]
    units: dict[str, Any]
    long_names: dict[str, Any]
    dims: dict[str, Any]
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
    return FileContents(axes=axes, datasets=datasets, attrs=attrs, units=units, path=path,
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


def _plain(value):
    """Turn an HDF5 attribute value into a plain Python value (arrays stay arrays)."""
    if isinstance(value, bytes):
        return value.decode("utf-8")
    if isinstance(value, np.generic):
        return value.item()
    return value
