"""Input types and messages shared by every API layer (fastrest._validation).

Non-numbers (strings, which NumPy would parse; booleans; None, which NumPy would turn into NaN;
complex numbers) raise TypeError naming the parameter; speeds past the model's limit raise
ValueError in the caller's own units and parameter names.
"""
import math
import os
import re
import subprocess
import sys
import warnings
from pathlib import Path

import numpy as np
import pytest

import fastrest
from fastrest import direct, tables
from fastrest.contact import omega_star_limit_kernel

NOT_REAL = ["5", b"5", True, np.bool_(False), None, 1 + 2j, [1.0, None], [2.0, "3"], np.array(["1"]),
            np.array([True]), np.array([1 + 0j])]


def _named(name):
    return re.compile(r"(?<![A-Za-z_])" + re.escape(name) + r"(?![A-Za-z_])")


@pytest.mark.parametrize("bad", NOT_REAL, ids=repr)
@pytest.mark.parametrize("position, name", [(0, "v1_star"), (1, "eps_y"), (2, "nu")])
def test_not_real_raises_type_error_naming_parameter(bad, position, name):
    args = [5.0, 0.005, 0.33]
    args[position] = bad
    for f in (fastrest.e_star, fastrest.omega_m_star, fastrest.loss_star, direct.e_exact, direct.omega_m_exact):
        with pytest.raises(TypeError, match=_named(name)):
            f(*args)


@pytest.mark.parametrize("bad", NOT_REAL, ids=repr)
def test_curve_and_scene_reject_not_real(bad):
    c = fastrest.curve(0.005, 0.33, v_max=10.0)
    for f in (c.e, c.omega_m, c.loss):
        with pytest.raises(TypeError, match="v1_star"):
            f(bad)
    if not isinstance(bad, (list, np.ndarray)):
        with pytest.raises(TypeError, match="eps_y"):
            fastrest.curve(bad, 0.33)
        with pytest.raises(TypeError, match=_named("nu")):
            fastrest.curve(0.005, bad)


def test_real_number_types_accepted():
    ref = direct.e_exact(5.0, 0.005, 0.33)
    for v in (5, np.int32(5), np.float32(5.0), np.array(5.0), [5.0], np.array([5], dtype=np.uint8),
              np.array([5.0], dtype=object)):
        assert np.ravel(fastrest.e_star(v, 0.005, 0.33))[0] == pytest.approx(ref, rel=1e-9)


@pytest.mark.parametrize("field", ["E", "nu", "Sy", "rho"])
@pytest.mark.parametrize("bad", ["200e9", True, None, [1.0, 2.0], 1j])
def test_material_rejects_non_numbers(field, bad):
    kw = dict(E=200e9, nu=0.3, Sy=1e9, rho=7800.0)
    if field == "rho" and bad is None:
        return  # rho=None means "no density"
    kw[field] = bad
    with pytest.raises(TypeError, match=_named(field)):
        fastrest.Material(**kw)


def test_material_stores_plain_floats():
    m = fastrest.Material(np.float32(2e11), np.array(0.3), 10**9, rho=np.int64(7800))
    for v in (m.E, m.nu, m.Sy, m.rho):
        assert type(v) is float
    assert m == fastrest.Material(float(np.float32(2e11)), 0.3, 1e9, rho=7800.0)


@pytest.mark.parametrize("bad", ["0.01", None, True])
def test_impact_radius_type(bad):
    steel = fastrest.Material(200e9, 0.33, 1.12e9, rho=7800)
    with pytest.raises(TypeError, match=_named("R")):
        fastrest.Impact(steel, bad)


# ---- limits in the caller's units ----------------------------------------------------------

def steel_impact():
    return fastrest.Impact(fastrest.Material(200e9, 0.33, 1.12e9, rho=7800), 0.01)


def test_impact_limit_in_metres_per_second():
    imp = steel_impact()
    v_max = imp.V_max()
    assert v_max == pytest.approx(fastrest.limit(imp.eps_y, imp.nu).v1_star * imp.V_c, rel=1e-15)
    assert imp.max_interference(v_max * (1 - 1e-9)) / imp.omega_c == pytest.approx(425.0, rel=1e-7)
    for V in (v_max * 1.001, [1.0, v_max * 2]):
        with pytest.raises(ValueError, match=r"V1 = [0-9.e+]+ m/s gives w_m\* > 425") as exc:
            imp.e(V)
        assert f"{v_max:.10g} m/s" in str(exc.value)
    # extrapolating, the limit moves to a/R = 1
    v_ar = imp.V_max(extrapolate=True)
    assert v_ar > v_max
    with pytest.warns(fastrest.ExtrapolationWarning):
        assert 0.0 < imp.e(v_ar * 0.999, extrapolate=True) < 1.0
    with pytest.raises(ValueError, match=r"a/R = 1.*m/s"):
        imp.e(v_ar * 1.001, extrapolate=True)


