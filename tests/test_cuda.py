"""fastrest on the GPU without a GPU: :mod:`fastrest.cuda` under Numba's CUDA simulator, its
kernels compiled to PTX, its import error, the GPU DEM example and ``python -m bench.gpu``.

The simulator runs each kernel thread in Python and calls fastrest's jit functions as compiled CPU
code: it checks the plumbing (indices, lengths, NaN, state rows, argument checks) against the CPU's
numbers bit for bit, not the GPU's arithmetic (``python -m bench.gpu`` on a GPU does that). It must
be switched on before numba.cuda is imported, so those checks run in a subprocess. PTX
compilation needs no GPU either: numba-cuda 0.30 still asks the driver for the current device's
compute capability when it compiles a nested device function, so the PTX subprocess answers that
query with the target's (9, 0) (a compile-time query only; nothing runs).
"""
import json
import os
import subprocess
import sys
import textwrap
import time
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]

try:
    import numba_cuda  # noqa: F401
    HAVE_NUMBA_CUDA = True
except ImportError:
    HAVE_NUMBA_CUDA = False

pytestmark = pytest.mark.cuda
needs_numba_cuda = pytest.mark.skipif(
    not HAVE_NUMBA_CUDA, reason='numba-cuda is not installed (pip install "fastrest[gpu]"): the simulator and '
                                "PTX checks need it")


def _run(code, *, sim=True, args=None, timeout=600):
    env = dict(os.environ)
    env.pop("NUMBA_ENABLE_CUDASIM", None)
    if sim:
        env["NUMBA_ENABLE_CUDASIM"] = "1"
    cmd = [sys.executable] + (args if args is not None else ["-c", textwrap.dedent(code)])
    return subprocess.run(cmd, capture_output=True, text=True, cwd=ROOT, env=env, timeout=timeout)


def _json(r):
    assert r.returncode == 0, r.stdout[-3000:] + r.stderr[-3000:]
    return json.loads(r.stdout.strip().splitlines()[-1])


# --- import ------------------------------------------------------------------------------------

def test_import_error_names_the_gpu_extra():
    """Without numba-cuda, ``import fastrest`` works and ``import fastrest.cuda`` names the extra."""
    r = _run("""
        import sys
        sys.modules["numba_cuda"] = None   # numba-cuda not installed ...
        sys.modules["numba.cuda"] = None   # ... and numba's own CUDA target unusable
        import fastrest
        assert "numba_cuda" not in sys.modules or sys.modules["numba_cuda"] is None
        try:
            import fastrest.cuda
        except ImportError as e:
            print(str(e))
        else:
            print("imported")
    """, sim=False)
    assert r.returncode == 0, r.stderr[-3000:]
    assert 'pip install "fastrest[gpu]"' in r.stdout, r.stdout


def test_import_fastrest_does_not_import_numba_cuda():
    r = _run("import sys, fastrest, fastrest.jit; print('numba_cuda' in sys.modules)", sim=False)
    assert r.returncode == 0 and r.stdout.strip() == "False", r.stdout + r.stderr[-2000:]


# --- the simulator: the CPU's numbers, bit for bit ------------------------------------------------

