"""Summits of a height map and the rough surface they make: :func:`find_summits`, :func:`topography_summits`,
:func:`from_topography`.

A summit is a pixel strictly higher than its 8 neighbours (Greenwood & Williamson 1966, Proc. R. Soc.
A 295:300, "summits" of a sampled surface; Greenwood 1984, Proc. R. Soc. A 393:133, the 8-neighbour
definition of a summit on a 2-D grid). Its radius of curvature is the inverse of the mean of the two
principal curvatures, estimated by central second differences:

    kappa = -(z_xx + z_yy) / 2,  z_xx = (z[i+1, j] - 2 z[i, j] + z[i-1, j]) / dx^2,
    z_yy = (z[i, j+1] - 2 z[i, j] + z[i, j-1]) / dy^2,  R = 1 / kappa

(Greenwood 1984, eq for the summit curvature as the mean of the two curvatures; Nayak 1971, ASME J.
Lubr. Technol. 93:398, uses the same sum z_xx + z_yy). User guide: docs/topography.md.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from .._validation import as_float_array, check_bool
from .surface import RoughSurface
from .topography import Topography, as_topography

__all__ = ["find_summits", "topography_summits", "from_topography", "TopographySummits"]

#: The 8 neighbour offsets (di, dj) of a pixel.
NEIGHBOURS = ((-1, -1), (-1, 0), (-1, 1), (0, -1), (0, 1), (1, -1), (1, 0), (1, 1))


def _grid(heights: Any, periodic: Any) -> tuple[np.ndarray, bool]:
    h = np.asarray(as_float_array(heights, "heights"), dtype=np.float64)
    periodic = check_bool(periodic, "periodic")
    if h.ndim != 2:
        raise ValueError(f"heights must be a 2-D height map (nx, ny); got {h.ndim} dimension(s)")
    if h.shape[0] < 3 or h.shape[1] < 3:
        raise ValueError(f"heights has {h.shape[0]} x {h.shape[1]} pixels: a summit needs at least 3 x 3")
    if not np.all(np.isfinite(h)):
        n = int(np.count_nonzero(~np.isfinite(h)))
        raise ValueError(f"heights has {n} NaN or infinite pixel(s): fill or crop them first")
    return h, periodic


def _padded(h: np.ndarray, periodic: bool) -> np.ndarray:
    """The map with a one-pixel frame: the wrapped rows and columns (periodic), else the map itself
    (its border pixels are then the frame, and never summits)."""
    return np.pad(h, 1, mode="wrap") if periodic else h


def find_summits(heights: Any, periodic: bool = False) -> tuple[np.ndarray, np.ndarray]:
    """Pixels strictly higher than all 8 neighbours (vectorised NumPy).

    Parameters
    ----------
    heights : array_like
        (nx, ny) height map (any length unit), finite, at least 3 x 3.
    periodic : bool
        True: the map wraps, and the neighbours of an edge pixel are across the opposite edge (every
        pixel can be a summit). False (default): border pixels are never summits, as their 8
        neighbours are not all known.

    Returns
    -------
    (i, j) : tuple of int64 ndarray
        Row (axis 0) and column (axis 1) of each summit, in C order: ``heights[i, j]`` are the
        summit heights.

    Raises
    ------
    TypeError
        Non-numeric heights, or ``periodic`` not a bool.
    ValueError
        Not 2-D, fewer than 3 x 3 pixels, or NaN/infinite pixels (refused, not filled;
        :func:`~fastrest.rough.load_topography` refuses them earlier).

    Notes
    -----
    Strict inequality: a pixel equal to any neighbour is no summit, so a flat top (a plateau of two
    or more equal pixels) has no summit, nor has a plane. A map's summits are the pixels with
    z[i, j] > z[i + di, j + dj] for all 8 (di, dj) (Greenwood 1984).

    Examples
    --------
    >>> import numpy as np
    >>> z = np.zeros((5, 5)); z[2, 2] = 1.0; z[1, 3] = 0.5
    >>> find_summits(z)
    (array([2]), array([2]))
    """
    h, periodic = _grid(heights, periodic)
    p = _padded(h, periodic)
    nx, ny = p.shape
    c = p[1:-1, 1:-1]
    top = np.ones(c.shape, dtype=bool)
    for di, dj in NEIGHBOURS:
        np.logical_and(top, c > p[1 + di:nx - 1 + di, 1 + dj:ny - 1 + dj], out=top)
    i, j = np.nonzero(top)
    if not periodic:  # interior pixel (i, j) of the unpadded map is (i + 1, j + 1)
        i += 1
        j += 1
    return i.astype(np.int64, copy=False), j.astype(np.int64, copy=False)


def _curvature(h: np.ndarray, i: np.ndarray, j: np.ndarray, dx: float, dy: float) -> np.ndarray:
    """kappa = -(z_xx + z_yy)/2 (1/m) at pixels (i, j) (wrapped indices), central differences; each
    second difference summed as two differences from the centre, both < 0 at a strict maximum."""
    nx, ny = h.shape
    z = h[i, j]
    zxx = ((h[(i + 1) % nx, j] - z) + (h[(i - 1) % nx, j] - z)) / dx**2
    zyy = ((h[i, (j + 1) % ny] - z) + (h[i, (j - 1) % ny] - z)) / dy**2
    with np.errstate(over="ignore", invalid="ignore"):
        return -0.5 * (zxx + zyy)


@dataclass(frozen=True, eq=False)
class TopographySummits:
    """The summits of a height map and what was counted on the way (:func:`topography_summits`).

    Attributes
    ----------
    heights, radii : numpy.ndarray
        Kept summits' heights (m, on the map's datum: after detrending, the mean plane for
        ``detrend="height"``) and radii of curvature R = 1/kappa (m), > 0.
    i, j : numpy.ndarray
        Their pixels (row, column) on the map.
    n_pixels : int
        Pixels of the map.
    n_border : int
        Border pixels that cannot be summits (2 nx + 2 ny - 4 for a non-periodic map, 0 periodic).
    n_found : int
        Strict local maxima found (:func:`find_summits`).
    n_curvature_left_out : int
        Of those, left out because kappa is not a finite, positive double or R = 1/kappa is not
        finite (a strict maximum has kappa > 0 exactly; only underflow or overflow of the second
        differences leaves one out).
    dx, dy : float
        Pixel spacing (m).
    periodic : bool
        Whether the map wrapped.
    area : float
        Nominal area of the map (m^2).
    source : str
        Where the map came from.

    Examples
    --------
    >>> import numpy as np
    >>> from fastrest.rough import Topography, topography_summits
    >>> z = np.zeros((5, 6)); z[2, 2] = 1e-7; z[2, 4] = z[1, 4] = 2e-7   # a summit and a 2-pixel top
    >>> s = topography_summits(Topography(z, 1e-6, 1e-6, False, "example"))
    >>> s.counts()
    {'n_pixels': 30, 'n_border': 18, 'n_found': 1, 'n_curvature_left_out': 0, 'n_summits': 1}
    """

    heights: np.ndarray
    radii: np.ndarray
    i: np.ndarray
    j: np.ndarray
    n_pixels: int
    n_border: int
    n_found: int
    n_curvature_left_out: int
    dx: float
    dy: float
    periodic: bool
    area: float
    source: str

    @property
    def n_summits(self) -> int:
        """Summits kept: n_found - n_curvature_left_out."""
        return int(self.heights.size)

    @property
    def density(self) -> float:
        """Summits kept per nominal area (1/m^2)."""
        return self.n_summits / self.area

    def counts(self) -> dict[str, int]:
        """The counts as a dict (pixels, border, found, left out, kept)."""
        return {"n_pixels": self.n_pixels, "n_border": self.n_border, "n_found": self.n_found,
                "n_curvature_left_out": self.n_curvature_left_out, "n_summits": self.n_summits}


def topography_summits(topography: Any, *, detrend: str | None = None, cutoff: float | None = None,
                       unit: str | None = None, physical_size: tuple[float, float] | None = None,
                       periodic: bool | None = None) -> TopographySummits:
    """The summits of a height map with their heights and radii of curvature.

    Parameters
    ----------
    topography : Topography, str, os.PathLike or SurfaceTopography topography
        A map from :func:`~fastrest.rough.load_topography`, or what it reads (then read with the
        options below).
    detrend, cutoff, unit, physical_size, periodic
        :func:`~fastrest.rough.load_topography`'s options, for a map still to be read (a ValueError
        with a :class:`Topography`); ``detrend`` None: "mean" for a periodic map, "height" otherwise.

    Returns
    -------
    TopographySummits
        Heights (m) and radii R = 1/kappa (m), kappa = -(z_xx + z_yy)/2 by central second
        differences with dx along axis 0 and dy along axis 1 (Greenwood 1984; Nayak 1971), of every
        strict 8-neighbour maximum with a finite positive curvature; and the counts.

    Raises
    ------
    ValueError
        No summit on the map (a plane, a bowl, a plateau), or :func:`load_topography`'s errors.

    Examples
    --------
    >>> import numpy as np
    >>> from fastrest.rough import Topography, topography_summits
    >>> z = np.zeros((5, 5)); z[2, 2] = 1e-7
    >>> s = topography_summits(Topography(z, 1e-6, 2e-6, False, "example"))
    >>> s.i, s.j, s.heights, s.radii   # kappa = (2e-7/1e-12 + 2e-7/4e-12)/2
    (array([2]), array([2]), array([1.e-07]), array([8.e-06]))
    """
    t = as_topography(topography, detrend=detrend, cutoff=cutoff, unit=unit, physical_size=physical_size,
                      periodic=periodic)
    h = t.heights
    i, j = find_summits(h, t.periodic)
    kappa = _curvature(h, i, j, t.dx, t.dy)
    with np.errstate(divide="ignore", over="ignore"):
        r = 1.0 / kappa
    ok = np.isfinite(kappa) & (kappa > 0) & np.isfinite(r)
    nx, ny = h.shape
    n_found = int(i.size)
    if not np.all(ok):
        i, j, r = i[ok], j[ok], r[ok]
    if i.size == 0:
        raise ValueError(f"no summit on {t.source} ({nx} x {ny} pixels, "
                         f"{'periodic' if t.periodic else 'non-periodic: border pixels excluded'}): no pixel "
                         f"is strictly higher than its 8 neighbours{' with a finite curvature' if n_found else ''}"
                         " (a plane, a bowl, a plateau, or a top shared by pixels of equal height: "
                         "ties to the last bit count as equal)")
    arrays = [h[i, j].copy(), np.array(r, dtype=np.float64), i, j]
    for a in arrays:
        a.setflags(write=False)  # the record is frozen: its arrays too
    return TopographySummits(
        heights=arrays[0], radii=arrays[1], i=arrays[2], j=arrays[3], n_pixels=nx * ny,
        n_border=0 if t.periodic else 2 * nx + 2 * ny - 4, n_found=n_found,
        n_curvature_left_out=n_found - int(i.size), dx=t.dx, dy=t.dy, periodic=t.periodic, area=t.area,
        source=t.source)


def from_topography(topography: Any, material: Any, *, detrend: str | None = None, cutoff: float | None = None,
                    unit: str | None = None, physical_size: tuple[float, float] | None = None,
                    periodic: bool | None = None, et_ratio: float | None = None, loading: Any = None) -> Any:
    """The rough surface of a measured map's summits: :func:`topography_summits`, then explicit
    :class:`~fastrest.rough.RoughSurface` ``(material, heights=z, radii=R)``.

    Parameters
    ----------
    topography : Topography, str, os.PathLike or SurfaceTopography topography
        The map (m), as in :func:`topography_summits`.
    material : fastrest.Material
        The surface's material (the flat is rigid).
    detrend, cutoff, unit, physical_size, periodic
        Reading options (:func:`~fastrest.rough.load_topography`; defaults: "mean" for a periodic
        map and "height" otherwise, no filter, from the file), for a map still to be read.
    et_ratio, loading
        As :class:`~fastrest.rough.RoughSurface`.

    Returns
    -------
    RoughSurface
        Explicit surface, one JGM sphere per summit (its own height and radius), with the attribute
        ``topography_summits``: the :class:`TopographySummits` record (counts, pixels, spacing,
        area, source) of the map.

    Raises
    ------
    ValueError
        No summit; reading errors (:func:`load_topography`); RoughSurface's (e.g. a radius outside
        the single-sphere model's range).

    Examples
    --------
    >>> import numpy as np, fastrest
    >>> from fastrest.rough import Topography, from_topography
    >>> z = np.zeros((5, 5)); z[2, 2] = 1e-7
    >>> t = Topography(heights=z, dx=1e-6, dy=1e-6, periodic=False, source="example")
    >>> s = from_topography(t, fastrest.Material(200e9, 0.3, 1e9))
    >>> s.topography_summits.n_summits, float(s.radii[0])
    (1, 5e-06)
    """
    found = topography_summits(topography, detrend=detrend, cutoff=cutoff, unit=unit, physical_size=physical_size,
                               periodic=periodic)
    surface = RoughSurface(material, heights=found.heights, radii=found.radii, et_ratio=et_ratio, loading=loading)
    setattr(surface, "topography_summits", found)  # the map's record travels with its surface
    return surface
