"""Greenwood-Williamson parameters of a measured (or synthesised) height map, from its moments.

A statistical rough surface (:class:`~fastrest.rough.GreenwoodWilliamson`) needs a summit density
eta, a summit radius R_a and a summit-height standard deviation sigma_s. For an isotropic Gaussian
surface they follow from three moments of a profile of the surface (Nayak 1971; McCool 1986):

* m0 = variance of the heights (m^2),
* m2 = variance of the profile slope dz/dx (-),
* m4 = variance of the profile curvature d^2z/dx^2 (1/m^2),

and the bandwidth parameter alpha = m0 m4 / m2^2 (Nayak 1971). Then (McCool 1986, the
"spectral-moment" estimates of the GW parameters, for large alpha):

    eta     = m4 / (6 pi sqrt(3) m2)              summit density (1/m^2)      (Nayak 1971)
    R       = (3/8) sqrt(pi / m4)                 mean summit radius (m)      (Nayak 1971, alpha -> inf)
    sigma_s = sqrt(1 - 0.8968/alpha) sqrt(m0)     summit-height std (m)       (McCool 1986)

:func:`spectral_moments` computes the moments of a :class:`~fastrest.rough.topography.Topography`,
:func:`gw_from_moments` the GW parameters and :func:`spectral_surface` the
:class:`~fastrest.rough.RoughSurface`. User guide, sources and a comparison with the explicit
summits of the same map: docs/rough-spectral.md.
"""
from __future__ import annotations

import math
import os
from dataclasses import dataclass
from typing import Any

import numpy as np

from .._validation import ValidityWarning, real_scalar, warn
from .heights import GreenwoodWilliamson
from .surface import RoughSurface
from .topography import Topography, as_topography

__all__ = ["SpectralMoments", "SpectralGW", "AnisotropyWarning", "MAX_SUMMITS_PER_PIXEL", "spectral_moments",
           "gw_from_moments",
           "spectral_surface", "ALPHA_MIN", "ANISOTROPY_TOL", "METHODS"]

#: Smallest bandwidth parameter accepted: every isotropic surface has alpha >= 3/2 (its profile
#: moments are m2 = <q^2>/2, m4 = 3 <q^4>/8 of the 2D spectrum, and <q^2>^2 <= <q^4> m0), with
#: equality only for a single wavenumber; McCool's formulas are asymptotic in large alpha.
ALPHA_MIN = 1.5
#: Relative difference of the moments along the two axes above which a map is called anisotropic
#: (:class:`AnisotropyWarning`): abs(m_x - m_y) / ((m_x + m_y)/2) > 0.2 for m2 or m4.
ANISOTROPY_TOL = 0.2
#: Most summits per pixel a map can hold: strict 8-neighbour maxima are never neighbours, so at
#: most one in each 2 x 2 block.
MAX_SUMMITS_PER_PIXEL = 0.25
#: How the moments are computed: "grid" (central differences, the default) or "fft" (spectral).
METHODS = ("grid", "fft")


class AnisotropyWarning(ValidityWarning):
    """The moments along the two axes of a map differ by more than :data:`ANISOTROPY_TOL`.

    Nayak's and McCool's formulas are for an isotropic surface; the moments used are the averages
    over the two axes. A subclass of :class:`fastrest.ValidityWarning`.

    Examples
    --------
    >>> import warnings
    >>> with warnings.catch_warnings():
    ...     warnings.simplefilter("ignore", AnisotropyWarning)  # a map known to be anisotropic
    """


