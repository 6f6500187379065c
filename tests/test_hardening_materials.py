"""Strain hardening in the SI / product layer: Material(Et=...), Impact, curves, scenes and
the exports (velocity tables, C header).

References: the direct solver with ``et_ratio`` (fastrest.direct, the Ghaednia et al. 2019 loading
law of fastrest.loading), never the object under test. At Et = 0 every number must be
Jackson-Green's bit for bit.
"""
import json
import math
import pickle
import warnings

import numpy as np
import pytest

import fastrest
from fastrest import ValidityWarning, cli, direct
from fastrest.export import c_header, velocity
from fastrest.interpolation import cell_edges

V_SWITCH = 1.9 ** 1.25
STEEL = dict(E=200e9, nu=0.33, Sy=1.12e9, rho=7850.0)  # JGM Table 1
#: Et/E of the accuracy checks (the brief's grid) and the material of the default run.
HARDENING = (0.001, 0.01, 0.1)
MATERIAL = (0.00525, 0.325)
UNLOADINGS = ("jcg", "etsion", "brake")
TOL_E = 1e-12       # relative, e and w_m* (as tests/test_curve.py)
TOL_LOSS = 1e-10    # relative 1 - e^2 (Etsion and Brake: relative to max(|loss|, 1e-3))


@pytest.fixture(autouse=True)
def _quiet_unfitted():
    """JCG/Etsion with hardening warn by design; tests that check the warning catch it themselves."""
    with warnings.catch_warnings():
        warnings.filterwarnings("ignore", "(?s).*fitted to elastic-perfectly plastic", ValidityWarning)
        yield


def _unfitted(record):
    return [w for w in record if issubclass(w.category, ValidityWarning)
            and "fitted to elastic-perfectly plastic" in str(w.message)]


# ============================================================================================
# Material

@pytest.mark.parametrize("Et", ["1e9", None, True, [1e9], np.array([1e9]), 1j])
def test_material_et_type_error_names_et(Et):
    with pytest.raises(TypeError, match=r"\bEt\b"):
        fastrest.Material(**STEEL, Et=Et)


@pytest.mark.parametrize("Et", [-1.0, -1e-300, math.nan, 200e9, 3e11, math.inf])
def test_material_et_value_error_names_et(Et):
    with pytest.raises(ValueError, match=r"^Et \(tangent modulus"):
        fastrest.Material(**STEEL, Et=Et)


def test_material_et_default_repr_equality_pickle():
    plain = fastrest.Material(**STEEL)
    zero = fastrest.Material(**STEEL, Et=0)
    assert plain.Et == 0.0 and type(zero.Et) is float and plain.et_ratio == 0.0
    assert zero == plain and hash(zero) == hash(plain)
    assert repr(zero) == repr(plain) == "Material(E=200000000000.0, nu=0.33, Sy=1120000000.0, rho=7850.0)"
    assert math.copysign(1.0, fastrest.Material(**STEEL, Et=-0.0).Et) == 1.0
    hard = fastrest.Material(**STEEL, Et=2e9)
    assert hard != plain and hard.et_ratio == 0.01
    assert repr(hard).endswith("rho=7850.0, Et=2000000000.0)")
    assert eval(repr(hard), {"Material": fastrest.Material}) == hard
    assert pickle.loads(pickle.dumps(hard)) == hard
    assert fastrest.Material(200e9, 0.33, 1.12e9, 7850.0, 2e9) == hard  # Et is the fifth field


def test_material_pickled_before_et_reads_zero():
    """A pickle of a Material from before ``Et`` existed (no ``Et`` in its state) loads as Et = 0."""
    m = fastrest.Material(**STEEL)
    state = dict(m.__dict__)
    del state["Et"]
    old = object.__new__(fastrest.Material)
    old.__dict__.update(state)
    back = pickle.loads(pickle.dumps(old))
    assert back.Et == 0.0 and back == m and fastrest.Impact(back, 0.01).et_ratio == 0.0
    imp = fastrest.Impact(back, 0.01)  # an Impact pickled before hardening: no loading law in its state
    del imp.__dict__["_law"]
    imp = pickle.loads(pickle.dumps(imp))
    assert (imp.et_ratio, imp.loading) == (0.0, "jackson-green") and imp.e(1.0) == fastrest.Impact(m, 0.01).e(1.0)


# ============================================================================================
# Impact

