"""Every deprecated name and call form still works for one release, warns DeprecationWarning naming
its replacement, and gives what the replacement gives; fastrest itself uses none of them."""
import importlib
import subprocess
import sys
import textwrap
import warnings

import numpy as np
import pytest

import fastrest
from fastrest import direct, forward, limits
import fastrest.jit as frj
from fastrest.tables import error as table_error_module


def _warns(replacement, fn):
    """fn() under pytest.warns(DeprecationWarning) whose message names ``replacement``."""
    with pytest.warns(DeprecationWarning) as rec:
        out = fn()
    messages = [str(w.message) for w in rec if issubclass(w.category, DeprecationWarning)]
    assert any(replacement in m and "deprecated" in m for m in messages), messages
    return out


# --- old module attributes: (module, name, replacement named in the warning, the new object) ----------

MOVED = [
    ("fastrest.materials", "Impact", "fastrest.Impact", lambda: fastrest.Impact),
    ("fastrest.curve", "Scene", "fastrest.Scene", lambda: fastrest.Scene),
    ("fastrest.curve", "scene", "fastrest.scene", lambda: fastrest.scene),
    ("fastrest.curve", "SceneData", "fastrest.jit.SceneData", lambda: frj.SceneData),
    ("fastrest.curve", "scene_value", "fastrest.scene import scene_value",
     lambda: sys.modules["fastrest.scene"].scene_value),
    ("fastrest.curve", "material_index", "fastrest.scene import material_index",
     lambda: sys.modules["fastrest.scene"].material_index),
    ("fastrest.curve", "CurveData", "fastrest.jit.CurveData", lambda: frj.CurveData),
    ("fastrest.curve", "e_curve", "fastrest.jit.e_curve", lambda: frj.e_curve),
    ("fastrest.curve", "loss_curve", "fastrest.jit.loss_curve", lambda: frj.loss_curve),
    ("fastrest.curve", "omega_m_curve", "fastrest.jit.omega_m_curve", lambda: frj.omega_m_curve),
    ("fastrest.curve", "BITS_PER_OCTAVE", "fastrest.curve_data.BITS_PER_OCTAVE",
     lambda: importlib.import_module("fastrest.curve_data").BITS_PER_OCTAVE),
    ("fastrest.curve", "V_SWITCH", "fastrest.energy.V_SWITCH", lambda: fastrest.energy.V_SWITCH),
    *[("fastrest.curve", n, f"fastrest.cells.{n}", (lambda n: lambda: getattr(fastrest.cells, n))(n))
      for n in ("HERTZ_BASE", "HERTZ_BITS_PER_OCTAVE", "HERTZ_EDGES", "HERTZ_SHIFT", "N_HERTZ", "closed_form",
                "hertz_rows", "jg_nodes")],
    ("fastrest.direct", "omega_m_star", "fastrest.direct.omega_m_exact", lambda: direct.omega_m_exact),
    ("fastrest.direct", "e_star", "fastrest.direct.e_exact", lambda: direct.e_exact),
    ("fastrest.direct", "loss_star", "fastrest.direct.loss_exact", lambda: direct.loss_exact),
    ("fastrest.direct", "residual_star", "fastrest.direct.residual_exact", lambda: direct.residual_exact),
    *[("fastrest.table_error", n, f"fastrest.tables.error.{n}", (lambda n: lambda: getattr(table_error_module, n))(n))
      for n in ("AccuracyWarning", "DEFAULT_TOL", "SAFETY", "SIGN_CHANGE_FLOOR", "adversarial_points",
                "sample_points", "measure", "meets", "worst", "build_to_tolerance", "warn_if_inaccurate")],
    ("fastrest", "table_error", "fastrest.tables.error", lambda: table_error_module),
]


def _module(name):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", DeprecationWarning)  # fastrest.table_error warns on import
        return importlib.import_module(name)


