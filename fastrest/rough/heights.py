"""Summit heights: a Gaussian sample (explicit surfaces) or a distribution (statistical surfaces).

:func:`gaussian_summits` draws explicit heights; :class:`GreenwoodWilliamson` describes a surface by
its summit density, height standard deviation, nominal area and height pdf (Greenwood &
Williamson 1966); :func:`gw_data` turns it into the :class:`~fastrest.rough.expectations.GWData`
the kernels read.
"""
from __future__ import annotations

from typing import Any, cast
from numpy.typing import ArrayLike, NDArray
import math
import numbers
from dataclasses import dataclass

import numpy as np

from .._validation import check_count, check_finite_positive, real_scalar
from ..interpolation import GAUSS_U, chebyshev_nodes, fit_cells
from .expectations import GWData

__all__ = ["gaussian_summits", "GreenwoodWilliamson", "gw_data", "MIN_SUMMITS", "MAX_SUMMITS", "SIGMA_SAMPLE_MAX",
           "PDF_CELLS_PER_SIGMA"]

#: Fewest summits (N = eta A_n) of a statistical surface: below it the flat would have to sink
#: tens of standard deviations into the tail of the height distribution to stop.
MIN_SUMMITS = 1e-6
#: Most summits of a statistical surface.
MAX_SUMMITS = 1e30
#: Cells per sigma of a tabulated user pdf (degree-5 Chebyshev cells).
PDF_CELLS_PER_SIGMA = 64
#: Largest sigma of :func:`gaussian_summits` (m): a normal draw never exceeds 64 sigma, so the heights
#: stay finite doubles.
SIGMA_SAMPLE_MAX = 2.0**1017


def gaussian_summits(n: int, sigma: float, seed: int | np.random.Generator | None = None) -> NDArray[np.float64]:
    """Summit heights drawn from a normal distribution of mean 0.

    Parameters
    ----------
    n : int
        Number of summits (-), 1 <= n <= 1e9 (an integer-valued float is accepted; a bool is not).
    sigma : float
        Standard deviation of the heights (m), 0 < sigma <= 2^1017 (~1.4e306: larger heights
        would overflow double precision).
    seed : int or numpy.random.Generator, optional
        Seed of :func:`numpy.random.default_rng` (an integer >= 0, a sequence of them, a
        ``SeedSequence``, ``BitGenerator`` or ``Generator``); the same seed gives the same heights.

    Returns
    -------
    ndarray
        ``n`` heights (m), for ``RoughSurface(material, R_a, heights=...)``.

    Raises
    ------
    ValueError
        If ``n`` is not a whole number in [1, 1e9], ``sigma`` is not in (0, 2^1017] or ``seed`` is
        negative or not a whole number.
    TypeError
        If ``n`` or ``sigma`` is not a real number (a bool, a string, None), or ``seed`` is not an
        integer, a sequence of them or a NumPy random generator.

    Notes
    -----
    Greenwood & Williamson (1966) model summit heights as Gaussian; docs/rough.md section 4
    compares a sample of 1e6 such summits with the statistical model.

    Examples
    --------
    >>> from fastrest import rough
    >>> z = rough.gaussian_summits(1000, 50e-9, seed=1)
    >>> z.shape
    (1000,)
    """
    n = check_count(n, "n (number of summits)", 1, 10**9)
    sigma = float(check_finite_positive(real_scalar(sigma, "sigma"), "sigma",
                                        "(m, standard deviation of summit heights)"))
    if sigma > SIGMA_SAMPLE_MAX:
        raise ValueError(f"sigma (m, standard deviation of summit heights) must be in (0, 2^1017 = "
                         f"{SIGMA_SAMPLE_MAX:.4g}]: larger heights overflow double precision; got {sigma!r}")
    z = _generator(seed).normal(0.0, sigma, n)
    if not np.all(np.isfinite(z)):  # cannot happen below SIGMA_SAMPLE_MAX; never return inf heights
        raise ValueError(f"sigma = {sigma!r} m gives heights beyond double precision")
    return z


