"""Every ``fastrest.jit`` function inside a user's ``numba.cuda.jit`` kernel, without a GPU.

* ``test_compiles_to_ptx``: one kernel per function (float64 arrays in and out; the data as an
  argument) compiles to PTX for sm_90 from the same Python source as on the CPU, and the LLVM IR
  fastrest hands to NVVM has no product feeding an addition: NVVM and ptxas would fuse such a pair
  into one fused multiply-add and round differently from the CPU (``fastrest._jit.mul_rn``).
* ``test_simulator_gives_cpu_numbers`` (also ``slow``): the same kernels under Numba's CUDA
  simulator (``NUMBA_ENABLE_CUDASIM=1``, in a child process: it must be set before numba.cuda is
  imported) give the CPU's numbers bit for bit. The simulator runs the jit functions as the CPU's
  compiled code, so this checks the kernels' plumbing (data as kernel arguments, per-contact state
  rows updated in place over a load-unload-reload path), not the GPU's arithmetic: that is
  ``python -m bench.gpu`` on a GPU (libdevice's exp/log/pow differ from the CPU's libm by an ulp).

The driver query: numba-cuda 0.30 compiles a nested device function (every fastrest function a
kernel calls) with the compute capability of the current device (``CUDADispatcher.compile_device``
-> ``get_current_device()``), which raises CudaSupportError without a driver although generating
PTX needs none. The tests replace that one query, in the test only (``monkeypatch``), by the compute
capability they compile for (``CC``, the same as ``compile_ptx``'s), so kernel and device
functions target one architecture; on a machine with a GPU the result is the same PTX.

Skipped, with the reason, when numba-cuda is not installed (``pip install -e ".[gpu]"``); run with
``pytest -m cuda`` (add ``-m "cuda and slow"`` for the simulator).
"""
import importlib.util
import json
import os
import re
import subprocess
import sys
import types

import numpy as np
import pytest

HAVE_NUMBA_CUDA = importlib.util.find_spec("numba_cuda") is not None
pytestmark = [pytest.mark.cuda,
              pytest.mark.skipif(not HAVE_NUMBA_CUDA,
                                 reason='numba-cuda is not installed (pip install -e ".[gpu]")')]

CC = (9, 0)  # sm_90 (H100/H200)
N = 64  # points (threads) per kernel in the simulator


# --- the kernels: one per fastrest.jit function, written as a user would --------------------------
# ``fn`` is bound as a global of each kernel (numba.cuda resolves it at compile time).

def _kernel(src, fn):
    namespace = {"fn": fn}
    exec(src, namespace)  # noqa: S102 - test kernels from the fixed templates below
    return namespace["kernel"]


_ONE = """
def kernel(a, out):
    i = cuda.grid(1)
    if i < out.size:
        out[i] = fn(a[i])
"""
_DATA_1 = """
def kernel(d, a, out):
    i = cuda.grid(1)
    if i < out.size:
        out[i] = fn(d, a[i])
"""
_DATA_2 = """
def kernel(d, a, b, out):
    i = cuda.grid(1)
    if i < out.size:
        out[i] = fn(d, a[i], b[i])
"""
_DATA_3 = """
def kernel(d, a, b, c, out):
    i = cuda.grid(1)
    if i < out.size:
        out[i] = fn(d, a[i], b[i], c[i])
"""
_DATA_4 = """
def kernel(d, a, b, c, e, out):
    i = cuda.grid(1)
    if i < out.size:
        out[i] = fn(d, a[i], b[i], c[i], e[i])
"""
_FORCE = """
def kernel(law, state, w, out):
    i = cuda.grid(1)
    if i < out.size:
        out[i] = fn(law, state[i], w[i])
"""
_FORCE_STACKED = """
def kernel(laws, material, state, w, out):
    i = cuda.grid(1)
    if i < out.size:
        out[i] = fn(laws, material[i], state[i], w[i])
"""
_DISSIPATED = """
def kernel(law, state, out):
    i = cuda.grid(1)
    if i < out.size:
        out[i] = fn(law, state[i])
"""
_DISSIPATED_STACKED = """
def kernel(laws, material, state, out):
    i = cuda.grid(1)
    if i < out.size:
        out[i] = fn(laws, material[i], state[i])
"""
_ET_RATIO = """
def kernel(p, out):
    i = cuda.grid(1)
    if i < out.size:
        out[i] = fn(p[i, 0], p[i, 1], p[i, 2], p[i, 3], p[i, 4], p[i, 5], p[i, 6], p[i, 7])
"""
_SCALES = """
def kernel(p, out):
    i = cuda.grid(1)
    if i < out.shape[0]:
        s = fn(p[i, 0], p[i, 1], p[i, 2], p[i, 3], p[i, 4], p[i, 5], p[i, 6], p[i, 7], p[i, 8], p[i, 9])
        for j in range(12):
            out[i, j] = s[j]
"""

