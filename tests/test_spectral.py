"""Tests of fastrest.rough.spectral: profile moments of a height map, the Nayak/McCool GW parameters,
and the statistical surface built from them.

References used here:
* closed forms of sinusoids, continuous (fft) and discrete (central differences: a mode of
  wavenumber q has slope factor sin(q h)/h and curvature factor 4 sin^2(q h/2)/h^2);
* the published formulas (Nayak 1971; McCool 1986) evaluated by hand below, not by the code;
* the count of strict 8-neighbour maxima of a self-affine map against Nayak's summit density.
"""
import math
import warnings
from dataclasses import dataclass
from types import SimpleNamespace

import numpy as np
import pytest

import fastrest
from fastrest import rough
from fastrest.rough import spectral
from fastrest.rough.spectral import (AnisotropyWarning, SpectralGW, gw_from_moments, spectral_moments,
                                     spectral_surface)

try:  # engineer A's Topography; a stand-in with the same fields until it exists
    from fastrest.rough.topography import Topography as _Topo

    def topo(z, dx, dy=None, periodic=True):
        return _Topo(heights=np.asarray(z, dtype=np.float64), dx=dx, dy=dx if dy is None else dy,
                     periodic=periodic, source="test")
except ImportError:  # pragma: no cover - depends on the checkout
    @dataclass(frozen=True)
    class _Topo:
        heights: np.ndarray
        dx: float
        dy: float
        periodic: bool
        source: str = "test"

    def topo(z, dx, dy=None, periodic=True):
        return _Topo(np.asarray(z, dtype=np.float64), dx, dx if dy is None else dy, periodic)

STEEL = fastrest.Material(E=200e9, nu=0.3, Sy=1e9)


def cosine_map(n, k, a, L, axis=0, ny=None):
    """a cos(2 pi k x / L) on an n x ny periodic grid, varying along ``axis``."""
    ny = n if ny is None else ny
    x = np.arange(n if axis == 0 else ny) / (n if axis == 0 else ny)
    line = a * np.cos(2.0 * np.pi * k * x)
    return np.broadcast_to(line[:, None] if axis == 0 else line[None, :], (n, ny)).copy()


# ---------------------------------------------------------------- moments of sinusoids

@pytest.mark.parametrize("n,k", [(64, 5), (48, 3), (32, 7)])
def test_single_sinusoid_grid_exact(n, k):
    a, L = 3e-7, 2e-4
    h = L / n
    with pytest.warns(AnisotropyWarning):
        m = spectral_moments(topo(cosine_map(n, k, a, L), h))
    qh = 2.0 * np.pi * k / n  # discrete frequency q h
    m2x = a**2 * math.sin(qh)**2 / (2.0 * h**2)
    m4x = a**2 * (4.0 * math.sin(qh / 2.0)**2 / h**2)**2 / 2.0
    assert m.m0 == pytest.approx(a**2 / 2.0, rel=1e-13)
    assert m.m2_x == pytest.approx(m2x, rel=1e-12)
    assert m.m4_x == pytest.approx(m4x, rel=1e-12)
    assert m.m2_y == 0.0 and m.m4_y == 0.0
    # convention: the mean over the two axes, so half the x value for a profile along x
    assert m.m2 == pytest.approx(m2x / 2.0, rel=1e-12) and m.m4 == pytest.approx(m4x / 2.0, rel=1e-12)
    assert m.method == "grid" and m.anisotropy == pytest.approx(2.0)


@pytest.mark.parametrize("n,k", [(64, 5), (48, 3), (32, 7)])
def test_single_sinusoid_fft_continuous(n, k):
    a, L = 3e-7, 2e-4
    with pytest.warns(AnisotropyWarning):
        m = spectral_moments(topo(cosine_map(n, k, a, L), L / n), method="fft")
    q = 2.0 * np.pi * k / L
    assert m.m0 == pytest.approx(a**2 / 2.0, rel=1e-12)
    assert m.m2_x == pytest.approx((q * a)**2 / 2.0, rel=1e-12)  # (2 pi a / lambda)^2 / 2
    assert m.m4_x == pytest.approx(q**4 * a**2 / 2.0, rel=1e-12)
    assert abs(m.m2_y) <= 1e-25 and abs(m.m4_y) <= 1e-25 * q**2
    assert m.m2 == pytest.approx((q * a)**2 / 4.0, rel=1e-12)
    # a single profile: alpha = m0 m4 / m2^2 = (a^2/2)(q^4 a^2/4)/(q^2 a^2/4)^2 = 2
    assert m.alpha == pytest.approx(2.0, rel=1e-12)


