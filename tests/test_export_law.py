"""The contact law as C (fastrest export c --law) against fastrest.jit.contact_force.

The C functions are translated from the jit law's source (fastrest/export/law_c.py); compiled
without contraction they must give the jit law's forces and history rows bit for bit (the issue
asks <= 2 ulp; any difference fails here) on load/unload/reload histories through every case:
virgin loading below and above w* = 1 and 1.9, cell edges +-1 ulp, unloading, reloading,
apart, NaN, -inf, past the end, and rows that are no history; law_step_branching (if/else, a
chained assignment), translated the same way, too. The translator refuses what it cannot follow.
"""
import ctypes
import shutil
import subprocess

import numba
import numpy as np
import pytest

import fastrest
from fastrest import interpolation
from fastrest import jit as frj
from fastrest import law_cells
from fastrest.export.law_c import LawTranslationError, law_header_text, law_source, translate

_DRIVER = r"""
#include "law.h"
#include "branching.h"
void run(const double *w, long n, int k, int branching, double *state, double *out, double *states)
{
    for (long i = 0; i < n; ++i) {
        out[i] = (branching ? fastrest_law_step_branching : fastrest_law_step)(
            fastrest_law_rows[0], fastrest_law_first[k], fastrest_law_last[k], fastrest_law_w_end[k], state, w[i]);
        for (int j = 0; j < FASTREST_STATE_SIZE; ++j) states[i * FASTREST_STATE_SIZE + j] = state[j];
    }
}
"""
_I = "FASTREST_INT64"
_STEP_TYPES = ["const double *", _I, _I, "double", "double *", "double"]

LAWS = [(0.005, 0.33, "jcg", 0.0), (0.002, 0.3, "etsion", 0.0), (0.008, 0.25, "brake", 0.0),
        (0.003, 0.3, "brake", 0.01)]


@numba.njit
def _jit_run(data, w, state, out, states):
    for i in range(w.size):
        out[i] = frj.contact_force(data, state, w[i])
        states[i] = state


def _history(law):
    """Interferences through every case of the law, in time order."""
    rows = law.data.law_rows
    edges = np.concatenate([rows[:, 0] - 1 / rows[:, 1], rows[:, 0] + 1 / rows[:, 1]])
    edges = edges[(edges > 0) & (edges < law.data.w_max)]
    near = np.concatenate([edges, np.nextafter(edges, 0), np.nextafter(edges, np.inf), [1.0, 1.9, 0.5]])
    near = np.concatenate([near, np.nextafter([1.0, 1.9], 0), np.nextafter([1.0, 1.9], 3)])
    rng = np.random.default_rng(7)
    up = np.sort(np.concatenate([near, rng.uniform(0, law.data.w_max, 2000)]))
    path = [-1.0, 0.0]
    for top in (0.3 * law.data.w_max, 0.6 * law.data.w_max, law.data.w_max):
        load = up[up <= top]
        path += list(load[load > (path[-1] if path[-1] > 0 else 0)])
        path += list(np.linspace(top, -0.5, 97))           # unloading, apart
        path += list(np.linspace(-0.5, 0.7 * top, 53))     # reloading below the maximum
    return np.array(path)


@pytest.fixture(scope="module")
def compiled(tmp_path_factory):
    if shutil.which("gcc") is None:
        pytest.skip("no gcc")
    laws = [fastrest.contact_law(e, n, u, et_ratio=h) for e, n, u, h in LAWS]
    d = tmp_path_factory.mktemp("law")
    (d / "law.h").write_text(law_header_text(laws))
    # law_step_branching (if/else, chained assignment) through the same translator: the same values
    (d / "branching.h").write_text(translate(law_cells.law_step_branching, "fastrest_law_step_branching",
                                             _STEP_TYPES, "double") + "\n")
    (d / "driver.c").write_text(_DRIVER)
    lib = d / "law.so"
    subprocess.run(["gcc", "-std=c99", "-O2", "-ffp-contract=off", "-Wall", "-Wextra", "-Werror", "-shared", "-fPIC",
                    "-I", str(d), str(d / "driver.c"), "-o", str(lib), "-lm"], check=True, capture_output=True)
    so = ctypes.CDLL(str(lib))
    p = ctypes.POINTER(ctypes.c_double)
    so.run.argtypes = [p, ctypes.c_long, ctypes.c_int, ctypes.c_int, p, p, p]
    return laws, so, d


def _c_run(so, k, w, state, branching=0):
    out = np.empty(w.size)
    states = np.empty((w.size, frj.STATE_SIZE))
    p = ctypes.POINTER(ctypes.c_double)
    so.run(w.ctypes.data_as(p), w.size, k, branching, state.ctypes.data_as(p), out.ctypes.data_as(p),
           states.ctypes.data_as(p))
    return out, states