#: fastrest.jit function -> (kernel template, the data it takes: None, "curve", "scene", "table",
#: "law", "laws"). A function added to fastrest.jit.__all__ needs a line here (test_every_function_has_a_kernel).
KERNELS = {
    "omega_m_curve": (_DATA_1, "curve"), "e_curve": (_DATA_1, "curve"), "loss_curve": (_DATA_1, "curve"),
    "omega_m_material": (_DATA_2, "scene"), "e_material": (_DATA_2, "scene"),
    "loss_material": (_DATA_2, "scene"),
    "omega_m_table": (_DATA_3, "table"), "e_table": (_DATA_4, "table"), "loss_table": (_DATA_4, "table"),
    "contact_force": (_FORCE, "law"), "contact_force_stacked": (_FORCE_STACKED, "laws"),
    "hertz_contact_time": (_ONE, None), "critical_scales": (_SCALES, None),
    "dissipated_energy": (_DISSIPATED, "law"), "dissipated_energy_stacked": (_DISSIPATED_STACKED, "laws"),
    "yield_et_ratio": (_ET_RATIO, None),
}


def _data():
    import fastrest
    from fastrest.force_law import stack_laws
    laws = [fastrest.contact_law(0.005, 0.33, w_max=30.0), fastrest.contact_law(0.002, 0.3, "etsion", w_max=30.0),
            fastrest.contact_law(0.004, 0.3, "brake", w_max=30.0, et_ratio=0.05)]  # strain hardening
    return {"curve": fastrest.curve(0.005, 0.33, v_max=50.0).data,
            "scene": fastrest.scene([(0.005, 0.33), (0.002, 0.3)], "brake", v_max=[50.0, 40.0]).data,
            "table": fastrest.load_table().data, "law": laws[0].data, "laws": stack_laws(laws)}


