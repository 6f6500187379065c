"""Tests of the direct solver (fastrest.direct) and the normalised JG law it rests on.

The independent slow path is tests/reference.py (mpmath, 40 digits). The empirical fits of
JGM (2010) eqs (42)-(45) are typed in below so that this file does not depend on fastrest.models.
"""
import math
import re
import warnings

import numpy as np
import pytest
from hypothesis import assume, given
from hypothesis import strategies as st

import fastrest
from fastrest import ExtrapolationWarning, Impact, Material, ValidityWarning, contact, direct, energy

import reference as ref

V_SWITCH = 1.9 ** 1.25          # V1* at which w_m* = 1.9 (Hertz -> JG switch)
EPS_RANGE = (0.0005, 0.01)      # validated by JGM
NU_RANGE = (0.2, 0.45)
UNLOADINGS = ("jcg", "etsion")


def rel_err(a, b):
    """|a - b| / |b|, and |a| when b == 0 (then a must be 0 too)."""
    a, b = float(a), float(b)
    if b == 0.0:
        return abs(a)
    return abs(a - b) / abs(b)


# ============================================================================================
# MODEL.md section 6 check values
MODEL_MD_ROWS = [
    # V1*, eps_y, nu, w_m, e (JCG), e (Etsion)
    (10.0, 0.005, 0.33, 6.549856322605, 0.828732572622, 0.865201796636),
    (300.0, 0.001, 0.25, 126.263984325110, 0.405336002185, 0.535560693544),
    (2.2, 0.005, 0.33, 1.879049170052, 0.967494217053, 1.0),
    (2.25, 0.005, 0.33, 1.913161497590, 0.965283934588, 0.997554804946),
]


@pytest.mark.parametrize("v, eps, nu, wm, e_jcg, e_ets", MODEL_MD_ROWS)
def test_model_md_check_values(v, eps, nu, wm, e_jcg, e_ets):
    assert direct.omega_m_exact(v, eps, nu) == pytest.approx(wm, rel=1e-10, abs=0)
    assert direct.e_exact(v, eps, nu, "jcg") == pytest.approx(e_jcg, abs=1e-10)
    assert direct.e_exact(v, eps, nu) == direct.e_exact(v, eps, nu, "jcg")
    assert direct.e_exact(v, eps, nu, "etsion") == pytest.approx(e_ets, abs=1e-10)
    if e_ets == 1.0:
        assert direct.e_exact(v, eps, nu, "etsion") == 1.0
    s = direct.solve(v, eps, nu, "jcg")
    assert s["omega_m_star"] == direct.omega_m_exact(v, eps, nu)
    assert s["e"] == direct.e_exact(v, eps, nu)
    assert s["loss"] == direct.loss_exact(v, eps, nu)
    assert (s["omega_res_star"], s["R_res_ratio"]) == direct.residual_exact(v, eps, nu)


# ============================================================================================
# Against the mpmath reference at 40 points spread over the validated range
SEED = 20100217
N_MATERIALS, N_SPEEDS = 10, 4


def _sample():
    """10 materials stratified over ln eps_y in [0.0005, 0.01] x nu in [0.2, 0.45], and for each
    4 speeds stratified in ln V1* over (1, V1*(w_m = 425)]: 40 points, fixed seed."""
    rng = np.random.default_rng(SEED)
    n = N_MATERIALS
    ue = (rng.permutation(n) + rng.uniform(size=n)) / n
    un = (rng.permutation(n) + rng.uniform(size=n)) / n
    lo, hi = math.log(EPS_RANGE[0]), math.log(EPS_RANGE[1])
    pts = []
    for k in range(n):
        eps = float(math.exp(lo + ue[k] * (hi - lo)))
        nu = float(NU_RANGE[0] + un[k] * (NU_RANGE[1] - NU_RANGE[0]))
        vmax = ref.ref_v1_star_at(425.0, eps, nu)
        for j in range(N_SPEEDS):
            u = (j + rng.uniform(0.02, 1.0)) / N_SPEEDS
            pts.append((float(vmax ** u), eps, nu))
    return pts


@pytest.fixture(scope="module")
def ref_sample():
    pts = _sample()
    rows = []
    for v, eps, nu in pts:
        row = {"v": v, "eps": eps, "nu": nu, "omega_m_star": ref.ref_omega_m_star(v, eps, nu)}
        for u in UNLOADINGS:
            row[("e", u)] = ref.ref_e_star(v, eps, nu, u)
            row[("loss", u)] = ref.ref_loss_star(v, eps, nu, u)
            row[("residual", u)] = ref.ref_residual_star(v, eps, nu, u)
        rows.append(row)
    v = np.array([r["v"] for r in rows])
    eps = np.array([r["eps"] for r in rows])
    nu = np.array([r["nu"] for r in rows])
    return rows, v, eps, nu


def _worst(got, rows, key, label):
    errs = [rel_err(g, r[key]) for g, r in zip(got, rows)]
    i = int(np.argmax(errs))
    r = rows[i]
    print(f"\n[reference] {label}: worst rel. error {errs[i]:.3e} at V1*={r['v']!r}, "
          f"eps_y={r['eps']!r}, nu={r['nu']!r}")
    return errs[i], r


