"""The C header of `fastrest export c`: compiled with the system C compiler and compared with the
Python path (the jitted curve kernels behind fastrest.Curve) at >= 1e5 points, cell boundaries and
their neighbours (+/- 1 ulp) included. Reference: fastrest.curve's own data evaluated by
fastrest.curve_data.curve_array, an independent implementation (Numba) of the same rule; the test
requires agreement to 2 ulp (the header is designed to agree bit for bit)."""
import os
import shutil
import subprocess

import numpy as np
import pytest

from fastrest import cli
from fastrest.cells import HERTZ_EDGES
from fastrest.curve_data import curve_array
from fastrest.energy import V_SWITCH
from fastrest.export import c_header
from fastrest.interpolation import cell_edges

CC = shutil.which("cc")
MATERIALS = [(0.005, 0.33), (0.0008, 0.25), (0.0095, 0.42)]

PROGRAM = r"""
#include <stdio.h>
#include <stdlib.h>
#include "scene.h"
int main(int argc, char **argv)
{
    FILE *in = fopen(argv[1], "rb"), *out = fopen(argv[2], "wb");
    long n, i;
    (void)argc;
    if (!in || !out || fread(&n, sizeof n, 1, in) != 1) return 1;
    for (i = 0; i < n; i++) {
        double kv[2], r[9];
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
        fwrite(r, sizeof(double), 9, out);
    }
    return fclose(out) != 0;
}
"""


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


@pytest.mark.skipif(CC is None, reason="no C compiler (`cc`) on PATH: the C header cannot be compiled here")
def test_c_header_matches_python(tmp_path):
    header = tmp_path / "scene.h"
    assert cli.main(["export", "c", "--materials"] + [f"{e}:{n}" for e, n in MATERIALS]
                    + ["--out", str(header)]) == 0
    curves = c_header.scene_curves(MATERIALS)
    (tmp_path / "main.c").write_text(PROGRAM)
    exe = tmp_path / "main"
    r = subprocess.run([CC, "-std=c99", "-O2", "-Wall", "-Wextra", "-pedantic", "-Werror", "-I", str(tmp_path),
                        str(tmp_path / "main.c"), "-o", str(exe), "-lm"], capture_output=True, text=True)
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
    from fastrest.limits import v1_star_limit
    assert f"v_max = {v1_star_limit(0.005, 0.33)!r}" in text
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
