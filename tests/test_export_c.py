"""The C header of `fastrest export c`: compiled with the system C compiler and compared with the
Python path (the jitted curve kernels behind fastrest.Curve) at >= 1e5 points, cell boundaries and
their neighbours (+/- 1 ulp) included. Reference: fastrest.curve's own data evaluated by
fastrest.curve_data.curve_array, an independent implementation (Numba) of the same rule; the test
requires agreement to 2 ulp (the header is designed to agree bit for bit). The same header as C++11
(`c++`), and as CUDA: `nvcc` compiles it unedited into a kernel and host code (the host part runs
without a GPU and agrees bit for bit; the device copies of the tables, read from the PTX, are the
Python rows bit for bit), and NVRTC (where its library is installed) compiles it at run time as a
code such as DEM-Engine does."""
import ctypes
import ctypes.util
import glob
import os
import re
import shutil
import subprocess

import numpy as np
import pytest

import fastrest
from fastrest import cli
from fastrest.cells import HERTZ_EDGES, N_HERTZ
from fastrest.curve_data import curve_array
from fastrest.energy import V_SWITCH
from fastrest.export import c_header
from fastrest.interpolation import cell_edges

CC = shutil.which("cc")
CXX = shutil.which("c++")
NVCC = shutil.which("nvcc")
MATERIALS = [(0.005, 0.33), (0.0008, 0.25), (0.0095, 0.42)]

def _host_main(n_out, extra=""):
    """The C driver both programs share: reads (k, v) pairs, writes w_m*, e and 1 - e^2 of every
    model (and NaN for unknown models), then ``extra`` (C statements filling r[9] ...), n_out values."""
    return HOST_MAIN.replace("N_OUT", str(n_out)).replace("EXTRA", extra)


HOST_MAIN = r"""int main(int argc, char **argv)
{
    FILE *in = fopen(argv[1], "rb"), *out = fopen(argv[2], "wb");
    long n, i;
    (void)argc;
    if (!in || !out || fread(&n, sizeof n, 1, in) != 1) return 1;
    for (i = 0; i < n; i++) {
        double kv[2], r[N_OUT];
        int k, m;
        if (fread(kv, sizeof(double), 2, in) != 2) return 1;
        k = (int)kv[0];
        r[0] = fastrest_omega_m(k, kv[1]);
        for (m = 0; m < FASTREST_N_UNLOADING; m++) {
            r[1 + m] = fastrest_e(k, kv[1], m);
            r[1 + FASTREST_N_UNLOADING + m] = fastrest_loss(k, kv[1], m);
        }
        r[7] = fastrest_e(k, kv[1], FASTREST_N_UNLOADING); /* unknown model: NaN */
        r[8] = fastrest_loss(k, kv[1], -1);
        EXTRAfwrite(r, sizeof(double), N_OUT, out);
    }
    return fclose(out) != 0;
}
"""

PROGRAM = r"""
#include <stdio.h>
#include <stdlib.h>
#include "scene.h"
""" + _host_main(9)


def _ulp_distance(a, b):
    """|a - b| in units in the last place (via the ordered integer image of the floats)."""
    def ordered(x):
        i = x.view(np.int64)
        return np.where(i < 0, np.int64(-2**63) - i, i)
    return np.abs(ordered(a) - ordered(b))


def _points(curves, rng):
    ks, vs = [], []
    for k, c in enumerate(curves):
        vmax = c[0].v_max
        v = np.exp(rng.uniform(np.log(1e-3), np.log(vmax * 1.05), 35000))
        _, jg = cell_edges(V_SWITCH, vmax, 5)
        edges = np.concatenate([HERTZ_EDGES.ravel(), jg.ravel(), [0.0, 1.0, V_SWITCH, vmax]])
        edges = np.concatenate([edges, np.nextafter(edges, np.inf), np.nextafter(edges, -np.inf)])
        special = np.array([-1.0, -0.0, np.nan, np.inf, 1e-300, 1 + 1e-15])
        v = np.concatenate([v, edges, special])
        vs.append(v)
        ks.append(np.full(v.size, k))
    ks.append(np.array([-1, len(curves), len(curves)]))  # unknown materials: NaN
    vs.append(np.array([2.0, 2.0, 20.0]))
    return np.concatenate(ks).astype(np.float64), np.concatenate(vs)