SIMULATOR_CHECKS = """
import json, math
import numpy as np
import fastrest, fastrest.cuda as fc
from fastrest import jit as frj
from fastrest.force_law import stack_laws
from numba import cuda
assert fc.SIMULATOR

rng = np.random.default_rng(3)
res = {}

def same(a, b):
    a, b = np.asarray(a), np.asarray(b)
    return bool(a.shape == b.shape and np.array_equal(a.view(np.int64), b.view(np.int64)))

# speeds across the domain, its edges and outside it (negative, NaN, inf, past v_max)
v = np.concatenate([rng.uniform(0.0, 120.0, 40), [0.0, 1.0, np.nextafter(1.0, 2.0), 1.9**1.25, 100.0,
                    np.nextafter(100.0, 200.0), -1.0, np.nan, np.inf, -0.0]])
dv = fc.to_device(v)

curve = fastrest.curve(0.005, 0.33, "etsion", v_max=100.0)
dc = fc.to_device(curve)
for name in ("omega_m_curve", "e_curve", "loss_curve"):
    cpu = np.array([getattr(frj, name)(curve.data, x) for x in v])
    res[name] = same(getattr(fc, name)(dc, dv).copy_to_host(), cpu)
out = cuda.device_array(v.size)
res["out_returned"] = fc.e_curve(dc, dv, out) is out
res["nan_where_cpu_nan"] = bool(np.array_equal(np.isnan(out.copy_to_host()),
                                               np.isnan([frj.e_curve(curve.data, x) for x in v])))

scene = fastrest.scene([(0.005, 0.33), (0.001, 0.25), (0.0008, 0.3)], v_max=[100.0, 300.0, 50.0])
ds = fc.to_device(scene)
k = np.concatenate([rng.integers(0, 3, v.size - 4), [-1, 3, 2, 0]])
for dtype in (np.int64, np.int32):
    dk = fc.to_device(k.astype(dtype))
    for name in ("omega_m_material", "e_material", "loss_material"):
        cpu = np.array([getattr(frj, name)(scene.data, x, int(m)) for x, m in zip(v, k)])
        res[f"{name}_{np.dtype(dtype).name}"] = same(getattr(fc, name)(ds, dv, dk).copy_to_host(), cpu)

tab = fastrest.load_table()
dt = fc.to_device(tab)
n = 24
vt = np.concatenate([rng.uniform(0.0, 150.0, n - 4), [-1.0, np.nan, 10.0, 10.0]])
eps = np.concatenate([rng.uniform(0.0005, 0.01, n - 2), [0.05, 0.005]])
nus = np.concatenate([rng.uniform(0.2, 0.45, n - 1), [0.6]])
dvt, deps, dnu = fc.to_device(vt), fc.to_device(eps), fc.to_device(nus)
cpu = np.array([frj.omega_m_table(tab.data, a, b, c) for a, b, c in zip(vt, eps, nus)])
res["omega_m_table"] = same(fc.omega_m_table(dt, dvt, deps, dnu).copy_to_host(), cpu)
for code in (frj.JCG, frj.ETSION, frj.BRAKE, 7):
    for name in ("e_table", "loss_table"):
        cpu = np.array([getattr(frj, name)(tab.data, a, b, c, code) for a, b, c in zip(vt, eps, nus)])
        res[f"{name}_{code}"] = same(getattr(fc, name)(dt, dvt, deps, dnu, code).copy_to_host(), cpu)

# contact force: a load-unload-reload path of 8 contacts, the CPU's force and state at every step
law = fastrest.contact_law(0.004, 0.3, w_max=60.0)
dl = fc.to_device(law)
steps = np.concatenate([np.linspace(0.0, 50.0, 6), np.linspace(50.0, 0.0, 6), np.linspace(0.0, 58.0, 4), [70.0, np.nan]])
paths = np.stack([steps * s for s in np.linspace(0.1, 1.0, 8)], 1)  # (step, contact)
state_cpu = np.zeros((8, frj.STATE_SIZE))
state = fc.new_state(8)
ok = True
for w in paths:
    cpu = np.array([frj.contact_force(law.data, state_cpu[i], w[i]) for i in range(8)])
    ok &= same(fc.contact_force(dl, state, fc.to_device(w)).copy_to_host(), cpu)
    ok &= same(state.copy_to_host(), state_cpu)
res["contact_force"] = bool(ok)

laws = stack_laws([fastrest.contact_law(0.005, 0.33), fastrest.contact_law(0.002, 0.3, "etsion")])
dls = fc.to_device(laws)
kk = np.array([0, 1, 1, 0, 2, -1])
state_cpu = np.zeros((6, frj.STATE_SIZE))
state = fc.new_state(6)
ok = True
for s in (10.0, 30.0, 20.0, 0.0):
    w = s * np.linspace(0.5, 1.0, 6)
    cpu = np.array([frj.contact_force_stacked(laws, kk[i], state_cpu[i], w[i]) for i in range(6)])
    ok &= same(fc.contact_force_stacked(dls, fc.to_device(kk), state, fc.to_device(w)).copy_to_host(), cpu)
    ok &= same(state.copy_to_host(), state_cpu)
res["contact_force_stacked"] = bool(ok)
res["empty"] = fc.e_curve(dc, fc.to_device(np.empty(0))).shape == (0,)

# bad input: (call, exception type, words the message must hold)
f32 = fc.to_device(v.astype(np.float32))
def call(f):
    try:
        f()
    except Exception as e:
        return [type(e).__name__, str(e)]
    return ["no error", ""]
bad = {
    "host_v1_star": (lambda: fc.e_curve(dc, v), "TypeError", ["v1_star", "host"]),
    "host_data": (lambda: fc.e_curve(curve.data, dv), "TypeError", ["data", "to_device"]),
    "curve_object": (lambda: fc.e_curve(curve, dv), "TypeError", ["data", "CurveData"]),
    "scene_for_curve": (lambda: fc.e_curve(ds, dv), "TypeError", ["data", "CurveData"]),
    "float32": (lambda: fc.e_curve(dc, f32), "TypeError", ["v1_star", "float64"]),
    "two_d": (lambda: fc.e_curve(dc, fc.to_device(np.zeros((2, 2)))), "ValueError", ["v1_star", "1-D"]),
    "out_length": (lambda: fc.e_curve(dc, dv, cuda.device_array(3)), "ValueError", ["out", "length"]),
    "out_host": (lambda: fc.e_curve(dc, dv, np.empty(v.size)), "TypeError", ["out", "host"]),
    "material_float": (lambda: fc.e_material(ds, dv, dv), "TypeError", ["material", "integer"]),
    "material_length": (lambda: fc.e_material(ds, dv, fc.to_device(k[:3])), "ValueError", ["material", "length"]),
    "material_host": (lambda: fc.e_material(ds, dv, k), "TypeError", ["material", "host"]),
    "nu_length": (lambda: fc.e_table(dt, dvt, deps, dnu[:2]), "ValueError", ["nu", "length"]),
    "unloading": (lambda: fc.e_table(dt, dvt, deps, dnu, 1.5), "TypeError", ["unloading"]),
    "table_host": (lambda: fc.e_table(tab.data, dvt, deps, dnu), "TypeError", ["tab", "to_device"]),
    "state_shape": (lambda: fc.contact_force(dl, fc.new_state(3), fc.to_device(np.zeros(4))), "ValueError", ["state", "(4, 4)"]),
    "state_host": (lambda: fc.contact_force(dl, np.zeros((4, 4)), fc.to_device(np.zeros(4))), "TypeError", ["state", "host"]),
    "law_host": (lambda: fc.contact_force(law.data, fc.new_state(4), fc.to_device(np.zeros(4))), "TypeError", ["data", "to_device"]),
    "stacked_for_law": (lambda: fc.contact_force(dls, fc.new_state(4), fc.to_device(np.zeros(4))), "TypeError", ["law"]),
    "new_state": (lambda: fc.new_state(-1), "ValueError", ["n"]),
    "to_device": (lambda: fc.to_device("curve"), "TypeError", ["to_device", "str"]),
}
res["bad"] = {key: call(f) + [t, words] for key, (f, t, words) in bad.items()}

import doctest
import fastrest.cuda._batch, fastrest.cuda._device, fastrest.cuda._rough
res["doctest"] = [0, 0]
for m in (fastrest.cuda._device, fastrest.cuda._batch, fastrest.cuda._rough):   # where the examples live
    r = doctest.testmod(m, optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE)
    res["doctest"] = [res["doctest"][0] + r.attempted, res["doctest"][1] + r.failed]
print(json.dumps(res))
"""


