"""The time-domain contact law (fastrest.contact_law, fastrest.jit.contact_force).

References: the energy balance (fastrest.curve, itself checked against the 40-digit reference in
test_curve.py), scipy's adaptive quadrature of the law's own force along a path, the published
tmdsimpy test data for Brake's unloading, and the dimensional formulas written out here.
"""
import math
import pickle

import numba
import numpy as np
import pytest
from scipy.integrate import quad

import fastrest
from fastrest import direct
from fastrest import jit as frj
from fastrest.force_law import STATE_SIZE, hertz_contact_time

NAMES = ("jcg", "etsion", "brake")
#: Velocity Verlet steps per Hertz contact duration that the README and docs/model.md section 10
#: quote for e within 1e-8 (bench/FORCE_LAW.md measures the whole table).
STEPS_1E8 = 40000


def _single(law, w):
    """The virgin-loading force at w (a fresh contact for each point)."""
    return float(law.force([w])[0])


# --- semantics ---------------------------------------------------------------------------------

def test_loading_follows_the_jg_law_and_gaps_give_zero():
    law = fastrest.contact_law(0.005, 0.33)
    w = np.array([-1.0, 0.0, 0.5, 1.0, 1.9, 1.9000001, 3.0, 50.0, 400.0])
    got = law.force(w)  # increasing: all virgin loading
    want = np.where(w > 0, fastrest.P_star(np.maximum(w, 0), 0.005, 0.33), 0.0)
    np.testing.assert_allclose(got, want, rtol=1e-13, atol=0)
    assert got[0] == 0.0 and got[1] == 0.0


@pytest.mark.parametrize("unloading", NAMES)
def test_unload_reload_is_elastic_and_rejoins_the_law(unloading):
    eps, nu = 0.004, 0.3
    law = fastrest.contact_law(eps, nu, unloading)
    wm = 20.0
    w_res, delta = _residual(law, wm)
    state = law.new_state()
    p_m = law.force([wm], state)[0]
    # unloading: eq (32) through (w_m, P_m) and w_res
    w = np.array([19.999999, 15.0, w_res + 0.5 * delta, w_res + 1e-9, w_res, w_res - 1.0, -0.1])
    got = law.force(w, state)
    x = np.clip((w - w_res) / delta, 0.0, None)
    np.testing.assert_allclose(got, p_m * x**1.5, rtol=1e-12, atol=1e-12 * p_m)
    assert got[-3] == 0.0 and got[-2] == 0.0 and got[-1] == 0.0
    # continuity where loading turns to unloading
    assert law.force([wm - 1e-9], state.copy())[0] == pytest.approx(p_m, rel=1e-9)
    # reloading below w_m retraces the same branch; past w_m the JG law again, continuously
    back = law.force(w[::-1][3:], state)
    np.testing.assert_allclose(back, got[::-1][3:], rtol=1e-14)
    assert law.force([wm], state)[0] == p_m
    above = law.force([wm * (1 + 1e-9), 30.0], state)
    assert above[0] == pytest.approx(p_m, rel=1e-8)
    assert above[1] == pytest.approx(_single(law, 30.0), rel=1e-14)
    assert state[0] == 30.0


def _residual(law, wm):
    """(w_res, w_m - w_res) of the unloading model after loading to wm, from direct's solver."""
    v = math.sqrt(fastrest.loading_energy(wm, law.eps_y, law.nu))
    s = direct.solve(v, law.eps_y, law.nu, law.unloading)
    return s["omega_res_star"], s["omega_m_star"] - s["omega_res_star"]


@pytest.mark.parametrize("unloading", NAMES)
def test_closed_cycle_below_w_max_returns_the_work_put_in(unloading):
    law = fastrest.contact_law(0.006, 0.25, unloading)
    state = law.new_state()
    law.force([0.0, 40.0], state)
    w_lo, w_hi = 12.0, 35.0
    s_down = state.copy()

    def down(w):
        return law.force([w], s_down.copy())[0]

    law.force([w_hi, w_lo], state)      # unload to w_lo
    s_up = state.copy()

    def up(w):
        return law.force([w], s_up.copy())[0]

    work_in, _ = quad(up, w_lo, w_hi, epsabs=0, epsrel=1e-13, limit=200)
    work_out, _ = quad(down, w_lo, w_hi, epsabs=0, epsrel=1e-13, limit=200)
    assert work_in == pytest.approx(work_out, rel=1e-12)