def _impacts():
    plain = fastrest.Impact(fastrest.Material(**STEEL), 0.01, mass=0.0327)
    zero = fastrest.Impact(fastrest.Material(**STEEL, Et=0.0), 0.01, mass=0.0327, loading="ghaednia")
    return plain, zero


def test_impact_et_zero_is_jackson_green_bit_for_bit():
    """Et = 0, even with the Ghaednia law named, gives JG's numbers exactly, through every method."""
    plain, zero = _impacts()
    assert plain.loading == "jackson-green" and zero.loading == "ghaednia" and zero.et_ratio == 0.0
    assert repr(zero).endswith(", loading='ghaednia')") and "loading" not in repr(plain)
    V = np.concatenate([[0.01, plain.V_c, 0.1, V_SWITCH * plain.V_c, 1.0, 5.0, 30.0], [plain.V_max()]])
    for u in UNLOADINGS:
        assert np.array_equal(zero.e(V, u), plain.e(V, u))
        assert np.array_equal(np.array(zero.residual(V, u)), np.array(plain.residual(V, u)))
        assert zero.V_max(u, extrapolate=True) == plain.V_max(u, extrapolate=True)
    assert np.array_equal(zero.max_interference(V), plain.max_interference(V))
    assert zero.V_max() == plain.V_max()
    ref = fastrest.curve(*MATERIAL, "brake", v_max=50.0)
    got = fastrest.curve(*MATERIAL, "brake", v_max=50.0, et_ratio=0.0, loading="ghaednia")
    for f in ("omega_rows", "e_rows", "loss_rows"):
        assert np.array_equal(getattr(got.data, f), getattr(ref.data, f))
    assert got.v_limit == ref.v_limit


@pytest.mark.parametrize("Et", [2e8, 2e9, 2e10])
def test_impact_with_et_is_the_direct_solver(Et):
    """Impact passes Et/E of the yielding body to the same kernels: bit for bit."""
    imp = fastrest.Impact(fastrest.Material(**STEEL, Et=Et), 0.01, mass=0.0327)
    h = Et / STEEL["E"]
    assert imp.et_ratio == h and imp.loading == "ghaednia"
    V = np.array([0.02, 0.1, 0.3, 1.0, 4.0, 20.0, 50.0])
    v = imp.v1_star(V)
    for u in UNLOADINGS:
        assert np.array_equal(imp.e(V, u), direct.e_exact(v, imp.eps_y, imp.nu, u, et_ratio=h))
        w_res, r = direct.residual_exact(v, imp.eps_y, imp.nu, u, et_ratio=h)
        assert np.array_equal(imp.residual(V, u)[0], w_res * imp.omega_c)
        lim = fastrest.limit(imp.eps_y, imp.nu, u, extrapolate=True, et_ratio=h).v1_star
        assert imp.V_max(u, extrapolate=True) == lim * imp.V_c
    assert np.array_equal(imp.max_interference(V), direct.omega_m_exact(v, imp.eps_y, imp.nu, et_ratio=h) * imp.omega_c)
    assert imp.V_max() == fastrest.limit(imp.eps_y, imp.nu, et_ratio=h).v1_star * imp.V_c
    assert imp.V_max() > _impacts()[0].V_max()  # a stiffer law: w_m* = 425 is reached later
    with pytest.raises(ValueError, match="V1"):
        imp.e(imp.V_max() * 1.001)


def test_impact_takes_et_of_the_body_that_yields_first():
    soft = fastrest.Material(70e9, 0.33, 0.28e9, rho=2700.0, Et=7e8)   # yields first
    hard = fastrest.Material(200e9, 0.3, 1.5e9, rho=7850.0, Et=4e10)   # never reaches yield here
    imp = fastrest.Impact(hard, 0.01, flat=soft)
    assert imp.yielding is soft and imp.et_ratio == 0.01
    two = fastrest.Impact.two_spheres(hard, 0.01, soft, 0.02)
    assert two.et_ratio == 0.01 and two.loading == "ghaednia"
    assert fastrest.Impact(soft, 0.01, flat=fastrest.Material(200e9, 0.3, math.inf, Et=1e10)).et_ratio == 0.01
    plain_flat = fastrest.Impact(hard, 0.01, flat=fastrest.Material(200e9, 0.3, 0.5e9))  # the flat yields first
    assert plain_flat.et_ratio == 0.0 and plain_flat.loading == "jackson-green"
    with pytest.raises(ValueError, match="jackson-green"):
        fastrest.Impact(hard, 0.01, flat=soft, loading="jackson-green")
    with pytest.raises(ValueError, match="loading must be one of"):
        fastrest.Impact(soft, 0.01, loading="hardening")