def test_sample_spread(ref_sample):
    rows, v, eps, nu = ref_sample
    assert len(rows) == 40
    assert v.min() > 1.0
    assert eps.min() < 0.001 and eps.max() > 0.007
    assert nu.min() < 0.23 and nu.max() > 0.42
    assert np.sum(v < V_SWITCH) >= 1 and np.sum(v > 300) >= 5   # both branches, up to w_m ~ 425


def test_reference_omega_m(ref_sample):
    rows, v, eps, nu = ref_sample
    got = direct.omega_m_exact(v, eps, nu)
    worst, r = _worst(got, rows, "omega_m_star", "omega_m_star")
    assert worst <= 1e-12, r


@pytest.mark.parametrize("unloading", UNLOADINGS)
def test_reference_e_and_loss(ref_sample, unloading):
    rows, v, eps, nu = ref_sample
    e = direct.e_exact(v, eps, nu, unloading)
    loss = direct.loss_exact(v, eps, nu, unloading)
    worst_e, r = _worst(e, rows, ("e", unloading), f"e_star {unloading}")
    assert worst_e <= 1e-12, r
    worst_l, r = _worst(loss, rows, ("loss", unloading), f"loss_star {unloading}")
    assert worst_l <= 1e-12, r


@pytest.mark.parametrize("unloading", UNLOADINGS)
def test_reference_residual(ref_sample, unloading):
    rows, v, eps, nu = ref_sample
    w_res, r_ratio = direct.residual_exact(v, eps, nu, unloading)
    worst_w, r = _worst(w_res, [dict(x, k=x[("residual", unloading)][0]) for x in rows], "k",
                        f"w_res* {unloading}")
    assert worst_w <= 1e-12, r
    worst_r, r = _worst(r_ratio, [dict(x, k=x[("residual", unloading)][1]) for x in rows], "k",
                        f"R_res/R {unloading}")
    assert worst_r <= 1e-12, r


def test_reference_corner_of_validated_range():
    """eps_y = 0.01, nu = 0.45 is where a/R is largest at w_m = 425 (the law ends at w = 471.6)."""
    eps, nu = 0.01, 0.45
    v = ref.ref_v1_star_at(400.0, eps, nu)
    assert direct.omega_m_exact(v, eps, nu) == pytest.approx(400.0, rel=1e-12)
    for u in UNLOADINGS:
        assert rel_err(direct.e_exact(v, eps, nu, u), ref.ref_e_star(v, eps, nu, u)) <= 1e-12


def test_package_corner_of_validated_range_self_consistent():
    """Same corner without the reference: F(w_m(V)) = V^2 and the 425 limit is reachable."""
    eps, nu = 0.01, 0.45
    vlim = fastrest.limit(eps, nu).v1_star
    v = np.array([10.0, 300.0, vlim * (1 - 1e-9)])
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        wm = direct.omega_m_exact(v, eps, nu)
    np.testing.assert_allclose(energy.loading_energy(wm, eps, nu), v ** 2, rtol=1e-13)
    assert wm[-1] == pytest.approx(425.0, rel=1e-8)


# ============================================================================================
# Hard cases
HARD_MATERIALS = [(0.005, 0.33), (0.0005, 0.2), (0.01, 0.45)]


@pytest.mark.parametrize("eps, nu", HARD_MATERIALS)
def test_onset_exactly_one(eps, nu):
    for u in UNLOADINGS:
        assert direct.e_exact(1.0, eps, nu, u) == 1.0
        assert direct.loss_exact(1.0, eps, nu, u) == 0.0
        assert direct.residual_exact(1.0, eps, nu, u) == (0.0, 1.0)
    assert direct.omega_m_exact(1.0, eps, nu) == 1.0
    # below onset: elastic, w_m = V^0.8 exactly
    for v in (0.0, 1e-300, 0.3, 0.999999):
        assert direct.e_exact(v, eps, nu) == 1.0
        assert direct.loss_exact(v, eps, nu, "jcg") == 0.0
        assert direct.omega_m_exact(v, eps, nu) == v ** 0.8


@pytest.mark.parametrize("eps, nu", HARD_MATERIALS)
@pytest.mark.parametrize("dv", [1e-9, 1e-12, 2.0 ** -52])
def test_just_above_onset(eps, nu, dv):
    v = 1.0 + dv
    for u in UNLOADINGS:
        e = direct.e_exact(v, eps, nu, u)
        loss = direct.loss_exact(v, eps, nu, u)
        loss_ref = ref.ref_loss_star(v, eps, nu, u)
        assert rel_err(loss, loss_ref) <= 1e-12, (u, loss, loss_ref)
        assert rel_err(e, ref.ref_e_star(v, eps, nu, u)) <= 1e-15
        assert 1.0 - 1e-9 < e <= 1.0                       # e = 1 to the size of the loss
        if u == "etsion":
            assert e == 1.0 and loss == 0.0               # Hertz loading: exactly elastic
        else:
            assert 0.0 < loss < 1e-10
    assert rel_err(direct.omega_m_exact(v, eps, nu), ref.ref_omega_m_star(v, eps, nu)) <= 1e-15


