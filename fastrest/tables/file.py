"""The bytes of a table file: written atomically, verified before HDF5 parses them (no HDF5 here).

A table file is an HDF5 file with a 512-byte user block (HDF5 skips it) that holds a short text
header::

    fastrest-table-file 1
    size <total length of the file in bytes>
    sha256 <hex digest of every byte after the user block>

and zero bytes up to offset 512. :func:`read_verified` reads a file with plain reads, refusing
anything that is not a regular file of bounded size, and checks the size and the digest before any
byte reaches HDF5: the HDF5 library can crash (double free, segfault) or hang on damaged metadata,
so damaged files must never get that far. The writer builds the whole file in memory and writes
the bytes itself (:func:`write_atomic`), so HDF5 never sees a write error (after a failed write,
h5py closing the file segfaulted on a full disk).
"""
import errno
import hashlib
import os
import stat
import tempfile

__all__ = ["MAX_FILE_BYTES", "USERBLOCK", "TableFileError", "check_target", "header",
           "read_verified", "write_atomic"]

#: Size of the HDF5 user block holding the header (HDF5's smallest).
USERBLOCK = 512
#: Largest table file read (bytes): the whole file is read into memory before it is parsed. The
#: shipped table is ~6 MiB; a grid 100 times larger still fits.
MAX_FILE_BYTES = 1 << 30
_MAGIC = b"fastrest-table-file 1\n"
_HDF5_SIGNATURE = b"\x89HDF\r\n\x1a\n"
#: Bytes per read and write call (tests make it small to provoke short writes).
CHUNK_BYTES = 1 << 20


class TableFileError(ValueError):
    """A table file is missing, truncated, corrupted, foreign, hostile, special (a FIFO, device or
    directory) or of another format version.

    A ValueError (``fastrest.TableFileError``); the message names the file and the problem. It is
    the only exception reading a table file raises.

    Examples
    --------
    >>> import fastrest
    >>> try:
    ...     fastrest.load_table("/nonexistent/t.h5")
    ... except fastrest.TableFileError as exc:
    ...     print(exc)
    /nonexistent/t.h5: table file does not exist
    """


def header(body_digest, size):
    """The 512-byte user block of a table file (docs/table-format.md, section 1.0).

    Parameters
    ----------
    body_digest : str
        SHA-256 hex digest of the file's bytes after the user block.
    size : int
        The file's total length in bytes.

    Returns
    -------
    bytes
        The text header padded with zero bytes to :data:`USERBLOCK`.

    Examples
    --------
    >>> header("0" * 64, 1000)[:26]
    b'fastrest-table-file 1\\nsize'
    """
    text = _MAGIC + f"size {size}\nsha256 {body_digest}\n".encode("ascii")
    return text + bytes(USERBLOCK - len(text))


def _kind(mode):
    for test, name in ((stat.S_ISDIR, "a directory"), (stat.S_ISFIFO, "a FIFO (named pipe)"),
                       (stat.S_ISCHR, "a character device"), (stat.S_ISBLK, "a block device"),
                       (stat.S_ISSOCK, "a socket")):
        if test(mode):
            return name
    return "not a regular file"


def _check_regular(st, path):
    if not stat.S_ISREG(st.st_mode):
        raise TableFileError(f"{path}: is {_kind(st.st_mode)}, not a table file")
    if st.st_size > MAX_FILE_BYTES:
        raise TableFileError(f"{path}: {st.st_size} bytes, larger than the {MAX_FILE_BYTES} bytes a "
                             "table file may have; not a fastrest table (or a damaged one)")


def read_verified(path):
    """The bytes of a table file after checking its header, size and SHA-256 digest.

    Parameters
    ----------
    path : str
        The file; a symbolic link is followed, but only to a regular file.

    Returns
    -------
    data : bytes
        The whole file (user block included), safe to hand to HDF5 as a file image.
    digest : str
        The verified SHA-256 hex digest of the bytes after the user block.

    Raises
    ------
    TableFileError
        Missing or unreadable file, not a regular file (FIFO, device, directory: refused without
        opening it for blocking reads), larger than :data:`MAX_FILE_BYTES`, no fastrest header
        (a foreign file, or a table written by fastrest before format version 3), or a size or
        digest that does not match (truncated or corrupted).

    Examples
    --------
    >>> from fastrest.tables import default_table_path
    >>> data, digest = read_verified(default_table_path())
    >>> data[512:516]
    b'\\x89HDF'
    """
    try:
        _check_regular(os.stat(path), path)
        # O_NONBLOCK: a FIFO swapped in after the stat must not block the open.
        fd = os.open(path, os.O_RDONLY | getattr(os, "O_NONBLOCK", 0) | getattr(os, "O_BINARY", 0)
                     | getattr(os, "O_CLOEXEC", 0))
    except FileNotFoundError:
        raise TableFileError(f"{path}: table file does not exist") from None
    except OSError as exc:
        raise TableFileError(f"{path}: cannot open the table file ({exc.strerror})") from None
    try:
        st = os.fstat(fd)
        _check_regular(st, path)
        parts, left = [], st.st_size
        while left > 0:
            part = os.read(fd, min(left, CHUNK_BYTES))
            if not part:
                break
            parts.append(part)
            left -= len(part)
    except OSError as exc:
        raise TableFileError(f"{path}: cannot read the table file ({exc.strerror})") from None
    finally:
        os.close(fd)
    data = b"".join(parts)
    return data, _check_header(data, path)