def test_impact_warns_once_per_call_for_unfitted_unloading():
    imp = fastrest.Impact(fastrest.Material(**STEEL, Et=2e9), 0.01)
    V = np.linspace(0.1, 5.0, 50)
    for u, n in (("jcg", 1), ("etsion", 1), ("brake", 0)):
        with warnings.catch_warnings(record=True) as rec:
            warnings.simplefilter("always")
            imp.e(V, u)
            imp.rebound_velocity(V, u)
        assert len(_unfitted(rec)) == 2 * n, (u, [str(w.message) for w in rec])
    with warnings.catch_warnings(record=True) as rec:
        warnings.simplefilter("always")
        _impacts()[0].e(V, "jcg")
    assert not _unfitted(rec)


@pytest.mark.parametrize("v1_star", [5.0, 20.0, 100.0, 400.0])
def test_e_rises_with_et_ratio(v1_star):
    """At a fixed V1* well above the switch, e rises monotonically with Et/E from 0 to 0.5 (a
    stiffer loading law: less plastic work). Just above the switch (V1* < ~3.1 for nu = 0.2) it
    need not: there JG's P* exceeds Hertz's and the hardening blend pulls it back towards Hertz."""
    h = np.linspace(0.0, 0.5, 26)
    for eps, nu in ((0.0005, 0.2), (0.01, 0.45), MATERIAL):
        for u in UNLOADINGS:
            e = direct.e_exact(v1_star, eps, nu, u, et_ratio=h)
            assert np.all(np.diff(e) > 0), (eps, nu, u, e)
            imp_e = fastrest.curve(eps, nu, u, v_max=v1_star, et_ratio=0.1).e(v1_star)
            assert imp_e == pytest.approx(e[5], rel=TOL_E, abs=0)


# ============================================================================================
# Curves and scenes against the direct solver

def _speeds(c):
    """Random (uniform and log-uniform) speeds, the hard cases of tests/test_curve.py, and every
    cell boundary of the curve with its neighbouring floats."""
    rng = np.random.default_rng(20240611)
    u = rng.uniform(0.0, c.v_max, 800)
    g = np.exp(rng.uniform(0.0, math.log(c.v_max), 800))
    vs, top = V_SWITCH, c.v_max
    hard = [0.0, 0.5, 1.0, 1.0 + 1e-12, 1.0 + 1e-9, 1.0 + 1e-6, vs, math.nextafter(vs, 0.0),
            math.nextafter(vs, math.inf), vs * (1 - 1e-12), vs * (1 + 1e-12), top, math.nextafter(top, 0.0),
            top * (1 - 1e-9)]
    _, edges = cell_edges(V_SWITCH, c.v_max, 5)
    e = np.unique(np.asarray(edges).ravel())
    bnd = np.concatenate([e, np.nextafter(e, 0.0), np.nextafter(e, np.inf)])
    v = np.concatenate([u[u > 0], g[g <= top], hard, bnd])
    return v[(v >= 0) & (v <= top)]


def _worst(c, extrapolate=False):
    v = _speeds(c)
    ref = direct.solve(v, c.eps_y, c.nu, c.unloading, et_ratio=c.et_ratio, extrapolate=extrapolate)
    floor = 1e-3 if c.unloading != "jcg" else 0.0
    out = {}
    for name, got, r, fl in (("omega_m", c.omega_m(v), ref["omega_m_star"], 0.0), ("e", c.e(v), ref["e"], 0.0),
                             ("loss", c.loss(v), ref["loss"], floor)):
        den = np.maximum(np.abs(r), fl)
        err = np.where(den > 0, np.abs(got - r) / np.where(den > 0, den, 1.0), np.abs(got - r))
        k = int(np.argmax(err))
        out[name] = (float(err[k]), float(v[k]))
    return out