@pytest.mark.parametrize("module, name, replacement, new", MOVED, ids=[f"{m}.{n}" for m, n, _, _ in MOVED])
def test_moved_name_warns_and_is_the_same_object(module, name, replacement, new, monkeypatch):
    mod = _module(module)
    if (module, name) == ("fastrest", "table_error"):
        monkeypatch.delattr(mod, name, raising=False)  # bound once the deprecated module is imported
    assert name not in vars(mod)
    got = _warns(replacement, lambda: getattr(mod, name))
    assert got is new()
    # ``from module import name`` goes through the same path
    ns = {}
    _warns(replacement, lambda: exec(f"from {module} import {name} as x", ns))
    assert ns["x"] is new()


def test_unknown_names_still_raise():
    for module in ("fastrest", "fastrest.materials", "fastrest.curve", "fastrest.direct", "fastrest.limits",
                   "fastrest.forward", "fastrest.table_error"):
        mod = _module(module)
        with pytest.raises(AttributeError, match="no_such_name"):
            getattr(mod, "no_such_name")
    with pytest.raises(ImportError):
        exec("from fastrest.curve import no_such_name", {})


def test_table_error_module_warns_on_import():
    code = ("import warnings, fastrest\n"
            "with warnings.catch_warnings(record=True) as rec:\n"
            "    warnings.simplefilter('always')\n"
            "    import fastrest.table_error\n"
            "print([str(w.message) for w in rec if w.category is DeprecationWarning])\n")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert "fastrest.table_error" in out and "fastrest.tables.error" in out


def test_unpickling_an_old_impact_path_works():
    """Pickles that name fastrest.materials.Impact (the class's first home) still load."""
    import pickle
    steel = fastrest.Material(200e9, 0.33, 1.12e9)
    data = pickle.dumps(fastrest.Impact(steel, 0.01, mass=0.0327), protocol=0).replace(b"fastrest.impact\n",
                                                                                b"fastrest.materials\n")
    assert b"fastrest.materials" in data
    imp = _warns("fastrest.Impact", lambda: pickle.loads(data))
    assert isinstance(imp, fastrest.Impact) and imp.e(1.0) == fastrest.Impact(steel, 0.01, mass=0.0327).e(1.0)


# --- limits: one function, the old ones give its fields ----------------------------------------------

@pytest.mark.parametrize("kw", [{}, {"extrapolate": True}, {"extrapolate": True, "unloading": "jcg"}])
def test_old_limit_functions_warn_and_agree_with_limit(kw):
    eps, nu = 0.0005, 0.33
    lim = fastrest.limit(eps, nu, kw.get("unloading"), extrapolate=kw.get("extrapolate", False))
    assert lim == limits.limit(eps, nu, **kw) and isinstance(lim, limits.Limit)
    assert _warns("fastrest.limit", lambda: limits.v1_star_limit(eps, nu, **kw)) == lim.v1_star
    assert _warns("fastrest.limit", lambda: direct.v1_star_limit(eps, nu, **kw)) == lim.v1_star
    assert _warns("fastrest.limit", lambda: limits.omega_limit(eps, nu, **kw)) == lim.omega_m_star
    if "unloading" not in kw:
        assert _warns("fastrest.limit", lambda: forward.forward_limit(eps, nu, **kw)) == lim.omega_m_star


def test_limit_is_where_the_solver_stops():
    lim = fastrest.limit(0.005, 0.33)
    assert direct.omega_m_exact(lim.v1_star, 0.005, 0.33) == pytest.approx(lim.omega_m_star, rel=1e-12)
    with pytest.raises(ValueError, match="w_m"):
        direct.e_exact(lim.v1_star * (1 + 1e-9), 0.005, 0.33)
    steel = fastrest.Material(200e9, 0.33, 1.12e9)
    imp = fastrest.Impact(steel, 0.01, mass=0.0327)
    assert imp.V_max() == fastrest.limit(imp.eps_y, imp.nu, "jcg").v1_star * imp.V_c


# --- exact and interpolated paths: distinct names --------------------------------------------------