def _check_header(data, path):
    rebuild = "rebuild it with `fastrest build` (`fastrest build --default` for the shipped table)"
    if data[:8] == _HDF5_SIGNATURE:
        raise TableFileError(f"{path}: HDF5 file without a fastrest header: written by another program, "
                             f"or by a fastrest older than table format version 3; {rebuild}")
    if not data.startswith(_MAGIC):
        if len(data) < len(_MAGIC) and _MAGIC.startswith(data):
            raise TableFileError(f"{path}: truncated table file ({len(data)} bytes); {rebuild}")
        raise TableFileError(f"{path}: not a fastrest table file (no fastrest header)")
    block = data[:USERBLOCK]
    text, _, pad = block.partition(b"\0")
    lines = text[len(_MAGIC):].split(b"\n")
    try:
        if len(block) < USERBLOCK or pad.strip(b"\0") or len(lines) != 3 or lines[2]:
            raise ValueError
        (k1, size), (k2, digest) = (line.decode("ascii").split(" ") for line in lines[:2])
        if (k1, k2) != ("size", "sha256") or not size.isdigit() or len(digest) != 64:
            raise ValueError
        size = int(size)
    except ValueError:
        raise TableFileError(f"{path}: damaged fastrest header (the first {USERBLOCK} bytes); "
                             f"{rebuild}") from None
    if size != len(data):
        raise TableFileError(f"{path}: {len(data)} bytes where the header says {size}: the file is "
                             f"truncated or was appended to; {rebuild}")
    computed = hashlib.sha256(memoryview(data)[USERBLOCK:]).hexdigest()
    if computed != digest:
        raise TableFileError(f"{path}: SHA-256 digest mismatch (header {digest}, file {computed}): "
                             f"the file is corrupted; {rebuild}")
    return digest


def _os_error(exc, path, what):
    """An OSError of the same kind (errno) whose message names the table file."""
    reason = exc.strerror or str(exc)
    return OSError(exc.errno, f"cannot {what} table file {os.fspath(path)!r}: {reason}")


def _check_existing(path):
    try:
        st = os.stat(path)
    except FileNotFoundError:
        return
    except OSError as exc:
        raise _os_error(exc, path, "write the") from None
    if not stat.S_ISREG(st.st_mode):
        code = errno.EISDIR if stat.S_ISDIR(st.st_mode) else errno.EEXIST
        raise OSError(code, f"cannot write the table file {path!r}: it is {_kind(st.st_mode)}; give a file name")


def check_target(path):
    """Refuse, before a long build, a target that cannot be written.

    Parameters
    ----------
    path : str or path-like
        The table file to be written.

    Raises
    ------
    OSError
        Naming the path, if it is an existing directory or special file (a table never replaces a
        device or FIFO), or if no file can be created in its directory (missing, read-only file
        system, no permission).

    Examples
    --------
    >>> import tempfile, os
    >>> with tempfile.TemporaryDirectory() as d:
    ...     check_target(os.path.join(d, "t.h5"))   # writable: no error, nothing left behind
    ...     os.listdir(d)
    []
    """
    path = os.fspath(path)
    _check_existing(path)
    try:
        fd, tmp = tempfile.mkstemp(dir=os.path.dirname(os.path.abspath(path)), suffix=".probe")
    except OSError as exc:
        raise _os_error(exc, path, "write the") from None
    os.close(fd)
    os.remove(tmp)


def write_atomic(path, image, mode):
    """Write a table file's bytes to a temporary file beside ``path``, fsync and rename over it.

    Parameters
    ----------
    path : str or path-like
        The target file.
    image : writable buffer
        The whole file; its first :data:`USERBLOCK` bytes (HDF5's user block) are overwritten with
        the :func:`header`.
    mode : int
        Permission bits of the new file.

    Returns
    -------
    str
        The SHA-256 hex digest written into the header.

    Raises
    ------
    OSError
        Naming ``path``, on any failure (disk full, I/O error); the temporary file is removed and
        the old file is untouched.

    Examples
    --------
    >>> import tempfile, os
    >>> with tempfile.TemporaryDirectory() as d:
    ...     p = os.path.join(d, "t.bin")
    ...     digest = write_atomic(p, bytearray(USERBLOCK + 8), 0o644)
    ...     data, digest = read_verified(p)
    >>> len(data)
    520
    """
    path = os.fspath(path)
    view = memoryview(image)
    digest = hashlib.sha256(view[USERBLOCK:]).hexdigest()
    view[:USERBLOCK] = header(digest, len(view))
    _check_existing(path)
    try:
        fd, tmp = tempfile.mkstemp(dir=os.path.dirname(os.path.abspath(path)), suffix=".tmp")
    except OSError as exc:
        raise _os_error(exc, path, "write the") from None
    try:
        try:
            pos = 0
            while pos < len(view):
                pos += os.write(fd, view[pos:pos + CHUNK_BYTES])
            # Make the data durable before the rename makes it visible.
            os.fsync(fd)
        finally:
            os.close(fd)
        os.chmod(tmp, mode)
        os.replace(tmp, path)
        return digest
    except BaseException as exc:
        try:
            os.remove(tmp)
        except OSError:
            pass
        if isinstance(exc, OSError):
            raise _os_error(exc, path, "write the") from None
        raise