def _check_curve(eps, nu, u, h):
    c = fastrest.curve(eps, nu, u, et_ratio=h)
    assert c.et_ratio == h and c.loading == "ghaednia"
    assert c.v_max == pytest.approx(fastrest.limit(eps, nu, et_ratio=h).v1_star, rel=1e-14)
    errs = _worst(c)
    msg = f"eps_y={eps} nu={nu} {u} et_ratio={h}: " + ", ".join(f"{k} {a:.2e} at V1*={b!r}" for k, (a, b) in errs.items())
    print("\n[hardening curve]", msg)
    assert errs["omega_m"][0] <= TOL_E and errs["e"][0] <= TOL_E and errs["loss"][0] <= TOL_LOSS, msg


@pytest.mark.parametrize("u", UNLOADINGS)
@pytest.mark.parametrize("h", HARDENING)
def test_hardening_curve_matches_direct(h, u):
    _check_curve(*MATERIAL, u, h)


@pytest.mark.slow
@pytest.mark.parametrize("u", UNLOADINGS)
@pytest.mark.parametrize("h", HARDENING)
@pytest.mark.parametrize("eps, nu", [(0.0005, 0.2), (0.0005, 0.45), (0.01, 0.2), (0.01, 0.45)])
def test_hardening_curve_matches_direct_corners(eps, nu, h, u):
    _check_curve(eps, nu, u, h)


def test_hardening_curve_extrapolated_matches_direct():
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", fastrest.ExtrapolationWarning)
        c = fastrest.curve(*MATERIAL, "brake", extrapolate=True, v_max=3000.0, et_ratio=0.1)
        errs = _worst(c, extrapolate=True)
    assert c.v_limit == fastrest.limit(*MATERIAL, et_ratio=0.1).v1_star < 3000.0
    assert errs["e"][0] <= TOL_E and errs["omega_m"][0] <= TOL_E, errs


def test_curve_records_et_ratio_repr_and_pickle():
    c = fastrest.curve(*MATERIAL, "brake", v_max=40.0, et_ratio=0.01)
    assert repr(c).startswith("Curve(eps_y=0.00525, nu=0.325, unloading='brake', et_ratio=0.01, v_max=40.0")
    plain = fastrest.curve(*MATERIAL, "brake", v_max=40.0)
    assert "et_ratio" not in repr(plain) and " loading=" not in repr(plain)
    assert plain.et_ratio == 0.0 and plain.loading == "jackson-green"
    assert "loading='ghaednia'" in repr(fastrest.curve(*MATERIAL, "brake", v_max=40.0, loading="ghaednia"))
    back = pickle.loads(pickle.dumps(c))
    assert (back.et_ratio, back.loading, repr(back)) == (c.et_ratio, c.loading, repr(c))
    v = np.linspace(0.0, 40.0, 101)
    assert np.array_equal(back.e(v), c.e(v)) and back.e(12.5) == c.e(12.5)
    with warnings.catch_warnings(record=True) as rec:  # curves pickled before hardening existed
        warnings.simplefilter("always")
        state = plain.__getstate__()
        del state["et_ratio"], state["loading"]
        old = object.__new__(fastrest.Curve)
        old.__setstate__(state)
    assert (old.et_ratio, old.loading) == (0.0, "jackson-green") and not rec


@pytest.mark.parametrize("kw, exc, match", [
    (dict(et_ratio=1.0), ValueError, "et_ratio"), (dict(et_ratio=-0.1), ValueError, "et_ratio"),
    (dict(et_ratio=math.nan), ValueError, "et_ratio"), (dict(et_ratio="0.1"), TypeError, "et_ratio"),
    (dict(et_ratio=[0.1]), TypeError, "et_ratio"), (dict(et_ratio=0.1, loading="jackson-green"), ValueError, "et_ratio"),
    (dict(loading="ghaednia2019"), ValueError, "loading"),
])
def test_curve_bad_hardening_inputs(kw, exc, match):
    with pytest.raises(exc, match=match):
        fastrest.curve(*MATERIAL, v_max=10.0, **kw)


def test_curve_and_scene_warn_once_for_unfitted_unloading():
    for u, n in (("jcg", 1), ("brake", 0)):
        with warnings.catch_warnings(record=True) as rec:
            warnings.simplefilter("always")
            fastrest.curve(*MATERIAL, u, v_max=10.0, et_ratio=0.01)
            fastrest.scene([(*MATERIAL, 0.01), (0.005, 0.33, 0.1), MATERIAL], u, v_max=10.0)
        assert len(_unfitted(rec)) == 2 * n, u


