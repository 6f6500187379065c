"""Tests of fastrest.models: the comparison models and empirical fits of JGM (2010).

Reference values are computed here from the printed equations (or read from the paper's tables and
../shared/MODEL.md), not taken from the module's output.
"""
import math
import warnings

import mpmath
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.integrate import quad
from scipy.optimize import brentq

from fastrest import Impact, Material, ValidityWarning
from fastrest import models

NUS_TABLE2 = [0.1, 0.15, 0.2, 0.25, 0.3, 0.35, 0.4, 0.45]
# JGM Table 2 as printed (the nu = 0.5 column is checked separately).
TABLE2 = {
    "johnson": [0.712, 0.780, 0.855, 0.938, 1.028, 1.127, 1.236, 1.355],
    "wu": [0.708, 0.777, 0.852, 0.934, 1.024, 1.122, 1.230, 1.349],
    "thornton": [2.294, 2.515, 2.757, 3.023, 3.314, 3.634, 3.984, 4.368],
}
TABLE2_NU_HALF = {"johnson": 1.486, "wu": 1.479, "thornton": 4.789}


def C_of(nu):
    """JGM eq (5), written out here."""
    return 1.295 * math.exp(0.736 * nu)


def KH_of(nu):
    """CEB: K H / Sy = 2.8 (0.454 + 0.41 nu)."""
    return 2.8 * (0.454 + 0.41 * nu)


@pytest.fixture(scope="module")
def table1():
    """JGM Table 1: steel sphere, E = 200 GPa, nu = 0.33, Sy = 1.12 GPa, R = 1 cm, rho = 7800, rigid flat."""
    return Impact(Material(E=200e9, nu=0.33, Sy=1.12e9, rho=7800.0), R=0.01)


def log_slope(f, v, h=1e-4):
    return (math.log(f(v * (1 + h))) - math.log(f(v * (1 - h)))) / (math.log1p(h) - math.log1p(-h))


# ------------------------------------------------------------------------------ Table 2
@pytest.mark.parametrize("model", sorted(TABLE2))
def test_table2_ratios_to_printed_decimals(model):
    for nu, printed in zip(NUS_TABLE2, TABLE2[model]):
        got = models.yield_velocity_ratio(nu, model)
        assert isinstance(got, float)
        assert abs(got - printed) <= 0.0005 + 1e-12, (model, nu, got, printed)
    arr = models.yield_velocity_ratio(np.array(NUS_TABLE2), model)
    np.testing.assert_array_equal(np.round(arr, 3), TABLE2[model])


@pytest.mark.parametrize("model", sorted(TABLE2_NU_HALF))
def test_table2_nu_half_is_outside_domain_but_limit_matches(model):
    with pytest.raises(ValueError, match="nu"):
        models.yield_velocity_ratio(0.5, model)
    assert round(models.yield_velocity_ratio(0.5 - 1e-12, model), 3) == TABLE2_NU_HALF[model]


def test_yield_velocity_ratio_extra_models_and_bad_name(table1):
    assert models.yield_velocity_ratio(0.3, "jgm") == 1.0
    nu = 0.3
    assert models.yield_velocity_ratio(nu, "ceb") == pytest.approx((C_of(nu) / KH_of(nu)) ** 2.5, rel=1e-14)
    with pytest.raises(ValueError, match="model"):
        models.yield_velocity_ratio(0.3, "hertz")
    # dimensional yield velocity of Thornton: V_c / C^2.5
    assert models.yield_velocity(table1, "thornton") == pytest.approx(table1.V_c / C_of(0.33) ** 2.5, rel=1e-13)


# ------------------------------------------------------------------------------ Thornton, eq (2)
def thornton_ref(v1_star, nu):
    """Eq (2) in mpmath with x = V_y,Th / V1 = 1 / (v1_star C^2.5)."""
    mpmath.mp.dps = 40
    x = 1 / (mpmath.mpf(v1_star) * mpmath.mpf(C_of(nu)) ** mpmath.mpf(2.5))
    k = mpmath.sqrt(6 * mpmath.sqrt(3) / 5)
    return float(k * mpmath.sqrt(1 - x**2 / 6) * (x / (x + 2 * mpmath.sqrt((6 - x**2) / 5))) ** 0.25)


