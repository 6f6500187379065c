"""Measured topographies: reading (fastrest.rough.topography), summits and their radii, the rough
surface they make (fastrest.rough.summits), ``fastrest rough FILE`` (fastrest.rough.cli)."""
import json
import os
import pickle
import subprocess
import sys

import numpy as np
import pytest

import fastrest
from fastrest import cli
from fastrest.rough import (RoughSurface, Topography, TopographySummits, find_summits, from_topography,
                            load_topography, topography_summits)
from fastrest.rough import topography as topo_mod

ST = pytest.importorskip("SurfaceTopography")
from SurfaceTopography.Generation import fourier_synthesis  # noqa: E402

STEEL = fastrest.Material(200e9, 0.3, 1e9)


def brute_summits(h, periodic):
    """Reference: a plain loop over every pixel, strictly above its 8 neighbours."""
    nx, ny = h.shape
    out = set()
    for i in range(nx):
        for j in range(ny):
            if not periodic and (i in (0, nx - 1) or j in (0, ny - 1)):
                continue
            if all(h[i, j] > h[(i + di) % nx, (j + dj) % ny]
                   for di in (-1, 0, 1) for dj in (-1, 0, 1) if (di, dj) != (0, 0)):
                out.add((i, j))
    return out


def as_set(ij):
    return set(zip(ij[0].tolist(), ij[1].tolist()))


def maps():
    rng = np.random.default_rng(7)
    fs = fourier_synthesis((64, 64), (64e-6, 64e-6), hurst=0.8, rms_height=1e-7, unit="m",
                           rng=np.random.default_rng(3), periodic=True).heights()
    ties = rng.integers(0, 3, size=(15, 13)).astype(float)  # many equal neighbours
    plateau = np.zeros((9, 9))
    plateau[2:4, 2:4] = 1.0   # a 2 x 2 flat top: no summit
    plateau[6, 6] = 1.0       # one strict summit
    plateau[0, 4] = 2.0       # border pixel: a summit only when periodic
    return {"noise": rng.normal(size=(20, 17)), "fourier": fs, "ties": ties, "plateau": plateau}


@pytest.mark.parametrize("periodic", [False, True])
@pytest.mark.parametrize("name", ["noise", "fourier", "ties", "plateau"])
def test_find_summits_matches_brute_force(name, periodic):
    h = maps()[name]
    got = find_summits(h, periodic)
    assert as_set(got) == brute_summits(h, periodic)
    assert np.all(np.diff(got[0] * h.shape[1] + got[1]) > 0)  # C order


def test_plateau_and_border_rules():
    h = maps()["plateau"]
    assert as_set(find_summits(h)) == {(6, 6)}
    assert as_set(find_summits(h, periodic=True)) == {(6, 6), (0, 4)}
    assert find_summits(np.ones((5, 5)))[0].size == 0


def caps_map(caps, nx=48, ny=40, dx=1.0e-6, dy=1.5e-6, floor=-2e-7):
    """max over paraboloid caps z = h_k - r^2/(2 R_k), apex (i_k, j_k) on a pixel, over a flat floor.
    Every pixel but an apex has a higher neighbour (one step towards its cap's apex) or equal ones
    (the floor): the apexes are the only summits."""
    x = np.arange(nx)[:, None] * dx
    y = np.arange(ny)[None, :] * dy
    z = np.full((nx, ny), floor)
    for i, j, hk, rk in caps:
        z = np.maximum(z, hk - ((x - i * dx) ** 2 + (y - j * dy) ** 2) / (2.0 * rk))
    return z, dx, dy


CAPS = [(10, 10, 3e-7, 20e-6), (12, 28, 1e-7, 5e-6), (34, 12, 2e-7, 50e-6), (36, 30, 0.5e-7, 10e-6)]


def write_x3p(tmp_path, z, dx, dy, name="caps.x3p"):
    """ISO 25178-72 x3p written by SurfaceTopography (float64 'D' heights, metres)."""
    path = tmp_path / name
    ST.Topography(z, (z.shape[0] * dx, z.shape[1] * dy), unit="m", periodic=False).to_x3p(str(path))
    return path