@pytest.mark.parametrize("method", ["grid", "fft"])
def test_two_sinusoids_x_and_y(method):
    """a cos(2 pi k1 x/Lx) + b cos(2 pi k2 y/Ly) on a 40 x 24 grid with dx != dy."""
    nx, ny, kx, ky, a, b = 40, 24, 3, 2, 2e-7, 1e-7
    Lx, Ly = 1e-4, 3e-5
    dx, dy = Lx / nx, Ly / ny
    z = cosine_map(nx, kx, a, Lx, 0, ny) + cosine_map(nx, ky, b, Ly, 1, ny)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", AnisotropyWarning)
        m = spectral_moments(topo(z, dx, dy), method=method)
    qx, qy = 2 * np.pi * kx / Lx, 2 * np.pi * ky / Ly
    if method == "fft":
        sx, cx, sy, cy = qx**2, qx**4, qy**2, qy**4
    else:
        sx, sy = math.sin(qx * dx)**2 / dx**2, math.sin(qy * dy)**2 / dy**2
        cx, cy = (4 * math.sin(qx * dx / 2)**2 / dx**2)**2, (4 * math.sin(qy * dy / 2)**2 / dy**2)**2
    assert m.m0 == pytest.approx((a**2 + b**2) / 2, rel=1e-12)
    assert m.m2_x == pytest.approx(a**2 * sx / 2, rel=1e-12)
    assert m.m2_y == pytest.approx(b**2 * sy / 2, rel=1e-12)
    assert m.m4_x == pytest.approx(a**2 * cx / 2, rel=1e-12)
    assert m.m4_y == pytest.approx(b**2 * cy / 2, rel=1e-12)
    assert m.alpha == pytest.approx(m.m0 * m.m4 / m.m2**2, rel=1e-15)


def test_isotropic_pair_no_warning_and_alpha_two():
    """cos along x plus the same cos along y: isotropic in m2, m4 (no warning), alpha = 2 (fft)."""
    n, k, a, L = 32, 4, 1e-7, 1e-4
    z = cosine_map(n, k, a, L, 0) + cosine_map(n, k, a, L, 1)
    with warnings.catch_warnings():
        warnings.simplefilter("error", AnisotropyWarning)
        m = spectral_moments(topo(z, L / n), method="fft")
        g = spectral_moments(topo(z, L / n))
    assert m.anisotropy < 1e-12 and g.anisotropy < 1e-12
    assert m.alpha == pytest.approx(2.0, rel=1e-12)


def test_non_periodic_interior_points():
    """A non-periodic map uses interior points only: for a linear ramp the slope is exact and the
    curvature zero (a periodic wrap would see a jump)."""
    n, h, s = 20, 1e-6, 0.01
    z = s * h * np.arange(n)[:, None] * np.ones((1, n))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", AnisotropyWarning)
        m = spectral_moments(topo(z, h, periodic=False))
    assert m.m2_x == pytest.approx(0.0, abs=1e-20)  # variance of a constant slope
    assert m.m4_x == pytest.approx(0.0, abs=1e-6)
    with pytest.raises(ValueError, match="periodic"):
        spectral_moments(topo(z, h, periodic=False), method="fft")


# ---------------------------------------------------------------- McCool / Nayak formulas

def test_mccool_formulas_by_hand():
    m0, m2, m4, A_n = 4e-14, 1e-3, 1e9, 2e-6
    # by hand from the published formulas:
    # alpha = 4e-14 * 1e9 / 1e-6 = 40
    # eta = m4 / (6 pi sqrt(3) m2) = 1e12 / 32.6483... = 3.06293831e10 1/m^2
    # R = 0.375 sqrt(pi/1e9) = 0.375 * 5.60499122e-5 = 2.10187171e-5 m
    # sigma_s = sqrt(1 - 0.8968/40) * 2e-7 = sqrt(0.97758) * 2e-7 = 1.97745796e-7 m
    p = gw_from_moments(m0, m2, m4, A_n)
    assert isinstance(p, SpectralGW)
    assert p.alpha == pytest.approx(40.0, rel=1e-14)
    assert p.eta == pytest.approx(3.06293831e10, rel=1e-8)
    assert p.R == pytest.approx(2.10187171e-5, rel=1e-8)
    assert p.sigma_s == pytest.approx(1.97745796e-7, rel=1e-8)
    assert p.n_summits == pytest.approx(3.06293831e10 * 2e-6, rel=1e-8)
    assert (p.gw.eta, p.gw.sigma, p.gw.A_n) == (p.eta, p.sigma_s, A_n)
    assert p.gw.pdf is None  # Gaussian summit heights


def test_alpha_at_bound_accepted():
    # alpha = 1.5 exactly (a ring spectrum): sigma_s = sqrt(1 - 0.8968/1.5) sqrt(m0)
    p = gw_from_moments(1.5e-14, 1e-4, 1e6, 1e-6)
    assert p.alpha == pytest.approx(1.5, rel=1e-14)
    assert p.sigma_s == pytest.approx(math.sqrt(1 - 0.8968 / 1.5) * math.sqrt(1.5e-14), rel=1e-14)


