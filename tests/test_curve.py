"""Tests of the one-material fast path, fastrest.curve / Curve (bit-indexed quintic cells).

Every reference value comes from the exact direct solver (fastrest.direct, ~1e-15 relative,
itself checked against the mpmath slow path in tests/test_direct.py), never from the curve.

Error measure: |got - ref| / |ref| for w_m*, e and 1 - e^2 (JCG). The Etsion loss 1 - e^2 crosses
zero just above V1* = 1.9^1.25 for nu below about 0.32 (the model gives e > 1 there), so its error
is measured relative to max(|1 - e^2|, 1e-3), the same convention as Table.measure_error.
"""
import math
import warnings

import numpy as np
import pytest

import fastrest
from fastrest import ExtrapolationWarning, ValidityWarning, direct
from fastrest import jit as frj

V_SWITCH = 1.9 ** 1.25          # V1* where w_m* = 1.9 (Hertz -> JG), exact float of the package
EPS_RANGE = (0.0005, 0.01)
NU_RANGE = (0.2, 0.45)
UNLOADINGS = ("jcg", "etsion", "brake")
#: Models whose 1 - e^2 changes sign just above V1* = 1.9^1.25 (e > 1 there for nu < ~0.32).
SIGN_CHANGING = ("etsion", "brake")
# Corners and centre of the validated (eps_y, nu) range.
MATERIALS = [(0.0005, 0.2), (0.0005, 0.45), (0.01, 0.2), (0.01, 0.45), (0.00525, 0.325)]
SEED = 20240611

TOL_E = 1e-12       # e and w_m*, relative
TOL_LOSS = 1e-10    # 1 - e^2, relative (Etsion: relative to max(|loss|, 1e-3))
ETSION_LOSS_FLOOR = 1e-3


def hard_speeds(v_max):
    """The hard cases: onset of plasticity, both sides of the Hertz/JG switch, the top end."""
    vs = V_SWITCH
    return np.array([
        0.0, 0.5, 1.0, 1.0 + 1e-12, 1.0 + 1e-9, 1.0 + 1e-6,
        vs, math.nextafter(vs, 0.0), math.nextafter(vs, math.inf),
        vs * (1 - 1e-12), vs * (1 + 1e-12), vs * (1 - 1e-6), vs * (1 + 1e-6),
        v_max, math.nextafter(v_max, 0.0), v_max * (1 - 1e-9),
    ])


def random_speeds(v_max, n=1500, seed=SEED):
    """Uniform over (0, v_max] and log-uniform over (1, v_max] (fixed seed)."""
    rng = np.random.default_rng(seed)
    u = rng.uniform(0.0, v_max, n)
    g = np.exp(rng.uniform(0.0, math.log(v_max), n))
    return np.concatenate([u[u > 0], g[g <= v_max]])


def rel_errors(got, ref, floor=0.0):
    got = np.asarray(got, dtype=float)
    ref = np.asarray(ref, dtype=float)
    den = np.maximum(np.abs(ref), floor)
    err = np.abs(got - ref)
    return np.where(den > 0, err / np.where(den > 0, den, 1.0), err)


_CURVES = {}


def get_curve(eps, nu, unloading, v_max=None):
    key = (eps, nu, unloading, v_max)
    if key not in _CURVES:
        _CURVES[key] = fastrest.curve(eps, nu, unloading, v_max=v_max)
    return _CURVES[key]


def compare(c, v):
    """Worst relative errors (and where) of w_m*, e, 1 - e^2 of curve c against the direct solver."""
    ref = direct.solve(v, c.eps_y, c.nu, c.unloading)
    floor = ETSION_LOSS_FLOOR if c.unloading in SIGN_CHANGING else 0.0
    out = {}
    for name, got, r, fl in (("omega_m", c.omega_m(v), ref["omega_m_star"], 0.0),
                             ("e", c.e(v), ref["e"], 0.0),
                             ("loss", c.loss(v), ref["loss"], floor)):
        assert np.all(np.isfinite(got)), name
        rel = rel_errors(got, r, fl)
        k = int(np.argmax(rel))
        out[name] = (float(rel[k]), float(v[k]))
    return out


def check(errs, label):
    msg = f"{label}: " + ", ".join(f"{k} {a:.2e} at V1*={b!r}" for k, (a, b) in errs.items())
    print("\n[curve]", msg)
    assert errs["omega_m"][0] <= TOL_E, msg
    assert errs["e"][0] <= TOL_E, msg
    assert errs["loss"][0] <= TOL_LOSS, msg