def test_scene_takes_et_ratio_triples():
    s = fastrest.scene([MATERIAL, (*MATERIAL, 0.01), [0.005, 0.33, 0.1]], "brake", v_max=[60.0, 50.0, 40.0])
    assert [c.et_ratio for c in s.curves] == [0.0, 0.01, 0.1]
    assert [c.loading for c in s.curves] == ["jackson-green", "ghaednia", "ghaednia"]
    v = np.linspace(0.0, 40.0, 301)
    for k, (eps, nu, h, vm) in enumerate([(*MATERIAL, 0.0, 60.0), (*MATERIAL, 0.01, 50.0), (0.005, 0.33, 0.1, 40.0)]):
        c = fastrest.curve(eps, nu, "brake", v_max=vm, et_ratio=h)
        assert np.array_equal(s.e(v, k), c.e(v)) and np.array_equal(s.loss(v, k), c.loss(v))
    back = pickle.loads(pickle.dumps(s))
    assert [c.et_ratio for c in back.curves] == [0.0, 0.01, 0.1]
    assert np.array_equal(back.e(v, 2), s.e(v, 2))
    g = fastrest.scene([MATERIAL, (*MATERIAL, 0.0)], "brake", v_max=30.0, loading="ghaednia")
    assert [c.loading for c in g.curves] == ["ghaednia", "ghaednia"]
    with pytest.raises(ValueError, match=r"materials\[1\].*et_ratio"):
        fastrest.scene([MATERIAL, (*MATERIAL, 1.5)], v_max=10.0)
    with pytest.raises(ValueError, match=r"materials\[0\] must be an \(eps_y, nu\) pair or \(eps_y, nu, et_ratio\)"):
        fastrest.scene([(*MATERIAL, 0.1, 2.0)], v_max=10.0)
    with pytest.raises(ValueError, match=r"materials\[0\].*jackson-green"):
        fastrest.scene([(*MATERIAL, 0.1)], v_max=10.0, loading="jackson-green")


# ============================================================================================
# Exports

HARD_STEEL = ["--E", "200e9", "--nu", "0.33", "--Sy", "1.12e9", "--R", "0.01", "--rho", "7800", "--Et", "2e9"]


def test_export_velocity_of_a_hardening_pair(tmp_path, capsys):
    out = tmp_path / "hard"
    tol = 1e-4
    with warnings.catch_warnings():
        warnings.simplefilter("always")  # not once per place in this process: this call's own
        assert cli.main(["export", "velocity"] + HARD_STEEL + ["--V-max", "5", "--tol", str(tol), "--out", str(out)]) == 0
    err = capsys.readouterr().err  # the command prints its warnings, one line each
    assert len([x for x in err.splitlines() if x.startswith("fastrest export velocity: warning: ")
                and "the pair hardens" in x]) == 1, err
    doc = json.loads((tmp_path / "hard.json").read_text())
    imp = fastrest.Impact(fastrest.Material(200e9, 0.33, 1.12e9, rho=7800, Et=2e9), 0.01)
    assert doc["pair"]["Et"] == 2e9
    assert doc["loading"]["law"] == "ghaednia" and doc["loading"]["et_ratio"] == imp.et_ratio == 0.01
    assert "E/Sy = (1 - nu^2)/eps_y" in doc["loading"]["note"]
    assert max(doc["measured_max_interpolation_error"].values()) <= tol
    rows = {k: np.array(v) for k, v in doc["rows"].items()}
    v = rows["V1_star"]
    for m in fastrest.unloading.NAMES:  # the rows are the direct solver's hardening values, exactly
        assert np.array_equal(rows[f"e_{m}"], direct.e_exact(v, imp.eps_y, imp.nu, m, et_ratio=0.01))
        assert np.array_equal(rows[f"loss_{m}"], direct.loss_exact(v, imp.eps_y, imp.nu, m, et_ratio=0.01))
    assert np.array_equal(rows["omega_m_star"], direct.omega_m_exact(v, imp.eps_y, imp.nu, et_ratio=0.01))
    # and not the elastic-perfectly plastic ones
    plain = fastrest.Impact(fastrest.Material(200e9, 0.33, 1.12e9, rho=7800), 0.01)
    assert np.all(rows["e_brake"][v > 3] > plain.e(rows["V_m_s"][v > 3], "brake"))
    # a JG pair records its law too, without the note
    res = velocity.velocity_table(plain, 2.0, 1e-3)
    assert (res["loading"], res["et_ratio"]) == ("jackson-green", 0.0)
    assert "note" not in velocity.json_obj({"name": "s"}, res)["loading"]


