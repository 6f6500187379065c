"""Where a multi-material table evaluation spends its time: ``python -m bench.stencil``.

Times, in one process, on one thread, ns per point (median over rounds):

1. ``fastrest.jit.e_table`` in an @njit loop over 1e6 points above V1* = 1.9^1.25 (where the 6 x 6
   stencil runs), every point its own random material, and all points one material (table data in
   cache: the difference is the cost of memory);
2. the same loop where the table (a tuple of arrays) stays alive across the blocks of an inner
   loop: Numba then counts references to each of its arrays with atomic instructions per point,
   as it did for the arrays the table kernel held across its branches before it read them through
   data pointers;
3. the stencil sum alone, at random positions of an array the size of the table's coefficients
   and at one position: the scalar loop the kernel used before, and the vector-lane intrinsic it
   uses (:func:`fastrest.tables.kernel.stencil_coefficients`, same numbers);
4. the material-axis map alone, xi = expm1(k C(nu) eps_y)/k (two exponentials and a division).

Numbers quoted in README ("What is not done yet").
"""
import math
import time

import numba as nb
import numpy as np

import fastrest
from fastrest import jit as frj
from fastrest.critical import c_of_nu
from fastrest.interpolation import data_pointer
from fastrest.tables.kernel import stencil_coefficients

N = 10**6
ROUNDS = 7


@nb.njit
def table_loop(tab, v, e, nu, out):
    for i in range(v.size):
        out[i] = frj.e_table(tab, v[i], e[i], nu[i], frj.JCG)


@nb.njit
def table_loop_counted(tab, v, e, nu, out):
    for i in range(v.size):
        t = tab  # a new reference to each of the table's arrays, alive across the inner loop's
        r = 0.0  # blocks: Numba counts it (atomically) per point, as the kernel's arrays once were
        for _ in range(1):
            r = frj.e_table(t, v[i], e[i], nu[i], frj.JCG)
        out[i] = r


@nb.njit(inline="always")
def _stencil_scalar(coef, first, row, we, wn):
    c0 = c1 = c2 = c3 = c4 = c5 = 0.0
    for a in range(6):
        for b in range(6):
            w = we[a] * wn[b]
            k = first + a * row + 6 * b
            c0 += w * coef[k]
            c1 += w * coef[k + 1]
            c2 += w * coef[k + 2]
            c3 += w * coef[k + 3]
            c4 += w * coef[k + 4]
            c5 += w * coef[k + 5]
    return c0, c1, c2, c3, c4, c5


@nb.njit
def stencil_scalar(coef, firsts, row, out):
    p = data_pointer(coef)
    for i in range(firsts.size):
        x = 0.1 + 1e-9 * i
        c = _stencil_scalar(p, firsts[i], row, (x, 1 - x, x * x, 0.5, 0.25, x * 0.5), (1 - x, x, 0.3, 0.2, x * x, 0.1))
        out[i] = c[0] + c[1] + c[2] + c[3] + c[4] + c[5]


@nb.njit
def stencil_vector(coef, firsts, row, out):
    p = data_pointer(coef)
    for i in range(firsts.size):
        x = 0.1 + 1e-9 * i
        c = stencil_coefficients(p, firsts[i], row, (x, 1 - x, x * x, 0.5, 0.25, x * 0.5),
                                 (1 - x, x, 0.3, 0.2, x * x, 0.1))
        out[i] = c[0] + c[1] + c[2] + c[3] + c[4] + c[5]


@nb.njit
def xi_map(rate, e, nu, out):
    for i in range(e.size):
        out[i] = math.expm1(rate * (c_of_nu(nu[i]) * e[i])) / rate


def _median_ns(fn, *args):
    fn(*args)
    ts = []
    for _ in range(ROUNDS):
        t0 = time.perf_counter()
        fn(*args)
        ts.append(time.perf_counter() - t0)
    return float(np.median(ts)) / N * 1e9


def main():
    nb.set_num_threads(1)
    tab = fastrest.load_table().data
    rng = np.random.default_rng(1)
    out = np.empty(N)
    v = np.exp(rng.uniform(np.log(2.3), np.log(600.0), N))
    e = rng.uniform(0.0005, 0.01, N)
    nu = rng.uniform(0.2, 0.45, N)
    e1, nu1 = np.full(N, 0.005), np.full(N, 0.33)
    print(f"table coefficients: {tab.coef.nbytes / 2**20:.2f} MiB; 1 thread, ns per point, V1* in [2.3, 600]")
    print(f"jit.e_table loop, random materials          : {_median_ns(table_loop, tab, v, e, nu, out):6.1f}")
    print(f"jit.e_table loop, one material              : {_median_ns(table_loop, tab, v, e1, nu1, out):6.1f}")
    print(f"jit.e_table loop, table counted per point   : {_median_ns(table_loop_counted, tab, v, e, nu, out):6.1f}")
    coef = rng.standard_normal(tab.coef.size)
    row = 6 * tab.n_nu
    firsts = rng.integers(0, coef.size - 6 * row, N)
    same = np.full(N, 12345)
    for name, f in (("scalar loop (before)", stencil_scalar), ("vector lanes (fastrest)", stencil_vector)):
        print(f"{'stencil sum alone, ' + name:44s}: random positions {_median_ns(f, coef, firsts, row, out):6.1f}, "
              f"one position {_median_ns(f, coef, same, row, out):6.1f}")
    print(f"xi = expm1(k C(nu) eps_y)/k alone           : {_median_ns(xi_map, tab.map_rate, e, nu, out):6.1f}")


if __name__ == "__main__":
    main()