# ============================================================================================
# Accuracy against the direct solver

@pytest.mark.parametrize("unloading", UNLOADINGS)
@pytest.mark.parametrize("eps, nu", MATERIALS)
def test_curve_matches_direct_random(eps, nu, unloading):
    c = get_curve(eps, nu, unloading)
    assert c.v_max == pytest.approx(fastrest.limit(eps, nu).v1_star, rel=1e-14)
    check(compare(c, random_speeds(c.v_max)), f"eps_y={eps} nu={nu} {unloading} random")


@pytest.mark.parametrize("unloading", UNLOADINGS)
@pytest.mark.parametrize("eps, nu", MATERIALS)
def test_curve_matches_direct_hard_cases(eps, nu, unloading):
    c = get_curve(eps, nu, unloading)
    check(compare(c, hard_speeds(c.v_max)), f"eps_y={eps} nu={nu} {unloading} hard cases")


@pytest.mark.parametrize("unloading", UNLOADINGS)
def test_curve_with_smaller_v_max_matches_direct(unloading):
    """A curve built only up to the speed a scene needs (last cell cut at v_max)."""
    v_max = 123.456
    c = get_curve(0.003, 0.3, unloading, v_max)
    assert c.v_max == v_max
    v = np.concatenate([random_speeds(v_max, 500), hard_speeds(v_max)])
    check(compare(c, v), f"v_max={v_max} {unloading}")


@pytest.mark.parametrize("v_max", [3.0, 8.0, 200.0, 256.0])
def test_v_max_on_a_cell_boundary(v_max):
    """v_max exactly on a cell boundary of the bit-indexed grid (any power of two, and e.g. the
    README's v_max = 200 = 2^7 * (1 + 18/32)): evaluating at V1* = v_max must still give the
    model's value (the last cell is dropped as empty, so V1* = v_max indexes one past the end)."""
    c = fastrest.curve(0.005, 0.33, v_max=v_max)
    ref = direct.solve(v_max, 0.005, 0.33)
    assert c.e(v_max) == pytest.approx(ref["e"], rel=TOL_E, abs=0)
    assert c.omega_m(v_max) == pytest.approx(ref["omega_m_star"], rel=TOL_E, abs=0)
    assert c.loss(v_max) == pytest.approx(ref["loss"], rel=TOL_LOSS, abs=0)
    assert c.e(np.array([v_max]))[0] == pytest.approx(ref["e"], rel=TOL_E, abs=0)


@pytest.mark.parametrize("eps, nu", MATERIALS)
def test_etsion_jump_at_switch_is_sharp(eps, nu):
    """Etsion unloading with Hertz loading gives e = 1 exactly up to and including V1* = 1.9^1.25;
    one float above, the JG law takes over and e jumps (no smearing across the switch)."""
    c = get_curve(eps, nu, "etsion")
    below = [1.0, 1.5, V_SWITCH * (1 - 1e-6), V_SWITCH * (1 - 1e-12), math.nextafter(V_SWITCH, 0.0),
             V_SWITCH]
    for v in below:
        assert c.e(v) == 1.0, v
        assert c.loss(v) == 0.0, v
        assert c.e(np.array([v]))[0] == 1.0, v
    for v in (math.nextafter(V_SWITCH, math.inf), V_SWITCH * (1 + 1e-12), V_SWITCH * (1 + 1e-6)):
        ref = direct.e_exact(v, eps, nu, "etsion")
        assert abs(ref - 1.0) > 1e-4  # the model's jump at this material
        got = c.e(v)
        assert got == pytest.approx(ref, rel=TOL_E, abs=0), v
        if nu >= 0.33:
            assert got < 1.0
        elif nu <= 0.3:
            assert got > 1.0  # JG force above Hertz's at w* = 1.9 (README, Domain and errors)


@pytest.mark.parametrize("eps, nu", MATERIALS)
def test_jcg_both_sides_of_switch(eps, nu):
    c = get_curve(eps, nu, "jcg")
    for v in (math.nextafter(V_SWITCH, 0.0), V_SWITCH, math.nextafter(V_SWITCH, math.inf)):
        ref = direct.solve(v, eps, nu, "jcg")
        assert c.e(v) == pytest.approx(ref["e"], rel=TOL_E, abs=0)
        assert c.loss(v) == pytest.approx(ref["loss"], rel=TOL_LOSS, abs=0)
        assert c.omega_m(v) == pytest.approx(ref["omega_m_star"], rel=TOL_E, abs=0)


