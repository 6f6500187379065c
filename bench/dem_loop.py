"""The contact law in the loop DEM codes write (step-major), against a Hertz force with a history slot.

``python -m bench.dem_loop [--quick]`` writes bench/DEM_LOOP.md.

A DEM code steps every contact at every time step: for each step, for each contact, the force
from the contact's interference and its history row. Here every contact follows its own path
w(t) (a triangle wave of its own phase, rate and amplitude, the amplitude growing by 10 % a
cycle for 8 cycles, then the contact ends, its row is zeroed and a new one starts): virgin
loading, unloading, reloading and time apart (w < w_res* or w < 0) are mixed across contacts at
every step, as in a granular flow. The loops, each in the same run, interleaved:

* ``empty``: the path only (out[i] = w): the loop's own cost, subtracted ("net");
* ``hertz``: ``w*sqrt(w)`` (0 for w <= 0) with one history slot (the largest overlap);
* ``contact_force`` of one law (JCG, Etsion, Brake; Brake with Et/E = 0.01: Ghaednia et al.);
* ``contact_force_stacked`` over three materials, a material index per contact;
* ``0.2 kernel``: fastrest 0.2's contact_force (branches on the state, the residual computed
  when a contact first unloads), kept here for the ratio;
* a DEM-shaped variant (forces scattered to the two particles of each contact, f[i] += P,
  f[j] -= P), where no compiler vectorises the Hertz loop either;

at 1e4 contacts (cache-resident) and 1e6 (not), serial, and ``numba.prange`` on all threads at
1e6. Whether each loop vectorised is read from its LLVM IR (vector types in the function), and
LLVM's own reason for the law's loop from its loop-vectorizer remarks (a child process).
"""
import argparse
import datetime
import math
import os
import re
import subprocess
import sys
from pathlib import Path

import numba
import numpy as np

import fastrest
from fastrest import jit as frj
from fastrest import unloading as _unloading
from fastrest.force_law import stack_laws
from fastrest.interpolation import cell_index, cell_polynomial
from fastrest.loading.jackson_green import W_SWITCH
from fastrest.unloading import elastic

from . import report
from .timing import interleaved, with_threads

REPO = Path(__file__).resolve().parent.parent
CYCLES = 8         # cycles of one contact before it ends and a new one starts
GROWTH = 0.1       # amplitude growth per cycle (virgin loading in every cycle)


@numba.njit(inline="always")
def path(t, phase, rate, lo, hi0):
    """(w, new): the interference of a contact at step t and whether a new contact starts now."""
    x = phase + t * rate
    c = np.floor(x)
    u = x - c
    k = c - CYCLES * np.floor(c / CYCLES)  # cycle of this contact, 0 .. CYCLES - 1
    hi = hi0 * (1.0 + GROWTH * k)
    w = lo * hi + (hi - lo * hi) * (1.0 - abs(2.0 * u - 1.0))
    return w, (k == 0.0) & (u < rate)


@numba.njit(inline="always")
def f_empty(data, m, row, w):
    return w


@numba.njit(inline="always")
def f_hertz(data, m, row, w):
    h = row[0]
    row[0] = w if w > h else h
    return w * math.sqrt(w) if w > 0.0 else 0.0


@numba.njit(inline="always")
def f_law(data, m, row, w):
    return frj.contact_force(data, row, w)


@numba.njit(inline="always")
def f_stacked(data, m, row, w):
    return frj.contact_force_stacked(data, m, row, w)


@numba.njit(inline="always")
def f_old(law, m, state, w):
    """fastrest 0.2's contact_force (its _force_step), for the ratio."""
    w_max = state[0]
    if w > w_max and w_max >= 0.0:
        if w <= W_SWITCH:
            p = w * math.sqrt(w)
        elif w <= law.w_max:
            p = cell_polynomial(law.p_rows, cell_index(w, law.shift, law.base), w)
        else:
            p = np.nan
        if p == p:
            state[0] = w
            state[1] = p
            state[3] = 0.0
            return p
    elif w_max > 0.0:
        if state[3] == 0.0:
            w_res, delta = _unloading.residual(law.model, w_max, w_max - 1.0, state[1], law.eps_y, law.nu, law.law,
                                               law.et_ratio)
            state[2] = w_res
            state[3] = delta
        if w > -math.inf:
            return elastic.force(w, w_max, state[1], state[2], state[3])
    elif w <= 0.0 and w > -math.inf and w_max == 0.0:
        return 0.0
    state[0] = state[1] = state[2] = state[3] = np.nan
    return np.nan