@pytest.mark.parametrize("k", range(len(LAWS)))
def test_c_law_equals_jit_law_bit_for_bit(compiled, k):
    laws, so, _ = compiled
    law = laws[k]
    w = _history(law)
    w = np.concatenate([w, [np.nan, 0.5, -np.inf], [0.0, 1.5 * law.data.w_max]])
    for start in (np.zeros(4), np.array([-1.0, 0, 0, 0]), np.array([5.0, 7.0, 0.0, 0.0]),
                  np.array([np.nan, 0, 0, 0])):
        ref_out, ref_states = np.empty(w.size), np.empty((w.size, 4))
        _jit_run(law.data, w, start.copy(), ref_out, ref_states)
        for branching in (0, 1):
            out, states = _c_run(so, k, w, start.copy(), branching)
            same = (out == ref_out) | (np.isnan(out) & np.isnan(ref_out))
            assert same.all(), (branching, w[~same][:5], out[~same][:5], ref_out[~same][:5])
            same = (states == ref_states) | (np.isnan(states) & np.isnan(ref_states))
            assert same.all(), branching
    # the history went through loading, unloading with force, apart, and NaN at the end
    ref_out = np.empty(w.size)
    _jit_run(law.data, w, np.zeros(4), ref_out, np.empty((w.size, 4)))
    assert (ref_out > 0).sum() > 1000 and (ref_out == 0).sum() > 50 and np.isnan(ref_out[-1])


def test_header_compiles_as_cpp_and_cuda(compiled, tmp_path):
    _, _, d = compiled
    src = tmp_path / "use.cpp"
    src.write_text('#include "law.h"\ndouble f(double *s, double w) { return fastrest_law_step(fastrest_law_rows[0], '
                   'fastrest_law_first[0], fastrest_law_last[0], fastrest_law_w_end[0], s, w); }\n')
    if shutil.which("g++"):
        subprocess.run(["g++", "-std=c++11", "-Wall", "-Wextra", "-Werror", "-c", "-I", str(d), str(src), "-o",
                        str(tmp_path / "use.o")], check=True, capture_output=True)
    (tmp_path / "law_only.h").write_text(law_source())
    plain = tmp_path / "plain.c"
    plain.write_text('#include "law_only.h"\n')
    subprocess.run(["gcc", "-std=c99", "-pedantic", "-Wall", "-Werror", "-c", str(plain), "-I", str(tmp_path), "-o",
                    str(tmp_path / "plain.o")], check=True, capture_output=True)
    if shutil.which("nvcc") is None:
        pytest.skip("no nvcc")
    cu = tmp_path / "use.cu"
    cu.write_text('#include "law.h"\n__global__ void k(double *s, const double *w, double *out, int n) {\n'
                  '  int i = blockIdx.x * blockDim.x + threadIdx.x;\n  if (i < n) out[i] = fastrest_law_step('
                  'FASTREST_ARRAY(fastrest_law_rows)[0], 0, FASTREST_ARRAY(fastrest_law_last)[0], 30.0, s + 4 * i, w[i]);\n}\n')
    run = subprocess.run(["nvcc", "--fmad=false", "-c", "-I", str(d), str(cu), "-o", str(tmp_path / "use_cu.o")],
                         capture_output=True, text=True)
    assert run.returncode == 0, run.stderr[-2000:]


def _while_loop(w, first, last):
    while w > 1.0:
        w = w * 0.5
    return w


def _call_unknown(w, first, last):
    return np.exp(w)


def _plain_division(w, first, last):
    return w / 2.0  # Numba raises ZeroDivisionError on 0, C gives inf: fdiv says which


def _unsigned_with_signed(w, first, last):
    i = np.uint64(first)
    return i + last  # float64 in Numba, uint64 in C


def _local_of_an_if(w, first, last):
    if w > 1.0:
        x = w
    else:
        x = 1.0
    return x  # C's x ended with each block


def _wrong_argument_type(w, first, last):
    return law_cells.law_row(w, w, last)  # Numba would compile another law_row for a double


def _c_word(w, first, last):
    default = w
    return default


def _int_return(w, first, last):
    return first  # declared double: C would convert where Numba returns an int64


def _chained_compare(w, first, last):
    return interpolation.select(0.0 < w < 1.0, w, 0.0)