@pytest.mark.parametrize("unloading", UNLOADINGS)
def test_onset_loss_relative_accuracy(unloading):
    """1 - e^2 keeps full relative accuracy as V1* -> 1 (no cancellation)."""
    c = get_curve(0.005, 0.33, unloading)
    for v in (1.0 + 1e-12, 1.0 + 1e-9, 1.0 + 1e-6):
        ref = direct.loss_exact(v, 0.005, 0.33, unloading)
        got = c.loss(v)
        if unloading in SIGN_CHANGING:  # e = 1 exactly under Hertz loading
            assert got == 0.0 and ref == 0.0
        else:
            assert ref > 0
            assert got == pytest.approx(ref, rel=TOL_LOSS, abs=0)
    assert c.loss(1.0) == 0.0 and c.e(1.0) == 1.0


def test_elastic_region():
    c = get_curve(0.005, 0.33, "jcg")
    v = np.array([0.0, 1e-300, 1e-10, 0.3, 0.999, 1.0])
    assert np.all(c.e(v) == 1.0)
    assert np.all(c.loss(v) == 0.0)
    np.testing.assert_allclose(c.omega_m(v), direct.omega_m_exact(v, 0.005, 0.33), rtol=1e-15, atol=0)


def test_extrapolate_matches_direct_and_warns():
    eps, nu = 0.005, 0.33
    lim = fastrest.limit(eps, nu).v1_star
    top = fastrest.limit(eps, nu, extrapolate=True).v1_star
    v_max = min(1.4 * lim, top)
    with pytest.warns(ExtrapolationWarning, match="425"):
        c = fastrest.curve(eps, nu, v_max=v_max, extrapolate=True)
    assert c.v_max == v_max
    v = np.linspace(lim, v_max, 50)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ExtrapolationWarning)
        ref = direct.solve(v, eps, nu, extrapolate=True)
    for f, key, tol in ((c.e, "e", TOL_E), (c.omega_m, "omega_m_star", TOL_E), (c.loss, "loss", TOL_LOSS)):
        with pytest.warns(ExtrapolationWarning, match="425") as rec:   # every evaluation past the limit
            np.testing.assert_allclose(f(v), ref[key], rtol=tol, atol=0)
        assert rec[0].filename == __file__        # attributed to the caller's line
        with pytest.warns(ExtrapolationWarning):
            f(float(v[-1]))                       # the scalar path too
    with warnings.catch_warnings():                # inside the validated range: silent
        warnings.simplefilter("error")
        assert c.e(lim * 0.5) == pytest.approx(direct.e_exact(lim * 0.5, eps, nu), rel=TOL_E, abs=0)
    with pytest.warns(ExtrapolationWarning):
        s = fastrest.scene([(eps, nu), (0.002, 0.3)], v_max=[v_max, 100.0], extrapolate=True)
    with pytest.warns(ExtrapolationWarning):
        s.e([v_max, 50.0], [0, 1])
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        s.e([lim * 0.5, 50.0], [0, 1])


def test_extrapolate_not_needed_does_not_warn():
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        c = fastrest.curve(0.005, 0.33, v_max=100.0, extrapolate=True)
    assert c.e(50.0) == pytest.approx(direct.e_exact(50.0, 0.005, 0.33), rel=TOL_E, abs=0)


# ============================================================================================
# Input handling

@pytest.fixture(scope="module")
def c50():
    return fastrest.curve(0.005, 0.33, "jcg", v_max=50.5)


@pytest.mark.parametrize("method", ["e", "loss", "omega_m"])
def test_scalar_in_float_out(c50, method):
    f = getattr(c50, method)
    ref = direct.solve(7.5, 0.005, 0.33)[{"e": "e", "loss": "loss", "omega_m": "omega_m_star"}[method]]
    for x in (7.5, np.float64(7.5), np.array(7.5), np.float32(7.5)):
        r = f(x)
        assert type(r) is float, type(x)
        assert r == pytest.approx(ref, rel=TOL_LOSS, abs=0)
    assert type(f(3)) is float            # Python int
    assert f(3) == f(3.0)


