"""Where a multi-material table evaluation spends its time: ``python -m bench.stencil``.

Times, in one process, (1) the 6 x 6 stencil sum of the table kernel (the loop form fastrest uses and a
fully unrolled form) at random table positions and at one position (cache-hot), on an array the size of
the shipped table's coefficients; (2) ``fastrest.jit.e_table`` over 1e6 random materials on the table as
loaded and on a copy in 2 MiB-aligned memory advised to use huge pages. Prints ns per point (median
over rounds). Numbers quoted in README ("What is not done yet").
"""
import mmap
import time

import numba as nb
import numpy as np

import fastrest
from fastrest import jit as frj

N = 10**6
ROW = 384  # 6 eps nodes x (6 nu nodes x 6 coefficients) doubles between eps rows, as the table


@nb.njit(inline="always")
def stencil_loop(coef, first, row, we, wn):
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
    return c0 + c1 + c2 + c3 + c4 + c5


def _unrolled_source():
    lines = ["def stencil_unrolled(coef, first, row, we, wn):", "    e0, e1, e2, e3, e4, e5 = we",
             "    n0, n1, n2, n3, n4, n5 = wn"]
    for c in range(6):
        terms = [f"e{a} * (" + " + ".join(f"n{b} * coef[first + {a} * row + {6 * b + c}]" for b in range(6)) + ")"
                 for a in range(6)]
        lines.append(f"    c{c} = " + " + ".join(terms))
    lines.append("    return c0 + c1 + c2 + c3 + c4 + c5")
    return "\n".join(lines)


_ns = {}
exec(_unrolled_source(), _ns)
stencil_unrolled = nb.njit(inline="always")(_ns["stencil_unrolled"])


def _driver(f):
    @nb.njit
    def run(coef, firsts, out):
        for i in range(firsts.size):
            x = 0.1 + 1e-9 * i
            out[i] = f(coef, firsts[i], ROW, (x, 1 - x, x * x, 0.5, 0.25, x * 0.5), (1 - x, x, 0.3, 0.2, x * x, 0.1))
    return run


@nb.njit
def table_loop(tab, v, e, nu, out):
    for i in range(v.size):
        out[i] = frj.e_table(tab, v[i], e[i], nu[i], frj.JCG)


def _median_ns(fn, *args, rounds=7):
    fn(*args)
    ts = []
    for _ in range(rounds):
        t0 = time.perf_counter()
        fn(*args)
        ts.append(time.perf_counter() - t0)
    return float(np.median(ts)) / N * 1e9


def _huge_page_copy(a):
    size = ((a.nbytes >> 21) + 2) << 21
    buf = mmap.mmap(-1, size, flags=mmap.MAP_PRIVATE | mmap.MAP_ANONYMOUS)
    buf.madvise(mmap.MADV_HUGEPAGE)
    raw = np.frombuffer(buf, dtype=np.uint8)
    off = (-raw.ctypes.data) % (2 << 20)
    out = raw[off:off + a.nbytes].view(a.dtype)
    out[:] = a
    return out


def main():
    tab = fastrest.load_table().data
    coef = np.random.default_rng(0).standard_normal(tab.coef.size)
    rng = np.random.default_rng(1)
    firsts = rng.integers(0, coef.size - 3000, N)
    same = np.full(N, 12345)
    out = np.empty(N)
    print(f"table coefficients: {tab.coef.nbytes / 2**20:.2f} MiB")
    for name, f in (("loop (as fastrest)", stencil_loop), ("unrolled", stencil_unrolled)):
        run = _driver(f)
        print(f"stencil {name:20s}: random positions {_median_ns(run, coef, firsts, out):6.1f} ns, "
              f"one position {_median_ns(run, coef, same, out):6.1f} ns")
    v = np.exp(rng.uniform(np.log(2.3), np.log(60.0), N))
    e = rng.uniform(0.0005, 0.01, N)
    nu = rng.uniform(0.2, 0.45, N)
    huge = tab._replace(coef=_huge_page_copy(tab.coef))
    for name, t in (("as loaded", tab), ("huge pages", huge)):
        print(f"jit.e_table, random materials, {name:10s}: {_median_ns(table_loop, t, v, e, nu, out):6.1f} ns")


if __name__ == "__main__":
    main()