def test_caps_from_x3p_heights_and_radii_exact(tmp_path):
    z, dx, dy = caps_map(CAPS)
    path = write_x3p(tmp_path, z, dx, dy)
    t = load_topography(path, detrend="none")
    assert t.shape == z.shape and t.periodic is False and t.source == str(path)
    np.testing.assert_array_equal(t.heights, z)  # float64 stored: read back bit for bit
    np.testing.assert_allclose([t.dx, t.dy], [dx, dy], rtol=1e-15)
    s = topography_summits(t)
    order = np.argsort(s.i)
    np.testing.assert_array_equal(s.i[order], [c[0] for c in CAPS])
    np.testing.assert_array_equal(s.heights[order], [c[2] for c in CAPS])  # exact: the apex pixels
    # Second differences of a paraboloid are exact in exact arithmetic (z_xx = -1/R). In floats
    # each neighbour difference dz = dx^2/(2R) ~ 2.5e-8 to 1e-7 m is taken between heights of up to
    # 3e-7 m rounded to 1 ulp (1e-16 relative): relative error <~ 4 ulp * h/dz ~ 1e-14; 1e-12 allows
    # for dx, dy read back from the file (1 ulp each).
    np.testing.assert_allclose(s.radii[order], [c[3] for c in CAPS], rtol=1e-12)
    assert (s.n_found, s.n_curvature_left_out, s.n_summits) == (4, 0, 4)
    assert s.n_border == 2 * 48 + 2 * 40 - 4 and s.n_pixels == 48 * 40
    # the default detrend (a plane) leaves the curvature as it was, bar rounding
    d = topography_summits(path)
    np.testing.assert_allclose(np.sort(d.radii), np.sort([c[3] for c in CAPS]), rtol=1e-9)


def test_curvature_uses_dx_along_axis_0_and_dy_along_axis_1():
    z = np.zeros((5, 5))
    z[2, 2] = 1e-7  # z_xx = -2e-7/dx^2, z_yy = -2e-7/dy^2
    t = Topography(heights=z, dx=1e-6, dy=2e-6, periodic=False, source="test")
    kappa = 0.5 * (2e-7 / 1e-12 + 2e-7 / 4e-12)
    np.testing.assert_allclose(topography_summits(t).radii, [1.0 / kappa], rtol=1e-15)


def test_flat_on_highest_cap_is_the_single_sphere(tmp_path):
    z, dx, dy = caps_map(CAPS)
    s = from_topography(write_x3p(tmp_path, z, dx, dy), STEEL, detrend="none")
    M, V = 1e-9, np.array([0.01, 0.1, 1.0])  # V_c ~ 0.02 m/s: elastic, then w* ~ 4 and 26
    r = s.impact(V, M)
    np.testing.assert_array_equal(r.n_contact, 1)  # the 1e-7 m gap to the next cap is never closed
    assert r.e[0] == 1.0 and np.all(r.e[1:] < 0.9) and np.all(r.n_yielded[1:] == 1)
    ref = fastrest.Impact(STEEL, 20e-6, mass=M).e(V)
    np.testing.assert_allclose(r.e, ref, rtol=1e-9)


def test_identical_caps_share_the_mass(tmp_path):
    caps = [(10, 10, 1e-7, 20e-6), (10, 28, 1e-7, 20e-6), (34, 10, 1e-7, 20e-6), (34, 28, 1e-7, 20e-6)]
    z, dx, dy = caps_map(caps)
    s = from_topography(write_x3p(tmp_path, z, dx, dy), STEEL, detrend="none")
    M, V = 4e-9, np.array([0.01, 0.3])
    r = s.impact(V, M)
    np.testing.assert_array_equal(r.n_contact, 4)
    np.testing.assert_allclose(r.e, fastrest.Impact(STEEL, 20e-6, mass=M / 4).e(V), rtol=1e-9)


def test_surface_carries_the_record_and_pickles(tmp_path):
    z, dx, dy = caps_map(CAPS)
    s = from_topography(write_x3p(tmp_path, z, dx, dy), STEEL)
    assert isinstance(s, RoughSurface) and isinstance(s.topography_summits, TopographySummits)
    assert s.topography_summits.counts()["n_summits"] == s.n_summits == 4
    np.testing.assert_allclose(s.topography_summits.density, 4 / (48e-6 * 60e-6), rtol=1e-12)
    s2 = pickle.loads(pickle.dumps(s))
    assert s2.topography_summits.n_found == 4
    np.testing.assert_array_equal(s2.impact(0.01, 1e-9).e, s.impact(0.01, 1e-9).e)