FORCES = {"empty": f_empty, "hertz": f_hertz, "law": f_law, "stacked": f_stacked, "old": f_old}


def step_loop(force, parallel, turnover=False):
    """The step-major loop: for each step, for each contact, path -> force (-> out[i]); with
    ``turnover`` a contact that ends has its row zeroed in the loop (a new contact starts)."""
    over = numba.prange if parallel else range
    if turnover:
        @numba.njit(parallel=parallel)
        def run(t0, nsteps, phase, rate, lo, hi0, data, mat, state, out):
            for t in range(t0, t0 + nsteps):
                for i in over(phase.size):
                    w, new = path(t, phase[i], rate[i], lo[i], hi0[i])
                    if new:
                        state[i, :] = 0.0
                    out[i] = force(data, mat[i], state[i], w)
        return run

    @numba.njit(parallel=parallel)
    def run_plain(t0, nsteps, phase, rate, lo, hi0, data, mat, state, out):
        for t in range(t0, t0 + nsteps):
            for i in over(phase.size):
                w, _ = path(t, phase[i], rate[i], lo[i], hi0[i])
                out[i] = force(data, mat[i], state[i], w)
    return run_plain


def scatter_loop(force):
    """The DEM shape: contact i between particles a[i] and b[i], its force added to both."""
    @numba.njit
    def run(t0, nsteps, phase, rate, lo, hi0, data, mat, state, pa, pb, f):
        for t in range(t0, t0 + nsteps):
            for i in range(phase.size):
                w, new = path(t, phase[i], rate[i], lo[i], hi0[i])
                if new:
                    state[i, :] = 0.0
                p = force(data, mat[i], state[i], w)
                f[pa[i]] += p
                f[pb[i]] -= p
    return run


@numba.njit
def census(t0, nsteps, phase, rate, lo, hi0, law, state, turnover):
    """Share of contact-steps in virgin loading, elastic contact (P > 0 below w_max), apart."""
    virgin = elastic_n = apart = 0
    for t in range(t0, t0 + nsteps):
        for i in range(phase.size):
            w, new = path(t, phase[i], rate[i], lo[i], hi0[i])
            if new and turnover:
                state[i, :] = 0.0
            top = state[i, 0]
            p = frj.contact_force(law, state[i], w)
            if w > top:
                virgin += 1
            elif p > 0.0:
                elastic_n += 1
            else:
                apart += 1
    n = virgin + elastic_n + apart
    return virgin / n, elastic_n / n, apart / n


def contacts(n, seed=1):
    rng = np.random.default_rng(seed)
    phase = rng.uniform(0.0, CYCLES, n)
    rate = rng.uniform(0.004, 0.02, n)              # 50 .. 250 steps per cycle
    hi0 = np.exp(rng.uniform(math.log(0.5), math.log(50.0), n))
    lo = np.full(n, -0.3)                           # apart for the bottom 30 % of each cycle's swing
    return phase, rate, lo, hi0


def laws():
    return {"jcg": fastrest.contact_law(0.005, 0.33, "jcg").data,
            "etsion": fastrest.contact_law(0.005, 0.33, "etsion").data,
            "brake": fastrest.contact_law(0.005, 0.33, "brake").data,
            "brake, Et/E = 0.01": fastrest.contact_law(0.005, 0.33, "brake", et_ratio=0.01).data}


def stacked():
    return stack_laws([fastrest.contact_law(0.005, 0.33), fastrest.contact_law(0.002, 0.3),
                       fastrest.contact_law(0.008, 0.25, "brake")])


def vectorised(dispatcher):
    """True when the compiled loop holds vector instructions (LLVM vector types in its IR)."""
    ir = "\n".join(dispatcher.inspect_llvm().values())
    return bool(re.search(r"<[248] x double>", ir))