@pytest.mark.parametrize("eps, nu", HARD_MATERIALS)
@pytest.mark.parametrize("side", [-1.0, 1.0])
@pytest.mark.parametrize("delta", [1e-12, 1e-6])
def test_switch_at_w_1p9_matches_reference(eps, nu, side, delta):
    v = V_SWITCH * (1.0 + side * delta)
    wm = direct.omega_m_exact(v, eps, nu)
    assert rel_err(wm, ref.ref_omega_m_star(v, eps, nu)) <= 1e-12
    assert (wm < 1.9) if side < 0 else (wm > 1.9)
    for u in UNLOADINGS:
        assert rel_err(direct.e_exact(v, eps, nu, u), ref.ref_e_star(v, eps, nu, u)) <= 1e-12
        assert rel_err(direct.loss_exact(v, eps, nu, u), ref.ref_loss_star(v, eps, nu, u)) <= 1e-12
        w_res, rr = direct.residual_exact(v, eps, nu, u)
        w_res_ref, rr_ref = ref.ref_residual_star(v, eps, nu, u)
        assert abs(w_res - w_res_ref) <= 1e-12 * wm
        assert rel_err(rr, rr_ref) <= 1e-12


@pytest.mark.parametrize("eps", [0.0005, 0.005, 0.01])
def test_etsion_jump_not_smeared(eps):
    """Etsion e is exactly 1 up to w_m = 1.9 and drops below 0.999 right after (nu = 0.33)."""
    nu = 0.33
    below = V_SWITCH * (1 - np.array([1e-6, 1e-9, 1e-12, 1e-14]))
    above = V_SWITCH * (1 + np.array([1e-14, 1e-12, 1e-9, 1e-6]))
    assert np.all(direct.e_exact(below, eps, nu, "etsion") == 1.0)
    e_above = direct.e_exact(above, eps, nu, "etsion")
    assert np.all(e_above < 0.999)
    assert np.ptp(e_above) < 1e-6                      # a clean step, no ramp
    # JCG e has a (small) jump there too
    e_jcg = direct.e_exact(np.r_[below[-1], above[0]], eps, nu, "jcg")
    assert e_jcg[1] < e_jcg[0] - 1e-4


def test_switch_exact_float_matches_reference():
    """V1* = float(1.9**1.25) and its neighbours. The reference puts a float on the Hertz side iff
    V1*^2 <= 1.9^2.5 exactly; float(1.9**1.25) is such a float (w_m = V^0.8 <= 1.9 exactly)."""
    eps, nu = 0.005, 0.33
    vs = [V_SWITCH]
    for _ in range(3):
        vs = [float(np.nextafter(vs[0], 0.0))] + vs + [float(np.nextafter(vs[-1], 3.0))]
    for v in vs:
        assert rel_err(direct.omega_m_exact(v, eps, nu), ref.ref_omega_m_star(v, eps, nu)) <= 1e-15
        for u in UNLOADINGS:
            e, e_ref = direct.e_exact(v, eps, nu, u), ref.ref_e_star(v, eps, nu, u)
            assert rel_err(e, e_ref) <= 1e-12, (v, u, e, e_ref)


@pytest.mark.parametrize("eps, nu", [(0.005, 0.33), (0.0005, 0.2), (0.001, 0.25), (0.0075, 0.4)])
def test_limit_w425(eps, nu):
    v425 = ref.ref_v1_star_at(425.0, eps, nu)
    with warnings.catch_warnings():
        warnings.simplefilter("error")           # in range: no warning at all
        wm = direct.omega_m_exact(v425, eps, nu)
        for u in UNLOADINGS:
            assert rel_err(direct.e_exact(v425, eps, nu, u), ref.ref_e_star(v425, eps, nu, u)) <= 1e-12
        # extrapolate=True below the limit: same number, no warning
        v_in = v425 * (1 - 1e-12)
        assert direct.omega_m_exact(v_in, eps, nu, extrapolate=True) == direct.omega_m_exact(v_in, eps, nu)
    assert wm == pytest.approx(425.0, rel=1e-12)
    assert fastrest.limit(eps, nu).v1_star == pytest.approx(v425, rel=1e-13)

    v_over = v425 * (1 + 1e-9)
    for fn in (direct.omega_m_exact, direct.e_exact, direct.loss_exact, direct.residual_exact):
        with pytest.raises(ValueError, match="425") as ei:
            fn(v_over, eps, nu)
        m = re.search(r"V1\* = ([0-9.eE+-]+)", str(ei.value))
        assert m, str(ei.value)
        assert float(m.group(1).rstrip(".")) == pytest.approx(v425, rel=1e-9)
        assert "extrapolate" in str(ei.value)

    for v in (v_over, v425 * 1.01):
        with pytest.warns(ExtrapolationWarning):
            e = direct.e_exact(v, eps, nu, "jcg", extrapolate=True)
        assert rel_err(e, ref.ref_e_star(v, eps, nu, "jcg")) <= 1e-12
        with pytest.warns(ExtrapolationWarning):
            wm = direct.omega_m_exact(v, eps, nu, extrapolate=True)
        assert wm > 425.0
        assert rel_err(wm, ref.ref_omega_m_star(v, eps, nu)) <= 1e-12
    assert issubclass(ExtrapolationWarning, ValidityWarning)