@pytest.mark.parametrize("method", ["e", "loss", "omega_m"])
def test_array_inputs(c50, method):
    f = getattr(c50, method)
    v = np.linspace(0.5, 50.0, 12)
    ref = np.array([f(float(x)) for x in v])     # scalar fast path
    np.testing.assert_array_equal(f(v), ref)     # array path: the same numbers
    assert f(v.tolist()).shape == (12,)
    np.testing.assert_array_equal(f(v.tolist()), ref)
    m = v.reshape(3, 4)
    assert f(m).shape == (3, 4)
    np.testing.assert_array_equal(f(m), ref.reshape(3, 4))
    ro = v.copy()
    ro.setflags(write=False)
    np.testing.assert_array_equal(f(ro), ref)
    nc = np.repeat(v, 2)[::2]                    # non-contiguous view
    assert not nc.flags.c_contiguous
    np.testing.assert_array_equal(f(nc), ref)
    np.testing.assert_array_equal(f(v.astype(np.float32)), [f(float(x)) for x in v.astype(np.float32)])
    assert f(np.empty(0)).shape == (0,)
    assert f(np.empty((2, 0))).shape == (2, 0)


@pytest.mark.parametrize("method", ["e", "loss", "omega_m"])
@pytest.mark.parametrize("v", [50.6, 1e6, [1.0, 60.0], np.array([[2.0], [51.0]])])
def test_beyond_v_max_raises(c50, method, v):
    with pytest.raises(ValueError, match="v_max"):
        getattr(c50, method)(v)


@pytest.mark.parametrize("method", ["e", "loss", "omega_m"])
@pytest.mark.parametrize("v", [-1.0, -1e-300, math.nan, math.inf, -math.inf, [2.0, math.nan],
                               np.array([3.0, -2.0])])
def test_invalid_speed_raises_naming_v1_star(c50, method, v):
    with pytest.raises(ValueError, match="v1_star"):
        getattr(c50, method)(v)


def test_v_max_below_switch_refuses_higher_speeds():
    """A curve built with v_max below 1.9^1.25 must refuse speeds above v_max like any other curve
    (the docstring: "Speeds outside [0, v_max] raise ValueError"; jit: NaN for V1* > v_max)."""
    c = fastrest.curve(0.005, 0.33, v_max=2.0)
    assert c.v_max == 2.0
    assert c.e(2.0) == pytest.approx(direct.e_exact(2.0, 0.005, 0.33), rel=TOL_E, abs=0)
    with pytest.raises(ValueError, match="v_max"):
        c.e(2.1)
    with pytest.raises(ValueError, match="v_max"):
        c.e(np.array([2.1]))
    assert math.isnan(frj.e_curve(c.data, 2.1))


def test_v_max_beyond_425_raises():
    lim = fastrest.limit(0.005, 0.33).v1_star
    with pytest.raises(ValueError, match="425"):
        fastrest.curve(0.005, 0.33, v_max=lim * 1.01)
    with pytest.raises(ValueError, match="425"):
        fastrest.curve(0.005, 0.33, v_max=1e5)


def test_extrapolate_past_a_over_r_1_raises():
    top = fastrest.limit(0.01, 0.45, extrapolate=True).v1_star
    with pytest.raises(ValueError, match="a/R"):
        fastrest.curve(0.01, 0.45, v_max=top * 1.01, extrapolate=True)


@pytest.mark.parametrize("v_max", [-1.0, math.nan, math.inf])
def test_bad_v_max_raises(v_max):
    with pytest.raises(ValueError, match="v_max"):
        fastrest.curve(0.005, 0.33, v_max=v_max)


@pytest.mark.parametrize("eps, nu", [(0.02, 0.3), (0.0002, 0.3), (0.005, 0.1), (0.005, 0.48)])
def test_outside_validated_range_warns(eps, nu):
    with pytest.warns(ValidityWarning, match="eps_y" if eps != 0.005 else "nu"):
        c = fastrest.curve(eps, nu, v_max=20.0)
    with pytest.warns(ValidityWarning):
        ref = direct.e_exact(15.0, eps, nu)
    assert c.e(15.0) == pytest.approx(ref, rel=TOL_E, abs=0)


def test_validated_range_does_not_warn():
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        for eps, nu in MATERIALS:
            fastrest.curve(eps, nu, v_max=10.0)