def test_negative_speed_named_in_metres_per_second():
    with pytest.raises(ValueError, match=r"V1 must be finite and >= 0 \(m/s\)"):
        steel_impact().e(-1.0)


def test_curve_v_max_named():
    lim = fastrest.limit(0.005, 0.33).v1_star
    with pytest.raises(ValueError, match=r"^v_max = .* 425"):
        fastrest.curve(0.005, 0.33, v_max=lim * 1.01)


def test_a_over_r_threshold_of_tables():
    """Below EPS_Y_AR_BINDS the law's end a/R = 1 is past w* = 425 for every nu (so the table
    kernel skips that check there); just above it, for nu near 0.5, it is not."""
    for nu in np.linspace(0.0, 0.5, 51):
        assert omega_star_limit_kernel(tables.EPS_Y_AR_BINDS, nu) > 425.0
    assert omega_star_limit_kernel(tables.EPS_Y_AR_BINDS * 1.003, 0.5) < 425.0


def test_wide_table_stops_at_a_over_r_limit():
    """A table past eps_y = 0.0102 holds materials whose law ends (a/R = 1) before w* = 425:
    it raises there, as the direct solver does, instead of returning the formula's continuation."""
    g = dict(eps_y_min=0.015, eps_y_max=0.025, n_eps_y=6, nu_min=0.3, nu_max=0.35, n_nu=6,
             bits_per_octave=1, eps_y_blocks=[], n_eps_y_energy=6)
    t = tables.Table(tables.generate(g, progress=False))
    eps, nu = 0.02, 0.32
    assert omega_star_limit_kernel(eps, nu) < 425.0
    lim = fastrest.limit(eps, nu).v1_star
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", fastrest.ValidityWarning)
        assert t.e(lim * 0.99, eps, nu) == pytest.approx(direct.e_exact(lim * 0.99, eps, nu), rel=1e-4)
        for v in (lim * 1.001, [10.0, lim * 1.5]):
            with pytest.raises(ValueError, match="a/R reaches 1"):
                t.e(v, eps, nu)
            with pytest.raises(ValueError, match="a/R reaches 1"):
                t.omega_m(v, eps, nu)
        out = np.empty(1)
        from fastrest.tables.kernel import table_array
        table_array(t.data, 1, np.array([lim * 1.001]), np.array([eps]), np.array([nu]), out)
        assert math.isnan(out[0])


def test_single_element_inputs_raise_no_numpy_warning():
    """Broadcasting a 1-element array against scalars must not hand Numba a broadcast view
    (NumPy warns FutureWarning when its writeable flag is read)."""
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        direct.solve(np.array([19.0]), 0.005, 0.33, "jcg")
        fastrest.e_star(np.array([5.0]), 0.005, 0.33)
        direct.e_exact(np.array([5.0]), np.array([0.005]), 0.33)


def test_submodules_reachable_after_import_fastrest():
    code = ("import fastrest; fastrest.models.MODELS['thornton']; fastrest.rough.RoughSurface; "
            "fastrest.jit.e_curve; fastrest.figures; import sys; print('ok')")
    env = dict(os.environ)
    env["PYTHONPATH"] = str(Path(__file__).resolve().parents[1]) + os.pathsep + env.get("PYTHONPATH", "")
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=300, env=env)
    assert r.returncode == 0 and r.stdout.strip() == "ok", r.stderr
    with pytest.raises(AttributeError, match="no_such_thing"):
        fastrest.no_such_thing


def test_curve_and_scene_inputs_name_the_parameter():
    with pytest.raises(TypeError, match="eps_y"):
        fastrest.curve(np.array([0.005, 0.006]), 0.33)
    with pytest.raises(TypeError, match="v_max"):
        fastrest.curve(0.005, 0.33, v_max="10")
    with pytest.raises(ValueError, match=r"materials\[1\].*\(eps_y, nu\) pair"):
        fastrest.scene([(0.005, 0.33), (0.005,)])