@pytest.mark.parametrize("fn,what", [(_while_loop, "the statement While"), (_call_unknown, "the call np.exp"),
                                     (_plain_division, "the expression 'w / 2.0'"),
                                     (_unsigned_with_signed, "mixing uint64 and int64"),
                                     (_local_of_an_if, "the name 'x'"),
                                     (_wrong_argument_type, "law_row with arguments"),
                                     (_c_word, "the local name 'default'"), (_chained_compare, "0.0 < w < 1.0"),
                                     (_int_return, "a return as double of C type 'FASTREST_INT64'")])
def test_translator_refuses_what_it_does_not_know(fn, what):
    with pytest.raises(LawTranslationError, match=what) as err:
        translate(fn, "f", ["double", _I, _I], "double")
    assert f"{fn.__name__}, line " in str(err.value)


def test_translator_refuses_material_law():
    # material_law reads first.size: not in the subset (the C header's tables carry FASTREST_N_LAWS)
    with pytest.raises(LawTranslationError, match="first.size"):
        translate(law_cells.material_law, "m", ["const FASTREST_INT64 *", _I, _I, _I], "double")


def test_cli_writes_the_law_header(tmp_path):
    from fastrest.cli import main

    out = tmp_path / "law.h"
    assert main(["export", "c", "--law", "--materials", "0.005:0.33", "0.003:0.3:0.01", "--unloading", "etsion",
                 "--w-max", "40", "--out", str(out)]) == 0
    text = out.read_text()
    assert "#define FASTREST_N_LAWS 2" in text and "etsion" in text and "fastrest_law_step" in text
    assert main(["export", "c", "--law", "--out", str(tmp_path / "x.h")]) == 2
    assert main(["export", "c", "--materials", "0.005:0.33", "--unloading", "etsion",
                 "--out", str(tmp_path / "y.h")]) == 2


def test_docstring_examples_run():
    import doctest

    from fastrest.export import law_c

    result = doctest.testmod(law_c, optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE)
    assert result.attempted > 0 and result.failed == 0


@pytest.mark.cuda   # CI's `-m cuda` run has the gpu extra, whose wheels bring libnvrtc
def test_law_header_compiles_with_nvrtc(tmp_path):
    """NVRTC (no system header) compiles the law header and a kernel stepping contacts, without a
    warning, with --fmad=false (bit for bit with the jit law)."""
    from tests.test_export_c import _nvrtc, _nvrtc_compile

    lib = _nvrtc()
    if lib is None:
        pytest.skip("NVRTC's library (libnvrtc) not found: `pip install nvidia-cuda-nvrtc`, or set FASTREST_NVRTC "
                    "to the library's path")
    text = law_header_text([fastrest.contact_law(0.005, 0.33, w_max=30.0)])
    kernel = ('extern "C" __global__ void fastrest_kernel(double *s, const double *w, double *out, int n) {\n'
              '  int i = blockIdx.x * blockDim.x + threadIdx.x;\n  if (i < n) out[i] = fastrest_law_step('
              'FASTREST_ARRAY(fastrest_law_rows)[0], FASTREST_ARRAY(fastrest_law_first)[0], '
              'FASTREST_ARRAY(fastrest_law_last)[0], FASTREST_ARRAY(fastrest_law_w_end)[0], s + 4 * i, w[i]);\n}\n')
    rc, log, ptx = _nvrtc_compile(lib, text + kernel, ["--gpu-architecture=compute_90", "-std=c++14", "--fmad=false"])
    assert rc == 0 and log.strip() == "", log
    assert ".entry fastrest_kernel" in ptx and "fma.rn.f64" in ptx


@pytest.mark.parametrize("w_max", [500.0, 1e300, np.inf])
def test_a_row_past_the_end_gives_nan_in_c_and_jit(compiled, w_max):
    """A history row whose w_max lies past the law's end (w* = 425: a damaged restart, a code's
    slot overwritten) is no history of the law: NaN and the row set to NaN, in the jit law and
    the C law (docs/export.md), never the elastic branch's force or 0."""
    laws, so, _ = compiled
    law = laws[0]
    w = np.array([0.5, 200.0])
    row = np.array([w_max, 1e3, 0.5 * min(w_max, 1e300), 0.5 * min(w_max, 1e300)])
    ref_out, ref_states = np.empty(w.size), np.empty((w.size, 4))
    _jit_run(law.data, w, row.copy(), ref_out, ref_states)
    assert np.isnan(ref_out).all() and np.isnan(ref_states).all()
    for branching in (0, 1):
        out, states = _c_run(so, 0, w, row.copy(), branching)
        assert np.isnan(out).all() and np.isnan(states).all(), branching
    # the law's end itself is still the law's
    end = law.data.w_max
    state = np.zeros(4)
    assert np.isfinite(frj.contact_force(law.data, state, end)) and np.isfinite(frj.contact_force(law.data, state, 1.0))
