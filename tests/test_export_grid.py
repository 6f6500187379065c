"""`fastrest export grid` and Table.to_xarray: the CF NetCDF4/HDF5 grid read back by xarray
(engine="h5netcdf"), `.interp` against the direct solver (fastrest.direct, the reference), NaN
outside the model's domain, atomic writes."""
import json
import os

import numpy as np
import pytest

import fastrest
from fastrest import cli
from fastrest.direct import impact_array

xr = pytest.importorskip("xarray")
pytest.importorskip("h5netcdf")

TOL = 1e-3


@pytest.fixture(scope="module")
def grid_file(tmp_path_factory):
    path = tmp_path_factory.mktemp("grid") / "grid.nc"
    assert cli.main(["export", "grid", "--out", str(path), "--tol", str(TOL), "--check-points", "2000"]) == 0
    return path


def _direct(v, e, n, model):
    out = np.empty((5, v.size))
    impact_array(v, e, n, np.zeros_like(v), model, False, 0, out)
    return out


def test_round_trip_variables_coords_attrs(grid_file):
    with xr.open_dataset(grid_file, engine="h5netcdf") as ds:
        names = {"omega_m"} | {f"{q}_{m}" for m in fastrest.unloading.NAMES for q in ("e", "loss")}
        assert set(ds.data_vars) == names
        for v in names:
            assert ds[v].dims == ("v1_star", "eps_y", "nu")
            assert ds[v].attrs["units"] == "1" and ds[v].attrs["long_name"]
        for c in ("v1_star", "eps_y", "nu"):
            assert ds[c].attrs["units"] == "1" and ds[c].attrs["long_name"]
            assert np.all(np.diff(ds[c].values) > 0)
        t = fastrest.load_table()
        assert ds.eps_y.values[0] == t.data.eps_lo and ds.eps_y.values[-1] == t.data.eps_hi
        assert ds.attrs["Conventions"].startswith("CF-")
        assert json.loads(ds.attrs["source"].split("table: ", 1)[1])["checksum"] == t.attrs["checksum"]
        rep = json.loads(ds.attrs["measured_error"])
        assert max(rep["linear"].values()) <= TOL
        # nodes equal the direct solver where the model is defined
        v, e, n = np.meshgrid(ds.v1_star.values[::7], ds.eps_y.values[::5], ds.nu.values[::3], indexing="ij")
        ref = _direct(v.ravel(), e.ravel(), n.ravel(), 0)
        got = ds.e_jcg.values[::7, ::5, ::3].ravel()
        assert np.array_equal(np.isnan(got), np.isnan(ref[1]))
        ok = ~np.isnan(ref[1])
        assert np.max(np.abs(got[ok] - ref[1][ok])) < 1e-8


def test_nan_outside_the_domain(grid_file):
    with xr.open_dataset(grid_file, engine="h5netcdf") as ds:
        v, e, n = np.meshgrid(ds.v1_star.values, ds.eps_y.values, ds.nu.values, indexing="ij")
        lim = np.array([fastrest.limit(a, b).v1_star for a, b in zip(e[0].ravel(), n[0].ravel())]).reshape(e[0].shape)
        beyond = v > lim[None] * (1 + 1e-9)
        inside = v < lim[None] * (1 - 1e-9)
        assert beyond.any()
        for name in ds.data_vars:
            a = ds[name].values
            assert np.isnan(a[beyond]).all(), name
            assert not np.isnan(a[inside]).any(), name


