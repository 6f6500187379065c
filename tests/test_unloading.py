"""Unloading models as units: the registry, the same error everywhere for an unknown model, NaN in
jit code, and Brake's model against the 40-digit reference (tests/reference.py) and the published
tmdsimpy test data.
"""
import math
import warnings

import numba
import numpy as np
import pytest

import fastrest
from fastrest import direct, forward, rough, unloading
from fastrest import jit as frj
from fastrest.cells import closed_form

from reference import ref_e_star, ref_loss_star, ref_omega_m_star, ref_residual_star

NAMES = ("jcg", "etsion", "brake")


def test_registry_names_codes_and_jit_constants():
    assert unloading.NAMES == NAMES
    for code, name in enumerate(NAMES):
        m = unloading.get(name)
        assert m.code == code and m.name == name and m.label and m.reference
        assert unloading.get(m) is m
    assert (frj.JCG, frj.ETSION, frj.BRAKE) == (0, 1, 2)
    assert unloading.get("jcg").omega_end == pytest.approx(10017.5, abs=0.1)
    assert math.isinf(unloading.get("etsion").omega_end) and math.isinf(unloading.get("brake").omega_end)


UNKNOWN = ["JCG", "hertz", 2, None, ""]


@pytest.mark.parametrize("bad", UNKNOWN)
def test_unknown_model_is_the_same_value_error_everywhere(bad):
    steel = fastrest.Material(200e9, 0.33, 1.12e9, 7800)
    imp = fastrest.Impact(steel, 0.01)
    calls = [
        lambda: direct.e_exact(3.0, 0.005, 0.33, bad),
        lambda: direct.loss_exact(3.0, 0.005, 0.33, bad),
        lambda: fastrest.curve(0.005, 0.33, bad),
        lambda: fastrest.scene([(0.005, 0.33)], bad),
        lambda: fastrest.e_star(3.0, 0.005, 0.33, bad),
        lambda: fastrest.loss_star(3.0, 0.005, 0.33, bad),
        lambda: forward.forward_data(0.005, 0.33, bad, w_max=10.0),
        lambda: fastrest.contact_law(0.005, 0.33, bad),
        lambda: imp.e(1.0, unloading=bad),
        lambda: imp.V_max(unloading="none" if bad is None else bad),  # None: the loading law's own limit
        lambda: imp.contact_law(bad),
        lambda: rough.RoughSurface(steel, 1e-4, heights=[0.0, 1e-7]).impact(0.01, 1e-3, unloading=bad),
    ]
    for call in calls:
        with pytest.raises(ValueError, match=r"unloading must be one of \('jcg', 'etsion', 'brake'\)"):
            call()


@numba.njit
def _dispatch(code):
    r = unloading.restitution(code, 30.0, 5.0, 4.0, 9.0, 0.005, 0.33, 0, 0.0)
    w_res, delta = unloading.residual(code, 5.0, 4.0, 9.0, 0.005, 0.33, 0, 0.0)
    return r[0], r[1], w_res, delta, unloading.omega_end(code)


def test_jit_dispatch_covers_every_registered_model_and_nan_for_unknown():
    for code in range(len(NAMES)):
        assert np.all(np.isfinite(_dispatch(code)[:4])), code
    for code in (-1, len(NAMES), 99):
        assert np.all(np.isnan(_dispatch(code)))
        assert all(math.isnan(x) for x in unloading.restitution_kernel(3.0, 2.5, 1.5, 0.005, 0.33, code, 0, 0.0))
        assert all(math.isnan(x) for x in unloading.restitution_kernel(0.5, 0.57, -0.43, 0.005, 0.33, code, 0, 0.0))


def test_jit_table_and_forward_nan_for_unknown_code():
    tab = fastrest.load_table().data
    held = (tab.n_quantities - 1) // 2
    for code in (-1, held, 7):
        assert math.isnan(frj.e_table(tab, 3.0, 0.005, 0.33, code))
        assert math.isnan(frj.loss_table(tab, 3.0, 0.005, 0.33, code))
    fd = forward.forward_data(0.005, 0.33, "jcg", w_max=10.0)._replace(model=5)
    assert all(math.isnan(x) for x in forward.forward_values(fd, 3.0))
    assert all(math.isnan(x) for x in forward.forward_values(fd, 0.5))