@pytest.fixture(scope="module")
def simulated():
    if not HAVE_NUMBA_CUDA:
        pytest.skip('numba-cuda is not installed (pip install "fastrest[gpu]")')
    return _json(_run(SIMULATOR_CHECKS))


@needs_numba_cuda
@pytest.mark.parametrize("name", ["omega_m_curve", "e_curve", "loss_curve", "out_returned", "nan_where_cpu_nan",
                                  "omega_m_material_int64", "e_material_int64", "loss_material_int64",
                                  "omega_m_material_int32", "e_material_int32", "loss_material_int32", "empty"])
def test_simulator_curves_and_scenes_equal_cpu(simulated, name):
    assert simulated[name] is True


@needs_numba_cuda
@pytest.mark.parametrize("name", ["omega_m_table", "e_table_0", "loss_table_0", "e_table_1", "loss_table_1",
                                  "e_table_2", "loss_table_2", "e_table_7", "loss_table_7"])
def test_simulator_tables_equal_cpu(simulated, name):
    assert simulated[name] is True


@needs_numba_cuda
@pytest.mark.parametrize("name", ["contact_force", "contact_force_stacked"])
def test_simulator_contact_force_and_state_equal_cpu(simulated, name):
    assert simulated[name] is True


@needs_numba_cuda
def test_bad_input_names_the_argument(simulated):
    wrong = {key: got for key, got in simulated["bad"].items()
             if got[0] != got[2] or not all(w in got[1] for w in got[3])}
    assert not wrong, json.dumps(wrong, indent=1)