def test_large_eps_y_a_over_R_reaches_one():
    """eps_y = 0.02, nu = 0.45: a/R = 1 at w = 123.4 < 425. Below it the model computes (with a
    ValidityWarning, eps_y > 0.01); past it ValueError mentioning a/R, extrapolating or not."""
    eps, nu = 0.02, 0.45
    w_lim = contact.omega_star_limit(eps, nu)
    assert 100 < w_lim < 425
    with pytest.warns(ValidityWarning):
        e = direct.e_exact(100.0, eps, nu)
    assert rel_err(e, ref.ref_e_star(100.0, eps, nu)) <= 1e-12
    for v in (300.0, 1e4):
        for extrapolate in (False, True):
            with warnings.catch_warnings():
                warnings.simplefilter("ignore", ValidityWarning)
                with pytest.raises(ValueError, match="a/R"):
                    direct.e_exact(v, eps, nu, extrapolate=extrapolate)
                with pytest.raises(ValueError, match="a/R"):
                    direct.omega_m_exact(v, eps, nu, extrapolate=extrapolate)


@pytest.mark.parametrize("frac", [1e-9, 1e-6, 1e-4, 2e-3])
@pytest.mark.parametrize("eps, nu, extrapolate", [
    (0.02, 0.45, False),      # a/R = 1 before w = 425
    (0.02, 0.45, True),
    (0.0105, 0.45, True),     # a/R = 1 at w = 430, just past 425
    (0.005, 0.33, True),      # extrapolation far past 425, a/R = 1 at w = 1994
    (0.001, 0.3, True),       # a/R = 1 at w = 37657
])
def test_computes_just_below_a_over_R_limit(eps, nu, extrapolate, frac):
    """A speed slightly below the a/R = 1 limit has w_m below the limit, so it must compute."""
    w_lim = contact.omega_star_limit(eps, nu)
    v = fastrest.limit(eps, nu, extrapolate=True).v1_star * (1 - frac)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ValidityWarning)
        wm = direct.omega_m_exact(v, eps, nu, extrapolate=extrapolate)
        assert wm < w_lim
        assert energy.loading_energy(wm, eps, nu) == pytest.approx(v * v, rel=1e-13)


@pytest.mark.parametrize("nu", [0.0, 0.499])
@pytest.mark.parametrize("v", [1.5, 2.25, 10.0, 200.0])
def test_nu_outside_validated_range(nu, v):
    eps = 0.005
    with pytest.warns(ValidityWarning, match="nu"):
        wm = direct.omega_m_exact(v, eps, nu)
    assert rel_err(wm, ref.ref_omega_m_star(v, eps, nu)) <= 1e-12
    for u in UNLOADINGS:
        with pytest.warns(ValidityWarning):
            e = direct.e_exact(v, eps, nu, u)
        with pytest.warns(ValidityWarning):
            loss = direct.loss_exact(v, eps, nu, u)
        assert rel_err(e, ref.ref_e_star(v, eps, nu, u)) <= 1e-12
        assert rel_err(loss, ref.ref_loss_star(v, eps, nu, u)) <= 1e-12


@pytest.mark.parametrize("eps", [0.0001, 0.02])
def test_eps_y_outside_validated_range_warns(eps):
    with pytest.warns(ValidityWarning, match="eps_y"):
        direct.e_exact(5.0, eps, 0.3)


def test_no_warning_inside_validated_range():
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        direct.e_exact(np.geomspace(0.5, 500, 7), np.array(EPS_RANGE)[:, None], 0.2)
        direct.e_exact(5.0, 0.01, 0.45, "etsion")


# ============================================================================================
# The paper's empirical fits, eqs (42)-(45), typed in here
def fit_jcg(v, eps_y):
    """JGM eqs (42)-(44): fit to the model with JCG unloading (35)."""
    v = np.asarray(v, dtype=float)
    e = np.ones_like(v)
    a = (v > 1) & (v <= 60)
    e[a] = 1 - 0.1 * np.log(v[a]) * ((v[a] - 1) / 59) ** 0.156                          # (43)
    b = v > 60
    e[b] = 1 - 0.1 * np.log(60) - 0.11 * np.log(v[b] / 60) * (v[b] - 60) ** (2.36 * eps_y)  # (44)
    return e


def fit_etsion(v, eps_y):
    """JGM eq (45): fit to the model with Etsion et al. unloading (33)."""
    v = np.asarray(v, dtype=float)
    vm1 = np.maximum(v - 1, 0.0)
    return np.where(v > 1, 1 - 0.0361 * eps_y ** -0.114 * np.log(v) * vm1 ** (9.5 * eps_y), 1.0)


FIT_EPS = [0.0005, 0.001, 0.002, 0.003, 0.005, 0.0075, 0.01]
FIT_BOUNDS = {"jcg": (0.015, 0.045), "etsion": (0.053, 0.084)}   # paper: mean, max