def test_topography_object_and_properties():
    t0 = fourier_synthesis((32, 24), (32e-6, 48e-6), hurst=0.8, rms_height=1e-7, unit="um",
                           rng=np.random.default_rng(1), periodic=True)
    t = load_topography(t0, detrend="mean")
    assert t.periodic is True and t.shape == (32, 24) and t.heights.dtype == np.float64
    assert t.heights.flags.c_contiguous and not t.heights.flags.writeable
    np.testing.assert_allclose(t.physical_size, (32e-12, 48e-12), rtol=1e-15)  # um -> m
    np.testing.assert_allclose(t.area, 32e-12 * 48e-12, rtol=1e-15)
    np.testing.assert_allclose(t.heights, (t0.heights() - t0.heights().mean()) * 1e-6, rtol=1e-12, atol=1e-22)
    assert load_topography(t0).periodic is True  # the default for a periodic map: the mean removed
    with pytest.warns(UserWarning, match="non-periodic"):
        assert load_topography(t0, detrend="height").periodic is False  # a plane removed (SurfaceTopography)


@pytest.mark.filterwarnings("ignore:`axes` should not be:DeprecationWarning")
def test_cutoff():
    t0 = fourier_synthesis((32, 32), (32e-6, 32e-6), hurst=0.8, rms_height=1e-7, unit="m",
                           rng=np.random.default_rng(2), periodic=True)
    per = load_topography(t0, detrend="none", cutoff=8e-6)
    ref = t0.shortcut(cutoff_wavelength=8e-6).heights()
    np.testing.assert_allclose(per.heights, ref, rtol=0, atol=1e-12 * np.abs(ref).max())
    flat = ST.Topography(t0.heights(), t0.physical_sizes, unit="m", periodic=False)
    # below the grid's shortest wavelength (the diagonal, sqrt(2) dx) nothing is removed
    kept = load_topography(flat, detrend="none", cutoff=1e-6)
    np.testing.assert_allclose(kept.heights, t0.heights(), rtol=0, atol=1e-12 * np.abs(ref).max())
    smooth = load_topography(flat, detrend="none", cutoff=16e-6)
    assert smooth.periodic is False and smooth.heights.std() < t0.heights().std()
    assert find_summits(smooth.heights)[0].size < find_summits(t0.heights())[0].size
    with pytest.raises(ValueError, match="no summit"):
        from_topography(flat, STEEL, cutoff=1.0)  # everything but the mean removed
    # a non-periodic map is filtered as its mirror extension: a half-cosine across the map (one
    # wavelength of the 2nx extension, 64 um) survives a 16 um cutoff, without edge ringing
    i = np.arange(32)[:, None] + 0.5
    wave = 1e-7 * np.cos(np.pi * i / 32) * np.ones((1, 24))
    out = load_topography(ST.Topography(wave, (32e-6, 24e-6), unit="m"), detrend="none", cutoff=16e-6)
    np.testing.assert_allclose(out.heights, wave, rtol=0, atol=1e-12 * 1e-7)


def test_bad_files_and_maps(tmp_path, capfd):
    junk = tmp_path / "junk.x3p"
    junk.write_bytes(os.urandom(300))
    with pytest.raises(ValueError, match="cannot read file .*junk.x3p"):
        load_topography(junk)
    out, err = capfd.readouterr()
    assert out == "" and err == ""  # SurfaceTopography's readers print what they try: kept quiet
    (tmp_path / "adir").mkdir()
    with pytest.raises(ValueError, match="adir' is a directory"):
        load_topography(tmp_path / "adir")
    with pytest.raises(ValueError, match="file .*missing.x3p' does not exist"):
        load_topography(tmp_path / "missing.x3p")
    np.savetxt(tmp_path / "plain.txt", np.random.default_rng(0).normal(size=(6, 5)))
    with pytest.raises(ValueError, match="units of length .*give unit"):
        load_topography(tmp_path / "plain.txt")
    t = load_topography(tmp_path / "plain.txt", unit="nm", physical_size=(5e-6, 6e-6))
    assert t.shape == (5, 6)  # SurfaceTopography reads a text matrix's columns along x (axis 0)
    np.testing.assert_allclose([t.dx, t.dy], [1e-6, 1e-6], rtol=1e-12)
    nan = np.zeros((6, 7))
    nan[2, 3] = nan[4, 1] = np.nan
    with pytest.raises(ValueError, match=r"2 undefined .*\(2, 3\), \(4, 1\)"):
        load_topography(ST.Topography(nan, (6e-6, 7e-6), unit="m"))
    with pytest.raises(ValueError, match="line scan"):
        load_topography(ST.UniformLineScan(np.arange(10.0), 1e-5, unit="m"))
    with pytest.raises(ValueError, match="lacks its units of length"):
        load_topography(ST.Topography(np.zeros((4, 4)), (1.0, 1.0)))
    x, y = np.meshgrid(np.arange(9.0), np.arange(8.0), indexing="ij")
    for z in (1e-9 * (x + 2 * y), 1e-9 * ((x - 4) ** 2 + (y - 4) ** 2)):  # a plane and a bowl
        with pytest.raises(ValueError, match="no summit"):
            from_topography(ST.Topography(z, (9e-6, 8e-6), unit="m"), STEEL, detrend="none")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["adir", "junk.x3p", "plain.txt"]  # nothing written


