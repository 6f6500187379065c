"""Rough surfaces of a strain-hardening material: every summit follows Ghaednia et al.
(2019) (tangent modulus ratio ``et_ratio`` = Et/E) instead of Jackson-Green.

References (independent of the rough-surface code and its forward tables):

* one summit, and n summits at one height (each takes E/n of the impact energy), against the
  single-sphere solver ``fastrest.direct`` with the same ``et_ratio``;
* a few summits at different heights against ``rough_reference.reference_impact`` (per-summit
  ``energy.f_star_kernel`` quadrature of the law, ``unloading.restitution_kernel``, scipy brentq);
* a statistical surface against scipy.integrate.quad of the same per-summit functions.

At et_ratio = 0 the Ghaednia law is Jackson-Green's bit for bit; so is the surface.
"""
import math
import pickle
import warnings

import numpy as np
import pytest

import fastrest
from fastrest import Material, direct, loading, rough
from fastrest._validation import ValidityWarning
from rough_reference import gw_quad_reference, reference_impact

STEEL = Material(E=200e9, nu=0.3, Sy=1e9)
R_A = 1e-4
IP = fastrest.Impact(STEEL, R_A, mass=1.0)
GW = dict(eta=1e10, sigma=IP.omega_c, A_n=1e-7)  # psi = 1, N = 1000 summits
V1_STAR = np.array([0.7, 1.0 + 1e-7, 1.5, 2.2, 3.0, 10.0, 55.5, 100.0, 300.0])


def _surface(et_ratio, **kw):
    return rough.RoughSurface(STEEL, R_A, et_ratio=et_ratio, **kw)


@pytest.mark.parametrize("model", ["brake", "jcg"])
@pytest.mark.parametrize("h", [0.01, 0.2])
def test_one_summit_is_the_hardening_single_sphere(h, model):
    s = _surface(h, heights=[2e-7])
    M = 1e-4
    Vc = math.sqrt(2.0 * s.U_c / M)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ValidityWarning)  # JCG with hardening: warned, tested below
        r = s.impact(V1_STAR * Vc, M, model)
        v = r.V1_star
        e = direct.e_exact(v, s.eps_y, s.nu, model, et_ratio=h)
        loss = direct.loss_exact(v, s.eps_y, s.nu, model, et_ratio=h)
    wm = direct.omega_m_exact(v, s.eps_y, s.nu, et_ratio=h)
    assert np.max(np.abs(r.e - e)) <= 1e-12
    np.testing.assert_allclose(r.loss, loss, rtol=1e-9, atol=1e-15)
    np.testing.assert_allclose(r.w_star_max, wm, rtol=1e-12)
    np.testing.assert_allclose(r.force_max, s.P_c * fastrest.P_star(wm, s.eps_y, s.nu, et_ratio=h), rtol=1e-12)
    # hardening changes the answer (the check is not of Jackson-Green twice)
    jg = direct.e_exact(v[-3:], s.eps_y, s.nu, model)
    assert np.all(np.abs(r.e[-3:] - jg) > 1e-4)


def test_one_summit_keeps_relative_accuracy_at_the_onset_of_yield():
    """V1* = 1 + x exactly (M = U_c/2: V_c = 2 m/s): 1 - e^2 as the hardening single sphere."""
    s = _surface(0.1, heights=[3e-7])
    M = s.U_c / 2
    assert math.sqrt(2 * s.U_c / M) == 2.0
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ValidityWarning)
        for x in (1e-12, 1e-9, 1e-6):
            v = 1.0 + x + np.arange(-3, 4) * 2.0**-52
            r = s.impact(2.0 * v, M, "jcg")
            ref = direct.loss_exact(v, s.eps_y, s.nu, "jcg", et_ratio=0.1)
            assert np.all(r.n_yielded == 1) and np.max(np.abs(r.loss / ref - 1)) <= 1e-12, x
        assert np.all(s.impact(2.0 * v, M, "brake").loss == 0.0)  # Hertz loading: Brake returns all