def test_interp_against_direct_solver(grid_file):
    rng = np.random.default_rng(14)
    with xr.open_dataset(grid_file, engine="h5netcdf") as ds:
        m = 3000
        e = rng.uniform(ds.eps_y.values[0], ds.eps_y.values[-1], m)
        n = rng.uniform(ds.nu.values[0], ds.nu.values[-1], m)
        lim = np.array([fastrest.limit(a, b).v1_star for a, b in zip(e, n)])
        v = np.exp(rng.uniform(0, 1, m) * np.log(lim))
        pts = dict(v1_star=xr.DataArray(v, dims="p"), eps_y=xr.DataArray(e, dims="p"), nu=xr.DataArray(n, dims="p"))
        for code, model in enumerate(fastrest.unloading.NAMES):
            ref = _direct(v, e, n, code)
            for name, row in ((f"e_{model}", 1), (f"loss_{model}", 2), ("omega_m", 0)):
                got = ds[name].interp(**pts).values  # xarray's own linear interpolation in V1*
                ok = ~np.isnan(got)
                assert ok.mean() > 0.98  # NaN only next to the domain's edge
                err = np.abs(got[ok] - ref[row][ok]) / np.maximum(np.abs(ref[row][ok]), 1.0)
                assert err.max() <= TOL, name


def test_to_xarray_matches_file(grid_file):
    ds = fastrest.load_table().to_xarray(tol=TOL, n_check=0)
    with xr.open_dataset(grid_file, engine="h5netcdf") as f:
        xr.testing.assert_equal(ds, f)  # values and coordinates
        assert ds.e_jcg.attrs == {k: f.e_jcg.attrs[k] for k in ("units", "long_name")}


@pytest.mark.parametrize("argv, option", [(["--tol", "1e-9"], "--tol"), (["--tol", "2"], "--tol"),
                                          (["--check-points", "3"], "--check-points")])
def test_bad_input(tmp_path, capsys, argv, option):
    out = tmp_path / "g.nc"
    assert cli.main(["export", "grid", "--out", str(out)] + argv) == 2
    assert option in capsys.readouterr().err
    assert os.listdir(tmp_path) == []


def test_unwritable_output(tmp_path, capsys):
    """A missing directory is a file-system error (exit 1, as `build`), found before the grid is built."""
    out = tmp_path / "no" / "g.nc"
    assert cli.main(["export", "grid", "--out", str(out)]) == 1
    err = capsys.readouterr().err
    assert "--out" in err and str(out) in err and "No such file or directory" in err


def test_elastic_range_is_gridded(grid_file):
    """0 <= V1* <= 1 (elastic) is on the grid: e = 1, 1 - e^2 = 0, w_m* = V1*^0.8 within tol
    (it was NaN: the grid started at V1* = 1)."""
    rng = np.random.default_rng(20)
    with xr.open_dataset(grid_file, engine="h5netcdf") as ds:
        v1 = ds.v1_star.values
        assert v1[0] == 0.0 and 1.0 in v1
        m = 400
        v = np.concatenate([[0.0, 1.0], rng.uniform(0.0, 1.0, m - 2)])
        e = rng.uniform(ds.eps_y.values[0], ds.eps_y.values[-1], m)
        n = rng.uniform(ds.nu.values[0], ds.nu.values[-1], m)
        pts = dict(v1_star=xr.DataArray(v, dims="p"), eps_y=xr.DataArray(e, dims="p"), nu=xr.DataArray(n, dims="p"))
        for code, model in enumerate(fastrest.unloading.NAMES):
            ref = _direct(v, e, n, code)
            assert np.all(ref[1] == 1.0) and np.all(ref[2] == 0.0)
            for name, row in ((f"e_{model}", 1), (f"loss_{model}", 2), ("omega_m", 0)):
                got = ds[name].interp(**pts).values
                assert not np.isnan(got).any(), name
                assert np.max(np.abs(got - ref[row])) <= TOL, name
            elastic = v1 <= 1.0
            assert np.all(ds[f"e_{model}"].values[elastic] == 1.0)
            assert np.all(ds[f"loss_{model}"].values[elastic] == 0.0)
        # one pow each: the table kernel's (libm) and NumPy's (its own SIMD kernel on some CPUs)
        np.testing.assert_allclose(ds.omega_m.values[elastic, 0, 0], v1[elastic] ** 0.8, rtol=5e-16, atol=0)