@dataclass(frozen=True)
class SpectralMoments:
    """Profile moments of a height map (averaged over the two axes).

    Attributes
    ----------
    m0 : float
        Variance of the heights (m^2).
    m2, m4 : float
        Profile slope variance (-) and profile curvature variance (1/m^2): the means of the
        values along axis 0 (``m2_x``, ``m4_x``) and axis 1 (``m2_y``, ``m4_y``).
    m2_x, m2_y, m4_x, m4_y : float
        The same along axis 0 (x) and axis 1 (y).
    method : str
        "grid" or "fft" (:func:`spectral_moments`).

    Notes
    -----
    ``alpha`` = m0 m4 / m2^2 is Nayak's (1971) bandwidth parameter; ``anisotropy`` is the larger of
    abs(m2_x - m2_y) / m2 and abs(m4_x - m4_y) / m4.

    Examples
    --------
    >>> m = SpectralMoments(1e-12, 1e-4, 1e4, 1e-4, 1e-4, 1e4, 1e4, "grid")
    >>> round(m.alpha, 12), m.anisotropy
    (1.0, 0.0)
    """

    m0: float
    m2: float
    m4: float
    m2_x: float
    m2_y: float
    m4_x: float
    m4_y: float
    method: str

    @property
    def alpha(self) -> float:
        """Bandwidth parameter m0 m4 / m2^2 (-) (Nayak 1971); NaN when m2 = 0."""
        return self.m0 * self.m4 / self.m2**2 if self.m2 > 0 else math.nan

    @property
    def anisotropy(self) -> float:
        """max(abs(m2_x - m2_y) / m2, abs(m4_x - m4_y) / m4) (-), 0 for an isotropic map."""
        a2 = abs(self.m2_x - self.m2_y) / self.m2 if self.m2 > 0 else 0.0
        a4 = abs(self.m4_x - self.m4_y) / self.m4 if self.m4 > 0 else 0.0
        return max(a2, a4)


@dataclass(frozen=True)
class SpectralGW:
    """Greenwood-Williamson parameters from moments (:func:`gw_from_moments`).

    Attributes
    ----------
    eta : float
        Summit density (1/m^2).
    R : float
        Mean summit radius of curvature (m): the ``R_a`` of :class:`~fastrest.rough.RoughSurface`.
    sigma_s : float
        Standard deviation of the summit heights (m).
    alpha : float
        Bandwidth parameter m0 m4 / m2^2 (-).
    A_n : float
        Nominal area (m^2).
    gw : GreenwoodWilliamson
        ``GreenwoodWilliamson(eta=eta, sigma=sigma_s, A_n=A_n)`` (Gaussian summit heights).

    Examples
    --------
    >>> p = gw_from_moments(1e-11, 1e-4, 1e4, 1e-6)
    >>> round(p.n_summits, 6), p.gw.A_n
    (3.062938, 1e-06)
    """

    eta: float
    R: float
    sigma_s: float
    alpha: float
    A_n: float
    gw: GreenwoodWilliamson

    @property
    def n_summits(self) -> float:
        """eta A_n (-)."""
        return self.eta * self.A_n


def _as_topography(t: Any, **options: Any) -> Topography:
    """A :class:`~fastrest.rough.Topography`: ``t`` itself, what :func:`load_topography` reads from
    a path or a SurfaceTopography object (with its reading ``options``), or an object with heights,
    dx, dy and periodic checked by the Topography constructor (reading options are then a
    ValueError, as for a Topography)."""
    if isinstance(t, (Topography, str, os.PathLike)) or (hasattr(t, "nb_grid_pts") and hasattr(t, "dim")):
        return as_topography(t, **options)
    given = [k for k, v in options.items() if v is not None]
    if given:
        raise ValueError(f"{', '.join(given)}: options for reading a map; this {type(t).__name__} is already a map "
                         "(give them with a file path or a SurfaceTopography topography)")
    if isinstance(t, (np.ndarray, list, tuple)) or not all(hasattr(t, a) for a in ("heights", "dx", "dy", "periodic")):
        raise TypeError("topography must be a fastrest.rough.Topography (see load_topography), a file path, a "
                        "SurfaceTopography topography, or an object with heights (m), dx, dy (m) and periodic; "
                        f"got {type(t).__name__}")
    return Topography(t.heights, t.dx, t.dy, t.periodic, type(t).__name__)


def _check_topography(t: Any) -> tuple[np.ndarray, float, float, bool]:
    """(heights, dx, dy, periodic) of a map (:func:`_as_topography`, whose Topography checks the
    heights (finite, 2-D) and the spacings), with at least 3 pixels along each axis."""
    t = _as_topography(t)
    z = t.heights
    if min(z.shape) < 3:
        raise ValueError(f"the height map must be 2D with at least 3 points along each axis; got shape {z.shape}")
    return z, t.dx, t.dy, t.periodic


def _grid_axis(z, h, axis, periodic):
    """(slope variance, curvature variance) along ``axis`` by central differences of spacing h."""
    if periodic:
        up, dn = np.roll(z, -1, axis), np.roll(z, 1, axis)
    else:  # interior points only
        n = z.shape[axis]
        up, dn = np.take(z, range(2, n), axis), np.take(z, range(0, n - 2), axis)
        z = np.take(z, range(1, n - 1), axis)
    slope = (up - dn) / (2.0 * h)
    curv = (up - 2.0 * z + dn) / (h * h)
    return float(np.var(slope)), float(np.var(curv))