@pytest.fixture(scope="module")
def fit_deviation():
    """Relative deviation |fit - model| / model on a 200-point log grid in (1, min(1000, V1*(425))]
    for each eps_y at nu = 0.33; returns {unloading: {eps_y: array}}."""
    out = {u: {} for u in UNLOADINGS}
    for eps in FIT_EPS:
        vmax = min(1000.0, fastrest.limit(eps, 0.33).v1_star)
        v = np.geomspace(1.0, vmax, 201)[1:]
        for u, fit in (("jcg", fit_jcg), ("etsion", fit_etsion)):
            e = direct.e_exact(v, eps, 0.33, u)
            out[u][eps] = np.abs(fit(v, eps) - e) / e
    print()
    for u in UNLOADINGS:
        allv = np.concatenate(list(out[u].values()))
        for eps, d in out[u].items():
            print(f"[fit {u:6s}] eps_y={eps:<7g} mean {100 * d.mean():.2f} %  max {100 * d.max():.2f} %")
        print(f"[fit {u:6s}] all         mean {100 * allv.mean():.2f} %  max {100 * allv.max():.2f} %"
              f"  (paper: {100 * FIT_BOUNDS[u][0]:.1f} % / {100 * FIT_BOUNDS[u][1]:.1f} %)")
    return out


def _pooled(dev, u):
    allv = np.concatenate(list(dev[u].values()))
    return allv.mean(), allv.max()


def test_fit_jcg_eqs_42_44(fit_deviation):
    mean, mx = _pooled(fit_deviation, "jcg")
    assert mean <= FIT_BOUNDS["jcg"][0]
    assert mx <= FIT_BOUNDS["jcg"][1]


def test_fit_etsion_eq_45_mean(fit_deviation):
    mean, _ = _pooled(fit_deviation, "etsion")
    assert mean <= FIT_BOUNDS["etsion"][0]


def test_fit_etsion_eq_45_max_at_printed_precision(fit_deviation):
    """The paper prints the maximum to one decimal (8.4 %); compare at that precision."""
    _, mx = _pooled(fit_deviation, "etsion")
    assert round(100 * mx, 1) <= 100 * FIT_BOUNDS["etsion"][1]


@pytest.mark.xfail(strict=True, reason="measured max deviation of eq (45) from the model is 8.43 % "
                                       "(eps_y = 0.0005, V1* ~ 25) > the paper's 8.4 %; equal at the "
                                       "paper's printed precision (kept as a record, not a bug)")
def test_fit_etsion_eq_45_max_strict(fit_deviation):
    _, mx = _pooled(fit_deviation, "etsion")
    assert mx <= FIT_BOUNDS["etsion"][1]


def test_fit_jcg_continuous_at_60():
    """Eqs (43) and (44) meet at V1* = 60 (sanity check of the typed-in fit)."""
    assert fit_jcg(60.0, 0.005)[()] == pytest.approx(1 - 0.1 * math.log(60), abs=1e-15)
    assert fit_jcg(np.nextafter(60.0, 61), 0.005)[()] == pytest.approx(1 - 0.1 * math.log(60), abs=1e-6)


# ============================================================================================
# Properties (hypothesis; bounded by tests/conftest.py)
eps_st = st.floats(*EPS_RANGE)
nu_st = st.floats(*NU_RANGE)
frac_st = st.floats(0.0, 1.0)


def _speed(eps, nu, u):
    """V1* in [0, V1*(425)) from u in [0, 1]: below 1 linearly for u < 0.2, then log-spaced."""
    vmax = fastrest.limit(eps, nu).v1_star * (1 - 1e-12)
    if u < 0.2:
        return u / 0.2
    return vmax ** ((u - 0.2) / 0.8)


@given(eps_st, nu_st, frac_st)
def test_prop_e_in_unit_interval_jcg(eps, nu, u):
    v = _speed(eps, nu, u)
    e = direct.e_exact(v, eps, nu, "jcg")
    assert 0.0 < e <= 1.0
    loss = direct.loss_exact(v, eps, nu, "jcg")
    assert 0.0 <= loss < 1.0
    assert loss == pytest.approx(1 - e * e, abs=4e-16)


@given(eps_st, st.floats(0.33, 0.45), frac_st)
def test_prop_e_in_unit_interval_etsion(eps, nu, u):
    """Etsion unloading keeps e <= 1 where P* jumps down at w = 1.9 (nu > ~0.323, see below)."""
    v = _speed(eps, nu, u)
    e = direct.e_exact(v, eps, nu, "etsion")
    assert 0.0 < e <= 1.0
    assert direct.loss_exact(v, eps, nu, "etsion") == pytest.approx(1 - e * e, abs=4e-16)


@pytest.mark.parametrize("nu", [0.0, 0.2, 0.25])
def test_model_property_e_above_one_for_small_nu(nu):
    """Not a bug of the package: for nu < ~0.32 the JG force (9) at w = 1.9 exceeds Hertz
    (C(nu) is small), so just past V1* = 1.9^1.25 Etsion unloading (33) gives e > 1 (2.6 % at
    nu = 0.2) and, at nu = 0, JCG too. fastrest reproduces the equations and does not clip."""
    eps, v = 0.005, 2.3
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ValidityWarning)
        assert contact.P_star(np.nextafter(1.9, 2), eps, nu) > 1.9 ** 1.5
        e = direct.e_exact(v, eps, nu, "etsion")
        assert e > 1.0
        assert rel_err(e, ref.ref_e_star(v, eps, nu, "etsion")) <= 1e-12
        assert direct.loss_exact(v, eps, nu, "etsion") < 0.0