def remarks_of_law_loop():
    """LLVM's loop-vectorizer remarks for the law's step loop (child process: the options are global)."""
    code = ("import llvmlite.binding as llvm, sys, numpy as np\n"
            "from bench import dem_loop as d\n"
            "run = d.step_loop(d.f_law, False, False)\n"
            "law = d.laws()['jcg']\n"
            "c = d.contacts(16)\n"
            "st = np.zeros((16, 4)); out = np.zeros(16); m = np.zeros(16, np.int64)\n"
            "print('=====', file=sys.stderr, flush=True)\n"
            "llvm.set_option('', '-pass-remarks-missed=loop-vectorize')\n"
            "llvm.set_option('', '-pass-remarks-analysis=loop-vectorize')\n"
            "run(0, 1, *c, law, m, st, out)\n")
    env = dict(os.environ, NUMBA_CACHE_DIR=os.environ.get("NUMBA_CACHE_DIR", "/nonexistent-cache"))
    r = subprocess.run([sys.executable, "-c", code], cwd=REPO, capture_output=True, text=True, env=env)
    text = r.stderr.split("=====", 1)[-1]
    seen = []
    for line in text.splitlines():
        m = re.search(r"remark: .*?: (.*)", line)
        if m and m.group(1) not in seen:
            seen.append(m.group(1))
    return seen


class _Contacts:
    """The contacts of one measurement: paths, laws, material indices."""

    def __init__(self, n):
        self.n = n
        self.path = contacts(n)
        self.laws, self.stacked = laws(), stacked()
        self.mat = np.random.default_rng(2).integers(0, 3, n)
        self.zero = np.zeros(n, dtype=np.int64)

    def case(self, kind, which, nsteps, parallel, turnover, threads):
        """(compiled loop, (fn, evaluations)) of one step loop; fn runs ``nsteps`` steps of every
        contact. With turnover the paths go on from call to call (the mix of states stays that of
        a running flow, rows reset inside the loop); without, every call zeroes the rows first, and
        every contact starts virgin at its own point of its path."""
        run = step_loop(FORCES[kind], parallel, turnover)
        data = self.stacked if kind == "stacked" else self.laws[which or "jcg"]
        state = np.zeros((self.n, 1 if kind in ("hertz", "empty") else frj.STATE_SIZE))
        out = np.zeros(self.n)
        m = self.mat if kind == "stacked" else self.zero
        clock = [0]

        def fn():
            if turnover:
                run(clock[0], nsteps, *self.path, data, m, state, out)
                clock[0] += nsteps
            else:
                state[:] = 0.0
                run(0, nsteps, *self.path, data, m, state, out)
        return run, (with_threads(threads, fn) if threads else fn, self.n * nsteps)


def measure(n, nsteps, rounds, turnover=False):
    """Every loop of the plan, serial, in one interleaved run: ({name: Timing}, {name: loop})."""
    c = _Contacts(n)
    plan = [("empty", "empty", None), ("hertz", "hertz", None)]
    plan += [(f"contact_force ({k})", "law", k) for k in c.laws]
    plan += [("contact_force_stacked (3 materials)", "stacked", None), ("0.2 kernel (jcg)", "old", "jcg")]
    cases, loops = {}, {}
    for name, kind, which in plan:
        loops[name], cases[name] = c.case(kind, which, nsteps, False, turnover, None)
    return interleaved(cases, rounds, ref="empty"), loops


def prange_measure(n, nsteps, rounds, threads):
    """Serial and prange loops of the same kinds in one interleaved run (with contact turnover: the
    rows are reset inside the loop, so nothing serial runs outside it)."""
    c = _Contacts(n)
    cases = {}
    for name, kind in (("empty", "empty"), ("hertz", "hertz"), ("contact_force (jcg)", "law"),
                       ("contact_force_stacked (3 materials)", "stacked")):
        for parallel in (False, True):
            label = f"{name} | {'prange' if parallel else 'serial'}"
            cases[label] = c.case(kind, None, nsteps, parallel, True, threads if parallel else None)[1]
    return interleaved(cases, rounds, ref="empty | serial")


