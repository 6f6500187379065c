"""Interleaved timing on a noisy machine (see PERF-NOTES: a fast and a slow state ~1.85x apart).

Every case is compiled and run once before timing (warm-up excluded). Then, in each round, every case
runs once (a block of ``inner`` calls, calibrated so a block lasts at least ``min_block`` seconds), in
an order shuffled per round. A case's time per evaluation is reported as the median and the minimum
over rounds; its ratio to a reference case is the median over rounds of the per-round ratio (the two
blocks of a round run within milliseconds of each other, so they usually share the machine's state).
"""
import gc
import math
import os
import time
from dataclasses import dataclass, field

import numpy as np


@dataclass
class Timing:
    """Seconds per evaluation of one case, per round, and its per-round ratio to the reference."""

    name: str
    per_eval: np.ndarray
    ratios: np.ndarray = field(default=None)
    n_evals: int = 1
    inner: int = 1
    ratio_min: float = math.nan  # min(this) / min(reference)
    other_cores: float = None    # other processes' average CPU use (cores) during the rounds
    attempts: int = 1            # groups of rounds run (repeated while other processes were busy)

    @property
    def median(self):
        return float(np.median(self.per_eval))

    @property
    def min(self):
        return float(np.min(self.per_eval))

    @property
    def ratio(self):
        """Median over rounds of (this case's time / the reference's time in the same round)."""
        return float(np.median(self.ratios)) if self.ratios is not None else math.nan

    @property
    def ratio_of_minima(self):
        return float(self.ratio_min)

    def as_dict(self):
        return {"median_s": self.median, "min_s": self.min, "ratio_to_ref": self.ratio,
                "ratio_of_minima": self.ratio_of_minima, "rounds": int(self.per_eval.size),
                "n_evals": self.n_evals, "inner": self.inner, "other_cores": self.other_cores,
                "attempts": self.attempts}


def cpu_counters():
    """(machine-wide busy CPU seconds from /proc/stat, this process's and its children's CPU seconds)."""
    try:
        with open("/proc/stat") as f:
            fields = f.readline().split()
        ticks = os.sysconf("SC_CLK_TCK")
        user, nice, system, idle, iowait, irq, softirq, steal = (int(x) for x in fields[1:9])
        busy = (user + nice + system + irq + softirq + steal) / ticks
    except (OSError, ValueError):
        return None
    t = os.times()
    return busy, t.user + t.system + t.children_user + t.children_system


class OtherLoad:
    """Average number of cores other processes kept busy between start() and stop()."""

    def __init__(self):
        self.c0 = cpu_counters()
        self.t0 = time.perf_counter()

    def stop(self):
        c1 = cpu_counters()
        if self.c0 is None or c1 is None:
            return None
        wall = time.perf_counter() - self.t0
        return max(0.0, (c1[0] - self.c0[0]) - (c1[1] - self.c0[1])) / max(wall, 1e-9)


#: How to cope with other processes on a shared machine (set by bench.run; the quick run neither waits
#: nor retries). Before each group of rounds, wait (up to max_wait s) for 1 s in which other processes
#: used < 0.05 cores; if they used more than `threshold` cores on average during the rounds, run the
#: group again (up to `retries` times) and keep the least disturbed attempt. `budget` caps the total
#: time spent waiting and repeating.
POLICY = {"threshold": 0.1, "retries": 0, "max_wait": 0.0, "budget": 0.0}
_SPENT = [0.0]


def _budget_left():
    return POLICY["budget"] - _SPENT[0]


def wait_for_quiet():
    """Wait (within the policy's limits) until other processes leave the cores alone for 1 s."""
    if POLICY["max_wait"] <= 0:
        return
    t0 = time.perf_counter()
    try:
        while True:
            left = min(POLICY["max_wait"] - (time.perf_counter() - t0), _budget_left() - (time.perf_counter() - t0))
            if left <= 0:
                return
            ld = OtherLoad()
            time.sleep(min(1.0, left))
            x = ld.stop()
            if x is None or x < 0.05:
                return
    finally:
        _SPENT[0] += time.perf_counter() - t0