def _pair_same_side(eps, nu, u1, u2, upper):
    vmax = fastrest.limit(eps, nu).v1_star * (1 - 1e-12)
    if upper:
        lo, hi = math.log(float(np.nextafter(V_SWITCH, 3))), math.log(vmax)
    else:
        lo, hi = math.log(1e-3), math.log(float(np.nextafter(V_SWITCH, 0)))
    a, b = sorted((math.exp(lo + u1 * (hi - lo)), math.exp(lo + u2 * (hi - lo))))
    return a, b


@given(eps_st, nu_st, frac_st, frac_st, st.booleans(), st.sampled_from(UNLOADINGS))
def test_prop_e_non_increasing(eps, nu, u1, u2, upper, unloading):
    a, b = _pair_same_side(eps, nu, u1, u2, upper)
    ea, eb = direct.e_exact(np.array([a, b]), eps, nu, unloading)
    assert eb <= ea * (1 + 4e-16), (a, b, ea, eb)


@given(eps_st, nu_st, frac_st, frac_st, st.booleans())
def test_prop_w_m_increasing(eps, nu, u1, u2, upper):
    a, b = _pair_same_side(eps, nu, u1, u2, upper)
    wa, wb = direct.omega_m_exact(np.array([a, b]), eps, nu)
    assert wb >= wa * (1 - 4e-16)
    if b > a * (1 + 1e-9):
        assert wb > wa


@st.composite
def impacts(draw, nu_min=NU_RANGE[0]):
    E = draw(st.floats(1e9, 500e9))
    nu = draw(st.floats(nu_min, NU_RANGE[1]))
    eps = draw(eps_st)
    R = draw(st.floats(1e-6, 0.1))
    rho = draw(st.floats(500.0, 20000.0))
    E_eff = E / (1 - nu * nu)
    return Impact(Material(E=E, nu=nu, Sy=eps * E_eff, rho=rho), R=R)


@pytest.mark.filterwarnings("ignore::fastrest.ValidityWarning")  # eps_y = Sy/E' may round past 0.01
@given(impacts(), frac_st, st.sampled_from(UNLOADINGS))
def test_prop_energy_never_created(imp, u, unloading):
    """V2 <= V1 (JCG over the validated range; Etsion where P* drops at w = 1.9, nu >= 0.33)."""
    if unloading == "etsion":
        assume(imp.nu >= 0.33)
    v1 = _speed(imp.eps_y, imp.nu, u) * imp.V_c
    v2 = imp.rebound_velocity(v1, unloading=unloading)
    assert 0.0 <= v2 <= v1


@pytest.mark.filterwarnings("ignore::fastrest.ValidityWarning")  # eps_y = Sy/E' may round past 0.01
@given(impacts(), frac_st, st.sampled_from(UNLOADINGS))
def test_prop_dimensional_api_matches_normalised(imp, u, unloading):
    v1 = _speed(imp.eps_y, imp.nu, u) * imp.V_c * (1 - 1e-9)
    vs = v1 / imp.V_c
    eps, nu = imp.eps_y, imp.nu
    assert imp.e(v1, unloading=unloading) == pytest.approx(
        direct.e_exact(vs, eps, nu, unloading), rel=1e-13)
    assert imp.max_interference(v1) == pytest.approx(direct.omega_m_exact(vs, eps, nu) * imp.omega_c, rel=1e-13)
    assert imp.rebound_velocity(v1, unloading=unloading) == pytest.approx(
        direct.e_exact(vs, eps, nu, unloading) * v1, rel=1e-13)
    w_res, R_res = imp.residual(v1, unloading=unloading)
    w_res_s, rr_s = direct.residual_exact(vs, eps, nu, unloading)
    assert w_res == pytest.approx(w_res_s * imp.omega_c, rel=1e-13, abs=1e-13 * imp.omega_c)
    assert R_res == pytest.approx(rr_s * imp.R_eff, rel=1e-13)


def test_dimensional_api_arrays_and_types():
    imp = Impact(Material(E=200e9, nu=0.33, Sy=1.12e9), R=0.01, mass=0.0327)
    v1 = np.array([0.5, 1.0, 10.0, 100.0]) * imp.V_c
    e = imp.e(v1)
    assert isinstance(e, np.ndarray) and e.shape == (4,)
    np.testing.assert_allclose(e, direct.e_exact(v1 / imp.V_c, imp.eps_y, imp.nu), rtol=1e-13)
    assert isinstance(imp.e(float(v1[2])), float)
    assert isinstance(imp.rebound_velocity(float(v1[2])), float)
    np.testing.assert_allclose(imp.rebound_velocity(v1), e * v1, rtol=1e-15)
    with pytest.raises(ValueError, match=r"\bV1\b"):
        imp.e(-1.0)
    with pytest.raises(ValueError, match=r"\bV1\b"):
        imp.max_interference(math.nan)
    with pytest.raises(ValueError, match="425"):
        imp.e(imp.V_c * 1e4)


