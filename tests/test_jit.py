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
        out[0, i] = frj.omega_m_material(sdata, v[i], k[i])
        out[1, i] = frj.e_material(sdata, v[i], k[i])
        out[2, i] = frj.loss_material(sdata, v[i], k[i])


def _kernel_light(cdata, tab, v, eps, nu, out):
    # the default run's loop: every curve function and one table call (each inlined table call
    # costs ~10 s of compiling on 2 cores; the full loops above are `slow`)
    for i in range(v.size):
        out[0, i] = frj.omega_m_curve(cdata, v[i])
        out[1, i] = frj.e_curve(cdata, v[i])
        out[2, i] = frj.loss_curve(cdata, v[i])
        out[4, i] = frj.e_table(tab, v[i], eps[i], nu[i], frj.JCG)


serial = numba.njit(_kernel)
light = numba.njit(_kernel_light)
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


@pytest.mark.slow
@pytest.mark.parametrize("fn", [serial, parallel], ids=["serial", "prange"])
def test_user_njit_matches_python_api(setup, fn):
    c, tab, v, eps, nu, expected = setup
    out = np.empty((8, v.size))
    fn(c.data, tab.data, v, eps, nu, out)
    rows = 8 if fn is serial else 5  # the prange loop computes rows 0-4 (see _kernel_parallel)
    np.testing.assert_array_equal(out[:rows], expected[:rows])


def test_user_njit_light_matches_python_api(setup):
    """The default run's check of a user's loop (the full serial and prange loops are `slow`)."""
    c, tab, v, eps, nu, expected = setup
    out = np.empty((8, v.size))
    light(c.data, tab.data, v, eps, nu, out)
    np.testing.assert_array_equal(out[[0, 1, 2, 4]], expected[[0, 1, 2, 4]])


def test_jit_values_are_the_model(setup):
    """Sanity: what the jitted loop returns is the direct solver's value (not only self-consistent)."""
    c, tab, v, eps, nu, _ = setup
    out = np.empty((8, v.size))
    light(c.data, tab.data, v, eps, nu, out)
    np.testing.assert_allclose(out[1], direct.e_exact(v, EPS, NU), rtol=1e-12, atol=0)
    np.testing.assert_allclose(out[4], direct.e_exact(v, eps, nu), rtol=1e-8, atol=0)


def test_parallel_reduction(setup):
    c, _, v, _, _, expected = setup
    s = sum_loss(c.data, v)
    assert s == pytest.approx(expected[2].sum(), rel=1e-13)
    assert s == pytest.approx(direct.loss_exact(v, EPS, NU).sum(), rel=1e-10)


@pytest.mark.parametrize("fn, table_rows", [
    (light, [4]),
    pytest.param(serial, [3, 4, 5, 6, 7], marks=pytest.mark.slow),
    pytest.param(parallel, [3, 4, 5, 6, 7], marks=pytest.mark.slow)], ids=["light", "serial", "prange"])
def test_invalid_points_give_nan_inside_njit(setup, fn, table_rows):
    c, tab, *_ = setup
    lim = fastrest.limit(EPS, NU).v1_star
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
    table = out[table_rows]
    for i, (_, _, _, bad_curve, bad_table) in enumerate(cases):
        assert np.isnan(out[:3, i]).all() == bad_curve and np.isnan(out[:3, i]).any() == bad_curve, cases[i]
        assert np.isnan(table[:, i]).all() == bad_table and np.isnan(table[:, i]).any() == bad_table, cases[i]


def test_etsion_curve_in_njit():
    c = fastrest.curve(0.002, 0.4, "etsion", v_max=50.0)
    v = np.array([0.5, 1.0, V_SWITCH, math.nextafter(V_SWITCH, math.inf), 10.0, 50.0])
    out = np.empty((8, v.size))
    light(c.data, fastrest.load_table().data, v, np.full(v.size, 0.002), np.full(v.size, 0.4), out)
    np.testing.assert_array_equal(out[1], c.e(v))
    np.testing.assert_array_equal(out[2], c.loss(v))
    assert out[1, 2] == 1.0 and out[1, 3] < 1.0
    np.testing.assert_allclose(out[1], direct.e_exact(v, 0.002, 0.4, "etsion"), rtol=1e-12, atol=0)


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


