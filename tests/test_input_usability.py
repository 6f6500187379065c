"""Input handling and usability: flags, non-numbers, extreme values, CLI user errors, jit input types,
table edges (the fuzz suite covers the rest)."""
import json
import math
import pickle
import subprocess
import sys

import numpy as np
import pytest

import fastrest
from fastrest import cli, models, rough

STEEL = fastrest.Material(2e11, 0.3, 1e9, rho=7800.0)


def test_zero_summits_refused_at_construction():
    with pytest.raises(ValueError, match="N = eta A_n"):
        rough.RoughSurface(STEEL, 1e-4, gw=dict(eta=1e-300, sigma=1e-6, A_n=1e-300))


@pytest.mark.parametrize("flag", ["False", "no", 2.5, math.nan, 1, None])
def test_flags_take_only_booleans(flag):
    imp = fastrest.Impact(STEEL, 0.01)
    for call in (lambda: imp.V_max(extrapolate=flag), lambda: fastrest.direct.e_exact(5.0, 0.005, 0.3, extrapolate=flag),
                 lambda: fastrest.curve(0.005, 0.3, extrapolate=flag), lambda: models.weir_tallon(1, 1e9, 2e11, 7800, cap=flag)):
        with pytest.raises(TypeError, match="extrapolate|cap"):
            call()
    assert imp.V_max(extrapolate=np.True_) == imp.V_max(extrapolate=True)


@pytest.mark.parametrize("call, word", [
    (lambda s: s.impact("0.01", 1e-3), "V1"), (lambda s: s.impact(True, 1e-3), "V1"),
    (lambda s: s.impact(0.01 + 0j, 1e-3), "V1"), (lambda s: rough.sweep([s], 1e-3, bytearray(b"1")), "M"),
    (lambda s: rough.RoughSurface(STEEL, 1e-4, heights=["0", "1e-6"]), "heights"),
    (lambda s: rough.RoughSurface(STEEL, 1e-4, heights=[True, False]), "heights"),
    (lambda s: fastrest.forward.forward_data(0.005, 0.33, "5"), "w_max"),
    (lambda s: fastrest.scene([(0.005, 0.33)], v_max=bytearray(b"1")), "v_max"),
    (lambda s: fastrest.scene([(0.005, 0.33), (0.004, 0.3)], v_max=[10.0, True]), "v_max"),
    (lambda s: rough.GreenwoodWilliamson(eta=np.array([1e10, 1e10]), sigma=1e-6), "eta"),
    (lambda s: fastrest.direct.e_exact(np.ma.masked_array([5.0, 6.0], [0, 1]), 0.005, 0.3), "masked"),
])
def test_non_numbers_raise_type_error(call, word):
    s = rough.RoughSurface(STEEL, 1e-4, heights=[0.0, 1e-8])
    with pytest.raises(TypeError, match=word):
        call(s)


def test_no_infinite_model_values_and_strict_json(capsys):
    imp = fastrest.Impact(STEEL, 0.01)
    with pytest.raises(ValueError, match="V1 must be > 0"):
        models.evaluate("weir_tallon", imp, 0.0)
    # Chang-Ling at huge speed: the stable form, e ~ (16/15)^(3/8) s^(-1/4) (reference: the formula)
    s = 1e160 * (fastrest.poisson_factor(0.3) / models.ceb_hardness_factor(0.3)) ** 2.5
    assert models.MODELS["chang_ling"](1e160, 0.005, 0.3) == pytest.approx((16 / 15) ** 0.375 * s**-0.25, rel=1e-12)
    with pytest.raises(ValueError, match="V1"):
        models.chang_ling_dimensional(imp, 1e200)
    with pytest.raises(ValueError, match="E_eff"):
        models.johnson(1.0, 1e9, 5e-324, 7800.0)
    assert cli.main(["e", "--E", "2e11", "--nu", "0.3", "--Sy", "1e9", "--R", "0.01", "--rho", "7800",
                     "--V", "0", "1", "--model", "all", "--json"]) == 0
    out = json.loads(capsys.readouterr().out, parse_constant=lambda c: pytest.fail(f"invalid JSON constant {c}"))
    assert out["impacts"][0]["e_weir_tallon"] is None and out["impacts"][1]["e_weir_tallon"] > 0
    assert any("weir_tallon" in w for w in out["warnings"])


def test_named_errors_for_extreme_values():
    for call, word in ((lambda: fastrest.direct.e_exact(10**400, 0.005, 0.3), "v1_star"),
                       (lambda: fastrest.Impact(STEEL, 1e300), "R"), (lambda: fastrest.Impact(STEEL, 1e-300), "R"),
                       (lambda: fastrest.Impact(fastrest.Material(1e70, 0.3, 5e67, rho=7800), 0.01), "Sy"),
                       (lambda: fastrest.Impact("steel", 0.01), "sphere"),
                       (lambda: fastrest.tables.normalise_grid(dict(eps_y_max=math.inf)), "eps_y_max"),
                       (lambda: fastrest.tables.normalise_grid(dict(n_eps_y=1e300)), "n_eps_y"),
                       (lambda: fastrest.tables.normalise_grid(dict(eps_y_blocks=[[128.0, 10**9]])), "eps_y_blocks"),
                       (lambda: fastrest.direct.e_exact([1.0, 2.0], [0.005, 0.004, 0.003], 0.3), "v1_star.*eps_y")):
        with pytest.raises((TypeError, ValueError), match=word):
            call()


@pytest.mark.parametrize("V1, M, word", [(1e-200, 1e-3, "too small"), (0.01, 1e300, "drives summits"),
                                         (1e200, 1e-3, "too large")])