@pytest.mark.parametrize("unloading", NAMES)
@pytest.mark.parametrize("v1", [1.5, 2.4, 30.0, 300.0])
def test_one_cycle_dissipates_the_energy_balance_loss(unloading, v1):
    """Loading to w_m(V1*) and unloading to separation dissipates U_c (1 - e^2) V1*^2."""
    eps, nu = 0.005, 0.33
    law = fastrest.contact_law(eps, nu, unloading)
    wm = direct.omega_m_exact(v1, eps, nu)
    pieces = [(0.0, min(wm, 1.9))] + ([(1.9, wm)] if wm > 1.9 else [])
    work_in = sum(2.5 * quad(lambda w: _single(law, w), a, b, epsabs=0, epsrel=1e-13, limit=200)[0]
                  for a, b in pieces)
    state = law.new_state()
    law.force([wm], state)
    w_res = state[0] - _residual(law, wm)[1]
    work_out = 2.5 * quad(lambda w: law.force([w], state.copy())[0], max(w_res, 0.0), wm,
                          epsabs=0, epsrel=1e-13, limit=200)[0]
    assert work_in == pytest.approx(v1**2, rel=1e-11)
    loss = direct.loss_exact(v1, eps, nu, unloading)
    assert (work_in - work_out) / v1**2 == pytest.approx(loss, rel=1e-9, abs=1e-12)


# --- the time-stepped impact reproduces the energy balance ---------------------------------------

MATERIALS = [(0.0005, 0.2), (0.005, 0.33), (0.01, 0.45), (0.002, 0.45)]


def _speeds(eps, nu, unloading):
    top = fastrest.limit(eps, nu).v1_star * (1 - 1e-6)  # Verlet overshoots w_m by O(dt^2)
    return [1.01, 1.5, 2.2, 2.3, 5.0, 40.0, top]


@pytest.mark.parametrize("unloading", NAMES)
@pytest.mark.parametrize("eps,nu", MATERIALS)
def test_time_stepped_impact_reproduces_energy_balance_e(unloading, eps, nu):
    law = fastrest.contact_law(eps, nu, unloading)
    c = fastrest.curve(eps, nu, unloading)
    for v in _speeds(eps, nu, unloading):
        r = law.impact(v, steps_per_contact=STEPS_1E8)
        assert r["e"] == pytest.approx(c.e(v), rel=1e-8), (v, r["e"], c.e(v))
        assert r["omega_m_star"] == pytest.approx(c.omega_m(v), rel=1e-6)


def test_time_stepping_converges_at_second_order_with_the_switch_located():
    v = [2.3, 2.5, 3.0, 7.0, 30.0, 200.0]

    def worst(eps, nu, n, locate=True):
        law = fastrest.contact_law(eps, nu, "jcg")
        c = fastrest.curve(eps, nu, "jcg")
        return max(abs(law.impact(x, steps_per_contact=n, locate_switch=locate)["e"] / c.e(x) - 1) for x in v)

    e1, e2 = worst(0.005, 0.33, 1000), worst(0.005, 0.33, 16000)
    order = math.log(e1 / e2) / math.log(16)
    assert order > 1.6, (e1, e2, order)
    # without locating the jump of the JG law at w = 1.9 the error stalls where the jump is large
    # (nu = 0.2: P*_JG(1.9+) exceeds Hertz by ~0.5 %)
    located, plain = worst(0.0005, 0.2, 16000), worst(0.0005, 0.2, 16000, False)
    assert plain > 10 * located, (plain, located)


def test_hertz_contact_time_is_the_classic_formula():
    """tau_c = 2 int_0^{w_m} dw / sqrt(V^2 - w^2.5) (energy of d2w/dtau2 = -(5/4) w^1.5), and in
    seconds 2.868 (m'^2/(R' E'^2 V))^(1/5)."""
    for v in (0.3, 1.0, 7.0):
        wm = v**0.8
        half = quad(lambda w: 1.0 / math.sqrt(v * v - w**2.5), 0.0, wm, epsabs=0, epsrel=1e-12, limit=200)[0]
        assert hertz_contact_time(v) == pytest.approx(2 * half, rel=1e-9)
    imp = fastrest.Impact(fastrest.Material(200e9, 0.33, 1.12e9, 7800), 0.01)
    V = 0.7
    t = hertz_contact_time(V / imp.V_c) * imp.omega_c / imp.V_c
    classic = 2.868265 * (imp.mass**2 / (imp.R_eff * imp.E_eff**2 * V)) ** 0.2
    assert t == pytest.approx(classic, rel=1e-6)


# --- errors, NaN, pickling, dimensional use -------------------------------------------------------

