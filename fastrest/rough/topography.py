"""Measured height maps: :class:`Topography` and :func:`load_topography` (SurfaceTopography reader).

A height map is read with SurfaceTopography (Pastewka group, https://github.com/ContactEngineering/
SurfaceTopography, >= 1.27; the optional extra ``fastrest[topography]``), checked (2-D, uniform grid,
units and physical size known, every pixel defined, fits in memory), converted to metres,
detrended and optionally low-pass filtered with SurfaceTopography's own operations, and handed
over as a read-only float64 array. SurfaceTopography is imported here only when a map is read:
``import fastrest`` and ``import fastrest.rough`` never import it. User guide: docs/topography.md.
"""
from __future__ import annotations

import contextlib
import io
import math
import os
import warnings
from dataclasses import dataclass
from typing import Any

import numpy as np

from .._validation import as_float_array, check_bool, real_scalar

__all__ = ["Topography", "load_topography", "DETREND_MODES", "BYTES_PER_PIXEL", "MAX_SPACING", "available_memory"]

#: Largest pixel spacing (m) of a :class:`Topography`: a metre-sized pixel is no asperity map (and
#: second differences over much larger spacings would overflow).
MAX_SPACING = 1.0
#: detrend= values and the SurfaceTopography ``detrend_mode`` each one runs (None: nothing done).
DETREND_MODES = {"height": "height", "mean": "mean", "slope": "slope", "curvature": "curvature",
                 "none": None}

#: Memory (bytes per pixel) reserved for a map: the heights as read, their conversion to metres and
#: detrending, the stored copy, and the summit search and curvature temporaries (8 float64-sized
#: arrays). A low-pass ``cutoff`` adds :data:`BYTES_PER_PIXEL_CUTOFF`.
BYTES_PER_PIXEL = 64
#: Extra bytes per pixel with ``cutoff``: the mirrored 2x2 extension (non-periodic maps) and its
#: real and complex spectra.
BYTES_PER_PIXEL_CUTOFF = 160

_MISSING = 'reading topographies needs SurfaceTopography: pip install "fastrest[topography]"'


@dataclass(frozen=True, eq=False)
class Topography:
    """A validated, filtered height map in SI units (the output of :func:`load_topography`).

    Attributes
    ----------
    heights : numpy.ndarray
        (nx, ny) float64 heights (m), all finite, C-contiguous, read-only; axis 0 is x, axis 1 y.
    dx, dy : float
        Pixel spacing along axis 0 and axis 1 (m), > 0.
    periodic : bool
        True when the map wraps: the pixels across each edge are neighbours.
    source : str
        The file path, or a short description of the object given.

    Raises
    ------
    TypeError, ValueError
        Built directly (not by :func:`load_topography`): heights not a finite 2-D real array, dx or
        dy not in (0, 1] m, periodic not a bool, source not a str. Heights are stored as a
        read-only C-contiguous float64 copy unless they already are one.

    Examples
    --------
    >>> import numpy as np
    >>> t = Topography(heights=np.zeros((4, 3)), dx=1e-6, dy=2e-6, periodic=False, source="zeros")
    >>> t.shape, t.physical_size, t.area
    ((4, 3), (4e-06, 6e-06), 2.4e-11)
    """

    heights: np.ndarray
    dx: float
    dy: float
    periodic: bool
    source: str

    def __post_init__(self) -> None:
        h = self.heights
        if not (isinstance(h, np.ndarray) and h.dtype == np.float64 and h.flags.c_contiguous
                and not h.flags.writeable):
            h = np.array(as_float_array(h, "heights"), dtype=np.float64, order="C", copy=True)
            h.setflags(write=False)
        if h.ndim != 2 or h.shape[0] < 1 or h.shape[1] < 1:
            raise ValueError(f"heights must be a 2-D height map (nx, ny) (m); got shape {h.shape}")
        if not np.all(np.isfinite(h)):
            raise ValueError("heights must be finite (m): fill or crop undefined pixels first")
        dx, dy = real_scalar(self.dx, "dx"), real_scalar(self.dy, "dy")
        for name, v in (("dx", dx), ("dy", dy)):
            if not (math.isfinite(v) and 0 < v <= MAX_SPACING):
                raise ValueError(f"{name} must be in (0, {MAX_SPACING:g}] (m, pixel spacing); got {v!r}")
        if not isinstance(self.source, str):
            raise TypeError(f"source must be a str; got {type(self.source).__name__}")
        object.__setattr__(self, "heights", h)
        object.__setattr__(self, "dx", dx)
        object.__setattr__(self, "dy", dy)
        object.__setattr__(self, "periodic", check_bool(self.periodic, "periodic"))

    def __reduce__(self) -> tuple[Any, tuple[Any, ...]]:
        # rebuilt through the constructor: the unpickled heights are checked and read-only again
        return (Topography, (np.array(self.heights), self.dx, self.dy, self.periodic, self.source))

    @property
    def shape(self) -> tuple[int, int]:
        """(nx, ny): pixels along axis 0 and axis 1."""
        nx, ny = self.heights.shape
        return (int(nx), int(ny))

    @property
    def physical_size(self) -> tuple[float, float]:
        """(nx dx, ny dy) (m)."""
        nx, ny = self.heights.shape
        return (nx * self.dx, ny * self.dy)

    @property
    def area(self) -> float:
        """Nominal area nx dx ny dy (m^2)."""
        sx, sy = self.physical_size
        return sx * sy