def test_thornton_printed_constant_is_the_exact_one_rounded():
    assert round(models.THORNTON_COEFFICIENT, 3) == 1.442


@pytest.mark.parametrize("v1_star,nu", [(0.5, 0.3), (3.0, 0.33), (47.0, 0.2), (1e4, 0.45)])
def test_thornton_reference_values(v1_star, nu):
    assert models.thornton(v1_star, nu) == pytest.approx(thornton_ref(v1_star, nu), rel=1e-13)


@pytest.mark.parametrize("nu", [0.0, 0.2, 0.33, 0.45])
def test_thornton_unity_at_its_yield_and_continuous(nu):
    onset = C_of(nu) ** -2.5  # V1/V_c at V1 = V_y,Th
    assert models.thornton(onset, nu) == 1.0
    assert models.thornton(onset * (1 - 1e-9), nu) == 1.0
    assert abs(models.thornton(onset * (1 + 1e-9), nu) - 1.0) < 1e-12
    # eq (2) leaves e = 1 with zero slope (d ln e/dx = -1/5 + 1/5 at x = 1): 1 - e = O(d^2)
    d = 1e-4
    assert 0.0 < 1.0 - models.thornton(onset * (1 + d), nu) < 10 * d**2
    assert models.thornton(onset * 1.01, nu) < 1.0
    assert models.thornton(0.0, nu) == 1.0


def test_thornton_high_speed_slope():
    assert log_slope(lambda v: models.thornton(v, 0.3), 1e6) == pytest.approx(-0.25, abs=1e-6)


# ------------------------------------------------------------------------------ Weir-Tallon, eq (3)
def test_weir_tallon_table1_value():
    E_eff = 200e9 / (1 - 0.33**2)
    ref = 3.1 * (1.12e9 / E_eff) ** (5 / 8) * (math.sqrt(E_eff / 7800.0) / 1.0) ** 0.25
    assert models.weir_tallon(1.0, 1.12e9, E_eff, 7800.0) == pytest.approx(ref, rel=1e-14)
    assert models.johnson(1.0, 1.12e9, E_eff, 7800.0) == pytest.approx(ref, rel=1e-14)
    # R1/R enters as (R1/R)^(3/8)
    assert models.weir_tallon(1.0, 1.12e9, E_eff, 7800.0, R1=0.02, R=0.01) == pytest.approx(ref * 2**0.375, rel=1e-14)
    assert models.weir_tallon(1.0, 1.12e9, E_eff, 7800.0, R=0.01) == pytest.approx(ref, rel=1e-14)
    with pytest.raises(ValueError, match="R"):
        models.weir_tallon(1.0, 1.12e9, E_eff, 7800.0, R1=0.01)


def test_weir_tallon_high_speed_slope_and_unit_velocity():
    E_eff, Sy, rho = 200e9 / (1 - 0.33**2), 1.12e9, 7800.0
    V_c = 0.05157  # ~ JGM V_c of Table 1 (m/s); only sets the scale
    assert log_slope(lambda v: models.weir_tallon(v * V_c, Sy, E_eff, rho), 1e6) == pytest.approx(-0.25, abs=1e-9)
    V_unit = 3.1**4 * (Sy / E_eff) ** 2.5 * math.sqrt(E_eff / rho)
    assert models.weir_tallon_unit_velocity(Sy, E_eff, rho) == pytest.approx(V_unit, rel=1e-14)
    assert models.weir_tallon(V_unit, Sy, E_eff, rho) == pytest.approx(1.0, rel=1e-14)
    # documented: formula returned below the unit speed (> 1), cap only on request
    assert models.weir_tallon(0.5 * V_unit, Sy, E_eff, rho) > 1.0
    assert models.weir_tallon(0.5 * V_unit, Sy, E_eff, rho, cap=True) == 1.0
    # infinite at V1 = 0, refused (capped: the limit 1)
    with pytest.raises(ValueError, match="V1 must be > 0"):
        models.weir_tallon(0.0, Sy, E_eff, rho)
    assert models.weir_tallon(0.0, Sy, E_eff, rho, cap=True) == 1.0


