"""Rough-surface benchmarks: ``python -m bench.rough [--quick] [--out bench/ROUGH.md]``.

Measures, after warm-up (JIT compilation excluded; every kernel is loaded once first):

* one impact of a rigid flat on 1e6 explicit summits (target <= 0.2 s on 2 cores), for a light, a
  typical and a heavy impact, with the surface's forward table already built ("warm") and on a
  fresh RoughSurface ("cold": constructor, Hertz estimate and forward-table build included);
* one impact on a statistical (Greenwood-Williamson) surface (target <= 1 ms), and per impact in
  a batch of 1000 speeds;
* the brute-force path (``tests/rough_reference.reference_impact``: per-summit quadrature + scipy
  brentq) on 100 summits against ``RoughSurface.impact``, with the speed-up and the difference in e_s;
* building the forward table up to w* = 425, and the forward kernels per point inside ``@njit``.

Timing, machine description and load averages come from the shared harness (:mod:`bench.timing`,
:mod:`bench.report`, :mod:`bench.run`): cases are timed in interleaved rounds (shuffled order per
round) and reported as median and minimum over rounds. Run from the repository root (the brute
force lives in tests/).
"""
import argparse
import math
import time
from pathlib import Path

import numba as nb
import numpy as np

import fastrest
from fastrest import forward as fw
from fastrest import rough
from tests.rough_reference import reference_impact

from .report import machine, versions
from .run import loadavg
from .timing import fmt_time as fmt
from .timing import interleaved

STEEL = fastrest.Material(E=200e9, nu=0.3, Sy=1e9)
R_A = 100e-6
M = 0.01
OMEGA_C = fastrest.Impact(STEEL, R_A, mass=M).omega_c
TARGET_EXPLICIT = 0.2
TARGET_STAT = 1e-3


def timed(cases, rounds, min_block=0.05):
    """{name: fn} -> {name: (median, min) seconds per call}, interleaved rounds (bench.timing)."""
    t = interleaved({k: (fn, 1) for k, fn in cases.items()}, rounds, min_block=min_block)
    return {k: (v.median, v.min) for k, v in t.items()}


def threading_layer():
    """Numba's threading layer, once a parallel kernel has run (a rough impact runs one)."""
    try:
        return nb.threading_layer()
    except ValueError:
        return "?"


def verdict(med, mn, target):
    if med <= target:
        return "met"
    if mn <= target:
        return "met by the minimum, **missed** by the median"
    return "**missed**"


def bench_explicit(rounds, n=10**6, psi=2.0):
    sigma = psi**2 * OMEGA_C
    z = rough.gaussian_summits(n, sigma, seed=1)
    warm = rough.RoughSurface(STEEL, R_A, heights=z)
    scenes = {"light": 0.01, "typical": 0.1, "heavy": 1.0}
    rows = []
    cases = {}
    info = {}
    for label, v in scenes.items():
        r = warm.impact(v, M)
        info[label] = r
        cases[f"{label} warm"] = (lambda v=v: warm.impact(v, M))
        cases[f"{label} cold"] = (lambda v=v: rough.RoughSurface(STEEL, R_A, heights=z).impact(v, M))
    t_ctor = timed({"ctor": lambda: rough.RoughSurface(STEEL, R_A, heights=z)}, rounds)["ctor"]
    times = timed(cases, rounds, min_block=0.0)
    for label, v in scenes.items():
        r = info[label]
        (w_med, w_min), (c_med, c_min) = times[f"{label} warm"], times[f"{label} cold"]
        rows.append({
            "scene": label, "V1": v, "contact": int(r.n_contact), "yielded": int(r.n_yielded),
            "e": r.e, "w_max": r.w_star_max, "warm_med": w_med, "warm_min": w_min,
            "cold_med": c_med, "cold_min": c_min,
        })
    return {"n": n, "psi": psi, "sigma": sigma, "rows": rows, "ctor": t_ctor[0]}


def bench_statistical(rounds):
    rows = []
    cases = {}
    surfaces = {}
    for psi in (0.5, 1.0, 2.0, 4.0):
        s = rough.RoughSurface(STEEL, R_A, gw=dict(eta=1e10, sigma=psi**2 * OMEGA_C, A_n=1e-4))
        surfaces[psi] = s
        for v in (0.01, 1.0):
            s.impact(v, M)
            cases[(psi, v)] = (lambda s=s, v=v: s.impact(v, M))
    batch_v = np.geomspace(1e-3, 3.0, 1000)
    for psi, s in surfaces.items():
        s.impact(batch_v, M)
        cases[(psi, "batch")] = (lambda s=s: s.impact(batch_v, M))
    times = timed(cases, rounds)
    for psi, s in surfaces.items():
        for v in (0.01, 1.0):
            r = s.impact(v, M)
            med, mn = times[(psi, v)]
            rows.append({"psi": psi, "V1": v, "contact": r.n_contact, "e": r.e, "med": med, "min": mn})
        med, mn = times[(psi, "batch")]
        rows.append({"psi": psi, "V1": "1000 speeds", "contact": math.nan, "e": math.nan,
                     "med": med / batch_v.size, "min": mn / batch_v.size})
    return rows