def test_export_velocity_pairs_file_with_et_and_bad_et(tmp_path, capsys):
    pairs = tmp_path / "pairs.csv"
    pairs.write_text("name,E,nu,Sy,R,rho,Et,flat_E,flat_nu,flat_Sy,flat_Et,V_max\n"
                     "steel,200e9,0.33,1.12e9,0.01,7800,2e9,,,,,2\n"
                     "al_on_steel,200e9,0.3,1.5e9,0.005,7800,,70e9,0.33,2.8e8,7e8,2\n")
    out = tmp_path / "dem"
    assert cli.main(["export", "velocity", "--pairs", str(pairs), "--tol", "1e-3", "--out", str(out)]) == 0
    doc = json.loads((tmp_path / "dem.json").read_text())["pairs"]
    assert doc["steel"]["loading"]["et_ratio"] == 0.01 and doc["al_on_steel"]["loading"]["et_ratio"] == 0.01
    assert cli.main(["export", "velocity"] + HARD_STEEL[:-1] + ["3e11", "--V-max", "1", "--out", str(out)]) == 2
    assert "--Et (tangent modulus" in capsys.readouterr().err
    assert cli.main(["export", "velocity"] + HARD_STEEL[:-2] + ["--flat-Et", "1e9", "--V-max", "1",
                                                               "--out", str(out)]) == 2
    assert "--flat-Et needs --flat-E" in capsys.readouterr().err


def test_export_c_of_hardening_materials(tmp_path, capsys):
    # JG materials given as triples with et_ratio 0: the very same header text as pairs
    pairs = [(0.005, 0.33), MATERIAL]
    curves = c_header.scene_curves(pairs, 20.0)
    text = c_header.header_text(pairs, curves, "h.h", "cmd")
    curves0 = c_header.scene_curves([(*m, 0.0) for m in pairs], 20.0)
    assert c_header.header_text([(*m, 0.0) for m in pairs], curves0, "h.h", "cmd") == text
    assert "et_ratio" not in text and "ghaednia" not in text.lower()
    # a hardening material: its rows are its curve's, and the comment records et_ratio and the law
    mats = [(0.005, 0.33), (*MATERIAL, 0.01)]
    with warnings.catch_warnings(record=True) as rec:
        warnings.simplefilter("always")
        path, curves = c_header.write_header(tmp_path / "h.h", mats, 20.0)
    assert len(_unfitted(rec)) == 1 and "a material hardens" in str(_unfitted(rec)[0].message)
    head = (tmp_path / "h.h").read_text()
    assert "1: eps_y = 0.00525, nu = 0.325, et_ratio = 0.01 (loading: ghaednia), v_max = 20.0" in head
    assert "Ghaednia" in head.split("*/", 1)[0]
    for code, u in enumerate(fastrest.unloading.NAMES):
        ref = fastrest.curve(*MATERIAL, u, v_max=20.0, et_ratio=0.01).data
        for f in ("omega_rows", "e_rows", "loss_rows"):
            assert np.array_equal(getattr(curves[1][code], f), getattr(ref, f))
    # from the command line: normalised EPS_Y:NU:ET_RATIO, and a pair with --Et
    assert cli.main(["export", "c", "--materials", "0.005:0.33:0.01", "--v-max", "10",
                     "--out", str(tmp_path / "m.h")]) == 0
    assert "et_ratio = 0.01" in capsys.readouterr().out
    assert cli.main(["export", "c"] + HARD_STEEL + ["--V-max", "2", "--out", str(tmp_path / "p.h")]) == 0
    capsys.readouterr()
    p = (tmp_path / "p.h").read_text()
    assert "--Et 2000000000.0" in p and "et_ratio = 0.01 (loading: ghaednia)" in p
    imp = fastrest.Impact(fastrest.Material(200e9, 0.33, 1.12e9, rho=7800, Et=2e9), 0.01)
    materials, v_max, critical = c_header.impact_materials([imp], [2.0])
    assert materials == [(imp.eps_y, imp.nu, 0.01)] and v_max == [2.0 / imp.V_c]
    assert cli.main(["export", "c", "--materials", "0.005:0.33:1.2", "--out", str(tmp_path / "x.h")]) == 2
    assert "et_ratio" in capsys.readouterr().err