@pytest.mark.parametrize("grid, word", [(dict(nu_max=0.5), "nu_max"), (dict(nu_min=-0.1), "nu_min"),
                                        (dict(eps_y_max="0.02"), "eps_y_max"), (dict(n_nu=6.5), "n_nu"),
                                        (dict(eps_y_min=0.0), "eps_y_min")])
def test_bad_grid_rejected(grid, word):
    with pytest.raises((TypeError, ValueError), match=word):
        tables.normalise_grid(grid)


@pytest.mark.slow
def test_jit_table_functions_reject_unknown_unloading():
    """The unloading code indexes the table's quantities: anything but a model the table holds
    (JCG, ETSION, BRAKE) is NaN, never a neighbouring quantity's value or a read outside the
    coefficient array."""
    import numba
    from fastrest import jit as frj

    @numba.njit
    def both(d, u):
        return frj.e_table(d, 5.0, 0.005, 0.33, u), frj.loss_table(d, 5.0, 0.005, 0.33, u)

    d = fastrest.load_table().data
    for u in (-1, 3, 4, 10**6, -(10**6)):
        e, loss = both(d, u)
        assert math.isnan(e) and math.isnan(loss), u
    e, loss = both(d, frj.ETSION)
    assert e == pytest.approx(direct.e_exact(5.0, 0.005, 0.33, unloading="etsion"), rel=1e-9)
    for q in (-1, d.n_quantities):
        assert math.isnan(tables.table_value(d, q, 5.0, 0.005, 0.33))


def _warning_line(f):
    with warnings.catch_warnings(record=True) as rec:
        warnings.simplefilter("always")
        f()
    assert rec, "no warning"
    return rec[0].filename


@pytest.mark.parametrize("call", [
    lambda: direct.e_exact(2000.0, 0.005, 0.33, extrapolate=True),
    lambda: direct.e_exact(5.0, 0.02, 0.33),
    lambda: steel_impact().e(100.0, extrapolate=True),
    lambda: fastrest.Impact(fastrest.Material(200e9, 0.1, 1e9, rho=7800), 0.01).e(1.0),
    lambda: fastrest.scene([(0.02, 0.33)], v_max=10.0),
    lambda: fastrest.curve(0.02, 0.33, v_max=10.0),
    lambda: fastrest.models.jgm_fit_jcg(2000.0, 0.005),
], ids=["direct-extrapolate", "direct-validity", "impact-extrapolate", "impact-validity", "scene",
        "curve", "fit"])
def test_warnings_point_at_the_callers_line(call):
    assert _warning_line(call) == __file__


def test_impact_accepts_its_own_v_max():
    """V_max() is accepted (the m/s check leaves the solver's rounding alone), for many materials."""
    rng = np.random.default_rng(7)
    for E, nu, Sy in zip(rng.uniform(70e9, 400e9, 60), rng.uniform(0.2, 0.45, 60), rng.uniform(2e8, 2e9, 60)):
        imp = fastrest.Impact(fastrest.Material(E, nu, Sy, rho=7800), 0.01)
        if not (0.0005 <= imp.eps_y <= 0.01):
            continue
        assert 0.0 < imp.e(imp.V_max()) < 1.0
        for unloading in ("jcg", "etsion"):
            with pytest.warns(fastrest.ExtrapolationWarning):
                v = imp.V_max(unloading, extrapolate=True)
                assert 0.0 <= imp.e(v, unloading, extrapolate=True) < 1.0


def test_scene_material_index_of_any_integer_type_in_njit():
    import numba
    from fastrest import jit as frj

    @numba.njit
    def run(d, k, v):
        out = np.empty(k.size)
        for i in range(k.size):
            out[i] = frj.e_material(d, v[i], k[i])
        return out

    s = fastrest.scene([(0.005, 0.3), (0.002, 0.25)], v_max=100.0)
    ref = s.e([10.0, 10.0], [0, 1])
    for dt in (np.uint64, np.int32, np.uint8, np.int64):
        out = run(s.data, np.array([0, 1, 2], dtype=dt), np.full(3, 10.0))
        np.testing.assert_array_equal(out[:2], ref)
        assert math.isnan(out[2])


def test_extrapolated_curve_copies_are_independent():
    import copy
    with pytest.warns(fastrest.ExtrapolationWarning):
        c = fastrest.curve(0.005, 0.33, extrapolate=True)
    for d in (copy.copy(c), copy.deepcopy(c)):
        assert type(d) is type(c)
        with pytest.warns(fastrest.ExtrapolationWarning):
            assert d.e(c.v_max) > 0.0
        with warnings.catch_warnings():
            warnings.simplefilter("error")
            assert d.e(20.0) == fastrest.curve(0.005, 0.33).e(20.0)