def _fft_axes(z, dx, dy):
    """(m0, m2_x, m2_y, m4_x, m4_y) of the trigonometric interpolant of a periodic map (Parseval)."""
    nx, ny = z.shape
    p = np.abs(np.fft.fft2(z - z.mean()))**2 / float(nx * ny)**2
    qx = 2.0 * np.pi * np.fft.fftfreq(nx, dx)[:, None]
    qy = 2.0 * np.pi * np.fft.fftfreq(ny, dy)[None, :]
    return (float(p.sum()), float((p * qx**2).sum()), float((p * qy**2).sum()), float((p * qx**4).sum()),
            float((p * qy**4).sum()))


def spectral_moments(topography: Any, *, method: str = "grid", warn_anisotropy: bool = True) -> SpectralMoments:
    """Profile moments m0, m2, m4 of a height map, averaged over its two axes.

    Parameters
    ----------
    topography : fastrest.rough.topography.Topography
        The height map (m) with pixel spacings ``dx`` (axis 0) and ``dy`` (axis 1) (m) and the
        ``periodic`` flag (any object with these four attributes is accepted).
    method : {"grid", "fft"}, optional
        "grid" (default): m2, m4 are the variances of the central-difference slope
        (z[i+1] - z[i-1])/(2h) and curvature (z[i+1] - 2 z[i] + z[i-1])/h^2 along each axis, over
        all pixels of a periodic map (wrapping round) or the interior ones of a non-periodic map.
        These are the stencils of the explicit summits' curvature (Greenwood 1984), so a
        comparison of explicit and spectral surfaces measures the models, not the discretisation.
        "fft": the moments of the map's trigonometric interpolant, m_n,x = sum_q abs(h_q)^2 q_x^n
        (Parseval; q_x = 2 pi k / L_x, the Nyquist mode at q_x = -pi/dx); periodic maps only.
        On a map with power up to the Nyquist wavenumber, "fft" gives a larger m4 than "grid"
        (the discrete curvature of a mode is 4 sin^2(q h/2)/h^2 <= q^2).
    warn_anisotropy : bool, optional
        Warn (:class:`AnisotropyWarning`) when the two axes differ by more than
        :data:`ANISOTROPY_TOL` (default True).

    Returns
    -------
    SpectralMoments
        m0 (m^2), m2 (-), m4 (1/m^2), the per-axis values, ``alpha`` and ``anisotropy``.

    Raises
    ------
    TypeError
        If ``topography`` is not a Topography.
    ValueError
        For a map smaller than 3 x 3, non-finite heights or spacings, an unknown ``method``, or
        ``method="fft"`` on a non-periodic map.

    Warns
    -----
    AnisotropyWarning
        If m2 or m4 along the two axes differ by more than 20 % of their mean. A small random
        map whose m2 comes from a few long-wavelength modes can reach this by sampling alone
        (a 128 x 128 self-affine map with a 25-wavelength cutoff: 2-35 % over three seeds).

    Notes
    -----
    Profile moments in Nayak's (1971) sense: for an isotropic surface, m2 and m4 are the same
    along every direction; averaging the two axes halves the sampling error. A single sinusoid
    z = a cos(2 pi x / L) has m2_x = (2 pi a / L)^2 / 2 and m2_y = 0, so m2 = (2 pi a/L)^2/4.

    Examples
    --------
    >>> import numpy as np
    >>> from types import SimpleNamespace
    >>> x = np.arange(64) / 64
    >>> z = 1e-6 * (np.cos(2 * np.pi * 4 * x)[:, None] + np.cos(2 * np.pi * 4 * x)[None, :])
    >>> t = SimpleNamespace(heights=z, dx=1e-4 / 64, dy=1e-4 / 64, periodic=True)
    >>> m = spectral_moments(t, method="fft")
    >>> round(m.m0 * 1e12, 12), round(m.alpha, 12)
    (1.0, 2.0)
    """
    if method not in METHODS:
        raise ValueError(f"method must be one of {METHODS}; got {method!r}")
    z, dx, dy, periodic = _check_topography(topography)
    if method == "fft":
        if not periodic:
            raise ValueError('method="fft" needs a periodic map (a non-periodic one leaks power through its '
                             'edges); use method="grid"')
        m0, m2x, m2y, m4x, m4y = _fft_axes(z, dx, dy)
    else:
        m0 = float(np.var(z))
        m2x, m4x = _grid_axis(z, dx, 0, periodic)
        m2y, m4y = _grid_axis(z, dy, 1, periodic)
    m = SpectralMoments(m0, 0.5 * (m2x + m2y), 0.5 * (m4x + m4y), m2x, m2y, m4x, m4y, method)
    if warn_anisotropy and m.anisotropy > ANISOTROPY_TOL:
        warn(f"the height map is anisotropic: m2 along x, y = {m2x:.4g}, {m2y:.4g}, m4 = {m4x:.4g}, {m4y:.4g} "
             f"1/m^2 (differ by {100 * m.anisotropy:.0f} % > {100 * ANISOTROPY_TOL:.0f} %); Nayak's and McCool's "
             "formulas are for isotropic surfaces and use the means of the two axes", AnisotropyWarning)
    return m