def test_old_direct_names_give_the_exact_solver():
    v, eps, nu = np.array([0.5, 5.0, 50.0]), 0.005, 0.33
    for old, new in (("omega_m_star", "omega_m_exact"), ("e_star", "e_exact"), ("loss_star", "loss_exact")):
        f = _warns(f"fastrest.direct.{new}", lambda: getattr(direct, old))
        np.testing.assert_array_equal(f(v, eps, nu), getattr(direct, new)(v, eps, nu))
    f = _warns("fastrest.direct.residual_exact", lambda: direct.residual_star)
    np.testing.assert_array_equal(f(v, eps, nu), direct.residual_exact(v, eps, nu))
    assert direct.e_exact is not fastrest.e_star and "e_star" not in direct.__all__


# --- the scene's jit functions: (scene, v1_star, material) ---------------------------------------------

def test_old_scene_functions_keep_their_order_and_warn():
    sc = fastrest.scene([(0.005, 0.33), (0.001, 0.25)], v_max=300.0).data
    for q in ("omega_m", "e", "loss"):
        old, new = getattr(frj, f"{q}_scene"), getattr(frj, f"{q}_material")
        assert _warns(f"fastrest.jit.{q}_material(scene, v1_star, material)", lambda: old(sc, 1, 30.0)) \
            == new(sc, 30.0, 1)


def test_old_scene_functions_warn_when_compiled_in_user_code():
    import numba

    sc = fastrest.scene([(0.005, 0.33), (0.001, 0.25)], v_max=300.0).data

    @numba.njit
    def user(sc, k, v):
        return frj.e_scene(sc, k, v)

    # a FutureWarning: shown by Python's default filters, although it comes from fastrest's code
    # while Numba compiles `user` (a DeprecationWarning there was hidden)
    with pytest.warns(FutureWarning, match="fastrest.jit.e_material") as rec:
        out = user(sc, 1, 30.0)
    assert any("deprecated" in str(w.message) for w in rec)
    assert out == frj.e_material(sc, 30.0, 1)