def test_errors_and_nan():
    law = fastrest.contact_law(0.005, 0.33, "jcg")
    with pytest.raises(ValueError, match="interference must be finite"):
        law.force([1.0, np.nan])
    with pytest.raises(ValueError, match="425"):
        law.force([1.0, 500.0])
    with pytest.raises(TypeError, match="interference"):
        law.force(["1.0"])
    with pytest.raises(ValueError, match="state must be"):
        law.force([1.0], np.zeros(3))
    with pytest.raises(ValueError, match="w_max"):
        fastrest.contact_law(0.005, 0.33, w_max=500.0)
    with pytest.raises(ValueError, match="a/R"):
        fastrest.contact_law(0.01, 0.45, w_max=1000.0, extrapolate=True)
    with pytest.raises(ValueError, match="eps_y"):
        fastrest.contact_law(-0.005, 0.33)
    with pytest.raises(ValueError, match="v1_star"):
        law.impact(-1.0)
    with pytest.raises(ValueError, match="steps_per_contact"):
        law.impact(2.0, steps_per_contact=2.5)
    # jit: NaN in, or past the end, poisons the contact's state (never a plausible force)
    state = np.zeros(STATE_SIZE)
    assert frj.contact_force(law.data, state, 10.0) > 0
    assert math.isnan(frj.contact_force(law.data, state, math.nan))
    assert np.all(np.isnan(state))
    assert math.isnan(frj.contact_force(law.data, state, 5.0))
    assert math.isnan(frj.contact_force(law.data, state, -1.0))
    state[:] = 0.0
    assert math.isnan(frj.contact_force(law.data, state, 1e4))
    assert math.isnan(frj.contact_force(law.data, state, 0.5))
    # a row that is no history: w_max > 0 with delta = 0 (what fastrest 0.2 left while loading)
    state[:] = [10.0, 25.0, 0.0, 0.0]
    assert math.isnan(frj.contact_force(law.data, state, 5.0)) and np.all(np.isnan(state))


def test_extrapolated_law_and_jcg_end():
    law = fastrest.contact_law(0.0005, 0.2, "jcg", extrapolate=True)
    assert law.w_max == pytest.approx(fastrest.unloading.get("jcg").omega_end, rel=1e-12)
    ets = fastrest.contact_law(0.0005, 0.2, "etsion", extrapolate=True)
    assert ets.w_max == pytest.approx(fastrest.omega_star_limit(0.0005, 0.2), rel=1e-12)


def test_pickle_round_trip():
    law = fastrest.Impact(fastrest.Material(200e9, 0.33, 1.12e9, 7800), 0.01).contact_law("brake")
    back = pickle.loads(pickle.dumps(law))
    path = np.linspace(0, 5 * law.omega_c, 7)
    np.testing.assert_array_equal(back.force(path), law.force(path))
    assert repr(back) == repr(law)


@numba.njit(parallel=True)
def _many(law, states, w, out):
    for k in numba.prange(w.shape[0]):
        for i in range(w.shape[1]):
            out[k, i] = frj.contact_force(law, states[k], w[k, i])


def test_contact_force_in_a_parallel_user_loop_matches_python():
    law = fastrest.contact_law(0.005, 0.33, "etsion")
    rng = np.random.default_rng(3)
    w = np.cumsum(rng.normal(0.0, 2.0, (64, 200)), axis=1)
    w = np.clip(w, -5, 300)
    out = np.empty_like(w)
    _many(law.data, np.zeros((64, STATE_SIZE)), w, out)
    for k in range(0, 64, 9):
        np.testing.assert_array_equal(out[k], law.force(w[k]))


@numba.njit(parallel=True)
def _many_stacked(laws, material, states, w, out):
    for k in numba.prange(w.shape[0]):
        for i in range(w.shape[1]):
            out[k, i] = frj.contact_force_stacked(laws, material[k], states[k], w[k, i])