def net(t, name, ref):
    """Median over rounds of (name - empty) / (ref - empty), and name's net ns (median)."""
    e = t["empty"].per_eval
    a, b = t[name].per_eval - e, t[ref].per_eval - e
    return float(np.median(a / b)), float(np.median(a)) * 1e9


def scatter_measure(n, nsteps, rounds):
    phase, rate, lo, hi0 = contacts(n)
    law = laws()["jcg"]
    rng = np.random.default_rng(3)
    n_part = n // 2
    pa, pb = rng.integers(0, n_part, n), rng.integers(0, n_part, n)
    zero = np.zeros(n, dtype=np.int64)
    cases, loops = {}, {}
    for name, kind in (("empty", "empty"), ("hertz", "hertz"), ("contact_force (jcg)", "law")):
        run = scatter_loop(FORCES[kind])
        loops[name] = run
        state = np.zeros((n, 1 if kind != "law" else frj.STATE_SIZE))
        f = np.zeros(n_part)
        clock = [0]

        def fn(run=run, state=state, f=f, clock=clock):
            run(clock[0], nsteps, phase, rate, lo, hi0, law, zero, state, pa, pb, f)
            clock[0] += nsteps
        cases[name] = (fn, n * nsteps)
    return interleaved(cases, rounds, ref="empty"), loops