def _block(fn, inner):
    t0 = time.perf_counter()
    for _ in range(inner):
        fn()
    return time.perf_counter() - t0


def _rounds(cases, names, inner, rounds, seed):
    rng = np.random.default_rng(seed)
    raw = {name: np.empty(rounds) for name in names}
    load = OtherLoad()
    gc_was = gc.isenabled()
    gc.disable()
    try:
        for r in range(rounds):
            for k in rng.permutation(len(names)):
                name = names[k]
                fn, n = cases[name]
                raw[name][r] = _block(fn, inner[name]) / (inner[name] * n)
    finally:
        if gc_was:
            gc.enable()
    return raw, load.stop()


def interleaved(cases, rounds, ref=None, min_block=2e-3, seed=0):
    """Time ``cases`` = {name: (fn, n_evals)} in interleaved rounds; returns {name: Timing}.

    ``fn()`` performs ``n_evals`` evaluations. ``ref`` names the case the ratios refer to.
    """
    names = list(cases)
    inner = {}
    for name in names:  # warm-up (compilation, caches), then calibration
        fn = cases[name][0]
        fn()
        t = min(_block(fn, 1) for _ in range(2))
        inner[name] = max(1, math.ceil(min_block / max(t, 1e-9)))
    best = None
    attempt = 0
    while True:
        wait_for_quiet()
        t_start = time.perf_counter()
        raw, other = _rounds(cases, names, inner, rounds, seed + attempt)
        if best is None or (other is not None and (best[1] is None or other < best[1])):
            best = (raw, other)
        attempt += 1
        if other is None or other <= POLICY["threshold"] or attempt > POLICY["retries"]:
            break
        if _budget_left() <= 0:
            break
        _SPENT[0] += time.perf_counter() - t_start
    raw, other = best
    out = {}
    for name in names:
        t = Timing(name, raw[name], n_evals=cases[name][1], inner=inner[name], other_cores=other,
                   attempts=attempt)
        if ref is not None:
            t.ratios = raw[name] / raw[ref]
            t.ratio_min = np.min(raw[name]) / np.min(raw[ref])
        out[name] = t
    return out


def with_threads(k, fn):
    """fn run with k Numba threads (restored to the maximum afterwards)."""
    import numba

    def f():
        numba.set_num_threads(k)
        try:
            return fn()
        finally:
            numba.set_num_threads(numba.config.NUMBA_NUM_THREADS)
    return f


def repeated(fn, repeats):
    """Wall-clock seconds of ``repeats`` calls of fn (for slow, one-off operations)."""
    out = np.empty(repeats)
    for i in range(repeats):
        wait_for_quiet()
        t0 = time.perf_counter()
        fn()
        out[i] = time.perf_counter() - t0
    return out


def fmt_time(s, unit=None):
    """Format seconds with a fitting unit (or a fixed one: 'ns', 'us', 'ms', 's')."""
    if s is None or not np.isfinite(s):
        return "-"
    if unit is None:
        unit = "ns" if s < 1e-6 else "us" if s < 1e-3 else "ms" if s < 1 else "s"
    scale = {"ns": 1e9, "us": 1e6, "ms": 1e3, "s": 1.0}[unit]
    x = s * scale
    return f"{x:.3g} {unit}" if x < 1000 else f"{x:.0f} {unit}"


def fmt_ratio(x):
    if x is None or not np.isfinite(x):
        return "-"
    return f"{x:.3g}x"


def fmt_err(x):
    if x is None or not np.isfinite(x):
        return "-"
    if x == 0:
        return "0"
    # rounded up: a stated error is never below the one measured
    s = f"{x:.1e}"
    if float(s) < x:
        m, e = s.split("e")
        m, e = round(float(m) + 0.1, 1), int(e)
        if m >= 10.0:
            m, e = 1.0, e + 1
        s = f"{m:.1f}e{e:+03d}"
    return s
