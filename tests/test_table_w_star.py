"""The table's stored W* has a reader: Table.W_star and Table.loading_energy,
and the registry of loaded tables does not keep a stale table after its file is rewritten.

References: fastrest.W_star / fastrest.loading_energy (composite Gauss-Legendre quadrature of the
law, one material at a time: an independent slow path, no interpolation) on a dense sample, and the
40-digit tests/reference.py at the corners.
"""
import math
import os
import pickle
import warnings

import numpy as np
import pytest

import fastrest
import reference
from fastrest import tables
from fastrest.tables import store

# random materials and w*, every edge and corner (and the last ulp inside) at w* from 0 to 425:
# the sample bench/W_STAR_READER.md reports on
from bench.w_star_reader import sample

#: Measured on the shipped table: 8.4e-11 (worst over this sample, at w* = 405, eps_y = 0.0091,
#: nu = 0.206: the plain eps_y axis of 32 nodes, where cos(pi a/R) varies fastest; bench/W_STAR_READER.md).
TOL_W_STAR = 2e-10
TINY_GRID = dict(eps_y_min=0.004, eps_y_max=0.006, n_eps_y=6, nu_min=0.3, nu_max=0.35, n_nu=6,
                 bits_per_octave=1, eps_y_blocks=[], n_eps_y_energy=6)


def test_loading_energy_matches_quadrature_over_the_domain():
    t = fastrest.load_table()
    w, e, nu = sample()
    ref = fastrest.loading_energy(w, e, nu)
    got = t.loading_energy(w, e, nu)
    rel = np.abs(got - ref) / np.where(ref > 0, ref, 1.0)   # F(0) = 0
    k = int(np.argmax(rel))
    print(f"\n[W* reader] F: worst relative error {rel[k]:.3g} at w* = {w[k]:.6g}, eps_y = {e[k]:.6g}, "
          f"nu = {nu[k]:.6g}; median {np.median(rel):.2g} over {w.size} points")
    assert rel[k] <= TOL_W_STAR
    # W* = 1 - F, including its zero at w* = 1; the Hertz range is the closed form, exactly
    W = t.W_star(w, e, nu)
    W_ref = fastrest.W_star(w, e, nu)
    assert np.all(np.abs(W - W_ref) <= TOL_W_STAR * np.maximum(np.abs(W_ref), 1.0) * 1.25)
    hertz = w <= 1.9
    # one pow each: the kernel's (libm) and NumPy's (its own SIMD kernel on some CPUs), an ulp or two apart
    assert np.all(np.abs(W[hertz] - (1.0 - w[hertz] ** 2.5)) <= 5e-16)
    assert t.W_star(1.0, 0.005, 0.33) == 0.0


@pytest.mark.parametrize("w, eps, nu", [(425.0, 0.01, 0.45), (425.0, 0.0005, 0.2), (424.0, 0.0087, 0.209),
                                        (2.0, 0.01, 0.2), (1.95, 0.0005, 0.45), (100.0, 0.005, 0.33)])
def test_w_star_matches_40_digit_reference(w, eps, nu):
    got = fastrest.load_table().W_star(w, eps, nu)
    ref = reference.ref_W_star(w, eps, nu)
    assert abs(got - ref) <= TOL_W_STAR * abs(ref), (got, ref)


def test_w_star_broadcasts_like_e_star():
    t = fastrest.load_table()
    w = np.array([[1.5], [30.0], [400.0]])         # (3, 1)
    e = np.array([0.001, 0.004, 0.009, 0.0051])    # (4,)
    nu = np.array([[[0.21]], [[0.44]]])            # (2, 1, 1)
    got = t.W_star(w, e, nu)
    assert got.shape == (2, 3, 4)
    wb, eb, nb_ = np.broadcast_arrays(w, e, nu)
    for idx in np.ndindex(got.shape):
        assert got[idx] == t.W_star(float(wb[idx]), float(eb[idx]), float(nb_[idx]))
    assert type(t.W_star(10.0, 0.005, 0.33)) is float
    assert type(t.loading_energy(np.array(10.0), 0.005, 0.33)) is float
    assert t.W_star([10.0, 20.0], 0.005, [0.3, 0.4]).shape == (2,)
    assert t.W_star(np.empty(0), 0.005, 0.33).shape == (0,)


@pytest.mark.parametrize("args, match", [
    ((-1.0, 0.005, 0.33), r"w .*\[0, 425\]"), ((math.nan, 0.005, 0.33), r"w .*\[0, 425\]"),
    ((425.5, 0.005, 0.33), r"w .*\[0, 425\]"), ((math.inf, 0.005, 0.33), r"w .*\[0, 425\]"),
    ((10.0, 0.02, 0.33), r"eps_y.*\[0\.0005, 0\.01\]"), ((10.0, 0.0001, 0.33), r"eps_y.*\[0\.0005, 0\.01\]"),
    ((10.0, 0.005, 0.1), r"nu.*\[0\.2, 0\.45\]"), ((10.0, 0.005, 0.49), r"nu.*\[0\.2, 0\.45\]"),
    ((10.0, -0.005, 0.33), "eps_y"), ((10.0, 0.005, math.nan), "nu")])