def test_summits_at_one_height_share_the_energy():
    """n equal summits: each is one sphere at V1*/sqrt(n); also on a statistical-free explicit path
    with several blocks of the parallel sums."""
    n, h = 3 * rough.explicit.BLOCK + 5, 0.05
    s = _surface(h, heights=np.full(n, 1e-7))
    M = 1e-2
    Vc = math.sqrt(2.0 * s.U_c / M)
    r = s.impact(Vc * math.sqrt(n) * np.array([0.5, 2.2, 20.0, 200.0]), M, "brake")
    v = r.V1_star / math.sqrt(n)
    assert np.max(np.abs(r.e - direct.e_exact(v, s.eps_y, s.nu, "brake", et_ratio=h))) <= 1e-12
    np.testing.assert_allclose(r.w_star_max, direct.omega_m_exact(v, s.eps_y, s.nu, et_ratio=h), rtol=1e-12)
    assert np.all(r.n_contact == n)


@pytest.mark.parametrize("model", ["brake", "etsion"])
def test_explicit_matches_brute_force(model):
    z = rough.gaussian_summits(7, 4.0 * IP.omega_c, seed=1)
    h = 0.1
    s = _surface(h, heights=z)
    M = 1e-4
    Vc = math.sqrt(2.0 * s.U_c / M)
    V = Vc * np.array([0.5, 3.0, 30.0, 150.0])
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ValidityWarning)
        r = s.impact(V, M, model)
        for k, v in enumerate(V):
            ref = reference_impact(STEEL, R_A, z, v, M, unloading=model, et_ratio=h)
            assert abs(r.e[k] - ref["e"]) <= 1e-10
            assert abs(r.w_star_max[k] / ref["w_star_max"] - 1) <= 1e-10
            assert abs(r.force_max[k] / ref["force_max"] - 1) <= 1e-10
            assert r.n_contact[k] == ref["n_contact"] and r.n_yielded[k] == ref["n_yielded"]
            assert abs(r.dissipated[k] - ref["dissipated"]) <= 1e-10 * r.energy_in[k]


def test_zero_hardening_is_jackson_green_bit_for_bit():
    z = rough.gaussian_summits(500, 2.0 * IP.omega_c, seed=2)
    V = np.array([0.003, 0.03, 0.3])
    for kw, M in ((dict(heights=z), 1e-4), (dict(gw=GW), 1e-3)):
        jg = rough.RoughSurface(STEEL, R_A, **kw).impact(V, M)
        gh = rough.RoughSurface(STEEL, R_A, **kw, loading="ghaednia").impact(V, M)
        assert gh.e.tobytes() == jg.e.tobytes() and gh.loss.tobytes() == jg.loss.tobytes()
        assert gh.force_max.tobytes() == jg.force_max.tobytes()
        assert gh.d_min.tobytes() == jg.d_min.tobytes()


def test_hardening_raises_restitution_statistical():
    """More hardening, stiffer summits: less sinking, less loss (Brake unloading)."""
    V = np.array([0.01, 0.1, 1.0])
    es = [_surface(h, gw=GW).impact(V, 1e-3, "brake") for h in (0.0, 0.01, 0.1, 0.5)]
    for a, b in zip(es, es[1:]):
        assert np.all(b.e > a.e) and np.all(b.w_star_max < a.w_star_max)


def test_surface_carries_its_law():
    s = _surface(0.02, gw=GW)
    assert s.law.name == "ghaednia" and s.et_ratio == 0.02 and s.loading is None
    d = s.forward("brake", w_max=50.0)
    assert d.law == loading.GHAEDNIA and d.et_ratio == 0.02
    assert "et_ratio=0.02" in repr(s) and "loading" not in repr(s)
    j = rough.RoughSurface(STEEL, R_A, gw=GW)
    assert "et_ratio" not in repr(j) and "loading" not in repr(j) and j.law.name == "jackson-green"
    assert j.forward().law == loading.JACKSON_GREEN and j.params().keys() == {"material", "R_a", "gw"}
    g0 = rough.RoughSurface(STEEL, R_A, gw=GW, loading=loading.get("ghaednia"))
    assert g0.loading == "ghaednia" and "loading='ghaednia'" in repr(g0) and "et_ratio" not in repr(g0)
    assert s.params() == {"material": STEEL, "R_a": R_A, "gw": s.gw, "et_ratio": 0.02}
    again = rough.RoughSurface(**s.params())
    assert (again.et_ratio, again.loading, again.law) == (s.et_ratio, s.loading, s.law)