@pytest.mark.parametrize("eps", [0.0, -0.001, math.nan, math.inf])
def test_bad_eps_y_raises(eps):
    with pytest.raises(ValueError, match="eps_y"):
        fastrest.curve(eps, 0.3)


@pytest.mark.parametrize("nu", [-0.1, 0.5, 0.7, math.nan])
def test_bad_nu_raises(nu):
    with pytest.raises(ValueError, match="nu"):
        fastrest.curve(0.005, nu)


def test_bad_unloading_raises():
    with pytest.raises(ValueError, match="unloading"):
        fastrest.curve(0.005, 0.3, unloading="hertz")


def test_curve_attributes_and_data():
    c = fastrest.curve(0.004, 0.31, "etsion", v_max=77.0)
    assert (c.eps_y, c.nu, c.unloading, c.v_max) == (0.004, 0.31, "etsion", 77.0)
    assert isinstance(c, fastrest.Curve)
    assert isinstance(c.data, frj.CurveData)
    assert c.data.model == frj.ETSION and c.data.v_max == 77.0
    for rows in (c.data.omega_rows, c.data.e_rows, c.data.loss_rows):
        assert rows.ndim == 2 and rows.shape[1] == 8 and rows.flags.c_contiguous
    assert "0.004" in repr(c) and "etsion" in repr(c)


# ============================================================================================
# Scenes: several materials' curves, one batch call by material index

SCENE_MATERIALS = [(0.0005, 0.2), (0.01, 0.45), (0.00525, 0.325)]


@pytest.mark.parametrize("unloading", UNLOADINGS)
def test_scene_matches_curves_and_direct(unloading):
    v_max = [200.0, 256.0, 2.0]          # two on cell boundaries, one below the switch
    s = fastrest.scene(SCENE_MATERIALS, unloading, v_max=v_max)
    assert isinstance(s, fastrest.Scene) and len(s) == 3
    rng = np.random.default_rng(SEED)
    k = rng.integers(0, 3, 3000)
    vm = np.array(v_max)[k]
    v = rng.uniform(0.0, 1.0, k.size) * vm
    v[:3], k[:3] = v_max, [0, 1, 2]     # each material at its own v_max
    eps = np.array([m[0] for m in SCENE_MATERIALS])[k]
    nu = np.array([m[1] for m in SCENE_MATERIALS])[k]
    ref = direct.solve(v, eps, nu, unloading)
    floor = ETSION_LOSS_FLOOR if unloading in SIGN_CHANGING else 0.0
    assert rel_errors(s.e(v, k), ref["e"]).max() <= TOL_E
    assert rel_errors(s.omega_m(v, k), ref["omega_m_star"]).max() <= TOL_E
    assert rel_errors(s.loss(v, k), ref["loss"], floor).max() <= TOL_LOSS
    for j, (e_, n_) in enumerate(SCENE_MATERIALS):   # same numbers as the material's own curve
        c = fastrest.curve(e_, n_, unloading, v_max=v_max[j])
        sel = k == j
        np.testing.assert_array_equal(s.e(v[sel], j), c.e(v[sel]))
        np.testing.assert_array_equal(s.loss(v[sel], j), c.loss(v[sel]))


def test_scene_inputs_and_errors():
    s = fastrest.scene(SCENE_MATERIALS, v_max=50.0)
    assert type(s.e(5.0, 1)) is float
    assert s.e([5.0, 6.0], [[0], [2]]).shape == (2, 2)
    assert s.e(5.0, np.int64(2)) == fastrest.curve(*SCENE_MATERIALS[2], v_max=50.0).e(5.0)
    with pytest.raises(ValueError, match="material"):
        s.e(5.0, 3)
    with pytest.raises(ValueError, match="material"):
        s.e(5.0, -1)
    with pytest.raises(ValueError, match="material"):
        s.e(5.0, 0.5)
    with pytest.raises(ValueError, match="v_max"):
        s.e([5.0, 51.0], [0, 1])
    for bad in (-1.0, math.nan, math.inf):
        with pytest.raises(ValueError, match="v1_star"):
            s.loss(bad, 0)
    with pytest.raises(ValueError):
        fastrest.scene([])


