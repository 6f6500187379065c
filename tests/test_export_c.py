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

import fastrest
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


# --- a header from physical properties (issue 21 item 7) ------------------------------------------

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
    assert "#define FASTREST_HAS_CRITICAL 1" in text and "static inline double fastrest_v1_star(int k, double V)" in text
    assert "--E 200000000000.0" in text and "--V-max 5.0" in text
    imp = fastrest.Impact(fastrest.Material(200e9, 0.33, 1.12e9, rho=7850), 0.01)
    assert f"fastrest_V_c[FASTREST_N_MATERIALS] = {{{imp.V_c.hex()}}}" in text
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