def test_compile_time_deprecation_is_shown_by_default_filters(tmp_path):
    """A plain script (no -W) compiling the old scene function sees the warning on stderr."""
    script = tmp_path / "user.py"
    script.write_text("import numba, fastrest\nfrom fastrest import jit\n"
                      "sc = fastrest.scene([(0.005, 0.33)], v_max=50.0).data\n"
                      "@numba.njit\ndef user(sc, v):\n    return jit.e_scene(sc, 0, v)\n"
                      "print(user(sc, 5.0))\n")
    r = subprocess.run([sys.executable, str(script)], capture_output=True, text=True, cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    assert "e_scene" in r.stderr and "e_material" in r.stderr and "deprecated" in r.stderr, r.stderr


# --- options keyword-only ------------------------------------------------------------------------

def test_forward_data_w_max_positional_warns_and_maps():
    new = forward.forward_data(0.005, 0.33, "etsion", w_max=50.0)
    old = _warns("w_max=", lambda: forward.forward_data(0.005, 0.33, 50.0, "etsion"))
    assert old.model == new.model and old.w_max == new.w_max
    np.testing.assert_array_equal(old.f_rows, new.f_rows)
    old = _warns("w_max=", lambda: forward.forward_data(0.005, 0.33, 50.0))
    assert old.model == forward.JCG and old.w_max == 50.0
    with pytest.raises(ValueError, match="unloading must be one of"):  # w_max by keyword: the new form
        forward.forward_data(0.005, 0.33, 50.0, w_max=40.0)


def test_keyword_only_options_positional_warn():
    t = fastrest.load_table()
    assert _warns("tol=", lambda: fastrest.load_table(None, 1e-3)) is t
    pts = (np.array([5.0]), np.array([0.005]), np.array([0.33]))
    got = _warns("search=", lambda: table_error_module.measure(t, pts, False))
    assert got == table_error_module.measure(t, pts, search=False)
    a = _warns("n_random_materials=", lambda: table_error_module.adversarial_points(t, 2, 2, 1))
    b = table_error_module.adversarial_points(t, n_random_materials=2, n_random_speeds=2, seed=1)
    for x, y in zip(a, b):
        np.testing.assert_array_equal(x, y)
    with pytest.raises(TypeError, match="positional"):
        table_error_module.adversarial_points(t, 2, 2, 1, 5)


def test_the_keyword_only_decorator():
    from fastrest._deprecation import keyword_only

    @keyword_only("b", "c")
    def f(a, *, b=1, c=2):
        return a, b, c

    assert f(0) == (0, 1, 2) and f(0, c=5) == (0, 1, 5)
    assert _warns("b=... and c=...", lambda: f(0, 3, 4)) == (0, 3, 4)
    assert f.__name__ == "f"
    with pytest.raises(TypeError):
        keyword_only("a")(lambda a, *, b=1: a)


def test_the_renamed_decorator():
    """A renamed parameter (``fastrest.cuda.contact_force``: law= -> data=) keeps its old keyword."""
    from fastrest._deprecation import renamed

    @renamed(law="data")
    def f(data, state=0):
        return data, state

    assert f(1) == (1, 0) and f(data=1, state=2) == (1, 2)
    assert _warns("data=", lambda: f(law=3, state=4)) == (3, 4)
    assert f.__name__ == "f"
    with pytest.raises(TypeError, match="both"):
        f(law=1, data=2)


def test_impact_omega_m_warns():
    steel = fastrest.Material(200e9, 0.33, 1.12e9)
    imp = fastrest.Impact(steel, 0.01, mass=0.0327)
    assert _warns("Impact.max_interference", lambda: imp.omega_m(1.0)) == imp.max_interference(1.0)


@pytest.mark.parametrize("old, new", [("omega_m_star", "omega_m"), ("e_star", "e"), ("loss_star", "loss")])
def test_table_star_methods_warn_and_agree(old, new):
    t = fastrest.load_table()
    v = np.array([0.5, 5.0, 50.0])
    assert _warns(f"Table.{new}", lambda: getattr(t, old)(5.0, 0.005, 0.33)) == getattr(t, new)(5.0, 0.005, 0.33)
    np.testing.assert_array_equal(_warns(f"Table.{new}", lambda: getattr(t, old)(v, 0.005, 0.33)),
                                  getattr(t, new)(v, 0.005, 0.33))
    if new != "omega_m":
        assert _warns(f"Table.{new}", lambda: getattr(t, old)(5.0, 0.005, 0.33, "etsion")) \
            == getattr(t, new)(5.0, 0.005, 0.33, "etsion")


# --- no internal use: the main paths raise nothing under DeprecationWarning-as-error -------------------

MAIN_PATHS = textwrap.dedent("""
    import warnings
    warnings.simplefilter("error", DeprecationWarning)
    import numpy as np
    import numba
    import fastrest
    from fastrest import direct, forward, models, rough, jit as frj, tables, limits, unloading
    from fastrest.export import grid, velocity
    from fastrest.tables import error
    steel = fastrest.Material(200e9, 0.33, 1.12e9, 7800)
    alu = fastrest.Material(70e9, 0.3, 2.8e8, 2700)
    imp = fastrest.Impact(steel, 0.01, alu)
    v = np.array([0.5, 5.0, 50.0])
    for m in unloading.NAMES:
        imp.e(1.0, m); imp.residual(1.0, m); imp.rebound_velocity(1.0, m); imp.max_interference(1.0)
        imp.V_max(m); imp.v1_star(1.0, m)
        direct.solve(v, 0.005, 0.33, m); direct.e_exact(v, 0.005, 0.33, m); direct.loss_exact(v, 0.005, 0.33, m)
        direct.residual_exact(v, 0.005, 0.33, m); direct.omega_m_exact(v, 0.005, 0.33)
        c = fastrest.curve(0.005, 0.33, m, v_max=200.0)
        c.e(v); c.loss(v); c.omega_m(v); c.e(5.0)
        sc = fastrest.scene([(0.005, 0.33), (0.002, 0.3)], m, v_max=100.0)
        sc.e(v, [0, 1, 0]); sc.loss(v, 1); sc.omega_m(v, 0)
        fastrest.e_star(v, 0.005, 0.33, m); fastrest.loss_star(v, 0.005, 0.33, m); fastrest.omega_m_star(v, 0.005, 0.33)
        law = fastrest.contact_law(0.005, 0.33, m, w_max=400.0)
        law.force(np.linspace(0.0, 300.0, 50)); law.impact(10.0, steps_per_contact=100)
        imp.contact_law(m)
        fd = forward.forward_data(0.005, 0.33, m, w_max=100.0)
        forward.forward_values(fd, 10.0)
        rs = rough.RoughSurface(steel, 1e-4, heights=rough.gaussian_summits(200, 1e-6, seed=1))
        rs.impact(np.array([0.01, 0.1]), 1e-3, unloading=m)
    t = fastrest.load_table()
    t.e(v, 0.005, 0.33); t.loss(v, 0.005, 0.33); t.omega_m(v, 0.005, 0.33); t.W_star(10.0, 0.005, 0.33); t.loading_energy(10.0, 0.005, 0.33)
    t.measure_error((np.array([5.0]), np.array([0.005]), np.array([0.33])))
    fastrest.P_star(10.0, 0.005, 0.33); fastrest.A_star(10.0, 0.005, 0.33); fastrest.W_star(10.0, 0.005, 0.33)
    fastrest.loading_energy(10.0, 0.005, 0.33); fastrest.omega_star_limit(0.005, 0.33)
    fastrest.limit(0.005, 0.33); fastrest.limit(0.005, 0.33, "jcg", extrapolate=True)
    fastrest.poisson_factor(0.3); fastrest.critical_velocity_ratios(0.3)
    for name in models.MODELS:
        with np.errstate(all="ignore"):
            try:
                models.evaluate(name, fastrest.Impact(steel, 0.01), np.array([0.01, 0.1]))
            except ValueError:
                pass

    @numba.njit
    def loop(cd, sd, td, ld, state):
        return (frj.e_curve(cd, 5.0) + frj.e_material(sd, 5.0, 1) + frj.loss_material(sd, 5.0, 0)
                + frj.omega_m_material(sd, 5.0, 0) + frj.e_table(td, 5.0, 0.005, 0.33, frj.JCG)
                + frj.contact_force(ld, state, 1.0))
    law = fastrest.contact_law(0.005, 0.33, w_max=400.0)
    loop(fastrest.curve(0.005, 0.33, v_max=20.0).data, sc.data, t.data, law.data, law.new_state())
    print("ok")
""")


def test_importing_every_module_uses_no_deprecated_name():
    """The default run's check (the main paths below are `slow`: a fresh process compiles them):
    importing every fastrest module with DeprecationWarning as an error raises nothing."""
    import pkgutil
    import importlib.util
    skip = {"fastrest.table_error", "fastrest.__main__"}
    if importlib.util.find_spec("numba_cuda") is None:
        skip.add("fastrest.cuda")   # needs the gpu extra (its ImportError is tested in test_cuda.py)
    names = [m.name for m in pkgutil.walk_packages(fastrest.__path__, "fastrest.") if m.name not in skip]
    code = "import importlib\n" + "".join(f"importlib.import_module({n!r})\n" for n in names) + "print('ok')"
    r = subprocess.run([sys.executable, "-W", "error::DeprecationWarning", "-c", code], capture_output=True, text=True)
    assert r.returncode == 0 and r.stdout.strip().endswith("ok"), r.stderr[-3000:]


@pytest.mark.slow
def test_main_paths_use_no_deprecated_name():
    """Importing fastrest and running its main paths with DeprecationWarning as an error raises
    nothing: fastrest uses none of its own deprecated names (a fresh process: nothing cached)."""
    r = subprocess.run([sys.executable, "-c", MAIN_PATHS], capture_output=True, text=True)
    assert r.returncode == 0 and r.stdout.strip().endswith("ok"), r.stderr[-3000:]