@pytest.mark.slow
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


# --- the NaN contract and scalar types of every function of fastrest.jit.__all__ -------------------

_INF = math.inf


def test_critical_scales_nan_outside_double_precision():
    """E1 = 1e-320 raised ZeroDivisionError inside jitted code; R1 = 1e300 gave V_c = inf."""
    for args in [(1e-320, 0.33, 1.12e9, 0.01, 0.0327, _INF, 0.3, _INF, _INF, _INF),
                 (200e9, 0.33, 1.12e9, 1e300, 0.0327, _INF, 0.3, _INF, _INF, _INF),
                 (5e-324, 0.33, 1.12e9, 0.01, 0.0327, _INF, 0.3, _INF, _INF, _INF),
                 (200e9, 0.33, 1.12e9, 0.01, 0.0, _INF, 0.3, _INF, _INF, _INF)]:
        s = frj.critical_scales(*args)
        assert all(math.isnan(x) for x in s), (args, s)
    s = frj.critical_scales(200e9, 0.33, 1.12e9, 0.01, 0.0327, _INF, 0.3, _INF, _INF, _INF)
    assert all(math.isfinite(x) for x in s) and round(s.V_c, 5) == 0.05155


def test_critical_formulas_never_raise():
    from fastrest import critical as cr

    assert math.isnan(cr.effective_modulus(0.0, 0.3, _INF, 0.0))
    assert math.isnan(cr.effective_modulus(5e-324, 0.3, _INF, 0.0))  # 1/E' overflows: E' = 0
    assert math.isnan(cr.effective_radius(1.0, -1.0)) and math.isnan(cr.effective_mass(0.0, 0.0))
    assert math.isnan(cr.critical_velocity(1.0, 0.0)) and math.isnan(cr.critical_energy(1.0, 1.0, 1e-100, 1.0))
    assert math.isnan(cr.critical_force(1.6, 1e9, 0.0, 0.01))


def test_hertz_contact_time_nan_outside_its_domain():
    """V1* = 0 gave inf, V1* = +/-inf gave 0.0."""
    for v in (0.0, -0.0, _INF, -_INF, math.nan, -1.0):
        assert math.isnan(frj.hertz_contact_time(v)), v
    assert round(frj.hertz_contact_time(1.0), 6) == 2.943275


def test_jit_nan_contract_fuzzed():
    """Every function of fastrest.jit.__all__ at extreme values: NaN or a finite number, never an
    exception (ZeroDivisionError inside njit) and never inf."""
    import random

    law = fastrest.contact_law(0.005, 0.33, w_max=30.0)
    c = fastrest.curve(0.005, 0.33, v_max=30.0).data
    s = fastrest.scene([(0.005, 0.33)], v_max=30.0).data
    t = fastrest.load_table().data
    X = [0.0, -0.0, 5e-324, 1e-320, 1e-300, 0.3, 1.0, 5.0, 1e300, 1.7e308, _INF, -_INF, math.nan, -1.0]
    codes = [-1, 0, 1, 2, 3, 2**62, -2**63]

    def ok(r):
        return all(x != x or math.isfinite(x) for x in (r if isinstance(r, tuple) else (r,)))

    for v in X:
        assert ok(frj.hertz_contact_time(v)), v
        assert ok((frj.omega_m_curve(c, v), frj.e_curve(c, v), frj.loss_curve(c, v))), v
        for k in codes:
            assert ok((frj.omega_m_material(s, v, k), frj.e_material(s, v, k), frj.loss_material(s, v, k))), (k, v)
            assert ok((frj.e_table(t, v, 0.005, 0.33, k), frj.loss_table(t, v, 0.005, 0.33, k))), (k, v)
        for e in X[::2]:
            assert ok(frj.omega_m_table(t, v, e, 0.33)) and ok(frj.e_table(t, 5.0, e, v, 0)), (v, e)
        for w in X:
            st = law.new_state()
            assert ok(frj.contact_force(law.data, st, w)) and ok(frj.contact_force(law.data, st, v)), (w, v)
    rng = random.Random(20)
    pool = X + [200e9, 0.3, 1e9, 0.01, 0.03]
    for _ in range(2000):
        a = [rng.choice(pool) for _ in range(10)]
        assert ok(tuple(frj.critical_scales(*a))), a


