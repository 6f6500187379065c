"""Embedding fastrest in user Numba code: fastrest.jit functions called from the user's own
@numba.njit loops, serial and parallel (prange), must give the Python API's numbers (which are
themselves checked against the direct solver in test_curve.py / test_tables.py), and NaN instead of
an exception for invalid points.
"""
import math
import re

import numba
import numpy as np
import pytest

import fastrest
from fastrest import direct
from fastrest import jit as frj

V_SWITCH = 1.9 ** 1.25


def _kernel(cdata, tab, v, eps, nu, out):
    for i in range(v.size):
        out[0, i] = frj.omega_m_curve(cdata, v[i])
        out[1, i] = frj.e_curve(cdata, v[i])
        out[2, i] = frj.loss_curve(cdata, v[i])
        out[3, i] = frj.omega_m_table(tab, v[i], eps[i], nu[i])
        out[4, i] = frj.e_table(tab, v[i], eps[i], nu[i], frj.JCG)
        out[5, i] = frj.loss_table(tab, v[i], eps[i], nu[i], frj.JCG)
        out[6, i] = frj.e_table(tab, v[i], eps[i], nu[i], frj.ETSION)
        out[7, i] = frj.loss_table(tab, v[i], eps[i], nu[i], frj.ETSION)


def _kernel_parallel(cdata, tab, v, eps, nu, out):
    # two table calls, not five: every inlined call of the table kernel costs compile time (the five
    # of the serial loop take over a minute to compile on 2 cores); rows 5-7 repeat row 4
    for i in numba.prange(v.size):
        out[0, i] = frj.omega_m_curve(cdata, v[i])
        out[1, i] = frj.e_curve(cdata, v[i])
        out[2, i] = frj.loss_curve(cdata, v[i])
        out[3, i] = frj.omega_m_table(tab, v[i], eps[i], nu[i])
        out[4, i] = frj.e_table(tab, v[i], eps[i], nu[i], frj.JCG)
        out[5, i] = out[6, i] = out[7, i] = out[4, i]


def _sum_loss_parallel(cdata, v):
    """A reduction, as in the README example."""
    s = 0.0
    for i in numba.prange(v.size):
        s += frj.loss_curve(cdata, v[i])
    return s


def _scene_kernel(sdata, k, v, out):
    for i in numba.prange(v.size):
        out[0, i] = frj.omega_m_scene(sdata, k[i], v[i])
        out[1, i] = frj.e_scene(sdata, k[i], v[i])
        out[2, i] = frj.loss_scene(sdata, k[i], v[i])


serial = numba.njit(_kernel)
scene_parallel = numba.njit(parallel=True)(_scene_kernel)
parallel = numba.njit(parallel=True)(_kernel_parallel)
sum_loss = numba.njit(parallel=True)(_sum_loss_parallel)

EPS, NU = 0.005, 0.33


@pytest.fixture(scope="module")
def setup():
    c = fastrest.curve(EPS, NU, "jcg", v_max=300.5)
    tab = fastrest.load_table()
    rng = np.random.default_rng(7)
    n = 2000
    v = np.concatenate([rng.uniform(0.0, 300.5, n), [0.0, 1.0, 1 + 1e-12, V_SWITCH,
                                                     math.nextafter(V_SWITCH, math.inf), 300.5]])
    eps = rng.uniform(0.0005, 0.01, v.size)
    nu = rng.uniform(0.2, 0.45, v.size)
    eps[-6:], nu[-6:] = EPS, NU
    expected = np.stack([
        c.omega_m(v), c.e(v), c.loss(v),
        fastrest.omega_m_star(v, eps, nu),
        fastrest.e_star(v, eps, nu, "jcg"), fastrest.loss_star(v, eps, nu, "jcg"),
        fastrest.e_star(v, eps, nu, "etsion"), fastrest.loss_star(v, eps, nu, "etsion"),
    ])
    return c, tab, v, eps, nu, expected


@pytest.mark.parametrize("fn", [serial, parallel], ids=["serial", "prange"])
def test_user_njit_matches_python_api(setup, fn):
    c, tab, v, eps, nu, expected = setup
    out = np.empty((8, v.size))
    fn(c.data, tab.data, v, eps, nu, out)
    rows = 8 if fn is serial else 5  # the prange loop computes rows 0-4 (see _kernel_parallel)
    np.testing.assert_array_equal(out[:rows], expected[:rows])


def test_jit_values_are_the_model(setup):
    """Sanity: what the jitted loop returns is the direct solver's value (not only self-consistent)."""
    c, tab, v, eps, nu, _ = setup
    out = np.empty((8, v.size))
    parallel(c.data, tab.data, v, eps, nu, out)
    np.testing.assert_allclose(out[1], direct.e_star(v, EPS, NU), rtol=1e-12, atol=0)
    np.testing.assert_allclose(out[4], direct.e_star(v, eps, nu), rtol=1e-8, atol=0)


def test_parallel_reduction(setup):
    c, _, v, _, _, expected = setup
    s = sum_loss(c.data, v)
    assert s == pytest.approx(expected[2].sum(), rel=1e-13)
    assert s == pytest.approx(direct.loss_star(v, EPS, NU).sum(), rel=1e-10)


