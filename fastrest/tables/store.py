"""Table files in use: the shipped default table, the user cache, building, reading and the
per-process registry of loaded tables."""
from __future__ import annotations

from typing import Any
import os
from pathlib import Path

from .._validation import check_tol, warn
from .._deprecation import keyword_only
from . import error
from .accuracy import warn_if_inaccurate
from .file import TableFileError, check_path, check_target, replace_files
from .generation import generate
from .grid import grid_key, normalise_grid
from .schema import read_generated, write_generated
from .table import Table

__all__ = ["LOADED", "default_table_path", "source_tree_table_path", "cache_dir", "read", "build",
           "load_table", "cached_table", "forget"]

#: Tables loaded in this process (documented internal; tests empty it): None (the shipped table)
#: or a resolved path -> (file identity (st_dev, st_ino, st_mtime_ns, st_size) or None, Table).
LOADED: dict[Any, Any] = {}
_HERE = Path(__file__).resolve().parent


def default_table_path() -> Path:
    """The shipped default table, ``fastrest/tables/default.h5`` (package data).

    Returns
    -------
    pathlib.Path

    Raises
    ------
    FileNotFoundError
        The file is missing (a broken installation, or a checkout where it was deleted): rebuild
        it with ``fastrest build --default``.

    Examples
    --------
    >>> from fastrest.tables import default_table_path
    >>> default_table_path().name
    'default.h5'
    """
    p = _HERE / "default.h5"
    if not p.exists():
        raise FileNotFoundError(f"fastrest's default table {str(p)!r} is missing; rebuild it with "
                                "`fastrest build --default`")
    return p


def source_tree_table_path() -> Path | None:
    """Where ``fastrest build --default`` writes.

    Returns
    -------
    pathlib.Path or None
        The shipped table's place in the source checkout this fastrest runs from
        (``fastrest/tables/default.h5`` beside ``pyproject.toml``), or None when fastrest is
        installed without one (from a wheel: then give ``--out``).

    Examples
    --------
    >>> p = source_tree_table_path()
    >>> p is None or p.name == "default.h5"
    True
    """
    root = _HERE.parent.parent
    if (root / "pyproject.toml").is_file() and (root / "fastrest" / "tables") == _HERE:
        return _HERE / "default.h5"
    return None


def cache_dir() -> Path:
    """The user cache for tables of other grids.

    Returns
    -------
    pathlib.Path
        ``$FASTREST_CACHE_DIR`` if set, else ``$XDG_CACHE_HOME/fastrest`` (default
        ``~/.cache/fastrest``); it may not exist yet.

    Examples
    --------
    >>> from fastrest.tables import cache_dir
    >>> cache_dir().name != ""
    True
    """
    d = os.environ.get("FASTREST_CACHE_DIR")
    if not d:
        d = os.path.join(os.environ.get("XDG_CACHE_HOME", os.path.expanduser("~/.cache")), "fastrest")
    return Path(d)


def _check_tol(tol):
    return check_tol(tol, 1e-14, "the relative error asked of the table")


def read(path: str | os.PathLike[str]) -> Table:
    """Read a table file into a new :class:`Table` (no registry: see :func:`load_table`).

    Parameters
    ----------
    path : str or path-like
        A table file written by ``fastrest build``.

    Returns
    -------
    Table
        A new table, read from the file at each call.

    Raises
    ------
    TableFileError
        A missing, special, truncated, corrupted, foreign, hostile or other-version file; the message
        names the file and the problem. Nothing else: the file is verified (size, SHA-256 digest)
        before HDF5 parses it, then every dataset's dtype, shape and finiteness against the grid
        attributes before anything sized by them is allocated (docs/table-format.md).

    Examples
    --------
    >>> from fastrest.tables import default_table_path, read
    >>> read(default_table_path()).grid["n_nu"]
    8
    """
    path = check_path(path)
    gen, attrs = read_generated(path)
    return Table(gen, attrs=attrs, path=path)


def forget(path: str | os.PathLike[str] | None = None) -> None:
    """Drop the registry's entries for a file, so that the next :func:`load_table` reads it again.

    Parameters
    ----------
    path : str or path-like, optional
        The file; None: the shipped table. :func:`build` calls this for the file it writes.

    Examples
    --------
    >>> import fastrest
    >>> t = fastrest.load_table()
    >>> forget()
    >>> fastrest.load_table() is t
    False
    """
    target = Path(_resolved(path) if path is not None else _HERE / "default.h5").resolve()
    LOADED.pop(str(target), None)
    if target == (_HERE / "default.h5").resolve():
        LOADED.pop(None, None)