def _generator(seed):
    """numpy.random.default_rng(seed), with errors that name ``seed``: TypeError for a bool, a float
    or another non-integer, ValueError for a negative or fractional number."""
    if seed is None or isinstance(seed, (np.random.Generator, np.random.BitGenerator, np.random.SeedSequence)):
        return np.random.default_rng(seed)
    what = "seed must be None, an integer >= 0, a sequence of them, or a numpy.random.Generator"
    if isinstance(seed, (bool, np.bool_)) or (isinstance(seed, (list, tuple)) and any(
            isinstance(x, (bool, np.bool_)) for x in seed)):
        raise TypeError(f"{what}; got {seed!r} (a bool is not a seed)")
    if isinstance(seed, numbers.Real) and not isinstance(seed, numbers.Integral):
        raise ValueError(f"{what}; got {seed!r} (not an integer)")
    if isinstance(seed, numbers.Integral) and seed < 0:
        raise ValueError(f"{what}; got {seed!r}")
    try:
        return np.random.default_rng(seed)
    except TypeError as exc:
        raise TypeError(f"{what}; got {seed!r} ({exc})") from None
    except ValueError as exc:
        raise ValueError(f"{what}; got {seed!r} ({exc})") from None


@dataclass(frozen=True)
class GreenwoodWilliamson:
    """Statistical description of a rough surface (Greenwood & Williamson 1966).

    Parameters
    ----------
    eta : float
        Summit density (1/m^2), > 0.
    sigma : float, optional
        Standard deviation of summit heights (m), > 0. Required for Gaussian heights; with a user
        ``pdf`` it defaults to the pdf's standard deviation (computed).
    A_n : float
        Nominal (apparent) contact area (m^2), > 0. The surface has N = eta A_n summits, with
        1e-6 <= N <= 1e30.
    pdf : callable, optional
        Summit-height probability density p(z) (1/m) of heights z (m) above the mean summit plane,
        vectorised over a NumPy array. Default: Gaussian with standard deviation sigma. It is
        tabulated on ``support`` (64 degree-5 cells per sigma) and normalised to 1 there. For
        Dask sweeps it must be picklable (a module-level function).
    support : (float, float), optional
        Heights (m) outside which ``pdf`` is zero; required with ``pdf``.

    Attributes
    ----------
    n_summits : float
        N = eta A_n (-).

    Raises
    ------
    ValueError
        For a parameter out of range (named in the message), a pdf without support, or a
        support with the Gaussian.
    TypeError
        For a non-numeric eta, sigma, A_n or support.

    Notes
    -----
    The sums over summits of docs/rough.md section 3 become N times expectations over the height
    distribution (section 4); the plasticity index is psi = sqrt(sigma/omega_c) (section 5).

    Examples
    --------
    >>> from fastrest import rough
    >>> rough.GreenwoodWilliamson(eta=1e10, sigma=50e-9, A_n=1e-4).n_summits
    1000000.0
    """

    eta: float
    sigma: float | None = None
    A_n: float = 1.0
    pdf: object = None
    support: tuple[Any, ...] | None = None

    def __post_init__(self):
        # plain floats: an array or a string here would fail far from its cause
        for name in ("eta", "A_n") + (("sigma",) if self.sigma is not None else ()):
            object.__setattr__(self, name, real_scalar(getattr(self, name), name))
        check_finite_positive(self.eta, "eta", "(1/m^2, summit density)")
        check_finite_positive(self.A_n, "A_n", "(m^2, nominal area)")
        n = self.eta * self.A_n
        if not (MIN_SUMMITS <= n <= MAX_SUMMITS):
            raise ValueError(f"the surface has N = eta A_n = {n!r} summits (eta = {self.eta!r} 1/m^2, A_n = "
                             f"{self.A_n!r} m^2); N must be in [{MIN_SUMMITS:g}, {MAX_SUMMITS:g}]")
        if self.pdf is None:
            if self.sigma is None:
                raise TypeError("sigma (m, standard deviation of summit heights) is required for the Gaussian "
                                "(it may be omitted only with a user pdf)")
            if self.support is not None:
                raise ValueError("support applies to a user pdf only (the Gaussian is integrated "
                                 "until its tail is negligible)")
        else:
            if not callable(self.pdf):
                raise ValueError("pdf must be a callable p(z) (1/m)")
            if self.support is None or np.ndim(self.support) != 1 or len(self.support) != 2:
                raise ValueError("a user pdf needs support=(z_lo, z_hi) (m)")
            lo, hi = (real_scalar(v, "support") for v in self.support)
            if not (math.isfinite(lo) and math.isfinite(hi) and lo < hi):
                raise ValueError(f"support must be finite with z_lo < z_hi (m); got {self.support!r}")
        if self.sigma is not None:
            check_finite_positive(self.sigma, "sigma", "(m, standard deviation of summit heights)")

    @property
    def n_summits(self) -> float:
        """N = eta A_n, the expected number of summits on the nominal area (-)."""
        return self.eta * self.A_n