@pytest.mark.parametrize("code", range(len(NAMES)))
def test_hertz_range_is_material_free_for_every_model(code):
    """Curves and tables share one set of Hertz-range cells: every model's e there must not depend
    on (eps_y, nu) (closed_form passes NaN for them)."""
    for v in (1.0 + 1e-9, 1.3, 2.0, 1.9**1.25):
        w, e, loss = closed_form(v, code)
        assert math.isfinite(e) and math.isfinite(loss)
        for eps, nu in ((0.0005, 0.2), (0.01, 0.45)):
            ref = ref_e_star(v, eps, nu, NAMES[code])
            assert e == pytest.approx(ref, rel=1e-15)


BRAKE_POINTS = [(v, eps, nu) for v in (1.5, 2.5, 10.0, 120.0) for eps, nu in ((0.0005, 0.2), (0.005, 0.33), (0.01, 0.45))]


@pytest.mark.parametrize("v,eps,nu", BRAKE_POINTS)
def test_brake_direct_matches_40_digit_reference(v, eps, nu):
    s = direct.solve(v, eps, nu, "brake")
    assert s["omega_m_star"] == pytest.approx(ref_omega_m_star(v, eps, nu), rel=2e-15)
    assert s["e"] == pytest.approx(ref_e_star(v, eps, nu, "brake"), rel=1e-14)
    assert s["loss"] == pytest.approx(ref_loss_star(v, eps, nu, "brake"), rel=1e-12, abs=1e-15)
    w_res, rr = ref_residual_star(v, eps, nu, "brake")
    assert s["omega_res_star"] == pytest.approx(w_res, rel=1e-12, abs=1e-14)
    assert s["R_res_ratio"] == pytest.approx(rr, rel=1e-12)


def test_brake_returns_more_energy_than_etsion_and_less_than_elastic():
    v = np.geomspace(2.5, 300.0, 30)
    eb, ee = direct.e_exact(v, 0.005, 0.33, "brake"), direct.e_exact(v, 0.005, 0.33, "etsion")
    assert np.all(eb > ee) and np.all(eb < 1.0)


@pytest.mark.parametrize("unloading_name", NAMES)
def test_brake_and_every_model_in_curves_scenes_tables_forward_and_rough(unloading_name):
    eps, nu = 0.004, 0.3
    v = np.array([1.0 + 1e-6, 1.7, 2.2306, 2.2308, 7.0, 60.0, 400.0])
    ref = np.array([ref_e_star(x, eps, nu, unloading_name) for x in v])
    c = fastrest.curve(eps, nu, unloading_name)
    np.testing.assert_allclose(c.e(v), ref, rtol=1e-12)
    s = fastrest.scene([(eps, nu), (0.002, 0.4)], unloading_name)
    np.testing.assert_allclose(s.e(v, 0), ref, rtol=1e-12)
    np.testing.assert_allclose(fastrest.e_star(v, eps, nu, unloading_name), ref, rtol=1e-9)
    # forward map: the returned energy of one summit at its w_m is e^2 V1*^2
    w = np.array([ref_omega_m_star(x, eps, nu) for x in v])
    fd = forward.forward_data(eps, nu, unloading_name, w_max=float(w.max()) * 1.01)
    ret = np.array([forward.returned_forward(fd, x) for x in w])
    np.testing.assert_allclose(ret, ref**2 * v**2, rtol=1e-12)
    # a rough surface of one summit is the single sphere
    steel = fastrest.Material(200e9, 0.3, 200e9 * eps / (1 - 0.09), 7800)
    surf = rough.RoughSurface(steel, 1e-4, heights=[0.0])
    imp = fastrest.Impact(steel, 1e-4, mass=1e-6)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        r = surf.impact(7.0 * imp.V_c, 1e-6, unloading=unloading_name)
    assert r.e == pytest.approx(ref_e_star(7.0, imp.eps_y, imp.nu, unloading_name), rel=1e-11)


def test_cli_prints_every_models_e(capsys):
    from fastrest import cli

    assert cli.main(["e", "--E", "200e9", "--nu", "0.33", "--Sy", "1.12e9", "--R", "0.01", "--rho", "7800",
                     "--V", "1", "--json"]) == 0
    import json

    row = json.loads(capsys.readouterr().out)["impacts"][0]
    imp = fastrest.Impact(fastrest.Material(200e9, 0.33, 1.12e9, 7800), 0.01)
    for name in NAMES:
        assert row[f"e_{name}"] == pytest.approx(ref_e_star(1.0 / imp.V_c, imp.eps_y, imp.nu, name), rel=1e-13)