# ---------------------------------------------------------------- the statistical surface

def self_affine(n=128, hurst=0.8, cutoff_px=8, seed=3, L=1e-4, rms=1e-7):
    from SurfaceTopography.Generation import fourier_synthesis
    h = fourier_synthesis((n, n), (L, L), hurst=hurst, rms_height=rms, short_cutoff=cutoff_px * L / n, rng=seed)
    return topo(h.heights(), L / n)


def test_spectral_surface_matches_gw_from_moments():
    t = self_affine()
    s = spectral_surface(t, STEEL)
    m = spectral_moments(t)
    p = gw_from_moments(m.m0, m.m2, m.m4, 1e-8)
    assert s.kind == "statistical" and s.R_a == p.R
    assert (s.gw.eta, s.gw.sigma, s.gw.A_n) == pytest.approx((p.eta, p.sigma_s, 1e-8), rel=1e-12)
    r = s.impact(0.1, 1e-6)
    assert 0.0 < r.e <= 1.0
    h = spectral_surface(t, STEEL, et_ratio=0.01, method="fft", A_n=2e-8)
    assert h.et_ratio == 0.01 and h.law.name == "ghaednia" and h.gw.A_n == 2e-8


def _count_summits(z):
    """Strict 8-neighbour maxima of a periodic map (A's find_summits when present)."""
    mask = np.ones(z.shape, dtype=bool)
    for i in (-1, 0, 1):
        for j in (-1, 0, 1):
            if i or j:
                mask &= z > np.roll(np.roll(z, i, 0), j, 1)
    return int(mask.sum())


@pytest.mark.parametrize("hurst,seed", [(0.5, 1), (0.8, 2)])
def test_summit_density_vs_nayak(hurst, seed):
    """Count of 8-neighbour maxima per area vs Nayak's eta = m4/(6 pi sqrt(3) m2).

    Nayak's density is for a continuous isotropic Gaussian surface; a discrete map is sampled and
    the 8-neighbour test is a discrete definition of a summit (Greenwood 1984). On 256 x 256
    self-affine maps, measured while writing this test: with the short cutoff at 8 pixels the
    ratio count/(eta A) is 0.90-1.00 (grid or fft moments, ~160-330 summits, so +-6-8 % sampling
    error); at 4 pixels 0.82-0.92 (the grid undercounts close maxima); at 16-32 pixels 0.89-1.07
    (14-80 summits). The band asserted here is the loose one of +-30 %.
    """
    t = self_affine(n=256, hurst=hurst, cutoff_px=8, seed=seed)
    try:
        from fastrest.rough.summits import find_summits
        n_found = len(find_summits(t.heights, periodic=True)[0])
        assert n_found == _count_summits(t.heights)
    except ImportError:  # pragma: no cover
        n_found = _count_summits(t.heights)
    area = t.heights.size * t.dx * t.dy
    for method in ("grid", "fft"):
        m = spectral_moments(t, method=method, warn_anisotropy=False)
        eta = gw_from_moments(m.m0, m.m2, m.m4, area).eta
        assert 0.7 < n_found / (eta * area) < 1.3, (method, n_found, eta * area)


# ---------------------------------------------------------------- bad input

def test_alpha_too_small():
    with pytest.raises(ValueError, match="alpha"):
        gw_from_moments(1e-14, 1e-4, 1e4, 1e-6)  # alpha = 0.01


@pytest.mark.parametrize("args,name", [((0.0, 1e-4, 1e6, 1e-6), "m0"), ((1e-14, 0.0, 1e6, 1e-6), "m2"),
                                       ((1e-14, 1e-4, 0.0, 1e-6), "m4"), ((1e-14, 1e-4, 1e6, 0.0), "A_n"),
                                       ((math.nan, 1e-4, 1e6, 1e-6), "m0"), ((1e-14, -1e-4, 1e6, 1e-6), "m2"),
                                       ((1e-14, 1e-4, math.inf, 1e-6), "m4")])
def test_bad_moments(args, name):
    with pytest.raises(ValueError, match=name):
        gw_from_moments(*args)


def test_non_real_moments():
    with pytest.raises(TypeError):
        gw_from_moments("1e-14", 1e-4, 1e6, 1e-6)
    with pytest.raises(TypeError):
        gw_from_moments(np.ones(2), 1e-4, 1e6, 1e-6)