def test_mixed_lists_and_buffers_rejected():
    for bad in ([1.0, True], [2.0, None], bytearray(b"1"), memoryview(b"ab")):
        with pytest.raises(TypeError, match="v1_star"):
            fastrest.e_star(bad, 0.005, 0.33)
    with pytest.raises(ValueError, match="whole numbers"):
        tables.normalise_grid({"eps_y_blocks": [[128, 24.9]]})


def test_jcg_unloading_ends_where_residual_reaches_maximum_interference():
    """JCG eq (35) gives w_res/w_m = 1 at w_m* = 10017.5 (reached only extrapolating): past it e is
    undefined and every API raises instead of returning NaN; Etsion goes on to a/R = 1."""
    from fastrest.unloading.jcg import OMEGA_END as JCG_OMEGA_END, residual_ratio as jcg_residual_ratio
    assert jcg_residual_ratio(JCG_OMEGA_END - 1.0) == pytest.approx(1.0, abs=1e-14)
    eps, nu = 0.0007, 0.35
    lim_ar = fastrest.limit(eps, nu, extrapolate=True).v1_star
    with pytest.raises(ValueError, match=r"JCG unloading \(eq 35\)"):
        direct.e_exact(lim_ar, eps, nu, extrapolate=True)
    with pytest.raises(ValueError, match=r"^v_max = .*JCG unloading"):
        fastrest.curve(eps, nu, v_max=lim_ar, extrapolate=True)
    with pytest.warns(fastrest.ExtrapolationWarning):
        assert 0.0 < direct.e_exact(lim_ar, eps, nu, "etsion", extrapolate=True) < 1.0
        c = fastrest.curve(eps, nu, extrapolate=True)
        # curves stop short of the end, where e falls like a square root
        assert c.e(c.v_max) > 0.0 and c.omega_m(c.v_max) == pytest.approx(0.6 * JCG_OMEGA_END, rel=1e-9)


def test_impact_jcg_end_in_metres_per_second():
    imp = fastrest.Impact(fastrest.Material(200e9, 0.33, 1.5e8, rho=7800), 0.01)   # eps_y ~ 0.00067
    v_jcg, v_ar = imp.V_max("jcg", extrapolate=True), imp.V_max("etsion", extrapolate=True)
    assert v_jcg < v_ar
    with pytest.raises(ValueError, match=r"V1 = .* m/s is past the end of JCG unloading"):
        imp.e(v_jcg * 1.01, extrapolate=True)
    with pytest.warns(fastrest.ExtrapolationWarning):
        assert 0.0 < imp.e(v_jcg * 1.01, "etsion", extrapolate=True) < 1.0
        assert imp.max_interference(v_ar * 0.999, extrapolate=True) > 0.0   # w_m does not depend on unloading


def test_limits_validate_the_material():
    """fastrest.limit is public: a bad material is a named error, not a plausible limit (the speed
    limit of eps_y = -1 once came out as 0.0923)."""
    f = fastrest.limit
    with pytest.raises(ValueError, match="eps_y"):
        f(-1.0, 0.33)
    with pytest.raises(ValueError, match="nu"):
        f(0.005, 0.5)
    with pytest.raises(TypeError, match="eps_y"):
        f("a", 0.33)
    with pytest.raises(TypeError):
        f(0.005, 0.33, None, True)  # extrapolate is keyword-only
    with pytest.raises(ValueError, match="unloading"):
        f(0.005, 0.33, "hertz")


def test_contact_law_names_its_own_w_max():
    law = fastrest.contact_law(0.005, 0.33, w_max=30.0)
    with pytest.raises(ValueError, match="w_max = 30.0"):
        law.force([1.0, 40.0])
    with pytest.raises(ValueError, match="425"):
        fastrest.contact_law(0.005, 0.33).force([1.0, 440.0])


def test_returned_energy_nan_in_nan_out():
    from fastrest.unloading import elastic
    assert math.isnan(elastic.returned_energy(math.nan, 10.0, 25.0, 2.0, 8.0))
    assert elastic.returned_energy(1.0, 10.0, 25.0, 2.0, 8.0) == 0.0   # below w_res: nothing returned


def test_impact_v1_star_scalar_is_a_python_float():
    imp = fastrest.Impact(fastrest.Material(200e9, 0.33, 1.12e9, 7800), 0.01)
    assert type(imp.v1_star(1.0)) is float
    assert imp.v1_star([1.0, 2.0]).shape == (2,)