def test_contact_force_nan_for_infinite_interference():
    law = fastrest.contact_law(0.005, 0.33, w_max=30.0)
    for w in (_INF, -_INF, math.nan):
        assert math.isnan(frj.contact_force(law.data, law.new_state(), w))
    st = law.new_state()
    frj.contact_force(law.data, st, 10.0)
    assert math.isnan(frj.contact_force(law.data, st, -_INF))  # unloading branch


@numba.njit
def _user_force(data, state, w):
    return frj.contact_force(data, state, w)


@numba.njit
def _user_hertz(v):
    return frj.hertz_contact_time(v)


@numba.njit
def _user_scales(E1, nu1, Sy1, R1, m1):
    return frj.critical_scales(E1, nu1, Sy1, R1, m1, math.inf, 0.3, math.inf, math.inf, math.inf)


@numba.njit
def _user_curve(d, v):
    return frj.omega_m_curve(d, v), frj.e_curve(d, v), frj.loss_curve(d, v)


@numba.njit
def _user_scene(d, k, v):
    return frj.omega_m_material(d, v, k), frj.e_material(d, v, k), frj.loss_material(d, v, k)


@numba.njit
def _user_table(t, v, e, n, u):
    return frj.omega_m_table(t, v, e, n), frj.e_table(t, v, e, n, u), frj.loss_table(t, v, e, n, u)


def _dtype_case(dtype, kinds):
    """The functions of fastrest.jit.__all__ (those of ``kinds``) called from a user's @njit
    function with ``dtype`` scalars equal the float64 call (inputs exact in every type)."""
    d = dtype
    if "force" in kinds:
        law = fastrest.contact_law(0.005, 0.33, w_max=30.0)
        assert _user_force(law.data, law.new_state(), d(5)) == _user_force(law.data, law.new_state(), 5.0)
        assert _user_hertz(d(5)) == _user_hertz(5.0)
        # integers that fit int32 and are exact in float32
        assert _user_scales(d(2**30), d(0), d(2**23), d(1), d(1)) == _user_scales(2.0**30, 0.0, 2.0**23, 1.0, 1.0)
    if "data" in kinds:
        c = fastrest.curve(0.005, 0.33, v_max=30.0).data
        s = fastrest.scene([(0.005, 0.33)], v_max=30.0).data
        t = fastrest.load_table().data
        assert _user_curve(c, d(5)) == _user_curve(c, 5.0)
        assert _user_scene(s, d(0), d(5)) == _user_scene(s, 0, 5.0)
        if d in (np.float32, np.float64):  # eps_y, nu are fractions
            e, n = d(0.005), d(0.25)
            assert _user_table(t, d(5), e, n, d(0)) == _user_table(t, 5.0, float(e), float(n), 0)
        else:
            assert _user_table(t, d(5), 0.005, 0.25, d(0)) == _user_table(t, 5.0, 0.005, 0.25, 0)


@pytest.mark.parametrize("dtype", [np.int64, np.float32], ids=["int64", "float32"])
def test_contact_force_and_critical_scales_take_integers_and_float32(dtype):
    """contact_force and critical_scales did not compile for an integer or float32 (TypingError
    in float_bits). The curve, scene and table functions: tests/test_input_usability.py (default run)
    and the full matrix below."""
    _dtype_case(dtype, ("force",))


@pytest.mark.slow
@pytest.mark.parametrize("dtype", [np.int64, np.int32, np.float32, np.float64],
                         ids=["int64", "int32", "float32", "float64"])
def test_jit_functions_take_every_scalar_type(dtype):
    _dtype_case(dtype, ("force", "data"))