def _mp_hertz(v):
    """Exact Hertz-range closed forms at 1 < V1* <= 1.9^1.25 in 40-digit mpmath (JGM eqs 19, 35):
    w_m* = V1*^0.8 and, JCG, 1 - e^2 = w_res/w_m = 1.02 (1 - ((w_m + 5.9)/6.9)^-0.54)."""
    import mpmath as mp
    with mp.workdps(40):
        w = mp.mpf(v) ** mp.mpf("0.8")
        loss = mp.mpf("1.02") * (1 - ((w + mp.mpf("5.9")) / mp.mpf("6.9")) ** mp.mpf("-0.54"))
        return float(w), float(mp.sqrt(1 - loss)), float(loss)


def test_hertz_range_cells_reproduce_closed_form_to_a_few_ulp():
    """Below 1.9^1.25 the curve evaluates the closed forms by polynomial cells: they must agree with
    the exact closed form (mpmath) to within 1e-15 relative (~4.5 ulp) for w_m* and e, and 2e-15 for
    1 - e^2 (whose float closed form, expm1/log1p, is itself off by up to ~3 ulp), including V1* -> 1."""
    rng = np.random.default_rng(SEED + 7)
    v = np.concatenate([np.exp(rng.uniform(0.0, math.log(V_SWITCH), 400)),
                        1.0 + np.logspace(-15, -1, 30), [math.nextafter(1.0, 2.0), V_SWITCH,
                                                         math.nextafter(V_SWITCH, 0.0), 2.0, 1.5]])
    v = v[(v > 1.0) & (v <= V_SWITCH)]
    ref = np.array([_mp_hertz(x) for x in v]).T
    c = fastrest.curve(0.005, 0.33, v_max=50.0)
    for got, want, name, tol in ((c.omega_m(v), ref[0], "w_m", 1e-15), (c.e(v), ref[1], "e", 1e-15),
                                 (c.loss(v), ref[2], "loss", 2e-15)):
        rel = rel_errors(got, want)
        assert rel.max() <= tol, (name, rel.max(), v[np.argmax(rel)])
    # Etsion: e = 1 and 1 - e^2 = 0 exactly under Hertz loading
    ce = fastrest.curve(0.005, 0.33, "etsion", v_max=50.0)
    assert np.all(ce.e(v) == 1.0) and np.all(ce.loss(v) == 0.0)


def test_options_are_keyword_only():
    """v_max and extrapolate after the model choice only by name."""
    with pytest.raises(TypeError):
        fastrest.curve(0.005, 0.33, "jcg", 10.0)
    with pytest.raises(TypeError):
        fastrest.scene([(0.005, 0.33)], "jcg", 10.0)
    from fastrest.curve_data import build_curve_data
    with pytest.raises(TypeError):
        build_curve_data(0.005, 0.33, "jcg", 10.0)
    assert fastrest.curve(0.005, 0.33, "jcg", v_max=10.0).v_max == 10.0


def test_fast_scalar_takes_real_scalars_only():
    from fastrest.fastpath import fast_scalar
    assert fast_scalar(2.5) == 2.5 and type(fast_scalar(np.float32(0.5))) is float
    assert fast_scalar(np.uint8(7)) == 7.0 and fast_scalar(3) == 3.0
    for other in (True, np.bool_(True), "1", None, 2**60, np.array(1.0), np.array([1.0]), 1j, [1.0]):
        assert fast_scalar(other) is None, other


def test_quantity_methods_of_curves_and_scenes():
    """One implementation per quantity: named and documented as the quantity, the same numbers on
    the fast scalar path, the array path, an extrapolated curve and a scene (bit for bit)."""
    c = fastrest.curve(0.005, 0.33, v_max=50.0)
    with pytest.warns(ExtrapolationWarning):
        x = fastrest.curve(0.005, 0.33, extrapolate=True, v_max=1.5 * c.v_limit)
    s = fastrest.scene([(0.002, 0.3), (0.005, 0.33)], v_max=50.0)
    v = np.array([0.5, 1.0 + 1e-9, 3.0, 47.0])
    for name in ("omega_m", "e", "loss"):
        for obj in (c, x, s):
            meth = getattr(type(obj), name)
            assert meth.__name__ == name and "Parameters" in meth.__doc__ and "Examples" in meth.__doc__
        arr = getattr(c, name)(v)
        assert [getattr(c, name)(float(t)) for t in v] == arr.tolist()
        assert getattr(x, name)(v).tolist() == arr.tolist()
        assert getattr(s, name)(v, 1).tolist() == arr.tolist()