def _inputs(name, data):
    """The kernel's arguments (all but ``out``) on N points, and ``out``: float64 arrays."""
    rng = np.random.default_rng(22)
    v = np.concatenate([[0.0, 0.5, 1.0, 1.5, 2.2, -1.0, np.nan, 1e9], np.geomspace(1.01, 45.0, N - 8)])
    template, which = KERNELS[name]
    d = data[which] if which else None
    if template is _ONE:
        return (v,), np.empty(N)
    if which in ("curve",):
        return (d, v), np.empty(N)
    if which == "scene":
        return (d, v, (np.arange(N) % 3).astype(float)), np.empty(N)  # material 2: none (NaN)
    if which == "table":
        eps = rng.uniform(0.0005, 0.01, N)
        nu = rng.uniform(0.2, 0.45, N)
        if template is _DATA_3:
            return (d, v, eps, nu), np.empty(N)
        return (d, v, eps, nu, (np.arange(N) % 4).astype(float)), np.empty(N)  # model 3: none (NaN)
    if template in (_DISSIPATED, _DISSIPATED_STACKED):  # histories: loaded to w_max, unloaded; and bad rows
        import fastrest
        material = (np.arange(N) % 4).astype(float)  # material 3: none (NaN)
        states = np.zeros((N, 4))
        w_max = np.concatenate([[0.0, 0.5, 1.0, 1.5, 2.2, 1.9], np.geomspace(1.01, 29.0, N - 6)])
        for i in range(N):
            for w in (w_max[i], 0.5 * w_max[i]):  # loading, then unloading (sets w_res*, delta)
                if template is _DISSIPATED_STACKED:
                    fastrest.jit.contact_force_stacked(d, material[i], states[i], w)
                else:
                    fastrest.jit.contact_force(d, states[i], w)
        states[-1] = np.nan
        states[-2, 0] = -1.0
        if template is _DISSIPATED:
            return (d, states), np.empty(N)
        return (d, material, states), np.empty(N)
    if template is _ET_RATIO:
        inf = np.inf  # steel on a rigid flat, on aluminium (which yields first) either way round, Et = E, invalid
        rows = [[200e9, 0.3, 1e9, 2e9, inf, 0.0, inf, 0.0], [200e9, 0.3, 1e9, 2e9, 70e9, 0.33, 0.28e9, 0.7e9],
                [70e9, 0.33, 0.28e9, 0.7e9, 200e9, 0.3, 1e9, 2e9], [200e9, 0.3, 1e9, 200e9, inf, 0.0, inf, 0.0],
                [-1.0] * 8]
        return (np.array([rows[k % 5] for k in range(N)], float) * (1.0 + 1e-3 * (np.arange(N) // 5))[:, None],), \
            np.empty(N)
    if which == "law":
        return (d, np.zeros((N, 4)), np.zeros(N)), np.empty(N)
    if which == "laws":
        return (d, (np.arange(N) % 3).astype(float), np.zeros((N, 4)), np.zeros(N)), np.empty(N)
    inf = np.inf  # critical_scales: a steel sphere on a rigid flat, on steel, and invalid rows
    rows = [[200e9, 0.33, 1.12e9, 0.01, 0.0327, inf, 0.0, inf, inf, inf],
            [200e9, 0.33, 1.12e9, 0.01, 0.0327, 70e9, 0.3, 2.8e8, 0.02, 0.1],
            [200e9, 0.33, inf, 0.01, 0.0327, inf, 0.0, inf, inf, inf], [-1.0] * 10]
    p = np.array([rows[k % 4] for k in range(N)], float) * (1.0 + 1e-3 * (np.arange(N) // 4))[:, None]
    return (p,), np.empty((N, 12))


# --- PTX for sm_90 ------------------------------------------------------------------------------

@pytest.fixture(scope="module")
def data():
    return _data()


@pytest.fixture
def ptx_compiler(monkeypatch):
    """compile(kernel, args) -> (ptx, [LLVM IR modules handed to NVVM]) for sm_90, without a GPU."""
    from numba import cuda, typeof
    import numba.cuda.cudadrv.nvvm as nvvm
    import numba.cuda.dispatcher as dispatcher

    # numba-cuda asks the driver for the current device when it compiles a nested device function;
    # answer with the compute capability compiled for (module docstring)
    monkeypatch.setattr(dispatcher, "get_current_device", lambda: types.SimpleNamespace(compute_capability=CC))
    modules = []
    compile_ir = nvvm.compile_ir

    def capture(llvmir, **options):
        modules.append(llvmir)
        return compile_ir(llvmir, **options)

    monkeypatch.setattr(nvvm, "compile_ir", capture)

    def compile_(kernel, args):
        modules.clear()
        ptx, _ = cuda.compile_ptx(kernel, tuple(typeof(a) for a in args), cc=CC, device=False)
        return ptx, list(modules)

    return compile_


def _fused_pairs(modules):
    """Products feeding an addition or subtraction in the IR handed to NVVM, after LLVM's own
    optimisation (mem2reg, inlining, ...; no fast-math, so no reassociation): each would become a
    fused multiply-add on CUDA."""
    import llvmlite.binding as llvm
    flat = []
    for m in modules:
        flat.extend(m if isinstance(m, (list, tuple)) else [m])
    mods = [llvm.parse_assembly(m if isinstance(m, str) else m.decode()) for m in flat]
    mod = mods[0]
    for other in mods[1:]:
        mod.link_in(other)
    mod.triple, mod.data_layout = "", ""  # target-independent passes only (no NVPTX in llvmlite)
    llvm.initialize_native_target()
    llvm.initialize_native_asmprinter()
    tm = llvm.Target.from_default_triple().create_target_machine()
    pb = llvm.create_pass_builder(tm, llvm.create_pipeline_tuning_options(speed_level=3))
    pb.getModulePassManager().run(mod, pb)
    text = str(mod)
    dbl = r"(?:double|<\d+ x double>)"
    pairs = []
    # value names are local to a function: a device function LLVM did not inline (a plain @jit one)
    # has its own %.207, which may be a product where the kernel's is not
    for body in re.split(r"\ndefine ", text)[1:]:
        products = set(re.findall(rf"(%[\w.]+) = fmul (?:\w+ )*{dbl}", body))
        for line in body.splitlines():
            m = re.match(rf"\s*%[\w.]+ = f(?:add|sub) (?:\w+ )*{dbl} ([^,]+), ([^,]+)", line)
            if m and {m.group(1).strip(), m.group(2).strip()} & products:
                pairs.append(line.strip())
    return pairs


def test_every_function_has_a_kernel():
    import fastrest.jit as fj
    functions = {n for n in fj.__all__ if callable(getattr(fj, n)) and not isinstance(getattr(fj, n), type)
                 and not hasattr(getattr(fj, n), "_fields")
                 and hasattr(getattr(fj, n), "py_func")}   # stack_laws: Python, called before the loop
    assert functions == set(KERNELS)


@pytest.mark.parametrize("name", sorted(KERNELS))
def test_compiles_to_ptx(name, data, ptx_compiler):
    import fastrest.jit as fj
    kernel = _kernel("from numba import cuda\n" + KERNELS[name][0], getattr(fj, name))
    args, out = _inputs(name, data)
    ptx, modules = ptx_compiler(kernel, (*args, out))
    assert ".visible .entry" in ptx and f".target sm_{CC[0]}{CC[1]}" in ptx
    assert _fused_pairs(modules) == [], f"{name}: a product feeds an addition (use fastrest._jit.mul_rn)"


# --- the CUDA simulator -------------------------------------------------------------------------

def _simulate():
    """In the child process (NUMBA_ENABLE_CUDASIM=1): every kernel against the CPU, as JSON."""
    import numba
    from numba import cuda
    from numba.cuda.simulator.cudadrv.devicearray import FakeCUDAArray, FakeWithinKernelCUDAArray
    import fastrest.jit as fj

    assert cuda.simulator is not None or os.environ.get("NUMBA_ENABLE_CUDASIM") == "1"
    # The simulator runs fastrest's jit functions as the CPU's compiled code, which takes NumPy
    # arrays: hand a row of a kernel's array argument (a contact's state) over as the NumPy view
    # the simulator's wrapper holds (writes go to the same memory, copied back after the launch).
    getitem = FakeWithinKernelCUDAArray.__getitem__

    def row_as_numpy(self, idx):
        item = getitem(self, idx)
        if isinstance(item, FakeWithinKernelCUDAArray):
            item = item._item
        return item._ary if isinstance(item, FakeCUDAArray) else item

    FakeWithinKernelCUDAArray.__getitem__ = row_as_numpy

    data = _data()
    cpu_call = {  # the CPU: the same function in an njit loop
        _ONE: "for i in range(out.size): out[i] = fn(a[i])",
        _DATA_1: "for i in range(out.size): out[i] = fn(d, a[i])",
        _DATA_2: "for i in range(out.size): out[i] = fn(d, a[i], b[i])",
        _DATA_3: "for i in range(out.size): out[i] = fn(d, a[i], b[i], c[i])",
        _DATA_4: "for i in range(out.size): out[i] = fn(d, a[i], b[i], c[i], e[i])",
        _FORCE: "for i in range(out.size): out[i] = fn(law, state[i], w[i])",
        _FORCE_STACKED: "for i in range(out.size): out[i] = fn(laws, material[i], state[i], w[i])",
        _DISSIPATED: "for i in range(out.size): out[i] = fn(law, state[i])",
        _DISSIPATED_STACKED: "for i in range(out.size): out[i] = fn(laws, material[i], state[i])",
        _ET_RATIO: "for i in range(out.size): out[i] = fn(p[i, 0], p[i, 1], p[i, 2], p[i, 3], p[i, 4], p[i, 5], "
                   "p[i, 6], p[i, 7])",
        _SCALES: ("for i in range(out.shape[0]):\n"
                  "        s = fn(p[i, 0], p[i, 1], p[i, 2], p[i, 3], p[i, 4], p[i, 5], p[i, 6], p[i, 7],"
                  " p[i, 8], p[i, 9])\n"
                  "        for j in range(12): out[i, j] = s[j]"),
    }
    report = {}
    for name, (template, _) in sorted(KERNELS.items()):
        fn = getattr(fj, name)
        gpu = cuda.jit(_kernel("from numba import cuda\n" + template, fn))
        header = template.strip().splitlines()[0]
        cpu = numba.njit(_kernel(header + "\n    " + cpu_call[template] + "\n", fn))
        args, out = _inputs(name, data)
        if template in (_FORCE, _FORCE_STACKED):  # a load-unload-reload path, history per contact
            path = np.concatenate([np.linspace(0.0, 20.0, 12), np.linspace(20.0, 2.0, 10),
                                   np.linspace(2.0, 25.0, 10), [0.0]])
            *head, state, w = args
            s_gpu, s_cpu, o_gpu, o_cpu = state.copy(), state.copy(), out.copy(), out.copy()
            worst, same = 0.0, True
            for step in path:
                w = step * (1.0 + np.arange(N) / N)
                gpu[(N + 31) // 32, 32](*head, s_gpu, w, o_gpu)
                cpu(*head, s_cpu, w, o_cpu)
                same &= bool(np.array_equal(o_gpu, o_cpu, equal_nan=True)
                             and np.array_equal(s_gpu, s_cpu, equal_nan=True))
            report[name] = {"identical": same, "points": int(N * path.size)}
            continue
        o_gpu, o_cpu = out.copy(), out.copy()
        gpu[(N + 31) // 32, 32](*args, o_gpu)
        cpu(*args, o_cpu)
        report[name] = {"identical": bool(np.array_equal(o_gpu, o_cpu, equal_nan=True)), "points": N,
                        "finite": int(np.isfinite(o_cpu).sum())}
    return report


@pytest.mark.slow
def test_simulator_gives_cpu_numbers():
    env = dict(os.environ, NUMBA_ENABLE_CUDASIM="1")
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    run = subprocess.run([sys.executable, os.path.abspath(__file__)], env=env, cwd=root, capture_output=True,
                         text=True, timeout=600)
    assert run.returncode == 0, run.stderr[-4000:]
    report = json.loads(run.stdout.strip().splitlines()[-1])
    assert set(report) == set(KERNELS)
    different = {k: v for k, v in report.items() if not v["identical"]}
    assert not different, different
    assert all(v["finite"] > N // 2 for v in report.values() if "finite" in v), report


if __name__ == "__main__":  # the child process of test_simulator_gives_cpu_numbers
    print(json.dumps(_simulate()))