def available_memory() -> int | None:
    """Memory available to this process (bytes): psutil's ``available`` when psutil is installed,
    else ``os.sysconf`` available pages times the page size; None when neither is known.

    Returns
    -------
    int or None
        Bytes available (:func:`load_topography` refuses maps that need more).

    Examples
    --------
    >>> m = available_memory()
    >>> m is None or m > 0
    True
    """
    try:
        import importlib  # psutil is optional (and untyped)
        return int(importlib.import_module("psutil").virtual_memory().available)
    except Exception:  # psutil missing or not working here
        pass
    try:
        return int(os.sysconf("SC_AVPHYS_PAGES")) * int(os.sysconf("SC_PAGE_SIZE"))
    except (ValueError, OSError, AttributeError):
        return None


def _import_st():
    try:
        with warnings.catch_warnings():  # NuMPI (SurfaceTopography's MPI layer) without mpi4py: its stub is what we use
            warnings.filterwarnings("ignore", "Could not import mpi4py", ImportWarning)
            import SurfaceTopography  # noqa: F401
        from SurfaceTopography import open_topography
        from SurfaceTopography.HeightContainer import UniformTopographyInterface
        from SurfaceTopography.Support.UnitConversion import get_unit_conversion_factor, length_units
    except ImportError:
        raise ImportError(_MISSING) from None
    return open_topography, UniformTopographyInterface, get_unit_conversion_factor, length_units


def _check_options(detrend, cutoff, unit, physical_size, periodic):
    if detrend is None:
        pass
    elif not isinstance(detrend, str):
        raise TypeError(f"detrend must be None or a str, one of {sorted(DETREND_MODES)}; got {type(detrend).__name__}")
    elif detrend not in DETREND_MODES:
        raise ValueError(f"detrend = {detrend!r} is unknown: use one of {sorted(DETREND_MODES)}")
    if cutoff is not None:
        cutoff = real_scalar(cutoff, "cutoff")
        if not (math.isfinite(cutoff) and cutoff > 0):
            raise ValueError(f"cutoff must be finite and > 0 (m, shortest wavelength kept); got {cutoff!r}")
    if unit is not None and not isinstance(unit, str):
        raise TypeError(f"unit must be a str such as 'm', 'um' or 'nm'; got {type(unit).__name__}")
    if physical_size is not None:
        if isinstance(physical_size, (str, bytes)) or not hasattr(physical_size, "__len__") or len(physical_size) != 2:
            raise TypeError("physical_size must be a pair (sx, sy) of lengths (m)")
        physical_size = tuple(real_scalar(s, "physical_size") for s in physical_size)
        if not all(math.isfinite(s) and s > 0 for s in physical_size):
            raise ValueError(f"physical_size must be two finite lengths > 0 (m); got {physical_size!r}")
    if periodic is not None and not isinstance(periodic, (bool, np.bool_)):
        raise TypeError(f"periodic must be None, True or False; got {type(periodic).__name__}")
    return cutoff, physical_size