def _tabulated_pdf(gw, scale):
    """(edges, rows) of the pdf of z/scale on degree-5 cells, normalised to 1 on the support."""
    zs_lo, zs_hi = (float(v) / scale for v in gw.support)
    ncell = max(4, int(math.ceil((zs_hi - zs_lo) * PDF_CELLS_PER_SIGMA)))
    edges_zs = np.linspace(zs_lo, zs_hi, ncell + 1)
    edges = np.stack([edges_zs[:-1], edges_zs[1:]], axis=1)
    nodes = chebyshev_nodes(edges, GAUSS_U)  # a pdf need not be defined at its support's ends
    try:
        vals = np.asarray(gw.pdf(nodes * scale), dtype=np.float64) * scale
    except Exception:  # not vectorised
        vals = np.array([float(gw.pdf(float(z))) for z in (nodes * scale).ravel()]).reshape(nodes.shape) * scale
    if vals.shape != nodes.shape or not np.all(np.isfinite(vals)) or np.any(vals < 0):
        raise ValueError("pdf must return finite, non-negative densities on its support")
    rows = fit_cells(edges, vals, GAUSS_U)
    # exact integrals of the cell polynomials: half * sum over even k of c_k 2/(k+1)
    half = 0.5 * (edges[:, 1] - edges[:, 0])
    k = np.arange(6)
    even = np.where(k % 2 == 0, 2.0 / (k + 1), 0.0)
    mass = float(np.sum(half * (rows[:, 2:] @ even)))
    if not (mass > 0 and math.isfinite(mass)):
        raise ValueError("pdf integrates to zero over its support")
    rows[:, 2:] /= mass
    return edges, rows


def _std(edges, rows):
    """Standard deviation of the tabulated density (Gauss-Legendre, exact for the cells)."""
    half = 0.5 * (edges[:, 1] - edges[:, 0])
    gx, gwt = np.polynomial.legendre.leggauss(8)
    center = 0.5 * (edges[:, 0] + edges[:, 1])
    pts = center[:, None] + half[:, None] * gx[None, :]
    u = gx[None, :]
    pv = sum(rows[:, 2 + j][:, None] * u**j for j in range(6))
    wts = half[:, None] * gwt[None, :] * pv
    m1 = float(np.sum(wts * pts))
    m2 = float(np.sum(wts * pts**2))
    return math.sqrt(max(m2 - m1 * m1, 0.0))


def gw_data(gw: GreenwoodWilliamson, omega_c: float) -> tuple[GWData, float]:
    """The kernels' :class:`~fastrest.rough.expectations.GWData` of ``gw``, and its sigma (m).

    Parameters
    ----------
    gw : GreenwoodWilliamson
        The surface's height statistics.
    omega_c : float
        Critical interference of one summit (m), JGM eq (4).

    Returns
    -------
    (GWData, float)
        The kernel data (heights in zs = z/sigma; rho_w = sigma/omega_c) and sigma (m): the
        given one, or the standard deviation of the user pdf.

    Raises
    ------
    ValueError
        If the pdf is negative, not finite, or zero on its support.

    Notes
    -----
    A user pdf is tabulated on degree-5 cells (:data:`PDF_CELLS_PER_SIGMA` per sigma) at
    Gauss-Legendre nodes and normalised by the cells' exact integrals.

    Examples
    --------
    >>> from fastrest.rough import heights
    >>> g, sigma = heights.gw_data(heights.GreenwoodWilliamson(eta=1e10, sigma=2e-8, A_n=1e-4), 1e-8)
    >>> g.rho_w, g.n_total, sigma
    (2.0, 1000000.0, 2e-08)
    """
    if gw.pdf is None:
        sigma = float(cast(float, gw.sigma))  # set whenever pdf is None (__post_init__)
        return GWData(0, float(gw.n_summits), sigma / omega_c, -np.inf, np.inf, 0.0, np.zeros((1, 8))), sigma
    if gw.sigma is None:  # tabulate on a provisional scale to find sigma, then again in z/sigma
        support = cast(tuple[float, float], gw.support)  # required with a pdf (__post_init__)
        span = float(support[1]) - float(support[0])
        edges, rows = _tabulated_pdf(gw, span / 8.0)
        sigma = _std(edges, rows) * span / 8.0
        check_finite_positive(sigma, "sigma", "(m, standard deviation of summit heights)")
    else:
        sigma = float(gw.sigma)
    edges, rows = _tabulated_pdf(gw, sigma)
    zs_lo, zs_hi = float(edges[0, 0]), float(edges[-1, 1])
    data = GWData(1, float(gw.n_summits), sigma / omega_c, zs_lo, zs_hi, edges.shape[0] / (zs_hi - zs_lo),
                  np.ascontiguousarray(rows))
    return data, sigma