def test_weir_tallon_normalised_equals_dimensional(table1):
    # Independent: the dimensional formula by hand, at V1 = v* V_c with the sphere's own density.
    E_eff, Sy = table1.E_eff, table1.Sy
    for v in [0.3, 1.0, 17.0, 500.0]:
        V1 = v * table1.V_c
        ref = 3.1 * (Sy / E_eff) ** 0.625 * (math.sqrt(E_eff / 7800.0) / V1) ** 0.25
        assert models.weir_tallon_normalised(v, table1.eps_y, table1.nu) == pytest.approx(ref, rel=1e-12)
        assert models.evaluate("weir_tallon", table1, V1) == pytest.approx(ref, rel=1e-12)
    # eps_y cancels; the coefficient at V1* = 1 depends on nu only
    a = models.weir_tallon_normalised(2.0, 0.001, 0.3)
    b = models.weir_tallon_normalised(2.0, 0.01, 0.3)
    assert a == pytest.approx(b, rel=1e-14)
    # explicit rho overrides the mass-equivalent density
    E_al = models.evaluate("weir_tallon", table1, 1.0, rho=2700.0)
    assert E_al == pytest.approx(3.1 * (Sy / E_eff) ** 0.625 * math.sqrt(E_eff / 2700.0) ** 0.25, rel=1e-13)


# ------------------------------------------------------------------------------ Chang-Ling, eq (1)
def chang_ling_reference(E_eff, R, m, Sy, nu, V1):
    """CEB loading integrated numerically, w_m by root finding, rebound energy U_c (a_m/a_c)^3."""
    KH = KH_of(nu) * Sy
    w_c = (math.pi * KH / (2 * E_eff)) ** 2 * R

    def P(z):
        return 4 / 3 * E_eff * math.sqrt(R) * z**1.5 if z <= w_c else KH * math.pi * R * (2 * z - w_c)

    def W(w):
        if w <= w_c:
            return quad(P, 0, w, epsabs=0, epsrel=1e-13)[0]
        return quad(P, 0, w_c, epsabs=0, epsrel=1e-13)[0] + quad(P, w_c, w, epsabs=0, epsrel=1e-13)[0]

    KE = 0.5 * m * V1**2
    U_c = W(w_c)
    if KE <= U_c:
        return 1.0, None
    w_m = brentq(lambda w: W(w) - KE, w_c, 1e3 * w_c + 10 * math.sqrt(KE / (KH * R)), xtol=1e-30, rtol=1e-15)
    a_m, a_c = math.sqrt(R * (2 * w_m - w_c)), math.sqrt(R * w_c)
    e_geom = math.sqrt(U_c * (a_m / a_c) ** 3 / KE)
    # eq (1) as read: literally, with the misplaced bracket corrected and omega_c^{5.2} -> ^{5/2}
    num = 8 / 15 * E_eff * math.sqrt(R) * w_c * (w_m * (2 - w_c / w_m)) ** 1.5
    den = 8 / 15 * E_eff * math.sqrt(R) * w_c**2.5 + math.pi * KH * R * w_m * (w_m - w_c)
    e_eq1 = math.sqrt(num / den)
    assert e_eq1 == pytest.approx(e_geom, rel=1e-12)
    return e_eq1, w_m


@pytest.mark.parametrize("v1_star", [0.5, 1.0005, 1.3, 10.0, 250.0, 3000.0])
def test_chang_ling_against_numerical_ceb_energy_balance(table1, v1_star):
    V1 = v1_star * table1.V_c
    ref, _ = chang_ling_reference(table1.E_eff, table1.R_eff, table1.mass, table1.Sy, table1.nu, V1)
    assert models.chang_ling_dimensional(table1, V1) == pytest.approx(ref, rel=1e-10)
    assert models.chang_ling(v1_star, table1.eps_y, table1.nu) == pytest.approx(ref, rel=1e-10)


def test_chang_ling_dimensional_matches_normalised(table1):
    V1 = np.geomspace(1e-3, 1e3, 301) * table1.V_c
    dim = models.chang_ling_dimensional(table1, V1)
    norm = models.chang_ling(V1 / table1.V_c, table1.eps_y, table1.nu)
    np.testing.assert_allclose(dim, norm, rtol=1e-12, atol=0)
    np.testing.assert_allclose(models.evaluate("chang_ling", table1, V1), norm, rtol=1e-12, atol=0)
    dim_j = models.chang_ling_dimensional(table1, V1, critical="jgm")
    norm_j = models.chang_ling(V1 / table1.V_c, table1.eps_y, table1.nu, critical="jgm")
    np.testing.assert_allclose(dim_j, norm_j, rtol=1e-12, atol=0)