def _check_shape(what, dim, uniform, nb, cutoff):
    if dim != 2:
        raise ValueError(f"{what} is a line scan ({dim}-D): summits need the 8 neighbours of a 2-D "
                         "height map; give an areal topography")
    if not uniform:
        raise ValueError(f"{what} is on a nonuniform grid: only uniform grids are read")
    nx, ny = (int(n) for n in nb)
    if nx < 3 or ny < 3:
        raise ValueError(f"{what} has {nx} x {ny} pixels: at least 3 x 3 are needed for one summit")
    need = nx * ny * (BYTES_PER_PIXEL + (BYTES_PER_PIXEL_CUTOFF if cutoff is not None else 0))
    avail = available_memory()
    if avail is not None and need > avail:
        raise ValueError(f"{what} has {nx} x {ny} = {nx * ny} pixels: processing it needs about "
                         f"{need / 2**30:.3g} GiB, more than the {avail / 2**30:.3g} GiB of memory available")


def _missing_metadata(what, size_missing, unit_missing):
    parts = []
    if size_missing:
        parts.append("its physical size (give physical_size (sx, sy) in metres, or "
                     "physical_sizes to SurfaceTopography)")
    if unit_missing:
        parts.append("its units of length (give unit ('m', 'um', 'nm', ...), or unit to SurfaceTopography)")
    raise ValueError(f"{what} lacks " + " and ".join(parts))


def _reason(exc):
    """SurfaceTopography's reason, on one line and at most 300 characters."""
    text = " ".join(str(exc).split())
    return f"{type(exc).__name__}: {text if len(text) <= 300 else text[:297] + '...'}"


@contextlib.contextmanager
def _quiet():
    """SurfaceTopography's readers print what they try (raw bytes of a file they cannot read) and
    scipy's NetCDF reader warns on close: neither is the user's business; errors are reported."""
    with warnings.catch_warnings(), contextlib.redirect_stdout(io.StringIO()), \
            contextlib.redirect_stderr(io.StringIO()):
        warnings.filterwarnings("ignore", "Cannot close a netcdf_file", RuntimeWarning)
        yield


def _read_file(path, unit, physical_size, periodic, cutoff, open_topography, factor):
    what = f"file {path!r}"
    if not os.path.exists(path):
        raise ValueError(f"{what} does not exist")
    if os.path.isdir(path):
        raise ValueError(f"{what} is a directory, not a topography file")
    try:
        with _quiet():
            reader = open_topography(path)
        ch = reader.channels[reader.default_channel.index] if hasattr(reader, "default_channel") \
            else reader.channels[0]
    except Exception as exc:  # SurfaceTopography's reasons vary by format
        raise ValueError(f"cannot read {what} as a topography: {_reason(exc)}") from None
    _check_shape(what, ch.dim, ch.is_uniform is not False, ch.nb_grid_pts, cutoff)
    file_unit, file_size = ch.unit, ch.physical_sizes
    if (file_size is None and physical_size is None) or (file_unit is None and unit is None):
        _missing_metadata(what, file_size is None and physical_size is None, file_unit is None and unit is None)
    if file_unit is not None and unit is not None and unit != file_unit:
        raise ValueError(f"{what} states its unit, {file_unit!r}, so unit ({unit!r}) is not accepted")
    if file_size is not None and physical_size is not None:
        raise ValueError(f"{what} states its physical size, {tuple(float(s) for s in file_size)!r} "
                         f"({file_unit}), so physical_size is not accepted")
    kw: dict[str, Any] = {}
    if unit is not None and file_unit is None:
        kw["unit"] = unit
    if physical_size is not None:  # metres, in the file's unit for the reader
        kw["physical_sizes"] = tuple(s * factor("m", file_unit or unit) for s in physical_size)
    if periodic is not None:
        kw["periodic"] = bool(periodic)
    try:
        with _quiet():
            return reader.topography(**kw), what
    except Exception as exc:
        raise ValueError(f"cannot read {what} as a topography: {_reason(exc)}") from None