def test_several_materials_in_one_parallel_loop_match_each_law():
    """A tuple of ContactLaw.data cannot be indexed by material inside prange; the stacked
    laws can, and give each law's forces bit for bit (three materials, three unloading models, a
    law with a smaller w_max, the last material's rows placed after the others')."""
    from fastrest.force_law import stack_laws

    laws = [fastrest.contact_law(0.005, 0.33, "etsion"), fastrest.contact_law(0.0008, 0.22, "jcg", w_max=150.0),
            fastrest.contact_law(0.009, 0.42, "brake")]
    stacked = stack_laws(laws)
    assert stacked.p_rows.shape[0] == sum(law.data.p_rows.shape[0] for law in laws)
    rng = np.random.default_rng(21)
    w = np.clip(np.cumsum(rng.normal(0.0, 2.0, (50, 150)), axis=1), -5, 140)
    material = np.arange(50) % 3
    material[-2:] = [3, -1]  # no such material: NaN
    w[1, 100:] = 160.0  # material 1's law ends at w_max = 150: NaN from there, as contact_force
    out = np.empty_like(w)
    states = np.zeros((50, STATE_SIZE))
    _many_stacked(stacked, material, states, w, out)
    for k in range(48):
        want = laws[material[k]].force(w[k]) if k != 1 else np.r_[laws[1].force(w[k, :100]), [np.nan] * 50]
        np.testing.assert_array_equal(out[k], want)
    assert np.isnan(out[-2:]).all() and np.isnan(states[-2:]).all() and np.isnan(states[1]).all()
    # a material index as an integer-valued float, as the jit API takes; a fraction is no material
    assert frj.contact_force_stacked(stacked, 2.0, np.zeros(STATE_SIZE), 10.0) == laws[2].force([10.0])[0]
    assert math.isnan(frj.contact_force_stacked(stacked, 1.5, np.zeros(STATE_SIZE), 10.0))
    with pytest.raises(TypeError, match="ContactLaw"):
        stack_laws([laws[0].data])
    with pytest.raises(ValueError, match="1 to 65536"):
        stack_laws([])


def test_dimensional_law_and_critical_scales_agree_with_impact():
    steel = fastrest.Material(200e9, 0.33, 1.12e9, 7800)
    alu = fastrest.Material(70e9, 0.33, 0.3e9, 2700)
    cases = [(fastrest.Impact(steel, 0.01), (200e9, 0.33, 1.12e9, 0.01, None, math.inf, 0.0, math.inf, math.inf, math.inf)),
             (fastrest.Impact(steel, 0.01, flat=alu), (200e9, 0.33, 1.12e9, 0.01, None, 70e9, 0.33, 0.3e9, math.inf, math.inf)),
             (fastrest.Impact.two_spheres(steel, 0.01, alu, 0.02), (200e9, 0.33, 1.12e9, 0.01, 4.0 / 3.0 * math.pi * 0.01**3 * 7800,
                                                                    70e9, 0.33, 0.3e9, 0.02, 4.0 / 3.0 * math.pi * 0.02**3 * 2700))]
    for imp, args in cases:
        args = list(args)
        if args[4] is None:
            args[4] = imp.mass
        s = frj.critical_scales(*args)
        crit = imp.critical_values()
        for k in s._fields:
            assert getattr(s, k) == crit[k], k  # the same compiled code: bit for bit
    # independent formulas (JGM eqs 4, 6, 28) for the rigid flat
    imp = cases[0][0]
    Ep = 200e9 / (1 - 0.33**2)
    C = 1.295 * math.exp(0.736 * 0.33)
    wc = (math.pi * C * 1.12e9 / (2 * Ep)) ** 2 * 0.01
    Pc = 4 / 3 * Ep * math.sqrt(0.01) * wc**1.5
    assert imp.omega_c == pytest.approx(wc, rel=1e-14) and imp.P_c == pytest.approx(Pc, rel=1e-14)
    assert imp.V_c == pytest.approx(math.sqrt(2 * 0.4 * Pc * wc / imp.mass), rel=1e-14)
    law = imp.contact_law("jcg")
    norm = fastrest.contact_law(imp.eps_y, imp.nu, "jcg")
    omega = np.array([0.0, 0.5, 3.0, 40.0, 20.0, 45.0]) * imp.omega_c
    np.testing.assert_allclose(law.force(omega), norm.force(omega / imp.omega_c) * imp.P_c, rtol=1e-15)
    nan = frj.critical_scales(200e9, 0.33, math.inf, 0.01, 1.0, math.inf, 0.0, math.inf, math.inf, math.inf)
    assert all(math.isnan(x) for x in nan)


# --- Brake's unloading against the published tmdsimpy test data -----------------------------------

