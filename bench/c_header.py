"""The C header of ``fastrest export c``: ns per point against ``Curve.e``.

``python -m bench.c_header [--quick]`` generates a header for four materials, compiles a timing
program with the system C compiler (``cc -std=c99 -O2``, and again with ``-march=native`` so
``fma`` is one instruction), and times ``fastrest_e`` over random V1* (log-uniform over each
material's range, random material per point) in a loop summing the results; then times the same
points through ``fastrest.Curve.e`` (array call, and scalar calls from Python) and
``fastrest.jit.e_curve`` in an ``@njit`` loop. Prints a small table (best of several rounds).
"""
import argparse
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numba
import numpy as np

import fastrest
from fastrest import jit as frj
from fastrest.export import c_header

MATERIALS = [(0.005, 0.33), (0.001, 0.3), (0.0095, 0.42), (0.0005, 0.25)]

PROGRAM = r"""
#define _POSIX_C_SOURCE 199309L
#include <stdio.h>
#include <stdlib.h>
#include <time.h>
#include "scene.h"
int main(int argc, char **argv)
{
    long n = atol(argv[2]), i;
    int rounds = atoi(argv[3]), r;
    double *v = malloc(n * sizeof *v), best = 1e30, sum = 0.0;
    int *k = malloc(n * sizeof *k);
    FILE *in = fopen(argv[1], "rb");
    for (i = 0; i < n; i++) {
        double kv[2];
        if (fread(kv, sizeof(double), 2, in) != 2) return 1;
        k[i] = (int)kv[0];
        v[i] = kv[1];
    }
    for (r = 0; r < rounds; r++) {
        struct timespec t0, t1;
        double dt;
        clock_gettime(CLOCK_MONOTONIC, &t0);
        for (i = 0; i < n; i++)
            sum += fastrest_e(k[i], v[i], FASTREST_JCG);
        clock_gettime(CLOCK_MONOTONIC, &t1);
        dt = (t1.tv_sec - t0.tv_sec) + 1e-9 * (t1.tv_nsec - t0.tv_nsec);
        if (dt < best) best = dt;
    }
    printf("%.4f %.17g\n", 1e9 * best / n, sum);
    return 0;
}
"""


@numba.njit
def _njit_loop(data, v):
    s = 0.0
    for i in range(v.size):
        s += frj.e_curve(data, v[i])
    return s


def _best(fn, rounds):
    best = np.inf
    for _ in range(rounds):
        t0 = time.perf_counter()
        fn()
        best = min(best, time.perf_counter() - t0)
    return best


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--quick", action="store_true", help="fewer points and rounds (checks the script runs)")
    args = p.parse_args(argv)
    n, rounds = (20_000, 3) if args.quick else (2_000_000, 7)
    cc = shutil.which("cc")
    if cc is None:
        print("no C compiler (cc) on PATH", file=sys.stderr)
        return 1
    rng = np.random.default_rng(1)
    curves = [fastrest.curve(e, nu) for e, nu in MATERIALS]
    k = rng.integers(0, len(MATERIALS), n)
    vmax = np.array([c.v_max for c in curves])
    v = np.exp(rng.uniform(0.0, 1.0, n) * np.log(vmax[k]))
    rows = []
    with tempfile.TemporaryDirectory() as d:
        d = Path(d)
        c_header.write_header(d / "scene.h", MATERIALS)
        (d / "bench.c").write_text(PROGRAM)
        with open(d / "in.bin", "wb") as fh:
            np.stack([k.astype(np.float64), v], 1).tofile(fh)
        for label, flags in (("C, cc -O2", ["-O2"]), ("C, cc -O2 -march=native", ["-O2", "-march=native"])):
            exe = d / "bench"
            subprocess.run([cc, "-std=c99", *flags, "-I", str(d), str(d / "bench.c"), "-o", str(exe), "-lm"],
                           check=True)
            out = subprocess.run([str(exe), str(d / "in.bin"), str(n), str(rounds)], check=True,
                                 capture_output=True, text=True).stdout.split()
            rows.append((label, float(out[0])))
    # Python paths, one material (the curve's data) per call
    c0 = curves[0]
    v0 = np.exp(rng.uniform(0.0, 1.0, n) * np.log(c0.v_max))
    c0.e(v0[:10])
    _njit_loop(c0.data, v0[:10])
    rows.append(("fastrest.jit.e_curve in an @njit loop", 1e9 * _best(lambda: _njit_loop(c0.data, v0), rounds) / n))
    rows.append(("Curve.e(array)", 1e9 * _best(lambda: c0.e(v0), rounds) / n))
    m = min(n, 200_000)
    vl = [float(x) for x in v0[:m]]
    rows.append(("Curve.e(float) from Python", 1e9 * _best(lambda: [c0.e(x) for x in vl], rounds) / m))
    print(f"fastrest_e (C header) against Curve.e: {n} points, best of {rounds} rounds")
    print(f"{'path':<42s} {'ns/point':>9s}")
    for label, ns in rows:
        print(f"{label:<42s} {ns:9.2f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