def gw_from_moments(m0: float, m2: float, m4: float, A_n: float) -> SpectralGW:
    """Greenwood-Williamson parameters of an isotropic Gaussian surface from its profile moments.

    Parameters
    ----------
    m0 : float
        Variance of the heights (m^2), > 0.
    m2 : float
        Variance of the profile slope (-), > 0.
    m4 : float
        Variance of the profile curvature (1/m^2), > 0.
    A_n : float
        Nominal area (m^2), > 0.

    Returns
    -------
    SpectralGW
        eta = m4 / (6 pi sqrt(3) m2) (1/m^2), R = (3/8) sqrt(pi/m4) (m),
        sigma_s = sqrt(1 - 0.8968/alpha) sqrt(m0) (m), alpha = m0 m4/m2^2, A_n, and ``gw``, the
        :class:`GreenwoodWilliamson` (Gaussian summit heights).

    Raises
    ------
    ValueError
        If a moment or A_n is not finite and > 0, if alpha < :data:`ALPHA_MIN` = 1.5 (no
        isotropic surface has such moments), or if the surface has too few or too many summits
        for :class:`GreenwoodWilliamson`.
    TypeError
        If an argument is not a real number.

    Notes
    -----
    eta is Nayak's (1971) summit density of an isotropic Gaussian surface (exact for all alpha);
    R is the reciprocal of the mean summit curvature (8/3) sqrt(m4/pi) in Nayak's large-alpha
    limit; sigma_s is McCool's (1986) large-alpha approximation of the summit-height variance
    (sigma_s^2 = (1 - 0.8968/alpha) m0). McCool used these three to map spectral moments onto the
    GW model; summit heights are then taken as Gaussian (Nayak's are skewed for small alpha).

    Examples
    --------
    >>> p = gw_from_moments(1e-11, 1e-4, 1e4, 1e-6)
    >>> round(p.alpha, 12), round(p.eta / 1e6, 6), round(p.R * 1e3, 6)
    (10.0, 3.062938, 6.646702)
    """
    vals = {}
    for name, v, unit in (("m0", m0, "m^2"), ("m2", m2, "-"), ("m4", m4, "1/m^2"), ("A_n", A_n, "m^2")):
        x = real_scalar(v, name)
        if not (x > 0 and math.isfinite(x)):
            raise ValueError(f"{name} ({unit}) must be finite and > 0; got {x!r}"
                             + (" (a flat map has no summits)" if name != "A_n" else ""))
        vals[name] = x
    m0, m2, m4, A_n = vals["m0"], vals["m2"], vals["m4"], vals["A_n"]
    alpha = m0 * m4 / (m2 * m2)
    if not alpha >= ALPHA_MIN * (1.0 - 1e-12):
        raise ValueError(f"bandwidth parameter alpha = m0 m4 / m2^2 = {alpha:.6g} < {ALPHA_MIN}: no isotropic "
                         "surface has these moments (Nayak 1971: alpha >= 3/2), and McCool's summit statistics "
                         "need large alpha")
    eta = m4 / (6.0 * math.pi * math.sqrt(3.0) * m2)
    R = 0.375 * math.sqrt(math.pi / m4)
    sigma_s = math.sqrt(1.0 - 0.8968 / alpha) * math.sqrt(m0)
    gw = GreenwoodWilliamson(eta=eta, sigma=sigma_s, A_n=A_n)
    return SpectralGW(eta, R, sigma_s, alpha, A_n, gw)


