"""fastrest on a GPU: every jit function against the CPU, and ns per point against the memory floor.

``python -m bench.gpu`` (from the repository root, on a machine with an NVIDIA GPU and
``pip install "fastrest[gpu]"``) writes ``bench/GPU.md`` (``--output``) naming the device and the
date, and prints the same:

1. **Agreement**: each :mod:`fastrest.jit` function called from a ``numba.cuda.jit`` kernel (through
   :mod:`fastrest.cuda` where it has a batch function) on points across its domain and outside it,
   against the same function in an ``@njit`` loop on the CPU: the fraction of results bit-identical,
   the worst relative difference, NaN where the CPU has NaN; or the compile error.
2. **Speed against the floor**, measured in the same run: the device's copy bandwidth (a
   device-to-device copy, bytes read + written per second), and for each kernel the bytes it must
   move per point (its inputs and output) over that bandwidth, the floor; the ratio ns per point /
   floor is checked against the GPU targets: ``e_curve`` <= 2x, ``e_material`` (16 materials)
   <= 3x, ``e_table`` (every point its own material) <= 10x, and ``contact_force`` in a DEM step
   <= 3x the same step with a Hertz force (no history); the exported C header (``fastrest export
   c``) compiled with ``nvcc`` as device code, timed and compared bit for bit with ``Curve.e``
   (skipped, with the reason, where ``nvcc`` is missing or the compile fails).
3. **Rough surfaces**: one impact (:func:`fastrest.cuda.rough_impact`) on explicit surfaces of 1e7
   and 1e8 Gaussian summits, the heights already on the device, against the target (one
   impact on 1e8 summits in under 50 ms), and e against ``RoughSurface.impact`` on the CPU.

Times are the best of several launches, wall-clock around ``cuda.synchronize()`` (sizes large enough
that launch latency is under 1 %). Without a GPU it exits with status 2 and says so;
``--simulate`` runs tiny sizes under Numba's CUDA simulator to check the script itself (its
numbers mean nothing and GPU.md says so).
"""
import argparse
import datetime
import math
import os
import platform
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]

#: The GPU targets: ns per point over the floor (e_*), or over the Hertz step (contact_force).
TARGETS = {"e_curve": 2.0, "e_material": 3.0, "e_table": 10.0, "contact_force": 3.0, "c_header": 2.0}
#: The target for one impact on 1e8 explicit summits (ms).
ROUGH_TARGET_MS = 50.0


def parse(argv):
    p = argparse.ArgumentParser(prog="python -m bench.gpu", description=__doc__.splitlines()[0])
    p.add_argument("--output", default=str(ROOT / "bench" / "GPU.md"), help="report file (default bench/GPU.md)")
    p.add_argument("--simulate", action="store_true",
                   help="tiny sizes under Numba's CUDA simulator: checks the script, measures nothing")
    p.add_argument("--rounds", type=int, default=None, help="timed launches per kernel (best taken; default 10)")
    p.add_argument("--no-header", action="store_true", help="skip the C header (nvcc)")
    return p.parse_args(argv)


ARGS = parse(sys.argv[1:]) if __name__ == "__main__" else None
if ARGS is not None and ARGS.simulate and os.environ.get("NUMBA_ENABLE_CUDASIM") != "1":
    os.environ["NUMBA_ENABLE_CUDASIM"] = "1"  # must be set before numba.cuda is imported
    os.execv(sys.executable, [sys.executable, "-m", "bench.gpu"] + sys.argv[1:])

import numba  # noqa: E402
import numpy as np  # noqa: E402

import fastrest  # noqa: E402
from fastrest import jit as frj  # noqa: E402
from fastrest.force_law import stack_laws  # noqa: E402

STATE_SIZE = frj.STATE_SIZE
#: numba.cuda, set by main() (a module global: the simulator swaps the module its kernels' globals name)
cuda = None


def _no_gpu(message):
    print(f"bench.gpu: {message}", file=sys.stderr)
    sys.exit(2)


# --- measuring ----------------------------------------------------------------------------------

def best_time(fn, rounds):
    """Best wall-clock seconds of ``fn()`` over ``rounds`` runs (after one warm-up run)."""
    fn()
    cuda.synchronize()
    best = math.inf
    for _ in range(rounds):
        t0 = time.perf_counter()
        fn()
        cuda.synchronize()
        best = min(best, time.perf_counter() - t0)
    return best