def test_surfaces_pickle_with_their_law():
    z = rough.gaussian_summits(50, IP.omega_c, seed=3)
    V = [0.01, 0.1]
    for s in (_surface(0.05, heights=z), _surface(0.05, gw=GW, loading="ghaednia")):
        r = s.impact(V, 1e-3, "brake")
        s2 = pickle.loads(pickle.dumps(s))
        assert (s2.et_ratio, s2.loading, s2.law) == (s.et_ratio, s.loading, s.law)
        assert repr(s2) == repr(s)
        assert s2.forward("brake").et_ratio == 0.05
        np.testing.assert_array_equal(s2.impact(V, 1e-3, "brake").e, r.e)
    # a surface pickled before hardening existed (no et_ratio/loading/law in its state) is JG
    old = rough.RoughSurface(STEEL, R_A, heights=z)
    state = dict(old.__dict__)
    for k in ("et_ratio", "loading", "law"):
        del state[k]
    cache = dict(state["_tables"].__dict__)
    del cache["et_ratio"], cache["loading"]
    state["_tables"].__dict__.clear()
    state["_tables"].__dict__.update(cache)
    s3 = rough.RoughSurface.__new__(rough.RoughSurface)
    s3.__dict__.update(state)
    assert s3.et_ratio == 0.0 and s3.law.name == "jackson-green" and "et_ratio" not in repr(s3)
    assert s3.impact(0.1, 1e-3).e == rough.RoughSurface(STEEL, R_A, heights=z).impact(0.1, 1e-3).e


def test_sweep_passes_the_law():
    specs = [_surface(0.05, gw=GW),
             {"material": STEEL, "R_a": R_A, "gw": GW, "et_ratio": 0.05},
             {"E": 200e9, "nu": 0.3, "Sy": 1e9, "R_a": R_A, "gw": GW, "et_ratio": 0.05, "loading": "ghaednia"},
             {"material": STEEL, "R_a": R_A, "gw": GW, "et_ratio": 1.5}]  # refused: reported
    with pytest.warns(RuntimeWarning, match="1 of 4 surfaces failed"):
        out = rough.sweep(specs, [0.01, 0.1], 1e-3, "brake")
    for r in out[1:3]:
        np.testing.assert_array_equal(r.e, out[0].e)
    assert [i for i, _ in out.errors] == [3] and "et_ratio" in str(out.errors[0][1])
    # the factory that rebuilds a RoughSurface on a Dask worker keeps the law
    s = rough.sweeps._rebuild_surface(**specs[0].params())
    assert (s.et_ratio, s.law.name) == (0.05, "ghaednia")


def test_bad_hardening_is_refused():
    for bad in (1.0, -0.1, math.nan, math.inf):
        with pytest.raises(ValueError, match="et_ratio"):
            _surface(bad, gw=GW)
    for bad in ("0.1", [0.1, 0.2], True):  # None: the material's own Et/E
        with pytest.raises(TypeError, match="et_ratio"):
            _surface(bad, gw=GW)
    with pytest.raises(ValueError, match="et_ratio = 0.1.*no strain hardening"):
        _surface(0.1, gw=GW, loading="jackson-green")
    with pytest.raises(ValueError, match="loading must be one of"):
        _surface(0.1, gw=GW, loading="hertz")
    with pytest.raises(TypeError):
        rough.RoughSurface(STEEL, R_A, None, GW, 0.1)  # et_ratio is keyword-only