def test_rough_extremes_give_domain_errors(V1, M, word):
    for s in (rough.RoughSurface(STEEL, 1e-4, heights=[0.0, 1e-8]),
              rough.RoughSurface(STEEL, 1e-4, gw=dict(eta=1e10, sigma=1e-6, A_n=1e-4))):
        with pytest.raises(ValueError, match=word):
            s.impact(V1, M)
    with pytest.raises(ValueError, match="sigma / omega_c"):
        rough.RoughSurface(STEEL, 1e-4, gw=dict(eta=1e10, sigma=1e300, A_n=1e-4))


@pytest.mark.slow
def test_rough_light_impacts_solved_where_the_gaussian_resolves():
    """Tiny impact energies: a converged answer (e -> 1 in the Hertz range) down to where the height
    density underflows, then a clear domain error (was "did not converge (please report)")."""
    ip = fastrest.Impact(STEEL, 1e-4, mass=1e-3)
    s = rough.RoughSurface(STEEL, 1e-4, gw=dict(eta=1e10, sigma=1e-4 * ip.omega_c, A_n=1e-4))
    r = s.impact(np.sqrt(1e-100) * ip.V_c, 1e-3)
    assert r.e == 1.0 and r.w_star_max < 1.0
    with pytest.raises(ValueError, match="too light"):
        s.impact(np.sqrt(1e-300) * ip.V_c, 1e-3)


@pytest.mark.parametrize("argv, word", [
    (["--E", "1e300"], "not a finite, normal double"), (["--R", "1e-300"], "mass"), (["--E", "-2e11"], "E must be"),
    (["--E", "-inf"], "E must be")])
def test_cli_user_errors_without_traceback(argv, word):
    base = ["e", "--E", "2e11", "--nu", "0.3", "--Sy", "1e9", "--R", "0.01", "--rho", "7800", "--V", "1"]
    args = list(base)
    args[args.index(argv[0]) + 1] = argv[1]
    r = subprocess.run([sys.executable, "-m", "fastrest"] + args, capture_output=True, text=True, timeout=300)
    assert r.returncode == 2 and "Traceback" not in r.stderr and word in r.stderr, r.stderr


def test_cli_build_bounds_and_info_default(capsys, tmp_path):
    out = str(tmp_path / "x.h5")
    assert cli.main(["build", "--out", out, "--eps-y-max", "inf"]) == 2
    assert cli.main(["build", "--out", out, "--n-eps-y", "1000000000"]) == 2
    assert not (tmp_path / "x.h5").exists()
    assert "n_eps_y" in capsys.readouterr().err
    assert cli.main(["info"]) == 0
    assert "default.h5" in capsys.readouterr().out


@pytest.mark.slow
def test_jit_functions_take_float32_and_integer_inputs():
    import numba as nb
    from fastrest import jit as frj

    c = fastrest.curve(0.005, 0.33, v_max=50.0)
    s = fastrest.scene([(0.005, 0.33), (0.003, 0.3)], v_max=50.0)
    t = fastrest.load_table()

    # one small function per kind of data: the integer/float32 signatures then recompile only the
    # kernel they concern (one function over all three compiled the table kernel 13 times: ~3 min)
    @nb.njit
    def f_curve(cd, v):
        return frj.e_curve(cd, v)

    @nb.njit
    def f_scene(sd, k, v):
        return frj.e_material(sd, v, k)

    @nb.njit
    def f_table(td, v):
        return frj.e_table(td, v, 0.005, 0.33, frj.JCG)

    want = (f_curve(c.data, 5.0), f_scene(s.data, 1, 5.0), f_table(t.data, 5.0))
    for v in (np.float32(5.0), 5, np.int32(5)):
        assert f_curve(c.data, v) == want[0]
        assert f_table(t.data, v) == want[2]
        for k in (1, np.int32(1), 1.0, np.uint8(1)):
            assert f_scene(s.data, k, v) == want[1]
    assert math.isnan(f_scene(s.data, 1.5, 5.0))  # not an index
    assert s.e(5.0, 1.0) == s.e(5.0, 1)
    with pytest.raises(ValueError, match="material"):
        s.e(5.0, 1.5)
    with pytest.raises(TypeError, match="material"):
        s.e(5.0, True)


def test_numpy_scalars_take_the_fast_path():
    """What a loop over an array yields (NumPy scalars) takes the scalar fast path, exactly; arrays,
    booleans and strings go to the checked path (the speed itself is in bench/, not asserted)."""
    from fastrest.fastpath import fast_scalar
    c = fastrest.curve(0.005, 0.33, v_max=50.0)
    for x in (5.0, np.float64(5.0), np.float32(5.0), np.int64(5), np.uint8(5), 5):
        assert fast_scalar(x) == 5.0 and isinstance(fast_scalar(x), float)  # np.float64 is a float
        assert c.e(x) == c.e(5.0)
    for x in (np.array(5.0), True, np.bool_(True), "5", 2**60):
        assert fast_scalar(x) is None


def test_last_ulp_at_table_edges_accepted_not_extrapolated():
    e = 0.001 + 0.0005 * 18
    assert e > 0.01
    assert fastrest.e_star(5.0, e, 0.33) == fastrest.e_star(5.0, 0.01, 0.33)
    assert fastrest.e_star(5.0, 0.005, 0.45 + 5e-17) == fastrest.e_star(5.0, 0.005, 0.45)
    with pytest.raises(ValueError, match="outside this table's range"):
        fastrest.e_star(5.0, 0.01 * (1 + 1e-14), 0.33)