@pytest.mark.parametrize("nu", [0.0, 0.2, 0.33, 0.45])
@pytest.mark.parametrize("critical", ["ceb", "jgm"])
def test_chang_ling_unity_and_continuous_at_onset(nu, critical):
    onset = (KH_of(nu) / C_of(nu)) ** 2.5 if critical == "ceb" else 1.0
    f = lambda v: models.chang_ling(v, 0.005, nu, critical=critical)  # noqa: E731
    assert f(onset * (1 - 1e-12)) == 1.0
    assert f(0.0) == 1.0
    for d in (1e-6, 1e-9):
        assert 0.0 < 1.0 - f(onset * (1 + d)) < 10 * d
    assert f(onset * 1.5) < 1.0


def test_chang_ling_high_speed_slope_and_eps_independence():
    assert log_slope(lambda v: models.chang_ling(v, 0.005, 0.3), 1e6) == pytest.approx(-0.25, abs=1e-6)
    v = np.geomspace(1, 1000, 50)
    np.testing.assert_array_equal(models.chang_ling(v, 0.0005, 0.3), models.chang_ling(v, 0.01, 0.3))
    with pytest.raises(ValueError, match="critical"):
        models.chang_ling(2.0, 0.005, 0.3, critical="hertz")


# ------------------------------------------------------------------------------ Wu et al., eqs (39)-(41)
def test_wu_exceeds_one_near_vc_documented():
    assert models.wu(1.0 + 1e-9, 0.005) == pytest.approx(2.08, rel=1e-8)
    assert models.wu(1.0 + 1e-9, 0.005) > 1.0
    assert models.wu(10.0, 0.005) > 1.0  # still > 1 below 2.08^4 = 18.7
    assert models.wu(20.0, 0.005) < 1.0
    assert models.wu(1.0, 0.005) == 1.0 and models.wu(0.0, 0.005) == 1.0  # elastic below V_c


@pytest.mark.parametrize("eps", [0.0005, 0.005, 0.01])
def test_wu_branches_and_vfp(eps):
    V_fp = 0.008 / eps**2
    assert models.wu_finite_plastic_velocity(eps) == pytest.approx(V_fp, rel=1e-14)
    for v in (0.5 * V_fp, 0.999 * V_fp):
        assert models.wu(v, eps) == pytest.approx(2.08 * v**-0.25, rel=1e-14)
    for v in (1.001 * V_fp, 3 * V_fp):
        assert models.wu(v, eps) == pytest.approx(0.62 * (v * eps) ** -0.5, rel=1e-14)
    below, above = models.wu(V_fp, eps), models.wu(V_fp * (1 + 1e-12), eps)
    gap = abs(below - above) / above
    expected_gap = 2.08 * 0.008**-0.25 / (0.62 / math.sqrt(0.008)) - 1  # 0.33 %
    assert gap == pytest.approx(expected_gap, rel=1e-6) and gap < 0.005


def test_wu_own_scale():
    nu, eps = 0.4, 0.005
    r = (C_of(nu) / 1.6) ** 2.5  # Table 2: V_c / V_y,Wu
    for v in (0.9 / r, 5.0, 400.0):
        assert models.wu(v, eps, nu, scale="wu") == pytest.approx(models.wu(v * r, eps), rel=1e-14)
    assert models.wu_finite_plastic_velocity(eps, nu, scale="wu") == pytest.approx(0.008 / eps**2 / r, rel=1e-14)
    with pytest.raises(ValueError, match="nu"):
        models.wu(5.0, eps, scale="wu")
    with pytest.raises(ValueError, match="scale"):
        models.wu(5.0, eps, nu, scale="thornton")


# ------------------------------------------------------------------------------ JGM fits, eqs (42)-(45)
def fit43(v):
    return 1 - 0.1 * math.log(v) * ((v - 1) / 59) ** 0.156


def fit44(v, eps):
    return 1 - 0.1 * math.log(60) - 0.11 * math.log(v / 60) * (v - 60) ** (2.36 * eps)


def fit45(v, eps):
    return 1 - 0.0361 * eps**-0.114 * math.log(v) * (v - 1) ** (9.5 * eps)