def _from_object(t, unit, physical_size, periodic, cutoff):
    what = f"{type(t).__name__} {t.info.get('name', '')}".strip() if hasattr(t, "info") else type(t).__name__
    _check_shape(what, t.dim, t.is_uniform, t.nb_grid_pts, cutoff)
    if physical_size is not None:
        raise ValueError(f"{what} carries its own physical size, so physical_size is not accepted")
    size_missing = getattr(t, "physical_sizes", None) is None
    if size_missing or (t.unit is None and unit is None):
        _missing_metadata(what, size_missing, t.unit is None and unit is None)
    if unit is not None:
        if t.unit is not None and t.unit != unit:
            raise ValueError(f"{what} states its unit, {t.unit!r}, so unit ({unit!r}) is not accepted")
        if t.unit is None:
            from SurfaceTopography import Topography as STTopography
            t = STTopography(t.heights(), t.physical_sizes, unit=unit, periodic=t.is_periodic)
    if periodic is not None and bool(periodic) != bool(t.is_periodic):
        from SurfaceTopography import Topography as STTopography
        t = STTopography(t.heights(), t.physical_sizes, unit=t.unit, periodic=bool(periodic))
    return t, what


def _check_defined(h, what):
    bad = np.ma.getmaskarray(h) | ~np.isfinite(np.ma.getdata(h))
    n = int(np.count_nonzero(bad))
    if n:
        where = [tuple(int(i) for i in ij) for ij in np.argwhere(bad)[:5]]
        raise ValueError(f"{what} has {n} undefined (masked, NaN or infinite) pixel(s) of {bad.size}, "
                         f"first at (i, j) = {', '.join(map(str, where))}{', ...' if n > 5 else ''}: "
                         "fill or crop them first (e.g. SurfaceTopography's interpolate_undefined_data)")


def _lowpass(t, cutoff, STTopography):
    """Heights (m) of ``t`` with wavelengths shorter than ``cutoff`` removed (see load_topography)."""
    with warnings.catch_warnings():  # SurfaceTopography 1.27's irfftn(s=...) call, under NumPy 2
        warnings.filterwarnings("ignore", "`axes` should not be `None`", DeprecationWarning)
        return _lowpass_st(t, cutoff, STTopography)


def _lowpass_st(t, cutoff, STTopography):
    if t.is_periodic:
        return np.asarray(t.shortcut(cutoff_wavelength=cutoff).heights())
    h = np.asarray(t.heights())
    nx, ny = h.shape
    sx, sy = t.physical_sizes
    ext = np.concatenate([h, h[::-1]], axis=0)  # even (mirror) extension: continuous across edges
    ext = np.concatenate([ext, ext[:, ::-1]], axis=1)
    per = STTopography(ext, (2 * sx, 2 * sy), unit=t.unit, periodic=True)
    return np.asarray(per.shortcut(cutoff_wavelength=cutoff).heights())[:nx, :ny]


def as_topography(source: Any, **options: Any) -> Topography:
    """``source`` itself if it is a :class:`Topography` (then reading ``options`` given, not None,
    are a ValueError), else :func:`load_topography` ``(source, **options)``."""
    if isinstance(source, Topography):
        given = [k for k, v in options.items() if v is not None]
        if given:
            raise ValueError(f"{', '.join(given)}: options for reading a map; this Topography is already "
                             "read (give them to load_topography, or pass the file)")
        return source
    return load_topography(source, **options)