def _identity(path):
    try:
        st = os.stat(path)
    except OSError:
        return None
    return st.st_dev, st.st_ino, st.st_mtime_ns, st.st_size


def _resolved(path):
    """The registry key of a table file: its resolved path; TableFileError if it has none."""
    path = check_path(path)
    if "\0" in path:
        raise TableFileError(f"{path!r}: a file name cannot hold a NUL byte")
    try:
        return str(Path(path).resolve())
    except (OSError, RuntimeError) as exc:  # RuntimeError: a symbolic link loop (Python < 3.13)
        raise TableFileError(f"{path}: cannot resolve the table file's path ({exc})") from None


@keyword_only("tol")
def load_table(path: str | os.PathLike[str] | None = None, *, tol: float | None = None) -> Table:
    """Load a restitution table once per process and return it.

    The file is read into NumPy arrays and closed; later calls with the same path return the same
    :class:`Table` without reading the file again, unless the file was replaced (another inode,
    modification time or size) or rewritten by :func:`build`.

    Parameters
    ----------
    path : str or path-like, optional
        A table file written by ``fastrest build``. Default: the shipped table
        (0.0005 <= eps_y <= 0.01, 0.2 <= nu <= 0.45, up to w_m* = 425).
    tol : float, optional
        The accuracy the caller needs (relative; see :mod:`fastrest.tables.error`), in [1e-14, 1);
        keyword-only (positional: deprecated).

    Returns
    -------
    Table
        The process's one table of that file: the same object for every call while the file is
        unchanged.

    Raises
    ------
    TableFileError
        The file is missing, truncated, corrupted (digest, checksum), not a fastrest table, or of an
        older or newer format version, or its name cannot be resolved (a NUL byte, a loop of
        symbolic links); the message names the file and what is wrong.
    TypeError
        ``path`` is not a str or path-like object.
    ValueError
        ``tol`` outside [1e-14, 1).

    Warns
    -----
    AccuracyWarning
        The file's measured error exceeds ``tol`` (or, without ``tol``, 1e-9 when first read).

    Examples
    --------
    >>> import fastrest
    >>> fastrest.load_table() is fastrest.load_table()
    True
    """
    return _load_table(path, tol)


def _load_table(path=None, tol=None):
    """:func:`load_table` without the check for a positional ``tol`` (the default table's functions
    call it on every evaluation)."""
    if tol is not None:
        tol = _check_tol(tol)
    if path is None:
        key, ident = None, None
    else:
        key = _resolved(path)
        ident = _identity(key)
    entry = LOADED.get(key)
    if entry is None or entry[0] != ident:
        table = read(default_table_path() if path is None else path)
        LOADED[key] = entry = (ident, table)
        if tol is None:
            warn_if_inaccurate(table.attrs.get("measured_error"), None, f"table {table.path}")
    table = entry[1]
    if tol is not None:
        warn_if_inaccurate(table.attrs.get("measured_error"), tol, f"table {table.path}")
    return table