def test_brake_matches_tmdsimpy_reference_data():
    """tmd-lab/tmdsimpy, tests/roughcontact/reference/normal_asperity.yaml, model 3 (E = 192 GPa,
    nu = 0.3, Sy = 330 MPa, effective radius 1.4 mm, no hardening): two spheres of radius 2.8 mm
    touching, total approach un. By symmetry one sphere of R = 2.8 mm on a rigid flat with
    E' = E/(1 - nu^2) and interference un/2. A reload/unload path with the peer's forces (N)."""
    un = np.array([-8.815764255743e-08, 4.407882127871e-08, 8.815764255743e-08, 4.407882127871e-08,
                   2.644729276723e-07, 1.372748078195e-07, 5.038343983363e-09])
    peer = np.array([0.0, 4.870544928015e-02, 1.377598138669e-01, 4.870544928015e-02,
                     6.885474816181e-01, 2.434382967105e-01, 0.0])
    imp = fastrest.Impact(fastrest.Material(192e9, 0.3, 330e6), 2.8e-3, mass=1.0)
    law = imp.contact_law("brake")
    got = law.force(un / 2)
    np.testing.assert_allclose(got, peer, rtol=1e-11, atol=0)
    # the other unloading models give other forces at the peer's unloading point
    for other in ("jcg", "etsion"):
        assert abs(imp.contact_law(other).force(un / 2)[5] / peer[5] - 1) > 0.01


def test_dem_example_reproduces_isolated_impacts():
    """docs/examples/dem_wall.py: particles of three materials, one global time step, the njit
    critical-scale helper and contact_force; every rebound agrees with Curve.e of the same impact."""
    import importlib.util
    from pathlib import Path

    path = Path(__file__).resolve().parent.parent / "docs" / "examples" / "dem_wall.py"
    spec = importlib.util.spec_from_file_location("dem_wall", path)
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    e_dem, e_curve, _, _ = mod.run(n_particles=40, steps_per_contact=2000)
    assert np.all(np.isfinite(e_dem))
    assert np.max(np.abs(e_dem / e_curve - 1)) < 1e-5


# --- every speed the other APIs accept integrates ------------------------------------------------

def test_limit_speed_integrates_with_any_step_count():
    """direct.v1_star_limit is accepted by the direct solver and the curves: the time-stepped impact
    there must integrate too, whatever the step (Verlet overshoots w_m* = 425 by O(dt^2); it used to
    raise), and land on the energy balance's e to the scheme's accuracy."""
    law = fastrest.contact_law(0.01, 0.45)
    lim = fastrest.limit(0.01, 0.45).v1_star
    ref = direct.e_exact(lim, 0.01, 0.45)
    for n, tol in ((10, 1e-2), (13, 1e-2), (2000, 1e-6), (STEPS_1E8, 1e-8)):
        r = law.impact(lim, steps_per_contact=n)
        assert abs(r["e"] / ref - 1) < tol, n
        assert abs(r["omega_m_star"] / 425.0 - 1) < 10 * tol, n
    for m in ("etsion", "brake"):
        r = fastrest.contact_law(0.01, 0.2, m).impact(fastrest.limit(0.01, 0.2).v1_star, steps_per_contact=37)
        assert math.isfinite(r["e"])
    # a speed past the limit is refused before integrating, naming the limit speed
    with pytest.raises(ValueError, match=r"v1_star = .* w_m\* > 425.*V1\* = 818\.47"):
        law.impact(lim * (1 + 1e-9))


def test_force_accepts_the_direct_solvers_w_m_at_the_limit_speed():
    """direct.omega_m_exact at the limit speed was 425 + 5 ulp (the Newton step clamped through
    e^(ln 425)); it is 425 (the solver clamps at w_hi itself), which the law serves."""
    for eps, nu in ((0.01, 0.45), (0.005, 0.33), (0.0005, 0.2), (0.01, 0.2)):
        lim = fastrest.limit(eps, nu).v1_star
        wm = direct.omega_m_exact(lim, eps, nu)
        assert wm <= 425.0
        law = fastrest.contact_law(eps, nu)
        assert law.force([wm])[0] == pytest.approx(fastrest.P_star(wm, eps, nu), rel=1e-13)


def test_tiny_speed_integrates_and_a_law_with_small_w_max_names_its_own_limit():
    """V1* = 1e-300 is a valid speed (e = 1, elastic): it integrated into nonsense (forces
    underflow) and reported an interference of 100.00000000000011 beyond w* = 425."""
    law = fastrest.contact_law(0.005, 0.33, w_max=100)
    ref = law.impact(0.5)
    for v in (1e-300, 5e-324, 1e-200, 2.0**-5, 0.03):
        r = law.impact(v)
        assert abs(r["e"] - 1.0) < 1e-10, v
        assert r["omega_m_star"] == pytest.approx(v**0.8, rel=1e-6), v
    assert abs(ref["e"] - 1.0) < 1e-10
    with pytest.raises(ValueError, match=r"v1_star = 1000.0 gives w_m\* beyond this law's w_max = 100.0: "
                                         r"it takes 0 < v1_star <= 226.30"):
        law.impact(1000.0)
