"""HDF5 parses an untrusted table file in a check process first: a crash or hang there is a
:class:`~fastrest.tables.TableFileError`, not the end of the caller's process.

The header digest (:mod:`fastrest.tables.file`) catches accidental damage before HDF5 sees a byte,
but a file altered and then given a recomputed digest ("resealed") reaches HDF5's parser, which can
crash (double free, segfault) or hang on damaged metadata; no check in Python can prevent that. So
the bytes of a table file whose digest is not trusted are first handed to a child Python process
(``sys.executable``, only h5py and NumPy imported) that parses them exactly as the caller will
(:func:`fastrest.tables.hdf5_read.parse_image`) and then walks every object, attribute and dataset,
with a time limit (:data:`CHECK_TIMEOUT`). Only if that child ends cleanly does the caller parse the
same bytes itself.

Trusted digests, parsed in-process at once: the shipped table's, recorded by ``fastrest build
--default`` in :mod:`fastrest.tables._default_digest` (a constant of the installed package: editing
the table file changes its digest, so the file alone cannot forge it), and the digests of files
this process wrote itself. A check that passed is remembered per process by digest (the same bytes
wherever they are): it costs once.
"""
from __future__ import annotations

from typing import Any
import os
import signal
import subprocess
import sys
from pathlib import Path

from .file import TableFileError

__all__ = ["CHECK_TIMEOUT", "TRUSTED", "CHECKED", "trust", "check_image"]

#: Seconds the check process may take (the shipped table, 10 MB, parses in well under a second).
CHECK_TIMEOUT = 60.0
#: SHA-256 digests parsed in-process without a check: the shipped table's and those this process wrote.
TRUSTED = set()
#: Digests whose check passed in this process.
CHECKED: set[str] = set()

try:
    from ._default_digest import SHA256 as _DEFAULT
except ImportError:  # a checkout before the digest was recorded: the shipped table is checked too
    _DEFAULT = None  # type: ignore[assignment]  # the module is absent in that case
if _DEFAULT:
    TRUSTED.add(_DEFAULT)

_PACKAGE = Path(__file__).resolve().parent.parent
# The child imports fastrest.tables' file-format modules without running fastrest/__init__.py
# (NumPy, Numba and the solvers are not needed): the parent packages are registered empty.
_CHILD = r"""
import sys, types
for name, where in (("fastrest", sys.argv[1]), ("fastrest.tables", sys.argv[1] + "/tables")):
    module = types.ModuleType(name)
    module.__path__ = [where]
    sys.modules[name] = module
from fastrest.tables.file import TableFileError
from fastrest.tables.hdf5_read import parse_image, walk_image
data = sys.stdin.buffer.read()
try:
    parse_image(data, sys.argv[2])
    walk_image(data)
except TableFileError as exc:
    sys.stdout.write("refused " + str(exc))
    sys.exit(0)
sys.stdout.write("ok")
"""


def trust(digest: str) -> None:
    """Parse files with this SHA-256 digest in-process from now on (a file this process wrote).

    Parameters
    ----------
    digest : str
        Hex digest of a file's bytes after its header.

    Examples
    --------
    >>> trust("0" * 64)
    >>> "0" * 64 in TRUSTED
    True
    """
    TRUSTED.add(digest)


def check_image(data: bytes, digest: str, path: str | os.PathLike[str]) -> None:
    """Refuse a table file's bytes that crash, hang or fail HDF5 in a check process.

    Parameters
    ----------
    data : bytes
        The whole file, verified against ``digest``.
    digest : str
        SHA-256 hex digest of the bytes after the header.
    path : str
        The file (for messages).

    Raises
    ------
    TableFileError
        Naming the file and what happened: the HDF5 library crashed (the signal), did not finish
        within :data:`CHECK_TIMEOUT` s, the structure checks refused it, or the check process could
        not run or failed.

    Notes
    -----
    Returns at once for a trusted or already checked digest. The child runs with
    ``MALLOC_PERTURB_`` set, so that glibc fills freed memory and a use after free is more likely
    to crash the child than to pass unnoticed.

    Examples
    --------
    >>> from fastrest.tables import default_table_path
    >>> from fastrest.tables.file import read_verified
    >>> data, digest = read_verified(default_table_path())
    >>> check_image(data, digest, "default.h5")   # trusted, or checked once: no error
    """
    if digest in TRUSTED or digest in CHECKED:
        return
    env = dict(os.environ, MALLOC_PERTURB_="165", PYTHONDONTWRITEBYTECODE="1")
    try:
        r = subprocess.run([sys.executable, "-c", _CHILD, str(_PACKAGE), str(path)], input=data,
                           capture_output=True, timeout=CHECK_TIMEOUT, env=env)
    except subprocess.TimeoutExpired:
        raise TableFileError(f"{path}: the HDF5 library did not finish parsing the file within "
                             f"{CHECK_TIMEOUT:g} s in a check process: the file is damaged or hostile (its "
                             "digest was recomputed after a change); rebuild it with `fastrest build`") from None
    except OSError as exc:
        raise TableFileError(f"{path}: cannot start the process that checks the file before it is parsed "
                             f"({exc.strerror or exc}); only the shipped table and files this process "
                             "wrote are read without it") from None
    out = r.stdout.decode("utf-8", "replace")
    if r.returncode < 0:
        try:
            sig = signal.Signals(-r.returncode).name
        except ValueError:
            sig = f"signal {-r.returncode}"
        raise TableFileError(f"{path}: the HDF5 library crashed ({sig}) parsing the file in a check process: "
                             "the file is damaged or hostile (its digest was recomputed after a change); "
                             "rebuild it with `fastrest build`")
    if r.returncode == 0 and out.startswith("refused "):
        raise TableFileError(out[len("refused "):])
    if r.returncode != 0 or out != "ok":
        tail = r.stderr.decode("utf-8", "replace").strip().splitlines()[-1:] or [out]
        raise TableFileError(f"{path}: the process checking the file failed (exit {r.returncode}): "
                             f"{tail[0][:300]}")
    CHECKED.add(digest)