# ============================================================================================
# Broadcasting and types
FUNCS = {
    "omega_m_star": lambda v, e, n, **k: direct.omega_m_exact(v, e, n),
    "e_star": direct.e_exact,
    "loss_star": direct.loss_exact,
    "residual_star": direct.residual_exact,
    "solve": direct.solve,
}


def _parts(res):
    """A result as a list of its arrays/floats (residual_star: tuple; solve: dict)."""
    if isinstance(res, tuple):
        return list(res)
    if isinstance(res, dict):
        return [res[k] for k in sorted(res)]
    return [res]


@pytest.mark.parametrize("name", FUNCS)
def test_scalar_in_python_float_out(name):
    f = FUNCS[name]
    for args in [(3.0, 0.005, 0.33), (3, 0.005, 0.33), (np.float64(3.0), np.float64(0.005), 0.33),
                 (np.array(3.0), np.array(0.005), np.array(0.33))]:
        for p in _parts(f(*args)):
            assert type(p) is float


@pytest.mark.parametrize("name", FUNCS)
@pytest.mark.parametrize("unloading", UNLOADINGS)
def test_broadcasting(name, unloading):
    f = FUNCS[name]
    v = np.array([[0.5], [3.0], [50.0]])                 # (3, 1)
    eps = np.array([[0.0005, 0.002, 0.005, 0.01]])      # (1, 4)
    nu = np.array([[0.2, 0.3, 0.33, 0.45]])             # (1, 4)
    res = _parts(f(v, eps, nu, unloading=unloading))
    for k, p in enumerate(res):
        assert isinstance(p, np.ndarray) and p.shape == (3, 4) and p.dtype == np.float64
        for i in range(3):
            for j in range(4):
                assert p[i, j] == _parts(f(float(v[i, 0]), float(eps[0, j]), float(nu[0, j]),
                                           unloading=unloading))[k]
    # three-way broadcast
    res3 = _parts(f(v[:, :, None], eps[:, :, None], np.array([0.25, 0.4]), unloading=unloading))
    for k, p in enumerate(res3):
        assert p.shape == (3, 4, 2)
        assert p[2, 1, 0] == _parts(f(50.0, 0.002, 0.25, unloading=unloading))[k]
    # read-only inputs, lists, non-contiguous views
    ro = [np.array(x, copy=True) for x in (v, eps, nu)]
    for x in ro:
        x.flags.writeable = False
    for a, b in zip(_parts(f(*ro, unloading=unloading)), res):
        np.testing.assert_array_equal(a, b)
    vl = [3.0, 50.0]
    for a, b in zip(_parts(f(vl, 0.005, 0.33, unloading=unloading)),
                    _parts(f(np.array(vl), 0.005, 0.33, unloading=unloading))):
        np.testing.assert_array_equal(a, b)
    big = np.linspace(1.5, 40.0, 20)
    for a, b in zip(_parts(f(big[::3], 0.005, 0.33, unloading=unloading)),
                    _parts(f(big[::3].copy(), 0.005, 0.33, unloading=unloading))):
        np.testing.assert_array_equal(a, b)


def test_broadcast_does_not_modify_inputs():
    v = np.array([0.5, 3.0, 50.0])
    eps = np.array([0.005])
    v0, eps0 = v.copy(), eps.copy()
    direct.solve(v, eps, 0.33)
    np.testing.assert_array_equal(v, v0)
    np.testing.assert_array_equal(eps, eps0)


def test_incompatible_shapes_raise():
    with pytest.raises(ValueError):
        direct.e_exact(np.ones(3), np.full(4, 0.005), 0.33)


# ============================================================================================
# Bad inputs: ValueError naming the parameter
def _named(pname):
    return re.compile(r"(?<![A-Za-z_])" + re.escape(pname) + r"(?![A-Za-z_])")


BAD = [
    ((-1.0, 0.005, 0.33), "v1_star"),
    ((math.nan, 0.005, 0.33), "v1_star"),
    ((math.inf, 0.005, 0.33), "v1_star"),
    ((-math.inf, 0.005, 0.33), "v1_star"),
    (([2.0, -1e-300], 0.005, 0.33), "v1_star"),
    ((2.0, 0.005, -0.01), "nu"),
    ((2.0, 0.005, 0.5), "nu"),
    ((2.0, 0.005, 0.7), "nu"),
    ((2.0, 0.005, math.nan), "nu"),
    ((2.0, 0.005, [0.3, math.nan]), "nu"),
    ((2.0, 0.0, 0.33), "eps_y"),
    ((2.0, -0.005, 0.33), "eps_y"),
    ((2.0, math.nan, 0.33), "eps_y"),
    ((2.0, math.inf, 0.33), "eps_y"),
]


@pytest.mark.parametrize("name", FUNCS)
@pytest.mark.parametrize("args, pname", BAD, ids=[f"{p}-{i}" for i, (_, p) in enumerate(BAD)])
def test_bad_inputs_name_parameter(name, args, pname):
    with pytest.raises(ValueError, match=_named(pname)):
        FUNCS[name](*args)


@pytest.mark.parametrize("name", FUNCS)
def test_non_numbers_raise_type_error_naming_parameter(name):
    with pytest.raises(TypeError, match=_named("v1_star")):
        FUNCS[name]("fast", 0.005, 0.33)