def table(t, loops):
    rows = ["| loop | ns per contact-step | net of the empty loop (ns) | net x Hertz | vectorised |",
            "|---|---|---|---|---|"]
    for name in t:
        r, ns = net(t, name, "hertz") if name != "empty" else (math.nan, 0.0)
        rows.append(f"| {name} | {t[name].median * 1e9:.2f} | {ns:.2f} | {'' if name == 'empty' else f'{r:.2f}x'} | "
                    f"{'yes' if vectorised(loops[name]) else 'no'} |")
    return rows + [""]


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="fewer rounds and steps (a smoke run)")
    ap.add_argument("--out", default=str(REPO / "bench" / "DEM_LOOP.md"))
    args = ap.parse_args(argv)
    rounds = 3 if args.quick else 9
    steps_small, steps_big = (20, 2) if args.quick else (100, 5)
    threads = numba.config.NUMBA_NUM_THREADS
    mach = report.machine()
    L = ["# The contact law in the loop DEM codes write", "",
         f"Generated by `python -m bench.dem_loop` on {datetime.datetime.now(datetime.timezone.utc):%Y-%m-%d %H:%M} "
         f"UTC; machine: {mach.get('cpu')}, {mach.get('nproc')} cores, flags {', '.join(mach.get('flags', []))}; "
         f"numba {numba.__version__}. Times are medians over {rounds} interleaved rounds; ratios are medians of "
         "per-round ratios of times net of the empty loop (the same round). The loops and paths: the module "
         "doc of bench/dem_loop.py.", ""]
    c = contacts(10**4)
    mix_a = census(0, steps_small, *c, laws()["jcg"], np.zeros((10**4, frj.STATE_SIZE)), False)
    mix_b = census(0, 2000, *c, laws()["jcg"], np.zeros((10**4, frj.STATE_SIZE)), True)
    L += ["Mix of states (1e4 contacts, JCG; virgin loading / in contact below w_max / apart):",
          f"the issue's loop, {steps_small} steps from virgin rows: {mix_a[0]:.1%} / {mix_a[1]:.1%} / {mix_a[2]:.1%}; "
          f"with contact turnover, 2000 steps: {mix_b[0]:.1%} / {mix_b[1]:.1%} / {mix_b[2]:.1%}.", ""]
    targets = []
    for n, nsteps in ((10**4, steps_small), (10**6, steps_big)):
        t, loops = measure(n, nsteps, rounds)
        where = "cache-resident" if n < 10**5 else "not cache-resident"
        L += [f"## The issue's loop: {n:.0e} contacts, serial ({where})",
              "", "Path -> force -> out[i], nothing else in the loop (the Hertz loop vectorises).", ""]
        L += table(t, loops)
        targets.append((net(t, "contact_force (jcg)", "hertz")[0],
                        net(t, "contact_force_stacked (3 materials)", "contact_force (jcg)")[0],
                        net(t, "0.2 kernel (jcg)", "contact_force (jcg)")[0]))
    turn = []
    for n, nsteps in ((10**4, steps_small), (10**6, steps_big)):
        t, loops = measure(n, nsteps, rounds, turnover=True)
        L += [f"## With contact turnover: {n:.0e} contacts, serial", "",
              "The same, and a contact that ends has its history zeroed in the loop (`if new: state[i, :] = 0`), as "
              "DEM codes create and delete history when contacts form and break.", ""]
        L += table(t, loops)
        turn.append(net(t, "contact_force (jcg)", "hertz")[0])
    both = prange_measure(10**6, steps_big, rounds, threads)
    L += [f"## 1e6 contacts with turnover: `numba.prange` on {threads} threads vs serial (interleaved)", "",
          "| loop | serial ns | prange ns | speed-up (median of per-round ratios) |", "|---|---|---|---|"]
    speedups = {}
    for name in ("empty", "hertz", "contact_force (jcg)", "contact_force_stacked (3 materials)"):
        ser_t, par_t = both[name + " | serial"], both[name + " | prange"]
        speedups[name] = float(np.median(ser_t.per_eval / par_t.per_eval))
        L.append(f"| {name} | {ser_t.median * 1e9:.2f} | {par_t.median * 1e9:.2f} | {speedups[name]:.2f}x |")
    L.append("")
    st, sloops = scatter_measure(10**4, steps_small, rounds)
    r_sc = net(st, "contact_force (jcg)", "hertz")[0]
    L += ["## The DEM shape: turnover, forces scattered to particles (1e4 contacts, 5e3 particles, serial)", ""]
    L += table(st, sloops)
    rem = remarks_of_law_loop()
    sp = speedups.get("contact_force (jcg)", math.nan)
    L += ["## Targets (issue 28)", "",
          "| target | 1e4 | 1e6 | met |", "|---|---|---|---|",
          f"| contact_force <= 3x Hertz with a history slot, net, serial (the issue's loop) | {targets[0][0]:.2f}x | "
          f"{targets[1][0]:.2f}x | {'yes' if max(targets[0][0], targets[1][0]) <= 3 else 'no'} |",
          f"| the same with contact turnover | {turn[0]:.2f}x | {turn[1]:.2f}x | "
          f"{'yes' if max(turn) <= 3 else 'no'} |",
          f"| the same in the DEM shape (scatter) | {r_sc:.2f}x | | {'yes' if r_sc <= 3 else 'no'} |",
          f"| contact_force_stacked <= 1.2x contact_force | {targets[0][1]:.2f}x | {targets[1][1]:.2f}x | "
          f"{'yes' if max(targets[0][1], targets[1][1]) <= 1.2 else 'no'} |",
          f"| prange on {threads} threads >= 1.8x serial at 1e6 | | {sp:.2f}x | {'yes' if sp >= 1.8 else 'no'} |",
          f"| (reference) fastrest 0.2's kernel / this one, net | {targets[0][2]:.2f}x | {targets[1][2]:.2f}x | |", "",
          "LLVM's loop-vectorizer on the issue's loop with contact_force (its remarks, deduplicated): "
          + ("; ".join(f"`{x}`" for x in rem) if rem else "none printed") + ".", "",
          "Where the first target is missed, the cause: in the bare loop LLVM runs the Hertz force on four "
          "contacts per instruction (AVX2) and the law on one. The law's cell rows are read at an index computed "
          "from w while the loop writes the history rows and out[i]; the vectorizer must bound every address it "
          "cannot prove disjoint from the stores, and a data-dependent gather has no bound (the remark above). "
          "Once the loop holds anything the vectorizer refuses (zeroing a finished contact's row, adding forces "
          "to particles), Hertz is scalar as well and the ratio is the law's own cost (the turnover and DEM-shape "
          "rows). The law itself has no branch and calls no log/exp/pow (fastrest/law_cells.py).", ""]
    Path(args.out).write_text("\n".join(L) + "\n")
    print("\n".join(L))


if __name__ == "__main__":
    main()