def test_too_large_is_refused_before_reading(tmp_path, monkeypatch):
    z, dx, dy = caps_map(CAPS)
    path = write_x3p(tmp_path, z, dx, dy)
    monkeypatch.setattr(topo_mod, "available_memory", lambda: 10_000)
    with pytest.raises(ValueError, match=r"48 x 40 = 1920 pixels: .*GiB, more than"):
        load_topography(path)
    assert topo_mod.available_memory() == 10_000


def test_wrong_types():
    t = ST.Topography(np.zeros((4, 4)), (1.0, 1.0), unit="m")
    with pytest.raises(TypeError, match="source"):
        load_topography(3.0)
    for kw, name in ((dict(detrend=1), "detrend"), (dict(cutoff="1"), "cutoff"), (dict(unit=3), "unit"),
                     (dict(physical_size="ab"), "physical_size"), (dict(periodic=1), "periodic")):
        with pytest.raises(TypeError, match=name):
            load_topography(t, **kw)
    with pytest.raises(ValueError, match="detrend"):
        load_topography(t, detrend="plane")
    with pytest.raises(ValueError, match="unit = 'furlong' is not a length unit"):
        load_topography(ST.Topography(np.zeros((4, 4)), (1.0, 1.0)), unit="furlong")
    with pytest.raises(TypeError, match="periodic"):
        find_summits(np.zeros((4, 4)), periodic="yes")
    with pytest.raises(ValueError, match="NaN"):
        find_summits(np.full((4, 4), np.nan))
    with pytest.raises(ValueError, match="2-D"):
        find_summits(np.zeros(9))
    with pytest.raises(ValueError, match="cutoff"):
        from_topography(Topography(np.zeros((3, 3)), 1.0, 1.0, False, "x"), STEEL, cutoff=1.0)


ARGS = ["--E", "200e9", "--nu", "0.3", "--Sy", "1e9", "--M", "1e-9", "--V", "0.01", "0.3"]