def load_topography(source: Any, *, detrend: str | None = None, cutoff: float | None = None,
                    unit: str | None = None, physical_size: tuple[float, float] | None = None,
                    periodic: bool | None = None) -> Topography:
    """Read a 2-D height map, check it, convert it to metres, detrend and (optionally) low-pass it.

    Parameters
    ----------
    source : str, os.PathLike or SurfaceTopography topography
        A file SurfaceTopography's ``open_topography`` reads (ISO 25178 ``.x3p``, NetCDF, Digital
        Instruments, Gwyddion, text matrices, ...), or a 2-D uniform SurfaceTopography topography.
    detrend : {None, "height", "mean", "slope", "curvature", "none"}
        Trend removed with SurfaceTopography's ``detrend(detrend_mode=...)``: "height" the plane
        of least rms height ("rms-tilt"), "mean" the mean height only, "slope" the plane of least
        rms slope, "curvature" the quadratic of least rms height, "none" nothing. Default None:
        "mean" for a periodic map (a period has no tilt to remove), "height" otherwise (a measured
        map's tilt). SurfaceTopography keeps a periodic map periodic only when a constant is
        removed: any other mode on a periodic map returns a non-periodic one, with a UserWarning.
    cutoff : float, optional
        Short-wavelength cutoff lambda_c (m), > 0; default None: no filter. When given, every
        Fourier component of wavevector ``|q| > 2 pi / lambda_c`` is set to zero
        (SurfaceTopography's ``shortcut(cutoff_wavelength=..., kind="circular step")``, an ideal
        isotropic low-pass on the real FFT). A periodic map is filtered as it is. A non-periodic
        map is first mirrored into its even 2nx x 2ny extension (continuous across the edges, so
        the map's edge jump does not ring), filtered as periodic, and cropped back: the same as a
        cosine-transform filter.
    unit : str, optional
        Length unit of a file or object that states none ("m", "um", "nm", ...: SurfaceTopography's
        names); one that states its unit keeps it (giving another is a ValueError).
    physical_size : (float, float), optional
        (sx, sy) (m), for a file that states no physical size (a ValueError if it does).
    periodic : bool, optional
        Whether the map is one period of a periodic surface; default None: as the file or object
        says (False when it does not say).

    Returns
    -------
    Topography
        Heights (m) as a read-only (nx, ny) float64 array, dx = sx/nx, dy = sy/ny (m), periodic.

    Raises
    ------
    ImportError
        SurfaceTopography is not installed (``pip install "fastrest[topography]"``).
    TypeError
        ``source`` is neither a path nor a SurfaceTopography topography, or an option has the wrong
        type (the message names it).
    ValueError
        The file cannot be read (naming it and SurfaceTopography's reason); a line scan (summits
        need 2-D neighbours); a nonuniform grid; fewer than 3 x 3 pixels; no unit or physical size
        (saying how to give them); undefined (masked or NaN) pixels (how many and where: they are
        not filled); a map needing more memory than available (``BYTES_PER_PIXEL`` per pixel,
        checked before the heights are read).

    Examples
    --------
    A SurfaceTopography object in micrometres (a file path works the same way):

    >>> import numpy as np
    >>> import SurfaceTopography as ST
    >>> st = ST.Topography(np.arange(12.0).reshape(3, 4), (3.0, 4.0), unit="um")
    >>> t = load_topography(st, detrend="mean")
    >>> t.shape, t.dx, round(float(t.heights[0, 1] - t.heights[0, 0]), 15)
    ((3, 4), 1e-06, 1e-06)
    """
    cutoff, physical_size = _check_options(detrend, cutoff, unit, physical_size, periodic)
    open_topography, Uniform, factor, length_units = _import_st()
    if unit is not None and unit not in length_units:
        raise ValueError(f"unit = {unit!r} is not a length unit SurfaceTopography knows: use one of "
                         f"{', '.join(length_units)}")
    from SurfaceTopography import Topography as STTopography
    if isinstance(source, (str, os.PathLike)):
        path = os.fspath(source)
        t, what = _read_file(path, unit, physical_size, periodic, cutoff, open_topography, factor)
        src = path
    elif hasattr(source, "heights") and hasattr(source, "nb_grid_pts") and hasattr(source, "dim"):
        t, what = _from_object(source, unit, physical_size, periodic, cutoff)
        src = f"<{what}>"
    else:
        raise TypeError(f"source must be a file path or a SurfaceTopography topography; got "
                        f"{type(source).__name__}")
    if t.dim != 2 or not isinstance(t, Uniform):
        _check_shape(what, t.dim, isinstance(t, Uniform), t.nb_grid_pts, None)
    _check_defined(t.heights(), what)
    t = t.to_unit("m")
    if detrend is None:
        detrend = "mean" if t.is_periodic else "height"
    mode = DETREND_MODES[detrend]
    if mode is not None:
        was_periodic = bool(t.is_periodic)
        t = t.detrend(detrend_mode=mode)
        if was_periodic and not t.is_periodic:
            warnings.warn(f"detrend = {detrend!r} fits a trend to a periodic map, which makes it non-periodic "
                          "(SurfaceTopography's rule): its edges are no longer neighbours; use detrend='mean' "
                          "(the default for periodic maps) to keep it periodic", UserWarning, stacklevel=2)
    h = _lowpass(t, cutoff, STTopography) if cutoff is not None else np.asarray(t.heights())
    h = np.array(h, dtype=np.float64, order="C", copy=True)
    if not np.all(np.isfinite(h)):
        raise ValueError(f"{what}: heights overflow in metres (check the unit)")
    h.setflags(write=False)
    nx, ny = h.shape
    sx, sy = (float(s) for s in t.physical_sizes)
    return Topography(heights=h, dx=sx / nx, dy=sy / ny, periodic=bool(t.is_periodic), source=src)