def test_w_star_out_of_domain_names_the_parameter(args, match):
    t = fastrest.load_table()
    for f in (t.W_star, t.loading_energy):
        with pytest.raises(ValueError, match=match):
            f(*args)
        with pytest.raises(ValueError, match=match):   # one bad point in an array
            f([10.0, args[0]], [0.005, args[1]], [0.33, args[2]])


def test_w_star_non_numbers_are_type_errors():
    t = fastrest.load_table()
    for args, name in ((("10", 0.005, 0.33), "w"), ((10.0, None, 0.33), "eps_y"), ((10.0, 0.005, True), "nu"),
                       ((10.0 + 1j, 0.005, 0.33), "w")):
        with pytest.raises(TypeError, match=name):
            t.W_star(*args)


def test_w_star_stops_at_the_end_of_the_law():
    """A table past eps_y = 0.0102 holds materials whose law ends (a/R = 1) before w* = 425: the
    reader refuses there (and where its stencil reaches past it), as fastrest.W_star does."""
    g = dict(TINY_GRID, eps_y_min=0.015, eps_y_max=0.025)
    t = tables.Table(tables.generate(g, progress=False))
    eps, nu = 0.02, 0.32
    end = float(fastrest.omega_star_limit(eps, nu))
    assert end < 425.0
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", fastrest.ValidityWarning)
        w = end * 0.5
        assert t.W_star(w, eps, nu) == pytest.approx(fastrest.W_star(w, eps, nu), rel=1e-5)
        for w in (end * 1.001, 424.0):
            with pytest.raises(ValueError, match="a/R = 1"):
                t.W_star(w, eps, nu)


def test_w_star_of_a_coarse_table():
    """n_eps_y_energy = 2 (the smallest allowed): linear in eps_y (0.3 % off midway, measured),
    still the model; on the eps_y nodes only the w* and nu interpolation remain."""
    t = tables.Table(tables.generate(dict(TINY_GRID, n_eps_y_energy=2), progress=False))
    for eps in (0.004, 0.006):    # on the nodes: only the w* and nu interpolation
        assert t.W_star(300.0, eps, 0.3) == pytest.approx(fastrest.W_star(300.0, eps, 0.3), rel=1e-9)
    assert t.W_star(300.0, 0.005, 0.33) == pytest.approx(fastrest.W_star(300.0, 0.005, 0.33), rel=1e-2)


def test_table_pickles_with_its_w_star():
    t = tables.Table(tables.generate(TINY_GRID, progress=False))
    u = pickle.loads(pickle.dumps(t))
    assert u.W_star(200.0, 0.005, 0.33) == t.W_star(200.0, 0.005, 0.33)
    assert not hasattr(t, "gen")     # no raw generation arrays kept alive


# --- the registry of loaded tables ---------------------------------------------------------------

@pytest.fixture
def registry(monkeypatch):
    monkeypatch.setattr(store, "LOADED", {})


def test_load_table_after_build_overwrites_the_same_path(tmp_path, registry):
    path = tmp_path / "t.h5"
    tables.build(path, TINY_GRID, progress=False, measure=False)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", fastrest.tables.AccuracyWarning)
        t1 = fastrest.load_table(path)
        assert fastrest.load_table(path) is t1
        tables.build(path, dict(TINY_GRID, n_nu=7), progress=False, measure=False)
        t2 = fastrest.load_table(path)
        assert t2 is not t1 and t2.grid["n_nu"] == 7
        assert fastrest.load_table(path) is t2
        # a file replaced by another program (rename over it) is read again too
        other = tmp_path / "other.h5"
        tables.build(other, TINY_GRID, progress=False, measure=False)
        os.replace(other, path)
        t3 = fastrest.load_table(path)
        assert t3 is not t2 and t3.grid["n_nu"] == 6


def test_build_over_the_shipped_table_path_drops_the_default_entry(tmp_path, registry, monkeypatch):
    """build() writing the default table's file (fastrest build --default) makes load_table() read
    it again (here the package directory is a temporary copy)."""
    fake = tmp_path / "default.h5"
    fake.write_bytes(store.default_table_path().read_bytes())
    monkeypatch.setattr(store, "_HERE", tmp_path)
    t1 = fastrest.load_table()
    assert fastrest.load_table() is t1
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", fastrest.tables.AccuracyWarning)
        tables.build(fake, TINY_GRID, progress=False, measure=False)
        t2 = fastrest.load_table()
    assert t2 is not t1 and t2.grid["n_eps_y"] == 6