def bench_brute(rounds, n=100, psi=2.0, v=0.1):
    z = rough.gaussian_summits(n, psi**2 * OMEGA_C, seed=2)
    s = rough.RoughSurface(STEEL, R_A, heights=z)
    fast = s.impact(v, M)
    ref = reference_impact(STEEL, R_A, z, v, M)
    times = timed({"fast": lambda: s.impact(v, M),
                   "brute": lambda: reference_impact(STEEL, R_A, z, v, M)}, max(3, rounds // 2))
    return {"n": n, "V1": v, "contact": fast.n_contact, "fast": times["fast"][0],
            "brute": times["brute"][0], "fast_min": times["fast"][1],
            "brute_min": times["brute"][1], "de": abs(fast.e - ref["e"]), "e": fast.e}


@nb.njit
def _loop_F(data, w):
    s = 0.0
    for i in range(w.size):
        s += fw.F_forward(data, w[i])
    return s


@nb.njit
def _loop_P(data, w):
    s = 0.0
    for i in range(w.size):
        s += fw.P_forward(data, w[i])
    return s


@nb.njit
def _loop_Pt(data, w):
    s = 0.0
    for i in range(w.size):
        s += fw.P_table_forward(data, w[i])
    return s


@nb.njit
def _loop_FPt(data, w):
    s = 0.0
    for i in range(w.size):
        f, p = fw.FP_table_forward(data, w[i])
        s += f + p
    return s


@nb.njit
def _loop_values(data, w):
    s = 0.0
    for i in range(w.size):
        f, p, r, loss = fw.forward_values(data, w[i])
        s += f + p + r + loss
    return s


def bench_forward(rounds):
    eps, nu = STEEL.Sy / (STEEL.E / (1 - STEEL.nu**2)), STEEL.nu
    build = timed({"build": lambda: fw.forward_data(eps, nu, w_max=425.0)}, rounds)["build"]
    data = fw.forward_data(eps, nu, w_max=425.0)
    w_jg = np.random.default_rng(0).uniform(1.9, 425.0, 10**6)
    w_h = np.random.default_rng(0).uniform(0.0, 1.9, 10**6)
    cases = {}
    for name, fn in (("F_forward", _loop_F), ("P_forward", _loop_P), ("P_table_forward", _loop_Pt),
                     ("FP_table_forward", _loop_FPt), ("forward_values", _loop_values)):
        cases[(name, "JG")] = (lambda fn=fn: fn(data, w_jg))
        cases[(name, "Hertz")] = (lambda fn=fn: fn(data, w_h))
    times = timed(cases, rounds)
    per = {k: v[0] / 1e6 for k, v in times.items()}
    return {"build": build[0], "build_min": build[1], "cells": data.f_rows.shape[0], "per_point": per}


def report(m, load0, load1, ex, st, br, fo, quick):
    L = []
    L.append("# Rough-surface benchmarks\n")
    L.append("Generated by `python -m bench.rough" + (" --quick" if quick else "") + "` "
             f"({time.strftime('%Y-%m-%d')}). Medians (and minima) over interleaved rounds, JIT "
             "compilation excluded.\n")
    L.append("## Machine\n")
    for k, v in m.items():
        L.append(f"- {k}: {v}")
    L.append(f"- load average before / after: {load0} / {load1} "
             "(other work on the machine slows parallel regions; see below)\n")
    L.append(f"Scene: steel summits (E = 200 GPa, nu = 0.3, Sy = 1 GPa), R_a = 100 um "
             f"(omega_c = {OMEGA_C * 1e9:.2f} nm), rigid flat of M = {M} kg, JCG unloading.\n")
    L.append(f"## One impact on {ex['n']:.0e} explicit summits (target <= {TARGET_EXPLICIT} s)\n")
    L.append(f"Gaussian heights, psi = {ex['psi']:g} (sigma = {ex['sigma'] * 1e9:.1f} nm). *warm*: "
             "the surface exists and holds its forward table; *cold*: a new RoughSurface "
             f"(constructor {fmt(ex['ctor'])}, Hertz estimate, table build) and its first impact.\n")
    L.append("| scene | V1 (m/s) | in contact | yielded | e_s | w* tallest | warm | cold | target |")
    L.append("|---|---|---|---|---|---|---|---|---|")
    for r in ex["rows"]:
        ok = verdict(r["warm_med"], r["warm_min"], TARGET_EXPLICIT)
        L.append(f"| {r['scene']} | {r['V1']:g} | {r['contact']:,} | {r['yielded']:,} | {r['e']:.4f} | "
                 f"{r['w_max']:.3g} | {fmt(r['warm_med'])} ({fmt(r['warm_min'])}) | "
                 f"{fmt(r['cold_med'])} ({fmt(r['cold_min'])}) | {ok} |")
    L.append("")
    L.append(f"## One impact on a statistical surface (target <= {TARGET_STAT * 1e3:g} ms)\n")
    L.append("Greenwood-Williamson, Gaussian heights, eta = 1e10 /m^2, A_n = 1 cm^2 (N = 1e6); "
             "warm (forward table built). '1000 speeds': one call with 1000 speeds, time per impact "
             "(parallel over speeds).\n")
    L.append("| psi | V1 (m/s) | expected contacts | e_s | time per impact | target |")
    L.append("|---|---|---|---|---|---|")
    for r in st:
        ok = verdict(r["med"], r["min"], TARGET_STAT)
        c = "" if isinstance(r["V1"], str) else f"{r['contact']:.4g}"
        e = "" if isinstance(r["V1"], str) else f"{r['e']:.4f}"
        L.append(f"| {r['psi']:g} | {r['V1']} | {c} | {e} | {fmt(r['med'])} ({fmt(r['min'])}) | {ok} |")
    L.append("")
    L.append("## Brute force against the fast path\n")
    L.append(f"{br['n']} explicit summits, V1 = {br['V1']} m/s ({br['contact']} in contact, e_s = "
             f"{br['e']:.6f}). Brute force: `tests/rough_reference.reference_impact` (per-summit "
             "`energy.f_star_kernel` quadrature, `scipy.optimize.brentq`).\n")
    L.append("| path | time | speed-up |")
    L.append("|---|---|---|")
    L.append(f"| brute force | {fmt(br['brute'])} ({fmt(br['brute_min'])}) | 1 |")
    L.append(f"| RoughSurface.impact | {fmt(br['fast'])} ({fmt(br['fast_min'])}) | "
             f"{br['brute'] / br['fast']:.0f}x |")
    L.append(f"\n|e_s(fast) - e_s(brute)| = {br['de']:.1e}.\n")
    L.append("## Forward map\n")
    L.append(f"`forward_data(eps_y, nu, w_max=425)`: {fo['cells']} cells, built in "
             f"{fmt(fo['build'])} ({fmt(fo['build_min'])}). Per point inside `@njit` (serial loop "
             "of 1e6 random w*):\n")
    L.append("| kernel | 0 <= w* <= 1.9 (Hertz) | 1.9 < w* <= 425 (JG) |")
    L.append("|---|---|---|")
    for name in ("F_forward", "P_forward", "P_table_forward", "FP_table_forward", "forward_values"):
        L.append(f"| {name} | {fmt(fo['per_point'][(name, 'Hertz')])} | "
                 f"{fmt(fo['per_point'][(name, 'JG')])} |")
    L.append("")
    L.append("## Notes\n")
    L.append("- Explicit impacts cost one pass over all summits per Newton step (~1 ns per summit "
             "out of contact) plus the forward kernels for the summits in contact (F from the "
             "table, the Newton slope P* from its table, the final pass with the exact P* and the "
             "JCG residual). The heavy scene, every summit in contact and yielded, is the worst "
             "case; time grows with the number of yielded summits.")
    L.append("- A single statistical impact runs serially (no parallel start-up); batches of speeds "
             "run in parallel.")
    L.append("- When another process keeps both cores busy, every parallel region waits for its "
             "threads: explicit impacts then take several times longer. Compare minima, and the "
             "load averages above.")
    return "\n".join(L) + "\n"


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="fewer rounds (about 30 s)")
    ap.add_argument("--out", default=str(Path(__file__).with_name("ROUGH.md")))
    a = ap.parse_args(argv)
    rounds = 3 if a.quick else 9
    load0 = loadavg()
    ex = bench_explicit(rounds)
    st = bench_statistical(rounds)
    br = bench_brute(rounds)
    fo = bench_forward(rounds)
    load1 = loadavg()
    m = {**machine(), **versions(), "numba threads (used)": nb.get_num_threads(),
         "threading layer": threading_layer()}
    text = report(m, load0, load1, ex, st, br, fo, a.quick)
    Path(a.out).write_text(text)
    print(text)
    print(f"wrote {a.out}")


if __name__ == "__main__":
    main()