def spectral_surface(topography: Any, material: Any, *, method: str = "grid", A_n: float | None = None,
                     et_ratio: float | None = None, loading: Any = None, detrend: str | None = None,
                     cutoff: float | None = None, unit: str | None = None,
                     physical_size: tuple[float, float] | None = None, periodic: bool | None = None) -> RoughSurface:
    """Statistical (Greenwood-Williamson) :class:`RoughSurface` of a height map, from its moments.

    Parameters
    ----------
    topography : Topography, str, os.PathLike or SurfaceTopography topography
        The height map (m): a :class:`~fastrest.rough.Topography`, or what
        :func:`~fastrest.rough.load_topography` reads (read with its defaults), or an object with
        ``heights`` (m), ``dx``, ``dy`` (m) and ``periodic`` (checked as a Topography).
    material : fastrest.Material
        The surface's material (the flat is rigid).
    method : {"grid", "fft"}, optional
        How the moments are computed (:func:`spectral_moments`; default "grid").
    A_n : float, optional
        Nominal area (m^2); default the map's area nx dx ny dy.
    et_ratio, loading : optional
        Strain hardening and loading law, as in :class:`RoughSurface`.
    detrend, cutoff, unit, physical_size, periodic : optional
        How a file path or a SurfaceTopography topography is read, as in
        :func:`~fastrest.rough.load_topography` (default: its defaults); a ValueError with a map
        already read.

    Returns
    -------
    RoughSurface
        ``RoughSurface(material, R, gw=GreenwoodWilliamson(eta=eta, sigma=sigma_s, A_n=A_n))``
        with eta, R, sigma_s of :func:`gw_from_moments`.

    Raises
    ------
    TypeError, ValueError
        As :func:`spectral_moments`, :func:`gw_from_moments` and :class:`RoughSurface`; a map that
        does not vary along one axis (no summits); a map too small or coarse for the model:
        Nayak's density above :data:`MAX_SUMMITS_PER_PIXEL` summits per pixel.

    Warns
    -----
    AnisotropyWarning
        For an anisotropic map (:func:`spectral_moments`).

    Notes
    -----
    Beside the explicit summits of the same map (``from_topography``), this model replaces the
    summits found on the map by Nayak's density, their radii by one mean radius and their heights
    by a Gaussian of McCool's standard deviation (docs/rough-spectral.md compares the two).

    Examples
    --------
    >>> import numpy as np, fastrest
    >>> from types import SimpleNamespace
    >>> from SurfaceTopography.Generation import fourier_synthesis
    >>> h = fourier_synthesis((128, 128), (1e-4, 1e-4), hurst=0.8, rms_height=1e-7, short_cutoff=4e-6, rng=3)
    >>> t = SimpleNamespace(heights=h.heights(), dx=1e-4 / 128, dy=1e-4 / 128, periodic=True)
    >>> s = spectral_surface(t, fastrest.Material(E=200e9, nu=0.3, Sy=1e9))
    >>> s.kind
    'statistical'
    """
    t = _as_topography(topography, detrend=detrend, cutoff=cutoff, unit=unit, physical_size=physical_size,
                       periodic=periodic)
    m = spectral_moments(t, method=method)
    for name, v in (("m2_x", m.m2_x), ("m2_y", m.m2_y), ("m4_x", m.m4_x), ("m4_y", m.m4_y)):
        if not v > 0.0:
            raise ValueError(f"{name} = {v!r}: the map does not vary along {'axis 0 (x)' if name.endswith('x') else 'axis 1 (y)'}, "
                             "so it has no summits; Nayak's and McCool's formulas are for isotropic areal surfaces")
    p = gw_from_moments(m.m0, m.m2, m.m4, t.area if A_n is None else A_n)
    per_pixel = p.eta * t.dx * t.dy
    if per_pixel > MAX_SUMMITS_PER_PIXEL:
        raise ValueError(f"Nayak's summit density eta = {p.eta:.6g} 1/m^2 gives {per_pixel:.3g} summits per pixel of "
                         f"{t.shape[0]} x {t.shape[1]}, more than the {MAX_SUMMITS_PER_PIXEL} a grid can hold (strict "
                         "maxima are never neighbours): the map is too small or too coarse for the spectral model")
    return RoughSurface(material, p.R, gw=p.gw, et_ratio=et_ratio, loading=loading)