@needs_numba_cuda
def test_docstring_examples_run_under_the_simulator(simulated):
    attempted, failed = simulated["doctest"]
    assert attempted > 30 and failed == 0


# --- PTX: the kernels compile for the GPU (no GPU needed) ----------------------------------------

PTX_CHECKS = """
import json, sys, types
import numba
from numba import cuda
import numba.cuda.dispatcher as dispatcher
# numba-cuda 0.30 asks the driver for the current device when compiling a nested device function
dispatcher.get_current_device = lambda: types.SimpleNamespace(compute_capability=(9, 0))
import fastrest
from fastrest import jit as frj
from fastrest.cuda._device import _kernel_function
from fastrest.force_law import stack_laws
f8, st = numba.float64[::1], numba.float64[:, ::1]
T = numba.typeof
data = {"curve": T(fastrest.curve(0.005, 0.33, v_max=100.0).data),
        "scene": T(fastrest.scene([(0.005, 0.33), (0.001, 0.25)], v_max=300.0).data),
        "law": T(fastrest.contact_law(0.005, 0.33).data),
        "laws": T(stack_laws([fastrest.contact_law(0.005, 0.33), fastrest.contact_law(0.002, 0.3)]))}
if "tables" in sys.argv:
    data["table"] = T(fastrest.load_table().data)
cases = {"e_curve": ("point", ("curve", f8, f8)), "loss_curve": ("point", ("curve", f8, f8)),
         "e_material": ("material", ("scene", f8, numba.int32[::1], f8)),
         "contact_force": ("contact", ("law", st, f8, f8)),
         "contact_force_stacked": ("stacked", ("laws", numba.int64[::1], st, f8, f8)),
         "omega_m_table": ("table", ("table", f8, f8, f8, f8)),
         "e_table": ("table_model", ("table", f8, f8, f8, numba.int64, f8))}
res = {}
for name, (shape, sig) in cases.items():
    if sig[0] not in data:
        continue
    try:
        ptx, _ = cuda.compile_ptx(_kernel_function(getattr(frj, name), shape), (data[sig[0]],) + sig[1:], cc=(9, 0))
        res[name] = "ok" if ".entry" in ptx else "no entry"
    except Exception as e:
        res[name] = f"{type(e).__name__}: {str(e)[:300]}"
# the GPU DEM example's step kernel and bench.gpu's DEM steps (contact law and Hertz)
sys.path.insert(0, "docs/examples")
import dem_gpu
import bench.gpu as bench_gpu
bench_gpu.cuda = cuda
step_law, step_hertz = bench_gpu._dem_kernels()
i8 = numba.int64[::1]
extra = {"dem_gpu.advance": (dem_gpu.advance, (data["law"], f8, f8, f8, st, f8, f8, f8, f8, numba.float64, numba.int64,
                                               f8, i8, i8)),
         "bench.gpu step_law": (step_law, (data["law"], f8, f8, f8, st, f8, f8, f8, numba.float64)),
         "bench.gpu step_hertz": (step_hertz, (f8,) * 6 + (numba.float64,))}
for name, (kernel, sig) in extra.items():
    try:
        ptx, _ = cuda.compile_ptx(kernel.py_func, sig, cc=(9, 0))
        res[name] = "ok" if ".entry" in ptx else "no entry"
    except Exception as e:
        res[name] = f"{type(e).__name__}: {str(e)[:300]}"
print(json.dumps(res))
"""