@pytest.mark.parametrize("fn", [serial, parallel], ids=["serial", "prange"])
def test_invalid_points_give_nan_inside_njit(setup, fn):
    c, tab, *_ = setup
    lim = direct.v1_star_limit(EPS, NU)
    #            V1*            eps_y    nu     curve invalid?  table invalid?
    cases = [(-1.0,          EPS,     NU,    True,  True),
             (math.nan,      EPS,     NU,    True,  True),
             (-math.inf,     EPS,     NU,    True,  True),
             (math.inf,      EPS,     NU,    True,  True),
             (300.6,         EPS,     NU,    True,  False),   # beyond the curve's v_max only
             (lim * 1.001,   EPS,     NU,    True,  True),    # past w_m* = 425
             (5.0,           0.02,    NU,    False, True),    # eps_y outside the table
             (5.0,           0.0001,  NU,    False, True),
             (1.0,           0.02,    NU,    False, True),    # ... also in the closed-form region
             (5.0,           EPS,     0.1,   False, True),    # nu outside the table
             (5.0,           EPS,     0.46,  False, True),
             (5.0,           math.nan, NU,   False, True),
             (5.0,           EPS,     math.nan, False, True)]
    v = np.array([k[0] for k in cases])
    eps = np.array([k[1] for k in cases])
    nu = np.array([k[2] for k in cases])
    out = np.empty((8, v.size))
    fn(c.data, tab.data, v, eps, nu, out)
    for i, (_, _, _, bad_curve, bad_table) in enumerate(cases):
        assert np.isnan(out[:3, i]).all() == bad_curve and np.isnan(out[:3, i]).any() == bad_curve, cases[i]
        assert np.isnan(out[3:, i]).all() == bad_table and np.isnan(out[3:, i]).any() == bad_table, cases[i]


def test_etsion_curve_in_njit():
    c = fastrest.curve(0.002, 0.4, "etsion", v_max=50.0)
    v = np.array([0.5, 1.0, V_SWITCH, math.nextafter(V_SWITCH, math.inf), 10.0, 50.0])
    out = np.empty((8, v.size))
    serial(c.data, fastrest.load_table().data, v, np.full(v.size, 0.002), np.full(v.size, 0.4), out)
    np.testing.assert_array_equal(out[1], c.e(v))
    np.testing.assert_array_equal(out[2], c.loss(v))
    assert out[1, 2] == 1.0 and out[1, 3] < 1.0
    np.testing.assert_allclose(out[1], direct.e_star(v, 0.002, 0.4, "etsion"), rtol=1e-12, atol=0)


def test_jit_functions_callable_from_python():
    """The jit functions are ordinary Numba dispatchers: callable from Python too."""
    c = fastrest.curve(EPS, NU, v_max=20.0)
    tab = fastrest.load_table().data
    assert frj.e_curve(c.data, 10.0) == c.e(10.0)
    assert frj.e_table(tab, 10.0, EPS, NU, frj.JCG) == fastrest.e_star(10.0, EPS, NU)
    assert frj.loss_table(tab, 10.0, EPS, NU, frj.ETSION) == fastrest.loss_star(10.0, EPS, NU, "etsion")
    assert frj.omega_m_table(tab, 10.0, EPS, NU) == fastrest.omega_m_star(10.0, EPS, NU)
    assert math.isnan(frj.e_curve(c.data, 21.0))
    assert (frj.JCG, frj.ETSION) == (0, 1)


def test_scene_in_user_njit():
    mats = [(0.001, 0.25), (0.008, 0.4)]
    s = fastrest.scene(mats, "etsion", v_max=[100.0, 64.0])
    rng = np.random.default_rng(3)
    k = rng.integers(0, 2, 500)
    v = rng.uniform(0.0, 1.0, k.size) * np.array([100.0, 64.0])[k]
    out = np.empty((3, v.size))
    scene_parallel(s.data, k, v, out)
    np.testing.assert_array_equal(out[0], s.omega_m(v, k))
    np.testing.assert_array_equal(out[1], s.e(v, k))
    np.testing.assert_array_equal(out[2], s.loss(v, k))
    # invalid points: NaN, no exception
    kb = np.array([0, 1, 2, -1, 0, 1])
    vb = np.array([101.0, 65.0, 5.0, 5.0, -1.0, math.nan])
    outb = np.empty((3, vb.size))
    scene_parallel(s.data, kb, vb, outb)
    assert np.isnan(outb).all()


def _table_loop(tab, v, eps, nu, out):
    for i in range(v.size):
        out[i] = frj.e_table(tab, v[i], eps[i], nu[i], frj.JCG)


def test_table_loop_takes_no_references_per_point():
    """A user's loop over jit.e_table does no reference counting per point: only the function's
    own entry takes a reference on each array argument (9 of the table, 4 of the loop). Atomic
    reference counts inside the loop made table loops ~1.6x slower (fastrest/tables/kernel.py)."""
    loop = numba.njit(_table_loop)  # not cached: the LLVM IR can be inspected
    tab = fastrest.load_table().data
    v = np.array([0.5, 2.0, 5.0, 600.0])
    out = np.empty(v.size)
    loop(tab, v, np.full(v.size, EPS), np.full(v.size, NU), out)
    np.testing.assert_array_equal(out, fastrest.e_star(v, EPS, NU))
    ir = next(iter(loop.inspect_llvm().values()))
    # the loop's own function (not its Python wrapper "cpython..." or C wrapper "cfunc...")
    bodies = [m.group(2) for m in re.finditer(r"^define [^@\n]*@([^\s(]+)\(.*?\n(.*?)^}$", ir, re.M | re.S)
              if "_table_loop" in m.group(1) and not m.group(1).startswith(("_ZN7cpython", "cfunc"))]
    assert len(bodies) == 1
    n_arrays = sum(isinstance(x, np.ndarray) for x in tab) + 4
    assert 0 < bodies[0].count("call void @NRT_incref(") <= n_arrays