def test_flat_map_has_no_summits():
    m = spectral_moments(topo(np.zeros((16, 16)), 1e-6))
    assert m.m0 == m.m2 == m.m4 == 0.0
    with pytest.raises(ValueError, match="flat"):
        gw_from_moments(m.m0, m.m2, m.m4, 1e-10)
    with pytest.raises(ValueError, match="does not vary along axis 0"):
        spectral_surface(topo(np.zeros((16, 16)), 1e-6), STEEL)


@pytest.mark.parametrize("bad", [np.zeros((8, 8)), [[0.0] * 8] * 8, None, 1.0])
def test_not_a_topography(bad):
    with pytest.raises(TypeError, match="Topography"):
        spectral_moments(bad)
    with pytest.raises(TypeError, match="Topography"):
        spectral_surface(bad, STEEL)


def test_a_path_is_read_and_duck_typed_maps_are_checked(tmp_path):
    """A path goes through load_topography (a missing file is its ValueError); an object with
    heights, dx, dy, periodic is checked as a Topography (strings, bools, periodic='no' refused)."""
    with pytest.raises(ValueError, match="does not exist"):
        spectral_surface(str(tmp_path / "map.txt"), STEEL)
    for heights, periodic in (([["a"] * 8] * 8, True), (np.ones((8, 8), bool), True), (np.ones((8, 8)), "no")):
        with pytest.raises(TypeError, match="heights|periodic"):
            spectral_moments(SimpleNamespace(heights=heights, dx=1e-6, dy=1e-6, periodic=periodic))


@pytest.mark.filterwarnings("ignore::fastrest.rough.spectral.AnisotropyWarning")
@pytest.mark.parametrize("n", [3, 5])
def test_maps_too_small_for_the_spectral_model(n):
    """Nayak's density above 1/4 summit per pixel (strict maxima are never neighbours): refused
    (white noise on 3 x 3 and 5 x 5 pixels: 0.37 and 0.43 per pixel)."""
    z = np.random.default_rng(1).normal(size=(n, n)) * 1e-7
    with pytest.raises(ValueError, match="summits per pixel"):
        spectral_surface(topo(z, 1e-6), STEEL)


def test_a_corrugation_has_no_summits():
    x = np.arange(64)
    z = 1e-7 * np.cos(2 * np.pi * x / 16)[:, None] * np.ones((1, 64))
    with pytest.warns(Warning), pytest.raises(ValueError, match="does not vary along axis 1"):
        spectral_surface(topo(z, 1e-6), STEEL)


def test_bad_maps_and_method():
    good = np.random.default_rng(0).normal(size=(8, 8))
    with pytest.raises(ValueError, match="method"):
        spectral_moments(topo(good, 1e-6), method="psd")
    with pytest.raises(ValueError, match="2D"):
        spectral_moments(SimpleNamespace(heights=good[:2], dx=1e-6, dy=1e-6, periodic=True))
    bad = good.copy()
    bad[1, 1] = np.nan
    # bypass Topography's own checks: spectral_moments checks duck-typed maps too
    with pytest.raises(ValueError, match="finite"):
        spectral_moments(SimpleNamespace(heights=bad, dx=1e-6, dy=1e-6, periodic=True))
    with pytest.raises(ValueError, match="spacing"):
        spectral_moments(SimpleNamespace(heights=good, dx=-1e-6, dy=1e-6, periodic=True))
    with pytest.raises(TypeError):
        spectral_surface(self_affine(n=32, cutoff_px=4), "steel")


def test_exports():
    for name in ("spectral_moments", "gw_from_moments", "spectral_surface", "SpectralMoments", "SpectralGW"):
        assert name in spectral.__all__
        if name in rough.__all__:
            assert getattr(rough, name) is getattr(spectral, name)


def test_spectral_surface_takes_load_topographys_reading_options(tmp_path):
    """A file read with the options load_topography takes (periodic, detrend, ...) gives the
    surface of the map load_topography reads with them; with a map already read they are refused."""
    import SurfaceTopography as ST
    from fastrest.rough import load_topography

    t = self_affine(n=64)
    path = tmp_path / "map.x3p"
    ST.Topography(t.heights, (64 * t.dx, 64 * t.dy), unit="m", periodic=False).to_x3p(str(path))
    s = spectral_surface(path, STEEL, periodic=True, detrend="mean")
    read = load_topography(path, periodic=True, detrend="mean")
    assert read.periodic is True
    ref = spectral_surface(read, STEEL)
    assert (s.R_a, s.gw.eta, s.gw.sigma, s.gw.A_n) == (ref.R_a, ref.gw.eta, ref.gw.sigma, ref.gw.A_n)
    with pytest.raises(ValueError, match="periodic: options for reading a map"):
        spectral_surface(read, STEEL, periodic=True)
    with pytest.raises(ValueError, match="detrend: options for reading a map"):
        spectral_surface(t, STEEL, detrend="mean")