def _python(curves, k, v):
    n = len(curves)
    out = np.full((9, v.size), np.nan)
    for m in range(n):
        sel = k == m
        if not sel.any():
            continue
        vs = np.ascontiguousarray(v[sel])
        for what, code, row in [(0, 0, 0)] + [(1, c, 1 + c) for c in range(3)] + [(2, c, 4 + c) for c in range(3)]:
            tmp = np.empty(vs.size)
            curve_array(curves[m][code], what, vs, tmp)
            out[row, sel] = tmp
    return out


@pytest.mark.parametrize("lang", ["c99", "c++11"])
def test_c_header_matches_python(tmp_path, lang):
    """The header as C99 (`cc`) and as C++11 (`c++`: no hexadecimal floating literals before C++17,
    hence the decimal ones), -Wall -Wextra -pedantic -Werror."""
    compiler = CC if lang == "c99" else CXX
    if compiler is None:
        pytest.skip(f"no {'C' if lang == 'c99' else 'C++'} compiler (`{'cc' if lang == 'c99' else 'c++'}`) on PATH: "
                    f"the header cannot be compiled as {lang} here")
    header = tmp_path / "scene.h"
    assert cli.main(["export", "c", "--materials"] + [f"{e}:{n}" for e, n in MATERIALS]
                    + ["--out", str(header)]) == 0
    curves = c_header.scene_curves(MATERIALS)
    src = tmp_path / ("main.c" if lang == "c99" else "main.cpp")
    src.write_text(PROGRAM)
    exe = tmp_path / "main"
    r = subprocess.run([compiler, f"-std={lang}", "-O2", "-Wall", "-Wextra", "-pedantic", "-Werror", "-I", str(tmp_path),
                        str(src), "-o", str(exe), "-lm"], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    k, v = _points(curves, np.random.default_rng(7))
    assert v.size >= 1e5
    with open(tmp_path / "in.bin", "wb") as fh:
        np.array([v.size], dtype=np.int64).tofile(fh)
        np.stack([k, v], 1).tofile(fh)
    r = subprocess.run([str(exe), str(tmp_path / "in.bin"), str(tmp_path / "out.bin")], timeout=60)
    assert r.returncode == 0
    got = np.fromfile(tmp_path / "out.bin").reshape(-1, 9).T
    want = _python(curves, k.astype(np.int64), v)
    nan_got, nan_want = np.isnan(got), np.isnan(want)
    assert np.array_equal(nan_got, nan_want)
    assert nan_want[7:].all()  # unknown unloading codes
    ok = ~nan_want
    assert np.count_nonzero(ok[1]) > 1e5
    assert _ulp_distance(got[ok], want[ok]).max() <= 2
    # the domain: NaN past v_max, values up to it
    for m, c in enumerate(curves):
        at = (k == m) & (v > c[0].v_max)
        assert at.any() and nan_got[:, at].all()


def test_c_header_default_reaches_w425_and_records_materials(tmp_path):
    out = tmp_path / "h.h"
    c_header.write_header(out, [(0.005, 0.33)])
    text = out.read_text()
    assert f"v_max = {fastrest.limit(0.005, 0.33).v1_star!r}" in text
    assert "#define FASTREST_JCG 0" in text and "#define FASTREST_ETSION 1" in text
    assert "#define FASTREST_BRAKE 2" in text


@pytest.mark.parametrize("argv, option", [
    (["--materials", "0.005"], "--materials"),
    (["--materials", "abc:0.3"], "--materials"),
    (["--materials", "0.005:0.6"], "nu"),
    (["--materials", "0.005:0.33", "--v-max", "5000"], "--v-max"),
    (["--materials", "0.005:0.33", "--v-max", "-1"], "--v-max"),
])
def test_c_header_bad_input(tmp_path, capsys, argv, option):
    out = tmp_path / "x.h"
    assert cli.main(["export", "c"] + argv + ["--out", str(out)]) == 2
    assert option in capsys.readouterr().err
    assert not out.exists() and os.listdir(tmp_path) == []


def test_c_header_unwritable(tmp_path, capsys):
    """A missing directory is a file-system error (exit 1, as `build`), naming --out and the file."""
    out = tmp_path / "missing" / "x.h"
    assert cli.main(["export", "c", "--materials", "0.005:0.33", "--out", str(out)]) == 1
    err = capsys.readouterr().err
    assert "--out" in err and str(out) in err


# --- a header from physical properties ------------------------------------------------------------

PHYSICAL_PROGRAM = r"""
#include <stdio.h>
#include "pairs.h"
int main(void)
{
    int k, m;
    double V;
    printf("%d\n", FASTREST_HAS_CRITICAL);
    for (k = 0; k < FASTREST_N_MATERIALS; k++)
        printf("%a %a %a %a %a %a %a %a\n", fastrest_V_c[k], fastrest_omega_c[k], fastrest_P_c[k], fastrest_A_c[k],
               fastrest_U_c[k], fastrest_E_eff[k], fastrest_R_eff[k], fastrest_mass[k]);
    while (scanf("%d %lf", &k, &V) == 2) {
        printf("%a", fastrest_v1_star(k, V));
        for (m = 0; m < FASTREST_N_UNLOADING; m++)
            printf(" %a", fastrest_e(k, fastrest_v1_star(k, V), m));
        printf("\n");
    }
    return 0;
}
"""

PAIRS_CSV = """name,E,nu,Sy,R,rho,mass,flat_E,flat_nu,flat_Sy,V_max
steel,200e9,0.33,1.12e9,0.01,7850,,,,,
alu_on_steel,70e9,0.33,0.28e9,0.005,2700,,200e9,0.3,,3.0
"""


def _compile(tmp_path, header_name, program):
    (tmp_path / "main.c").write_text(program)
    exe = tmp_path / "main"
    r = subprocess.run([CC, "-std=c99", "-O2", "-Wall", "-Wextra", "-pedantic", "-Werror", "-I", str(tmp_path),
                        str(tmp_path / "main.c"), "-o", str(exe), "-lm"], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    return exe


@pytest.mark.skipif(CC is None, reason="no C compiler (`cc`) on PATH: the C header cannot be compiled here")
def test_c_header_from_physical_properties_matches_impact(tmp_path, capsys):
    """`export c --pairs` (the file format of `export velocity`): the header's critical values are
    the Impact's bit for bit, fastrest_v1_star(k, V) = V/V_c, and fastrest_e(k, fastrest_v1_star(k, V))
    is Impact.e(V) (the exact solver) within the curves' accuracy, up to each pair's V_max."""
    import math

    (tmp_path / "pairs.csv").write_text(PAIRS_CSV)
    header = tmp_path / "pairs.h"
    assert cli.main(["export", "c", "--pairs", str(tmp_path / "pairs.csv"), "--out", str(header)]) == 0
    assert "V_c = 0.0514104 m/s" in capsys.readouterr().out
    steel = fastrest.Material(200e9, 0.33, 1.12e9, rho=7850)
    alu = fastrest.Material(70e9, 0.33, 0.28e9, rho=2700)
    impacts = [fastrest.Impact(steel, 0.01), fastrest.Impact(alu, 0.005, flat=fastrest.Material(200e9, 0.3, math.inf))]
    V_max = [impacts[0].V_max(), 3.0]
    exe = _compile(tmp_path, "pairs.h", PHYSICAL_PROGRAM)
    rng = np.random.default_rng(21)
    V = [np.concatenate([[0.0, 0.5 * imp.V_c, imp.V_c * (1 + 1e-9), vm, vm * (1 + 1e-9)],
                         np.exp(rng.uniform(np.log(imp.V_c), np.log(vm), 300))]) for imp, vm in zip(impacts, V_max)]
    stdin = "".join(f"{k} {float(v)!r}\n" for k in range(2) for v in V[k]) + "2 1.0\n-1 1.0\n"
    r = subprocess.run([str(exe)], input=stdin, capture_output=True, text=True, timeout=60)
    assert r.returncode == 0, r.stderr
    lines = r.stdout.split("\n")
    assert lines[0] == "1"
    for k, imp in enumerate(impacts):
        crit = imp.critical_values()
        got = [float.fromhex(x) for x in lines[1 + k].split()]
        assert got == [crit[q] for q in ("V_c", "omega_c", "P_c", "A_c", "U_c", "E_eff", "R_eff", "mass")]
    rows = np.array([[float.fromhex(x) for x in line.split()] for line in lines[3:] if line])
    n0 = V[0].size
    for k, imp in enumerate(impacts):
        part = rows[:n0] if k == 0 else rows[n0:n0 + V[1].size]
        np.testing.assert_array_equal(part[:, 0], V[k] / imp.V_c)  # the helper: V / V_c, bit for bit
        inside = V[k] <= V_max[k]
        assert np.isnan(part[~inside, 1:]).all()  # past the pair's V_max
        for m, name in enumerate(("jcg", "etsion", "brake")):
            want = imp.e(V[k][inside], name)
            np.testing.assert_allclose(part[inside, 1 + m], want, rtol=1e-11, atol=1e-12, err_msg=f"{k} {name}")
    assert np.isnan(rows[-2:]).all()  # unknown pairs


def test_c_header_from_options_records_critical_values(tmp_path, capsys):
    """--E --nu --Sy --R --rho as `export velocity` takes them; --V-max in m/s; mixing with --materials
    or --v-max, and --pairs with --E, are refused naming the options."""
    out = tmp_path / "one.h"
    argv = ["export", "c", "--E", "200e9", "--nu", "0.33", "--Sy", "1.12e9", "--R", "0.01", "--rho", "7850"]
    assert cli.main(argv + ["--V-max", "5", "--out", str(out)]) == 0
    text = out.read_text()
    assert "#define FASTREST_HAS_CRITICAL 1" in text and "static inline FASTREST_FN double fastrest_v1_star(int k, double V)" in text
    assert "--E 200000000000.0" in text and "--V-max 5.0" in text
    imp = fastrest.Impact(fastrest.Material(200e9, 0.33, 1.12e9, rho=7850), 0.01)
    assert f"FASTREST_TABLE(double, fastrest_V_c, [FASTREST_N_MATERIALS], {{{imp.V_c!r}}});" in text
    assert f"v_max = {5.0 / imp.V_c!r}" in text
    capsys.readouterr()
    for extra, option in ([["--V-max", "500"], "--V-max"], [["--materials", "0.005:0.33"], "--materials"],
                          [["--v-max", "5"], "--v-max"], [["--pairs", "x.csv"], "--pairs"]):
        bad = tmp_path / "bad.h"
        assert cli.main(argv + extra + ["--out", str(bad)]) == 2
        assert option in capsys.readouterr().err
        assert not bad.exists()
    # a normalised header has no critical values
    c_header.write_header(tmp_path / "norm.h", [(0.005, 0.33)])
    norm = (tmp_path / "norm.h").read_text()
    assert "#define FASTREST_HAS_CRITICAL 0" in norm and "fastrest_v1_star" not in norm


# --- the header as CUDA ---------------------------------------------------------------------------

CUDA_PROGRAM = r"""
#include <stdio.h>
#include "pairs.h"
/* every function from device code: the header compiles unedited as CUDA */
__global__ void fastrest_kernel(const double *v, double *out, int n)
{
    int i = blockIdx.x * blockDim.x + threadIdx.x;
    if (i < n) {
        double x = fastrest_v1_star(i % FASTREST_N_MATERIALS, v[i]);
        out[i] = fastrest_e(0, x, FASTREST_JCG) + fastrest_loss(0, x, FASTREST_ETSION) + fastrest_omega_m(0, x)
                 + FASTREST_ARRAY(fastrest_omega_c)[0];
    }
}
/* the same __host__ __device__ functions from host code: runs without a GPU */
""" + _host_main(
    10, "r[9] = fastrest_v1_star(k, kv[1]); /* kv[1] read as a speed in m/s */\n        ")

KERNEL = r"""
extern "C" __global__ void fastrest_kernel(const double *v, double *out, int n)
{
    int i = blockIdx.x * blockDim.x + threadIdx.x;
    if (i < n) {
        double x = fastrest_v1_star(0, v[i]);
        out[i] = fastrest_e(0, x, FASTREST_JCG) + fastrest_loss(0, x, FASTREST_BRAKE) + fastrest_omega_m(0, x)
                 + FASTREST_ARRAY(fastrest_mass)[0];
    }
}
"""


def _physical_header(path, pairs=2):
    """A header from physical properties (two pairs, the second on an elastic flat, capped at 3 m/s)
    written by write_header; returns its (curves, critical)."""
    import math
    steel = fastrest.Material(200e9, 0.33, 1.12e9, rho=7850)
    alu = fastrest.Material(70e9, 0.33, 0.28e9, rho=2700)
    impacts = [fastrest.Impact(steel, 0.01), fastrest.Impact(alu, 0.005, flat=fastrest.Material(200e9, 0.3, math.inf))]
    materials, v_max, critical = c_header.impact_materials(impacts[:pairs], [None, 3.0][:pairs])
    _, curves = c_header.write_header(path, materials, v_max, critical=critical)
    return curves, critical


def _ptx_tables(ptx):
    """{name: bytes} of the `.global` arrays of a PTX text (the tables' device copies); PTX leaves
    out trailing zero bytes of an initializer, put back here."""
    out = {}
    for name, size, body in re.findall(r"\.global \.align \d+ \.b8 (\w+)\[(\d+)\] = \{([^}]*)\}", ptx):
        data = bytes(int(x) for x in body.split(","))
        out[name] = data + bytes(int(size) - len(data))
    return out


def _check_device_tables(ptx, curves, critical, names=None):
    """The device copies of the tables in a PTX are the Python rows (and critical values) bit for bit."""
    tables = _ptx_tables(ptx)

    def cat(field, code):
        return np.concatenate([getattr(curves[0][code], field)[:N_HERTZ]] + [getattr(c[code], field)[N_HERTZ:] for c in curves])

    want = {"fastrest_omega_rows_device": cat("omega_rows", 0),
            "fastrest_e_rows_device": np.stack([cat("e_rows", m) for m in range(3)]),
            "fastrest_loss_rows_device": np.stack([cat("loss_rows", m) for m in range(3)]),
            "fastrest_v_max_device": np.array([c[0].v_max for c in curves])}
    if critical:
        want["fastrest_V_c_device"] = np.array([c["V_c"] for c in critical])
        want["fastrest_mass_device"] = np.array([c["mass"] for c in critical])
    for name in names or want:
        assert name in tables, f"{name} not in the PTX (found {sorted(tables)})"
        got = np.frombuffer(tables[name], dtype="<f8")
        assert np.array_equal(got.view(np.int64), np.ascontiguousarray(want[name]).ravel().view(np.int64)), name


@pytest.mark.skipif(NVCC is None, reason="no CUDA compiler (`nvcc`) on PATH: the header's CUDA build cannot be checked "
                                         "here (install the CUDA toolkit, or the nvidia-cuda-nvcc wheel, to run it)")
def test_c_header_compiles_as_cuda_and_its_host_code_matches_python(tmp_path):
    """`nvcc` compiles the unedited header into a __global__ kernel calling fastrest_e, fastrest_loss,
    fastrest_omega_m and fastrest_v1_star (sm_90, -Werror all-warnings; the host compiler with
    -Wall -Wextra -Werror); the program's host part, the same __host__ __device__ functions, runs
    without a GPU and gives Curve.e's doubles bit for bit; the device copies of the tables in the
    PTX are the Python rows bit for bit."""
    curves, critical = _physical_header(tmp_path / "pairs.h")
    (tmp_path / "main.cu").write_text(CUDA_PROGRAM)
    exe = tmp_path / "main"
    # -keep: the PTX of the device pass stays in keep/ (one nvcc run for the host and the device code)
    (tmp_path / "keep").mkdir()
    flags = ["-std=c++14", "-arch=sm_90", "-O2", "-Werror", "all-warnings", "-Xcompiler", "-Wall,-Wextra,-Werror",
             "-I", str(tmp_path), "-keep", "-keep-dir", str(tmp_path / "keep")]
    r = subprocess.run([NVCC] + flags + [str(tmp_path / "main.cu"), "-o", str(exe)], capture_output=True, text=True,
                       timeout=300)
    assert r.returncode == 0, r.stdout + r.stderr
    k, v = _points(curves, np.random.default_rng(22))
    with open(tmp_path / "in.bin", "wb") as fh:
        np.array([v.size], dtype=np.int64).tofile(fh)
        np.stack([k, v], 1).tofile(fh)
    r = subprocess.run([str(exe), str(tmp_path / "in.bin"), str(tmp_path / "out.bin")], capture_output=True,
                       timeout=60)
    assert r.returncode == 0, r.stderr
    got = np.fromfile(tmp_path / "out.bin").reshape(-1, 10).T
    want = _python(curves, k.astype(np.int64), v)
    assert np.array_equal(got[:9], want[:9], equal_nan=True)  # bit for bit (0.0 and -0.0 aside)
    assert np.array_equal(np.signbit(got[:9]), np.signbit(want[:9]))
    assert np.count_nonzero(~np.isnan(want[1])) > 5e4
    ki = k.astype(np.int64)
    V_c = np.array([c["V_c"] for c in critical] + [np.nan])[np.where((ki >= 0) & (ki < len(critical)), ki, -1)]
    assert np.array_equal(got[9], v / V_c, equal_nan=True)  # fastrest_v1_star: V / V_c
    # the device code: the kernel and the tables' device copies, bit for bit
    ptx = (tmp_path / "keep" / "main.ptx").read_text()
    assert ".entry" in ptx and "fastrest_kernel" in ptx
    _check_device_tables(ptx, curves, critical)


def _nvrtc():
    """NVRTC's library (ctypes) or None: $FASTREST_NVRTC, the nvidia-cuda-nvrtc wheel, the system's."""
    paths = [os.environ.get("FASTREST_NVRTC")]
    try:
        import nvidia  # namespace package of NVIDIA's wheels
        for base in nvidia.__path__:
            paths += sorted(p for p in glob.glob(os.path.join(base, "*", "lib", "libnvrtc.so*")) if ".alt." not in p)
    except ImportError:
        pass
    paths.append(ctypes.util.find_library("nvrtc"))
    for path in paths:
        if not path:
            continue
        try:
            # libnvrtc opens libnvrtc-builtins by name at compile time: load it from the same folder first
            for b in glob.glob(os.path.join(os.path.dirname(path), "libnvrtc-builtins.so*")):
                if ".alt." not in b:
                    ctypes.CDLL(b, mode=ctypes.RTLD_GLOBAL)
            return ctypes.CDLL(path)
        except OSError:
            continue
    return None


def _nvrtc_compile(lib, source, options):
    """(result code, log, PTX) of NVRTC compiling ``source`` with ``options``."""
    prog = ctypes.c_void_p()
    assert lib.nvrtcCreateProgram(ctypes.byref(prog), source.encode(), b"fastrest_kernel.cu", 0, None, None) == 0
    try:
        opts = (ctypes.c_char_p * len(options))(*[o.encode() for o in options])
        rc = lib.nvrtcCompileProgram(prog, len(options), opts)
        size = ctypes.c_size_t()
        lib.nvrtcGetProgramLogSize(prog, ctypes.byref(size))
        log = ctypes.create_string_buffer(size.value)
        lib.nvrtcGetProgramLog(prog, log)
        ptx = ""
        if rc == 0:
            lib.nvrtcGetPTXSize(prog, ctypes.byref(size))
            buf = ctypes.create_string_buffer(size.value)
            lib.nvrtcGetPTX(prog, buf)
            ptx = buf.value.decode()
        return rc, log.value.decode(), ptx
    finally:
        lib.nvrtcDestroyProgram(ctypes.byref(prog))


@pytest.mark.cuda   # CI's `-m cuda` run has the gpu extra, whose wheels bring libnvrtc
def test_c_header_compiles_with_nvrtc_at_run_time(tmp_path):
    """NVRTC (CUDA source compiled at run time, as DEM-Engine's custom force models are) compiles the
    header's text followed by a kernel, with no system header available (the header includes
    none under __CUDACC_RTC__), without a warning; the tables' device copies are the Python rows
    bit for bit."""
    lib = _nvrtc()
    if lib is None:
        pytest.skip("NVRTC's library (libnvrtc) not found: `pip install nvidia-cuda-nvrtc`, or set FASTREST_NVRTC "
                    "to the library's path, to check the header under NVRTC")
    curves, critical = _physical_header(tmp_path / "one.h", pairs=1)
    text = (tmp_path / "one.h").read_text()
    rc, log, ptx = _nvrtc_compile(lib, text + KERNEL, ["--gpu-architecture=compute_90", "-std=c++14"])
    assert rc == 0 and log.strip() == "", log
    assert ".entry fastrest_kernel" in ptx
    _check_device_tables(ptx, curves, critical, ["fastrest_omega_rows_device", "fastrest_e_rows_device",
                                                  "fastrest_loss_rows_device", "fastrest_v_max_device",
                                                  "fastrest_V_c_device", "fastrest_mass_device"])
    # an unknown name is an error there: the check is not vacuous
    rc, log, _ = _nvrtc_compile(lib, text + KERNEL.replace("fastrest_mass", "fastrest_nothing"),
                                ["--gpu-architecture=compute_90"])
    assert rc != 0 and "fastrest_nothing" in log