@keyword_only("progress", "measure", "tol")
def build(path: str | os.PathLike[str] | None = None, grid: dict[str, Any] | None = None, *, progress: Any = None, measure: bool = True,
          tol: float | None = None) -> Table:
    """Generate a table, measure its error against the direct solver, write it; return the Table.

    Parameters
    ----------
    path : str or path-like, optional
        The file to write (replaced atomically). None: the user cache (:func:`cache_dir`) under
        :func:`grid_key`.
    grid : dict, optional
        Grid specification (:func:`normalise_grid`); None: the shipped table's.
    progress : None or bool
        None: a progress bar if on a terminal (tqdm); False: none.
    measure : bool
        Measure the error against the direct solver and store it in the file (``measured_error``).
    tol : float, optional
        Refine the grid's node counts until the measured error meets ``tol``
        (:func:`fastrest.tables.error.build_to_tolerance`), in [1e-14, 1).

    Returns
    -------
    Table
        The new table; ``attrs["measured_error"]`` holds the errors, ``path`` the file.

    Raises
    ------
    TypeError, ValueError
        A bad grid or ``tol``; ``tol`` not reached in the allowed refinements (the message names the
        error reached and what to change); a ``path`` that is not a file name.
    OSError
        The file cannot be written (a directory, FIFO or device: never replaced; a read-only or
        full file system), naming the file; checked before the generation where it can be; an
        existing file is then unchanged.

    Warns
    -----
    AccuracyWarning
        Without ``tol``, a table whose measured error exceeds 1e-9 (it is written all the same).

    Notes
    -----
    ``build(path)`` with the same grid gives the same bytes on every machine (docs/table-format.md).
    Building the shipped table's file (``fastrest build --default``) also records its digest in
    ``fastrest/tables/_default_digest.py``: commit both.

    Examples
    --------
    >>> import tempfile, os
    >>> from fastrest.tables import build
    >>> grid = dict(eps_y_min=0.004, eps_y_max=0.006, n_eps_y=6, nu_min=0.3, nu_max=0.35, n_nu=6,
    ...             bits_per_octave=1, eps_y_blocks=[], n_eps_y_energy=6)
    >>> with tempfile.TemporaryDirectory() as d:
    ...     t = build(os.path.join(d, "t.h5"), grid, progress=False, measure=False)
    >>> t.grid["n_eps_y"]
    6
    """
    g = normalise_grid(grid)
    if tol is not None:
        tol = _check_tol(tol)
    if path is None:
        path = cache_dir() / f"{grid_key(g)}.h5"
    path = Path(check_target(path, "path", "the table file", parents=True))  # before the long build
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise OSError(exc.errno, f"cannot create the directory of table file {str(path)!r}: "
                                 f"{exc.strerror}") from None
    if tol is not None:
        gen, table, errors, _ = error.build_to_tolerance(g, tol, progress=progress)
    else:
        gen = generate(g, progress=progress)
        table = Table(gen)
        errors = table.measure_error() if measure else None
        if errors is not None:
            error.warn_if_inaccurate(errors, None, "fastrest.tables.build")
    digest = write_generated(gen, path, errors)
    if path.resolve() == (_HERE / "default.h5").resolve():
        _record_default_digest(digest)
    forget(path)
    table.attrs = {"measured_error": errors} if errors else {}
    table.path = str(path)
    return table


def _record_default_digest(digest):
    """Write the shipped table's digest into the package (``fastrest build --default``): the one
    table file fastrest parses without a check process (:mod:`fastrest.tables.probe`)."""
    text = ('"""The SHA-256 digest of the shipped table\'s bytes after its header (fastrest/tables/default.h5).\n\n'
            "Written by `fastrest build --default` (do not edit): fastrest parses the shipped table in-process\n"
            "only while its digest is this one; any other table file is parsed in a check process first\n"
            '(fastrest.tables.probe)."""\n'
            f"#: Hex digest (docs/table-format.md, section 1.0).\nSHA256 = {digest!r}\n")
    replace_files({_HERE / "_default_digest.py": text.encode("ascii")}, what="the default table's digest file")


@keyword_only("progress", "tol")
def cached_table(grid: dict[str, Any] | None = None, *, progress: Any = None, tol: float | None = None) -> Table:
    """A table for any grid: the shipped one if it matches, else the user cache, built on first use.

    Parameters
    ----------
    grid : dict, optional
        Grid specification (:func:`normalise_grid`); None or the default grid: the shipped table.
    progress : None or bool
        Progress bar while building (see :func:`build`).
    tol : float, optional
        Build to that accuracy (refining the grid's node counts; see :func:`build`), and warn if a
        table found in the cache does not meet it.

    Returns
    -------
    Table

    Raises
    ------
    TypeError, ValueError
        A bad grid or ``tol``.
    OSError
        The cache file cannot be written (e.g. a full disk), or a directory, FIFO or device stands
        in its place (never replaced), naming the file.

    Warns
    -----
    RuntimeWarning
        A cached file failed verification (:class:`TableFileError`): it is rebuilt.
    AccuracyWarning
        The table's measured error exceeds ``tol`` (or 1e-9).

    Examples
    --------
    >>> import fastrest
    >>> from fastrest.tables import cached_table
    >>> cached_table(None) is fastrest.load_table()
    True
    """
    g = normalise_grid(grid)
    if tol is not None:
        tol = _check_tol(tol)
    if g == normalise_grid(None):
        return load_table(tol=tol)
    key = grid_key(g) if tol is None else f"{grid_key(g)}-tol{tol:.0e}"
    path = cache_dir() / f"{key}.h5"
    if os.path.lexists(path):
        try:
            return load_table(path, tol=tol)
        except TableFileError as exc:
            # a FIFO, device or directory in the file's place is refused (OSError), never replaced
            check_target(path, "grid", "the cached table")
            # a damaged cache entry is rebuilt, not re-raised on every call
            warn(f"rebuilding the cached table: {exc}", RuntimeWarning)  # the caller's line
    build(path, g, progress=progress, tol=tol)
    return load_table(path, tol=tol)