@needs_numba_cuda
def test_kernels_compile_to_ptx():
    res = _json(_run(PTX_CHECKS, sim=False))
    assert res and all(v == "ok" for v in res.values()), res


@needs_numba_cuda
@pytest.mark.slow
def test_table_kernels_compile_to_ptx():
    res = _json(_run(None, sim=False, args=["-c", textwrap.dedent(PTX_CHECKS), "tables"]))
    assert res.get("e_table") == "ok" and res.get("omega_m_table") == "ok", res


# --- the GPU DEM example and bench.gpu: the scripts themselves, under the simulator ---------------

@needs_numba_cuda
def test_dem_gpu_example_under_the_simulator():
    t0 = time.perf_counter()
    r = _run(None, sim=False, args=[str(ROOT / "docs" / "examples" / "dem_gpu.py"), "--simulate", "--n", "100"])
    assert r.returncode == 0, r.stdout[-3000:] + r.stderr[-3000:]
    assert "rebound e vs Curve.e" in r.stdout, r.stdout
    assert time.perf_counter() - t0 < 60


@needs_numba_cuda
def test_bench_gpu_without_a_gpu_exits_2():
    r = _run(None, sim=False, args=["-m", "bench.gpu", "--output", os.devnull])
    if r.returncode == 0:
        pytest.skip("this machine has a GPU: bench.gpu ran for real")
    assert r.returncode == 2, r.stdout[-2000:] + r.stderr[-2000:]
    assert "no CUDA GPU" in r.stdout + r.stderr


@needs_numba_cuda
@pytest.mark.slow
def test_bench_gpu_script_under_the_simulator(tmp_path):
    """~25 s: the simulator runs every kernel of the script on 64 points, and numba compiles the CPU loops."""
    out = tmp_path / "GPU.md"
    r = _run(None, sim=False, args=["-m", "bench.gpu", "--simulate", "--output", str(out)])
    assert r.returncode == 0, r.stdout[-3000:] + r.stderr[-3000:]
    text = out.read_text()
    assert "simulator" in text and "e_curve" in text and "contact_force" in text


# --- rough surfaces: explicit summits, the sums on the device --------------------------------------

ROUGH_CHECKS = """
import json, math
import numpy as np
import fastrest, fastrest.cuda as fc
from fastrest import rough
assert fc.SIMULATOR
rng = np.random.default_rng(22)
mat = fastrest.Material(200e9, 0.3, 1e9)
s = rough.RoughSurface(mat, 1e-4, heights=rng.normal(0.0, 3e-8, 60))
res = {"worst": {}, "counts": True, "scalar": None, "bad": {}}
v = np.array([0.01, 1.0])  # tallest summits near the onset / every summit in contact, most yielded
# the same heights with each summit its own radius (30 um to 300 um)
sr = rough.RoughSurface(mat, heights=s.heights, radii=np.exp(rng.uniform(np.log(3e-5), np.log(3e-4), 60)))
for name, surf, v in (("one radius", s, v), ("radii", sr, np.array([0.01, 0.3]))):
    for unloading in ("jcg", "etsion", "brake"):
        g, c = fc.rough_impact(surf, v, 1e-3, unloading), surf.impact(v, 1e-3, unloading)
        assert type(g) is type(c) and g.unloading == unloading and g.kind == "explicit"
        for f in ("e", "loss", "d_min", "force_max", "dissipated", "w_star_max", "V1_star", "energy_in"):
            a, b = np.asarray(getattr(g, f)), np.asarray(getattr(c, f))
            res["worst"][f"{name} {unloading} {f}"] = float(np.max(np.abs(a - b) / np.abs(b)))
        res["counts"] &= bool(np.array_equal(g.n_contact, c.n_contact) and np.array_equal(g.n_yielded, c.n_yielded)
                              and np.all(c.n_contact > 0) and np.any(c.n_yielded > 0))
g = fc.rough_impact(s, 0.3, 1e-3)
res["scalar"] = [type(g.e).__name__, abs(g.e - s.impact(0.3, 1e-3).e)]

def err(fn):
    try:
        fn()
    except Exception as e:
        return [type(e).__name__, str(e)]
    return ["no error", ""]

gw = rough.RoughSurface(mat, 1e-4, gw=dict(eta=1e10, sigma=1e-7, A_n=1e-8))
res["bad"]["statistical"] = err(lambda: fc.rough_impact(gw, 0.1, 1e-3))
res["bad"]["not a surface"] = err(lambda: fc.rough_impact(np.zeros(5), 0.1, 1e-3))
res["bad"]["device V1"] = err(lambda: fc.rough_impact(s, fc.to_device(np.array([0.1])), 1e-3))
res["bad"]["V1 <= 0"] = err(lambda: fc.rough_impact(s, [0.1, -1.0], 1e-3))
res["bad"]["unloading"] = err(lambda: fc.rough_impact(s, 0.1, 1e-3, "nope"))
print(json.dumps(res))
"""