def test_fitted_unloading_models_warn_with_hardening():
    s = _surface(0.05, heights=[0.0, 1e-8])
    for model in ("jcg", "etsion"):
        with pytest.warns(ValidityWarning, match="extrapolation"):
            s.impact(0.1, 1e-3, model)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        s.impact(0.1, 1e-3, "brake")
        rough.RoughSurface(STEEL, R_A, heights=[0.0, 1e-8]).impact(0.1, 1e-3, "jcg")


def test_past_the_model_range_with_hardening():
    s = _surface(0.1, heights=[0.0])
    M = 1e-4
    v_max = fastrest.limit(s.eps_y, s.nu, et_ratio=0.1).v1_star * math.sqrt(2.0 * s.U_c / M)
    assert s.impact(0.999 * v_max, M, "brake").w_star_max > 400.0
    with pytest.raises(ValueError, match="past the model's range|beyond w\\* = 425"):
        s.impact(1.01 * v_max, M, "brake")


# --- statistical surfaces against quadrature ------------------------------------------------------

@pytest.mark.parametrize("psi, V1, h, model", [(1.0, 0.1, 0.01, "brake"), (2.0, 0.1, 0.1, "brake"),
                                               (4.0, 1.0, 0.3, "brake"), (4.0, 0.01, 0.1, "jcg")])
def test_statistical_matches_quad(psi, V1, h, model):
    s = _surface(h, gw=dict(eta=1e10, sigma=psi**2 * IP.omega_c, A_n=1e-4))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ValidityWarning)
        r = s.impact(V1, 1e-2, model)
    sd, e = gw_quad_reference(s, V1, 1e-2, model)
    assert abs(r.d_min / s.sigma - sd) <= 1e-10
    assert abs(r.e - e) <= 1e-10


@pytest.mark.slow
def test_sweep_on_dask_keeps_the_law():
    """Surfaces and dicts with et_ratio on a LocalCluster (about 20 s, a worker compiling): bit-identical to the local sweep."""
    distributed = pytest.importorskip("distributed")
    z = rough.gaussian_summits(2000, 2.0 * IP.omega_c, seed=9)
    specs = [_surface(0.05, heights=z), _surface(0.05, gw=GW, loading="ghaednia"),
             {"material": STEEL, "R_a": R_A, "heights": z, "et_ratio": 0.05}]
    V = np.geomspace(0.01, 1.0, 4)
    local = rough.sweep(specs, V, 1e-3, "brake")
    with distributed.LocalCluster(n_workers=1, processes=True, threads_per_worker=1,
                                  dashboard_address=None) as cluster, distributed.Client(cluster) as client:
        remote = rough.sweep(specs, V, 1e-3, "brake", client=client, scatter_min=1000)
    assert not local.errors and not remote.errors
    np.testing.assert_array_equal(remote[2].e, remote[0].e)
    jg = rough.RoughSurface(STEEL, R_A, heights=z).impact(V, 1e-3, "brake")
    assert np.all(local[0].e > jg.e)
    for a, b in zip(local, remote):
        for key, val in a.as_dict().items():
            np.testing.assert_array_equal(np.asarray(b[key]), np.asarray(val), err_msg=key)


def test_surface_takes_the_materials_tangent_modulus():
    import fastrest
    from fastrest import rough
    hard = fastrest.Material(200e9, 0.3, 1e9, Et=4e9)
    a = rough.RoughSurface(hard, 100e-6, heights=[0.0])
    b = rough.RoughSurface(fastrest.Material(200e9, 0.3, 1e9), 100e-6, heights=[0.0], et_ratio=0.02)
    assert a.et_ratio == 0.02 and a.law.name == "ghaednia"
    assert a.impact(0.05, 1e-3)["e"] == b.impact(0.05, 1e-3)["e"]
    with pytest.raises(ValueError, match="contradicts the material's Et/E"):
        rough.RoughSurface(hard, 100e-6, heights=[0.0], et_ratio=0.01)