@pytest.mark.parametrize("eps", [0.0005, 0.002, 0.005, 0.01])
def test_fits_pieces_and_continuity(eps):
    assert models.jgm_fit_jcg(0.0, eps) == models.jgm_fit_jcg(1.0, eps) == 1.0
    assert models.jgm_fit_etsion(0.3, eps) == models.jgm_fit_etsion(1.0, eps) == 1.0
    for v in (1.5, 10.0, 59.9):
        assert models.jgm_fit_jcg(v, eps) == pytest.approx(fit43(v), rel=1e-14)
    for v in (60.1, 300.0, 1000.0):
        assert models.jgm_fit_jcg(v, eps) == pytest.approx(fit44(v, eps), rel=1e-14)
    for v in (1.5, 10.0, 300.0, 1000.0):
        assert models.jgm_fit_etsion(v, eps) == pytest.approx(fit45(v, eps), rel=1e-14)
    # "continuous": at V1* = 60 both pieces equal 1 - 0.1 ln 60 (the measured gap is zero)
    gap = abs(fit43(60.0) - fit44(60.0, eps))  # the paper's claim, measured on the printed pieces
    assert gap <= 1e-15
    e60 = 1 - 0.1 * math.log(60)
    assert models.jgm_fit_jcg(60.0, eps) == pytest.approx(e60, abs=1e-15)
    assert abs(models.jgm_fit_jcg(60.0 * (1 - 1e-9), eps) - e60) < 1e-8
    assert abs(models.jgm_fit_jcg(60.0 * (1 + 1e-9), eps) - e60) < 1e-8
    # continuous at V1* = 1
    assert 1 - models.jgm_fit_jcg(1 + 1e-9, eps) < 1e-9
    assert 1 - models.jgm_fit_etsion(1 + 1e-9, eps) < 1e-9


@pytest.mark.parametrize("v,eps,nu,e_jcg,e_etsion", [
    (10, 0.005, 0.33, 0.828732572622, 0.865201796636),
    (300, 0.001, 0.25, 0.405336002185, 0.535560693544),
    (2.2, 0.005, 0.33, 0.967494217053, 1.0),
    (2.25, 0.005, 0.33, 0.965283934588, 0.997554804946),
])
def test_fits_within_paper_error_of_model_check_values(v, eps, nu, e_jcg, e_etsion):
    """MODEL.md section 6 check values of the JGM model; the paper's fits are within 4.5 % / 8.4 %."""
    assert abs(models.jgm_fit_jcg(v, eps) / e_jcg - 1) < 0.045
    assert abs(models.jgm_fit_etsion(v, eps) / e_etsion - 1) < 0.084


def test_fit_warnings():
    with pytest.warns(ValidityWarning, match="eps_y"):
        models.jgm_fit_jcg(10.0, 0.05)
    with pytest.warns(ValidityWarning, match="1000"):
        models.jgm_fit_jcg(2000.0, 0.005)
    with pytest.warns(ValidityWarning, match="eps_y"):
        models.jgm_fit_etsion(10.0, 0.0001)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        models.jgm_fit_jcg(np.array([0.5, 10.0, 1000.0]), 0.005)
        models.jgm_fit_etsion(5000.0, 0.005)


#: The fits' jit kernels (libm's log and pow) against their NumPy paths (NumPy's log and power, its
#: own SIMD kernels on some CPUs, up to ~4 ulp each): e = 1 - t, t ~0.6 a product of two or three
#: such calls, so a few ulp of 1 (9 ulp; a wrong formula is off by far more).
FIT_PATHS_ATOL = 2e-15


def test_fit_kernel_matches_numpy_path():
    rng = np.random.default_rng(1)
    v = np.concatenate([10 ** rng.uniform(-1, 3, 20000), [0.0, 1.0, 1.0 + 1e-12, 60.0, 60.0 * (1 + 1e-15), 1000.0]])
    eps = rng.uniform(0.0005, 0.01, v.size)
    out = np.empty_like(v)
    assert models.jgm_fit_jcg_array(v, eps, out) is out
    np.testing.assert_allclose(out, models.jgm_fit_jcg(v, eps), rtol=0, atol=FIT_PATHS_ATOL)
    out1 = np.empty_like(v)
    models.jgm_fit_jcg_array(v, np.array([0.005]), out1)
    np.testing.assert_allclose(out1, models.jgm_fit_jcg(v, 0.005), rtol=0, atol=FIT_PATHS_ATOL)
    for vi in (0.5, 10.0, 60.0, 999.0):
        assert models.jgm_fit_jcg_kernel(vi, 0.005) == pytest.approx(models.jgm_fit_jcg(vi, 0.005), abs=FIT_PATHS_ATOL)
    bad = np.empty(5)
    models.jgm_fit_jcg_array(np.array([-1.0, np.nan, np.inf, 5.0, 5.0]), np.array([0.005, 0.005, 0.005, 0.0, np.nan]), bad)
    assert np.isnan(bad).all()
    with pytest.raises(ValueError):
        models.jgm_fit_jcg_array(v, eps[:3], out)
    with pytest.raises(ValueError):
        models.jgm_fit_jcg_array(v, eps, out[:3])