def test_cli_table_and_json(tmp_path, capsys):
    z, dx, dy = caps_map(CAPS)
    path = str(write_x3p(tmp_path, z, dx, dy))
    assert cli.main(["rough", path, *ARGS, "--detrend", "none"]) == 0
    out = capsys.readouterr().out
    assert "summits: 4 (4 strict 8-neighbour maxima, 0 left out" in out and "n_contact" in out
    assert cli.main(["rough", path, *ARGS, "--detrend", "none", "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert d["topography"]["n_summits"] == 4 and [r["n_contact"] for r in d["impacts"]] == [1, 1]
    np.testing.assert_allclose([r["e"] for r in d["impacts"]],
                               fastrest.Impact(STEEL, 20e-6, mass=1e-9).e([0.01, 0.3]), rtol=1e-9)
    assert cli.main(["rough", path, *ARGS, "--physical-size", "1", "1"]) == 2
    err = capsys.readouterr().err
    assert err.startswith("fastrest rough: error: ") and "--physical-size is not accepted" in err


def test_cli_keeps_the_speeds_the_model_covers(tmp_path, capsys):
    """A speed past the model's end among valid ones: the valid rows are printed (the same e as
    alone), the refused speed gets its own error line, the exit status is 1."""
    z, dx, dy = caps_map(CAPS)
    path = str(write_x3p(tmp_path, z, dx, dy))
    head = ARGS[:ARGS.index("--V")]
    assert cli.main(["rough", path, *head, "--V", "0.01", "1e4", "0.3", "--detrend", "none", "--json"]) == 1
    captured = capsys.readouterr()
    d = json.loads(captured.out)
    assert [r["V"] for r in d["impacts"]] == [0.01, 0.3] and [r["V"] for r in d["refused"]] == [1e4]
    assert captured.err.count("fastrest rough: error: --V 10000: ") == 1
    assert cli.main(["rough", path, *ARGS, "--detrend", "none", "--json"]) == 0
    alone = json.loads(capsys.readouterr().out)
    assert [r["e"] for r in d["impacts"]] == [r["e"] for r in alone["impacts"]]
    assert cli.main(["rough", path, *head, "--V", "1e4", "--detrend", "none"]) == 2  # none covered


def test_cli_unit_slip_warnings_name_the_options(tmp_path, capsys):
    """--E in GPa: the warnings name --E, not the Material, Impact or sphere.E of the summits."""
    import warnings
    z, dx, dy = caps_map(CAPS)
    path = str(write_x3p(tmp_path, z, dx, dy))
    with warnings.catch_warnings():
        warnings.simplefilter("always")
        cli.main(["rough", path, "--E", "200", "--nu", "0.3", "--Sy", "1e9", "--M", "1e-9", "--V", "1e-6",
                  "--detrend", "none"])
    err = capsys.readouterr().err
    assert "fastrest rough: warning: --E = 200.0 Pa is below" in err, err
    assert "Material:" not in err and "Impact:" not in err and "sphere.E" not in err, err


def test_without_surfacetopography(tmp_path, monkeypatch):
    monkeypatch.setitem(sys.modules, "SurfaceTopography", None)
    with pytest.raises(ImportError, match=r'pip install "fastrest\[topography\]"'):
        load_topography(tmp_path / "any.x3p")
    assert cli.main(["rough", str(tmp_path / "any.x3p"), *ARGS]) == 2


def test_import_does_not_load_surfacetopography():
    code = "import sys, fastrest, fastrest.rough; assert 'SurfaceTopography' not in sys.modules"
    subprocess.run([sys.executable, "-c", code], check=True)


def test_docstring_examples_run():
    import doctest

    from fastrest.rough import cli as rough_cli
    from fastrest.rough import summits as summits_mod

    for mod in (topo_mod, summits_mod, rough_cli):
        res = doctest.testmod(mod, raise_on_error=False, verbose=False,
                              optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE)
        assert res.failed == 0 and res.attempted > 0, mod.__name__


def test_topography_built_directly_is_checked_and_read_only():
    z = np.zeros((4, 3))
    t = Topography(z, 1, 2e-6, False, "array")
    assert t.heights is not z and not t.heights.flags.writeable and t.dx == 1.0
    z[0, 0] = 1.0
    assert t.heights[0, 0] == 0.0  # a copy
    with pytest.raises(ValueError, match="finite"):
        Topography(np.full((3, 3), np.nan), 1.0, 1.0, False, "nan")
    with pytest.raises(ValueError, match="dy"):
        Topography(z, 1.0, 0.0, False, "x")
    with pytest.raises(TypeError, match="periodic"):
        Topography(z, 1.0, 1.0, 1, "x")
    with pytest.raises(ValueError, match="2-D"):
        Topography(np.zeros(5), 1.0, 1.0, False, "x")


def test_topography_and_summits_pickle():
    """What users build pickles (Dask ships it): the unpickled map is checked and read-only again."""
    z = np.random.default_rng(4).normal(size=(24, 20)) * 1e-7
    t = Topography(z, 1e-6, 2e-6, True, "noise")
    t2 = pickle.loads(pickle.dumps(t))
    assert np.array_equal(t2.heights, t.heights) and not t2.heights.flags.writeable
    assert (t2.dx, t2.dy, t2.periodic, t2.source) == (1e-6, 2e-6, True, "noise")
    found = topography_summits(t)
    again = pickle.loads(pickle.dumps(found))
    assert np.array_equal(again.radii, found.radii) and again.counts() == found.counts()


def test_results_are_read_only():
    """The arrays a surface computes with, and the frozen summit record's, cannot be changed under it."""
    z, dx, dy = caps_map(CAPS)
    s = from_topography(Topography(z, dx, dy, False, "caps"), STEEL)
    for a in (s.heights, s.radii, s.topography_summits.heights, s.topography_summits.radii,
              s.topography_summits.i):
        with pytest.raises(ValueError, match="read-only"):
            a[0] = 1.0


def test_periodic_option_of_the_cli(tmp_path, capsys):
    """--periodic reads an .x3p map (which cannot say so) as one period: the mean is removed, the
    edges are neighbours."""
    t0 = fourier_synthesis((32, 32), (32e-6, 32e-6), hurst=0.8, rms_height=1e-7, unit="m",
                           rng=np.random.default_rng(5), periodic=True)
    path = str(tmp_path / "p.x3p")
    t0.to_x3p(path)
    assert cli.main(["rough", path, *ARGS, "--periodic", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["topography"]["periodic"] is True and out["detrend"] == "mean" and out["topography"]["n_border"] == 0
