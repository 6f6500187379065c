"""Is an Et/E axis in the shipped table worth its size? ``python -m bench.hardening_axis``.

A table gets an Et/E axis only if measured worth its size. e depends on
h = Et/E through h^(1 - (w - 1) k^2) (Ghaednia et al. 2019's Upsilon), which is not analytic at
h = 0 and whose exponent varies with w: a polynomial axis in h converges slowly. For the Table 1
material and Brake unloading, this fits one Chebyshev polynomial in h (and in sqrt(h)) on [0, 0.5]
through n nodes of the exact solver and measures the worst relative error of e at 401 values of h
(0 and 1e-8 ... 0.5, log-spaced) against the exact solver; it also times building a curve (the
per-material alternative). Writes bench/HARDENING_AXIS.md.
"""
import time
from pathlib import Path

import numpy as np

import fastrest
from fastrest import direct

from .report import machine

EPS_Y, NU, UNLOADING, H_MAX = 0.005, 0.33, "brake", 0.5
SPEEDS = (3.0, 100.0)
NODES = (9, 17, 33, 65)


def _cheb_nodes(a, b, n):
    return (a + b) / 2 + (b - a) / 2 * np.cos(np.pi * np.arange(n) / (n - 1))


def measure():
    hs = np.concatenate([[0.0], np.geomspace(1e-8, H_MAX, 400)])
    rows = []
    for v in SPEEDS:
        ref = direct.e_exact(v, EPS_Y, NU, UNLOADING, et_ratio=hs)
        for n in NODES:
            errs = []
            for tr, inv in ((lambda h: h, lambda u: u), (np.sqrt, np.square)):
                u = _cheb_nodes(0.0, tr(H_MAX), n)
                fit = np.polynomial.chebyshev.Chebyshev.fit(
                    u, direct.e_exact(v, EPS_Y, NU, UNLOADING, et_ratio=inv(u)), n - 1, domain=[0.0, tr(H_MAX)])
                errs.append(float(np.max(np.abs(fit(tr(hs)) / ref - 1))))
            rows.append((v, n, *errs))
    t = time.perf_counter()
    fastrest.curve(EPS_Y, NU, UNLOADING, et_ratio=0.05)
    return rows, time.perf_counter() - t


def main():
    rows, t_curve = measure()
    m = machine()
    size = Path(fastrest.__file__).parent.joinpath("tables", "default.h5").stat().st_size / 1e6
    lines = ["# An Et/E axis for the table? (`python -m bench.hardening_axis`)", "",
             f"Machine: {m.get('nproc')}-core {m.get('cpu')}; material eps_y = {EPS_Y}, nu = {NU}, {UNLOADING} "
             f"unloading, Et/E in [0, {H_MAX}].", "",
             "Worst relative error of e from one Chebyshev polynomial in h (or sqrt h) through n nodes:", "",
             "| V1* | n | in h | in sqrt(h) |", "| --- | --- | --- | --- |"]
    lines += [f"| {v:g} | {n} | {a:.1e} | {b:.1e} |" for v, n, a, b in rows]
    lines += ["", f"The shipped table is {size:.1f} MB over (V1*, eps_y, nu); an Et/E axis reaching the table's "
              "~1e-9 at V1* = 100 needs about 33 nodes even in sqrt(h) (17 give 1.4e-7), i.e. a table about "
              f"33x larger (~{33 * size:.0f} MB). "
              f"A curve for one hardening material builds in {t_curve * 1e3:.0f} ms and is as accurate as a JG "
              "curve: no Et/E axis is shipped."]
    out = Path(__file__).with_name("HARDENING_AXIS.md")
    out.write_text("\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