def test_fit_kernel_names():
    """Kernel = one point, array = loop into out; the scalar's old name is the same object."""
    assert models.jgm_fit_jcg_scalar is models.jgm_fit_jcg_kernel
    for name in ("jgm_fit_jcg_kernel", "jgm_fit_jcg_array", "jgm_fit_etsion_kernel", "jgm_fit_jcg_scalar"):
        assert name in models.__all__


def test_etsion_fit_kernel_matches_numpy_path():
    rng = np.random.default_rng(2)
    v = np.concatenate([10 ** rng.uniform(-1, 3, 5000), [0.0, 1.0, 1.0 + 1e-12, 425.0]])
    eps = rng.uniform(0.0005, 0.01, v.size)
    got = np.array([models.jgm_fit_etsion_kernel(a, b) for a, b in zip(v, eps)])
    np.testing.assert_allclose(got, models.jgm_fit_etsion(v, eps), rtol=0, atol=FIT_PATHS_ATOL)
    for a, b in ((-1.0, 0.005), (np.nan, 0.005), (np.inf, 0.005), (5.0, 0.0), (5.0, np.nan)):
        assert math.isnan(models.jgm_fit_etsion_kernel(a, b))


@settings(max_examples=200, deadline=None)
@given(st.floats(0.0, 1000.0), st.floats(0.0005, 0.01))
def test_fit_kernel_matches_numpy_path_property(v, eps):
    assert abs(models.jgm_fit_jcg_kernel(v, eps) - models.jgm_fit_jcg(v, eps)) <= FIT_PATHS_ATOL


def test_wu_branches_are_eqs_40_41_and_make_wu():
    """JGM eq (40) 2.08 V^-1/4 and eq (41) 0.62 (V eps_y)^-1/2, written out here from the paper."""
    v = np.geomspace(1.01, 2000.0, 300)
    e40, e41 = models.wu_branches(v, 0.005)
    # NumPy's power (its own SIMD kernel on some CPUs, up to ~4 ulp) against Python's (libm)
    np.testing.assert_allclose(e40, [2.08 * x**-0.25 for x in v], rtol=2e-15)
    np.testing.assert_allclose(e41, [0.62 / math.sqrt(x * 0.005) for x in v], rtol=2e-15)
    np.testing.assert_array_equal(models.wu(v, 0.005), np.where(v <= 320.0, e40, e41))
    w40, _ = models.wu_branches(2.0, 0.005, 0.3, scale="wu")
    ratio = float(models.yield_velocity_ratio(0.3, "wu"))
    assert w40 == pytest.approx(2.08 * (2.0 * ratio) ** -0.25, rel=2e-15)
    with pytest.raises(ValueError, match="v1_star"):
        models.wu_branches(0.0, 0.005)
    with pytest.raises(ValueError, match="scale"):
        models.wu_branches(2.0, 0.005, scale="x")