def copy_bandwidth(nbytes, rounds):
    """Device-to-device copy of ``nbytes``: bytes read + written per second."""
    n = max(1, nbytes // 8)
    src = cuda.to_device(np.ones(n))
    dst = cuda.device_array(n)
    t = best_time(lambda: dst.copy_to_device(src), rounds)
    return 2.0 * 8 * n / t


def compare(gpu, cpu):
    """(fraction bit-identical, worst relative difference where both finite, NaN mismatches)."""
    gpu, cpu = np.asarray(gpu, dtype=np.float64).ravel(), np.asarray(cpu, dtype=np.float64).ravel()
    same = gpu.view(np.int64) == cpu.view(np.int64)
    both_nan = np.isnan(gpu) & np.isnan(cpu)
    nan_mismatch = int(np.sum(np.isnan(gpu) != np.isnan(cpu)))
    ok = np.isfinite(gpu) & np.isfinite(cpu)
    rel = np.abs(gpu[ok] - cpu[ok]) / np.maximum(np.abs(cpu[ok]), 1e-300)
    return float(np.mean(same | both_nan)), float(rel.max()) if rel.size else 0.0, nan_mismatch


# --- kernels (GPU) and loops (CPU) of the same jit functions --------------------------------------

def _cpu_loop(fn, shape):
    if shape == "point":
        def loop(data, v, out):
            for i in range(v.size):
                out[i] = fn(data, v[i])
    elif shape == "material":
        def loop(data, v, k, out):
            for i in range(v.size):
                out[i] = fn(data, v[i], k[i])
    elif shape == "table_model":
        def loop(data, v, a, b, code, out):
            for i in range(v.size):
                out[i] = fn(data, v[i], a[i], b[i], code)
    elif shape == "table":
        def loop(data, v, a, b, out):
            for i in range(v.size):
                out[i] = fn(data, v[i], a[i], b[i])
    elif shape == "contact":
        def loop(data, state, w, out):
            for i in range(w.size):
                out[i] = fn(data, state[i], w[i])
    elif shape == "stacked":
        def loop(data, k, state, w, out):
            for i in range(w.size):
                out[i] = fn(data, k[i], state[i], w[i])
    return numba.njit(loop)


def agreement(fc, n, rng):
    """Rows (function, points, bit-identical fraction, worst rel. difference, NaN mismatches, note)."""
    rows = []

    def row(name, gpu_call, cpu_call, points, note=""):
        try:
            gpu = gpu_call()
        except Exception as e:  # a compile error is a result here
            rows.append((name, points, None, None, None, f"{type(e).__name__}: {str(e).splitlines()[0][:160]}"))
            return
        rows.append((name, points) + compare(gpu, cpu_call()) + (note,))

    v = np.concatenate([np.exp(rng.uniform(-3.0, math.log(120.0), n - 6)), [-1.0, np.nan, np.inf, 0.0, 1.0, 100.0]])
    dv = fc.to_device(v)
    curve = fastrest.curve(0.005, 0.33, v_max=100.0)
    dcurve = fc.to_device(curve)
    for name in ("omega_m_curve", "e_curve", "loss_curve"):
        out = np.empty(n)
        row(name, lambda: getattr(fc, name)(dcurve, dv).copy_to_host(),
            lambda: (_cpu_loop(getattr(frj, name), "point")(curve.data, v, out), out)[1], n)

    scene = _scene(16)
    dscene = fc.to_device(scene)
    k = np.concatenate([rng.integers(0, 16, n - 2), [-1, 16]]).astype(np.int32)
    dk = fc.to_device(k)
    for name in ("omega_m_material", "e_material", "loss_material"):
        out = np.empty(n)
        row(name, lambda: getattr(fc, name)(dscene, dv, dk).copy_to_host(),
            lambda: (_cpu_loop(getattr(frj, name), "material")(scene.data, v, k, out), out)[1], n)

    tab = fastrest.load_table()
    dtab = fc.to_device(tab)
    eps = rng.uniform(0.0005, 0.01, n)
    nus = rng.uniform(0.2, 0.45, n)
    eps[-1] = 0.05  # outside the table
    deps, dnu = fc.to_device(eps), fc.to_device(nus)
    out = np.empty(n)
    row("omega_m_table", lambda: fc.omega_m_table(dtab, dv, deps, dnu).copy_to_host(),
        lambda: (_cpu_loop(frj.omega_m_table, "table")(tab.data, v, eps, nus, out), out)[1], n)
    for name in ("e_table", "loss_table"):
        for code, model in ((frj.JCG, "JCG"), (frj.ETSION, "Etsion")):
            out = np.empty(n)
            row(f"{name} ({model})", lambda: getattr(fc, name)(dtab, dv, deps, dnu, code).copy_to_host(),
                lambda: (_cpu_loop(getattr(frj, name), "table_model")(tab.data, v, eps, nus, code, out), out)[1], n)

    # contact force: every contact on its own load-unload-reload path, all steps compared
    m = max(8, n // 16)
    law = fastrest.contact_law(0.004, 0.3)
    dlaw = fc.to_device(law)
    peak = np.exp(rng.uniform(math.log(0.5), math.log(400.0), m))
    path = np.concatenate([np.linspace(0, 1, 6), np.linspace(1, 0, 6)[1:], np.linspace(0, 1.05, 4)[1:]])
    path = np.minimum(path[:, None] * peak[None, :], 425.0)
    laws = stack_laws([fastrest.contact_law(0.004, 0.3), fastrest.contact_law(0.002, 0.25, "etsion")])
    dlaws = fc.to_device(laws)
    kk = rng.integers(0, 2, m)
    dkk = fc.to_device(kk)
    for name in ("contact_force", "contact_force_stacked"):
        state, state_cpu = fc.new_state(m), np.zeros((m, STATE_SIZE))
        loop = _cpu_loop(getattr(frj, name), "contact" if name == "contact_force" else "stacked")
        gpu_all, cpu_all = [], []
        try:
            for w in path:
                out = np.empty(m)
                dw = fc.to_device(w)
                if name == "contact_force":
                    gpu_all.append(fc.contact_force(dlaw, state, dw).copy_to_host())
                    loop(law.data, state_cpu, w, out)
                else:
                    gpu_all.append(fc.contact_force_stacked(dlaws, dkk, state, dw).copy_to_host())
                    loop(laws, kk, state_cpu, w, out)
                cpu_all.append(out)
            row(name, lambda: np.array(gpu_all), lambda: np.array(cpu_all), m * len(path),
                "load-unload-reload paths; unloading uses pow: libdevice vs libm")
        except Exception as e:
            rows.append((name, m * len(path), None, None, None, f"{type(e).__name__}: {str(e).splitlines()[0][:160]}"))

    out = np.empty(n)
    row("hertz_contact_time", lambda: _launch_scalar(fc, v), lambda: np.array([frj.hertz_contact_time(x) for x in v]),
        n, "pow: libdevice vs libm")
    row("critical_scales (V_c)", lambda: _launch_critical(fc, eps * 200e9),
        lambda: np.array([_critical_cpu(x) for x in eps * 200e9]), n, "pow, sqrt: libdevice vs libm")
    return rows


def _scene(n_materials):
    rng = np.random.default_rng(16)
    mats = list(zip(rng.uniform(0.0005, 0.01, n_materials), rng.uniform(0.2, 0.45, n_materials)))
    return fastrest.scene(mats, v_max=100.0)


_SCALAR_KERNELS = {}


def _launch_scalar(fc, v):
    if "hertz" not in _SCALAR_KERNELS:
        @cuda.jit
        def k(v, out):
            i = cuda.grid(1)
            if i < out.size:
                out[i] = frj.hertz_contact_time(v[i])
        _SCALAR_KERNELS["hertz"] = k
    dv, out = fc.to_device(v), cuda.device_array(v.size)
    _SCALAR_KERNELS["hertz"][(v.size + 255) // 256, 256](dv, out)
    return out.copy_to_host()


def _launch_critical(fc, sy):
    if "critical" not in _SCALAR_KERNELS:
        @cuda.jit
        def k(sy, out):
            i = cuda.grid(1)
            if i < out.size:
                out[i] = frj.critical_scales(200e9, 0.3, sy[i], 1e-3, 3e-5, math.inf, 0.0, math.inf, math.inf,
                                             math.inf).V_c
        _SCALAR_KERNELS["critical"] = k
    dsy, out = fc.to_device(sy), cuda.device_array(sy.size)
    _SCALAR_KERNELS["critical"][(sy.size + 255) // 256, 256](dsy, out)
    return out.copy_to_host()


def _critical_cpu(sy):
    return frj.critical_scales(200e9, 0.3, sy, 1e-3, 3e-5, math.inf, 0.0, math.inf, math.inf, math.inf).V_c


# --- DEM step: contact_force with history against a Hertz force, in the same kernel ----------------

def _dem_kernels():
    @cuda.jit(device=True, inline=True)
    def hertz(w):
        return w * math.sqrt(w) if w > 0.0 else 0.0

    @cuda.jit
    def step_law(law, x, v, a, state, omega_c, P_c, mass, dt):
        i = cuda.grid(1)
        if i < x.size:
            row = cuda.local.array(STATE_SIZE, numba.float64)
            for j in range(STATE_SIZE):
                row[j] = state[i, j]
            xi = x[i] + v[i] * dt + 0.5 * a[i] * dt * dt
            f = P_c[i] * frj.contact_force(law, row, xi / omega_c[i])
            a_new = -f / mass[i]
            v[i] += 0.5 * (a[i] + a_new) * dt
            a[i] = a_new
            x[i] = xi
            for j in range(STATE_SIZE):
                state[i, j] = row[j]

    @cuda.jit
    def step_hertz(x, v, a, omega_c, P_c, mass, dt):
        i = cuda.grid(1)
        if i < x.size:
            xi = x[i] + v[i] * dt + 0.5 * a[i] * dt * dt
            f = P_c[i] * hertz(xi / omega_c[i])
            a_new = -f / mass[i]
            v[i] += 0.5 * (a[i] + a_new) * dt
            a[i] = a_new
            x[i] = xi

    return step_law, step_hertz


# --- the C header under nvcc --------------------------------------------------------------------

HEADER_PROGRAM = r"""
#include <stdio.h>
#include <stdlib.h>
#include <cuda_runtime.h>
#include "fastrest_scene.h"

__global__ void e_kernel(const double *v, double *out, long n)
{
    long i = blockIdx.x * (long)blockDim.x + threadIdx.x;
    if (i < n)
        out[i] = fastrest_e(0, v[i], FASTREST_JCG);
}

int main(int argc, char **argv)
{
    /* usage: prog in.bin out.bin n rounds; prints the best seconds of one launch */
    long n = atol(argv[3]);
    int rounds = atoi(argv[4]);
    double *h = (double *)malloc(n * sizeof(double));
    FILE *f = fopen(argv[1], "rb");
    if (!f || fread(h, sizeof(double), n, f) != (size_t)n) return 3;
    fclose(f);
    double *v, *out;
    if (cudaMalloc(&v, n * sizeof(double)) || cudaMalloc(&out, n * sizeof(double))) return 4;
    cudaMemcpy(v, h, n * sizeof(double), cudaMemcpyHostToDevice);
    int threads = 256;
    long blocks = (n + threads - 1) / threads;
    cudaEvent_t t0, t1;
    cudaEventCreate(&t0);
    cudaEventCreate(&t1);
    e_kernel<<<blocks, threads>>>(v, out, n);
    float best = 1e30f;
    for (int r = 0; r < rounds; r++) {
        cudaEventRecord(t0);
        e_kernel<<<blocks, threads>>>(v, out, n);
        cudaEventRecord(t1);
        cudaEventSynchronize(t1);
        float ms;
        cudaEventElapsedTime(&ms, t0, t1);
        if (ms < best) best = ms;
    }
    if (cudaGetLastError() != cudaSuccess) return 5;
    cudaMemcpy(h, out, n * sizeof(double), cudaMemcpyDeviceToHost);
    f = fopen(argv[2], "wb");
    fwrite(h, sizeof(double), n, f);
    fclose(f);
    printf("%.9g\n", best * 1e-3);
    return 0;
}
"""


def c_header(n, rounds, run, rng):
    """(status, seconds per launch or None, (bit-identical fraction, worst rel.) or None)."""
    nvcc = shutil.which("nvcc")
    if nvcc is None:
        return "skipped: nvcc not found", None, None
    from fastrest.export import c_header as ch
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        ch.write_header(tmp / "fastrest_scene.h", [(0.005, 0.33)], v_max=100.0)
        (tmp / "bench.cu").write_text(HEADER_PROGRAM)
        arch = ["-arch=native"] if run else ["-arch=sm_90", "-c"]
        cmd = [nvcc, "-O3", "-std=c++17", *arch, "bench.cu", "-o", "bench" if run else "bench.o"]
        r = subprocess.run(cmd, cwd=tmp, capture_output=True, text=True)
        if r.returncode != 0:
            return f"nvcc failed: {(r.stderr or r.stdout).strip().splitlines()[-1][:200]}", None, None
        if not run:
            return "compiled as device code (nvcc, sm_90); not run (no GPU)", None, None
        v = np.exp(rng.uniform(0.0, math.log(100.0), n))
        v.tofile(tmp / "in.bin")
        r = subprocess.run([str(tmp / "bench"), "in.bin", "out.bin", str(n), str(rounds)], cwd=tmp,
                           capture_output=True, text=True)
        if r.returncode != 0:
            return f"run failed (exit {r.returncode}): {r.stderr.strip()[:200]}", None, None
        seconds = float(r.stdout.strip().splitlines()[-1])
        out = np.fromfile(tmp / "out.bin")
        cpu = fastrest.curve(0.005, 0.33, v_max=100.0).e(v)
        return "ran", seconds, compare(out, cpu)[:2]


# --- the run ------------------------------------------------------------------------------------

def main(args):
    global cuda
    try:
        import numba_cuda  # noqa: F401
        from numba import cuda
    except ImportError as err:
        _no_gpu(f'numba-cuda is not installed (pip install "fastrest[gpu]"): {err}')
    if not args.simulate and not cuda.is_available():
        _no_gpu("no CUDA GPU found (numba.cuda.is_available() is False): run it on a machine with an NVIDIA GPU; "
                "--simulate checks the script under Numba's CUDA simulator")
    import fastrest.cuda as fc

    sim = fc.SIMULATOR
    rounds = args.rounds or (2 if sim else 10)
    n_check = 64 if sim else 1_000_000
    sizes = dict(curve=64, scene=64, table=64, dem=64, header=1000) if sim else \
        dict(curve=10_000_000, scene=4_000_000, table=4_000_000, dem=4_000_000, header=50_000_000)
    rng = np.random.default_rng(22)
    if sim:
        device = "Numba's CUDA simulator (no GPU: every number below is meaningless; this run checks the script)"
    else:
        dev = cuda.get_current_device()
        name = dev.name.decode() if isinstance(dev.name, bytes) else dev.name
        device = f"{name} (compute capability {dev.compute_capability[0]}.{dev.compute_capability[1]})"
    lines = [f"# fastrest on a GPU (`python -m bench.gpu`)", "",
             f"Device: {device}. Date: {datetime.date.today().isoformat()}. numba {numba.__version__}, "
             f"numba-cuda {_version('numba-cuda')}, fastrest {fastrest.__version__}, Python {platform.python_version()}.",
             ""]
    print(lines[2])

    # 1. agreement with the CPU
    rows = agreement(fc, n_check, rng)
    lines += ["## Agreement with the CPU (the same jit function in an @njit loop)", "",
              "| function | points | bit-identical | worst relative difference | NaN mismatches | note |",
              "| --- | ---: | ---: | ---: | ---: | --- |"]
    for name, pts, same, rel, nanm, note in rows:
        if same is None:
            lines.append(f"| `{name}` | {pts} | - | - | - | does not run: {note} |")
        else:
            lines.append(f"| `{name}` | {pts} | {same:.4%} | {rel:.2e} | {nanm} | {note} |")
    for row in lines[-len(rows):]:
        print(row)

    # 2. speed against the floor
    timings = []  # (name, ns per point, bytes per point, floor ns, ratio, target, reference)

    def timed(name, n, nbytes, fn, ref="floor"):
        bw = copy_bandwidth(n * nbytes // 2, rounds)  # the same bytes moved: n*nbytes read + written
        try:
            t = best_time(fn, rounds) / n * 1e9
        except Exception as e:
            timings.append((name, None, nbytes, None, None, TARGETS.get(name.split()[0]), f"{type(e).__name__}: "
                            f"{str(e).splitlines()[0][:120]}"))
            return None
        floor = nbytes / bw * 1e9
        timings.append((name, t, nbytes, floor, t / floor, TARGETS.get(name.split()[0]), ref, bw))
        return t

    n = sizes["curve"]
    dcurve = fc.to_device(fastrest.curve(0.005, 0.33, v_max=100.0))
    dv = fc.to_device(np.exp(rng.uniform(0.0, math.log(100.0), n)))
    out = cuda.device_array(n)
    timed("e_curve", n, 16, lambda: fc.e_curve(dcurve, dv, out))

    n = sizes["scene"]
    dscene = fc.to_device(_scene(16))
    dv = fc.to_device(np.exp(rng.uniform(0.0, math.log(100.0), n)))
    dk = fc.to_device(rng.integers(0, 16, n).astype(np.int32))
    out = cuda.device_array(n)
    timed("e_material (16 materials, int32 index)", n, 20, lambda: fc.e_material(dscene, dv, dk, out))

    n = sizes["table"]
    dtab = fc.to_device(fastrest.load_table())
    dv = fc.to_device(np.exp(rng.uniform(0.0, math.log(100.0), n)))
    deps, dnu = fc.to_device(rng.uniform(0.0005, 0.01, n)), fc.to_device(rng.uniform(0.2, 0.45, n))
    out = cuda.device_array(n)
    timed("e_table (every point its own material)", n, 32, lambda: fc.e_table(dtab, dv, deps, dnu, frj.JCG, out))

    # DEM step: x, v, a (read + write), omega_c, P_c, mass (read), state row (read + write)
    n = sizes["dem"]
    law = fastrest.contact_law(0.004, 0.3)
    dlaw = fc.to_device(law)
    omega_c = rng.uniform(1e-7, 1e-6, n)
    arrays = {k: fc.to_device(a) for k, a in dict(
        x=omega_c * rng.uniform(0.0, 40.0, n), v=rng.uniform(-1.0, 1.0, n), a=np.zeros(n), omega_c=omega_c,
        P_c=rng.uniform(1.0, 10.0, n), mass=rng.uniform(1e-6, 1e-5, n)).items()}
    state = fc.new_state(n)
    dt = 1e-9
    step_law, step_hertz = _dem_kernels()
    blocks = (n + 255) // 256
    A = arrays
    t_law = timed("contact_force DEM step (history)", n, 6 * 8 + 3 * 8 + 2 * 32, lambda: step_law[blocks, 256](
        dlaw, A["x"], A["v"], A["a"], state, A["omega_c"], A["P_c"], A["mass"], dt), ref="Hertz step")
    t_hertz = timed("Hertz DEM step (no history)", n, 6 * 8 + 3 * 8, lambda: step_hertz[blocks, 256](
        A["x"], A["v"], A["a"], A["omega_c"], A["P_c"], A["mass"], dt), ref="-")

    header = ("skipped (--no-header)", None, None) if args.no_header else \
        c_header(sizes["header"], rounds, not sim, rng)
    if header[1] is not None:
        bw = copy_bandwidth(sizes["header"] * 8, rounds)
        t = header[1] / sizes["header"] * 1e9
        timings.append(("c_header fastrest_e (nvcc)", t, 16, 16 / bw * 1e9, t / (16 / bw * 1e9), TARGETS["c_header"],
                        "floor", bw))

    lines += ["", "## Speed against the memory floor (measured in this run)", "",
              "Floor: the bytes a kernel must move per point (inputs read + output written) over the device's "
              "device-to-device copy bandwidth (bytes read + written per second) measured on a copy of the same "
              "size in this run. The contact law's DEM step is compared with the same step with a Hertz force "
              "(no history row), not with the floor.", "",
              "| kernel | ns per point | bytes per point | copy bandwidth (GB/s) | floor (ns) | ratio to floor | target | met |",
              "| --- | ---: | ---: | ---: | ---: | ---: | ---: | --- |"]
    for t in timings:
        name, ns, nbytes, floor, ratio, target, ref = t[:7]
        if ns is None:
            lines.append(f"| {name} | - | {nbytes} | - | - | - | - | does not run: {ref} |")
            continue
        bw = t[7]
        if name.startswith("contact_force") and t_hertz:
            ratio_h = ns / t_hertz
            met = "met" if ratio_h <= target else "not met"
            lines.append(f"| {name} | {ns:.4f} | {nbytes} | {bw / 1e9:.0f} | {floor:.4f} | {ratio:.2f} | "
                         f"<= {target:g}x Hertz step: {ratio_h:.2f}x | {met} |")
        elif target is None:
            lines.append(f"| {name} | {ns:.4f} | {nbytes} | {bw / 1e9:.0f} | {floor:.4f} | {ratio:.2f} | - | - |")
        else:
            met = "met" if ratio <= target else "not met"
            lines.append(f"| {name} | {ns:.4f} | {nbytes} | {bw / 1e9:.0f} | {floor:.4f} | {ratio:.2f} | "
                         f"<= {target:g}x | {met} |")
    lines += ["", f"C header (`fastrest export c`, one material, `fastrest_e` in a `__global__` kernel): {header[0]}"
              + (f"; against `Curve.e`: {header[2][0]:.4%} bit-identical, worst relative difference "
                 f"{header[2][1]:.2e}" if header[2] else ""), ""]
    if sim:
        lines += ["Under the simulator every timing above is the simulator's (Python threads): meaningless; "
                  "the agreement rows compare the CPU's code with itself and check the plumbing only.", ""]
    lines += rough_section(fc, [40] if sim else [10_000_000, 100_000_000], rounds, rng)
    lines += ["Not measured here: the CPU side (`python -m bench`).", ""]
    for row in lines[lines.index("| --- | ---: | ---: | ---: | ---: | ---: | ---: | --- |") + 1:]:
        print(row)
    Path(args.output).write_text("\n".join(lines))
    print(f"wrote {args.output}")
    return 0


def rough_section(fc, sizes, rounds, rng):
    """Lines of section 3: one impact on explicit Gaussian summits, GPU time and e against the CPU."""
    from fastrest import rough
    mat = fastrest.Material(200e9, 0.3, 1e9)
    lines = ["## Rough surfaces: one impact on explicit summits (`fastrest.cuda.rough_impact`)", "",
             "Gaussian summit heights (sigma = 30 nm, R_a = 100 um, steel), V1 = 1 m/s, M = 1e-5 kg per 1000 "
             "summits; the heights on the device already (copied at the first call); best of the runs, the "
             "whole solve (every kernel launch and the host's Newton steps). e against `RoughSurface.impact` "
             "on this machine's CPU.", "",
             "| summits | GPU ms per impact | CPU s per impact | e (GPU) | relative difference from the CPU | "
             "in contact | target | met |",
             "| ---: | ---: | ---: | ---: | ---: | ---: | ---: | --- |"]
    for n in sizes:
        try:
            s = rough.RoughSurface(mat, 100e-6, heights=rng.normal(0.0, 30e-9, n))
            M = 1e-5 * n / 1000
            g = fc.rough_impact(s, 1.0, M)  # compiles, copies the heights and the table
            t = best_time(lambda: fc.rough_impact(s, 1.0, M), rounds) * 1e3
            t0 = time.perf_counter()
            c = s.impact(1.0, M)
            t_cpu = time.perf_counter() - t0
        except Exception as e:  # noqa: BLE001 - reported in the table
            lines.append(f"| {n:.0e} | - | - | - | - | - | - | does not run: {type(e).__name__}: "
                         f"{str(e).splitlines()[0][:120]} |")
            continue
        target = ROUGH_TARGET_MS if n >= 100_000_000 else None
        met = "-" if target is None else ("met" if t <= target else "not met")
        lines.append(f"| {n:.0e} | {t:.2f} | {t_cpu:.3f} | {g.e:.12f} | {abs(g.e - c.e) / c.e:.2e} | {g.n_contact} | "
                     f"{'-' if target is None else f'< {target:g} ms'} | {met} |")
        del s
    for row in lines[-len(sizes):]:
        print(row)
    return lines + [""]


def _version(dist):
    try:
        from importlib.metadata import version
        return version(dist)
    except Exception:
        return "?"


if __name__ == "__main__":
    sys.exit(main(ARGS))