@pytest.fixture(scope="module")
def rough_simulated():
    if not HAVE_NUMBA_CUDA:
        pytest.skip('numba-cuda is not installed (pip install "fastrest[gpu]")')
    t0 = time.perf_counter()
    res = _json(_run(ROUGH_CHECKS))
    res["seconds"] = time.perf_counter() - t0
    return res


@needs_numba_cuda
def test_rough_impact_equals_cpu_under_the_simulator(rough_simulated):
    """60 summits of one radius and of their own radii, 2 speeds, each unloading model: the CPU path
    to its stated accuracy (docs/rough.md, 1e-12 relative and better); measured ~2e-15 (only the
    summation order differs)."""
    worst = rough_simulated["worst"]
    assert len(worst) == 48 and max(worst.values()) < 1e-13, worst
    assert rough_simulated["counts"] is True
    kind, diff = rough_simulated["scalar"]
    assert kind == "float" and diff < 1e-13


@needs_numba_cuda
def test_rough_impact_bad_input(rough_simulated):
    bad = rough_simulated["bad"]
    expect = {"statistical": ("TypeError", "explicit"), "not a surface": ("TypeError", "RoughSurface"),
              "device V1": ("TypeError", "device array"), "V1 <= 0": ("ValueError", "V1"),
              "unloading": ("ValueError", "nope")}
    wrong = {k: bad[k] for k, (typ, word) in expect.items() if bad[k][0] != typ or word not in bad[k][1]}
    assert not wrong, wrong


ROUGH_PTX = """
import json, types
import numba
from numba import cuda
import numba.cuda.dispatcher as dispatcher
dispatcher.get_current_device = lambda: types.SimpleNamespace(compute_capability=(9, 0))
import fastrest.cuda as fc
import fastrest.cuda._rough as fcr
from fastrest import forward
law = numba.typeof(forward.forward_data(0.005, 0.3, "brake", w_max=40.0))
f8, part = numba.float64[::1], numba.float64[:, ::1]
res = {}
for kind, lt in (("hertz", numba.float64), ("jg", law), ("impact", law)):
    try:
        ptx, _ = cuda.compile_ptx(fcr._rough_kernel_function(fcr._ROUGH_ROWS[kind]),
                                  (lt, f8, f8, numba.boolean, numba.float64, numba.float64, numba.boolean, part),
                                  cc=(9, 0))
        res[kind] = "ok" if ".entry" in ptx else "no entry"
    except Exception as e:
        res[kind] = f"{type(e).__name__}: {str(e)[:300]}"
print(json.dumps(res))
"""


@needs_numba_cuda
def test_rough_kernels_compile_to_ptx():
    res = _json(_run(ROUGH_PTX, sim=False))
    assert res == {"hertz": "ok", "jg": "ok", "impact": "ok"}, res