# ------------------------------------------------------------------------------ registry and evaluate
def test_registry_convention(table1):
    assert set(models.MODELS) == {"thornton", "weir_tallon", "chang_ling", "wu", "jgm_fit_jcg", "jgm_fit_etsion"}
    v = np.array([0.5, 2.0, 30.0, 300.0])
    for name, f in models.MODELS.items():
        s = f(30.0, 0.005, 0.3)
        assert isinstance(s, float) and math.isfinite(s) and s > 0, name
        a = f(v, 0.005, 0.3)
        assert isinstance(a, np.ndarray) and a.shape == (4,), name
        assert f(v[:, None], np.array([0.002, 0.005]), 0.3).shape == (4, 2), name
        assert f(30.0, 0.005, np.array([0.2, 0.3, 0.4])).shape == (3,), name  # nu broadcast even if unused
        np.testing.assert_array_equal(a[2], s)
        V1 = np.array([0.5, 2.0, 30.0]) * table1.V_c
        np.testing.assert_allclose(models.evaluate(name, table1, V1),
                                   f(V1 / table1.V_c, table1.eps_y, table1.nu), rtol=1e-12)
    assert models.MODELS["thornton"](7.0, 0.005, 0.3) == models.thornton(7.0, 0.3)
    assert models.MODELS["wu"](7.0, 0.005, 0.3) == models.wu(7.0, 0.005)
    with pytest.raises(ValueError, match="model_name"):
        models.evaluate("hertz", table1, 1.0)
    with pytest.raises(ValueError, match="rho"):
        models.evaluate("thornton", table1, 1.0, rho=7800.0)


# ------------------------------------------------------------------------------ input validation
NORMALISED = [
    ("thornton", lambda v=2.0, eps=0.005, nu=0.3: models.thornton(v, nu)),
    ("chang_ling", lambda v=2.0, eps=0.005, nu=0.3: models.chang_ling(v, eps, nu)),
    ("wu", lambda v=2.0, eps=0.005, nu=0.3: models.wu(v, eps, nu)),
    ("wu_scale", lambda v=2.0, eps=0.005, nu=0.3: models.wu(v, eps, nu, scale="wu")),
    ("fit_jcg", lambda v=2.0, eps=0.005, nu=0.3: models.jgm_fit_jcg(v, eps)),
    ("fit_etsion", lambda v=2.0, eps=0.005, nu=0.3: models.jgm_fit_etsion(v, eps)),
    ("wt_norm", lambda v=2.0, eps=0.005, nu=0.3: models.weir_tallon_normalised(v, eps, nu)),
] + [(f"MODELS[{k}]", (lambda f: lambda v=2.0, eps=0.005, nu=0.3: f(v, eps, nu))(f)) for k, f in models.MODELS.items()]


@pytest.mark.parametrize("name,f", NORMALISED, ids=[n for n, _ in NORMALISED])
def test_bad_normalised_inputs(name, f):
    for bad in (-1.0, math.nan, math.inf, [1.0, -0.1]):
        with pytest.raises(ValueError, match="v1_star"):
            f(v=bad)
    if "fit" not in name:
        for bad in (0.5, -0.1, math.nan):
            with pytest.raises(ValueError, match="nu"):
                f(nu=bad)
    if name != "thornton":
        for bad in (0.0, -0.001, math.nan):
            with pytest.raises(ValueError, match="eps_y"):
                f(eps=bad)


def test_bad_dimensional_inputs(table1):
    good = dict(V1=1.0, Sy=1.12e9, E_eff=224e9, rho=7800.0)
    for key in good:
        for bad in (-1.0, math.nan):
            kw = dict(good, **{key: bad})
            with pytest.raises(ValueError, match=key):
                models.weir_tallon(**kw)
    with pytest.raises(ValueError, match="Sy"):
        models.weir_tallon(1.0, 0.0, 224e9, 7800.0)
    with pytest.raises(ValueError, match="R1"):
        models.weir_tallon(1.0, 1.12e9, 224e9, 7800.0, R1=-1.0, R=0.01)
    with pytest.raises(ValueError, match="V1"):
        models.chang_ling_dimensional(table1, -0.1)
    with pytest.raises(ValueError, match="V1"):
        models.evaluate("thornton", table1, math.nan)
    with pytest.raises(ValueError, match="nu"):
        models.ceb_hardness_factor(0.5)


def test_scalar_in_float_out_and_broadcasting():
    assert type(models.thornton(np.float64(5.0), 0.3)) is float
    assert type(models.weir_tallon(1, 1e9, 2e11, 7800)) is float
    assert type(models.wu_finite_plastic_velocity(0.005)) is float
    assert models.thornton([[1.0], [5.0]], [0.2, 0.3, 0.4]).shape == (2, 3)
    assert models.chang_ling(np.ones((2, 1)) * 3, [0.001, 0.005], 0.3).shape == (2, 2)
    assert models.wu([5.0, 500.0], [[0.001], [0.005], [0.01]]).shape == (3, 2)