@pytest.mark.parametrize("name", ["e_star", "loss_star", "residual_star", "solve"])
@pytest.mark.parametrize("unloading", ["foo", "", None, "thornton", 1])
def test_unknown_unloading(name, unloading):
    with pytest.raises(ValueError, match="unloading"):
        FUNCS[name](2.0, 0.005, 0.33, unloading=unloading)


# ============================================================================================
# The normalised law: P*, A*, F (loading_energy), W*
LAW_W = [0.0, 0.3, 1.0, 1.5, 1.9, float(np.nextafter(1.9, 2)), 2.5, 10.0, 57.3, 100.0, 425.0]
LAW_MATERIALS = [(0.005, 0.33), (0.001, 0.25), (0.0095, 0.42)]


@pytest.mark.parametrize("eps, nu", LAW_MATERIALS)
def test_law_against_reference(eps, nu):
    w = np.array(LAW_W)
    P = contact.P_star(w, eps, nu)
    A = contact.A_star(w, eps, nu)
    F = energy.loading_energy(w, eps, nu)
    W = energy.W_star(w, eps, nu)
    for i, wi in enumerate(LAW_W):
        assert rel_err(P[i], ref.ref_P_star(wi, eps, nu)) <= 1e-14, wi
        assert rel_err(A[i], ref.ref_A_star(wi, eps, nu)) <= 1e-14, wi
        assert rel_err(F[i], ref.ref_F(wi, eps, nu)) <= 1e-14, wi
        # W* = 1 - F crosses zero at w = 1: absolute error on the scale of F
        assert abs(W[i] - ref.ref_W_star(wi, eps, nu)) <= 1e-14 * max(1.0, F[i]), wi
        assert contact.P_star(wi, eps, nu) == P[i]       # scalar path == array path
        assert energy.W_star(wi, eps, nu) == W[i]


def test_P_star_jump_at_1p9():
    """MODEL.md section 2: Hertz 2.618969, JG branch 2.614812 at eps_y = 0.005, nu = 0.33."""
    p_h = contact.P_star(1.9, 0.005, 0.33)
    p_jg = contact.P_star(float(np.nextafter(1.9, 2)), 0.005, 0.33)
    assert p_h == 1.9 ** 1.5
    assert p_h == pytest.approx(2.618969, abs=5e-7)
    assert p_jg == pytest.approx(2.614812, abs=5e-7)
    assert (p_jg - p_h) / p_h == pytest.approx(-0.0016, abs=1e-4)
    # A* and F are continuous there
    a = contact.A_star(np.array([1.9, np.nextafter(1.9, 2)]), 0.005, 0.33)
    assert a[1] - a[0] < 1e-14
    f = energy.loading_energy(np.array([1.9, np.nextafter(1.9, 2)]), 0.005, 0.33)
    assert 0 <= f[1] - f[0] < 1e-14


def test_W_star_elastic_part():
    assert energy.W_star(1.0, 0.005, 0.33) == 0.0
    w = np.array([0.0, 0.1, 0.5, 0.9, 0.999, 1.0])
    # w^2.5 is one pow: the kernel's (libm) and NumPy's (its own SIMD kernel on some CPUs) may differ
    # by an ulp or two; 0 and 1 are exact in every pow
    np.testing.assert_allclose(energy.W_star(w, 0.005, 0.33), 1.0 - w ** 2.5, rtol=0, atol=5e-16)
    np.testing.assert_allclose(energy.loading_energy(w, 0.005, 0.33), w ** 2.5, rtol=5e-16, atol=0)
    assert energy.loading_energy(1.0, 0.005, 0.33) == 1.0 and energy.loading_energy(0.0, 0.005, 0.33) == 0.0
    # negative above w = 1 and decreasing
    W = energy.W_star(np.array([1.0, 1.5, 2.0, 10.0, 100.0]), 0.005, 0.33)
    assert W[0] == 0.0 and np.all(np.diff(W) < 0)


@pytest.mark.parametrize("eps, nu", LAW_MATERIALS)
def test_loading_energy_inverts_omega_m(eps, nu):
    w = np.array([1.2, 1.9, 2.0, 7.7, 123.0, 425.0])
    v = np.sqrt(energy.loading_energy(w, eps, nu))
    np.testing.assert_allclose(direct.omega_m_exact(v, eps, nu), w, rtol=1e-13)


def test_law_bad_inputs():
    for f in (contact.P_star, contact.A_star, energy.loading_energy, energy.W_star):
        with pytest.raises(ValueError, match=_named("w")):
            f(-1.0, 0.005, 0.33)
        with pytest.raises(ValueError, match=_named("w")):
            f(math.nan, 0.005, 0.33)
        with pytest.raises(ValueError, match=_named("eps_y")):
            f(2.0, 0.0, 0.33)
        with pytest.raises(ValueError, match=_named("nu")):
            f(2.0, 0.005, 0.5)
        with pytest.raises(ValueError, match="a/R"):
            f(200.0, 0.02, 0.45)      # a/R = 1 at w = 123.4


def test_public_names():
    assert fastrest.ValidityWarning is ValidityWarning
    assert fastrest.ExtrapolationWarning is ExtrapolationWarning
